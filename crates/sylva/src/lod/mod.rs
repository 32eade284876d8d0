//! Seamless degradation at range (Weber & Penn, section 5; spec section 13).
//!
//! One stored geometry per tree, reinterpreted by range, never rebuilt: four item lists (stem
//! levels 0, 1, >= 2, and leaves), each stored rank-major ([`order`]) so that a level of detail
//! is one contiguous range per list and primitive. With range, stem meshes become lines along
//! their axes and leaf polygons become points; items drop out one at a time.

pub mod impostor;
pub mod order;

use crate::mesh::{MeshOptions, SegmentTriangles, TreeMesh, mesh_stems_by_segment};
use crate::skeleton::Skeleton;
use order::{LEAF_MASS, STEM_MASS, prefix_len, rank_major};
use std::ops::Range;

/// Which of the paper's four lists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ListKind {
    /// Stems of level 0 (trunks and their clones).
    Trunk,
    /// Stems of level 1.
    Branches,
    /// Stems of level 2 and deeper.
    Twigs,
    /// Leaves.
    Leaves,
}

/// One list's geometry, rank-major by item.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LodList {
    /// Items per mass (16 cross-sections for stems, 4 leaves).
    pub mass: usize,
    /// Number of items (stem segments, or leaves).
    pub items: usize,
    /// Triangle indices into the tree's bark (stems) or leaf (leaves) vertices, item after item
    /// in rank-major order.
    pub indices: Vec<u32>,
    /// `indices` used by the first k items: `index_prefix[k]`, k = 0..=items.
    pub index_prefix: Vec<u32>,
    /// Stems: two points per item, the segment's axis. Leaves: one point per item, its centre.
    pub points: Vec<[f32; 3]>,
    /// Per point, what it stands for: the stem's diameter (metres) or the blade's area (square
    /// metres), so that a renderer can give a line or point the coverage of what it replaces.
    pub sizes: Vec<f32>,
    /// Per point, a unit direction for lighting: the stem's axis, or the blade's normal.
    pub normals: Vec<[f32; 3]>,
    /// Mean stem diameter of the items (0 for leaves), metres.
    pub diameter: f32,
    /// Mean item length: segment length, or leaf length, metres.
    pub length: f32,
}

/// A tree stored for drawing at any range.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LodTree {
    /// Vertices of bark and leaves. Their index lists are left empty: the four rank-major
    /// lists hold every triangle once ([`LodTree::full_mesh`] puts them back together).
    pub mesh: TreeMesh,
    /// Trunk, branches, twigs, leaves.
    pub lists: [LodList; 4],
}

/// What to draw of one list: ranges into its buffers.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ListDraw {
    /// Range of [`LodList::indices`] to draw as triangles.
    pub triangles: Range<u32>,
    /// Range of [`LodList::points`] to draw: as a line list for stems, as points for leaves.
    pub points: Range<u32>,
}

impl ListDraw {
    /// Primitives drawn: triangles + lines (or points).
    pub fn primitives(&self, is_leaves: bool) -> usize {
        let tris = (self.triangles.end - self.triangles.start) as usize / 3;
        let pts = (self.points.end - self.points.start) as usize;
        tris + if is_leaves { pts } else { pts / 2 }
    }
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

    /// Draw ranges for a range.
    pub fn select(&self, leaves: bool, range: f32, viewer: &Viewer) -> ListDraw {
        let (x_mesh, x_drawn) = self.levels_of_detail(leaves, range, viewer);
        let meshed = prefix_len(self.items, self.mass, x_mesh);
        let drawn = prefix_len(self.items, self.mass, x_drawn).max(meshed);
        let per_item = if leaves { 1 } else { 2 };
        ListDraw {
            triangles: 0..self.index_prefix[meshed],
            points: (meshed * per_item) as u32..(drawn * per_item) as u32,
        }
    }
}

impl LodTree {
    /// Builds the rank-major lists of a tree.
    pub fn build(skeleton: &Skeleton, options: &MeshOptions) -> Self {
        let mut tree = Self::build_with(skeleton, options, false);
        // The lists hold the same triangles: keeping the mesh's own order too would double
        // the biggest buffers of every tree.
        tree.mesh.bark.indices = Vec::new();
        tree
    }

    /// [`LodTree::build`], keeping the mesh's own triangle order too (for tests).
    #[cfg(test)]
    pub(crate) fn build_keeping_indices(skeleton: &Skeleton, options: &MeshOptions) -> Self {
        Self::build_with(skeleton, options, true)
    }

