//! Leaves meshed on every core, straight into the final buffers.
//!
//! A leaf's vertices and triangles depend on that leaf alone and take a fixed number of slots
//! (its template's), so runs of leaves can be meshed at once, each into its own stretch of the
//! buffers' spare capacity, with the very bytes one thread writes in order. Nothing is zeroed
//! first and nothing is copied after: for a willow's half a million leaves that would cost as
//! much as the meshing saves.

use super::Mesh;
use super::leaves::{Templates, corners, count, luminance};
use crate::skeleton::{Leaf, Skeleton};
use rayon::prelude::*;
use std::mem::MaybeUninit;

/// Leaves meshed by one task.
const RUN: usize = 4096;

/// Below this many leaves one thread is quicker than sharing out.
const APART_FROM: usize = 4 * RUN;

/// One run's stretch of each buffer.
struct Stretch<'a> {
    positions: &'a mut [MaybeUninit<[f32; 3]>],
    normals: &'a mut [MaybeUninit<[f32; 3]>],
    uvs: &'a mut [MaybeUninit<[f32; 2]>],
    indices: &'a mut [MaybeUninit<u32>],
    shades: &'a mut [MaybeUninit<f32>],
    /// Index of the run's first vertex in the whole mesh.
    first: u32,
}

/// Meshes `skeleton`'s leaves into `mesh` on every core where that pays (enough leaves, more
/// than one thread, `mesh` empty) and returns true; otherwise, or if the counts did not come
/// out as planned (they always do: the same templates size and fill the buffers), returns
/// false with `mesh` as it was, and the caller meshes them on one thread.
pub(super) fn mesh_leaves_apart(skeleton: &Skeleton, mesh: &mut Mesh) -> bool {
    let empty = mesh.positions.is_empty() && mesh.indices.is_empty() && mesh.shades.is_empty();
    if !empty || skeleton.leaves.len() < APART_FROM || rayon::current_num_threads() < 2 {
        return false;
    }
    let runs: Vec<&[Leaf]> = skeleton.leaves.chunks(RUN).collect();
    // Vertices and indices of each run.
    let sizes: Vec<(usize, usize)> = runs.iter().map(|run| count(run)).collect();
    let vertices: usize = sizes.iter().map(|s| s.0).sum();
    let indices: usize = sizes.iter().map(|s| s.1).sum();
    let shaded = skeleton.leaves.iter().any(|l| l.light < 1.0);
    let shades = if shaded { vertices } else { 0 };
    mesh.positions.reserve_exact(vertices);
    mesh.normals.reserve_exact(vertices);
    mesh.uvs.reserve_exact(vertices);
    mesh.indices.reserve_exact(indices);
    mesh.shades.reserve_exact(shades);
    let mut stretches = Vec::with_capacity(runs.len());
    {
        let mut positions = &mut mesh.positions.spare_capacity_mut()[..vertices];
        let mut normals = &mut mesh.normals.spare_capacity_mut()[..vertices];
        let mut uvs = &mut mesh.uvs.spare_capacity_mut()[..vertices];
        let mut index_slots = &mut mesh.indices.spare_capacity_mut()[..indices];
        let mut shade_slots = &mut mesh.shades.spare_capacity_mut()[..shades];
        let mut first = 0u32;
        for &(v, i) in &sizes {
            let s = if shaded { v } else { 0 };
            stretches.push(Stretch {
                positions: take(&mut positions, v),
                normals: take(&mut normals, v),
                uvs: take(&mut uvs, v),
                indices: take(&mut index_slots, i),
                shades: take(&mut shade_slots, s),
                first,
            });
            first += v as u32;
        }
    }
    let filled = runs
        .into_par_iter()
        .zip(stretches)
        .map(|(run, stretch)| fill(run, stretch, shaded))
        .collect::<Vec<bool>>();
    if !filled.iter().all(|&f| f) {
        return false;
    }
    // SAFETY: the stretches tile the first `vertices` (`indices`, `shades`) slots of each
    // buffer's spare capacity, and every stretch reported each of its slots written (`fill`
    // writes slot by slot and checks it reached the end of every stretch).
    unsafe {
        mesh.positions.set_len(vertices);
        mesh.normals.set_len(vertices);
        mesh.uvs.set_len(vertices);
        mesh.indices.set_len(indices);
        mesh.shades.set_len(shades);
    }
    true
}

/// The first `n` slots of `rest`, leaving the others in it.
fn take<'a, T>(rest: &mut &'a mut [T], n: usize) -> &'a mut [T] {
    let (head, tail) = std::mem::take(rest).split_at_mut(n);
    *rest = tail;
    head
}

/// Writes one run of leaves into its stretch, as `leaves::leaf_vertices` and
/// `leaves::mesh_leaves` write them; true if every slot of the stretch was written.
fn fill(run: &[Leaf], out: Stretch<'_>, shaded: bool) -> bool {
    let (mut v, mut i) = (0usize, 0usize);
    let mut templates = Templates::default();
    for leaf in run {
        let template = templates.of(leaf.shape);
        let t = template.0;
        let n = t.positions.len();
        let whole = t.normals.len() == n && t.uvs.len() == n;
        if !whole || v + n > out.positions.len() || i + t.indices.len() > out.indices.len() {
            return false;
        }
        let base = out.first + v as u32;
        for (k, (p, normal, uv)) in corners(leaf, template).enumerate() {
            out.positions[v + k].write(p.to_array());
            out.normals[v + k].write(normal.to_array());
            out.uvs[v + k].write(uv);
            if shaded {
                out.shades[v + k].write(luminance(leaf.light));
            }
        }
        for (slot, &j) in out.indices[i..i + t.indices.len()]
            .iter_mut()
            .zip(&t.indices)
        {
            slot.write(base + j);
        }
        v += n;
        i += t.indices.len();
    }
    v == out.positions.len() && i == out.indices.len() && (!shaded || v == out.shades.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{MeshOptions, mesh_tree};

    /// An aspen's 22,000 leaves, half of them in some shade, meshed on one thread and on three
    /// (in runs, straight into the buffers): the same bytes.
    #[test]
    fn leaves_meshed_apart_are_the_leaves_meshed_in_order() {
        let params = crate::species::builtin("quaking_aspen").expect("built-in");
        let mut skeleton = crate::generate(&params, &Default::default()).expect("grows");
        assert!(
            skeleton.leaves.len() >= APART_FROM,
            "{}",
            skeleton.leaves.len()
        );
        for (k, leaf) in skeleton.leaves.iter_mut().enumerate() {
            leaf.light = (k % 7) as f32 / 6.0;
        }
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool")
                .install(|| mesh_tree(&skeleton, &MeshOptions::default()))
        };
        let (one, three) = (on(1), on(3));
        assert_eq!(one.leaves.shades.len(), one.leaves.vertex_count());
        assert!(one.leaves.shades.iter().any(|&s| s < 1.0));
        assert!(one == three, "the leaf meshes differ");
        // And the bark is untouched by it.
        assert!(one.bark.triangle_count() > 0 && one.bark == three.bark);
    }
}
