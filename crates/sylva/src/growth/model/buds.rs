//! Buds and shoots at the end of a year, after Palubicki et al. (2009): every bud's exposure
//! comes from space colonisation of the coming year's crown envelope and the light grid; the
//! tree's vigour is allocated to the buds by Borchert-Honda with the habit's apical control; a
//! bud given at least one metamer's worth makes a shoot of that many metamers, steered by its
//! markers and the habit's tropism, with a lateral bud at every node. The leader is held to
//! the measured height; shaded branches die; past the segment budget the darkest make room.

use super::colonise::Markers;
use super::directions::{sag_at, sag_down, within};
use super::*;

/// Dormant lateral buds older than this die, years.
pub(super) const BUD_YEARS: f64 = 4.0;
/// Highest branch order.
pub(super) const MAX_ORDER: u8 = 4;
/// Most metamers one shoot makes in a year.
pub(super) const MAX_METAMERS: f32 = 8.0;
/// Weight of the direction toward a bud's markers in a new shoot's direction (xi).
pub(super) const ENVIRONMENT_WEIGHT: f32 = 0.3;
/// How much wider than next year's crown the markers are scattered: buds at the crown's
/// edge see the open space beyond it (where the shoots that reach out will be stopped at the
/// crown), and a young crown, filled by its own shoots, still has buds that do.
const MARKER_MARGIN: f32 = 1.3;
/// Height over which a decurrent trunk hands its lead to its laterals, m: the buds in it
/// become the tree's few codominant scaffolds.
pub(super) const FORK_ZONE: f32 = 1.0;
/// Most lateral buds of one annual shoot of a branch that may break in a year: those most
/// exposed. A shoot has a bud at every node, but a tree's side shoots come from a few of
/// them (the rest stay dormant, and die after `BUD_YEARS`), so the year's resource makes a
/// few strong laterals instead of a broom of weak ones (issue G2: fewer, stronger laterals).
/// Sylva's choice; the trunk's buds (and a multi-stem tree's stems'), its scaffolds, are not limited.
pub(super) const LATERALS_PER_SHOOT: usize = 2;
/// Longest shoot regrowth after a cut makes in a year, m: the most yearly length growth
/// measured on pruned street trees, in the first year after pruning (about 1.5 m in green ash,
/// Norway and silver maple: Follett et al. 2016, Arboric. Urban For. 42(3):133-145).
pub const LONGEST_REGROWTH: f32 = 1.5;
/// Share of the season in which a shoot elongates.
pub(super) const GROWING_SEASON: f64 = 0.5;

/// A lateral bud waiting in a leaf axil.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bud {
    pub branch: u32,
    pub segment: u32,
    /// Where on the segment, as a share of its length.
    pub at: f32,
    /// The direction a shoot from it sets out in.
    pub direction: Vec3,
    pub born: f64,
    /// Released by a cut (`sprouts.rs`): it may break whatever its shoot's other buds do.
    pub sprout: bool,
}

/// A shoot to be made this year.
pub(super) struct Plan {
    /// Terminal: the branch it continues; lateral: the bud's index in `Grower::buds`.
    pub from: usize,
    pub lateral: bool,
    pub start: Vec3,
    pub direction: Vec3,
    pub length: f32,
}

