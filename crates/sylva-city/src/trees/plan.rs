//! From an inventory's rows to the trees of a city at each epoch: where each stands in the
//! city's local frame, what it is grown as (species, region, age class, seed variant), how it
//! is turned and scaled, and its measured dimensions. Every row is accounted for in the
//! [`Summary`].

use crate::error::CityError;
use crate::geo::{LocalFrame, Projection};
use crate::inventory::regions::nearest;
use crate::inventory::species::{Fallback, Named, Resolved, SpeciesIndex};
use crate::inventory::{Inventory, Position, Rejected, Status};
use glam::DVec3;
use std::collections::{BTreeMap, HashMap};
use sylva::growth::{Database, Measured};

/// How a city is planned.
#[derive(Clone, Debug, PartialEq)]
pub struct CityOptions {
    /// The climate region of every tree; by each tree's nearest reference city if none.
    pub region: Option<String>,
    /// Seed variants grown of each species and age class (trees are shared among them).
    pub variants: u32,
    /// Draw dead trees and stumps as stumps instead of skipping them.
    pub stumps: bool,
    /// Years after the inventory's year at which the city is drawn, one tileset each.
    pub years: Vec<u32>,
    /// The year the inventory describes: trees planted after it (plus an epoch's years) are
    /// not yet in the ground.
    pub base_year: i32,
    /// Ground height above the WGS84 ellipsoid, m, of rows without a ground column.
    pub ground: f64,
    /// Seed of the variants and of each tree's turn.
    pub seed: u64,
    /// Where grown trees are kept between runs, and the most it may hold, MiB
    /// (see `cache.rs`); none: every tree is grown.
    pub cache: Option<(std::path::PathBuf, u64)>,
    /// Also write the city's report (`report.html`, `.csv`, `.json`) beside the tiles.
    pub report: bool,
    /// Also write each epoch's planting plan as DXF (`trees::cad`) beside its tileset.
    pub dxf: bool,
}

impl Default for CityOptions {
    fn default() -> Self {
        CityOptions {
            region: None,
            variants: 2,
            stumps: false,
            years: vec![0],
            base_year: 2026,
            ground: 0.0,
            seed: 0,
            cache: None,
            report: false,
            dxf: false,
        }
    }
}

impl CityOptions {
    /// Most seed variants, epochs, and years on (Sylva's bounds: a run's growth stays some
    /// minutes on a laptop).
    pub const MAX_VARIANTS: u32 = 16;
    pub const MAX_EPOCHS: usize = 20;
    pub const MAX_YEARS: u32 = 200;

    /// The options checked against their bounds, the epochs in rising order, each once.
    pub fn checked(&self) -> Result<CityOptions, CityError> {
        if self.variants == 0 || self.variants > Self::MAX_VARIANTS {
            return Err(CityError::setting(
                "--variants",
                format!("{}: expected 1 to {}", self.variants, Self::MAX_VARIANTS),
            ));
        }
        let mut years = self.years.clone();
        years.sort_unstable();
        years.dedup();
        if years.is_empty()
            || years.len() > Self::MAX_EPOCHS
            || years.iter().any(|&y| y > Self::MAX_YEARS)
        {
            return Err(CityError::setting(
                "--years",
                format!(
                    "{years:?}: expected 1 to {} epochs, each at most {} years on",
                    Self::MAX_EPOCHS,
                    Self::MAX_YEARS
                ),
            ));
        }
        Ok(CityOptions {
            years,
            ..self.clone()
        })
    }
}

/// A grown tree shared by every tree of its species, region, age class and variant.
#[derive(
    Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub struct ProtoKey {
    /// Region whose equations grow it.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Age, years: the age class.
    pub age: u32,
    /// Seed variant.
    pub variant: u32,
}

impl ProtoKey {
    /// The same class's first seed variant: what coarse levels draw (variants differ in
    /// detail a coarse level does not show).
    pub fn first_variant(&self) -> ProtoKey {
        ProtoKey {
            variant: 0,
            ..self.clone()
        }
    }

