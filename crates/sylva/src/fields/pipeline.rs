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

use super::lobe::{Lobe, LobeShape};
use super::rules::{Crown, TreeRules};
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
    /// The species' lobe shape (LeafTaper and stretch).
    pub shape: LobeShape,
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
    /// Height of the highest lobe's top: the tree's height as placed.
    pub fn height(&self, shape: LobeShape) -> f32 {
        self.lobes
            .iter()
            .map(|l| l.centre.z + l.half_height(shape))
            .chain(self.trunks.iter().map(|t| t.end.z.max(t.start.z)))
            .fold(0.0, f32::max)
    }

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
/// ground and the lobes above them. A species that gives its mature crown gets that crown,
/// filled with its number of lobes; otherwise one lobe of the layout's radius (the paper's).
pub fn auto_placement(rules: &TreeRules, seed: u64) -> Placement {
    let base = rules.layout.crown_base as f32;
    let lobes = match &rules.layout.crown {
        Some(crown) => crown_lobes(crown, base, LobeShape::of(rules), seed),
        None => {
            let r = rules.layout.lobe_radius as f32;
            vec![Lobe {
                centre: Vec3::new(0.0, 0.0, base + r),
                radius: r,
            }]
        }
    };
    placement_for_lobes(rules, seed, lobes)
}

/// Lobes that fill a mature crown from `base` to its height and across its width, as a user
/// would place them: one crowning the top and the rest round the sides, alternately low (their
/// bottoms on the crown base) and halfway up, each turned and sized a little differently per
/// seed, so the outline is irregular. A crown of one lobe is that lobe, stretched to fit.
fn crown_lobes(crown: &Crown, base: f32, shape: LobeShape, seed: u64) -> Vec<Lobe> {
    let (height, half_width) = (crown.height as f32, 0.5 * crown.width as f32);
    if crown.lobes <= 1 {
        let radius = half_width / shape.widest();
        return vec![Lobe {
            centre: Vec3::new(0.0, 0.0, base + radius * shape.stretch),
            radius,
        }];
    }
    let mut random = StreamKey::from_seed(seed).child(6).stream();
    let size = |random: &mut Random| 0.5 * half_width * (1.0 + random.var(0.1) as f32);
    let r = size(&mut random).min(0.5 * (height - base));
    let nudge = 0.1 * half_width;
    let mut lobes = vec![Lobe {
        centre: Vec3::new(
            random.var(nudge as f64) as f32,
            random.var(nudge as f64) as f32,
            height - r,
        ),
        radius: r,
    }];
    let around = crown.lobes as usize - 1;
    let turn = random.unit() as f32 * TAU;
    for i in 0..around {
        let r = size(&mut random).min(0.5 * (height - base));
        let bearing = turn + TAU * (i as f32 + random.var(0.15) as f32) / around as f32;
        let out = (half_width - r * shape.widest()).max(0.0) + random.var(nudge as f64) as f32;
        let z = if i % 2 == 0 {
            base + r
        } else {
            0.5 * (base + height) + random.var(0.5 * nudge as f64) as f32
        };
        lobes.push(Lobe {
            centre: Vec3::new(out * bearing.cos(), out * bearing.sin(), z.max(base + r)),
            radius: r,
        });
    }
    // Bottom up: stage 3 connects each lobe to the nearest trunk end made so far, so the low
    // lobes' limbs leave the trunk and the higher ones fork from them, as an oak's limbs do.
    lobes.sort_by(|a, b| a.centre.z.total_cmp(&b.centre.z));
    lobes
}

/// Stage 1 for lobes the user placed: trunk iterations reaching 90% of the way to the lowest
/// lobe's bottom.
pub fn placement_for_lobes(rules: &TreeRules, seed: u64, lobes: Vec<Lobe>) -> Placement {
    let shape = LobeShape::of(rules);
    let lowest = lobes
        .iter()
        .map(|l| l.centre.z - l.half_height(shape))
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
    pub(super) shape: LobeShape,
    /// What the width rules are multiplied by for this tree (see `set_widths`).
    pub(super) width_scale: f32,
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
                    Some(l) if l.outside(curve, self.shape) <= 0.0 => l.clamp_inside(p, self.shape),
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
        // N ± V: a whole number from -V to V added (rounding toward zero keeps V = 0 exact; the
        // oak's "2" once came out as 1 half the time).
        let parts = (n as f64 + self.random.var(v as f64 + 0.999).trunc()).max(1.0) as usize;
        let dir = (end - start).try_normalize().unwrap_or(d);
        let len = start.distance(end);
        for sub in split_around(&points, end, dir, parts) {
            // Section 4.1.1 reads the oak's render as children "rotated 45 degrees apart": the
            // children of a split stand BranchAngle apart, half of it each side of their
            // parent, while the appendix gives SubsequentAngle 15. Sylva follows the render
            // and lets SubsequentAngle vary each child's half by up to half of it, so the
            // pairs are not all alike.
            let half = (0.5 * self.rules.branch_angle as f32
                + 0.5 * self.random.var(self.rules.subsequent_angle) as f32)
                .to_radians();
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
