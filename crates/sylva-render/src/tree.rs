//! A tree ready to draw: its vertices in the renderer's own layout, kept in memory so that any
//! backend (the GPU, or the CPU rasteriser after a GPU failure) can draw it, plus the GPU's
//! buffers when it was uploaded to one.

use crate::props::Vertex;
use glam::Vec3;
use sylva::mesh::{Mesh, TreeMesh};

/// A line or point vertex: position, the size of what it stands for (stem diameter or blade
/// area) and a unit direction for lighting (stem axis or blade normal).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct FlatVertex {
    pub position: [f32; 3],
    pub size: f32,
    pub normal: [i8; 4],
}

/// Triangles of one material.
#[derive(Debug, Default)]
pub(crate) struct MeshData {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

/// The rank-major lists of a [`sylva::lod::LodTree`]: per list (trunk, branches, twigs,
/// leaves), triangle indices into the bark or leaf vertices, and line/point vertices.
#[derive(Debug)]
pub(crate) struct LodData {
    pub indices: [Vec<u32>; 4],
    pub points: [Vec<FlatVertex>; 4],
    /// The lists without their big buffers: enough to choose draw ranges.
    pub choice: [sylva::lod::LodList; 4],
}

/// Everything a backend needs to draw a tree.
#[derive(Debug, Default)]
pub(crate) struct TreeData {
    pub bark: MeshData,
    pub leaves: MeshData,
    pub lod: Option<LodData>,
}

/// A tree uploaded to a [`crate::Renderer`]: bark and leaves, with their bounds.
#[derive(Debug)]
pub struct RenderTree {
    pub(crate) data: TreeData,
    /// The GPU's copy, when the renderer has a GPU and the upload succeeded.
    pub(crate) gpu: Option<TreeBuffers>,
    /// Lowest corner of the tree's bounds (metres, Z up).
    pub lo: Vec3,
    /// Highest corner.
    pub hi: Vec3,
    /// Triangles uploaded (bark + leaves).
    pub triangles: usize,
}

fn mesh_data(mesh: &Mesh) -> MeshData {
    let vertices = mesh
        .positions
        .iter()
        .zip(&mesh.normals)
        .enumerate()
        .map(|(i, (p, n))| Vertex {
            position: *p,
            normal: *n,
            shade: mesh.shades.get(i).copied().unwrap_or(1.0),
        })
        .collect();
    MeshData {
        vertices,
        indices: mesh.indices.clone(),
    }
}

fn bounds(mesh: &TreeMesh) -> (Vec3, Vec3) {
    let (lo, hi) = [&mesh.bark, &mesh.leaves]
        .iter()
        .filter_map(|m| m.bounds())
        .fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), (a, b)| (lo.min(Vec3::from(a)), hi.max(Vec3::from(b))),
        );
    if lo.x <= hi.x {
        (lo, hi)
    } else {
        (Vec3::ZERO, Vec3::ONE)
    }
}

impl TreeData {
    pub fn from_mesh(mesh: &TreeMesh) -> Self {
        Self {
            bark: mesh_data(&mesh.bark),
            leaves: mesh_data(&mesh.leaves),
            lod: None,
        }
    }

    pub fn from_lod(lod: &sylva::lod::LodTree) -> Self {
        let snorm = |v: f32| (v.clamp(-1.0, 1.0) * 127.0).round() as i8;
        Self {
            lod: Some(LodData {
                indices: std::array::from_fn(|i| lod.lists[i].indices.clone()),
                points: std::array::from_fn(|i| {
                    let l = &lod.lists[i];
                    l.points
                        .iter()
                        .zip(&l.sizes)
                        .zip(&l.normals)
                        .map(|((p, &size), n)| FlatVertex {
                            position: *p,
                            size,
                            normal: [snorm(n[0]), snorm(n[1]), snorm(n[2]), 0],
                        })
                        .collect()
                }),
                choice: std::array::from_fn(|i| {
                    let l = &lod.lists[i];
                    sylva::lod::LodList {
                        mass: l.mass,
                        items: l.items,
                        indices: Vec::new(),
                        index_prefix: l.index_prefix.clone(),
                        points: Vec::new(),
                        sizes: Vec::new(),
                        normals: Vec::new(),
                        diameter: l.diameter,
                        length: l.length,
                    }
                }),
            }),
            ..Self::from_mesh(&lod.mesh)
        }
    }
}

/// The tree's data with its bounds, before any GPU upload.
pub(crate) fn prepare(mesh: &TreeMesh, data: TreeData, triangles: usize) -> RenderTree {
    let (lo, hi) = bounds(mesh);
    RenderTree {
        data,
        gpu: None,
        lo,
        hi,
        triangles,
    }
}

// The GPU's buffers for a tree are declared here, beside the data they hold, and made by
// `gpu::buffers`: the backend depends on the tree, not the other way round.

/// One piece of a mesh: its own vertices and the triangles that use them.
#[derive(Debug)]
pub(crate) struct GpuPart {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub count: u32,
}

/// A mesh as one or more parts; more than one only when it outgrows `max_buffer_size`.
#[derive(Debug)]
pub(crate) struct GpuMesh {
    pub parts: Vec<GpuPart>,
}

/// Per list of a range-degraded tree: triangle indices into the bark or leaf vertices, and
/// line or point vertices.
#[derive(Debug)]
pub(crate) struct GpuLod {
    pub indices: [wgpu::Buffer; 4],
    pub points: [wgpu::Buffer; 4],
}

/// A tree's GPU buffers.
#[derive(Debug)]
pub(crate) struct TreeBuffers {
    pub bark: GpuMesh,
    pub leaves: GpuMesh,
    pub lod: Option<GpuLod>,
}
