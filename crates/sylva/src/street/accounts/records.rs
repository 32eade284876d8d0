//! A year's account as one output record: the shape `sylva grow --json`, the planners' page
//! (`/api/growth`) and the Python wheel all give, so they cannot drift apart. Figures are
//! rounded to what their sources resolve; `null` where a model or a price is missing, never
//! a zero.
//!
//! Write them with [`crate::record::to_json`].

use crate::growth::CutKind;
use crate::street::accounts::costs::YearCosts;
use crate::street::accounts::items::Benefit;
use crate::street::accounts::ledger::YearAccount;
use crate::street::accounts::money::{Basis, Money};
use crate::street::accounts::pruner::{LineYear, PruningYear};
use crate::street::accounts::typical::Typical;
use crate::street::work::conflicts::{Conflict, Kind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// `v` to `1/k`.
fn round(v: f64, k: f64) -> f64 {
    (v * k).round() / k
}

/// An optional `v` to `1/k`.
fn round_some(v: Option<f64>, k: f64) -> Option<f64> {
    v.map(|v| round(v, k))
}

/// Dollars in each of i-Tree's benefit categories, to the cent, by [`Benefit`] key (`null`
/// where not computed).
pub type MoneyRecord = BTreeMap<String, Option<f64>>;

/// `m` to the cent.
pub fn money_record(m: &Money) -> MoneyRecord {
    (Benefit::ALL.iter())
        .map(|&b| (b.item().key.to_string(), round_some(m.get(b), 100.0)))
        .collect()
}

/// A year's costs by item, dollars to the cent, by
/// [`Cost`](crate::street::accounts::items::Cost) key.
pub type CostsRecord = BTreeMap<String, f64>;

/// `c` to the cent.
pub fn costs_record(c: &YearCosts) -> CostsRecord {
    (c.items())
        .map(|(item, v)| (item.item().key.to_string(), round(v, 100.0)))
        .collect()
}

/// Kinds of conflict by name.
fn kind_names(kinds: &[Kind]) -> Vec<String> {
    kinds.iter().map(|k| k.name().to_string()).collect()
}

/// A year's pruning: its reasons, cuts, what they took, visits and cost, and the conflicts
/// they resolved and left.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct PruningRecord {
    pub reasons: Vec<String>,
    pub removal_cuts: usize,
    pub reduction_cuts: usize,
    /// Stems the utility's crew headed back between unions, having no lateral below a line's
    /// clearance to cut back to (Dahle et al. 2006: 80% of headed leaders decay from the cut).
    pub heading_cuts: usize,
    pub largest_cut_cm: f64,
    pub wood_removed_m3: f64,
    pub leaf_removed_m2: f64,
    pub visits: u32,
    /// The utility's visits between its cycles: hot spots its yearly patrol saw growing into
    /// a line's clearance at cutting before the next patrol.
    pub hot_spots: u32,
    pub cost_usd: f64,
    pub deferred_cuts: usize,
    pub resolved: Vec<String>,
    pub unresolved: Vec<String>,
}

impl PruningRecord {
    /// The record of `p`.
    pub fn of(p: &PruningYear) -> PruningRecord {
        PruningRecord {
            reasons: p.reasons.iter().map(|r| r.name().to_string()).collect(),
            removal_cuts: p.count(CutKind::Removal),
            reduction_cuts: p.count(CutKind::Reduction),
            heading_cuts: p.count(CutKind::Heading),
            largest_cut_cm: round(100.0 * p.cuts.largest_diameter() as f64, 10.0),
            wood_removed_m3: round(p.wood_m3(), 1e4),
            leaf_removed_m2: round(p.leaf_m2(), 10.0),
            visits: p.visits,
            hot_spots: p.hot_spots,
            cost_usd: round(p.cost, 100.0),
            deferred_cuts: p.cuts.deferred,
            resolved: kind_names(&p.resolved()),
            unresolved: kind_names(&p.unresolved),
        }
    }
}

/// One line in one whole year: how near the tree came before the year's cuts, how much of its
/// leaf was inside the line's clearance at cutting and inside its minimum, and the utility's
/// visit.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LineRecord {
    /// The age, years.
    pub age: f64,
    /// Which of the site's wires (0 the first).
    pub wire: usize,
    /// The nearest wood or leaf to the line, and the nearest wood, m (`null`: nothing grown).
    pub closest_m: Option<f64>,
    #[allow(missing_docs)]
    pub closest_wood_m: Option<f64>,
    /// The share of the tree's leaf area inside the clearance at cutting.
    pub leaf_share_in_clearance: f64,
    /// Leaf area inside the minimum clearance, m².
    pub leaf_in_minimum_m2: f64,
    /// Leaf or wood inside the minimum clearance.
    pub breach: bool,
    /// The utility's visit that year.
    pub visit: Option<LineVisitRecord>,
}

