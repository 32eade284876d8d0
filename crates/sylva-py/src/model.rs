//! Trees for Python: a Weber & Penn tree from a species, a street tree grown from the Urban
//! Tree Database, each a [`Model`] whose meshes come out as numpy arrays or GLB bytes.

use crate::{error, to_python};
use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::collections::BTreeMap;
use sylva::GenerateOptions;
use sylva::export::{Materials, to_glb};
use sylva::growth::Database;
use sylva::growth::season::{Month, dressed_mesh};
use sylva::growth::survey::report;
use sylva::mesh::{Mesh, TreeMesh};
use sylva::record::to_json;
use sylva::street::records::YearRecord;
use sylva::street::study::{Pruning, Spread, StreetTree, Study};
use sylva::street::{Costs, Prices, Site};
use sylva::weber_penn::made::{MakeError, make};

/// A tree's mesh, its materials and what was made.
#[pyclass(frozen, module = "sylva._sylva")]
pub struct Model {
    mesh: TreeMesh,
    name: String,
    materials: Materials,
    summary: serde_json::Value,
}

#[pymethods]
impl Model {
    /// The tree's name (its species).
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// What was made, as a dict (for a grown tree: its dimensions beside the equations', its
    /// benefits and conflicts).
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.summary)
    }

    /// Triangles of every part.
    #[getter]
    fn triangles(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// Vertices of every part.
    #[getter]
    fn vertices(&self) -> usize {
        self.mesh.vertex_count()
    }

    /// Base colours (linear RGBA) of the bark, leaf and flower materials.
    #[getter]
    fn materials(&self) -> BTreeMap<&'static str, [f32; 4]> {
        BTreeMap::from([
            ("bark", self.materials.bark),
            ("leaves", self.materials.leaves),
            ("flowers", self.materials.flowers),
        ])
    }

    /// The mesh as numpy arrays, one dict per material that has triangles (`bark`, `leaves`,
    /// `flowers`): `positions` and `normals` (n, 3) float32 in metres, Z up; `uvs` (n, 2)
    /// float32; `indices` (m, 3) uint32, counter-clockwise seen from outside; `shades` (n,)
    /// float32 where the leaves carry light classes, else absent.
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for (name, mesh) in [
            ("bark", &self.mesh.bark),
            ("leaves", &self.mesh.leaves),
            ("flowers", &self.mesh.flowers),
        ] {
            if mesh.triangle_count() > 0 {
                out.set_item(name, part(py, mesh)?)?;
            }
        }
        Ok(out)
    }

    /// The tree as a GLB file's bytes (glTF 2.0, Y up as glTF asks).
    fn glb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let bytes = py
            .detach(|| to_glb(&self.mesh, &self.name, &self.materials))
            .map_err(error)?;
        Ok(PyBytes::new(py, &bytes))
    }

    fn __repr__(&self) -> String {
        format!(
            "<sylva.Model {}: {} triangles, {} vertices>",
            self.name,
            self.mesh.triangle_count(),
            self.mesh.vertex_count()
        )
    }
}

/// One material's arrays.
fn part<'py>(py: Python<'py>, mesh: &Mesh) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let rows =
        |flat: Vec<f32>, k: usize| Array2::from_shape_vec((flat.len() / k, k), flat).map_err(error);
    let n = mesh.positions.len();
    let flat3 = |v: &[[f32; 3]]| v.iter().flatten().copied().collect::<Vec<f32>>();
    d.set_item(
        "positions",
        rows(flat3(&mesh.positions), 3)?.into_pyarray(py),
    )?;
    d.set_item("normals", rows(flat3(&mesh.normals), 3)?.into_pyarray(py))?;
    let uvs: Vec<f32> = mesh.uvs.iter().flatten().copied().collect();
    d.set_item("uvs", rows(uvs, 2)?.into_pyarray(py))?;
    let indices =
        Array2::from_shape_vec((mesh.indices.len() / 3, 3), mesh.indices.clone()).map_err(error)?;
    d.set_item("indices", indices.into_pyarray(py))?;
    if mesh.shades.len() == n && n > 0 {
        d.set_item("shades", mesh.shades.clone().into_pyarray(py))?;
    }
    Ok(d)
}