    fn build_with(skeleton: &Skeleton, options: &MeshOptions, keep_leaf_indices: bool) -> Self {
        let mut mesh = TreeMesh::default();
        if keep_leaf_indices {
            crate::mesh::mesh_leaves_into(skeleton, &mut mesh.leaves);
        } else {
            crate::mesh::mesh_leaf_vertices_into(skeleton, &mut mesh.leaves);
        }
        let mut segments = Vec::new();
        mesh_stems_by_segment(skeleton, options, &mut mesh.bark, &mut segments);
        let mut lists: [LodList; 4] = Default::default();
        let mut kinds: [Vec<&SegmentTriangles>; 3] = Default::default();
        for s in &segments {
            let level = skeleton.stems[s.stem as usize].level as usize;
            kinds[level.min(2)].push(s);
        }
        for (list, items) in lists.iter_mut().zip(&kinds) {
            list.mass = STEM_MASS;
            list.items = items.len();
            // Sized exactly up front: these are the biggest buffers a forest holds.
            let triangles: usize = items.iter().map(|s| s.indices.len()).sum();
            list.indices.reserve_exact(triangles);
            list.index_prefix.reserve_exact(items.len() + 1);
            list.points.reserve_exact(items.len() * 2);
            list.sizes.reserve_exact(items.len() * 2);
            list.normals.reserve_exact(items.len() * 2);
            let (mut dsum, mut lsum) = (0.0f64, 0.0f64);
            for s in items {
                let secs = skeleton.sections_of(crate::StemId(s.stem));
                let (a, b) = (secs[s.section as usize], secs[s.section as usize + 1]);
                dsum += (a.radius + b.radius) as f64;
                lsum += a.position.distance(b.position) as f64;
            }
            let n = items.len().max(1) as f64;
            list.diameter = (dsum / n) as f32;
            list.length = (lsum / n) as f32;
            list.index_prefix.push(0);
            for &i in &rank_major(items.len(), STEM_MASS) {
                let s = items[i as usize];
                list.indices.extend_from_slice(
                    &mesh.bark.indices[s.indices.start as usize..s.indices.end as usize],
                );
                list.index_prefix.push(list.indices.len() as u32);
                let secs = skeleton.sections_of(crate::StemId(s.stem));
                let (a, b) = (secs[s.section as usize], secs[s.section as usize + 1]);
                let axis = (b.position - a.position).normalize_or(glam::Vec3::Z);
                list.points.push(a.position.to_array());
                list.points.push(b.position.to_array());
                list.sizes.extend([a.radius * 2.0, b.radius * 2.0]);
                list.normals.extend([axis.to_array(); 2]);
            }
        }
        let leaves = &mut lists[3];
        let count = skeleton.leaves.len();
        leaves.mass = LEAF_MASS;
        leaves.items = count;
        // Where each leaf's vertices start in the leaf mesh (leaves are meshed in order).
        let mut first_vertex = Vec::with_capacity(count);
        let mut total_indices = 0;
        let mut next = 0u32;
        for l in &skeleton.leaves {
            let t = crate::mesh::leaf_template(l.shape);
            first_vertex.push(next);
            next += t.positions.len() as u32;
            total_indices += t.indices.len();
        }
        leaves.length = skeleton.leaves.iter().map(|l| l.length).sum::<f32>() / count.max(1) as f32;
        leaves.indices.reserve_exact(total_indices);
        leaves.index_prefix.reserve_exact(count + 1);
        leaves.points.reserve_exact(count);
        leaves.sizes.reserve_exact(count);
        leaves.normals.reserve_exact(count);
        leaves.index_prefix.push(0);
        let areas: Vec<f32> = crate::LeafShape::ALL
            .iter()
            .map(|&s| crate::mesh::leaf_template(s).area())
            .collect();
        for &i in &rank_major(count, LEAF_MASS) {
            let i = i as usize;
            let l = &skeleton.leaves[i];
            let t = crate::mesh::leaf_template(l.shape);
            let base = first_vertex[i];
            // The leaf's triangles written straight into rank-major order: the same indices
            // the leaf mesh would hold, without building and copying that buffer.
            leaves.indices.extend(t.indices.iter().map(|&k| base + k));
            leaves.index_prefix.push(leaves.indices.len() as u32);
            let centre = l.position + l.orientation * glam::Vec3::new(0.0, 0.0, l.length / 2.0);
            leaves.points.push(centre.to_array());
            let shape = crate::LeafShape::ALL
                .iter()
                .position(|&s| s == l.shape)
                .unwrap_or(0);
            leaves.sizes.push(l.length * l.width * areas[shape]);
            leaves
                .normals
                .push((l.orientation * glam::Vec3::Y).to_array());
        }
        Self { mesh, lists }
    }

    /// Triangles at full detail.
    pub fn triangle_count(&self) -> usize {
        self.lists.iter().map(|l| l.indices.len() / 3).sum()
    }

    /// Bytes this tree holds: vertices (position, normal, texture coordinate), the lists'
    /// triangles, prefix table and line/point positions.
    pub fn heap_bytes(&self) -> usize {
        let vertices = self.mesh.vertex_count() * (12 + 12 + 8);
        let lists: usize = self
            .lists
            .iter()
            .map(|l| {
                l.indices.len() * 4
                    + l.index_prefix.len() * 4
                    + l.points.len() * 12
                    + l.sizes.len() * 4
                    + l.normals.len() * 12
            })
            .sum();
        vertices + lists + (self.mesh.bark.indices.len() + self.mesh.leaves.indices.len()) * 4
    }

