//! The street's output records: a grown year, a ranking's row, a calibration's row, the page's
//! growth table. `sylva grow --json`, `sylva rank --json`, the planners' page and the Python
//! wheel write these types and no hand-built JSON, so the same request gives the same figures
//! everywhere (`sylva-cli/tests/cli/records.rs` holds the CLI to the page's API).
//!
//! Write them with [`to_json`]: its objects keep their keys in alphabetical order.

use super::accounts::calibrate::Row;
use super::accounts::money::Basis;
use super::accounts::records::{AccountRecord, PruningRecord};
use super::rank::Ranked;
use super::study::StudyYear;
use super::work::conflicts::Kind;
use crate::growth::survey::report::{AgeRecord, GrowthRecord};
use crate::growth::{Dimensions, Measured};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

pub use crate::record::to_json;

fn round(v: f64, k: f64) -> f64 {
    (v * k).round() / k
}

/// One age of a grown street tree: the tree measured beside the equations, and the year's
/// account on its site (`sylva grow --json`, one line per age and species).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct YearRecord {
    /// The grown tree.
    #[serde(flatten)]
    pub growth: GrowthRecord,
    /// The year's account.
    pub street: AccountRecord,
}

impl YearRecord {
    /// Age `year` of species `m`, on its first site.
    pub fn of(m: &Measured, year: &StudyYear) -> YearRecord {
        YearRecord {
            growth: GrowthRecord::of(m, &year.record),
            street: AccountRecord::of(&year.accounts[0]),
        }
    }
}

/// Dollars by name, to the cent (`null` where not computed).
pub type Dollars = BTreeMap<String, Option<f64>>;

fn dollars(items: &[(&'static str, Option<f64>)]) -> Dollars {
    (items.iter())
        .map(|(name, v)| (name.to_string(), v.map(|x| round(x, 100.0))))
        .collect()
}

/// A ranking's sums on one basis.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NetRecord {
    /// Benefits over the years per tree planted, dollars.
    pub benefits_usd: f64,
    /// Less the costs.
    pub net_usd: f64,
    /// Benefits by i-Tree's category.
    pub by_category_usd: Dollars,
}

impl NetRecord {
    fn of(r: &Ranked, basis: Basis) -> NetRecord {
        NetRecord {
            benefits_usd: round(r.benefits(basis), 100.0),
            net_usd: round(r.net(basis), 100.0),
            by_category_usd: dollars(&r.by_category(basis)),
        }
    }
}

/// The first year of a kind of conflict.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FirstConflictRecord {
    /// The kind.
    pub kind: String,
    /// The age, years.
    pub age: f64,
    /// The part that causes it.
    pub part: String,
    /// Its share of the tree's leaf area.
    pub leaf_share: f64,
}

/// A year in which a cycle fell due, in a ranking's pruning.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PrunedYearRecord {
    /// The cycle.
    #[serde(flatten)]
    pub pruning: PruningRecord,
    /// The age, years.
    pub age: f64,
    /// Leaf area after the cuts, m².
    pub leaf_area_m2: f64,
    /// Benefits on the site the cuts cost that year (with `--pruning-losses`), dollars.
    pub benefits_lost_usd: Option<f64>,
}

/// A ranking's pruning: its totals and each year a cycle fell due.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct RankPruningRecord {
    pub cycles_with_cuts: usize,
    pub visits: u32,
    pub wood_removed_m3: f64,
    pub leaf_removed_m2: f64,
    pub cost_usd: f64,
    pub benefits_lost_usd: Option<f64>,
    /// Kinds of conflict some cycle cleared, and those left.
    pub resolved: Vec<String>,
    pub unresolved: Vec<String>,
    pub years: Vec<PrunedYearRecord>,
}

