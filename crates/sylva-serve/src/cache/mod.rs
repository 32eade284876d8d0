//! Grown species kept for every age at once, keyed by (region, species, seed, the site whose
//! pruning cuts them), within a memory bound.
//!
//! - **Grown once.** The first request for a key starts its growth on a thread of its own and
//!   leaves a [`Growth`] in the map; every request for the same key, however many arrive
//!   while it grows, waits on that one.
//! - **Shown early.** Ages are published as they are reached: a request for age 5 is answered
//!   when the tree is 5, while it grows on to 50.
//! - **Bounded, at every step.** Each age's entry is counted in a [`Ledger`] from the moment it
//!   is published until the last holder drops it (the cache, or a request still meshing a
//!   tree the cache has let go of), so [`Cache::bytes`] is what is alive, not what the map
//!   holds. A growth starts only if the bytes alive, plus what each running growth is still
//!   expected to add, plus what the new one is expected to take ([`Cache::expected`]), fit
//!   under the bound, once the least recently used finished growths nobody is using are
//!   dropped. Each age is published only if it fits the same way; a growth whose next age
//!   cannot fit (it outgrew what was expected of it while the rest is in use) is stopped and
//!   let go of, and asked again later. So the count never passes the bound: requests that
//!   cannot be served within it are refused ([`Refused`]: 503 and a time to try again, or 507
//!   for a species that alone outgrows the bound), never let through.
//! - **Out of the way.** Growths run in a thread pool of their own, at a lower priority than
//!   everything else (on Linux), so that the threads answering requests, and the meshing of
//!   a tree someone asked for, never queue behind a growth's parallel work.

use crate::grown::{AgeEntry, ages_of, grow_all};
use crate::ledger::{Held, Ledger};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
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

/// One age of a growth, counted in the cache's ledger while anything holds it.
pub type Entry = Arc<Held<AgeEntry>>;

/// One species growing, or grown, through all its ages.
pub struct Growth {
    /// The species.
    pub measured: Measured,
    /// The ages it will reach, in order.
    pub ages: Vec<u32>,
    entries: Mutex<Vec<Entry>>,
    /// How many of `ages` are in `entries`; the sender lives with the growing thread.
    reached: watch::Receiver<usize>,
    /// Bytes of the entries published.
    bytes: AtomicUsize,
    /// Bytes it was expected to take in all when it started.
    expected: usize,
    /// Its thread has ended (every age grown, or stopped).
    ended: AtomicBool,
    /// It was stopped to keep the bound.
    stopped: AtomicBool,
    used: AtomicU64,
}

impl Growth {
    fn entries(&self) -> MutexGuard<'_, Vec<Entry>> {
        // A growing thread that panicked leaves a poisoned lock; what it pushed is whole.
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The entry of `age`, once grown. `None` if `age` is not one of [`Growth::ages`] or the
    /// growth stopped before it ([`Growth::stopped`] says whether to keep the bound).
    pub async fn at(&self, age: u32) -> Option<Entry> {
        let index = self.ages.iter().position(|&a| a == age)?;
        let mut reached = self.reached.clone();
        // An error means the sender is gone: the growth ended (finished or stopped).
        let _ = reached.wait_for(|&n| n > index).await;
        self.entries().get(index).cloned()
    }

    /// Every age, once all are grown (fewer if the growth stopped).
    pub async fn all(&self) -> Vec<Entry> {
        let mut reached = self.reached.clone();
        let total = self.ages.len();
        let _ = reached.wait_for(|&n| n >= total).await;
        self.entries().clone()
    }

    /// Ages reached so far.
    pub fn reached(&self) -> usize {
        *self.reached.borrow()
    }

    /// Whether every age is grown.
    pub fn finished(&self) -> bool {
        self.reached() >= self.ages.len()
    }

    /// Whether it was stopped short to keep the cache's bound.
    pub fn stopped(&self) -> bool {
        self.stopped.load(Ordering::Relaxed)
    }

    /// Bytes of the ages published.
    pub fn bytes(&self) -> usize {
        self.bytes.load(Ordering::Relaxed)
    }

    /// Not yet ended: an age still to publish (its thread ends just after the last).
    fn running(&self) -> bool {
        !self.ended.load(Ordering::Relaxed) && !self.finished()
    }

    /// What the bound must leave it: while it runs, what it is expected to take in all (or
    /// what it has, if more); once ended, what it has.
    fn claim(&self) -> usize {
        if self.running() {
            self.bytes().max(self.expected)
        } else {
            self.bytes()
        }
    }
}

