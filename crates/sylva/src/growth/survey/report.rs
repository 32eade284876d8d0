//! A growth report: street trees grown side by side through a run of ages, each age measured
//! the way the Urban Tree Database measured its trees and set beside the equations. The rows
//! feed the CSV, the charts and the captions of `sylva grow`; drawing them is the caller's.
//!
//! ```
//! use sylva::growth::Database;
//! use sylva::growth::survey::report::{Cohort, run_ages};
//! let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
//! let ages = run_ages(&plane, Some(5.0), Some(10.0), 5.0).unwrap();
//! let mut cohort = Cohort::new(vec![plane], 0);
//! for &age in &ages {
//!     let skeletons = cohort.advance_to(age);
//!     assert_eq!(skeletons.len(), 1);
//! }
//! let csv = sylva::growth::survey::report::csv(&cohort.history[0]);
//! assert_eq!(csv.lines().count(), 3);
//! ```

use crate::Skeleton;
use crate::growth::data::measured::Measured;
use crate::growth::model::{Grower, GrowthOptions, Targets};
use crate::growth::survey::form::{FormMeasures, measure_form};
use crate::growth::survey::measure::{Dimensions, measure};
use crate::mesh::MeshOptions;
use std::fmt::Write as _;

/// Oldest age a run may ask for, years.
pub const MAX_AGE: f64 = 300.0;
/// Most ages one run may hold.
pub const MAX_AGES: usize = 400;

/// How finely grown trees are meshed: a street tree has tens of thousands of thin segments,
/// so rings are coarser than a lone Weber-Penn tree's.
pub const MESH: MeshOptions = MeshOptions {
    quality: 0.6,
    sides: None,
    bark: crate::mesh::BarkPattern::Smooth,
    young_bark: 1.0,
    twig_copies: false,
};

/// The ages of a run: `from` to `to` every `step` years, by default the ages the species'
/// data cover. Errors name the flags and the data's ages.
pub fn run_ages(
    first: &Measured,
    from: Option<f64>,
    to: Option<f64>,
    step: f64,
) -> Result<Vec<f64>, String> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(format!(
            "--step {step}: expected a positive number of years"
        ));
    }
    let from = from.unwrap_or(first.ages.0.ceil());
    let to = to.unwrap_or(first.ages.1.floor());
    if !(0.0..=MAX_AGE).contains(&from) || !(0.0..=MAX_AGE).contains(&to) || from > to {
        return Err(format!(
            "--from {from} --to {to}: expected 0 <= from <= to <= {MAX_AGE} years (the data for \
             {} cover ages {:.0} to {:.0})",
            first.label(),
            first.ages.0,
            first.ages.1
        ));
    }
    let count = ((to - from) / step + 1e-9).floor() as usize + 1;
    if count > MAX_AGES {
        return Err(format!(
            "--from {from} --to {to} --step {step}: {count} ages, at most {MAX_AGES}"
        ));
    }
    Ok((0..count).map(|i| from + i as f64 * step).collect())
}

/// An age's output record: each grown dimension beside the equations' (`_measured`), and
/// the crown's form (`sylva grow --json`, the wheel's summary).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[allow(missing_docs)]
pub struct GrowthRecord {
    /// The species' code.
    pub species: String,
    pub age: f64,
    pub height_m: f64,
    pub height_measured_m: f64,
    pub crown_height_m: f64,
    pub crown_height_measured_m: f64,
    pub crown_diameter_m: f64,
    pub crown_diameter_measured_m: f64,
    pub dbh_cm: f64,
    pub dbh_measured_cm: f64,
    pub leaf_area_m2: f64,
    pub leaf_area_measured_m2: f64,
    pub inner_leaf_share: f64,
    pub leaders: usize,
    pub scaffold_angle_deg: Option<f64>,
    pub pipe_exponent: Option<f64>,
    pub live_branches: usize,
    pub shed_branches: usize,
    pub live_segments: usize,
}

