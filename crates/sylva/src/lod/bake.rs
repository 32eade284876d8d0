//! Impostors baked on the CPU: the views of an [`ImpostorFrame`] drawn by the library's own
//! rasteriser (`preview`), so that a machine without a GPU (a city's run on a cluster, CI)
//! bakes the same picture. `sylva-render` bakes richer ones (shadows, sky) where a GPU is.
//!
//! Each view is orthographic along its direction, z-buffered and supersampled; its light is
//! baked in (the impostor's material is unlit): a sky's share from every side and the sun's
//! from the south-west, high, as the city view lights its meshes.

use super::impostor::{Impostor, ImpostorFrame};
use crate::colour::linear_to_srgb;
use crate::export::Materials;
use crate::mesh::{Mesh, TreeMesh};
use glam::Vec3;

/// Samples per pixel along each axis.
const SS: u32 = 2;
/// The sky's share of a surface's light and the sun's (Sylva's choice, not calibrated: in the
/// city view's screenshots the baked crowns come out a little darker than the Lambert-lit
/// meshes they stand in for).
const SKY: f32 = 0.55;
const SUN: f32 = 0.6;

/// The eight views of `mesh` (Z up, trunk at the origin) in an atlas whose cells are
/// `cell_height` pixels tall, coloured by `materials` (linear RGB) times each vertex's shade.
/// Pixels the tree does not cover are transparent; their colour is the view's mean, so that a
/// filtered texture fringes in the crown's colour, not black.
pub fn bake_on_cpu(mesh: &TreeMesh, materials: &Materials, cell_height: u32) -> Impostor {
    let frame = ImpostorFrame::around(mesh);
    let (cw, ch) = frame.cell_size(cell_height.max(8));
    let (columns, rows) = (frame.columns.max(1), frame.rows().max(1));
    let (aw, ah) = (cw * columns, ch * rows);
    let mut atlas = vec![[0u8; 4]; (aw * ah) as usize];
    let sun = Vec3::new(-0.45, -0.55, 0.7).normalize();
    for k in 0..frame.views {
        let cell = view(mesh, materials, &frame, k, (cw, ch), sun);
        let (x0, y0) = ((k % columns) * cw, (k / columns) * ch);
        for y in 0..ch {
            for x in 0..cw {
                atlas[((y0 + y) * aw + x0 + x) as usize] = cell[(y * cw + x) as usize];
            }
        }
    }
    Impostor {
        png: png_of(&atlas, aw, ah),
        frame,
    }
}

/// One view, `size` pixels, as straight-alpha sRGB bytes.
fn view(
    mesh: &TreeMesh,
    materials: &Materials,
    frame: &ImpostorFrame,
    k: u32,
    size: (u32, u32),
    sun: Vec3,
) -> Vec<[u8; 4]> {
    let (w, h) = (size.0 * SS, size.1 * SS);
    let back = frame.direction(k);
    let right = Vec3::Z.cross(back).normalize();
    let height = (frame.top - frame.bottom).max(1e-3);
    // Screen x from the left edge of the quad, y down from its top, depth towards the eye.
    let to_pixel = |p: Vec3| {
        Vec3::new(
            (p.dot(right) / frame.half_width + 1.0) * 0.5 * w as f32,
            (frame.top - p.z) / height * h as f32,
            p.dot(back),
        )
    };
    let mut colour = vec![[0.0f32; 3]; (w * h) as usize];
    let mut depth = vec![f32::NEG_INFINITY; (w * h) as usize];
    let mut draw = |part: &Mesh, base: [f32; 4], two_sided: bool| {
        for t in part.indices.chunks_exact(3) {
            let at = |i: u32| Vec3::from(part.positions[i as usize]);
            let v = [t[0], t[1], t[2]].map(|i| to_pixel(at(i)));
            let n = [t[0], t[1], t[2]].map(|i| Vec3::from(part.normals[i as usize]));
            let s = [t[0], t[1], t[2]].map(|i| part.shades.get(i as usize).copied().unwrap_or(1.0));
            crate::preview::raster(&v, w, h, |x, y, b| {
                let i = (y * w + x) as usize;
                let z = v[0].z * b.x + v[1].z * b.y + v[2].z * b.z;
                if z <= depth[i] {
                    return;
                }
                depth[i] = z;
                let mut normal = (n[0] * b.x + n[1] * b.y + n[2] * b.z).normalize_or(back);
                if two_sided && normal.dot(back) < 0.0 {
                    normal = -normal;
                }
                let shade = s[0] * b.x + s[1] * b.y + s[2] * b.z;
                let light = SKY * (0.5 + 0.5 * normal.z) + SUN * normal.dot(sun).max(0.0);
                colour[i] = [0, 1, 2].map(|c| base[c] * shade * light);
            });
        }
    };
    draw(&mesh.bark, materials.bark, false);
    draw(&mesh.leaves, materials.leaves, true);
    draw(&mesh.flowers, materials.flowers, true);
    // Each pixel: the share of its samples covered, and their mean colour.
    let (ow, oh) = size;
    let mut out = vec![[0u8; 4]; (ow * oh) as usize];
    let mut mean = ([0.0f32; 3], 0usize);
    let mut covered = vec![None; out.len()];
    for y in 0..oh {
        for x in 0..ow {
            let (mut sum, mut n) = ([0.0f32; 3], 0u32);
            for sy in 0..SS {
                for sx in 0..SS {
                    let i = ((y * SS + sy) * w + x * SS + sx) as usize;
                    if depth[i] > f32::NEG_INFINITY {
                        (0..3).for_each(|c| sum[c] += colour[i][c]);
                        n += 1;
                    }
                }
            }
            if n > 0 {
                let c = sum.map(|s| s / n as f32);
                (0..3).for_each(|j| mean.0[j] += c[j]);
                mean.1 += 1;
                covered[(y * ow + x) as usize] = Some((c, n as f32 / (SS * SS) as f32));
            }
        }
    }
    let fringe = mean.0.map(|s| s / mean.1.max(1) as f32);
    for (px, c) in out.iter_mut().zip(&covered) {
        let (rgb, alpha) = c.unwrap_or((fringe, 0.0));
        let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        *px = [
            byte(linear_to_srgb(rgb[0])),
            byte(linear_to_srgb(rgb[1])),
            byte(linear_to_srgb(rgb[2])),
            byte(alpha),
        ];
    }
    out
}

