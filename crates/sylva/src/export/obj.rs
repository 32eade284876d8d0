//! Wavefront OBJ with its MTL: groups `bark` and `leaves`, each with its material, positions,
//! UVs and normals, Y up.
//!
//! OBJ is text, and a tree is large: a Black Tupelo is half a million vertices. What makes the
//! file small and quick to write, without losing a bit of any value:
//!
//! - numbers are the shortest text that reads back as the same `f32` (Żmij's digits; `0`, not
//!   `0.0`), and integers are written without `fmt`;
//! - each vertex is written just before the first triangle that needs it, and triangles refer
//!   to vertices relative to the last one written (`f -3/-3/-2 ...`, as the OBJ format allows):
//!   a few characters where absolute indices take six or seven;
//! - a normal equal to the previous vertex's is not written again (a flat leaf's vertices
//!   share one), so `vn` lines are fewer than `v` lines;
//! - the text is formatted in blocks of triangles on every core, then written in order.

use super::{Materials, write_atomically, write_atomically_with, y_up};
use crate::error::ExportError;
use crate::mesh::{Mesh, TreeMesh};
use rayon::prelude::*;
use std::fmt::Write;
use std::path::Path;

/// Triangles formatted together: blocks of some hundreds of kilobytes of text.
const BLOCK: usize = 8192;

