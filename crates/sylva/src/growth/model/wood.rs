//! Primary and secondary growth: a segment elongates in its first year, bending toward light
//! and sagging under its own weight within the crown's heights; then it only thickens, its
//! radius following the pipe model with the trunk held to f_DBH.

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

    /// Radii by the pipe model (Shinozaki; da Vinci's rule): a segment's base carries every
    /// shoot beyond it, radius^n = the sum of their radius^n, each live tip counting one. The
    /// tip's radius is then the one that makes the trunk at breast height f_DBH(t): DBH follows
    /// the data while every branch stays pipe-consistent, so the trunk tapers as limbs leave it
    /// and swells below forks.
    pub(super) fn refresh_radii(&mut self) {
        let n = PIPE_EXPONENT;
        let count = self.segments.len();
        // What each segment's base carries, in tips (radius^n in units of a tip's).
        let mut carried = vec![0.0f32; count];
        let mut joining = vec![0.0f32; count];
        // Children come after their parents: walking back, every child is summed before the
        // segment it grows from.
        for b in (0..self.branches.len()).rev() {
            let branch = &self.branches[b];
            if !branch.alive {
                continue;
            }
            let mut acc = 1.0f32;
            for &s in branch.segments.iter().rev() {
                acc += joining[s as usize];
                carried[s as usize] = acc;
            }
            if let Some((_, from)) = branch.parent {
                joining[from as usize] += acc;
            }
        }
        let unit: Vec<f32> = carried.iter().map(|&c| c.powf(1.0 / n)).collect();
        let at_breast = self.trunk_profile(&unit, 1.0, BREAST_HEIGHT);
        let dbh = self.targets_now().dbh as f32;
        self.tip_radius = if at_breast > 0.0 {
            dbh / 200.0 / at_breast
        } else {
            0.001
        };
        let scale = self.tip_radius;
        self.radii = unit.iter().map(|&u| u * scale).collect();
    }

    /// The trunk's radius at height z from per-segment base radii: from each segment's base to
    /// the next one's, and down to half a tip's radius (`tip`) over the leader's last shoot.
    fn trunk_profile(&self, base: &[f32], tip: f32, z: f32) -> f32 {
        let trunk = &self.branches[0].segments;
        let Some(&first) = trunk.first() else {
            return 0.0;
        };
        if z <= self.segments[first as usize].start.z {
            return base[first as usize];
        }
        for (k, &s) in trunk.iter().enumerate() {
            let seg = &self.segments[s as usize];
            let (z0, z1) = (seg.start.z, seg.end().z);
            if z >= z0 && z < z1 {
                let next = trunk.get(k + 1).map_or(tip * 0.5, |&t| base[t as usize]);
                let f = (z - z0) / (z1 - z0).max(1e-6);
                return base[s as usize] + (next - base[s as usize]) * f;
            }
        }
        // Above the leader: its tip.
        tip * 0.5
    }

    /// Trunk radius at height z now, m.
    pub(super) fn trunk_radius(&self, z: f32) -> f32 {
        self.trunk_profile(&self.radii, self.tip_radius, z)
    }

    pub(super) fn step_length(&self) -> f64 {
        1.0 / self.options.steps_per_year.max(1) as f64
    }

    /// Radius of a segment's base now, m.
    pub(super) fn radius_of(&self, segment: u32) -> f32 {
        self.radii.get(segment as usize).copied().unwrap_or(0.0)
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
