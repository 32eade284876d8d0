//! Primary and secondary growth: a segment elongates in its first year, bending toward light
//! and sagging under its own weight within the crown's heights; then it only thickens, its
//! radius following f_DBH down the trunk and the pipe model out to the twigs.

use super::*;

impl Grower {
    /// Primary growth: the last segment of every growing branch reaches for the branch's
    /// target length.
    pub(super) fn elongate(&mut self) {
        let t = self.targets_now();
        let top = t.height as f32;
        let base = t.crown_base() as f32;
        let leaf = self.drawn_leaf_size().0;
        for b in 0..self.branches.len() {
            let branch = &self.branches[b];
            if !branch.alive {
                continue;
            }
            let finished = branch.finished;
            let last = *branch.segments.last().expect("a segment") as usize;
            let seg = self.segments[last];
            let target = if branch.order == 0 {
                top
            } else {
                let (parent, pseg) = branch.parent.expect("a side branch has a parent");
                let pb = &self.branches[parent as usize];
                // Relative position p_r along the parent; for the trunk, within the crown.
                let (p_r, l_p) = if pb.order == 0 {
                    let z = self.segments[pseg as usize].start.z
                        + self.segments[pseg as usize].direction.z * branch.along;
                    ((z - base) / (top - base).max(0.1), (top - base).max(0.1))
                } else {
                    let last = *pb.segments.last().expect("a segment") as usize;
                    let l_p = pb.finished + self.segments[last].length;
                    (branch.offset / l_p.max(1e-3), l_p)
                };
                // Little light at the apex: the branch reaches further, out of the shade.
                let apex_light = self.light.light_at(seg.end());
                let reach = 1.0 + 0.5 * (1.0 - apex_light).clamp(0.0, 1.0);
                let order_factor = 0.5 + 0.5 * branch.order as f32;
                let gain = if branch.order == 1 {
                    self.gain as f32
                } else {
                    1.0
                };
                gain * branch.s_l * reach * self.shape.relative_length(p_r) * l_p / order_factor
            };
            let mut length = (target - finished).max(seg.length);
            if branch.order == 0 {
                length = target - finished;
            } else if length > seg.length {
                let rel = (branch.anchor - base) / (top - base).max(0.1);
                // A shoot in its first year sags from where its bud aimed, the more the lower
                // in the crown its scaffold leaves the trunk; the sag is fitted to the crown
                // height. It bends rather than pass above the leader or below the crown base
                // (where its leaves would hang out of the measured crown).
                let direction = if self.age - seg.born < 1.0 {
                    let sag = self.droop as f32 * (1.0 - rel).clamp(0.0, 1.0).powi(2);
                    let floor = base + leaf;
                    // The crown's top is rounded: the ceiling falls away from the leader by
                    // the shape's roof over the crown's radius (once more, for where the bent
                    // tip ends up).
                    let radius = (t.crown_diameter * 0.5 * self.spread) as f32;
                    let roof = self.shape.roof() * (top - base);
                    let ceiling =
                        |r: f32| top - 0.05 - roof * (r / radius.max(0.1)).min(1.0).powi(2);
                    let aimed = sag_down(seg.aim, sag);
                    let mut d = aimed;
                    for _ in 0..2 {
                        let r = (seg.start + d * length).truncate().length();
                        d = within_heights(aimed, seg.start, length, floor, ceiling(r).max(floor));
                    }
                    d
                } else {
                    seg.direction
                };
                self.segments[last].direction = direction;
                // Nothing leaves the crown's envelope: the measured crown diameter shaped by
                // c(p) at each height. Break-outs may go 15% past it.
                let slack = if branch.s_l > 1.0 { 1.15 } else { 1.0 };
                let half = (t.crown_diameter * 0.5 * self.spread) as f32 * slack;
                let reach = half * self.shape.relative_length(rel).max(0.15);
                let inside = |p: Vec3| p.z <= top - 0.04 && p.truncate().length() <= reach;
                let tip = |l: f32| seg.start + direction * l;
                if !inside(tip(length)) {
                    // The longest length whose tip is inside, by bisection from the current
                    // one (which may itself be outside if the crown base rose: then no growth).
                    let (mut lo, mut hi) = (seg.length, length);
                    if inside(tip(lo)) {
                        for _ in 0..20 {
                            let mid = 0.5 * (lo + hi);
                            if inside(tip(mid)) {
                                lo = mid;
                            } else {
                                hi = mid;
                            }
                        }
                    }
                    length = lo;
                }
            }
            self.segments[last].length = length.max(0.0);
        }
    }

