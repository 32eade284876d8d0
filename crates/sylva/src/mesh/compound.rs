//! Templates of compound leaves and needle bundles: many small blades drawn as one leaf, so a
//! grown crown places, lights and counts them as it does a simple leaf. Each is laid out in
//! leaf lengths (the petiole's base at the origin, the leaf along +z), then fitted to the unit
//! box like every other template; its natural width, the box's width in leaf lengths before
//! fitting, is what keeps leaflets in proportion when a leaf of a given length is drawn
//! ([`natural_aspect`]).
//!
//! Leaflets, pinnae and needles are triangles standing on the rachis (or the sheath): at the
//! size a street tree is seen, a triangle reads as a leaflet, and a compound leaf of ten
//! leaflets costs ten triangles where ten simple leaves would cost sixty.

use super::LeafTemplate;
use crate::skeleton::LeafShape;
use glam::{Vec2, Vec3};

/// Angle between a leaflet (or pinna) and the rachis, radians: leaflets and pinnae of the
/// street trees these draw stand forward of square (55 degrees).
const LEAFLET_ANGLE: f32 = 55.0 * std::f32::consts::PI / 180.0;

/// Where the leaflets begin along a compound leaf, in leaf lengths: the bare petiole below.
const PETIOLE: f32 = 0.12;

/// Half the angle a bundle's needles open to, radians.
const NEEDLE_SPREAD: f32 = 12.0 * std::f32::consts::PI / 180.0;

/// A needle's width at its base against its length (a pine needle is 1-2 mm across and
/// 5-25 cm long; drawn a little wider so that a bundle still reads from a few metres away).
const NEEDLE_WIDTH: f32 = 0.02;

/// The template of a compound shape or needle bundle, or `None` for the other shapes.
pub(super) fn build(shape: LeafShape) -> Option<LeafTemplate> {
    blades(shape).map(|b| fitted(&b))
}

/// Width against length of a compound leaf or bundle as it grows (the template's box before
/// fitting); `None` for shapes whose width is given with their length.
pub fn natural_aspect(shape: LeafShape) -> Option<f32> {
    let (lo, hi) = bounds(&blades(shape)?);
    Some((hi.x - lo.x) / (hi.y - lo.y).max(1e-6))
}

/// The blades of a compound shape or bundle, laid out in leaf lengths.
fn blades(shape: LeafShape) -> Option<Blades> {
    Some(match shape.clamped() {
        LeafShape::Pinnate(n) => feather(n, leaflet_length(n / 2), 0.45),
        LeafShape::Bipinnate(n) => feather(n, pinna_length(n / 2), 0.3),
        LeafShape::Palmate(n) => palmate(n),
        LeafShape::Needles(n) => needles(n),
        LeafShape::NeedleSpray => needle_spray(),
        LeafShape::ScaleSpray => scale_spray(),
        _ => return None,
    })
}

/// A leaflet's length in leaf lengths for `pairs` pairs: fewer pairs, longer leaflets (an
/// ash's five leaflets reach a third of the leaf, a goldenrain tree's dozen a fifth).
fn leaflet_length(pairs: u8) -> f32 {
    (2.0 / (f32::from(pairs) + 2.0)).clamp(0.15, 0.45)
}

/// A pinna's length in leaf lengths for `pairs` pairs of pinnae.
fn pinna_length(pairs: u8) -> f32 {
    (2.2 / (f32::from(pairs) + 2.0)).clamp(0.2, 0.45)
}

/// Triangles as (base, base, apex) in the leaf's plane (x across, y along), each facing +y
/// once placed ([`fitted`] winds them).
type Blades = Vec<[Vec2; 3]>;

/// `count` blades of length `blade` in pairs along a rachis, each as wide at its base as
/// `base` of its length; an odd count ends in a blade along the rachis.
fn feather(count: u8, blade: f32, base: f32) -> Blades {
    let pairs = usize::from(count / 2);
    let terminal = count % 2 == 1;
    let (s, c) = LEAFLET_ANGLE.sin_cos();
    // The last pair's tips, or the terminal blade's, reach the leaf's tip.
    let end = if terminal {
        1.0 - blade
    } else {
        1.0 - blade * c
    };
    let spacing = (end - PETIOLE) / pairs.max(1) as f32;
    let half = (blade * base).min(spacing * 0.9) / 2.0;
    let mut blades = Vec::with_capacity(usize::from(count));
    for i in 0..pairs {
        let at = PETIOLE + (i as f32 + 0.5) * spacing;
        for side in [-1.0, 1.0] {
            let (a, b) = (Vec2::new(0.0, at - half), Vec2::new(0.0, at + half));
            blades.push([a, b, Vec2::new(side * blade * s, at + blade * c)]);
        }
    }
    if terminal {
        let at = 1.0 - blade;
        blades.push([
            Vec2::new(-half, at),
            Vec2::new(half, at),
            Vec2::new(0.0, 1.0),
        ]);
    }
    blades
}

