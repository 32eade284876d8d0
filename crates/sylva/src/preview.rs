//! A small CPU rasteriser for quick pictures of a [`TreeMesh`]: orthographic, z-buffered,
//! Lambert-shaded, supersampled. It needs no GPU, so every machine (and every test) can look at
//! a tree; the full renderer with shadows and sky lives in its own crate.

use crate::mesh::{Mesh, TreeMesh};
use glam::{Vec2, Vec3};

/// Which way the camera looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// Looking along +Y (north), X to the right, Z up.
    Front,
    /// Looking along -X, Y to the right, Z up.
    Side,
    /// Looking down, X to the right, Y up the picture.
    Top,
}

/// Picture settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreviewOptions {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Camera direction.
    pub view: View,
    /// Bark colour (sRGB 0..1).
    pub bark: [f32; 3],
    /// Leaf colour (sRGB 0..1).
    pub leaves: [f32; 3],
}

impl Default for PreviewOptions {
    fn default() -> Self {
        Self {
            width: 640,
            height: 800,
            view: View::Front,
            bark: [0.42, 0.33, 0.26],
            leaves: [0.30, 0.52, 0.20],
        }
    }
}

/// An RGB picture, row-major from the top-left.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// 3 bytes per pixel.
    pub rgb: Vec<u8>,
}

/// Supersampling factor per axis.
const SS: u32 = 2;
const SKY: [f32; 3] = [0.93, 0.95, 0.97];
const GROUND: [f32; 3] = [0.78, 0.75, 0.68];

/// Draws the tree on a light background with the ground line at its base; the whole tree fits.
pub fn render_preview(mesh: &TreeMesh, options: &PreviewOptions) -> Picture {
    let (w, h) = (options.width.max(8) * SS, options.height.max(8) * SS);
    let project = |p: [f32; 3]| -> Vec3 {
        let p = Vec3::from(p);
        // (screen x, screen y up, depth towards the camera)
        match options.view {
            View::Front => Vec3::new(p.x, p.z, -p.y),
            View::Side => Vec3::new(p.y, p.z, p.x),
            View::Top => Vec3::new(p.x, p.y, p.z),
        }
    };
    let (mut lo, mut hi) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
    for p in mesh.bark.positions.iter().chain(&mesh.leaves.positions) {
        let s = project(*p).truncate();
        lo = lo.min(s);
        hi = hi.max(s);
    }
    if lo.x > hi.x {
        lo = Vec2::ZERO;
        hi = Vec2::ONE;
    }
    let size = (hi - lo).max(Vec2::splat(1e-3));
    let scale = ((w as f32 * 0.9) / size.x).min(h as f32 * 0.9 / size.y);
    let centre = (lo + hi) / 2.0;
    let to_pixel = |s: Vec3| {
        Vec3::new(
            w as f32 / 2.0 + (s.x - centre.x) * scale,
            h as f32 / 2.0 - (s.y - centre.y) * scale,
            s.z,
        )
    };
    let mut colour = vec![SKY; (w * h) as usize];
    let mut depth = vec![f32::NEG_INFINITY; (w * h) as usize];
    if options.view != View::Top {
        let ground = to_pixel(Vec3::new(0.0, lo.y.min(0.0), 0.0)).y.max(0.0) as u32;
        for y in ground.min(h)..h {
            colour[(y * w) as usize..((y + 1) * w) as usize].fill(GROUND);
        }
    }
    let light = match options.view {
        View::Top => Vec3::new(-0.3, 0.4, 0.86),
        _ => Vec3::new(-0.45, 0.75, 0.5),
    }
    .normalize();
    let mut draw = |part: &Mesh, base: [f32; 3], two_sided: bool| {
        for t in part.indices.chunks_exact(3) {
            let v = [t[0], t[1], t[2]].map(|i| to_pixel(project(part.positions[i as usize])));
            let n = [t[0], t[1], t[2]].map(|i| project(part.normals[i as usize]));
            raster(&v, w, h, |x, y, b| {
                let k = (y * w + x) as usize;
                let z = v[0].z * b.x + v[1].z * b.y + v[2].z * b.z;
                if z <= depth[k] {
                    return;
                }
                depth[k] = z;
                let normal = (n[0] * b.x + n[1] * b.y + n[2] * b.z).normalize_or(Vec3::Z);
                let d = normal.dot(light);
                let lambert = if two_sided { d.abs() * 0.8 } else { d.max(0.0) };
                let shade = 0.35 + 0.75 * lambert;
                colour[k] = base.map(|c| (c * shade).min(1.0));
            });
        }
    };
    draw(&mesh.bark, options.bark, false);
    draw(&mesh.leaves, options.leaves, true);
    // Average SS x SS blocks.
    let (ow, oh) = (w / SS, h / SS);
    let mut rgb = Vec::with_capacity((ow * oh * 3) as usize);
    for y in 0..oh {
        for x in 0..ow {
            let mut sum = [0.0f32; 3];
            for sy in 0..SS {
                for sx in 0..SS {
                    let c = colour[((y * SS + sy) * w + x * SS + sx) as usize];
                    (0..3).for_each(|i| sum[i] += c[i]);
                }
            }
            rgb.extend(sum.map(|s| (s / (SS * SS) as f32 * 255.0).round() as u8));
        }
    }
    Picture {
        width: ow,
        height: oh,
        rgb,
    }
}

