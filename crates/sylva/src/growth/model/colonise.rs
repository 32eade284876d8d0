//! The buds' environment by space colonisation (Runions et al. 2007, as Palubicki et al. 2009
//! use it): each year marker points are scattered through the space the crown may fill next
//! year, the measured crown's envelope. Markers near wood already there are taken; each free
//! marker belongs to the nearest bud that sees it (within a perception radius, inside a cone
//! about the bud's direction). A bud's exposure is how many markers it owns, its preferred
//! direction the mean direction to them. The crown therefore fills the envelope, and
//! expands as the envelope does, without any branch being told its length.

use super::*;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// Most markers scattered in a year: beyond this they are spaced wider, not made more.
const MAX_MARKERS: usize = 6000;
/// Most the lobes push a grown crown's outline in or out, as a share of its radius.
pub(super) const LOBE_DEPTH: f32 = 0.18;
/// Cosine of the perception cone's half-angle (about 55 degrees).
const PERCEPTION_COS: f32 = 0.57;

/// The space the crown may fill at an age: a solid of revolution about the trunk's axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct Space {
    /// Tree top, m.
    pub top: f32,
    /// Crown base, m.
    pub base: f32,
    /// Widest radius, m.
    pub radius: f32,
    /// Its profile.
    pub envelope: Envelope,
    /// How far the profile has come to its mature form (`Envelope::grown`).
    pub grown: f32,
    /// Phases of the crown's lobes, radians (see `lobe`).
    pub lobes: [f32; 3],
    /// The sine and cosine of the lobes' third phase, their twist with height: worked out
    /// once a space, not once a point (`contains` is asked some 16 times a shoot per fit).
    pub twist: [f32; 2],
    /// How deep they are, a share of the radius.
    pub lobe_depth: f32,
}

impl Space {
    /// Radius of the space at height z, m (never under 15% of the widest: the crown's bottom
    /// and top are rounded, not pointed).
    pub fn reach_at(&self, z: f32) -> f32 {
        let p = (z - self.base) / (self.top - self.base).max(0.1);
        self.radius * self.envelope.relative_radius(p, self.grown).max(0.15)
    }

    /// Whether `p` lies inside (a little under the top, which the leader holds).
    pub fn contains(&self, p: Vec3) -> bool {
        p.z <= self.top - 0.04
            && p.z >= self.base
            && p.truncate().length() <= self.reach_at(p.z) * self.lobe(p)
    }

    /// The crown's outline is not a solid of revolution: limbs of unequal vigour make it
    /// lobed. A factor about 1 (within `lobe_depth`) from two and three lobes around the
    /// axis that twist with height, fixed for a tree by its phases; it averages 1 around
    /// the axis, so the envelope's volume and width stay the measured ones.
    fn lobe(&self, p: Vec3) -> f32 {
        if p.x == 0.0 && p.y == 0.0 {
            return 1.0;
        }
        let azimuth = p.y.atan2(p.x);
        let rel = (p.z - self.base) / (self.top - self.base).max(0.1);
        let [a, b, _] = self.lobes;
        let [twist_sin, twist_cos] = self.twist;
        let wave = 0.6 * (2.0 * azimuth + a + 2.0 * rel * twist_sin).sin()
            + 0.4 * (3.0 * azimuth + b + 3.0 * rel * twist_cos).sin();
        1.0 + self.lobe_depth * wave
    }

    fn volume(&self) -> f32 {
        // Midpoint sum over twenty slices.
        let h = (self.top - self.base).max(0.0);
        (0..20)
            .map(|k| {
                let z = self.base + h * (k as f32 + 0.5) / 20.0;
                PI * self.reach_at(z).powi(2) * h / 20.0
            })
            .sum()
    }
}

/// Points hashed into cubes of one size, for neighbour queries.
struct PointGrid {
    cell: f32,
    /// Keyed by a fast hash: the grid is probed 27 times a point, and nothing iterates the
    /// map, so its order does not reach the tree.
    cells: FxHashMap<(i32, i32, i32), Vec<u32>>,
}

impl PointGrid {
    fn new(cell: f32) -> Self {
        PointGrid {
            cell,
            cells: FxHashMap::default(),
        }
    }

    fn key(&self, p: Vec3) -> (i32, i32, i32) {
        let k = p / self.cell;
        let floor =
            |x: f32| crate::whole::floor_i64(x).clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        (floor(k.x), floor(k.y), floor(k.z))
    }

    fn insert(&mut self, p: Vec3, id: u32) {
        let k = self.key(p);
        self.cells.entry(k).or_default().push(id);
    }

    /// Every id within one cell of `p`'s cell (a superset of those within `cell` of `p`), in
    /// a fixed order.
    fn near(&self, p: Vec3, mut f: impl FnMut(u32)) {
        self.any_near(p, |i| {
            f(i);
            false
        });
    }

