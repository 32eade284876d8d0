//! What the subcommands share: a species loaded with its `--set` overrides, the mesh options a
//! species asks for, the benchmark set and its timer, picture sizes and PNG files, a grown
//! street tree's colours. Imports no subcommand, so that none of
//! them imports another through it.

use anyhow::{Context, Result};
use image::ImageEncoder;
use std::path::Path;
use std::time::Instant;
use sylva::TreeParams;
use sylva::export::write_atomically;
use sylva::growth::Measured;
use sylva::mesh::MeshOptions;

/// The paper's four appendix species: the benchmark set.
pub const APPENDIX_SPECIES: [&str; 4] = [
    "quaking_aspen",
    "black_tupelo",
    "weeping_willow",
    "ca_black_oak",
];

/// Fastest of `runs` timings of `f`, milliseconds (the least disturbed by a shared machine).
pub fn fastest_ms(runs: u32, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let mut best = f64::MAX;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        f()?;
        best = best.min(t.elapsed().as_secs_f64());
    }
    Ok(best * 1e3)
}

/// Loads the species and applies `--set` overrides.
pub fn load_params(species: &str, overrides: &[String]) -> Result<TreeParams> {
    let mut params = sylva::species::load(species)?;
    for note in &params.notes {
        eprintln!("sylva: warning: {species}: {note}");
    }
    for item in overrides {
        let (name, value) = item.split_once('=').with_context(|| {
            format!("--set {item}: expected NAME=VALUE, e.g. --set 1Branches=30")
        })?;
        let value: f64 = value
            .trim()
            .parse()
            .with_context(|| format!("--set {item}: `{value}` is not a number"))?;
        params
            .set(name.trim(), value)
            .with_context(|| format!("--set {item}"))?;
    }
    params
        .validate()
        .with_context(|| format!("species {species}"))?;
    Ok(params)
}

pub fn mesh_options(params: &TreeParams, quality: f64) -> MeshOptions {
    // Arbaro's Smooth (0..1, default 0.5) scales the mesh resolution around the default.
    MeshOptions {
        quality: quality * (0.5 + params.smooth),
        ..Default::default()
    }
}

/// Parses `WxH`.
pub fn parse_size(text: &str) -> Result<(u32, u32)> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--size {text}: expected WIDTHxHEIGHT, e.g. 1280x720"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (16..=8192).contains(v))
            .with_context(|| {
                format!("--size {text}: each side must be a whole number of pixels, 16..8192")
            })
    };
    Ok((parse(w)?, parse(h)?))
}

pub fn encode_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgba, width, height, image::ExtendedColorType::Rgba8)
        .context("encoding PNG")?;
    write_atomically(path, &bytes)?;
    Ok(())
}

/// Colours of a grown street tree's pictures and models: bark, and leaves (evergreens darker).
pub fn street_tree_colours(m: &Measured) -> ([f32; 3], [f32; 3]) {
    let evergreen = m.species.tree_type.get(1..2) == Some("E");
    let leaves = if evergreen {
        [0.2, 0.36, 0.16]
    } else {
        [0.33, 0.5, 0.2]
    };
    ([0.42, 0.36, 0.3], leaves)
}
