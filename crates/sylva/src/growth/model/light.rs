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
    /// Each sky direction's shade (`illuminate`), kept so a step reuses the last one's memory.
    shades: Vec<Vec<f32>>,
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
            shades: Vec::new(),
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
        if let Some((i, passing)) = self.occluder(p, branch, leaves) {
            self.density[i] *= passing;
        }
    }

    /// The cell an occluder at `p` lies in and the share of light it lets through there,
    /// (1 - A)(1 - l) (see [`LightGrid::occlude`]); none outside the grid.
    pub fn occluder(&self, p: Vec3, branch: f32, leaves: f32) -> Option<(usize, f32)> {
        Some((self.index_of(p)?, self.passing(branch, leaves)))
    }

    /// The share of light an occluder covering `branch` m² of wood and `leaves` m² of leaves
    /// lets through a cell: (1 - A)(1 - l) (see [`LightGrid::occlude`]). The same wherever in
    /// the grid it lies, so the pieces of one shoot work it out once.
    pub fn passing(&self, branch: f32, leaves: f32) -> f32 {
        let area = self.cell * self.cell;
        let a = (branch / area).clamp(0.0, 1.0);
        let l = (leaves / area).clamp(0.0, 1.0);
        (1.0 - a) * (1.0 - l)
    }

    /// The flat index of the cell holding a point, if inside.
    #[inline]
    pub fn index_of(&self, p: Vec3) -> Option<usize> {
        self.cell_of(p).map(|[x, y, z]| self.index(x, y, z))
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
        let mut shades = std::mem::take(&mut self.shades);
        shades.resize_with(sky.len(), Vec::new);
        (sky.par_iter().zip(shades.par_iter_mut()))
            .for_each(|(ray, shade)| self.shade_of(ray, shade));
        self.light.fill(1.0);
        for shade in &shades[..sky.len()] {
            for (l, s) in self.light.iter_mut().zip(shade) {
                *l *= s;
            }
        }
        for l in &mut self.light {
            *l = 1.0 - *l;
        }
        self.shades = shades;
    }

    /// The share of each cell's light that one direction of the sky does not supply, into
    /// `shade`.
    fn shade_of(&self, ray: &Ray, shade: &mut Vec<f32>) {
        shade.clear();
        shade.resize(self.density.len(), 1.0);
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
            let start = |i: usize, j: usize| {
                let mut start = [0.0f32; 3];
                start[u] = i as f32 + 0.5;
                start[v] = j as f32 + 0.5;
                start[w] = at;
                Vec3::from_array(start)
            };
            // Every ray of a face starts at the same point of its own cell (the centre across
            // the face, `at` through it), so every one takes the same steps in the same order:
            // the walk is worked out once a face and each ray replays it from its cell.
            let walk = Walk::new(self, start(0, 0), d);
            for j in 0..self.size[v] {
                for i in 0..self.size[u] {
                    walk.replay(self, start(i, j), ray.intensity, shade);
                }
            }
        }
    }
}

/// The cells one ray passes, in order, as steps from the cell it starts in: Amanatides &
/// Woo's 3-D DDA, the generalisation of Bresenham's walk to every cell a line passes. Which
/// axis a step crosses depends only on where in its cell the ray starts and on its direction,
/// so rays that start at the same point of different cells take the same steps; each stops
/// where it leaves the grid or its light is spent.
///
/// Replaying the steps from a table, rather than choosing the axis at every cell, takes the
/// walk's one unpredictable branch out of the loop: growing a plane to 40 years spent 31% of
/// its time in the walk before, 16% after (`perf`, dev build).
struct Walk {
    /// Offset of each cell along the walk from the first (0 first), in the grid's flat index.
    offsets: Vec<isize>,
    /// For each axis, where along `offsets` its first, second, ... step leads.
    steps: [Vec<usize>; 3],
    /// The walk's direction along each axis: -1, 0 or 1.
    sign: [i64; 3],
}

