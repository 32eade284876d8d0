//! `sylva forest`: many trees of several species on a plot, grown in parallel and written as
//! one GLB in which every tree is a node referring to its variant's mesh.

use crate::args::ForestArgs;
use crate::shared::{forest_species, with_progress};
use anyhow::{Context, Result, bail};
use sylva::export::write_atomically;
use sylva::forest::{ForestSpec, grow_meshes, plant};
use sylva::record::to_json;

fn parse_area(text: &str) -> Result<[f32; 2]> {
    let (w, d) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--area {text}: expected WIDTHxDEPTH in metres, e.g. 200x100"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f32>()
            .with_context(|| format!("--area {text}: `{v}` is not a number of metres"))
    };
    Ok([parse(w)?, parse(d)?])
}

/// The forest a forest file or the flags describe.
fn spec_of(args: &ForestArgs) -> Result<ForestSpec> {
    if let Some(file) = &args.file {
        return Ok(ForestSpec::from_file(file)?);
    }
    let spec = ForestSpec {
        species: args.species.clone(),
        count: args.count,
        area: parse_area(&args.area)?,
        seed: args.seed,
        variants: args.variants,
        quality: args.quality,
    };
    spec.validate().map_err(|e| anyhow::anyhow!("--{e}"))?;
    Ok(spec)
}

pub fn run(args: &ForestArgs) -> Result<()> {
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"))
    {
        bail!(
            "output {}: a forest is written as GLB; use a .glb file name",
            args.output.display()
        );
    }
    let spec = spec_of(args)?;
    let origin = || match &args.file {
        Some(f) => f.display().to_string(),
        None => "sylva forest".into(),
    };
    let species = forest_species(&spec).with_context(origin)?;
    let variants = plant(&spec).variants.len();
    let forest =
        with_progress(variants, |tick| grow_meshes(&spec, species, tick)).with_context(origin)?;
    write_atomically(&args.output, &forest.to_glb()?)?;
    let (stored, placed) = forest.triangles();
    let count = forest.planting.trees.len();
    let per_second = variants as f64 / forest.seconds;
    if args.json {
        let mut record = to_json(&forest.record());
        record["output"] = args.output.display().to_string().into();
        println!("{record}");
    } else {
        println!(
            "{count} trees ({variants} distinct) on {}x{} m: {stored} triangles stored, {placed} placed",
            spec.area[0], spec.area[1]
        );
        println!(
            "  grown in {:.1} s on {} threads ({per_second:.1} trees/s); wrote {}",
            forest.seconds,
            rayon::current_num_threads(),
            args.output.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn areas() {
        assert!(parse_area("10x").is_err());
        assert!(parse_area("10xten").is_err());
        assert_eq!(parse_area("20x30").unwrap(), [20.0, 30.0]);
    }
}
