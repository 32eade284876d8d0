//! Stage 5 of Fields' pipeline: leaves, made as the species' `CreateLeaves` rule says, on twigs
//! that join them to the branches (adding leaves adds stems, as the report notes).
//!
//! The paper leaves leaf placement to each species. Sylva's three styles fill the outer part of
//! each lobe, not only its skin: an oak's clusters sit on sprays all along the branches and
//! twigs that run through the lobe's outer half toward its leaf points; a fir's shoots line its
//! branches, the branchlets they carry and short branchlets between the whorls; a weeping
//! cherry's blossoms hang on strands falling along the lobe's surface. How many leaves a lobe
//! gets follows from its surface: laid flat, they would cover seven tenths of it
//! ([`LEAF_COVER`]).

use super::lobe::{Lobe, LobeShape};
use super::pipeline::{Branch, Grower, Kind, MAX_LEAVES, length, rotate_away};
use super::rules::{LeafStyle, TreeRules};
use super::widths::set_widths;
use crate::error::{GenerateError, ParamsError};
use crate::rng::Random;
use crate::skeleton::{Leaf, StemId};
use glam::{Mat3, Quat, Vec3};
use std::f32::consts::{PI, TAU};

/// Leaf area over lobe surface: laid flat, a lobe's leaves would cover this share of it.
/// Spread through the outer half of the lobe, they leave gaps the eye reads as depth.
pub const LEAF_COVER: f32 = 0.7;

/// How deep into a lobe leaves reach, as a fraction of the way from its outline to its axis.
const OUTER_PART: f32 = 0.5;

/// A leaf frame: blade along `dir`, its face as near to `up` as the blade allows.
fn frame(dir: Vec3, up: Vec3) -> Quat {
    let z = dir.try_normalize().unwrap_or(Vec3::Z);
    let x = up
        .cross(z)
        .try_normalize()
        .unwrap_or_else(|| z.any_orthonormal_vector());
    let y = z.cross(x);
    Quat::from_mat3(&Mat3::from_cols(x, y, z))
}

/// The nearest point to `p` on any branch (not trunk) grown in `lobe`, as (branch, point); on
/// any stem if that lobe has no branches. Keeping to the lobe's own branches keeps a twig from
/// crossing the gap between two lobes.
fn nearest_on_branches(branches: &[Branch], p: Vec3, lobe: usize) -> Option<(usize, Vec3)> {
    nearest_on(branches, p, |b| {
        b.kind == Kind::Branch && b.lobe == Some(lobe)
    })
}

/// The nearest point to `p` on any stem `mine` accepts; on any stem if it accepts none.
fn nearest_on(
    branches: &[Branch],
    p: Vec3,
    mine: impl Fn(&Branch) -> bool,
) -> Option<(usize, Vec3)> {
    let mut best: Option<(usize, Vec3, f32)> = None;
    let any_branch = branches.iter().any(&mine);
    for (i, b) in branches.iter().enumerate() {
        if any_branch && !mine(b) {
            continue;
        }
        for w in b.points.windows(2) {
            let ab = w[1] - w[0];
            let t = ((p - w[0]).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
            let q = w[0] + ab * t;
            let d = q.distance_squared(p);
            if best.is_none_or(|(_, _, bd)| d < bd) {
                best = Some((i, q, d));
            }
        }
    }
    best.map(|(i, q, _)| (i, q))
}

/// Puts leaves, under the tree's leaf budget, shaded by how deep in their lobe they sit.
struct Planter<'a> {
    leaves: &'a mut Vec<Leaf>,
    size: f32,
    aspect: f32,
    look: crate::skeleton::LeafShape,
}

impl Planter<'_> {
    fn put(&mut self, at: Vec3, dir: Vec3, stem: usize, depth: f32) -> Result<(), GenerateError> {
        self.put_facing(at, dir, Vec3::Z, stem, depth)
    }

    /// A leaf whose face turns as near to `up` as its blade allows.
    fn put_facing(
        &mut self,
        at: Vec3,
        dir: Vec3,
        up: Vec3,
        stem: usize,
        depth: f32,
    ) -> Result<(), GenerateError> {
        if self.leaves.len() >= MAX_LEAVES {
            return Err(GenerateError::Params(ParamsError::Combination(format!(
                "the tree would have more than {MAX_LEAVES} leaves; raise leaf_size in [layout] \
                 or use smaller or fewer lobes"
            ))));
        }
        self.leaves.push(Leaf {
            position: at,
            orientation: frame(dir, up),
            length: self.size,
            width: self.size * self.aspect,
            shape: self.look,
            stem: StemId(stem as u32),
            // Leaves deeper in the crown see less of the sky.
            light: (1.0 - 0.6 * (depth / OUTER_PART).clamp(0.0, 1.0)).clamp(0.3, 1.0),
        });
        Ok(())
    }
}