impl Walk {
    /// The walk of a ray from `start` (in cell units) along `d`, as long as any ray of the
    /// grid can take (a walk leaves the grid within nx + ny + nz cells).
    fn new(grid: &LightGrid, start: Vec3, d: Vec3) -> Self {
        let [nx, ny, nz] = grid.size;
        let len = nx + ny + nz;
        let mut axes = [
            Axis::new(start.x, d.x, 1),
            Axis::new(start.y, d.y, nx),
            Axis::new(start.z, d.z, nx * ny),
        ];
        let mut offsets = Vec::with_capacity(len);
        let mut steps: [Vec<usize>; 3] = Default::default();
        let mut at = 0isize;
        offsets.push(at);
        while offsets.len() < len {
            let [x, y, z] = &axes;
            let a = if x.t_max < y.t_max {
                if x.t_max < z.t_max { 0 } else { 2 }
            } else if y.t_max < z.t_max {
                1
            } else {
                2
            };
            if axes[a].step == 0 {
                // Every axis left has an infinite distance to its next boundary: a ray of
                // no direction, which never leaves its cell.
                break;
            }
            axes[a].t_max += axes[a].t_delta;
            at += axes[a].step as isize * axes[a].stride;
            steps[a].push(offsets.len());
            offsets.push(at);
        }
        Walk {
            offsets,
            steps,
            sign: axes.map(|a| a.step),
        }
    }

    /// One ray of intensity `intensity` from `start`, which must lie at the same point of its
    /// cell as the walk's own start: each cell it passes keeps (1 - I_r) of its shade, and the
    /// ray keeps the cell's density.
    fn replay(&self, grid: &LightGrid, start: Vec3, intensity: f32, shade: &mut [f32]) {
        let cell = start.to_array().map(crate::whole::floor_i64);
        let mut cells = self.offsets.len();
        for (a, &c) in cell.iter().enumerate() {
            let size = grid.size[a] as i64;
            if c < 0 || c >= size {
                return;
            }
            // The steps this axis takes before its next leaves the grid.
            let room = match self.sign[a] {
                1 => size - 1 - c,
                -1 => c,
                _ => continue,
            } as usize;
            if let Some(&out) = self.steps[a].get(room) {
                cells = cells.min(out);
            }
        }
        let first = grid.index(cell[0] as usize, cell[1] as usize, cell[2] as usize) as isize;
        let mut ir = intensity;
        for &offset in &self.offsets[..cells] {
            // The walk goes on while the ray's light is over 10^-4 (and a number).
            if ir <= 1e-4 || ir.is_nan() {
                break;
            }
            let at = (first + offset) as usize;
            shade[at] *= 1.0 - ir;
            ir *= grid.density[at];
        }
    }
}

/// One axis of a ray's walk through the grid: the step it takes, the distance along the ray
/// to its next cell boundary and between boundaries, and the flat index's stride.
#[derive(Clone, Copy)]
struct Axis {
    step: i64,
    stride: isize,
    t_max: f32,
    t_delta: f32,
}

