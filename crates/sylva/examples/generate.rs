//! Generates a Weber-Penn tree from a built-in species and writes it as a GLB, printing what
//! was made.
//!
//! ```text
//! cargo run -p sylva --example generate -- [SPECIES] [SEED] [OUT.glb]
//! cargo run -p sylva --example generate -- black_tupelo 3 tupelo.glb
//! ```

use sylva::export::{Materials, to_glb, write_atomically};
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva::{GenerateOptions, species};

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("generate: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "quaking_aspen".into());
    let seed: u64 = match args.next() {
        Some(s) => s
            .parse()
            .map_err(|_| format!("SEED `{s}`: expected a whole number"))?,
        None => 0,
    };
    let out = args.next().unwrap_or_else(|| format!("{name}-{seed}.glb"));

    // A built-in name or a .toml / Arbaro .xml file.
    let params = species::load(&name)?;
    let options = GenerateOptions {
        seed,
        ..Default::default()
    };
    let skeleton = sylva::generate(&params, &options)?;
    let mesh = mesh_tree(&skeleton, &MeshOptions::for_species(&params, 1.0));
    let materials = Materials::from_srgb(params.bark_color, params.leaf_color);
    write_atomically(out.as_ref(), &to_glb(&mesh, &params.name, &materials)?)?;

    let stats = skeleton.stats();
    println!(
        "{} (seed {seed}): {:.1} m tall, crown {:.1} m, {} leaves, {} triangles -> {out}",
        params.name,
        stats.height,
        stats.crown_width,
        stats.leaves,
        mesh.triangle_count()
    );
    Ok(())
}
