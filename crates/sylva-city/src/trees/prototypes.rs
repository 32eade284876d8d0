//! The grown trees a city shares: each species, region and seed variant grown once, through
//! its age classes in rising order, and each class meshed at three levels of detail, written
//! once as a binary file that every tile drawing it refers to.

use crate::error::CityError;
use crate::trees::plan::ProtoKey;
use crate::trees::typical::{OnTypicalStreet, on_typical_street};
use std::collections::BTreeMap;
#[cfg(test)]
use std::collections::HashMap;
use sylva::drawing::cad::PlanSymbol;
use sylva::export::{Materials, SharedImpostor, SharedMesh};
use sylva::growth::season::dressed_skeleton;
use sylva::growth::{Grower, GrowthOptions, Measured, measure};
use sylva::lod::bake::bake_on_cpu;
use sylva::lod::impostor::ImpostorFrame;
use sylva::lod::{Choice, LodTree};
use sylva::mesh::{MeshOptions, TreeMesh};
use sylva::street::energy::crown::{Crown, leaves_of};

/// Most triangles of a tree at each level of detail (Sylva's choice): a leaf tile's trees
/// (the nearest) at 10,000, so a leaf tile's 250 trees draw 2.5 million; its parent's at
/// 2,000; every coarser tile's at 400, a trunk, its limbs and the crown's leaf area in some
/// hundred cards, so a city of 10^5 trees seen whole draws some 4 x 10^7.
pub const LOD_TRIANGLES: [usize; 3] = [10_000, 2_000, 400];

/// Height of each view of a prototype's impostor, pixels (Sylva's choice): a far tile's tree
/// is drawn a few to some tens of pixels tall, so 64 rows keep its crown's texture at every
/// range the coarsest level is drawn at, in an atlas of some 35 kB (7 to 58 kB over the
/// 100,000-tree demo's 254).
pub const IMPOSTOR_PIXELS: u32 = 64;

/// The meshes' options: the growth pictures' ring resolution.
const MESH: MeshOptions = MeshOptions {
    quality: 0.6,
    sides: None,
    bark: sylva::mesh::BarkPattern::Smooth,
    young_bark: 1.0,
    twig_copies: false,
};

/// A grown tree, meshed and written.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Prototype {
    /// What it is.
    pub key: ProtoKey,
    /// Its height as grown, m.
    pub height: f32,
    /// Its crown diameter as grown, m.
    pub crown_diameter: f32,
    /// Its materials.
    pub materials: Materials,
    /// Its one-sided leaf area, bark (stem silhouette) area and crown projection, m², as the
    /// street accounts measure them (`sylva::street::energy::crown::Crown`).
    pub surfaces: (f64, f64, f64),
    /// Its levels of detail, most detailed first, each in its own file.
    pub lods: [SharedMesh; 3],
    /// How far each level's surface lies from the whole tree's, m: the one-sided distance from
    /// the whole tree's vertices to the level's (their largest), never less than the level
    /// before's. The coarsest level's is its impostor's, where it has one.
    pub errors: [f32; 3],
    /// Its impostor, drawn in place of the coarsest level (`tiles::content`): baked for each
    /// class's first seed variant, the one coarse levels draw. Its picture lies in the city's
    /// atlas once packed (`atlas::pack`, by `CityJob::lay_out`).
    pub impostor: Option<SharedImpostor>,
    /// Its impostor's picture (PNG) until the city's atlas takes it.
    pub impostor_png: Option<Vec<u8>>,
    /// Its plan symbol (crown outline and trunk from above), for the planting plans.
    pub plan: PlanSymbol,
    /// Its conflicts on a typical narrow street, unpruned (`typical`).
    pub typical_street: OnTypicalStreet,
}

/// One growth task: a species, region and seed variant grown once, its age classes taken on
/// the way up. A pure function of its fields, so any process may run it.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub struct GrowthTask {
    /// Region whose equations grow it.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Seed variant.
    pub variant: u32,
    /// The classes' ages, rising.
    pub ages: Vec<u32>,
    /// The run's seed.
    pub seed: u64,
}

