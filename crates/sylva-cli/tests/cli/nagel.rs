//! Nagel's trees (`fractal`, `whisk`, `stick`) and `sylva draw`.

use crate::*;

#[test]
fn fractal_tree_writes_vector_file_drawings_and_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let run = sylva(&[
        "fractal",
        "--theta1",
        "-35",
        "--theta2",
        "10",
        "--r1",
        "0.73",
        "--r2",
        "0.83",
        "--depth",
        "12",
        "-o",
        p("out.glb").to_str().unwrap(),
        "-o",
        p("out.svg").to_str().unwrap(),
        "-o",
        p("out.png").to_str().unwrap(),
        "-o",
        p("out.vec").to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("8191 segments, 4096 tips"),
        "{}",
        text(&run.stdout)
    );
    // One `L` per segment; a `P` wherever a segment does not start where the last one ended.
    let (moves, draws) = pen_moves(&p("out.vec"));
    assert_eq!(draws, 8191);
    assert!(moves > 1000 && moves < 8191, "{moves}");
    let (doc, _, _) = gltf::import(p("out.glb")).expect("valid GLB");
    assert_eq!(doc.meshes().count(), 1);
    assert!(inked(&p("out.png")) > 20_000);
    let svg = std::fs::read_to_string(p("out.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("front view"));

    // The same tree drawn from its vector file looks the same from the top.
    let top_a = p("a.png");
    let run = sylva(&[
        "fractal",
        "--depth",
        "12",
        "--view",
        "top",
        "-o",
        top_a.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let top_b = p("b.png");
    let run = sylva(&[
        "draw",
        p("out.vec").to_str().unwrap(),
        "--view",
        "top",
        "-o",
        top_b.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (a, b) = (inked(&top_a) as f64, inked(&top_b) as f64);
    // The vector file has no widths, so its strokes are hairlines: less ink, same figure.
    assert!(b > 0.2 * a && b < a, "{a} {b}");
}

#[test]
fn whisk_and_stick_trees_from_drawn_profiles() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    let run = sylva(&[
        "whisk",
        "--profile",
        &profiles("round.csv"),
        "--ribs",
        "8",
        "--rings",
        "2",
        "--spokes",
        "3",
        "-o",
        &p("w.vec"),
        "-o",
        &p("w.glb"),
        "-o",
        &p("w.png"),
        "--view",
        "perspective",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("8 ribs, 2 rings, 3 spokes per rib"));
    // Trunk 1 line, 8 ribs of 9 lines, 2 rings of 32, 8×3 spokes of 1.
    let (_, draws) = pen_moves(Path::new(&p("w.vec")));
    assert_eq!(draws, 1 + 8 * 9 + 2 * 32 + 24);
    gltf::import(p("w.glb")).expect("valid GLB");
    assert!(inked(Path::new(&p("w.png"))) > 5_000);
    // Density 3 is Nagel's 12 ribs; an SVG profile scaled to 12 m.
    let run = sylva(&[
        "whisk",
        "--profile",
        &profiles("vase.svg"),
        "--height",
        "12",
        "--density",
        "3",
        "-o",
        &p("v.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("12 ribs") && text(&run.stdout).contains("12.0"));
    let run = sylva(&[
        "stick",
        "--branches",
        &profiles("sticks.csv"),
        "--ribs",
        "6",
        "-o",
        &p("s.glb"),
        "-o",
        &p("s.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("4 branches x 6 ribs"));
    let (_, draws) = pen_moves(Path::new(&p("s.vec")));
    assert_eq!(draws, 1 + 6 * (3 + 3 + 3 + 2));
}

#[test]
fn draw_makes_every_view_of_a_species() {
    let dir = tempfile::tempdir().unwrap();
    let mut sizes = Vec::new();
    for view in ["front", "side", "top", "perspective", "overlay"] {
        let png = dir.path().join(format!("{view}.png"));
        let run = sylva(&[
            "draw",
            "quaking_aspen",
            "--no-leaves",
            "--view",
            view,
            "--size",
            "320x400",
            "-o",
            png.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{view}: {}", text(&run.stderr));
        assert_eq!(png_size(&png), (320, 400));
        sizes.push(inked(&png));
    }
    assert!(sizes.iter().all(|&n| n > 2_000), "{sizes:?}");
    // The overlay holds two elevations: more ink than either.
    assert!(sizes[4] > sizes[0] && sizes[4] > sizes[1], "{sizes:?}");
}

#[test]
fn nagel_commands_refuse_bad_input_with_line_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (input, out) = (
        |n: &str, body: &str| scratch_input(d, n, body),
        |n: &str| scratch(d, n),
    );
    let bad_csv = input("p.csv", "radius,height\n0,2\n1,3\n2,abc\n");
    refuses(
        &[
            "whisk",
            "--profile",
            &bad_csv,
            "-o",
            &out("a.vec"),
            "-o",
            &out("a.glb"),
        ],
        &["in-p.csv, line 4", "expected numbers"],
        d,
    );
    let bad_svg = input(
        "p.svg",
        "<svg viewBox=\"0 0 10 10\">\n\n<polyline points=\"5,5 2,2\"/></svg>",
    );
    refuses(
        &["whisk", "--profile", &bad_svg, "-o", &out("a.svg")],
        &["in-p.svg, line 3", "left of the trunk"],
        d,
    );
    let bad_vec = input("t.vec", "P 0,0,0\nL 1,1,1\nL 2,2\n");
    refuses(
        &["draw", &bad_vec, "-o", &out("a.png")],
        &["in-t.vec, line 3", "three coordinates"],
        d,
    );
    let vec_file = input("ok.vec", "P 0,0,0\nL 1,1,1\n");
    refuses(
        &["draw", &vec_file, "-o", &out("a.glb")],
        &["no stem radii"],
        d,
    );
    refuses(
        &[
            "whisk",
            "--profile",
            &profiles("round.csv"),
            "--density",
            "7",
            "-o",
            &out("a.vec"),
        ],
        &["--density 7", "1 (least dense) to 5"],
        d,
    );
    refuses(
        &["fractal", "--depth", "30", "-o", &out("a.vec")],
        &["budget", "--max-segments"],
        d,
    );
    refuses(
        &["fractal", "--r1", "-1", "-o", &out("a.vec")],
        &["r1", "0..1.5"],
        d,
    );
    refuses(
        &["fractal", "-o", &out("a.dwg")],
        &["unknown format", ".vec"],
        d,
    );
    refuses(
        &["stick", "--branches", &bad_csv, "-o", &out("a.vec")],
        &["expected 3 values"],
        d,
    );
    refuses(
        &["fractal", "--size", "10x10", "-o", &out("a.png")],
        &["16..16384"],
        d,
    );
}

#[test]
fn a_dxf_that_cannot_be_written_is_refused_and_nothing_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let profile = concat!(env!("CARGO_MANIFEST_DIR"), "/../../profiles/round.csv");
    let missing = dir.path().join("no-such-folder").join("tree.dxf");
    let run = sylva(&[
        "whisk",
        "--profile",
        profile,
        "-o",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(1), "{}", text(&run.stderr));
    let said = text(&run.stderr);
    assert!(
        said.contains("cannot write") && said.contains("tree.dxf"),
        "{said}"
    );
    assert!(!missing.exists());
    // Where it can be written, it is, whole: a DXF's last group is its EOF.
    let ok = dir.path().join("tree.dxf");
    let run = sylva(&["whisk", "--profile", profile, "-o", ok.to_str().unwrap()]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let written = std::fs::read_to_string(&ok).unwrap();
    assert!(
        written.trim_end().ends_with("EOF"),
        "{}",
        &written[written.len() - 40..]
    );
    // Nothing but the file: no temporary left beside it.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
