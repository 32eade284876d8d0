//! The leaf shell: a crown drawn as one closed surface, as far out in each direction from the
//! crown's middle as its outer leaves reach, shaded by the light those leaves receive.
//!
//! The coarsest thing the web page draws. A browser that draws WebGL on its CPU pays for every
//! pixel it fills, and a crown of separate leaves (or of separate clumps) fills each pixel of
//! its outline once per layer in front of it, several times over. One outward-facing surface
//! seen from outside fills it about once, with 1,280 triangles whatever the number of leaves.
//! The surface follows the leaves direction by direction, so a lopsided, flat-topped or
//! columnar crown keeps its outline; what it loses is the crown's gaps (it is opaque) and any
//! hollow a ray from the middle would cross twice.

use crate::mesh::{Mesh, luminance};
use crate::skeleton::Leaf;
use glam::Vec3;
use std::sync::OnceLock;

/// Times each face of the icosahedron is split in four: 3 gives 642 directions and 1,280
/// triangles, one direction every 9 degrees (a metre apart on a crown of 7 m radius).
const SPLITS: u32 = 3;

/// The share of a direction's leaves that lie inside the shell: the surface sits at this
/// quantile of their distances from the middle (plus half a blade), so that a few leaves on a
/// long shoot do not pull a spike out of it.
const REACH_QUANTILE: f32 = 0.9;

/// Leaves beyond this share of a direction's reach count as its outer layer, whose light
/// shades the surface there.
const OUTER_LAYER: f32 = 0.7;

/// How far a vertex of the shell is moved in or out, at most, as a share of its reach.
const ROUGHNESS: f32 = 0.07;

/// How much darker the deepest hollow of the shell's skin is drawn than its highest bump.
const HOLLOW_SHADE: f32 = 0.25;

/// Rows and columns of the table that finds a direction's nearest vertex without searching.
const LOOKUP: (usize, usize) = (48, 96);

/// A crown's leaf shell: one closed surface, outward-facing (drawn single-sided), with the
/// luminance classes of the outer leaves as vertex shades. Empty when there are no leaves.
pub fn leaf_shell(leaves: &[Leaf]) -> Mesh {
    let mut mesh = Mesh::default();
    if leaves.is_empty() {
        return mesh;
    }
    let sphere = sphere();
    let centres: Vec<Vec3> = leaves.iter().map(blade_centre).collect();
    let (lo, hi) = centres.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), c| (lo.min(*c), hi.max(*c)),
    );
    let middle = 0.5 * (lo + hi);
    let n = sphere.directions.len();
    // Each leaf's reach from the middle (its blade's centre, plus half a blade) in the
    // direction nearest it.
    let mut reach: Vec<Vec<f32>> = vec![Vec::new(); n];
    let mut bin = Vec::with_capacity(leaves.len());
    for (leaf, c) in leaves.iter().zip(&centres) {
        let d = *c - middle;
        let k = sphere.nearest(d);
        bin.push(k);
        reach[k].push(d.length() + 0.5 * leaf.length);
    }
    let mut radius: Vec<Option<f32>> = reach
        .iter_mut()
        .map(|r| {
            if r.is_empty() {
                return None;
            }
            let at = ((r.len() - 1) as f32 * REACH_QUANTILE).round() as usize;
            Some(*r.select_nth_unstable_by(at, f32::total_cmp).1)
        })
        .collect();
    // The light of each direction's outer layer.
    let mut light = vec![(0.0f32, 0.0f32); n];
    for ((leaf, c), &k) in leaves.iter().zip(&centres).zip(&bin) {
        if let Some(r) = radius[k]
            && (*c - middle).length() + 0.5 * leaf.length >= OUTER_LAYER * r
        {
            let w = leaf.length * leaf.width;
            light[k].0 += w * leaf.light;
            light[k].1 += w;
        }
    }
    let mut shade: Vec<Option<f32>> = light
        .iter()
        .map(|&(sum, w)| (w > 0.0).then(|| sum / w))
        .collect();
    // Directions no leaf lies in (below the crown, towards the trunk) close over from their
    // neighbours.
    let longest = leaves.iter().map(|l| l.length).fold(0.01f32, f32::max);
    let radius = fill_in(&sphere.neighbours, &mut radius, longest);
    let shade = fill_in(&sphere.neighbours, &mut shade, 1.0);
    // One pass of smoothing: a direction between two reaching ones is not a notch.
    let radius: Vec<f32> = (0..n)
        .map(|k| {
            let around = &sphere.neighbours[k];
            let mean =
                around.iter().map(|&j| radius[j as usize]).sum::<f32>() / around.len() as f32;
            0.5 * (radius[k] + mean)
        })
        .collect();
    for (k, u) in sphere.directions.iter().enumerate() {
        // A crown's skin is clumps of leaves, not a smooth hull: each vertex moved a little in
        // or out, and darker where it lies in (as the hollows between clumps are).
        let bump = 2.0 * hash01(k as u32) - 1.0;
        let r = radius[k] * (1.0 + ROUGHNESS * bump);
        mesh.positions.push((middle + r * *u).to_array());
        mesh.uvs.push([0.5, 0.5]);
        mesh.shades
            .push(luminance(shade[k]) * (1.0 - HOLLOW_SHADE * (1.0 - bump) / 2.0));
    }
    mesh.indices
        .extend(sphere.triangles.iter().flatten().copied());
    mesh.normals = vertex_normals(&mesh.positions, &mesh.indices);
    mesh
}

