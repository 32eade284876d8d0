//! `sylva lobes`: Fields' lobe-driven trees, `.tree` files and point clouds.

use crate::*;

#[test]
fn lobes_grows_the_three_species_saves_and_reloads_tree_files() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    for species in ["black_oak", "balsam_fir", "weeping_cherry"] {
        let run = sylva(&[
            "lobes",
            species,
            "--seed",
            "4",
            "-o",
            &p(&format!("{species}.glb")),
            "-o",
            &p(&format!("{species}.tree")),
            "-o",
            &p(&format!("{species}.vec")),
        ]);
        assert!(run.status.success(), "{species}: {}", text(&run.stderr));
        let (doc, _, _) = gltf::import(p(&format!("{species}.glb"))).expect("valid GLB");
        // Bark and leaves, each as one primitive or more (cut to fit 16-bit indices).
        let mut parts: Vec<String> = doc
            .meshes()
            .next()
            .unwrap()
            .primitives()
            .map(|p| p.material().name().unwrap_or_default().to_string())
            .collect();
        parts.dedup();
        assert_eq!(parts, ["bark", "leaves"]);
        // The .tree file regrows the same tree.
        let again = p(&format!("{species}-again.vec"));
        let run = sylva(&["lobes", &p(&format!("{species}.tree")), "-o", &again]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        assert!(text(&run.stdout).contains("from the .tree file"));
        assert_eq!(
            std::fs::read(p(&format!("{species}.vec"))).unwrap(),
            std::fs::read(&again).unwrap(),
            "{species}"
        );
    }
    // The appendix's own file, Y up in room coordinates, grows as a two-lobed cherry.
    let appendix = p("appendix.tree");
    std::fs::write(
        &appendix,
        "Cherry Tree\n100\n#BRANCHES\n0 -1 1.110022 -1.582516 4.728205 1.14952 -0.8700994 4.896452 1\n\
         1 0 1.14952 -0.8700994 4.896452 1.800362 -0.3780254 4.764441 1\n\
         2 0 1.14952 -0.8700994 4.896452 0.7252637 -0.7159721 4.99926 1\n\
         3 2 0.7252637 -0.7159721 4.99926 0.5519101 0.02624928 5.070594 1\n\
         #LEAF LOBES\n2.307282 0.5082518 4.534246 1\n0.4439276 1.201943 4.939856 1\n",
    )
    .unwrap();
    let run = sylva(&["lobes", &appendix, "-o", &p("appendix.glb")]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("Weeping Cherry Tree (seed 100)"));
    assert!(text(&run.stdout).contains(": 2 lobes"));
    // Lobes of one's own.
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--lobe",
        "0,0,3,1",
        "--lobe",
        "1.5,0,3.5,0.8",
        "-o",
        &p("own.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("lobes as given: 2 lobes"));
}

#[test]
fn lobes_fit_a_point_cloud() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = dir.path().join("scan.xyz");
    // A trunk 2 m tall and a ball of crown 1.2 m in radius above it, 3 m up.
    let mut body = String::new();
    for i in 0..400 {
        let a = i as f32 * 0.7;
        body.push_str(&format!(
            "{} {} {}\n",
            0.1 * a.cos(),
            0.1 * a.sin(),
            2.0 * i as f32 / 400.0
        ));
    }
    // xorshift64*: plain, seeded, good enough to fill a ball.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let mut n = 0;
    while n < 4000 {
        let (x, y, z) = (next(), next(), next());
        if x * x + y * y + z * z <= 1.0 {
            body.push_str(&format!("{} {} {}\n", 1.2 * x, 1.2 * y, 3.2 + 1.2 * z));
            n += 1;
        }
    }
    std::fs::write(&cloud, body).unwrap();
    let tree = dir.path().join("fit.tree");
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--points",
        cloud.to_str().unwrap(),
        "-o",
        tree.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let out = text(&run.stdout);
    assert!(
        out.contains("fitted to 4400 points") && out.contains("1 lobes"),
        "{out}"
    );
    let saved = std::fs::read_to_string(&tree).unwrap();
    let lobe: Vec<f32> = saved
        .lines()
        .last()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    // Y up in the file: the lobe's centre 3.2 m up becomes its y.
    assert!(
        (lobe[1] - 3.2).abs() < 0.15 && (lobe[3] - 1.2).abs() < 0.15,
        "{saved}"
    );
    // --fit-lobes K: K lobes, whatever the crown's shape would choose.
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--points",
        cloud.to_str().unwrap(),
        "--fit-lobes",
        "3",
        "-o",
        tree.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains(": 3 lobes"),
        "{}",
        text(&run.stdout)
    );
    let saved = std::fs::read_to_string(&tree).unwrap();
    assert_eq!(
        saved
            .split("#LEAF LOBES")
            .nth(1)
            .unwrap()
            .trim()
            .lines()
            .count(),
        3
    );
}

