//! Where the sun stands and how strongly it shines on a clear day.
//!
//! Position: the declination of Spencer (1971, "Fourier series representation of the position
//! of the sun", Search 2(5):172), the Fourier series NOAA's solar calculator documents, at a
//! given day of the year and local solar time (hours from solar noon give the hour angle
//! directly, so the equation of time is not needed for whole days). Elevation and azimuth
//! follow from spherical trigonometry.
//!
//! Beam: the clear-sky direct normal irradiance of Meinel & Meinel (1976, "Applied Solar
//! Energy", Addison-Wesley): `1353 * 0.7^(AM^0.678)` W/m², with the air mass AM of Kasten &
//! Young (1989, Applied Optics 28(22):4735). Clouds are not modelled: the figures are an upper
//! bound, close in dry summers such as the Central Valley's.

use std::f64::consts::PI;

/// The sun seen from the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Angle above the horizon, degrees.
    pub elevation: f64,
    /// Compass direction, degrees clockwise from north.
    pub azimuth: f64,
}

/// Solar declination on day `day` of the year (1 = 1 January) at `solar_hour`, radians.
pub fn declination(day: f64, solar_hour: f64) -> f64 {
    let g = 2.0 * PI / 365.0 * (day - 1.0 + (solar_hour - 12.0) / 24.0);
    0.006918 - 0.399912 * g.cos() + 0.070257 * g.sin() - 0.006758 * (2.0 * g).cos()
        + 0.000907 * (2.0 * g).sin()
        - 0.002697 * (3.0 * g).cos()
        + 0.00148 * (3.0 * g).sin()
}

/// The sun at `latitude` (degrees north) on `day` at local solar time `solar_hour`.
pub fn position(latitude: f64, day: f64, solar_hour: f64) -> SunPosition {
    let phi = latitude.to_radians();
    let delta = declination(day, solar_hour);
    let h = ((solar_hour - 12.0) * 15.0).to_radians();
    let sin_e = phi.sin() * delta.sin() + phi.cos() * delta.cos() * h.cos();
    let elevation = sin_e.clamp(-1.0, 1.0).asin();
    // Azimuth from south, positive to the west; then from north, clockwise.
    let from_south = h.sin().atan2(h.cos() * phi.sin() - delta.tan() * phi.cos());
    SunPosition {
        elevation: elevation.to_degrees(),
        azimuth: (from_south.to_degrees() + 180.0).rem_euclid(360.0),
    }
}

/// Clear-sky direct normal irradiance with the sun `elevation` degrees up, W/m² (0 below the
/// horizon).
pub fn beam_irradiance(elevation: f64) -> f64 {
    if elevation <= 0.0 {
        return 0.0;
    }
    let zenith = 90.0 - elevation;
    let air_mass = 1.0 / (zenith.to_radians().cos() + 0.50572 * (96.07995 - zenith).powf(-1.6364));
    1353.0 * 0.7f64.powf(air_mass.powf(0.678))
}

/// The clear-day ratio of diffuse sky irradiance on a horizontal surface to the direct normal
/// beam, January to December: the `C` of the ASHRAE clear-day model (ASHRAE Handbook of
/// Fundamentals 1985, ch. 27, Table 1, after Threlkeld and Jordan 1958). Hazier summer skies
/// scatter more.
pub const DIFFUSE_RATIO: [f64; 12] = [
    0.058, 0.060, 0.071, 0.097, 0.121, 0.134, 0.136, 0.122, 0.092, 0.073, 0.063, 0.057,
];

/// Clear-day diffuse sky irradiance on a horizontal surface in month `month` (0 = January) with
/// the sun `elevation` degrees up, W/m²: ASHRAE's ratio [`DIFFUSE_RATIO`] times the beam.
pub fn diffuse_horizontal(month: usize, elevation: f64) -> f64 {
    DIFFUSE_RATIO[month] * beam_irradiance(elevation)
}

/// First day of each month in a 365-day year, and the day after the last.
pub const MONTH_STARTS: [u32; 13] = [1, 32, 60, 91, 121, 152, 182, 213, 244, 274, 305, 335, 366];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noon_elevation_is_90_minus_latitude_plus_declination() {
        // Near the June solstice (day 172) the declination is about +23.44 degrees.
        let d = declination(172.0, 12.0).to_degrees();
        assert!((d - 23.44).abs() < 0.1, "{d}");
        let p = position(37.64, 172.0, 12.0);
        assert!((p.elevation - (90.0 - 37.64 + d)).abs() < 1e-6, "{p:?}");
        assert!((p.azimuth - 180.0).abs() < 1e-6, "{p:?}");
        // December solstice: -23.44.
        let d = declination(355.0, 12.0).to_degrees();
        assert!((d + 23.44).abs() < 0.1, "{d}");
    }

    #[test]
    fn morning_sun_is_in_the_east_and_sets_at_the_right_hour() {
        let p = position(37.64, 172.0, 8.0);
        assert!(p.azimuth > 60.0 && p.azimuth < 100.0, "{p:?}");
        let p = position(37.64, 172.0, 16.0);
        assert!(p.azimuth > 260.0 && p.azimuth < 300.0, "{p:?}");
        // Sunset hour angle: cos h = -tan(phi) tan(delta); about 7.3 h after noon in June.
        let (phi, d) = (37.64f64.to_radians(), declination(172.0, 19.0));
        let h = (-phi.tan() * d.tan()).acos().to_degrees() / 15.0;
        assert!(position(37.64, 172.0, 12.0 + h - 0.05).elevation > 0.0);
        assert!(position(37.64, 172.0, 12.0 + h + 0.05).elevation < 0.0);
    }

    #[test]
    fn meinel_beam_at_zenith_and_horizon() {
        // Air mass 1 at the zenith: 1353 * 0.7 = 947 W/m².
        assert!((beam_irradiance(90.0) - 947.1).abs() < 0.5);
        assert!(beam_irradiance(10.0) < beam_irradiance(30.0));
        assert_eq!(beam_irradiance(-1.0), 0.0);
        // ASHRAE's July ratio: 0.136 of the beam comes from the sky on a horizontal surface.
        assert!((diffuse_horizontal(6, 90.0) - 0.136 * 947.1).abs() < 0.1);
        assert_eq!(diffuse_horizontal(0, -5.0), 0.0);
    }
}
