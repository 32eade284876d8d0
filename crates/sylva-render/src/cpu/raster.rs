//! Rasterising triangles, lines and points into a grid of samples, as a GPU does.
//!
//! Triangles are rasterised in homogeneous coordinates (Olano and Greer 1997): with the clip
//! positions of the corners as the columns of M = [x; y; w], the vector e = M⁻¹ (X, Y, 1) at a
//! point (X, Y) of normalised device coordinates is the point's barycentric weights divided by
//! its w. All three are non-negative exactly where the triangle covers the point in front of the
//! eye, and depth z/w = Σ eᵢ zᵢ is linear on the screen: no clipping is needed, even for the
//! ground running under the camera.

use glam::{Mat3, Vec2, Vec3, Vec4, Vec4Swizzles};

/// Where a pixel's 4 samples lie (the standard pattern of Vulkan, D3D and Metal).
pub(crate) const SAMPLE_POSITIONS: [Vec2; 4] = [
    Vec2::new(0.375, 0.125),
    Vec2::new(0.875, 0.375),
    Vec2::new(0.125, 0.625),
    Vec2::new(0.625, 0.875),
];

/// A triangle set up for rasterising: its edge functions over normalised device coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Setup {
    /// Rows: eᵢ = row · (X, Y, 1).
    inverse: Mat3,
    /// Clip z of the corners.
    z: Vec3,
    /// Where all corners lie in front of the eye, depth as a plane over the screen through
    /// the first corner: (X₀, Y₀, z₀/w₀, ∂z/∂X, ∂z/∂Y). Far more precise than Σ eᵢ zᵢ for the
    /// small, distant triangles of leaves, whose M is nearly singular.
    plane: Option<[f32; 5]>,
    /// Whether the triangle turns anticlockwise on the screen (faces the eye).
    pub front: bool,
}

impl Setup {
    /// Sets up the triangle with clip-space corners `c`; `None` when it is edge-on, degenerate
    /// or wholly behind the eye.
    pub fn new(c: [Vec4; 3]) -> Option<Self> {
        if c.iter().all(|v| v.w <= 0.0) || !c.iter().all(|v| v.is_finite()) {
            return None;
        }
        let m = Mat3::from_cols(c[0].xyw(), c[1].xyw(), c[2].xyw());
        let det = m.determinant();
        if det.abs() < 1e-20 || !det.is_finite() {
            return None;
        }
        Some(Self {
            inverse: m.inverse().transpose(),
            z: Vec3::new(c[0].z, c[1].z, c[2].z),
            plane: screen_plane(c),
            front: det > 0.0,
        })
    }

    /// e at a point of normalised device coordinates.
    #[inline]
    pub fn weights(&self, ndc: Vec2) -> Vec3 {
        let q = ndc.extend(1.0);
        Vec3::new(
            self.inverse.x_axis.dot(q),
            self.inverse.y_axis.dot(q),
            self.inverse.z_axis.dot(q),
        )
    }

    /// Perspective-correct barycentric weights at a point, if it lies in front of the eye.
    pub fn barycentric(&self, ndc: Vec2) -> Option<Vec3> {
        let e = self.weights(ndc);
        let sum = e.x + e.y + e.z;
        (sum > 1e-30).then(|| e / sum)
    }

    /// Depth (z/w) at `ndc`, where the weights are `e`.
    #[inline]
    pub fn depth(&self, ndc: Vec2, e: Vec3) -> f32 {
        match self.plane {
            Some([x0, y0, z0, a, b]) => z0 + a * (ndc.x - x0) + b * (ndc.y - y0),
            None => e.dot(self.z),
        }
    }

    /// Depth's change per unit of X and Y (the plane's slope), for the shadow's slope bias.
    pub fn depth_slope(&self) -> Vec2 {
        if let Some([_, _, _, a, b]) = self.plane {
            return Vec2::new(a, b);
        }
        let dx = Vec3::new(
            self.inverse.x_axis.x,
            self.inverse.y_axis.x,
            self.inverse.z_axis.x,
        );
        let dy = Vec3::new(
            self.inverse.x_axis.y,
            self.inverse.y_axis.y,
            self.inverse.z_axis.y,
        );
        Vec2::new(dx.dot(self.z), dy.dot(self.z))
    }
}

