//! GLB (binary glTF 2.0): one node, one mesh with a bark primitive and a leaf primitive (and a
//! flower primitive when the tree is in flower), each with its own material; positions,
//! normals, UVs, 16-bit indices and the vertex shades (COLOR_0) in one binary chunk. A part
//! with more vertices than 16-bit indices reach is cut into primitives that each fit them.

use super::y_up;
use crate::error::ExportError;
use crate::mesh::{Mesh, TreeMesh};
use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use std::collections::{BTreeMap, HashMap};
use std::io::Write;

/// Base colours (linear RGBA) of the materials.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Materials {
    /// Bark colour.
    pub bark: [f32; 4],
    /// Leaf colour.
    pub leaves: [f32; 4],
    /// Flower colour (used only by a mesh with flowers).
    pub flowers: [f32; 4],
}

/// White, for flowers of no named colour.
const WHITE: [f32; 4] = [1.0; 4];

impl Materials {
    /// Materials from sRGB colours, as species files give them.
    pub fn from_srgb(bark: [f32; 3], leaves: [f32; 3]) -> Self {
        let lin = |c: [f32; 3]| {
            let l = c.map(crate::colour::srgb_to_linear);
            [l[0], l[1], l[2], 1.0]
        };
        Self {
            bark: lin(bark),
            leaves: lin(leaves),
            flowers: WHITE,
        }
    }

    /// These materials with flowers of an sRGB colour.
    pub fn with_flowers(self, flowers: [f32; 3]) -> Self {
        let l = flowers.map(crate::colour::srgb_to_linear);
        Self {
            flowers: [l[0], l[1], l[2], 1.0],
            ..self
        }
    }
}

impl Default for Materials {
    /// Grey-brown bark and a mid summer green, in linear RGB.
    fn default() -> Self {
        Self {
            bark: [0.16, 0.11, 0.075, 1.0],
            leaves: [0.10, 0.24, 0.045, 1.0],
            flowers: WHITE,
        }
    }
}

pub(super) struct Builder<'a> {
    pub(super) root: json::Root,
    /// The binary chunk's views in order, each with the zero bytes that align it to 4.
    pieces: Vec<(usize, Piece<'a>)>,
    /// Bytes of the binary chunk so far.
    bin_len: usize,
    buffer: json::Index<json::Buffer>,
    /// The material of each impostor picture in a file of its own, by URI: the impostors of
    /// many trees packed in one picture (a city's atlas) share one image, texture and
    /// material, so a client decodes the picture and makes its mipmaps once.
    shared_atlases: HashMap<String, json::Index<json::Material>>,
}