    pub(super) fn refresh_radii(&mut self) {
        // f_DBH along the sapling-ramped curve, by whole steps from the nursery's start: a
        // segment's radius depends only on its age, and ages come in steps.
        let dt = self.step_length();
        let start = self.measured.ages.0 - NURSERY_YEARS;
        let steps = ((self.age - start) / dt).round().max(0.0) as usize + 1;
        for k in self.dbh_by_step.len()..steps {
            let d = self.targets(start + k as f64 * dt).dbh;
            self.dbh_by_step.push(d as f32);
        }
        let radii: Vec<f32> = self
            .segments
            .iter()
            .map(|s| {
                if self.branches[s.branch as usize].alive {
                    self.radius_at_base(s)
                } else {
                    0.0
                }
            })
            .collect();
        self.radii = radii;
    }

    pub(super) fn step_length(&self) -> f64 {
        1.0 / self.options.steps_per_year.max(1) as f64
    }

    /// Radius of a segment's base section now, m.
    pub(super) fn radius_at_base(&self, s: &Segment) -> f32 {
        let b = &self.branches[s.branch as usize];
        if b.order == 0 {
            self.trunk_radius(s.start.z)
        } else {
            // f_DBH of the segment's own age, read on the sapling-ramped curve.
            let age = (self.age - s.born).max(0.0);
            let k = (age / self.step_length()).round() as usize;
            let d = match self.dbh_by_step.get(k) {
                Some(&d) => d as f64,
                None => self.targets(self.measured.ages.0 - NURSERY_YEARS + age).dbh,
            };
            (b.c_d as f64 * d / 200.0) as f32
        }
    }

    /// Trunk radius at height z, m: the DBH of the tree when the leader passed breast height,
    /// shifted by how much later the leader passed z, so the trunk tapers and is f_DBH(t)
    /// exactly at 1.37 m.
    pub(super) fn trunk_radius(&self, z: f32) -> f32 {
        let passed = |z: f32| -> f64 {
            // The age at which the target height first reached z (bisection on the ramped,
            // rising height).
            let (mut lo, mut hi) = (self.measured.ages.0 - NURSERY_YEARS, self.age);
            if self.targets(lo).height >= z as f64 {
                return lo;
            }
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if self.targets(mid).height < z as f64 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        };
        let shift = passed(z) - passed(BREAST_HEIGHT);
        let d = self.targets(self.age - shift).dbh;
        let top = self.targets_now().height as f32;
        // Thin to a point over the leader's last half metre (less on a sapling, never down
        // to breast height).
        let zone = ((top - BREAST_HEIGHT) * 0.9).clamp(0.05, 0.5);
        let tip = ((top - z) / zone).clamp(0.05, 1.0);
        (d / 200.0) as f32 * tip
    }
}

/// `aim` turned `sag` radians further down in its vertical plane, never steeper than 40 degrees
/// below the horizontal.
pub(super) fn sag_down(aim: Vec3, sag: f32) -> Vec3 {
    let horizontal = aim.truncate().normalize_or(glam::Vec2::X);
    let elevation = (aim.z.clamp(-1.0, 1.0).asin() - sag).max(-0.7);
    (horizontal * elevation.cos()).extend(elevation.sin())
}

/// `direction` tilted in its vertical plane so that a shoot of `length` from `start` ends
/// between the heights `floor` and `ceiling`.
pub(super) fn within_heights(
    direction: Vec3,
    start: Vec3,
    length: f32,
    floor: f32,
    ceiling: f32,
) -> Vec3 {
    let end = start.z + direction.z * length;
    let rise = if end > ceiling {
        (ceiling - start.z) / length.max(1e-6)
    } else if end < floor {
        (floor - start.z) / length.max(1e-6)
    } else {
        return direction;
    };
    let rise = rise.clamp(-1.0, 1.0);
    let horizontal = direction.truncate().normalize_or(glam::Vec2::X);
    (horizontal * (1.0 - rise * rise).sqrt()).extend(rise)
}
