//! The lighting of `shader.wgsl`, in Rust: sun with a filtered shadow map, sky and ground
//! bounce, two-sided translucent leaves, the ground's metre grid, and the share of a pixel a
//! far stem or leaf covers. Kept line for line with the shader, so both backends agree.

use crate::frame::{Globals, KIND_GROUND, Material};
use glam::{Mat4, Vec2, Vec3, Vec4};

/// Taps of the shadow filter, as the shader's `TAPS`: a golden-angle spiral filling the unit
/// disc evenly, for the ground and bark.
const TAPS: [Vec2; 12] = [
    Vec2::new(0.2041, 0.0000),
    Vec2::new(-0.2607, 0.2388),
    Vec2::new(0.0399, -0.4547),
    Vec2::new(0.3286, 0.4286),
    Vec2::new(-0.6030, -0.1067),
    Vec2::new(0.5712, -0.3634),
    Vec2::new(-0.1911, 0.7107),
    Vec2::new(-0.3644, -0.7016),
    Vec2::new(0.7906, 0.2887),
    Vec2::new(-0.8224, 0.3395),
    Vec2::new(0.3965, -0.8472),
    Vec2::new(0.2930, 0.9341),
];

/// The shader's `LEAF_TAPS`: a turned square, for leaves, whose fragments are most of a
/// forest's and whose shadows are broken up by the leaves around them anyway.
const LEAF_TAPS: [Vec2; 4] = [
    Vec2::new(0.6374, 0.2640),
    Vec2::new(-0.2640, 0.6374),
    Vec2::new(-0.6374, -0.2640),
    Vec2::new(0.2640, -0.6374),
];

/// The shadow map: depth from the sun, `size` x `size` texels.
pub(crate) struct ShadowMap {
    pub size: u32,
    pub depth: Vec<f32>,
}

