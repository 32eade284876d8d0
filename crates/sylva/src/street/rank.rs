//! A region's species side by side: each grown year by year on the same site, its benefits
//! and costs summed over the years, and the first year it runs into the street.

use super::accounts::costs::{Costs, YearCosts};
use super::accounts::ledger::{Assessor, YearAccount};
use super::accounts::money::Basis;
use super::accounts::prices::Prices;
use super::accounts::pruner::{Pruner, PruningYear};
use super::accounts::survival::Survival;
use super::site::Site;
use super::work::conflicts::{Conflict, Kind};
use crate::growth::Measured;
use crate::growth::report::Cohort;
use rayon::prelude::*;

/// One species' run.
#[derive(Clone, Debug)]
pub struct Ranked {
    /// The species.
    pub species: Measured,
    /// Every year's account, in order.
    pub accounts: Vec<YearAccount>,
    /// What was not computed, with reasons.
    pub missing: Vec<String>,
    /// Whether it was grown under a pruning regime (a site's, and not `Pruning::Off`).
    pub pruned: bool,
    /// With [`Pruning::Compare`], each year's benefits on the site that pruning cost: the same
    /// tree never cut less the cut one, dollars, in the order of `accounts`.
    pub benefits_lost: Option<Vec<f64>>,
    /// The survival its years are weighted by, in words.
    pub survival: String,
}

impl Ranked {
    /// Benefits over the years per tree planted, dollars (undiscounted): each year's for a
    /// living tree, weighted by the share of the trees planted standing through it.
    pub fn benefits(&self, basis: Basis) -> f64 {
        self.accounts
            .iter()
            .map(|a| a.planted_benefits(basis))
            .sum()
    }

    /// Costs over the years per tree planted, dollars.
    pub fn costs(&self) -> f64 {
        self.accounts.iter().map(|a| a.planted_costs()).sum()
    }

    /// Benefits less costs per tree planted.
    pub fn net(&self, basis: Basis) -> f64 {
        self.benefits(basis) - self.costs()
    }

