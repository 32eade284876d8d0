//! What a unit of each benefit is worth: built-in regional prices with their source, or a
//! user's TOML file.
//!
//! The built-in prices are i-Tree Streets' regional defaults, which come from the regional
//! Community Tree Guides of the USDA Forest Service's Center for Urban Forest Research (for the
//! Inland Valleys, Modesto: McPherson et al. 1999, "Tree Guidelines for San Joaquin Valley
//! Communities"). They are read from the table OpenTreeMap ships with them (otm-core,
//! `treemap/species/codes.py`, `ITREE_REGIONS`) and converted here to metric units. They are
//! in the dollars of each guide's year, which is why `--prices` exists.
//!
//! Costs are in `costs.rs`.

use super::StreetError;
use serde::Deserialize;
use std::path::Path;

/// Prices of the benefits, dollars per unit.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Prices {
    /// Where the prices come from.
    pub source: String,
    /// The year of the dollars.
    pub year: u32,
    /// Electricity, $/kWh.
    pub electricity_per_kwh: Option<f64>,
    /// Natural gas, $/kBtu.
    pub natural_gas_per_kbtu: Option<f64>,
    /// Stormwater held back, $/m³.
    pub stormwater_per_m3: Option<f64>,
    /// CO2, $/kg.
    pub co2_per_kg: Option<f64>,
}

/// US gallons per m³.
const GAL_PER_M3: f64 = 264.172;
/// Pounds per kg.
const LB_PER_KG: f64 = 2.20462;

/// i-Tree Streets' regional defaults: region, $/kWh, $/kBtu, $/gal of water, $/lb of CO2.
const ITREE: [(&str, f64, f64, f64, f64); 16] = [
    ("CenFla", 0.13182, 0.002678, 0.003, 0.0034),
    ("GulfCo", 0.09339, 0.019742, 0.00605, 0.0075),
    ("InlEmp", 0.20148, 0.0066871, 0.0055, 0.00334),
    ("InlVal", 0.1166, 0.0125278, 0.0078, 0.0075),
    ("InterW", 0.078844, 0.011, 0.005, 0.00334),
    ("LoMidW", 0.068, 0.00973, 0.0062, 0.00334),
    ("MidWst", 0.0759, 0.0098, 0.0271, 0.0075),
    // Shipped as 0.636 $/kWh, ten times every neighbour's: read as a slip and left out below.
    ("NMtnPr", 0.636, 0.009066, 0.0108, 0.0075),
    ("NoCalC", 0.1323, 0.013048, 0.004, 0.0075),
    ("NoEast", 0.1401, 0.01408, 0.0008, 0.00334),
    ("PacfNW", 0.0512, 0.01146, 0.02779, 0.00334),
    ("Piedmt", 0.0759, 0.01046, 0.0099, 0.0075),
    ("SoCalC", 0.16281, 0.0131, 0.00183, 0.0150),
    ("SWDsrt", 0.1208, 0.009409, 0.0048, 0.0075),
    ("TpIntW", 0.060936, 0.0114245, 0.005, 0.00334),
    ("Tropic", 0.122, 0.0235, 0.01, 0.00334),
];

impl Prices {
    /// The built-in prices of a region, if i-Tree has the region (the Sacramento Valley, added
    /// to the database later, has none).
    pub fn builtin(region: &str) -> Option<Prices> {
        let &(_, kwh, kbtu, gal, lb) = ITREE.iter().find(|r| r.0 == region)?;
        Some(Prices {
            source: format!(
                "i-Tree Streets regional defaults for {region} (regional Community Tree Guide, \
                 USDA Forest Service), as shipped in OpenTreeMap otm-core ITREE_REGIONS"
            ),
            // The guides span 1999-2010; i-Tree does not say which year's dollars each is.
            year: 0,
            electricity_per_kwh: (region != "NMtnPr").then_some(kwh),
            natural_gas_per_kbtu: Some(kbtu),
            stormwater_per_m3: Some(gal * GAL_PER_M3),
            co2_per_kg: Some(lb * LB_PER_KG),
        })
    }

    /// Reads a prices file: every price, its source and year.
    pub fn load(path: &Path) -> Result<Prices, StreetError> {
        let file = path.display().to_string();
        let text = read(path)?;
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            source: String,
            year: u32,
            electricity_per_kwh: f64,
            natural_gas_per_kbtu: f64,
            stormwater_per_m3: f64,
            co2_per_kg: f64,
        }
        let f: File = parse(&text, &file)?;
        for (key, v) in [
            ("electricity_per_kwh", f.electricity_per_kwh),
            ("natural_gas_per_kbtu", f.natural_gas_per_kbtu),
            ("stormwater_per_m3", f.stormwater_per_m3),
            ("co2_per_kg", f.co2_per_kg),
        ] {
            non_negative(&file, key, v)?;
        }
        Ok(Prices {
            source: f.source,
            year: f.year,
            electricity_per_kwh: Some(f.electricity_per_kwh),
            natural_gas_per_kbtu: Some(f.natural_gas_per_kbtu),
            stormwater_per_m3: Some(f.stormwater_per_m3),
            co2_per_kg: Some(f.co2_per_kg),
        })
    }
}

pub(super) fn read(path: &Path) -> Result<String, StreetError> {
    std::fs::read_to_string(path).map_err(|e| StreetError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// TOML into `T`, errors naming the file and the line.
pub(super) fn parse<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &str,
) -> Result<T, StreetError> {
    toml::from_str(text).map_err(|e| StreetError::Syntax {
        file: file.to_string(),
        message: e.message().to_string()
            + &e.span()
                .map(|s| format!(" (line {})", text[..s.start].lines().count().max(1)))
                .unwrap_or_default(),
    })
}

pub(super) fn value(file: &str, key: &str, v: f64, allowed: &str) -> StreetError {
    StreetError::Value {
        file: file.to_string(),
        key: key.to_string(),
        value: v,
        allowed: allowed.to_string(),
    }
}

pub(super) fn non_negative(file: &str, key: &str, v: f64) -> Result<(), StreetError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(value(file, key, v, "a finite amount >= 0"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modesto_prices_in_metric() {
        let p = Prices::builtin("InlVal").unwrap();
        // 0.0075 $/lb of CO2 is 16.5 $/t; 0.0078 $/gal is 2.06 $/m³.
        assert!((p.co2_per_kg.unwrap() - 0.016535).abs() < 1e-5);
        assert!((p.stormwater_per_m3.unwrap() - 2.0605).abs() < 1e-3);
        assert_eq!(p.electricity_per_kwh, Some(0.1166));
        assert!(Prices::builtin("SacVal").is_none());
        assert_eq!(Prices::builtin("NMtnPr").unwrap().electricity_per_kwh, None);
    }

    #[test]
    fn a_prices_file_missing_a_price_or_with_a_bad_one_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("prices.toml");
        std::fs::write(&path, "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\n").unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(e.contains("prices.toml") && e.contains("co2_per_kg"), "{e}");
        std::fs::write(&path, "source = \"x\"\nyear = 2024\nelectricity_per_kwh = -0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n").unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(
            e.contains("electricity_per_kwh") && e.contains(">= 0"),
            "{e}"
        );
    }
}
