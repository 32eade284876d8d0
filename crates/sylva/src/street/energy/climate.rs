//! What the benefit models need to know about a region's reference city: where the sun stands
//! (latitude), how often it shines, and how much rain falls, in how many events.
//!
//! Latitudes are the reference cities' (U.S. Census Bureau Gazetteer place coordinates, rounded
//! to 0.01 degree). Sunshine is NOAA's percent of possible sunshine at the nearest station of its
//! Comparative Climatic Data (`data/climate/possible-sunshine.csv`, whose README names the file
//! and its version). Rainfall is given only where a source was found; elsewhere the crown's own
//! interception falls back on i-Tree's (`street::accounts::ledger`).

use std::sync::OnceLock;

/// A year's rain: total depth and the number of days it falls on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rain {
    /// Mean annual precipitation, mm.
    pub annual_mm: f64,
    /// Mean number of days a year with measurable precipitation (0.01 in or more).
    pub days: f64,
    /// Where the figures come from.
    pub source: &'static str,
}

/// A region's reference city as the benefit models see it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Climate {
    /// Region code as the growth equations write it (`InlVal`).
    pub region: &'static str,
    /// Latitude of the reference city, degrees north.
    pub latitude: f64,
    /// Its rain, where sourced.
    pub rain: Option<Rain>,
}

const IN: f64 = 25.4;

/// Every region of the Urban Tree Database (table TS1's reference cities).
pub const CLIMATES: [Climate; 17] = [
    Climate {
        region: "CenFla",
        latitude: 28.54, // Orlando
        rain: None,
    },
    Climate {
        region: "GulfCo",
        latitude: 32.78, // Charleston
        rain: Some(Rain {
            annual_mm: 51.06 * IN,
            days: 119.0,
            source: "Charleston County Economic Development, climate data (National Weather \
                     Service normals), 2017: 51.06 in, 119 days",
        }),
    },
    Climate {
        region: "InlEmp",
        latitude: 34.10, // Claremont
        rain: None,
    },
    Climate {
        region: "InlVal",
        latitude: 37.64, // Modesto
        rain: Some(Rain {
            annual_mm: 13.0 * IN,
            days: 56.0,
            source: "BestPlaces, Modesto CA climate (NOAA normals): 13 in, 56 days of \
                     precipitation",
        }),
    },
    Climate {
        region: "InterW",
        latitude: 35.08, // Albuquerque
        rain: None,
    },
    Climate {
        region: "LoMidW",
        latitude: 39.77, // Indianapolis
        rain: None,
    },
    Climate {
        region: "MidWst",
        latitude: 44.98, // Minneapolis
        rain: Some(Rain {
            annual_mm: 31.9 * IN,
            days: 111.6,
            source: "BestPlaces, Minneapolis MN climate (NOAA normals): 31.9 in, 111.6 days of \
                     precipitation",
        }),
    },
    Climate {
        region: "NMtnPr",
        latitude: 40.59, // Fort Collins
        rain: None,
    },
    Climate {
        region: "NoCalC",
        latitude: 37.87, // Berkeley
        rain: None,
    },
    Climate {
        region: "NoEast",
        latitude: 40.73, // Queens
        rain: None,
    },
    Climate {
        region: "PacfNW",
        latitude: 46.14, // Longview
        rain: None,
    },
    Climate {
        region: "Piedmt",
        latitude: 35.23, // Charlotte
        rain: None,
    },
    Climate {
        region: "SacVal",
        latitude: 38.58, // Sacramento
        rain: Some(Rain {
            annual_mm: 17.93 * IN,
            days: 62.0,
            source: "Sun City Roseville, Sacramento climate (NOAA normals): 17.93 in, 62 days \
                     of precipitation",
        }),
    },
    Climate {
        region: "SoCalC",
        latitude: 34.02, // Santa Monica
        rain: None,
    },
    Climate {
        region: "SWDsrt",
        latitude: 33.54, // Glendale AZ
        rain: None,
    },
    Climate {
        region: "TpIntW",
        latitude: 43.62, // Boise
        rain: None,
    },
    Climate {
        region: "Tropic",
        latitude: 21.31, // Honolulu
        rain: None,
    },
];

/// The climate of a region code, if the database has that region.
pub fn climate(region: &str) -> Option<&'static Climate> {
    CLIMATES.iter().find(|c| c.region == region)
}

/// How much of the possible sunshine a region's reference city gets, month by month.
#[derive(Clone, Debug, PartialEq)]
pub struct Sunshine {
    /// Region code.
    pub region: String,
    /// The NOAA station read, as NOAA names it.
    pub station: String,
    /// Its distance from the reference city, km.
    pub km: f64,
    /// Share of the possible sunshine, January to December, 0..1.
    pub share: [f64; 12],
}

const SUNSHINE_CSV: &str = include_str!("../../../data/climate/possible-sunshine.csv");

