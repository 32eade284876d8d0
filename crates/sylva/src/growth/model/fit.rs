//! Shedding and fitting to the measured targets: lower branches are shed as the crown base
//! (monotone) rises, and one gain on branch length is corrected every step so that the
//! crown's measured diameter follows f_CD.

use super::*;

impl Grower {
    /// Sheds what the rising crown base leaves below it.
    pub(super) fn shed(&mut self) {
        let base = self.targets_now().crown_base() as f32;
        for b in 1..self.branches.len() {
            if !self.branches[b].alive {
                continue;
            }
            // Scaffolds go when the crown base passes where they leave the trunk; smaller
            // branches as soon as any of them hangs below it.
            let branch = &self.branches[b];
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
            if lowest < base - 0.02 {
                self.kill(b);
            }
        }
    }

    /// The crown's diameter and height now, measured as `measure` measures the skeleton: the
    /// mean of the x and y extents of the branches and their leaves, and the top of the tree
    /// less the lowest point of either.
    pub(crate) fn crown_now(&self) -> (f64, f64) {
        self.crown_above(f32::NEG_INFINITY)
    }

    /// `crown_now` of the branches whose scaffolds leave the trunk at or above `base`.
    pub(super) fn crown_above(&self, base: f32) -> (f64, f64) {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        let mut top = f32::NEG_INFINITY;
        let counted = |b: &Branch| b.alive && b.order > 0 && b.anchor >= base;
        for s in &self.segments {
            let b = &self.branches[s.branch as usize];
            if b.alive {
                top = top.max(s.end().z);
            }
            if counted(b) && s.length > 1e-4 {
                lo = lo.min(s.start.min(s.end()));
                hi = hi.max(s.start.max(s.end()));
            }
        }
        if lo.x > hi.x {
            return (0.0, 0.0);
        }
        // Leaves widen the crown only where a shoot comes within a leaf's length of its
        // bounds: those branches' leaves are placed exactly as the skeleton places them.
        let leaf = self.drawn_leaf_size().0;
        let tree_top = self.targets_now().height as f32;
        let (wood_lo, wood_hi) = (lo, hi);
        let near_edge = |p: Vec3| {
            p.x - leaf < wood_lo.x
                || p.y - leaf < wood_lo.y
                || p.z - leaf < wood_lo.z
                || p.x + leaf > wood_hi.x
                || p.y + leaf > wood_hi.y
        };
        for (i, b) in self.branches.iter().enumerate() {
            // The leader's young shoot carries leaves too: always look at those.
            if (i > 0 && !counted(b))
                || !b.segments.iter().any(|&si| {
                    let s = &self.segments[si as usize];
                    self.leaves_on.get(si as usize).is_some_and(|&n| n > 0)
                        && (near_edge(s.start) || near_edge(s.end()))
                })
            {
                continue;
            }
            self.for_each_leaf(i, leaf, tree_top, |p, q| {
                let tip = p + q * Vec3::new(0.0, 0.0, leaf);
                lo = lo.min(p.min(tip));
                hi = hi.max(p.max(tip));
            });
        }
        (
            (((hi.x - lo.x) + (hi.y - lo.y)) / 2.0) as f64,
            (top - lo.z).max(0.0) as f64,
        )
    }

    /// Inverse modelling: corrects the length gain toward the measured crown diameter and the
    /// sag toward the measured crown height.
    pub(super) fn fit_crown(&mut self) {
        let t = self.targets_now();
        let (diameter, height) = self.crown_now();
        // The gain steers the crown that will still be there in a year: scaffolds the crown
        // base is about to pass are shed soon whatever their length.
        let coming_base = self.targets(self.age + 1.0).crown_base() as f32;
        let (mut coming, _) = self.crown_above(coming_base);
        if coming <= 1e-3 {
            coming = diameter;
        }
        if diameter > 1e-3 {
            // Two corrections. The gain lets branches reach for a crown a fifth wider than
            // measured, so their tips meet the envelope; the envelope's scale then holds the
            // crown to the measured diameter. It also widens where a sparse crown (a
            // sapling's few scaffolds) meets its envelope in only a few directions. Both move
            // a little every step: the crown answers a year late, so haste overshoots.
            let ratio = (1.2 * t.crown_diameter / coming)
                .powf(0.5)
                .clamp(0.95, 1.05);
            self.gain = (self.gain * ratio).clamp(0.05, 20.0);
            let ratio = (t.crown_diameter / diameter).clamp(0.97, 1.03);
            self.spread = (self.spread * ratio).clamp(0.8, 1.6);
        }
        if height > 1e-3 {
            let short = (t.crown_height - height) / t.crown_height.max(0.1);
            self.droop = (self.droop + (0.5 * short).clamp(-0.03, 0.03)).clamp(0.0, 1.5);
        }
    }
}