/// The lobe's surface area: Thomsen's formula for a spheroid (within about 1%).
fn surface(lobe: &Lobe, shape: LobeShape) -> f32 {
    let (a, c) = (lobe.radius, lobe.half_height(shape));
    let p = 1.6075f32;
    let mean = (a.powf(2.0 * p) + 2.0 * a.powf(p) * c.powf(p)) / 3.0;
    4.0 * PI * mean.powf(1.0 / p)
}

/// Leaves a lobe should carry (see [`LEAF_COVER`]).
fn wanted_in(rules: &TreeRules, lobe: &Lobe, shape: LobeShape) -> usize {
    let size = rules.layout.leaf_size as f32;
    let leaf_area = 0.6 * size * size * rules.leaf_texture.aspect;
    (LEAF_COVER * surface(lobe, shape) / leaf_area.max(1e-9)) as usize
}

/// Stage 5, by the species' `CreateLeaves` rule.
pub(super) fn add_leaves(
    rules: &TreeRules,
    lobes: &[Lobe],
    leaf_points: &[Vec<Vec3>],
    shape: LobeShape,
    g: &mut Grower,
    leaves: &mut Vec<Leaf>,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let look = rules.leaf_texture;
    let mut planter = Planter {
        leaves,
        size: rules.layout.leaf_size as f32,
        aspect: look.aspect,
        look: look.shape,
    };
    let twig_level = g.branches.iter().map(|b| b.level).max().unwrap_or(0) + 1;
    match rules.create_leaves {
        LeafStyle::Needles => needles(g, &mut planter, lobes, shape, twig_level, random)?,
        LeafStyle::Clusters => {
            for (li, lobe) in lobes.iter().enumerate() {
                clusters(
                    g,
                    &mut planter,
                    (li, lobe),
                    &leaf_points[li],
                    shape,
                    twig_level,
                    wanted_in(rules, lobe, shape),
                    random,
                )?;
            }
        }
        LeafStyle::Hanging => hanging(
            g,
            &mut planter,
            (lobes, shape),
            leaf_points,
            twig_level,
            random,
        )?,
    }
    if rules.create_leaves == LeafStyle::Needles {
        // Sprays toward the leaf points fill what the branches' shoots leave of each lobe.
        let placed = planter.leaves.len() / lobes.len().max(1);
        for (li, lobe) in lobes.iter().enumerate() {
            let points = &leaf_points[li];
            let wanted = wanted_in(rules, lobe, shape).saturating_sub(placed) / points.len().max(1);
            for &p in points {
                let Some((from, q)) = nearest_on_branches(&g.branches, p, li) else {
                    continue;
                };
                let end = q.lerp(p, 0.85);
                if q.distance(end) < 1e-4 {
                    continue;
                }
                let twig = g.push(twig(from, twig_level, vec![q, q.lerp(end, 0.5), end]))?;
                let reach = 0.35 * lobe.radius;
                spray(
                    g,
                    &mut planter,
                    (twig, end),
                    (lobe, shape),
                    reach,
                    twig_level + 1,
                    wanted.min(2000),
                    random,
                )?;
            }
        }
    }
    let widths_needed = g
        .branches
        .iter()
        .any(|b| b.widths.iter().all(|w| *w == 0.0));
    if widths_needed {
        set_widths(rules, g.width_scale, &mut g.branches);
    }
    Ok(())
}

fn twig(parent: usize, level: u8, points: Vec<Vec3>) -> Branch {
    Branch {
        parent: Some(parent),
        kind: Kind::Twig,
        level,
        widths: vec![0.0; points.len()],
        points,
        lobe: None,
        target: None,
    }
}

/// Points every `step` metres along `points` where the lobe is no deeper than the outer part,
/// with the direction of travel and the depth there.
fn sites_along(
    points: &[Vec3],
    step: f32,
    lobe: &Lobe,
    shape: LobeShape,
) -> Vec<(Vec3, Vec3, f32)> {
    let mut out = Vec::new();
    let mut next = 0.5 * step;
    let mut along = 0.0;
    for w in points.windows(2) {
        let piece = w[0].distance(w[1]);
        let dir = (w[1] - w[0]) / piece.max(1e-9);
        while next <= along + piece {
            let at = w[0] + dir * (next - along);
            let depth = lobe.depth(at, shape);
            if (0.0..=OUTER_PART).contains(&depth) {
                out.push((at, dir, depth));
            }
            next += step;
        }
        along += piece;
    }
    out
}

