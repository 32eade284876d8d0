//! The JSON API under the page. Every handler checks its parameters first ([`crate::params`]),
//! then reads the cache; growth, meshing and drawing run on blocking threads, never on the
//! async ones, so a request that only reads is never held up by another's growth.

use crate::State;
use crate::cache::{Entry, Growth, Key, Refused};
use crate::grown::{self, AgeEntry, first_conflicts, sites};
use crate::params::{ApiError, Busy, Query};
use axum::Json;
use axum::extract::{Query as AxumQuery, State as AxumState};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use sylva::drawing::{DrawOptions, View, draw_svg};
use sylva::growth::Measured;
use sylva::growth::survey::report::{self, AgeRecord};
use sylva::street::accounts::table;
use sylva::street::picture::site_picture;
use sylva::street::records::{
    ConflictCostRecord, GrowableRecord, PageConflict, PageGrowth, PageRow, RegionLabel,
    RegionRecord, SpeciesLabel, to_json,
};

type Params = AxumQuery<HashMap<String, String>>;
type Reply = Result<Response, ApiError>;

/// `GET /api/regions`: the 17 regions, Modesto's first, with the latitude the page's sun
/// uses and how many species can be grown there.
pub async fn regions(AxumState(state): AxumState<Arc<State>>) -> Response {
    once(&state, "regions", || regions_json(&state))
}

fn regions_json(state: &State) -> serde_json::Value {
    let db = state.db;
    let mut regions: Vec<_> = db.regions().iter().collect();
    // Modesto (the seeds' city) first, the rest as the database lists them.
    regions.sort_by_key(|r| r.code != "InlVal");
    let list: Vec<_> = regions.iter().map(|r| RegionRecord::of(r, db)).collect();
    to_json(&list)
}

/// The account's items (`sylva::street::accounts::items`): each benefit and cost's key,
/// label, unit, colour and who pays, which the page's charts draw from.
pub async fn items(AxumState(state): AxumState<Arc<State>>) -> Response {
    once(&state, "items", || {
        to_json(&sylva::street::accounts::items::all().collect::<Vec<_>>())
    })
}

/// A JSON answer made once and kept.
fn once(state: &State, name: &str, make: impl FnOnce() -> serde_json::Value) -> Response {
    let kept = state
        .lists
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get(name)
        .cloned();
    let bytes = kept.unwrap_or_else(|| {
        let bytes = axum::body::Bytes::from(make().to_string());
        state
            .lists
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .insert(name.to_string(), bytes.clone());
        bytes
    });
    ([(header::CONTENT_TYPE, "application/json")], bytes).into_response()
}

/// `GET /api/species?region=R`: the region's species that can be grown, with the ages their
/// data cover.
pub async fn species(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let region = Query(&q).region(state.db)?;
    Ok(once(&state, &format!("species/{region}"), || {
        species_json(&state, &region)
    }))
}

fn species_json(state: &State, region: &str) -> serde_json::Value {
    let db = state.db;
    let mut list = Vec::new();
    for s in db.growable(region) {
        // growable() has checked the five equations, so find() succeeds.
        let Ok(m) = db.find(region, &s.code) else {
            continue;
        };
        let ages = grown::ages_of(&m);
        let shown = [ages.first().copied(), ages.last().copied()];
        list.push(GrowableRecord::of(&m, shown));
    }
    to_json(&list)
}

/// `GET /api/sites`: the built-in planting sites, as the page draws them (metres; the trunk
/// at the origin, x along the street, y across it towards the buildings).
pub async fn site_list() -> Json<serde_json::Value> {
    let list: Vec<_> = sites()
        .iter()
        .map(|s| serde_json::json!({"key": s.key, "label": s.label, "site": s.site}))
        .collect();
    Json(serde_json::Value::Array(list))
}

