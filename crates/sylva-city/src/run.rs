//! The whole job: an inventory file in, a folder of 3D Tiles out (one tileset per epoch), with
//! the summary of what became of every row. The folder is written beside its final place and
//! moved there only when complete, so a failed run leaves no half-written tileset.

use crate::CityError;
use crate::inventory::{self, Layout};
use crate::plan::{self, CityOptions, Kind, Plan, ProtoKey, Summary};
use crate::prototypes::{self, Prototype};
use crate::tiles::{self, TilesetReport, content};
use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use sylva::export::SharedMesh;
use sylva::growth::Database;

/// What a run is doing, for a progress bar: a stage's name, its steps done and its steps.
pub trait Progress: Sync {
    /// Called as the stage moves on.
    fn step(&self, stage: &str, done: usize, total: usize);
}

/// No progress shown.
pub struct Quiet;

impl Progress for Quiet {
    fn step(&self, _: &str, _: usize, _: usize) {}
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
    /// Seconds spent reading and planning, growing, and writing tiles.
    pub seconds: [f64; 3],
}

/// Reads the inventory at `path` (a GeoPackage's `layer`) with `layout`, plans its trees with
/// `options`, grows the trees they share and writes a tileset per epoch into `out`: `out/`
/// itself for the inventory's year alone, else `out/year-<N>/`; the shared meshes in
/// `out/prototypes/`, the summary in `out/summary.json`.
pub fn tile_city(
    path: &Path,
    layer: Option<&str>,
    layout: &Layout,
    options: &CityOptions,
    out: &Path,
    progress: &dyn Progress,
) -> Result<CityRun, CityError> {
    let t0 = std::time::Instant::now();
    prepare_out(out)?;
    let inventory = inventory::load(path, layer, layout)?;
    let mut plan = plan::plan(&inventory, options)?;
    let staging = staging_dir(out);
    let result = write_all(&mut plan, &inventory, options, &staging, progress, t0);
    match result {
        Ok(mut run) => {
            replace(&staging, out)?;
            run.epochs = run
                .epochs
                .into_iter()
                .map(|(y, dir, r, n)| {
                    let rel = dir
                        .strip_prefix(&staging)
                        .map(Path::to_path_buf)
                        .unwrap_or(dir);
                    (y, out.join(rel), r, n)
                })
                .collect();
            Ok(run)
        }
        Err(e) => {
            let _ = std::fs::remove_dir_all(&staging);
            Err(e)
        }
    }
}

