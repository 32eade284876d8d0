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
fn obj_and_mtl_read_back() {
    let (_, mesh) = aspen();
    let (obj, mtl) = to_obj(&mesh, "aspen", "aspen.mtl", &Materials::default());
    let count = |prefix: &str| obj.lines().filter(|l| l.starts_with(prefix)).count();
    assert_eq!(count("v "), mesh.vertex_count());
    assert_eq!(count("vt "), mesh.vertex_count());
    assert_eq!(count("vn "), mesh.vertex_count());
    assert_eq!(count("f "), mesh.triangle_count());
    assert!(
        obj.contains("mtllib aspen.mtl")
            && obj.contains("usemtl bark")
            && obj.contains("usemtl leaves")
    );
    assert!(mtl.contains("newmtl bark") && mtl.contains("newmtl leaves"));
    // Every face index refers to an existing vertex (1-based).
    let n = mesh.vertex_count();
    for line in obj.lines().filter(|l| l.starts_with("f ")) {
        for corner in line[2..].split_whitespace() {
            let i: usize = corner.split('/').next().unwrap().parse().unwrap();
            assert!((1..=n).contains(&i), "{line}");
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