/// How long a request waits for the ages it needs before it is answered 503 with a time to
/// ask again: on a busy machine a growth may take minutes, and a page (or any client) waiting
/// on an open request cannot tell a slow server from a hung one.
pub const WAIT_LIMIT: std::time::Duration = std::time::Duration::from_secs(30);

/// When a request stops waiting for growths: [`crate::Options::wait_limit`] (by default
/// [`WAIT_LIMIT`]) after it began, however many species it waits for.
#[derive(Clone, Copy)]
struct Deadline(tokio::time::Instant);

impl Deadline {
    fn new(state: &State) -> Deadline {
        Deadline(tokio::time::Instant::now() + state.wait_limit)
    }
}

/// Seconds a request refused as busy is told to wait before asking again: about the time a
/// small species takes to reach its first ages.
pub const RETRY_SECONDS: u32 = 2;

/// A 503 while `growing` growths run: `message`, then when to ask again (also in the
/// `Retry-After` header).
fn busy(message: String, growing: usize) -> ApiError {
    ApiError::busy(
        format!("{message}; ask again in {RETRY_SECONDS} s"),
        Busy {
            retry_after: RETRY_SECONDS,
            growing,
        },
    )
}

impl State {
    /// The growth of a species, started if need be.
    fn growth(
        &self,
        region: &str,
        m: &Measured,
        seed: u64,
        pruned: Option<usize>,
    ) -> Result<Arc<Growth>, ApiError> {
        let key = Key {
            region: region.to_string(),
            code: m.species.code.clone(),
            seed,
            pruned,
        };
        self.cache.get(key, m).map_err(|r| self.refused(m, r))
    }

    /// The answer to a growth the cache would not start.
    fn refused(&self, m: &Measured, refused: Refused) -> ApiError {
        let mb = |bytes: usize| bytes.div_ceil(1 << 20);
        let bound = mb(self.cache.bound());
        match refused {
            Refused::Busy { growing } => busy(
                format!(
                    "busy: waiting for {growing} growths ({growing} species are growing, the \
                     most at once)"
                ),
                growing,
            ),
            Refused::Full {
                expected,
                committed,
                growing,
            } => busy(
                format!(
                    "busy: waiting for {growing} growths; the trees in memory and growing \
                     ({} MiB) leave no room under the server's bound for grown trees ({bound} \
                     MiB) for {} (about {} MiB) until they finish or their requests end",
                    mb(committed),
                    m.label(),
                    mb(expected)
                ),
                growing,
            ),
            Refused::TooLarge { expected } => ApiError {
                status: StatusCode::INSUFFICIENT_STORAGE,
                parameter: Some("species"),
                message: format!(
                    "{}: its {} ages take about {} MiB, more than this server's whole bound \
                     for grown trees ({bound} MiB): start `sylva serve` with --cache-mib {} \
                     or more to show it",
                    m.label(),
                    grown::ages_of(m).len(),
                    mb(expected),
                    crate::cache_mib_for(expected)
                ),
                allowed: None,
                busy: None,
            },
        }
    }

    /// `wait`, or a 503 once `deadline` has passed (the growth goes on, and the answer comes
    /// when asked again).
    async fn waited<T>(
        &self,
        m: &Measured,
        growth: &Growth,
        deadline: Deadline,
        wait: impl std::future::Future<Output = T>,
    ) -> Result<T, ApiError> {
        let refuse = |message: String| busy(message, self.cache.growing());
        let got = tokio::time::timeout_at(deadline.0, wait)
            .await
            .map_err(|_| {
                self.cache.refusals.waited.fetch_add(1, Ordering::Relaxed);
                refuse(format!(
                    "{}: still growing after {} s ({} of its {} ages grown; waiting for {} \
                 growths)",
                    m.label(),
                    self.wait_limit.as_secs(),
                    growth.reached(),
                    growth.ages.len(),
                    self.cache.growing()
                ))
            })?;
        if growth.stopped() {
            return Err(refuse(format!(
                "{}: its growth was stopped at {} of {} ages to keep the server's memory \
                 bound, and grows again when the trees in use make room",
                m.label(),
                growth.reached(),
                growth.ages.len()
            )));
        }
        Ok(got)
    }

