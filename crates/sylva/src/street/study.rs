//! The street's one study pipeline: a street tree grown year by year on its site, cut by the
//! site's pruning regime as its cycles fall due, and accounted (benefits, costs, survival) at
//! every age asked. `sylva grow`, `sylva rank`, the planners' page and the Python wheel all
//! grow their street trees through [`StreetTree`], so a year means the same everywhere.

use super::accounts::costs::Costs;
use super::accounts::ledger::{Assessor, YearAccount};
use super::accounts::prices::Prices;
use super::accounts::pruner::{Pruner, PruningYear};
use super::accounts::survival::Survival;
use super::energy::crown::{Crown, leaves_of};
use super::error::StreetError;
use super::site::Site;
use super::work::conflicts::{Conflict, Kind};
use crate::Skeleton;
use crate::growth::survey::report::{AgeRecord, Cohort};
use crate::growth::{Grower, Measured};

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

    /// Checks what the study's files say together: every mitigation the site asks for is
    /// priced by its costs (or the built-in table). Run before anything grows, so a gap is an
    /// error naming the file and the key, with nothing written.
    pub fn check(&self) -> Result<(), StreetError> {
        if let Some(site) = &self.site
            && let Some(m) = &site.mitigation
        {
            (self.costs.as_ref().unwrap_or_else(|| Costs::sized()))
                .mitigation(m)
                .map_err(|message| StreetError::Syntax {
                    file: site.file.clone(),
                    message,
                })?;
        }
        Ok(())
    }

    /// The account keeper of species `m` under this study: its site, prices, costs and
    /// survival.
    pub fn assessor(&self, m: &Measured) -> Assessor {
        let a = Assessor::new(
            m,
            self.site.clone(),
            self.prices.clone(),
            self.costs.clone(),
        );
        match &self.survival {
            Some(s) => a.with_survival(s.clone()),
            None => a,
        }
    }

    /// The pruner of this study's site, where its regime is to be carried out and cuts
    /// anything.
    fn pruner(&self) -> Option<Pruner> {
        match (&self.site, self.pruning) {
            (Some(site), Pruning::Regime) => Pruner::new(site, self.costs.as_ref()),
            _ => None,
        }
    }
}

/// How a record carries the pruning cycles carried out since the record before.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spread {
    /// Whole: a run whose records are summed (a ranking, the page's table) loses no cycle's
    /// cost.
    Whole,
    /// As a yearly rate over the years since the record before (since planting for the
    /// first): `sylva grow --step 10` shows ten years' visits as a tenth a year, beside one
    /// year's benefits.
    PerYear,
}

/// One age of a street tree.
pub struct StudyYear {
    /// The age, years.
    pub age: f64,
    /// The grown tree measured, beside the equations.
    pub record: AgeRecord,
    /// The year's account on each of the tree's sites, in the order given.
    pub accounts: Vec<YearAccount>,
    /// The conflicts on the first site of a kind never met before, in report order.
    pub new_conflicts: Vec<Conflict>,
    /// The tree.
    pub skeleton: Skeleton,
}

/// A street tree growing: its growth, its accounts on one or more sites, and the pruning
/// regime of one of them.
pub struct StreetTree {
    cohort: Cohort,
    assessors: Vec<Assessor>,
    /// The pruner, and the site whose account carries its cycles.
    pruner: Option<(usize, Pruner)>,
    last_age: Option<f64>,
    seen: Vec<Kind>,
}

impl StreetTree {
    /// A sapling of `m` as `study` asks: on its site, pruned by its regime unless
    /// [`Pruning::Off`] ([`Pruning::Compare`] is the caller's to grow twice, as
    /// the ranking does).
    pub fn new(m: &Measured, study: &Study) -> StreetTree {
        let pruner = study.pruner().map(|p| (0, p));
        StreetTree::build(m, study.seed, vec![study.assessor(m)], pruner)
    }