/// `count` leaflets spread like fingers from the petiole's tip, the middle one longest: each
/// a pair of triangles (a kite) from the common centre.
fn palmate(count: u8) -> Blades {
    let n = usize::from(count);
    let centre = Vec2::new(0.0, 0.3);
    // Seven leaflets of a horsechestnut open to about 150 degrees; fewer to less.
    let spread = (25.0_f32 * (n as f32 - 1.0)).min(150.0).to_radians();
    let mut blades = Vec::with_capacity(2 * n);
    for k in 0..n {
        let t = if n > 1 {
            k as f32 / (n - 1) as f32 - 0.5
        } else {
            0.0
        };
        let angle = t * spread;
        let length = 0.7 * (1.0 - 0.7 * t.abs());
        let along = Vec2::new(angle.sin(), angle.cos());
        let across = Vec2::new(along.y, -along.x);
        let widest = centre + along * length * 0.6;
        let half = across * length * 0.18;
        let tip = centre + along * length;
        blades.push([centre, widest + half, tip]);
        blades.push([centre, tip, widest - half]);
    }
    blades
}

/// `count` needles from one sheath, opening to [`NEEDLE_SPREAD`] either side.
fn needles(count: u8) -> Blades {
    let n = usize::from(count);
    (0..n)
        .map(|k| {
            let t = if n > 1 {
                k as f32 / (n - 1) as f32 * 2.0 - 1.0
            } else {
                0.0
            };
            let angle = t * NEEDLE_SPREAD;
            let along = Vec2::new(angle.sin(), angle.cos());
            let across = Vec2::new(along.y, -along.x) * (NEEDLE_WIDTH / 2.0);
            [-across, across, along]
        })
        .collect()
}

/// Needles a spray of single needles carries, in two ranks and one at its tip.
const SPRAY_NEEDLES: u8 = 17;

/// A spray's length in needle lengths: a spruce's needles stand about a quarter of a
/// year's shoot long (Sylva's drawing choice: a twig that reads as a bottle brush from a few
/// metres away).
pub const NEEDLE_SPRAY_LENGTH: f32 = 4.0;

/// Single needles in two ranks along a twig, each as wide at its base as a tenth of its
/// length (a 2.5 cm spruce needle drawn 2.5 mm across, about as it is).
fn needle_spray() -> Blades {
    feather(SPRAY_NEEDLES, 1.0 / NEEDLE_SPRAY_LENGTH, 0.1)
}

/// A flat spray of scale-leaved branchlets: four pairs of side branchlets and a leading one
/// along an axis, each branchlet forking twice more on alternate sides, every branchlet a
/// narrow blade (the scales themselves, a millimetre or two, are far below what a street
/// tree is seen at).
fn scale_spray() -> Blades {
    let main = feather(9, 0.4, 0.15);
    let mut blades = main.clone();
    for (k, [a, b, apex]) in main.into_iter().enumerate() {
        let base = (a + b) / 2.0;
        let along = apex - base;
        for (i, t) in [0.35f32, 0.65].into_iter().enumerate() {
            // Alternate sides along each branchlet, and from one branchlet to the next.
            let side = if (i + k) % 2 == 0 { 1.0 } else { -1.0 };
            let at = base + along * t;
            let (s, c) = (side * 45f32.to_radians()).sin_cos();
            let twig = Vec2::new(along.x * c - along.y * s, along.x * s + along.y * c) * 0.4;
            let half = Vec2::new(-twig.y, twig.x).normalize_or_zero() * along.length() * 0.03;
            blades.push([at - half, at + half, at + twig]);
        }
    }
    blades
}

