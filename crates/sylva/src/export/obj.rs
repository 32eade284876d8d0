//! Wavefront OBJ with its MTL: groups `bark` and `leaves`, each with its material, positions,
//! UVs and normals, Y up.

use super::{Materials, write_atomically, y_up};
use crate::error::ExportError;
use crate::mesh::{Mesh, TreeMesh};
use std::fmt::Write;
use std::path::Path;

/// OBJ text and MTL text for a mesh; the OBJ refers to the MTL by `mtl_name`.
pub fn to_obj(
    mesh: &TreeMesh,
    name: &str,
    mtl_name: &str,
    materials: &Materials,
) -> (String, String) {
    let mut obj = String::with_capacity(64 * mesh.vertex_count() + 32 * mesh.triangle_count());
    let _ = writeln!(
        obj,
        "# {name}, written by Sylva {}; metres, Y up",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        obj,
        "mtllib {mtl_name}\no {}",
        name.replace(char::is_whitespace, "_")
    );
    let mut base = 1usize;
    for (group, part) in [("bark", &mesh.bark), ("leaves", &mesh.leaves)] {
        if part.indices.is_empty() {
            continue;
        }
        write_part(&mut obj, group, part, base);
        base += part.vertex_count();
    }
    let mut mtl = String::new();
    for (m, c, double) in [
        ("bark", materials.bark, false),
        ("leaves", materials.leaves, true),
    ] {
        let _ = writeln!(
            mtl,
            "newmtl {m}\nKd {:.4} {:.4} {:.4}\nKa 0 0 0\nKs 0.02 0.02 0.02\nNs 10\nd {}\nillum 2{}\n",
            c[0],
            c[1],
            c[2],
            c[3],
            if double { "\n# double-sided" } else { "" }
        );
    }
    (obj, mtl)
}

fn write_part(obj: &mut String, group: &str, part: &Mesh, base: usize) {
    for p in &part.positions {
        let [x, y, z] = y_up(*p);
        let _ = writeln!(obj, "v {x} {y} {z}");
    }
    for uv in &part.uvs {
        let _ = writeln!(obj, "vt {} {}", uv[0], uv[1]);
    }
    for n in &part.normals {
        let [x, y, z] = y_up(*n);
        let _ = writeln!(obj, "vn {x} {y} {z}");
    }
    let _ = writeln!(obj, "g {group}\nusemtl {group}");
    for t in part.indices.chunks(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize + base);
        let _ = writeln!(obj, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}");
    }
}

/// Writes `path` (the OBJ) and the MTL beside it (same stem, `.mtl`), each atomically.
pub fn write_obj(
    path: &Path,
    mesh: &TreeMesh,
    name: &str,
    materials: &Materials,
) -> Result<(), ExportError> {
    let mtl_path = path.with_extension("mtl");
    let mtl_name = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "tree.mtl".into());
    let (obj, mtl) = to_obj(mesh, name, &mtl_name, materials);
    write_atomically(&mtl_path, mtl.as_bytes())?;
    write_atomically(path, obj.as_bytes())
}
