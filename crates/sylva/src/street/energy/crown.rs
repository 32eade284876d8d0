//! The grown crown as the benefit models see it: its leaf and bark surfaces, the ground it
//! covers, and its leaf area density on a grid that sunlight crosses.

use crate::Skeleton;
use crate::mesh::template_area;
use crate::skeleton::Leaf;
use glam::{DVec3, Vec3};

/// One side of a leaf, m² (its template's area, computed once per shape, times its size).
pub fn leaf_area(l: &Leaf) -> f64 {
    (template_area(l.shape) * l.length * l.width) as f64
}

/// A leaf's centre, where its area is counted.
pub fn leaf_centre(l: &Leaf) -> Vec3 {
    l.position + l.orientation * Vec3::new(0.0, 0.0, l.length * 0.5)
}

/// Grid cell edge of a crown 12 m across or more, m: coarse enough that a ray crosses a 20 m
/// crown in a few dozen steps.
pub const CELL: f64 = 0.5;
/// A smaller crown's cells are this fraction of its widest extent: at 0.5 m a young sweetgum's
/// crown 3 m wide drew its outline to the edges of cells a sixth of its width, a third wider
/// than its picture, and its mean stop 0.12 under the picture's (issue R, item 3); at a
/// twenty-fourth the two agree within 0.04.
const CELLS_ACROSS: f64 = 24.0;
/// ...but no finer than this, m: about a leaf's size, below which a cell holds less than one
/// leaf and Beer-Lambert's leaves spread at random through it no longer describe it.
const MIN_CELL: f64 = 0.15;
/// Most cells along one axis (a 150 m crown at 0.5 m); larger crowns take larger cells.
const MAX_CELLS: usize = 300;
/// Bits of fraction in a ray's fixed-point walk through the grid ([`Crown::optical_depth`]).
const FIXED_BITS: u32 = 32;
const FIXED_ONE: f64 = (1u64 << FIXED_BITS) as f64;
/// Leaf projection coefficient for randomly (spherically) oriented leaves: the share of leaf
/// area a beam sees per unit path (Ross 1981, "The Radiation Regime and Architecture of Plant
/// Stands"; Monsi & Saeki 1953's Beer-Lambert law for canopies).
pub const G: f64 = 0.5;
/// Projection coefficient of wood per unit of its silhouette (diameter x length): a randomly
/// oriented cylinder shows on average pi/4 of its silhouette to a beam (the mean of sin over
/// the sphere), ends left out.
pub const G_WOOD: f64 = std::f64::consts::FRAC_PI_4;

/// Every leaf as its centre and area, m² (leaves of no area or off the map left out).
pub fn leaves_of(skeleton: &Skeleton) -> Vec<(Vec3, f64)> {
    skeleton
        .leaves
        .iter()
        .map(|l| (leaf_centre(l), leaf_area(l)))
        .filter(|(c, a)| c.is_finite() && a.is_finite() && *a > 0.0)
        .collect()
}

/// Leaf area density on a grid, and the crown's surfaces.
#[derive(Clone, Debug)]
pub struct Crown {
    /// One-sided leaf area, m².
    pub leaf_area: f64,
    /// Bark as a stem area: every segment's silhouette (diameter times length), one side like
    /// leaf area, as canopy hydrology counts stem area index, m².
    pub bark_area: f64,
    /// Ground the leaves cover seen from above, m².
    pub projection: f64,
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    /// Extinction coefficient of each cell in leaf, per m of path: `G` x leaf area per cell
    /// volume (m²/m³), plus `G_WOOD` x wood silhouette per cell volume once
    /// [`Crown::with_wood`] has added it. One array per season, summed as a ray crosses it,
    /// because the rays through it are most of an account's time (`sylva bench --street`).
    in_leaf: Vec<f32>,
    /// Bare, wood only: `G_WOOD` x wood silhouette (diameter x length) per cell volume, within
    /// the leaves' box; empty unless [`Crown::with_wood`] added it.
    bare: Vec<f32>,
}

/// How much of a beam a crown stops over its outline seen along the beam.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BeamStop {
    /// The outline's area: every ray between the first and the last that meets the crown in
    /// its row, m².
    pub outline_m2: f64,
    /// Mean share of the beam stopped over the outline, 0..1.
    pub stopped: f64,
}

impl Crown {
    /// Measures a grown tree: its leaves and its wood.
    pub fn of(skeleton: &Skeleton) -> Crown {
        Crown::with_leaves(skeleton, &leaves_of(skeleton)).with_wood(skeleton)
    }