/// The growth tasks that make every prototype of `keys`, in a stable order.
pub fn growth_tasks(keys: &[ProtoKey], seed: u64) -> Vec<GrowthTask> {
    let mut runs: BTreeMap<(String, String, u32), Vec<u32>> = BTreeMap::new();
    for k in keys {
        runs.entry((k.region.clone(), k.code.clone(), k.variant))
            .or_default()
            .push(k.age);
    }
    runs.into_iter()
        .map(|((region, code, variant), mut ages)| {
            ages.sort_unstable();
            ages.dedup();
            GrowthTask {
                region,
                code,
                variant,
                ages,
                seed,
            }
        })
        .collect()
}

/// A prototype's level file: its name (in the run's `prototypes/` folder) and its bytes.
pub type LevelFile = (String, Vec<u8>);

/// Runs `task`: its prototypes, and the files of their levels of detail.
pub fn grow(task: &GrowthTask) -> Result<(Vec<Prototype>, Vec<LevelFile>), CityError> {
    let m = sylva::growth::Database::builtin()
        .find(&task.region, &task.code)
        .map_err(|e| CityError::Growth(e.to_string()))?;
    let options = GrowthOptions {
        seed: task.seed.wrapping_add(task.variant as u64),
        ..Default::default()
    };
    let mut grower = Grower::new(m.clone(), options);
    let mut prototypes = Vec::with_capacity(task.ages.len());
    let mut files = Vec::with_capacity(task.ages.len() * 3);
    for &age in &task.ages {
        grower.advance_to(age as f64);
        let key = ProtoKey {
            region: task.region.clone(),
            code: task.code.clone(),
            age,
            variant: task.variant,
        };
        let (p, levels) = prototype(key, &m, &grower.skeleton());
        prototypes.push(p);
        files.extend(levels);
    }
    Ok((prototypes, files))
}

/// Grows every prototype of `keys` and writes their files into `dir` (for tests), each
/// impostor's picture a file of its own (`SharedImpostor::uri` as grown).
#[cfg(test)]
pub(crate) fn grow_all(
    keys: &[ProtoKey],
    seed: u64,
    dir: &std::path::Path,
) -> Result<HashMap<ProtoKey, Prototype>, CityError> {
    let mut out = HashMap::new();
    for task in growth_tasks(keys, seed) {
        let (prototypes, mut files) = grow(&task)?;
        for p in &prototypes {
            if let (Some(imp), Some(png)) = (&p.impostor, &p.impostor_png) {
                files.push((imp.uri.clone(), png.clone()));
            }
        }
        for (name, bytes) in files {
            let path = dir.join(name);
            std::fs::write(&path, bytes).map_err(|e| CityError::write(&path, e))?;
        }
        out.extend(prototypes.into_iter().map(|p| (p.key.clone(), p)));
    }
    Ok(out)
}

