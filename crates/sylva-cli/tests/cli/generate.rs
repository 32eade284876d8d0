//! `sylva generate` and `sylva species`: models, summaries, overrides, and bad input refused.

use crate::*;

#[test]
fn generate_writes_a_glb_and_a_json_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("aspen.glb");
    let png = dir.path().join("aspen.png");
    let o = out.to_str().unwrap();
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--seed",
        "3",
        "-o",
        o,
        "--preview",
        png.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).expect("one JSON object");
    for key in [
        "species",
        "seed",
        "stems_per_level",
        "leaves",
        "vertices",
        "triangles",
        "height_m",
        "crown_width_m",
        "generate_ms",
        "mesh_ms",
    ] {
        assert!(v.get(key).is_some(), "missing {key} in {v}");
    }
    assert_eq!(v["species"], "Quaking Aspen");
    assert_eq!(v["seed"], 3);
    assert_eq!(v["stems_per_level"][0], 1);
    let (doc, _, _) = gltf::import(&out).expect("valid GLB");
    let tris: usize = doc
        .meshes()
        .flat_map(|m| {
            m.primitives()
                .map(|p| p.indices().unwrap().count() / 3)
                .collect::<Vec<_>>()
        })
        .sum();
    assert_eq!(tris as u64, v["triangles"].as_u64().unwrap());
    // The preview is a real PNG with something drawn in it.
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn same_seed_same_bytes_other_seed_other_tree() {
    let dir = tempfile::tempdir().unwrap();
    let path = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    for (name, seed) in [("a.glb", "9"), ("b.glb", "9"), ("c.glb", "10")] {
        assert!(
            sylva(&[
                "generate",
                "black_tupelo",
                "--seed",
                seed,
                "-o",
                &path(name)
            ])
            .status
            .success()
        );
    }
    let read = |n: &str| std::fs::read(path(n)).unwrap();
    assert_eq!(read("a.glb"), read("b.glb"));
    assert_ne!(read("a.glb"), read("c.glb"));
}

#[test]
fn obj_export_writes_obj_and_mtl() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("oak.obj");
    let run = sylva(&[
        "generate",
        "ca_black_oak",
        "--quality",
        "0.5",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let obj = std::fs::read_to_string(&out).unwrap();
    assert!(obj.contains("mtllib oak.mtl"));
    assert!(dir.path().join("oak.mtl").exists());
    assert!(text(&run.stdout).contains("stems per level"));
}

#[test]
fn arbaro_files_and_parameter_overrides_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.glb");
    let xml = arbaro("sassafras.xml");
    let run = sylva(&[
        "generate",
        xml.to_str().unwrap(),
        "--set",
        "Leaves=0",
        "--levels",
        "2",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["leaves"], 0);
    assert_eq!(v["stems_per_level"].as_array().unwrap().len(), 2);
    // Arbaro's shave-grass has ScaleV > Scale: it loads with a warning.
    let run = sylva(&[
        "generate",
        arbaro("shave-grass.xml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stderr).contains("warning") && text(&run.stderr).contains("ScaleV"));
}

#[test]
fn species_list_and_show() {
    let run = sylva(&["species", "list"]);
    assert!(run.status.success());
    let list = text(&run.stdout);
    for id in [
        "quaking_aspen",
        "black_tupelo",
        "weeping_willow",
        "ca_black_oak",
    ] {
        assert!(list.contains(id), "{list}");
    }
    let run = sylva(&["species", "show", "black_tupelo"]);
    let show = text(&run.stdout);
    assert!(run.status.success());
    assert!(
        show.lines()
            .any(|l| l.starts_with("1DownAngleV") && l.contains("-40") && l.contains("deg")),
        "{show}"
    );
    assert!(show.contains("AttractionUp"));
    // --toml prints a file that loads back to the same species.
    let run = sylva(&["species", "show", "weeping_willow", "--toml"]);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("w.toml");
    std::fs::write(&file, &run.stdout).unwrap();
    let out = dir.path().join("w.glb");
    let made = sylva(&[
        "generate",
        file.to_str().unwrap(),
        "--levels",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(made.status.success(), "{}", text(&made.stderr));
}

#[test]
fn bad_input_gives_clear_errors_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let write = |name: &str, body: &str| {
        let p = d.join(name);
        std::fs::write(&p, body).unwrap();
        p.to_str().unwrap().to_string()
    };
    let malformed = write("broken.toml", "[params\nShape = 7\n");
    fails(&["generate", &malformed], &["broken.toml", "TOML"], d);
    let out_of_range = write(
        "range.toml",
        "[species]\nname = \"r\"\n[params]\nShape = 7\n1DownAngle = 240\n",
    );
    fails(
        &["generate", &out_of_range],
        &["1DownAngle", "240", "-180..180", "line 5"],
        d,
    );
    let negative = write("neg.toml", "[params]\nScale = 5\nScaleV = 6\n");
    fails(&["generate", &negative], &["ScaleV", "Scale"], d);
    let levels = write("levels.toml", "[params]\nLevels = 50\n");
    fails(&["generate", &levels], &["Levels", "50", "1..9"], d);
    let bad_xml = write(
        "bad.xml",
        "<arbaro><species name='x'><param name='Shape' value='7'></arbaro>",
    );
    fails(&["generate", &bad_xml], &["bad.xml", "XML"], d);
    let unknown_xml = write(
        "unknown.xml",
        "<arbaro><species name='x'>\n<param name='Bogus' value='7'/></species></arbaro>",
    );
    fails(&["generate", &unknown_xml], &["Bogus", "line 2"], d);
    fails(
        &["generate", "quaking_aspen", "--set", "1Branches=1000000000"],
        &["1Branches", "1000000000"],
        d,
    );
    fails(
        &[
            "generate",
            "quaking_aspen",
            "--set",
            "2Branches=90000",
            "--set",
            "3Branches=0",
        ],
        &["budget", "--max-triangles"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--max-triangles", "1000"],
        &["budget"],
        d,
    );
    fails(
        &["generate", "no_such_tree"],
        &["no_such_tree", "species list"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--set", "Shape"],
        &["NAME=VALUE"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--quality", "0"],
        &["quality"],
        d,
    );
    // An unknown output format fails before any work.
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "-o",
        d.join("x.fbx").to_str().unwrap(),
    ]);
    assert!(!run.status.success() && text(&run.stderr).contains(".glb or .obj"));
}
