//! Recording a frame's draws: which buffers each reads, and the calls that draw them.

use super::pipelines::{COPY_STRIDE, Pipelines};
use crate::RenderError;
use crate::frame::{Draw, Frame, InstanceData, Part, Primitive};

/// The frame's own buffers (the props).
pub(super) struct Props {
    pub ground: crate::tree::GpuPart,
    pub person: crate::tree::GpuPart,
}

/// Buffers one draw reads.
pub(super) enum Source<'a> {
    /// Indexed triangles, placed by the instance buffer.
    Mesh {
        vertices: &'a wgpu::Buffer,
        indices: &'a wgpu::Buffer,
        /// The part's own index count when a mesh is cut into parts (each drawn whole).
        whole: Option<u32>,
    },
    /// A stored tree's records, one per instance, placed by the draw's copy entry.
    Stored {
        records: &'a wgpu::Buffer,
        /// What each record draws.
        each: Each,
        /// Index of the leaf outline in [`super::pipelines::Templates`].
        shape: usize,
    },
    /// A quad of six vertices made by the shader, showing the atlas (bind group 3).
    Impostor,
}

/// What one record of a stored tree draws.
#[derive(Clone, Copy)]
pub(super) enum Each {
    /// A tube of this many sides, through the shared index buffer of tube sides.
    Tube(u32),
    /// A leaf card: its outline's template.
    Card,
    /// This many vertices: a line's 2, a point's 1.
    Vertices(u32),
}

/// What a stored tree's draw reads from the shader's copy entry: where the copy stands and the
/// scales of its records (the layout of `Copy` in the shader).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct CopyData {
    place: [f32; 4],
    turn: [f32; 4],
    lo: [f32; 4],
    size: [f32; 4],
    run: [f32; 4],
    sway: [f32; 4],
}

/// The copy entries of a frame's stored-tree draws, `COPY_STRIDE` bytes apart, and each draw's
/// offset (0 for draws that read none).
pub(super) fn copies(frame: &Frame) -> (Vec<u8>, Vec<u32>) {
    let mut bytes = Vec::new();
    let offsets = frame
        .draws
        .iter()
        .map(|d| {
            let i = &frame.instances[d.instances.start as usize];
            let data = match (d.part, d.part.run()) {
                (Part::Impostor { cell, .. }, _) => impostor_copy(i, &cell),
                (_, Some((lod, run))) => stored_copy(d, i, lod, run),
                _ => return 0,
            };
            let offset = bytes.len() as u32;
            bytes.extend_from_slice(bytemuck::bytes_of(&data));
            bytes.resize(offset as usize + COPY_STRIDE as usize, 0);
            offset
        })
        .collect();
    if bytes.is_empty() {
        bytes.resize(COPY_STRIDE as usize, 0);
    }
    (bytes, offsets)
}

/// The copy entry of an impostor: where it stands and the atlas cell it shows (`impostor.wgsl`).
fn impostor_copy(i: &InstanceData, cell: &crate::impostor::Cell) -> CopyData {
    CopyData {
        place: i.place,
        turn: [i.turn[0], i.turn[1], 0.0, 0.0],
        lo: [
            cell.x0 as f32,
            cell.y0 as f32,
            cell.width as f32,
            cell.half_width,
        ],
        size: [cell.bottom, cell.top, 0.0, 0.0],
        run: [0.0; 4],
        sway: i.sway,
    }
}

/// The copy entry of a stored tree's run: where it stands and its records' scales.
fn stored_copy(
    d: &Draw,
    i: &InstanceData,
    lod: &sylva::lod::LodTree,
    run: &sylva::lod::Run,
) -> CopyData {
    let q = &lod.quantiser;
    let card = match d.part {
        Part::Run { card, .. } => card,
        _ => run.shape,
    };
    CopyData {
        place: i.place,
        turn: [
            i.turn[0],
            i.turn[1],
            i.stands_for[0],
            sylva::lod::card_scale(run.shape, card, i.stands_for[1]),
        ],
        lo: q.lo.extend(q.radius).to_array(),
        size: q.size.extend(q.leaf_length).to_array(),
        run: if run.sides > 0 {
            [
                run.sides as f32,
                run.lobes as f32,
                run.lobe_depth,
                q.leaf_width,
            ]
        } else {
            let area = sylva::mesh::leaf_template(run.shape).area();
            [area, 0.0, 0.0, q.leaf_width]
        },
        sway: i.sway,
    }
}