/// A buffer view's bytes, left where the mesh holds them until the file is written: a GLB is
/// written straight from the mesh's buffers, never gathered into a copy of itself.
pub(super) enum Piece<'a> {
    Bytes(&'a [u8]),
    /// Bytes made for the file (instances' transforms, property tables).
    Owned(Vec<u8>),
    /// Positions or normals, turned Y up as they are written.
    YUp(&'a [[f32; 3]]),
    /// Leaf or bark shades, written as grey colours of four normalised bytes (RGBA; a vertex
    /// attribute's elements must start on four bytes, so RGB would take four as well).
    Shades(&'a [f32]),
}

impl Piece<'_> {
    fn len(&self) -> usize {
        match self {
            Piece::Bytes(b) => b.len(),
            Piece::Owned(b) => b.len(),
            Piece::YUp(v) => std::mem::size_of_val(*v),
            Piece::Shades(s) => s.len() * 4,
        }
    }

    fn write_to(&self, w: &mut dyn Write) -> std::io::Result<()> {
        // Converted pieces go out through a small buffer, some thousands of vertices at a time.
        const AT_ONCE: usize = 4096;
        let mut converted: Vec<[f32; 3]> = Vec::new();
        let mut out = |items: &mut dyn Iterator<Item = [f32; 3]>| -> std::io::Result<()> {
            loop {
                converted.clear();
                converted.extend(items.take(AT_ONCE));
                if converted.is_empty() {
                    return Ok(());
                }
                w.write_all(bytes_of(&converted))?;
            }
        };
        match self {
            Piece::Bytes(b) => w.write_all(b),
            Piece::Owned(b) => w.write_all(b),
            Piece::YUp(v) => out(&mut v.iter().map(|p| y_up(*p))),
            Piece::Shades(s) => {
                let mut grey: Vec<[u8; 4]> = Vec::with_capacity(AT_ONCE.min(s.len()));
                for run in s.chunks(AT_ONCE) {
                    grey.clear();
                    grey.extend(run.iter().map(|&s| {
                        let g = (s.clamp(0.0, 1.0) * 255.0).round() as u8;
                        [g, g, g, 255]
                    }));
                    w.write_all(bytes_of(&grey))?;
                }
                Ok(())
            }
        }
    }
}

impl<'a> Builder<'a> {
    /// Adds `piece` as a buffer view (4-byte aligned) and returns it.
    pub(super) fn view(
        &mut self,
        piece: Piece<'a>,
        target: impl Into<Option<json::buffer::Target>>,
    ) -> json::Index<json::buffer::View> {
        let target = target.into();
        let pad = self.bin_len.next_multiple_of(4) - self.bin_len;
        let offset = self.bin_len + pad;
        let length = piece.len();
        self.bin_len = offset + length;
        self.pieces.push((pad, piece));
        self.root.push(json::buffer::View {
            buffer: self.buffer,
            byte_length: USize64::from(length),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: target.map(Valid),
            extensions: None,
            extras: Default::default(),
        })
    }

    pub(super) fn accessor(
        &mut self,
        view: json::Index<json::buffer::View>,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        self.accessor_at(view, 0, count, component, type_, bounds)
    }

    /// An accessor of `count` elements from byte `offset` of `view`.
    fn accessor_at(
        &mut self,
        view: json::Index<json::buffer::View>,
        offset: usize,
        count: usize,
        component: json::accessor::ComponentType,
        type_: json::accessor::Type,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64::from(offset)),
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

    /// `mesh` as primitives of `material`: one where its vertices fit 16-bit indices, else
    /// one per run of its triangles whose vertices do ([`short_runs`]), each run's
    /// attributes read from its stretch of the mesh's arrays (written once). A mesh with a
    /// triangle too long for 16 bits is one primitive of 32-bit indices.
    pub(super) fn primitives(
        &mut self,
        mesh: &'a Mesh,
        material: json::Index<json::Material>,
    ) -> Vec<json::mesh::Primitive> {
        use json::accessor::{ComponentType as C, Type as T};
        use json::buffer::Target;
        let n = mesh.positions.len();
        let (runs, short) = match short_runs(&mesh.indices, n) {
            Some(runs) => (runs, true),
            None => {
                let whole = Run {
                    triangles: 0..mesh.indices.len(),
                    vertices: 0..n,
                };
                (vec![whole], false)
            }
        };
        let positions = self.view(Piece::YUp(&mesh.positions), Target::ArrayBuffer);
        let normals = self.view(Piece::YUp(&mesh.normals), Target::ArrayBuffer);
        let uvs = self.view(Piece::Bytes(bytes_of(&mesh.uvs)), Target::ArrayBuffer);
        // glTF multiplies the base colour by COLOR_0: the leaves' luminance classes, the
        // bark's pattern.
        let shades = (mesh.shades.len() == n)
            .then(|| self.view(Piece::Shades(&mesh.shades), Target::ArrayBuffer));
        // An application's own attribute, which glTF names with a leading underscore.
        let radii = (mesh.radii.len() == n)
            .then(|| self.view(Piece::Bytes(bytes_of(&mesh.radii)), Target::ArrayBuffer));
        if runs.len() > 1 {
            // glTF asks the stride of a view that several accessors read.
            let strided = [(Some(positions), 12), (Some(normals), 12), (Some(uvs), 8)];
            for (view, stride) in strided.into_iter().chain([(shades, 4), (radii, 4)]) {
                if let Some(v) = view {
                    self.root.buffer_views[v.value()].byte_stride =
                        Some(json::buffer::Stride(stride));
                }
            }
        }
        let mut primitives = Vec::with_capacity(runs.len());
        for run in &runs {
            let (lo, count) = (run.vertices.start, run.vertices.len());
            let bounds = mesh.positions[run.vertices.clone()].iter().fold(
                ([f32::MAX; 3], [f32::MIN; 3]),
                |(lo, hi), p| {
                    let p = y_up(*p);
                    (
                        [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                        [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
                    )
                },
            );
            let mut attributes = BTreeMap::new();
            let pos = self.accessor_at(positions, lo * 12, count, C::F32, T::Vec3, Some(bounds));
            attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
            let nor = self.accessor_at(normals, lo * 12, count, C::F32, T::Vec3, None);
            attributes.insert(Valid(json::mesh::Semantic::Normals), nor);
            let uv = self.accessor_at(uvs, lo * 8, count, C::F32, T::Vec2, None);
            attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), uv);
            if let Some(view) = shades {
                let colour = self.accessor_at(view, lo * 4, count, C::U8, T::Vec4, None);
                self.root.accessors[colour.value()].normalized = true;
                attributes.insert(Valid(json::mesh::Semantic::Colors(0)), colour);
            }
            if let Some(view) = radii {
                let radius = self.accessor_at(view, lo * 4, count, C::F32, T::Scalar, None);
                attributes.insert(Valid(json::mesh::Semantic::Extras("RADIUS".into())), radius);
            }
            let indices = &mesh.indices[run.triangles.clone()];
            let idx = if short {
                let base = lo as u32;
                let local: Vec<u16> = indices.iter().map(|&i| (i - base) as u16).collect();
                let v = self.view(
                    Piece::Owned(bytes_of(&local).to_vec()),
                    Target::ElementArrayBuffer,
                );
                self.accessor(v, indices.len(), C::U16, T::Scalar, None)
            } else {
                let v = self.view(Piece::Bytes(bytes_of(indices)), Target::ElementArrayBuffer);
                self.accessor(v, indices.len(), C::U32, T::Scalar, None)
            };
            primitives.push(triangles(attributes, idx, material));
        }
        primitives
    }
}

/// Most vertices one primitive of 16-bit indices spans: glTF reserves the index 65,535
/// (a primitive restart in some graphics APIs), so its indices run 0..=65,534.
const SHORT_SPAN: usize = u16::MAX as usize;

/// A run of a mesh's triangles (a range of its indices) and the vertices they use.
struct Run {
    triangles: std::ops::Range<usize>,
    vertices: std::ops::Range<usize>,
}

/// The mesh's triangles, in order, cut into runs each of whose vertices lie within
/// [`SHORT_SPAN`] of one another, so that each run is written with 16-bit indices (half the
/// bytes of 32-bit ones) counted from its lowest vertex. A tree's mesh is laid out stem by
/// stem, so its triangles' vertices climb with them and a run is a long stretch of stems: a
/// 30-year plane's 80,793 bark vertices are two runs. `None` where one triangle alone
/// spans more.
fn short_runs(indices: &[u32], vertices: usize) -> Option<Vec<Run>> {
    if vertices <= SHORT_SPAN {
        // One run of all the vertices, used or not.
        let whole = Run {
            triangles: 0..indices.len(),
            vertices: 0..vertices,
        };
        return Some(vec![whole]);
    }
    let mut runs = Vec::new();
    let (mut start, mut lo, mut hi) = (0, usize::MAX, 0);
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        let a = tri.iter().map(|&i| i as usize);
        let (tlo, thi) = (a.clone().min().unwrap_or(0), a.max().unwrap_or(0));
        if thi - tlo >= SHORT_SPAN {
            return None;
        }
        let (nlo, nhi) = (lo.min(tlo), hi.max(thi));
        if nhi - nlo >= SHORT_SPAN {
            runs.push(Run {
                triangles: start..t * 3,
                vertices: lo..hi + 1,
            });
            (start, lo, hi) = (t * 3, tlo, thi);
        } else {
            (lo, hi) = (nlo, nhi);
        }
    }
    if start < indices.len() {
        runs.push(Run {
            triangles: start..indices.len(),
            vertices: lo..hi + 1,
        });
    }
    Some(runs)
}

