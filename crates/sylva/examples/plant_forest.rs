//! Plants a mixed forest, grows its distinct trees in parallel and writes it as one GLB in
//! which every tree is a node sharing its variant's mesh.
//!
//! ```text
//! cargo run -p sylva --release --example plant_forest -- [COUNT] [OUT.glb]
//! ```

use sylva::export::write_atomically;
use sylva::forest::{ForestSpec, grow_meshes};

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("plant_forest: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let count: u32 = match args.next() {
        Some(s) => s
            .parse()
            .map_err(|_| format!("COUNT `{s}`: expected a whole number"))?,
        None => 200,
    };
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