/// Calls `plot(x, y, barycentric)` for every pixel centre inside the triangle.
pub(crate) fn raster(v: &[Vec3; 3], w: u32, h: u32, mut plot: impl FnMut(u32, u32, Vec3)) {
    let area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let min_x = v
        .iter()
        .map(|p| p.x)
        .fold(f32::MAX, f32::min)
        .floor()
        .max(0.0) as u32;
    let max_x = v
        .iter()
        .map(|p| p.x)
        .fold(f32::MIN, f32::max)
        .ceil()
        .min(w as f32 - 1.0);
    let min_y = v
        .iter()
        .map(|p| p.y)
        .fold(f32::MAX, f32::min)
        .floor()
        .max(0.0) as u32;
    let max_y = v
        .iter()
        .map(|p| p.y)
        .fold(f32::MIN, f32::max)
        .ceil()
        .min(h as f32 - 1.0);
    if max_x < 0.0 || max_y < 0.0 {
        return;
    }
    let edge = |a: Vec3, b: Vec3, x: f32, y: f32| (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
    for y in min_y..=max_y as u32 {
        for x in min_x..=max_x as u32 {
            let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
            let b = Vec3::new(
                edge(v[1], v[2], px, py),
                edge(v[2], v[0], px, py),
                edge(v[0], v[1], px, py),
            ) / area;
            if b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0 {
                plot(x, y, b);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_fills_the_middle_and_leaves_corners_empty() {
        let mesh = TreeMesh {
            bark: Mesh {
                positions: vec![
                    [-1.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 0.0, 2.0],
                    [-1.0, 0.0, 2.0],
                ],
                normals: vec![[0.0, -1.0, 0.0]; 4],
                uvs: vec![[0.0, 0.0]; 4],
                indices: vec![0, 1, 2, 0, 2, 3],
                shades: vec![],
                radii: vec![],
            },
            leaves: Mesh::default(),
            flowers: Mesh::default(),
            twigs: Default::default(),
        };
        let pic = render_preview(
            &mesh,
            &PreviewOptions {
                width: 100,
                height: 100,
                ..Default::default()
            },
        );
        let px = |x: u32, y: u32| &pic.rgb[((y * pic.width + x) * 3) as usize..][..3];
        assert_ne!(px(50, 50), px(2, 2), "centre is drawn");
        assert_eq!(px(2, 2), px(97, 2), "corners keep the sky");
    }
}
