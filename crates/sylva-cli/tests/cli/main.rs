//! Runs the real `sylva` binary and reads back what it writes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod city;
mod forest;
mod generate;
mod grow;
mod lobes;
mod nagel;
mod records;
mod regrowth;
mod render;
mod street;
mod view;

pub fn sylva(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sylva"))
        .args(args)
        .output()
        .expect("runs sylva")
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs a command that must succeed and prints one JSON object a line: the objects.
pub fn json_lines(args: &[&str]) -> Vec<serde_json::Value> {
    let run = sylva(args);
    assert!(run.status.success(), "{args:?}: {}", text(&run.stderr));
    text(&run.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

pub fn arbaro(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/arbaro-species")
        .join(name)
}

/// Runs a generation that must fail: non-zero exit, a message containing every `needle`, no file.
pub fn fails(args: &[&str], needles: &[&str], dir: &Path) {
    let out = dir.join("bad.glb");
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["-o", out.to_str().unwrap()]);
    let run = sylva(&all);
    let err = text(&run.stderr);
    assert!(!run.status.success(), "{args:?} should fail");
    assert!(err.starts_with("sylva: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists(), "{args:?} left a file");
    let leftovers: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert!(leftovers.iter().all(|e| {
        !e.as_ref()
            .unwrap()
            .file_name()
            .to_string_lossy()
            .ends_with(".tmp")
    }));
}

pub fn png_size(path: &Path) -> (u32, u32) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (img.width(), img.height())
}

/// The JSON chunk of a GLB file.
pub fn glb_json(path: &Path) -> serde_json::Value {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).unwrap()
}

pub fn profiles(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../profiles")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// Counts `P` and `L` lines of a vector file.
pub fn pen_moves(path: &Path) -> (usize, usize) {
    let v = std::fs::read_to_string(path).unwrap();
    let count = |c| v.lines().filter(|l| l.starts_with(c)).count();
    assert_eq!(
        count('P') + count('L'),
        v.lines().count(),
        "only P and L lines"
    );
    (count('P'), count('L'))
}

/// Dark pixels of a PNG written by a drawing.
pub fn inked(path: &Path) -> usize {
    let img = image::open(path).unwrap().to_rgb8();
    img.pixels()
        .filter(|p| p.0.iter().any(|&c| c < 160))
        .count()
}

/// Writes an input file `in-NAME` (which [`refuses`] does not count as output); its path.
pub fn scratch_input(dir: &Path, name: &str, body: &str) -> String {
    let path = dir.join(format!("in-{name}"));
    std::fs::write(&path, body).unwrap();
    path.to_string_lossy().into_owned()
}

/// Path of an output file in `dir`, as text.
pub fn scratch(dir: &Path, name: &str) -> String {
    dir.join(name).to_string_lossy().into_owned()
}

/// A command that must fail: non-zero exit, every needle in the message, no file, no temp file.
pub fn refuses(args: &[&str], needles: &[&str], dir: &Path) {
    let run = sylva(args);
    let err = text(&run.stderr);
    assert!(!run.status.success(), "{args:?} should fail");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    let files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with("in-"))
        .collect();
    assert!(files.is_empty(), "{args:?} left {files:?}");
}
