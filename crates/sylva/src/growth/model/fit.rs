//! Shedding and fitting to the measured targets: lower branches are shed as the crown base
//! (monotone) rises, and the vigour and the envelope's spread are corrected every step so
//! that the crown's measured diameter follows f_CD.

use super::buds::Plan;
use super::directions::{sag_at, sag_down, within};
use super::*;
use glam::Vec2;
use rayon::prelude::*;

/// Widest scale of the envelope the crown's fit may use.
const MAX_SCALE: f32 = 2.0;
/// Most the year's shoots may be lengthened to reach the measured crown.
const MAX_STRETCH: f32 = 3.0;
/// Scale of the envelope while the shoots are stretched.
const REACH_SCALE: f32 = 1.2;
/// Bounds of the fitted vigour (Borchert-Honda's alpha), so a fit chasing a crown it cannot
/// make stops somewhere. A sapling's few buds see little of its crown's space and need the
/// most per unit of exposure: with the bound at 12, a southern magnolia of Modesto (seed 2)
/// sat on it from its first year and its crown stayed a fifth narrower than measured at 3;
/// at 20 it keeps up. Over the database to age 8 (`sylva sweep --to 8`) 20 brought six more
/// species-regions within bounds than 12, and 30 four.
const MIN_VIGOUR: f64 = 2.0;
const MAX_VIGOUR: f64 = 20.0;
/// Years without a new shoot anywhere on it after which a low branch of a cut tree is dead
/// wood: as long as deep shade takes to kill a branch (`turnover.rs`).
const STALLED_YEARS: f64 = 3.0;

impl Grower {
    /// Sheds what the rising crown base leaves below it.
    pub(super) fn shed(&mut self) {
        let base = self.targets_now().crown_base() as f32;
        for b in 1..self.branches.len() {
            if self.branches[b].alive && self.sheds_below(b, base) {
                self.kill(b);
            }
        }
    }

    /// Whether a crown base at `base` sheds branch `b`. The stems of a multi-stem tree stay,
    /// like the trunk. Scaffolds go when the crown base passes where they leave the trunk;
    /// smaller branches as soon as any of them hangs below it. The year's shoots are planned
    /// (and the crown's reach predicted) without the branches next year's base sheds: a
    /// sagging twig of an evergreen pear's sapling that carried its crown's width was shed
    /// in mid-season, and its crown came out a fifth too narrow (issue R).
    pub(super) fn sheds_below(&self, b: usize, base: f32) -> bool {
        let branch = &self.branches[b];
        if branch.order == 0 {
            return false;
        }
        // On a tree the street has cut, a limb goes only when all of it is below the crown
        // base: the limbs the cuts left carry the crown around the cleared zone, and shedding
        // one by where it leaves the trunk, or where it dips, would take the crown above with
        // it (a plane cut under a wire lost its whole crown at 33 years that way).
        if self.regrowth.is_some() {
            return self.cut_tree_sheds(b, base - 0.02);
        }
        // A scaffold's shedding takes everything on it.
        if branch.anchor < base - 0.02 {
            return true;
        }
        let lowest = if branch.order == 1 {
            self.segments[branch.segments[0] as usize].start.z
        } else {
            branch
                .segments
                .iter()
                .map(|&s| {
                    let s = &self.segments[s as usize];
                    s.start.z.min(s.end().z)
                })
                .fold(f32::INFINITY, f32::min)
        };
        lowest < base - 0.02
    }

