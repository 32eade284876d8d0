//! A site's pruning regime carried out on the grown tree, year by year (issue U): in each year
//! a cycle falls due, the zones it keeps clear are cut free at branch unions
//! ([`Grower::cut`]), a young tree is trained ([`Grower::train`]), and the year's record says
//! what was cut, what it cost, and which conflicts it resolved.
//!
//! Cost of a crew's visit: sized by the tree, at its DBH class's price in the run's cost table
//! (`--costs`, or the built-in `data/street/costs.toml`, whose visit price rises with DBH);
//! where the run's costs are a programme's average, the built-in table prices the visits and
//! the average drops its pruning share. A year's line clearance (the utility's crew, which
//! the utility pays: [`PruningYear::line_cost`]) and the city's raising, building clearance
//! and training (its own crew) are a visit each, charged when the crew finds something to cut.

use crate::Skeleton;
use crate::growth::{CutKind, CutMark, Cuts, Grower, LONGEST_REGROWTH};
use crate::street::accounts::costs::Costs;
use crate::street::energy::crown::leaves_of;
use crate::street::site::{Access, Site, Wire};
use crate::street::work::conflicts::{Conflict, Kind, Zones, conflicts_with};
use crate::street::work::lines::{LineCheck, away, check, distance};
use crate::street::work::pruning::{Regime, due};
use glam::Vec3;

/// Most of a tree's height that crown raising may clear of branches: the street's clear heights
/// are reached over the years, as the tree grows, never by stripping a young tree's crown.
/// ANSI A300 (1995, 5.3.1) asks that half the foliage remain in the lower two-thirds of the
/// crown after pruning; municipal specifications written to it keep a live crown ratio of at
/// least 60%, no more than the lower 40% of the tree clear of branches (A Plus Tree, "Pruning
/// definitions", tree maintenance specifications). Without it a 5-year black pine lost 90% of
/// its leaves to one raising.
pub const RAISED_SHARE: f64 = 0.4;

/// Most of the foliage the city's routine pruning (crown raising, building clearance,
/// training) takes at one visit: ANSI A300-1995, 5.3.1, "not more than one-fourth of the
/// foliage" of a mature tree in a growing season (read in a transcription of the standard;
/// later editions leave the dose to the specification). Line clearance is the utility's and
/// takes what the clearance needs, however much that is; what the dose leaves in a zone is
/// cut at the next visits ([`Cuts::deferred`]).
pub const ROUTINE_DOSE: f64 = 0.25;

/// Why the street cut a tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Reason {
    /// Line clearance, by the utility.
    Line,
    /// Crown raising over the roadway, the sidewalk and a sight triangle.
    Raise,
    /// Clearance from the façade, awnings, signs and street lights.
    Building,
    /// Structural pruning of a young tree.
    Structural,
}

impl Reason {
    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Reason::Line => "line clearance",
            Reason::Raise => "crown raising",
            Reason::Building => "building clearance",
            Reason::Structural => "structural",
        }
    }

    /// The reason that clears a kind of conflict; none for the trunk at the curb, which no
    /// pruning moves.
    pub fn of(kind: Kind) -> Option<Reason> {
        match kind {
            Kind::Wire | Kind::WireMinimum => Some(Reason::Line),
            Kind::Roadway | Kind::Sidewalk | Kind::SightTriangle => Some(Reason::Raise),
            Kind::Facade | Kind::Awning | Kind::Sign | Kind::Light => Some(Reason::Building),
            Kind::TrunkFlare => None,
        }
    }
}

/// One year's pruning of a tree.
#[derive(Clone, Debug, PartialEq)]
pub struct PruningYear {
    /// The cycles due this year (line clearance also where the utility's patrol called its
    /// crew out between cycles to a hot spot).
    pub reasons: Vec<Reason>,
    /// What the cuts took.
    pub cuts: Cuts,
    /// Crews' visits that cut something (the utility's, the city's).
    pub visits: u32,
    /// Of those, the utility's visits between its cycles: hot spots its yearly patrol saw
    /// growing into a line's clearance at cutting before the next patrol.
    pub hot_spots: u32,
    /// Their cost, $: the utility's line clearance and the city's crews together.
    pub cost: f64,
    /// The part of `cost` the utility pays: its line clearance, which no city budget carries
    /// (utilities clear their own lines and treat it as their own function: USDA Forest
    /// Service, Northeastern Area, Urban & Community Forestry technical guide, "Utility
    /// arboriculture").
    pub line_cost: f64,
    /// Conflicts of the kinds cleared this year that were there before the cuts.
    pub before: Vec<Kind>,
    /// Of those and any other, the kinds the tree still has after the cuts though a cycle
    /// was due for them, or that no pruning clears (the trunk at the curb).
    pub unresolved: Vec<Kind>,
}

