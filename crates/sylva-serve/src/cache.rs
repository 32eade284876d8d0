//! Grown species kept for every age at once, keyed by (region, species, seed, the site whose
//! pruning cuts them), within a memory bound.
//!
//! - **Grown once.** The first request for a key starts its growth on a blocking thread and
//!   leaves a [`Growth`] in the map; every request for the same key, however many arrive
//!   while it grows, waits on that one.
//! - **Shown early.** Ages are published as they are reached: a request for age 5 is answered
//!   when the tree is 5, while it grows on to 50.
//! - **Bounded.** Every entry counts the bytes it holds. When a new growth would take the total
//!   over the bound, the least recently used finished growths are dropped first (a request
//!   that holds one keeps its copy). Growths still running are never dropped: at most
//!   [`Cache::growing_limit`] run at once, and a request past that gets "busy" rather than
//!   waiting behind the others.
//! - **Out of the way.** Growths run in a thread pool of their own, at a lower priority than
//!   everything else (on Linux), so that the threads answering requests, and the meshing of
//!   a tree someone asked for, never queue behind a growth's parallel work.

use crate::grown::{AgeEntry, ages_of, grow_all};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use sylva::growth::Measured;
use tokio::sync::watch;

/// What identifies one growth.
#[derive(Clone, Debug, Hash, PartialEq, Eq)]
pub struct Key {
    /// Region code, as the database spells it.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Seed.
    pub seed: u64,
    /// The built-in site whose pruning regime cuts the tree (its index in
    /// [`crate::grown::sites`]); none: never cut.
    pub pruned: Option<usize>,
}

/// One species growing, or grown, through all its ages.
pub struct Growth {
    /// The species.
    pub measured: Measured,
    /// The ages it will reach, in order.
    pub ages: Vec<u32>,
    entries: Mutex<Vec<Arc<AgeEntry>>>,
    /// How many of `ages` are in `entries`; the sender lives with the growing thread.
    reached: watch::Receiver<usize>,
    bytes: AtomicUsize,
    used: AtomicU64,
}

impl Growth {
    fn entries(&self) -> MutexGuard<'_, Vec<Arc<AgeEntry>>> {
        // A growing thread that panicked leaves a poisoned lock; what it pushed is whole.
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The entry of `age`, once grown. `None` if `age` is not one of [`Growth::ages`] or the
    /// growth stopped before it.
    pub async fn at(&self, age: u32) -> Option<Arc<AgeEntry>> {
        let index = self.ages.iter().position(|&a| a == age)?;
        let mut reached = self.reached.clone();
        // An error means the sender is gone: the growth ended (finished or stopped).
        let _ = reached.wait_for(|&n| n > index).await;
        self.entries().get(index).cloned()
    }

    /// Every age, once all are grown (fewer if the growth stopped).
    pub async fn all(&self) -> Vec<Arc<AgeEntry>> {
        let mut reached = self.reached.clone();
        let total = self.ages.len();
        let _ = reached.wait_for(|&n| n >= total).await;
        self.entries().clone()
    }

    /// Whether every age is grown.
    pub fn finished(&self) -> bool {
        *self.reached.borrow() >= self.ages.len()
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.bytes.load(Ordering::Relaxed)
    }
}

/// Why a growth could not start.
#[derive(Debug, PartialEq)]
pub enum Refused {
    /// As many growths as allowed are running.
    Busy(usize),
}

/// The cache. Cheap to share behind an `Arc`.
pub struct Cache {
    map: Mutex<HashMap<Key, Arc<Growth>>>,
    bound: usize,
    growing_limit: usize,
    clock: AtomicU64,
}

impl Cache {
    /// A cache that holds at most `bound` bytes of finished growths, with at most
    /// `growing_limit` growths running at once.
    pub fn new(bound: usize, growing_limit: usize) -> Cache {
        Cache {
            map: Mutex::new(HashMap::new()),
            bound,
            growing_limit: growing_limit.max(1),
            clock: AtomicU64::new(0),
        }
    }

    /// The memory bound, bytes.
    pub fn bound(&self) -> usize {
        self.bound
    }

    /// Growths allowed to run at once.
    pub fn growing_limit(&self) -> usize {
        self.growing_limit
    }

    fn map(&self) -> MutexGuard<'_, HashMap<Key, Arc<Growth>>> {
        self.map.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Bytes held by every growth, finished or not.
    pub fn bytes(&self) -> usize {
        self.map().values().map(|g| g.bytes()).sum()
    }

    /// Growths held (finished or running).
    pub fn len(&self) -> usize {
        self.map().len()
    }

    /// Growths still running.
    pub fn growing(&self) -> usize {
        self.map().values().filter(|g| !g.finished()).count()
    }

