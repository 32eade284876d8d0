//! Meshing on every core, straight into the final buffers.
//!
//! A stem's or a leaf's vertices and triangles depend on it alone and take a number of slots
//! known before meshing, so runs of them can be meshed at once, each into its own stretch of
//! the buffers' spare capacity, with the very bytes one thread writes in order. Nothing is
//! zeroed first and nothing is copied after: for a willow's half a million leaves that would
//! cost as much as the meshing saves. `stems` and `leaves_apart` say what a run is.

use super::Mesh;
use glam::Vec3;
use rayon::prelude::*;
use std::mem::MaybeUninit;

/// Where meshing writes: a whole [`Mesh`] (one thread, in order) or one run's [`Stretch`].
pub(super) trait Sink {
    /// Index, in the whole mesh, of the next vertex written.
    fn next_vertex(&self) -> u32;
    /// Writes a vertex; its index in the whole mesh.
    fn vertex(&mut self, position: Vec3, normal: Vec3, uv: [f32; 2]) -> u32;
    /// Writes triangle indices.
    fn indices(&mut self, indices: &[u32]);
    /// Writes the shade of the next vertex whose shade is not yet written (meshes with shades
    /// give every vertex one).
    fn shade(&mut self, shade: f32);
}

impl Sink for Mesh {
    fn next_vertex(&self) -> u32 {
        self.positions.len() as u32
    }

    fn vertex(&mut self, position: Vec3, normal: Vec3, uv: [f32; 2]) -> u32 {
        self.push(position, normal, uv)
    }

    fn indices(&mut self, indices: &[u32]) {
        self.indices.extend_from_slice(indices);
    }

    fn shade(&mut self, shade: f32) {
        self.shades.push(shade);
    }
}

/// One run's stretch of each buffer, written slot by slot from the start.
pub(super) struct Stretch<'a> {
    positions: &'a mut [MaybeUninit<[f32; 3]>],
    normals: &'a mut [MaybeUninit<[f32; 3]>],
    uvs: &'a mut [MaybeUninit<[f32; 2]>],
    indices: &'a mut [MaybeUninit<u32>],
    shades: &'a mut [MaybeUninit<f32>],
    /// Index of the run's first vertex in the whole mesh.
    first: u32,
    /// Slots written so far (vertices, indices, shades).
    written: (usize, usize, usize),
    /// Set when a write found no slot left: the run did not mesh as counted.
    overflowed: bool,
}

impl Stretch<'_> {
    /// Writes `indices` each raised by `base` (a template's triangles placed at a vertex).
    pub(super) fn indices_from(&mut self, base: u32, indices: &[u32]) {
        let at = self.written.1;
        match self.indices.get_mut(at..at + indices.len()) {
            Some(slots) => {
                for (slot, &i) in slots.iter_mut().zip(indices) {
                    slot.write(base + i);
                }
                self.written.1 += indices.len();
            }
            None => self.overflowed = true,
        }
    }

    /// Whether every slot of the stretch was written, and none more asked for.
    fn full(&self) -> bool {
        !self.overflowed
            && self.written.0 == self.positions.len()
            && self.written.1 == self.indices.len()
            && self.written.2 == self.shades.len()
    }
}

impl Sink for Stretch<'_> {
    fn next_vertex(&self) -> u32 {
        self.first + self.written.0 as u32
    }

    fn vertex(&mut self, position: Vec3, normal: Vec3, uv: [f32; 2]) -> u32 {
        let k = self.written.0;
        if k >= self.positions.len() {
            self.overflowed = true;
            return self.first + k as u32;
        }
        self.positions[k].write(position.to_array());
        self.normals[k].write(normal.to_array());
        self.uvs[k].write(uv);
        self.written.0 += 1;
        self.first + k as u32
    }

    fn indices(&mut self, indices: &[u32]) {
        self.indices_from(0, indices);
    }

    fn shade(&mut self, shade: f32) {
        match self.shades.get_mut(self.written.2) {
            Some(slot) => {
                slot.write(shade);
                self.written.2 += 1;
            }
            None => self.overflowed = true,
        }
    }
}

/// Meshes `runs` (each with its vertex and index count) into the empty `mesh` on every core,
/// `fill` writing each run into its stretch, and returns true; with `shaded`, each vertex
/// also gets a shade. If any run does not fill its stretch exactly (they always do: the same
/// counts size and fill it) returns false with `mesh` empty, and the caller meshes on one
/// thread.
pub(super) fn mesh_apart<T: Send>(
    mesh: &mut Mesh,
    runs: Vec<(T, (usize, usize))>,
    shaded: bool,
    fill: impl Fn(T, &mut Stretch<'_>) + Sync,
) -> bool {
    debug_assert!(mesh.positions.is_empty() && mesh.indices.is_empty());
    let vertices: usize = runs.iter().map(|r| r.1.0).sum();
    let indices: usize = runs.iter().map(|r| r.1.1).sum();
    let shades = if shaded { vertices } else { 0 };
    mesh.positions.reserve_exact(vertices);
    mesh.normals.reserve_exact(vertices);
    mesh.uvs.reserve_exact(vertices);
    mesh.indices.reserve_exact(indices);
    mesh.shades.reserve_exact(shades);
    let mut work = Vec::with_capacity(runs.len());
    {
        let mut positions = &mut mesh.positions.spare_capacity_mut()[..vertices];
        let mut normals = &mut mesh.normals.spare_capacity_mut()[..vertices];
        let mut uvs = &mut mesh.uvs.spare_capacity_mut()[..vertices];
        let mut index_slots = &mut mesh.indices.spare_capacity_mut()[..indices];
        let mut shade_slots = &mut mesh.shades.spare_capacity_mut()[..shades];
        let mut first = 0u32;
        for (run, (v, i)) in runs {
            let stretch = Stretch {
                positions: take(&mut positions, v),
                normals: take(&mut normals, v),
                uvs: take(&mut uvs, v),
                indices: take(&mut index_slots, i),
                shades: take(&mut shade_slots, if shaded { v } else { 0 }),
                first,
                written: (0, 0, 0),
                overflowed: false,
            };
            work.push((run, stretch));
            first += v as u32;
        }
    }
    let filled = work
        .into_par_iter()
        .map(|(run, mut stretch)| {
            fill(run, &mut stretch);
            stretch.full()
        })
        .collect::<Vec<bool>>();
    if !filled.iter().all(|&f| f) {
        return false;
    }
    // SAFETY: the stretches tile the first `vertices` (`indices`, `shades`) slots of each
    // buffer's spare capacity, and every stretch reported each of its slots written (a
    // stretch writes slot by slot from its start and `full` checks it reached the end of
    // every buffer, with no write refused).
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
