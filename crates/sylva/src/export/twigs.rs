//! A tree's twig copies (`mesh::TwigCopies`) in a GLB: the twig once, as a mesh in the bark's
//! colour, and a node that draws it at every copy's place (`EXT_mesh_gpu_instancing`: a
//! translation, rotation and scale, 32 bytes a copy), a child of each node of its tree.

use super::glb::{Builder, Materials, Piece, bytes_of, material};
use super::y_up;
use crate::mesh::{TreeMesh, TwigCopies};
use glam::Quat;
use gltf_json as json;
use json::accessor::{ComponentType as C, Type as T};
use serde_json::{Map, Value, json};

/// The extension the twig nodes use. A viewer without it would draw one twig at the tree's
/// base, so a file with twig copies requires it.
pub(super) const INSTANCING: &str = "EXT_mesh_gpu_instancing";

/// A unit quaternion's component as a normalised 16-bit integer, as `EXT_mesh_gpu_instancing`
/// allows a ROTATION (a reader takes it back as `max(c / 32767, -1)`): 8 of a copy's 40 bytes
/// saved, for a turn off by under a hundredth of a degree.
fn to_short(c: f32) -> i16 {
    (c.clamp(-1.0, 1.0) * i16::MAX as f32).round() as i16
}

/// The twig's mesh and its copies' accessors, written once for a tree however many nodes
/// show it.
pub(super) struct TwigNode {
    mesh: json::Index<json::Mesh>,
    attributes: Value,
}