/// The depth plane of a triangle whose corners all lie in front of the eye.
fn screen_plane(c: [Vec4; 3]) -> Option<[f32; 5]> {
    if c.iter().any(|v| v.w <= 0.0) {
        return None;
    }
    let p = c.map(|v| v.truncate() / v.w);
    let (d1, d2) = (p[1] - p[0], p[2] - p[0]);
    let det = d1.x * d2.y - d2.x * d1.y;
    if det.abs() < 1e-30 {
        return None;
    }
    let a = (d1.z * d2.y - d2.z * d1.y) / det;
    let b = (d2.z * d1.x - d1.z * d2.x) / det;
    (a.is_finite() && b.is_finite()).then_some([p[0].x, p[0].y, p[0].z, a, b])
}

/// A grid of `width` x `height` pixels of `samples` samples each, mapped to normalised device
/// coordinates as WebGPU maps its viewport (y down the picture).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Grid {
    pub width: u32,
    pub height: u32,
    pub samples: usize,
}

impl Grid {
    /// Normalised device coordinates of a point in pixels.
    #[inline]
    pub fn ndc(&self, p: Vec2) -> Vec2 {
        Vec2::new(
            p.x / self.width as f32 * 2.0 - 1.0,
            1.0 - p.y / self.height as f32 * 2.0,
        )
    }

    /// Pixel coordinates of a point of normalised device coordinates.
    #[inline]
    pub fn pixel(&self, ndc: Vec2) -> Vec2 {
        Vec2::new(
            (ndc.x + 1.0) / 2.0 * self.width as f32,
            (1.0 - ndc.y) / 2.0 * self.height as f32,
        )
    }

