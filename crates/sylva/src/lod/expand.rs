//! The stored records rebuilt into triangles, lines and points on the CPU: for an engine's
//! meshes, the CPU rasteriser, and as the reference that `sylva-render`'s shader follows
//! (`tube_vertex`, `leaf_vertex`, the line and point of a far stem or leaf).

use super::order::prefix_len;
use super::packed::{Leaf, Quantiser, Segment, class_shade};
use super::{LodTree, Run};
use crate::mesh::{Mesh, TreeMesh, leaf_template};
use crate::skeleton::LeafShape;
use glam::{Quat, Vec3};
use std::f32::consts::TAU;

/// A stem segment unpacked: its rings' centres, radii and frames.
#[derive(Clone, Copy, Debug)]
pub struct Tube {
    /// Centres of the near and far ring.
    pub centre: [Vec3; 2],
    /// Their radii.
    pub radius: [f32; 2],
    /// Their frames (local z along the stem).
    pub frame: [Quat; 2],
}

impl Tube {
    /// Unpacks a segment.
    pub fn of(q: &Quantiser, s: &Segment) -> Self {
        let (ca, ra, fa) = q.unpack_ring(&s.a);
        let (cb, rb, fb) = q.unpack_ring(&s.b);
        Self {
            centre: [ca, cb],
            radius: [ra, rb],
            frame: [fa, fb],
        }
    }

    /// Change of radius per metre along the segment, which tilts the normals of a tapering
    /// stem.
    pub fn slope(&self) -> f32 {
        let length = self.centre[0].distance(self.centre[1]);
        if length > 1e-9 {
            (self.radius[1] - self.radius[0]) / length
        } else {
            0.0
        }
    }

    /// Position and unit normal of vertex `i` (0..=sides) of ring `end` (0 near, 1 far), lobed
    /// by `run`: what the shader's `tube_vertex` computes.
    pub fn vertex(&self, end: usize, i: u32, run: &Run, slope: f32) -> (Vec3, Vec3) {
        let q = self.frame[end];
        let (x, y, z) = (q * Vec3::X, q * Vec3::Y, q * Vec3::Z);
        let t = TAU * i as f32 / run.sides as f32;
        let (sin, cos) = t.sin_cos();
        let radial = x * cos + y * sin;
        let r0 = self.radius[end];
        let (r, in_plane) = if run.lobes > 0 {
            let (ls, lc) = (run.lobes as f32 * t).sin_cos();
            let r = r0 * (1.0 + run.lobe_depth * ls);
            let dr = r0 * run.lobe_depth * run.lobes as f32 * lc;
            let tangent = y * cos - x * sin;
            (r, (radial * r - tangent * dr).normalize_or(radial))
        } else {
            (r0, radial)
        };
        (
            self.centre[end] + radial * r,
            (in_plane - z * slope).normalize_or(radial),
        )
    }

    /// The segment's triangles appended to `mesh`: quads between the rings, or a fan where
    /// the far ring has no radius (a stem's pointed tip).
    pub fn mesh_into(&self, run: &Run, mesh: &mut Mesh) {
        let n = run.sides;
        let slope = self.slope();
        let first = mesh.positions.len() as u32;
        for end in 0..2 {
            for i in 0..=n {
                let (p, normal) = self.vertex(end, i, run, slope);
                mesh.push(p, normal, [i as f32 / n as f32, end as f32]);
            }
            mesh.radii
                .extend(std::iter::repeat_n(self.radius[end], n as usize + 1));
        }
        let (a, b) = (first, first + n + 1);
        for i in 0..n {
            if self.radius[1] > 0.0 {
                mesh.indices.extend_from_slice(&[
                    a + i,
                    a + i + 1,
                    b + i + 1,
                    a + i,
                    b + i + 1,
                    b + i,
                ]);
            } else {
                mesh.indices.extend_from_slice(&[a + i, a + i + 1, b + i]);
            }
        }
    }

    /// A far stem's line: its ends, the diameters there, and its unit direction.
    pub fn line(&self) -> ([Vec3; 2], [f32; 2], Vec3) {
        (
            self.centre,
            self.radius.map(|r| 2.0 * r),
            (self.centre[1] - self.centre[0]).normalize_or(Vec3::Z),
        )
    }
}

/// A leaf unpacked.
#[derive(Clone, Copy, Debug)]
pub struct Card {
    /// Base of the blade.
    pub base: Vec3,
    /// Blade frame: z along the blade, x across, y its normal.
    pub frame: Quat,
    /// Blade length and width, metres.
    pub length: f32,
    /// Width.
    pub width: f32,
    /// Luminance factor.
    pub shade: f32,
}

impl Card {
    /// Unpacks a leaf.
    pub fn of(q: &Quantiser, l: &Leaf) -> Self {
        let (base, frame, length, width, class) = q.unpack_leaf(l);
        Self {
            base,
            frame,
            length,
            width,
            shade: class_shade(class),
        }
    }

