//! A region's species side by side: each grown year by year on the same site, its benefits
//! and costs summed over the years, and the first year it runs into the street.

use super::accounts::items::{Cost, Payer};
use super::accounts::ledger::YearAccount;
use super::accounts::money::Basis;
use super::accounts::pruner::PruningYear;
use super::error::StreetError;
use super::study::{Spread, StreetTree};
use super::work::conflicts::{Conflict, Kind};
use crate::growth::{CutKind, Database, Measured};
use rayon::prelude::*;

pub use super::study::{Pruning, Study};

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

    /// Costs over the years per tree planted, item by item ([`costs_by_item`]).
    pub fn costs_by_item(&self) -> Vec<(Cost, Option<f64>)> {
        costs_by_item(&self.years())
    }

    /// Costs over the years per tree planted by who pays them ([`costs_by_payer`]).
    pub fn costs_by_payer(&self) -> Vec<(Payer, f64)> {
        costs_by_payer(&self.years())
    }

    /// What each of the street's conflicts cost, by who paid ([`conflict_costs`]).
    pub fn conflict_costs(&self) -> Vec<(&'static str, Payer, f64)> {
        conflict_costs(&self.years())
    }

    /// How many years each kind of conflict was in the way ([`conflict_years`]).
    pub fn conflict_years(&self) -> Vec<(Kind, usize)> {
        conflict_years(&self.years())
    }

    /// Where the species does not suit the site ([`unsuited`]).
    pub fn unsuited(&self) -> Vec<String> {
        unsuited(&self.years())
    }

    fn years(&self) -> Vec<&YearAccount> {
        self.accounts.iter().collect()
    }

    /// The share of the trees planted alive at the end of the run.
    pub fn alive_at_end(&self) -> f64 {
        self.accounts.last().map_or(1.0, |a| a.cohort.alive_at_end)
    }

    /// The last age grown.
    pub fn last_age(&self) -> f64 {
        self.accounts.last().map_or(0.0, |a| a.age)
    }

    /// The earliest first conflict that clearance pruning meets (growing into the clear
    /// heights over roadway and sidewalk: the crown is raised) with `clearance`, or that it
    /// does not (a fixture: wall, awnings, signs, lines, lamps, sight lines, curb): its age and
    /// kind.
    pub fn earliest(&self, clearance: bool) -> Option<(f64, Kind)> {
        first_conflicts(&self.accounts)
            .into_iter()
            .filter(|(_, c)| matches!(c.kind, Kind::Roadway | Kind::Sidewalk) == clearance)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(age, c)| (age, c.kind))
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

/// Costs over the years per tree planted, item by item (`items.rs`'s [`Cost`]), dollars:
/// the city's, the utility's and the owners' (none where the run has no costs).
pub fn costs_by_item(accounts: &[&YearAccount]) -> Vec<(Cost, Option<f64>)> {
    let mut out: Vec<(Cost, Option<f64>)> = Cost::ALL.map(|c| (c, None)).to_vec();
    for a in accounts {
        let Some(c) = &a.costs else { continue };
        for (i, (item, v)) in c.items().enumerate() {
            // Planting, and what is done at planting, is paid for every tree planted, the rest
            // for the living.
            let weight = if item.at_planting() {
                1.0
            } else {
                a.cohort.alive
            };
            out[i].1 = Some(out[i].1.unwrap_or(0.0) + weight * v);
        }
    }
    out
}

/// Costs over the years per tree planted by who pays them (`items.rs`'s [`Payer`]),
/// dollars.
pub fn costs_by_payer(accounts: &[&YearAccount]) -> Vec<(Payer, f64)> {
    let items = costs_by_item(accounts);
    (Payer::ALL.into_iter())
        .map(|p| {
            let paid = (items.iter())
                .filter(|(c, _)| c.payer() == p)
                .filter_map(|(_, v)| *v)
                .sum();
            (p, paid)
        })
        .collect()
}

/// What each of the street's conflicts cost over the years per tree planted, by who paid:
/// the line's clearance (the utility's crews), the clear heights and the building (the
/// city's crews, whose visits also train the young tree), and the pavement the roots lift
/// (its repairs, the city's and the owners' shares, and the claims and administration
/// that come with them), dollars; only those that cost anything.
pub fn conflict_costs(accounts: &[&YearAccount]) -> Vec<(&'static str, Payer, f64)> {
    let items = costs_by_item(accounts);
    let of = |wanted: &[Cost]| -> f64 {
        (items.iter())
            .filter(|(c, _)| wanted.contains(c))
            .filter_map(|(_, v)| *v)
            .sum()
    };
    [
        ("line clearance", Payer::Utility, of(&[Cost::LineClearance])),
        (
            "clear heights, building and training",
            Payer::City,
            of(&[Cost::Cycles]),
        ),
        (
            "pavement lifted by the roots",
            Payer::City,
            of(&[Cost::Sidewalk, Cost::Liability, Cost::Mitigation]),
        ),
        (
            "pavement lifted by the roots",
            Payer::Owners,
            of(&[Cost::SidewalkOwners]),
        ),
    ]
    .into_iter()
    .filter(|c| c.2 > 0.0)
    .collect()
}