#[test]
fn lobes_renders_pictures_and_keeps_line_drawings_as_svg() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (png, svg) = (scratch(d, "cherry.png"), scratch(d, "cherry.svg"));
    let run = sylva(&["lobes", "weeping_cherry", "-o", &png, "-o", &svg]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("rendered, 1024x768"));
    // Rendered: sky, ground, shadow and the cherry's pink blossoms, not black lines on white.
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!((img.width(), img.height()), (1024, 768));
    let share = |f: &dyn Fn(&[u8; 3]) -> bool| {
        img.pixels().filter(|p| f(&p.0)).count() as f32 / (1024.0 * 768.0)
    };
    let pink = share(&|p| p[0] > 170 && p[0] as i32 - p[1] as i32 > 25 && p[2] > 120);
    let white = share(&|p| p.iter().all(|&c| c > 245));
    assert!(pink > 0.01, "pink blossoms: {pink}");
    assert!(white < 0.05, "a line drawing's white page: {white}");
    let drawing = std::fs::read_to_string(&svg).unwrap();
    assert!(drawing.starts_with("<svg") || drawing.contains("<svg"));
    // Other sizes and views; an overlay is a line drawing only.
    let side = scratch(d, "side.png");
    let run = sylva(&[
        "lobes",
        "balsam_fir",
        "--view",
        "side",
        "--size",
        "320x480",
        "-o",
        &side,
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(png_size(std::path::Path::new(&side)), (320, 480));
    let bad = tempfile::tempdir().unwrap();
    refuses(
        &[
            "lobes",
            "balsam_fir",
            "--view",
            "overlay",
            "-o",
            &scratch(bad.path(), "o.png"),
        ],
        &["overlay", ".svg"],
        bad.path(),
    );
}

#[test]
fn lobes_refuses_bad_input_with_line_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (input, out) = (
        |n: &str, body: &str| scratch_input(d, n, body),
        |n: &str| scratch(d, n),
    );
    let bad_tree = input(
        "t.tree",
        "Black Oak\n1\n#BRANCHES\n0 -1 0 0 0 0 1\n#LEAF LOBES\n0 2 0 1\n",
    );
    refuses(
        &["lobes", &bad_tree, "-o", &out("a.glb")],
        &["in-t.tree, line 4", "found 7 values"],
        d,
    );
    let odd_type = input("u.tree", "Baobab\n1\n#BRANCHES\n#LEAF LOBES\n0 2 0 1\n");
    refuses(&["lobes", &odd_type, "-o", &out("a.glb")], &["Baobab"], d);
    let bad_ply = input(
        "c.ply",
        "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n1 2 x\n",
    );
    refuses(
        &[
            "lobes",
            "black_oak",
            "--points",
            &bad_ply,
            "-o",
            &out("a.glb"),
        ],
        &["in-c.ply, line 9", "`x`"],
        d,
    );
    let bad_rules = input("r.toml", "[rules]\nname = \"Mine\"\nTrunkAngle = 10\n");
    refuses(
        &["lobes", &bad_rules, "-o", &out("a.glb")],
        &["in-r.toml", "lacks 24 of the 25 rules", "BranchAngle"],
        d,
    );
    refuses(
        &["lobes", "baobab", "-o", &out("a.glb")],
        &["black_oak, balsam_fir"],
        d,
    );
    refuses(
        &["lobes", "black_oak", "--lobe", "0,0,1", "-o", &out("a.glb")],
        &["--lobe 0,0,1", "X,Y,Z,R"],
        d,
    );
    refuses(
        &["lobes", "black_oak", "--scale", "0", "-o", &out("a.tree")],
        &["--scale 0"],
        d,
    );
    refuses(
        &[
            "lobes",
            "black_oak",
            "--tessellation",
            "2",
            "-o",
            &out("a.glb"),
        ],
        &["--tessellation 2", "3..64"],
        d,
    );
}
