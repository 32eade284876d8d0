//! The city view's data: folders `sylva city` wrote, opened once as the server starts.
//!
//! Each folder is read for what the page needs (its `summary.json`: who wrote it, its epochs
//! and the tileset of each; whether a report lies beside it) and listed file by file. A
//! request for a city's file is answered only when its path is one of that list, matched as a
//! whole string, so a path is never joined to a folder from what a request says: `..`,
//! absolute paths, links (never followed while listing) and hidden files (a run's staging
//! folder) cannot reach anything outside.
//!
//! What stops the server at start: a folder that is missing or not a folder, and two folders of
//! one name (the name is the city's address on the page). What only marks that city, listed on
//! the page with why: no `summary.json`, one that is not JSON, one written by another tool or
//! another layout of Sylva's, an epoch whose `tileset.json` is missing or damaged.

use crate::ServeError;
use axum::extract::{Path as UrlPath, State};
use axum::http::{HeaderMap, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::{Value, json};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use sylva_city::tasks::{SUMMARY_FORMAT, SUMMARY_GENERATOR};

/// Most files listed in one city's folder (Sylva's choice): a 100,000-tree city at four epochs
/// holds some 4,000 tiles and 1,000 grown trees' meshes, so this is far above any city's, and
/// bounds what a folder given by mistake (a home folder) costs.
pub const MOST_FILES: usize = 200_000;

/// Deepest folder listed below a city's (its tiles lie at `year-N/content/LEVEL/`).
const DEEPEST: usize = 6;

/// One city's epoch.
#[derive(Clone, Debug, PartialEq)]
pub struct Epoch {
    /// Years after the inventory.
    pub years: u32,
    /// Its `tileset.json`, relative to the city's folder.
    pub tileset: String,
    /// Trees drawn.
    pub trees: u64,
}

/// A city the server was given.
#[derive(Clone, Debug)]
pub struct City {
    /// Its address on the page: the folder's name.
    pub name: String,
    /// Its folder.
    pub dir: PathBuf,
    /// Why the page cannot show it, if it cannot.
    pub problem: Option<String>,
    /// Its epochs, first to last.
    pub epochs: Vec<Epoch>,
    /// Every file the page may ask for, relative to `dir` with `/` between names.
    pub files: HashSet<String>,
    /// The summary as written (for the page's header: rows, layout, rejected rows).
    pub summary: Value,
}

/// The cities the server shows, and the ground they are drawn on.
#[derive(Clone, Debug, Default)]
pub struct Cities {
    /// In the order given.
    pub list: Vec<City>,
    /// An XYZ tile source (`{z}`, `{x}`, `{y}` in it) drawn under the cities, if given.
    pub basemap: Option<String>,
}

impl Cities {
    /// Opens every folder in `dirs`; `basemap` must name `{z}`, `{x}` and `{y}`.
    pub fn open(dirs: &[PathBuf], basemap: Option<String>) -> Result<Cities, ServeError> {
        if let Some(url) = &basemap {
            let missing: Vec<&str> = ["{z}", "{x}", "{y}"]
                .into_iter()
                .filter(|k| !url.contains(k))
                .collect();
            if !missing.is_empty() {
                return Err(ServeError(format!(
                    "--basemap {url}: an XYZ tile address must hold {}, as https://tile.example.org/{{z}}/{{x}}/{{y}}.png",
                    missing.join(", ")
                )));
            }
            if !(url.starts_with("http://") || url.starts_with("https://")) {
                return Err(ServeError(format!(
                    "--basemap {url}: expected an http:// or https:// address"
                )));
            }
        }
        let mut list: Vec<City> = Vec::new();
        for dir in dirs {
            let city = City::open(dir)?;
            if let Some(other) = list.iter().find(|c| c.name == city.name) {
                return Err(ServeError(format!(
                    "--city {} and --city {}: two cities named `{}` (a city's name on the page is its folder's); rename one folder",
                    other.dir.display(),
                    dir.display(),
                    city.name
                )));
            }
            list.push(city);
        }
        Ok(Cities { list, basemap })
    }

    /// The city named `name`.
    pub fn find(&self, name: &str) -> Option<&City> {
        self.list.iter().find(|c| c.name == name)
    }

    /// What `/api/cities` answers: each city with its epochs' tilesets and report, or its
    /// problem.
    pub fn json(&self) -> Value {
        let cities: Vec<Value> = self
            .list
            .iter()
            .map(|c| {
                let url = |rel: &str| format!("/city/{}/{rel}", c.name);
                let has = |rel: &str| c.files.contains(rel).then(|| url(rel));
                json!({
                    "name": c.name,
                    "problem": c.problem,
                    "origin": c.summary.get("origin"),
                    "rows": c.summary.get("rows"),
                    "trees": c.summary.get("trees"),
                    "layout": c.summary.get("layout"),
                    "rejected": c.summary.get("rejected").and_then(Value::as_array).map_or(0, Vec::len),
                    "epochs": c.epochs.iter().map(|e| json!({
                        "years": e.years, "trees": e.trees, "tileset": url(&e.tileset),
                    })).collect::<Vec<_>>(),
                    "report": { "json": has("report.json"), "html": has("report.html"), "csv": has("report.csv") },
                })
            })
            .collect();
        json!({
            "basemap": self.basemap,
            "cities": cities,
            // The filter's classes: the Urban Tree Database's, as the report counts them.
            "dbh_class_edges_cm": sylva::growth::DBH_CLASS_EDGES_CM,
        })
    }
}

impl City {
    /// Reads the folder `dir`. Only a missing folder is an error; anything wrong inside it is
    /// the city's `problem`.
    pub fn open(dir: &Path) -> Result<City, ServeError> {
        let meta = std::fs::metadata(dir)
            .map_err(|e| ServeError(format!("--city {}: {e}", dir.display())))?;
        if !meta.is_dir() {
            return Err(ServeError(format!(
                "--city {}: not a folder (expected the folder `sylva city -o` wrote)",
                dir.display()
            )));
        }
        let name = dir
            .canonicalize()
            .ok()
            .and_then(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| "city".into());
        let mut city = City {
            name,
            dir: dir.to_path_buf(),
            problem: None,
            epochs: Vec::new(),
            files: HashSet::new(),
            summary: Value::Null,
        };
        if let Err(why) = city.read() {
            city.problem = Some(format!("{}: {why}", dir.display()));
            city.epochs.clear();
            city.files.clear();
        }
        Ok(city)
    }

    fn read(&mut self) -> Result<(), String> {
        let summary_path = self.dir.join("summary.json");
        let text = match std::fs::read(&summary_path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Err(
                    "no summary.json: not a folder `sylva city` wrote (give the folder named by its -o)"
                        .into(),
                );
            }
            Err(e) => return Err(format!("summary.json: {e}")),
        };
        let summary: Value =
            serde_json::from_slice(&text).map_err(|e| format!("summary.json is damaged: {e}"))?;
        let generator = summary.get("generator").and_then(Value::as_str);
        if generator != Some(SUMMARY_GENERATOR) {
            return Err(match generator {
                Some(g) => format!("summary.json was written by `{g}`, not by `sylva city`"),
                None if summary.get("epochs").is_some() => {
                    "summary.json was written by an older `sylva city` (it names no generator): run `sylva city` on the inventory again".into()
                }
                None => "summary.json was not written by `sylva city` (it names no generator)".into(),
            });
        }
        let format = summary.get("format").and_then(Value::as_u64);
        if format != Some(SUMMARY_FORMAT as u64) {
            let version = summary
                .get("version")
                .and_then(Value::as_str)
                .unwrap_or("?");
            return Err(format!(
                "summary.json is in format {} (Sylva {version}); this sylva reads format {SUMMARY_FORMAT}: run this version's `sylva city` on the inventory again",
                format.map_or("?".into(), |f| f.to_string())
            ));
        }
        self.files = list_files(&self.dir)?;
        let epochs = summary
            .get("epochs")
            .and_then(Value::as_array)
            .ok_or("summary.json has no `epochs` list")?;
        for (i, e) in epochs.iter().enumerate() {
            let years = e.get("years").and_then(Value::as_u64);
            let tileset = e.get("tileset").and_then(Value::as_str);
            let (Some(years), Some(tileset)) = (years, tileset) else {
                return Err(format!(
                    "summary.json: epoch {i} has no `years` or `tileset`"
                ));
            };
            if !self.files.contains(tileset) {
                return Err(format!("epoch +{years}: {tileset} is missing"));
            }
            let bytes = std::fs::read(self.dir.join(tileset))
                .map_err(|e| format!("epoch +{years}: {tileset}: {e}"))?;
            let json: Value = serde_json::from_slice(&bytes)
                .map_err(|e| format!("epoch +{years}: {tileset} is damaged: {e}"))?;
            let by = json.pointer("/asset/generator").and_then(Value::as_str);
            if !by.is_some_and(|g| g.starts_with("Sylva")) || json.get("root").is_none() {
                return Err(format!(
                    "epoch +{years}: {tileset} is not a tileset `sylva city` wrote (generator {})",
                    by.unwrap_or("not named")
                ));
            }
            self.epochs.push(Epoch {
                years: years as u32,
                tileset: tileset.to_string(),
                trees: e.get("trees").and_then(Value::as_u64).unwrap_or(0),
            });
        }
        if self.epochs.is_empty() {
            return Err("summary.json lists no epoch".into());
        }
        self.summary = summary;
        Ok(())
    }
}

