//! Where a tree stands on the Earth: longitude and latitude from a projected coordinate system
//! (state plane, UTM, ...) named by EPSG code, the Earth-centred frame 3D Tiles draws in, and a
//! city's local east-north-up frame, in which tiles and trees are laid out in metres.

use crate::error::CityError;
use glam::DVec3;
use proj4rs::proj::Proj;

/// WGS84's semi-major axis, m, and flattening (NIMA TR8350.2, the World Geodetic System 1984
/// definition).
const WGS84_A: f64 = 6_378_137.0;
const WGS84_F: f64 = 1.0 / 298.257_223_563;

/// Earth-centred, Earth-fixed coordinates (EPSG:4978), m, of a point `height` metres above the
/// WGS84 ellipsoid at `lon`, `lat` degrees.
pub fn ecef(lon: f64, lat: f64, height: f64) -> DVec3 {
    let (lon, lat) = (lon.to_radians(), lat.to_radians());
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let n = WGS84_A / (1.0 - e2 * lat.sin().powi(2)).sqrt();
    DVec3::new(
        (n + height) * lat.cos() * lon.cos(),
        (n + height) * lat.cos() * lon.sin(),
        (n * (1.0 - e2) + height) * lat.sin(),
    )
}

/// A local east-north-up frame on the ellipsoid: a city's trees in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFrame {
    /// The frame's origin, ECEF, m.
    pub origin: DVec3,
    east: DVec3,
    north: DVec3,
    up: DVec3,
}

impl LocalFrame {
    /// The frame at `lon`, `lat` degrees, on the ellipsoid.
    pub fn at(lon: f64, lat: f64) -> Self {
        let (l, p) = (lon.to_radians(), lat.to_radians());
        LocalFrame {
            origin: ecef(lon, lat, 0.0),
            east: DVec3::new(-l.sin(), l.cos(), 0.0),
            north: DVec3::new(-p.sin() * l.cos(), -p.sin() * l.sin(), p.cos()),
            up: DVec3::new(p.cos() * l.cos(), p.cos() * l.sin(), p.sin()),
        }
    }

    /// The frame's origin as longitude and latitude, degrees (from its up direction, which is
    /// the ellipsoid's normal there).
    pub fn lon_lat(&self) -> (f64, f64) {
        (
            self.up.y.atan2(self.up.x).to_degrees(),
            self.up.z.clamp(-1.0, 1.0).asin().to_degrees(),
        )
    }

    /// A point given in ECEF, in this frame (east, north, up), m.
    pub fn local(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        DVec3::new(d.dot(self.east), d.dot(self.north), d.dot(self.up))
    }

    /// The point `lon`, `lat` degrees and `height` m above the ellipsoid, in this frame.
    pub fn of(&self, lon: f64, lat: f64, height: f64) -> DVec3 {
        self.local(ecef(lon, lat, height))
    }

    /// The frame as a 3D Tiles `transform`: the column-major 4 x 4 matrix that takes a point
    /// in this frame to ECEF.
    pub fn to_ecef_matrix(&self) -> [f64; 16] {
        let (e, n, u, o) = (self.east, self.north, self.up, self.origin);
        [
            e.x, e.y, e.z, 0.0, n.x, n.y, n.z, 0.0, u.x, u.y, u.z, 0.0, o.x, o.y, o.z, 1.0,
        ]
    }
}

/// A projected coordinate system, to longitude and latitude.
pub struct Projection {
    epsg: u16,
    from: Proj,
    to: Proj,
    unit: Option<(&'static str, f64)>,
}

impl std::fmt::Debug for Projection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Projection(EPSG:{})", self.epsg)
    }
}

impl Projection {
    /// The EPSG code `text` names (`EPSG:2263`, `epsg:2263` or `2263`).
    pub fn parse_epsg(text: &str) -> Result<u32, CityError> {
        let code = text.trim().to_ascii_uppercase();
        let code = code.strip_prefix("EPSG:").unwrap_or(&code);
        code.parse::<u32>().map_err(|_| {
            CityError::setting(
                "--crs",
                format!("`{text}` is not an EPSG code; expected e.g. EPSG:2263"),
            )
        })
    }

    /// The coordinate system of EPSG code `code` (as `--crs EPSG:2263` names it).
    pub fn epsg(code: u32) -> Result<Self, CityError> {
        let flag = |m: String| CityError::setting("--crs", m);
        let def = u16::try_from(code)
            .ok()
            .and_then(crs_definitions::from_code)
            .ok_or_else(|| {
                flag(format!(
                    "EPSG:{code} is not in the EPSG registry Sylva carries (projected and \
                     geographic systems up to EPSG:32767, e.g. EPSG:2263, EPSG:32618)"
                ))
            })?;
        let from = Proj::from_proj_string(def.proj4)
            .map_err(|e| flag(format!("EPSG:{code} ({}): {e}", def.proj4)))?;
        let to = Proj::from_proj_string("+proj=longlat +datum=WGS84 +no_defs")
            .map_err(|e| flag(e.to_string()))?;
        Ok(Projection {
            epsg: def.code,
            from,
            to,
            unit: unit_of(def.proj4),
        })
    }