impl PruningYear {
    /// The kinds the cuts cleared.
    pub fn resolved(&self) -> Vec<Kind> {
        (self.before.iter())
            .filter(|k| !self.unresolved.contains(k))
            .copied()
            .collect()
    }

    /// Wood removed, m³.
    pub fn wood_m3(&self) -> f64 {
        self.cuts.wood_volume
    }

    /// Leaf area removed, m².
    pub fn leaf_m2(&self) -> f64 {
        self.cuts.leaf_area
    }

    /// Every cut's place, for pictures.
    pub fn marks(&self) -> &[CutMark] {
        &self.cuts.marks
    }

    /// The cuts of a kind.
    pub fn count(&self, kind: CutKind) -> usize {
        self.cuts.count(kind)
    }

    /// Two years' pruning as one: a run that records every few years reports the cycles
    /// since its last record together.
    pub fn merged(mut earlier: PruningYear, later: PruningYear) -> PruningYear {
        for r in later.reasons {
            if !earlier.reasons.contains(&r) {
                earlier.reasons.push(r);
            }
        }
        earlier.reasons.sort();
        for k in later.before {
            if !earlier.before.contains(&k) {
                earlier.before.push(k);
            }
        }
        earlier.before.sort();
        earlier.cuts.merge(later.cuts);
        earlier.visits += later.visits;
        earlier.hot_spots += later.hot_spots;
        earlier.cost += later.cost;
        earlier.line_cost += later.line_cost;
        earlier.unresolved = later.unresolved;
        earlier
    }

    /// Notes what the tree's conflicts are after the cuts.
    pub fn settle(&mut self, after: &[Conflict]) {
        self.unresolved = after
            .iter()
            .map(|c| c.kind)
            .filter(|&k| Reason::of(k).is_none_or(|r| self.reasons.contains(&r)))
            .collect();
    }
}

/// One overhead line in one whole year of a tree grown under a pruning regime: how close the
/// tree came before that year's cuts, and the utility's visit, if it made one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineYear {
    /// The age, years.
    pub age: f64,
    /// Which of the site's wires.
    pub wire: usize,
    /// The tree as it stood before the year's cuts.
    pub check: LineCheck,
    /// Whether leaf or wood was inside the line's minimum clearance then.
    pub breach: bool,
    /// The utility's visit.
    pub visit: Option<LineVisit>,
}

/// A visit of the utility's crew to a tree under one of its lines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineVisit {
    /// On the line's cycle, or called out between cycles by the patrol to a hot spot.
    pub scheduled: bool,
    /// The regrowth the crew allows for before its next visit, m: the species' growth in
    /// height over the cycle, the cut held to [`MOST_CUT`].
    pub allowance_m: f64,
    /// The radius cut to: the line's clearance at cutting and the allowance, m.
    pub cut_to_m: f64,
    /// The nearest wood or leaf to the line after the cuts, m.
    pub closest_after_m: f64,
}

/// The largest radius a utility's crew cuts to around a distribution line, m: 15 ft, the
/// clearance United Electric Cooperative specifies for fast-growing species ("a minimum 10-foot
/// clearance ... Fast growth tree species will require a minimum of 15-foot clearance"; its
/// specification for primary distribution lines), within PG&E's 12 to 20 ft (tree maintenance
/// FAQ) and the 10 ft below a line Eversource cuts to. A tree that grows back faster is met by
/// the yearly patrol between cycles: a tree that "does not make the normal trim cycle", which
/// utilities remove from under their lines (Peninsula Light Co., tree trimming FAQ).
pub const MOST_CUT: f64 = 15.0 * 0.3048;

