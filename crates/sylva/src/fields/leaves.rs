//! Stage 5 of Fields' pipeline: leaves, made as the species' `CreateLeaves` rule says, on twigs
//! that join them to the branches (adding leaves adds stems, as the report notes).

use super::lobe::Lobe;
use super::pipeline::{Branch, Grower, Kind, MAX_LEAVES, length, rotate_away, set_widths};
use super::rules::{LeafStyle, TreeRules};
use crate::error::{GenerateError, ParamsError};
use crate::rng::Random;
use crate::skeleton::{Leaf, StemId};
use glam::{Mat3, Quat, Vec3};
use std::f32::consts::TAU;

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

/// The nearest point on any branch (not trunk) to `p`, as (branch, point); the trunk if there
/// are no branches.
fn nearest_on_branches(branches: &[Branch], p: Vec3) -> Option<(usize, Vec3)> {
    let mut best: Option<(usize, Vec3, f32)> = None;
    let any_branch = branches.iter().any(|b| b.kind == Kind::Branch);
    for (i, b) in branches.iter().enumerate() {
        if any_branch && b.kind != Kind::Branch {
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

/// Stage 5, by the species' `CreateLeaves` rule.
pub(super) fn add_leaves(
    rules: &TreeRules,
    lobes: &[Lobe],
    leaf_points: &[Vec<Vec3>],
    taper: f32,
    g: &mut Grower,
    leaves: &mut Vec<Leaf>,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let look = rules.leaf_texture;
    let size = rules.layout.leaf_size as f32;
    let mut put = |leaves: &mut Vec<Leaf>, at: Vec3, dir: Vec3, stem: usize| {
        if leaves.len() >= MAX_LEAVES {
            return Err(GenerateError::Params(ParamsError::Combination(format!(
                "the tree would have more than {MAX_LEAVES} leaves; raise leaf_size in [layout] \
                 or use smaller or fewer lobes"
            ))));
        }
        leaves.push(Leaf {
            position: at,
            orientation: frame(dir, Vec3::Z),
            length: size,
            width: size * look.aspect,
            shape: look.shape,
            stem: StemId(stem as u32),
            light: 1.0,
        });
        Ok(())
    };
    let twig_level = g.branches.iter().map(|b| b.level).max().unwrap_or(0) + 1;
    match rules.create_leaves {
        LeafStyle::Needles => {
            // Needles in pairs all along every branch's outer two thirds.
            let spacing = 0.5 * size;
            for i in 0..g.branches.len() {
                if g.branches[i].kind != Kind::Branch {
                    continue;
                }
                let points = g.branches[i].points.clone();
                let total = length(&points);
                let mut along = 0.0;
                let mut next = total / 3.0;
                for w in points.windows(2) {
                    let piece = w[0].distance(w[1]);
                    let dir = (w[1] - w[0]).try_normalize().unwrap_or(Vec3::X);
                    while next <= along + piece {
                        let at = w[0] + dir * (next - along);
                        for side in [-1.0f32, 1.0] {
                            let out = rotate_away(dir, 0.8, side * 1.4 + random.var(0.3) as f32);
                            put(leaves, at, out, i)?;
                        }
                        next += spacing;
                    }
                    along += piece;
                }
            }
        }
        LeafStyle::Clusters => {}
        LeafStyle::Hanging => {
            // Strands from the lobe's upper part fall along its surface to each leaf point.
            for (li, pts) in leaf_points.iter().enumerate() {
                let lobe = lobes[li];
                for &p in pts {
                    let d = p - lobe.centre;
                    let bearing = d.y.atan2(d.x);
                    let polar_end = (d.z / lobe.radius).clamp(-1.0, 1.0).acos();
                    let polar_start = 0.35f32.min(polar_end);
                    let on = |polar: f32| {
                        let r = 0.97 * lobe.radius;
                        lobe.centre
                            + Vec3::new(
                                r * polar.sin() * bearing.cos(),
                                r * polar.sin() * bearing.sin(),
                                r * polar.cos(),
                            )
                    };
                    let top = on(polar_start);
                    let Some((from, q)) = nearest_on_branches(&g.branches, top) else {
                        continue;
                    };
                    let mut strand = vec![q];
                    let steps = 10;
                    for k in 0..=steps {
                        let polar =
                            polar_start + (polar_end - polar_start) * k as f32 / steps as f32;
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
                    let index = g.push(Branch {
                        parent: Some(from),
                        kind: Kind::Twig,
                        level: twig_level,
                        widths: vec![0.0; strand.len()],
                        points: strand.clone(),
                        lobe: Some(li),
                        target: None,
                    })?;
                    // Blossoms along the falling part, hanging.
                    let total = length(&strand[1..]);
                    let count = ((total / (1.2 * size)) as usize).max(1);
                    for k in 0..count {
                        let t = (k as f32 + 0.5) / count as f32;
                        let at = point_at(&strand[1..], t * total);
                        let dir = Vec3::new(random.var(0.5) as f32, random.var(0.5) as f32, -1.0);
                        put(leaves, at, dir, index)?;
                    }
                }
            }
        }
    }
    if rules.create_leaves != LeafStyle::Hanging {
        // Sprays toward the leaf points fill what needles on the branches leave of the lobe's
        // surface (all of it, for clusters).
        let placed = leaves.len();
        for (li, pts) in leaf_points.iter().enumerate() {
            let wanted = wanted_per_point(rules, &lobes[li], pts.len(), placed / lobes.len());
            for &p in pts {
                spray(
                    g, leaves, &mut put, p, &lobes[li], taper, twig_level, wanted, size, random,
                )?;
            }
        }
    }
    let widths_needed = g
        .branches
        .iter()
        .any(|b| b.widths.iter().all(|w| *w == 0.0));
    if widths_needed {
        set_widths(rules, &mut g.branches);
    }
    Ok(())
}

/// Leaves each leaf point's spray should carry so that the lobe's leaves, laid flat, cover its
/// sphere's surface about once and a half (a crown the eye reads as full), less `already` placed.
fn wanted_per_point(rules: &TreeRules, lobe: &Lobe, points: usize, already: usize) -> usize {
    let size = rules.layout.leaf_size as f32;
    let leaf_area = 0.6 * size * size * rules.leaf_texture.aspect;
    let surface = 4.0 * std::f32::consts::PI * lobe.radius * lobe.radius;
    let total = (1.5 * surface / leaf_area.max(1e-9)) as usize;
    (total.saturating_sub(already) / points.max(1)).min(2000)
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

/// A leaf spray toward leaf point `p`: a twig from the nearest branch to just inside `p`, and
/// short twigs from its end into the space around it, leaves in pairs along each, until it
/// carries `wanted` leaves.
#[allow(clippy::too_many_arguments)]
fn spray(
    g: &mut Grower,
    leaves: &mut Vec<Leaf>,
    put: &mut impl FnMut(&mut Vec<Leaf>, Vec3, Vec3, usize) -> Result<(), GenerateError>,
    p: Vec3,
    lobe: &Lobe,
    taper: f32,
    level: u8,
    wanted: usize,
    size: f32,
    random: &mut Random,
) -> Result<(), GenerateError> {
    let Some((from, q)) = nearest_on_branches(&g.branches, p) else {
        return Ok(());
    };
    let end = q.lerp(p, 0.85);
    if q.distance(end) < 1e-4 {
        return Ok(());
    }
    let twig = g.push(Branch {
        parent: Some(from),
        kind: Kind::Twig,
        level,
        widths: vec![0.0; 3],
        points: vec![q, q.lerp(end, 0.5), end],
        lobe: None,
        target: None,
    })?;
    // Spray as far as leaf points lie apart on the lobe, so neighbouring sprays meet.
    let reach = 0.35 * lobe.radius;
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
        let tip = lobe.clamp_inside(end + offset, taper);
        if tip.distance(end) < 2.0 * size {
            continue;
        }
        let fork = g.push(Branch {
            parent: Some(twig),
            kind: Kind::Twig,
            level: level + 1,
            widths: vec![0.0; 2],
            points: vec![end, tip],
            lobe: None,
            target: None,
        })?;
        let len = end.distance(tip);
        let dir = (tip - end) / len;
        let count = (len / (0.6 * size)) as usize;
        for k in 0..count {
            let at = end + dir * (len * (k as f32 + 0.5) / count as f32);
            let turn = random.unit() as f32 * TAU;
            for side in [0.0, std::f32::consts::PI] {
                put(leaves, at, rotate_away(dir, 0.9, turn + side), fork)?;
                placed += 1;
            }
        }
    }
    Ok(())
}
