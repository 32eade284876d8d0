//! `sylva sweep`: every species of every region of the Urban Tree Database grown through the
//! ages its data cover and measured against its targets: a line per species and region, the
//! count within bounds, and the targets the data themselves limit.

use crate::args::SweepArgs;
use crate::shared::with_progress;
use anyhow::{Result, bail};
use sylva::export::write_atomically;
use sylva::growth::Database;
use sylva::growth::sweep::{QUANTITIES, growable_pairs, markdown, sweep_all};

pub fn run(args: &SweepArgs) -> Result<()> {
    let db = Database::builtin();
    for r in &args.region {
        if !db.regions().iter().any(|k| k.code.eq_ignore_ascii_case(r)) {
            let known: Vec<&str> = db.regions().iter().map(|k| k.code.as_str()).collect();
            bail!(
                "--region {r}: no such region; regions: {}",
                known.join(", ")
            );
        }
    }
    let mut pairs = growable_pairs(db, &args.region);
    if !args.species.is_empty() {
        pairs.retain(|m| {
            args.species
                .iter()
                .any(|c| c.eq_ignore_ascii_case(&m.species.code))
        });
    }
    if pairs.is_empty() {
        bail!("no species to sweep: --species names none that grows in the regions asked");
    }
    if !args.beam.is_empty() {
        return beam(&pairs, args);
    }
    let rows = with_progress(pairs.len(), |tick| {
        sweep_all(&pairs, args.seed, args.to, tick)
    });
    for r in &rows {
        if args.json {
            let misses: Vec<_> = r
                .misses()
                .iter()
                .map(|&(k, worst, age)| {
                    serde_json::json!({"quantity": QUANTITIES[k], "worst": worst, "age": age})
                })
                .collect();
            let adjusted: Vec<_> = r
                .adjustments
                .iter()
                .map(|a| {
                    serde_json::json!({
                        "quantity": QUANTITIES[a.quantity],
                        "ages": [a.ages.0, a.ages.1],
                        "shift": a.shift,
                        "why": a.why,
                    })
                })
                .collect();
            let line = serde_json::json!({
                "region": r.region,
                "species": r.code,
                "ages": [r.ages.0, r.ages.1],
                "worst": r.worst,
                "at": r.at,
                "within": r.within(),
                "misses": misses,
                "adjusted": adjusted,
                "seconds": r.seconds,
            });
            println!("{line}");
        } else {
            let worst: Vec<String> = (0..5)
                .map(|k| format!("{} {:+5.1}%@{:<3}", short(k), r.worst[k] * 100.0, r.at[k]))
                .collect();
            println!(
                "{:<7} {:<7} ages {:>3}-{:<3} {}  {}  {:.0} s",
                r.region,
                r.code,
                r.ages.0,
                r.ages.1,
                worst.join(" "),
                if r.within() { "within" } else { "MISSES" },
                r.seconds
            );
        }
    }
    let within = rows.iter().filter(|r| r.within()).count();
    eprintln!(
        "{within} of {} species-regions within bounds at every age (height, DBH 5%; crown \
         diameter, crown height, leaf area 10%)",
        rows.len()
    );
    if let Some(path) = &args.markdown {
        write_atomically(path, markdown(&rows, args.seed).as_bytes())?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// `--beam AGES`: the share of a beam each crown stops, in leaf and bare.
fn beam(pairs: &[sylva::growth::Measured], args: &SweepArgs) -> Result<()> {
    use sylva::street::opacity::opacity_all;
    if let Some(a) = args.beam.iter().find(|a| !a.is_finite() || **a < 1.0) {
        bail!("--beam {a}: ages are years from planting, 1 or more");
    }
    let mut ages = args.beam.clone();
    ages.sort_by(f64::total_cmp);
    ages.dedup();
    let rows = with_progress(pairs.len(), |tick| {
        opacity_all(pairs, &ages, args.seed, &tick)
    });
    if !args.json {
        println!(
            "Share of a beam the crown stops over its outline (street::opacity), in leaf and \
             bare, seen from the side and along a sun 60 degrees up. Published: 65-80% in leaf, \
             30-40% bare (Heisler 1986, inside street trees' shadows)."
        );
        println!(
            "{:<7} {:<7} {:>4} {:>7} {:>7}  {:>6} {:>6}  {:>6} {:>6}  {:>8}",
            "region",
            "species",
            "age",
            "leaf m2",
            "wood m2",
            "side",
            "bare",
            "sun",
            "bare",
            "outline"
        );
    }
    for r in rows.iter().flatten() {
        if args.json {
            let b = |s: sylva::street::crown::BeamStop| serde_json::json!({"stopped": s.stopped, "outline_m2": s.outline_m2});
            println!(
                "{}",
                serde_json::json!({
                    "region": r.region, "species": r.code, "age": r.age,
                    "leaf_area_m2": r.leaf_area_m2, "bark_area_m2": r.bark_area_m2,
                    "side": {"leaf": b(r.side.0), "bare": b(r.side.1)},
                    "sun": {"leaf": b(r.sun.0), "bare": b(r.sun.1)},
                })
            );
        } else {
            println!(
                "{:<7} {:<7} {:>4.0} {:>7.0} {:>7.0}  {:>5.0}% {:>5.0}%  {:>5.0}% {:>5.0}%  {:>6.1} m2",
                r.region,
                r.code,
                r.age,
                r.leaf_area_m2,
                r.bark_area_m2,
                r.side.0.stopped * 100.0,
                r.side.1.stopped * 100.0,
                r.sun.0.stopped * 100.0,
                r.sun.1.stopped * 100.0,
                r.side.0.outline_m2
            );
        }
    }
    Ok(())
}

fn short(k: usize) -> &'static str {
    ["H", "DBH", "CD", "CH", "LA"][k]
}