/// What the utility's patrols know of the tree under one line.
#[derive(Clone, Copy, Debug, Default)]
struct LineCrew {
    /// How near the tree stood to the line after last year's patrol and its cuts, m.
    seen: Option<f64>,
    /// The most it has come nearer the line from one year's patrol to the next, m (crews keep
    /// the worst they have seen of a tree).
    yearly: f64,
    /// Whether the crew has cut it for the line.
    cut: bool,
}

/// A site's regime, ready to cut trees by.
pub struct Pruner {
    site: Site,
    regime: Regime,
    /// Price of a visit by DBH, and where it comes from.
    costs: Option<Costs>,
    /// The utility's record of the tree under each of the site's wires.
    crews: Vec<LineCrew>,
    /// Each whole year's line checks not yet taken ([`Pruner::take_lines`]).
    lines: Vec<LineYear>,
}

impl Pruner {
    /// The pruner of a site, none where its regime cuts nothing. `costs` price the visits
    /// where they are itemised.
    pub fn new(site: &Site, costs: Option<&Costs>) -> Option<Pruner> {
        let regime = Regime::of(site);
        regime.prunes().then(|| Pruner {
            site: site.clone(),
            crews: vec![LineCrew::default(); site.wire.len()],
            regime,
            costs: costs.cloned(),
            lines: Vec::new(),
        })
    }

    /// The regime it follows.
    pub fn regime(&self) -> &Regime {
        &self.regime
    }

    /// Price of one of the city's crews' visits to a tree of `dbh_cm`, $: the run's itemised
    /// costs' price, else the built-in sized table's.
    pub fn visit_price(&self, dbh_cm: f64) -> f64 {
        (self.costs.as_ref())
            .and_then(|c| c.pruning_visit(dbh_cm))
            .or_else(|| Costs::sized().pruning_visit(dbh_cm))
            .map_or(0.0, |(price, _cycle)| price)
    }

    /// The utility's price of one line-clearance visit to a tree of `dbh_cm` reached by
    /// `access`, $ (`Costs::line_visit`).
    pub fn line_price(&self, dbh_cm: f64, access: Access) -> f64 {
        (self.costs.as_ref())
            .unwrap_or_else(|| Costs::sized())
            .line_visit(dbh_cm, access)
    }

    /// The lines' checks of every whole year grown since they were last taken, in order.
    pub fn take_lines(&mut self) -> Vec<LineYear> {
        std::mem::take(&mut self.lines)
    }

    /// Grows `grower` on to `age` a year at a time, carrying out every cycle that falls due
    /// on the way, and returns them as one ([`PruningYear::merged`]; none if none fell due).
    /// `each` is shown each year's pruning, the tree as it stood before the cuts, and the
    /// grower after them.
    pub fn advance(
        &mut self,
        grower: &mut Grower,
        age: f64,
        mut each: impl FnMut(f64, &PruningYear, Skeleton, &Grower),
    ) -> Option<PruningYear> {
        let mut merged: Option<PruningYear> = None;
        let mut year = (grower.age() + 1e-6).floor() + 1.0;
        while year <= age + 1e-9 {
            grower.advance_to(year);
            if let Some((cycle, before)) = self.year(grower, year) {
                each(year, &cycle, before, grower);
                merged = Some(match merged {
                    Some(earlier) => PruningYear::merged(earlier, cycle),
                    None => cycle,
                });
            }
            year += 1.0;
        }
        grower.advance_to(age);
        merged
    }

