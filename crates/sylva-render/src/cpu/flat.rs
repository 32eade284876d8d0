//! Far stems (lines) and leaves (points) on the CPU: each lit once, as the shader's vertex
//! stage lights it, and written to the samples its share of a pixel covers.

use super::raster::Grid;
use super::shade::{self, Light};
use super::{FLAT, FlatVertex, SAMPLES, Samples};
use crate::frame::InstanceData;
use glam::{Mat4, Vec3};

/// Far stems (lines) and leaves (points) of one copy of a tree.
pub(super) struct FlatDraw<'a> {
    pub light: &'a Light<'a>,
    pub material: &'a crate::frame::Material,
    pub instance: &'a InstanceData,
    pub view_proj: Mat4,
    pub grid: Grid,
    /// The share of pixels the copy's impostor has taken.
    pub fade: f32,
}

/// Where flat primitives go: the visibility buffer and the colours its flat keys point to.
pub(super) type FlatOut<'a> = (&'a mut Samples, &'a mut Vec<Vec3>);

impl FlatDraw<'_> {
    /// The colour and the share of a pixel of a line or point at `world` whose vertex is `v`,
    /// stored under a new key.
    fn lit(&self, world: Vec3, v: &FlatVertex, colours: &mut Vec<Vec3>) -> (u64, f32) {
        let n = Vec3::new(v.normal[0] as f32, v.normal[1] as f32, v.normal[2] as f32) / 127.0;
        let size = Vec3::new(v.size, self.instance.stands_for[0], self.instance.place[3]);
        let (lit, cover) = self
            .light
            .flat(self.material, world, self.instance.turn(n), size);
        colours.push(lit);
        (FLAT | (colours.len() - 1) as u64, cover)
    }

    fn write(&self, out: &mut FlatOut, pixel: (u32, u32), z: f32, key: u64, mask: u32) {
        if self.fade > 0.0 && shade::dither(pixel.0, pixel.1).0 < self.fade {
            return;
        }
        let width = self.grid.width;
        let base = (pixel.1 * width + pixel.0) as usize * SAMPLES;
        for s in 0..SAMPLES {
            if mask & (1 << s) != 0 {
                out.0.test(base + s, z, key);
            }
        }
    }

    /// A point: lit once; every pixel it touches shows the same samples of its share, as the
    /// GPU's fragments of one point (same position, same seed) do.
    pub fn point(&self, v: &FlatVertex, out: &mut FlatOut) {
        let world = self.instance.place(Vec3::from(v.position));
        let mut key = None;
        self.grid
            .point(self.view_proj * world.extend(1.0), |x, y, z, shape| {
                let (k, cover) = *key.get_or_insert_with(|| self.lit(world, v, out.1));
                let mask = shade::coverage_mask(cover, shade::world_seed(world)) & shape;
                self.write(out, (x, y), z, k, mask);
            });
    }

    /// A line: lit once at its middle (a far stem is a few pixels long); each pixel draws its
    /// own share of samples, seeded by where along the line it lies.
    pub fn line(&self, va: &FlatVertex, vb: &FlatVertex, out: &mut FlatOut) {
        let (a, b) = (
            self.instance.place(Vec3::from(va.position)),
            self.instance.place(Vec3::from(vb.position)),
        );
        let (ca, cb) = (
            self.view_proj * a.extend(1.0),
            self.view_proj * b.extend(1.0),
        );
        let mut key = None;
        self.grid.line(ca, cb, |x, y, z, t, shape| {
            let (k, cover) = *key.get_or_insert_with(|| self.lit((a + b) / 2.0, va, out.1));
            let seed = shade::world_seed(a + (b - a) * t);
            let mask = shade::coverage_mask(cover, seed) & shape;
            self.write(out, (x, y), z, k, mask);
        });
    }
}
