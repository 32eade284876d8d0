//! Forests: where trees stand on a plot, which species and variant each is, and how each copy
//! is turned and scaled ([`plant`], cheap and deterministic), then every variant grown in
//! parallel ([`grow`], [`grow_meshes`]) into a [`Forest`] that exporters and the renderer take.
//!
//! ```
//! use sylva::forest::{ForestSpec, grow_meshes};
//! let spec = ForestSpec {
//!     species: vec!["quaking_aspen".into(), "hazel".into()],
//!     count: 20,
//!     area: [40.0, 40.0],
//!     ..ForestSpec::default()
//! };
//! let forest = grow_meshes(&spec, spec.load_species().unwrap(), &|| {}).unwrap();
//! let glb = forest.to_glb().unwrap();
//! assert_eq!(forest.planting.trees.len(), 20);
//! assert_eq!(&glb[..4], b"glTF");
//! ```

mod file;
mod grow;
mod species;

pub use file::is_forest_file;
pub use grow::{Forest, MAX_FOREST_BYTES, grow, grow_lod, grow_meshes};
pub use species::{ForestSpecies, LOBES_PREFIX};

use crate::rng::StreamKey;
use serde::Deserialize;

/// A forest that cannot be planted or grown. Each message names the file, species or field.
#[derive(Debug, thiserror::Error)]
pub enum ForestError {
    /// A field of the spec out of range.
    #[error("forest: {0}")]
    Spec(String),
    /// A forest file that cannot be read or holds no valid `[forest]` table.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A species that cannot be loaded.
    #[error(transparent)]
    Load(#[from] crate::ParamsError),
    /// A species whose parameters fail validation.
    #[error("species {name}: {cause}")]
    Species {
        /// The species as the spec names it.
        name: String,
        /// Why, told in the message (not chained, or it would be told twice).
        cause: crate::ParamsError,
    },
    /// A variant that cannot be generated (a budget).
    #[error("growing {name} (seed {seed}): {cause}")]
    Grow {
        /// The species' name.
        name: String,
        /// The variant's seed.
        seed: u64,
        /// Why, told in the message.
        cause: crate::GenerateError,
    },
    /// The trees would hold more than [`MAX_FOREST_BYTES`].
    #[error(
        "forest: its {variants} distinct trees would hold more than {:.1} GB (after {grown} \
         trees); use fewer --variants or a lower --quality",
        MAX_FOREST_BYTES as f64 / 1e9
    )]
    Budget {
        /// Distinct trees planted.
        variants: usize,
        /// Trees grown when the budget was passed.
        grown: usize,
    },
}

/// The most trees one forest may hold.
pub const MAX_TREES: u32 = 100_000;
/// The largest side of a plot, metres.
pub const MAX_SIDE: f32 = 100_000.0;

/// What to plant: the `[forest]` table of a forest file, or `sylva forest`'s flags. The
/// default is `sylva forest`'s: 100 trees on 100 x 100 m, 4 variants per species, quality 0.5,
/// and no species (name at least one).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForestSpec {
    /// Species: built-in names or species files, Weber-Penn or lobe species (`lobes:NAME`
    /// where both models have one by that name; see [`ForestSpecies::load`]).
    pub species: Vec<String>,
    /// Number of trees.
    #[serde(default = "default_count")]
    pub count: u32,
    /// Plot size, metres: width along X, depth along Y, centred on the origin.
    #[serde(default = "default_area")]
    pub area: [f32; 2],
    /// Seed of the whole forest.
    #[serde(default)]
    pub seed: u64,
    /// Distinct trees per species, shared by copies turned and scaled at random; 0: every tree
    /// unique.
    #[serde(default = "default_variants")]
    pub variants: u32,
    /// Detail of each tree (leaf count and ring resolution), as `generate --quality`; forests
    /// usually need less than a lone tree, so the default is 0.5.
    #[serde(default = "default_quality")]
    pub quality: f64,
}

fn default_count() -> u32 {
    100
}
fn default_area() -> [f32; 2] {
    [100.0, 100.0]
}
fn default_variants() -> u32 {
    4
}
fn default_quality() -> f64 {
    0.5
}

impl Default for ForestSpec {
    fn default() -> Self {
        Self {
            species: Vec::new(),
            count: default_count(),
            area: default_area(),
            seed: 0,
            variants: default_variants(),
            quality: default_quality(),
        }
    }
}

impl ForestSpec {
    /// Checks the numbers; the message names the field and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        if self.species.is_empty() {
            return Err("species: name at least one species".into());
        }
        if self.count == 0 || self.count > MAX_TREES {
            return Err(format!("count {}: expected 1..={MAX_TREES}", self.count));
        }
        for (name, side) in ["width", "depth"].iter().zip(self.area) {
            if !(side.is_finite() && side > 0.0 && side <= MAX_SIDE) {
                return Err(format!("area {name} {side}: expected 0..{MAX_SIDE} m"));
            }
        }
        if !(self.quality > 0.0 && self.quality <= 4.0) {
            return Err(format!("quality {}: expected 0..4", self.quality));
        }
        Ok(())
    }
}

/// One distinct tree: a species (index into the spec's list) and the seed it grows from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    /// Index into [`ForestSpec::species`].
    pub species: usize,
    /// Generation seed.
    pub seed: u64,
}

/// One copy of a variant on the plot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedTree {
    /// Index into [`Planting::variants`].
    pub variant: usize,
    /// Base of the trunk, metres (Z up).
    pub position: [f32; 3],
    /// Turn about the vertical, radians.
    pub turn: f32,
    /// Uniform scale.
    pub scale: f32,
}

