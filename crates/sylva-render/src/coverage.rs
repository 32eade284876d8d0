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
use sylva::colour::srgb_to_linear;
use sylva::mesh::TreeMesh;

/// Lens of the measuring view, degrees: the tree seen from about 14 of its heights away, so
/// rays through its near and far sides part by under 4 degrees.
const LENS: f32 = 4.0;

/// What a picture of a tree covers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Pixels of the outline: in each row, from the first pixel the tree touches to the last.
    pub outline_px: f64,
    /// Share of the outline covered (each pixel by its alpha).
    pub covered: f64,
    /// Share of the covered pixels that is leaf rather than wood.
    pub leaf_share: f64,
    /// Metres a pixel spans at the tree, about.
    pub metres_per_px: f64,
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
    let (mut outline, mut covered, mut leaf) = (0.0f64, 0.0f64, 0.0f64);
    for y in rows.start.min(h)..rows.end.min(h) {
        let row = &picture.rgba[y * w * 4..(y + 1) * w * 4];
        let alpha = |x: usize| row[x * 4 + 3] as f64 / 255.0;
        let Some(first) = (0..w).find(|&x| alpha(x) > 0.0) else {
            continue;
        };
        let last = (first..w).rev().find(|&x| alpha(x) > 0.0).unwrap_or(first);
        outline += (last - first + 1) as f64;
        for x in first..=last {
            let a = alpha(x);
            if a <= 0.0 {
                continue;
            }
            covered += a;
            let lin = |k: usize, c: f32| {
                (srgb_to_linear(row[x * 4 + k] as f32 / 255.0) - (1.0 - a as f32) * c).max(0.0)
            };
            let (r, g) = (lin(0, clear[0]), lin(1, clear[1]));
            if r + g > 0.0 {
                leaf += a * (g / (r + g)) as f64;
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

    /// A picture with nothing on it has no outline.
    #[test]
    fn empty_picture() {
        let c = of_picture(&picture(&[[0, 0, 0, 0]; 16], 4), [0.0, 0.0], 0..4);
        assert_eq!((c.outline_px, c.covered, c.leaf_share), (0.0, 0.0, 0.0));
    }
}
