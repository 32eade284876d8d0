//! Reading a GLB back for pictures and the model viewer: each distinct mesh once, with every
//! node that shows it as a placement, so a forest of a thousand copies of three trees costs
//! three trees of memory and draws instanced.

use crate::{Placement, RenderTree, Renderer, Scene, Stand};
use glam::{Mat4, Vec3};
use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;
use sylva::mesh::{Mesh, TreeMesh, place_copies};

/// Deepest node hierarchy read, and most nodes visited: a malformed file (a node listed as its
/// own child) stops here instead of looping.
const MAX_DEPTH: usize = 64;
const MAX_NODES: usize = 4_000_000;
/// Largest model file read (a GLB's lengths are 32-bit), and largest external buffer.
const MAX_FILE_BYTES: u64 = 2 << 30;

/// A model file that cannot be drawn; the message names the file and what is wrong.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct GlbError(String);

/// Fails with a message made by `format!`.
macro_rules! fail {
    ($($arg:tt)*) => { return Err(GlbError(format!($($arg)*))) };
}

/// One mesh of a GLB and where it stands.
pub struct GlbModel {
    /// The mesh in Sylva's frame (metres, Z up).
    pub mesh: TreeMesh,
    /// sRGB base colour of its bark material.
    pub bark: [f32; 3],
    /// sRGB base colour of its leaf material.
    pub leaves: [f32; 3],
    /// sRGB base colour of its flower material, where it has flowers.
    pub flowers: Option<[f32; 3]>,
    /// Every node showing it.
    pub placements: Vec<Placement>,
}

/// The models of a GLB's default scene.
pub struct GlbScene {
    /// Each distinct mesh once, with its placements.
    pub models: Vec<GlbModel>,
}

impl GlbScene {
    /// Triangles in the scene, every copy counted.
    pub fn triangles_placed(&self) -> usize {
        self.models
            .iter()
            .map(|m| m.mesh.triangle_count() * m.placements.len())
            .sum()
    }
}

/// glTF's Y up to Sylva's Z up: (x, y, z) -> (x, -z, y).
const Y_UP_TO_Z_UP: Mat4 = Mat4::from_cols_array(&[
    1.0, 0.0, 0.0, 0.0, //
    0.0, 0.0, 1.0, 0.0, //
    0.0, -1.0, 0.0, 0.0, //
    0.0, 0.0, 0.0, 1.0,
]);

/// A node's transform (Z up) as a placement, when it is one: a uniform scale, a turn about the
/// vertical and a move, as Sylva's forests write them.
fn as_placement(m: Mat4) -> Option<Placement> {
    let (x, y, z) = (
        m.x_axis.truncate(),
        m.y_axis.truncate(),
        m.z_axis.truncate(),
    );
    let scale = z.z;
    let tolerance = 1e-4 * scale.abs().max(1.0);
    let close = |a: Vec3, b: Vec3| (a - b).abs().max_element() <= tolerance;
    let (cos, sin) = (x.x / scale, x.y / scale);
    let ok = scale > 0.0
        && scale.is_finite()
        && close(z, Vec3::new(0.0, 0.0, scale))
        && close(x, Vec3::new(cos, sin, 0.0) * scale)
        && close(y, Vec3::new(-sin, cos, 0.0) * scale)
        && ((cos * cos + sin * sin) - 1.0).abs() < 1e-3
        && m.row(3) == glam::Vec4::W;
    ok.then(|| Placement {
        position: m.w_axis.truncate(),
        turn: sin.atan2(cos),
        scale,
    })
}

/// sRGB colours of a mesh's bark, leaf and flower materials, where it has them.
type Colours = [Option<[f32; 3]>; 3];

