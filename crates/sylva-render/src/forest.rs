//! A grown forest on the renderer: every variant stored for range and uploaded once, every
//! copy a placement, so a thousand trees of sixteen variants cost sixteen trees of memory.

use crate::caption::grouped;
use crate::{FrameStats, Placement, RenderTree, Renderer, Scene, Stand};
use glam::Vec3;
use std::borrow::Cow;
use sylva::forest::Forest;
use sylva::lod::LodTree;

/// GPU trees for every variant of a forest, and where their copies stand.
pub struct ForestOnGpu {
    /// One tree per variant.
    pub trees: Vec<RenderTree>,
    /// Bark and leaf colours (sRGB) per variant.
    pub colours: Vec<([f32; 3], [f32; 3])>,
    /// Every copy of each variant.
    pub placements: Vec<Vec<Placement>>,
    /// Bytes the variants hold for range rendering.
    pub stored_bytes: usize,
    /// Triangles at full detail, every copy counted.
    pub triangles_placed: usize,
    /// Wall-clock seconds the forest took to grow.
    pub grow_seconds: f64,
}

impl ForestOnGpu {
    /// Uploads every variant of `forest` and places its copies.
    pub fn upload(renderer: &Renderer, forest: &Forest<LodTree>) -> Self {
        let mut placements = vec![Vec::new(); forest.planting.variants.len()];
        for t in &forest.planting.trees {
            placements[t.variant].push(Placement {
                position: Vec3::from(t.position),
                turn: t.turn,
                scale: t.scale,
            });
        }
        let colours = forest
            .planting
            .variants
            .iter()
            .map(|v| forest.species[v.species].colours())
            .collect();
        Self {
            trees: forest
                .grown
                .iter()
                .map(|t| renderer.upload_lod(t))
                .collect(),
            stored_bytes: forest.grown.iter().map(LodTree::heap_bytes).sum(),
            triangles_placed: forest
                .planting
                .trees
                .iter()
                .map(|t| forest.grown[t.variant].triangle_count())
                .sum(),
            colours,
            placements,
            grow_seconds: forest.seconds,
        }
    }

    /// The scene of every copy.
    pub fn scene(&self) -> Scene<'_> {
        let stands = self
            .trees
            .iter()
            .zip(&self.colours)
            .zip(&self.placements)
            .map(|((tree, &(bark, leaves)), p)| Stand {
                tree,
                bark,
                leaves,
                placements: Cow::Borrowed(p),
            })
            .collect();
        Scene::forest(stands)
    }
}

impl FrameStats {
    /// One line describing a frame: what it drew and, given `ms`, how long it took.
    pub fn describe(&self, ms: f64) -> String {
        format!(
            "{} triangles, {} lines, {} points ({} primitives) in {} of {} trees{}; {:.0} ms",
            grouped(self.triangles),
            grouped(self.lines),
            grouped(self.points),
            grouped(self.primitives()),
            grouped(self.trees_drawn),
            grouped(self.trees),
            match self.impostors {
                0 => String::new(),
                n => format!(" ({} as impostors)", grouped(n)),
            },
            ms
        )
    }
}
