//! GLB whose meshes are drawn many times over by the GPU (`EXT_mesh_gpu_instancing`), each copy
//! a feature with a row in a property table (`EXT_instance_features` with
//! `EXT_structural_metadata`): the content of a 3D Tiles tile of street trees. The meshes are
//! written once however many copies stand; a copy costs its translation, rotation and scale
//! (40 bytes) and its row.

use super::glb::{Builder, Image, Materials, Piece, bytes_of, finish, material, triangles};
use super::y_up;
use crate::error::ExportError;
use crate::lod::impostor::ImpostorFrame;
use crate::mesh::{Mesh, TreeMesh};
use gltf_json as json;
use json::accessor::{ComponentType as C, Type as T};
use json::validation::Checked::Valid;
use json::validation::USize64;
use serde_json::{Map, Value, json};
use std::collections::{BTreeMap, HashMap};

/// A mesh's geometry in a binary file of its own, which many GLB files refer to: a city's tiles
/// share each grown tree's mesh instead of each holding a copy. Made with [`SharedMesh::new`].
/// It serialises (serde) so that a city's tasks can carry it to other processes.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SharedMesh {
    /// The binary file's URI, relative to the GLB files that refer to it.
    pub uri: String,
    /// Its length, bytes.
    pub byte_length: usize,
    primitives: Vec<SharedPrimitive>,
}

/// Where one primitive's arrays lie in a shared mesh's file.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
struct SharedPrimitive {
    /// 0 bark, 1 leaves, 2 flowers.
    material: usize,
    vertices: usize,
    indices: usize,
    /// Byte offsets of positions, normals, UVs, colours (if any) and indices.
    offsets: [usize; 5],
    /// Indices as 16-bit numbers (under 65,536 vertices), else 32-bit.
    short: bool,
    colours: bool,
    bounds: ([f32; 3], [f32; 3]),
}

impl SharedMesh {
    /// `mesh` laid out for a file of its own at `uri`: the layout, and the file's bytes
    /// (positions and normals Y up, UVs, shades as RGBA bytes, 32-bit indices; each array on a
    /// 4-byte boundary).
    pub fn new(mesh: &TreeMesh, uri: impl Into<String>) -> (SharedMesh, Vec<u8>) {
        let mut bytes = Vec::new();
        let mut put = |b: &[u8]| {
            let at = bytes.len();
            bytes.extend_from_slice(b);
            while !bytes.len().is_multiple_of(4) {
                bytes.push(0);
            }
            at
        };
        let mut primitives = Vec::new();
        for (material, m) in [&mesh.bark, &mesh.leaves, &mesh.flowers]
            .into_iter()
            .enumerate()
        {
            if m.indices.is_empty() {
                continue;
            }
            let n = m.positions.len();
            let up: Vec<[f32; 3]> = m.positions.iter().map(|&p| y_up(p)).collect();
            let bounds = bounds_of(&up);
            let normals: Vec<[f32; 3]> = m.normals.iter().map(|&p| y_up(p)).collect();
            let colours = m.shades.len() == n;
            let grey: Vec<[u8; 4]> = if colours {
                m.shades
                    .iter()
                    .map(|&s| {
                        let g = (s.clamp(0.0, 1.0) * 255.0).round() as u8;
                        [g, g, g, 255]
                    })
                    .collect()
            } else {
                Vec::new()
            };
            // A tree's levels of detail have some thousands of vertices: 16-bit indices
            // halve the indices' bytes.
            let short = n <= u16::MAX as usize;
            let indices: Vec<u16> = if short {
                m.indices.iter().map(|&i| i as u16).collect()
            } else {
                Vec::new()
            };
            let offsets = [
                put(bytes_of(&up)),
                put(bytes_of(&normals)),
                put(bytes_of(&m.uvs)),
                if colours { put(bytes_of(&grey)) } else { 0 },
                if short {
                    put(bytes_of(&indices))
                } else {
                    put(bytes_of(&m.indices))
                },
            ];
            primitives.push(SharedPrimitive {
                material,
                vertices: n,
                indices: m.indices.len(),
                offsets,
                short,
                colours,
                bounds,
            });
        }
        let shared = SharedMesh {
            uri: uri.into(),
            byte_length: bytes.len(),
            primitives,
        };
        (shared, bytes)
    }

    /// Triangles it draws.
    pub fn triangles(&self) -> usize {
        self.primitives.iter().map(|p| p.indices / 3).sum()
    }
}

