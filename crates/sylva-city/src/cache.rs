//! Grown trees kept on disk between runs (issue T): a city's shared trees take nearly all of a
//! run's time (the 143-row NYC census sample: 61-65 s on 2 cores, nearly all of it growing its
//! 81 shared trees), and a second run, or an inventory with a few rows changed, asks for the
//! same ones again.
//!
//! - **Keyed by what makes the tree.** A growth task (species, region, seed variant, the ages
//!   of its classes) and the growth engine's identity ([`ENGINE`], a hash of every source and
//!   data file the growth and the meshing read, made at build time): a tree another engine
//!   grew is never used. Each file also holds its task and engine in full, and is used only if
//!   both match, so a clash of file names costs a growth, never a wrong tree.
//! - **Bounded.** After a run the least recently used files go until the folder is under its
//!   bound.
//! - **Never in the way.** A file that cannot be read, decoded or written is grown again, and
//!   the run goes on.

use crate::tasks::{OutFile, from_bytes, to_bytes};
use crate::trees::prototypes::{GrowthTask, Prototype};
use std::hash::Hasher;
use std::path::{Path, PathBuf};

include!(concat!(env!("OUT_DIR"), "/engine.rs"));

/// What one growth task made: its prototypes and their files.
pub type Grown = (Vec<Prototype>, Vec<OutFile>);

/// A folder of grown trees.
#[derive(Clone, Debug)]
pub struct GrowthCache {
    dir: PathBuf,
    bound: u64,
}

/// What is stored: the key in full, then the result.
#[derive(serde::Serialize, serde::Deserialize)]
struct Entry {
    engine: String,
    task: GrowthTask,
    grown: Vec<u8>,
}

impl GrowthCache {
    /// A cache in `dir` (made when first written) of at most `bound_mib` MiB.
    pub fn new(dir: impl Into<PathBuf>, bound_mib: u64) -> GrowthCache {
        GrowthCache {
            dir: dir.into(),
            bound: bound_mib.saturating_mul(1 << 20),
        }
    }

    /// The user's cache folder for grown trees: `$XDG_CACHE_HOME/sylva/city-trees`, else
    /// `$HOME/.cache/sylva/city-trees`; none where neither is set.
    pub fn default_dir() -> Option<PathBuf> {
        let base = std::env::var_os("XDG_CACHE_HOME")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .or_else(|| {
                std::env::var_os("HOME")
                    .filter(|v| !v.is_empty())
                    .map(|h| Path::new(&h).join(".cache"))
            })?;
        Some(base.join("sylva").join("city-trees"))
    }

    /// Its folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn path(&self, task: &GrowthTask) -> Option<PathBuf> {
        let bytes = to_bytes(task).ok()?;
        let mut h = fnv::FnvHasher::default();
        h.write(ENGINE.as_bytes());
        h.write(&bytes);
        Some(
            self.dir
                .join(format!("{}-{:016x}.tree", task.code, h.finish())),
        )
    }

    /// The trees `task` grew in an earlier run of this engine, if kept.
    pub fn get(&self, task: &GrowthTask) -> Option<Grown> {
        let path = self.path(task)?;
        let bytes = std::fs::read(&path).ok()?;
        let entry: Entry = from_bytes(&bytes).ok()?;
        if entry.engine != ENGINE || &entry.task != task {
            return None;
        }
        let grown = from_bytes(&entry.grown).ok()?;
        // Touched, so that trimming takes the least recently used first.
        let _ = std::fs::File::options()
            .append(true)
            .open(&path)
            .and_then(|f| f.set_modified(std::time::SystemTime::now()));
        Some(grown)
    }

    /// Keeps what `task` grew. A failure to write is not an error: the next run grows it again.
    pub fn put(&self, task: &GrowthTask, grown: &Grown) {
        let (Some(path), Ok(grown)) = (self.path(task), to_bytes(grown)) else {
            return;
        };
        let entry = Entry {
            engine: ENGINE.to_string(),
            task: task.clone(),
            grown,
        };
        if let Ok(bytes) = to_bytes(&entry)
            && std::fs::create_dir_all(&self.dir).is_ok()
        {
            let _ = sylva::export::write_atomically(&path, &bytes);
        }
    }

    /// Removes the least recently used files until the folder holds at most its bound, and
    /// says how many went.
    pub fn trim(&self) -> usize {
        let Ok(entries) = std::fs::read_dir(&self.dir) else {
            return 0;
        };
        let mut files: Vec<(std::time::SystemTime, u64, PathBuf)> = entries
            .flatten()
            .filter(|e| e.path().extension().is_some_and(|x| x == "tree"))
            .filter_map(|e| {
                let m = e.metadata().ok()?;
                Some((m.modified().ok()?, m.len(), e.path()))
            })
            .collect();
        files.sort();
        let mut total: u64 = files.iter().map(|f| f.1).sum();
        let mut removed = 0;
        for (_, len, path) in files {
            if total <= self.bound {
                break;
            }
            if std::fs::remove_file(&path).is_ok() {
                total -= len;
                removed += 1;
            }
        }
        removed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tasks::run_growth;

    fn task(ages: Vec<u32>) -> GrowthTask {
        GrowthTask {
            region: "InlVal".into(),
            code: "LAIN".into(),
            variant: 0,
            ages,
            seed: 0,
        }
    }

    #[test]
    fn a_kept_growth_comes_back_whole_and_a_broken_or_other_one_does_not() {
        let dir = tempfile::tempdir().unwrap();
        let cache = GrowthCache::new(dir.path().join("trees"), 64);
        let young = task(vec![2, 4]);
        assert!(cache.get(&young).is_none(), "nothing kept yet");
        let grown = run_growth(&young).unwrap();
        cache.put(&young, &grown);
        assert_eq!(
            cache.get(&young),
            Some(grown),
            "the same prototypes and files"
        );
        // Another task (an age class more) is not this one's trees.
        assert!(cache.get(&task(vec![2, 4, 6])).is_none());
        // A damaged file is grown again, never read as trees.
        let file = cache.path(&young).unwrap();
        let mut bytes = std::fs::read(&file).unwrap();
        bytes.truncate(bytes.len() / 2);
        std::fs::write(&file, bytes).unwrap();
        assert!(cache.get(&young).is_none());
        // Over its bound, the cache is emptied from the least recently used.
        cache.put(&young, &run_growth(&young).unwrap());
        assert_eq!(GrowthCache::new(cache.dir(), 0).trim(), 1);
        assert!(cache.get(&young).is_none());
    }
}