/// The utility's visit to a tree under a line.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LineVisitRecord {
    /// On the line's cycle (`false`: called out by a breach).
    pub scheduled: bool,
    /// The regrowth allowed for beyond the clearance, m.
    pub allowance_m: f64,
    /// The radius cut to, m.
    pub cut_to_m: f64,
    /// The nearest wood or leaf after the cuts, m.
    pub closest_after_m: Option<f64>,
}

impl LineRecord {
    /// The record of `l`.
    pub fn of(l: &LineYear) -> LineRecord {
        let metres = |v: f64| v.is_finite().then(|| round(v, 100.0));
        LineRecord {
            age: l.age,
            wire: l.wire,
            closest_m: metres(l.check.closest_m),
            closest_wood_m: metres(l.check.closest_wood_m),
            leaf_share_in_clearance: round(l.check.leaf_share_in_clearance, 1e3),
            leaf_in_minimum_m2: round(l.check.leaf_in_minimum_m2, 100.0),
            breach: l.breach,
            visit: l.visit.map(|v| LineVisitRecord {
                scheduled: v.scheduled,
                allowance_m: round(v.allowance_m, 100.0),
                cut_to_m: round(v.cut_to_m, 100.0),
                closest_after_m: metres(v.closest_after_m),
            }),
        }
    }
}

/// One conflict with the site.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ConflictRecord {
    /// What the tree runs into.
    pub kind: String,
    /// The part that causes it.
    pub part: String,
    /// Leaf area in the way, m².
    pub leaf_area_m2: f64,
    /// Its share of the tree's leaf area.
    pub leaf_share: f64,
    /// Lowest and highest point in the way, m.
    pub from_m: f64,
    #[allow(missing_docs)]
    pub to_m: f64,
}

impl ConflictRecord {
    /// The record of `c`.
    pub fn of(c: &Conflict) -> ConflictRecord {
        ConflictRecord {
            kind: c.kind.name().to_string(),
            part: c.part.name().to_string(),
            leaf_area_m2: round(c.leaf_area, 10.0),
            leaf_share: round(c.leaf_share, 1e3),
            from_m: round(c.heights.0, 100.0),
            to_m: round(c.heights.1, 100.0),
        }
    }
}

/// i-Tree Streets' figures for the species at the grown DBH, at its usual spread of
/// positions around buildings.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct TypicalRecord {
    /// The i-Tree region whose tables were read.
    pub region: String,
    /// The table row read.
    pub row: String,
    /// The DBH lay outside the class midpoints and the end class was held.
    pub held: bool,
    pub electricity_kwh: f64,
    pub natural_gas_kbtu: f64,
    pub stormwater_m3: f64,
    pub co2_sequestered_kg: f64,
    pub co2_avoided_kg: f64,
    pub air_removed_kg: f64,
    pub bvoc_kg: f64,
    pub leaf_gain_m2: f64,
    pub value_usd: MoneyRecord,
    /// A living tree's benefits less costs, dollars.
    pub net_usd: f64,
    /// The same per tree planted (weighted by the share alive).
    pub planted_net_usd: f64,
}

impl TypicalRecord {
    /// The typical position `t` of account `a`.
    fn of(t: &Typical, a: &YearAccount) -> TypicalRecord {
        let m = &t.amounts;
        TypicalRecord {
            region: t.region.to_string(),
            row: t.row.clone(),
            held: t.held,
            electricity_kwh: round(m.electricity_kwh, 10.0),
            natural_gas_kbtu: round(m.natural_gas_kbtu, 10.0),
            stormwater_m3: round(m.stormwater_m3, 1e3),
            co2_sequestered_kg: round(m.co2_sequestered_kg, 100.0),
            co2_avoided_kg: round(m.co2_avoided_kg, 100.0),
            air_removed_kg: round(m.air.removed_kg(), 1e3),
            bvoc_kg: round(m.air.bvoc_kg, 1e3),
            leaf_gain_m2: round(m.leaf_gain_m2, 10.0),
            value_usd: money_record(&t.money),
            net_usd: round(a.net(Basis::Typical), 100.0),
            planted_net_usd: round(a.planted_net(Basis::Typical), 100.0),
        }
    }
}