/// A planted forest: the distinct trees to grow and where their copies stand.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Planting {
    /// Trees to grow, in the order their first copy was planted.
    pub variants: Vec<Variant>,
    /// Every tree on the plot.
    pub trees: Vec<PlacedTree>,
}

/// Plants `spec` (assumed valid): positions by dart throwing, then a species, variant, turn
/// and scale per tree, all from the forest's seed.
pub fn plant(spec: &ForestSpec) -> Planting {
    let key = StreamKey::from_seed(spec.seed);
    let count = spec.count as usize;
    let positions = spread(count, (spec.area[0], spec.area[1]), key);
    let species = spec.species.len().max(1);
    let mut rng = key.child(2).stream();
    let mut planting = Planting::default();
    let mut variant_of = std::collections::HashMap::new();
    for (i, p) in positions.iter().enumerate() {
        let s = (rng.unit() * species as f64) as usize % species;
        let v = if spec.variants == 0 {
            i
        } else {
            (rng.unit() * spec.variants as f64) as usize % spec.variants as usize
        };
        let variant = *variant_of.entry((s, v)).or_insert_with(|| {
            planting.variants.push(Variant {
                species: s,
                seed: key.child(3).child(s as u64).child(v as u64).0,
            });
            planting.variants.len() - 1
        });
        let turn = rng.unit() as f32 * std::f32::consts::TAU;
        let scale = 0.85 + 0.3 * rng.unit() as f32;
        planting.trees.push(PlacedTree {
            variant,
            position: [p[0], p[1], 0.0],
            turn,
            scale,
        });
    }
    planting
}

/// Positions on a `w` x `d` plot centred on the origin, kept apart by dart throwing (a few
/// tries each, then accepted anyway so that a crowded plot still gets all its trees).
pub fn spread(count: usize, (w, d): (f32, f32), key: StreamKey) -> Vec<[f32; 2]> {
    let mut rng = key.child(1).stream();
    let spacing = (w * d / count.max(1) as f32).sqrt() * 0.6;
    let mut cells: std::collections::HashMap<(i64, i64), Vec<[f32; 2]>> = Default::default();
    let cell = |p: [f32; 2]| {
        (
            (p[0] / spacing).floor() as i64,
            (p[1] / spacing).floor() as i64,
        )
    };
    let mut points = Vec::with_capacity(count);
    for _ in 0..count {
        let mut best = [0.0, 0.0];
        for _ in 0..12 {
            best = [
                rng.var(w as f64 / 2.0) as f32,
                rng.var(d as f64 / 2.0) as f32,
            ];
            let (cx, cy) = cell(best);
            let crowded = (-1..=1).any(|dx| {
                (-1..=1).any(|dy| {
                    cells.get(&(cx + dx, cy + dy)).is_some_and(|ps| {
                        ps.iter()
                            .any(|q| (q[0] - best[0]).hypot(q[1] - best[1]) < spacing)
                    })
                })
            });
            if !crowded {
                break;
            }
        }
        cells.entry(cell(best)).or_default().push(best);
        points.push(best);
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(count: u32, variants: u32) -> ForestSpec {
        ForestSpec {
            species: vec!["a".into(), "b".into(), "c".into()],
            count,
            area: [100.0, 50.0],
            seed: 3,
            variants,
            quality: 1.0,
        }
    }

    #[test]
    fn spreading_stays_on_the_plot_and_keeps_trees_apart() {
        let pts = spread(200, (100.0, 50.0), StreamKey::from_seed(1));
        assert_eq!(pts.len(), 200);
        assert!(pts.iter().all(|p| p[0].abs() <= 50.0 && p[1].abs() <= 25.0));
        let spacing = (100.0f32 * 50.0 / 200.0).sqrt() * 0.6;
        let close = pts
            .iter()
            .enumerate()
            .flat_map(|(i, a)| {
                pts[i + 1..]
                    .iter()
                    .map(move |b| (a[0] - b[0]).hypot(a[1] - b[1]))
            })
            .filter(|&d| d < spacing * 0.5)
            .count();
        assert!(close < 10, "{close} pairs closer than half the spacing");
    }

    #[test]
    fn variants_are_shared_or_unique_as_asked() {
        let shared = plant(&spec(300, 2));
        assert_eq!(shared.trees.len(), 300);
        assert_eq!(shared.variants.len(), 6, "3 species x 2 variants");
        for s in 0..3 {
            assert_eq!(shared.variants.iter().filter(|v| v.species == s).count(), 2);
        }
        let unique = plant(&spec(50, 0));
        assert_eq!(unique.variants.len(), 50);
        let mut seeds: Vec<u64> = unique.variants.iter().map(|v| v.seed).collect();
        seeds.sort_unstable();
        seeds.dedup();
        assert_eq!(seeds.len(), 50, "every unique tree has its own seed");
        assert_eq!(plant(&spec(300, 2)), shared, "planting is deterministic");
        assert!(
            shared
                .trees
                .iter()
                .all(|t| (0.85..=1.15).contains(&t.scale) && t.variant < 6)
        );
    }

    #[test]
    fn bad_specs_are_named() {
        let mut s = spec(0, 1);
        assert!(s.validate().unwrap_err().contains("count"));
        s.count = 5;
        s.area = [10.0, -1.0];
        assert!(s.validate().unwrap_err().contains("depth"));
        s.area = [10.0, 10.0];
        s.species.clear();
        assert!(s.validate().unwrap_err().contains("species"));
    }
}