/// Why a growth could not start.
#[derive(Debug, PartialEq)]
pub enum Refused {
    /// As many growths as allowed are running.
    Busy {
        /// Growths running.
        growing: usize,
    },
    /// The trees alive (growing, or held by requests) leave no room under the bound for this
    /// one now; they will.
    Full {
        /// Bytes it is expected to take.
        expected: usize,
        /// Bytes alive, and expected of the growths running.
        committed: usize,
        /// Growths running.
        growing: usize,
    },
    /// This species alone takes more than the whole bound: it can never be held.
    TooLarge {
        /// Bytes it takes (as far as a stopped growth of it showed, at least this).
        expected: usize,
    },
}

/// Growths started and requests refused, by reason, since the server started.
#[derive(Debug, Default)]
pub struct Refusals {
    /// Growths started.
    pub started: AtomicU64,
    /// [`Refused::Busy`].
    pub busy: AtomicU64,
    /// [`Refused::Full`].
    pub full: AtomicU64,
    /// [`Refused::TooLarge`].
    pub too_large: AtomicU64,
    /// Growths stopped short to keep the bound.
    pub stopped: AtomicU64,
    /// Requests answered 503 after waiting the API's limit for their ages.
    pub waited: AtomicU64,
}

/// What the cache holds, as `/api/status` tells it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Holding {
    /// Bytes alive: every age published and not yet dropped by its last holder.
    pub bytes: usize,
    /// Of those, what the cache's growths hold.
    pub held: usize,
    /// Of those, what the cache has let go of and requests still hold.
    pub in_use: usize,
    /// What the running growths are still expected to add.
    pub expected: usize,
    /// Growths held.
    pub growths: usize,
    /// Growths running.
    pub growing: usize,
}

/// What a growth's size is learnt by: its region, species and whether it is pruned (a pruned
/// tree is smaller); seeds differ less, and the sixteenth added to what one took covers them.
type SizeKey = (String, String, bool);

fn size_key(key: &Key) -> SizeKey {
    (key.region.clone(), key.code.clone(), key.pruned.is_some())
}

/// The cache. Cheap to share behind an `Arc`.
pub struct Cache {
    map: Mutex<HashMap<Key, Arc<Growth>>>,
    ledger: Arc<Ledger>,
    bound: usize,
    growing_limit: usize,
    clock: AtomicU64,
    /// What a whole growth of (region, species, pruned) took, once one finished (or at least
    /// took, for one stopped short).
    sizes: Mutex<HashMap<SizeKey, usize>>,
    /// Refusals so far.
    pub refusals: Refusals,
    room_wait: std::time::Duration,
}

/// Bytes a growth is expected to hold per age before one of its species has finished: more
/// than nine in thirteen Modesto species take, grown through all their ages (2.0 MB an age for
/// southern magnolia, 3.4 MB for Modesto ash, 4.9 MB for Chinese hackberry; the ignored test
/// `what_each_species_takes` prints them). The four that take more (Japanese zelkova, Moraine
/// ash, silver maple and holly oak: 5.6 to 6.4 MB) are held to the bound as they grow, like any growth
/// that outgrows what was expected of it. A guess at the most of them all would keep the
/// page's two species (the London plane and Chinese pistache, 64 and 75 ages) from growing at
/// once under the default bound the first time. The species' own size replaces the guess once
/// it has grown.
pub const BYTES_PER_AGE: usize = 5_000_000;

/// How long a growth whose next age does not fit waits for requests to let go of the ages
/// they hold (a GLB meshed, a picture drawn: well under a second each) before it is stopped.
pub const ROOM_WAIT: std::time::Duration = std::time::Duration::from_secs(5);

impl Cache {
    /// A cache whose ages alive never take more than `bound` bytes, with at most
    /// `growing_limit` growths running at once.
    pub fn new(bound: usize, growing_limit: usize) -> Cache {
        Cache {
            map: Mutex::new(HashMap::new()),
            ledger: Arc::new(Ledger::default()),
            bound,
            growing_limit: growing_limit.max(1),
            clock: AtomicU64::new(0),
            sizes: Mutex::new(HashMap::new()),
            refusals: Refusals::default(),
            room_wait: ROOM_WAIT,
        }
    }