impl Axis {
    fn new(pos: f32, dir: f32, stride: usize) -> Self {
        let cell = crate::whole::floor_i64(pos);
        let (step, t_max, t_delta) = if dir > 0.0 {
            (1, ((cell + 1) as f32 - pos) / dir, 1.0 / dir)
        } else if dir < 0.0 {
            (-1, (cell as f32 - pos) / dir, -1.0 / dir)
        } else {
            (0, f32::INFINITY, f32::INFINITY)
        };
        Axis {
            step,
            stride: stride as isize,
            t_max,
            t_delta,
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

    /// The walk as first written, the state in arrays indexed by the axis stepped: the
    /// reference the faster walk must match bit for bit.
    fn reference_trace(g: &LightGrid, start: Vec3, d: Vec3, intensity: f32, shade: &mut [f32]) {
        let size = g.size.map(|n| n as i64);
        let mut cell = start.to_array().map(|x| x.floor() as i64);
        let (dir, pos) = (d.to_array(), start.to_array());
        let (mut step, mut t_max, mut t_delta) =
            ([0i64; 3], [f32::INFINITY; 3], [f32::INFINITY; 3]);
        for a in 0..3 {
            if dir[a] > 0.0 {
                (step[a], t_max[a], t_delta[a]) =
                    (1, ((cell[a] + 1) as f32 - pos[a]) / dir[a], 1.0 / dir[a]);
            } else if dir[a] < 0.0 {
                (step[a], t_max[a], t_delta[a]) =
                    (-1, (cell[a] as f32 - pos[a]) / dir[a], -1.0 / dir[a]);
            }
        }
        let mut ir = intensity;
        while (0..3).all(|a| cell[a] >= 0 && cell[a] < size[a]) && ir > 1e-4 {
            let i = g.index(cell[0] as usize, cell[1] as usize, cell[2] as usize);
            shade[i] *= 1.0 - ir;
            ir *= g.density[i];
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

    #[test]
    fn the_walk_shades_the_cells_the_reference_walk_shades_bit_for_bit() {
        let mut g = LightGrid::new(Vec3::ZERO, Vec3::new(7.0, 5.0, 9.0), 1.0, 64);
        let mut rng = crate::rng::StreamKey::from_seed(11).stream();
        for d in g.density.iter_mut() {
            *d = 0.5 + rng.var(0.5) as f32;
        }
        let mut directions: Vec<Vec3> = daylight().iter().map(|r| r.direction).collect();
        // Diagonals from cell centres cross two boundaries at once: the walk's ties.
        for v in [
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(0.0, 1.0, -1.0),
        ] {
            directions.push(v.normalize());
        }
        for _ in 0..40 {
            let v = Vec3::new(
                rng.var(1.0) as f32,
                rng.var(1.0) as f32,
                -1.0 - rng.var(0.9) as f32,
            );
            directions.push(v.normalize());
        }
        for d in directions {
            for _ in 0..50 {
                // Starts inside, on the faces and just outside the grid.
                let mut start = Vec3::new(
                    3.5 + rng.var(4.0) as f32,
                    2.5 + rng.var(3.0) as f32,
                    4.5 + rng.var(5.0) as f32,
                );
                if rng.var(1.0) > 0.0 {
                    start = start.floor() + Vec3::splat(0.5);
                }
                let (mut want, mut got) =
                    (vec![1.0f32; g.density.len()], vec![1.0f32; g.density.len()]);
                reference_trace(&g, start, d, 0.8, &mut want);
                Walk::new(&g, start, d).replay(&g, start, 0.8, &mut got);
                let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&got), bits(&want), "ray from {start} along {d}");
            }
        }
    }

    #[test]
    fn a_face_s_rays_replaying_one_walk_shade_as_the_reference_walk_bit_for_bit() {
        // Grids of uneven sides, so the entry faces' positions (n - 0.001) round differently.
        for hi in [Vec3::new(7.0, 5.0, 9.0), Vec3::new(28.0, 13.0, 21.0)] {
            let mut g = LightGrid::new(Vec3::ZERO, hi, 1.0, 64);
            let mut rng = crate::rng::StreamKey::from_seed(5).stream();
            for d in g.density.iter_mut() {
                *d = 0.3 + rng.var(0.3) as f32;
            }
            let [nx, ny, nz] = g.size;
            let mut sky = daylight();
            sky.push(Ray {
                direction: Vec3::new(1.0, 1.0, -1.0).normalize(),
                intensity: 0.9,
            });
            for ray in &sky {
                let d = ray.direction;
                let mut want = vec![1.0f32; g.density.len()];
                let mut starts = Vec::new();
                for y in 0..ny {
                    for x in 0..nx {
                        starts.push(Vec3::new(x as f32 + 0.5, y as f32 + 0.5, nz as f32 - 1e-3));
                    }
                }
                if d.x != 0.0 {
                    let at = if d.x > 0.0 { 1e-3 } else { nx as f32 - 1e-3 };
                    for z in 0..nz {
                        for y in 0..ny {
                            starts.push(Vec3::new(at, y as f32 + 0.5, z as f32 + 0.5));
                        }
                    }
                }
                if d.y != 0.0 {
                    let at = if d.y > 0.0 { 1e-3 } else { ny as f32 - 1e-3 };
                    for z in 0..nz {
                        for x in 0..nx {
                            starts.push(Vec3::new(x as f32 + 0.5, at, z as f32 + 0.5));
                        }
                    }
                }
                for start in starts {
                    reference_trace(&g, start, d, ray.intensity, &mut want);
                }
                let mut got = Vec::new();
                g.shade_of(ray, &mut got);
                let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&got), bits(&want), "{:?} along {d}", g.size);
            }
        }
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
