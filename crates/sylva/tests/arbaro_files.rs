//! Every Arbaro species and test file shipped with Arbaro 1.9.9b must load and generate.
//! The files are read from the shared data folder, never copied into the repository.

use std::path::PathBuf;
use sylva::{GenerateOptions, generate, params::from_arbaro_xml};

fn arbaro_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/arbaro-species")
}

fn xml_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for dir in [arbaro_dir(), arbaro_dir().join("test")] {
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "xml") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

#[test]
fn all_24_arbaro_files_load_and_generate() {
    let files = xml_files();
    assert_eq!(
        files.len(),
        24,
        "expected Arbaro's 16 species and 8 test files"
    );
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let params = from_arbaro_xml(&text, &name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let skeleton = generate(&params, &GenerateOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let stats = skeleton.stats();
        assert!(stats.stems_per_level[0] >= 1, "{name}");
        assert!(
            stats.height > 0.0 && stats.height.is_finite(),
            "{name}: height {}",
            stats.height
        );
        assert!(
            skeleton
                .sections
                .iter()
                .all(|c| c.position.is_finite() && c.radius.is_finite()),
            "{name}"
        );
        if params.leaves != 0 {
            assert!(
                stats.leaves > 0,
                "{name} has Leaves {} but no leaf",
                params.leaves
            );
        }
    }
}

#[test]
fn arbaro_quaking_aspen_matches_the_builtin_paper_values() {
    // Arbaro's file and the paper's appendix agree on the aspen's model parameters.
    let text = std::fs::read_to_string(arbaro_dir().join("quaking_aspen.xml")).unwrap();
    let arbaro = from_arbaro_xml(&text, "quaking_aspen.xml").unwrap();
    let paper = sylva::species::builtin("quaking_aspen").unwrap();
    for name in [
        "Shape",
        "BaseSize",
        "Scale",
        "1Branches",
        "1DownAngleV",
        "2CurveV",
        "Leaves",
        "LeafScale",
    ] {
        assert_eq!(arbaro.get(name), paper.get(name), "{name}");
    }
    // A parameter Arbaro's file omits takes Arbaro's documented default.
    assert_eq!(arbaro.get("3Branches"), Some(5.0));
}
