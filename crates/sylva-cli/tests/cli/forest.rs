//! `sylva forest`: shared variants written as instances.

use crate::*;

#[test]
fn forest_writes_shared_variants_as_instances() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("forest.glb");
    let run = sylva(&[
        "forest",
        "--species",
        "quaking_aspen,hazel",
        "--count",
        "25",
        "--area",
        "40x30",
        "--variants",
        "2",
        "--quality",
        "0.3",
        "--seed",
        "5",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["trees"], 25);
    let variants = v["variants"].as_u64().unwrap();
    assert!((2..=4).contains(&variants), "{v}");
    let (doc, _, _) = gltf::import(&out).expect("valid GLB");
    assert_eq!(
        doc.meshes().count() as u64,
        variants,
        "one mesh per variant"
    );
    let nodes: Vec<_> = doc.nodes().collect();
    assert_eq!(nodes.len(), 25, "one node per tree");
    for n in &nodes {
        let (t, _, s) = n.transform().decomposed();
        // Y up: trees stand on the ground (y = 0) inside the plot.
        assert!(
            t[1].abs() < 1e-6 && t[0].abs() <= 20.0 && t[2].abs() <= 15.0,
            "{t:?}"
        );
        assert!((0.85..=1.15).contains(&s[0]));
    }
    for (args, needle) in [
        (
            vec![
                "forest",
                "--species",
                "quaking_aspen",
                "--count",
                "0",
                "-o",
                "f.glb",
            ],
            "--count",
        ),
        (
            vec![
                "forest",
                "--species",
                "quaking_aspen",
                "--area",
                "big",
                "-o",
                "f.glb",
            ],
            "WIDTHxDEPTH",
        ),
        (
            vec!["forest", "--species", "no_such_tree", "-o", "f.glb"],
            "no_such_tree",
        ),
    ] {
        let run = sylva(&args);
        assert!(
            !run.status.success() && text(&run.stderr).contains(needle),
            "{args:?}: {}",
            text(&run.stderr)
        );
    }
}

#[test]
fn a_unique_forest_is_the_same_on_one_thread_as_on_two() {
    // Every tree its own, of the paper's four appendix species by default: the same bytes
    // whatever the number of threads that grew them.
    let dir = tempfile::tempdir().unwrap();
    let write = |threads: &str| {
        let out = dir.path().join(format!("forest-{threads}.glb"));
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_sylva"))
            .args([
                "forest",
                "--count",
                "8",
                "--variants",
                "0",
                "--quality",
                "0.1",
            ])
            .args(["--seed", "3", "--json", "-o", out.to_str().unwrap()])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .expect("runs sylva");
        assert!(run.status.success(), "{}", text(&run.stderr));
        let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
        assert_eq!(
            (v["trees"].as_u64(), v["variants"].as_u64()),
            (Some(8), Some(8))
        );
        std::fs::read(&out).unwrap()
    };
    let (one, two) = (write("1"), write("2"));
    assert!(one == two, "{} and {} bytes differ", one.len(), two.len());
    let (doc, _, _) = gltf::import_slice(&one).expect("valid GLB");
    assert_eq!(doc.meshes().count(), 8, "one mesh per tree");
}