/// The smallest box around `points`.
fn bounds_of(points: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    points
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                std::array::from_fn(|i| lo[i].min(p[i])),
                std::array::from_fn(|i| hi[i].max(p[i])),
            )
        })
}

/// Where a mesh of an instanced file comes from.
#[derive(Clone, Copy, Debug)]
pub enum MeshSource<'a> {
    /// Written into the file.
    Inline(&'a TreeMesh),
    /// Read from its own binary file ([`SharedMesh`]).
    Shared(&'a SharedMesh),
    /// A baked impostor: its quads written into the file, its atlas read from its own PNG
    /// file ([`SharedImpostor`]).
    Impostor(&'a SharedImpostor),
}

/// A baked impostor ([`crate::lod::impostor`]) whose atlas lies in a PNG file outside the
/// GLB, which many GLB files refer to: a city's coarse tiles draw each far tree as its 16
/// triangles and share the picture. The picture may hold many trees' atlases (a city packs
/// them all in one, `rect` saying where this tree's lies): the files that draw them then
/// share one image, texture and material.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SharedImpostor {
    /// The PNG file's URI, relative to the GLB files that refer to it.
    pub uri: String,
    /// Its views' layout and size.
    pub frame: ImpostorFrame,
    /// Where its atlas lies in the picture, as shares of the picture's width and height: left,
    /// top, width, height (`[0, 0, 1, 1]`: the whole picture).
    pub rect: [f32; 4],
}

/// A mesh of an instanced file: its name, where it comes from and its materials.
#[derive(Clone, Copy, Debug)]
pub struct InstancedMesh<'a> {
    /// The mesh's (and its nodes') name.
    pub name: &'a str,
    /// Its geometry.
    pub source: MeshSource<'a>,
    /// Its materials' colours.
    pub materials: Materials,
}

/// Copies of one mesh: one node of the file.
#[derive(Clone, Copy, Debug)]
pub struct InstancedGroup<'a> {
    /// Index into the file's meshes.
    pub mesh: usize,
    /// Where each copy stands (the base of the tree), metres, Z up, relative to the file's
    /// origin.
    pub positions: &'a [[f32; 3]],
    /// Turn of each copy about the vertical, radians.
    pub turns: &'a [f32],
    /// Uniform scale of each copy.
    pub scales: &'a [f32],
    /// The rows of the copies in a property table, if any: each copy a feature.
    pub features: Option<Features<'a>>,
}

/// Which property table rows a group's copies are (`EXT_instance_features`, through the
/// `_FEATURE_ID_0` instance attribute): a tile's trees of every mesh share one table.
#[derive(Clone, Copy, Debug)]
pub struct Features<'a> {
    /// The table.
    pub table: usize,
    /// Each copy's row, in the copies' order.
    pub rows: &'a [u32],
}

/// Points drawn once each, not instanced: a coarse tile's trees that it leaves out of its
/// meshes, where they stand (`POSITION`), each of a class (`_CLASS`, an index into the
/// mesh's `extras.classes`): a far viewer draws them as dots.
#[derive(Clone, Copy, Debug)]
pub struct PointSet<'a> {
    /// The mesh's and node's name.
    pub name: &'a str,
    /// Where each point stands, metres, Z up, relative to the file's origin.
    pub positions: &'a [[f32; 3]],
    /// Each point's class, an index into `classes`.
    pub class_of: &'a [u16],
    /// The classes' names.
    pub classes: &'a [String],
}

/// One property's values, a row per feature.
#[derive(Clone, Debug, PartialEq)]
pub enum Column {
    /// `FLOAT32` scalars.
    Float32(Vec<f32>),
    /// `UINT32` scalars.
    UInt32(Vec<u32>),
    /// `UINT16` scalars, or the values of an enum whose `valueType` is `UINT16`.
    UInt16(Vec<u16>),
    /// `STRING`s, with `UINT32` offsets.
    Text(Vec<String>),
}

impl Column {
    fn len(&self) -> usize {
        match self {
            Column::Float32(v) => v.len(),
            Column::UInt32(v) => v.len(),
            Column::UInt16(v) => v.len(),
            Column::Text(v) => v.len(),
        }
    }
}

/// A property table of `EXT_structural_metadata`: a row per feature of its class.
#[derive(Clone, Debug, PartialEq)]
pub struct PropertyTable {
    /// Its class in the schema.
    pub class: String,
    /// Its properties, each named as the class names it.
    pub columns: Vec<(String, Column)>,
}

