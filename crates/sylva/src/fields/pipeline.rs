//! Fields' six-stage pipeline (section 3.1): trunk iterations, leaf lobes, trunks connected to
//! the lobes, branches grown toward control points on the lobes, leaves filling the lobes, and
//! branch geometry (a [`Skeleton`] meshed with the Tessellation rule).
//!
//! Branches are built backwards from their targets, as the report describes: control points are
//! grouped (one group per first branch, `NumBranchesOffSplit^(BranchIterations-1)` points each),
//! a first branch leaves the trunk where it sees its group's centre at `BranchAngle`, covers the
//! share of the way that `LengthReductionFactor` gives its generation, and splits; the last
//! generation ends exactly on the control points. Each branch leaves its parent at the rule's
//! angle and bends toward its target (a quadratic curve), cut into `NumSegmentsInBranch` pieces
//! whose ends wander by `SegmentOffset` and are kept inside the lobe.

use super::lobe::Lobe;
use super::rules::TreeRules;
use crate::error::{GenerateError, ParamsError};
use crate::rng::{Random, StreamKey};
use crate::skeleton::{Leaf, Skeleton, StemId};
use glam::Vec3;
use std::f32::consts::TAU;

/// What a stem is, which sets its widths (rules 12–17).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Trunk iterations and the trunks connected to lobes.
    Trunk,
    /// Branches grown toward control points.
    Branch,
    /// Twigs carrying leaves.
    Twig,
}

/// A trunk piece as the user, a `.tree` file or automatic placement gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrunkPiece {
    /// Index of the parent piece (earlier in the list), `None` for a root.
    pub parent: Option<usize>,
    /// Start, metres (Z up).
    pub start: Vec3,
    /// End.
    pub end: Vec3,
}

/// Trunks and lobes before growth: what stages 1 and 2 make and a `.tree` file stores.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Placement {
    /// The trunk hierarchy.
    pub trunks: Vec<TrunkPiece>,
    /// The leaf lobes.
    pub lobes: Vec<Lobe>,
}

/// One stem of the grown tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Branch {
    /// Parent stem, earlier in the list.
    pub parent: Option<usize>,
    /// Trunk, branch or twig.
    pub kind: Kind,
    /// Generation: 0 trunks, 1 first branches, ...
    pub level: u8,
    /// Polyline from base to tip.
    pub points: Vec<Vec3>,
    /// Width (diameter) at each point.
    pub widths: Vec<f32>,
    /// The lobe it grows in.
    pub lobe: Option<usize>,
    /// The control point a last-generation branch was grown to.
    pub target: Option<Vec3>,
}

/// A grown lobe tree with everything the stages made, for inspection and tests.
#[derive(Clone, Debug, PartialEq)]
pub struct LobeTree {
    /// The lobes.
    pub lobes: Vec<Lobe>,
    /// Branch control points per lobe, after LeafTaper.
    pub control_points: Vec<Vec<Vec3>>,
    /// Leaf control points per lobe.
    pub leaf_points: Vec<Vec<Vec3>>,
    /// Stems: trunks first, parents before children.
    pub branches: Vec<Branch>,
    /// Leaves.
    pub leaves: Vec<Leaf>,
    /// Sides of every stem's cylinder (the Tessellation rule).
    pub tessellation: u32,
    /// LeafTaper, which shapes the lobes.
    pub taper: f32,
}

/// Most stems and leaves a lobe tree may have.
pub const MAX_STEMS: usize = 200_000;
/// Most leaves.
pub const MAX_LEAVES: usize = 2_000_000;

pub(super) fn rotate_away(dir: Vec3, angle: f32, azimuth: f32) -> Vec3 {
    // A unit vector at `angle` from `dir`, turned `azimuth` about it.
    let side = dir.any_orthonormal_vector();
    let other = dir.cross(side);
    let across = side * azimuth.cos() + other * azimuth.sin();
    (dir * angle.cos() + across * angle.sin()).normalize()
}

impl Placement {
    /// The same trunk and lobes `s` times as large (about the ground point under the trunk).
    pub fn scaled(&self, s: f32) -> Placement {
        let mut scaled = self.clone();
        for t in &mut scaled.trunks {
            t.start *= s;
            t.end *= s;
        }
        for l in &mut scaled.lobes {
            l.centre *= s;
            l.radius *= s;
        }
        scaled
    }
}