/// Oak clusters: a twig from the nearest branch toward each leaf point, then sprays of short
/// twigs all along the lobe's branches and those twigs, wherever they run through the lobe's
/// outer part, until the lobe carries `wanted` leaves.
#[allow(clippy::too_many_arguments)]
fn clusters(
    g: &mut Grower,
    planter: &mut Planter,
    (li, lobe): (usize, &Lobe),
    points: &[Vec3],
    shape: LobeShape,
    level: u8,
    wanted: usize,
    random: &mut Random,
) -> Result<(), GenerateError> {
    for &p in points {
        let Some((from, q)) = nearest_on_branches(&g.branches, p, li) else {
            continue;
        };
        let end = q.lerp(p, 0.9);
        if q.distance(end) > 1e-4 {
            let mut t = twig(from, level, vec![q, q.lerp(end, 0.5), end]);
            t.lobe = Some(li);
            g.push(t)?;
        }
    }
    // Sites along every branch and twig of the lobe where it runs through the outer part.
    let step = 0.06 * lobe.radius;
    let mut sites = Vec::new();
    for (i, b) in g.branches.iter().enumerate() {
        if b.lobe == Some(li) && b.kind != Kind::Trunk {
            for s in sites_along(&b.points, step, lobe, shape) {
                sites.push((i, s));
            }
        }
    }
    if sites.is_empty() {
        return Ok(());
    }
    let reach = 0.16 * lobe.radius;
    let per_site = wanted.div_ceil(sites.len());
    for (stem, (at, _, _)) in sites {
        spray(
            g,
            planter,
            (stem, at),
            (lobe, shape),
            reach,
            level + 1,
            per_site,
            random,
        )?;
    }
    Ok(())
}

/// Short twigs from `at` (on stem `from`) into the space around it, within `reach`, with leaves
/// in pairs along each, until they carry `wanted` leaves.
#[allow(clippy::too_many_arguments)]
fn spray(
    g: &mut Grower,
    planter: &mut Planter,
    (from, at): (usize, Vec3),
    (lobe, shape): (&Lobe, LobeShape),
    reach: f32,
    level: u8,
    wanted: usize,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let size = planter.size;
    let mut placed = 0;
    for _ in 0..200 {
        if placed >= wanted {
            break;
        }
        let offset = Vec3::new(
            random.var(1.0) as f32,
            random.var(1.0) as f32,
            random.var(1.0) as f32,
        ) * reach;
        let tip = lobe.clamp_inside(at + offset, shape);
        if tip.distance(at) < (2.5 * size).min(0.5 * reach) {
            continue;
        }
        let fork = g.push(twig(from, level, vec![at, tip]))?;
        let len = at.distance(tip);
        let dir = (tip - at) / len;
        let count = ((len / (0.5 * size)) as usize).min(wanted - placed);
        for k in 0..count {
            let p = at + dir * (len * (k as f32 + 0.5) / count as f32);
            let turn = random.unit() as f32 * TAU;
            let depth = lobe.depth(p, shape).max(0.0);
            for side in [0.0, PI] {
                planter.put(p, rotate_away(dir, 0.9, turn + side), fork, depth)?;
                placed += 1;
            }
        }
    }
    Ok(())
}