impl RankPruningRecord {
    /// `r`'s pruning, where it was grown under a regime.
    fn of(r: &Ranked) -> Option<RankPruningRecord> {
        let total = r.pruning()?;
        let kinds = |k: &[Kind]| k.iter().map(|k| k.name().to_string()).collect();
        let years = (r.accounts.iter().enumerate())
            .filter_map(|(i, a)| {
                Some(PrunedYearRecord {
                    pruning: PruningRecord::of(a.pruning.as_ref()?),
                    age: a.age,
                    leaf_area_m2: round(a.surfaces.0, 10.0),
                    benefits_lost_usd: r.benefits_lost.as_ref().map(|l| round(l[i], 100.0)),
                })
            })
            .collect();
        Some(RankPruningRecord {
            cycles_with_cuts: total.cycles,
            visits: total.visits,
            wood_removed_m3: round(total.wood_m3, 1e4),
            leaf_removed_m2: round(total.leaf_m2, 10.0),
            cost_usd: round(total.cost, 100.0),
            benefits_lost_usd: total.benefits_lost.map(|v| round(v, 100.0)),
            resolved: kinds(&total.resolved),
            unresolved: kinds(&total.unresolved),
            years,
        })
    }
}

/// What one of the street's conflicts cost over a ranking's years per tree planted, and who
/// paid it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ConflictCostRecord {
    /// The conflict.
    pub conflict: String,
    /// Who paid: `city`, `utility` or `owners`.
    pub payer: String,
    /// Dollars.
    pub usd: f64,
}

/// One species of a ranking (`sylva rank --json`, one line per species, best first).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RankRow {
    /// The species' code and common name.
    pub species: String,
    #[allow(missing_docs)]
    pub name: String,
    /// The last age grown.
    pub years: f64,
    /// The basis ranked by (`typical`, `site`).
    pub ranked_by: String,
    /// Benefits, costs and net over the years per tree planted on that basis, dollars.
    pub benefits_usd: f64,
    #[allow(missing_docs)]
    pub costs_usd: Option<f64>,
    #[allow(missing_docs)]
    pub net_usd: f64,
    /// Always true: every sum is per tree planted.
    pub per_tree_planted: bool,
    /// The share of the trees planted alive at the end.
    pub alive_at_end: f64,
    /// The survival the years are weighted by, in words.
    pub survival: String,
    /// Costs by item.
    pub costs_by_item_usd: Dollars,
    /// Costs by who pays them: `city`, `utility`, `owners`.
    pub costs_by_payer_usd: Dollars,
    /// What each of the street's conflicts cost, by who paid.
    pub conflict_costs: Vec<ConflictCostRecord>,
    /// Years each kind of conflict was in the way (or, a line, made the utility cut).
    pub conflict_years: BTreeMap<String, usize>,
    /// Where the species does not suit the site, with why; empty where it does.
    pub does_not_suit: Vec<String>,
    /// The sums at typical position and on the site.
    pub typical: NetRecord,
    #[allow(missing_docs)]
    pub site: NetRecord,
    /// The first year of each kind of conflict.
    pub first_conflicts: Vec<FirstConflictRecord>,
    /// Its pruning, where it was grown under a regime.
    pub pruning: Option<RankPruningRecord>,
    /// What was not computed, with reasons.
    pub not_computed: Vec<String>,
}

impl RankRow {
    /// Species `r` of a ranking by `basis`.
    pub fn of(r: &Ranked, basis: Basis) -> RankRow {
        let first = (super::rank::first_conflicts(&r.accounts).iter())
            .map(|(age, c)| FirstConflictRecord {
                kind: c.kind.name().to_string(),
                age: *age,
                part: c.part.name().to_string(),
                leaf_share: round(c.leaf_share, 1e3),
            })
            .collect();
        RankRow {
            species: r.species.species.code.clone(),
            name: r.species.species.common.clone(),
            years: r.last_age(),
            ranked_by: basis.name().to_string(),
            benefits_usd: round(r.benefits(basis), 100.0),
            costs_usd: (r.accounts.iter().any(|a| a.costs.is_some()))
                .then(|| round(r.costs(), 100.0)),
            net_usd: round(r.net(basis), 100.0),
            per_tree_planted: true,
            alive_at_end: round(r.alive_at_end(), 1e4),
            survival: r.survival.clone(),
            costs_by_item_usd: dollars(
                &(r.costs_by_item().into_iter())
                    .map(|(c, v)| (c.item().key, v))
                    .collect::<Vec<_>>(),
            ),
            costs_by_payer_usd: dollars(
                &(r.costs_by_payer().into_iter())
                    .map(|(p, v)| (p.name(), Some(v)))
                    .collect::<Vec<_>>(),
            ),
            conflict_costs: ConflictCostRecord::of(&r.accounts.iter().collect::<Vec<_>>()),
            conflict_years: (r.conflict_years().into_iter())
                .map(|(k, n)| (k.name().to_string(), n))
                .collect(),
            does_not_suit: r.unsuited(),
            typical: NetRecord::of(r, Basis::Typical),
            site: NetRecord::of(r, Basis::Site),
            first_conflicts: first,
            pruning: RankPruningRecord::of(r),
            not_computed: r.missing.clone(),
        }
    }
}

