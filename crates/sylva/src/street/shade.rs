//! The crown's shadow on the site's façade through a season, and what it saves or costs in
//! energy.
//!
//! The sun walks its clear-day path (`sun.rs`) at the region's latitude on the 15th of each
//! month of the season, every half hour from sunrise to sunset. Each beam that reaches a point
//! of the wall passes the crown's leaf area density (`crown.rs`); what the leaves stop is solar
//! heat the wall does not receive.
//!
//! Only the windows' share is turned into energy: glass passes solar heat into the rooms by its
//! solar heat gain coefficient, 0.76 for clear double glazing at normal incidence (ASHRAE
//! Handbook of Fundamentals 2017, ch. 15, Table 10); opaque wall is left out, so cooling saved
//! is a lower bound. Summer heat kept out saves an air conditioner's electricity at a seasonal
//! COP of 13 / 3.412 = 3.81 (SEER 13, the US federal minimum for split systems from 2006, 10
//! CFR 430.32(c)); winter sun kept out of the rooms must be replaced by a gas furnace at 80%
//! AFUE (10 CFR 430.32(e)). Seasons are the meteorological ones: summer June to August, winter
//! December to February.

use super::crown::Crown;
use super::site::Facade;
use super::sun::{MONTH_STARTS, beam_irradiance, position};
use glam::DVec3;

/// Solar heat gain coefficient of the windows.
pub const SHGC: f64 = 0.76;
/// Seasonal coefficient of performance of the air conditioner (SEER 13 in W/W).
pub const COOLING_COP: f64 = 13.0 / 3.412;
/// Annual fuel utilisation efficiency of the furnace.
pub const FURNACE_AFUE: f64 = 0.80;
/// kBtu per kWh.
pub const KBTU_PER_KWH: f64 = 3.412;
/// Summer months (0 = January).
pub const SUMMER: [usize; 3] = [5, 6, 7];
/// Winter months.
pub const WINTER: [usize; 3] = [11, 0, 1];
/// Wall sample spacing, m, and most samples along one side: a crown's shadow is metres wide,
/// so a metre resolves it: cooling for a 40-year London plane 3.1 m from a south wall
/// changed by 0.2% against 0.5 m and half-hourly steps.
const SPACING: f64 = 1.0;
const MAX_SAMPLES: usize = 16;
/// Time step, hours (samples at the half hours).
const STEP_H: f64 = 1.0;

/// Sunlight on the wall through a season.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FacadeSun {
    /// Beam solar energy the bare wall would receive, kWh.
    pub incident_kwh: f64,
    /// The part the crown stops, kWh.
    pub blocked_kwh: f64,
    /// Wall area in the crown's shade over time, m²·h (shade weighted by how much it stops).
    pub shaded_m2h: f64,
}

/// A wall in the tree's frame: the plane y = `setback` (the trunk at the origin, x along the
/// wall), from x0 to x1 and from the ground to `height`, looking out along -y towards the
/// compass direction `faces`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall {
    /// y of the wall, m.
    pub setback: f64,
    /// Height, m.
    pub height: f64,
    /// Its ends along x, m.
    pub x: [f64; 2],
    /// Compass direction it faces, degrees clockwise from north.
    pub faces: f64,
}

impl Wall {
    /// A site's façade: centred on the tree.
    pub fn of(facade: &Facade) -> Wall {
        Wall {
            setback: facade.setback,
            height: facade.height,
            x: [-facade.width / 2.0, facade.width / 2.0],
            faces: facade.faces,
        }
    }
}

/// Sun on the façade over the months `months` at `latitude`, with the crown in front of it.
/// The trunk stands at the origin; the wall is the plane y = `facade.setback`.
pub fn facade_sun(crown: &Crown, facade: &Facade, latitude: f64, months: &[usize]) -> FacadeSun {
    wall_sun(crown, &Wall::of(facade), latitude, months)
}

/// Sun on a wall over the months `months` at `latitude`, with the crown in front of it.
pub fn wall_sun(crown: &Crown, wall: &Wall, latitude: f64, months: &[usize]) -> FacadeSun {
    let width = wall.x[1] - wall.x[0];
    let nx = ((width / SPACING).ceil() as usize).clamp(1, MAX_SAMPLES);
    let nz = ((wall.height / SPACING).ceil() as usize).clamp(1, MAX_SAMPLES);
    let (dx, dz) = (width / nx as f64, wall.height / nz as f64);
    let cell_area = dx * dz;
    let mut out = FacadeSun::default();
    for &m in months {
        let days = (MONTH_STARTS[m + 1] - MONTH_STARTS[m]) as f64;
        let day = MONTH_STARTS[m] as f64 + 14.0;
        let mut hour = STEP_H * 0.5;
        while hour < 24.0 {
            let sun = position(latitude, day, hour);
            hour += STEP_H;
            let beam = beam_irradiance(sun.elevation);
            if beam <= 0.0 {
                continue;
            }
            let rel = (sun.azimuth - wall.faces).to_radians();
            let (e, cos_e) = (sun.elevation.to_radians(), sun.elevation.to_radians().cos());
            let dir = DVec3::new(-rel.sin() * cos_e, -rel.cos() * cos_e, e.sin());
            // The wall looks out along -y: lit only while the sun is on that side.
            let incidence = -dir.y;
            if incidence <= 0.0 {
                continue;
            }
            let on_wall = beam * incidence * STEP_H * days / 1000.0; // kWh per m²
            for i in 0..nx {
                for k in 0..nz {
                    let p = DVec3::new(
                        wall.x[0] + (i as f64 + 0.5) * dx,
                        wall.setback - 1e-3,
                        (k as f64 + 0.5) * dz,
                    );
                    let stopped = 1.0 - crown.transmittance(p, dir);
                    out.incident_kwh += on_wall * cell_area;
                    out.blocked_kwh += on_wall * cell_area * stopped;
                    out.shaded_m2h += stopped * cell_area * STEP_H * days;
                }
            }
        }
    }
    out
}