/// How many years each kind of conflict was in the way, before the year's cuts or after
/// them, or (a line) made the utility's crew cut.
pub fn conflict_years(accounts: &[&YearAccount]) -> Vec<(Kind, usize)> {
    (Kind::ALL.into_iter())
        .map(|k| {
            let years = (accounts.iter().copied())
                .filter(|a| {
                    a.conflicts.iter().any(|c| c.kind == k)
                        || a.pruning.as_ref().is_some_and(|p| p.before.contains(&k))
                        || (k == Kind::Wire && a.lines.iter().any(|l| l.visit.is_some()))
                })
                .count();
            (k, years)
        })
        .filter(|(_, n)| *n > 0)
        .collect()
}

/// Where the species does not suit the site, each reason in words; empty where it does:
/// - it does not make the utility's trim cycle, the crews coming back between cycles to
///   keep its crown out of the line (utilities remove such trees from under their lines:
///   "Trees under the power lines such as locust, cherry and maple are removed when they're
///   young because they are fast growers and do not make the normal trim cycle", Peninsula
///   Light Co.'s tree trimming FAQ);
/// - its leader had to be headed back to clear the line, having no lateral to be cut back
///   to (Dahle et al. 2006 found 80% of headed silver maple leaders decayed from the cut);
/// - any leaf or wood entered a line's minimum clearance;
/// - its trunk's flare outgrew its bed, reaching the curb or the sidewalk.
pub fn unsuited(accounts: &[&YearAccount]) -> Vec<String> {
    let mut out = Vec::new();
    let years: Vec<&PruningYear> = accounts.iter().filter_map(|a| a.pruning.as_ref()).collect();
    let hot: u32 = years.iter().map(|y| y.hot_spots).sum();
    if hot > 0 {
        let first = (accounts.iter().copied())
            .find(|a| a.pruning.as_ref().is_some_and(|p| p.hot_spots > 0))
            .map_or(0.0, |a| a.age);
        out.push(format!(
            "does not make the utility's trim cycle: {} between cycles to keep it out of \
             the line, from age {first:.0}",
            counted(hot as usize, "visit", "visits")
        ));
    }
    let headed: usize = years.iter().map(|y| y.count(CutKind::Heading)).sum();
    if headed > 0 {
        out.push(format!(
            "its leader headed back {} to clear the line (no lateral to cut back to)",
            counted(headed, "time", "times")
        ));
    }
    let breaches = (accounts.iter().copied())
        .flat_map(|a| &a.lines)
        .filter(|l| l.breach)
        .count();
    if breaches > 0 {
        out.push(format!(
            "leaf or wood inside the line's minimum clearance in {}",
            counted(breaches, "year", "years")
        ));
    }
    let flare =
        (accounts.iter().copied()).find(|a| a.conflicts.iter().any(|c| c.kind == Kind::TrunkFlare));
    if let Some(a) = flare {
        out.push(format!(
            "its trunk's flare outgrows its bed, reaching the pavement at age {:.0}",
            a.age
        ));
    }
    out
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

/// A ranking asked for: a region's growable species (or those of them named), grown as
/// `study` says, ranked by the net on `basis` (default: the site's where there is one, else
/// typical position's).
#[derive(Clone, Debug)]
pub struct RankRequest {
    /// The Urban Tree Database region.
    pub region: String,
    /// Species codes to rank (any case); empty: every growable species of the region.
    pub species: Vec<String>,
    /// How each is grown and accounted.
    pub study: Study,
    /// The net the ranking is by.
    pub basis: Option<Basis>,
}

impl RankRequest {
    /// Every growable species of `region`, grown as `study` says.
    pub fn new(region: &str, study: Study) -> RankRequest {
        RankRequest {
            region: region.to_string(),
            species: Vec::new(),
            study,
            basis: None,
        }
    }

    /// The basis ranked by.
    pub fn basis(&self) -> Basis {
        self.basis
            .unwrap_or_else(|| Basis::default_for(self.study.site.is_some()))
    }

    /// The species the request names, from `db`, in the database's order: an error names a
    /// code that is not a growable species of the region, or a region without any.
    pub fn species(&self, db: &Database) -> Result<Vec<Measured>, StreetError> {
        let region = &self.region;
        let mut species: Vec<Measured> = (db.growable(region).iter())
            .map(|s| db.find(region, &s.code))
            .collect::<Result<_, _>>()
            .map_err(|e| StreetError::Missing(e.to_string()))?;
        for code in &self.species {
            if !(species.iter()).any(|m| m.species.code.eq_ignore_ascii_case(code)) {
                return Err(StreetError::Missing(format!(
                    "--species {code}: not a growable species of {region}; see `sylva species \
                     --region {region}`"
                )));
            }
        }
        if !self.species.is_empty() {
            species
                .retain(|m| (self.species.iter()).any(|c| c.eq_ignore_ascii_case(&m.species.code)));
        }
        if species.is_empty() {
            let known: Vec<&str> = db.regions().iter().map(|r| r.code.as_str()).collect();
            return Err(StreetError::Missing(format!(
                "--region {region}: no such region with growable species; regions: {}",
                known.join(", ")
            )));
        }
        Ok(species)
    }
}

/// Grows every species of `request` yearly, in parallel, and returns them by net benefit per
/// tree planted on its basis, best first. `done` is called as each species finishes.
pub fn rank(
    request: &RankRequest,
    db: &Database,
    done: &(dyn Fn(&Measured) + Sync),
) -> Result<Vec<Ranked>, StreetError> {
    let basis = request.basis();
    let study = &request.study;
    study.check()?;
    let mut out: Vec<Ranked> = request
        .species(db)?
        .into_par_iter()
        .map(|m| {
            let r = run(&m, study);
            done(&m);
            r
        })
        .collect();
    out.sort_by(|a, b| b.net(basis).total_cmp(&a.net(basis)));
    Ok(out)
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
    let mut tree = StreetTree::new(m, study);
    let accounts = ages(m, study.years)
        .into_iter()
        .map(|age| {
            (tree.grow_to(age, Spread::Whole, |_, _, _, _| {}).accounts)
                .pop()
                .expect("a study's tree is accounted on one site")
        })
        .collect();
    let assessor = tree.assessor(0);
    Ranked {
        species: m.clone(),
        accounts,
        missing: assessor.missing().to_vec(),
        pruned: tree.pruned(),
        benefits_lost: None,
        survival: assessor.survival().source.clone(),
    }
}

/// `n` and its noun: "1 visit", "9 visits".
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::street::site::narrow_for_tests as narrow;

    /// Under the narrow site's line a plane does not make the utility's trim cycle and its
    /// conflicts cost the utility, the city and the owners; a crapemyrtle, which matures below
    /// the line, suits it. Nothing here ranks by height: each says so from its own account.
    #[test]
    fn a_species_that_outgrows_the_line_does_not_suit_the_site_and_says_who_pays() {
        let db = Database::builtin();
        let study = Study {
            site: Some(narrow()),
            ..Study::new(16.0)
        };
        let plane = run(&db.find("InlVal", "PLAC").unwrap(), &study);
        let myrtle = run(&db.find("InlVal", "LAIN").unwrap(), &study);
        let unsuited = plane.unsuited();
        assert!(
            unsuited.iter().any(|u| u.contains("trim cycle")),
            "{unsuited:?}"
        );
        assert!(myrtle.unsuited().is_empty(), "{:?}", myrtle.unsuited());
        // Who pays what: the payers' sums are the costs; the line is the utility's alone.
        for r in [&plane, &myrtle] {
            let paid: f64 = r.costs_by_payer().iter().map(|p| p.1).sum();
            assert!((paid - r.costs()).abs() < 1e-6, "{paid} {}", r.costs());
        }
        let line = (plane.conflict_costs().into_iter())
            .find(|c| c.0 == "line clearance")
            .expect("the plane's line clearance");
        assert_eq!(line.1, Payer::Utility);
        assert!(line.2 > 0.0);
        assert!(
            (plane.conflict_costs().iter())
                .any(|c| c.0.contains("pavement") && c.1 == Payer::Owners && c.2 > 0.0)
        );
        assert!(
            myrtle
                .conflict_costs()
                .iter()
                .all(|c| c.1 != Payer::Utility)
        );
        // The years the line made the utility cut are counted as the wire's.
        let wire = (plane.conflict_years().into_iter()).find(|k| k.0 == Kind::Wire);
        assert!(wire.is_some_and(|(_, n)| n >= 4), "{wire:?}");
        // What the cuts do to the tree is not priced, and the account says so; a site with
        // no line does not.
        let harm = |r: &Ranked| {
            r.missing
                .iter()
                .any(|m| m.contains("repeated line clearance"))
        };
        assert!(harm(&plane), "{:?}", plane.missing);
        let mut open = narrow();
        open.wire.clear();
        let unwired = Study {
            site: Some(open),
            ..Study::new(2.0)
        };
        assert!(!harm(&run(&db.find("InlVal", "PLAC").unwrap(), &unwired)));
    }
}
