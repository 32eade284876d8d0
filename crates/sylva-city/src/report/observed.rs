//! What the inventory's surveyors saw, in the city's report: each species' condition and its
//! relative performance index, and the street's problems by species and DBH class
//! (`inventory::observed` reads them).
//!
//! The relative performance index (RPI) is i-Tree Streets' (CUFR, "What are your trees'
//! relative performance index?", Urban Forest Research newsletter, Summer 2004): a species'
//! share of trees in good condition over the whole population's. 1 is the city's average;
//! above 1 the species does better than the population, below 1 worse, and a planner reads a
//! species well below 1 as one to plant less of. Shares are of the trees whose condition was
//! recorded; the rest are counted as not recorded.

use crate::inventory::Condition;
use crate::trees::plan::{Kind, Plan};
use serde::Serialize;
use std::collections::BTreeMap;
use sylva::growth::DBH_CLASS_EDGES_CM;

/// One species' condition.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConditionRow {
    /// Species code it is grown as.
    pub code: String,
    /// Its trees in good, fair and poor condition.
    pub good_fair_poor: [usize; 3],
    /// Its trees whose condition was not recorded (or could not be placed).
    pub not_recorded: usize,
    /// Its relative performance index, where it and the city have trees in good condition
    /// recorded.
    pub rpi: Option<f64>,
}

/// Trees with a problem recorded, of those for which it was recorded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Seen {
    /// Trees for which it was recorded.
    pub recorded: usize,
    /// Of those, trees with it.
    pub with: usize,
}

impl Seen {
    fn add(&mut self, v: Option<bool>) {
        if let Some(v) = v {
            self.recorded += 1;
            self.with += usize::from(v);
        }
    }

    /// The share with it, where any was recorded.
    pub fn share(&self) -> Option<f64> {
        (self.recorded > 0).then(|| self.with as f64 / self.recorded as f64)
    }
}

/// One species' problems in one DBH class.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ProblemRow {
    /// Species code it is grown as.
    pub code: String,
    /// DBH class (i-Tree's nine, 0-based: 0-3 in, 3-6, 6-12, ..., over 42).
    pub dbh_class: usize,
    /// Its trees in the class.
    pub trees: usize,
    /// A damaged sidewalk flag beside it.
    pub sidewalk_damage: Seen,
    /// Lights or wires in its branches.
    pub branch_lights: Seen,
    /// Wire, rope or lights on its trunk.
    pub trunk_wire_or_lights: Seen,
    /// Paving stones or a grate on its roots.
    pub root_paving: Seen,
}

/// All that was observed, for the report.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Observations {
    /// Condition by species, most trees first.
    pub condition: Vec<ConditionRow>,
    /// The whole population's trees in good, fair and poor condition.
    pub good_fair_poor: [usize; 3],
    /// The whole population's trees whose condition was not recorded.
    pub not_recorded: usize,
    /// Values the inventory gave that could not be placed: column, value, rows.
    pub unread: Vec<(String, String, usize)>,
    /// Problems by species and DBH class, where any was recorded.
    pub problems: Vec<ProblemRow>,
}

/// `s`'s share of trees in good condition over `all`'s: the relative performance index.
pub fn rpi(s: [usize; 3], all: [usize; 3]) -> Option<f64> {
    let share = |c: [usize; 3]| {
        let n: usize = c.iter().sum();
        (n > 0).then(|| c[0] as f64 / n as f64)
    };
    match (share(s), share(all)) {
        (Some(s), Some(a)) if a > 0.0 => Some(s / a),
        _ => None,
    }
}

/// How i-Tree Streets reads an RPI.
pub fn reading(rpi: Option<f64>) -> &'static str {
    match rpi {
        None => "not recorded",
        Some(r) if r > 1.0 => "better than the city's trees",
        Some(r) if r < 1.0 => "worse than the city's trees",
        Some(_) => "as the city's trees",
    }
}

