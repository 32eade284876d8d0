//! Impostors on the CPU, as `impostor.wgsl` draws them: a quad per copy standing on the trunk
//! and facing the eye, showing the two baked views either side of it cross-faded, on the
//! pixels whose thresholds its alpha and the dissolve pass.

use super::raster::{Grid, Setup};
use super::shade::dither;
use super::{FLAT, SAMPLES, Samples};
use crate::frame::InstanceData;
use crate::impostor::{Atlas, CELL, Cell, VIEWS};
use glam::{Mat4, Vec2, Vec3};

/// What one impostor draw needs of the frame.
pub(super) struct ImpostorDraw<'a> {
    pub atlas: &'a Atlas,
    pub view_proj: Mat4,
    pub eye: Vec3,
    pub grid: Grid,
}

impl ImpostorDraw<'_> {
    /// Draws the impostor of the copy `instance` (whose `sway[3]` is its share of pixels)
    /// showing `cell`, its colours stored in `colours` under flat keys.
    pub fn draw(
        &self,
        instance: &InstanceData,
        cell: &Cell,
        samples: &mut Samples,
        colours: &mut Vec<Vec3>,
    ) {
        let place = Vec3::from_slice(&instance.place[..3]);
        let towards = (self.eye - place)
            .truncate()
            .try_normalize()
            .unwrap_or(Vec2::new(0.0, -1.0));
        // The picture's right as the eye sees it, in the tree's own frame.
        let right = Vec2::new(-towards.y, towards.x);
        let [c, s] = instance.turn;
        let own_right = Vec3::new(c * right.x + s * right.y, -s * right.x + c * right.y, 0.0);
        let [tx, ty, length, fade] = instance.sway;
        let sway = sylva::lod::sway::Sway {
            turn: [tx, ty],
            length,
        };
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(a, u)| {
            let p = own_right * ((2.0 * a - 1.0) * cell.half_width)
                + Vec3::Z * (cell.bottom + (cell.top - cell.bottom) * u);
            let world = instance.place(p + sway.displacement(p));
            (Vec2::new(a, u), self.view_proj * world.extend(1.0))
        });
        let (first, second, weight) = sylva::lod::view_blend(VIEWS, towards);
        // From the centre of the cell's first texel to that of its last (as the shader).
        let texel = |at: Vec2, view: u32| {
            Vec2::new(
                cell.x0 as f32 + 0.5 + at.x * (cell.width as f32 - 1.0),
                cell.y0 as f32 + 0.5 + (view * CELL) as f32 + (1.0 - at.y) * (CELL as f32 - 1.0),
            )
        };
        let width = self.grid.width;
        for tri in [[0, 1, 2], [0, 2, 3]] {
            let clip = tri.map(|k| corners[k].1);
            let Some(setup) = Setup::new(clip) else {
                continue;
            };
            let at = tri.map(|k| corners[k].0);
            self.grid.triangle(&setup, &clip, |i, z, _| {
                let pixel = (i / SAMPLES) as u32;
                let (x, y) = (pixel % width, pixel / width);
                let (share, alpha_threshold) = dither(x, y);
                if share >= fade {
                    return;
                }
                let centre = self.grid.ndc(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                let Some(b) = setup.barycentric(centre) else {
                    return;
                };
                let uv = at[0] * b.x + at[1] * b.y + at[2] * b.z;
                let colour = self
                    .atlas
                    .sample(texel(uv, first))
                    .lerp(self.atlas.sample(texel(uv, second)), weight);
                if colour.w <= alpha_threshold {
                    return;
                }
                colours.push(colour.truncate() / colour.w);
                samples.test(i, z, FLAT | (colours.len() - 1) as u64);
            });
        }
    }
}