impl TwigNode {
    /// Writes `twigs`' mesh and copies into `b`; `None` where there are none.
    pub(super) fn write<'a>(
        b: &mut Builder<'a>,
        name: &str,
        twigs: &'a TwigCopies,
        materials: &Materials,
    ) -> Option<TwigNode> {
        if twigs.is_empty() {
            return None;
        }
        let m = b.root.push(material("bark", materials.bark, false, 0.95));
        let primitives = b.primitives(&twigs.twig, m);
        let mesh = b.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(format!("{name} twigs")),
            primitives,
            weights: None,
        });
        // The twig's vertices are written Y up (`Builder::primitive`), so each copy's turn is
        // taken into the file's frame on both sides, and its scale along the twig (model Z)
        // becomes a scale along file Y.
        let to_file = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
        let n = twigs.copies.len();
        let (mut moves, mut turns, mut scales) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for c in &twigs.copies {
            moves.push(y_up(c.position));
            let q = to_file * Quat::from_array(c.rotation) * to_file.inverse();
            turns.push(q.normalize().to_array().map(to_short));
            let [x, y, z] = c.scale;
            scales.push([x, z, y]);
        }
        let mut attribute = |bytes: Vec<u8>, c: C, ty: T| {
            let v = b.view(Piece::Owned(bytes), None);
            b.accessor(v, n, c, ty, None).value()
        };
        let t = attribute(bytes_of(&moves).to_vec(), C::F32, T::Vec3);
        let r = attribute(bytes_of(&turns).to_vec(), C::I16, T::Vec4);
        let s = attribute(bytes_of(&scales).to_vec(), C::F32, T::Vec3);
        b.root.accessors[r].normalized = true;
        Some(TwigNode {
            mesh,
            attributes: json!({ "TRANSLATION": t, "ROTATION": r, "SCALE": s }),
        })
    }

    /// [`TwigNode::write`] for each of a scene's meshes.
    pub(super) fn write_all<'a>(
        b: &mut Builder<'a>,
        meshes: &[(&str, &'a TreeMesh, Materials)],
    ) -> Vec<Option<TwigNode>> {
        meshes
            .iter()
            .map(|(name, mesh, materials)| TwigNode::write(b, name, &mesh.twigs, materials))
            .collect()
    }

    /// Requires the instancing extension where any mesh has twig copies.
    pub(super) fn require(b: &mut Builder<'_>, twigs: &[Option<TwigNode>]) {
        if twigs.iter().any(Option::is_some) {
            b.root.extensions_used = vec![INSTANCING.into()];
            b.root.extensions_required = vec![INSTANCING.into()];
        }
    }

    /// A node drawing the copies, to be made a child of a node of the tree.
    pub(super) fn node(&self, b: &mut Builder<'_>, name: &str) -> json::Index<json::Node> {
        let mut others = Map::new();
        others.insert(INSTANCING.into(), json!({ "attributes": self.attributes }));
        b.root.push(json::Node {
            mesh: Some(self.mesh),
            name: Some(format!("{name} twigs")),
            extensions: Some(json::extensions::scene::Node { others }),
            ..Default::default()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{MeshOptions, mesh_tree, twigs_tests::bare_stem_with_twigs};
    use glam::{Mat4, Vec3};

    #[test]
    fn a_bare_crown_s_twigs_are_one_instanced_twig_that_a_reader_places_where_they_grew() {
        let sk = bare_stem_with_twigs();
        let direct = mesh_tree(&sk, &MeshOptions::default());
        let options = MeshOptions {
            twig_copies: true,
            ..Default::default()
        };
        let mesh = mesh_tree(&sk, &options);
        let bytes = crate::export::to_glb(&mesh, "twiggy", &Materials::default()).unwrap();
        // The gltf crate refuses a file requiring an extension it does not know, so the
        // file is checked with that one taken off the list.
        let gltf::Gltf { document, blob } =
            gltf::Gltf::from_slice_without_validation(&bytes).unwrap();
        let mut root = document.into_json();
        assert_eq!(root.extensions_required, [INSTANCING]);
        assert_eq!(root.extensions_used, [INSTANCING]);
        root.extensions_required.clear();
        let doc = gltf::Document::from_json(root).expect("a valid glTF otherwise");
        let buffers = gltf::import_buffers(&doc, None, blob).unwrap();
        // The tree's node holds the frame; its child draws the twig at each copy.
        let tree = doc.default_scene().unwrap().nodes().next().unwrap();
        let twig = tree.children().next().expect("a twig node");
        let ext = &doc.as_json().nodes[twig.index()]
            .extensions
            .as_ref()
            .unwrap()
            .others[INSTANCING]["attributes"];
        let read = |name: &str, width: usize| -> Vec<f32> {
            let a = doc
                .accessors()
                .nth(ext[name].as_u64().unwrap() as usize)
                .unwrap();
            assert_eq!(a.count(), 3, "{name}: a copy per twig");
            let view = a.view().unwrap();
            let data = &buffers[view.buffer().index()].0[view.offset()..][..view.length()];
            // Turns are normalised 16-bit integers, the rest floats.
            let floats: Vec<f32> = if name == "ROTATION" {
                assert!(a.normalized() && a.data_type() == gltf::accessor::DataType::I16);
                let shorts: Vec<i16> = bytemuck::pod_collect_to_vec(data);
                shorts
                    .iter()
                    .map(|&c| (c as f32 / 32767.0).max(-1.0))
                    .collect()
            } else {
                assert_eq!(a.data_type(), gltf::accessor::DataType::F32);
                bytemuck::pod_collect_to_vec(data)
            };
            assert_eq!(floats.len(), 3 * width);
            floats
        };
        let (t, r, s) = (
            read("TRANSLATION", 3),
            read("ROTATION", 4),
            read("SCALE", 3),
        );
        let prim = twig.mesh().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|b| Some(&buffers[b.index()].0[..]));
        let template: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
        // Each copy, placed in the file's frame (Y up), lands on its twig as meshed one by
        // one, turned Y up.
        let frame_vertices = mesh.bark.vertex_count();
        for k in 0..3 {
            let m = Mat4::from_scale_rotation_translation(
                Vec3::from_slice(&s[3 * k..]),
                glam::Quat::from_slice(&r[4 * k..]),
                Vec3::from_slice(&t[3 * k..]),
            );
            for (i, v) in template.iter().enumerate() {
                let want = y_up(direct.bark.positions[frame_vertices + k * template.len() + i]);
                let gap = m.transform_point3(*v).distance(Vec3::from(want));
                // A 16-bit turn is off by under 1e-4 radians: a tenth of a millimetre on a
                // metre-long twig.
                assert!(gap < 1e-4, "copy {k}, vertex {i}: {gap} m off");
            }
        }
    }
}