/// A fixed pseudo-random number in 0..1 for a vertex: the same shell every time.
fn hash01(vertex: u32) -> f32 {
    (crate::rng::mix64(u64::from(vertex)) >> 40) as f32 / (1u64 << 24) as f32
}

/// The middle of a leaf's blade (its frame's z runs along the blade from its base).
fn blade_centre(leaf: &Leaf) -> Vec3 {
    leaf.position + leaf.orientation * Vec3::new(0.0, 0.0, 0.5 * leaf.length)
}

/// `values` with every gap filled by the mean of its filled neighbours, repeatedly, until
/// none is left (`otherwise` where nothing at all is known).
fn fill_in(neighbours: &[Vec<u32>], values: &mut [Option<f32>], otherwise: f32) -> Vec<f32> {
    if values.iter().all(Option::is_none) {
        return vec![otherwise; values.len()];
    }
    while values.iter().any(Option::is_none) {
        let known: Vec<Option<f32>> = values.to_vec();
        for (k, v) in values.iter_mut().enumerate() {
            if v.is_some() {
                continue;
            }
            let around: Vec<f32> = neighbours[k]
                .iter()
                .filter_map(|&j| known[j as usize])
                .collect();
            if !around.is_empty() {
                *v = Some(around.iter().sum::<f32>() / around.len() as f32);
            }
        }
    }
    values.iter().map(|v| v.unwrap_or(otherwise)).collect()
}

/// Area-weighted vertex normals of a triangle mesh.
fn vertex_normals(positions: &[[f32; 3]], indices: &[u32]) -> Vec<[f32; 3]> {
    let mut normals = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks(3) {
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(positions[t[k] as usize]));
        let face = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += face;
        }
    }
    normals
        .into_iter()
        .map(|n| n.normalize_or(Vec3::Z).to_array())
        .collect()
}

/// The unit sphere the shell is drawn on: an icosahedron split [`SPLITS`] times, each
/// vertex's neighbours, and a table from latitude and longitude to the nearest vertex.
struct Sphere {
    directions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    neighbours: Vec<Vec<u32>>,
    lookup: Vec<u32>,
}

