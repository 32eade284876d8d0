//! A tree's buffers on the GPU, cut to fit the device's largest buffer.

use crate::props::Vertex;
use crate::tree::{GpuLod, GpuMesh, GpuPart, MeshData, TreeBuffers, TreeData};

/// A buffer with `contents`; wgpu refuses empty buffers, so an empty one keeps 12 zero bytes.
///
/// Not `DeviceExt::create_buffer_init`: that `expect`s the new buffer's mapping, so a buffer the
/// device refuses (out of memory, over a limit) would panic. Here a refused buffer simply gets
/// no contents; its error reaches the caller's error scope.
pub(crate) fn buffer(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let contents = if contents.is_empty() {
        &[0u8; 12][..]
    } else {
        contents
    };
    let size = (contents.len() as u64).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: true,
    });
    if let Ok(mut view) = buffer.get_mapped_range_mut(..) {
        view.slice(..contents.len()).copy_from_slice(contents);
    }
    buffer.unmap();
    buffer
}

/// Cuts `indices` into runs of whole triangles whose vertices and indices each fit in
/// `max_bytes`, each with its own compact vertex list. One run when everything fits.
pub(crate) fn split(
    vertices: &[Vertex],
    indices: &[u32],
    max_bytes: u64,
) -> Vec<(Vec<Vertex>, Vec<u32>)> {
    let vertex_size = std::mem::size_of::<Vertex>() as u64;
    let fits =
        |v: usize, i: usize| v as u64 * vertex_size <= max_bytes && i as u64 * 4 <= max_bytes;
    if fits(vertices.len(), indices.len()) {
        return vec![(vertices.to_vec(), indices.to_vec())];
    }
    // At most this many vertices and indices per part, whole triangles (a triangle adds at
    // most three new vertices).
    let max_indices = ((max_bytes / 4) as usize / 3 * 3).max(3);
    let max_vertices = ((max_bytes / vertex_size) as usize).max(3);
    let mut parts = Vec::new();
    let mut remap = vec![u32::MAX; vertices.len()];
    let mut part = (Vec::new(), Vec::new());
    for triangle in indices.chunks_exact(3) {
        if part.1.len() + 3 > max_indices || part.0.len() + 3 > max_vertices {
            remap.fill(u32::MAX);
            parts.push(std::mem::take(&mut part));
        }
        for &i in triangle {
            let slot = &mut remap[i as usize];
            if *slot == u32::MAX {
                *slot = part.0.len() as u32;
                part.0.push(vertices[i as usize]);
            }
            part.1.push(*slot);
        }
    }
    if !part.1.is_empty() {
        parts.push(part);
    }
    parts
}

fn upload_mesh(device: &wgpu::Device, label: &str, mesh: &MeshData, max_bytes: u64) -> GpuMesh {
    let parts = split(&mesh.vertices, &mesh.indices, max_bytes)
        .into_iter()
        .map(|(v, i)| GpuPart {
            // Empty buffers get a few zero bytes (see `buffer`): a tree stored for range
            // degradation has vertices but no triangles of its own (its lists hold them).
            vertices: buffer(
                device,
                label,
                bytemuck::cast_slice(&v),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer(
                device,
                label,
                bytemuck::cast_slice(&i),
                wgpu::BufferUsages::INDEX,
            ),
            count: i.len() as u32,
        })
        .collect();
    GpuMesh { parts }
}

/// Uploads `data`: a mesh cut to fit `max_bytes` per buffer, or a tree stored for range as
/// its records (`None` when they are over the limit: a draw reads them from one buffer).
pub(crate) fn upload(
    device: &wgpu::Device,
    data: &TreeData,
    max_bytes: u64,
) -> Option<TreeBuffers> {
    let bark = upload_mesh(device, "bark", &data.bark, max_bytes);
    let leaves = upload_mesh(device, "leaves", &data.leaves, max_bytes);
    let lod = match &data.lod {
        None => None,
        Some(lod) => {
            let (segments, cards): (&[u8], &[u8]) = (
                bytemuck::cast_slice(&lod.segments),
                bytemuck::cast_slice(&lod.leaves),
            );
            if segments.len().max(cards.len()) as u64 > max_bytes {
                return None;
            }
            Some(GpuLod {
                segments: buffer(device, "segments", segments, wgpu::BufferUsages::VERTEX),
                leaves: buffer(device, "leaf cards", cards, wgpu::BufferUsages::VERTEX),
            })
        }
    };
    Some(TreeBuffers { bark, leaves, lod })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(i: u32) -> Vertex {
        Vertex {
            position: [i as f32, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            shade: 1.0,
        }
    }

    #[test]
    fn split_keeps_every_triangle_within_the_limit() {
        // A strip of 1000 triangles over 502 vertices, cut to 1 kB parts.
        let vertices: Vec<Vertex> = (0..502).map(vertex).collect();
        let indices: Vec<u32> = (0..1000u32)
            .flat_map(|t| [t / 2, t / 2 + 1, t / 2 + 2])
            .collect();
        let parts = split(&vertices, &indices, 1024);
        assert!(parts.len() > 1);
        let mut triangles = Vec::new();
        for (v, i) in &parts {
            assert!(std::mem::size_of_val(v.as_slice()) <= 1024);
            assert!(i.len() * 4 <= 1024);
            assert_eq!(i.len() % 3, 0);
            triangles.extend(i.chunks(3).map(|t| {
                t.iter()
                    .map(|&k| v[k as usize].position[0])
                    .collect::<Vec<_>>()
            }));
        }
        let expected: Vec<Vec<f32>> = indices
            .chunks(3)
            .map(|t| t.iter().map(|&k| k as f32).collect())
            .collect();
        assert_eq!(triangles, expected, "same triangles, same order");
        assert_eq!(split(&vertices, &indices, 1 << 20).len(), 1);
    }
}
