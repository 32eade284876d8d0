//! The whole job: an inventory file in, a folder of 3D Tiles out (one tileset per epoch), with
//! the summary of what became of every row. The folder is written beside its final place and
//! moved there only when complete, so a failed run leaves no half-written tileset.

use crate::cache::GrowthCache;
use crate::error::CityError;
use crate::inventory::Layout;
use crate::tasks::{CityJob, CityRun, OutFile, PROTOTYPES_DIR, run_growth, run_tile, stump_file};
use crate::tiles::Tile;
use crate::trees::plan::CityOptions;
use crate::trees::prototypes::Prototype;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

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

/// Reads the inventory at `path` (a GeoPackage's `layer`) with `layout`, plans its trees with
/// `options`, grows the trees they share and writes a tileset per epoch into `out`: `out/`
/// itself for the inventory's year alone, else `out/year-<N>/`; the shared meshes in
/// `out/prototypes/`, the summary in `out/summary.json`. The work is [`crate::tasks`]' tasks,
/// run on this machine's threads.
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
    let mut job = CityJob::prepare(path, layer, layout, options)?;
    let staging = begin(out)?;
    match run_tasks(&mut job, &staging, progress, t0) {
        Ok(mut run) => {
            commit(&staging, out)?;
            for e in &mut run.epochs {
                e.1 = in_output(out, &e.1.to_string_lossy());
            }
            Ok(run)
        }
        Err(e) => {
            let _ = std::fs::remove_dir_all(&staging);
            Err(e)
        }
    }
}

fn run_tasks(
    job: &mut CityJob,
    dir: &Path,
    progress: &dyn Progress,
    t0: std::time::Instant,
) -> Result<CityRun, CityError> {
    let planned = t0.elapsed().as_secs_f64();
    let total = job.prototype_count();
    let grown = std::sync::atomic::AtomicUsize::new(0);
    progress.step("growing trees", 0, total);
    let tasks = job.growth_tasks();
    // The oldest trees first, each thread taking the next task as it comes free: the growth
    // of a city's oldest species can take a fifth of the whole, and started last it would run
    // alone at the end. The results go back into the tasks' own order.
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(tasks[i].ages.last().copied().unwrap_or(0)));
    let cache = (job.options().cache.as_ref()).map(|(dir, mib)| GrowthCache::new(dir, *mib));
    let cached = std::sync::atomic::AtomicUsize::new(0);
    let mut results: Vec<(usize, Vec<Prototype>)> = order
        .into_iter()
        .par_bridge()
        .map(|i| {
            let task = &tasks[i];
            let (prototypes, files) = match cache.as_ref().and_then(|c| c.get(task)) {
                Some(kept) => {
                    cached.fetch_add(1, Ordering::Relaxed);
                    kept
                }
                None => {
                    let grown = run_growth(task)?;
                    if let Some(c) = &cache {
                        c.put(task, &grown);
                    }
                    grown
                }
            };
            write_files(dir, &files)?;
            let n = grown.fetch_add(prototypes.len(), Ordering::Relaxed) + prototypes.len();
            progress.step("growing trees", n, total);
            Ok((i, prototypes))
        })
        .collect::<Result<_, CityError>>()?;
    results.sort_by_key(|(i, _)| *i);
    if let Some(c) = &cache {
        c.trim();
    }
    job.add_prototypes(results.into_iter().flat_map(|(_, p)| p));
    write_files(dir, &[stump_file().1])?;
    let grown_at = t0.elapsed().as_secs_f64();
    let tiles = job.lay_out()?;
    let written = std::sync::atomic::AtomicUsize::new(0);
    let made: Vec<Tile> = (0..tiles)
        .into_par_iter()
        .map(|i| {
            let task = job
                .tile_task(i)
                .ok_or_else(|| CityError::Growth(format!("tile task {i} of {tiles} is missing")))?;
            let (tile, file) = run_tile(&task)?;
            write_files(dir, std::slice::from_ref(&file))?;
            progress.step(
                "writing tiles",
                written.fetch_add(1, Ordering::Relaxed) + 1,
                tiles,
            );
            Ok(tile)
        })
        .collect::<Result<_, CityError>>()?;
    let (mut run, files) = job.finish(&made)?;
    write_files(dir, &files)?;
    let proto_dir = dir.join(PROTOTYPES_DIR);
    run.prototype_bytes = std::fs::read_dir(&proto_dir)
        .map_err(|e| CityError::write(&proto_dir, e))?
        .filter_map(|f| f.ok()?.metadata().ok())
        .map(|m| m.len())
        .sum();
    run.growths = tasks.len();
    run.from_cache = cached.load(Ordering::Relaxed);
    run.seconds = [
        planned,
        grown_at - planned,
        t0.elapsed().as_secs_f64() - grown_at,
    ];
    Ok(run)
}