impl Sphere {
    /// The vertex nearest direction `d` (any length; the middle itself maps to the top).
    fn nearest(&self, d: Vec3) -> usize {
        let u = d.normalize_or(Vec3::Z);
        let (rows, cols) = LOOKUP;
        let row = ((u.z.clamp(-1.0, 1.0).acos() / std::f32::consts::PI * rows as f32) as usize)
            .min(rows - 1);
        let turn = u.y.atan2(u.x) / std::f32::consts::TAU + 0.5;
        let col = ((turn * cols as f32) as usize).min(cols - 1);
        // The table's cell gives a vertex near the cell's middle; its neighbours are tried too,
        // so the answer is the nearest to `u` itself.
        let start = self.lookup[row * cols + col] as usize;
        let mut best = start;
        loop {
            let from = best;
            for &j in &self.neighbours[from] {
                if self.directions[j as usize].dot(u) > self.directions[best].dot(u) {
                    best = j as usize;
                }
            }
            if best == from {
                return best;
            }
        }
    }
}

fn sphere() -> &'static Sphere {
    static SPHERE: OnceLock<Sphere> = OnceLock::new();
    SPHERE.get_or_init(|| {
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let mut directions: Vec<Vec3> = [
            (-1.0, t, 0.0),
            (1.0, t, 0.0),
            (-1.0, -t, 0.0),
            (1.0, -t, 0.0),
            (0.0, -1.0, t),
            (0.0, 1.0, t),
            (0.0, -1.0, -t),
            (0.0, 1.0, -t),
            (t, 0.0, -1.0),
            (t, 0.0, 1.0),
            (-t, 0.0, -1.0),
            (-t, 0.0, 1.0),
        ]
        .into_iter()
        .map(|(x, y, z)| Vec3::new(x, y, z).normalize())
        .collect();
        // Counter-clockwise seen from outside.
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..SPLITS {
            let mut middles = std::collections::HashMap::new();
            let mut middle = |a: u32, b: u32, directions: &mut Vec<Vec3>| -> u32 {
                *middles.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let m = (directions[a as usize] + directions[b as usize]).normalize();
                    directions.push(m);
                    directions.len() as u32 - 1
                })
            };
            let mut split = Vec::with_capacity(4 * triangles.len());
            for [a, b, c] in triangles {
                let ab = middle(a, b, &mut directions);
                let bc = middle(b, c, &mut directions);
                let ca = middle(c, a, &mut directions);
                split.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            triangles = split;
        }
        let mut neighbours = vec![Vec::new(); directions.len()];
        for t in &triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if !neighbours[a as usize].contains(&b) {
                    neighbours[a as usize].push(b);
                    neighbours[b as usize].push(a);
                }
            }
        }
        let (rows, cols) = LOOKUP;
        let lookup = (0..rows * cols)
            .map(|cell| {
                let polar = ((cell / cols) as f32 + 0.5) / rows as f32 * std::f32::consts::PI;
                let turn = ((cell % cols) as f32 + 0.5) / cols as f32 - 0.5;
                let azimuth = turn * std::f32::consts::TAU;
                let u = Vec3::new(
                    polar.sin() * azimuth.cos(),
                    polar.sin() * azimuth.sin(),
                    polar.cos(),
                );
                (0..directions.len())
                    .max_by(|&i, &j| directions[i].dot(u).total_cmp(&directions[j].dot(u)))
                    .unwrap_or(0) as u32
            })
            .collect();
        Sphere {
            directions,
            triangles,
            neighbours,
            lookup,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{LeafShape, StemId};
    use glam::Quat;

    fn leaf(position: Vec3, light: f32) -> Leaf {
        Leaf {
            position,
            orientation: Quat::IDENTITY,
            length: 0.1,
            width: 0.05,
            shape: LeafShape::Oval,
            stem: StemId(0),
            light,
        }
    }

    /// Leaves filling an ellipsoid 8 m wide (x), 4 m deep (y) and 5 m tall, centred 6 m up, lit
    /// from above (the top half in full light, the bottom half in a fifth of it).
    fn crown() -> Vec<Leaf> {
        let mut leaves = vec![];
        let n = 30;
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let u =
                        Vec3::new(i as f32, j as f32, k as f32) / (n - 1) as f32 * 2.0 - Vec3::ONE;
                    if u.length() <= 1.0 {
                        let light = if u.z > 0.0 { 1.0 } else { 0.2 };
                        let p = u * Vec3::new(4.0, 2.0, 2.5) + Vec3::new(0.0, 0.0, 6.0);
                        leaves.push(leaf(p - Vec3::new(0.0, 0.0, 0.05), light));
                    }
                }
            }
        }
        leaves
    }

    #[test]
    fn a_shell_is_one_surface_with_the_crowns_outline() {
        let shell = leaf_shell(&crown());
        assert_eq!(shell.triangle_count(), 1280);
        assert_eq!(shell.shades.len(), shell.positions.len());
        let (lo, hi) = shell.positions.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(Vec3::from(*p)), hi.max(Vec3::from(*p))),
        );
        // Each half-width within a tenth of the crown's (the quantile sits a little inside
        // the outermost leaves, the half blade a little outside).
        for (k, half) in [4.0, 2.0, 2.5].into_iter().enumerate() {
            let centre = [0.0, 0.0, 6.0][k];
            for reach in [hi[k] - centre, centre - lo[k]] {
                assert!((reach / half - 1.0).abs() < 0.12, "axis {k}: {lo} .. {hi}");
            }
        }
    }

    #[test]
    fn a_shell_faces_out_and_is_shaded_by_the_light_its_outer_leaves_got() {
        let shell = leaf_shell(&crown());
        let middle = Vec3::new(0.0, 0.0, 6.0);
        let (mut top, mut bottom) = (vec![], vec![]);
        for ((p, n), s) in shell
            .positions
            .iter()
            .zip(&shell.normals)
            .zip(&shell.shades)
        {
            let (p, n) = (Vec3::from(*p), Vec3::from(*n));
            assert!(n.dot(p - middle) > 0.0, "{p} {n}");
            if p.z > 7.5 {
                top.push(*s);
            }
            if p.z < 4.5 {
                bottom.push(*s);
            }
        }
        let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
        assert!(
            mean(&top) > 0.85 && mean(&bottom) < 0.5,
            "{} {}",
            mean(&top),
            mean(&bottom)
        );
        // Triangles wind outward (counter-clockwise seen from outside), as single-sided
        // drawing needs.
        for t in shell.indices.chunks(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(shell.positions[t[k] as usize]));
            assert!((b - a).cross(c - a).dot(a - middle) > 0.0);
        }
    }

    #[test]
    fn the_nearest_direction_is_found_without_a_search() {
        let s = sphere();
        for i in 0..500 {
            let a = i as f32 * 2.399_963;
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / 500.0;
            let u = Vec3::new(
                (1.0 - z * z).sqrt() * a.cos(),
                (1.0 - z * z).sqrt() * a.sin(),
                z,
            );
            let best = (0..s.directions.len())
                .max_by(|&i, &j| s.directions[i].dot(u).total_cmp(&s.directions[j].dot(u)))
                .unwrap();
            assert!(s.directions[s.nearest(u)].dot(u) >= s.directions[best].dot(u) - 1e-6);
        }
    }

    #[test]
    fn no_leaves_no_shell_and_one_leaf_a_small_one() {
        assert_eq!(leaf_shell(&[]).triangle_count(), 0);
        let one = leaf_shell(&[leaf(Vec3::ZERO, 1.0)]);
        assert_eq!(one.triangle_count(), 1280);
        let r = one
            .positions
            .iter()
            .map(|p| (Vec3::from(*p) - Vec3::new(0.0, 0.0, 0.05)).length())
            .fold(0.0, f32::max);
        assert!(r <= 0.05 * (1.0 + ROUGHNESS) + 1e-4, "{r}");
    }
}