    /// The length unit of a projected system's coordinates, as PROJ names it (`m`, `us-ft`,
    /// ...), and its length in metres; none for a geographic system (degrees) or a unit
    /// Sylva does not know.
    pub fn unit(&self) -> Option<(&'static str, f64)> {
        if self.from.is_latlong() {
            None
        } else {
            self.unit
        }
    }

    /// The EPSG code.
    pub fn code(&self) -> u16 {
        self.epsg
    }

    /// Longitude and latitude, degrees (WGS84), of the point `x`, `y` in this system's units.
    pub fn lon_lat(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let mut p = (x, y, 0.0);
        // Geographic systems take degrees in and give radians back, as PROJ.4 did.
        if self.from.is_latlong() {
            p = (x.to_radians(), y.to_radians(), 0.0);
        }
        proj4rs::transform::transform(&self.from, &self.to, &mut p).ok()?;
        let (lon, lat) = (p.0.to_degrees(), p.1.to_degrees());
        (lon.is_finite() && lat.is_finite() && lat.abs() <= 90.0).then_some((lon, lat))
    }
}

/// The length units of projected systems, in metres, as PROJ defines them (PROJ's unit table,
/// `proj -lu`: the international foot 0.3048 m, the US survey foot 1200/3937 m, ...).
const UNITS: [(&str, f64); 10] = [
    ("m", 1.0),
    ("km", 1000.0),
    ("cm", 0.01),
    ("mm", 0.001),
    ("ft", 0.3048),
    ("us-ft", 1200.0 / 3937.0),
    ("yd", 0.9144),
    ("us-yd", 3600.0 / 3937.0),
    ("mi", 1609.344),
    ("us-mi", 6_336_000.0 / 3937.0),
];

/// The unit of a PROJ.4 definition: its `+units=`, or `+to_meter=` when that matches one of
/// [`UNITS`] (some definitions give the US survey foot only as a number); metres when it names
/// neither, PROJ's default.
fn unit_of(proj4: &str) -> Option<(&'static str, f64)> {
    let arg = |name: &str| {
        proj4
            .split_whitespace()
            .find_map(|a| a.strip_prefix(name))
            .map(str::to_string)
    };
    if let Some(u) = arg("+units=") {
        return UNITS.iter().find(|(n, _)| *n == u).copied();
    }
    if let Some(v) = arg("+to_meter=") {
        let v: f64 = v.parse().ok()?;
        return UNITS
            .iter()
            .find(|(_, m)| (m / v - 1.0).abs() < 1e-6)
            .copied();
    }
    Some(UNITS[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ecef_and_the_local_frame_agree_with_known_values() {
        // On the equator at the prime meridian the ellipsoid is the semi-major axis away.
        let p = ecef(0.0, 0.0, 0.0);
        assert!((p - DVec3::new(WGS84_A, 0.0, 0.0)).length() < 1e-6);
        // At the pole, the semi-minor axis b = a (1 - f) = 6,356,752.314 m.
        assert!((ecef(0.0, 90.0, 0.0).z - 6_356_752.314_245).abs() < 1e-3);
        // A point 100 m north and 10 m up of a frame's origin reads so in the frame (within
        // the ellipsoid's curvature over 100 m: under a millimetre up, here).
        let f = LocalFrame::at(-73.95, 40.7);
        // The frame gives back the longitude and latitude it was made at.
        let (lon, lat) = f.lon_lat();
        assert!(
            (lon + 73.95).abs() < 1e-9 && (lat - 40.7).abs() < 1e-9,
            "{lon} {lat}"
        );
        let north = f.of(-73.95, 40.7 + 100.0 / 111_033.0, 10.0);
        assert!(north.x.abs() < 1e-3, "{north}");
        assert!((north.y - 100.0).abs() < 0.2, "{north}");
        assert!((north.z - 10.0).abs() < 0.01, "{north}");
        // The matrix takes the frame's points back to ECEF.
        let m = glam::DMat4::from_cols_array(&f.to_ecef_matrix());
        let back = m.transform_point3(north);
        assert!((back - ecef(-73.95, 40.7 + 100.0 / 111_033.0, 10.0)).length() < 1e-6);
    }

    #[test]
    fn state_plane_feet_reach_the_right_street_corner() {
        // NAD83 / New York Long Island (ftUS): the 2015 street-tree census gives each tree
        // both; its first row (tree 180683, Queens) reads x 1027431.148, y 202756.7687 and
        // longitude -73.84421522, latitude 40.72309177.
        let p = Projection::epsg(2263).unwrap();
        let (lon, lat) = p.lon_lat(1_027_431.148, 202_756.768_7).unwrap();
        assert!((lon - -73.844_215_22).abs() < 2e-6, "{lon}");
        assert!((lat - 40.723_091_77).abs() < 2e-6, "{lat}");
        // Its coordinates are US survey feet; UTM's are metres; WGS84's degrees have none.
        assert_eq!(p.unit(), Some(("us-ft", 1200.0 / 3937.0)));
        assert_eq!(Projection::epsg(32618).unwrap().unit(), Some(("m", 1.0)));
        assert_eq!(Projection::epsg(4326).unwrap().unit(), None);
        let e = Projection::epsg(99_999).unwrap_err().to_string();
        assert!(e.contains("--crs") && e.contains("EPSG:99999"), "{e}");
    }
}