/// A fir's foliage: every branch carries shoots in two ranks and a rising row along its whole
/// length, and branchlets, alternating and angled forward, that carry shoots of their own
/// (Abies branches are flat, pinnately branched sprays); short internodal branchlets fill the
/// trunk between the whorls.
fn needles(
    g: &mut Grower,
    planter: &mut Planter,
    lobes: &[Lobe],
    shape: LobeShape,
    level: u8,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let size = planter.size;
    let shoots = |g: &mut Grower,
                  planter: &mut Planter,
                  stem: usize,
                  points: &[Vec3],
                  from: f32,
                  random: &mut Random|
     -> Result<(), GenerateError> {
        let total = length(points);
        let mut along = 0.0;
        let mut next = from * total;
        let lobe = g.branches[stem].lobe.map(|l| lobes[l]);
        for w in points.windows(2) {
            let piece = w[0].distance(w[1]);
            let dir = (w[1] - w[0]).try_normalize().unwrap_or(Vec3::X);
            let flat = dir.cross(Vec3::Z).try_normalize().unwrap_or(Vec3::X);
            while next <= along + piece {
                let at = w[0] + dir * (next - along);
                let depth = lobe.map_or(0.0, |l| l.depth(at, shape).max(0.0));
                for side in [-1.0f32, 1.0] {
                    // Forward and out to one side, tilted up or down and rolled about their
                    // own axis: a fir's sprays are flat near the tips, but a branch carries
                    // them at every angle, so the crown looks dense from the side too.
                    let out =
                        (dir * 0.55 + flat * side + Vec3::Z * random.var(0.7) as f32).normalize();
                    let roll = Quat::from_axis_angle(out, 1.3 * random.var(1.0) as f32);
                    planter.put_facing(at, out, roll * Vec3::Z, stem, depth)?;
                }
                // And one rising from the top of the stem, face to the side: seen end-on, a
                // branch pointing at the viewer is hidden by these, not only flanked by the
                // two ranks (Abies shoots turn up toward the light).
                let out = (dir * 0.5 + Vec3::Z * 0.8 + flat * random.var(0.5) as f32).normalize();
                planter.put_facing(at, out, flat, stem, depth)?;
                next += 0.25 * size;
            }
            along += piece;
        }
        Ok(())
    };
    // A straight branchlet of `(parent, lobe)` from `at` to `tip`, lined with shoots from `from`
    // of its length; none shorter than a shoot.
    let branchlet = |g: &mut Grower,
                     planter: &mut Planter,
                     (parent, lobe): (usize, Option<usize>),
                     (at, tip): (Vec3, Vec3),
                     from: f32,
                     random: &mut Random|
     -> Result<(), GenerateError> {
        if tip.distance(at) < size {
            return Ok(());
        }
        let mut t = twig(parent, level, vec![at, tip]);
        t.lobe = lobe;
        let index = g.push(t)?;
        shoots(g, planter, index, &[at, tip], from, random)
    };
    let firsts: Vec<usize> = (0..g.branches.len())
        .filter(|&i| g.branches[i].kind == Kind::Branch)
        .collect();
    // The leader: shoots all round the trunk where the cone is too narrow for branches.
    for i in 0..g.branches.len() {
        if g.branches[i].kind != Kind::Trunk {
            continue;
        }
        let points = g.branches[i].points.clone();
        for (lobe, k) in lobes.iter().zip(0..) {
            let step = 0.3 * size;
            for (at, dir, _) in sites_along(&points, step, lobe, shape) {
                if lobe.reach(at.z - lobe.centre.z, shape) > 2.5 * size {
                    continue;
                }
                let turn = (k as f32 + at.z / step) * 2.4;
                planter.put(at, rotate_away(dir, 1.0, turn), i, 0.0)?;
            }
        }
        // Internodal branchlets: Abies grows short branches between its whorls as well. The
        // paper's 55 control points give a whorl every 0.7 m of a 15 m fir, and without these
        // the trunk shows through every gap between the tiers, which a fir's crown never does.
        let total = length(&points);
        let mut s = 0.5 * size;
        while s < total {
            let at = point_at(&points, s);
            let up = (point_at(&points, s + 0.1) - at)
                .try_normalize()
                .unwrap_or(Vec3::Z);
            s += 0.8 * size * (1.0 + random.var(0.3) as f32);
            for (li, lobe) in lobes.iter().enumerate() {
                let reach = lobe.reach(at.z - lobe.centre.z, shape);
                if lobe.outside(at, shape) > 0.0 || reach <= 2.5 * size {
                    continue;
                }
                // Out at the whorl branches' 20 degrees above the perpendicular, a golden turn
                // from the last, 40-70% as long as the crown reaches there.
                let turn = s / size * 2.4;
                let way = rotate_away(up, 70f32.to_radians(), turn);
                let len = reach * (0.4 + 0.3 * random.unit() as f32);
                let tip = lobe.clamp_inside(at + way * len, shape);
                branchlet(g, planter, (i, Some(li)), (at, tip), 0.05, random)?;
            }
        }
    }
    for i in firsts {
        let points = g.branches[i].points.clone();
        shoots(g, planter, i, &points, 0.0, random)?;
        // Branchlets, alternately left and right and shorter toward the branch's tip.
        let total = length(&points);
        let gap = 0.25 * size;
        let mut s = 0.12 * total;
        let mut side = if random.unit() < 0.5 { -1.0f32 } else { 1.0 };
        while s < total - gap {
            let at = point_at(&points, s);
            let dir = (point_at(&points, s + 0.5 * gap) - at)
                .try_normalize()
                .unwrap_or(Vec3::X);
            let flat = dir.cross(Vec3::Z).try_normalize().unwrap_or(Vec3::X);
            let len = (0.6 * (total - s)).min(2.5 * size);
            let way = (dir * 0.8 + flat * side * 0.75 + Vec3::Z * (random.var(0.35) as f32 - 0.1))
                .normalize();
            let mut tip = at + way * len;
            if let Some(l) = g.branches[i].lobe {
                tip = lobes[l].clamp_inside(tip, shape);
            }
            let lobe = g.branches[i].lobe;
            branchlet(g, planter, (i, lobe), (at, tip), 0.25, random)?;
            side = -side;
            s += gap * (1.0 + random.var(0.2) as f32);
        }
    }
    Ok(())
}