/// One grown tree dressed for summer and meshed at each level: the prototype, and each
/// level's file.
fn prototype(
    key: ProtoKey,
    m: &Measured,
    skeleton: &sylva::Skeleton,
) -> (Prototype, Vec<LevelFile>) {
    let dims = measure(skeleton);
    let crown = Crown::with_leaves(skeleton, &leaves_of(skeleton));
    let dress = m.dress(None);
    let tree = dressed_skeleton(skeleton, dress.state);
    let options = dress.mesh_options(&MESH);
    let lod = LodTree::build(&tree, &options);
    let whole = lod.full_mesh();
    let meshes: Vec<TreeMesh> = LOD_TRIANGLES
        .iter()
        .map(|&budget| lod.engine_mesh(shares_within(&lod, budget)))
        .collect();
    let mut errors = [0.0f32; 3];
    let mut worst = 0.0f32;
    for (k, mesh) in meshes.iter().enumerate() {
        worst = worst.max(distance_to(&whole, mesh));
        errors[k] = worst;
    }
    let mut files = Vec::with_capacity(3);
    let lods = [0, 1, 2].map(|k| {
        let name = format!("{}-L{k}.bin", key.file_stem());
        let (shared, bytes) = SharedMesh::new(&meshes[k], name.clone());
        files.push((name, bytes));
        shared
    });
    // The impostor is baked from the most detailed level: its leaves keep the crown's area
    // and outline at a tenth of the whole tree's triangles.
    let (impostor, impostor_png) = if key.variant == 0 {
        let baked = bake_on_cpu(&meshes[0], &dress.materials(), IMPOSTOR_PIXELS);
        errors[2] = errors[2].max(off_the_quads(&whole, &baked.frame));
        let own = SharedImpostor {
            uri: format!("{}-impostor.png", key.file_stem()),
            frame: baked.frame,
            rect: [0.0, 0.0, 1.0, 1.0],
        };
        (Some(own), Some(baked.png))
    } else {
        (None, None)
    };
    let prototype = Prototype {
        key,
        height: dims.height as f32,
        crown_diameter: dims.crown_diameter as f32,
        materials: dress.materials(),
        surfaces: (crown.leaf_area, crown.bark_area, crown.projection),
        lods,
        errors,
        impostor,
        impostor_png,
        plan: PlanSymbol::of(skeleton),
        typical_street: on_typical_street(skeleton),
    };
    (prototype, files)
}