/// Stages 1 and 2 done automatically (the paper's button L): the trunk iterations from the
/// ground and one lobe above them, sized by the rules' layout.
pub fn auto_placement(rules: &TreeRules, seed: u64) -> Placement {
    let r = rules.layout.lobe_radius as f32;
    let base = rules.layout.crown_base as f32;
    let lobe = Lobe {
        centre: Vec3::new(0.0, 0.0, base + r),
        radius: r,
    };
    Placement {
        trunks: trunk_iterations(rules, seed, (0.9 * base).max(0.1 * r)),
        lobes: vec![lobe],
    }
}

/// Stage 1 for lobes the user placed: trunk iterations reaching 90% of the way to the lowest
/// lobe's bottom.
pub fn placement_for_lobes(rules: &TreeRules, seed: u64, lobes: Vec<Lobe>) -> Placement {
    let lowest = lobes
        .iter()
        .map(|l| l.centre.z - l.radius)
        .fold(f32::MAX, f32::min)
        .max(0.0);
    let least = lobes.iter().map(|l| l.radius).fold(f32::MAX, f32::min);
    Placement {
        trunks: trunk_iterations(rules, seed, (0.9 * lowest).max(0.1 * least)),
        lobes,
    }
}

/// The trunk and its iterations, `height` tall in all: each split gives
/// `NumTrunkBranchesOffSplit` trunks spread evenly around their parent, `TrunkAngle` apart
/// (each half of it from the parent's direction), `LengthReductionFactor` as long.
fn trunk_iterations(rules: &TreeRules, seed: u64, height: f32) -> Vec<TrunkPiece> {
    let n = rules.num_trunk_iterations;
    let lrf = rules.length_reduction_factor as f32;
    let sum: f32 = (0..=n).map(|i| lrf.powi(i as i32)).sum();
    let first = height / sum;
    let mut random = StreamKey::from_seed(seed).child(1).stream();
    let mut pieces = vec![TrunkPiece {
        parent: None,
        start: Vec3::ZERO,
        end: Vec3::new(0.0, 0.0, first),
    }];
    let mut tips = vec![0usize];
    let half = (rules.trunk_angle as f32 / 2.0).to_radians();
    let k = rules.num_trunk_branches_off_split as usize;
    for i in 1..=n {
        let length = first * lrf.powi(i as i32);
        let mut next = Vec::new();
        for &t in &tips {
            let parent = pieces[t];
            let dir = (parent.end - parent.start).normalize();
            let phase = random.unit() as f32 * TAU;
            for j in 0..k {
                let d = rotate_away(dir, half, phase + TAU * j as f32 / k as f32);
                pieces.push(TrunkPiece {
                    parent: Some(t),
                    start: parent.end,
                    end: parent.end + d * length,
                });
                next.push(pieces.len() - 1);
            }
        }
        tips = next;
    }
    pieces
}

/// Groups points by halving along their widest spread until each group has at most `size`.
pub(super) fn group(points: Vec<Vec3>, size: usize, out: &mut Vec<Vec<Vec3>>) {
    if points.len() <= size.max(1) {
        if !points.is_empty() {
            out.push(points);
        }
        return;
    }
    let (lo, hi) = points.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
        (lo.min(*p), hi.max(*p))
    });
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mut points = points;
    points.sort_by(|a, b| a[axis].total_cmp(&b[axis]));
    // Cut at a multiple of `size` so groups come out full.
    let groups = points.len().div_ceil(size);
    let cut = groups.div_ceil(2) * size;
    let rest = points.split_off(cut.min(points.len()));
    group(points, size, out);
    group(rest, size, out);
}

/// Splits points into `parts` groups around the direction `axis`, by bearing.
fn split_around(points: &[Vec3], from: Vec3, axis: Vec3, parts: usize) -> Vec<Vec<Vec3>> {
    let side = axis.any_orthonormal_vector();
    let other = axis.cross(side);
    let mut sorted: Vec<(f32, Vec3)> = points
        .iter()
        .map(|p| {
            let d = *p - from;
            (d.dot(other).atan2(d.dot(side)), *p)
        })
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let parts = parts.clamp(1, sorted.len().max(1));
    let mut out = vec![Vec::new(); parts];
    for (i, (_, p)) in sorted.into_iter().enumerate() {
        out[i * parts / points.len()].push(p);
    }
    out.retain(|g| !g.is_empty());
    out
}

pub(super) struct Grower<'a> {
    pub(super) rules: &'a TreeRules,
    pub(super) taper: f32,
    pub(super) branches: Vec<Branch>,
    pub(super) random: Random,
}