impl Props {
    pub fn sources<'a>(&'a self, d: &Draw<'a>) -> Result<Vec<Source<'a>>, RenderError> {
        let missing = || RenderError::Gpu {
            what: "drawing a frame",
            message: "a tree was not uploaded to this device".into(),
        };
        let part = |p: &'a crate::tree::GpuPart, whole| Source::Mesh {
            vertices: &p.vertices,
            indices: &p.indices,
            whole,
        };
        Ok(match d.part {
            Part::Ground => vec![part(&self.ground, None)],
            Part::Impostor { .. } => vec![Source::Impostor],
            Part::Person => vec![part(&self.person, None)],
            Part::Mesh { tree, leaves } => {
                let gpu = tree.gpu.as_ref().ok_or_else(missing)?;
                let mesh = if leaves { &gpu.leaves } else { &gpu.bark };
                match mesh.parts.as_slice() {
                    [one] => vec![part(one, None)],
                    many => many.iter().map(|p| part(p, Some(p.count))).collect(),
                }
            }
            Part::Run {
                tree,
                list,
                flat,
                card,
                ..
            } => {
                let gpu = tree.gpu.as_ref().ok_or_else(missing)?;
                let lod = gpu.lod.as_ref().ok_or_else(missing)?;
                let (_, run) = d.part.run().ok_or_else(missing)?;
                let shape = sylva::LeafShape::ALL
                    .iter()
                    .position(|&s| s == card)
                    .unwrap_or(0);
                let leaves = list == 3;
                let records = if leaves { &lod.leaves } else { &lod.segments };
                let each = match (leaves, flat) {
                    (false, false) => Each::Tube(run.sides),
                    (false, true) => Each::Vertices(2),
                    (true, false) => Each::Card,
                    (true, true) => Each::Vertices(1),
                };
                vec![Source::Stored {
                    records,
                    each,
                    shape,
                }]
            }
        })
    }
}

/// The pipeline of a draw in the colour pass (`shadow`: the shadow pass).
pub(super) fn pipeline<'p>(p: &'p Pipelines, d: &Draw, shadow: bool) -> &'p wgpu::RenderPipeline {
    if let Part::Impostor { .. } = d.part {
        // Impostors cast no shadow: their trees' own draws do.
        return if shadow {
            &p.shadow_triangles
        } else {
            &p.impostors
        };
    }
    let pair = match (d.part, d.primitive) {
        (Part::Run { list: 3, .. }, Primitive::Triangles) => &p.cards,
        (Part::Run { list: 3, .. }, _) => &p.dots,
        (Part::Run { .. }, Primitive::Triangles) => &p.tubes,
        (Part::Run { .. }, _) => &p.axes,
        _ if shadow => return &p.shadow_triangles,
        (Part::Mesh { leaves: true, .. }, _) => return &p.leaf_triangles,
        _ => return &p.triangles,
    };
    match (shadow, d.part) {
        (true, _) => &pair.shadow,
        (false, Part::Run { fading: true, .. }) => &pair.fading,
        _ => &pair.colour,
    }
}

/// Records one draw of `range` (its records, for a stored tree).
pub(super) fn record(
    pass: &mut wgpu::RenderPass<'_>,
    d: &Draw,
    sources: &[Source],
    draw_buffers: (
        &wgpu::Buffer,
        &wgpu::BindGroup,
        u32,
        Option<&wgpu::BindGroup>,
    ),
    templates: &super::pipelines::Templates,
    range: std::ops::Range<u32>,
) {
    if range.is_empty() || d.instances.is_empty() {
        return;
    }
    let (instances, copy_group, copy_offset, atlas) = draw_buffers;
    for s in sources {
        match *s {
            Source::Mesh {
                vertices,
                indices,
                whole,
            } => {
                // A mesh cut into parts is only ever drawn whole.
                let range = whole.map_or(range.clone(), |n| 0..n);
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.set_vertex_buffer(1, instances.slice(..));
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(range, 0, d.instances.clone());
            }
            Source::Impostor => {
                if let Some(atlas) = atlas {
                    pass.set_bind_group(2, copy_group, &[copy_offset]);
                    pass.set_bind_group(3, atlas, &[]);
                    pass.draw(0..6, 0..1);
                }
            }
            Source::Stored {
                records,
                each,
                shape,
            } => {
                pass.set_bind_group(2, copy_group, &[copy_offset]);
                // The whole buffer, its records picked by the first instance. Bound at a new
                // offset for every draw instead, lavapipe spent three quarters of a stand's
                // frame of lines (11 s) in LLVM, compiling as the offsets changed; now 1.6 s.
                let items = records.slice(..);
                let count = range.clone();
                match each {
                    Each::Vertices(n) => {
                        pass.set_vertex_buffer(0, items);
                        pass.draw(0..n, count);
                    }
                    Each::Tube(sides) => {
                        pass.set_vertex_buffer(0, items);
                        pass.set_index_buffer(templates.tube.slice(..), wgpu::IndexFormat::Uint32);
                        pass.draw_indexed(0..6 * sides, 0, count);
                    }
                    Each::Card => {
                        let (first, indices, base) = templates.ranges[shape];
                        pass.set_vertex_buffer(0, templates.vertices.slice(..));
                        pass.set_vertex_buffer(1, items);
                        pass.set_index_buffer(
                            templates.indices.slice(..),
                            wgpu::IndexFormat::Uint32,
                        );
                        pass.draw_indexed(first..first + indices, base, count);
                    }
                }
            }
        }
    }
}
