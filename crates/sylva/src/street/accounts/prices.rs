//! What a unit of each benefit is worth: built-in regional prices with their source, or a
//! user's TOML file.
//!
//! The built-in prices are i-Tree Streets' regional defaults, which come from the regional
//! Community Tree Guides of the USDA Forest Service's Center for Urban Forest Research (for the
//! Inland Valleys, Modesto: McPherson et al. 1999, "Tree Guidelines for San Joaquin Valley
//! Communities"). They are read from the table OpenTreeMap ships with them (otm-core commit
//! b26aec8c, `treemap/species/codes.py`, `ITREE_REGIONS`; the R package treeco's `tmoney`
//! table, from i-Tree, holds the same 144 figures) and converted here to metric units. They are
//! in the dollars of each guide's year, which is why `--prices` exists.
//!
//! The air-quality prices are per pound of pollutant taken up or not emitted. i-Tree gives
//! biogenic VOCs no price of their own; they are charged at the region's VOC price, the price
//! of the same ozone precursor when a power plant emits it (the R package treeco does the same;
//! OpenTreeMap leaves BVOCs unpriced and says it is unsure).
//!
//! Aesthetics and property value are priced per m² of leaf area gained in a year from the
//! region's median home price (`street::accounts::aesthetics`, McPherson 2007's method); a prices file
//! gives its own `median_home_price` (and `location_factor`) or `leaf_gain_per_m2`.
//!
//! Costs are in `costs.rs`.

use crate::street::accounts::aesthetics;
use crate::street::error::StreetError;
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
    /// Ozone taken up, $/kg.
    pub ozone_per_kg: Option<f64>,
    /// NOx taken up or not emitted, $/kg.
    pub nox_per_kg: Option<f64>,
    /// PM10 taken up or not emitted, $/kg.
    pub pm10_per_kg: Option<f64>,
    /// SO2 taken up or not emitted, $/kg.
    pub so2_per_kg: Option<f64>,
    /// VOCs not emitted (and biogenic VOCs emitted, as a cost), $/kg.
    pub voc_per_kg: Option<f64>,
    /// Aesthetics and property value: a square metre of leaf area gained in a year, $/m²
    /// (`street::accounts::aesthetics`).
    pub leaf_gain_per_m2: Option<f64>,
}

/// US gallons per m³.
const GAL_PER_M3: f64 = 264.172;
/// Pounds per kg.
const LB_PER_KG: f64 = 2.20462;

/// One region's i-Tree Streets defaults, in i-Tree's units.
struct Itree {
    region: &'static str,
    kwh: f64,
    kbtu: f64,
    /// $/gal of rain held back.
    gal: f64,
    /// $/lb of CO2, O3, NOx, PM10, SO2 and VOC.
    lb: [f64; 6],
}

const fn r(region: &'static str, kwh: f64, kbtu: f64, gal: f64, lb: [f64; 6]) -> Itree {
    Itree {
        region,
        kwh,
        kbtu,
        gal,
        lb,
    }
}

/// i-Tree Streets' regional defaults ($/lb: CO2, O3, NOx, PM10, SO2, VOC).
const ITREE: [Itree; 16] = [
    r(
        "CenFla",
        0.13182,
        0.002678,
        0.003,
        [0.0034, 2.2, 2.2, 2.1, 2.01, 1.03],
    ),
    r(
        "GulfCo",
        0.09339,
        0.019742,
        0.00605,
        [0.0075, 1.04, 1.04, 0.76, 1.28, 1.48],
    ),
    r(
        "InlEmp",
        0.20148,
        0.0066871,
        0.0055,
        [0.00334, 3.84, 3.84, 4.63, 2.43, 1.92],
    ),
    r(
        "InlVal",
        0.1166,
        0.0125278,
        0.0078,
        [0.0075, 5.0032, 12.79, 9.41, 3.72, 4.69],
    ),
    r(
        "InterW",
        0.078844,
        0.011,
        0.005,
        [0.00334, 0.61, 0.61, 1.14, 1.42, 0.19],
    ),
    r(
        "LoMidW",
        0.068,
        0.00973,
        0.0062,
        [0.00334, 0.82, 0.82, 0.99, 1.5, 0.3],
    ),
    r(
        "MidWst",
        0.0759,
        0.0098,
        0.0271,
        [0.0075, 3.334, 3.334, 2.84, 2.06, 3.75],
    ),
    // Shipped as 0.636 $/kWh, ten times every neighbour's: read as a slip and left out below.
    r(
        "NMtnPr",
        0.636,
        0.009066,
        0.0108,
        [0.0075, 2.77, 2.77, 0.49, 0.98, 2.61],
    ),
    r(
        "NoCalC",
        0.1323,
        0.013048,
        0.004,
        [0.0075, 10.3101, 10.3101, 11.7901, 3.67, 7.22],
    ),
    r(
        "NoEast",
        0.1401,
        0.01408,
        0.0008,
        [0.00334, 4.59, 4.59, 8.31, 3.48, 2.31],
    ),
    r(
        "PacfNW",
        0.0512,
        0.01146,
        0.02779,
        [0.00334, 0.94, 0.94, 1.67, 1.88, 0.35],
    ),
    r(
        "Piedmt",
        0.0759,
        0.01046,
        0.0099,
        [0.0075, 6.55, 6.55, 2.49, 1.97, 6.26],
    ),
    r(
        "SoCalC",
        0.16281,
        0.0131,
        0.00183,
        [0.0150, 16.44, 16.44, 51.32, 21.47, 3.34],
    ),
    r(
        "SWDsrt",
        0.1208,
        0.009409,
        0.0048,
        [0.0075, 4.0, 4.0, 6.0, 15.7, 4.0],
    ),
    r(
        "TpIntW",
        0.060936,
        0.0114245,
        0.005,
        [0.00334, 0.51, 0.51, 0.92, 0.06, 0.14],
    ),
    r(
        "Tropic",
        0.122,
        0.0235,
        0.01,
        [0.00334, 1.47, 1.47, 1.34, 1.52, 0.6],
    ),
];

