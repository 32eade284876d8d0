//! GLB (binary glTF 2.0): one node, one mesh with a bark primitive and a leaf primitive, each
//! with its own material; positions, normals, UVs and 32-bit indices in one binary chunk.

use super::y_up;
use crate::error::ExportError;
use crate::mesh::{Mesh, TreeMesh};
use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use std::collections::BTreeMap;

/// Base colours (linear RGBA) of the two materials.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Materials {
    /// Bark colour.
    pub bark: [f32; 4],
    /// Leaf colour.
    pub leaves: [f32; 4],
}

/// sRGB 0..1 to linear (the exact piecewise curve).
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

impl Materials {
    /// Materials from sRGB colours, as species files give them.
    pub fn from_srgb(bark: [f32; 3], leaves: [f32; 3]) -> Self {
        let lin = |c: [f32; 3]| {
            let l = c.map(srgb_to_linear);
            [l[0], l[1], l[2], 1.0]
        };
        Self {
            bark: lin(bark),
            leaves: lin(leaves),
        }
    }
}

impl Default for Materials {
    /// Grey-brown bark and a mid summer green, in linear RGB.
    fn default() -> Self {
        Self {
            bark: [0.16, 0.11, 0.075, 1.0],
            leaves: [0.10, 0.24, 0.045, 1.0],
        }
    }
}

struct Builder {
    root: json::Root,
    bin: Vec<u8>,
    buffer: json::Index<json::Buffer>,
}

impl Builder {
    /// Appends `bytes` as a buffer view (4-byte aligned) and returns it.
    fn view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.root.push(json::buffer::View {
            buffer: self.buffer,
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    fn accessor(
        &mut self,
        view: json::Index<json::buffer::View>,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64(0)),
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(type_),
            min: bounds.map(|(lo, _)| json::Value::from(lo.to_vec())),
            max: bounds.map(|(_, hi)| json::Value::from(hi.to_vec())),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    fn primitive(
        &mut self,
        mesh: &Mesh,
        material: json::Index<json::Material>,
    ) -> json::mesh::Primitive {
        use json::accessor::{ComponentType as C, Type as T};
        use json::buffer::Target;
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| y_up(*p)).collect();
        let normals: Vec<[f32; 3]> = mesh.normals.iter().map(|n| y_up(*n)).collect();
        let bounds = positions
            .iter()
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                    [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                )
            });
        let n = positions.len();
        let v = self.view(bytes_of(&positions), Target::ArrayBuffer);
        let pos = self.accessor(v, n, C::F32, T::Vec3, Some(bounds));
        let v = self.view(bytes_of(&normals), Target::ArrayBuffer);
        let nor = self.accessor(v, n, C::F32, T::Vec3, None);
        let v = self.view(bytes_of(&mesh.uvs), Target::ArrayBuffer);
        let uv = self.accessor(v, n, C::F32, T::Vec2, None);
        let v = self.view(bytes_of(&mesh.indices), Target::ElementArrayBuffer);
        let idx = self.accessor(v, mesh.indices.len(), C::U32, T::Scalar, None);
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(json::mesh::Semantic::Normals), nor);
        attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uv);
        json::mesh::Primitive {
            attributes,
            extensions: None,
            extras: Default::default(),
            indices: Some(idx),
            material: Some(material),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        }
    }
}

/// Little-endian bytes of plain numeric arrays.
fn bytes_of<T: Copy + AsBytes>(items: &[T]) -> &[u8] {
    T::as_bytes(items)
}

trait AsBytes: Sized {
    fn as_bytes(items: &[Self]) -> &[u8];
}