/// Reads `possible-sunshine.csv`: a header, then one row per region (`region, reference_city,
/// station, wban, period, jan … dec, km`), each month a whole percent from 0 to 100.
pub fn parse_sunshine(text: &str) -> Result<Vec<Sunshine>, String> {
    let mut lines = text.lines().enumerate();
    let header = lines.next().map(|l| l.1).unwrap_or_default();
    let cols: Vec<&str> = header.split(',').collect();
    if cols.len() != 18 || cols[0] != "region" || cols[5] != "jan" || cols[17] != "km" {
        return Err(format!(
            "possible-sunshine.csv: header {header:?} is not region, reference_city, station, \
             wban, period, jan … dec, km"
        ));
    }
    let mut out = Vec::new();
    for (n, line) in lines.filter(|(_, l)| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').collect();
        let bad = |what: &str| format!("possible-sunshine.csv line {}: {what}", n + 1);
        if f.len() != 18 {
            return Err(bad(&format!("{} fields, 18 expected", f.len())));
        }
        let mut share = [0.0; 12];
        for (m, v) in f[5..17].iter().enumerate() {
            let p: f64 = v
                .parse()
                .map_err(|_| bad(&format!("{} is {v:?}, not a number", cols[5 + m])))?;
            if !(0.0..=100.0).contains(&p) {
                return Err(bad(&format!(
                    "{} is {p}; a percentage is 0 to 100",
                    cols[5 + m]
                )));
            }
            share[m] = p / 100.0;
        }
        let km: f64 = f[17].parse().map_err(|_| bad("km is not a number"))?;
        out.push(Sunshine {
            region: f[0].to_string(),
            station: f[2].to_string(),
            km,
            share,
        });
    }
    Ok(out)
}

/// The sunshine of a region, if the built-in table has it.
pub fn sunshine(region: &str) -> Option<&'static Sunshine> {
    static TABLE: OnceLock<Vec<Sunshine>> = OnceLock::new();
    TABLE
        .get_or_init(|| parse_sunshine(SUNSHINE_CSV).expect("the built-in sunshine table parses"))
        .iter()
        .find(|s| s.region == region)
}

/// Storage of water on plant surfaces, mm per m² of leaf or bark surface: i-Tree Hydro's
/// interception storage (Wang, Endreny & Nowak 2008, J. American Water Resources Association
/// 44(1):75-85, after Aston 1979).
pub const STORAGE_MM: f64 = 0.2;

/// Rain a crown holds back in a year, m³: each of the year's rain days brings the mean depth,
/// and the crown keeps what lands on its projection up to its storage (`STORAGE_MM` over leaf
/// and bark surface), which then evaporates. Leaves are assumed on every rain day (see
/// docs/benefits.md on deciduous trees in winter-rain climates).
pub fn interception_m3(rain: &Rain, surface_m2: f64, crown_projection_m2: f64) -> f64 {
    if rain.days.is_nan() || rain.days <= 0.0 {
        return 0.0;
    }
    let storage = STORAGE_MM * 1e-3 * surface_m2.max(0.0);
    let per_event = rain.annual_mm / rain.days * 1e-3 * crown_projection_m2.max(0.0);
    rain.days * storage.min(per_event)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_region_has_a_climate() {
        for r in crate::growth::Database::builtin().regions() {
            assert!(climate(&r.code).is_some(), "{}", r.code);
        }
        assert_eq!(climate("InlVal").unwrap().rain.unwrap().days, 56.0);
    }

    #[test]
    fn every_region_has_its_sunshine_and_a_damaged_table_is_refused() {
        for c in &CLIMATES {
            let s = sunshine(c.region).unwrap_or_else(|| panic!("{}", c.region));
            assert!(s.share.iter().all(|v| (0.0..=1.0).contains(v)), "{s:?}");
        }
        // Modesto reads Sacramento: tule-fog Decembers, cloudless Julys (NOAA CCD 2018).
        let v = sunshine("InlVal").unwrap();
        assert_eq!(v.station, "SACRAMENTO CA");
        assert_eq!((v.share[11], v.share[6]), (0.47, 0.97));
        let head = SUNSHINE_CSV.lines().next().unwrap();
        let row = |r: &str| format!("{head}\n{r}\n");
        let e = parse_sunshine(&row("X,c,s,1,p,1,2,3,4,5,6,7,8,9,10,11,120,0")).unwrap_err();
        assert!(
            e.contains("line 2") && e.contains("dec") && e.contains("0 to 100"),
            "{e}"
        );
        let e = parse_sunshine(&row("X,c,s,1,p,1,2,3,4,5,6,7,8,9,10,11,x,0")).unwrap_err();
        assert!(e.contains("dec is \"x\""), "{e}");
        let e = parse_sunshine(&row("X,c,s,1,p,1,2")).unwrap_err();
        assert!(e.contains("7 fields"), "{e}");
        assert!(parse_sunshine("a,b\n").unwrap_err().contains("header"));
    }

    #[test]
    fn interception_is_storage_limited_or_rain_limited() {
        let rain = Rain {
            annual_mm: 560.0,
            days: 56.0,
            source: "",
        };
        // 10 mm per event on 20 m² of crown: 0.2 m³ falls; 100 m² of leaves store 0.02 m³.
        assert!((interception_m3(&rain, 100.0, 20.0) - 56.0 * 0.02).abs() < 1e-12);
        // 1,000 m² store 0.2 m³, as much as falls.
        assert!((interception_m3(&rain, 2000.0, 20.0) - 56.0 * 0.2).abs() < 1e-12);
        assert_eq!(interception_m3(&rain, 0.0, 20.0), 0.0);
    }
}