    fn offsets(&self) -> &'static [Vec2] {
        const CENTRE: [Vec2; 1] = [Vec2::new(0.5, 0.5)];
        if self.samples == 4 {
            &SAMPLE_POSITIONS
        } else {
            &CENTRE
        }
    }

    /// The pixels a triangle can touch: its corners' bounding box where all lie in front of
    /// the eye, else the box of the part in front (clipped at a small w).
    fn bounds(&self, c: &[Vec4; 3]) -> Option<(u32, u32, u32, u32)> {
        const NEAR_W: f32 = 1e-5;
        let mut lo = Vec2::splat(f32::MAX);
        let mut hi = Vec2::splat(f32::MIN);
        let mut add = |v: Vec4| {
            let p = self.pixel(v.xy() / v.w);
            lo = lo.min(p);
            hi = hi.max(p);
        };
        for i in 0..3 {
            let (a, b) = (c[i], c[(i + 1) % 3]);
            if a.w > NEAR_W {
                add(a);
            }
            if (a.w > NEAR_W) != (b.w > NEAR_W) {
                let t = (NEAR_W - a.w) / (b.w - a.w);
                add(a + (b - a) * t);
            }
        }
        if lo.x > hi.x || !lo.is_finite() || !hi.is_finite() {
            // Corners at infinity: the whole picture.
            if lo.x > hi.x {
                return None;
            }
            lo = lo.max(Vec2::ZERO);
            hi = hi.min(Vec2::new(self.width as f32, self.height as f32));
        }
        let x0 = lo.x.floor().max(0.0);
        let y0 = lo.y.floor().max(0.0);
        let x1 = hi.x.floor().min(self.width as f32 - 1.0);
        let y1 = hi.y.floor().min(self.height as f32 - 1.0);
        (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
    }

    /// Calls `hit(sample index, depth, weights)` for every sample the triangle covers in
    /// front of the eye and between the near and far planes.
    pub fn triangle(
        &self,
        setup: &Setup,
        corners: &[Vec4; 3],
        mut hit: impl FnMut(usize, f32, Vec3),
    ) {
        let Some((x0, y0, x1, y1)) = self.bounds(corners) else {
            return;
        };
        let offsets = self.offsets();
        let dx = Vec2::new(2.0 / self.width as f32, 0.0);
        for y in y0..=y1 {
            for (s, o) in offsets.iter().enumerate() {
                let start = self.ndc(Vec2::new(x0 as f32, y as f32) + *o);
                let mut e = setup.weights(start);
                let step = setup.weights(start + dx) - e;
                for x in x0..=x1 {
                    if e.x >= 0.0 && e.y >= 0.0 && e.z >= 0.0 {
                        let ndc = start + dx * (x - x0) as f32;
                        let z = setup.depth(ndc, e);
                        if (0.0..=1.0).contains(&z) && e.x + e.y + e.z > 0.0 {
                            let i = ((y * self.width + x) as usize) * self.samples + s;
                            hit(i, z, e);
                        }
                    }
                    e += step;
                }
            }
        }
    }

    /// Calls `hit(pixel x, y, depth, t, samples)` for each pixel a one-pixel-wide line from
    /// `a` to `b` (clip space) covers: a rectangle one pixel wide about the segment, as GPUs
    /// draw lines with multisampling. `t` is where along the line the pixel's centre lies (0 at
    /// `a`, in clip space), `samples` a bit per covered sample. Ends behind the eye are cut at
    /// the near plane.
    pub fn line(&self, a: Vec4, b: Vec4, mut hit: impl FnMut(u32, u32, f32, f32, u32)) {
        let Some((a, b, t0, t1)) = clip_line(a, b) else {
            return;
        };
        let (pa, pb) = (self.pixel(a.xy() / a.w), self.pixel(b.xy() / b.w));
        let (za, zb) = (a.z / a.w, b.z / b.w);
        let d = pb - pa;
        let length2 = d.length_squared();
        if !(1e-12..=1e10).contains(&length2) {
            return;
        }
        let across = Vec2::new(-d.y, d.x) / length2.sqrt();
        // Screen fraction s to clip fraction: z/w is linear on the screen, the rest is not.
        let to_clip = |s: f32| {
            let (ia, ib) = ((1.0 - s) / a.w, s / b.w);
            t0 + (t1 - t0) * ib / (ia + ib)
        };
        let lo = (pa.min(pb) - 1.0).max(Vec2::ZERO);
        let hi =
            (pa.max(pb) + 1.0).min(Vec2::new(self.width as f32 - 1.0, self.height as f32 - 1.0));
        let offsets = self.offsets();
        for y in lo.y as u32..=hi.y.max(0.0) as u32 {
            for x in lo.x as u32..=hi.x.max(0.0) as u32 {
                let pixel = Vec2::new(x as f32, y as f32);
                let mut samples = 0u32;
                for (k, o) in offsets.iter().enumerate() {
                    let q = pixel + *o - pa;
                    let s = q.dot(d) / length2;
                    if (0.0..1.0).contains(&s) && q.dot(across).abs() <= 0.5 {
                        samples |= 1 << k;
                    }
                }
                if samples == 0 {
                    continue;
                }
                let s = ((pixel + 0.5 - pa).dot(d) / length2).clamp(0.0, 1.0);
                let z = za + (zb - za) * s;
                if (0.0..=1.0).contains(&z) {
                    hit(x, y, z, to_clip(s), samples);
                }
            }
        }
    }

    /// Calls `hit(pixel x, y, depth, samples)` for each pixel a point (clip space) covers: a
    /// one-pixel square about it, over up to four pixels.
    pub fn point(&self, c: Vec4, mut hit: impl FnMut(u32, u32, f32, u32)) {
        if c.w <= 0.0 {
            return;
        }
        let p = self.pixel(c.xy() / c.w);
        let z = c.z / c.w;
        if !p.is_finite() || !(0.0..=1.0).contains(&z) {
            return;
        }
        let offsets = self.offsets();
        let (x0, y0) = ((p.x - 0.5).floor(), (p.y - 0.5).floor());
        for y in [y0, y0 + 1.0] {
            for x in [x0, x0 + 1.0] {
                if x < 0.0 || y < 0.0 || x >= self.width as f32 || y >= self.height as f32 {
                    continue;
                }
                let mut samples = 0u32;
                for (k, o) in offsets.iter().enumerate() {
                    let q = Vec2::new(x, y) + *o - p;
                    if q.x.abs() <= 0.5 && q.y.abs() <= 0.5 {
                        samples |= 1 << k;
                    }
                }
                if samples != 0 {
                    hit(x as u32, y as u32, z, samples);
                }
            }
        }
    }
}

