//! Line drawings of trees: Nagel's move/draw vector files and projected views (front, side, top,
//! perspective, and the thesis' front-and-side overlay) as SVG or PNG.
//!
//! Everything here works on a stream of 3-D segments pushed into a [`LineSink`], never on a
//! stored list, so a model that can regenerate its segments (the fractal tree) draws in constant
//! memory however deep it goes. A [`Skeleton`] becomes such a stream with [`skeleton_lines`].
//! Drawings that must know their extent before the first stroke (SVG, PNG) replay the source
//! once per pass instead of buffering it.

pub mod cad;
mod outputs;
mod picture;
mod vec_file;
mod view;

pub use outputs::{LineFormat, MeshLook, Meshable, Planned, plan, wants_mesh, write_outputs};
pub use picture::{DrawOptions, draw_png, draw_rgba, draw_svg, write_svg};
pub use vec_file::{VecWriter, read_vec, write_vec};
pub use view::View;

use crate::skeleton::{Leaf, Skeleton};
use glam::Vec3;

/// What a stroke belongs to; drawings colour them apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Part {
    /// Trunk, branches, ribs, rings, spokes.
    Wood,
    /// Leaf outlines.
    Leaf,
}

/// How a segment is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// Which part of the tree.
    pub part: Part,
    /// Width in metres (a stem's diameter); drawings keep a visible minimum.
    pub width: f32,
}

impl Stroke {
    /// A wood stroke `width` metres wide.
    pub fn wood(width: f32) -> Self {
        Self {
            part: Part::Wood,
            width,
        }
    }
}

/// Receives a tree as straight 3-D segments (metres, Z up), in drawing order.
pub trait LineSink {
    /// One segment from `a` to `b`.
    fn segment(&mut self, a: Vec3, b: Vec3, stroke: Stroke);
}

impl<F: FnMut(Vec3, Vec3, Stroke)> LineSink for F {
    fn segment(&mut self, a: Vec3, b: Vec3, stroke: Stroke) {
        self(a, b, stroke)
    }
}

/// Something that can push its segments into a sink as often as asked, always the same ones in
/// the same order (a skeleton, a generator with fixed parameters, a parsed vector file).
pub trait LineSource {
    /// Pushes every segment into `sink`.
    fn lines(&self, sink: &mut dyn LineSink);
}

impl LineSource for Skeleton {
    fn lines(&self, sink: &mut dyn LineSink) {
        skeleton_lines(self, sink);
    }
}

/// Polylines as read from a vector file.
impl LineSource for Vec<Vec<Vec3>> {
    fn lines(&self, sink: &mut dyn LineSink) {
        for line in self {
            for w in line.windows(2) {
                sink.segment(w[0], w[1], Stroke::wood(0.0));
            }
        }
    }
}

/// Pushes a skeleton's stems (one segment between neighbouring cross-sections, as wide as the
/// stem there) and its leaves (each blade's outline as a four-sided loop).
pub fn skeleton_lines(skeleton: &Skeleton, sink: &mut dyn LineSink) {
    for stem in &skeleton.stems {
        let sections = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        for w in sections.windows(2) {
            sink.segment(
                w[0].position,
                w[1].position,
                Stroke::wood(w[0].radius + w[1].radius),
            );
        }
    }
    for leaf in &skeleton.leaves {
        leaf_lines(leaf, sink);
    }
}

/// A leaf blade's outline: base, widest point on each side, tip, as one closed loop.
pub fn leaf_lines(leaf: &Leaf, sink: &mut dyn LineSink) {
    let stroke = Stroke {
        part: Part::Leaf,
        width: 0.0,
    };
    let at = |x: f32, z: f32| leaf.position + leaf.orientation * Vec3::new(x, 0.0, z);
    let (half, mid) = (0.5 * leaf.width, 0.5 * leaf.length);
    let outline = [
        leaf.position,
        at(-half, mid),
        at(0.0, leaf.length),
        at(half, mid),
        leaf.position,
    ];
    for w in outline.windows(2) {
        sink.segment(w[0], w[1], stroke);
    }
}

#[cfg(test)]
mod tests;