/// Every plain file below `dir` (not following links, leaving hidden names out), as paths with
/// `/` between names; at most [`MOST_FILES`], at most [`DEEPEST`] folders down.
fn list_files(dir: &Path) -> Result<HashSet<String>, String> {
    let mut files = HashSet::new();
    let mut stack = vec![(dir.to_path_buf(), String::new(), 0usize)];
    while let Some((path, prefix, depth)) = stack.pop() {
        let entries = std::fs::read_dir(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        for entry in entries {
            let entry = entry.map_err(|e| format!("{}: {e}", path.display()))?;
            let name = entry.file_name();
            // Names that are not UTF-8, hidden, or could read as a path step are never served.
            let Some(name) = name.to_str() else { continue };
            if name.starts_with('.') || name.contains(['/', '\\']) {
                continue;
            }
            let kind = entry
                .file_type()
                .map_err(|e| format!("{}: {e}", entry.path().display()))?;
            let rel = format!("{prefix}{name}");
            if kind.is_file() {
                if files.len() == MOST_FILES {
                    return Err(format!(
                        "more than {MOST_FILES} files: not a folder `sylva city` wrote"
                    ));
                }
                files.insert(rel);
            } else if kind.is_dir() && depth < DEEPEST {
                stack.push((entry.path(), format!("{rel}/"), depth + 1));
            }
        }
    }
    Ok(files)
}

/// The content type of a city's file.
fn content_type(path: &str) -> &'static str {
    match path.rsplit('.').next() {
        Some("json") => "application/json",
        Some("glb") => "model/gltf-binary",
        Some("html") => "text/html; charset=utf-8",
        Some("csv") => "text/csv; charset=utf-8",
        _ => "application/octet-stream",
    }
}

