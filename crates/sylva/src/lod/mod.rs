//! Seamless degradation at range (Weber & Penn, section 5; spec section 13).
//!
//! One stored form per tree, reinterpreted by range, never rebuilt: four item lists (stem
//! levels 0, 1, >= 2, and leaves), each stored rank-major ([`order`]) so that a level of detail
//! is one contiguous range per run of like items. With range, stem meshes become lines along
//! their axes and leaf polygons become points; items drop out one at a time.
//!
//! The form is compact ([`packed`]): a stem segment is its two rings and a leaf is a card, and
//! the GPU rebuilds their triangles each frame, so a tree that a full mesh holds in 21 MB is
//! stored in under 1 MB. [`expand`] rebuilds the same triangles on the CPU (an engine's meshes,
//! the CPU rasteriser), the reference the shader follows.

pub mod bake;
mod budget;
mod build;
pub mod expand;
pub mod impostor;
pub mod order;
pub mod packed;
mod shell;
pub mod sway;

pub use budget::{Choice, PER_SQUARE_PIXEL, THINNED_OUTLINE, card_scale, share_out, tree_cap};
pub use impostor::{IMPOSTOR_PIXELS, IMPOSTOR_WHOLE_PIXELS, impostor_share, view_blend};
pub use shell::leaf_shell;

use crate::skeleton::LeafShape;
use order::prefix_len;
use packed::{Leaf, Quantiser, Segment};
use std::ops::Range;

/// Items of one list that are drawn alike (stem segments with the same ring, or leaves of the
/// same outline), stored rank-major among themselves.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The run's records in [`LodTree::segments`] or [`LodTree::leaves`].
    pub items: Range<u32>,
    /// Stems: vertices around the ring (3 or more). Leaves: 0.
    pub sides: u32,
    /// Stems: sinusoidal lobes around the ring (0: round), and their depth relative to the
    /// radius.
    pub lobes: u32,
    /// Lobe amplitude relative to the radius.
    pub lobe_depth: f32,
    /// Leaves: their outline.
    pub shape: LeafShape,
}

impl Run {
    /// Records in the run.
    pub fn len(&self) -> usize {
        (self.items.end - self.items.start) as usize
    }

    /// Whether the run holds no record.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Triangles one item draws as a mesh: `2 sides` for a segment (a cone's tip draws half of
    /// them with no area), the template's for a leaf.
    pub fn triangles_per_item(&self) -> usize {
        if self.sides > 0 {
            2 * self.sides as usize
        } else {
            crate::mesh::leaf_triangles(self.shape)
        }
    }

    /// The records drawn as meshes and as lines or points for levels of detail `x_mesh` and
    /// `x_drawn` (0..=mass).
    pub fn draw(&self, mass: usize, x_mesh: f64, x_drawn: f64) -> RunDraw {
        let meshed = prefix_len(self.len(), mass, x_mesh);
        let drawn = prefix_len(self.len(), mass, x_drawn).max(meshed);
        let s = self.items.start;
        RunDraw {
            meshed: s..s + meshed as u32,
            flat: s + meshed as u32..s + drawn as u32,
        }
    }
}

/// One list: its runs, stored rank-major.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LodList {
    /// Items per mass (16 cross-sections for stems, 4 leaves).
    pub mass: usize,
    /// Number of items (stem segments, or leaves) in all runs.
    pub items: usize,
    /// Runs of like items.
    pub runs: Vec<Run>,
    /// Mean stem diameter of the items (0 for leaves), metres.
    pub diameter: f32,
    /// Mean item length: segment length, or leaf length, metres.
    pub length: f32,
}

/// A tree stored for drawing at any range.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LodTree {
    /// The scales of the records.
    pub quantiser: Quantiser,
    /// Stem segments of the first three lists, run after run.
    pub segments: Vec<Segment>,
    /// Leaves, run after run.
    pub leaves: Vec<Leaf>,
    /// Trunk, branches, twigs, leaves.
    pub lists: [LodList; 4],
    /// How much darker the young shoots' bark is than the bark (1 less
    /// `MeshOptions::young_bark`; 0: no difference): drawn as the bark's vertex shades.
    pub young_bark_darkening: f32,
}

/// What to draw of one run: ranges of its records.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RunDraw {
    /// Records drawn as meshes.
    pub meshed: Range<u32>,
    /// Records drawn as lines (stems) or points (leaves), after the meshed ones.
    pub flat: Range<u32>,
}

/// How a camera sees: picture height in pixels and vertical field of view in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewer {
    /// Picture height, pixels.
    pub image_height: f32,
    /// Vertical field of view, degrees.
    pub fov_y: f32,
    /// The paper's quality factor: 1 normal; 2 keeps detail twice as far.
    pub quality: f32,
}