/// generate(species, seed=0, quality=1.0, set=None, levels=None, leaves=True,
/// max_triangles=5_000_000)
///
/// A Weber & Penn tree: `species` is a built-in name (`sylva.species()`), a Sylva `.toml` or
/// an Arbaro `.xml` file; `set` overrides parameters by name (`{"1Branches": 30}`).
#[pyfunction]
#[pyo3(signature = (species, seed=0, quality=1.0, set=None, levels=None, leaves=true, max_triangles=5_000_000))]
#[allow(clippy::too_many_arguments)]
fn generate(
    py: Python<'_>,
    species: &str,
    seed: u64,
    quality: f64,
    set: Option<BTreeMap<String, f64>>,
    levels: Option<u32>,
    leaves: bool,
    max_triangles: u64,
) -> PyResult<Model> {
    if !(quality > 0.0 && quality <= 8.0) {
        return Err(error(format!(
            "quality {quality}: expected a number above 0, at most 8"
        )));
    }
    if levels == Some(0) {
        return Err(error("levels 0: expected 1 (trunk only) or more"));
    }
    py.detach(|| {
        let mut params = sylva::species::load(species).map_err(error)?;
        for (name, value) in set.unwrap_or_default() {
            params
                .set(&name, value)
                .map_err(|e| error(format!("set {name}={value}: {e}")))?;
        }
        params
            .validate()
            .map_err(|e| error(format!("species {species}: {e}")))?;
        let options = GenerateOptions {
            seed,
            max_levels: levels,
            quality,
            leaves,
            max_triangles,
            ..Default::default()
        };
        // The same tree and summary as `sylva generate --json` (less its output file).
        let made = make(&params, &options, quality).map_err(|e| match e {
            MakeError::OverBudget(e) => error(format!("{e} (max_triangles)")),
            e => error(format!("species {species}: {e}")),
        })?;
        let mut summary = to_json(&made.record(&params, seed));
        summary["notes"] = serde_json::json!(params.notes);
        Ok(Model {
            materials: Materials::from_srgb(params.bark_color, params.leaf_color),
            name: params.name.clone(),
            mesh: made.mesh,
            summary,
        })
    })
}

/// grow(code, region, age, seed=0, season=None, site=None, prices=None, costs=None)
///
/// A street tree of species `code` (or its scientific or common name) grown by `region`'s
/// equations of the Urban Tree Database to `age` years. Its summary holds the grown tree's
/// dimensions beside the equations', and the year's benefits, costs and conflicts with the
/// site (`site`, `prices`, `costs`: TOML files as `sylva grow --site` reads them).
#[pyfunction]
#[pyo3(signature = (code, region, age, seed=0, season=None, site=None, prices=None, costs=None))]
#[allow(clippy::too_many_arguments)]
fn grow(
    py: Python<'_>,
    code: &str,
    region: &str,
    age: f64,
    seed: u64,
    season: Option<&str>,
    site: Option<std::path::PathBuf>,
    prices: Option<std::path::PathBuf>,
    costs: Option<std::path::PathBuf>,
) -> PyResult<Model> {
    py.detach(|| {
        let m = Database::builtin().find(region, code).map_err(error)?;
        // The CLI's bounds on ages, said in this function's words.
        let ages = report::run_ages(&m, Some(age), Some(age), 1.0).map_err(|_| {
            error(format!(
                "age {age}: expected 0 to 300 years (the data for {} cover ages {} to {})",
                m.label(),
                m.ages.0,
                m.ages.1
            ))
        })?;
        let month = season.map(Month::parse).transpose().map_err(error)?;
        let site = site.as_deref().map(Site::load).transpose().map_err(error)?;
        let money = prices.is_some() || costs.is_some();
        let prices = prices
            .as_deref()
            .map(Prices::load)
            .transpose()
            .map_err(error)?;
        let costs = costs
            .as_deref()
            .map(Costs::load)
            .transpose()
            .map_err(error)?;
        // The wheel's tree is grown straight to its age and never cut: its summary is the
        // study pipeline's year, as `sylva grow --json` writes it.
        let study = Study {
            seed,
            site,
            prices,
            costs,
            pruning: Pruning::Off,
            ..Study::new(ages[0])
        };
        study.check().map_err(error)?;
        let assessor = study.assessor(&m);
        if money {
            assessor.require_carbon().map_err(error)?;
        }
        let mut tree = StreetTree::new(&m, &study);
        let year = tree.grow_to(ages[0], Spread::Whole, |_, _, _, _| {});
        let skeleton = &year.skeleton;
        let (mesh, dress) = dressed_mesh(skeleton, &m, month, &report::MESH);
        let mut summary = to_json(&YearRecord::of(&m, &year));
        summary["region"] = serde_json::json!(m.region.code);
        summary["common_name"] = serde_json::json!(m.species.common);
        summary["scientific_name"] = serde_json::json!(m.species.scientific);
        summary["missing"] = serde_json::json!(tree.assessor(0).missing());
        Ok(Model {
            materials: dress.materials(),
            name: m.label(),
            mesh,
            summary,
        })
    })
}

/// The built-in Weber & Penn species, by id.
#[pyfunction]
fn species() -> Vec<&'static str> {
    sylva::species::builtin_ids().collect()
}

/// The Urban Tree Database's species in every region: dicts of `code`, `region`, `common`
/// and `scientific` names.
#[pyfunction]
fn street_species(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let list: Vec<serde_json::Value> = Database::builtin()
        .species()
        .iter()
        .map(|s| {
            serde_json::json!({ "code": s.code, "region": s.region, "common": s.common,
                                "scientific": s.scientific })
        })
        .collect();
    to_python(py, &serde_json::Value::Array(list))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Model>()?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(grow, m)?)?;
    m.add_function(wrap_pyfunction!(species, m)?)?;
    m.add_function(wrap_pyfunction!(street_species, m)?)?;
    Ok(())
}
