//! The whole database grown and measured: every species of every region that has its five
//! equations, grown year by year through the ages its data cover and measured as the survey
//! measured, each quantity's worst error against its target beside the bounds (height
//! and DBH within 5%, crown diameter, crown height and leaf area within 10%).
//!
//! Targets are the measured functions as [`Measured`] keeps them sensible, and
//! [`Measured::adjustments`] says where and why they part from the raw equations: an age→DBH
//! cubic that falls before it rises, a DBH→X curve that turns over or leaves the range it was
//! fitted on, a fitted crown taller than the tree, a crown base that would sink with age. Those
//! are the data's own limits, listed so that a reader can tell them from the model's misses.

use crate::growth::data::database::Database;
use crate::growth::data::measured::Measured;
use crate::growth::model::{Grower, GrowthOptions};
use crate::growth::survey::measure::{Dimensions, measure};
use crate::skeleton::Skeleton;

/// The quantities measured, in the order of every `[f64; 5]` here.
pub const QUANTITIES: [&str; 5] = [
    "height",
    "DBH",
    "crown diameter",
    "crown height",
    "leaf area",
];

/// Largest relative error allowed per quantity.
pub const BOUNDS: [f64; 5] = [0.05, 0.05, 0.10, 0.10, 0.10];

/// A target shifted by more than this from its raw equation counts as adjusted.
const ADJUSTED: f64 = 0.01;

/// One species in one region, grown and measured.
#[derive(Clone, Debug)]
pub struct SweepRow {
    /// Region code.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Whole ages grown, first and last.
    pub ages: (u32, u32),
    /// Worst relative error per quantity over those ages...
    pub worst: [f64; 5],
    /// ...and the age of each.
    pub at: [u32; 5],
    /// Where the targets part from the raw equations, and why.
    pub adjustments: Vec<Adjustment>,
    /// Seconds the growth took.
    pub seconds: f64,
}

impl SweepRow {
    /// The quantities past their bound: (index into [`QUANTITIES`], worst error, its age).
    pub fn misses(&self) -> Vec<(usize, f64, u32)> {
        (0..5)
            .filter(|&k| self.worst[k].abs() > BOUNDS[k])
            .map(|k| (k, self.worst[k], self.at[k]))
            .collect()
    }

    /// Whether every quantity stayed within its bound at every age.
    pub fn within(&self) -> bool {
        self.misses().is_empty()
    }
}

/// A quantity past its bound in a sweep (`sylva sweep --json`'s `misses`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MissRecord {
    /// The quantity (`height`, `dbh`, ...).
    pub quantity: String,
    /// Its worst relative error.
    pub worst: f64,
    /// The age of it.
    pub age: u32,
}

/// Where a species' targets part from its raw equations (`adjusted`).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AdjustmentRecord {
    /// The quantity.
    pub quantity: String,
    /// First and last whole age affected.
    pub ages: [u32; 2],
    /// Largest relative shift of the target from the raw equation.
    pub shift: f64,
    /// Why, in words.
    pub why: String,
}

/// One species and region of a sweep (`sylva sweep --json`, one line each).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[allow(missing_docs)]
pub struct SweepRecord {
    pub region: String,
    pub species: String,
    pub ages: [u32; 2],
    /// Worst relative error per quantity ([`QUANTITIES`]' order), and the age of each.
    pub worst: [f64; 5],
    pub at: [u32; 5],
    /// Whether every quantity stayed within its bound at every age.
    pub within: bool,
    pub misses: Vec<MissRecord>,
    pub adjusted: Vec<AdjustmentRecord>,
    /// Seconds the growth took.
    pub seconds: f64,
}

impl SweepRecord {
    /// The record of `r`.
    pub fn of(r: &SweepRow) -> SweepRecord {
        SweepRecord {
            region: r.region.clone(),
            species: r.code.clone(),
            ages: [r.ages.0, r.ages.1],
            worst: r.worst,
            at: r.at,
            within: r.within(),
            misses: (r.misses().into_iter())
                .map(|(k, worst, age)| MissRecord {
                    quantity: QUANTITIES[k].to_string(),
                    worst,
                    age,
                })
                .collect(),
            adjusted: (r.adjustments.iter())
                .map(|a| AdjustmentRecord {
                    quantity: QUANTITIES[a.quantity].to_string(),
                    ages: [a.ages.0, a.ages.1],
                    shift: a.shift,
                    why: a.why.to_string(),
                })
                .collect(),
            seconds: r.seconds,
        }
    }
}

/// A span of ages where a target is not its raw equation.
#[derive(Clone, Debug, PartialEq)]
pub struct Adjustment {
    /// Index into [`QUANTITIES`].
    pub quantity: usize,
    /// Why, in words.
    pub why: &'static str,
    /// First and last whole age affected.
    pub ages: (u32, u32),
    /// Largest relative shift of the target from the raw equation over those ages.
    pub shift: f64,
}