/// OBJ text (as bytes, in blocks to be written in order) and MTL text for a mesh; the OBJ
/// refers to the MTL by `mtl_name`.
fn to_obj_blocks(
    mesh: &TreeMesh,
    name: &str,
    mtl_name: &str,
    materials: &Materials,
) -> (Vec<Vec<u8>>, String) {
    let mut head = String::new();
    let _ = writeln!(
        head,
        "# {name}, written by Sylva {}; metres, Y up\nmtllib {mtl_name}\no {}",
        env!("CARGO_PKG_VERSION"),
        name.replace(char::is_whitespace, "_")
    );
    let mut blocks = vec![head.into_bytes()];
    // OBJ has no instancing: twig copies are written out one by one.
    let bark = mesh.bark_with_twigs();
    for (group, part) in [
        ("bark", &*bark),
        ("leaves", &mesh.leaves),
        ("flowers", &mesh.flowers),
    ] {
        if !part.indices.is_empty() {
            blocks.push(format!("g {group}\nusemtl {group}\n").into_bytes());
            blocks.extend(part_blocks(part));
        }
    }
    let mut mtl = String::new();
    let flowers =
        (!mesh.flowers.indices.is_empty()).then_some(("flowers", materials.flowers, true));
    for (m, c, double) in [
        ("bark", materials.bark, false),
        ("leaves", materials.leaves, true),
    ]
    .into_iter()
    .chain(flowers)
    {
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
    (blocks, mtl)
}

/// OBJ text (bytes; plain ASCII but for the tree's name) and MTL text for a mesh; the OBJ
/// refers to the MTL by `mtl_name`.
pub fn to_obj(
    mesh: &TreeMesh,
    name: &str,
    mtl_name: &str,
    materials: &Materials,
) -> (Vec<u8>, String) {
    let (blocks, mtl) = to_obj_blocks(mesh, name, mtl_name, materials);
    (blocks.concat(), mtl)
}

/// Where each triangle stands in the text: how many vertices and normals are written before
/// it. Vertices go out in index order, each just before the first triangle that needs it.
struct Layout {
    /// Per triangle, the vertices written once it may be written (one past its highest index,
    /// or past an earlier triangle's).
    vertices_before: Vec<u32>,
    /// Per vertex, the normals written up to and including its own (1-based count): a vertex
    /// whose normal equals the previous vertex's writes none.
    normals_through: Vec<u32>,
}

fn layout(part: &Mesh) -> Layout {
    let mut seen = 0u32;
    let vertices_before = part
        .indices
        .chunks_exact(3)
        .map(|t| {
            seen = seen.max(t[0].max(t[1]).max(t[2]) + 1);
            seen
        })
        .collect();
    let mut count = 0u32;
    let mut previous: Option<[u32; 3]> = None;
    let normals_through = part
        .normals
        .iter()
        .map(|n| {
            let bits = n.map(f32::to_bits);
            if previous != Some(bits) {
                count += 1;
                previous = Some(bits);
            }
            count
        })
        .collect();
    Layout {
        vertices_before,
        normals_through,
    }
}

/// A part's vertices and triangles as text blocks, formatted in parallel.
fn part_blocks(part: &Mesh) -> Vec<Vec<u8>> {
    let layout = layout(part);
    let triangles = part.indices.len() / 3;
    let mut blocks: Vec<Vec<u8>> = (0..triangles.div_ceil(BLOCK))
        .into_par_iter()
        .map(|b| {
            let range = b * BLOCK..((b + 1) * BLOCK).min(triangles);
            let mut text = Text::with_capacity(range.len() * 96);
            let mut written = if range.start == 0 {
                0
            } else {
                layout.vertices_before[range.start - 1]
            };
            for t in range {
                let upto = layout.vertices_before[t];
                text.vertices(part, &layout, written..upto);
                written = upto;
                let normals = layout.normals_through[upto as usize - 1];
                text.face(&part.indices[3 * t..3 * t + 3], &layout, upto, normals);
            }
            text.out
        })
        .collect();
    // Vertices no triangle uses still belong to the mesh.
    let written = layout.vertices_before.last().copied().unwrap_or(0);
    let mut rest = Text::with_capacity(0);
    rest.vertices(part, &layout, written..part.vertex_count() as u32);
    blocks.push(rest.out);
    blocks
}

/// OBJ text being formatted.
struct Text {
    out: Vec<u8>,
    float: zmij::Buffer,
    int: itoa::Buffer,
}

impl Text {
    fn with_capacity(bytes: usize) -> Self {
        Self {
            out: Vec::with_capacity(bytes),
            float: zmij::Buffer::new(),
            int: itoa::Buffer::new(),
        }
    }

    /// The shortest text that reads back as `v`: Żmij's digits, and no `.0` on whole numbers.
    fn float(&mut self, v: f32) {
        let s = self.float.format(v);
        let s = s.strip_suffix(".0").unwrap_or(s);
        self.out.extend_from_slice(s.as_bytes());
    }

    fn line(&mut self, tag: &[u8], values: &[f32]) {
        self.out.extend_from_slice(tag);
        for &v in values {
            self.out.push(b' ');
            self.float(v);
        }
        self.out.push(b'\n');
    }

    /// `v`, `vt` and (where it changes) `vn` lines of vertices `range`.
    fn vertices(&mut self, part: &Mesh, layout: &Layout, range: std::ops::Range<u32>) {
        for i in range.start as usize..range.end as usize {
            self.line(b"v", &y_up(part.positions[i]));
            self.line(b"vt", &part.uvs[i]);
            let first = i == 0 || layout.normals_through[i] != layout.normals_through[i - 1];
            if first {
                self.line(b"vn", &y_up(part.normals[i]));
            }
        }
    }

    /// An `f` line for `triangle`, written when `vertices` vertices and `normals` normals are.
    fn face(&mut self, triangle: &[u32], layout: &Layout, vertices: u32, normals: u32) {
        self.out.push(b'f');
        for &i in triangle {
            // Relative indices: -1 is the last vertex (or normal) written.
            let v = vertices as i64 - i as i64;
            let n = normals as i64 - layout.normals_through[i as usize] as i64 + 1;
            self.out.extend_from_slice(b" -");
            self.out.extend_from_slice(self.int.format(v).as_bytes());
            self.out.extend_from_slice(b"/-");
            self.out.extend_from_slice(self.int.format(v).as_bytes());
            self.out.extend_from_slice(b"/-");
            self.out.extend_from_slice(self.int.format(n).as_bytes());
        }
        self.out.push(b'\n');
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
    let (blocks, mtl) = to_obj_blocks(mesh, name, &mtl_name, materials);
    write_atomically(&mtl_path, mtl.as_bytes())?;
    write_atomically_with(path, |w| blocks.iter().try_for_each(|b| w.write_all(b)))
}