/// Writes `files` (paths relative to `dir`) into `dir`, each whole or not at all.
pub fn write_files(dir: &Path, files: &[OutFile]) -> Result<(), CityError> {
    for (rel, bytes) in files {
        let path = dir.join(rel);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| CityError::write(parent, e))?;
        }
        sylva::export::write_atomically(&path, bytes).map_err(|e| CityError::write(&path, e))?;
    }
    Ok(())
}

/// A run's folder within `out` (`""` is `out` itself).
fn in_output(out: &Path, rel: &str) -> PathBuf {
    let rel = rel.trim_end_matches('/');
    if rel.is_empty() {
        out.to_path_buf()
    } else {
        out.join(rel)
    }
}

/// Checks that `out` may be written and makes the folder the run is written into beside it
/// (moved to `out` by [`commit`] once complete).
pub fn begin(out: &Path) -> Result<PathBuf, CityError> {
    prepare_out(out)?;
    remove_abandoned(out);
    let staging = staging_dir(out);
    if staging.exists() {
        let _ = std::fs::remove_dir_all(&staging);
    }
    std::fs::create_dir_all(&staging).map_err(|e| CityError::write(&staging, e))?;
    Ok(staging)
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
    staging_for(out, std::process::id())
}

/// The folder a run with process id `pid` writes `out` into: `.NAME.sylva-PID` beside it.
fn staging_for(out: &Path, pid: u32) -> PathBuf {
    let name = out
        .file_name()
        .map_or("tiles".into(), |n| n.to_string_lossy().into_owned());
    out.with_file_name(format!(".{name}.sylva-{pid}"))
}

/// Removes the staging folders that runs writing `out` left when they were killed part-way
/// (`.NAME.sylva-PID` beside it, whose process is gone), and says how many. A folder whose
/// process still runs is another run's, and is left; so is every folder where this system
/// cannot tell (only Linux's `/proc` is asked).
pub fn remove_abandoned(out: &Path) -> usize {
    let Some(parent) = out.parent().map(|p| {
        if p.as_os_str().is_empty() {
            Path::new(".")
        } else {
            p
        }
    }) else {
        return 0;
    };
    let prefix = staging_for(out, 0)
        .file_name()
        .map(|n| n.to_string_lossy().trim_end_matches('0').to_string())
        .unwrap_or_default();
    let Ok(entries) = std::fs::read_dir(parent) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = name
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid != std::process::id()
            && process_gone(pid)
            && std::fs::remove_dir_all(entry.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
}

/// Whether process `pid` is known to be gone.
fn process_gone(pid: u32) -> bool {
    #[cfg(target_os = "linux")]
    {
        Path::new("/proc/self").exists() && !Path::new(&format!("/proc/{pid}")).exists()
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = pid;
        false
    }
}

/// Moves the finished `staging` folder (from [`begin`]) to `out`, replacing an earlier run
/// there.
pub fn commit(staging: &Path, out: &Path) -> Result<(), CityError> {
    let err = |e: std::io::Error| CityError::write(out, e);
    if out.exists() {
        std::fs::remove_dir_all(out).map_err(err)?;
    }
    std::fs::rename(staging, out).map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg(target_os = "linux")]
    fn a_killed_runs_staging_folder_is_removed_by_the_next_and_a_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("tiles");
        // Process ids on Linux stay under 2^22: this one cannot be running.
        let gone = staging_for(&out, 4_194_999);
        // Process 1 always runs.
        let alive = staging_for(&out, 1);
        let other = dir.path().join(".elsewhere.sylva-4194999");
        for d in [&gone, &alive, &other] {
            std::fs::create_dir_all(d.join("prototypes")).unwrap();
        }
        let staging = begin(&out).unwrap();
        assert!(!gone.exists(), "the killed run's folder is gone");
        assert!(
            alive.exists() && other.exists(),
            "a live run's, and another output's, stay"
        );
        assert!(staging.exists());
        assert_eq!(remove_abandoned(&out), 0);
    }
}
