//! A city's run split into independent tasks, so that one machine's threads or a cluster's
//! workers may share it with the same result to the byte:
//!
//! 1. [`CityJob::prepare`] reads and plans the inventory (one process: cheap).
//! 2. Its [`GrowthTask`]s grow the trees the city shares ([`prototypes::grow`]): one task a
//!    species, region and seed variant, a pure function of its fields.
//! 3. [`CityJob::lay_out`] takes their prototypes, packs their impostors' pictures into the
//!    city's atlas, scales every tree and splits each epoch into its quadtree of tiles.
//! 4. Its [`TileTask`]s make the tiles' GLB files ([`tiles::make_tile`]): each task carries
//!    every tree and prototype its tile draws, and is a pure function of them.
//! 5. [`CityJob::finish`] writes the atlas, each epoch's `tileset.json` and the run's
//!    `summary.json` from what the tile tasks report.
//!
//! Tasks and their results cross processes as bytes ([`to_bytes`], [`from_bytes`]: postcard,
//! which keeps every float exact). Who writes the files is the caller's choice: each task
//! returns its files' paths (relative to the run's output folder) and bytes.

use crate::error::CityError;
use crate::inventory::{self, Inventory, Layout};
use crate::report;
use crate::tiles::quadtree::{self, Node};
use crate::tiles::{self, LEAF_TREES, Tile, TileTask, TilesetReport, content};
use crate::trees::benefits::{self, TreeYear};
use crate::trees::cad;
use crate::trees::plan::Summary;
use crate::trees::plan::{self, CityOptions, Kind, Plan, ProtoKey};
use crate::trees::prototypes::{self, GrowthTask, Prototype};
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use std::path::PathBuf;
use sylva::export::SharedMesh;

/// A file of the run's output: its path relative to the output folder, and its bytes.
pub type OutFile = (String, Vec<u8>);

/// The folder the prototypes' files lie in, relative to the output folder.
pub const PROTOTYPES_DIR: &str = "prototypes";

/// A city's run between its stages: its inventory, its plan, and (once grown) its prototypes
/// and tiles.
pub struct CityJob {
    inventory: Inventory,
    plan: Plan,
    options: CityOptions,
    keys: Vec<ProtoKey>,
    prototypes: HashMap<ProtoKey, Prototype>,
    stump: SharedMesh,
    epochs: Vec<EpochTiles>,
    /// The city's atlas of impostors (`atlas::pack`), written with the tilesets.
    atlas: Vec<OutFile>,
}

/// One epoch laid out in tiles.
struct EpochTiles {
    years: u32,
    /// Its tileset's folder, relative to the output folder (`""` or `"year-10/"`).
    dir: String,
    root: Node,
    /// Its tiles (level, x, y), parents before their children: the tile tasks' order.
    order: Vec<(u32, u32, u32)>,
    years_of_trees: Vec<TreeYear>,
}

impl CityJob {
    /// Reads the inventory at `path` (a GeoPackage's `layer`) with `layout` and plans its
    /// trees with `options`.
    pub fn prepare(
        path: &Path,
        layer: Option<&str>,
        layout: &Layout,
        options: &CityOptions,
    ) -> Result<CityJob, CityError> {
        let options = &options.checked()?;
        let inventory = inventory::load(path, layer, layout)?;
        let plan = plan::plan(&inventory, options)?;
        if options.dxf {
            cad::check(&plan)?;
        }
        if let Some(e) = plan.epochs.iter().find(|e| e.trees.is_empty()) {
            return Err(CityError::setting(
                "--years",
                format!("no tree stands {} years on", e.years),
            ));
        }
        let keys: Vec<ProtoKey> = plan
            .epochs
            .iter()
            .flat_map(|e| &e.trees)
            .filter_map(|t| match &t.kind {
                Kind::Tree(k) => Some(k.clone()),
                Kind::Stump => None,
            })
            // Coarse levels draw each class's first variant (`content::tile_glb`).
            .flat_map(|k| [k.first_variant(), k])
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        Ok(CityJob {
            inventory,
            plan,
            options: options.clone(),
            keys,
            prototypes: HashMap::new(),
            atlas: Vec::new(),
            stump: stump_file().0,
            epochs: Vec::new(),
        })
    }

    /// The options it was planned with.
    pub fn options(&self) -> &CityOptions {
        &self.options
    }

    /// The growth tasks, in a stable order.
    pub fn growth_tasks(&self) -> Vec<GrowthTask> {
        prototypes::growth_tasks(&self.keys, self.options.seed)
    }

    /// The grown trees the city shares, once all are grown.
    pub fn prototype_count(&self) -> usize {
        self.keys.len()
    }

    /// Takes prototypes that growth tasks made.
    pub fn add_prototypes(&mut self, grown: impl IntoIterator<Item = Prototype>) {
        self.prototypes
            .extend(grown.into_iter().map(|p| (p.key.clone(), p)));
    }