/// What was observed of the trees standing at `plan`'s first epoch (the inventory's).
pub fn observations(plan: &Plan) -> Observations {
    let mut o = Observations::default();
    let mut by_species: BTreeMap<String, ConditionRow> = BTreeMap::new();
    let mut problems: BTreeMap<(String, usize), ProblemRow> = BTreeMap::new();
    let mut unread: BTreeMap<(String, String), usize> = BTreeMap::new();
    for t in plan.epochs.first().map_or(&[][..], |e| &e.trees) {
        let Kind::Tree(key) = &t.kind else { continue };
        let Some(seen) = plan.observed.get(t.row) else {
            continue;
        };
        let row = by_species
            .entry(key.code.clone())
            .or_insert_with(|| ConditionRow {
                code: key.code.clone(),
                good_fair_poor: [0; 3],
                not_recorded: 0,
                rpi: None,
            });
        match seen.condition {
            Some(c) => {
                let k = Condition::ALL.iter().position(|x| *x == c).unwrap_or(0);
                row.good_fair_poor[k] += 1;
                o.good_fair_poor[k] += 1;
            }
            None => {
                row.not_recorded += 1;
                o.not_recorded += 1;
            }
        }
        for (column, value) in &seen.unread {
            *unread.entry((column.clone(), value.clone())).or_default() += 1;
        }
        let class = DBH_CLASS_EDGES_CM.partition_point(|&edge| edge <= t.dbh as f64);
        let p = problems
            .entry((key.code.clone(), class))
            .or_insert_with(|| ProblemRow {
                code: key.code.clone(),
                dbh_class: class,
                trees: 0,
                sidewalk_damage: Seen::default(),
                branch_lights: Seen::default(),
                trunk_wire_or_lights: Seen::default(),
                root_paving: Seen::default(),
            });
        p.trees += 1;
        p.sidewalk_damage.add(seen.sidewalk_damage);
        p.branch_lights.add(seen.branch_lights);
        p.trunk_wire_or_lights.add(seen.trunk_wire_or_lights);
        p.root_paving.add(seen.root_paving);
    }
    for row in by_species.values_mut() {
        row.rpi = rpi(row.good_fair_poor, o.good_fair_poor);
    }
    o.condition = by_species.into_values().collect();
    o.condition.sort_by(|a, b| {
        let n = |r: &ConditionRow| r.good_fair_poor.iter().sum::<usize>() + r.not_recorded;
        n(b).cmp(&n(a)).then(a.code.cmp(&b.code))
    });
    o.unread = unread.into_iter().map(|((c, v), n)| (c, v, n)).collect();
    o.problems = problems
        .into_values()
        .filter(|p| {
            p.sidewalk_damage.recorded
                + p.branch_lights.recorded
                + p.trunk_wire_or_lights.recorded
                + p.root_paving.recorded
                > 0
        })
        .collect();
    o
}

impl Observations {
    /// Whether the inventory recorded any condition.
    pub fn has_condition(&self) -> bool {
        self.good_fair_poor.iter().sum::<usize>() > 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rpi_is_a_species_share_in_good_condition_over_the_citys() {
        // By hand: the city has 100 trees recorded, 60 good, 30 fair, 10 poor (60% good).
        // A species of 20 with 15 good (75%) reads 0.75 / 0.60 = 1.25; one of 10 with 3 good
        // (30%) reads 0.30 / 0.60 = 0.5; one of 60 good as the city, 36 of 60, reads 1.
        let city = [60, 30, 10];
        assert!((rpi([15, 4, 1], city).unwrap() - 1.25).abs() < 1e-12);
        assert!((rpi([3, 5, 2], city).unwrap() - 0.5).abs() < 1e-12);
        assert!((rpi([36, 20, 4], city).unwrap() - 1.0).abs() < 1e-12);
        // Nothing recorded, or no tree in good condition in the city: no index.
        assert_eq!(rpi([0, 0, 0], city), None);
        assert_eq!(rpi([0, 2, 1], [0, 5, 5]), None);
        assert_eq!(reading(Some(1.25)), "better than the city's trees");
        assert_eq!(reading(Some(0.5)), "worse than the city's trees");
        assert_eq!(reading(None), "not recorded");
    }
}