/// Energy effects of a crown's shade on one façade in one year.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energy {
    /// Summer sun on the wall.
    pub summer: FacadeSun,
    /// Winter sun on the wall (zero for a tree that is bare then).
    pub winter: FacadeSun,
    /// Air-conditioning electricity saved, kWh.
    pub cooling_kwh: f64,
    /// Extra furnace gas for the winter sun kept out, kBtu (evergreens only; >= 0).
    pub heating_penalty_kbtu: f64,
}

impl FacadeSun {
    /// Adds `o` divided by `n` (1: a second wall; n: one of n positions averaged).
    pub(super) fn add_share(&mut self, o: FacadeSun, n: f64) {
        self.incident_kwh += o.incident_kwh / n;
        self.blocked_kwh += o.blocked_kwh / n;
        self.shaded_m2h += o.shaded_m2h / n;
    }
}

/// The energy a crown saves and costs the walls of a building whose walls are `glass` windows
/// (a share, 0..1), as [`energy`] counts it for one façade.
pub fn energy_of_walls(
    crown: &Crown,
    walls: &[Wall],
    glass: f64,
    latitude: f64,
    evergreen: bool,
) -> Energy {
    let (mut summer, mut winter) = (FacadeSun::default(), FacadeSun::default());
    for w in walls {
        summer.add_share(wall_sun(crown, w, latitude, &SUMMER), 1.0);
        if evergreen {
            winter.add_share(wall_sun(crown, w, latitude, &WINTER), 1.0);
        }
    }
    Energy {
        summer,
        winter,
        cooling_kwh: summer.blocked_kwh * glass * SHGC / COOLING_COP,
        heating_penalty_kbtu: winter.blocked_kwh * glass * SHGC / FURNACE_AFUE * KBTU_PER_KWH,
    }
}

/// The energy a crown saves and costs a façade. `evergreen` trees keep their leaves in winter;
/// a deciduous tree's bare winter branches are not counted.
pub fn energy(crown: &Crown, facade: &Facade, latitude: f64, evergreen: bool) -> Energy {
    let summer = facade_sun(crown, facade, latitude, &SUMMER);
    let winter = if evergreen {
        facade_sun(crown, facade, latitude, &WINTER)
    } else {
        FacadeSun::default()
    };
    let glass = facade.window_share;
    Energy {
        summer,
        winter,
        cooling_kwh: summer.blocked_kwh * glass * SHGC / COOLING_COP,
        heating_penalty_kbtu: winter.blocked_kwh * glass * SHGC / FURNACE_AFUE * KBTU_PER_KWH,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Skeleton;

    fn wall(faces: f64) -> Facade {
        Facade {
            setback: 4.0,
            height: 6.0,
            width: 10.0,
            faces,
            window_share: 0.5,
        }
    }

    #[test]
    fn a_bare_site_blocks_nothing_and_a_north_wall_gets_little_summer_sun() {
        let crown = Crown::of(&Skeleton::default());
        let south = facade_sun(&crown, &wall(180.0), 37.64, &SUMMER);
        assert!(south.incident_kwh > 0.0);
        assert_eq!(south.blocked_kwh, 0.0);
        let north = facade_sun(&crown, &wall(0.0), 37.64, &SUMMER);
        let west = facade_sun(&crown, &wall(270.0), 37.64, &SUMMER);
        // In a mid-latitude summer a west wall takes more beam than a south wall (the noon sun
        // is high), and a north wall the least.
        assert!(west.incident_kwh > south.incident_kwh, "{west:?} {south:?}");
        assert!(
            north.incident_kwh < south.incident_kwh,
            "{north:?} {south:?}"
        );
        // In winter the south wall takes far more than in summer.
        let winter = facade_sun(&crown, &wall(180.0), 37.64, &WINTER);
        assert!(
            winter.incident_kwh > south.incident_kwh,
            "{winter:?} {south:?}"
        );
    }

    #[test]
    fn energy_follows_the_blocked_heat() {
        // A dense block of leaves between trunk and wall, 2-6 m up.
        let crown_tree = super::super::crown::leaf_block(
            glam::Vec3::new(-4.0, 1.0, 2.0),
            [16, 8, 8],
            glam::Vec3::new(0.5, 0.35, 0.5),
        );
        let crown = Crown::of(&crown_tree);
        let e = energy(&crown, &wall(180.0), 37.64, true);
        assert!(e.summer.blocked_kwh > 0.0 && e.summer.blocked_kwh < e.summer.incident_kwh);
        let expected = e.summer.blocked_kwh * 0.5 * SHGC / COOLING_COP;
        assert!((e.cooling_kwh - expected).abs() < 1e-9);
        assert!(e.heating_penalty_kbtu > 0.0);
        let bare = energy(&crown, &wall(180.0), 37.64, false);
        assert_eq!(bare.heating_penalty_kbtu, 0.0);
        assert_eq!(bare.cooling_kwh, e.cooling_kwh);
    }
}
