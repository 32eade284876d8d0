//! Age → DBH for the palms, fitted here to the database's own raw measurements.
//!
//! The Urban Tree Database publishes no age→DBH equation for any of its 13 palm species (its
//! table TS6 predicts their height, crown and leaf area from DBH only), yet its raw table TS3
//! records an age for 28 to 71 measured palms of each. Growth needs age→DBH, so for every palm
//! that lacks one we fit the database's own log-log form to those trees, by least squares on
//! ln DBH against ln(ln(age + 1)), with no bias term: DBH = exp(a + b ln(ln(age + 1))). Its
//! range is what it predicts between the youngest and the oldest measured tree, so growth
//! stays where the trees were measured.
//!
//! A palm thickens only while young and then mostly grows in height, and measured palms
//! scatter widely (their trunks were planted at many sizes), so the fit is a rough guide and
//! is said to be one wherever it is shown (`Row::fitted_to`).

use crate::growth::data::equations::{Equation, Form};
use crate::growth::error::GrowthError;
use std::collections::BTreeMap;

/// Fewest measured trees of a species for a fit.
const MIN_TREES: usize = 10;

/// An age→DBH fitted to the measured palms of one species in one region.
#[derive(Clone, Debug)]
pub(super) struct PalmFit {
    pub region: String,
    pub code: String,
    /// How many measured trees it was fitted to.
    pub trees: usize,
    pub equation: Equation,
}

/// An age→DBH for every palm (tree type `P..`) of `raw` (TS3, or its palm rows) with enough
/// measured trees whose DBH rises with age. `source` names the file for errors.
pub(super) fn fit_palm_ages(raw: &str, source: &str) -> Result<Vec<PalmFit>, GrowthError> {
    let text = raw.trim_start_matches('\u{feff}');
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_reader(text.as_bytes());
    let syntax = |line: usize, message: String| GrowthError::Syntax {
        file: source.to_string(),
        line,
        message,
    };
    let header = reader
        .headers()
        .map_err(|e| syntax(1, e.to_string()))?
        .clone();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h.trim().eq_ignore_ascii_case(name))
            .ok_or_else(|| syntax(1, format!("no column `{name}`")))
    };
    let (region, code, kind, age, dbh) = (
        column("Region")?,
        column("SpCode")?,
        column("TreeType")?,
        column("Age")?,
        column("DBH (cm)")?,
    );
    // (region, code) -> (ln(ln(age + 1)), ln DBH) of every palm measured with both.
    let mut trees: BTreeMap<(String, String), Vec<(f64, f64)>> = BTreeMap::new();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line() as usize);
            syntax(line, e.to_string())
        })?;
        let field = |i: usize| record.get(i).map(str::trim).unwrap_or("");
        if !field(kind).starts_with('P') {
            continue;
        }
        // Missing values are -1 in TS3; a palm under a year old has no log-log value.
        let (Ok(a), Ok(d)) = (field(age).parse::<f64>(), field(dbh).parse::<f64>()) else {
            continue;
        };
        if a >= 1.0 && d > 0.0 {
            trees
                .entry((field(region).replace(' ', ""), field(code).to_string()))
                .or_default()
                .push(((a + 1.0).ln().ln(), d.ln()));
        }
    }
    Ok(trees
        .into_iter()
        .filter(|(_, points)| points.len() >= MIN_TREES)
        .filter_map(|((region, code), points)| {
            fit(&points).map(|equation| PalmFit {
                region,
                code,
                trees: points.len(),
                equation,
            })
        })
        .collect())
}

/// Least squares of y on x; `None` unless DBH rises with age.
fn fit(points: &[(f64, f64)]) -> Option<Equation> {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(sx, sy), (x, y)| (sx + x / n, sy + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(sxy, sxx), (x, y)| {
        (sxy + (x - mx) * (y - my), sxx + (x - mx) * (x - mx))
    });
    if sxx <= 0.0 || sxy <= 0.0 {
        return None;
    }
    let b = sxy / sxx;
    let a = my - b * mx;
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (x, _)| {
            (lo.min(*x), hi.max(*x))
        });
    Some(Equation {
        form: Form::LogLogW1,
        coefficients: [a, b, 0.0, 0.0, 0.0],
        mse: 0.0,
        range: ((a + b * lo).exp(), (a + b * hi).exp()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers a log-log law from points on it.
    #[test]
    fn the_fit_recovers_a_known_law() {
        let points: Vec<(f64, f64)> = [2.0f64, 5.0, 10.0, 20.0, 40.0]
            .iter()
            .map(|&age| {
                let x = (age + 1.0).ln().ln();
                (x, 2.0 + 1.5 * x)
            })
            .collect();
        let e = fit(&points).unwrap();
        assert!((e.coefficients[0] - 2.0).abs() < 1e-9 && (e.coefficients[1] - 1.5).abs() < 1e-9);
        let at_10 = (2.0f64 + 1.5 * (11.0f64).ln().ln()).exp();
        assert!((e.raw(10.0) - at_10).abs() < 1e-9);
        // Falling DBH is not a growth law.
        let falling: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x, -y)).collect();
        assert!(fit(&falling).is_none());
    }
}