    /// Every age of a species, once grown.
    async fn all(
        &self,
        region: &str,
        m: &Measured,
        seed: u64,
        pruned: Option<usize>,
        deadline: Deadline,
    ) -> Result<Vec<Entry>, ApiError> {
        let growth = self.growth(region, m, seed, pruned)?;
        let entries = self.waited(m, &growth, deadline, growth.all()).await?;
        if entries.len() < growth.ages.len() {
            return Err(ApiError::internal(format!(
                "{}: the growth stopped at {} of {} ages",
                m.label(),
                entries.len(),
                growth.ages.len()
            )));
        }
        Ok(entries)
    }

    /// Each species' entry at `age`.
    async fn at(
        &self,
        region: &str,
        species: &[Measured],
        age: u32,
        seed: u64,
        pruned: Option<usize>,
    ) -> Result<Vec<Entry>, ApiError> {
        let deadline = Deadline::new(self);
        let mut entries = Vec::new();
        for m in species {
            let growth = self.growth(region, m, seed, pruned)?;
            let entry = self.waited(m, &growth, deadline, growth.at(age)).await?;
            let entry = entry.ok_or_else(|| {
                ApiError::internal(format!(
                    "{}: the growth stopped before age {age}",
                    m.label()
                ))
            })?;
            entries.push(entry);
        }
        Ok(entries)
    }
}

/// `GET /api/growth?region=R&species=S[&seed=0][&site=narrow]`: every age of one species:
/// the grown tree's dimensions against the equations, the year's benefits, costs and
/// conflicts on the site, the first year of each conflict, and what is not computed.
pub async fn growth(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let query = Query(&q);
    let region = query.region(state.db)?;
    let m = &query.one_species(state.db, &region, "the growth table is one species'")?;
    let seed = query.seed()?;
    let site = query.site()?;
    let pruned = query.pruned()?;
    let kept = format!(
        "growth/{region}/{}/{seed}/{site}/{}",
        m.species.code,
        pruned.is_some()
    );
    if let Some(json) = state.recent.get(&kept) {
        return Ok(([(header::CONTENT_TYPE, "application/json")], json).into_response());
    }
    let entries = state
        .all(&region, m, seed, pruned, Deadline::new(&state))
        .await?;
    let accounts: Vec<&sylva::street::YearAccount> =
        entries.iter().map(|e| &e.accounts[site]).collect();
    let body = to_json(&PageGrowth {
        species: SpeciesLabel::of(m),
        region: RegionLabel::of(m),
        seed,
        site: sites()[site].key.to_string(),
        pruning: pruned.is_some(),
        rows: (entries.iter())
            .map(|e| PageRow::of(&e.record, &e.accounts[site]))
            .collect(),
        first_conflicts: (first_conflicts(entries.iter().map(|e| -> &AgeEntry { e }), site)
            .into_iter())
        .map(|(age, kind)| PageConflict {
            kind: kind.name().to_string(),
            age,
        })
        .collect(),
        does_not_suit: sylva::street::rank::unsuited(&accounts),
        conflict_costs: ConflictCostRecord::of(&accounts),
        missing: grown::missing(m, site),
    });
    let json = axum::body::Bytes::from(body.to_string());
    state.recent.put(kept, json.clone());
    Ok(([(header::CONTENT_TYPE, "application/json")], json).into_response())
}

/// What a request for one tree at one age names, checked in the order region, species, age,
/// seed (the GLB, the plan symbol and the site picture share it).
struct OneTree {
    region: String,
    m: Measured,
    age: u32,
    seed: u64,
    /// The site whose pruning cuts the tree (`pruning=on`), if any.
    pruned: Option<usize>,
}

