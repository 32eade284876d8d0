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
use crate::growth::{CutKind, CutMark, Cuts, Grower};
use crate::street::accounts::costs::Costs;
use crate::street::site::Site;
use crate::street::work::conflicts::{Conflict, Kind, Zones, conflicts};
use crate::street::work::pruning::{Regime, due};

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
            Kind::Wire => Some(Reason::Line),
            Kind::Roadway | Kind::Sidewalk | Kind::SightTriangle => Some(Reason::Raise),
            Kind::Facade | Kind::Awning | Kind::Sign | Kind::Light => Some(Reason::Building),
            Kind::TrunkFlare => None,
        }
    }
}

/// One year's pruning of a tree.
#[derive(Clone, Debug, PartialEq)]
pub struct PruningYear {
    /// The cycles due this year.
    pub reasons: Vec<Reason>,
    /// What the cuts took.
    pub cuts: Cuts,
    /// Crews' visits that cut something (the utility's, the city's).
    pub visits: u32,
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

/// A site's regime, ready to cut trees by.
pub struct Pruner {
    site: Site,
    regime: Regime,
    /// Price of a visit by DBH, and where it comes from.
    costs: Option<Costs>,
}

impl Pruner {
    /// The pruner of a site, none where its regime cuts nothing. `costs` price the visits
    /// where they are itemised.
    pub fn new(site: &Site, costs: Option<&Costs>) -> Option<Pruner> {
        let regime = Regime::of(site);
        regime.prunes().then(|| Pruner {
            site: site.clone(),
            regime,
            costs: costs.cloned(),
        })
    }

    /// The regime it follows.
    pub fn regime(&self) -> &Regime {
        &self.regime
    }

    /// Price of one crew's visit to a tree of `dbh_cm`, $: the run's itemised costs' price,
    /// else the built-in sized table's.
    pub fn visit_price(&self, dbh_cm: f64) -> f64 {
        (self.costs.as_ref())
            .and_then(|c| c.pruning_visit(dbh_cm))
            .or_else(|| Costs::sized().pruning_visit(dbh_cm))
            .map_or(0.0, |(price, _cycle)| price)
    }