/// Reads a glTF mesh's triangle primitives into a tree mesh transformed by `transform` (glTF's
/// frame to Sylva's): primitives whose material is named `leaves` are leaves, the rest bark.
/// Returns the mesh and its bark and leaf colours (`None` where it has no such material).
fn read_mesh(
    mesh: &gltf::Mesh,
    buffers: &[gltf::buffer::Data],
    transform: Mat4,
) -> (TreeMesh, Colours) {
    let mut out = TreeMesh::default();
    let (mut bark, mut leaves, mut flowers) = (None, None, None);
    for prim in mesh.primitives() {
        if prim.mode() != gltf::mesh::Mode::Triangles {
            continue;
        }
        let [r, g, b, _] = prim.material().pbr_metallic_roughness().base_color_factor();
        let srgb = [r, g, b].map(sylva::colour::linear_to_srgb);
        let part: &mut Mesh = match prim.material().name() {
            Some("leaves") => {
                leaves = Some(srgb);
                &mut out.leaves
            }
            // Sylva's flowers in their season (any other file's primitives draw as bark).
            Some("flowers") => {
                flowers = Some(srgb);
                &mut out.flowers
            }
            _ => {
                bark = Some(srgb);
                &mut out.bark
            }
        };
        let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
        let Some(positions) = reader.read_positions() else {
            continue;
        };
        let base = part.positions.len() as u32;
        let positions: Vec<[f32; 3]> = positions
            .map(|p| transform.transform_point3(Vec3::from(p)).to_array())
            .collect();
        let count = positions.len() as u32;
        let normals: Vec<[f32; 3]> = match reader.read_normals() {
            Some(n) => n
                .map(|n| {
                    transform
                        .transform_vector3(Vec3::from(n))
                        .normalize_or_zero()
                        .to_array()
                })
                .take(count as usize)
                .collect(),
            None => Vec::new(),
        };
        let normals = if normals.len() == count as usize {
            normals
        } else {
            vec![[0.0, 0.0, 1.0]; count as usize]
        };
        // COLOR_0 (a grown tree's leaf light classes) becomes the shade; the other primitives
        // of a part with shades are fully lit.
        let shades: Option<Vec<f32>> = reader
            .read_colors(0)
            .map(|c| c.into_rgb_f32().map(|c| c[1].clamp(0.0, 1.0)).collect())
            .filter(|c: &Vec<f32>| c.len() == count as usize);
        match shades {
            Some(c) => {
                part.shades.resize(base as usize, 1.0);
                part.shades.extend(c);
            }
            None if !part.shades.is_empty() => {
                part.shades.resize(base as usize + count as usize, 1.0);
            }
            None => {}
        }
        part.positions.extend(positions);
        part.normals.extend(normals);
        part.uvs
            .extend(std::iter::repeat_n([0.0, 0.0], count as usize));
        match reader.read_indices() {
            Some(idx) => part
                .indices
                .extend(idx.into_u32().filter(|&i| i < count).map(|i| i + base)),
            None => part.indices.extend(base..base + count),
        }
        // Indices that pointed outside the primitive were dropped: keep whole triangles only.
        part.indices.truncate(part.indices.len() / 3 * 3);
    }
    (out, [bark, leaves, flowers])
}

/// Reads the default scene of a GLB (or glTF) file: each mesh once, placed by every node that
/// shows it. A node whose transform is more than a move, a turn about the vertical and a
/// uniform scale gets its own transformed copy of the mesh.
pub fn read_glb_scene(path: &Path) -> Result<GlbScene, GlbError> {
    glb_scene_of(read_bounded(path)?, path)
}

/// [`read_glb_scene`] for a GLB in memory (one Sylva just made); `name` stands for its path in
/// messages.
pub fn glb_scene_from_bytes(bytes: Vec<u8>, name: &str) -> Result<GlbScene, GlbError> {
    glb_scene_of(bytes, Path::new(name))
}

