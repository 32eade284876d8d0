//! Cities for Python: `city()` runs the whole job on this machine's threads; [`Job`] and the
//! task functions expose its stages (`sylva_city::tasks`) so that `sylva.dask` can spread the
//! growth and tile tasks over a cluster's workers, with the same bytes as the one-process run.

use crate::{error, to_python};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use sylva_city::geo::Projection;
use sylva_city::tasks::{self, CityJob, from_bytes, to_bytes};
use sylva_city::tiles::{Tile, TileTask};
use sylva_city::trees::prototypes::{GrowthTask, Prototype};
use sylva_city::{CityOptions, Layout, LengthUnit, Quiet};

/// A city's settings as the `sylva` package passes them (JSON): the inventory and its columns,
/// and the run's options. Names as `sylva city`'s flags, without their `--`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Settings {
    inventory: PathBuf,
    layer: Option<String>,
    #[serde(default)]
    columns: BTreeMap<String, ColumnNames>,
    dbh_unit: Option<String>,
    circumference_unit: Option<String>,
    height_unit: Option<String>,
    crs: Option<String>,
    region: Option<String>,
    variants: u32,
    stumps: bool,
    years: Vec<u32>,
    year: i32,
    ground: f64,
    seed: u64,
}

/// A column's name, or several tried in order (the species').
#[derive(Deserialize)]
#[serde(untagged)]
enum ColumnNames {
    One(String),
    Many(Vec<String>),
}

/// The columns a layout can name.
const COLUMNS: [&str; 13] = [
    "id",
    "species",
    "dbh",
    "circumference",
    "lon",
    "lat",
    "x",
    "y",
    "height",
    "planted",
    "status",
    "ground",
    "condition",
];

impl Settings {
    fn parse(json: &str) -> PyResult<Settings> {
        serde_json::from_str(json).map_err(|e| error(format!("city settings: {e}")))
    }

    fn layout(&self) -> PyResult<Layout> {
        if let Some(bad) = self.columns.keys().find(|k| !COLUMNS.contains(&k.as_str())) {
            return Err(error(format!(
                "columns: `{bad}` is no column Sylva reads; expected some of {}",
                COLUMNS.join(", ")
            )));
        }
        let one = |key: &str| match self.columns.get(key) {
            Some(ColumnNames::One(s)) => Ok(Some(s.clone())),
            Some(ColumnNames::Many(_)) => Err(error(format!(
                "columns: `{key}` takes one column name, not a list"
            ))),
            None => Ok(None),
        };
        let pair = |a: &str, b: &str| -> PyResult<Option<(String, String)>> {
            match (one(a)?, one(b)?) {
                (Some(x), Some(y)) => Ok(Some((x, y))),
                (None, None) => Ok(None),
                _ => Err(error(format!(
                    "columns: `{a}` and `{b}` go together; name both"
                ))),
            }
        };
        let unit = |flag: &str, v: &Option<String>| -> PyResult<Option<LengthUnit>> {
            v.as_deref()
                .map(|s| LengthUnit::parse(flag, s))
                .transpose()
                .map_err(error)
        };
        Ok(Layout {
            id: one("id")?,
            species: match self.columns.get("species") {
                Some(ColumnNames::One(s)) => vec![s.clone()],
                Some(ColumnNames::Many(v)) => v.clone(),
                None => Vec::new(),
            },
            dbh: one("dbh")?,
            dbh_unit: unit("dbh_unit", &self.dbh_unit)?,
            circumference: one("circumference")?,
            circumference_unit: unit("circumference_unit", &self.circumference_unit)?,
            lon_lat: pair("lon", "lat")?,
            xy: pair("x", "y")?,
            crs: self
                .crs
                .as_deref()
                .map(Projection::parse_epsg)
                .transpose()
                .map_err(error)?,
            height: one("height")?,
            height_unit: unit("height_unit", &self.height_unit)?,
            planted: one("planted")?,
            status: one("status")?,
            ground: one("ground")?,
            observed: sylva_city::inventory::ObservedColumns {
                condition: one("condition")?,
                ..Default::default()
            },
            name: String::new(),
        })
    }

    fn options(&self) -> CityOptions {
        CityOptions {
            region: self.region.clone(),
            variants: self.variants,
            stumps: self.stumps,
            years: self.years.clone(),
            base_year: self.year,
            ground: self.ground,
            seed: self.seed,
            // A cluster's workers grow their own tasks; the local run grows them all.
            cache: None,
            report: false,
            dxf: false,
        }
    }
}

/// Tiles a city on this machine's threads into `out`; its summary (as `summary.json`).
#[pyfunction]
fn city<'py>(py: Python<'py>, settings: &str, out: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let s = Settings::parse(settings)?;
    let layout = s.layout()?;
    let run = py
        .detach(|| {
            sylva_city::tile_city(
                &s.inventory,
                s.layer.as_deref(),
                &layout,
                &s.options(),
                &out,
                &Quiet,
            )
        })
        .map_err(error)?;
    to_python(py, &sylva_city::summary_json(&run))
}

/// A file for Python: its path relative to the output folder, and its bytes.
type PyFile<'py> = (String, Bound<'py, PyBytes>);

/// A city's run between its stages, on the process that drives it.
#[pyclass(module = "sylva._sylva")]
struct Job {
    job: CityJob,
}

