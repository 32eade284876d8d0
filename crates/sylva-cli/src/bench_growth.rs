//! `sylva bench --growth`: milliseconds per growth step (production rules, light, meshing) of
//! a street tree as it passes 5,000, 10,000, 20,000 and 30,000 branch segments.

use crate::shared::fastest_ms;
use anyhow::{Context, Result, bail};
use sylva::growth::{Database, Grower, GrowthOptions};
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree_into};

const SIZES: [usize; 4] = [5_000, 10_000, 20_000, 30_000];
/// Steps timed at each size: one year.
const STEPS: usize = 20;
/// Rudnick et al. 2007, 30,000 segments: growth, light and mesh, ms per step.
const RUDNICK_MS: (f64, f64, f64) = (40.0, 13.0, 60.0);

pub fn bench_growth(runs: u32) -> Result<()> {
    let measured = Database::builtin()
        .find("InlVal", "PLAC")
        .context("London plane in the built-in database")?;
    let (_, last_age) = measured.ages;
    let mut grower = Grower::new(measured, GrowthOptions::default());
    let dt = 1.0 / GrowthOptions::default().steps_per_year as f64;
    println!();
    println!(
        "growth steps of a London plane (InlVal), 1/20 year each, {STEPS} steps per row; light: \
         the sky's directions spread over the cores, the rest on one thread; mesh = skeleton and \
         mesh (quality 0.6), fastest of {runs}; x copy = step total / time to copy the tree's \
         skeleton"
    );
    println!(
        "{:>9} {:>5} {:>8} {:>10} {:>9} {:>9} {:>13} {:>9} {:>9} {:>7}",
        "segments",
        "age",
        "leaves",
        "growth ms",
        "light ms",
        "mesh ms",
        "(skeleton ms)",
        "total ms",
        "copy ms",
        "x copy"
    );
    let mut skeleton = grower.skeleton();
    let mut mesh = TreeMesh::default();
    let options = MeshOptions {
        quality: 0.6,
        ..Default::default()
    };
    for size in SIZES {
        while grower.segment_count() < size {
            if grower.age() > last_age {
                bail!(
                    "the London plane stopped at {} segments by age {last_age:.0}",
                    grower.segment_count()
                );
            }
            grower.step_once(dt);
        }
        let (mut growth, mut light) = (0.0, 0.0);
        for _ in 0..STEPS {
            grower.step_once(dt);
            growth += grower.times.growth;
            light += grower.times.light;
        }
        let (growth, light) = (growth * 1e3 / STEPS as f64, light * 1e3 / STEPS as f64);
        let skeleton_ms = fastest_ms(runs, || {
            grower.skeleton_into(&mut skeleton);
            Ok(())
        })?;
        let mesh_ms = skeleton_ms
            + fastest_ms(runs, || {
                mesh_tree_into(&skeleton, &options, &mut mesh);
                Ok(())
            })?;
        // Baseline, same run: copying the tree's skeleton (memory traffic of its size).
        let mut copy = sylva::Skeleton::default();
        let copy_ms = fastest_ms(runs, || {
            copy.clone_from(&skeleton);
            Ok(())
        })?;
        let total = growth + light + mesh_ms;
        println!(
            "{:>9} {:>5.1} {:>8} {:>10.2} {:>9.2} {:>9.2} {:>13.2} {:>9.2} {:>9.3} {:>7.0}",
            grower.segment_count(),
            grower.age(),
            skeleton.leaves.len(),
            growth,
            light,
            mesh_ms,
            skeleton_ms,
            total,
            copy_ms,
            total / copy_ms
        );
    }
    let (g, l, m) = RUDNICK_MS;
    println!(
        "Rudnick et al. 2007 at 30,000 segments: {g} + {l} + {m} = {} ms per step on 2007 \
         hardware; target here: under 10 ms in total",
        g + l + m
    );
    Ok(())
}
