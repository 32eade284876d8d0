//! Grows a street tree from the USDA Urban Tree Database to an age, compares it with the
//! measured equations, and writes it as a GLB.
//!
//! ```text
//! cargo run -p sylva --example grow_street_tree -- [SPECIES] [AGE] [REGION]
//! cargo run -p sylva --example grow_street_tree -- "London planetree" 20 InlVal
//! ```

use sylva::export::{Materials, to_glb, write_atomically};
use sylva::growth::survey::report::{MAX_AGE, MESH};
use sylva::growth::{Database, Grower, GrowthOptions, measure};
use sylva::mesh::mesh_tree;

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("grow_street_tree: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let species = args.next().unwrap_or_else(|| "PLAC".into());
    let age: f64 = match args.next() {
        Some(s) => s
            .parse()
            .map_err(|_| format!("AGE `{s}`: expected a number of years"))?,
        None => 20.0,
    };
    let region = args.next().unwrap_or_else(|| "InlVal".into());

    // A species code, scientific or common name; the region's equations as functions of age.
    let measured = Database::builtin().find(&region, &species)?;
    // The grower steps through every year up to the age asked for: bound it as `sylva grow`
    // does.
    if !(0.0..=MAX_AGE).contains(&age) {
        return Err(format!(
            "AGE {age}: expected 0..{MAX_AGE} years (the data for {} cover {:.0} to {:.0})",
            measured.label(),
            measured.ages.0,
            measured.ages.1
        )
        .into());
    }
    let label = measured.label();
    let (bark, leaves) = measured.colours();
    let mut grower = Grower::new(measured, GrowthOptions::default());
    grower.advance_to(age);
    let skeleton = grower.skeleton();

    // Measured the way the survey measured its trees, beside what the equations say.
    let grown = measure(&skeleton);
    let wanted = grower.targets(age);
    println!(
        "{label} at {age} years ({} segments):",
        grower.segment_count()
    );
    println!(
        "  height          {:6.1} m   (equations {:6.1})",
        grown.height, wanted.height
    );
    println!(
        "  crown diameter  {:6.1} m   (equations {:6.1})",
        grown.crown_diameter, wanted.crown_diameter
    );
    println!(
        "  DBH             {:6.1} cm  (equations {:6.1})",
        grown.dbh, wanted.dbh
    );
    println!(
        "  leaf area       {:6.0} m²  (equations {:6.0})",
        grown.leaf_area, wanted.leaf_area
    );

    let mesh = mesh_tree(&skeleton, &MESH);
    let out = format!("{}-{age}.glb", species.replace(' ', "_"));
    write_atomically(
        out.as_ref(),
        &to_glb(&mesh, &label, &Materials::from_srgb(bark, leaves))?,
    )?;
    println!("wrote {out}");
    Ok(())
}