    /// The blade's vertices (`outline`'s template placed by the card) and triangles appended
    /// to `mesh`, each vertex with the card's shade when `shaded`; the blade's length and width
    /// grow by `grow` about its centre.
    pub fn mesh_into(&self, outline: LeafShape, grow: f32, shaded: bool, mesh: &mut Mesh) {
        let t = leaf_template(outline);
        let scale = Vec3::new(self.width, self.width, self.length);
        let centre = self.centre();
        let first = mesh.positions.len() as u32;
        for ((p, n), uv) in t.positions.iter().zip(&t.normals).zip(&t.uvs) {
            let at = self.base + self.frame * (*p * scale);
            mesh.push(centre + (at - centre) * grow, self.frame * *n, *uv);
            if shaded {
                mesh.shades.push(self.shade);
            }
        }
        mesh.indices.extend(t.indices.iter().map(|i| first + i));
    }

    /// The middle of the blade, where a far leaf's point stands.
    pub fn centre(&self) -> Vec3 {
        self.base + self.frame * Vec3::new(0.0, 0.0, self.length / 2.0)
    }

    /// The blade's normal.
    pub fn normal(&self) -> Vec3 {
        self.frame * Vec3::Y
    }
}

impl LodTree {
    /// The tree as an ordinary mesh with the first `x[i]` items of every mass of list `i`
    /// (meshes only: lines and points have no place in a triangle mesh). `[16, 16, 16, 4]`
    /// (or more) gives the whole tree.
    pub fn mesh_at(&self, x: [f64; 4]) -> TreeMesh {
        self.expanded(x, false)
    }

    /// Like [`LodTree::mesh_at`], but the leaves that remain grow about their centres so that
    /// the crown keeps its leaf area (and so its density and colour at range): with half the
    /// leaves, each is 1.41 times as long and wide. The meshes of an engine's LOD chain.
    pub fn engine_mesh(&self, x: [f64; 4]) -> TreeMesh {
        self.expanded(x, true)
    }

    fn expanded(&self, x: [f64; 4], keep_leaf_area: bool) -> TreeMesh {
        let q = &self.quantiser;
        let mut out = TreeMesh::default();
        // Every buffer at its final size from the start. A growing Vec moves its contents
        // and maps memory anew at each doubling, and threads that map memory wait on one
        // another in the kernel: a server meshing five trees at once (10 ms each alone) took
        // 100-160 ms over each before, 20-50 ms after.
        let (mut vertices, mut indices) = (0, 0);
        for (i, list) in self.lists[..3].iter().enumerate() {
            for run in &list.runs {
                let n = prefix_len(run.len(), list.mass, x[i]);
                vertices += n * 2 * (run.sides as usize + 1);
                indices += n * 6 * run.sides as usize;
            }
        }
        out.bark.reserve(vertices, indices);
        out.bark.radii.reserve_exact(vertices);
        for (i, list) in self.lists[..3].iter().enumerate() {
            for run in &list.runs {
                let n = prefix_len(run.len(), list.mass, x[i]) as u32;
                for s in &self.segments[run.items.start as usize..(run.items.start + n) as usize] {
                    Tube::of(q, s).mesh_into(run, &mut out.bark);
                }
            }
        }
        // A species whose twigs are darker than its bark shades each vertex by its ring's
        // radius, as `mesh_tree` does (the bark's pattern is left to the full mesh).
        if self.young_bark_darkening > 0.0 {
            let young = 1.0 - self.young_bark_darkening;
            out.bark.shades = (out.bark.radii.iter())
                .map(|&r| crate::mesh::young_bark_shade(r, young))
                .collect();
        }
        let list = &self.lists[3];
        let kept: Vec<(&Run, usize)> = list
            .runs
            .iter()
            .map(|r| (r, prefix_len(r.len(), list.mass, x[3])))
            .collect();
        let drawn: usize = kept.iter().map(|k| k.1).sum();
        let grow = if keep_leaf_area && drawn > 0 {
            (list.items as f32 / drawn as f32).sqrt()
        } else {
            1.0
        };
        let leaves = |run: &Run, n: usize| {
            &self.leaves[run.items.start as usize..run.items.start as usize + n]
        };
        let shaded = kept
            .iter()
            .any(|&(r, n)| leaves(r, n).iter().any(|l| l.xyzs[3] >> 12 < 10));
        let (vertices, indices) = kept.iter().fold((0, 0), |(v, i), &(run, n)| {
            let t = leaf_template(run.shape);
            (v + n * t.positions.len(), i + n * t.indices.len())
        });
        out.leaves.reserve(vertices, indices);
        if shaded {
            out.leaves.shades.reserve_exact(vertices);
        }
        for (run, n) in kept {
            for l in leaves(run, n) {
                Card::of(q, l).mesh_into(run.shape, grow, shaded, &mut out.leaves);
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
}