/// The site model around the standard house beside i-Tree's figures at one DBH
/// (`sylva rank --calibrate --json`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct CalibrationRecord {
    pub species: String,
    pub dbh_target_cm: f64,
    /// The age the grown tree reached the DBH, and its DBH then (`null` where its data end
    /// first, as is every figure of the grown tree).
    pub age: Option<f64>,
    pub dbh_cm: Option<f64>,
    pub projection_m2: Option<f64>,
    pub shade_cooling_kwh: Option<f64>,
    pub shade_gas_kbtu: Option<f64>,
    pub climate_cooling_kwh: Option<f64>,
    pub climate_gas_kbtu: Option<f64>,
    pub useful_winter_share: Option<f64>,
    pub cooling_kwh: Option<f64>,
    pub itree_electricity_kwh: Option<f64>,
    pub gas_kbtu: Option<f64>,
    pub itree_natural_gas_kbtu: Option<f64>,
    pub cooling_in_bounds: Option<bool>,
    pub heating_in_bounds: Option<bool>,
}

impl CalibrationRecord {
    /// The record of `r`.
    pub fn of(r: &Row) -> CalibrationRecord {
        let grown = |v: f64| r.reached.map(|_| v);
        CalibrationRecord {
            species: r.code.clone(),
            dbh_target_cm: r.target_cm,
            age: r.reached.map(|x| x.0),
            dbh_cm: r.reached.map(|x| x.1),
            projection_m2: grown(r.projection_m2),
            shade_cooling_kwh: grown(r.shade.0),
            shade_gas_kbtu: grown(r.shade.1),
            climate_cooling_kwh: r.climate.map(|c| c.0),
            climate_gas_kbtu: r.climate.map(|c| c.1),
            useful_winter_share: r.useful_share,
            cooling_kwh: grown(r.cooling_kwh),
            itree_electricity_kwh: grown(r.itree.0),
            gas_kbtu: grown(r.gas_kbtu),
            itree_natural_gas_kbtu: grown(r.itree.1),
            cooling_in_bounds: r.reached.map(|_| r.cooling_in_bounds()),
            heating_in_bounds: r.reached.map(|_| r.heating_in_bounds()),
        }
    }
}

/// A tree's dimensions as the page reads them: metres to the centimetre, DBH in cm and leaf
/// area in m² to a tenth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct DimsRecord {
    pub height: f64,
    pub crown_height: f64,
    pub crown_diameter: f64,
    pub dbh: f64,
    pub leaf_area: f64,
}

impl DimsRecord {
    /// `d`, rounded.
    pub fn of(d: &Dimensions) -> DimsRecord {
        DimsRecord {
            height: round(d.height, 100.0),
            crown_height: round(d.crown_height, 100.0),
            crown_diameter: round(d.crown_diameter, 100.0),
            dbh: round(d.dbh, 10.0),
            leaf_area: round(d.leaf_area, 10.0),
        }
    }
}

/// One age of the page's growth table (`/api/growth`'s `rows`): the grown tree and the
/// equations, and the year's account on the site shown.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PageRow {
    /// The age, years.
    pub age: f64,
    /// The grown tree.
    pub model: DimsRecord,
    /// The equations at that age.
    pub measured: DimsRecord,
    /// The year's account: the same record as `sylva grow --json`'s `street`.
    pub street: AccountRecord,
}

impl PageRow {
    /// Age `r` with its account on the site shown.
    pub fn of(r: &AgeRecord, account: &super::YearAccount) -> PageRow {
        let t = &r.measured;
        let measured = Dimensions {
            height: t.height,
            crown_height: t.crown_height,
            crown_diameter: t.crown_diameter,
            dbh: t.dbh,
            leaf_area: t.leaf_area,
        };
        PageRow {
            age: r.age,
            model: DimsRecord::of(&r.model),
            measured: DimsRecord::of(&measured),
            street: AccountRecord::of(account),
        }
    }
}