impl Grower {
    /// The apex of every live branch and every waiting bud have their say; shoots are made.
    /// At the end of a year every bud may break. In a young tree's mid-season (`sylleptic`)
    /// only this year's buds on the leader may, for half a season's growth: a vigorous leader
    /// branches the year it grows, so its crown keeps up with a crown base rising fast.
    pub(super) fn flush(&mut self, sylleptic: bool) {
        let next = self.targets((self.age + 0.25).floor() + 1.0);
        if !sylleptic {
            self.make_room();
            self.shade_deaths();
            self.grow_short_shoots(next.crown_base() as f32);
        }
        let space = self.space(&next, self.spread as f32 * MARKER_MARGIN);
        self.prune_buds(next.crown_base() as f32);
        if !sylleptic {
            self.compact();
        }
        // A branch cut back to a lateral has no apex left: the lateral grows on for it.
        let terminals: Vec<u32> = (0..self.branches.len() as u32)
            .filter(|&b| self.branches[b as usize].alive && !self.branches[b as usize].headed)
            .collect();
        let mut sites: Vec<(Vec3, Vec3)> = terminals
            .iter()
            .map(|&b| {
                let s = self.apex_segment(b as usize);
                (s.end(), s.direction)
            })
            .collect();
        sites.extend(
            self.buds
                .iter()
                .map(|b| (self.bud_position(b), b.direction)),
        );
        // Space is taken by the leafy shoots of the last years: old limbs inside the crown
        // leave room for foliage around them.
        let age = self.age;
        let wood: Vec<(Vec3, Vec3)> = self
            .segments
            .iter()
            .filter(|s| {
                self.branches[s.branch as usize].alive
                    && s.length > 1e-4
                    && age - s.born <= LEAF_SHOOT_YEARS + 1.0
            })
            .map(|s| (s.start, s.end()))
            .collect();
        // One stream per half year (a sapling's ages are negative).
        let half_year = (self.age * 2.0).round() as i64;
        let mut rng = self.key.child((1_000_000 + half_year) as u64).stream();
        let markers = Markers::scatter(&space, self.metamer_now(), &mut rng, &wood);
        let (owned, towards) = markers.perceive(&sites);
        let mut q: Vec<f32> = sites
            .iter()
            .zip(&owned)
            .map(|(&(p, _), &n)| {
                (n as f32 / markers.saturation).min(1.0) * self.light.light_at(p).sqrt()
            })
            .collect();
        self.hold_dormant(&mut q[terminals.len()..]);
        let lambda = self.apical_control();
        let v = self.allocate(&terminals, &q, lambda);
        let mut plans = Vec::new();
        let leader_holds = lambda >= 0.5;
        for (i, &b) in terminals.iter().enumerate() {
            // The trunk's apex grows only as the held leader. Once a decurrent tree forks its
            // terminal bud stops (sympodial growth), and the laterals below it take the top
            // between them: the trunk ends in a fork instead of running on through the crown.
            if sylleptic || b == 0 {
                continue;
            }
            let n = v[i].min(MAX_METAMERS);
            if n < 1.0 {
                continue;
            }
            // A multi-stem tree's stems steer as its scaffolds do (the habit's pull, not the
            // trunk's), so they keep opening into a vase.
            let order = self.branches[b as usize].order.max(1);
            let (start, d) = sites[i];
            let direction = self.steer(d, towards[i], order);
            let direction = self.zigzag(direction, b as usize);
            plans.push(Plan {
                from: b as usize,
                lateral: false,
                start,
                direction,
                length: n * self.metamer_now(),
            });
        }
        for (k, bud) in self.buds.iter().enumerate() {
            let site = terminals.len() + k;
            let n = v[site].min(MAX_METAMERS);
            let order = self.branches[bud.branch as usize].order + 1;
            // A sprout on wood of the highest order still breaks (`start_branch` ranks it as
            // a scaffold): a cut grows back from whatever wood it leaves.
            let rank = self.branches[bud.branch as usize].rank + 1;
            if n < 1.0 || (rank > MAX_ORDER && !bud.sprout) {
                continue;
            }
            if sylleptic && !self.breaks_sylleptic(bud, order, age) {
                continue;
            }
            plans.push(Plan {
                from: k,
                lateral: true,
                start: sites[site].0,
                direction: Vec3::ZERO,
                length: n * self.metamer_now(),
            });
        }
        for p in plans.iter_mut().filter(|p| p.lateral) {
            let bud = self.buds[p.from];
            let order = self.branches[bud.branch as usize].order + 1;
            p.direction = self.steer(bud.direction, towards[terminals.len() + p.from], order);
        }
        // Nothing leaves next year's envelope: a shoot stops where it would.
        // Branches whose scaffold the rising crown base passes this year are shed: they grow
        // no more.
        let floor = next.crown_base() as f32;
        plans.retain(|p| {
            let b = if p.lateral {
                self.buds[p.from].branch as usize
            } else {
                p.from
            };
            let branch = &self.branches[b];
            let anchor = if p.lateral && branch.order == 0 {
                p.start.z
            } else {
                branch.anchor
            };
            // The trunk and stems are never shed, nor are shoots from them cut at the floor
            // here (`prune_buds` has already dropped their buds below it). On a tree the
            // street has cut, limbs leaving the trunk below the crown base carry the crown
            // around the cleared zone (`sheds_below`), and grow on: held to their anchors,
            // a plane under a wire made a tenth of its twin's shoots.
            let anchored = self.regrowth.is_some() || anchor >= floor;
            branch.order == 0 || (anchored && !self.sheds_below(b, floor))
        });
        // Shoots low in the crown sag as far as the crown must reach down.
        let sag = self.fit_sag(&plans, &next);
        let (base, top) = (next.crown_base() as f32, next.height as f32);
        for p in &mut plans {
            p.direction = sag_down(p.direction, sag_at(sag, p.start.z, base, top));
        }
        // Nothing leaves next year's envelope, scaled so the crown comes out as wide as
        // measured: a shoot stops where it would leave it.
        let (scale, stretch) = self.fit_reach(&plans, &next);
        let reach = self.space(&next, scale);
        for p in &mut plans {
            p.length = within(&reach, p.start, p.direction, p.length * stretch);
            // Regrowth after a cut is vigorous, but no shoot of it grows longer in a year
            // than the longest measured on pruned street trees.
            let sprung = if p.lateral {
                let bud = &self.buds[p.from];
                bud.sprout || self.branches[bud.branch as usize].sprung
            } else {
                self.branches[p.from].sprung
            };
            if sprung {
                p.length = p.length.min(LONGEST_REGROWTH);
            }
        }
        plans.retain(|p| p.length > 0.02);
        if !sylleptic {
            self.hold_height(&mut plans, &next, leader_holds);
        }
        let mut budget = self
            .options
            .max_segments
            .saturating_sub(self.segment_count());
        let mut broken = Vec::new();
        for p in plans {
            if budget == 0 {
                break;
            }
            budget -= 1;
            if p.lateral {
                let bud = self.buds[p.from];
                broken.push(p.from);
                self.start_branch(&bud, p.direction, p.length);
            } else {
                self.extend(p.from, p.direction, p.length);
            }
        }
        broken.sort_unstable();
        let mut k = 0;
        let mut index = 0;
        self.buds.retain(|_| {
            let keep = broken.get(k) != Some(&index);
            if !keep {
                k += 1;
            }
            index += 1;
            keep
        });
    }

    /// Whether `bud` (of a shoot of `order`) breaks in the mid-season flush: only a bud of
    /// this year's shoot, and only on a young tree's leader and scaffolds (so its crown keeps up
    /// with a crown base rising fast) or on regrowth after a cut. Vigorous shoots branch in
    /// the year they grow (sylleptic branching: Barthélémy & Caraglio 2007, Annals of Botany
    /// 99:375), and a cut's sprouts are a tree's most vigorous shoots; so its regrowth is
    /// branched in its first season (pruned crowns regained their volume within a year:
    /// Lecigne et al. 2018, Urban For. Urban Green., from laser scans), not a year of whips.
    fn breaks_sylleptic(&self, bud: &Bud, order: u8, age: f64) -> bool {
        let this_year = age - bud.born <= 0.5 + 1e-6;
        let young_leader = order <= 1 && self.targets_now().crown_height < SYLLEPTIC_CROWN;
        let regrowth = bud.sprout || self.branches[bud.branch as usize].sprung;
        this_year && (young_leader || regrowth)
    }
}