impl GrowthRecord {
    /// The record of age `r` of species `m`.
    pub fn of(m: &Measured, r: &AgeRecord) -> GrowthRecord {
        let (d, t, f) = (&r.model, &r.measured, &r.form);
        let round = |v: f64, k: f64| (v * k).round() / k;
        GrowthRecord {
            species: m.species.code.clone(),
            age: r.age,
            height_m: round(d.height, 1e3),
            height_measured_m: round(t.height, 1e3),
            crown_height_m: round(d.crown_height, 1e3),
            crown_height_measured_m: round(t.crown_height, 1e3),
            crown_diameter_m: round(d.crown_diameter, 1e3),
            crown_diameter_measured_m: round(t.crown_diameter, 1e3),
            dbh_cm: round(d.dbh, 1e2),
            dbh_measured_cm: round(t.dbh, 1e2),
            leaf_area_m2: round(d.leaf_area, 10.0),
            leaf_area_measured_m2: round(t.leaf_area, 10.0),
            inner_leaf_share: round(f.inner_leaf_share, 1e3),
            leaders: f.leaders,
            scaffold_angle_deg: f.scaffold_angle.map(|a| round(a, 10.0)),
            pipe_exponent: f.pipe_exponent.map(|n| round(n, 1e2)),
            live_branches: r.branches.0,
            shed_branches: r.branches.1,
            live_segments: r.segments,
        }
    }
}

/// One age of one tree: what the model grew and what the equations say.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AgeRecord {
    /// Age, years.
    pub age: f64,
    /// The grown tree, measured.
    pub model: Dimensions,
    /// The equations at that age.
    pub measured: Targets,
    /// The grown tree's form.
    pub form: FormMeasures,
    /// Branches alive, and shed since the tree was planted.
    pub branches: (usize, usize),
    /// Segments of the live branches (issue W sets a cut tree's per m² of leaf beside its
    /// uncut twin's).
    pub segments: usize,
}

/// Street trees of several species grown through the same ages from one seed.
pub struct Cohort {
    /// The species, in the order given.
    pub species: Vec<Measured>,
    /// Each tree's grower, in the same order.
    pub growers: Vec<Grower>,
    /// Each tree's record of every age reached.
    pub history: Vec<Vec<AgeRecord>>,
}

impl Cohort {
    /// Saplings of every species, not yet grown.
    pub fn new(species: Vec<Measured>, seed: u64) -> Self {
        let growers = species
            .iter()
            .map(|m| {
                let options = GrowthOptions {
                    seed,
                    ..Default::default()
                };
                Grower::new(m.clone(), options)
            })
            .collect();
        let history = species.iter().map(|_| Vec::new()).collect();
        Self {
            species,
            growers,
            history,
        }
    }

    /// Grows every tree to `age`, records it, and returns each one's skeleton in order.
    pub fn advance_to(&mut self, age: f64) -> Vec<Skeleton> {
        let mut skeletons = Vec::with_capacity(self.growers.len());
        for (g, history) in self.growers.iter_mut().zip(&mut self.history) {
            g.advance_to(age);
            let skeleton = g.skeleton();
            let model = measure(&skeleton);
            let base = model.height - model.crown_height;
            history.push(AgeRecord {
                age,
                model,
                measured: g.targets(age),
                form: measure_form(&skeleton, base, model.height, model.crown_diameter),
                branches: g.branch_counts(),
                segments: g.segment_count(),
            });
            skeletons.push(skeleton);
        }
        skeletons
    }

    /// The frame of a run's pictures ([`extent`]).
    pub fn extent(&self, ages: &[f64]) -> (f64, f64) {
        extent(&self.species, ages)
    }
}

/// The tallest height and widest crown the equations give any species at any of `ages`
/// (at least 2 m and 1 m): the frame a run's pictures share, so that ages compare.
pub fn extent(species: &[Measured], ages: &[f64]) -> (f64, f64) {
    let mut tallest = 2.0f64;
    let mut widest = 1.0f64;
    for m in species {
        for &a in ages {
            tallest = tallest.max(m.height(a));
            widest = widest.max(m.crown_diameter(a));
        }
    }
    (tallest, widest)
}

/// `5` for whole ages, `5.5` otherwise, padded so that files sort by age.
pub fn age_label(age: f64) -> String {
    if age.fract().abs() < 1e-9 {
        format!("{:02}", age as u32)
    } else {
        format!("{age:04.1}")
    }
}

/// Worst signed relative error per quantity over a history: height, DBH, crown diameter,
/// crown height, leaf area.
pub fn worst_errors(history: &[AgeRecord]) -> [f64; 5] {
    let mut worst = [0.0f64; 5];
    for g in history {
        let e = g.model.relative_errors(&g.measured);
        for k in 0..5 {
            if e[k].abs() > worst[k].abs() {
                worst[k] = e[k];
            }
        }
    }
    worst
}