    /// The cycles due at `age` (a whole number of years since planting), carried out on the
    /// tree `grower` holds at that age, with the tree as it stood before the cuts; none where
    /// no cycle is due and no line's minimum clearance is breached. The crews look at the
    /// tree's conflicts before they cut; the lines' checks are kept for
    /// [`Pruner::take_lines`].
    pub fn year(&mut self, grower: &mut Grower, age: f64) -> Option<(PruningYear, Skeleton)> {
        let year = age.round();
        if (age - year).abs() > 1e-6 || year < 1.0 {
            return None;
        }
        let year = year as u32;
        let cycle_due = |c: Option<u32>| c.is_some_and(|c| due(c, year));
        let scheduled: Vec<bool> = self.regime.lines.iter().map(|&c| cycle_due(c)).collect();
        let dbh = grower.targets(age).dbh;
        let mut reasons = Vec::new();
        if cycle_due(self.regime.raise) {
            reasons.push(Reason::Raise);
        }
        if cycle_due(self.regime.building) {
            reasons.push(Reason::Building);
        }
        if let Some((cycle, until)) = self.regime.structural
            && due(cycle, year)
            && dbh < until
        {
            reasons.push(Reason::Structural);
        }
        if reasons.is_empty() && self.site.wire.is_empty() {
            return None;
        }
        let standing = grower.skeleton();
        let leaves = leaves_of(&standing);
        // Every line is checked every year, as the utility's patrol does.
        let checks: Vec<LineCheck> = (self.site.wire.iter())
            .map(|w| check(&standing, &leaves, w))
            .collect();
        // What the patrol sees: how much nearer the tree has come since last year.
        for (crew, c) in self.crews.iter_mut().zip(&checks) {
            if let Some(was) = crew.seen {
                crew.yearly = crew.yearly.max(was - c.closest_m);
            }
            crew.seen = Some(c.closest_m);
        }
        // The utility patrols its lines every year and trims a tree between cycles where it
        // would grow into the line's clearance at cutting before the next patrol, at the rate
        // it grows back: a hot spot. The clearance at cutting, not the minimum, is what the
        // patrol keeps, so a year's regrowth faster than any seen still leaves the minimum.
        let patrol = |i: usize| {
            let w = &self.site.wire[i];
            checks[i].closest_m < w.clearance + self.margin(grower, year, i)
        };
        let visited: Vec<usize> = (0..self.site.wire.len())
            .filter(|&i| scheduled[i] || (self.regime.lines[i].is_some() && patrol(i)))
            .collect();
        if !visited.is_empty() {
            reasons.insert(0, Reason::Line);
        }
        let hot_spot = visited.iter().any(|&i| !scheduled[i]);
        let mut lines: Vec<LineYear> = (checks.iter().enumerate())
            .map(|(i, c)| LineYear {
                age,
                wire: i,
                check: *c,
                breach: c.breaches(&self.site.wire[i]),
                visit: None,
            })
            .collect();
        if reasons.is_empty() {
            self.lines.extend(lines);
            return None;
        }
        let before: Vec<Kind> = conflicts_with(&standing, &leaves, &self.site)
            .iter()
            .map(|c| c.kind)
            .filter(|&k| Reason::of(k).is_some_and(|r| reasons.contains(&r)))
            .collect();
        // The utility's crew cuts each line it visits to its clearance at cutting and the
        // regrowth the tree will make before the next visit, by directional cuts to laterals
        // growing away from the line, whatever that takes.
        let allowances: Vec<(usize, f64)> = (visited.iter())
            .map(|&i| (i, self.allowance(grower, year, i)))
            .collect();
        let tubes: Vec<(&Wire, f64)> = (allowances.iter())
            .map(|&(i, a)| (&self.site.wire[i], self.site.wire[i].clearance + a))
            .collect();
        let in_tube = |p: Vec3, _order: u8| tubes.iter().any(|&(w, r)| distance(p, w) < r);
        let away_from = |p: Vec3| {
            (tubes.iter())
                .min_by(|a, b| distance(p, a.0).total_cmp(&distance(p, b.0)))
                .map_or(-Vec3::Z, |&(w, _)| away(p, w))
        };
        let mut cuts = if tubes.is_empty() {
            Default::default()
        } else {
            grower.cut_directional(&in_tube, &away_from)
        };
        let line = !cuts.marks.is_empty();
        if line {
            let after = grower.skeleton();
            let after_leaves = leaves_of(&after);
            for &(i, allowance) in &allowances {
                let w = &self.site.wire[i];
                let closest = check(&after, &after_leaves, w).closest_m;
                lines[i].visit = Some(LineVisit {
                    scheduled: scheduled[i],
                    allowance_m: allowance,
                    cut_to_m: w.clearance + allowance,
                    closest_after_m: closest,
                });
                let crew = &mut self.crews[i];
                crew.seen = Some(closest);
                crew.cut = true;
            }
        }
        self.lines.extend(lines);
        // The city's crew then raises the crown, clears the building and trains the young
        // tree, taking no more than a quarter of the foliage it finds: the zones of its
        // cycles due this year, with the clear heights no higher than a young tree's live
        // crown allows.
        let mut site = self.site.clone();
        site.wire.clear();
        let top = (standing.sections.iter().map(|c| c.position.z))
            .chain(standing.leaves.iter().map(|l| l.position.z))
            .fold(0.0f32, f32::max) as f64;
        let street = &mut site.street;
        street.roadway_clearance = street.roadway_clearance.min(RAISED_SHARE * top);
        street.sidewalk_clearance = street.sidewalk_clearance.min(RAISED_SHARE * top);
        let city_zones = Zones::new(&site)
            .only(|k| Reason::of(k).is_some_and(|r| r != Reason::Line && reasons.contains(&r)));
        let most = ROUTINE_DOSE * grower.leaf_carried() as f64;
        let city_cuts = grower.cut_within(
            &|p, order| city_zones.kind_of(p, Some(order)).is_some(),
            most,
        );
        let city = before.iter().any(|&k| Reason::of(k) != Some(Reason::Line))
            && !city_cuts.marks.is_empty();
        let left = most - city_cuts.leaf_area;
        cuts.merge(city_cuts);
        let mut trained = false;
        if reasons.contains(&Reason::Structural) {
            let t = grower.train_within(left.max(0.0));
            trained = !t.marks.is_empty();
            cuts.merge(t);
        }
        let access = if (visited.iter()).any(|&i| self.site.wire[i].access == Access::Backyard) {
            Access::Backyard
        } else {
            Access::Street
        };
        let line_cost = if line {
            self.line_price(dbh, access)
        } else {
            0.0
        };
        let city_cost = if city || trained {
            self.visit_price(dbh)
        } else {
            0.0
        };
        let year = PruningYear {
            reasons,
            cuts,
            visits: u32::from(line) + u32::from(city || trained),
            hot_spots: u32::from(line && hot_spot),
            cost: line_cost + city_cost,
            line_cost,
            before,
            unresolved: Vec::new(),
        };
        Some((year, standing))
    }