impl OneTree {
    /// `what` says why one species (`"a GLB holds one tree"`).
    fn parse(state: &State, query: &Query, what: &str) -> Result<OneTree, ApiError> {
        let region = query.region(state.db)?;
        let m = query.one_species(state.db, &region, what)?;
        let age = query.age(std::slice::from_ref(&m))?;
        let seed = query.seed()?;
        let pruned = query.pruned()?;
        Ok(OneTree {
            region,
            m,
            age,
            seed,
            pruned,
        })
    }

    /// The tree, once grown to the age.
    async fn entry(&self, state: &State) -> Result<Entry, ApiError> {
        let species = std::slice::from_ref(&self.m);
        Ok(state
            .at(&self.region, species, self.age, self.seed, self.pruned)
            .await?
            .remove(0))
    }
}

/// `GET /api/tree.glb?region=R&species=S&age=A[&seed=0][&detail=0]`: the grown tree as the
/// page draws it, whole or thinned for a slow graphics path (detail 1 to 3).
pub async fn tree_glb(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let query = Query(&q);
    let tree = OneTree::parse(&state, &query, "a GLB holds one tree")?;
    let detail = query.detail()?;
    let (code, age, seed) = (&tree.m.species.code, tree.age, tree.seed);
    let name = format!("{code}-age-{age:02}.glb");
    let kept = format!(
        "{}/{code}/{seed}/{age}/{detail}/{:?}",
        tree.region, tree.pruned
    );
    if let Some(glb) = state.recent.get(&kept) {
        return Ok(file(glb, "model/gltf-binary", &name));
    }
    let entry = tree.entry(&state).await?;
    if detail == grown::OPENING && !entry.opening.is_empty() {
        return Ok(file(entry.opening.clone(), "model/gltf-binary", &name));
    }
    let m = tree.m.clone();
    let glb = blocking(&state, move || {
        let mut glb =
            grown::web_glb(&m, &entry, detail).map_err(|e| ApiError::internal(e.to_string()))?;
        // Kept among the recent answers, counted by its length: no room past it.
        glb.shrink_to_fit();
        Ok(glb)
    })
    .await?;
    let glb = axum::body::Bytes::from(glb);
    state.recent.put(kept, glb.clone());
    Ok(file(glb, "model/gltf-binary", &name))
}

/// `GET /api/plan.svg?region=R&species=S&age=A[&seed=0]`: the tree from above, a line
/// drawing with a scale bar, as `sylva draw --view top` makes for CAD.
pub async fn plan_svg(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let tree = OneTree::parse(&state, &Query(&q), "a plan symbol is one tree's")?;
    let entry = tree.entry(&state).await?;
    let svg = blocking(&state, move || {
        let options = DrawOptions {
            view: View::Top,
            ..Default::default()
        };
        Ok(draw_svg(&entry.skeleton, &options))
    })
    .await?;
    let name = format!("{}-age-{:02}-plan.svg", tree.m.species.code, tree.age);
    Ok(file(svg.into_bytes(), "image/svg+xml", &name))
}

/// `GET /api/table.csv?region=R&species=A,B[&seed=0][&site=narrow]`: every age of each
/// species, as `sylva grow` writes its CSV, with the species' code first on each row.
pub async fn table_csv(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let query = Query(&q);
    let region = query.region(state.db)?;
    let species = query.species(state.db, &region)?;
    let seed = query.seed()?;
    let site = query.site()?;
    let pruned = query.pruned()?;
    let mut out = String::new();
    let deadline = Deadline::new(&state);
    for (i, m) in species.iter().enumerate() {
        let entries = state.all(&region, m, seed, pruned, deadline).await?;
        let history: Vec<AgeRecord> = entries.iter().map(|e| e.record).collect();
        let accounts: Vec<_> = entries.iter().map(|e| e.accounts[site].clone()).collect();
        let csv = table::join_csv(&report::csv(&history), &accounts);
        for (n, line) in csv.lines().enumerate() {
            if n == 0 {
                if i == 0 {
                    out.push_str("species,");
                    out.push_str(line);
                    out.push('\n');
                }
                continue;
            }
            out.push_str(&m.species.code);
            out.push(',');
            out.push_str(line);
            out.push('\n');
        }
    }
    let codes: Vec<&str> = species.iter().map(|m| m.species.code.as_str()).collect();
    Ok(file(
        out.into_bytes(),
        "text/csv",
        &format!("{}.csv", codes.join("-")),
    ))
}