    /// Whether `f` holds for any id within one cell of `p`'s cell, asked in `near`'s order
    /// until it does.
    fn any_near(&self, p: Vec3, mut f: impl FnMut(u32) -> bool) -> bool {
        let (x, y, z) = self.key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(ids) = self.cells.get(&(x + dx, y + dy, z + dz))
                        && ids.iter().any(|&i| f(i))
                    {
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// This year's markers and the distances the colonisation works at.
pub(super) struct Markers {
    pub points: Vec<Vec3>,
    /// The occupancy radius: markers this near the wood are taken, m. The perception radius
    /// is four times it.
    pub reach: f32,
    /// Markers a bud must own to count as fully exposed: three for every cube of `reach`'s
    /// side.
    pub saturation: f32,
}

impl Markers {
    /// Markers scattered evenly through `space`, half `reach` apart on average (wider where
    /// `MAX_MARKERS` would be passed, and `reach` with them), then those within `reach` of
    /// any of the `wood` segments (start, end) removed: that space is taken. A sapling's few
    /// buds then still see a space sampled finely enough for most of them to own a marker
    /// or two, where markers one metamer apart left a handful in its whole crown.
    pub fn scatter(space: &Space, reach: f32, rng: &mut Random, wood: &[(Vec3, Vec3)]) -> Markers {
        let volume = space.volume();
        let widest = (volume / MAX_MARKERS as f32).cbrt();
        let spacing = (0.5 * reach).max(widest);
        let reach = reach.max(widest);
        let count = ((volume / spacing.powi(3)) as usize).min(MAX_MARKERS);
        let mut points = Vec::with_capacity(count);
        let r = space.radius;
        // Rejection sampling in the bounding cylinder; a bounded number of tries.
        for _ in 0..count * 4 {
            if points.len() >= count {
                break;
            }
            let p = Vec3::new(
                rng.var(r as f64) as f32,
                rng.var(r as f64) as f32,
                space.base + (space.top - space.base) * rng.unit() as f32,
            );
            if space.contains(p) {
                points.push(p);
            }
        }
        let mut taken = PointGrid::new(reach);
        let mut wood_points = Vec::new();
        for &(a, b) in wood {
            // Points half a reach apart: every point of the segment is then within a
            // quarter reach of one.
            let pieces = crate::whole::pieces(a.distance(b) / (reach * 0.5));
            for k in 0..=pieces {
                let p = a.lerp(b, k as f32 / pieces as f32);
                taken.insert(p, wood_points.len() as u32);
                wood_points.push(p);
            }
        }
        let limit = reach * reach;
        // Taken where any wood point is not farther than the reach (a NaN distance takes it,
        // as it always has).
        // Each marker is looked at on any core; the free ones keep their order.
        let points: Vec<Vec3> = points
            .into_par_iter()
            .filter(|&m| {
                !taken.any_near(m, |i| {
                    let d = wood_points[i as usize].distance_squared(m);
                    d.partial_cmp(&limit) != Some(std::cmp::Ordering::Greater)
                })
            })
            .collect();
        Markers {
            points,
            reach,
            saturation: 3.0 * (reach / spacing).powi(3),
        }
    }

    /// For every bud (position, direction): the markers it owns and the unit direction toward
    /// them (zero if none). A marker belongs to the nearest bud that perceives it.
    pub fn perceive(&self, buds: &[(Vec3, Vec3)]) -> (Vec<u32>, Vec<Vec3>) {
        let radius = self.reach * 4.0;
        let far = radius * radius * 1.001;
        let mut grid = PointGrid::new(radius);
        for (i, (p, _)) in buds.iter().enumerate() {
            grid.insert(*p, i as u32);
        }
        // Each marker's owner is found on any core; the owners' tallies and sums are then
        // made in the markers' order, so the sums come out the same to the bit on any number
        // of cores.
        let owners: Vec<Option<(f32, u32)>> = self
            .points
            .par_iter()
            .map(|&m| {
                let mut best: Option<(f32, u32)> = None;
                grid.near(m, |i| {
                    let (p, d) = buds[i as usize];
                    let to = m - p;
                    // Most buds the grid offers lie beyond the radius: the square, with a margin
                    // for the root's rounding, turns them away before the root is taken.
                    if to.length_squared() > far {
                        return;
                    }
                    let dist = to.length();
                    if dist > radius || dist < 1e-5 || to.dot(d) < PERCEPTION_COS * dist {
                        return;
                    }
                    if best.is_none_or(|(bd, bi)| dist < bd || (dist == bd && i < bi)) {
                        best = Some((dist, i));
                    }
                });
                best
            })
            .collect();
        let mut owned = vec![0u32; buds.len()];
        let mut towards = vec![Vec3::ZERO; buds.len()];
        for (&m, owner) in self.points.iter().zip(owners) {
            if let Some((dist, i)) = owner {
                owned[i as usize] += 1;
                towards[i as usize] += (m - buds[i as usize].0) / dist;
            }
        }
        for t in &mut towards {
            *t = t.normalize_or_zero();
        }
        (owned, towards)
    }
}