/// A weeping cherry's strands: from the lobe's upper part each falls along its surface to a
/// leaf point, blossoms hanging along it.
fn hanging(
    g: &mut Grower,
    planter: &mut Planter,
    (lobes, shape): (&[Lobe], LobeShape),
    leaf_points: &[Vec<Vec3>],
    level: u8,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let size = planter.size;
    for (li, pts) in leaf_points.iter().enumerate() {
        let lobe = lobes[li];
        // Three strands fall toward each leaf point, a little apart: a weeping cherry's
        // pendulous shoots hang in curtains, not one by one.
        let strands = pts.iter().flat_map(|&p| {
            let d = p - lobe.centre;
            [-0.12f32, 0.0, 0.12].map(move |turn| (d, d.y.atan2(d.x) + turn))
        });
        for (d, bearing) in strands.collect::<Vec<_>>() {
            let polar_end = (d.z / lobe.half_height(shape)).clamp(-1.0, 1.0).acos();
            let polar_start = 0.35f32.min(polar_end);
            let on = |polar: f32| {
                // Along the surface down to the widest circle, then nearly straight down: a
                // strand hangs, it does not curl back under the crown.
                let r = 0.97 * lobe.radius;
                let out = if polar <= 0.5 * PI {
                    r * polar.sin()
                } else {
                    r * (1.0 - 0.12 * (polar - 0.5 * PI))
                };
                lobe.centre
                    + Vec3::new(
                        out * bearing.cos(),
                        out * bearing.sin(),
                        r * polar.cos() * shape.stretch,
                    )
            };
            let top = on(polar_start);
            // From the lobe's branches or the trunk through it, whichever is nearer: a strand
            // arches out of the crown's top, not across it from a low branch's end.
            let near = |b: &Branch| {
                b.kind == Kind::Trunk || (b.kind == Kind::Branch && b.lobe == Some(li))
            };
            let Some((from, q)) = nearest_on(&g.branches, top, near) else {
                continue;
            };
            let mut strand = vec![q];
            let steps = 10;
            for k in 0..=steps {
                let polar = polar_start + (polar_end - polar_start) * k as f32 / steps as f32;
                let mut s = on(polar);
                s.x += random.var(0.02 * lobe.radius as f64) as f32;
                s.y += random.var(0.02 * lobe.radius as f64) as f32;
                if strand.last().is_some_and(|l: &Vec3| l.distance(s) > 1e-4) {
                    strand.push(s);
                }
            }
            if strand.len() < 2 {
                continue;
            }
            let mut t = twig(from, level, strand.clone());
            t.lobe = Some(li);
            let index = g.push(t)?;
            // Blossoms along the falling part, hanging.
            let total = length(&strand[1..]);
            let count = ((total / (0.8 * size)) as usize).max(1);
            for k in 0..count {
                let t = (k as f32 + 0.5) / count as f32;
                let at = point_at(&strand[1..], t * total);
                let dir = Vec3::new(random.var(0.5) as f32, random.var(0.5) as f32, -1.0);
                planter.put(at, dir, index, 0.0)?;
            }
        }
    }
    Ok(())
}

fn point_at(points: &[Vec3], mut s: f32) -> Vec3 {
    for w in points.windows(2) {
        let l = w[0].distance(w[1]);
        if s <= l {
            return w[0].lerp(w[1], s / l.max(1e-9));
        }
        s -= l;
    }
    *points.last().unwrap()
}