    /// The tree as an ordinary mesh with the first `x[i]` items of every mass of list `i`
    /// (meshes only: lines and points have no place in a triangle mesh). `[16, 16, 16, 4]`
    /// (or more) gives the whole tree. Vertices no triangle uses are dropped.
    pub fn mesh_at(&self, x: [f64; 4]) -> TreeMesh {
        let mut out = TreeMesh::default();
        for (i, list) in self.lists.iter().enumerate() {
            let n = prefix_len(list.items, list.mass, x[i]);
            let part = if i == 3 {
                &mut out.leaves
            } else {
                &mut out.bark
            };
            part.indices
                .extend_from_slice(&list.indices[..list.index_prefix[n] as usize]);
        }
        for (part, source) in [
            (&mut out.bark, &self.mesh.bark),
            (&mut out.leaves, &self.mesh.leaves),
        ] {
            let mut remap = vec![u32::MAX; source.positions.len()];
            for index in part.indices.iter_mut() {
                let old = *index as usize;
                if remap[old] == u32::MAX {
                    remap[old] = part.positions.len() as u32;
                    part.positions.push(source.positions[old]);
                    part.normals.push(source.normals[old]);
                    part.uvs.push(source.uvs[old]);
                    if let Some(&shade) = source.shades.get(old) {
                        part.shades.push(shade);
                    }
                }
                *index = remap[old];
            }
        }
        out
    }

    /// Like [`LodTree::mesh_at`], but the leaves that remain grow about their centres so that
    /// the crown keeps its leaf area (and so its density and colour at range): with half the
    /// leaves, each is 1.41 times as long and wide. The meshes of an engine's LOD chain.
    pub fn engine_mesh(&self, x: [f64; 4]) -> TreeMesh {
        let mut out = self.mesh_at([x[0], x[1], x[2], 0.0]);
        let list = &self.lists[3];
        let n = prefix_len(list.items, list.mass, x[3]);
        if n == 0 {
            return out;
        }
        let grow = (list.items as f32 / n as f32).sqrt();
        let (source, part) = (&self.mesh.leaves, &mut out.leaves);
        let mut remap = vec![u32::MAX; source.positions.len()];
        for p in 0..n {
            let centre = glam::Vec3::from(list.points[p]);
            let range = list.index_prefix[p] as usize..list.index_prefix[p + 1] as usize;
            for &old in &list.indices[range] {
                let old = old as usize;
                if remap[old] == u32::MAX {
                    remap[old] = part.positions.len() as u32;
                    let at = centre + (glam::Vec3::from(source.positions[old]) - centre) * grow;
                    part.positions.push(at.to_array());
                    part.normals.push(source.normals[old]);
                    part.uvs.push(source.uvs[old]);
                    if let Some(&shade) = source.shades.get(old) {
                        part.shades.push(shade);
                    }
                }
                part.indices.push(remap[old]);
            }
        }
        out
    }

    /// An engine's chain of meshes, most detailed first, each with the share of the screen's
    /// height below which the next one takes over (the `MSFT_lod` screen coverage): the whole
    /// tree; half the twigs and leaves; a quarter of the leaves and an eighth of the twigs with
    /// half the branches. Leaves keep the crown's leaf area at every level.
    pub fn engine_chain(&self) -> Vec<(TreeMesh, f32)> {
        [
            ([16.0, 16.0, 16.0, 4.0], 0.5),
            ([16.0, 16.0, 8.0, 2.0], 0.25),
            ([16.0, 8.0, 2.0, 1.0], 0.1),
        ]
        .into_iter()
        .map(|(x, coverage)| (self.engine_mesh(x), coverage))
        .collect()
    }

    /// The whole tree as an ordinary mesh (triangles in rank-major order).
    pub fn full_mesh(&self) -> TreeMesh {
        self.mesh_at([f64::INFINITY; 4])
    }

    /// Draw ranges of the four lists at `range` metres.
    pub fn select(&self, range: f32, viewer: &Viewer) -> [ListDraw; 4] {
        std::array::from_fn(|i| self.lists[i].select(i == 3, range, viewer))
    }

    /// Triangles, lines and points drawn at `range`.
    pub fn counts(&self, range: f32, viewer: &Viewer) -> LodCounts {
        let draws = self.select(range, viewer);
        let mut c = LodCounts::default();
        for (i, d) in draws.iter().enumerate() {
            c.triangles += (d.triangles.end - d.triangles.start) as usize / 3;
            let n = (d.points.end - d.points.start) as usize;
            if i == 3 {
                c.points += n;
            } else {
                c.lines += n / 2;
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
