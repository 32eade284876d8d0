//! `sylva serve`: a local web page on which city planners compare street trees of the Urban
//! Tree Database growing side by side over the years (Rudnick, Linsen & McPherson 2007 build
//! their tool to reach planners "over the web"), with the JSON API under it.
//!
//! - [`assets`]: the page (HTML, JavaScript, three.js) compiled into the binary.
//! - [`api`]: regions, species, sites, a species' growth table, a grown tree as GLB, the
//!   comparison picture, the CSV and the plan symbol. [`params`] checks every parameter.
//! - [`cache`]: each (region, species, seed) grown once for every age, within a memory bound,
//!   counting every age alive in a [`ledger`]; [`grown`] is what one growth holds;
//!   [`pictures`] draws with Sylva's renderer; [`recent`] keeps the last GLB files sent;
//!   [`status`] tells every byte kept against the bound.
//!
//! Growth runs on blocking threads; the async threads only route and copy.
//!
//! ```no_run
//! let options = sylva_serve::Options::default();
//! sylva_serve::run(&options, |url, _cities| println!("open {url}")).unwrap();
//! ```

pub mod api;
pub mod assets;
pub mod cache;
pub mod city;
pub mod grown;
pub mod ledger;
pub mod params;
pub mod pictures;
pub mod recent;
pub mod status;

use axum::Router;
use axum::routing::get;
use std::net::SocketAddr;
use std::sync::Arc;
use sylva::growth::Database;

/// How the server runs.
#[derive(Clone, Debug)]
pub struct Options {
    /// Address to bind: localhost unless told otherwise.
    pub host: String,
    /// Port (0: any free one).
    pub port: u16,
    /// Most bytes kept between requests: grown trees, and the answers kept for asking again
    /// (at most an eighth of it, and [`RECENT_BYTES`]). Never passed: growths that would
    /// pass it wait (503 with a time to ask again), least recently used ones are dropped.
    pub cache_bytes: usize,
    /// Most species growing at once; requests for more get 503 "busy".
    pub growing_limit: usize,
    /// Species grown as the server starts, so that the page's first trees are ready:
    /// (region, species code).
    pub warm: Vec<(String, String)>,
    /// Folders `sylva city` wrote, shown in the page's city view.
    pub cities: Vec<std::path::PathBuf>,
    /// An XYZ tile source drawn under the cities (`{z}`, `{x}`, `{y}` in it).
    pub basemap: Option<String>,
    /// The memory allocator the binary was built with, as `/api/status` names it.
    pub allocator: &'static str,
    /// How long a request waits for the growths it needs before it is answered 503
    /// ([`api::WAIT_LIMIT`]).
    pub wait_limit: std::time::Duration,
}

/// The default memory bound: 1 GiB kept between requests, grown trees (skeletons, packed
/// trees, the opening level's GLBs and accounts of every age) and recent answers (128 MiB).
/// Measured (`sylva-serve`'s ignored test `what_each_species_takes`): Modesto's species take
/// 120 to 450 MB each through all their ages (London plane 206 MB, Chinese pistache 242 MB),
/// so this keeps three to six of them.
pub const DEFAULT_CACHE_BYTES: usize = 1 << 30;

impl Default for Options {
    fn default() -> Self {
        Options {
            host: "127.0.0.1".into(),
            port: 8080,
            cache_bytes: DEFAULT_CACHE_BYTES,
            // The page's four species at once.
            growing_limit: 4,
            // The page opens on Modesto's London plane and Chinese pistache.
            warm: vec![
                ("InlVal".into(), "PLAC".into()),
                ("InlVal".into(), "PICH".into()),
            ],
            cities: Vec::new(),
            basemap: None,
            allocator: "the system's",
            wait_limit: api::WAIT_LIMIT,
        }
    }
}

/// Most bytes of answers (GLB files, growth tables) kept for requests asked again, whatever
/// the bound.
pub const RECENT_BYTES: usize = 128 << 20;

/// The part of a bound of `bound` bytes kept for recent answers: an eighth, at most
/// [`RECENT_BYTES`]; the rest is for grown trees.
pub fn recent_share(bound: usize) -> usize {
    (bound / 8).min(RECENT_BYTES)
}

/// The least `--cache-mib` whose share for grown trees holds `bytes`.
pub fn cache_mib_for(bytes: usize) -> usize {
    // The recent share is an eighth of the bound until it reaches RECENT_BYTES.
    let bound = if bytes >= 7 * RECENT_BYTES {
        bytes + RECENT_BYTES
    } else {
        (bytes * 8).div_ceil(7)
    };
    bound.div_ceil(1 << 20)
}

/// The age the page opens at (`state.age` in `assets/app.js`).
pub const PAGE_AGE: u32 = 20;

