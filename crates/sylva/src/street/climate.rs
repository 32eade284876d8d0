//! What the benefit models need to know about a region's reference city: where the sun stands
//! (latitude) and how much rain falls, in how many events.
//!
//! Latitudes are the reference cities' (U.S. Census Bureau Gazetteer place coordinates, rounded
//! to 0.01 degree). Rainfall is given only where a source was found; elsewhere interception is
//! reported as not computed, never as zero.

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