impl Prices {
    /// The built-in prices of a region: i-Tree's own, or for the Sacramento Valley, which
    /// i-Tree does not cover, those of the region whose tables stand in for it (the Inland
    /// Valleys), saying so in `source`.
    pub fn builtin(region: &str) -> Option<Prices> {
        let (reference, why) = crate::street::accounts::itree::reference_region(region)?;
        let t = ITREE.iter().find(|t| t.region == reference)?;
        let per_kg = |i: usize| Some(t.lb[i] * LB_PER_KG);
        let home = aesthetics::home_price(region);
        Some(Prices {
            source: format!(
                "i-Tree Streets regional defaults for {reference} (regional Community Tree \
                 Guide, USDA Forest Service), as shipped in OpenTreeMap otm-core \
                 ITREE_REGIONS{}{}",
                why.map(|w| format!("; {w}")).unwrap_or_default(),
                home.map(|h| format!("; {}", h.describe()))
                    .unwrap_or_default()
            ),
            // The guides span 1999-2010; i-Tree does not say which year's dollars each is.
            year: 0,
            electricity_per_kwh: (reference != "NMtnPr").then_some(t.kwh),
            natural_gas_per_kbtu: Some(t.kbtu),
            stormwater_per_m3: Some(t.gal * GAL_PER_M3),
            co2_per_kg: per_kg(0),
            ozone_per_kg: per_kg(1),
            nox_per_kg: per_kg(2),
            pm10_per_kg: per_kg(3),
            so2_per_kg: per_kg(4),
            voc_per_kg: per_kg(5),
            leaf_gain_per_m2: home
                .map(|h| aesthetics::price_per_m2(h.price, aesthetics::STREET_LOCATION_FACTOR)),
        })
    }