    /// Benefits over the years per tree planted in each of i-Tree's categories, dollars (none
    /// where a category is never computed).
    pub fn by_category(&self, basis: Basis) -> Vec<(&'static str, Option<f64>)> {
        let mut out: Vec<(&'static str, Option<f64>)> = Vec::new();
        for a in &self.accounts {
            for (i, (name, v)) in a.money(basis).categories().into_iter().enumerate() {
                if out.len() <= i {
                    out.push((name, None));
                }
                if let Some(v) = v {
                    out[i].1 = Some(out[i].1.unwrap_or(0.0) + a.cohort.alive * v);
                }
            }
        }
        out
    }

    /// Costs over the years per tree planted, item by item, dollars: the city's items, the
    /// site's pruning cycles, and the utility's line clearance (none where the run has no
    /// costs).
    pub fn costs_by_item(&self) -> Vec<(&'static str, Option<f64>)> {
        let items = |c: &YearCosts| {
            [
                ("planting", c.planting),
                ("pruning", c.pruning),
                ("pruning_cycles", c.cycles),
                ("removal", c.removal),
                ("sidewalk_repair", c.sidewalk),
                ("cleanup", c.cleanup),
                ("pest_liability_administration", c.other),
                ("programme_average", c.average),
                ("line_clearance_utility", c.utility),
            ]
        };
        let mut out: Vec<(&'static str, Option<f64>)> = items(&YearCosts::default())
            .map(|(n, _)| (n, None))
            .to_vec();
        for a in &self.accounts {
            let Some(c) = &a.costs else { continue };
            for (i, (name, v)) in items(c).into_iter().enumerate() {
                // Planting is paid for every tree planted, the rest for the living.
                let weight = if name == "planting" {
                    1.0
                } else {
                    a.cohort.alive
                };
                out[i].1 = Some(out[i].1.unwrap_or(0.0) + weight * v);
            }
        }
        out
    }

    /// The share of the trees planted alive at the end of the run.
    pub fn alive_at_end(&self) -> f64 {
        self.accounts.last().map_or(1.0, |a| a.cohort.alive_at_end)
    }

    /// The last age grown.
    pub fn last_age(&self) -> f64 {
        self.accounts.last().map_or(0.0, |a| a.age)
    }

    /// Its pruning over the years, where it was grown with a regime (no cycle may have
    /// fallen due yet: then it is all zeros).
    pub fn pruning(&self) -> Option<PruningSummary> {
        let years: Vec<&PruningYear> = (self.accounts.iter())
            .filter_map(|a| a.pruning.as_ref())
            .collect();

        let mut unresolved: Vec<Kind> = years.iter().flat_map(|y| y.unresolved.clone()).collect();
        unresolved.sort();
        unresolved.dedup();
        let mut resolved: Vec<Kind> = years.iter().flat_map(|y| y.resolved()).collect();
        resolved.sort();
        resolved.dedup();
        self.pruned.then(|| PruningSummary {
            cycles: years.iter().filter(|y| !y.cuts.marks.is_empty()).count(),
            visits: years.iter().map(|y| y.visits).sum(),
            wood_m3: years.iter().map(|y| y.wood_m3()).sum(),
            leaf_m2: years.iter().map(|y| y.leaf_m2()).sum(),
            cost: years.iter().map(|y| y.cost).sum(),
            benefits_lost: self.benefits_lost.as_ref().map(|l| l.iter().sum()),
            resolved,
            unresolved,
        })
    }
}

/// A run's pruning, summed over its years.
#[derive(Clone, Debug, PartialEq)]
pub struct PruningSummary {
    /// Years in which something was cut.
    pub cycles: usize,
    /// Crews' visits that cut something.
    pub visits: u32,
    /// Wood removed, m³.
    pub wood_m3: f64,
    /// Leaf area removed, m².
    pub leaf_m2: f64,
    /// What the visits cost, $.
    pub cost: f64,
    /// Benefits on the site lost to pruning over the years, $ (with [`Pruning::Compare`]).
    pub benefits_lost: Option<f64>,
    /// Kinds of conflict some cycle cleared.
    pub resolved: Vec<Kind>,
    /// Kinds of conflict left after some cycle due for them, or that no pruning clears.
    pub unresolved: Vec<Kind>,
}

/// The first year of each kind of conflict in a run of accounts, with the conflict as it was
/// that year, in report order.
pub fn first_conflicts(accounts: &[YearAccount]) -> Vec<(f64, Conflict)> {
    let mut out: Vec<(f64, Conflict)> = Vec::new();
    for a in accounts {
        for c in &a.conflicts {
            if out.iter().all(|(_, seen)| seen.kind != c.kind) {
                out.push((a.age, *c));
            }
        }
    }
    out.sort_by_key(|(_, c)| c.kind);
    out
}

/// The earliest conflict of any kind: its year and kind.
pub fn first_conflict(accounts: &[YearAccount]) -> Option<(f64, Kind)> {
    first_conflicts(accounts)
        .into_iter()
        .map(|(age, c)| (age, c.kind))
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// The whole ages a species is grown through for a run of `years`: from its first whole age
/// (at least 1) to `years` or the end of its data.
pub fn ages(m: &Measured, years: f64) -> Vec<f64> {
    let first = m.ages.0.ceil().max(1.0);
    let last = years.min(m.ages.1.floor());
    let mut out = Vec::new();
    let mut a = first;
    while a <= last + 1e-9 {
        out.push(a);
        a += 1.0;
    }
    out
}

/// How a run treats the site's pruning regime.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pruning {
    /// The site's regime cuts the tree as its cycles fall due (the default).
    Regime,
    /// The regime cuts the tree, and the same tree is grown uncut beside it, so that each
    /// year's benefits lost to pruning are known (it takes both growths' time).
    Compare,
    /// Nothing is ever cut: the tree grows on through the street's zones.
    Off,
}

/// What a run of street trees is asked: how long, which seed, on which site, at which prices
/// and costs, with which survival, and how the site's pruning regime is treated. `None`s are
/// the built-in defaults (no site: typical position only).
#[derive(Clone, Debug)]
pub struct Study {
    /// Years each tree is grown (or as long as its data reach).
    pub years: f64,
    /// The growth's seed.
    pub seed: u64,
    /// The planting site.
    pub site: Option<Site>,
    /// Prices (default: the region's built-in ones).
    pub prices: Option<Prices>,
    /// Costs (default: the built-in sized table).
    pub costs: Option<Costs>,
    /// Survival (default: the region's built-in).
    pub survival: Option<Survival>,
    /// How the site's pruning regime is treated.
    pub pruning: Pruning,
}

impl Study {
    /// A run of `years` on typical position, with every default.
    pub fn new(years: f64) -> Study {
        Study {
            years,
            seed: 0,
            site: None,
            prices: None,
            costs: None,
            survival: None,
            pruning: Pruning::Regime,
        }
    }
}

/// Grows every species yearly as `study` asks, in parallel, and returns them by net benefit
/// per tree planted on `basis`, best first. `done` is called as each species finishes.
pub fn rank(
    species: Vec<Measured>,
    study: &Study,
    basis: Basis,
    done: &(dyn Fn(&Measured) + Sync),
) -> Vec<Ranked> {
    let mut out: Vec<Ranked> = species
        .into_par_iter()
        .map(|m| {
            let r = run(&m, study);
            done(&m);
            r
        })
        .collect();
    out.sort_by(|a, b| b.net(basis).total_cmp(&a.net(basis)));
    out
}

/// One species grown and accounted yearly, pruned as `study.pruning` says where there is a
/// site.
pub fn run(m: &Measured, study: &Study) -> Ranked {
    if study.pruning == Pruning::Compare {
        let with = |pruning| Study {
            pruning,
            ..study.clone()
        };
        let (mut cut, uncut) = rayon::join(
            || run(m, &with(Pruning::Regime)),
            || run(m, &with(Pruning::Off)),
        );
        let total = |a: &YearAccount| a.planted_benefits(Basis::Site);
        cut.benefits_lost = cut.pruned.then(|| {
            (cut.accounts.iter().zip(&uncut.accounts))
                .map(|(c, u)| total(u) - total(c))
                .collect()
        });
        return cut;
    }
    let site = study.site.as_ref();
    let mut assessor = Assessor::new(
        m,
        study.site.clone(),
        study.prices.clone(),
        study.costs.clone(),
    );
    if let Some(s) = &study.survival {
        assessor = assessor.with_survival(s.clone());
    }
    let mut cohort = Cohort::new(vec![m.clone()], study.seed);
    let pruner = match (site, study.pruning) {
        (Some(site), Pruning::Regime) => Pruner::new(site, study.costs.as_ref()),
        _ => None,
    };
    if pruner.is_some() {
        assessor.charge_cycles();
    }
    let mut accounts = Vec::new();
    for age in ages(m, study.years) {
        let cycle =
            (pruner.as_ref()).and_then(|p| p.advance(&mut cohort.growers[0], age, |_, _, _, _| {}));
        let skeleton = cohort.advance_to(age).remove(0);
        let dims = cohort.history[0]
            .last()
            .map(|r| r.model)
            .unwrap_or_default();
        let mut account = assessor.year(age, &dims, &skeleton);
        if pruner.is_some() {
            account.record_pruning(cycle, 1.0);
        }
        accounts.push(account);
    }
    Ranked {
        species: m.clone(),
        accounts,
        missing: assessor.missing().to_vec(),
        pruned: pruner.is_some(),
        benefits_lost: None,
        survival: assessor.survival().source.clone(),
    }
}
