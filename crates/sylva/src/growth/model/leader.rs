//! The leader held to the measured height: an excurrent trunk's apex grows straight to next
//! year's height; a forked crown lifts its highest shoot near the axis to it; a multi-stem
//! tree's stems share it; and the apical control that hands the lead to the scaffolds.

use super::buds::{FORK_ZONE, MAX_METAMERS, Plan};
use super::*;

impl Grower {
    /// The leader follows the measured height: while the tree is excurrent the trunk's apex
    /// grows straight to next year's height; once it has forked, the highest shoot near the
    /// axis is lifted to reach it, so one of the codominant limbs holds the top.
    pub(super) fn hold_height(
        &mut self,
        plans: &mut Vec<Plan>,
        next: &Targets,
        leader_holds: bool,
    ) {
        let top = next.height as f32;
        if self.habit.stems > 1 {
            self.hold_stems(plans, next);
        }
        // A trunk cut back to a lateral hands the top to its highest limb, as a forked one does.
        if (leader_holds && !self.branches[0].headed) || self.habit.form == TreeForm::Palm {
            let apex = self.apex_segment(0);
            let rise = top - apex.end().z;
            if rise > 0.02 {
                plans.insert(
                    0,
                    Plan {
                        from: 0,
                        lateral: false,
                        start: apex.end(),
                        direction: Vec3::Z,
                        length: rise,
                    },
                );
            }
            return;
        }
        let highest = plans
            .iter()
            .map(|p| p.start.z + p.direction.z * p.length)
            .fold(self.apex_segment(0).end().z, f32::max);
        // A tree whose leader the street has cut back is no longer held to the measured
        // height: its top grows as its shoots do, wherever the cuts left them room (lifting
        // the highest shoot near the axis would send it into the wire's zone every year).
        if highest >= top - 0.02 || (self.regrowth.is_some() && self.branches[0].headed) {
            return;
        }
        // The apex that is high and near the axis: the one a forester would call the leader.
        // Not the trunk's: it has handed the top to its codominant limbs.
        let score = |p: Vec3| p.z - 0.5 * p.truncate().length();
        let best = (1..self.branches.len())
            .filter(|&b| self.branches[b].alive && !self.branches[b].headed)
            .max_by(|&a, &b| {
                let (sa, sb) = (
                    score(self.apex_segment(a).end()),
                    score(self.apex_segment(b).end()),
                );
                sa.total_cmp(&sb).then(b.cmp(&a))
            })
            .unwrap_or(0);
        let apex = self.apex_segment(best);
        let start = apex.end();
        let i = match plans.iter().position(|p| !p.lateral && p.from == best) {
            Some(i) => i,
            None => {
                plans.push(Plan {
                    from: best,
                    lateral: false,
                    start,
                    direction: apex.direction,
                    length: 0.0,
                });
                plans.len() - 1
            }
        };
        // It climbs steeply: a shoot that rose gently would reach far out of the crown first.
        let p = &mut plans[i];
        let rise = 0.9f32;
        p.length = (top - start.z) / rise;
        // On a tree the street has cut, the leader climbs back no faster than the most
        // vigorous shoot grows in a year: it is held to the measured height again only when
        // it gets there (a tree cut below a wire would otherwise be back at full height in a
        // season).
        if self.regrowth.is_some() {
            p.length = p.length.min(MAX_METAMERS * self.metamer_now());
        }
        let heading = p.direction.truncate().normalize_or(glam::Vec2::X);
        p.direction = (heading * (1.0 - rise * rise).sqrt()).extend(rise);
    }

    /// A multi-stem tree's stems are its trunk: each is held on up to the fork zone above
    /// next year's crown base, as a decurrent trunk is held to its fork, and only there opens
    /// into the crown. Left to the allocation, a stem whose tip the rising crown base passes
    /// sees nothing of the crown's space and stops, and one stem carries the whole crown.
    pub(super) fn hold_stems(&mut self, plans: &mut Vec<Plan>, next: &Targets) {
        let fork = (next.crown_base() as f32 + FORK_ZONE).min(next.height as f32);
        for b in 1..self.branches.len() {
            let branch = &self.branches[b];
            if !branch.alive || branch.order != 0 || branch.headed {
                continue;
            }
            let apex = self.apex_segment(b);
            let start = apex.end();
            if fork - start.z <= 0.02 {
                continue;
            }
            // On in the stem's own lean, straight: its first shoot's direction.
            let direction = self.segments[branch.segments[0] as usize].direction;
            let length = (fork - start.z) / direction.z.max(0.2);
            match plans.iter_mut().find(|p| !p.lateral && p.from == b) {
                Some(p) => {
                    p.direction = direction;
                    p.length = p.length.max(length);
                }
                None => plans.push(Plan {
                    from: b,
                    lateral: false,
                    start,
                    direction,
                    length,
                }),
            }
        }
    }

    /// Apical control now. A decurrent species keeps a leader until its trunk reaches the
    /// grown tree's crown base (street trees are trained so), then forks within `FORK_ZONE`:
    /// its codominant limbs then leave the trunk where pruning never reaches.
    pub(super) fn apical_control(&self) -> f32 {
        let own = self.habit.apical_control;
        // A multi-stem tree has no leader to hand over: its stems share the top from the start.
        if own >= 0.5 || self.habit.stems > 1 {
            return own;
        }
        let young = 0.56;
        let top = self.apex_segment(0).end().z;
        let grown = ((top - self.fork_height) / FORK_ZONE).clamp(0.0, 1.0);
        young + (own - young) * grown
    }
}