    /// A name fit for a file: `PLAC-InlVal-30-1`.
    pub fn file_stem(&self) -> String {
        format!(
            "{}-{}-{}-{}",
            self.code, self.region, self.age, self.variant
        )
    }
}

/// What stands at a tree's place.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Kind {
    /// A grown tree.
    Tree(ProtoKey),
    /// A stump (a dead tree or stump, with `--stumps`).
    Stump,
}

/// One tree of the city at one epoch.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Planned {
    /// Its row in the inventory's trees.
    pub row: usize,
    /// Where its base stands in the city's local frame (east, north, up), m.
    pub at: DVec3,
    /// What stands there.
    pub kind: Kind,
    /// Its turn about the vertical, radians.
    pub turn: f32,
    /// Its scale: the height asked for over the grown tree's.
    pub scale: f32,
    /// Age, years since planting.
    pub age: f32,
    /// DBH, cm.
    pub dbh: f32,
    /// Height, m.
    pub height: f32,
    /// Crown diameter, m.
    pub crown_diameter: f32,
}

/// The city at one epoch.
#[derive(Clone, Debug, PartialEq)]
pub struct Epoch {
    /// Years after the inventory's year.
    pub years: u32,
    /// Its trees.
    pub trees: Vec<Planned>,
    /// Rows planted later than it.
    pub not_yet_planted: usize,
}

/// How one species name of the inventory was matched.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeciesLine {
    /// How the name was recognised.
    pub named: Named,
    /// Its trees' fallbacks and what they are grown as (`PLAC in InlVal`), with counts.
    pub grown_as: BTreeMap<(String, Fallback), usize>,
}

/// Every row of an inventory, by what became of it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    /// Rows in the file, readable or not.
    pub rows: usize,
    /// The layout it was read with.
    pub layout: String,
    /// Rows that could not be used, with line and reason.
    pub rejected: Vec<Rejected>,
    /// Readable rows by what they are.
    pub by_status: BTreeMap<Status, usize>,
    /// Rows drawn as grown trees (living trees in the ground at the first epoch).
    pub trees: usize,
    /// Rows drawn as stumps.
    pub stumps: usize,
    /// Rows skipped, by why (dead trees, stumps and planting sites without `--stumps`).
    pub skipped: BTreeMap<String, usize>,
    /// Each species name as written, and how it was matched.
    pub species: BTreeMap<String, SpeciesLine>,
}

/// The age classes trees are grown at, each about a quarter older than the last. A tree is
/// drawn as the class nearest its age, scaled to its own height; the classes are Sylva's
/// choice, so that a crown's form is within some tenth of the tree's age, and a species needs
/// some twelve grown trees per seed variant however many of it a city has.
const AGE_CLASSES: [u32; 15] = [0, 2, 4, 7, 10, 14, 19, 25, 32, 40, 50, 62, 76, 92, 110];

/// The age class of a tree `age` years old whose species' data cover `ages`.
fn age_class(age: f64, ages: (f64, f64)) -> u32 {
    let (first, last) = (
        ages.0.ceil() as u32,
        ages.1.floor().max(ages.0.ceil()) as u32,
    );
    let nearest = AGE_CLASSES
        .iter()
        .copied()
        .chain([first, last])
        .filter(|&c| c >= first && c <= last)
        .min_by(|a, b| {
            (*a as f64 - age)
                .abs()
                .total_cmp(&(*b as f64 - age).abs())
                .then(a.cmp(b))
        })
        .unwrap_or(first);
    nearest.clamp(first, last)
}

/// A number from 0 to 1 that depends only on `id` and `salt`: a tree's turn and variant stay
/// the same however the inventory is sorted or split.
fn unit_hash(id: &str, salt: u64) -> f64 {
    // FNV-1a, 64 bits.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    for b in id.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x100_0000_01b3);
    }
    h ^= h >> 33;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// The city: its frame, its trees at every epoch, and what became of every row.