impl Grower<'_> {
    pub(super) fn push(&mut self, branch: Branch) -> Result<usize, GenerateError> {
        if self.branches.len() >= MAX_STEMS {
            return Err(GenerateError::Params(ParamsError::Combination(format!(
                "the tree would have more than {MAX_STEMS} stems; lower NumBranchControlPointsOnLobe, \
                 BranchIterations, NumBranchesOffSplit or NumLeafPointsOnLobe, or use fewer lobes"
            ))));
        }
        self.branches.push(branch);
        Ok(self.branches.len() - 1)
    }

    /// The path of a branch from `start` to `end` that leaves along `dir0`: a quadratic curve
    /// in `NumSegmentsInBranch` pieces, each end wandering by `SegmentOffset` (a random walk
    /// pinned to both ends), kept inside `lobe`.
    fn path(&mut self, start: Vec3, dir0: Vec3, end: Vec3, lobe: Option<&Lobe>) -> Vec<Vec3> {
        let n = self.rules.num_segments_in_branch.max(1) as usize;
        let span = start.distance(end);
        let knee = start + dir0 * (0.45 * span);
        let piece = span / n as f32;
        let so = self.rules.segment_offset;
        let mut walk = vec![Vec3::ZERO; n + 1];
        for i in 1..=n {
            let step = Vec3::new(
                self.random.var(so[0]) as f32,
                self.random.var(so[1]) as f32,
                self.random.var(so[2]) as f32,
            ) * piece;
            walk[i] = walk[i - 1] + step;
        }
        let drift = walk[n];
        (0..=n)
            .map(|i| {
                let t = i as f32 / n as f32;
                let curve =
                    start * (1.0 - t) * (1.0 - t) + knee * 2.0 * t * (1.0 - t) + end * t * t;
                if i == 0 || i == n {
                    return curve;
                }
                let p = curve + walk[i] - drift * t;
                match lobe {
                    Some(l) if l.outside(curve, self.taper) <= 0.0 => l.clamp_inside(p, self.taper),
                    _ => p,
                }
            })
            .collect()
    }

    /// Where on the parent's axis `a + s·d` (s in `range`) a branch to `target` leaves at
    /// `angle` from `d`: s = (target − a)·d − ρ / tan(angle), kept in range.
    fn attach(a: Vec3, d: Vec3, range: (f32, f32), target: Vec3, angle: f32) -> f32 {
        let rel = target - a;
        let along = rel.dot(d);
        let rho = (rel - d * along).length();
        let s = if angle.tan().abs() < 1e-4 {
            range.0
        } else {
            along - rho / angle.tan()
        };
        // max/min rather than clamp: a degenerate axis (a NaN length) must not panic.
        s.max(range.0).min(range.1)
    }

    /// Direction leaving axis `d` at `angle`, turned toward `target` from `from`.
    fn leave(d: Vec3, from: Vec3, target: Vec3, angle: f32) -> Vec3 {
        let rel = target - from;
        let perp = rel - d * rel.dot(d);
        let side = perp
            .try_normalize()
            .unwrap_or_else(|| d.any_orthonormal_vector());
        (d * angle.cos() + side * angle.sin()).normalize()
    }

    /// One branch from `start` on a parent running along `d` to `end`, leaving at `angle`.
    #[allow(clippy::too_many_arguments)]
    fn branch(
        &mut self,
        parent: usize,
        d: Vec3,
        start: Vec3,
        end: Vec3,
        angle: f32,
        level: u8,
        lobe_index: usize,
        lobe: &Lobe,
        target: Option<Vec3>,
    ) -> Result<usize, GenerateError> {
        let dir0 = Self::leave(d, start, end, angle);
        let path = self.path(start, dir0, end, Some(lobe));
        self.push(Branch {
            parent: Some(parent),
            kind: Kind::Branch,
            level,
            widths: vec![0.0; path.len()],
            points: path,
            lobe: Some(lobe_index),
            target,
        })
    }

    /// Grows the branches for `points` from the parent axis (a, d, range), `m` generations.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn grow(
        &mut self,
        parent: usize,
        axis: (Vec3, Vec3, (f32, f32)),
        points: Vec<Vec3>,
        m: u32,
        angle: f32,
        level: u8,
        lobe_index: usize,
        lobe: &Lobe,
    ) -> Result<(), GenerateError> {
        let (a, d, range) = axis;
        if m <= 1 || points.len() == 1 {
            // The last generation: one branch onto each control point.
            for p in points {
                let start = a + d * Self::attach(a, d, range, p, angle);
                if start.distance(p) < 1e-5 {
                    continue;
                }
                self.branch(parent, d, start, p, angle, level, lobe_index, lobe, Some(p))?;
            }
            return Ok(());
        }
        let centre = points.iter().copied().sum::<Vec3>() / points.len() as f32;
        let start = a + d * Self::attach(a, d, range, centre, angle);
        // This generation's share of the way: 1 / (1 + LRF + ... + LRF^(m-1)).
        let lrf = self.rules.length_reduction_factor as f32;
        let share = 1.0 / (0..m).map(|i| lrf.powi(i as i32)).sum::<f32>();
        let end = start + (centre - start) * share;
        let index = self.branch(parent, d, start, end, angle, level, lobe_index, lobe, None)?;
        let (n, v) = self.rules.num_branches_off_split;
        let parts = (n as f64 + self.random.var(v as f64 + 0.999))
            .floor()
            .max(1.0) as usize;
        let dir = (end - start).try_normalize().unwrap_or(d);
        let half = (self.rules.subsequent_angle as f32 / 2.0).to_radians();
        let len = start.distance(end);
        for sub in split_around(&points, end, dir, parts) {
            // Later generations start at their parent's end (rule 5).
            self.grow(
                index,
                (start, dir, (len, len)),
                sub,
                m - 1,
                half,
                level + 1,
                lobe_index,
                lobe,
            )?;
        }
        Ok(())
    }
}

