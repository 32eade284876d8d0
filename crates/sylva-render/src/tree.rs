//! A tree ready to draw: its vertices in the renderer's own layout, kept in memory so that any
//! backend (the GPU, or the CPU rasteriser after a GPU failure) can draw it, plus the GPU's
//! buffers when it was uploaded to one.

use crate::props::Vertex;
use glam::Vec3;
use sylva::mesh::{Mesh, TreeMesh};

/// Triangles of one material.
#[derive(Debug, Default)]
pub(crate) struct MeshData {
    pub vertices: Vec<Vertex>,
    pub indices: Vec<u32>,
}

/// Everything a backend needs to draw a tree: a mesh, or a tree stored for range (its packed
/// segments and leaf cards, which the GPU rebuilds each frame and the CPU unpacks as it draws).
#[derive(Debug, Default)]
pub(crate) struct TreeData {
    pub bark: MeshData,
    pub leaves: MeshData,
    pub lod: Option<sylva::lod::LodTree>,
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
    /// Unique among the trees of this process: what baked impostors are kept under.
    pub(crate) id: u64,
}

/// A mesh in the renderer's vertex layout.
pub(crate) fn mesh_data(mesh: &Mesh) -> MeshData {
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

fn bounds(data: &TreeData) -> (Vec3, Vec3) {
    let (lo, hi) = [&data.bark, &data.leaves]
        .iter()
        .flat_map(|m| &m.vertices)
        .fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), v| {
                (
                    lo.min(Vec3::from(v.position)),
                    hi.max(Vec3::from(v.position)),
                )
            },
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
            // The twig copies a model file draws instanced (`MeshOptions::twig_copies`) are
            // drawn here as the bark they stand for.
            bark: mesh_data(&mesh.bark_with_twigs()),
            leaves: mesh_data(&mesh.leaves),
            lod: None,
        }
    }
}

/// The tree's data with its bounds, before any GPU upload.
pub(crate) fn prepare(data: TreeData, triangles: usize) -> RenderTree {
    let (lo, hi) = match &data.lod {
        Some(lod) => lod.quantiser.bounds(),
        None => bounds(&data),
    };
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    RenderTree {
        data,
        gpu: None,
        lo,
        hi,
        triangles,
        id: NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
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

/// A tree stored for range: its packed segments and leaf cards, read by the shader as
/// instances.
#[derive(Debug)]
pub(crate) struct GpuLod {
    pub segments: wgpu::Buffer,
    pub leaves: wgpu::Buffer,
}

/// A tree's GPU buffers.
#[derive(Debug)]
pub(crate) struct TreeBuffers {
    pub bark: GpuMesh,
    pub leaves: GpuMesh,
    pub lod: Option<GpuLod>,
}
