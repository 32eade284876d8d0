//! Meshing a [`Skeleton`]: stems become closed-around tubes, leaves become
//! their outlines. Output is flat buffers (positions, normals, UVs, 32-bit indices), one mesh for
//! bark and one for leaves, in the skeleton's Z-up metres; exporters convert the axes.

mod apart;
mod bark;
mod compound;
mod leaves;
mod leaves_apart;
mod stems;
mod twigs;

pub use bark::{BarkPattern, young_bark_shade};
pub use compound::{NEEDLE_SPRAY_LENGTH, natural_aspect};
pub use leaves::{
    LUMINANCE_CLASSES, LeafTemplate, leaf_template, leaf_triangles, luminance, template_area,
};
pub(crate) use stems::ring_frame;
pub use stems::ring_vertices;
#[cfg(test)]
pub(crate) use twigs::tests as twigs_tests;
pub use twigs::{TwigCopies, TwigCopy, place_copies};

use crate::skeleton::Skeleton;

/// A triangle mesh as flat buffers. Triangles wind counter-clockwise seen from the front.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, metres.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates. Bark: u around (0..1, the seam's vertex repeated on rings of four
    /// sides or more), v along the stem in units
    /// of the base circumference. Leaves: 0..1 over the blade.
    pub uvs: Vec<[f32; 2]>,
    /// Three indices per triangle.
    pub indices: Vec<u32>,
    /// Luminance factor of each vertex (0..1), or empty where every vertex is fully lit: the
    /// leaves of a grown crown in their ten light classes. glTF's COLOR_0.
    pub shades: Vec<f32>,
    /// The stem's radius at each vertex, metres, or empty: a renderer widens a stem thinner
    /// than a pixel to one pixel and covers that share of it (the web page does). Only the
    /// meshes of an engine's level of detail carry it. glTF's `_RADIUS`.
    pub radii: Vec<f32>,
}

impl Mesh {
    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Axis-aligned bounds (min, max), or `None` for an empty mesh.
    pub fn bounds(&self) -> Option<([f32; 3], [f32; 3])> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        }))
    }

    /// Makes room for this many more vertices and indices (exactly, to keep memory tight).
    pub(crate) fn reserve(&mut self, vertices: usize, indices: usize) {
        self.positions.reserve_exact(vertices);
        self.normals.reserve_exact(vertices);
        self.uvs.reserve_exact(vertices);
        self.indices.reserve_exact(indices);
    }

    pub(crate) fn push(&mut self, position: glam::Vec3, normal: glam::Vec3, uv: [f32; 2]) -> u32 {
        let i = self.positions.len() as u32;
        self.positions.push(position.to_array());
        self.normals.push(normal.to_array());
        self.uvs.push(uv);
        i
    }
}

/// Bark and leaves of one tree.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TreeMesh {
    /// All stems.
    pub bark: Mesh,
    /// All leaves (drawn double-sided).
    pub leaves: Mesh,
    /// Showy flowers in their season (drawn double-sided, in a material of their own); empty
    /// for most trees and seasons.
    pub flowers: Mesh,
    /// A bare crown's short twigs as copies of one twig, where the options asked for them
    /// ([`MeshOptions::twig_copies`]); empty otherwise, the twigs then in `bark`. Bark
    /// material.
    pub twigs: TwigCopies,
}

impl TreeMesh {
    /// Vertices of every part, each twig copy's counted.
    pub fn vertex_count(&self) -> usize {
        self.bark.vertex_count()
            + self.leaves.vertex_count()
            + self.flowers.vertex_count()
            + self.twigs.vertex_count()
    }

    /// Triangles of every part, each twig copy's counted.
    pub fn triangle_count(&self) -> usize {
        self.bark.triangle_count()
            + self.leaves.triangle_count()
            + self.flowers.triangle_count()
            + self.twigs.triangle_count()
    }

    /// The bark with the twig copies placed in it: what a mesh drawn without instancing
    /// shows (borrowed where there are no copies).
    pub fn bark_with_twigs(&self) -> std::borrow::Cow<'_, Mesh> {
        if self.twigs.is_empty() {
            return std::borrow::Cow::Borrowed(&self.bark);
        }
        let mut bark = self.bark.clone();
        self.twigs.place_into(&mut bark);
        std::borrow::Cow::Owned(bark)
    }
}