/// The schema (`EXT_structural_metadata`'s `schema` object, classes and enums) and the tables.
#[derive(Clone, Debug, PartialEq)]
pub struct Metadata {
    /// The schema as JSON.
    pub schema: Value,
    /// The property tables.
    pub tables: Vec<PropertyTable>,
}

/// Encodes `meshes` (each once: bark, leaf and flower primitives with their materials) and a
/// node per group that draws its mesh at every copy's place, with `metadata`'s tables in the
/// file. Rows of a table must be as many as the copies of every group that points at it.
pub fn instanced_glb(
    meshes: &[InstancedMesh<'_>],
    groups: &[InstancedGroup<'_>],
    metadata: Option<&Metadata>,
    points: Option<&PointSet<'_>>,
) -> Result<Vec<u8>, ExportError> {
    let bad = |m: String| Err(ExportError::Format(m));
    let tables = metadata.map_or(&[][..], |m| &m.tables[..]);
    for (k, t) in tables.iter().enumerate() {
        let rows = t.columns.first().map_or(0, |c| c.1.len());
        if let Some((name, _)) = t.columns.iter().find(|c| c.1.len() != rows) {
            return bad(format!(
                "property table {k}: `{name}` has a different number of rows"
            ));
        }
    }
    for (g, group) in groups.iter().enumerate() {
        let n = group.positions.len();
        if group.mesh >= meshes.len() {
            return bad(format!(
                "group {g} draws mesh {} of {}",
                group.mesh,
                meshes.len()
            ));
        }
        if n == 0 || group.turns.len() != n || group.scales.len() != n {
            return bad(format!(
                "group {g}: {n} positions, {} turns, {} scales (all equal and more than 0)",
                group.turns.len(),
                group.scales.len()
            ));
        }
        if let Some(f) = group.features {
            let rows = tables
                .get(f.table)
                .and_then(|t| t.columns.first())
                .map(|c| c.1.len());
            let Some(rows) = rows else {
                return bad(format!("group {g}: there is no table {}", f.table));
            };
            if f.rows.len() != n || f.rows.iter().any(|&r| r as usize >= rows) {
                return bad(format!(
                    "group {g}: {} rows given for {n} copies, each under the table's {rows}",
                    f.rows.len()
                ));
            }
        }
    }
    // The impostors' quads, made before the builder that borrows them.
    let quads: Vec<Option<Mesh>> = meshes
        .iter()
        .map(|m| match m.source {
            MeshSource::Impostor(imp) => Some(imp.frame.quads_within(imp.rect)),
            _ => None,
        })
        .collect();
    let mut b = Builder::new();
    let mut materials = HashMap::new();
    let gltf_meshes: Vec<_> = meshes
        .iter()
        .zip(&quads)
        .map(|(m, quads)| match (m.source, quads) {
            (MeshSource::Inline(mesh), _) => b.tree_mesh(m.name, mesh, &m.materials),
            (MeshSource::Shared(shared), _) => {
                shared_mesh(&mut b, m.name, shared, &m.materials, &mut materials)
            }
            (MeshSource::Impostor(imp), Some(quads)) => {
                b.impostor_mesh(m.name, Image::Uri(&imp.uri), quads)
            }
            (MeshSource::Impostor(_), None) => unreachable!("every impostor's quads are made"),
        })
        .collect();
    let mut nodes = Vec::with_capacity(groups.len());
    for group in groups {
        let attributes = instance_attributes(&mut b, group);
        let mut others = Map::new();
        others.insert(
            "EXT_mesh_gpu_instancing".into(),
            json!({ "attributes": attributes }),
        );
        if let Some(f) = group.features {
            others.insert(
                "EXT_instance_features".into(),
                json!({ "featureIds": [{
                    "featureCount": group.positions.len(),
                    "attribute": 0,
                    "propertyTable": f.table,
                }]}),
            );
        }
        nodes.push(b.root.push(json::Node {
            mesh: Some(gltf_meshes[group.mesh]),
            name: Some(meshes[group.mesh].name.into()),
            extensions: Some(json::extensions::scene::Node { others }),
            ..Default::default()
        }));
    }
    if let Some(p) = points.filter(|p| !p.positions.is_empty()) {
        if p.class_of.len() != p.positions.len()
            || p.class_of.iter().any(|&c| c as usize >= p.classes.len())
        {
            return bad(format!(
                "points `{}`: {} classes for {} points, each under {}",
                p.name,
                p.class_of.len(),
                p.positions.len(),
                p.classes.len()
            ));
        }
        let mesh = point_mesh(&mut b, p)?;
        nodes.push(b.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(p.name.into()),
            ..Default::default()
        }));
    }
    let mut used = vec!["EXT_mesh_gpu_instancing".to_string()];
    if quads.iter().any(Option::is_some) {
        used.push("KHR_materials_unlit".into());
    }
    if let Some(m) = metadata {
        let tables: Vec<Value> = m.tables.iter().map(|t| table_json(&mut b, t)).collect();
        let mut others = Map::new();
        others.insert(
            "EXT_structural_metadata".into(),
            json!({ "schema": m.schema, "propertyTables": tables }),
        );
        b.root.extensions = Some(json::extensions::root::Root { others });
        used.push("EXT_structural_metadata".into());
        if groups.iter().any(|g| g.features.is_some()) {
            used.push("EXT_instance_features".into());
        }
    }
    // A viewer without instancing would draw each mesh once, at the origin: required.
    b.root.extensions_required = vec!["EXT_mesh_gpu_instancing".into()];
    b.root.extensions_used = used;
    b.scene(nodes);
    Ok(finish(b)?.to_vec())
}