    /// Grows `grower` on to `age` a year at a time, carrying out every cycle that falls due
    /// on the way, and returns them as one ([`PruningYear::merged`]; none if none fell due).
    /// `each` is shown each year's pruning, the tree as it stood before the cuts, and the
    /// grower after them.
    pub fn advance(
        &self,
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
    /// no cycle is due. The crews look at the tree's conflicts before they cut.
    pub fn year(&self, grower: &mut Grower, age: f64) -> Option<(PruningYear, Skeleton)> {
        let year = age.round();
        if (age - year).abs() > 1e-6 || year < 1.0 {
            return None;
        }
        let year = year as u32;
        let cycle_due = |c: Option<u32>| c.is_some_and(|c| due(c, year));
        let wires: Vec<bool> = self.regime.lines.iter().map(|&c| cycle_due(c)).collect();
        let dbh = grower.targets(age).dbh;
        let mut reasons = Vec::new();
        if wires.iter().any(|&w| w) {
            reasons.push(Reason::Line);
        }
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
        if reasons.is_empty() {
            return None;
        }
        let standing = grower.skeleton();
        let before: Vec<Kind> = conflicts(&standing, &self.site)
            .iter()
            .map(|c| c.kind)
            .filter(|&k| Reason::of(k).is_some_and(|r| reasons.contains(&r)))
            .collect();
        // The zones this year's cycles clear: only the wires whose cycle is due, and the clear
        // heights no higher than a young tree's live crown allows.
        let mut site = self.site.clone();
        let mut wire = wires.iter();
        site.wire.retain(|_| *wire.next().unwrap_or(&false));
        let top = (standing.sections.iter().map(|c| c.position.z))
            .chain(standing.leaves.iter().map(|l| l.position.z))
            .fold(0.0f32, f32::max) as f64;
        let street = &mut site.street;
        street.roadway_clearance = street.roadway_clearance.min(RAISED_SHARE * top);
        street.sidewalk_clearance = street.sidewalk_clearance.min(RAISED_SHARE * top);
        // The utility's crew clears its lines of whatever the clearance needs; the city's
        // crew then raises the crown, clears the building and trains the young tree, taking
        // no more than a quarter of the foliage it finds.
        let due = |line: bool| {
            Zones::new(&site).only(|k| {
                Reason::of(k).is_some_and(|r| reasons.contains(&r) && (r == Reason::Line) == line)
            })
        };
        let line_zones = due(true);
        let mut cuts = grower.cut(&|p, order| line_zones.kind_of(p, Some(order)).is_some());
        let line =
            before.iter().any(|&k| Reason::of(k) == Some(Reason::Line)) && !cuts.marks.is_empty();
        let city_zones = due(false);
        let most = ROUTINE_DOSE * grower.leaf_carried() as f64;
        let city_cuts = grower.cut_within(
            &|p, order| city_zones.kind_of(p, Some(order)).is_some(),
            most,
        );
        let city = before.iter().any(|&k| Reason::of(k) != Some(Reason::Line))
            && !city_cuts.marks.is_empty();
        let left = most - city_cuts.leaf_area;
        cuts.merge(city_cuts);
        let mut visits = 0;
        if line {
            visits += 1;
        }
        let mut trained = false;
        if reasons.contains(&Reason::Structural) {
            let t = grower.train_within(left.max(0.0));
            trained = !t.marks.is_empty();
            cuts.merge(t);
        }
        if city || trained {
            visits += 1;
        }
        let price = self.visit_price(dbh);
        let year = PruningYear {
            reasons,
            cuts,
            visits,
            cost: visits as f64 * price,
            line_cost: if line { price } else { 0.0 },
            before,
            unresolved: Vec::new(),
        };
        Some((year, standing))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::street::accounts::costs::YearCosts;
    use crate::street::accounts::items::Cost;
    use crate::street::rank::{Pruning, Study, run};

    fn narrow() -> Site {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../sites/narrow-under-wires.toml"
        ))
        .expect("the narrow site");
        Site::parse(&text, "narrow-under-wires.toml").expect("a good site")
    }

    #[test]
    fn a_line_clearance_cycle_clears_the_wire_and_is_charged() {
        let site = narrow();
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, crate::growth::GrowthOptions::default());
        grower.advance_to(12.0);
        let pruner = Pruner::new(&site, None).expect("the default standard prunes");
        // Year 12 falls on the 4-year line cycle; 11 on none.
        assert!(pruner.year(&mut grower, 11.0).is_none());
        let (mut year, standing) = pruner.year(&mut grower, 12.0).expect("a cycle is due");
        assert!(
            conflicts(&standing, &site)
                .iter()
                .any(|c| c.kind == Kind::Wire)
        );
        assert_eq!(year.reasons, vec![Reason::Line]);
        assert!(year.before.contains(&Kind::Wire), "{:?}", year.before);
        let after = conflicts(&grower.skeleton(), &site);
        year.settle(&after);
        assert!(!after.iter().any(|c| c.kind == Kind::Wire), "{after:?}");
        assert_eq!(year.resolved(), vec![Kind::Wire]);
        assert!(year.count(CutKind::Removal) + year.count(CutKind::Reduction) > 0);
        assert!(year.leaf_m2() > 0.0 && year.wood_m3() > 0.0);
        assert_eq!(year.visits, 1);
        // One line-clearance visit, priced by the tree's DBH, and the utility's to pay.
        let dbh = grower.targets(12.0).dbh;
        assert!((year.cost - pruner.visit_price(dbh)).abs() < 1e-9);
        assert!(
            (year.cost - 3.90 * dbh).abs() < 1e-9,
            "{} at {dbh} cm",
            year.cost
        );
        assert_eq!(year.line_cost, year.cost);
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
        let site = narrow();
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, crate::growth::GrowthOptions::default());
        grower.advance_to(5.0);
        let pruner = Pruner::new(&site, None).unwrap();
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