/// What the handlers share.
pub struct State {
    /// The growth tables.
    pub db: &'static Database,
    /// Most bytes kept between requests ([`Options::cache_bytes`]): `cache`'s bound and
    /// `recent`'s together.
    pub bound: usize,
    /// The memory allocator, by name.
    pub allocator: &'static str,
    /// [`Options::wait_limit`].
    pub wait_limit: std::time::Duration,
    /// Grown species.
    pub cache: Arc<cache::Cache>,
    /// The renderer for pictures.
    pub pictures: pictures::Pictures,
    /// Answers that never change while the server runs (the region list, each region's
    /// species), made once.
    pub lists: std::sync::Mutex<std::collections::HashMap<String, axum::body::Bytes>>,
    /// The trees last sent as GLB and the growth tables last sent as JSON, so that what is
    /// asked for again (the page's slider going back and forth, several viewers) is not made
    /// again.
    pub recent: recent::Recent,
    /// Turns for work a request does on a blocking thread (meshing a tree, drawing a
    /// picture): one per core.
    pub workers: tokio::sync::Semaphore,
    /// The cities of the city view.
    pub cities: city::Cities,
}

impl State {
    /// A state with the built-in database and no city.
    pub fn new(options: &Options) -> Arc<State> {
        Self::with_cities(options, city::Cities::default())
    }

    /// A state with the built-in database and `cities`.
    pub fn with_cities(options: &Options, cities: city::Cities) -> Arc<State> {
        Arc::new(State {
            db: Database::builtin(),
            bound: options.cache_bytes,
            allocator: options.allocator,
            wait_limit: options.wait_limit,
            cache: Arc::new(cache::Cache::new(
                options.cache_bytes - recent_share(options.cache_bytes),
                options.growing_limit,
            )),
            pictures: pictures::Pictures::default(),
            lists: Default::default(),
            recent: recent::Recent::new(recent_share(options.cache_bytes)),
            workers: tokio::sync::Semaphore::new(
                std::thread::available_parallelism().map_or(2, |n| n.get()),
            ),
            cities,
        })
    }
}

/// The routes: the API under `/api/`, the page's files at every other path they have, 404
/// for the rest.
pub fn router(state: Arc<State>) -> Router {
    Router::new()
        .route("/api/regions", get(api::regions))
        .route("/api/species", get(api::species))
        .route("/api/sites", get(api::site_list))
        .route("/api/items", get(api::items))
        .route("/api/status", get(status::status))
        .route("/api/growth", get(api::growth))
        .route("/api/tree.glb", get(api::tree_glb))
        .route("/api/plan.svg", get(api::plan_svg))
        .route("/api/table.csv", get(api::table_csv))
        .route("/api/compare.png", get(api::compare_png))
        .route("/api/site.png", get(api::site_png))
        .route("/api/cities", get(city::list))
        .route("/city/{name}/{*path}", get(city::file))
        .fallback(assets::serve)
        .with_state(state)
}

/// Why the server could not run.
#[derive(Debug)]
pub struct ServeError(pub String);

impl std::fmt::Display for ServeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ServeError {}

/// Opens the cities, binds, calls `ready` with the page's address and the cities, and serves
/// until Ctrl-C.
pub fn run(options: &Options, ready: impl FnOnce(&str, &city::Cities)) -> Result<(), ServeError> {
    // A city that cannot be opened at all stops the server before it binds; one that is only
    // damaged is listed with its problem.
    let cities = city::Cities::open(&options.cities, options.basemap.clone())?;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| ServeError(format!("cannot start the server's threads: {e}")))?;
    runtime.block_on(async {
        let addr = format!("{}:{}", options.host, options.port);
        let listener = tokio::net::TcpListener::bind(&addr).await.map_err(|e| {
            ServeError(format!(
                "--host {} --port {}: cannot listen there: {e}",
                options.host, options.port
            ))
        })?;
        let bound: SocketAddr = listener
            .local_addr()
            .map_err(|e| ServeError(format!("cannot read the bound address: {e}")))?;
        let state = State::with_cities(options, cities);
        let mut warming = Vec::new();
        for (region, code) in &options.warm {
            if let Ok(m) = state.db.find(region, code) {
                let key = cache::Key {
                    region: m.region.code.clone(),
                    code: m.species.code.clone(),
                    seed: 0,
                    // The page opens at the typical position: a tree no street has cut.
                    pruned: None,
                };
                // A refusal (more warm species than growths allowed) only means it grows
                // when first asked for.
                if let Ok(g) = state.cache.get(key, &m) {
                    warming.push(g);
                }
            }
        }
        // The page is announced once its first trees are grown to the age it opens at (a
        // second or two), so that whoever opens it sees trees at once; they go on growing.
        for g in warming {
            let _ = tokio::time::timeout(std::time::Duration::from_secs(10), g.at(PAGE_AGE)).await;
        }
        let host = if bound.ip().is_unspecified() {
            "127.0.0.1".to_string()
        } else {
            bound.ip().to_string()
        };
        ready(&format!("http://{host}:{}/", bound.port()), &state.cities);
        tokio::spawn(async {
            let mut every = tokio::time::interval(status::GIVE_BACK_EVERY);
            loop {
                every.tick().await;
                // A few milliseconds of walking the heap: off the threads that answer.
                let _ = tokio::task::spawn_blocking(status::give_back_free_memory).await;
            }
        });
        axum::serve(listener, router(state))
            .with_graceful_shutdown(async {
                let _ = tokio::signal::ctrl_c().await;
            })
            .await
            .map_err(|e| ServeError(format!("the server stopped: {e}")))
    })
}