macro_rules! as_bytes {
    ($($t:ty),*) => {$(
        impl AsBytes for $t {
            fn as_bytes(items: &[Self]) -> &[u8] {
                // SAFETY: arrays of f32/u32 have no padding and any byte pattern is a valid u8;
                // glTF wants little-endian, which the compile-time check below guarantees.
                const _: () = assert!(cfg!(target_endian = "little"));
                unsafe { std::slice::from_raw_parts(items.as_ptr().cast::<u8>(), std::mem::size_of_val(items)) }
            }
        }
    )*};
}
as_bytes!(u32, [f32; 2], [f32; 3]);

fn material(name: &str, colour: [f32; 4], double_sided: bool, roughness: f32) -> json::Material {
    json::Material {
        name: Some(name.into()),
        double_sided,
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor(colour),
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(roughness),
            ..Default::default()
        },
        ..Default::default()
    }
}

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
    let instance = Instance {
        mesh: 0,
        position: [0.0; 3],
        turn: 0.0,
        scale: 1.0,
    };
    to_glb_scene(&[(name, mesh, *materials)], &[instance])
}

/// Encodes a scene: each mesh once (bark and leaf primitives with their materials), and one
/// node per instance referring to it, so a forest of K variants stores K meshes however many
/// trees it has. Instance nodes get Y-up translations and rotations about Y.
pub fn to_glb_scene(
    meshes: &[(&str, &TreeMesh, Materials)],
    instances: &[Instance],
) -> Result<Vec<u8>, ExportError> {
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
    let mut b = Builder {
        root: json::Root::default(),
        bin: Vec::new(),
        buffer: json::Index::new(0),
    };
    b.root.asset = json::Asset {
        generator: Some(format!("Sylva {}", env!("CARGO_PKG_VERSION"))),
        version: "2.0".into(),
        ..Default::default()
    };
    b.buffer = b.root.push(json::Buffer {
        byte_length: USize64(0),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let mut gltf_meshes = Vec::with_capacity(meshes.len());
    for (name, mesh, materials) in meshes {
        let mut primitives = Vec::new();
        if !mesh.bark.indices.is_empty() {
            let m = b.root.push(material("bark", materials.bark, false, 0.95));
            primitives.push(b.primitive(&mesh.bark, m));
        }
        if !mesh.leaves.indices.is_empty() {
            let m = b.root.push(material("leaves", materials.leaves, true, 0.6));
            primitives.push(b.primitive(&mesh.leaves, m));
        }
        gltf_meshes.push(b.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some((*name).into()),
            primitives,
            weights: None,
        }));
    }
    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    b.root.buffers[0].byte_length = USize64::from(b.bin.len());
    let mut nodes = Vec::with_capacity(instances.len());
    for inst in instances {
        let identity = inst.position == [0.0; 3] && inst.turn == 0.0 && inst.scale == 1.0;
        let (s, c) = (inst.turn / 2.0).sin_cos();
        let p = inst.position;
        nodes.push(b.root.push(json::Node {
            mesh: Some(gltf_meshes[inst.mesh]),
            name: Some(meshes[inst.mesh].0.into()),
            translation: (!identity).then(|| super::y_up(p)),
            // A turn about Z (up) in the model is a turn about Y (up) in the file.
            rotation: (!identity).then_some(json::scene::UnitQuaternion([0.0, s, 0.0, c])),
            scale: (!identity).then_some([inst.scale; 3]),
            ..Default::default()
        }));
    }
    let scene = b.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some("scene".into()),
        nodes,
    });
    b.root.scene = Some(scene);
    finish(b)
}

/// Packs the JSON and binary chunks into a GLB file.
fn finish(b: Builder) -> Result<Vec<u8>, ExportError> {
    let mut json_bytes = b
        .root
        .to_vec()
        .map_err(|e| ExportError::Format(e.to_string()))?;
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let total = 12 + 8 + json_bytes.len() + 8 + b.bin.len();
    let total = u32::try_from(total).map_err(|_| {
        ExportError::Format(format!(
            "{total} bytes exceed the 4 GiB limit of a GLB file"
        ))
    })?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b.bin);
    Ok(out)
}