/// One year's account: the grown tree on its site, with i-Tree's typical position under
/// `typical`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct AccountRecord {
    pub co2_stored_kg: Option<f64>,
    pub co2_sequestered_kg: Option<f64>,
    pub co2_avoided_kg: Option<f64>,
    pub interception_m3: Option<f64>,
    /// Cooling saved, the shade's and the climate effect's, kWh.
    pub cooling_kwh: Option<f64>,
    /// Heating's gas, saved (+) or spent (-), kBtu.
    pub natural_gas_kbtu: Option<f64>,
    pub shade_cooling_kwh: Option<f64>,
    pub heating_penalty_kbtu: Option<f64>,
    pub useful_winter_share: Option<f64>,
    pub climate_cooling_kwh: Option<f64>,
    pub climate_heating_kbtu: Option<f64>,
    pub facade_shaded_m2h: Option<f64>,
    pub air_removed_kg: Option<f64>,
    pub bvoc_kg: Option<f64>,
    pub leaf_gain_m2: f64,
    pub value_usd: MoneyRecord,
    pub cost_usd: Option<CostsRecord>,
    pub pruning: Option<PruningRecord>,
    /// A living tree's benefits on the site less costs, dollars.
    pub net_usd: f64,
    /// The share of the trees planted standing through the year, and dying in it.
    pub alive_share: f64,
    pub died_share: f64,
    /// The net per tree planted.
    pub planted_net_usd: f64,
    pub typical: Option<TypicalRecord>,
    pub leaf_outside_zones_m2: Option<f64>,
    pub conflicts: Vec<ConflictRecord>,
    /// Each line in each whole year since the record before, where the tree was grown with
    /// the site's regime.
    pub lines: Vec<LineRecord>,
}

impl AccountRecord {
    /// The record of `a`.
    pub fn of(a: &YearAccount) -> AccountRecord {
        let e = a.energy;
        let energy = |f: fn(&crate::street::energy::shade::Energy) -> f64, k: f64| {
            round_some(e.map(|e| f(&e)), k)
        };
        AccountRecord {
            co2_stored_kg: round_some(a.co2_stored_kg, 10.0),
            co2_sequestered_kg: round_some(a.co2_sequestered_kg, 100.0),
            co2_avoided_kg: round_some(a.co2_avoided_kg, 100.0),
            interception_m3: round_some(a.interception_m3, 1e3),
            cooling_kwh: energy(|e| e.electricity_kwh(), 10.0),
            natural_gas_kbtu: energy(|e| e.natural_gas_kbtu(), 10.0),
            shade_cooling_kwh: energy(|e| e.shade_cooling_kwh, 10.0),
            heating_penalty_kbtu: energy(|e| e.heating_penalty_kbtu, 10.0),
            useful_winter_share: energy(|e| e.useful_winter_share, 1e3),
            climate_cooling_kwh: round_some(e.and_then(|e| e.climate).map(|c| c.0), 10.0),
            climate_heating_kbtu: round_some(e.and_then(|e| e.climate).map(|c| c.1), 10.0),
            facade_shaded_m2h: energy(|e| e.summer.shaded_m2h, 1.0),
            air_removed_kg: round_some(a.air.map(|q| q.removed_kg()), 1e3),
            bvoc_kg: round_some(a.air.map(|q| q.bvoc_kg), 1e3),
            leaf_gain_m2: round(a.leaf_gain_m2, 10.0),
            value_usd: money_record(&a.money),
            cost_usd: a.costs.as_ref().map(costs_record),
            pruning: a.pruning.as_ref().map(PruningRecord::of),
            net_usd: round(a.net(Basis::Site), 100.0),
            alive_share: round(a.cohort.alive, 1e4),
            died_share: round(a.cohort.died, 1e4),
            planted_net_usd: round(a.planted_net(Basis::Site), 100.0),
            typical: a.typical.as_ref().map(|t| TypicalRecord::of(t, a)),
            leaf_outside_zones_m2: round_some(a.leaf_outside_zones_m2, 10.0),
            conflicts: a.conflicts.iter().map(ConflictRecord::of).collect(),
            lines: a.lines.iter().map(LineRecord::of).collect(),
        }
    }
}