fn bounds(blades: &Blades) -> (Vec2, Vec2) {
    blades.iter().flatten().fold(
        (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// The blades as a flat template in the unit box, each triangle wound to face +y.
fn fitted(blades: &Blades) -> LeafTemplate {
    let (lo, hi) = bounds(blades);
    let size = (hi - lo).max(Vec2::splat(1e-6));
    let mut t = LeafTemplate {
        positions: Vec::with_capacity(blades.len() * 3),
        normals: Vec::with_capacity(blades.len() * 3),
        uvs: Vec::with_capacity(blades.len() * 3),
        indices: Vec::with_capacity(blades.len() * 3),
    };
    for blade in blades {
        let [a, b, c] = blade.map(|p| {
            let x = (p.x - lo.x) / size.x - 0.5;
            let z = (p.y - lo.y) / size.y;
            Vec3::new(x, 0.0, z)
        });
        // Corners blades share (a pair's two points on the rachis, a palmate leaf's centre)
        // are one vertex: the same flat normal and texture coordinate.
        let [ia, ib, ic] = [a, b, c].map(|p| {
            t.positions.iter().position(|q| *q == p).unwrap_or_else(|| {
                t.positions.push(p);
                t.normals.push(Vec3::Y);
                t.uvs.push([p.x + 0.5, p.z]);
                t.positions.len() - 1
            }) as u32
        });
        // Counter-clockwise seen from +y is clockwise in (x, z).
        if (b - a).cross(c - a).y > 0.0 {
            t.indices.extend_from_slice(&[ia, ib, ic]);
        } else {
            t.indices.extend_from_slice(&[ia, ic, ib]);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compound_leaves_have_their_count_of_blades() {
        let tris = |s| build(s).unwrap().indices.len() / 3;
        assert_eq!(tris(LeafShape::Pinnate(10)), 10);
        assert_eq!(tris(LeafShape::Pinnate(5)), 5);
        assert_eq!(tris(LeafShape::Bipinnate(10)), 10);
        assert_eq!(tris(LeafShape::Palmate(7)), 14);
        assert_eq!(tris(LeafShape::Needles(5)), 5);
        // Counts outside the bounds take the nearest.
        assert_eq!(tris(LeafShape::Pinnate(99)), 25);
        assert!(build(LeafShape::Oval).is_none());
        // A pair of leaflets shares its two points on the rachis; a palmate leaf its centre.
        let verts = |s| build(s).unwrap().positions.len();
        assert_eq!(verts(LeafShape::Pinnate(10)), 20);
        assert_eq!(verts(LeafShape::Palmate(7)), 22);
        assert_eq!(verts(LeafShape::Needles(5)), 15);
        // A spray of single needles: two ranks and a tip needle; a scale spray: nine
        // branchlets, each forking twice.
        assert_eq!(tris(LeafShape::NeedleSpray), 17);
        assert_eq!(tris(LeafShape::ScaleSpray), 27);
    }

    /// A spray of needles is a narrow twig, its needles a quarter of it; a scale spray is
    /// a frond about half as wide as long.
    #[test]
    fn sprays_have_their_proportions() {
        // Two ranks of needles at 55 degrees to the twig, each a quarter of its length.
        let (lo, hi) = bounds(&needle_spray());
        let want = 2.0 * (55f32.to_radians().sin() / NEEDLE_SPRAY_LENGTH);
        assert!(
            (hi.x - lo.x - want).abs() < 0.01,
            "{} vs {want}",
            hi.x - lo.x
        );
        assert!((hi.y - 1.0).abs() < 1e-4, "the tip needle ends the twig");
        let scales = natural_aspect(LeafShape::ScaleSpray).unwrap();
        assert!((0.5..1.0).contains(&scales), "{scales}");
    }

    #[test]
    fn a_pistache_leaf_is_longer_than_wide_and_a_horsechestnut_leaf_nearly_round() {
        let pinnate = natural_aspect(LeafShape::Pinnate(10)).unwrap();
        assert!((0.3..0.8).contains(&pinnate), "{pinnate}");
        let palmate = natural_aspect(LeafShape::Palmate(7)).unwrap();
        assert!((0.8..1.6).contains(&palmate), "{palmate}");
        let bundle = natural_aspect(LeafShape::Needles(5)).unwrap();
        assert!((0.3..0.5).contains(&bundle), "{bundle}");
        assert!(natural_aspect(LeafShape::Cordate).is_none());
    }
}