impl Measured {
    /// Where, over its whole ages, this species' targets part from its raw equations by more
    /// than 1%, and why; and whether its growth starts late because its age→DBH fit does.
    pub fn adjustments(&self) -> Vec<Adjustment> {
        let eq = &self.equations;
        let mut out: Vec<Adjustment> = Vec::new();
        let mut note = |quantity: usize, why: &'static str, age: u32, shift: f64| match out
            .iter_mut()
            .find(|a| a.quantity == quantity && a.why == why)
        {
            Some(a) => {
                a.ages.1 = age;
                a.shift = if shift.abs() > a.shift.abs() {
                    shift
                } else {
                    a.shift
                };
            }
            None => out.push(Adjustment {
                quantity,
                why,
                ages: (age, age),
                shift,
            }),
        };
        let start = if eq[0].form.is_log_log() { 1.0 } else { 0.0 };
        if self.ages.0 > start + 0.5 {
            let why = if eq[0].raw(start) > eq[0].raw(self.ages.0) {
                "the age->DBH fit falls before it rises: growth starts at its trough"
            } else {
                "the age->DBH fit predicts below its DBH range: growth starts where it enters"
            };
            note(1, why, self.ages.0.ceil() as u32, 0.0);
        }
        for age in self.whole_ages() {
            let t = f64::from(age);
            let raw_dbh = eq[0].raw(t);
            let dbh = self.dbh(t);
            let rel = |sensible: f64, raw: f64| {
                if raw.abs() > 1e-9 {
                    sensible / raw - 1.0
                } else {
                    0.0
                }
            };
            if rel(dbh, raw_dbh).abs() > ADJUSTED {
                note(
                    1,
                    "the age->DBH fit leaves its DBH range: held at its edge",
                    age,
                    rel(dbh, raw_dbh),
                );
            }
            let sensible = [
                self.height(t),
                self.crown_diameter(t),
                self.crown_height(t),
                self.leaf_area(t),
            ];
            for (i, &value) in sensible.iter().enumerate() {
                let k = i + 1;
                let quantity = [0, 2, 3, 4][i];
                let e = &eq[k];
                let raw = e.raw(dbh);
                let shift = rel(value, raw);
                if shift.abs() <= ADJUSTED {
                    continue;
                }
                let clamped = raw.clamp(e.range.0, e.range.1);
                let why = if quantity == 3 && raw > self.height(t) {
                    "the fitted crown is taller than the tree: the crown reaches the ground"
                } else if quantity == 3 && value < raw.min(self.height(t)) - 1e-6 {
                    "the fitted crown base sinks with age: held at its highest"
                } else if (clamped - raw).abs() > 1e-9 && (value - clamped).abs() < 1e-9 {
                    "outside the range its DBH->X fit was made on: held at its edge"
                } else {
                    "its DBH->X fit turns over: held at its peak beyond"
                };
                note(quantity, why, age, shift);
            }
        }
        out
    }
}

