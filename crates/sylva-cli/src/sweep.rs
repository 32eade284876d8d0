//! `sylva sweep`: every species of every region of the Urban Tree Database grown through the
//! ages its data cover and measured against its targets: a line per species and region, the
//! count within bounds, and the targets the data themselves limit.

use crate::args::SweepArgs;
use crate::shared::{headless, save_picture, with_progress};
use anyhow::{Context, Result, bail};
use sylva::export::write_atomically;
use sylva::growth::Database;
use sylva::growth::survey::sweep::{SweepRecord, growable_pairs, markdown, sweep_all};
use sylva::record::to_json;
use sylva::skeleton::Skeleton;
use sylva::street::energy::opacity::{CoverageRecord, LeafAndBare, OpacityRecord};
use sylva_render::coverage;

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
            println!("{}", to_json(&SweepRecord::of(r)));
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

/// A crown's picture measured in leaf and bare (`--picture`).
type Pictured = Option<LeafAndBare<CoverageRecord>>;

/// `--beam AGES`: the share of a beam each crown stops, in leaf and bare; with `--picture`,
/// what its picture covers too.
fn beam(pairs: &[sylva::growth::Measured], args: &SweepArgs) -> Result<()> {
    use sylva::street::energy::opacity::opacity_all;
    if let Some(a) = args.beam.iter().find(|a| !a.is_finite() || **a < 1.0) {
        bail!("--beam {a}: ages are years from planting, 1 or more");
    }
    if let Some(px) = args.picture.filter(|px| !(64..=8192).contains(px)) {
        bail!("--picture {px}: expected 64 to 8192 pixels a side");
    }
    let mut ages = args.beam.clone();
    ages.sort_by(f64::total_cmp);
    ages.dedup();
    if pairs.iter().all(|m| ages[0] > m.ages.1) {
        let m = &pairs[0];
        bail!(
            "--beam {}: {} in {} is grown to {:.0} years (the ages its data cover)",
            ages[0],
            m.species.code,
            m.region.code,
            m.ages.1
        );
    }
    // Ages past a species' data are left out of its rows, and said so.
    for m in pairs {
        let past: Vec<String> = ages
            .iter()
            .filter(|&&a| a > m.ages.1)
            .map(|a| a.to_string())
            .collect();
        if !past.is_empty() {
            eprintln!(
                "sylva: {} in {}: its data end at {:.0} years; age {} left out",
                m.species.code,
                m.region.code,
                m.ages.1,
                past.join(", ")
            );
        }
    }
    let renderer = args.picture.map(|_| headless()).transpose()?;
    if let Some(dir) = &args.pictures {
        std::fs::create_dir_all(dir).with_context(|| format!("--pictures {}", dir.display()))?;
    }
    let picture =
        |m: &sylva::growth::Measured, age: f64, skeleton: &Skeleton| -> Result<Pictured> {
            let (Some(renderer), Some(px)) = (&renderer, args.picture) else {
                return Ok(None);
            };
            let drawn = coverage::crown_coverage(renderer, m, skeleton, px)?;
            if let Some(dir) = &args.pictures {
                for (what, (_, png)) in [("leaf", &drawn.leaf), ("bare", &drawn.bare)] {
                    let name = format!("{}-{}-{age}-{what}.png", m.region.code, m.species.code);
                    save_picture(&dir.join(name), png)?;
                }
            }
            Ok(Some(LeafAndBare {
                leaf: drawn.leaf.0.record(),
                bare: drawn.bare.0.record(),
            }))
        };
    let rows = with_progress(pairs.len(), |tick| {
        opacity_all(pairs, &ages, args.seed, &picture, &tick)
    });
    if !args.json {
        println!(
            "Share of a beam the crown stops over its outline (street::energy::opacity), in leaf and \
             bare, seen from the side and along a sun 60 degrees up. Published: 65-80% in leaf, \
             30-40% bare (Heisler 1986, inside street trees' shadows).{}",
            if args.picture.is_some() {
                " Picture: the share of the outline the renderer's picture from the side covers, \
                 in leaf and bare, and the leaf share of what it covers."
            } else {
                ""
            }
        );
        print!(
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
        if args.picture.is_some() {
            print!(
                "   {:>6} {:>6} {:>6} {:>6}",
                "pic", "bare", "leaf%", "tips%"
            );
        }
        println!();
    }
    for (r, pictured) in rows.iter().flatten() {
        let pictured = pictured.as_ref().map_err(|e| anyhow::anyhow!("{e:#}"))?;
        if args.json {
            println!("{}", to_json(&OpacityRecord::of(r, *pictured)));
        } else {
            print!(
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
            if let Some(LeafAndBare { leaf: l, bare: w }) = pictured {
                print!(
                    "   {:>5.0}% {:>5.0}% {:>5.0}% {:>5.1}%",
                    l.covered * 100.0,
                    w.covered * 100.0,
                    l.leaf_share * 100.0,
                    l.bare_tips * 100.0
                );
            }
            println!();
        }
    }
    Ok(())
}

fn short(k: usize) -> &'static str {
    ["H", "DBH", "CD", "CH", "LA"][k]
}