/// `GET /api/compare.png?region=R&species=A,B&age=A[&seed=0][&size=1280x720]`: the species
/// side by side at that age, drawn as `sylva grow --compare` draws them.
pub async fn compare_png(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let query = Query(&q);
    let region = query.region(state.db)?;
    let species = query.species(state.db, &region)?;
    let age = query.age(&species)?;
    let seed = query.seed()?;
    let size = query.size()?;
    let pruned = query.pruned()?;
    let entries = state.at(&region, &species, age, seed, pruned).await?;
    let pictures = state.clone();
    let names: Vec<&str> = species.iter().map(|m| m.species.code.as_str()).collect();
    let name = format!("compare-{}-age-{age:02}.png", names.join("-"));
    let png = blocking(&state, move || {
        pictures.pictures.compare(&species, &entries, age, size)
    })
    .await?;
    Ok(file(png, "image/png", &name))
}

/// `GET /api/site.png?region=R&species=S&age=A[&seed=N][&site=K][&size=640x300]`: the tree
/// on its site that year, across the street and from above, with what is in the way in red
/// and the zones of that year's conflicts outlined (as `sylva grow --site` draws it).
pub async fn site_png(AxumState(state): AxumState<Arc<State>>, AxumQuery(q): Params) -> Reply {
    let query = Query(&q);
    let tree = OneTree::parse(&state, &query, "a site picture is one tree's")?;
    let site = query.site()?;
    let size = if q.contains_key("size") {
        query.size()?
    } else {
        (640, 300)
    };
    let entry = tree.entry(&state).await?;
    let png = blocking(&state, move || {
        let kinds: Vec<_> = entry.accounts[site]
            .conflicts
            .iter()
            .map(|c| c.kind)
            .collect();
        let (w, h, rgba) = site_picture(&entry.skeleton, &sites()[site].site, &kinds, size);
        let mut png = Vec::new();
        image::ImageEncoder::write_image(
            image::codecs::png::PngEncoder::new(&mut png),
            &rgba,
            w,
            h,
            image::ExtendedColorType::Rgba8,
        )
        .map_err(|e| ApiError::internal(format!("encoding the site picture: {e}")))?;
        Ok(png)
    })
    .await?;
    let name = format!("{}-site-age-{:02}.png", tree.m.species.code, tree.age);
    Ok(file(png, "image/png", &name))
}

/// Runs `work` on a blocking thread once one of the [`State::workers`] turns is free: as
/// many pieces of work at once as the machine has cores. More at once would only share the
/// cores, each holding the memory of a mesh or picture in the making the while (twenty
/// comparison pictures asked at once would hold twenty frames).
async fn blocking<T: Send + 'static>(
    state: &State,
    work: impl FnOnce() -> Result<T, ApiError> + Send + 'static,
) -> Result<T, ApiError> {
    let _turn = state
        .workers
        .acquire()
        .await
        .map_err(|e| ApiError::internal(format!("the work stopped: {e}")))?;
    tokio::task::spawn_blocking(work)
        .await
        .map_err(|e| ApiError::internal(format!("the work stopped: {e}")))?
}

/// A download: its type and the file name a browser saves it as.
fn file(bytes: impl Into<axum::body::Bytes>, content_type: &'static str, name: &str) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type.to_string()),
            (
                header::CONTENT_DISPOSITION,
                format!("inline; filename=\"{name}\""),
            ),
        ],
        bytes.into(),
    )
        .into_response()
}