fn glb_scene_of(bytes: Vec<u8>, path: &Path) -> Result<GlbScene, GlbError> {
    // The reader subtracts the 12-byte header from the length a GLB declares without checking
    // it (gltf 1.4.1): a length under 20 (header and one chunk header) must not reach it.
    if let Some(declared) = bytes.strip_prefix(b"glTF").and_then(|b| b.get(4..8)) {
        let declared = u32::from_le_bytes(declared.try_into().expect("4 bytes")) as usize;
        if declared < 20 || declared > bytes.len() {
            fail!(
                "{}: not a readable glTF file: its header says {declared} bytes, the file has {}",
                path.display(),
                bytes.len()
            );
        }
    }
    // From a slice, whose lengths the reader checks against the data (its stream reader
    // trusts the header's length: it underflows below 12 and allocates whatever it says).
    let unreadable =
        |e: gltf::Error| GlbError(format!("{}: not a readable glTF file: {e}", path.display()));
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(&bytes).map_err(unreadable)?;
    drop(bytes);
    // The reader refuses a file that requires an extension it does not know; instanced copies
    // (a bare crown's twigs) are read here (`instances`), so that one is taken off its list
    // before it checks the rest of the file.
    let mut root = document.into_json();
    root.extensions_required.retain(|e| e != INSTANCING);
    let gltf = gltf::Gltf {
        document: gltf::Document::from_json(root).map_err(unreadable)?,
        blob,
    };
    let base = path.parent().unwrap_or(Path::new("."));
    check_external_buffers(&gltf.document, base, path)?;
    let buffers = gltf::import_buffers(&gltf.document, Some(base), gltf.blob.clone())
        .map_err(|e| GlbError(format!("{}: cannot load its buffers: {e}", path.display())))?;
    let doc = &gltf.document;
    let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        // No scene: every node that is nobody's child is a root.
        None => {
            let children: std::collections::HashSet<usize> = doc
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()))
                .collect();
            doc.nodes()
                .filter(|n| !children.contains(&n.index()))
                .collect()
        }
    };
    let mut models: Vec<GlbModel> = Vec::new();
    let mut by_mesh: HashMap<usize, usize> = HashMap::new();
    let mut stack: Vec<(gltf::Node, Mat4, usize)> =
        roots.into_iter().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    let mut visited = 0usize;
    let z_up = Y_UP_TO_Z_UP;
    let y_up = z_up.inverse();
    while let Some((node, parent, depth)) = stack.pop() {
        visited += 1;
        if depth > MAX_DEPTH || visited > MAX_NODES {
            fail!(
                "{}: its node hierarchy is deeper than {MAX_DEPTH} or has over {MAX_NODES} \
                 nodes (a node listed inside itself?)",
                path.display()
            );
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        for child in node.children() {
            stack.push((child, world, depth + 1));
        }
        let Some(mesh) = node.mesh() else { continue };
        if let Some(copies) = instances(doc, &node, &buffers, path)? {
            // Copies drawn by the GPU (a bare crown's twigs): read here as one mesh holding
            // every copy, each placed.
            let (m, colours) = read_copies(&mesh, &buffers, z_up * world, &copies, path)?;
            models.push(model(m, colours, vec![Placement::ORIGIN]));
            continue;
        }
        let placed = z_up * world * y_up;
        match (as_placement(placed), by_mesh.get(&mesh.index())) {
            (Some(p), Some(&k)) => models[k].placements.push(p),
            (Some(p), None) => {
                let (m, colours) = read_mesh(&mesh, &buffers, z_up);
                by_mesh.insert(mesh.index(), models.len());
                models.push(model(m, colours, vec![p]));
            }
            (None, _) => {
                let (m, colours) = read_mesh(&mesh, &buffers, placed * z_up);
                models.push(model(m, colours, vec![Placement::ORIGIN]));
            }
        }
    }
    // Meshes without triangles draw nothing; drop them.
    models.retain(|m| m.mesh.triangle_count() > 0);
    if models.is_empty() {
        fail!("{}: no triangles to render", path.display());
    }
    Ok(GlbScene { models })
}

/// glTF's extension for copies of a mesh drawn by the GPU.
const INSTANCING: &str = "EXT_mesh_gpu_instancing";
/// Most vertices a GLB's instanced copies are read into (about a gigabyte of mesh).
const MAX_COPIED_VERTICES: usize = 30_000_000;

