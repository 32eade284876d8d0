//! GLB files of whole trees: a tree's mesh at the origin, or a scene of meshes each drawn by
//! the nodes of its instances; a mesh's twig copies under each of its nodes (`twigs.rs`).

use super::glb::{Builder, Glb, Materials, finish};
use super::twigs::TwigNode;
use super::write_atomically_with;
use crate::error::ExportError;
use crate::mesh::TreeMesh;
use gltf_json as json;
use std::path::Path;

/// One placed copy of a mesh in a scene: where it stands (metres, Z up), its turn about the
/// vertical (radians) and its uniform scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Index into the scene's meshes.
    pub mesh: usize,
    /// Base of the tree, metres, Z up.
    pub position: [f32; 3],
    /// Turn about the vertical, radians.
    pub turn: f32,
    /// Uniform scale.
    pub scale: f32,
}

/// Encodes a tree mesh as GLB bytes. `name` names the node and mesh.
pub fn to_glb(mesh: &TreeMesh, name: &str, materials: &Materials) -> Result<Vec<u8>, ExportError> {
    Ok(tree_glb(mesh, name, materials)?.to_vec())
}

/// Writes a tree mesh to `path` as GLB (atomically), straight from the mesh's buffers.
pub fn write_glb(
    path: &Path,
    mesh: &TreeMesh,
    name: &str,
    materials: &Materials,
) -> Result<(), ExportError> {
    let glb = tree_glb(mesh, name, materials)?;
    write_atomically_with(path, |w| glb.write_to(w))
}

/// A tree mesh laid out as a GLB, one node at the origin: [`to_glb`] without gathering the
/// bytes, to be written with [`Glb::write_to`].
pub fn tree_glb<'a>(
    mesh: &'a TreeMesh,
    name: &str,
    materials: &Materials,
) -> Result<Glb<'a>, ExportError> {
    let instance = Instance {
        mesh: 0,
        position: [0.0; 3],
        turn: 0.0,
        scale: 1.0,
    };
    glb_scene(&[(name, mesh, *materials)], &[instance])
}

/// Encodes a scene: each mesh once (bark and leaf primitives with their materials), and one
/// node per instance referring to it, so a forest of K variants stores K meshes however many
/// trees it has. Instance nodes get Y-up translations and rotations about Y.
pub fn to_glb_scene(
    meshes: &[(&str, &TreeMesh, Materials)],
    instances: &[Instance],
) -> Result<Vec<u8>, ExportError> {
    Ok(glb_scene(meshes, instances)?.to_vec())
}

/// [`to_glb_scene`], laid out to be written straight from the meshes.
pub fn glb_scene<'a>(
    meshes: &[(&str, &'a TreeMesh, Materials)],
    instances: &[Instance],
) -> Result<Glb<'a>, ExportError> {
    if meshes
        .iter()
        .all(|(_, m, _)| m.bark.indices.is_empty() && m.leaves.indices.is_empty())
    {
        return Err(ExportError::Format("the mesh is empty".into()));
    }
    if let Some(bad) = instances.iter().find(|i| i.mesh >= meshes.len()) {
        return Err(ExportError::Format(format!(
            "instance of mesh {} but the scene has {}",
            bad.mesh,
            meshes.len()
        )));
    }
    let mut b = Builder::new();
    let gltf_meshes: Vec<_> = meshes
        .iter()
        .map(|(name, mesh, materials)| b.tree_mesh(name, mesh, materials))
        .collect();
    // A bare crown's twigs as copies of one, drawn by a child of each of its tree's nodes.
    let twigs = TwigNode::write_all(&mut b, meshes);
    let mut nodes = Vec::with_capacity(instances.len());
    for inst in instances {
        let identity = inst.position == [0.0; 3] && inst.turn == 0.0 && inst.scale == 1.0;
        let (s, c) = (inst.turn / 2.0).sin_cos();
        let p = inst.position;
        let name = meshes[inst.mesh].0;
        let children = twigs[inst.mesh]
            .as_ref()
            .map(|t| vec![t.node(&mut b, name)]);
        nodes.push(b.root.push(json::Node {
            mesh: Some(gltf_meshes[inst.mesh]),
            name: Some(name.into()),
            translation: (!identity).then(|| super::y_up(p)),
            // A turn about Z (up) in the model is a turn about Y (up) in the file.
            rotation: (!identity).then_some(json::scene::UnitQuaternion([0.0, s, 0.0, c])),
            scale: (!identity).then_some([inst.scale; 3]),
            children,
            ..Default::default()
        }));
    }
    TwigNode::require(&mut b, &twigs);
    b.scene(nodes);
    finish(b)
}