/// A species as the page names and colours it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct SpeciesLabel {
    pub code: String,
    pub common: String,
    pub scientific: String,
    /// The Urban Tree Database's tree type (`BDL`, `CEM`, ...).
    #[serde(rename = "type")]
    pub tree_type: String,
    pub label: String,
    /// Bark and summer leaves, sRGB 0..1.
    pub bark: [f32; 3],
    pub leaves: [f32; 3],
}

/// A region as the page names it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct RegionLabel {
    pub code: String,
    pub name: String,
    /// Its reference city.
    pub city: String,
}

/// The first year of a kind of conflict, as the page's table marks it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PageConflict {
    /// The kind.
    pub kind: String,
    /// The whole age, years.
    pub age: u32,
}

/// The page's growth table (`/api/growth`): one species grown through every age on one of the
/// built-in sites, each age a [`PageRow`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PageGrowth {
    /// The species and region.
    pub species: SpeciesLabel,
    #[allow(missing_docs)]
    pub region: RegionLabel,
    /// The growth's seed, the site's key, and whether its regime cut the tree.
    pub seed: u64,
    #[allow(missing_docs)]
    pub site: String,
    #[allow(missing_docs)]
    pub pruning: bool,
    /// Every age.
    pub rows: Vec<PageRow>,
    /// The first age of each kind of conflict, by age.
    pub first_conflicts: Vec<PageConflict>,
    /// Where the species does not suit the site, with why (`street::rank::unsuited`).
    pub does_not_suit: Vec<String>,
    /// What the street's conflicts cost over every age shown, per tree planted, by who paid.
    pub conflict_costs: Vec<ConflictCostRecord>,
    /// What was not computed, with reasons.
    pub missing: Vec<String>,
}

impl ConflictCostRecord {
    /// Each conflict's cost over `accounts`, by who paid (`street::rank::conflict_costs`).
    pub fn of(accounts: &[&super::YearAccount]) -> Vec<ConflictCostRecord> {
        (super::rank::conflict_costs(accounts).into_iter())
            .map(|(conflict, payer, usd)| ConflictCostRecord {
                conflict: conflict.to_string(),
                payer: payer.name().to_string(),
                usd: round(usd, 100.0),
            })
            .collect()
    }
}

impl SpeciesLabel {
    /// `m`'s.
    pub fn of(m: &Measured) -> SpeciesLabel {
        let (bark, leaves) = m.colours();
        SpeciesLabel {
            code: m.species.code.clone(),
            common: m.species.common.clone(),
            scientific: m.species.scientific.clone(),
            tree_type: m.species.tree_type.clone(),
            label: m.label(),
            bark,
            leaves,
        }
    }
}

impl RegionLabel {
    /// `m`'s region.
    pub fn of(m: &Measured) -> RegionLabel {
        RegionLabel {
            code: m.region.code.clone(),
            name: m.region.name.clone(),
            city: m.region.city.clone(),
        }
    }
}

/// A region the page offers (`/api/regions`): its reference city, latitude where Sylva's
/// climate table has it, and how many of its species can be grown.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct RegionRecord {
    pub code: String,
    pub name: String,
    pub city: String,
    pub latitude: Option<f64>,
    pub species: usize,
}

impl RegionRecord {
    /// Region `r` of `db`.
    pub fn of(r: &crate::growth::Region, db: &crate::growth::Database) -> RegionRecord {
        RegionRecord {
            code: r.code.clone(),
            name: r.name.clone(),
            city: r.city.clone(),
            latitude: super::energy::climate::climate(&r.code).map(|c| c.latitude),
            species: db.growable(&r.code).len(),
        }
    }
}

/// A species the page can grow in a region (`/api/species`), with the first and last whole
/// age it is shown at.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct GrowableRecord {
    pub code: String,
    pub common: String,
    pub scientific: String,
    #[serde(rename = "type")]
    pub tree_type: String,
    pub ages: [Option<u32>; 2],
}

impl GrowableRecord {
    /// Species `m`, shown from age `ages[0]` to `ages[1]`.
    pub fn of(m: &Measured, ages: [Option<u32>; 2]) -> GrowableRecord {
        GrowableRecord {
            code: m.species.code.clone(),
            common: m.species.common.clone(),
            scientific: m.species.scientific.clone(),
            tree_type: m.species.tree_type.clone(),
            ages,
        }
    }
}
