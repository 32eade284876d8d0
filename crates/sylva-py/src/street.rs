//! A region's species ranked for Python: the same request and rows as `sylva rank --json`
//! (`street::rank::RankRequest`, `street::records::RankRow`).

use crate::{error, to_python};
use pyo3::prelude::*;
use std::path::PathBuf;
use sylva::growth::Database;
use sylva::record::to_json;
use sylva::street::rank::{Pruning, RankRequest, rank as rank_species};
use sylva::street::records::RankRow;
use sylva::street::study::Study;
use sylva::street::{Basis, Costs, Prices, Site};

/// rank(region, years, species, seed, site, prices, costs, pruning, by)
///
/// `region`'s growable species (or those of `species`) grown yearly for `years` on `site`
/// and ranked per tree planted, best first: a list of dicts as `sylva rank --json` writes them.
/// `pruning` is `regime` (the site's cycles cut the tree), `compare` (and each year's benefits
/// lost to them) or `off`; `by` is `typical` or `site` (default: the site's where given).
#[pyfunction]
#[pyo3(signature = (region, years, species, seed, site, prices, costs, pruning, by))]
#[allow(clippy::too_many_arguments)]
fn rank<'py>(
    py: Python<'py>,
    region: &str,
    years: f64,
    species: Vec<String>,
    seed: u64,
    site: Option<PathBuf>,
    prices: Option<PathBuf>,
    costs: Option<PathBuf>,
    pruning: &str,
    by: Option<&str>,
) -> PyResult<Bound<'py, PyAny>> {
    let max = sylva::growth::survey::report::MAX_AGE;
    if !(1.0..=max).contains(&years) {
        return Err(error(format!("years {years}: expected 1 to {max}")));
    }
    let pruning = match pruning {
        "regime" => Pruning::Regime,
        "compare" => Pruning::Compare,
        "off" => Pruning::Off,
        other => {
            return Err(error(format!(
                "pruning `{other}`: expected regime, compare or off"
            )));
        }
    };
    let basis = match by {
        None => None,
        Some("typical") => Some(Basis::Typical),
        Some("site") => Some(Basis::Site),
        Some(other) => return Err(error(format!("by `{other}`: expected typical or site"))),
    };
    let rows = py.detach(|| {
        let request = RankRequest {
            region: region.to_string(),
            species,
            study: Study {
                seed,
                site: site.as_deref().map(Site::load).transpose().map_err(error)?,
                prices: prices
                    .as_deref()
                    .map(Prices::load)
                    .transpose()
                    .map_err(error)?,
                costs: costs
                    .as_deref()
                    .map(Costs::load)
                    .transpose()
                    .map_err(error)?,
                pruning,
                ..Study::new(years)
            },
            basis,
        };
        let ranked = rank_species(&request, Database::builtin(), &|_| {}).map_err(error)?;
        let rows: Vec<RankRow> = (ranked.iter())
            .map(|r| RankRow::of(r, request.basis()))
            .collect();
        Ok::<_, PyErr>(to_json(&rows))
    })?;
    to_python(py, &rows)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rank, m)?)?;
    Ok(())
}