    /// Measures a grown tree whose leaves [`leaves_of`] has listed.
    pub fn with_leaves(skeleton: &Skeleton, leaves: &[(Vec3, f64)]) -> Crown {
        let mut bark_area = 0.0f64;
        for stem in &skeleton.stems {
            let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
            for w in s.windows(2) {
                let len = w[0].position.distance(w[1].position) as f64;
                bark_area += (w[0].radius + w[1].radius) as f64 * len;
            }
        }
        let leaf_area = leaves.iter().map(|l| l.1).sum();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for &(c, _) in leaves {
            lo = lo.min(c);
            hi = hi.max(c);
        }
        if leaves.is_empty() {
            return Crown {
                leaf_area: 0.0,
                bark_area,
                projection: 0.0,
                origin: DVec3::ZERO,
                cell: CELL,
                dims: [0; 3],
                in_leaf: Vec::new(),
                bare: Vec::new(),
            };
        }
        let span = (hi - lo).as_dvec3();
        let widest = span.max_element();
        let cell = (widest / CELLS_ACROSS)
            .clamp(MIN_CELL, CELL)
            .max(widest / MAX_CELLS as f64 * 1.0001);
        let dims = [0, 1, 2].map(|k| (span[k] / cell).floor() as usize + 1);
        let origin = lo.as_dvec3();
        let mut area = vec![0.0f64; dims[0] * dims[1] * dims[2]];
        let mut covered = vec![false; dims[0] * dims[1]];
        // Axis by axis rather than `[0, 1, 2].map`, which was not inlined; and truncation
        // rather than `floor` (a call into libm on baseline x86-64), the same for the
        // non-negative offsets from the box's lowest leaf, and 0 for anything below it.
        let index = |v: f32, k: usize| (((v as f64 - origin[k]) / cell) as usize).min(dims[k] - 1);
        for (c, a) in leaves {
            let (x, y, z) = (index(c.x, 0), index(c.y, 1), index(c.z, 2));
            area[(z * dims[1] + y) * dims[0] + x] += a;
            covered[y * dims[0] + x] = true;
        }
        let volume = cell * cell * cell;
        Crown {
            leaf_area,
            bark_area,
            projection: covered.iter().filter(|&&c| c).count() as f64 * cell * cell,
            origin,
            cell,
            dims,
            in_leaf: area.iter().map(|a| (G * a / volume) as f32).collect(),
            bare: Vec::new(),
        }
    }

    /// The crown with its wood as well: every stem segment's silhouette spread along it in
    /// steps of half a cell, inside the leaves' box (the trunk below the crown is not crown).
    pub fn with_wood(mut self, skeleton: &Skeleton) -> Crown {
        if self.in_leaf.is_empty() {
            return self;
        }
        let mut wood = vec![0.0f64; self.in_leaf.len()];
        let inv = 1.0 / self.cell;
        let size = DVec3::new(
            self.dims[0] as f64,
            self.dims[1] as f64,
            self.dims[2] as f64,
        ) * self.cell;
        for stem in &skeleton.stems {
            let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
            for w in s.windows(2) {
                let (a, b) = (w[0].position.as_dvec3(), w[1].position.as_dvec3());
                let len = a.distance(b);
                let silhouette = (w[0].radius + w[1].radius) as f64 * len;
                let n = (len / (self.cell * 0.5)).ceil().max(1.0);
                let share = silhouette / n;
                for j in 0..n as usize {
                    let p = a.lerp(b, (j as f64 + 0.5) / n) - self.origin;
                    if p.cmplt(DVec3::ZERO).any() || p.cmpge(size).any() {
                        continue;
                    }
                    wood[self.cell_of(p * inv)] += share;
                }
            }
        }
        let volume = self.cell * self.cell * self.cell;
        self.bare = wood.iter().map(|a| (G_WOOD * a / volume) as f32).collect();
        for (k, b) in self.in_leaf.iter_mut().zip(&self.bare) {
            *k += b;
        }
        self
    }

