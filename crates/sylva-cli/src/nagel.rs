//! `sylva fractal`, `sylva whisk` and `sylva stick`: Nagel's trees for landscape CAD.

use crate::args::LineOutputArgs;
use crate::args::{FractalArgs, RibArgs, StickArgs, WhiskArgs};
use crate::lines::{LineFormat, MeshLook, Meshable, plan, write, write_skeleton};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use sylva::nagel::{FractalParams, WhiskParams, read_profile, read_sticks, stick_tree, whisk_tree};

pub fn fractal(args: &FractalArgs) -> Result<()> {
    let planned = plan(&args.out)?;
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
    let written = write(
        &planned,
        &args.out,
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
    for line in written {
        println!("wrote {line}");
    }
    Ok(())
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

fn rib_params(ribs: &RibArgs, rings: u32, spokes: u32) -> Result<WhiskParams> {
    let count = match (ribs.ribs, ribs.density) {
        (Some(n), _) => n,
        (None, Some(d)) => sylva::nagel::whisk::density_ribs(d)
            .with_context(|| format!("--density {d}: expected 1 (least dense) to 5 (most)"))?,
        (None, None) => 8,
    };
    if let Some(h) = ribs.height
        && !(h.is_finite() && h > 0.0 && h <= 200.0)
    {
        bail!("--height {h}: expected 0..200 metres");
    }
    Ok(WhiskParams {
        ribs: count,
        rings,
        spokes,
        wire_radius: ribs.wire_radius,
        trunk_radius: ribs.trunk_radius,
    })
}

/// Writes a whisk or stick tree's outputs and prints what was made.
fn finish(
    planned: &[(PathBuf, LineFormat)],
    out: &LineOutputArgs,
    skeleton: &sylva::Skeleton,
    name: &str,
    summary: String,
) -> Result<()> {
    let written = write_skeleton(planned, out, skeleton, name, &MeshLook::default())?;
    let stats = skeleton.stats();
    println!(
        "{summary}: {} stems, {:.2} m tall, crown {:.2} m across",
        skeleton.stems.len(),
        stats.height,
        stats.crown_width
    );
    for line in written {
        println!("wrote {line}");
    }
    Ok(())
}

pub fn whisk(args: &WhiskArgs) -> Result<()> {
    let planned = plan(&args.out)?;
    let params = rib_params(&args.ribs, args.rings, args.spokes)?;
    let name = args.profile.display().to_string();
    let profile = read_profile(&name, &read(&args.profile)?, args.ribs.height)?;
    let skeleton = whisk_tree(&profile, &params)?;
    let summary = format!(
        "whisk tree: {} ribs, {} rings, {} spokes per rib",
        params.ribs, params.rings, params.spokes
    );
    finish(&planned, &args.out, &skeleton, "whisk tree", summary)
}

pub fn stick(args: &StickArgs) -> Result<()> {
    let planned = plan(&args.out)?;
    let params = rib_params(&args.ribs, 0, 0)?;
    let name = args.branches.display().to_string();
    let branches = read_sticks(&name, &read(&args.branches)?, args.ribs.height)?;
    let skeleton = stick_tree(&branches, &params)?;
    let summary = format!(
        "stick tree: {} branches x {} ribs",
        branches.len(),
        params.ribs
    );
    finish(&planned, &args.out, &skeleton, "stick tree", summary)
}