pub struct Plan {
    /// The city's local frame (at the middle of its trees).
    pub frame: LocalFrame,
    /// The city at each epoch.
    pub epochs: Vec<Epoch>,
    /// What became of every row.
    pub summary: Summary,
    /// The measured functions of every species and region drawn.
    pub measured: HashMap<(String, String), Measured>,
    /// What the surveyors saw of each of the inventory's trees, by row.
    pub observed: Vec<crate::inventory::Observed>,
}

/// Plans the trees of `inventory` (read from a file whose rows were `rows` in all).
pub fn plan(inventory: &Inventory, options: &CityOptions) -> Result<Plan, CityError> {
    let db = Database::builtin();
    if let Some(r) = &options.region
        && !db.regions().iter().any(|x| x.code.eq_ignore_ascii_case(r))
    {
        return Err(CityError::setting(
            "--region",
            format!(
                "`{r}` is no region of the Urban Tree Database; expected one of {}",
                db.regions()
                    .iter()
                    .map(|r| r.code.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    let region_code = |r: &str| {
        db.regions()
            .iter()
            .find(|x| x.code.eq_ignore_ascii_case(r))
            .map_or(r.to_string(), |x| x.code.clone())
    };
    let projection = match inventory.crs {
        Some(code)
            if inventory
                .trees
                .iter()
                .any(|t| matches!(t.position, Position::Projected(..))) =>
        {
            Some(Projection::epsg(code)?)
        }
        _ => None,
    };
    let mut summary = Summary {
        rows: inventory.trees.len() + inventory.rejected.len(),
        layout: inventory.layout.clone(),
        rejected: inventory.rejected.clone(),
        ..Default::default()
    };
    // Every row's place in degrees, or why it has none.
    let mut placed: Vec<Option<(f64, f64)>> = Vec::with_capacity(inventory.trees.len());
    for t in &inventory.trees {
        let p = match t.position {
            Position::LonLat(lon, lat) => Some((lon, lat)),
            Position::Projected(x, y) => projection.as_ref().and_then(|p| p.lon_lat(x, y)),
        };
        if p.is_none() {
            summary.rejected.push(Rejected {
                line: t.line,
                reason: format!(
                    "position {:?} cannot be projected from EPSG:{}",
                    t.position,
                    inventory.crs.unwrap_or(0)
                ),
            });
        }
        placed.push(p);
    }
    summary.rejected.sort_by_key(|r| r.line);
    let usable: Vec<(f64, f64)> = placed.iter().flatten().copied().collect();
    if usable.is_empty() {
        return Err(CityError::setting(
            "inventory",
            format!(
                "no row has a usable position and tree ({} rows, {} rejected)",
                summary.rows,
                summary.rejected.len()
            ),
        ));
    }
    let n = usable.len() as f64;
    let centre = usable
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0 / n, a.1 + p.1 / n));
    let frame = LocalFrame::at(centre.0, centre.1);
    let mut index = SpeciesIndex::new();
    let mut measured: HashMap<(String, String), Measured> = HashMap::new();
    let mut epochs: Vec<Epoch> = options
        .years
        .iter()
        .map(|&years| Epoch {
            years,
            trees: Vec::new(),
            not_yet_planted: 0,
        })
        .collect();
    for (row, (t, place)) in inventory.trees.iter().zip(&placed).enumerate() {
        let Some((lon, lat)) = *place else { continue };
        *summary.by_status.entry(t.status).or_default() += 1;
        let at = frame.of(lon, lat, t.ground.unwrap_or(options.ground));
        let turn = (unit_hash(&t.id, options.seed) * std::f64::consts::TAU) as f32;
        if t.status != Status::Alive {
            let drawn = options.stumps && matches!(t.status, Status::Dead | Status::Stump);
            if drawn {
                summary.stumps += 1;
                let dbh = t.dbh.unwrap_or(30.0) as f32;
                for e in &mut epochs {
                    e.trees.push(Planned {
                        row,
                        at,
                        kind: Kind::Stump,
                        turn,
                        scale: 1.0,
                        age: 0.0,
                        dbh,
                        height: 0.0,
                        crown_diameter: 0.0,
                    });
                }
            } else {
                let why = format!("{} (skipped)", t.status.words());
                *summary.skipped.entry(why).or_default() += 1;
            }
            continue;
        }
        let region = options
            .region
            .as_deref()
            .map_or_else(|| nearest(lon, lat).to_string(), region_code);
        let Some(resolved) = index.resolve(&t.species, &region) else {
            summary.rejected.push(Rejected {
                line: t.line,
                reason: format!("region {region} has no species to grow"),
            });
            continue;
        };
        let line = summary
            .species
            .entry(t.species.clone())
            .or_insert_with(|| SpeciesLine {
                named: resolved.named,
                grown_as: BTreeMap::new(),
            });
        *line
            .grown_as
            .entry((
                format!("{} in {}", resolved.code, resolved.region),
                resolved.fallback.clone(),
            ))
            .or_default() += 1;
        let Resolved { region, code, .. } = resolved;
        let m = match measured.entry((region.clone(), code.clone())) {
            std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(
                db.find(&region, &code)
                    .map_err(|e| CityError::Growth(e.to_string()))?,
            ),
        };
        summary.trees += 1;
        let variant =
            (unit_hash(&t.id, options.seed ^ 0x5eed) * options.variants.max(1) as f64) as u32;
        for e in &mut epochs {
            let year = options.base_year + e.years as i32;
            if t.planted.is_some_and(|p| p > year) {
                e.not_yet_planted += 1;
                continue;
            }
            // Its age: from its DBH; else from its planting year; else a new planting.
            let now = match (t.dbh, t.planted) {
                (Some(d), _) => m.age_at_dbh(d),
                (None, Some(p)) => (options.base_year - p) as f64,
                (None, None) => m.ages.0,
            };
            let age = (now + e.years as f64).clamp(m.ages.0, m.ages.1);
            let class = age_class(age, m.ages);
            // Its own height where the row gives one (at the inventory's year), else the
            // measured height at its age.
            let height = match t.height {
                Some(h) if e.years == 0 => h,
                Some(h) => h * m.height(age) / m.height(now.clamp(m.ages.0, m.ages.1)).max(0.1),
                None => m.height(age),
            };
            e.trees.push(Planned {
                row,
                at,
                kind: Kind::Tree(ProtoKey {
                    region: region.clone(),
                    code: code.clone(),
                    age: class,
                    variant,
                }),
                turn,
                // Filled in once the prototype is grown.
                scale: 1.0,
                age: age as f32,
                dbh: m.dbh(age) as f32,
                height: height as f32,
                crown_diameter: m.crown_diameter(age) as f32,
            });
        }
    }
    summary.rejected.sort_by_key(|r| r.line);
    Ok(Plan {
        frame,
        epochs,
        summary,
        measured,
        observed: inventory.trees.iter().map(|t| t.observed.clone()).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ages_fall_in_their_class_within_the_data() {
        assert_eq!(age_class(0.2, (0.0, 50.0)), 0);
        assert_eq!(age_class(11.9, (0.0, 50.0)), 10);
        assert_eq!(age_class(12.1, (0.0, 50.0)), 14);
        assert_eq!(age_class(47.0, (1.0, 47.3)), 47);
        assert_eq!(age_class(0.0, (2.4, 47.3)), 3);
        let a = unit_hash("tree 1", 0);
        assert!((0.0..1.0).contains(&a));
        assert_eq!(a, unit_hash("tree 1", 0));
        assert_ne!(a, unit_hash("tree 2", 0));
    }
}