/// The transforms of a node's copies (`EXT_mesh_gpu_instancing`: each copy's TRANSLATION,
/// ROTATION and SCALE, glTF's frame), or `None` where the node has no such extension.
fn instances(
    doc: &gltf::Document,
    node: &gltf::Node,
    buffers: &[gltf::buffer::Data],
    path: &Path,
) -> Result<Option<Vec<Mat4>>, GlbError> {
    let json = &doc.as_json().nodes[node.index()];
    let Some(ext) = (json.extensions.as_ref()).and_then(|e| e.others.get(INSTANCING)) else {
        return Ok(None);
    };
    use gltf::accessor::{DataType, Iter};
    // Each attribute's accessor: floats, or for a ROTATION normalised 8- or 16-bit integers,
    // as the extension allows (Sylva writes a twig's turns as 16-bit ones).
    let attribute = |name: &str| -> Result<Option<gltf::Accessor>, GlbError> {
        let Some(index) = ext["attributes"].get(name) else {
            return Ok(None);
        };
        let found = index.as_u64().and_then(|i| doc.accessors().nth(i as usize));
        let integer_turn = |a: &gltf::Accessor| {
            name == "ROTATION"
                && a.normalized()
                && matches!(a.data_type(), DataType::I16 | DataType::I8)
        };
        match found {
            Some(a) if a.data_type() == DataType::F32 || integer_turn(&a) => Ok(Some(a)),
            _ => fail!(
                "{}: node {}'s EXT_mesh_gpu_instancing {name} names no accessor of floats (or, \
                 for ROTATION, of normalised 8- or 16-bit integers)",
                path.display(),
                node.index()
            ),
        }
    };
    let data = |b: gltf::Buffer| buffers.get(b.index()).map(|d| &d.0[..]);
    let read3 = |a: Option<gltf::Accessor>| -> Vec<[f32; 3]> {
        a.and_then(|a| Iter::<[f32; 3]>::new(a, data))
            .map_or_else(Vec::new, Iterator::collect)
    };
    let moves = read3(attribute("TRANSLATION")?);
    let scales = read3(attribute("SCALE")?);
    // glTF's normalised signed integers: c / max, and never below -1.
    fn unit<T: Copy + Into<f32>>(q: [T; 4], max: f32) -> [f32; 4] {
        q.map(|c| (c.into() / max).max(-1.0))
    }
    let turns: Vec<[f32; 4]> = match attribute("ROTATION")? {
        None => Vec::new(),
        Some(a) => match a.data_type() {
            DataType::I16 => Iter::<[i16; 4]>::new(a, data)
                .map_or_else(Vec::new, |q| q.map(|q| unit(q, 32767.0)).collect()),
            DataType::I8 => Iter::<[i8; 4]>::new(a, data)
                .map_or_else(Vec::new, |q| q.map(|q| unit(q, 127.0)).collect()),
            _ => Iter::<[f32; 4]>::new(a, data).map_or_else(Vec::new, Iterator::collect),
        },
    };
    let n = moves.len().max(scales.len()).max(turns.len());
    let fits = |len: usize| len == 0 || len == n;
    if !(fits(moves.len()) && fits(scales.len()) && fits(turns.len())) {
        fail!(
            "{}: node {}'s copies have {} translations, {} rotations and {} scales (each \
             must be absent or as many as the copies)",
            path.display(),
            node.index(),
            moves.len(),
            turns.len(),
            scales.len()
        );
    }
    Ok(Some(
        (0..n)
            .map(|i| {
                Mat4::from_scale_rotation_translation(
                    scales.get(i).map_or(Vec3::ONE, |&s| Vec3::from(s)),
                    turns.get(i).map_or(glam::Quat::IDENTITY, |&q| {
                        glam::Quat::from_array(q).normalize()
                    }),
                    moves.get(i).map_or(Vec3::ZERO, |&t| Vec3::from(t)),
                )
            })
            .collect(),
    ))
}

/// `mesh` read once and written out at each of `copies` (glTF's frame, under `to_sylva`): one
/// mesh of every copy (`sylva::mesh::place_copies`).
fn read_copies(
    mesh: &gltf::Mesh,
    buffers: &[gltf::buffer::Data],
    to_sylva: Mat4,
    copies: &[Mat4],
    path: &Path,
) -> Result<(TreeMesh, Colours), GlbError> {
    let (one, colours) = read_mesh(mesh, buffers, Mat4::IDENTITY);
    if one.vertex_count().saturating_mul(copies.len()) > MAX_COPIED_VERTICES {
        fail!(
            "{}: {} copies of a mesh of {} vertices are more than the \
             {MAX_COPIED_VERTICES} vertices read from instanced copies",
            path.display(),
            copies.len(),
            one.vertex_count()
        );
    }
    let mut out = TreeMesh::default();
    for (from, to) in [
        (&one.bark, &mut out.bark),
        (&one.leaves, &mut out.leaves),
        (&one.flowers, &mut out.flowers),
    ] {
        place_copies(from, copies.iter().map(|&copy| to_sylva * copy), to);
    }
    Ok((out, colours))
}