/// Grows `m` from its first whole age to its last (or `last`, if sooner), measuring it at
/// every whole age against its targets; `visit` sees each age's skeleton and measures.
pub fn sweep_one(
    m: &Measured,
    seed: u64,
    last: Option<u32>,
    mut visit: impl FnMut(u32, &Skeleton, &Dimensions),
) -> SweepRow {
    let started = std::time::Instant::now();
    let ages: Vec<u32> = m
        .whole_ages()
        .filter(|&a| last.is_none_or(|l| a <= l))
        .collect();
    let mut grower = Grower::new(
        m.clone(),
        GrowthOptions {
            seed,
            ..Default::default()
        },
    );
    let (mut worst, mut at) = ([0.0f64; 5], [0u32; 5]);
    let mut skeleton = Skeleton::default();
    for &age in &ages {
        grower.advance_to(f64::from(age));
        grower.skeleton_into(&mut skeleton);
        let d = measure(&skeleton);
        let errors = d.relative_errors(&grower.targets(f64::from(age)));
        for k in 0..5 {
            if errors[k].abs() > worst[k].abs() {
                (worst[k], at[k]) = (errors[k], age);
            }
        }
        visit(age, &skeleton, &d);
    }
    SweepRow {
        region: m.region.code.clone(),
        code: m.species.code.clone(),
        ages: (
            ages.first().copied().unwrap_or(0),
            ages.last().copied().unwrap_or(0),
        ),
        worst,
        at,
        adjustments: m.adjustments(),
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// [`sweep_one`] over `pairs` on every core (each tree on one thread, its light on any),
/// calling `tick` as each finishes; rows in the order of `pairs`.
pub fn sweep_all(
    pairs: &[Measured],
    seed: u64,
    last: Option<u32>,
    tick: &(dyn Fn() + Sync),
) -> Vec<SweepRow> {
    use rayon::prelude::*;
    pairs
        .par_iter()
        .map(|m| {
            let row = sweep_one(m, seed, last, |_, _, _| {});
            tick();
            row
        })
        .collect()
}

/// The sweep's summary and its tables in Markdown: the count within bounds, every miss, and
/// every pair whose targets the data made part from the raw equations (and why).
pub fn markdown(rows: &[SweepRow], seed: u64) -> String {
    use std::fmt::Write;
    let within = rows.iter().filter(|r| r.within()).count();
    let mut out = String::new();
    let _ = writeln!(out, "# Every species of the database, grown and measured\n");
    let _ = writeln!(
        out,
        "Written by `sylva sweep --markdown` (crates/sylva/src/growth/survey/sweep.rs): every species \
         of every region that has its five equations, grown from the first whole age its data \
         cover to the last, measured at every whole age as the survey measured (height, DBH at \
         breast height, crown diameter, crown height, one-sided leaf area) and compared with \
         its targets. The targets are the equations as `Measured` keeps them sensible: where the \
         data themselves rule a raw equation out (a fit that turns over or leaves its range, a \
         crown taller than its tree, a crown base that would sink), the tree follows the nearest \
         sensible target, and the second table lists each such case and why.\n"
    );
    let _ = writeln!(
        out,
        "{within} of {} species-regions grow within bounds at every whole age their data \
         cover (seed {seed}; height and DBH within 5%, crown diameter, crown height and leaf \
         area within 10%).\n",
        rows.len()
    );
    let _ = writeln!(out, "### Misses\n");
    let _ = writeln!(
        out,
        "| region | species | quantity | worst | at age | ages grown |"
    );
    let _ = writeln!(out, "|---|---|---|---:|---:|---|");
    for r in rows {
        for (k, worst, age) in r.misses() {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {:+.1}% | {age} | {}-{} |",
                r.region,
                r.code,
                QUANTITIES[k],
                worst * 100.0,
                r.ages.0,
                r.ages.1
            );
        }
    }
    let _ = writeln!(out, "\n### Targets the data themselves limit\n");
    let _ = writeln!(
        out,
        "| region | species | quantity | ages | largest shift | why |"
    );
    let _ = writeln!(out, "|---|---|---|---|---:|---|");
    for r in rows {
        for a in &r.adjustments {
            let _ = writeln!(
                out,
                "| {} | {} | {} | {}-{} | {:+.0}% | {} |",
                r.region,
                r.code,
                QUANTITIES[a.quantity],
                a.ages.0,
                a.ages.1,
                a.shift * 100.0,
                a.why
            );
        }
    }
    out
}

/// Every species that can be grown in each of `regions` (every region if empty), region by
/// region in the database's order.
pub fn growable_pairs(db: &Database, regions: &[String]) -> Vec<Measured> {
    db.regions()
        .iter()
        .filter(|r| regions.is_empty() || regions.iter().any(|q| q.eq_ignore_ascii_case(&r.code)))
        .flat_map(|r| {
            db.growable(&r.code)
                .into_iter()
                .filter_map(|s| db.find(&r.code, &s.code).ok())
                .collect::<Vec<_>>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed sample of region-species pairs across the database, from seven regions:
    /// broadleaves with lobed, star-lobed, heart-shaped and bipinnate leaves, an evergreen oak and
    /// a pine, each grown through its first fifteen years: every quantity within bounds. The
    /// full sweep is `sylva sweep`.
    #[test]
    fn a_sample_of_the_database_grows_within_bounds() {
        let db = Database::builtin();
        let sample = [
            ("InlVal", "PLAC"),
            ("NoEast", "TICO"),
            ("PacfNW", "ACPL"),
            ("CenFla", "QUVI"),
            ("SoCalC", "LIST"),
            ("MidWst", "GLTR"),
            ("NMtnPr", "PINI"),
        ];
        let mut report = Vec::new();
        for (region, code) in sample {
            let m = db.find(region, code).unwrap();
            let row = sweep_one(&m, 1, Some(15), |_, _, _| {});
            assert!(
                row.ages.1 >= row.ages.0 + 5,
                "{region} {code}: {:?}",
                row.ages
            );
            for (k, worst, age) in row.misses() {
                report.push(format!(
                    "{region} {code}: {} {:+.1}% at {age}",
                    QUANTITIES[k],
                    worst * 100.0
                ));
            }
        }
        assert!(report.is_empty(), "{}", report.join("\n"));
    }

    #[test]
    fn adjustments_name_the_datas_own_limits() {
        let db = Database::builtin();
        // InlEmp's Turkish pine: its age->DBH cubic falls before it rises.
        let pine = db.find("InlEmp", "PIBR2").unwrap();
        let a = pine.adjustments();
        assert!(
            a.iter().any(|a| a.why.contains("falls before it rises")),
            "{a:?}"
        );
        for a in &a {
            assert!(a.ages.0 <= a.ages.1 && a.quantity < 5, "{a:?}");
        }
    }
}
