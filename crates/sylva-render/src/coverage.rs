//! How much of a tree's outline its picture covers, and how much of that is leaf: the picture's
//! side of issue R's measure (`sylva sweep --beam --picture`), held to the shade model's
//! `Crown::beam` along the same direction.
//!
//! The tree is drawn by the renderer itself (whichever backend answers), alone, on a clear
//! background, with its bark pure red and its leaves pure green. Every light term of the
//! renderer multiplies a surface's colour, so a pixel's red and green still say how much of it
//! is wood and how much leaf, and its alpha how much of it the tree covers (4 samples a pixel;
//! a twig thinner than a pixel covers the samples it crosses). A narrow lens from far away
//! makes the view nearly parallel, as the model's beam is.

use crate::{Picture, RenderError, Renderer, Scene, View};
use std::ops::Range;
use sylva::Skeleton;
use sylva::colour::srgb_to_linear;
use sylva::growth::survey::report::MESH;
use sylva::growth::{Measured, Month, dressed_mesh};
use sylva::mesh::TreeMesh;
use sylva::street::energy::crown::leaf_centre;
use sylva::street::energy::opacity::{CoverageRecord, LeafAndBare};

/// Lens of the measuring view, degrees: the tree seen from about 14 of its heights away, so
/// rays through its near and far sides part by under 4 degrees.
const LENS: f32 = 4.0;

/// Linear colour below which what is left of a pixel once the clear colour is taken out is
/// the stored byte's rounding (a step of an 8-bit sRGB channel is up to 0.004 in linear light
/// at the clear colours used), not the tree's.
const ROUNDING: f32 = 0.004;

/// What a picture of a tree covers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Pixels of the outline: in each row, from the first pixel the tree touches to the last.
    pub outline_px: f64,
    /// Share of the outline covered (each pixel by its alpha).
    pub covered: f64,
    /// Share of the covered pixels that is leaf rather than wood.
    pub leaf_share: f64,
    /// Share of the covered pixels that is wood outside the leaves: beyond a row's outermost
    /// leaf on either side, or above its column's highest leaf. Bare whips poking past the
    /// foliage in summer; 0 where no leaf is drawn (a bare crown has no foliage to pass).
    pub bare_tips: f64,
    /// Metres a pixel spans at the tree, about.
    pub metres_per_px: f64,
}

impl Coverage {
    /// As output: the outline in square metres.
    pub fn record(&self) -> CoverageRecord {
        CoverageRecord {
            covered: self.covered,
            leaf_share: self.leaf_share,
            bare_tips: self.bare_tips,
            outline_m2: self.outline_px * self.metres_per_px * self.metres_per_px,
        }
    }
}

/// A grown street tree's crown measured from the side in summer, in leaf and bare (the short
/// twigs its leaves hid showing), in pictures `side` pixels across, with the pictures.
pub fn crown_coverage(
    renderer: &Renderer,
    m: &Measured,
    skeleton: &Skeleton,
    side: u32,
) -> Result<LeafAndBare<(Coverage, Picture)>, RenderError> {
    let (mesh, _) = dressed_mesh(skeleton, m, Some(Month::SUMMER), &MESH);
    // The crown's heights, as the model's beam takes them: its leaves'.
    let crown = (skeleton.leaves.iter())
        .map(|l| leaf_centre(l).z)
        .fold((f32::MAX, f32::MIN), |(lo, hi), z| (lo.min(z), hi.max(z)));
    let leaf = measure(renderer, &mesh, 0.0, side, true, crown)?;
    let leafless = Skeleton {
        leaves: Vec::new(),
        ..skeleton.clone()
    };
    let (bare_mesh, _) = dressed_mesh(&leafless, m, Some(Month::SUMMER), &MESH);
    let bare = measure(renderer, &bare_mesh, 0.0, side, false, crown)?;
    Ok(LeafAndBare { leaf, bare })
}