#[pymethods]
impl Job {
    /// Reads and plans the inventory the settings name.
    #[new]
    fn new(py: Python<'_>, settings: &str) -> PyResult<Job> {
        let s = Settings::parse(settings)?;
        let layout = s.layout()?;
        let job = py
            .detach(|| CityJob::prepare(&s.inventory, s.layer.as_deref(), &layout, &s.options()))
            .map_err(error)?;
        Ok(Job { job })
    }

    /// The growth tasks, as bytes for `run_growth`.
    fn growth_tasks<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyBytes>>> {
        self.job
            .growth_tasks()
            .iter()
            .map(|t| Ok(PyBytes::new(py, &to_bytes(t).map_err(error)?)))
            .collect()
    }

    /// Takes the prototypes `run_growth` returned (its first item, each task's).
    fn add_prototypes(&mut self, grown: Vec<Vec<u8>>) -> PyResult<()> {
        for bytes in grown {
            let prototypes: Vec<Prototype> = from_bytes(&bytes).map_err(error)?;
            self.job.add_prototypes(prototypes);
        }
        Ok(())
    }

    /// Lays the epochs out in tiles once every prototype is added; the tile tasks in all.
    fn lay_out(&mut self, py: Python<'_>) -> PyResult<usize> {
        let job = &mut self.job;
        py.detach(|| job.lay_out()).map_err(error)
    }

    /// Tile task `index`, as bytes for `run_tile`.
    fn tile_task<'py>(&self, py: Python<'py>, index: usize) -> PyResult<Bound<'py, PyBytes>> {
        let task = py.detach(|| self.job.tile_task(index)).ok_or_else(|| {
            error(format!(
                "tile task {index}: there are {}",
                self.job.tile_count()
            ))
        })?;
        Ok(PyBytes::new(py, &to_bytes(&task).map_err(error)?))
    }

    /// Each tileset's JSON and the summary from the tiles `run_tile` made (its first item,
    /// each task's, in any order): the summary, and the files (paths relative to the output).
    fn finish<'py>(
        &self,
        py: Python<'py>,
        tiles: Vec<Vec<u8>>,
    ) -> PyResult<(Bound<'py, PyAny>, Vec<PyFile<'py>>)> {
        let tiles: Vec<Tile> = tiles
            .iter()
            .map(|b| from_bytes(b))
            .collect::<Result<_, _>>()
            .map_err(error)?;
        let (run, files) = self.job.finish(&tiles).map_err(error)?;
        let summary = to_python(py, &sylva_city::summary_json(&run))?;
        Ok((summary, with_bytes(py, files)))
    }
}

fn with_bytes(py: Python<'_>, files: Vec<tasks::OutFile>) -> Vec<PyFile<'_>> {
    files
        .into_iter()
        .map(|(path, bytes)| (path, PyBytes::new(py, &bytes)))
        .collect()
}

/// Runs a growth task (bytes from `Job.growth_tasks`): its prototypes as bytes for
/// `Job.add_prototypes`, and its files.
#[pyfunction]
fn run_growth<'py>(
    py: Python<'py>,
    task: &[u8],
) -> PyResult<(Bound<'py, PyBytes>, Vec<PyFile<'py>>)> {
    let task: GrowthTask = from_bytes(task).map_err(error)?;
    let (prototypes, files) = py.detach(|| tasks::run_growth(&task)).map_err(error)?;
    let bytes = to_bytes(&prototypes).map_err(error)?;
    Ok((PyBytes::new(py, &bytes), with_bytes(py, files)))
}

/// Runs a tile task (bytes from `Job.tile_task`): the tile as bytes for `Job.finish`, and its
/// GLB file.
#[pyfunction]
fn run_tile<'py>(py: Python<'py>, task: &[u8]) -> PyResult<(Bound<'py, PyBytes>, PyFile<'py>)> {
    let task: TileTask = from_bytes(task).map_err(error)?;
    let (tile, (path, glb)) = py.detach(|| tasks::run_tile(&task)).map_err(error)?;
    let bytes = to_bytes(&tile).map_err(error)?;
    Ok((PyBytes::new(py, &bytes), (path, PyBytes::new(py, &glb))))
}

/// The stump's mesh file: its path and bytes.
#[pyfunction]
fn stump_file(py: Python<'_>) -> PyFile<'_> {
    let (path, bytes) = tasks::stump_file().1;
    (path, PyBytes::new(py, &bytes))
}

/// Checks that `out` may be written and makes the folder to write the run into; its path.
#[pyfunction]
fn begin(out: PathBuf) -> PyResult<PathBuf> {
    sylva_city::run::begin(&out).map_err(error)
}

/// Moves the finished folder from `begin` to `out`.
#[pyfunction]
fn commit(staging: PathBuf, out: PathBuf) -> PyResult<()> {
    sylva_city::run::commit(&staging, &out).map_err(error)
}

/// Writes files (paths relative to `dir`) into `dir`, each whole or not at all.
#[pyfunction]
fn write_files(py: Python<'_>, dir: PathBuf, files: Vec<(String, Vec<u8>)>) -> PyResult<()> {
    py.detach(|| sylva_city::run::write_files(Path::new(&dir), &files))
        .map_err(error)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Job>()?;
    for f in [
        wrap_pyfunction!(city, m)?,
        wrap_pyfunction!(run_growth, m)?,
        wrap_pyfunction!(run_tile, m)?,
        wrap_pyfunction!(stump_file, m)?,
        wrap_pyfunction!(begin, m)?,
        wrap_pyfunction!(commit, m)?,
        wrap_pyfunction!(write_files, m)?,
    ] {
        m.add_function(f)?;
    }
    Ok(())
}
