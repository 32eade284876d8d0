//! Measures of a tree's form (growth-architecture spec section 5): what separates a plane from a
//! coat rack when the five survey dimensions agree. They read only the Skeleton, so any model's
//! tree can be measured.

use crate::skeleton::{Skeleton, StemId};
use glam::Vec3;

/// A tree's form, measured.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FormMeasures {
    /// Share of the leaf area within half the crown radius of the trunk's vertical axis, 0..1
    /// (an evenly filled ellipsoid: 0.35; a shell of foliage: near 0).
    pub inner_leaf_share: f64,
    /// Woody axes crossing a plane a third or half way up the crown (whichever has more) with
    /// at least two-thirds of the largest radius there (codominant: arborists call stems of
    /// about the trunk's diameter codominant, and keep side branches under half of it) that
    /// carry the crown to its top quarter: 1 for a tree that keeps its leader, 2 or more where
    /// the trunk has forked into codominant limbs, 0 for a palm (nothing woody in its crown).
    pub leaders: usize,
    /// Median angle above the horizontal of the first metre of each branch leaving the trunk,
    /// degrees (`None` without branches).
    pub scaffold_angle: Option<f64>,
    /// The pipe-model exponent n (parent^n = sum of children^n) fitted at the forks, median of
    /// the forks where one exists (`None` without forks).
    pub pipe_exponent: Option<f64>,
}

/// Measures the form of a skeleton whose first stem is the trunk, standing at the origin, with
/// its crown from `crown_base` to `top` metres and `crown_diameter` metres across (as
/// [`crate::growth::measure()`] finds them). The form is the crown's frame: a grown tree's short twigs
/// (its [`Skeleton::short_twigs`]) are no leaders, scaffolds or forks of the pipe model.
pub fn measure_form(
    skeleton: &Skeleton,
    crown_base: f64,
    top: f64,
    crown_diameter: f64,
) -> FormMeasures {
    // Every measure below walks the frame's stems alone (`Skeleton::frame_stems`: the twigs
    // are the last stems, so the frame's ids and sections are the whole skeleton's), and the
    // tree is not copied to drop its twigs.
    FormMeasures {
        inner_leaf_share: inner_leaf_share(skeleton, crown_diameter as f32 / 2.0),
        leaders: leaders(skeleton, crown_base as f32, top as f32),
        scaffold_angle: median(scaffold_angles(skeleton)),
        pipe_exponent: median(fork_exponents(skeleton)),
    }
}

fn inner_leaf_share(skeleton: &Skeleton, crown_radius: f32) -> f64 {
    let (mut inner, mut total) = (0.0f64, 0.0f64);
    for l in &skeleton.leaves {
        let area = (l.length * l.width) as f64;
        let centre = l.position + l.orientation * Vec3::new(0.0, 0.0, l.length / 2.0);
        total += area;
        if centre.truncate().length() <= crown_radius / 2.0 {
            inner += area;
        }
    }
    if total > 0.0 { inner / total } else { 0.0 }
}

/// Least share of the thickest axis's radius for an axis to count as a leader.
const CODOMINANT: f32 = 2.0 / 3.0;

/// Where, between the crown base and the top, an axis must reach to lead (the top quarter).
const LEADS_FROM: f32 = 0.75;

/// Heights, as shares of the crown from its base, at which leaders are counted.
const LEADER_PLANES: [f32; 2] = [1.0 / 3.0, 0.5];

/// Leaders where the crown is most divided: a decurrent trunk may fork low or high in the crown,
/// and one plane alone would see the crown before its fork or after one limb has won.
fn leaders(skeleton: &Skeleton, base: f32, top: f32) -> usize {
    let reach = reaches(skeleton);
    LEADER_PLANES
        .iter()
        .map(|share| leaders_at(skeleton, &reach, base, top, base + (top - base) * share))
        .max()
        .unwrap_or(0)
}

fn leaders_at(skeleton: &Skeleton, reach: &[f32], base: f32, top: f32, height: f32) -> usize {
    // Radius where each stem crosses the plane going up (a stem may cross more than once).
    let mut crossings = Vec::new();
    for (i, _) in skeleton.frame_stems().iter().enumerate() {
        let s = skeleton.sections_of(StemId(i as u32));
        for w in s.windows(2) {
            let (a, b) = (w[0], w[1]);
            if a.position.z <= height && b.position.z > height {
                let t = (height - a.position.z) / (b.position.z - a.position.z);
                crossings.push((a.radius + (b.radius - a.radius) * t, reach[i]));
            }
        }
    }
    let widest = crossings.iter().map(|c| c.0).fold(0.0f32, f32::max);
    // A thick limb that bends out and ends in the crown's middle does not lead it: a leader
    // (or a codominant stem) carries the crown to its top.
    let upper = base + (top - base) * LEADS_FROM;
    crossings
        .iter()
        .filter(|&&(r, z)| widest > 0.0 && r >= widest * CODOMINANT && z >= upper)
        .count()
}

