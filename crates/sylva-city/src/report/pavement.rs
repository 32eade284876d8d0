//! Sidewalk damage in the city's report: Sylva's roots model (`sylva::street::work::roots`)
//! beside what the inventory's surveyors recorded, tree by tree: each standing tree with its
//! sidewalk recorded is given the model's share of such trees beside a damaged flag, from its
//! own DBH, its bed's place against the curb (the census's `curb_loc`; a tree whose place is not
//! recorded is read as along the curb, and counted apart) and its species' rooting habit; the
//! shares are set side by side by DBH class, by place and by species.
//!
//! A difference is read against the sampling error of the recorded share (the binomial
//! standard error of a class's trees): one within two errors is what a sample of that size
//! gives, and the report says which differences past 10 points are not.

use crate::inventory::observed::Curb;
use crate::trees::plan::{Kind, Plan};
use serde::Serialize;
use std::collections::BTreeMap;
use sylva::growth::DBH_CLASS_EDGES_CM;
use sylva::street::work::roots::{Habit, RootDamage};

/// How many species the report lists (most trees recorded first).
pub const SPECIES_LISTED: usize = 15;
/// A difference, in points, the report explains.
pub const EXPLAINED_PAST: f64 = 0.10;

/// One class of trees: how many had their sidewalk recorded, the share recorded damaged, and
/// the model's.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Class {
    /// What the class is (a DBH class, a place, a species).
    pub class: String,
    /// Trees with their sidewalk recorded.
    pub trees: usize,
    /// The share of them recorded beside a damaged flag.
    pub observed: f64,
    /// The model's share for the same trees.
    pub predicted: f64,
    /// The observed share's standard error (binomial, at the model's share).
    pub error: f64,
}

impl Class {
    /// The model's share less the recorded one, points (a share, -1 to 1).
    pub fn difference(&self) -> f64 {
        self.predicted - self.observed
    }

    /// Why a difference past [`EXPLAINED_PAST`] is there, where the class's sampling error
    /// explains it; `None` where it is within 10 points, or where sampling does not explain
    /// it (the report's note does).
    pub fn sampling(&self) -> Option<String> {
        let d = self.difference().abs();
        (d > EXPLAINED_PAST && d <= 2.0 * self.error).then(|| {
            format!(
                "within two standard errors ({:.0} points) of {} trees' share",
                200.0 * self.error,
                self.trees
            )
        })
    }

    fn add(&mut self, damaged: bool, p: f64) {
        self.trees += 1;
        self.observed += f64::from(u8::from(damaged));
        self.predicted += p;
    }

    fn finish(mut self) -> Class {
        let n = self.trees.max(1) as f64;
        self.observed /= n;
        self.predicted /= n;
        self.error = (self.predicted * (1.0 - self.predicted) / n).sqrt();
        self
    }
}

/// The comparison, where any tree's sidewalk was recorded.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Pavement {
    /// Every tree with its sidewalk recorded.
    pub all: Class,
    /// By i-Tree's nine DBH classes (only those with trees).
    pub by_dbh: Vec<Class>,
    /// Along the curb, offset from it, and not recorded (read as along it).
    pub by_place: Vec<Class>,
    /// The species with most trees recorded, [`SPECIES_LISTED`] at most, each with how its
    /// rooting habit was found (`species`, `genus`, or `the census's mean`).
    pub by_species: Vec<(Class, String)>,
}

/// The classes' names, in cm: i-Tree's nine.
fn dbh_class_name(k: usize) -> String {
    let edges = DBH_CLASS_EDGES_CM;
    match k {
        0 => format!("under {:.1} cm", edges[0]),
        k if k >= edges.len() => format!("{:.1} cm and over", edges[edges.len() - 1]),
        k => format!("{:.1}-{:.1} cm", edges[k - 1], edges[k]),
    }
}

/// The comparison over the trees standing at `plan`'s first epoch; none where no tree's
/// sidewalk was recorded.
pub fn pavement(plan: &Plan) -> Option<Pavement> {
    let model = RootDamage::builtin();
    let mut all = Class {
        class: "every tree".into(),
        ..Default::default()
    };
    let mut by_dbh: BTreeMap<usize, Class> = BTreeMap::new();
    let mut by_place: BTreeMap<Option<Curb>, Class> = BTreeMap::new();
    let mut by_species: BTreeMap<String, (Class, String)> = BTreeMap::new();
    for t in plan.epochs.first().map_or(&[][..], |e| &e.trees) {
        let Kind::Tree(key) = &t.kind else { continue };
        let Some(seen) = plan.observed.get(t.row) else {
            continue;
        };
        let Some(damaged) = seen.sidewalk_damage else {
            continue;
        };
        let Some(m) = plan.measured.get(&(key.region.clone(), key.code.clone())) else {
            continue;
        };
        let rooting = model.rooting(&m.species.scientific);
        let place = seen.curb.unwrap_or(Curb::Along);
        let p = model.prevalence(t.dbh as f64, place.distance_m(), &rooting);
        all.add(damaged, p);
        let k = DBH_CLASS_EDGES_CM.partition_point(|&e| e <= t.dbh as f64);
        (by_dbh.entry(k))
            .or_insert_with(|| Class {
                class: dbh_class_name(k),
                ..Default::default()
            })
            .add(damaged, p);
        (by_place.entry(seen.curb))
            .or_insert_with(|| Class {
                class: seen
                    .curb
                    .map_or("not recorded (read as along the curb)", Curb::name)
                    .into(),
                ..Default::default()
            })
            .add(damaged, p);
        let habit = match rooting.habit {
            Habit::Species => "species",
            Habit::Genus => "genus",
            Habit::Unknown => "the census's mean",
        };
        (by_species.entry(key.code.clone()))
            .or_insert_with(|| {
                let class = Class {
                    class: m.label(),
                    ..Default::default()
                };
                (class, habit.to_string())
            })
            .0
            .add(damaged, p);
    }
    if all.trees == 0 {
        return None;
    }
    let mut species: Vec<(Class, String)> = by_species.into_values().collect();
    species.sort_by(|a, b| b.0.trees.cmp(&a.0.trees).then(a.0.class.cmp(&b.0.class)));
    species.truncate(SPECIES_LISTED);
    Some(Pavement {
        all: all.finish(),
        by_dbh: by_dbh.into_values().map(Class::finish).collect(),
        by_place: by_place.into_values().map(Class::finish).collect(),
        by_species: (species.into_iter())
            .map(|(c, h)| (c.finish(), h))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_class_says_when_sampling_explains_its_difference() {
        let mut c = Class::default();
        for k in 0..20 {
            c.add(k < 2, 0.3);
        }
        let c = c.finish();
        assert!((c.observed - 0.1).abs() < 1e-12 && (c.predicted - 0.3).abs() < 1e-12);
        // 20 trees at 30%: a standard error of 10 points, so 20 points off is sampling.
        assert!((c.error - 0.1025).abs() < 1e-3);
        assert!(c.sampling().is_some());
        let mut big = Class::default();
        for k in 0..400 {
            big.add(k < 40, 0.3);
        }
        assert!(big.finish().sampling().is_none(), "400 trees 20 points off");
        assert_eq!(dbh_class_name(0), "under 7.6 cm");
    }
}