    /// Optical depth along the ray from `from` along unit `dir` through the crown's box: leaves
    /// (`G` x leaf area crossed per unit cross-section) where `leaves`, plus wood (`G_WOOD` x
    /// silhouette crossed) where the crown has it.
    pub fn optical_depth(&self, from: DVec3, dir: DVec3, leaves: bool) -> f64 {
        let Some((t0, n, step)) = self.span(from, dir) else {
            return 0.0;
        };
        let grid = if leaves { &self.in_leaf } else { &self.bare };
        if grid.is_empty() {
            return 0.0;
        }
        // The walk in cell units, in fixed point (32 bits of fraction): each step adds the
        // stride and a shift gives the cell, with no float-to-integer conversion in the loop.
        // The first point is the first step's middle.
        let inv = 1.0 / self.cell;
        let start = (from + dir * (t0 + 0.5 * step) - self.origin) * inv;
        let stride = dir * (step * inv);
        let fixed = |v: DVec3| v.to_array().map(|c| (c * FIXED_ONE) as i64);
        let (mut at, by) = (fixed(start), fixed(stride));
        let top = self.dims.map(|d| d as i64 - 1);
        let [nx, ny, _] = self.dims;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let cell = |k: usize| (at[k] >> FIXED_BITS).clamp(0, top[k]) as usize;
            sum += grid[(cell(2) * ny + cell(1)) * nx + cell(0)] as f64;
            at = [at[0] + by[0], at[1] + by[1], at[2] + by[2]];
        }
        sum * step
    }

    /// The share of a parallel beam along unit `dir` that the crown stops over its outline:
    /// rays half a cell apart, rows across the beam's most vertical cross direction, each row's
    /// outline from its first ray that meets the crown to its last, as a picture's covered
    /// outline is measured between its outermost drawn pixels. `leaves: false` is the crown in
    /// winter, wood only ([`Crown::with_wood`]).
    pub fn beam(&self, dir: DVec3, leaves: bool) -> BeamStop {
        if self.in_leaf.is_empty() {
            return BeamStop::default();
        }
        let dir = dir.normalize();
        // u across the beam and level; v across it and as vertical as it can be.
        let u = if dir.cross(DVec3::Z).length() > 1e-9 {
            dir.cross(DVec3::Z).normalize()
        } else {
            DVec3::X
        };
        let v = u.cross(dir).normalize();
        let size = DVec3::new(
            self.dims[0] as f64,
            self.dims[1] as f64,
            self.dims[2] as f64,
        ) * self.cell;
        let centre = self.origin + size * 0.5;
        let reach = size.length() * 0.5;
        let h = self.cell * 0.5;
        let n = (2.0 * reach / h).ceil() as i64;
        let (mut rays, mut stopped) = (0usize, 0.0f64);
        for row in 0..n {
            let y = -reach + (row as f64 + 0.5) * h;
            let shares: Vec<f64> = (0..n)
                .map(|col| {
                    let x = -reach + (col as f64 + 0.5) * h;
                    let from = centre + u * x + v * y - dir * (reach + self.cell);
                    1.0 - (-self.optical_depth(from, dir, leaves)).exp()
                })
                .collect();
            let hit = |s: &&f64| **s > 1e-9;
            let (Some(first), Some(last)) = (
                shares.iter().position(|s| hit(&s)),
                shares.iter().rposition(|s| hit(&s)),
            ) else {
                continue;
            };
            rays += last - first + 1;
            stopped += shares[first..=last].iter().sum::<f64>();
        }
        BeamStop {
            outline_m2: rays as f64 * h * h,
            stopped: if rays > 0 { stopped / rays as f64 } else { 0.0 },
        }
    }

    /// The part of the ray from `from` along unit `dir` inside the grid's box: where it enters,
    /// how many steps of at most 0.75 cell, and their length; `None` if it misses.
    fn span(&self, from: DVec3, dir: DVec3) -> Option<(f64, usize, f64)> {
        if self.in_leaf.is_empty() {
            return None;
        }
        let size = DVec3::new(
            self.dims[0] as f64,
            self.dims[1] as f64,
            self.dims[2] as f64,
        ) * self.cell;
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for k in 0..3 {
            let o = from[k] - self.origin[k];
            if dir[k].abs() < 1e-12 {
                if o < 0.0 || o > size[k] {
                    return None;
                }
                continue;
            }
            let (a, b) = ((0.0 - o) / dir[k], (size[k] - o) / dir[k]);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        if t0 >= t1 {
            return None;
        }
        let n = ((t1 - t0) / (self.cell * 0.75)).ceil().max(1.0);
        Some((t0, n as usize, (t1 - t0) / n))
    }

    /// The grid cell at `q` in cell units from the grid's origin (clamped to the grid).
    fn cell_of(&self, q: DVec3) -> usize {
        let index = |v: f64, dim: usize| (v.max(0.0) as usize).min(dim - 1);
        let [nx, ny, nz] = self.dims;
        (index(q.z, nz) * ny + index(q.y, ny)) * nx + index(q.x, nx)
    }

    /// Share of a beam from `from` along unit `dir` that passes the crown in leaf
    /// (Beer-Lambert: `exp(-optical depth)`, [`Crown::optical_depth`]): its leaves, and its
    /// wood where [`Crown::with_wood`] added it.
    pub fn transmittance(&self, from: DVec3, dir: DVec3) -> f64 {
        self.transmittance_in(from, dir, true)
    }

    /// [`Crown::transmittance`] in leaf (`leaves`) or bare: a deciduous crown in winter
    /// stops the sun with its wood alone.
    pub fn transmittance_in(&self, from: DVec3, dir: DVec3, leaves: bool) -> f64 {
        (-self.optical_depth(from, dir, leaves)).exp()
    }

    /// Whether the crown's wood is on its grid ([`Crown::with_wood`]).
    pub fn has_wood(&self) -> bool {
        !self.bare.is_empty()
    }
}