    /// Whether a cut tree sheds branch `b` below `z`: its own axis lies below, and so does
    /// every live branch on it, or nothing on it has grown for `STALLED_YEARS`, or nothing on
    /// it carries a leaf (this step's new shoots, not yet leafed, count as leafy). A low limb
    /// the cuts headed back carries regrowth above the crown base on its side branches and
    /// sprouts: judged by its own axis alone, a plane's limb went at 26 with 1,205 live
    /// segments on it. A branch that has stopped growing, or has no leaf to feed it, is dead
    /// wood and goes as a shaded one does (`shade_deaths`): kept, the old side branches of
    /// those limbs hung leafless below the crown, and a black pine stripped of its leaves by
    /// line clearance kept growing bare limbs for years. The branch's own axis is looked at
    /// first: it is above on nearly every call, and what grows on it then needs no walk.
    pub(super) fn cut_tree_sheds(&self, b: usize, z: f32) -> bool {
        let below = |b: usize| {
            self.branches[b].segments.iter().all(|&s| {
                let s = &self.segments[s as usize];
                s.start.z.max(s.end().z) < z
            })
        };
        if !below(b) {
            return false;
        }
        let (mut above, mut leafy, mut youngest) = (false, false, f64::NEG_INFINITY);
        let mut stack = vec![b];
        while let Some(c) = stack.pop() {
            let branch = &self.branches[c];
            if !branch.alive {
                continue;
            }
            above |= c != b && !below(c);
            for &s in &branch.segments {
                let born = self.segments[s as usize].born;
                youngest = youngest.max(born);
                leafy |= born >= self.age - 1e-9
                    || self.leaves_on.get(s as usize).is_some_and(|&n| n > 0);
            }
            stack.extend(branch.children.iter().map(|&c| c as usize));
        }
        !above || !leafy || youngest < self.age - STALLED_YEARS
    }

    /// The crown's diameter and height now, measured as `measure` measures the skeleton: the
    /// mean of the x and y extents of the branches and their leaves, and the top of the tree
    /// less the lowest point of either.
    #[cfg(test)]
    pub(crate) fn crown_now(&self) -> (f64, f64) {
        let [(diameter, height, _)] = self.crowns_above([f32::NEG_INFINITY], true);
        (diameter, height)
    }

    /// The crown's diameter and height, as `crown_now`, of the branches whose scaffolds leave
    /// the trunk at or above each of `bases`, and the diameter of its wood alone, measured at
    /// once: a branch's leaves are placed once for all the crowns that count it. Where
    /// `skip`, the leaves that cannot widen any of them are passed over. Bounds are minima
    /// and maxima, exact in any order, so each crown comes out to the bit as measured alone
    /// with every leaf placed (`crowns_measured_with_inner_leaves_passed_over_are_the_same`).
    pub(super) fn crowns_above<const N: usize>(
        &self,
        bases: [f32; N],
        skip: bool,
    ) -> [(f64, f64, f64); N] {
        let empty = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        let mut bounds = [empty; N];
        let mut top = f32::NEG_INFINITY;
        let counted = |b: &Branch, k: usize| b.alive && b.order > 0 && b.anchor >= bases[k];
        for s in &self.segments {
            let b = &self.branches[s.branch as usize];
            if b.alive {
                top = top.max(s.end().z);
            }
            for (k, (lo, hi)) in bounds.iter_mut().enumerate() {
                if counted(b, k) && s.length > 1e-4 {
                    *lo = lo.min(s.start.min(s.end()));
                    *hi = hi.max(s.start.max(s.end()));
                }
            }
        }
        // The wood's bounds; a crown with no wood measures nothing.
        let wood = bounds;
        let measured = wood.map(|(lo, hi)| lo.x <= hi.x);
        // Leaves widen a crown only where a shoot comes within a leaf's length of its
        // bounds: those branches' leaves are placed exactly as the skeleton places them.
        let leaf = self.drawn_leaf_size().0;
        let tree_top = self.targets_now().height as f32;
        // Whether `p` lies within `by` of a bound crown `k` is measured by (its top is the
        // highest shoot's, so not the box's).
        let within = |k: usize, p: Vec3, by: f32| {
            let (lo, hi) = wood[k];
            p.x - by < lo.x
                || p.y - by < lo.y
                || p.z - by < lo.z
                || p.x + by > hi.x
                || p.y + by > hi.y
        };
        // A leaf reaches at most its length from its node, and its node lies on its shoot:
        // the leaves of shoots farther than that inside every bound cannot move one, and are
        // not placed (the margin is a thousand times the rounding).
        let margin = leaf * 1.01 + 1e-3;
        let floor = self.leaf_floor();
        for (i, b) in self.branches.iter().enumerate() {
            // The leader's young shoot carries leaves too: always look at those.
            let near = |k: usize| {
                measured[k]
                    && (i == 0 || counted(b, k))
                    && b.segments.iter().any(|&si| {
                        let s = &self.segments[si as usize];
                        self.leaves_on.get(si as usize).is_some_and(|&n| n > 0)
                            && (within(k, s.start, leaf) || within(k, s.end(), leaf))
                    })
            };
            let widens: [bool; N] = std::array::from_fn(near);
            if !widens.contains(&true) {
                continue;
            }
            let wanted = |s: &Segment| {
                !skip
                    || (0..N).any(|k| {
                        widens[k] && (within(k, s.start, margin) || within(k, s.end(), margin))
                    })
            };
            let (mut lo, mut hi) = empty;
            self.for_each_leaf_on(i, (leaf, tree_top, floor), wanted, |p, q, _| {
                let tip = p + q * Vec3::new(0.0, 0.0, leaf);
                lo = lo.min(p.min(tip));
                hi = hi.max(p.max(tip));
            });
            for (k, crown) in bounds.iter_mut().enumerate() {
                if widens[k] {
                    *crown = (crown.0.min(lo), crown.1.max(hi));
                }
            }
        }
        std::array::from_fn(|k| {
            let ((lo, hi), (wood_lo, wood_hi)) = (bounds[k], wood[k]);
            if !measured[k] {
                return (0.0, 0.0, 0.0);
            }
            (
                (((hi.x - lo.x) + (hi.y - lo.y)) / 2.0) as f64,
                (top - lo.z).max(0.0) as f64,
                (((wood_hi.x - wood_lo.x) + (wood_hi.y - wood_lo.y)) / 2.0) as f64,
            )
        })
    }