    /// Scales every tree to its prototype and splits each epoch into tiles; the number of
    /// tile tasks. Every prototype must have been added.
    pub fn lay_out(&mut self) -> Result<usize, CityError> {
        if let Some(k) = self.keys.iter().find(|k| !self.prototypes.contains_key(k)) {
            return Err(CityError::Growth(format!(
                "the grown tree {} is missing: not every growth task's prototypes were added",
                k.file_stem()
            )));
        }
        // The impostors' pictures into the city's atlas (once: packing takes them).
        if self.prototypes.values().any(|p| p.impostor_png.is_some()) {
            let pictures = crate::tiles::atlas::pack(&mut self.prototypes)?.into_iter();
            self.atlas = pictures
                .map(|(name, png)| (format!("{PROTOTYPES_DIR}/{name}"), png))
                .collect();
        }
        // Each tree scaled to its height.
        for e in &mut self.plan.epochs {
            for t in &mut e.trees {
                if let Kind::Tree(k) = &t.kind {
                    let p = &self.prototypes[k];
                    t.scale = (t.height / p.height.max(0.01)).clamp(0.05, 20.0);
                } else {
                    t.scale = t.dbh / 100.0;
                }
            }
        }
        let single = self.options.years == [0];
        self.epochs = self
            .plan
            .epochs
            .iter()
            .map(|e| {
                let at: Vec<[f64; 2]> = e.trees.iter().map(|t| [t.at.x, t.at.y]).collect();
                let root = quadtree::build(&at, LEAF_TREES);
                let mut nodes = Vec::new();
                root.walk(&mut nodes);
                let order = nodes.iter().map(|n| (n.level, n.x, n.y)).collect();
                EpochTiles {
                    years: e.years,
                    dir: if single {
                        String::new()
                    } else {
                        format!("year-{}/", e.years)
                    },
                    root,
                    order,
                    years_of_trees: benefits::years(
                        &e.trees,
                        &self.plan.measured,
                        &self.prototypes,
                    ),
                }
            })
            .collect();
        Ok(self.tile_count())
    }

    /// Tile tasks in all, once laid out.
    pub fn tile_count(&self) -> usize {
        self.epochs.iter().map(|e| e.order.len()).sum()
    }

    /// Tile task `index` (of [`CityJob::tile_count`]): the epochs' tiles in order, each
    /// epoch's parents before their children.
    pub fn tile_task(&self, index: usize) -> Option<TileTask> {
        let mut i = index;
        for (e, tiles) in self.plan.epochs.iter().zip(&self.epochs) {
            let Some(&(level, x, y)) = tiles.order.get(i) else {
                i -= tiles.order.len();
                continue;
            };
            let node = tiles.root.find(level, x, y)?;
            let uri = if tiles.dir.is_empty() {
                format!("{PROTOTYPES_DIR}/")
            } else {
                format!("../{PROTOTYPES_DIR}/")
            };
            let labels = |row: usize| {
                let t = &self.inventory.trees[row];
                tiles::Labels {
                    id: t.id.clone(),
                    written: t.species.clone(),
                    condition: t.observed.condition.map_or("", |c| c.name()).to_string(),
                }
            };
            return Some(TileTask::new(
                &tiles.dir,
                node,
                &e.trees,
                &tiles.years_of_trees,
                &labels,
                &self.prototypes,
                &self.stump,
                &uri,
            ));
        }
        None
    }

    /// The city's atlas of impostors, each epoch's `tileset.json` from the tiles the tasks
    /// made (in any order), and the run's `summary.json`; the run's account (its seconds left
    /// at zero).
    pub fn finish(&self, tiles: &[Tile]) -> Result<(CityRun, Vec<OutFile>), CityError> {
        let mut files = self.atlas.clone();
        let mut epochs = Vec::new();
        for (e, laid) in self.plan.epochs.iter().zip(&self.epochs) {
            let mine: Vec<Tile> = tiles
                .iter()
                .filter(|t| t.tileset == laid.dir)
                .cloned()
                .collect();
            let tallest = e.trees.iter().map(|t| t.height).fold(1.0f32, f32::max);
            let (json, report): (Vec<u8>, TilesetReport) =
                tiles::tileset_json(&laid.root, &mine, self.plan.frame.to_ecef_matrix(), tallest)?;
            files.push((format!("{}tileset.json", laid.dir), json));
            if self.options.dxf {
                let dxf = cad::planting_plan(&self.inventory, &self.plan, e, &self.prototypes)?;
                files.push((format!("{}{}", laid.dir, cad::PLAN_FILE), dxf));
            }
            epochs.push((
                laid.years,
                laid.dir.clone().into(),
                report,
                e.not_yet_planted,
            ));
        }
        let run = CityRun {
            summary: self.plan.summary.clone(),
            epochs,
            prototypes: self.prototypes.len(),
            prototype_bytes: 0,
            growths: 0,
            from_cache: 0,
            seconds: [0.0; 3],
            origin: self.plan.frame.lon_lat(),
        };
        let text = serde_json::to_vec_pretty(&summary_json(&run))
            .map_err(|e| CityError::write(Path::new("summary.json"), e))?;
        files.push(("summary.json".into(), text));
        if self.options.report {
            let r = report::report(&self.plan, &self.prototypes);
            let json = serde_json::to_vec_pretty(&r.json())
                .map_err(|e| CityError::write(Path::new("report.json"), e))?;
            files.push(("report.json".into(), json));
            files.push(("report.csv".into(), r.csv().into_bytes()));
            files.push(("report.html".into(), r.html().into_bytes()));
        }
        Ok((run, files))
    }
}