    /// How long a growth that outgrew what was expected of it waits for room before it is
    /// stopped ([`ROOM_WAIT`] unless told).
    pub fn room_wait(mut self, wait: std::time::Duration) -> Cache {
        self.room_wait = wait;
        self
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

    /// Bytes alive: every age any growth published that something still holds.
    pub fn bytes(&self) -> usize {
        self.ledger.bytes()
    }

    /// Growths held (finished or running).
    pub fn len(&self) -> usize {
        self.map().len()
    }

    /// Growths still running.
    pub fn growing(&self) -> usize {
        self.map().values().filter(|g| g.running()).count()
    }

    /// Whether nothing is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// What is held, in use and expected, read at one moment.
    pub fn holding(&self) -> Holding {
        self.tally(&self.map())
    }

    fn tally(&self, map: &HashMap<Key, Arc<Growth>>) -> Holding {
        let bytes = self.ledger.bytes();
        let held: usize = map.values().map(|g| g.bytes()).sum();
        let running = map.values().filter(|g| g.running());
        Holding {
            bytes,
            held,
            in_use: bytes.saturating_sub(held),
            expected: running.clone().map(|g| g.claim() - g.bytes()).sum(),
            growths: map.len(),
            growing: running.count(),
        }
    }

    /// Bytes alive plus what the running growths are still expected to add.
    fn committed(&self, map: &HashMap<Key, Arc<Growth>>) -> usize {
        let now = self.tally(map);
        now.bytes + now.expected
    }

    /// Bytes a whole growth of `key` is expected to take: what the species took the last
    /// time it grew whole (pruned or not, as asked: a pruned tree is smaller), else
    /// [`BYTES_PER_AGE`] for each of its ages.
    pub fn expected(&self, key: &Key, m: &Measured) -> usize {
        self.learnt(key)
            .unwrap_or_else(|| BYTES_PER_AGE * ages_of(m).len())
    }

    /// What a whole growth of `key`'s species took, once one has grown (or at least took, for
    /// one stopped short).
    fn learnt(&self, key: &Key) -> Option<usize> {
        self.sizes().get(&size_key(key)).copied()
    }

    fn learn(&self, key: &Key, bytes: usize) {
        self.sizes().insert(size_key(key), bytes);
    }

    fn learn_at_least(&self, key: &Key, bytes: usize) {
        let mut sizes = self.sizes();
        let size = sizes.entry(size_key(key)).or_insert(0);
        *size = (*size).max(bytes);
    }

    fn sizes(&self) -> MutexGuard<'_, HashMap<SizeKey, usize>> {
        self.sizes.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Drops the least recently used finished growths that no request holds until `more`
    /// bytes fit under the bound; whether they do.
    fn make_room(&self, map: &mut HashMap<Key, Arc<Growth>>, more: usize) -> bool {
        if self.committed(map) + more <= self.bound {
            return true;
        }
        let mut idle: Vec<(u64, Key)> = map
            .iter()
            .filter(|(_, g)| !g.running() && Arc::strong_count(g) == 1)
            .map(|(k, g)| (g.used.load(Ordering::Relaxed), k.clone()))
            .collect();
        idle.sort_by_key(|(used, _)| *used);
        for (_, k) in idle {
            // Its entries go with it, but for those a request still holds: those stay
            // counted until the request ends.
            map.remove(&k);
            if self.committed(map) + more <= self.bound {
                return true;
            }
        }
        false
    }

    /// The growth of `key`: the one held, or a new one started on a thread of its own, if it
    /// fits under the bound.
    pub fn get(self: &Arc<Self>, key: Key, measured: &Measured) -> Result<Arc<Growth>, Refused> {
        let now = self.clock.fetch_add(1, Ordering::Relaxed);
        let mut map = self.map();
        if let Some(g) = map.get(&key) {
            g.used.store(now, Ordering::Relaxed);
            return Ok(g.clone());
        }
        let growing = map.values().filter(|g| g.running()).count();
        if growing >= self.growing_limit {
            self.refusals.busy.fetch_add(1, Ordering::Relaxed);
            return Err(Refused::Busy { growing });
        }
        let expected = match self.learnt(&key) {
            Some(took) if took > self.bound => {
                self.refusals.too_large.fetch_add(1, Ordering::Relaxed);
                return Err(Refused::TooLarge { expected: took });
            }
            Some(took) => took,
            None => BYTES_PER_AGE * ages_of(measured).len(),
        };
        // A first guess over the bound is tried at the bound: the growth shows what it takes.
        let expected = expected.min(self.bound);
        if !self.make_room(&mut map, expected) {
            self.refusals.full.fetch_add(1, Ordering::Relaxed);
            return Err(Refused::Full {
                expected,
                committed: self.committed(&map),
                growing,
            });
        }
        let (tell, reached) = watch::channel(0usize);
        let growth = Arc::new(Growth {
            measured: measured.clone(),
            ages: ages_of(measured),
            entries: Mutex::new(Vec::new()),
            reached,
            bytes: AtomicUsize::new(0),
            expected,
            ended: AtomicBool::new(false),
            stopped: AtomicBool::new(false),
            used: AtomicU64::new(now),
        });
        map.insert(key.clone(), growth.clone());
        drop(map);
        self.refusals.started.fetch_add(1, Ordering::Relaxed);
        let cache = self.clone();
        let grower = growth.clone();
        let own = key.clone();
        // A thread of its own (not the runtime's blocking pool, whose threads later do work
        // for requests), at a lower priority for the whole of its life.
        let started = std::thread::Builder::new()
            .name(format!("sylva-grow-{}", key.code))
            .spawn(move || {
                lower_priority();
                // Marks the growth ended however the thread ends, a panic included.
                let _end = Ended {
                    cache: &cache,
                    key: &key,
                    growth: &grower,
                };
                growth_pool().install(|| {
                    grow_all(&grower.measured, key.seed, key.pruned, |entry| {
                        cache.publish(&key, &grower, entry, &tell)
                    })
                });
                // Dropping `tell` here wakes anyone still waiting, if the growth ended early.
            });
        if started.is_err() {
            // No thread: `tell` was dropped with the closure, so waiters wake to nothing.
            growth.ended.store(true, Ordering::Relaxed);
            self.map().remove(&own);
        }
        Ok(growth)
    }

    /// Publishes the next age of `growth`, if it fits under the bound; if not (it outgrew what
    /// was expected of it, and what else is alive is in use), waits up to
    /// [`Cache::room_wait`] for requests to let go, then stops the growth and lets go of it.
    /// Whether to go on.
    fn publish(
        &self,
        key: &Key,
        growth: &Arc<Growth>,
        entry: AgeEntry,
        tell: &watch::Sender<usize>,
    ) -> bool {
        let bytes = entry.bytes();
        let waited = std::time::Instant::now();
        let map = loop {
            let mut map = self.map();
            let more = (growth.bytes() + bytes).max(growth.expected) - growth.claim();
            if self.make_room(&mut map, more) {
                break map;
            }
            // Alone over the bound, it can never fit; else what requests hold is let go of
            // within moments.
            let alone = growth.bytes() + bytes > self.bound;
            if alone || waited.elapsed() >= self.room_wait {
                self.stop(&mut map, key, growth, bytes);
                return false;
            }
            drop(map);
            std::thread::sleep(std::time::Duration::from_millis(50));
        };
        let held = Arc::new(Held::new(entry, bytes, &self.ledger));
        growth.bytes.fetch_add(bytes, Ordering::Relaxed);
        let n = {
            let mut entries = growth.entries();
            entries.push(held);
            entries.len()
        };
        if n == growth.ages.len() {
            // Whole: what it took is what the next growth of its species is expected to
            // take, with a sixteenth to spare (seeds differ a little).
            let bytes = growth.bytes();
            self.learn(key, bytes + bytes / 16);
        }
        drop(map);
        tell.send_replace(n);
        true
    }
}

impl Cache {
    /// Stops `growth`, whose next age of `bytes` cannot fit, and lets go of it.
    fn stop(
        &self,
        map: &mut HashMap<Key, Arc<Growth>>,
        key: &Key,
        growth: &Arc<Growth>,
        bytes: usize,
    ) {
        growth.stopped.store(true, Ordering::Relaxed);
        self.refusals.stopped.fetch_add(1, Ordering::Relaxed);
        // The rest of its ages are at least as large as this one: what it takes in all is
        // at least that, and next time it is expected so.
        let left = growth.ages.len() - growth.reached();
        self.learn_at_least(key, growth.bytes() + bytes * left);
        if map.get(key).is_some_and(|g| Arc::ptr_eq(g, growth)) {
            map.remove(key);
        }
    }
}

/// Ends a growth as its thread ends: one that ended short (stopped, or its thread failed) is
/// let go of, to be grown again when asked.
struct Ended<'a> {
    cache: &'a Cache,
    key: &'a Key,
    growth: &'a Arc<Growth>,
}

impl Drop for Ended<'_> {
    fn drop(&mut self) {
        let mut map = self.cache.map();
        self.growth.ended.store(true, Ordering::Relaxed);
        if !self.growth.finished()
            && map
                .get(self.key)
                .is_some_and(|g| Arc::ptr_eq(g, self.growth))
        {
            map.remove(self.key);
        }
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
mod tests;