impl ShadowMap {
    /// A comparison sample with bilinear filtering and clamping at the edges, as a
    /// `sampler_comparison` with linear filters gives: the lit share of the 4 nearest texels.
    fn compare(&self, uv: Vec2, reference: f32) -> f32 {
        let n = self.size as i32;
        let p = uv * self.size as f32 - 0.5;
        let (x0, y0) = (p.x.floor(), p.y.floor());
        let (fx, fy) = (p.x - x0, p.y - y0);
        let texel = |x: i32, y: i32| {
            let (x, y) = (x.clamp(0, n - 1), y.clamp(0, n - 1));
            f32::from(reference <= self.depth[(y * n + x) as usize])
        };
        let (x0, y0) = (x0 as i32, y0 as i32);
        let top = texel(x0, y0) * (1.0 - fx) + texel(x0 + 1, y0) * fx;
        let bottom = texel(x0, y0 + 1) * (1.0 - fx) + texel(x0 + 1, y0 + 1) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// Fraction of sunlight reaching a point at `light_clip`, filtered over a disc three texels
    /// wide each way through `taps`.
    pub fn sunlit(&self, g: &Globals, light_clip: Vec4, taps: &[Vec2]) -> f32 {
        let p = light_clip.truncate() / light_clip.w;
        let uv = Vec2::new(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
        if uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0 || p.z > 1.0 {
            return 1.0;
        }
        let sum: f32 = taps
            .iter()
            .map(|t| self.compare(uv + *t * (3.0 * g.shadow[0]), p.z - g.shadow[1]))
            .sum();
        sum / taps.len() as f32
    }
}

fn v3(a: [f32; 4]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

fn mix(a: Vec3, b: Vec3, t: f32) -> Vec3 {
    a + (b - a) * t
}

/// The frame's lighting, ready for shading.
pub(crate) struct Light<'a> {
    pub globals: &'a Globals,
    pub light_view_proj: Mat4,
    pub shadow: &'a ShadowMap,
}

/// What a triangle's fragment knows at the pixel.
pub(crate) struct Fragment {
    pub world: Vec3,
    pub normal: Vec3,
    pub shade: f32,
    pub front: bool,
    /// fwidth(world.xy): how far the ground moves across one pixel.
    pub fwidth: Vec2,
}

/// Anti-aliased grid lines every metre, stronger every 5 m.
fn grid(world: Vec2, w1: Vec2) -> f32 {
    let line = |p: Vec2, w: Vec2| {
        let d = ((p + 0.5).fract_gl() - 0.5).abs() / w.max(Vec2::splat(1e-4));
        d.x.min(d.y)
    };
    let line1 = 1.0 - line(world, w1).min(1.0);
    let line5 = 1.0 - (line(world / 5.0, w1 / 5.0) / 1.6).min(1.0);
    (line1 * 0.35).max(line5 * 0.6)
}

impl Light<'_> {
    fn sun(&self) -> Vec3 {
        v3(self.globals.sun_color)
    }

    fn sunlit(&self, world: Vec3, taps: &[Vec2]) -> f32 {
        self.shadow
            .sunlit(self.globals, self.light_view_proj * world.extend(1.0), taps)
    }

    /// `fs_main`: a triangle's linear colour.
    pub fn surface(&self, m: &Material, f: &Fragment) -> Vec3 {
        let g = self.globals;
        let kind = m.kind[0];
        let mut n = f.normal.normalize_or(Vec3::Z);
        let mut base = v3(m.color) * f.shade;
        if kind > 1.5 {
            base = mix(
                base,
                base * 0.55,
                grid(Vec2::new(f.world.x, f.world.y), f.fwidth),
            );
        }
        let leaf = kind > 0.5 && kind < 1.5;
        if leaf && !f.front {
            n = -n;
        }
        let l = v3(g.sun_dir);
        let ndl = n.dot(l);
        let sun = self.sun() * self.sunlit(f.world, if leaf { &LEAF_TAPS } else { &TAPS });
        // Sky from above, light bounced off the ground from below.
        let hemi = mix(v3(g.ground_bounce), v3(g.sky_color), 0.5 + 0.5 * n.z);
        let mut lit = base * (hemi + sun * ndl.max(0.0));
        if leaf {
            // Light through the leaf when the sun is behind it.
            lit += base * sun * (-ndl).max(0.0) * 0.45;
        }
        lit
    }

    /// `flat_shade`: a far stem's (a line's) or leaf's (a point's) colour and the share of a
    /// pixel it covers. `size` holds metres of size, items stood for and the copy's scale.
    pub fn flat(&self, m: &Material, world: Vec3, direction: Vec3, size: Vec3) -> (Vec3, f32) {
        let g = self.globals;
        let l = v3(g.sun_dir);
        let sun = self.sun() * self.sunlit(world, &TAPS);
        let base = v3(m.color);
        let to_eye = v3(g.eye) - world;
        let pixels_per_metre = g.eye[3] * size.z / to_eye.length().max(1e-3);
        if m.kind[0] > 0.5 {
            // A leaf: two-sided, facing the eye.
            let mut n = direction.normalize_or(Vec3::Z);
            if n.dot(to_eye) < 0.0 {
                n = -n;
            }
            let ndl = n.dot(l);
            let hemi = mix(v3(g.ground_bounce), v3(g.sky_color), 0.5 + 0.5 * n.z);
            let lit = base * (hemi + sun * ndl.max(0.0) + sun * (-ndl).max(0.0) * 0.45);
            (lit, size.x * pixels_per_metre * pixels_per_metre * size.y)
        } else {
            // A stem: a cylinder about its axis, half of it towards the sun.
            let t = direction.normalize_or(Vec3::Z);
            let across = (1.0 - t.dot(l) * t.dot(l)).max(0.0).sqrt();
            let lit = base * (mix(v3(g.ground_bounce), v3(g.sky_color), 0.6) + sun * across * 0.5);
            (lit, size.x * pixels_per_metre * size.y)
        }
    }
}

/// Whether a material is the ground's, whose grid needs the pixel's footprint.
pub(crate) fn is_ground(m: &Material) -> bool {
    (m.kind[0] - KIND_GROUND).abs() < 0.5
}

/// A well-mixed 32-bit hash (PCG output permutation), as in the shader.
pub(crate) fn hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

/// The shader's `dither`: two thresholds in 0..1 for pixel (x, y), the same in every frame:
/// the first for the dissolve between a tree and its impostor, the second for the impostor's
/// alpha.
pub(crate) fn dither(x: u32, y: u32) -> (f32, f32) {
    let h = hash(x ^ hash(y.wrapping_add(0x9e37_79b9)));
    ((h & 0xffff) as f32 / 65536.0, (h >> 16) as f32 / 65536.0)
}

/// The shader's `world_seed`.
pub(crate) fn world_seed(world: Vec3) -> u32 {
    hash(world.x.to_bits() ^ hash(world.y.to_bits() ^ hash(world.z.to_bits())))
}

/// The shader's `coverage_mask`: which of 4 samples a line or point covering `cover` of a
/// pixel lights.
pub(crate) fn coverage_mask(cover: f32, seed: u32) -> u32 {
    let jitter = (seed & 0xffff) as f32 / 65536.0;
    let samples = (cover * 4.0 + jitter).floor().clamp(0.0, 4.0) as u32;
    let first = (seed >> 16) & 3;
    let run = (1u32 << samples) - 1;
    ((run << first) | (run >> (4 - first))) & 15
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coverage_masks_light_the_share_on_average() {
        for share in [0.0, 0.1, 0.25, 0.6, 1.0] {
            let n = 20_000;
            let lit: u32 = (0..n)
                .map(|i| coverage_mask(share, hash(i)).count_ones())
                .sum();
            let mean = lit as f32 / (4 * n) as f32;
            assert!((mean - share).abs() < 0.01, "{share}: {mean}");
        }
        assert_eq!(coverage_mask(1.0, 12345), 15);
    }

    #[test]
    fn a_shadow_map_darkens_only_what_lies_behind() {
        let map = ShadowMap {
            size: 4,
            depth: vec![0.5; 16],
        };
        assert_eq!(map.compare(Vec2::splat(0.5), 0.4), 1.0);
        assert_eq!(map.compare(Vec2::splat(0.5), 0.6), 0.0);
    }
}