/// Where an impostor's atlas (a PNG file) lies.
#[derive(Clone, Copy, Debug)]
pub(super) enum Image<'a> {
    /// In the GLB's own buffer.
    Embedded(&'a [u8]),
    /// In a file of its own, at this URI.
    Uri(&'a str),
}

/// A primitive of indexed triangles.
pub(super) fn triangles(
    attributes: BTreeMap<
        json::validation::Checked<json::mesh::Semantic>,
        json::Index<json::Accessor>,
    >,
    indices: json::Index<json::Accessor>,
    material: json::Index<json::Material>,
) -> json::mesh::Primitive {
    json::mesh::Primitive {
        attributes,
        extensions: None,
        extras: Default::default(),
        indices: Some(indices),
        material: Some(material),
        mode: Valid(json::mesh::Mode::Triangles),
        targets: None,
    }
}

/// Little-endian bytes of plain numeric arrays: glTF wants little-endian, which this machine
/// is (checked at compile time), so the arrays go out as they lie in memory.
pub(super) fn bytes_of<T: bytemuck::Pod>(items: &[T]) -> &[u8] {
    const _: () = assert!(cfg!(target_endian = "little"));
    bytemuck::cast_slice(items)
}

pub(super) fn material(
    name: &str,
    colour: [f32; 4],
    double_sided: bool,
    roughness: f32,
) -> json::Material {
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

/// Encodes a tree as a chain of levels of detail in one GLB with the `MSFT_lod` extension: the
/// scene holds the most detailed node, `<name>_LOD0`, which lists the others (`<name>_LOD1`,
/// ...; the impostor last) in its `MSFT_lod` extension and their screen coverages in its
/// `extras.MSFT_screencoverage`, as Babylon.js and other MSFT_lod readers expect; viewers
/// without the extension show LOD0. `chain` pairs each mesh with the share of the screen's
/// height below which the next level takes over. The impostor's material is unlit (its light
/// is baked in), alpha-masked and single-sided.
pub fn to_glb_lod(
    name: &str,
    chain: &[(TreeMesh, f32)],
    impostor: Option<(&super::super::lod::impostor::Impostor, f32)>,
    materials: &Materials,
) -> Result<Vec<u8>, ExportError> {
    if chain.is_empty() || chain[0].0.triangle_count() == 0 {
        return Err(ExportError::Format("the LOD chain is empty".into()));
    }
    let quads = impostor.map(|(imp, _)| imp.frame.quads());
    let mut b = Builder::new();
    let mut levels: Vec<(json::Index<json::Mesh>, f32)> = chain
        .iter()
        .enumerate()
        .map(|(k, (mesh, coverage))| {
            (
                b.tree_mesh(&format!("{name}_LOD{k}"), mesh, materials),
                *coverage,
            )
        })
        .collect();
    let mut extensions_used = vec!["MSFT_lod".to_string()];
    if let (Some((imp, coverage)), Some(quads)) = (impostor, &quads) {
        extensions_used.push("KHR_materials_unlit".into());
        levels.push((
            b.impostor_mesh(
                &format!("{name}_LOD{}", chain.len()),
                Image::Embedded(&imp.png),
                quads,
            ),
            coverage,
        ));
    }
    // The lower levels first, so that LOD0 can list their indices.
    let lower: Vec<json::Index<json::Node>> = levels[1..]
        .iter()
        .enumerate()
        .map(|(k, (mesh, _))| {
            b.root.push(json::Node {
                mesh: Some(*mesh),
                name: Some(format!("{name}_LOD{}", k + 1)),
                ..Default::default()
            })
        })
        .collect();
    let ids: Vec<json::Value> = lower.iter().map(|n| json::Value::from(n.value())).collect();
    let mut others = serde_json::Map::new();
    others.insert("MSFT_lod".into(), serde_json::json!({ "ids": ids }));
    let coverage: Vec<f32> = levels.iter().map(|(_, c)| *c).collect();
    let extras =
        serde_json::value::to_raw_value(&serde_json::json!({ "MSFT_screencoverage": coverage }))
            .map_err(|e| ExportError::Format(e.to_string()))?;
    let top = b.root.push(json::Node {
        mesh: Some(levels[0].0),
        name: Some(format!("{name}_LOD0")),
        extensions: Some(json::extensions::scene::Node { others }),
        extras: Some(extras),
        ..Default::default()
    });
    b.root.extensions_used = extensions_used;
    b.scene(vec![top]);
    Ok(finish(b)?.to_vec())
}

impl<'a> Builder<'a> {
    pub(super) fn new() -> Self {
        let mut b = Builder {
            root: json::Root::default(),
            pieces: Vec::new(),
            bin_len: 0,
            buffer: json::Index::new(0),
            shared_atlases: HashMap::new(),
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
        b
    }

    /// A tree's mesh: bark and leaf primitives with their materials.
    pub(super) fn tree_mesh(
        &mut self,
        name: &str,
        mesh: &'a TreeMesh,
        materials: &Materials,
    ) -> json::Index<json::Mesh> {
        let mut primitives = Vec::new();
        if !mesh.bark.indices.is_empty() {
            let m = self
                .root
                .push(material("bark", materials.bark, false, 0.95));
            primitives.extend(self.primitives(&mesh.bark, m));
        }
        if !mesh.leaves.indices.is_empty() {
            let m = self
                .root
                .push(material("leaves", materials.leaves, true, 0.6));
            primitives.extend(self.primitives(&mesh.leaves, m));
        }
        if !mesh.flowers.indices.is_empty() {
            let m = self
                .root
                .push(material("flowers", materials.flowers, true, 0.6));
            primitives.extend(self.primitives(&mesh.flowers, m));
        }
        self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.into()),
            primitives,
            weights: None,
        })
    }

    /// The impostor's quads with the atlas as an unlit, alpha-masked texture.
    pub(super) fn impostor_mesh(
        &mut self,
        name: &str,
        atlas: Image<'a>,
        quads: &'a Mesh,
    ) -> json::Index<json::Mesh> {
        let material = match atlas {
            Image::Embedded(png) => {
                let view = self.view(Piece::Bytes(png), None);
                self.impostor_material("impostor".into(), Some(view), None)
            }
            Image::Uri(uri) => match self.shared_atlases.get(uri) {
                Some(&material) => material,
                None => {
                    // Named by the picture's file, so that a viewer can tell pictures apart
                    // (and tiles in other folders name the same one alike).
                    let file = uri.rsplit('/').next().unwrap_or(uri);
                    let material =
                        self.impostor_material(file.to_string(), None, Some(uri.to_string()));
                    self.shared_atlases.insert(uri.to_string(), material);
                    material
                }
            },
        };
        let primitives = self.primitives(quads, material);
        self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.into()),
            primitives,
            weights: None,
        })
    }

    /// An impostor picture's unlit, alpha-masked material named `label`: the picture in the
    /// buffer view `view` or in the file at `uri`.
    fn impostor_material(
        &mut self,
        label: String,
        view: Option<json::Index<json::buffer::View>>,
        uri: Option<String>,
    ) -> json::Index<json::Material> {
        let image = self.root.push(json::Image {
            buffer_view: view,
            mime_type: Some(json::image::MimeType("image/png".into())),
            name: Some(format!("{label} atlas")),
            uri,
            extensions: None,
            extras: Default::default(),
        });
        let sampler = self.root.push(json::texture::Sampler {
            mag_filter: Some(Valid(json::texture::MagFilter::Linear)),
            min_filter: Some(Valid(json::texture::MinFilter::LinearMipmapLinear)),
            wrap_s: Valid(json::texture::WrappingMode::ClampToEdge),
            wrap_t: Valid(json::texture::WrappingMode::ClampToEdge),
            ..Default::default()
        });
        let texture = self.root.push(json::Texture {
            name: None,
            sampler: Some(sampler),
            source: image,
            extensions: None,
            extras: Default::default(),
        });
        let mut others = serde_json::Map::new();
        others.insert("KHR_materials_unlit".into(), serde_json::json!({}));
        self.root.push(json::Material {
            name: Some(label),
            alpha_mode: Valid(json::material::AlphaMode::Mask),
            alpha_cutoff: Some(json::material::AlphaCutoff(0.5)),
            double_sided: false,
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_texture: Some(json::texture::Info {
                    index: texture,
                    tex_coord: 0,
                    extensions: None,
                    extras: Default::default(),
                }),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(1.0),
                ..Default::default()
            },
            extensions: Some(json::extensions::material::Material { others }),
            ..Default::default()
        })
    }

    /// Closes the buffer and makes the default scene of `nodes`.
    pub(super) fn scene(&mut self, nodes: Vec<json::Index<json::Node>>) {
        let pad = self.bin_len.next_multiple_of(4) - self.bin_len;
        if pad > 0 {
            self.pieces.push((pad, Piece::Bytes(&[])));
            self.bin_len += pad;
        }
        self.root.buffers[0].byte_length = USize64::from(self.bin_len);
        let scene = self.root.push(json::Scene {
            extensions: None,
            extras: Default::default(),
            name: Some("scene".into()),
            nodes,
        });
        self.root.scene = Some(scene);
    }
}

