//! Leaves meshed on every core, straight into the final buffers (see `apart`): a leaf takes
//! its template's slots, so runs of leaves are sized before any is meshed.

use super::Mesh;
use super::apart::{Sink, Stretch, mesh_apart};
use super::leaves::{Templates, corners, count, luminance};
use crate::skeleton::{Leaf, Skeleton};

/// Leaves meshed by one task.
const RUN: usize = 4096;

/// Below this many leaves one thread is quicker than sharing out.
const APART_FROM: usize = 4 * RUN;

/// Meshes `skeleton`'s leaves into `mesh` on every core where that pays (enough leaves, more
/// than one thread, `mesh` empty) and returns true; otherwise, or if the counts did not come
/// out as planned, returns false with `mesh` as it was, and the caller meshes them on one
/// thread.
pub(super) fn mesh_leaves_apart(skeleton: &Skeleton, mesh: &mut Mesh) -> bool {
    let empty = mesh.positions.is_empty() && mesh.indices.is_empty() && mesh.shades.is_empty();
    if !empty || skeleton.leaves.len() < APART_FROM || rayon::current_num_threads() < 2 {
        return false;
    }
    let runs: Vec<(&[Leaf], (usize, usize))> = skeleton
        .leaves
        .chunks(RUN)
        .map(|run| (run, count(run)))
        .collect();
    let shaded = skeleton.leaves.iter().any(|l| l.light < 1.0);
    mesh_apart(mesh, runs, shaded, |run, out| fill(run, out, shaded))
}

/// Writes one run of leaves into its stretch, as `leaves::leaf_vertices` and
/// `leaves::mesh_leaves` write them.
fn fill(run: &[Leaf], out: &mut Stretch<'_>, shaded: bool) {
    let mut templates = Templates::default();
    for leaf in run {
        let template = templates.of(leaf.shape);
        let base = out.next_vertex();
        for (p, normal, uv) in corners(leaf, template) {
            out.vertex(p, normal, uv);
            if shaded {
                out.shade(luminance(leaf.light));
            }
        }
        out.indices_from(base, &template.0.indices);
    }
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