/// Highest point of each stem with everything that grows from it.
fn reaches(skeleton: &Skeleton) -> Vec<f32> {
    let mut reach: Vec<f32> = (0..skeleton.frame_stems().len())
        .map(|i| {
            let s = skeleton.sections_of(StemId(i as u32));
            s.iter()
                .map(|c| c.position.z)
                .fold(f32::NEG_INFINITY, f32::max)
        })
        .collect();
    // Lift every ancestor to its descendants' height; a parent's chain is short (the
    // branching order), so walking it from each stem is cheap.
    for i in 0..skeleton.frame_stems().len() {
        let z = reach[i];
        let mut parent = skeleton.stems[i].parent;
        while let Some(StemId(p)) = parent {
            let p = p as usize;
            if reach[p] >= z {
                break;
            }
            reach[p] = z;
            parent = skeleton.stems[p].parent;
        }
    }
    reach
}

fn scaffold_angles(skeleton: &Skeleton) -> Vec<f64> {
    let mut angles = Vec::new();
    for (i, stem) in skeleton.frame_stems().iter().enumerate() {
        if stem.parent != Some(StemId(0)) || stem.clone_of.is_some() {
            continue;
        }
        let s = skeleton.sections_of(StemId(i as u32));
        let Some(first) = s.first() else { continue };
        // The point a metre along the branch (or its tip, if shorter).
        let mut walked = 0.0f32;
        let mut end = first.position;
        for w in s.windows(2) {
            let step = w[0].position.distance(w[1].position);
            if walked + step >= 1.0 {
                let t = (1.0 - walked) / step.max(1e-6);
                end = w[0].position.lerp(w[1].position, t);
                walked = 1.0;
                break;
            }
            walked += step;
            end = w[1].position;
        }
        let d = end - first.position;
        if walked > 0.05 && d.length() > 1e-4 {
            angles.push((d.z / d.length()).clamp(-1.0, 1.0).asin().to_degrees() as f64);
        }
    }
    angles
}

/// Per fork (a parent and the children leaving it at one place), the n solving
/// below^n = above^n + sum of children^n, where the parent is thicker than each part.
fn fork_exponents(skeleton: &Skeleton) -> Vec<f64> {
    use std::collections::BTreeMap;
    // (parent, unit position on it in 1/10,000ths) -> children's base radii
    let mut forks: BTreeMap<(u32, i64), Vec<f32>> = BTreeMap::new();
    for (i, stem) in skeleton.frame_stems().iter().enumerate() {
        let Some(parent) = stem.parent else { continue };
        let length = skeleton.stems[parent.0 as usize].length;
        let Some(base) = skeleton.sections_of(StemId(i as u32)).first() else {
            continue;
        };
        if length <= 0.0 || stem.clone_of.is_some() {
            continue;
        }
        let z = (stem.offset / length).clamp(0.0, 1.0);
        let key = (parent.0, (z * 10_000.0).round() as i64);
        forks.entry(key).or_default().push(base.radius);
    }
    let mut exponents = Vec::new();
    // The fork before each, on the same parent (or its base): a limb carries the radius it
    // leaves that fork with up to the next (the pipe model's radius steps at the forks, and
    // sections between them, such as a drawn limb's kinks, only taper the tube).
    let mut last: Option<(u32, f32)> = None;
    for ((parent, z), children) in forks {
        let z = z as f32 / 10_000.0;
        let from = match last {
            Some((p, before)) if p == parent => before,
            _ => f32::NEG_INFINITY,
        };
        last = Some((parent, z));
        let s = skeleton.sections_of(StemId(parent));
        // A section exactly at the fork is the parent going on past it. A trunk is read just
        // below the fork: it is drawn straight, and flares towards the ground.
        let below = if skeleton.stems[parent as usize].level == 0 {
            s.iter().rev().find(|c| c.z < z - 1e-5)
        } else {
            s.iter().find(|c| c.z >= from - 1e-5 && c.z < z - 1e-5)
        }
        .map(|c| c.radius);
        let above = s.iter().find(|c| c.z >= z - 1e-5).map(|c| c.radius);
        let (Some(below), Some(above)) = (below, above) else {
            continue;
        };
        let mut parts = children;
        parts.push(above);
        if let Some(n) = pipe_exponent(below, &parts) {
            exponents.push(n);
        }
    }
    exponents
}