/// Draws `mesh` level from `azimuth` degrees (0: from the south, looking north, as the model's
/// beam along +Y) in a `side` x `side` picture, with or without its leaves, and measures the
/// rows between heights `crown` (metres: the crown, not the bare trunk below it).
pub fn measure(
    renderer: &Renderer,
    mesh: &TreeMesh,
    azimuth: f32,
    side: u32,
    leaves: bool,
    crown: (f32, f32),
) -> Result<(Coverage, Picture), RenderError> {
    let tree = renderer.upload(mesh);
    let mut scene = Scene::new(&tree, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    scene.show_ground = false;
    scene.show_person = false;
    scene.show_leaves = leaves;
    scene.transparent = true;
    scene.impostors = false;
    let view = View {
        fov_y: LENS,
        ..View::orbit(azimuth, 0.0)
    };
    let picture = renderer.render(&scene, &view, side, side)?;
    let (lo, hi) = scene.tree_bounds();
    let camera = scene.camera(&view, 1.0);
    let range = camera.eye.distance((lo + hi) / 2.0) as f64;
    let metres_per_px = 2.0 * range * (LENS as f64 / 2.0).to_radians().tan() / side as f64;
    let clear = scene.transparent_clear();
    // The rows the crown's heights fall on, top first, on the tree's axis.
    let row = |z: f32| {
        camera
            .project(glam::Vec3::new(0.0, 0.0, z), side, side)
            .map_or(0, |(_, y)| y.round().clamp(0.0, side as f32) as usize)
    };
    let rows = row(crown.1)..row(crown.0);
    Ok((
        Coverage {
            metres_per_px,
            ..of_picture(&picture, [clear[0], clear[1]], rows)
        },
        picture,
    ))
}

/// The outline, cover and leaf share of `rows` of a picture drawn as [`measure`] draws: alpha
/// is cover; the colour, less the clear colour (`clear`: its linear red and green) in the
/// uncovered share, is lit wood (red) and lit leaf (green).
pub fn of_picture(picture: &Picture, clear: [f32; 2], rows: Range<usize>) -> Coverage {
    let (w, h) = (picture.width as usize, picture.height as usize);
    let rows = rows.start.min(h)..rows.end.min(h);
    // Each pixel's cover and the share of it that is leaf.
    let pixel = |x: usize, y: usize| -> (f64, f64) {
        let p = &picture.rgba[(y * w + x) * 4..(y * w + x) * 4 + 4];
        let a = p[3] as f64 / 255.0;
        if a <= 0.0 {
            return (0.0, 0.0);
        }
        let lin = |k: usize, c: f32| {
            (srgb_to_linear(p[k] as f32 / 255.0) - (1.0 - a as f32) * c).max(0.0)
        };
        let (r, g) = (lin(0, clear[0]), lin(1, clear[1]));
        (
            a,
            // A colour within the 8-bit rounding of the clear colour it was blended with has no
            // hue left to read: a half-covered, unlit twig pixel came out as a green residue of
            // 0.0002 and, counted as leaf, made a bare plane's twigs 99% "past the leaves".
            if r + g > ROUNDING {
                (g / (r + g)) as f64
            } else {
                0.0
            },
        )
    };
    // A pixel mostly covered by leaf marks where the foliage reaches.
    let is_leaf = |(a, g): (f64, f64)| a * g >= 0.5;
    let mut top_leaf = vec![usize::MAX; w];
    for y in rows.clone() {
        for (x, top) in top_leaf.iter_mut().enumerate() {
            if *top == usize::MAX && is_leaf(pixel(x, y)) {
                *top = y;
            }
        }
    }
    let any_leaf = top_leaf.iter().any(|&t| t != usize::MAX);
    let (mut outline, mut covered, mut leaf, mut tips) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for y in rows {
        let alpha = |x: usize| picture.rgba[(y * w + x) * 4 + 3];
        let Some(first) = (0..w).find(|&x| alpha(x) > 0) else {
            continue;
        };
        let last = (first..w).rev().find(|&x| alpha(x) > 0).unwrap_or(first);
        outline += (last - first + 1) as f64;
        // The row's foliage, from its outermost leaf on one side to that on the other, and
        // always as far as the picture's middle, where the tree stands: wood between the trunk
        // and a row's leaves (the limbs at the crown base) is inside the crown, not past it.
        let middle = w / 2;
        let leaves = (first..=last).find(|&x| is_leaf(pixel(x, y))).map(|lo| {
            let hi = (lo..=last)
                .rev()
                .find(|&x| is_leaf(pixel(x, y)))
                .unwrap_or(lo);
            lo.min(middle)..=hi.max(middle)
        });
        for (x, &top) in top_leaf.iter().enumerate().take(last + 1).skip(first) {
            let (a, g) = pixel(x, y);
            covered += a;
            leaf += a * g;
            // A row without a leaf (the crown's base) is judged by its columns alone.
            let within_row = leaves.as_ref().is_none_or(|l| l.contains(&x));
            if any_leaf && !(within_row && y >= top) {
                tips += a * (1.0 - g);
            }
        }
    }
    Coverage {
        outline_px: outline,
        covered: if outline > 0.0 {
            covered / outline
        } else {
            0.0
        },
        leaf_share: if covered > 0.0 { leaf / covered } else { 0.0 },
        bare_tips: if covered > 0.0 { tips / covered } else { 0.0 },
        metres_per_px: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn picture(pixels: &[[u8; 4]], width: u32) -> Picture {
        Picture {
            width,
            height: pixels.len() as u32 / width,
            rgba: pixels.iter().flatten().copied().collect(),
            stats: Default::default(),
        }
    }

    /// A row of four pixels: empty, full wood, half-covered leaf, empty, full leaf, empty;
    /// the outline runs from the first covered pixel to the last.
    #[test]
    fn outline_cover_and_leaf_share_of_a_row() {
        let clear_green = 0.25f32;
        // Half a leaf pixel: linear green 0.5 x 1.0 + 0.5 x clear.
        let half = (sylva::colour::linear_to_srgb(0.5 + 0.5 * clear_green) * 255.0).round() as u8;
        let p = picture(
            &[
                [0, 0, 0, 0],
                [255, 0, 0, 255],
                [0, half, 0, 128],
                [0, 0, 0, 0],
                [0, 255, 0, 255],
                [0, 0, 0, 0],
            ],
            6,
        );
        let c = of_picture(&p, [0.0, clear_green], 0..1);
        assert_eq!(c.outline_px, 4.0);
        let cover = (1.0 + 128.0 / 255.0 + 1.0) / 4.0;
        assert!((c.covered - cover).abs() < 1e-9, "{c:?}");
        // Leaf: the half pixel's unmixed green and the full leaf pixel, of 2.5 covered.
        let leaf = (128.0 / 255.0 + 1.0) / (1.0 + 128.0 / 255.0 + 1.0);
        assert!((c.leaf_share - leaf).abs() < 0.01, "{c:?}");
    }

    /// Wood past the foliage: a twig sticking out of a row's leaves sideways and one above its
    /// column's highest leaf count; wood between leaves, and below them, does not.
    #[test]
    fn bare_tips_are_wood_past_the_leaves() {
        const L: [u8; 4] = [0, 255, 0, 255];
        const W: [u8; 4] = [255, 0, 0, 255];
        const O: [u8; 4] = [0, 0, 0, 0];
        // Five columns, four rows: a whip above the leaves (row 0, column 2), a bare twig out to
        // the right (row 1, column 4), wood inside (row 2, column 2) and a trunk below (row 3).
        let p = picture(
            &[
                O, O, W, O, O, //
                L, L, L, L, W, //
                L, L, W, L, O, //
                O, O, W, O, O, //
            ],
            5,
        );
        let c = of_picture(&p, [0.0, 0.0], 0..4);
        let covered = 1.0 + 5.0 + 4.0 + 1.0;
        assert!((c.bare_tips - 2.0 / covered).abs() < 1e-9, "{c:?}");
        // No leaves at all: nothing to pass.
        let bare = of_picture(&picture(&[W, W, O, W], 2), [0.0, 0.0], 0..2);
        assert_eq!(bare.bare_tips, 0.0);
        // Nor where an unlit twig covers half a pixel over a green clear colour (linear 0.5,
        // sRGB 137 at half cover): its byte's rounding leaves no green to call leaf.
        const D: [u8; 4] = [0, 137, 0, 128];
        let dark = of_picture(&picture(&[W, D, O, W], 2), [0.0, 0.5], 0..2);
        assert_eq!((dark.bare_tips, dark.leaf_share), (0.0, 0.0), "{dark:?}");
    }

    /// A picture with nothing on it has no outline.
    #[test]
    fn empty_picture() {
        let c = of_picture(&picture(&[[0, 0, 0, 0]; 16], 4), [0.0, 0.0], 0..4);
        assert_eq!((c.outline_px, c.covered, c.leaf_share), (0.0, 0.0, 0.0));
    }
}