fn not_found(what: &str) -> Response {
    (
        StatusCode::NOT_FOUND,
        [(header::CONTENT_TYPE, "application/json")],
        json!({ "error": format!("{what}: not found") }).to_string(),
    )
        .into_response()
}

/// `GET /api/cities`.
pub async fn list(State(state): State<Arc<crate::State>>) -> Response {
    (
        [(header::CONTENT_TYPE, "application/json")],
        state.cities.json().to_string(),
    )
        .into_response()
}

/// `GET /city/{name}/{*path}`: one of the city's listed files, read from disk as asked (the
/// operating system keeps what is read often; the server keeps none of it). Each answer
/// carries an entity tag of the file's size and time, and the browser asks again each time
/// with it: a tile's many shared meshes then cost a 304 each, and a folder written again while
/// the page is open is never taken from an old copy.
pub async fn file(
    State(state): State<Arc<crate::State>>,
    UrlPath((name, path)): UrlPath<(String, String)>,
    headers: HeaderMap,
) -> Response {
    let Some(city) = state.cities.find(&name) else {
        return not_found(&format!("city `{name}`"));
    };
    if !city.files.contains(&path) {
        return not_found(&format!("/city/{name}/{path}"));
    }
    let full = city.dir.join(&path);
    let failed = |e: std::io::Error| {
        (
            StatusCode::INTERNAL_SERVER_ERROR,
            [(header::CONTENT_TYPE, "application/json")],
            json!({ "error": format!("/city/{name}/{path}: {e}") }).to_string(),
        )
            .into_response()
    };
    let meta = match tokio::fs::metadata(&full).await {
        Ok(m) => m,
        Err(e) => return failed(e),
    };
    let time = meta
        .modified()
        .ok()
        .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
        .map_or(0, |d| d.as_nanos());
    let tag = format!("\"{:x}-{time:x}\"", meta.len());
    let fresh = headers
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.split(',').any(|t| t.trim() == tag));
    let cache = [
        (header::ETAG, tag.clone()),
        (header::CACHE_CONTROL, "no-cache".to_string()),
    ];
    if fresh {
        return (StatusCode::NOT_MODIFIED, cache).into_response();
    }
    match tokio::fs::read(&full).await {
        Ok(bytes) => (cache, [(header::CONTENT_TYPE, content_type(&path))], bytes).into_response(),
        Err(e) => failed(e),
    }
}
