//! `sylva render`: pictures, turntables, wind frames, LOD chains and forest files.

use crate::*;

#[test]
fn render_species_glb_turntable_and_wind_frames() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let s = |path: &PathBuf| path.to_str().unwrap().to_string();
    let run = sylva(&[
        "render",
        "queen_palm",
        "--size",
        "320x240",
        "--view",
        "iso",
        "-o",
        &s(&p("palm.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(png_size(&p("palm.png")), (320, 240));
    // A GLB written by generate renders too.
    assert!(
        sylva(&["generate", "saguaro", "-o", &s(&p("cactus.glb"))])
            .status
            .success()
    );
    let run = sylva(&[
        "render",
        &s(&p("cactus.glb")),
        "--size",
        "200x200",
        "-o",
        &s(&p("cactus.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // Turntable: 4 views on one 2x2 sheet.
    let run = sylva(&[
        "render",
        "hazel",
        "--turntable",
        "4",
        "--size",
        "100x80",
        "-o",
        &s(&p("sheet.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(png_size(&p("sheet.png")), (200, 160));
    // Wind animation: numbered frames that differ.
    let run = sylva(&[
        "render",
        "weeping_birch",
        "--wind",
        "8",
        "--gust",
        "4",
        "--frames",
        "3",
        "--fps",
        "4",
        "--size",
        "120x120",
        "--bare",
        "-o",
        &s(&p("sway.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let frames: Vec<Vec<u8>> = (0..3)
        .map(|i| std::fs::read(p(&format!("sway-{i:04}.png"))).unwrap())
        .collect();
    assert_ne!(frames[0], frames[2], "the tree moves between frames");
    // Wind that is not a number is refused by name, and nothing is written.
    for (flag, value) in [("--wind", "nan"), ("--gust", "1e9"), ("--time", "inf")] {
        let run = sylva(&[
            "render",
            "hazel",
            flag,
            value,
            "--size",
            "64x64",
            "-o",
            &s(&p("bad-wind.png")),
        ]);
        assert_eq!(run.status.code(), Some(1), "{flag} {value}");
        assert!(text(&run.stderr).contains(flag), "{}", text(&run.stderr));
        assert!(!p("bad-wind.png").exists());
    }
    // Levels as a design aid: the trunk alone.
    let run = sylva(&[
        "render",
        "black_tupelo",
        "--levels",
        "1",
        "--size",
        "100x100",
        "-o",
        &s(&p("trunk.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
}

#[test]
fn render_rejects_bad_requests_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = out.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["render", "quaking_aspen", "--size", "9x9", "-o", o],
            "16..8192",
        ),
        (
            vec!["render", "quaking_aspen", "--size", "big", "-o", o],
            "WIDTHxHEIGHT",
        ),
        (vec!["render", "quaking_aspen", "-o", "x.jpg"], "PNG"),
        (
            vec!["render", "quaking_aspen", "--turntable", "0", "-o", o],
            "at least 1",
        ),
        (vec!["render", "missing.glb", "-o", o], "missing.glb"),
    ] {
        let run = sylva(&args);
        let err = text(&run.stderr);
        assert!(
            !run.status.success() && err.contains(needle),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!out.exists());
}

#[test]
fn lod_chain_glb_has_msft_lod_levels_and_a_baked_impostor() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("aspen-lod.glb");
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--quality",
        "0.4",
        "--lod-chain",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // A real reader loads it, atlas included.
    let (doc, _, images) = gltf::import(&out).expect("valid GLB");
    assert_eq!(images.len(), 1, "one impostor atlas");
    let atlas = &images[0];
    assert_eq!(atlas.format, gltf::image::Format::R8G8B8A8);
    let alphas: Vec<u8> = atlas.pixels.chunks(4).map(|p| p[3]).collect();
    let clear = alphas.iter().filter(|&&a| a == 0).count();
    let solid = alphas.iter().filter(|&&a| a == 255).count();
    assert!(
        clear > alphas.len() / 5 && solid > alphas.len() / 20,
        "the atlas has transparent background ({clear}) and opaque tree ({solid}) pixels"
    );
    let triangles = |name: &str| {
        let node = doc.nodes().find(|n| n.name() == Some(name)).unwrap();
        node.mesh()
            .unwrap()
            .primitives()
            .map(|p| p.indices().unwrap().count() / 3)
            .sum::<usize>()
    };
    let counts: Vec<usize> = (0..4)
        .map(|k| triangles(&format!("Quaking_Aspen_LOD{k}")))
        .collect();
    assert!(
        counts.windows(2).all(|w| w[1] < w[0]) && counts[3] == 16,
        "{counts:?}"
    );
    // The scene shows LOD0, which lists the others and their screen coverages.
    let json = glb_json(&out);
    assert!(
        json["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&serde_json::json!("MSFT_lod"))
    );
    let root = json["scenes"][0]["nodes"][0].as_u64().unwrap() as usize;
    let node = &json["nodes"][root];
    assert_eq!(node["name"], "Quaking_Aspen_LOD0");
    let ids = node["extensions"]["MSFT_lod"]["ids"].as_array().unwrap();
    assert_eq!(ids.len(), 3);
    for (k, id) in ids.iter().enumerate() {
        let n = &json["nodes"][id.as_u64().unwrap() as usize];
        assert_eq!(n["name"], format!("Quaking_Aspen_LOD{}", k + 1));
    }
    let coverage: Vec<f64> = node["extras"]["MSFT_screencoverage"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(coverage.len(), 4);
    assert!(coverage.windows(2).all(|w| w[1] < w[0]), "{coverage:?}");
    // OBJ has no LOD chains.
    let obj = dir.path().join("t.obj");
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--lod-chain",
        "-o",
        obj.to_str().unwrap(),
    ]);
    assert!(!run.status.success() && text(&run.stderr).contains("--lod-chain"));
    assert!(!obj.exists());
}

#[test]
fn forest_file_renders_with_and_without_lod_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("grove.toml");
    std::fs::write(
        &file,
        "[forest]\nspecies = [\"quaking_aspen\", \"hazel\"]\ncount = 12\narea = [40, 40]\nvariants = 1\nquality = 0.3\n",
    )
    .unwrap();
    let png = dir.path().join("grove.png");
    let run = sylva(&[
        "render",
        file.to_str().unwrap(),
        "--lod",
        "compare",
        "--range",
        "400",
        "--size",
        "200x150",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (w, h) = png_size(&png);
    assert_eq!(w, 2 * 200 + 8, "two pictures side by side");
    assert!(h > 150, "with a caption band");
    let out = text(&run.stdout);
    let primitives = |label: &str| -> usize {
        let line = out.lines().find(|l| l.starts_with(label)).unwrap();
        let inner = line.split('(').nth(1).unwrap().split(' ').next().unwrap();
        inner.replace(',', "").parse().unwrap()
    };
    let (with, without) = (primitives("with LOD:"), primitives("without LOD:"));
    assert!(
        with * 5 < without,
        "LOD draws {with} primitives, full detail {without}"
    );
    // Bad requests name what is wrong and write nothing.
    let bad = dir.path().join("bad.png");
    let unknown = dir.path().join("unknown.toml");
    std::fs::write(&unknown, "[forest]\nspecies = [\"no_such_tree\"]\n").unwrap();
    let f = file.to_str().unwrap();
    for (args, needles) in [
        (vec!["render", f, "--fov", "0"], vec!["--fov 0", "1..170"]),
        (vec!["render", f, "--range", "-5"], vec!["--range -5"]),
        (
            vec!["render", f, "--eye", "1,2", "--target", "0,0,0"],
            vec!["--eye", "three numbers"],
        ),
        (vec!["render", f, "--turntable", "3"], vec!["--turntable"]),
        (
            vec!["render", unknown.to_str().unwrap()],
            vec!["unknown.toml", "no_such_tree"],
        ),
    ] {
        let mut all = args.clone();
        all.extend(["-o", bad.to_str().unwrap()]);
        let run = sylva(&all);
        let err = text(&run.stderr);
        assert!(!run.status.success(), "{args:?} should fail");
        for n in needles {
            assert!(err.contains(n), "{args:?}: `{n}` not in {err}");
        }
        assert!(
            !err.contains("panicked") && !bad.exists(),
            "{args:?}: {err}"
        );
    }
    // The GLB of the same forest file.
    let glb = dir.path().join("grove.glb");
    let run = sylva(&[
        "forest",
        file.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (doc, _, _) = gltf::import(&glb).expect("valid GLB");
    assert_eq!(doc.nodes().count(), 12);
}