    /// A sapling of `m` from `seed` accounted on each of `sites` (built-in prices, costs and
    /// survival), cut by the regime of `sites[pruned]` where given; that site's accounts
    /// carry the cycles, the others are of the same cut tree.
    pub fn on_sites(m: &Measured, seed: u64, sites: &[Site], pruned: Option<usize>) -> StreetTree {
        let pruner = pruned.and_then(|s| Some((s, Pruner::new(sites.get(s)?, None)?)));
        let assessors = sites
            .iter()
            .map(|s| Assessor::new(m, Some(s.clone()), None, None))
            .collect();
        StreetTree::build(m, seed, assessors, pruner)
    }

    fn build(
        m: &Measured,
        seed: u64,
        mut assessors: Vec<Assessor>,
        pruner: Option<(usize, Pruner)>,
    ) -> StreetTree {
        // The pruned site's account charges its cycles in place of the cost table's own
        // pruning.
        if let Some((s, _)) = &pruner {
            assessors[*s].charge_cycles();
        }
        StreetTree {
            cohort: Cohort::new(vec![m.clone()], seed),
            assessors,
            pruner,
            last_age: None,
            seen: Vec::new(),
        }
    }

    /// The species.
    pub fn species(&self) -> &Measured {
        &self.cohort.species[0]
    }

    /// Whether a pruning regime cuts the tree.
    pub fn pruned(&self) -> bool {
        self.pruner.is_some()
    }

    /// The account keeper of site `i` (what it could not compute, the reference it reads).
    pub fn assessor(&self, i: usize) -> &Assessor {
        &self.assessors[i]
    }

    /// Every age recorded so far.
    pub fn history(&self) -> &[AgeRecord] {
        &self.cohort.history[0]
    }

    /// Live segments of the growing tree.
    pub fn segment_count(&self) -> usize {
        self.cohort.growers[0].segment_count()
    }

    /// Grows the tree on to `age`, carrying out every pruning cycle that falls due on the way
    /// (each shown to `each` with the tree before the cuts and the grower after them, for
    /// pictures), and accounts the year on every site.
    pub fn grow_to(
        &mut self,
        age: f64,
        spread: Spread,
        each: impl FnMut(f64, &PruningYear, Skeleton, &Grower),
    ) -> StudyYear {
        let span = match spread {
            Spread::Whole => 1.0,
            Spread::PerYear => self.last_age.map_or(age, |a| age - a),
        };
        self.last_age = Some(age);
        let cycle = (self.pruner.as_mut())
            .and_then(|(_, p)| p.advance(&mut self.cohort.growers[0], age, each));
        let lines = (self.pruner.as_mut()).map_or(Vec::new(), |(_, p)| p.take_lines());
        let skeleton =
            (self.cohort.advance_to(age).pop()).expect("a cohort of one tree gives one skeleton");
        let record = *(self.cohort.history[0].last()).expect("advance_to records the age");
        // A tree the street cuts is accounted at the DBH the equations give, which the growth
        // holds its pipe model to: a cut takes wood above the trunk but none of its girth,
        // while the survey's reading, on a trunk cut back over laterals that leave it below
        // breast height, or a tree cut below it, would fall.
        let mut dims = record.model;
        if self.pruner.is_some() {
            dims.dbh = record.measured.dbh;
        }
        let mut accounts: Vec<YearAccount> = if self.assessors.len() > 1 {
            // The tree's leaves and crown are the same on every site: made once.
            let leaves = leaves_of(&skeleton);
            let crown = Crown::with_leaves(&skeleton, &leaves).with_wood(&skeleton);
            (self.assessors.iter_mut())
                .map(|a| a.year_on(age, &dims, &skeleton, (&leaves, &crown)))
                .collect()
        } else {
            (self.assessors.iter_mut())
                .map(|a| a.year(age, &dims, &skeleton))
                .collect()
        };
        if let Some((s, _)) = &self.pruner {
            accounts[*s].record_pruning(cycle, span);
            accounts[*s].lines = lines;
        }
        let new_conflicts: Vec<Conflict> = (accounts.first())
            .map_or(&[][..], |a| &a.conflicts)
            .iter()
            .filter(|c| !self.seen.contains(&c.kind))
            .copied()
            .collect();
        self.seen.extend(new_conflicts.iter().map(|c| c.kind));
        StudyYear {
            age,
            record,
            accounts,
            new_conflicts,
            skeleton,
        }
    }
}