fn write_all(
    plan: &mut Plan,
    inventory: &inventory::Inventory,
    options: &CityOptions,
    dir: &Path,
    progress: &dyn Progress,
    t0: std::time::Instant,
) -> Result<CityRun, CityError> {
    let write_err = |p: &Path, e: &dyn std::fmt::Display| CityError::write(p, e);
    std::fs::create_dir_all(dir).map_err(|e| write_err(dir, &e))?;
    let planned = t0.elapsed().as_secs_f64();
    let keys: Vec<ProtoKey> = plan
        .epochs
        .iter()
        .flat_map(|e| &e.trees)
        .filter_map(|t| match &t.kind {
            Kind::Tree(k) => Some(k.clone()),
            Kind::Stump => None,
        })
        // Coarse levels draw each class's first variant (`content::tile_glb`).
        .flat_map(|k| {
            let first = ProtoKey {
                variant: 0,
                ..k.clone()
            };
            [k, first]
        })
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let proto_dir = dir.join("prototypes");
    let total = keys.len();
    progress.step("growing trees", 0, total);
    let protos: HashMap<ProtoKey, Prototype> =
        prototypes::grow_all(&keys, &plan.measured, options.seed, &proto_dir, &|n| {
            progress.step("growing trees", n, total)
        })?;
    let (stump, bytes) = SharedMesh::new(&content::stump_mesh(), "stump.bin");
    let stump_path = proto_dir.join("stump.bin");
    std::fs::create_dir_all(&proto_dir).map_err(|e| write_err(&proto_dir, &e))?;
    sylva::export::write_atomically(&stump_path, &bytes).map_err(|e| write_err(&stump_path, &e))?;
    let grown = t0.elapsed().as_secs_f64();
    // Each tree scaled to its height.
    for e in &mut plan.epochs {
        for t in &mut e.trees {
            if let Kind::Tree(k) = &t.kind {
                let p = &protos[k];
                t.scale = (t.height / p.height.max(0.01)).clamp(0.05, 20.0);
            } else {
                t.scale = t.dbh / 100.0;
            }
        }
    }
    let db = Database::builtin();
    let names = |code: &str, region: &str| {
        db.species()
            .iter()
            .find(|s| s.code == code && s.region == region)
            .map_or((String::new(), String::new()), |s| {
                (s.common.clone(), s.scientific.clone())
            })
    };
    let labels = content::Labels {
        id: &|row| inventory.trees[row].id.clone(),
        written: &|row| inventory.trees[row].species.clone(),
        names: &names,
    };
    let single = options.years == [0];
    let mut epochs = Vec::new();
    for e in &plan.epochs {
        let (edir, uri) = if single {
            (dir.to_path_buf(), "prototypes/".to_string())
        } else {
            (
                dir.join(format!("year-{}", e.years)),
                "../prototypes/".to_string(),
            )
        };
        if e.trees.is_empty() {
            return Err(CityError::setting(
                "--years",
                format!("no tree stands {} years on", e.years),
            ));
        }
        let stage = format!("writing tiles (year {})", e.years);
        let years = crate::benefits::years(&e.trees, &plan.measured, &protos);
        let report = tiles::write(
            &edir,
            &e.trees,
            &years,
            plan.frame.to_ecef_matrix(),
            &protos,
            &stump,
            &uri,
            &labels,
            &|n| progress.step(&stage, n, 0),
        )?;
        epochs.push((e.years, edir, report, e.not_yet_planted));
    }
    let prototype_bytes = std::fs::read_dir(&proto_dir)
        .map_err(|e| write_err(&proto_dir, &e))?
        .filter_map(|f| f.ok()?.metadata().ok())
        .map(|m| m.len())
        .sum();
    let run = CityRun {
        summary: plan.summary.clone(),
        epochs,
        prototypes: protos.len(),
        prototype_bytes,
        seconds: [planned, grown - planned, t0.elapsed().as_secs_f64() - grown],
    };
    let summary_path = dir.join("summary.json");
    let text =
        serde_json::to_vec_pretty(&summary_json(&run)).map_err(|e| write_err(&summary_path, &e))?;
    sylva::export::write_atomically(&summary_path, &text)
        .map_err(|e| write_err(&summary_path, &e))?;
    Ok(run)
}

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
        "rows": s.rows,
        "layout": s.layout,
        "trees": s.trees,
        "stumps": s.stumps,
        "skipped": s.skipped,
        "by_status": s.by_status.iter().map(|(k, v)| (k.words().to_string(), *v)).collect::<std::collections::BTreeMap<_, _>>(),
        "rejected": s.rejected.iter().map(|r| serde_json::json!({ "line": r.line, "reason": r.reason })).collect::<Vec<_>>(),
        "species": species,
        "prototypes": run.prototypes,
        "epochs": run.epochs.iter().map(|(y, _, r, later)| serde_json::json!({
            "years": y, "tiles": r.tiles, "depth": r.depth, "trees": r.trees,
            "content_bytes": r.content_bytes, "not_yet_planted": later,
        })).collect::<Vec<_>>(),
    })
}

/// `out` may be written: it does not exist, or is empty, or holds an earlier run's tiles (its
/// `summary.json` and `tileset.json` or `year-*` folders), which the new run replaces.
fn prepare_out(out: &Path) -> Result<(), CityError> {
    let Ok(entries) = std::fs::read_dir(out) else {
        return Ok(());
    };
    let names: Vec<String> = entries
        .filter_map(|e| Some(e.ok()?.file_name().to_string_lossy().into_owned()))
        .collect();
    let ours = names.iter().any(|n| n == "summary.json") && names.iter().any(|n| n == "prototypes");
    if names.is_empty() || ours {
        return Ok(());
    }
    Err(CityError::setting(
        "-o",
        format!(
            "{} exists and holds other files ({}); give a new or empty folder, or an earlier \
             `sylva city` output to replace",
            out.display(),
            names.iter().take(5).cloned().collect::<Vec<_>>().join(", ")
        ),
    ))
}

fn staging_dir(out: &Path) -> PathBuf {
    let name = out
        .file_name()
        .map_or("tiles".into(), |n| n.to_string_lossy().into_owned());
    out.with_file_name(format!(".{name}.sylva-{}", std::process::id()))
}

/// Moves the finished `staging` folder to `out`, replacing an earlier run there.
fn replace(staging: &Path, out: &Path) -> Result<(), CityError> {
    let err = |e: std::io::Error| CityError::write(out, e);
    if out.exists() {
        std::fs::remove_dir_all(out).map_err(err)?;
    }
    std::fs::rename(staging, out).map_err(err)
}