/// A GLB ready to be written: its header and JSON chunk, and the views of its binary chunk
/// where the meshes hold them.
pub struct Glb<'a> {
    head: Vec<u8>,
    pieces: Vec<(usize, Piece<'a>)>,
    /// Bytes of the whole file.
    len: usize,
}

impl Glb<'_> {
    /// Writes the file to `w`, the binary chunk straight from the meshes.
    pub fn write_to(&self, w: &mut dyn Write) -> std::io::Result<()> {
        w.write_all(&self.head)?;
        for (pad, piece) in &self.pieces {
            w.write_all(&[0; 3][..*pad])?;
            piece.write_to(w)?;
        }
        Ok(())
    }

    /// The file as bytes.
    pub fn to_vec(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.len);
        // Writing into a Vec cannot fail.
        let _ = self.write_to(&mut out);
        out
    }
}

/// Closes the JSON and lays out the chunks of a GLB file.
pub(super) fn finish(b: Builder<'_>) -> Result<Glb<'_>, ExportError> {
    let mut json_bytes = b
        .root
        .to_vec()
        .map_err(|e| ExportError::Format(e.to_string()))?;
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let total = 12 + 8 + json_bytes.len() + 8 + b.bin_len;
    let total32 = u32::try_from(total).map_err(|_| {
        ExportError::Format(format!(
            "{total} bytes exceed the 4 GiB limit of a GLB file"
        ))
    })?;
    let mut head = Vec::with_capacity(28 + json_bytes.len());
    head.extend_from_slice(b"glTF");
    head.extend_from_slice(&2u32.to_le_bytes());
    head.extend_from_slice(&total32.to_le_bytes());
    head.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    head.extend_from_slice(b"JSON");
    head.extend_from_slice(&json_bytes);
    head.extend_from_slice(&(b.bin_len as u32).to_le_bytes());
    head.extend_from_slice(b"BIN\0");
    Ok(Glb {
        head,
        pieces: b.pieces,
        len: total,
    })
}
