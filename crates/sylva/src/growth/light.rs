//! Light inside the crown (Rudnick et al. 2007, section 3.4): a box cut into horizontal slabs of
//! square cells; every branch piece and its leaves lower the fraction of light a cell lets
//! through; daylight rays, strongest from the zenith, walk the cells with a 3-D DDA and leave
//! light behind by the accumulation rule I_c <- I_c + I_r - I_c I_r, then I_r <- I_r D.

use glam::Vec3;
use rayon::prelude::*;

/// One daylight direction (pointing down into the crown) and the intensity of its rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Unit direction of travel (z < 0).
    pub direction: Vec3,
    /// Intensity each ray of this direction starts with.
    pub intensity: f32,
}

/// The sky used for growth: a zenith ray of full intensity and two rings of weaker oblique rays
/// (45 and 70 degrees from the zenith, four azimuths each), so that the zenith dominates as in
/// an overcast sky and the sides still reach a crown's flanks.
pub fn daylight() -> Vec<Ray> {
    let mut rays = vec![Ray {
        direction: Vec3::NEG_Z,
        intensity: 1.0,
    }];
    for (zenith_deg, intensity, turn) in [(45.0f32, 0.25f32, 0.0f32), (70.0, 0.1, 45.0)] {
        let z = zenith_deg.to_radians();
        for k in 0..4 {
            let a = (turn + 90.0 * k as f32).to_radians();
            rays.push(Ray {
                direction: Vec3::new(z.sin() * a.cos(), z.sin() * a.sin(), -z.cos()),
                intensity,
            });
        }
    }
    rays
}

/// The voxel grid: densities (fraction of light passing) and accumulated light per cell.
#[derive(Clone, Debug)]
pub struct LightGrid {
    /// Lower corner, metres.
    pub origin: Vec3,
    /// Edge of a square cell and height of a slab, metres.
    pub cell: f32,
    /// Cells along x, y and z (slabs).
    pub size: [usize; 3],
    /// Fraction of light a cell lets through (1: empty).
    pub density: Vec<f32>,
    /// Light accumulated in each cell (0..1).
    pub light: Vec<f32>,
}

impl LightGrid {
    /// A grid over a box with cells of about `cell` metres, at most `max_cells` along an axis.
    pub fn new(lo: Vec3, hi: Vec3, cell: f32, max_cells: usize) -> Self {
        let mut g = LightGrid {
            origin: lo,
            cell,
            size: [1; 3],
            density: Vec::new(),
            light: Vec::new(),
        };
        g.reshape(lo, hi, cell, max_cells);
        g
    }

    /// Re-fits the grid to a new box (keeping its buffers), emptied.
    pub fn reshape(&mut self, lo: Vec3, hi: Vec3, cell: f32, max_cells: usize) {
        let extent = (hi - lo).max(Vec3::splat(1e-3));
        let cell = cell.max(extent.max_element() / max_cells as f32);
        self.size = [
            (extent.x / cell).ceil().max(1.0) as usize,
            (extent.y / cell).ceil().max(1.0) as usize,
            (extent.z / cell).ceil().max(1.0) as usize,
        ];
        self.origin = lo;
        self.cell = cell;
        let n = self.size[0] * self.size[1] * self.size[2];
        self.density.clear();
        self.density.resize(n, 1.0);
        self.light.clear();
        self.light.resize(n, 0.0);
    }

    /// Index of the cell at integer coordinates.
    #[inline]
    pub fn index(&self, x: usize, y: usize, z: usize) -> usize {
        (z * self.size[1] + y) * self.size[0] + x
    }

    /// Integer coordinates of the cell holding a point, if inside.
    pub fn cell_of(&self, p: Vec3) -> Option<[usize; 3]> {
        let q = (p - self.origin) / self.cell;
        if q.x < 0.0 || q.y < 0.0 || q.z < 0.0 {
            return None;
        }
        let c = [q.x as usize, q.y as usize, q.z as usize];
        (c[0] < self.size[0] && c[1] < self.size[1] && c[2] < self.size[2]).then_some(c)
    }

    /// Empties the grid (every cell lets all light through, none accumulated).
    pub fn clear(&mut self) {
        self.density.fill(1.0);
        self.light.fill(0.0);
    }

