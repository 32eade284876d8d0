//! Plants a mixed forest, grows its distinct trees in parallel and writes it as one GLB in
//! which every tree is a node sharing its variant's mesh.
//!
//! ```text
//! cargo run -p sylva --release --example plant_forest -- [COUNT] [OUT.glb]
//! ```

use sylva::export::write_atomically;
use sylva::forest::{ForestSpec, grow_meshes};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let count: u32 = args.next().map_or(Ok(200), |s| s.parse())?;
    let out = args.next().unwrap_or_else(|| "forest.glb".into());

    let spec = ForestSpec {
        species: vec![
            "quaking_aspen".into(),
            "hazel".into(),
            "black_tupelo".into(),
        ],
        count,
        area: [120.0, 80.0],
        seed: 7,
        ..Default::default()
    };
    // Species load first, so a misspelt name fails before any growing.
    let species = spec.load_species()?;
    let forest = grow_meshes(&spec, species, &|| {})?;
    write_atomically(out.as_ref(), &forest.to_glb()?)?;

    let (stored, placed) = forest.triangles();
    println!(
        "{} trees of {} variants grown in {:.2} s: {stored} triangles stored, {placed} placed -> {out}",
        forest.planting.trees.len(),
        forest.grown.len(),
        forest.seconds
    );
    Ok(())
}