/// Widths: the trunk tapers from `TrunkStartWidth` at the ground by `TrunkTaperPercent` over
/// its longest path; each limb (a first branch and all it carries) from `BranchStartWidth` (no
/// wider than the trunk where it starts) by `BranchTaperPercent` over its longest path; twigs
/// from `TwigStartWidth`. Nothing is thinner than `MinBranchWidth`.
pub(super) fn set_widths(rules: &TreeRules, branches: &mut [Branch]) {
    let n = branches.len();
    // Path length from the root of each branch's run (trunk: ground; limb: first branch base).
    let mut base = vec![0.0f32; n];
    let mut root = vec![0usize; n];
    for i in 0..n {
        let b = &branches[i];
        let parent = b.parent.filter(|&p| branches[p].kind == b.kind);
        match parent {
            Some(p) => {
                base[i] = base[p] + length(&branches[p].points);
                root[i] = root[p];
            }
            None => root[i] = i,
        }
    }
    let mut longest = vec![0.0f32; n];
    for i in 0..n {
        let end = base[i] + length(&branches[i].points);
        longest[root[i]] = longest[root[i]].max(end);
    }
    let min = rules.min_branch_width as f32;
    for i in 0..n {
        let (start, taper) = match branches[i].kind {
            Kind::Trunk => (
                rules.trunk_start_width as f32,
                rules.trunk_taper_percent as f32,
            ),
            Kind::Branch => (
                rules.branch_start_width as f32,
                rules.branch_taper_percent as f32,
            ),
            Kind::Twig => (
                rules.twig_start_width as f32,
                rules.branch_taper_percent as f32,
            ),
        };
        // A limb is never wider than what it grows from.
        let start = match branches[root[i]].parent {
            Some(p) if branches[i].kind != Kind::Trunk => {
                let w = &branches[p].widths;
                start.min(w.iter().copied().fold(f32::MAX, f32::min).max(min) * 2.0)
            }
            _ => start,
        };
        let total = longest[root[i]].max(1e-6);
        let mut along = base[i];
        let points = branches[i].points.clone();
        let widths = &mut branches[i].widths;
        for (k, w) in widths.iter_mut().enumerate() {
            if k > 0 {
                along += points[k].distance(points[k - 1]);
            }
            *w = (start * (1.0 - (1.0 - taper) * along / total)).max(min);
        }
    }
}

pub(super) fn length(points: &[Vec3]) -> f32 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

impl LobeTree {
    /// Stage 6: the stems as a skeleton (widths become radii), with the leaves.
    pub fn skeleton(&self) -> Skeleton {
        let mut skeleton = Skeleton::default();
        for b in &self.branches {
            let radii: Vec<f32> = b.widths.iter().map(|w| 0.5 * w).collect();
            skeleton.push_polyline(
                &b.points,
                &radii,
                b.level,
                b.parent.map(|p| StemId(p as u32)),
            );
        }
        skeleton.leaves = self.leaves.clone();
        skeleton
    }
}
