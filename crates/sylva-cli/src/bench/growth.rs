//! `sylva bench --growth`: milliseconds per growth step (production rules, light, meshing) of
//! a street tree as it passes 5,000, 10,000, 20,000 and 30,000 branch segments.

use anyhow::Result;
use sylva::bench::{GROWTH_STEPS, growth_steps};

/// Rudnick et al. 2007, 30,000 segments: growth, light and mesh, ms per step.
const RUDNICK_MS: (f64, f64, f64) = (40.0, 13.0, 60.0);

pub fn bench_growth(runs: u32) -> Result<()> {
    println!();
    println!(
        "growth steps of a silver maple (InlVal), 1/{GROWTH_STEPS} year each, {GROWTH_STEPS} \
         steps per row (growth and light: their mean; year = growth and light over the row's \
         year, what a step's length does not change); light: the sky's directions spread over the cores; \
         skeleton: wood and leaves at once, the leaves in runs of branches; mesh = skeleton and \
         mesh (quality 0.6: bark and leaves at once, leaves in runs), fastest of {runs}; x copy \
         = step total / time to copy the tree's skeleton; bark: the mesh alone with the maple's \
         bark pattern drawn (strips), and x plain: its ratio to the mesh alone without it"
    );
    println!(
        "{:>9} {:>5} {:>8} {:>10} {:>9} {:>8} {:>9} {:>13} {:>9} {:>9} {:>7} {:>8} {:>7}",
        "segments",
        "age",
        "leaves",
        "growth ms",
        "light ms",
        "year ms",
        "mesh ms",
        "(skeleton ms)",
        "total ms",
        "copy ms",
        "x copy",
        "bark ms",
        "x plain"
    );
    for row in growth_steps(runs)? {
        println!(
            "{:>9} {:>5.1} {:>8} {:>10.2} {:>9.2} {:>8.1} {:>9.2} {:>13.2} {:>9.2} {:>9.3} {:>7.0} \
             {:>8.2} {:>7.2}",
            row.segments,
            row.age,
            row.leaves,
            row.growth_ms,
            row.light_ms,
            (row.growth_ms + row.light_ms) * GROWTH_STEPS as f64,
            row.mesh_ms,
            row.skeleton_ms,
            row.total_ms(),
            row.copy_ms,
            row.total_ms() / row.copy_ms,
            row.patterned_mesh_ms,
            row.patterned_mesh_ms / row.plain_mesh_ms
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

/// A London plane in Modesto grown yearly to 40 on a narrow street: the time its yearly
/// accounts (carbon, rain, the façade's shade, conflicts) take beside the growth's.
pub fn bench_street() -> Result<()> {
    let t = sylva::bench::street_times("InlVal", "PLAC", 40.0)?;
    println!();
    println!(
        "street accounts, London plane (InlVal) grown yearly, {} years, on a narrow street \
         (facade 3.1 m, awnings, sign, wires, lamp): growth {:.2} s, accounts {:.3} s = {:.1}% \
         of the growth (target: under 5%)",
        t.years,
        t.growth_s,
        t.account_s,
        t.account_s / t.growth_s * 100.0
    );
    // Issue U: cutting and regrowing must not make ranking much slower than growing.
    let (pruned, grown) = sylva::bench::pruning_times("InlVal", "PLAC", 40.0, 2)?;
    println!(
        "pruning, the same plane ranked over 40 years: {pruned:.2} s with the site's regime \
         (us-street: lines every 4 years, raising and building clearance every 5), {grown:.2} s \
         never cut: {:.2} times (target: at most 1.20)",
        pruned / grown
    );
    Ok(())
}

/// How the grown crowns branch, beside the published twig and bifurcation figures (issue W).
pub fn bench_twigs() -> Result<()> {
    println!();
    println!(
        "branching at 10, 20 and 30 years (seed 0, no site): twigs (each axis beyond its last \
         lateral), their median length, the shares under 4 cm and of 10 cm or more, the \
         Horton-Strahler orders with their stream counts, and the bifurcation ratio"
    );
    println!(
        "{:<14} {:>4} {:>7} {:>9} {:>6} {:>6} {:>6}  streams by order",
        "species", "age", "twigs", "median cm", "<4 cm", ">=10", "ratio"
    );
    for (region, code) in sylva::bench::TWIG_SPECIES {
        for (age, b) in sylva::bench::branching_at(region, code, &[10.0, 20.0, 30.0])? {
            println!(
                "{:<14} {:>4} {:>7} {:>9.1} {:>6.2} {:>6.2} {:>6}  {:?}",
                format!("{region} {code}"),
                age,
                b.twigs,
                b.median_twig_cm.unwrap_or(f64::NAN),
                b.share_under(4.0),
                b.share_from(10.0),
                b.bifurcation_ratio
                    .map_or("-".into(), |r| format!("{r:.2}")),
                b.streams
            );
        }
    }
    println!(
        "published: most twigs 1-4 cm, their number falling steeply through 6-10 cm, old \
         branches only twigs under 5 cm (red maple, scarlet oak: \"Tree branches as populations \
         of twigs\"); bifurcation ratio 3.19 forest-grown, 7.05 open-grown sugar maple saplings \
         (Steingraeber, Kascht & Franck 1979)"
    );
    Ok(())
}