    /// Adds an occluder in the cell holding `p`: it covers `branch` m² and `leaves` m² of the
    /// cell's square (as projected into the slab's lower plane). D <- D (1 - A)(1 - l).
    pub fn occlude(&mut self, p: Vec3, branch: f32, leaves: f32) {
        if let Some([x, y, z]) = self.cell_of(p) {
            let area = self.cell * self.cell;
            let a = (branch / area).clamp(0.0, 1.0);
            let l = (leaves / area).clamp(0.0, 1.0);
            let i = self.index(x, y, z);
            self.density[i] *= (1.0 - a) * (1.0 - l);
        }
    }

    /// Light at a point (1 outside the grid: nothing shades it there).
    pub fn light_at(&self, p: Vec3) -> f32 {
        self.cell_of(p)
            .map_or(1.0, |[x, y, z]| self.light[self.index(x, y, z)])
    }

    /// Density (fraction passing) at a point (1 outside).
    pub fn density_at(&self, p: Vec3) -> f32 {
        self.cell_of(p)
            .map_or(1.0, |[x, y, z]| self.density[self.index(x, y, z)])
    }

    /// Direction of increasing light at a point (central differences over neighbouring
    /// cells), zero where it is flat.
    pub fn gradient_at(&self, p: Vec3) -> Vec3 {
        let c = self.cell;
        let f = |d: Vec3| self.light_at(p + d) - self.light_at(p - d);
        Vec3::new(f(Vec3::X * c), f(Vec3::Y * c), f(Vec3::Z * c))
    }

    /// Sends the sky's rays through the grid: one ray per cell of every face a direction
    /// enters through, each walking its cells until it leaves.
    pub fn illuminate(&mut self, sky: &[Ray]) {
        // I_c <- I_c + I_r - I_c I_r is 1 - I_c <- (1 - I_c)(1 - I_r): each direction darkens
        // its own copy of the grid on its own thread, and the copies are multiplied in the
        // sky's order, so the result does not depend on how the work was spread.
        let shades: Vec<Vec<f32>> = sky.par_iter().map(|ray| self.shade_of(ray)).collect();
        self.light.fill(1.0);
        for shade in &shades {
            for (l, s) in self.light.iter_mut().zip(shade) {
                *l *= s;
            }
        }
        for l in &mut self.light {
            *l = 1.0 - *l;
        }
    }

    /// The share of each cell's light that one direction of the sky does not supply.
    fn shade_of(&self, ray: &Ray) -> Vec<f32> {
        let mut shade = vec![1.0f32; self.density.len()];
        let [nx, ny, nz] = self.size;
        let d = ray.direction;
        // The top face for every direction; a side face where the ray enters through it.
        // Each face is spanned by two axes (u, v) at a fixed third coordinate.
        let mut faces = vec![(0, 1, 2, nz as f32 - 1e-3)];
        if d.x != 0.0 {
            faces.push((1, 2, 0, if d.x > 0.0 { 1e-3 } else { nx as f32 - 1e-3 }));
        }
        if d.y != 0.0 {
            faces.push((0, 2, 1, if d.y > 0.0 { 1e-3 } else { ny as f32 - 1e-3 }));
        }
        for (u, v, w, at) in faces {
            for j in 0..self.size[v] {
                for i in 0..self.size[u] {
                    let mut start = [0.0f32; 3];
                    start[u] = i as f32 + 0.5;
                    start[v] = j as f32 + 0.5;
                    start[w] = at;
                    self.trace(Vec3::from_array(start), d, ray.intensity, &mut shade);
                }
            }
        }
        shade
    }

