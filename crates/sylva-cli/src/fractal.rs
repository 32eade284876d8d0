//! `sylva fractal`: Honda's fractal tree as Nagel (1986) drew it for landscape CAD. Vector
//! files and drawings stream generation by generation in constant memory; a mesh is built only
//! when one is asked for.

use crate::args::FractalArgs;
use crate::shared::{draw_options, print_written};
use anyhow::Result;
use sylva::drawing::{MeshLook, Meshable, plan, write_outputs};
use sylva::nagel::FractalParams;

pub fn run(args: &FractalArgs) -> Result<()> {
    let planned = plan(&args.out.outputs)?;
    let fractal = FractalParams {
        theta1: args.theta1,
        theta2: args.theta2,
        r1: args.r1,
        r2: args.r2,
        depth: args.depth,
        tip_daughters: args.tip_daughters,
        trunk_length: args.trunk_length,
        trunk_radius: args.trunk_radius,
        length_variation: args.vary_length,
        angle_variation: args.vary_angle,
        seed: args.seed,
        leaves: args.leaves,
        max_segments: args.max_segments,
    }
    .build()
    .map_err(|e| anyhow::anyhow!("{e}").context("sylva fractal"))?;
    let written = write_outputs(
        &planned,
        &draw_options(&args.out),
        &fractal,
        Meshable::Build(&|| fractal.skeleton()),
        "fractal tree",
        &MeshLook::default(),
    )?;
    println!(
        "fractal tree: theta {}°/{}°, R {}/{}, depth {}: {} segments, {} tips",
        args.theta1,
        args.theta2,
        args.r1,
        args.r2,
        args.depth,
        fractal.segment_count(),
        fractal.tip_count()
    );
    print_written(written);
    Ok(())
}