/// The n in (0.5, 8) with `parent^n = sum of part^n`, when the parent is thicker than every
/// part (the sum falls from the part count toward 0 as n grows, so the root is unique).
pub fn pipe_exponent(parent: f32, parts: &[f32]) -> Option<f64> {
    if parent <= 0.0 || parts.is_empty() || parts.iter().any(|&r| r <= 0.0 || r >= parent) {
        return None;
    }
    let excess = |n: f64| -> f64 {
        parts
            .iter()
            .map(|&r| (r as f64 / parent as f64).powf(n))
            .sum::<f64>()
            - 1.0
    };
    let (mut lo, mut hi) = (0.5f64, 8.0f64);
    if excess(lo) < 0.0 || excess(hi) > 0.0 {
        return None;
    }
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if excess(mid) > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    Some((lo + hi) / 2.0)
}

fn median(mut values: Vec<f64>) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    Some(if n % 2 == 1 {
        values[n / 2]
    } else {
        (values[n / 2 - 1] + values[n / 2]) / 2.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{Leaf, LeafShape};
    use glam::Quat;

    /// A trunk from the ground to 10 m with two limbs `limb` metres long leaving it at 4 m,
    /// rising at 45 degrees. The trunk above the fork and each limb have radius 0.1, the trunk
    /// below 3^(1/2.5) x 0.1: a pipe exponent of 2.5.
    ///
    /// ```text
    ///    \   /
    ///     \ /      limbs at 45 degrees
    ///      |  4 m
    ///      |
    /// ```
    fn forked(limb: f32) -> Skeleton {
        let mut sk = Skeleton::default();
        let below = 0.1 * 3f32.powf(1.0 / 2.5);
        // The trunk is thick below the fork and as thick as each limb above it.
        let trunk = sk.push_polyline(
            &[
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 4.0),
                Vec3::new(0.0, 0.0, 4.1),
                Vec3::new(0.0, 0.0, 10.0),
            ],
            &[below, below, 0.1, 0.05],
            0,
            None,
        );
        for x in [-1.0f32, 1.0] {
            let d = Vec3::new(x, 0.0, 1.0).normalize();
            let start = Vec3::new(0.0, 0.0, 4.05);
            let id = sk.push_polyline(&[start, start + d * limb], &[0.1, 0.08], 1, Some(trunk));
            sk.stems[id.0 as usize].offset = 4.05;
        }
        sk
    }

    #[test]
    fn a_fork_gives_its_exponent_angle_and_leaders() {
        let sk = forked(8.0);
        let form = measure_form(&sk, 3.0, 10.0, 4.0);
        assert!((form.pipe_exponent.unwrap() - 2.5).abs() < 0.05, "{form:?}");
        assert!(
            (form.scaffold_angle.unwrap() - 45.0).abs() < 0.5,
            "{form:?}"
        );
        // Half way up the crown (6.5 m): the trunk (0.080) and both limbs (0.091),
        // codominant, and all reach the top quarter (above 8.25 m; the limbs end at 9.7 m);
        // with limbs 4 m long, only the trunk crosses 8.5 m.
        assert_eq!(form.leaders, 3);
        assert_eq!(measure_form(&forked(4.0), 7.0, 10.0, 4.0).leaders, 1);
        // Limbs that end at 6.9 m, in the crown's middle, are thick there but lead nothing.
        assert_eq!(measure_form(&forked(4.0), 3.0, 10.0, 4.0).leaders, 1);
        assert_eq!(
            pipe_exponent(1.0, &[0.5, 0.5]).map(|n| (n * 1e6).round()),
            Some(1e6)
        );
        assert!(pipe_exponent(1.0, &[1.2]).is_none());
    }

    #[test]
    fn leaves_near_the_axis_count_by_area() {
        let mut sk = forked(4.0);
        let leaf = |x: f32, size: f32| Leaf {
            position: Vec3::new(x, 0.0, 6.0),
            orientation: Quat::IDENTITY,
            length: size,
            width: size,
            shape: LeafShape::Oval,
            stem: StemId(0),
            light: 1.0,
        };
        sk.leaves = vec![
            leaf(0.2, 0.2),
            leaf(1.8, 0.2),
            leaf(-1.9, 0.2),
            leaf(0.5, 0.4),
        ];
        // Crown radius 2: within 1 m of the axis are the first and last (0.04 + 0.16 of 0.28).
        let share = measure_form(&sk, 3.0, 10.0, 4.0).inner_leaf_share;
        assert!((share - 0.2 / 0.28).abs() < 1e-6, "{share}");
    }
}