/// Straight-alpha RGBA pixels as a PNG file (tiny-skia holds premultiplied pixels and
/// writes straight ones).
fn png_of(pixels: &[[u8; 4]], w: u32, h: u32) -> Vec<u8> {
    let mut map = tiny_skia::Pixmap::new(w.max(1), h.max(1)).expect("an atlas of a few cells");
    for (out, p) in map.pixels_mut().iter_mut().zip(pixels) {
        let a = p[3] as u16;
        let pre = |c: u8| ((c as u16 * a + 127) / 255) as u8;
        *out = tiny_skia::PremultipliedColorU8::from_rgba(pre(p[0]), pre(p[1]), pre(p[2]), p[3])
            .expect("premultiplied channels are at most alpha");
    }
    map.encode_png()
        .expect("encoding an in-memory picture cannot fail")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{MeshOptions, mesh_tree};
    use crate::{GenerateOptions, generate, species::builtin};

    /// A quaking aspen as the library generates it, meshed.
    fn aspen() -> TreeMesh {
        let p = builtin("quaking_aspen").unwrap();
        let sk = generate(
            &p,
            &GenerateOptions {
                seed: 3,
                quality: 0.5,
                ..Default::default()
            },
        )
        .unwrap();
        mesh_tree(
            &sk,
            &MeshOptions {
                quality: 0.5,
                ..Default::default()
            },
        )
    }

    #[test]
    fn each_view_covers_the_trees_own_outline_in_its_colours() {
        let mesh = aspen();
        let materials = Materials::default();
        let baked = bake_on_cpu(&mesh, &materials, 64);
        let f = baked.frame;
        let atlas = tiny_skia::Pixmap::decode_png(&baked.png).unwrap();
        let (cw, ch) = f.cell_size(64);
        assert_eq!(
            (atlas.width(), atlas.height()),
            (cw * f.columns, ch * f.rows())
        );
        let height = f.top - f.bottom;
        let mut cells = Vec::new();
        for k in 0..f.views {
            let (x0, y0) = ((k % f.columns) * cw, (k / f.columns) * ch);
            let alpha = |x: u32, y: u32| atlas.pixel(x0 + x, y0 + y).unwrap().alpha();
            let opaque: Vec<(u32, u32)> = (0..ch)
                .flat_map(|y| (0..cw).map(move |x| (x, y)))
                .filter(|&(x, y)| alpha(x, y) >= 128)
                .collect();
            let share = opaque.len() as f32 / (cw * ch) as f32;
            assert!(
                share > 0.1 && share < 0.9,
                "view {k}: {share} of the cell opaque"
            );
            // The outline: the mesh's own extent across and up this view, in pixels.
            let right = Vec3::Z.cross(f.direction(k)).normalize();
            let (mut lo, mut hi, mut top) = (f32::MAX, f32::MIN, f32::MIN);
            for p in mesh.bark.positions.iter().chain(&mesh.leaves.positions) {
                let p = Vec3::from(*p);
                lo = lo.min(p.dot(right));
                hi = hi.max(p.dot(right));
                top = top.max(p.z);
            }
            let column = |x: f32| (x / f.half_width + 1.0) * 0.5 * cw as f32;
            let row = |z: f32| (f.top - z) / height * ch as f32;
            let (left, right_edge) = opaque
                .iter()
                .fold((u32::MAX, 0), |(a, b), p| (a.min(p.0), b.max(p.0)));
            let (first_row, last_row) = opaque
                .iter()
                .fold((u32::MAX, 0), |(a, b), p| (a.min(p.1), b.max(p.1)));
            assert!(
                (left as f32 - column(lo)).abs() <= 2.0,
                "view {k}: left {left} vs {}",
                column(lo)
            );
            assert!(
                (right_edge as f32 + 1.0 - column(hi)).abs() <= 2.0,
                "view {k}: right {right_edge} vs {}",
                column(hi)
            );
            assert!(
                (first_row as f32 - row(top)).abs() <= 2.0,
                "view {k}: top row {first_row}"
            );
            // The trunk reaches the ground: the lowest opaque row is the cell's last.
            assert!(
                last_row >= ch - 2,
                "view {k}: lowest row {last_row} of {ch}"
            );
            // Leaves' green over the crown: green the largest channel on average.
            let sum = opaque.iter().fold([0u32; 3], |s, &(x, y)| {
                let p = atlas.pixel(x0 + x, y0 + y).unwrap().demultiply();
                [
                    s[0] + p.red() as u32,
                    s[1] + p.green() as u32,
                    s[2] + p.blue() as u32,
                ]
            });
            assert!(
                sum[1] > sum[0] && sum[1] > sum[2],
                "view {k}: mean colour {sum:?}"
            );
            cells.push(opaque);
        }
        // The views are the tree seen from different sides, not one picture eight times.
        assert_ne!(cells[0], cells[2]);
        // Where nothing is, nothing shows.
        assert!(atlas.pixels().iter().any(|p| p.alpha() == 0));
    }
}
