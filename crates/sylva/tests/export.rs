//! Files written by the exporters, read back by real readers.

use sylva::export::{Materials, to_glb, to_obj};
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva::{GenerateOptions, generate, species::builtin};

fn aspen() -> (sylva::Skeleton, sylva::mesh::TreeMesh) {
    let p = builtin("quaking_aspen").unwrap();
    let sk = generate(
        &p,
        &GenerateOptions {
            seed: 1,
            ..Default::default()
        },
    )
    .unwrap();
    let mesh = mesh_tree(&sk, &MeshOptions::default());
    (sk, mesh)
}

/// A triangle's corner: position, normal, UV.
type Corner = ([f32; 3], [f32; 3], [f32; 2]);

/// Every triangle of each part of `mesh`, read back from the GLB `bytes` as glTF's corners
/// (positions, normals and UVs, Y up) in the file's order, per material name; and checks that
/// every primitive's indices are 16-bit, short of the reserved 65,535.
fn corners_by_material(bytes: &[u8]) -> (Vec<String>, Vec<Vec<Corner>>) {
    let (doc, buffers, _) = gltf::import_slice(bytes).expect("gltf reads the GLB");
    let mut names: Vec<String> = Vec::new();
    let mut corners: Vec<Vec<_>> = Vec::new();
    for prim in doc.meshes().next().unwrap().primitives() {
        let name = prim.material().name().unwrap().to_string();
        if names.last() != Some(&name) {
            names.push(name);
            corners.push(Vec::new());
        }
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        let uvs: Vec<[f32; 2]> = reader.read_tex_coords(0).unwrap().into_f32().collect();
        assert!(positions.len() <= 65_535);
        let indices: Vec<u16> = match reader.read_indices().unwrap() {
            gltf::mesh::util::ReadIndices::U16(it) => it.collect(),
            _ => panic!("indices must be 16-bit"),
        };
        assert!(indices.iter().all(|&i| i < u16::MAX));
        let out = corners.last_mut().unwrap();
        out.extend(indices.iter().map(|&i| {
            let i = i as usize;
            (positions[i], normals[i], uvs[i])
        }));
    }
    (names, corners)
}

/// `part`'s triangles' corners as a GLB holds them (Y up).
fn corners_of(part: &sylva::mesh::Mesh) -> Vec<Corner> {
    let up = |[x, y, z]: [f32; 3]| [x, z, -y];
    part.indices
        .iter()
        .map(|&i| {
            let i = i as usize;
            (up(part.positions[i]), up(part.normals[i]), part.uvs[i])
        })
        .collect()
}

#[test]
fn glb_reads_back_with_two_primitives_materials_and_y_up() {
    let (sk, mesh) = aspen();
    let bytes = to_glb(&mesh, "Quaking Aspen", &Materials::default()).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
        bytes.len()
    );
    let (doc, _, _) = gltf::import_slice(&bytes).expect("gltf reads the GLB");
    let materials: Vec<_> = doc.materials().collect();
    assert!(!materials[0].double_sided(), "bark");
    assert!(materials[1].double_sided(), "leaves");
    let (names, corners) = corners_by_material(&bytes);
    assert_eq!(names, ["bark", "leaves"]);
    // Every triangle as meshed, in order, whether a part is one primitive or cut in several.
    assert_eq!(corners[0], corners_of(&mesh.bark));
    assert_eq!(corners[1], corners_of(&mesh.leaves));
    // Y up in the file: the highest point is the tree's height.
    let max_y = corners
        .iter()
        .flatten()
        .fold(f32::MIN, |m, c| m.max(c.0[1]));
    assert!(
        (max_y - sk.stats().height).abs() < 0.05,
        "{max_y} vs {}",
        sk.stats().height
    );
}

/// A part with more vertices than 16-bit indices reach is cut into primitives that each
/// reach theirs, and reads back triangle for triangle.
#[test]
fn a_large_part_is_cut_into_primitives_of_16_bit_indices() {
    let mut mesh = sylva::mesh::TreeMesh::default();
    // 150,000 vertices in a strip of triangles, each using three neighbours.
    let n = 150_000u32;
    for k in 0..n {
        let x = k as f32 * 1e-3;
        mesh.bark.positions.push([x, (k % 2) as f32, x.sin()]);
        mesh.bark.normals.push([0.0, 0.0, 1.0]);
        mesh.bark.uvs.push([x, 0.5]);
    }
    for k in 0..n - 2 {
        mesh.bark.indices.extend([k, k + 1, k + 2]);
    }
    let bytes = to_glb(&mesh, "strip", &Materials::default()).unwrap();
    let (doc, _, _) = gltf::import_slice(&bytes).unwrap();
    assert_eq!(doc.meshes().next().unwrap().primitives().count(), 3);
    let (names, corners) = corners_by_material(&bytes);
    assert_eq!(names, ["bark"]);
    assert_eq!(corners[0], corners_of(&mesh.bark));
}

#[test]
fn obj_and_mtl_read_back_exactly_through_a_real_reader() {
    let (_, mesh) = aspen();
    let (obj, mtl) = to_obj(&mesh, "aspen", "aspen.mtl", &Materials::default());
    let text = std::str::from_utf8(&obj).expect("OBJ is text");
    assert!(text.contains("mtllib aspen.mtl") && text.contains("usemtl bark"));
    assert!(text.contains("usemtl leaves"));
    assert!(mtl.contains("newmtl bark") && mtl.contains("newmtl leaves"));
    // Flat leaves share a normal per blade, so there are fewer normals than vertices.
    let lines = |tag: &str| text.lines().filter(|l| l.starts_with(tag)).count();
    assert_eq!(lines("v "), mesh.vertex_count());
    assert!(
        lines("vn ") < mesh.vertex_count() * 3 / 4,
        "{}",
        lines("vn ")
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("aspen.obj");
    std::fs::write(&path, &obj).unwrap();
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(&path, &options).expect("tobj reads the OBJ");
    let read: Vec<&tobj::Model> = models
        .iter()
        .filter(|m| !m.mesh.indices.is_empty())
        .collect();
    assert_eq!(read.len(), 2, "bark and leaves");
    // Every corner of every triangle reads back bit for bit: position (Y up), UV, normal.
    for (model, part) in read.iter().zip([&mesh.bark, &mesh.leaves]) {
        let m = &model.mesh;
        assert_eq!(m.indices.len(), part.indices.len(), "{}", model.name);
        for (k, &i) in part.indices.iter().enumerate() {
            let i = i as usize;
            let at = |v: &[f32], j: u32, n: usize| v[j as usize * n..j as usize * n + n].to_vec();
            let [x, y, z] = part.positions[i];
            let [nx, ny, nz] = part.normals[i];
            assert_eq!(at(&m.positions, m.indices[k], 3), [x, z, -y]);
            assert_eq!(at(&m.normals, m.normal_indices[k], 3), [nx, nz, -ny]);
            assert_eq!(at(&m.texcoords, m.texcoord_indices[k], 2), part.uvs[i]);
        }
    }
}

#[test]
fn an_empty_mesh_is_an_error_not_a_file() {
    let empty = sylva::mesh::TreeMesh::default();
    assert!(to_glb(&empty, "x", &Materials::default()).is_err());
}

#[test]
fn atomic_write_leaves_nothing_on_failure() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("no_such_dir").join("tree.glb");
    assert!(sylva::export::write_atomically(&target, b"x").is_err());
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}