/// The whole file, if it is a regular file within the budget.
fn read_bounded(path: &Path) -> Result<Vec<u8>, GlbError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| GlbError(format!("cannot read {}: {e}", path.display())))?;
    if !meta.is_file() {
        fail!("{}: not a file", path.display());
    }
    if meta.len() > MAX_FILE_BYTES {
        fail!(
            "{}: {} MB, over the {} MB a model may take",
            path.display(),
            meta.len() >> 20,
            MAX_FILE_BYTES >> 20
        );
    }
    std::fs::read(path).map_err(|e| GlbError(format!("cannot read {}: {e}", path.display())))
}

/// Buffers in other files must be regular files within the budget (a `.gltf` naming
/// `/dev/zero` would otherwise be read without end).
fn check_external_buffers(doc: &gltf::Document, base: &Path, path: &Path) -> Result<(), GlbError> {
    for buffer in doc.buffers() {
        if let gltf::buffer::Source::Uri(uri) = buffer.source()
            && !uri.starts_with("data:")
        {
            let file = base.join(uri);
            let ok =
                std::fs::metadata(&file).is_ok_and(|m| m.is_file() && m.len() <= MAX_FILE_BYTES);
            if !ok {
                fail!(
                    "{}: buffer {} names `{uri}`, which is not a readable file of at most {} MB",
                    path.display(),
                    buffer.index(),
                    MAX_FILE_BYTES >> 20
                );
            }
        }
    }
    Ok(())
}

fn model(
    mesh: TreeMesh,
    [bark, leaves, flowers]: [Option<[f32; 3]>; 3],
    placements: Vec<Placement>,
) -> GlbModel {
    GlbModel {
        mesh,
        bark: bark.unwrap_or(sylva::params::DEFAULT_BARK),
        leaves: leaves.unwrap_or(sylva::params::DEFAULT_LEAVES),
        flowers,
        placements,
    }
}

/// The trees of a GLB's scene on a renderer: each distinct mesh uploaded once, its copies
/// placed.
pub struct UploadedScene {
    /// Each model's tree, and its flowers where it has them.
    trees: Vec<(RenderTree, Option<RenderTree>)>,
    glb: GlbScene,
}

impl UploadedScene {
    /// Uploads every distinct mesh of `glb`.
    pub fn new(renderer: &Renderer, glb: GlbScene) -> Self {
        let trees = glb
            .models
            .iter()
            .map(|m| (renderer.upload(&m.mesh), renderer.upload_flowers(&m.mesh)))
            .collect();
        Self { trees, glb }
    }

