//! A region's species side by side: each grown year by year on the same site, its benefits
//! and costs summed over the years, and the first year it runs into the street.

use super::conflicts::{Conflict, Kind};
use super::costs::Costs;
use super::ledger::{Assessor, YearAccount};
use super::money::Basis;
use super::prices::Prices;
use super::pruner::{Pruner, PruningYear};
use super::site::Site;
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
}

impl Ranked {
    /// Benefits over the years, dollars (undiscounted).
    pub fn benefits(&self, basis: Basis) -> f64 {
        self.accounts.iter().map(|a| a.money(basis).total()).sum()
    }

    /// Costs over the years, dollars.
    pub fn costs(&self) -> f64 {
        self.accounts
            .iter()
            .map(|a| a.costs.map_or(0.0, |c| c.total()))
            .sum()
    }

    /// Benefits less costs.
    pub fn net(&self, basis: Basis) -> f64 {
        self.benefits(basis) - self.costs()
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

/// Grows every species yearly to `years` on the same site, in parallel, and returns them by
/// net benefit on `basis`, best first. `done` is called as each species finishes.
#[allow(clippy::too_many_arguments)]
pub fn rank(
    species: Vec<Measured>,
    years: f64,
    seed: u64,
    site: Option<&Site>,
    prices: Option<&Prices>,
    costs: Option<&Costs>,
    pruning: Pruning,
    basis: Basis,
    done: &(dyn Fn(&Measured) + Sync),
) -> Vec<Ranked> {
    let mut out: Vec<Ranked> = species
        .into_par_iter()
        .map(|m| {
            let r = run(&m, years, seed, site, prices, costs, pruning);
            done(&m);
            r
        })
        .collect();
    out.sort_by(|a, b| b.net(basis).total_cmp(&a.net(basis)));
    out
}

/// One species grown and accounted yearly, pruned as `pruning` says where there is a site.
pub fn run(
    m: &Measured,
    years: f64,
    seed: u64,
    site: Option<&Site>,
    prices: Option<&Prices>,
    costs: Option<&Costs>,
    pruning: Pruning,
) -> Ranked {
    if pruning == Pruning::Compare {
        let (mut cut, uncut) = rayon::join(
            || run(m, years, seed, site, prices, costs, Pruning::Regime),
            || run(m, years, seed, site, prices, costs, Pruning::Off),
        );
        let total = |a: &YearAccount| a.money(Basis::Site).total();
        cut.benefits_lost = cut.pruned.then(|| {
            (cut.accounts.iter().zip(&uncut.accounts))
                .map(|(c, u)| total(u) - total(c))
                .collect()
        });
        return cut;
    }
    let mut assessor = Assessor::new(m, site.cloned(), prices.cloned(), costs.cloned());
    let mut cohort = Cohort::new(vec![m.clone()], seed);
    let pruner = match (site, pruning) {
        (Some(site), Pruning::Regime) => Pruner::new(site, costs),
        _ => None,
    };
    let mut accounts = Vec::new();
    for age in ages(m, years) {
        let cycle =
            (pruner.as_ref()).and_then(|p| p.advance(&mut cohort.growers[0], age, |_, _, _, _| {}));
        let skeleton = cohort.advance_to(age).remove(0);
        let dims = cohort.history[0]
            .last()
            .map(|r| r.model)
            .unwrap_or_default();
        let mut account = assessor.year(age, &dims, &skeleton);
        if let Some(p) = &pruner {
            account.record_pruning(cycle, p.replaces_itemised_pruning());
        }
        accounts.push(account);
    }
    Ranked {
        species: m.clone(),
        accounts,
        missing: assessor.missing().to_vec(),
        pruned: pruner.is_some(),
        benefits_lost: None,
    }
}