    /// One ray from `start` (in cell units) along `d`: Amanatides & Woo's 3-D DDA, the
    /// generalisation of Bresenham's walk to every cell a line passes.
    fn trace(&self, start: Vec3, d: Vec3, intensity: f32, shade: &mut [f32]) {
        let size = [
            self.size[0] as i64,
            self.size[1] as i64,
            self.size[2] as i64,
        ];
        let mut cell = [
            start.x.floor() as i64,
            start.y.floor() as i64,
            start.z.floor() as i64,
        ];
        let dir = d.to_array();
        let pos = start.to_array();
        let mut step = [0i64; 3];
        let mut t_max = [f32::INFINITY; 3];
        let mut t_delta = [f32::INFINITY; 3];
        for a in 0..3 {
            if dir[a] > 0.0 {
                step[a] = 1;
                t_max[a] = ((cell[a] + 1) as f32 - pos[a]) / dir[a];
                t_delta[a] = 1.0 / dir[a];
            } else if dir[a] < 0.0 {
                step[a] = -1;
                t_max[a] = (cell[a] as f32 - pos[a]) / dir[a];
                t_delta[a] = -1.0 / dir[a];
            }
        }
        let mut ir = intensity;
        while (0..3).all(|a| cell[a] >= 0 && cell[a] < size[a]) && ir > 1e-4 {
            let i = self.index(cell[0] as usize, cell[1] as usize, cell[2] as usize);
            shade[i] *= 1.0 - ir;
            ir *= self.density[i];
            let a = if t_max[0] < t_max[1] {
                if t_max[0] < t_max[2] { 0 } else { 2 }
            } else if t_max[1] < t_max[2] {
                1
            } else {
                2
            };
            cell[a] += step[a];
            t_max[a] += t_delta[a];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> LightGrid {
        LightGrid::new(Vec3::ZERO, Vec3::splat(8.0), 1.0, 64)
    }

    #[test]
    fn an_empty_grid_is_fully_lit() {
        let mut g = grid();
        g.illuminate(&daylight());
        assert!(g.light.iter().all(|&l| (l - 1.0).abs() < 1e-6));
    }

    #[test]
    fn a_cell_under_a_dense_layer_is_darker() {
        let mut g = grid();
        for x in 0..8 {
            for y in 0..8 {
                let p = Vec3::new(x as f32 + 0.5, y as f32 + 0.5, 6.5);
                g.occlude(p, 0.0, 0.9);
            }
        }
        g.illuminate(&daylight());
        let under = g.light_at(Vec3::new(4.5, 4.5, 2.5));
        let above = g.light_at(Vec3::new(4.5, 4.5, 7.5));
        assert_eq!(above, 1.0);
        // The zenith ray loses 90% in the layer; the oblique rays still come in under it from
        // the open sides of the box: 1 - 0.9 (0.75^4)(0.9^4) = 0.81.
        assert!(under < 0.85, "under the layer {under}");
        let mut open = grid();
        open.illuminate(&daylight());
        assert_eq!(open.light_at(Vec3::new(4.5, 4.5, 2.5)), 1.0);
    }

    #[test]
    fn rays_from_the_zenith_dominate() {
        // One cell with only the zenith open (a wall of leaves around its sides, a chimney
        // above), one with the zenith blocked and the sides open.
        let mut g = grid();
        let probe_a = Vec3::new(2.5, 2.5, 1.5);
        let probe_b = Vec3::new(5.5, 5.5, 1.5);
        for z in 1..8 {
            for dx in -1i32..=1 {
                for dy in -1i32..=1 {
                    if dx == 0 && dy == 0 {
                        continue;
                    }
                    let p = probe_a + Vec3::new(dx as f32, dy as f32, (z - 1) as f32);
                    g.occlude(p, 0.0, 1.0);
                }
            }
        }
        g.occlude(probe_b + Vec3::Z, 0.0, 1.0);
        g.illuminate(&daylight());
        let (a, b) = (g.light_at(probe_a), g.light_at(probe_b));
        assert!(a > b, "zenith only {a}, sides only {b}");
    }

    #[test]
    fn accumulation_does_not_depend_on_ray_order() {
        let mut g = grid();
        for i in 0..40 {
            let p = Vec3::new(
                (i * 7 % 8) as f32 + 0.3,
                (i * 3 % 8) as f32 + 0.6,
                (i % 8) as f32,
            );
            g.occlude(p, 0.2, 0.3);
        }
        let sky = daylight();
        g.illuminate(&sky);
        let forward = g.light.clone();
        let mut reversed = sky.clone();
        reversed.reverse();
        g.illuminate(&reversed);
        for (a, b) in forward.iter().zip(&g.light) {
            assert!((a - b).abs() < 1e-5, "{a} vs {b}");
        }
    }
}