/// What a run made.
#[derive(Clone, Debug)]
pub struct CityRun {
    /// What became of every row.
    pub summary: Summary,
    /// Each epoch's years, the folder of its tileset and what it came to, and rows not yet
    /// planted then.
    pub epochs: Vec<(u32, PathBuf, TilesetReport, usize)>,
    /// Trees grown and shared.
    pub prototypes: usize,
    /// Bytes of the shared prototype files.
    pub prototype_bytes: u64,
    /// Growth tasks (a species, region and variant grown through its age classes).
    pub growths: usize,
    /// Of those, the ones whose trees came from the cache of an earlier run.
    pub from_cache: usize,
    /// Seconds spent reading and planning, growing, and writing tiles.
    pub seconds: [f64; 3],
    /// Longitude and latitude of the city's local frame, degrees: where every tileset's root
    /// transform puts east-north-up (0, 0, 0).
    pub origin: (f64, f64),
}

/// What `summary.json` says wrote it (`generator`): a reader (`sylva serve --city`) takes a
/// folder as Sylva's city by this.
pub const SUMMARY_GENERATOR: &str = "Sylva sylva city";

/// The layout of a city's folder and of its `summary.json` (`format`); raised whenever a
/// reader of an older folder would misread it.
pub const SUMMARY_FORMAT: u32 = 1;

/// The summary as JSON (what `summary.json` holds).
pub fn summary_json(run: &CityRun) -> serde_json::Value {
    let s = &run.summary;
    let species: serde_json::Map<String, serde_json::Value> = s
        .species
        .iter()
        .map(|(name, line)| {
            let grown: Vec<serde_json::Value> = line
                .grown_as
                .iter()
                .map(|((what, how), n)| serde_json::json!({ "as": what, "how": how.words(), "trees": n }))
                .collect();
            (
                name.clone(),
                serde_json::json!({ "named": format!("{:?}", line.named), "grown": grown }),
            )
        })
        .collect();
    serde_json::json!({
        "generator": SUMMARY_GENERATOR,
        "version": env!("CARGO_PKG_VERSION"),
        "format": SUMMARY_FORMAT,
        "origin": { "longitude": run.origin.0, "latitude": run.origin.1 },
        "rows": s.rows,
        "layout": s.layout,
        "trees": s.trees,
        "stumps": s.stumps,
        "skipped": s.skipped,
        "by_status": s.by_status.iter().map(|(k, v)| (k.words().to_string(), *v)).collect::<std::collections::BTreeMap<_, _>>(),
        "rejected": s.rejected.iter().map(|r| serde_json::json!({ "line": r.line, "reason": r.reason })).collect::<Vec<_>>(),
        "species": species,
        "prototypes": run.prototypes,
        "epochs": run.epochs.iter().map(|(y, dir, r, later)| serde_json::json!({
            "years": y, "tileset": format!("{}tileset.json", dir.display()), "tiles": r.tiles, "depth": r.depth, "trees": r.trees,
            "content_bytes": r.content_bytes, "not_yet_planted": later,
        })).collect::<Vec<_>>(),
    })
}

/// The stump's mesh, and its file.
pub fn stump_file() -> (SharedMesh, OutFile) {
    let (mesh, bytes) = SharedMesh::new(&content::stump_mesh(), "stump.bin");
    (mesh, (format!("{PROTOTYPES_DIR}/stump.bin"), bytes))
}

/// Runs a growth task: its prototypes, and their files (paths relative to the output folder).
pub fn run_growth(task: &GrowthTask) -> Result<(Vec<Prototype>, Vec<OutFile>), CityError> {
    let (grown, files) = prototypes::grow(task)?;
    let files = files
        .into_iter()
        .map(|(name, bytes)| (format!("{PROTOTYPES_DIR}/{name}"), bytes))
        .collect();
    Ok((grown, files))
}

/// Runs a tile task: what its tileset's JSON needs of it, and its GLB file.
pub fn run_tile(task: &TileTask) -> Result<(Tile, OutFile), CityError> {
    let (tile, glb) = tiles::make_tile(task)?;
    let path = format!("{}{}", tile.tileset, tile.uri);
    Ok((tile, (path, glb)))
}

/// A task or its result as bytes, to carry to another process.
pub fn to_bytes<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, CityError> {
    postcard::to_stdvec(value).map_err(|e| CityError::Growth(format!("encoding a task: {e}")))
}

/// A task or its result from [`to_bytes`]' bytes.
pub fn from_bytes<T: serde::de::DeserializeOwned>(bytes: &[u8]) -> Result<T, CityError> {
    postcard::from_bytes(bytes).map_err(|e| {
        CityError::Growth(format!(
            "decoding a task ({} bytes): {e}; were both sides built from the same Sylva?",
            bytes.len()
        ))
    })
}
