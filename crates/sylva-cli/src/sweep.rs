//! `sylva sweep`: every species of every region of the Urban Tree Database grown through the
//! ages its data cover and measured against its targets: a line per species and region, the
//! count within bounds, and the targets the data themselves limit.

use crate::args::SweepArgs;
use crate::shared::{headless, save_picture, with_progress};
use anyhow::{Context, Result, bail};
use sylva::export::write_atomically;
use sylva::growth::Database;
use sylva::growth::report;
use sylva::growth::sweep::{QUANTITIES, growable_pairs, markdown, sweep_all};
use sylva::growth::{Month, dressed_mesh};
use sylva::skeleton::Skeleton;
use sylva::street::energy::crown::leaf_centre;
use sylva_render::coverage::{self, Coverage};

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

/// A crown's picture measured in leaf and bare (`--picture`).
type Pictured = Option<(Coverage, Coverage)>;

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
            let (mesh, _) = dressed_mesh(skeleton, m, Some(Month::SUMMER), &report::MESH);
            // The crown's heights, as the model's beam takes them: its leaves'.
            let crown = skeleton
                .leaves
                .iter()
                .map(|l| leaf_centre(l).z)
                .fold((f32::MAX, f32::MIN), |(lo, hi), z| (lo.min(z), hi.max(z)));
            let (leaf, leaf_png) = coverage::measure(renderer, &mesh, 0.0, px, true, crown)?;
            // Bare, the crown shows the short twigs its leaves hid (`Skeleton::short_twigs`).
            let leafless = Skeleton {
                leaves: Vec::new(),
                ..skeleton.clone()
            };
            let (bare_mesh, _) = dressed_mesh(&leafless, m, Some(Month::SUMMER), &report::MESH);
            let (bare, bare_png) = coverage::measure(renderer, &bare_mesh, 0.0, px, false, crown)?;
            if let Some(dir) = &args.pictures {
                for (what, png) in [("leaf", leaf_png), ("bare", bare_png)] {
                    let name = format!("{}-{}-{age}-{what}.png", m.region.code, m.species.code);
                    save_picture(&dir.join(name), &png)?;
                }
            }
            Ok(Some((leaf, bare)))
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
            let b = |s: sylva::street::energy::crown::BeamStop| serde_json::json!({"stopped": s.stopped, "outline_m2": s.outline_m2});
            let c = |c: &Coverage| serde_json::json!({"covered": c.covered, "leaf_share": c.leaf_share, "bare_tips": c.bare_tips, "outline_m2": c.outline_px * c.metres_per_px * c.metres_per_px});
            println!(
                "{}",
                serde_json::json!({
                    "region": r.region, "species": r.code, "age": r.age,
                    "leaf_area_m2": r.leaf_area_m2, "bark_area_m2": r.bark_area_m2,
                    "side": {"leaf": b(r.side.0), "bare": b(r.side.1)},
                    "sun": {"leaf": b(r.sun.0), "bare": b(r.sun.1)},
                    "picture": pictured.as_ref().map(|(l, w)| serde_json::json!({"leaf": c(l), "bare": c(w)})),
                })
            );
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
            if let Some((l, w)) = pictured {
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
