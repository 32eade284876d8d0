//! The growth engine's identity, for the cache of grown trees (`src/cache.rs`): a hash of every
//! file a grown tree depends on (the growth model and its data, the city's meshing, the
//! species files). A tree grown by another engine is never taken from the cache.

use std::hash::Hasher;
use std::path::{Path, PathBuf};

/// Folders, from the workspace root, whose files shape a grown and meshed tree.
const SOURCES: [&str; 4] = [
    "crates/sylva/src",
    "crates/sylva/data",
    "crates/sylva-city/src",
    "species",
];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files(&path, out);
        } else {
            out.push(path);
        }
    }
}

fn main() {
    let manifest = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = Path::new(&manifest).join("../..");
    let mut all = Vec::new();
    for dir in SOURCES {
        let dir = root.join(dir);
        println!("cargo:rerun-if-changed={}", dir.display());
        files(&dir, &mut all);
    }
    all.sort();
    // Two FNV-1a streams, one over the files in order and one in reverse, make 128 bits.
    let (mut a, mut b) = (
        fnv::FnvHasher::default(),
        fnv::FnvHasher::with_key(0x9e37_79b9_7f4a_7c15),
    );
    for (forward, backward) in all.iter().zip(all.iter().rev()) {
        for (h, path) in [(&mut a, forward), (&mut b, backward)] {
            let rel = path.strip_prefix(&root).unwrap_or(path);
            h.write(rel.to_string_lossy().as_bytes());
            h.write(&std::fs::read(path).unwrap_or_default());
        }
    }
    let id = format!("{:016x}{:016x}", a.finish(), b.finish());
    let out = Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("engine.rs");
    std::fs::write(
        &out,
        format!(
            "/// The growth engine's identity (`build.rs`).\npub const ENGINE: &str = \"{id}\";\n"
        ),
    )
    .expect("OUT_DIR is writable");
}