/// A shared mesh as a mesh of the file: a buffer of its own (its URI), views and accessors on
/// it, and materials as [`Builder::tree_mesh`] makes them.
fn shared_mesh(
    b: &mut Builder<'_>,
    name: &str,
    shared: &SharedMesh,
    materials: &Materials,
    made: &mut HashMap<(usize, [u32; 4]), json::Index<json::Material>>,
) -> json::Index<json::Mesh> {
    let buffer = b.root.push(json::Buffer {
        byte_length: USize64::from(shared.byte_length),
        name: None,
        uri: Some(shared.uri.clone()),
        extensions: None,
        extras: Default::default(),
    });
    let mut primitives = Vec::new();
    for p in &shared.primitives {
        let (material_name, colour, double_sided, roughness) = match p.material {
            0 => ("bark", materials.bark, false, 0.95),
            1 => ("leaves", materials.leaves, true, 0.6),
            _ => ("flowers", materials.flowers, true, 0.6),
        };
        // One material per kind and colour in a file: a species' trees of every age share it.
        let material = *made
            .entry((p.material, colour.map(f32::to_bits)))
            .or_insert_with(|| {
                b.root
                    .push(material(material_name, colour, double_sided, roughness))
            });
        type Bounds = Option<([f32; 3], [f32; 3])>;
        let mut accessor = |at: usize, length: usize, count: usize, c: C, t: T, bounds: Bounds| {
            let indices = matches!(t, T::Scalar);
            let view = b.root.push(json::buffer::View {
                buffer,
                byte_length: USize64::from(length),
                byte_offset: Some(USize64::from(at)),
                byte_stride: None,
                name: None,
                target: Some(Valid(if indices {
                    json::buffer::Target::ElementArrayBuffer
                } else {
                    json::buffer::Target::ArrayBuffer
                })),
                extensions: None,
                extras: Default::default(),
            });
            b.accessor(view, count, c, t, bounds)
        };
        let (n, o) = (p.vertices, p.offsets);
        let pos = accessor(o[0], n * 12, n, C::F32, T::Vec3, Some(p.bounds));
        let nor = accessor(o[1], n * 12, n, C::F32, T::Vec3, None);
        let uv = accessor(o[2], n * 8, n, C::F32, T::Vec2, None);
        let colour = p
            .colours
            .then(|| accessor(o[3], n * 4, n, C::U8, T::Vec4, None));
        let idx = if p.short {
            accessor(o[4], p.indices * 2, p.indices, C::U16, T::Scalar, None)
        } else {
            accessor(o[4], p.indices * 4, p.indices, C::U32, T::Scalar, None)
        };
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(json::mesh::Semantic::Normals), nor);
        attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uv);
        if let Some(colour) = colour {
            b.root.accessors[colour.value()].normalized = true;
            attributes.insert(Valid(json::mesh::Semantic::Colors(0)), colour);
        }
        primitives.push(triangles(attributes, idx, material));
    }
    b.root.push(json::Mesh {
        extensions: None,
        extras: Default::default(),
        name: Some(name.into()),
        primitives,
        weights: None,
    })
}