/// How finely to mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// Resolution factor: 1 is the default; ring vertices scale with it (at least 3).
    pub quality: f64,
    /// Vertices around every stem, whatever its level (Fields' Tessellation rule); `None`: by
    /// level and quality.
    pub sides: Option<u32>,
    /// The bark's pattern, drawn as vertex shades; [`BarkPattern::Smooth`] gives none.
    pub bark: BarkPattern,
    /// Luminance of the young shoots' bark as a share of the bark's (1: the same), drawn as
    /// vertex shades on thin stems (see [`bark::young_bark_shade`]): a white birch's dark
    /// twigs.
    pub young_bark: f32,
    /// Draws a bare crown's short twigs as copies of one twig ([`TreeMesh::twigs`]) instead of
    /// in the bark: a model file then holds one twig and a placement a copy. Off where a
    /// mesh is drawn or read as it is (pictures, the viewer, Python).
    pub twig_copies: bool,
}

impl Default for MeshOptions {
    fn default() -> Self {
        Self {
            quality: 1.0,
            sides: None,
            bark: BarkPattern::Smooth,
            young_bark: 1.0,
            twig_copies: false,
        }
    }
}

impl MeshOptions {
    /// Whether the bark carries vertex shades: a pattern, or young bark of its own shade.
    pub fn shaded_bark(&self) -> bool {
        self.bark != BarkPattern::Smooth || self.young_bark < 1.0
    }

    /// The options a Weber-Penn species asks for at a quality (1: the default): Arbaro's Smooth
    /// (0..1, default 0.5) scales the ring resolution around it.
    pub fn for_species(params: &crate::TreeParams, quality: f64) -> Self {
        Self {
            quality: quality * (0.5 + params.smooth),
            ..Default::default()
        }
    }

    /// Vertices around a stem's rings.
    pub fn ring_vertices(&self, stem: &crate::skeleton::Stem) -> usize {
        match self.sides {
            Some(n) => (n as usize).clamp(3, 256),
            None => stems::ring_vertices(stem.level as usize, self.quality, stem.lobes),
        }
    }
}

/// Meshes every stem and leaf of a skeleton.
pub fn mesh_tree(skeleton: &Skeleton, options: &MeshOptions) -> TreeMesh {
    let mut mesh = TreeMesh::default();
    mesh_tree_into(skeleton, options, &mut mesh);
    mesh
}

/// Like [`mesh_tree`], but reuses `mesh`'s buffers (cleared first), so re-meshing after an
/// edit allocates nothing once warm.
pub fn mesh_tree_into(skeleton: &Skeleton, options: &MeshOptions, mesh: &mut TreeMesh) {
    for part in [&mut mesh.bark, &mut mesh.leaves, &mut mesh.flowers] {
        part.positions.clear();
        part.normals.clear();
        part.uvs.clear();
        part.indices.clear();
        part.shades.clear();
    }
    mesh.twigs = if options.twig_copies {
        twigs::twig_copies(skeleton, options)
    } else {
        TwigCopies::default()
    };
    // Size every buffer exactly first: growing them by doubling costs more than filling them.
    let (v, i) = stems::count(skeleton, options);
    mesh.bark.reserve(v, i);
    let (v, i) = leaves::count(&skeleton.leaves);
    mesh.leaves.reserve(v, i);
    // Bark and leaves fill buffers of their own, so they can be meshed at once on two
    // threads with the same bytes as one after the other.
    let TreeMesh { bark, leaves, .. } = mesh;
    rayon::join(
        || stems::mesh_stems(skeleton, options, bark),
        || {
            if !leaves_apart::mesh_leaves_apart(skeleton, leaves) {
                leaves::mesh_leaves(skeleton, leaves)
            }
        },
    );
    debug_assert_eq!(
        (mesh.bark.vertex_count(), mesh.bark.indices.len()),
        stems::count(skeleton, options)
    );
}
