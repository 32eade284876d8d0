//! A region's species side by side: each grown year by year on the same site, its benefits
//! and costs summed over the years, and the first year it runs into the street.

use super::conflicts::{Conflict, Kind};
use super::costs::Costs;
use super::ledger::{Assessor, YearAccount};
use super::money::Basis;
use super::prices::Prices;
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
    basis: Basis,
    done: &(dyn Fn(&Measured) + Sync),
) -> Vec<Ranked> {
    let mut out: Vec<Ranked> = species
        .into_par_iter()
        .map(|m| {
            let r = run(&m, years, seed, site, prices, costs);
            done(&m);
            r
        })
        .collect();
    out.sort_by(|a, b| b.net(basis).total_cmp(&a.net(basis)));
    out
}

/// One species grown and accounted yearly.
pub fn run(
    m: &Measured,
    years: f64,
    seed: u64,
    site: Option<&Site>,
    prices: Option<&Prices>,
    costs: Option<&Costs>,
) -> Ranked {
    let mut assessor = Assessor::new(m, site.cloned(), prices.cloned(), costs.cloned());
    let mut cohort = Cohort::new(vec![m.clone()], seed);
    let mut accounts = Vec::new();
    for age in ages(m, years) {
        let skeleton = cohort.advance_to(age).remove(0);
        let dims = cohort.history[0]
            .last()
            .map(|r| r.model)
            .unwrap_or_default();
        accounts.push(assessor.year(age, &dims, &skeleton));
    }
    Ranked {
        species: m.clone(),
        accounts,
        missing: assessor.missing().to_vec(),
    }
}