/// A test crown: square 0.4 m leaves on a regular grid, `counts` along x, y, z from `origin`
/// at `step` apart (the shade and calibration tests stand such a block before a wall).
#[cfg(test)]
pub(crate) fn leaf_block(origin: Vec3, counts: [usize; 3], step: Vec3) -> Skeleton {
    let mut tree = Skeleton::default();
    for i in 0..counts[0] {
        for j in 0..counts[1] {
            for k in 0..counts[2] {
                tree.leaves.push(crate::skeleton::Leaf {
                    position: origin + Vec3::new(i as f32, j as f32, k as f32) * step,
                    orientation: glam::Quat::IDENTITY,
                    length: 0.4,
                    width: 0.4,
                    shape: crate::skeleton::LeafShape::Square,
                    stem: crate::StemId(0),
                    light: 1.0,
                });
            }
        }
    }
    tree
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::leaf_template;
    use crate::skeleton::{LeafShape, StemId};
    use glam::Quat;

    /// A cube of `n` x `n` x `n` square leaves `spacing` m apart, each `area` m², in the
    /// cube of side `n * spacing` standing on z = 3 and centred on x = y = 0; a speck of a leaf
    /// at its lowest corner puts the grid's origin there, so the leaves sit at the centres of
    /// cells `spacing` wide (not on their edges, where rounding would choose their cell).
    fn cube(n: usize, spacing: f32, area: f32) -> Skeleton {
        let mut s = Skeleton::default();
        let t = leaf_template(LeafShape::Square).area();
        let leaf = |centre: Vec3, area: f32| {
            let side = (area / t).sqrt();
            Leaf {
                position: centre - Vec3::new(0.0, 0.0, side * 0.5),
                orientation: Quat::IDENTITY,
                length: side,
                width: side,
                shape: LeafShape::Square,
                stem: StemId(0),
                light: 1.0,
            }
        };
        let half = n as f32 * spacing * 0.5;
        let corner = Vec3::new(-half, -half, 3.0);
        s.leaves.push(leaf(corner, 1e-9));
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let at = Vec3::new(i as f32, j as f32, k as f32) * spacing + spacing * 0.5;
                    s.leaves.push(leaf(corner + at, area));
                }
            }
        }
        s
    }

    /// Four leaves a side a finest cell apart, `density` m² of leaf per m³: a 0.6 m cube
    /// whose leaves sit at its cells' centres.
    fn small_cube(density: f32) -> Skeleton {
        let c = MIN_CELL as f32;
        cube(4, c, density * c * c * c)
    }

    #[test]
    fn a_crowns_cells_follow_its_size() {
        // A twenty-fourth of the widest extent of the leaves' centres (from the speck at the
        // corner to the last leaf's centre), within 0.15 and 0.5 m.
        for (n, spacing, cell) in [(4, 0.15, MIN_CELL), (17, 0.5, 8.25 / 24.0), (31, 0.5, CELL)] {
            let crown = Crown::of(&cube(n, spacing, 0.01));
            assert!(
                (crown.cell - cell).abs() < 1e-6,
                "{n} {spacing}: {}",
                crown.cell
            );
        }
    }

    #[test]
    fn beer_lambert_through_a_uniform_cube() {
        // Density 2 m²/m³; the leaves sit at the cells' centres, so a vertical ray crosses 4
        // cells, 0.6 m.
        let crown = Crown::of(&small_cube(2.0));
        let c = MIN_CELL;
        assert!((crown.leaf_area - 64.0 * 2.0 * c.powi(3)).abs() < 1e-6);
        assert_eq!(crown.dims, [4, 4, 4]);
        assert!(
            (crown.projection - 16.0 * c * c).abs() < 1e-9,
            "{}",
            crown.projection
        );
        let t = crown.transmittance(DVec3::new(0.01, 0.01, 0.0), DVec3::Z);
        let expected = (-G * 2.0 * 4.0 * c).exp();
        assert!((t - expected).abs() < 1e-3, "{t} vs {expected}");
        // A ray that passes beside the crown is not dimmed.
        assert_eq!(
            crown.transmittance(DVec3::new(5.0, 0.0, 0.0), DVec3::Z),
            1.0
        );
        // A denser crown lets less through.
        let dense = Crown::of(&small_cube(4.0));
        assert!(dense.transmittance(DVec3::new(0.01, 0.01, 0.0), DVec3::Z) < t);
    }

    #[test]
    fn a_leafless_tree_passes_all_light() {
        let crown = Crown::of(&Skeleton::default());
        assert_eq!(crown.transmittance(DVec3::ZERO, DVec3::Z), 1.0);
        assert_eq!(crown.leaf_area, 0.0);
    }

    #[test]
    fn a_beam_through_a_uniform_cube_is_stopped_as_beer_lambert_says() {
        // 2 m²/m³ over 0.6 m: optical depth 0.5 x 2 x 0.6 = 0.6 on every level ray through it.
        let crown = Crown::of(&small_cube(2.0));
        let b = crown.beam(DVec3::Y, true);
        let expected = 1.0 - (-0.6f64).exp();
        assert!((b.stopped - expected).abs() < 0.01, "{b:?} vs {expected}");
        // The outline is the cube's 0.6 m x 0.6 m face, to half a cell.
        assert!((b.outline_m2 - 0.36).abs() < 0.1, "{b:?}");
        // Without wood, a bare crown stops nothing.
        assert_eq!(crown.beam(DVec3::Y, false).stopped, 0.0);
    }

    #[test]
    fn wood_stops_light_by_its_silhouette() {
        // The 0.6 m leaf cube with a limb 2 cm thick, 1 m long, laid along y through it, in
        // the middle of the column of cells x -0.075..0.075, z 3.225..3.375.
        let mut tree = small_cube(2.0);
        let section = |y: f32| crate::skeleton::CrossSection {
            position: Vec3::new(0.0, y, 3.3),
            orientation: Quat::IDENTITY,
            radius: 0.01,
            z: 0.0,
        };
        tree.sections = vec![section(-0.5), section(0.5)];
        tree.stems.push(crate::skeleton::Stem {
            level: 1,
            parent: None,
            clone_of: None,
            offset: 0.0,
            length: 1.0,
            sections: 0..2,
            lobes: 0,
            lobe_depth: 0.0,
        });
        let crown = Crown::of(&tree);
        // The leaves' box is the cube, so 0.6 m of the limb, 0.012 m² of its silhouette, lies
        // in the 0.0225 m² column a ray along it crosses.
        let from = DVec3::new(0.0, -5.0, 3.3);
        let bare = crown.optical_depth(from, DVec3::Y, false);
        let expected = G_WOOD * 0.012 / 0.0225;
        assert!((bare / expected - 1.0).abs() < 0.1, "{bare} vs {expected}");
        let leafy = crown.optical_depth(from, DVec3::Y, true);
        assert!((leafy - bare - 0.6).abs() < 0.02, "{leafy} {bare}");
        let b = crown.beam(DVec3::Y, false);
        assert!(
            b.stopped > 0.0 && b.stopped < crown.beam(DVec3::Y, true).stopped,
            "{b:?}"
        );
        // The shade model's transmittance reads the same crown: leaves and wood in leaf, wood
        // alone bare; without its wood the crown passes what its leaves pass.
        let t = crown.transmittance(from, DVec3::Y);
        assert!((t - (-leafy).exp()).abs() < 1e-12, "{t}");
        let t = crown.transmittance_in(from, DVec3::Y, false);
        assert!((t - (-bare).exp()).abs() < 1e-12, "{t}");
        let leaves_only = Crown::with_leaves(&tree, &leaves_of(&tree));
        let t = leaves_only.transmittance(from, DVec3::Y);
        assert!((t - (-0.6f64).exp()).abs() < 0.01, "{t}");
    }
}
