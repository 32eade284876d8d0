//! Recording a frame's draws: which buffers each reads, and the calls that draw them.

use crate::RenderError;
use crate::frame::{Draw, Part};

/// The frame's own buffers (the props).
pub(super) struct Props {
    pub ground: crate::tree::GpuPart,
    pub person: crate::tree::GpuPart,
}

/// Buffers one draw reads: vertices, and indices for triangles.
pub(super) struct Source<'a> {
    vertices: &'a wgpu::Buffer,
    indices: Option<&'a wgpu::Buffer>,
    /// The part's own triangle count when a mesh is cut into parts (each drawn whole).
    whole: Option<u32>,
}

impl Props {
    pub fn sources<'a>(&'a self, d: &Draw<'a>) -> Result<Vec<Source<'a>>, RenderError> {
        let missing = || RenderError::Gpu {
            what: "drawing a frame",
            message: "a tree was not uploaded to this device".into(),
        };
        let part = |p: &'a crate::tree::GpuPart, whole| Source {
            vertices: &p.vertices,
            indices: Some(&p.indices),
            whole,
        };
        Ok(match d.part {
            Part::Ground => vec![part(&self.ground, None)],
            Part::Person => vec![part(&self.person, None)],
            Part::Mesh { tree, leaves } => {
                let gpu = tree.gpu.as_ref().ok_or_else(missing)?;
                let mesh = if leaves { &gpu.leaves } else { &gpu.bark };
                match mesh.parts.as_slice() {
                    [one] => vec![part(one, None)],
                    many => many.iter().map(|p| part(p, Some(p.count))).collect(),
                }
            }
            Part::LodTriangles { tree, list } => {
                let gpu = tree.gpu.as_ref().ok_or_else(missing)?;
                let lod = gpu.lod.as_ref().ok_or_else(missing)?;
                let mesh = if list == 3 { &gpu.leaves } else { &gpu.bark };
                vec![Source {
                    vertices: &mesh.parts.first().ok_or_else(missing)?.vertices,
                    indices: Some(&lod.indices[list]),
                    whole: None,
                }]
            }
            Part::LodFlat { tree, list } => {
                let gpu = tree.gpu.as_ref().ok_or_else(missing)?;
                let lod = gpu.lod.as_ref().ok_or_else(missing)?;
                vec![Source {
                    vertices: &lod.points[list],
                    indices: None,
                    whole: None,
                }]
            }
        })
    }
}

pub(super) fn record(
    pass: &mut wgpu::RenderPass<'_>,
    d: &Draw,
    sources: &[Source],
    instances: &wgpu::Buffer,
    range: std::ops::Range<u32>,
) {
    if range.is_empty() || d.instances.is_empty() {
        return;
    }
    for s in sources {
        // A mesh cut into parts is only ever drawn whole.
        let range = s.whole.map_or(range.clone(), |n| 0..n);
        pass.set_vertex_buffer(0, s.vertices.slice(..));
        pass.set_vertex_buffer(1, instances.slice(..));
        match s.indices {
            Some(indices) => {
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(range, 0, d.instances.clone());
            }
            None => pass.draw(range, d.instances.clone()),
        }
    }
}