impl Viewer {
    /// The paper's calibrated range: `range * 1000 / image_height * fov_y / 60`, the range at
    /// which a 1000-pixel, 60-degree picture would show the same detail.
    pub fn calibrated_range(&self, range: f32) -> f32 {
        range * 1000.0 / self.image_height * self.fov_y / 60.0
    }

    /// Pixels covered by one metre at `range` metres (times the quality factor).
    pub fn pixels_per_metre(&self, range: f32) -> f32 {
        self.quality * self.image_height
            / (2.0 * range.max(1e-3) * (self.fov_y.to_radians() / 2.0).tan())
    }
}

/// Below this projected diameter (pixels) no stem is drawn as a mesh; above `MESH_FULL` all are.
const MESH_NONE: f32 = 0.5;
const MESH_FULL: f32 = 1.5;
/// A stem segment becomes a line as its projected area (diameter x length) grows from
/// `LINE_NONE` to `LINE_FULL` square pixels: a sub-pixel stem drawn as a 1-pixel line covers far
/// more than itself, so thin short segments drop out first (calibrated on the paper's figure:
/// a 100,000-facet tree at 2 km as about 30 lines).
const LINE_NONE: f32 = 0.001;
const LINE_FULL: f32 = 0.02;
/// Leaves are polygons from `POLY_NONE` pixels long, all of them from `POLY_FULL`.
const POLY_NONE: f32 = 2.0;
const POLY_FULL: f32 = 4.0;
/// Leaves shown as points per pixel of leaf length below full size (calibrated on the paper's
/// figure: a 100,000-facet tree at 2 km as about 1000 points).
const POINTS_PER_PIXEL: f32 = 0.6;

fn ramp(v: f32, lo: f32, hi: f32) -> f32 {
    ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
}

impl LodList {
    /// The x (0..=mass) of meshes and of all drawn items at `range`, from projected sizes.
    pub fn levels_of_detail(&self, leaves: bool, range: f32, viewer: &Viewer) -> (f64, f64) {
        let px = viewer.pixels_per_metre(range);
        let m = self.mass as f32;
        let (mesh, drawn) = if leaves {
            let len = self.length * px;
            // Polygons while a leaf spans a few pixels; points for the rest, their number
            // falling with the leaf's projected size so that the crown's density holds.
            (
                m * ramp(len, POLY_NONE, POLY_FULL),
                m * (POINTS_PER_PIXEL * len).min(1.0),
            )
        } else {
            // Meshes while a stem is wider than about a pixel, lines below, until the segment's
            // projected area is too small to matter.
            let (d, l) = (self.diameter * px, self.length * px);
            (
                m * ramp(d, MESH_NONE, MESH_FULL),
                m * ramp(d * l, LINE_NONE, LINE_FULL),
            )
        };
        (mesh as f64, mesh.max(drawn) as f64)
    }

    /// What each run draws at `range`.
    pub fn select(
        &self,
        leaves: bool,
        range: f32,
        viewer: &Viewer,
    ) -> impl Iterator<Item = (&Run, RunDraw)> + '_ {
        let (x_mesh, x_drawn) = self.levels_of_detail(leaves, range, viewer);
        self.runs
            .iter()
            .map(move |r| (r, r.draw(self.mass, x_mesh, x_drawn)))
    }
}

impl LodTree {
    /// Stores `skeleton` for range: its segments and leaves packed, in the four lists, each a
    /// few runs of like items stored rank-major; rings as `options` meshes them.
    pub fn build(skeleton: &crate::Skeleton, options: &crate::mesh::MeshOptions) -> Self {
        build::build(skeleton, options)
    }

    /// Triangles at full detail.
    pub fn triangle_count(&self) -> usize {
        self.lists
            .iter()
            .flat_map(|l| &l.runs)
            .map(|r| r.len() * r.triangles_per_item())
            .sum()
    }

    /// Bytes this tree holds: its records and run tables.
    pub fn heap_bytes(&self) -> usize {
        let runs: usize = self.lists.iter().map(|l| l.runs.len()).sum();
        std::mem::size_of::<Self>()
            + std::mem::size_of_val(self.segments.as_slice())
            + std::mem::size_of_val(self.leaves.as_slice())
            + runs * std::mem::size_of::<Run>()
    }

    /// Triangles, lines and points drawn at `range`.
    pub fn counts(&self, range: f32, viewer: &Viewer) -> LodCounts {
        let mut c = LodCounts::default();
        for (i, list) in self.lists.iter().enumerate() {
            for (run, d) in list.select(i == 3, range, viewer) {
                c.triangles += d.meshed.len() * run.triangles_per_item();
                if i == 3 {
                    c.points += d.flat.len();
                } else {
                    c.lines += d.flat.len();
                }
            }
        }
        c
    }
}

/// Primitives drawn at one range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LodCounts {
    /// Triangles (stem meshes and leaf polygons).
    pub triangles: usize,
    /// Lines (stem axes).
    pub lines: usize,
    /// Points (leaves).
    pub points: usize,
}

#[cfg(test)]
mod tests;