    /// The scale of next year's envelope, and a stretch of the shoots' lengths (the year's
    /// vigour, where they fall short whatever the envelope), at which this year's shoots,
    /// stopped at it, make
    /// the crown as wide as measured next year (times the learnt bias, `spread`): the crown
    /// is predicted from the wood that will still be there and the shoots' planned tips, and
    /// the scale found by bisection. A sparse sapling crown needs a wide envelope to reach
    /// its measured width; a full one only its own.
    pub(super) fn fit_reach(&self, plans: &[Plan], next: &Targets) -> (f32, f32) {
        let base = next.crown_base() as f32;
        let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
        // Branch by branch, so whether each is shed is asked once, not once per segment.
        for (i, b) in self.branches.iter().enumerate() {
            if !b.alive || b.order == 0 || self.sheds_below(i, base) {
                continue;
            }
            for s in b.segments.iter().map(|&s| &self.segments[s as usize]) {
                if s.goal > 1e-4 {
                    let end = (s.start + s.direction * s.goal.max(s.length)).truncate();
                    lo = lo.min(s.start.truncate().min(end));
                    hi = hi.max(s.start.truncate().max(end));
                }
            }
        }
        // Leaves drawn larger for want of shoots will be drawn smaller on this year's new
        // shoots: the crown is fitted with them at their own size (a hackberry's sapling
        // fitted with this year's enlarged leaves came out a tenth too narrow).
        let leaves = 2.0 * self.leaf_reach * self.leaf_size_boosted(1.0).0;
        let want = next.crown_diameter as f32;
        // The shoots' tips are found on every core: bounds are minima and maxima, exact in
        // any order, so the prediction is the same to the bit on any number of cores.
        let predicted = |scale: f32, stretch: f32| {
            let space = self.space(next, scale);
            let (lo, hi) = plans
                .par_iter()
                .map(|p| {
                    let l = within(&space, p.start, p.direction, p.length * stretch);
                    let tip = (p.start + p.direction * l).truncate();
                    (tip, tip)
                })
                .reduce(|| (lo, hi), |a, b| (a.0.min(b.0), a.1.max(b.1)));
            if lo.x > hi.x {
                return leaves;
            }
            ((hi.x - lo.x) + (hi.y - lo.y)) / 2.0 + leaves
        };
        let solve = |f: &dyn Fn(f32) -> f32, (mut a, mut b): (f32, f32)| {
            for _ in 0..14 {
                let mid = 0.5 * (a + b);
                if f(mid) < want {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            b
        };
        if predicted(MAX_SCALE, 1.0) >= want {
            (solve(&|s| predicted(s, 1.0), (0.5, MAX_SCALE)), 1.0)
        } else if predicted(REACH_SCALE, MAX_STRETCH) < want {
            // The shoots are too short to reach the crown at the stretched envelope: they are
            // stretched all they may be, and the envelope widened as far as the crown needs.
            let s = solve(&|s| predicted(s, MAX_STRETCH), (REACH_SCALE, MAX_SCALE));
            (s, MAX_STRETCH)
        } else {
            let k = solve(&|k| predicted(REACH_SCALE, k), (1.0, MAX_STRETCH));
            (REACH_SCALE, k)
        }
    }

    /// The sag of this year's shoots at the crown base (radians, less higher up) at which
    /// next year's lowest wood comes down to the measured crown base: basal buds starve under
    /// apical control, so without it the crown would end above its measured base. Found by
    /// bisection on the predicted lowest point, as `fit_reach` finds the width.
    pub(super) fn fit_sag(&self, plans: &[Plan], next: &Targets) -> f32 {
        let (base, top) = (next.crown_base() as f32, next.height as f32);
        let space = self.space(next, 2.0);
        let mut wood = f32::INFINITY;
        for s in &self.segments {
            let b = &self.branches[s.branch as usize];
            if b.alive && b.order > 0 && b.anchor >= base && s.goal > 1e-4 {
                let end = s.start + s.direction * s.goal.max(s.length);
                wood = wood.min(s.start.z.min(end.z));
            }
        }
        let lowest = |sag: f32| {
            plans
                .par_iter()
                .map(|p| {
                    let d = sag_down(p.direction, sag_at(sag, p.start.z, base, top));
                    let l = within(&space, p.start, d, p.length);
                    (p.start + d * l).z
                })
                .reduce(|| wood, f32::min)
        };
        let goal = base + 0.01 * (top - base);
        if lowest(0.0) <= goal {
            return 0.0;
        }
        let (mut a, mut b) = (0.0f32, 1.2f32);
        if lowest(b) > goal {
            return b;
        }
        for _ in 0..12 {
            let mid = 0.5 * (a + b);
            if lowest(mid) > goal {
                a = mid;
            } else {
                b = mid;
            }
        }
        b
    }

    /// Inverse modelling: corrects the vigour, so the crown grows out to its envelope, and
    /// the bias of the envelope's fitting (`spread`) by how the crown came out.
    pub(super) fn fit_crown(&mut self) {
        let t = self.targets_now();
        // The corrections' rates are set per twentieth of a year (`RATE_STEP`): a longer step
        // takes them k times over, compounded, so a year corrects as much at any step length.
        let k = self.step_length() / RATE_STEP;
        // The vigour steers the crown that will still be there in a year: scaffolds the crown
        // base is about to pass are shed soon whatever their length. Both crowns are
        // measured in one pass, each branch's leaves placed once for both.
        let coming_base = self.targets(self.age + 1.0).crown_base() as f32;
        let [(diameter, _, wood), (mut coming, _, _)] =
            self.crowns_above([f32::NEG_INFINITY, coming_base], true);
        // The leaves' reach as they came out, so next year's crown is fitted with it: a
        // walnut's 45 cm leaves at its shoots' tips reach out 0.8 of their length, and with
        // the half assumed its sapling's crown came out 14% too wide (issue R).
        let leaf = self.drawn_leaf_size().0 as f64;
        if leaf > 1e-3 && wood > 1e-3 {
            let (lo, hi) = LEAF_REACH_BOUNDS;
            let measured = (((diameter - wood) / (2.0 * leaf)) as f32).clamp(lo, hi);
            let rate = 1.0 - (1.0 - LEAF_REACH_RATE).powf(k as f32);
            self.leaf_reach += rate * (measured - self.leaf_reach);
        }
        if coming <= 1e-3 {
            coming = diameter;
        }
        if diameter > 1e-3 {
            let ratio = (1.1 * t.crown_diameter / coming)
                .powf(0.5 * k)
                .clamp(0.95f64.powf(k), 1.05f64.powf(k));
            self.vigour = (self.vigour * ratio).clamp(MIN_VIGOUR, MAX_VIGOUR);
            let ratio = (t.crown_diameter / diameter)
                .powf(0.2 * k)
                .clamp(0.995f64.powf(k), 1.005f64.powf(k));
            self.spread = (self.spread * ratio).clamp(0.85, 1.15);
        }
    }
}