    /// [`Prices::builtin`], made once per region and shared: for callers that price many
    /// trees (a city's inventory).
    pub fn builtin_shared(region: &str) -> Option<&'static Prices> {
        static ALL: std::sync::OnceLock<Vec<(&'static str, Prices)>> = std::sync::OnceLock::new();
        ALL.get_or_init(|| {
            (crate::street::accounts::itree::regions().keys().copied())
                .chain(["SacVal"])
                .filter_map(|r| Some((r, Prices::builtin(r)?)))
                .collect()
        })
        .iter()
        .find(|(r, _)| *r == region)
        .map(|(_, p)| p)
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
            ozone_per_kg: f64,
            nox_per_kg: f64,
            pm10_per_kg: f64,
            so2_per_kg: f64,
            voc_per_kg: f64,
            // Aesthetics, optional: a price per m² of leaf gained, or a median home price (and
            // a location factor); without either they are reported as not computed.
            leaf_gain_per_m2: Option<f64>,
            median_home_price: Option<f64>,
            location_factor: Option<f64>,
        }
        let f: File = parse(&text, &file)?;
        if let Some(p) = f.median_home_price
            && !(p.is_finite() && p > 0.0 && p <= 1e8)
        {
            return Err(value(
                &file,
                "median_home_price",
                p,
                "dollars, over 0 and at most 1e8",
            ));
        }
        if let Some(c) = f.location_factor {
            if !(0.0..=1.0).contains(&c) {
                return Err(value(&file, "location_factor", c, "a factor, 0 to 1"));
            }
            if f.median_home_price.is_none() {
                return Err(StreetError::Syntax {
                    file: file.clone(),
                    message: "location_factor needs median_home_price".into(),
                });
            }
        }
        if f.median_home_price.is_some() && f.leaf_gain_per_m2.is_some() {
            return Err(StreetError::Syntax {
                file: file.clone(),
                message: "give aesthetics either as leaf_gain_per_m2 or as median_home_price, \
                          not both"
                    .into(),
            });
        }
        for (key, v) in [
            ("electricity_per_kwh", f.electricity_per_kwh),
            ("natural_gas_per_kbtu", f.natural_gas_per_kbtu),
            ("stormwater_per_m3", f.stormwater_per_m3),
            ("co2_per_kg", f.co2_per_kg),
            ("ozone_per_kg", f.ozone_per_kg),
            ("nox_per_kg", f.nox_per_kg),
            ("pm10_per_kg", f.pm10_per_kg),
            ("so2_per_kg", f.so2_per_kg),
            ("voc_per_kg", f.voc_per_kg),
        ]
        .into_iter()
        .chain(f.leaf_gain_per_m2.map(|v| ("leaf_gain_per_m2", v)))
        {
            non_negative(&file, key, v)?;
        }
        Ok(Prices {
            source: f.source,
            year: f.year,
            electricity_per_kwh: Some(f.electricity_per_kwh),
            natural_gas_per_kbtu: Some(f.natural_gas_per_kbtu),
            stormwater_per_m3: Some(f.stormwater_per_m3),
            co2_per_kg: Some(f.co2_per_kg),
            ozone_per_kg: Some(f.ozone_per_kg),
            nox_per_kg: Some(f.nox_per_kg),
            pm10_per_kg: Some(f.pm10_per_kg),
            so2_per_kg: Some(f.so2_per_kg),
            voc_per_kg: Some(f.voc_per_kg),
            leaf_gain_per_m2: f.leaf_gain_per_m2.or(f.median_home_price.map(|p| {
                aesthetics::price_per_m2(
                    p,
                    f.location_factor
                        .unwrap_or(aesthetics::STREET_LOCATION_FACTOR),
                )
            })),
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
        // 12.79 $/lb of NOx (Modesto's guide) is 28.20 $/kg.
        assert!((p.nox_per_kg.unwrap() - 28.197).abs() < 1e-2);
        // 0.88% of Stanislaus County's $140,000 over 675 m².
        assert!((p.leaf_gain_per_m2.unwrap() - 1.8252).abs() < 1e-3);
        assert!(p.source.contains("140000") && p.source.contains("McPherson 2007"));
        let sacramento = Prices::builtin("SacVal").unwrap();
        assert_eq!(sacramento.electricity_per_kwh, Some(0.1166));
        assert!(
            sacramento.source.contains("Sacramento"),
            "{}",
            sacramento.source
        );
        assert_eq!(Prices::builtin("NMtnPr").unwrap().electricity_per_kwh, None);
        assert!(Prices::builtin("Nowhere").is_none());
    }

    #[test]
    fn a_prices_file_missing_a_price_or_with_a_bad_one_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("prices.toml");
        std::fs::write(&path, "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\n").unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(e.contains("prices.toml") && e.contains("co2_per_kg"), "{e}");
        const AIR: &str = "ozone_per_kg = 11.0\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\n";
        std::fs::write(&path, format!("source = \"x\"\nyear = 2024\nelectricity_per_kwh = -0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n{AIR}")).unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(
            e.contains("electricity_per_kwh") && e.contains(">= 0"),
            "{e}"
        );
        // A price for air quality missing, or a non-finite aesthetic price: each named.
        std::fs::write(&path, "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n").unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(e.contains("ozone_per_kg"), "{e}");
        std::fs::write(&path, format!("source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n{AIR}leaf_gain_per_m2 = nan\n")).unwrap();
        let e = Prices::load(&path).unwrap_err().to_string();
        assert!(
            e.contains("leaf_gain_per_m2") && e.contains("finite"),
            "{e}"
        );
        std::fs::write(&path, format!("source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n{AIR}leaf_gain_per_m2 = 0.5\n")).unwrap();
        assert_eq!(Prices::load(&path).unwrap().leaf_gain_per_m2, Some(0.5));
        // Or from a home price, with a location factor; bad ones named.
        let base = format!(
            "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n{AIR}"
        );
        std::fs::write(
            &path,
            format!("{base}median_home_price = 337500.0\nlocation_factor = 0.5\n"),
        )
        .unwrap();
        let p = Prices::load(&path).unwrap().leaf_gain_per_m2.unwrap();
        assert!((p - 2.2).abs() < 1e-9, "{p}");
        for (bad, key) in [
            ("median_home_price = -5.0\n", "median_home_price"),
            ("median_home_price = inf\n", "median_home_price"),
            (
                "median_home_price = 300000.0\nlocation_factor = 1.5\n",
                "location_factor",
            ),
            (
                "median_home_price = 300000.0\nlocation_factor = nan\n",
                "location_factor",
            ),
            ("location_factor = 0.5\n", "location_factor"),
            (
                "median_home_price = 300000.0\nleaf_gain_per_m2 = 2.0\n",
                "median_home_price",
            ),
        ] {
            std::fs::write(&path, format!("{base}{bad}")).unwrap();
            let e = Prices::load(&path).unwrap_err().to_string();
            assert!(e.contains("prices.toml") && e.contains(key), "{bad}: {e}");
        }
    }
}