/// A history as CSV: one row per age, model and measured side by side, then the form (an
/// empty cell where a measure has nothing to measure).
pub fn csv(history: &[AgeRecord]) -> String {
    let mut s = String::from(
        "age,height_model_m,height_measured_m,crown_height_model_m,crown_height_measured_m,\
         crown_diameter_model_m,crown_diameter_measured_m,dbh_model_cm,dbh_measured_cm,\
         leaf_area_model_m2,leaf_area_measured_m2,inner_leaf_share,leaders,\
         scaffold_angle_deg,pipe_exponent,live_branches,shed_branches,live_segments\n",
    );
    let cell = |v: Option<f64>, digits: usize| v.map_or(String::new(), |v| format!("{v:.digits$}"));
    for g in history {
        let (m, t, f) = (&g.model, &g.measured, &g.form);
        // Writing into a String cannot fail.
        let _ = writeln!(
            s,
            "{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.2},{:.2},{:.1},{:.1},{:.3},{},{},{},{},{},{}",
            g.age,
            m.height,
            t.height,
            m.crown_height,
            t.crown_height,
            m.crown_diameter,
            t.crown_diameter,
            m.dbh,
            t.dbh,
            m.leaf_area,
            t.leaf_area,
            f.inner_leaf_share,
            f.leaders,
            cell(f.scaffold_angle, 1),
            cell(f.pipe_exponent, 2),
            g.branches.0,
            g.branches.1,
            g.segments
        );
    }
    s
}

/// A quantity charted against age: its name with unit, how to read it from a grown tree and
/// from the equations.
pub struct Quantity {
    /// Name and unit, as a chart's title.
    pub name: &'static str,
    /// The grown tree's value.
    pub model: fn(&Dimensions) -> f64,
    /// The equations' value.
    pub measured: fn(&Targets) -> f64,
}

/// The five quantities a growth chart shows, in its panel order.
pub const CHARTED: [Quantity; 5] = [
    Quantity {
        name: "height (m)",
        model: |d| d.height,
        measured: |t| t.height,
    },
    Quantity {
        name: "crown height (m)",
        model: |d| d.crown_height,
        measured: |t| t.crown_height,
    },
    Quantity {
        name: "crown diameter (m)",
        model: |d| d.crown_diameter,
        measured: |t| t.crown_diameter,
    },
    Quantity {
        name: "DBH (cm)",
        model: |d| d.dbh,
        measured: |t| t.dbh,
    },
    Quantity {
        name: "leaf area (m²)",
        model: |d| d.leaf_area,
        measured: |t| t.leaf_area,
    },
];

impl Measured {
    /// Colours of this species' pictures and models (sRGB): bark, and leaves in summer, as
    /// the foliage table names them; for species without a row, one bark and a green
    /// (evergreens darker).
    pub fn colours(&self) -> ([f32; 3], [f32; 3]) {
        if let Some(f) = crate::growth::data::foliage::of(&self.species.code) {
            return (f.bark.srgb, f.summer.srgb);
        }
        let evergreen = self.species.tree_type.get(1..2) == Some("E");
        let leaves = if evergreen {
            [0.2, 0.36, 0.16]
        } else {
            [0.33, 0.5, 0.2]
        };
        ([0.42, 0.36, 0.3], leaves)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::data::database::Database;

    #[test]
    fn ages_labels_and_errors() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        assert_eq!(
            run_ages(&plane, Some(10.0), Some(20.0), 5.0).unwrap(),
            [10.0, 15.0, 20.0]
        );
        assert!(run_ages(&plane, Some(20.0), Some(10.0), 5.0).is_err());
        assert!(run_ages(&plane, None, None, 0.0).is_err());
        let e = run_ages(&plane, Some(0.0), Some(300.0), 0.5).unwrap_err();
        assert!(e.contains("601 ages"), "{e}");
        assert_eq!(age_label(5.0), "05");
        assert_eq!(age_label(5.5), "05.5");
        assert_eq!(age_label(120.0), "120");
    }

    #[test]
    fn records_carry_the_form_and_the_csv_reads_back() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut cohort = Cohort::new(vec![plane], 0);
        cohort.advance_to(8.0);
        let r = cohort.history[0][0];
        assert!(r.branches.0 > 0, "{r:?}");
        assert!(
            r.form.leaders >= 1 && r.form.scaffold_angle.is_some(),
            "{r:?}"
        );
        let text = csv(&cohort.history[0]);
        let mut rows = csv::Reader::from_reader(text.as_bytes());
        let header = rows.headers().unwrap().clone();
        assert_eq!(header.len(), 18);
        let row = rows.records().next().unwrap().unwrap();
        assert_eq!(row.len(), 18);
        let live: usize = row[15].parse().unwrap();
        assert_eq!(live, r.branches.0);
        // Every live branch has at least one segment.
        assert_eq!(&header[17], "live_segments");
        let segments: usize = row[17].parse().unwrap();
        assert!(segments == r.segments && segments >= live, "{r:?}");
    }
}