/// Cuts a clip-space line to the part in front of the near plane (z >= 0, WebGPU's depth
/// range), returning the new ends and where they lie along the original.
fn clip_line(a: Vec4, b: Vec4) -> Option<(Vec4, Vec4, f32, f32)> {
    let (da, db) = (a.z, b.z);
    if da < 0.0 && db < 0.0 {
        return None;
    }
    if da >= 0.0 && db >= 0.0 {
        return Some((a, b, 0.0, 1.0));
    }
    let t = da / (da - db);
    let cut = a + (b - a) * t;
    if da < 0.0 {
        Some((cut, b, t, 1.0))
    } else {
        Some((a, cut, 0.0, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(width: u32, height: u32) -> Grid {
        Grid {
            width,
            height,
            samples: 4,
        }
    }

    #[test]
    fn a_triangle_covers_its_area_in_samples() {
        // Lower-left half of the picture (NDC), at w = 2 to exercise the division.
        let g = grid(64, 64);
        let c = [
            Vec4::new(-2.0, -2.0, 1.0, 2.0),
            Vec4::new(2.0, -2.0, 1.0, 2.0),
            Vec4::new(-2.0, 2.0, 1.0, 2.0),
        ];
        let s = Setup::new(c).unwrap();
        assert!(s.front, "anticlockwise with y up faces the eye");
        let mut n = 0i32;
        g.triangle(&s, &c, |_, z, _| {
            assert!((z - 0.5).abs() < 1e-5);
            n += 1;
        });
        let half = 64 * 64 * 4 / 2;
        assert!((n - half).abs() <= 64 * 2, "{n} samples of {half}");
    }

    #[test]
    fn barycentrics_are_perspective_correct() {
        // A triangle receding in depth: the midpoint of an edge in world space is not the
        // midpoint on the screen, but its weights must be 1/2, 1/2.
        let near = Vec4::new(-1.0, 0.0, 0.5, 1.0);
        let far = Vec4::new(3.0, 0.0, 2.5, 5.0);
        let third = Vec4::new(0.0, 1.0, 0.5, 1.0);
        let s = Setup::new([near, far, third]).unwrap();
        let mid = (near + far) / 2.0;
        let b = s.barycentric(mid.xy() / mid.w).unwrap();
        assert!((b - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-4, "{b}");
    }

    #[test]
    fn a_triangle_through_the_eye_plane_draws_only_its_front() {
        // The ground under the camera: one corner behind the eye.
        let g = grid(32, 32);
        let c = [
            Vec4::new(0.0, -1.0, 0.5, 1.0),
            Vec4::new(1.0, -1.0, 0.5, 1.0),
            Vec4::new(0.0, -1.0, -0.5, -1.0),
        ];
        let s = Setup::new(c).unwrap();
        g.triangle(&s, &c, |_, z, e| {
            assert!((0.0..=1.0).contains(&z));
            assert!(e.x + e.y + e.z > 0.0);
        });
    }

    #[test]
    fn a_line_covers_one_pixel_of_width_along_its_length() {
        // 9 pixels long, across the middle of a 10 x 10 picture, slanted.
        let g = grid(10, 10);
        let mut covered = 0;
        g.line(
            Vec4::new(-0.9, -0.3, 0.5, 1.0),
            Vec4::new(0.9, 0.3, 0.5, 1.0),
            |_, _, z, t, samples| {
                assert!((z - 0.5).abs() < 1e-6 && (0.0..=1.0).contains(&t));
                covered += samples.count_ones();
            },
        );
        // Area: length x 1 pixel, in samples of a quarter pixel each.
        let length = (9.0f32 * 9.0 + 3.0 * 3.0).sqrt();
        let expected = length * 4.0;
        assert!(
            (covered as f32 - expected).abs() < 6.0,
            "{covered} vs {expected}"
        );
    }

    #[test]
    fn a_point_covers_one_pixel_of_samples() {
        let g = grid(8, 8);
        for p in [
            Vec2::new(0.1, 0.2),
            Vec2::new(-0.37, 0.55),
            Vec2::new(0.0, 0.0),
        ] {
            let mut covered = 0;
            g.point(p.extend(0.5).extend(1.0), |_, _, _, samples| {
                covered += samples.count_ones()
            });
            assert_eq!(covered, 4, "{p}");
        }
    }
}
