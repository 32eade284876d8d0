//! Primary and secondary growth: a segment elongates in its first season to the length its
//! bud was given; then it only thickens, its radius following the pipe model with the trunk
//! held to f_DBH.

use super::buds::GROWING_SEASON;
use super::*;

impl Grower {
    /// Primary growth: every shoot of this year reaches for its length over the season.
    pub(super) fn elongate(&mut self) {
        for b in 0..self.branches.len() {
            let branch = &self.branches[b];
            if !branch.alive {
                continue;
            }
            let last = *branch.segments.last().expect("a segment") as usize;
            let seg = &mut self.segments[last];
            let grown = ((self.age - seg.born) / GROWING_SEASON).clamp(0.0, 1.0) as f32;
            seg.length = seg.goal * grown;
        }
    }

    /// Radii by the pipe model (Shinozaki; da Vinci's rule): a segment's base carries every
    /// shoot beyond it, radius^n = the sum of their radius^n, each live tip counting one; along
    /// the segment it carries less after each side branch leaves. The tip's radius is then the
    /// one that makes the trunk at breast height f_DBH(t): DBH follows the data while every
    /// branch stays pipe-consistent, so the trunk tapers as limbs leave it.
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
        let at_breast = self.diameter_carried(&carried, self.dbh_read_at());
        let dbh = self.targets_now().dbh as f32;
        self.tip_radius = if at_breast > 0.0 {
            dbh / 200.0 / at_breast
        } else {
            0.001
        };
        let scale = self.tip_radius;
        self.radii = carried.iter().map(|&c| c.powf(1.0 / n) * scale).collect();
    }

    /// Where the trunk's diameter is held to f_DBH: breast height, or caliper height for a
    /// species whose measured trees are too short for it (by the data's height, not the
    /// nursery sapling's on its way up to it).
    pub(super) fn dbh_read_at(&self) -> f32 {
        let age = self.age.max(self.measured.ages.0);
        diameter_height(self.targets(age).height as f32)
    }

    /// The trunk's radius at height z, in tip radii (a tip carrying itself is 1). A multi-
    /// stem tree's is that of a single stem with the basal area of all its stems crossing z
    /// together (the square root of the sum of their squared diameters), as the Urban Tree
    /// Database's own DBH of such trees is: in its raw data (TS3, columns dbh1-dbh8), 265 of
    /// the 363 trees measured with two or more stems have a DBH equal to that sum (within
    /// 0.15 cm), and none the plain sum of their diameters.
    ///
    /// A trunk the street has cut back (`Branch::headed`) may have handed its crown to laterals
    /// that leave it below z: the survey reads such a tree as one forking below breast height,
    /// by the stems crossing z, and so does this, counting every live branch of the trunk that
    /// leaves it below z and crosses z. Read on the trunk alone, a cut-back stub carrying a
    /// few tips past z was held to the whole DBH, and the pipe model made its base metres
    /// thick.
    fn diameter_carried(&self, carried: &[f32], z: f32) -> f32 {
        let n = PIPE_EXPONENT;
        let headed = self.branches[0].headed;
        let crossing = |branch: &Branch| {
            branch.order == 0
                || (headed
                    && branch.order == 1
                    && branch.parent.is_some_and(|(p, _)| p == 0)
                    && self.segments[branch.segments[0] as usize].start.z <= z)
        };
        let mut radii = self.branches.iter().filter_map(|branch| {
            if !branch.alive || !crossing(branch) {
                return None;
            }
            let seg = self.axis_segment_at(branch, z)?;
            Some(self.axis_carried(branch, carried, seg, z).powf(1.0 / n))
        });
        let Some(first) = radii.next() else {
            // Below z everywhere (a sapling shorter than breast height): the trunk's top.
            let trunk = &self.branches[0];
            return trunk.segments.last().map_or(0.0, |&s| {
                self.axis_carried(trunk, carried, s, z).powf(1.0 / n)
            });
        };
        match radii.next() {
            None => first,
            Some(second) => {
                let squares: f32 = radii.map(|r| r * r).sum();
                (first * first + second * second + squares).sqrt()
            }
        }
    }

    /// The segment of an order-0 axis (the trunk or a stem) that crosses height z.
    fn axis_segment_at(&self, branch: &Branch, z: f32) -> Option<u32> {
        let first = *branch.segments.first()?;
        if self.segments[first as usize].start.z > z {
            return None;
        }
        branch
            .segments
            .iter()
            .copied()
            .find(|&s| self.segments[s as usize].end().z > z)
    }

    /// What an axis carries at height z on its segment `seg`, in tips: the segment's base
    /// less the side branches leaving it below z.
    fn axis_carried(&self, branch: &Branch, carried: &[f32], seg: u32, z: f32) -> f32 {
        let mut c = carried[seg as usize];
        for &child in &branch.children {
            let b = &self.branches[child as usize];
            let first = b.segments[0] as usize;
            if b.alive && b.parent.map(|p| p.1) == Some(seg) && self.segments[first].start.z <= z {
                c -= carried[first];
            }
        }
        c.max(1.0)
    }

    /// Radii along a segment: at its base, then just past each side branch leaving it (`children`:
    /// distance from the segment's start and the branch's base radius, in order), by the pipe
    /// model. Fills `out` with (distance from the start, radius) pairs.
    pub(super) fn radii_along(
        &self,
        segment: u32,
        children: &[(f32, f32)],
        out: &mut Vec<(f32, f32)>,
    ) {
        let n = PIPE_EXPONENT;
        let tip = self.tip_radius.max(1e-6);
        let base = self.radius_of(segment);
        let mut c = (base / tip).powf(n);
        out.clear();
        out.push((0.0, base));
        for &(along, child_radius) in children {
            c -= (child_radius / tip).powf(n);
            out.push((along, tip * c.max(1.0).powf(1.0 / n)));
        }
    }

    /// The length of the next step, years (see [`GrowthOptions::steps_per_year`]): a young
    /// tree's more, and shorter.
    pub fn step_length(&self) -> f64 {
        let steps = self.options.steps_per_year.max(1);
        if self.young_year {
            1.0 / steps.max(YOUNG_STEPS_PER_YEAR) as f64
        } else {
            1.0 / steps as f64
        }
    }

    /// Whether the year beginning now is a young tree's (its crown next year under
    /// `SYLLEPTIC_CROWN`): chosen only as a year begins, so every year's steps end on its last
    /// day.
    pub(super) fn young_year(&self) -> bool {
        let next = self.targets((self.age + 1e-9).floor() + 1.0);
        next.crown_height < SYLLEPTIC_CROWN
    }

    /// Radius of a segment's base now, m.
    pub(super) fn radius_of(&self, segment: u32) -> f32 {
        self.radii.get(segment as usize).copied().unwrap_or(0.0)
    }
}