/// A mesh of one POINTS primitive, its classes named in its extras.
fn point_mesh(
    b: &mut Builder<'_>,
    p: &PointSet<'_>,
) -> Result<json::Index<json::Mesh>, ExportError> {
    let n = p.positions.len();
    let positions: Vec<[f32; 3]> = p.positions.iter().map(|&q| y_up(q)).collect();
    let bounds = bounds_of(&positions);
    let v = b.view(Piece::Owned(bytes_of(&positions).to_vec()), None);
    let pos = b.accessor(v, n, C::F32, T::Vec3, Some(bounds));
    // Classes as floats: exact to 2^24, and a type every reader takes for an attribute.
    let class_of: Vec<f32> = p.class_of.iter().map(|&c| c as f32).collect();
    let v = b.view(Piece::Owned(bytes_of(&class_of).to_vec()), None);
    let class = b.accessor(v, n, C::F32, T::Scalar, None);
    let mut attributes = BTreeMap::new();
    attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
    attributes.insert(Valid(json::mesh::Semantic::Extras("CLASS".into())), class);
    let extras = serde_json::value::to_raw_value(&json!({ "classes": p.classes }))
        .map_err(|e| ExportError::Format(e.to_string()))?;
    Ok(b.root.push(json::Mesh {
        extensions: None,
        extras: Some(extras),
        name: Some(p.name.into()),
        primitives: vec![json::mesh::Primitive {
            attributes,
            extensions: None,
            extras: Default::default(),
            indices: None,
            material: None,
            mode: Valid(json::mesh::Mode::Points),
            targets: None,
        }],
        weights: None,
    }))
}

/// The TRANSLATION, ROTATION and SCALE accessors of a group's copies, Y up.
fn instance_attributes(b: &mut Builder<'_>, group: &InstancedGroup<'_>) -> Value {
    let n = group.positions.len();
    let translations: Vec<[f32; 3]> = group.positions.iter().map(|&p| y_up(p)).collect();
    let bounds = bounds_of(&translations);
    // A turn about Z (up) in the model is a turn about Y (up) in the file.
    let rotations: Vec<[f32; 4]> = group
        .turns
        .iter()
        .map(|&t| {
            let (s, c) = (t / 2.0).sin_cos();
            [0.0, s, 0.0, c]
        })
        .collect();
    let scales: Vec<[f32; 3]> = group.scales.iter().map(|&s| [s; 3]).collect();
    let mut attribute = |bytes: Vec<u8>, ty: T, bounds| {
        let v = b.view(Piece::Owned(bytes), None);
        b.accessor(v, n, C::F32, ty, bounds).value()
    };
    let t = attribute(bytes_of(&translations).to_vec(), T::Vec3, Some(bounds));
    let r = attribute(bytes_of(&rotations).to_vec(), T::Vec4, None);
    let s = attribute(bytes_of(&scales).to_vec(), T::Vec3, None);
    match group.features {
        // Feature ids as floats: exact to 2^24 rows, and a type every reader takes for an
        // attribute.
        Some(f) => {
            let ids: Vec<f32> = f.rows.iter().map(|&r| r as f32).collect();
            let id = attribute(bytes_of(&ids).to_vec(), T::Scalar, None);
            json!({ "TRANSLATION": t, "ROTATION": r, "SCALE": s, "_FEATURE_ID_0": id })
        }
        None => json!({ "TRANSLATION": t, "ROTATION": r, "SCALE": s }),
    }
}

/// A property table's JSON, its columns added as buffer views (each 4-byte aligned, which every
/// component type here needs).
fn table_json(b: &mut Builder<'_>, t: &PropertyTable) -> Value {
    let mut properties = Map::new();
    for (name, column) in &t.columns {
        let mut view = |bytes: Vec<u8>| b.view(Piece::Owned(bytes), None).value();
        let property = match column {
            Column::Float32(v) => json!({ "values": view(bytes_of(v).to_vec()) }),
            Column::UInt32(v) => json!({ "values": view(bytes_of(v).to_vec()) }),
            Column::UInt16(v) => json!({ "values": view(bytes_of(v).to_vec()) }),
            Column::Text(v) => {
                let mut offsets = Vec::with_capacity(v.len() + 1);
                let mut text = Vec::new();
                for s in v {
                    offsets.push(text.len() as u32);
                    text.extend_from_slice(s.as_bytes());
                }
                offsets.push(text.len() as u32);
                // A buffer view holds at least one byte; past the last offset it is unread.
                if text.is_empty() {
                    text.push(b' ');
                }
                json!({
                    "values": view(text),
                    "stringOffsets": view(bytes_of(&offsets).to_vec()),
                    "stringOffsetType": "UINT32",
                })
            }
        };
        properties.insert(name.clone(), property);
    }
    json!({
        "class": t.class,
        "count": t.columns.first().map_or(0, |c| c.1.len()),
        "properties": properties,
    })
}