/// The most of a tree that an engine mesh of at most `budget` triangles draws: twigs and
/// leaves by one share f, the branches by 4f and the trunk by 8f (each at most whole), the
/// largest f that fits, found by bisection; the leaves that remain grow to keep the crown's
/// leaf area. The trunk and limbs go last, as the paper's degradation drops them last.
fn shares_within(lod: &LodTree, budget: usize) -> [f64; 4] {
    let x = |f: f64| -> [f64; 4] {
        let m = |i: usize| lod.lists[i].mass as f64;
        [
            m(0) * (8.0 * f).min(1.0),
            m(1) * (4.0 * f).min(1.0),
            m(2) * f,
            m(3) * f,
        ]
    };
    let triangles = |x: [f64; 4]| {
        lod.primitives(&Choice {
            x: x.map(|v| (v, v)),
            leaf_grow: 1.0,
            outline: None,
            blade_pixels: None,
        })
    };
    if triangles(x(1.0)) <= budget {
        return x(1.0);
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if triangles(x(mid)) <= budget {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    x(lo)
}

/// The largest distance from a vertex of `whole` (at most some 4,000 of them, evenly taken) to
/// the nearest vertex of `part`, m: how far the part's surface is from the whole's.
fn distance_to(whole: &TreeMesh, part: &TreeMesh) -> f32 {
    let targets: Vec<glam::Vec3> = [&part.bark, &part.leaves]
        .iter()
        .flat_map(|m| m.positions.iter().map(|&p| glam::Vec3::from(p)))
        .collect();
    let sources: Vec<glam::Vec3> = [&whole.bark, &whole.leaves]
        .iter()
        .flat_map(|m| m.positions.iter().map(|&p| glam::Vec3::from(p)))
        .collect();
    if targets.is_empty() || sources.is_empty() {
        return 0.0;
    }
    let step = sources.len().div_ceil(4000);
    let grid = Grid::new(&targets);
    sources
        .iter()
        .step_by(step)
        .map(|&p| grid.nearest(p, &targets))
        .fold(0.0, f32::max)
}

/// How far the whole tree's vertices lie from the nearest of the impostor's quads, m (their
/// largest, over a sample as `distance_to` takes it): each quad is a plane through the trunk's
/// axis, so a point r from the axis, at an angle a from the nearest plane, lies r |sin a| from
/// it.
fn off_the_quads(whole: &TreeMesh, frame: &ImpostorFrame) -> f32 {
    let points: Vec<[f32; 3]> = [&whole.bark, &whole.leaves]
        .iter()
        .flat_map(|m| m.positions.iter().copied())
        .collect();
    let step = points.len().div_ceil(4000).max(1);
    // Quads k and k + views/2 lie in one plane (they face away from each other).
    let planes = (frame.views / 2).max(1);
    let spacing = std::f32::consts::PI / planes as f32;
    points
        .iter()
        .step_by(step)
        .map(|p| {
            let r = p[0].hypot(p[1]);
            // The quads' planes, seen from above, lie at azimuths k * spacing from the x axis
            // (view 0 looks from the south, so its quad spans x).
            let a = p[1].atan2(p[0]).rem_euclid(spacing);
            r * a.min(spacing - a).sin()
        })
        .fold(0.0, f32::max)
}

/// Points binned in cubic cells over their box, for nearest-point queries: each cell's points
/// lie together in one list (cells in x, then y, then z order), so a query reads a cell with
/// two array lookups, where a hash map of cells hashed every cell a query looked at.
struct Grid {
    lo: glam::Vec3,
    cell: f32,
    dims: [i64; 3],
    /// Where each cell's points begin in `ids`; one more entry than cells.
    starts: Vec<u32>,
    ids: Vec<u32>,
}

impl Grid {
    /// Most cells along an axis: points strung out along one line still give a grid of
    /// bounded size.
    const MAX_DIM: f32 = 256.0;

    fn new(points: &[glam::Vec3]) -> Self {
        let (lo, hi) = points.iter().fold(
            (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        // About 8 points a cell on average, over the points' box.
        let extent = hi - lo;
        let volume = extent.max(glam::Vec3::splat(0.01)).element_product();
        let cell = (volume * 8.0 / points.len() as f32)
            .cbrt()
            .max(0.02)
            .max(extent.max_element() / Self::MAX_DIM);
        let mut g = Grid {
            lo,
            cell,
            dims: [0; 3],
            starts: Vec::new(),
            ids: vec![0; points.len()],
        };
        let top = g.key(hi);
        g.dims = top.map(|k| k + 1);
        let cells = g.dims.iter().product::<i64>() as usize;
        let index: Vec<usize> = points.iter().map(|&p| g.index(g.key(p))).collect();
        // Counting sort: each cell's count, their running sum, then the points in order.
        let mut starts = vec![0u32; cells + 1];
        for &c in &index {
            starts[c + 1] += 1;
        }
        for c in 0..cells {
            starts[c + 1] += starts[c];
        }
        let mut next = starts.clone();
        for (i, &c) in index.iter().enumerate() {
            g.ids[next[c] as usize] = i as u32;
            next[c] += 1;
        }
        g.starts = starts;
        g
    }

    fn key(&self, p: glam::Vec3) -> [i64; 3] {
        let k = ((p - self.lo) / self.cell).floor();
        [k.x as i64, k.y as i64, k.z as i64]
    }

    fn index(&self, [x, y, z]: [i64; 3]) -> usize {
        ((z * self.dims[1] + y) * self.dims[0] + x) as usize
    }

    /// Distance from `p` to the nearest of `points`: shells of cells around p's, outward,
    /// until the next shell lies farther than the nearest found or past every cell.
    fn nearest(&self, p: glam::Vec3, points: &[glam::Vec3]) -> f32 {
        let c = self.key(p);
        let mut best = f32::INFINITY;
        // The nearest and the farthest shells that meet the grid (a point outside it starts
        // at the grid, not at its own cell).
        let first = (0..3)
            .map(|a| (-c[a]).max(c[a] - (self.dims[a] - 1)).max(0))
            .max()
            .unwrap_or(0);
        let last = (0..3)
            .map(|a| c[a].abs().max((self.dims[a] - 1 - c[a]).abs()))
            .max()
            .unwrap_or(0);
        let scan = |x: i64, y: i64, z: i64, best: &mut f32| {
            let i = self.index([x, y, z]);
            for &id in &self.ids[self.starts[i] as usize..self.starts[i + 1] as usize] {
                *best = best.min(points[id as usize].distance(p));
            }
        };
        // Each axis' cells of shell r that lie in the grid.
        let span = |a: usize, r: i64| (c[a] - r).max(0)..=(c[a] + r).min(self.dims[a] - 1);
        for r in first..=last {
            if (r as f32 - 1.0) * self.cell > best {
                break;
            }
            for z in span(2, r) {
                for y in span(1, r) {
                    if (z - c[2]).abs() == r || (y - c[1]).abs() == r {
                        for x in span(0, r) {
                            scan(x, y, z, &mut best);
                        }
                    } else {
                        // Inside the shell's faces in y and z: only its two x faces.
                        for x in [c[0] - r, c[0] + r] {
                            if (0..self.dims[0]).contains(&x) {
                                scan(x, y, z, &mut best);
                            }
                        }
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_finds_the_nearest_point_as_a_search_of_every_point() {
        let mut rng = sylva::rng::StreamKey::from_seed(3).stream();
        let mut v = |r: f64| rng.var(r) as f32;
        // A crown of clustered points, a line of them and a flat sheet; queries inside, on
        // the edges and far outside their box.
        let clusters: Vec<glam::Vec3> = (0..3000)
            .map(|i| {
                let c = glam::Vec3::new((i % 7) as f32, (i % 5) as f32 * 2.0, 6.0 + (i % 3) as f32);
                c + glam::Vec3::new(v(0.3), v(0.3), v(0.3))
            })
            .collect();
        let line: Vec<glam::Vec3> = (0..500)
            .map(|i| glam::Vec3::new(i as f32 * 0.1, 0.0, 0.0))
            .collect();
        let sheet: Vec<glam::Vec3> = (0..900)
            .map(|i| glam::Vec3::new((i % 30) as f32 * 0.2, (i / 30) as f32 * 0.2, 1.0))
            .collect();
        for points in [clusters, line, sheet] {
            let grid = Grid::new(&points);
            for k in 0..400 {
                let spread = if k % 4 == 0 { 40.0 } else { 8.0 };
                let p = glam::Vec3::new(3.0 + v(spread), 4.0 + v(spread), 5.0 + v(spread));
                let want = points
                    .iter()
                    .map(|q| q.distance(p))
                    .fold(f32::INFINITY, f32::min);
                assert_eq!(grid.nearest(p, &points).to_bits(), want.to_bits(), "{p}");
            }
        }
    }

    #[test]
    fn levels_keep_their_budgets_and_their_errors_grow() {
        let key = ProtoKey {
            region: "InlVal".into(),
            code: "PYCA_B".into(),
            age: 12,
            variant: 0,
        };
        let dir = tempfile::tempdir().unwrap();
        let grown = grow_all(std::slice::from_ref(&key), 0, dir.path()).unwrap();
        let p = &grown[&key];
        for (k, lod) in p.lods.iter().enumerate() {
            assert!(
                lod.triangles() <= LOD_TRIANGLES[k],
                "L{k}: {}",
                lod.triangles()
            );
            assert!(
                lod.triangles() > LOD_TRIANGLES[k] / 4,
                "L{k}: {}",
                lod.triangles()
            );
            let file = dir.path().join(&lod.uri);
            assert_eq!(
                std::fs::metadata(file).unwrap().len() as usize,
                lod.byte_length
            );
        }
        assert!(
            p.errors[0] <= p.errors[1] && p.errors[1] <= p.errors[2],
            "{:?}",
            p.errors
        );
        // The coarsest level misses the crown by some tens of centimetres, never by the tree.
        assert!(
            p.errors[2] > 0.05 && p.errors[2] < p.height * 0.5,
            "{:?}",
            p.errors
        );
        assert!(p.height > 3.0, "{}", p.height);
    }
}