    /// The regrowth the utility's crew allows for beyond wire `i`'s clearance at a visit in
    /// `year`, m: the species' measured growth in height over the line's cycle (the Urban
    /// Tree Database's equations, `Grower::targets`), as utilities allow for a species' growth
    /// rate ("so the minimum holds until the next cycle", United Electric Cooperative's
    /// specification; 10-12 ft for fast growers, 5-7 ft for slow ones, the City of Lodi's
    /// electric utility); and at least the fastest the crew has seen this tree grow back
    /// toward the line in a year, since it is back at the next yearly patrol if not before.
    /// The cut is held to [`MOST_CUT`], 15 ft.
    fn allowance(&self, grower: &Grower, year: u32, i: usize) -> f64 {
        let cycle = self.regime.lines[i].unwrap_or(1) as f64;
        let age = year as f64;
        let height = |t: f64| grower.targets(t).height;
        let growth = (height(age + cycle) - height(age)).max(0.0);
        let most = (MOST_CUT - self.site.wire[i].clearance).max(0.0);
        let years = self.regime.lines[i].map_or(1, |c| c - year % c.max(1)) as f64;
        growth.max(self.margin(grower, year, i) * years).min(most)
    }

    /// How far the tree under wire `i` may grow toward it in a year, m, as the crew judges it
    /// at `year`'s patrol: the species' measured growth in height this year, or the fastest
    /// the tree has grown back toward the line since the crew first cut it, where that was
    /// more (a cut tree's sprouts grow up to `growth::LONGEST_REGROWTH` a year, Follett et al.
    /// 2016, faster than the species' height).
    fn margin(&self, grower: &Grower, year: u32, i: usize) -> f64 {
        let crew = &self.crews[i];
        let age = year as f64;
        let growth = (grower.targets(age + 1.0).height - grower.targets(age).height).max(0.0);
        let sprouts = if crew.cut {
            LONGEST_REGROWTH as f64
        } else {
            0.0
        };
        growth.max(crew.yearly).max(sprouts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::street::accounts::costs::YearCosts;
    use crate::street::accounts::items::Cost;
    use crate::street::rank::{Pruning, Study, run};
    use crate::street::work::conflicts::conflicts;

    use crate::street::site::narrow_for_tests as narrow;

    #[test]
    fn a_line_clearance_cycle_clears_the_wire_for_its_regrowth_and_is_the_utilitys() {
        let site = narrow();
        let wire = &site.wire[0];
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, crate::growth::GrowthOptions::default());
        grower.advance_to(12.0);
        let mut pruner = Pruner::new(&site, None).expect("the default standard prunes");
        // Year 12 falls on the 4-year line cycle: an uncut 12-year plane is well into the
        // line's clearance.
        let (mut year, standing) = pruner.year(&mut grower, 12.0).expect("a cycle is due");
        assert!(
            conflicts(&standing, &site)
                .iter()
                .any(|c| c.kind == Kind::Wire)
        );
        assert_eq!(year.reasons, vec![Reason::Line]);
        assert!(year.before.contains(&Kind::Wire), "{:?}", year.before);
        let lines = pruner.take_lines();
        assert_eq!(lines.len(), 1);
        let visit = lines[0].visit.expect("the utility's crew cut");
        assert!(visit.scheduled && year.hot_spots == 0);
        // It cut for the regrowth before its next visit: the species' growth in height over
        // the cycle at least, beyond GO 95's 4 ft, and no more than PG&E's 20 ft.
        let growth = grower.targets(16.0).height - grower.targets(12.0).height;
        assert!(
            visit.allowance_m >= growth - 1e-9,
            "{visit:?} against {growth} m"
        );
        assert!((visit.cut_to_m - wire.clearance - visit.allowance_m).abs() < 1e-9);
        assert!(visit.cut_to_m <= MOST_CUT + 1e-9);
        assert!(visit.closest_after_m > wire.clearance, "{visit:?}");
        let after = conflicts(&grower.skeleton(), &site);
        year.settle(&after);
        assert!(
            !(after.iter()).any(|c| matches!(c.kind, Kind::Wire | Kind::WireMinimum)),
            "{after:?}"
        );
        assert!(year.resolved().contains(&Kind::Wire));
        assert!(year.count(CutKind::Removal) + year.count(CutKind::Reduction) > 0);
        assert!(year.leaf_m2() > 0.0 && year.wood_m3() > 0.0);
        assert_eq!(year.visits, 1);
        // One visit, priced as the utility pays for a tree worked from the street, not by
        // the city's rate, and the utility's to pay.
        let dbh = grower.targets(12.0).dbh;
        assert!((year.cost - pruner.line_price(dbh, Access::Street)).abs() < 1e-9);
        assert!((year.cost - 55.42).abs() < 1e-9, "{}", year.cost);
        assert_eq!(year.line_cost, year.cost);
        assert!(pruner.line_price(dbh, Access::Backyard) > year.cost);
    }

    #[test]
    fn the_narrow_site_plane_never_enters_the_lines_minimum_clearance() {
        let site = narrow();
        let m = Database::builtin().find("InlVal", "PLAC").unwrap();
        let study = Study {
            site: Some(site.clone()),
            ..Study::new(30.0)
        };
        let ran = run(&m, &study);
        let lines: Vec<&LineYear> = ran.accounts.iter().flat_map(|a| &a.lines).collect();
        assert_eq!(lines.len(), 30, "a check every year");
        for l in &lines {
            assert!(!l.breach, "age {}: {:?}", l.age, l.check);
            assert!(l.check.closest_m >= site.wire[0].minimum);
        }
        // The crews visit on the cycle, and between cycles where the regrowth would reach the
        // minimum before the next patrol.
        let visits: Vec<f64> = (lines.iter())
            .filter(|l| l.visit.is_some())
            .map(|l| l.age)
            .collect();
        assert!(
            visits.contains(&8.0) && visits.contains(&12.0),
            "{visits:?}"
        );
    }

    #[test]
    fn a_run_prunes_by_the_regime_unless_told_not_to() {
        let site = narrow();
        let m = Database::builtin().find("InlVal", "PLAC").unwrap();
        let study = |pruning| Study {
            site: Some(site.clone()),
            pruning,
            ..Study::new(9.0)
        };
        let pruned = run(&m, &study(Pruning::Regime));
        let grown = run(&m, &study(Pruning::Off));
        assert!(grown.accounts.iter().all(|a| a.pruning.is_none()));
        let total = pruned.pruning().expect("pruned");
        assert!(total.cycles >= 2 && total.cost > 0.0, "{total:?}");
        // The cycles' cost is in the accounts, in place of the table's own pruning (no cut is
        // paid for twice); the leaf area taken shows in the crown.
        let per_tree = |r: &crate::street::rank::Ranked, f: &dyn Fn(&YearCosts) -> f64| -> f64 {
            r.accounts
                .iter()
                .map(|a| a.costs.map_or(0.0, |c| f(&c)))
                .sum()
        };
        assert_eq!(per_tree(&pruned, &|c| c[Cost::Pruning]), 0.0);
        assert!(per_tree(&grown, &|c| c[Cost::Pruning]) > 0.0);
        let cycles = per_tree(&pruned, &|c| c[Cost::Cycles] + c[Cost::LineClearance]);
        assert!(
            (cycles - total.cost).abs() < 1e-6,
            "{cycles} {}",
            total.cost
        );
        let leaf = |r: &crate::street::rank::Ranked| r.accounts.last().unwrap().surfaces.0;
        assert!(
            leaf(&pruned) < leaf(&grown),
            "{} {}",
            leaf(&pruned),
            leaf(&grown)
        );
        // Compared, the benefits lost are the uncut tree's less the cut one's, year by year.
        use crate::street::Basis;
        let compared = run(&m, &study(Pruning::Compare));
        let lost = compared.benefits_lost.clone().expect("compared");
        assert_eq!(lost.len(), compared.accounts.len());
        let sum: f64 = lost.iter().sum();
        let gap = grown.benefits(Basis::Site) - pruned.benefits(Basis::Site);
        assert!((sum - gap).abs() < 1e-6 && sum > 0.0, "{sum} {gap}");
        assert_eq!(compared.pruning().unwrap().benefits_lost, Some(sum));
        assert!(pruned.benefits_lost.is_none());
    }

    #[test]
    fn raising_a_young_tree_keeps_its_live_crown() {
        // The narrow site's street, its line left out: this visit is the city's alone.
        let mut site = narrow();
        site.wire.clear();
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, crate::growth::GrowthOptions::default());
        grower.advance_to(5.0);
        let mut pruner = Pruner::new(&site, None).unwrap();
        let carried = grower.leaf_carried() as f64;
        let (year, standing) = pruner.year(&mut grower, 5.0).expect("raising falls at 5");
        assert!(year.reasons.contains(&Reason::Raise));
        // The city's visit takes at most a quarter of the foliage (there is no line
        // clearance this year), and leaves what it could not take for a later visit.
        assert!(!year.reasons.contains(&Reason::Line));
        assert!(
            year.leaf_m2() <= ROUTINE_DOSE * carried + 1e-6 && year.leaf_m2() > 0.0,
            "{} of {carried} m²",
            year.leaf_m2()
        );
        let top = standing
            .sections
            .iter()
            .map(|c| c.position.z)
            .fold(0.0, f32::max);
        let clear = (RAISED_SHARE as f32 * top).min(site.street.roadway_clearance as f32);
        assert!(
            clear < site.street.roadway_clearance as f32,
            "a young tree: {top} m"
        );
        // Nothing over the roadway below the raised height once the deferred cuts are made
        // at the next visits, but wood is left above it that the street's full clearance
        // would take.
        let mut visits = 0;
        let mut year = year;
        while year.cuts.deferred > 0 && visits < 6 {
            grower.advance_to(6.0 + visits as f64);
            let before = grower.leaf_carried() as f64;
            let site = pruner.site.clone();
            let zones = Zones::new(&site).only(|k| Reason::of(k) == Some(Reason::Raise));
            let cuts = grower.cut_within(
                &|p, order| zones.kind_of(p, Some(order)).is_some() && p.z < clear,
                ROUTINE_DOSE * before,
            );
            assert!(cuts.leaf_area <= ROUTINE_DOSE * before + 1e-6);
            year.cuts = cuts;
            visits += 1;
        }
        assert_eq!(year.cuts.deferred, 0, "cleared over {visits} more visits");
        let after = grower.skeleton();
        let over_road = |z: std::ops::Range<f32>| {
            after.frame_stems().iter().filter(|s| s.level > 0).any(|s| {
                after.sections[s.sections.start as usize..s.sections.end as usize]
                    .iter()
                    .any(|c| {
                        c.position.y < site.street.curb as f32 - 0.05 && z.contains(&c.position.z)
                    })
            })
        };
        assert!(!over_road(0.0..clear - 0.05));
        assert!(over_road(
            clear + 0.05..site.street.roadway_clearance as f32
        ));
    }
}