    /// The scene with ground and person, as a single tree's picture shows them.
    pub fn scene(&self) -> Scene<'_> {
        let stands = self
            .trees
            .iter()
            .zip(&self.glb.models)
            .flat_map(|((tree, flowers), m)| {
                let stand = Stand {
                    tree,
                    bark: m.bark,
                    leaves: m.leaves,
                    placements: Cow::Borrowed(&m.placements),
                };
                stand.with_flowers(flowers.as_ref().map(|f| (f, m.flowers.unwrap_or([1.0; 3]))))
            })
            .collect();
        Scene {
            show_person: true,
            ..Scene::forest(stands)
        }
    }

    /// Triangles drawn, every copy counted.
    pub fn triangles(&self) -> usize {
        self.glb.triangles_placed()
    }

    /// The scene's bounds (metres, Z up).
    pub fn bounds(&self) -> (Vec3, Vec3) {
        self.scene().tree_bounds()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_moves_and_scales_are_placements_and_shears_are_not() {
        let m = Mat4::from_translation(Vec3::new(3.0, -2.0, 0.5))
            * Mat4::from_rotation_z(0.7)
            * Mat4::from_scale(Vec3::splat(1.3));
        let p = as_placement(m).unwrap();
        assert!((p.turn - 0.7).abs() < 1e-5 && (p.scale - 1.3).abs() < 1e-5);
        let corner = Vec3::new(1.0, 2.0, 3.0);
        assert!((p.apply(corner) - m.transform_point3(corner)).length() < 1e-4);
        assert!(as_placement(Mat4::from_rotation_x(0.3)).is_none());
        assert!(as_placement(Mat4::from_scale(Vec3::new(1.0, 2.0, 1.0))).is_none());
        assert!(as_placement(Mat4::from_scale(Vec3::splat(-1.0))).is_none());
        let origin = as_placement(Mat4::IDENTITY).unwrap();
        assert_eq!(origin, Placement::ORIGIN);
    }

    #[test]
    fn instanced_twig_copies_are_read_as_every_twig_placed() {
        use sylva::mesh::{MeshOptions, mesh_tree};
        use sylva::skeleton::{CrossSection, Skeleton, Stem, StemId};
        // A bare stem with two short twigs, the second a turned, larger copy of the first.
        let ring = |p: Vec3, d: Vec3, radius| CrossSection {
            position: p,
            orientation: glam::Quat::from_rotation_arc(Vec3::Z, d.normalize()),
            radius,
            z: 0.0,
        };
        let stem = |level, sections: std::ops::Range<u32>| Stem {
            level,
            parent: (level > 0).then_some(StemId(0)),
            clone_of: None,
            offset: 0.0,
            length: 1.0,
            sections,
            lobes: 0,
            lobe_depth: 0.0,
        };
        let (a, b) = (Vec3::new(1.0, 0.3, 0.4), Vec3::new(-0.2, 1.0, -0.1));
        let sk = Skeleton {
            stems: vec![stem(0, 0..2), stem(3, 2..4), stem(3, 4..6)],
            sections: vec![
                ring(Vec3::ZERO, Vec3::Z, 0.04),
                ring(Vec3::Z * 2.0, Vec3::Z, 0.01),
                ring(Vec3::Z, a, 0.003),
                ring(Vec3::Z + a.normalize() * 0.03, a, 0.00105),
                ring(Vec3::Z * 1.5, b, 0.004),
                ring(Vec3::Z * 1.5 + b.normalize() * 0.05, b, 0.0014),
            ],
            short_twigs: 2,
            ..Default::default()
        };
        let direct = mesh_tree(&sk, &MeshOptions::default());
        let options = MeshOptions {
            twig_copies: true,
            ..Default::default()
        };
        let glb = sylva::export::to_glb(&mesh_tree(&sk, &options), "t", &Default::default());
        let scene = glb_scene_from_bytes(glb.unwrap(), "twigs.glb").unwrap();
        let triangles: usize = scene.models.iter().map(|m| m.mesh.triangle_count()).sum();
        assert_eq!(triangles, direct.triangle_count());
        // The copies' vertices are where the twigs meshed one by one put theirs (Z up).
        let copies = scene
            .models
            .iter()
            .find(|m| m.mesh.bark.vertex_count() < 40)
            .unwrap();
        let twig_vertices = &direct.bark.positions[direct.bark.vertex_count() - 32..];
        for (p, q) in copies.mesh.bark.positions.iter().zip(twig_vertices) {
            assert!(
                Vec3::from(*p).distance(Vec3::from(*q)) < 1e-5,
                "{p:?} against {q:?}"
            );
        }
    }

    #[test]
    fn a_turn_about_y_in_gltf_is_a_turn_about_z_here() {
        // Sylva's forests write turns as rotations about glTF's Y axis.
        let gltf = Mat4::from_rotation_y(0.5);
        let p = as_placement(Y_UP_TO_Z_UP * gltf * Y_UP_TO_Z_UP.inverse()).unwrap();
        assert!((p.turn.abs() - 0.5).abs() < 1e-5, "{}", p.turn);
    }
}
