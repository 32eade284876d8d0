//! The Urban Tree Database's 17 climate regions by their reference cities (table TS1): a tree
//! with no `--region` takes the region of the reference city nearest to it.

/// Each region's reference city (TS1) and where it stands: city centres in decimal degrees,
/// WGS84, to 0.001 degree (about 100 m), as gazetteers list them (the US Geological Survey's
/// Geographic Names Information System). TS1 places Longview in Oregon; the city is Longview,
/// Washington, across the Columbia from Oregon, and it is placed there.
pub const REFERENCE_CITIES: [(&str, &str, f64, f64); 17] = [
    ("CenFla", "Orlando, FL", -81.379, 28.538),
    ("GulfCo", "Charleston, SC", -79.931, 32.776),
    ("InlEmp", "Claremont, CA", -117.720, 34.097),
    ("InlVal", "Modesto, CA", -120.997, 37.639),
    ("InterW", "Albuquerque, NM", -106.650, 35.084),
    ("LoMidW", "Indianapolis, IN", -86.158, 39.768),
    ("MidWst", "Minneapolis, MN", -93.265, 44.978),
    ("NMtnPr", "Fort Collins, CO", -105.084, 40.585),
    ("NoCalC", "Berkeley, CA", -122.273, 37.872),
    ("NoEast", "Queens, NY", -73.795, 40.728),
    ("PacfNW", "Longview, WA", -122.938, 46.138),
    ("Piedmt", "Charlotte, NC", -80.843, 35.227),
    ("SacVal", "Sacramento, CA", -121.494, 38.582),
    ("SoCalC", "Santa Monica, CA", -118.491, 34.020),
    ("SWDsrt", "Glendale, AZ", -112.186, 33.539),
    ("TpIntW", "Boise, ID", -116.202, 43.615),
    ("Tropic", "Honolulu, HI", -157.858, 21.307),
];

/// Mean radius of the Earth, m (IUGG: (2a + b) / 3 of WGS84).
const EARTH_RADIUS: f64 = 6_371_008.8;

/// Great-circle distance between two points given in degrees, m (haversine).
pub fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (l1, p1) = (a.0.to_radians(), a.1.to_radians());
    let (l2, p2) = (b.0.to_radians(), b.1.to_radians());
    let h = ((p2 - p1) / 2.0).sin().powi(2) + p1.cos() * p2.cos() * ((l2 - l1) / 2.0).sin().powi(2);
    2.0 * EARTH_RADIUS * h.sqrt().min(1.0).asin()
}

/// Where region `code`'s reference city stands (longitude, latitude), if it is one of the 17.
pub fn city_of(code: &str) -> Option<(f64, f64)> {
    REFERENCE_CITIES
        .iter()
        .find(|r| r.0.eq_ignore_ascii_case(code))
        .map(|r| (r.2, r.3))
}

/// The region whose reference city is nearest to `lon`, `lat` (degrees).
pub fn nearest(lon: f64, lat: f64) -> &'static str {
    REFERENCE_CITIES
        .iter()
        .min_by(|a, b| {
            distance((lon, lat), (a.2, a.3)).total_cmp(&distance((lon, lat), (b.2, b.3)))
        })
        .map_or("InlVal", |r| r.0)
}

/// Regions by the distance of their reference city from region `from`'s, nearest first
/// (`from` itself first).
pub fn by_distance_from(from: &str) -> Vec<&'static str> {
    let here = city_of(from).unwrap_or((0.0, 0.0));
    let mut all: Vec<(f64, &'static str)> = REFERENCE_CITIES
        .iter()
        .map(|r| (distance(here, (r.2, r.3)), r.0))
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(b.1)));
    all.into_iter().map(|a| a.1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_region_of_the_database_has_its_city_and_trees_find_the_nearest() {
        let db = sylva::growth::Database::builtin();
        for r in db.regions() {
            assert!(city_of(&r.code).is_some(), "{}", r.code);
        }
        // One degree of latitude is about 111.2 km on the mean sphere.
        assert!((distance((0.0, 0.0), (0.0, 1.0)) - 111_195.0).abs() < 10.0);
        // Manhattan is nearest to Queens; Seattle to Longview; Phoenix to Glendale; Chicago
        // to Indianapolis (265 km) rather than Minneapolis (570 km).
        assert_eq!(nearest(-73.97, 40.78), "NoEast");
        assert_eq!(nearest(-122.33, 47.61), "PacfNW");
        assert_eq!(nearest(-112.07, 33.45), "SWDsrt");
        assert_eq!(nearest(-87.63, 41.88), "LoMidW");
        let order = by_distance_from("InlVal");
        assert_eq!(order[0], "InlVal");
        assert_eq!(order[1], "SacVal");
        assert_eq!(order.len(), 17);
    }
}