    /// Whether nothing is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The growth of `key`: the one held, or a new one started on a blocking thread of the
    /// current tokio runtime.
    pub fn get(&self, key: Key, measured: &Measured) -> Result<Arc<Growth>, Refused> {
        let now = self.clock.fetch_add(1, Ordering::Relaxed);
        let mut map = self.map();
        if let Some(g) = map.get(&key) {
            g.used.store(now, Ordering::Relaxed);
            return Ok(g.clone());
        }
        let running = map.values().filter(|g| !g.finished()).count();
        if running >= self.growing_limit {
            return Err(Refused::Busy(running));
        }
        // Make room: the least recently used finished growths go first. A new growth's size
        // is not known until it ends, so the bound is kept at each start.
        let mut finished: Vec<(u64, Key, usize)> = map
            .iter()
            .filter(|(_, g)| g.finished())
            .map(|(k, g)| (g.used.load(Ordering::Relaxed), k.clone(), g.bytes()))
            .collect();
        finished.sort_by_key(|(used, _, _)| *used);
        let mut total: usize = map.values().map(|g| g.bytes()).sum();
        for (_, k, bytes) in finished {
            if total <= self.bound {
                break;
            }
            map.remove(&k);
            total -= bytes;
        }
        let (tell, reached) = watch::channel(0usize);
        let growth = Arc::new(Growth {
            measured: measured.clone(),
            ages: ages_of(measured),
            entries: Mutex::new(Vec::new()),
            reached,
            bytes: AtomicUsize::new(0),
            used: AtomicU64::new(now),
        });
        map.insert(key.clone(), growth.clone());
        drop(map);
        let grower = growth.clone();
        // A thread of its own (not the runtime's blocking pool, whose threads later do work
        // for requests), at a lower priority for the whole of its life.
        let started = std::thread::Builder::new()
            .name(format!("sylva-grow-{}", key.code))
            .spawn(move || {
                lower_priority();
                growth_pool().install(|| {
                    grow_all(&grower.measured, key.seed, key.pruned, |entry| {
                        grower.bytes.fetch_add(entry.bytes(), Ordering::Relaxed);
                        let n = {
                            let mut entries = grower.entries();
                            entries.push(Arc::new(entry));
                            entries.len()
                        };
                        tell.send_replace(n);
                        true
                    })
                });
                // Dropping `tell` here wakes anyone still waiting, if the growth ended early.
            });
        if started.is_err() {
            // No thread: `tell` was dropped with the closure, so waiters wake to nothing and
            // the empty growth is dropped at the next start.
            self.map().remove(&key);
        }
        Ok(growth)
    }
}

/// The threads growths run their parallel work on: as many as the machine has cores, all at
/// a lower priority, apart from the global pool that meshes trees for requests.
fn growth_pool() -> &'static rayon::ThreadPool {
    static POOL: std::sync::OnceLock<rayon::ThreadPool> = std::sync::OnceLock::new();
    POOL.get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .thread_name(|i| format!("sylva-growth-{i}"))
            .start_handler(|_| lower_priority())
            .build()
            // Without threads of its own a growth runs on the global pool: slower to share,
            // never wrong.
            .unwrap_or_else(|_| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(1)
                    .build()
                    .expect("a one-thread pool")
            })
    })
}

/// Lowers the calling thread's priority so that the scheduler runs it only on a core nothing
/// else wants: Linux's SCHED_IDLE (a weight of 3 against an ordinary thread's 1024; nice 10
/// still takes one part in ten of a busy core), or failing that nice 19. Requests, their
/// meshing, and a browser on the same machine drawing the page, come first. Elsewhere nothing
/// changes.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: sched_setscheduler reads the parameter we pass and nothing else; pid 0 is the
    // calling thread. gettid and setpriority take plain integers; on Linux a thread id names
    // one thread for PRIO_PROCESS.
    unsafe {
        let idle = libc::sched_param { sched_priority: 0 };
        if libc::sched_setscheduler(0, libc::SCHED_IDLE, &idle) != 0 {
            let tid = libc::syscall(libc::SYS_gettid) as libc::id_t;
            libc::setpriority(libc::PRIO_PROCESS, tid, 19);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::growth::Database;

    fn key(code: &str, seed: u64) -> Key {
        Key {
            region: "InlVal".into(),
            code: code.into(),
            seed,
            pruned: None,
        }
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn one_growth_serves_every_request_and_ages_come_as_grown() {
        let db = Database::builtin();
        let m = db.find("InlVal", "PICH").unwrap();
        let cache = Cache::new(usize::MAX, 2);
        let a = cache.get(key("PICH", 0), &m).unwrap();
        let b = cache.get(key("PICH", 0), &m).unwrap();
        assert!(Arc::ptr_eq(&a, &b), "the same growth is shared");
        let early = a.at(3).await.expect("age 3 is grown");
        assert_eq!(early.record.age, 3.0);
        assert!(a.at(999).await.is_none(), "an age outside the data");
        let all = b.all().await;
        assert_eq!(all.len(), a.ages.len());
        assert!(a.finished());
        assert!(cache.bytes() > 0);
        assert_eq!(cache.len(), 1);
    }

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn running_growths_are_limited_and_old_ones_make_room() {
        let db = Database::builtin();
        let m = db.find("InlVal", "PICH").unwrap();
        // A bound of one byte: every finished growth is over it.
        let cache = Cache::new(1, 1);
        let first = cache.get(key("PICH", 1), &m).unwrap();
        assert_eq!(
            cache.get(key("PICH", 2), &m).err(),
            Some(Refused::Busy(1)),
            "a second growth waits for the first to end"
        );
        first.all().await;
        let second = cache.get(key("PICH", 2), &m).unwrap();
        assert_eq!(cache.len(), 1, "the finished growth made room");
        second.all().await;
        // The dropped growth is still whole for whoever held it.
        assert_eq!(first.all().await.len(), first.ages.len());
    }
}
