//! A tree whose crown is a leaf shell ([`crate::lod::leaf_shell`]) as a GLB: the bark as any
//! tree's, the shell in a material of its own that is drawn single-sided. The shell is a
//! closed, outward-facing surface, so its back faces are never seen and a renderer that drew
//! them (as it must a leaf's) would fill each pixel of the crown twice over for nothing.

use super::glb::{Builder, Glb, Materials, finish, material};
use crate::error::ExportError;
use crate::mesh::Mesh;
use gltf_json as json;

/// Encodes `bark` and the crown's `shell` as a GLB, one node at the origin named `name`.
pub fn shelled_glb<'a>(
    bark: &'a Mesh,
    shell: &'a Mesh,
    name: &str,
    materials: &Materials,
) -> Result<Glb<'a>, ExportError> {
    if bark.indices.is_empty() && shell.indices.is_empty() {
        return Err(ExportError::Format("the mesh is empty".into()));
    }
    let mut b = Builder::new();
    let mut primitives = Vec::new();
    if !bark.indices.is_empty() {
        let m = b.root.push(material("bark", materials.bark, false, 0.95));
        primitives.extend(b.primitives(bark, m));
    }
    if !shell.indices.is_empty() {
        let m = b
            .root
            .push(material("leaf shell", materials.leaves, false, 0.6));
        primitives.extend(b.primitives(shell, m));
    }
    let mesh = b.root.push(json::Mesh {
        extensions: None,
        extras: Default::default(),
        name: Some(name.into()),
        primitives,
        weights: None,
    });
    let node = b.root.push(json::Node {
        mesh: Some(mesh),
        name: Some(name.into()),
        ..Default::default()
    });
    b.scene(vec![node]);
    finish(b)
}
