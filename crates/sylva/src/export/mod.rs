//! Writing meshes to files: glTF 2.0 binary (GLB) and Wavefront OBJ + MTL.
//!
//! Both formats get Y up (glTF's convention, and what most OBJ readers assume): a skeleton
//! point (x, y, z) with Z up becomes (x, z, -y), a rotation, so winding and handedness are kept.
//! Files are written to a temporary name beside the target and renamed into place, so a failure
//! never leaves half a file.

mod atomic;
mod glb;
mod instanced;
mod obj;
mod scene;
mod shelled;
mod twigs;

pub use atomic::{write_atomically, write_atomically_with};
pub use glb::{Glb, Materials, to_glb_lod};
pub use instanced::{
    Column, Features, InstancedGroup, InstancedMesh, MeshSource, Metadata, PointSet, PropertyTable,
    SharedImpostor, SharedMesh, instanced_glb,
};
pub use obj::{to_obj, write_obj};
pub use scene::{Instance, glb_scene, to_glb, to_glb_scene, tree_glb, write_glb};
pub use shelled::shelled_glb;

/// Z-up model coordinates to Y-up file coordinates.
#[inline]
pub(crate) fn y_up(v: [f32; 3]) -> [f32; 3] {
    [v[0], v[2], -v[1]]
}
