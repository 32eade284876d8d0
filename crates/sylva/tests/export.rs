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

#[test]
fn glb_reads_back_with_two_primitives_materials_and_y_up() {
    let (sk, mesh) = aspen();
    let bytes = to_glb(&mesh, "Quaking Aspen", &Materials::default()).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
        bytes.len()
    );
    let (doc, buffers, _) = gltf::import_slice(&bytes).expect("gltf reads the GLB");
    let gmesh = doc.meshes().next().unwrap();
    let prims: Vec<_> = gmesh.primitives().collect();
    assert_eq!(prims.len(), 2);
    let names: Vec<_> = prims
        .iter()
        .map(|p| p.material().name().unwrap().to_string())
        .collect();
    assert_eq!(names, ["bark", "leaves"]);
    assert!(!prims[0].material().double_sided());
    assert!(prims[1].material().double_sided());
    let mut max_y = f32::MIN;
    let mut total_tris = 0;
    for (prim, part) in prims.iter().zip([&mesh.bark, &mesh.leaves]) {
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
        let uvs: Vec<[f32; 2]> = reader.read_tex_coords(0).unwrap().into_f32().collect();
        let indices: Vec<u32> = match reader.read_indices().unwrap() {
            gltf::mesh::util::ReadIndices::U32(it) => it.collect(),
            _ => panic!("indices must be 32-bit"),
        };
        assert_eq!(positions.len(), part.vertex_count());
        assert_eq!(normals.len(), positions.len());
        assert_eq!(uvs.len(), positions.len());
        assert_eq!(indices.len(), part.indices.len());
        assert!(indices.iter().all(|&i| (i as usize) < positions.len()));
        total_tris += indices.len() / 3;
        max_y = positions.iter().fold(max_y, |m, p| m.max(p[1]));
    }
    assert_eq!(total_tris, mesh.triangle_count());
    // Y up in the file: the highest point is the tree's height.
    assert!(
        (max_y - sk.stats().height).abs() < 0.05,
        "{max_y} vs {}",
        sk.stats().height
    );
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
