//! The crown's shadow on the site's façade through a season, and what it saves or costs in
//! energy.
//!
//! The sun walks its clear-day path (`sun.rs`) at the region's latitude on the 15th of each
//! month of the season, every hour from sunrise to sunset. Each beam that reaches a point of the
//! wall passes the crown's leaf area density and its wood's silhouette (`crown.rs`); what they
//! stop is solar heat the wall does not receive. A deciduous crown in winter stops it with its
//! bare wood alone (Heisler 1986 measured leafless street crowns stopping 30-40%). Two things make
//! the clear day a real month:
//! - the beam shines only for the month's share of possible sunshine at the region's nearest
//!   NOAA station (`climate::sunshine`); Modesto's tule-fog Decembers get 47% of it, its Julys
//!   97%;
//! - the sky's diffuse light, ASHRAE's clear-day share of the beam (`sun::diffuse_horizontal`),
//!   reaches a vertical wall from the half of the sky in front of it, and the crown takes the
//!   part of that sky it hides from each point of the wall. Diffuse light is counted in every
//!   daylight hour: under cloud it is no less than on a clear day.
//!
//! Heat through the wall: glass passes solar heat into the rooms by its solar heat gain
//! coefficient, 0.76 for clear double glazing at normal incidence (ASHRAE Handbook of
//! Fundamentals 2017, ch. 15, Table 10). Opaque wall passes the share `U * alpha / h_o` of the sun
//! on it (the sol-air temperature's excess over the air, ASHRAE Handbook of Fundamentals, ch. 18),
//! with U = 0.082 Btu/h·ft²·°F (0.466 W/m²K), the wood-frame wall of the IECC's prescriptive
//! table for climate zones 1 to 4 (IRC N1102.1.3 / IECC R402.1.4), and alpha / h_o = 0.039 m²K/W,
//! midway between ASHRAE's 0.026 for a light-coloured and 0.052 for a dark surface. The roof is
//! left out, so cooling saved is a lower bound.
//!
//! Summer heat kept out saves an air conditioner's electricity at a seasonal COP of 13 / 3.412 =
//! 3.81 (SEER 13, the US federal minimum for split systems from 2006, 10 CFR 430.32(c)); winter
//! sun kept out of the rooms must be replaced by a gas furnace at 80% AFUE (10 CFR 430.32(e)).
//! Seasons are the meteorological ones: summer June to August, winter December to February.

use crate::street::energy::climate::Climate;
use crate::street::energy::crown::Crown;
use crate::street::energy::sun::{MONTH_STARTS, beam_irradiance, diffuse_horizontal, position};
use crate::street::site::Facade;
use glam::DVec3;

/// Solar heat gain coefficient of the windows.
pub const SHGC: f64 = 0.76;
/// Seasonal coefficient of performance of the air conditioner (SEER 13 in W/W).
pub const COOLING_COP: f64 = 13.0 / 3.412;
/// Annual fuel utilisation efficiency of the furnace.
pub const FURNACE_AFUE: f64 = 0.80;
/// kBtu per kWh.
pub const KBTU_PER_KWH: f64 = 3.412;
/// U-factor of the opaque wall, W/m²K (0.082 Btu/h·ft²·°F).
pub const WALL_U: f64 = 0.082 * 5.678;
/// Solar absorptance over the outside surface's heat transfer coefficient, m²K/W.
pub const WALL_ALPHA_OVER_HO: f64 = 0.039;
/// Summer months (0 = January).
pub const SUMMER: [usize; 3] = [5, 6, 7];
/// Winter months.
pub const WINTER: [usize; 3] = [11, 0, 1];
/// Wall sample spacing, m, and most samples along one side: a crown's shadow is metres wide,
/// so a metre resolves it: cooling for a 40-year London plane 3.1 m from a south wall
/// changed by 0.2% against 0.5 m and half-hourly steps.
const SPACING: f64 = 1.0;
const MAX_SAMPLES: usize = 16;
/// Wall sample spacing for the sky the crown hides, m.
const SKY_SPACING: f64 = 2.0;
/// Time step, hours (samples at the half hours).
const STEP_H: f64 = 1.0;

/// Where the sun stands and how often it shines: a region's latitude and its months' shares of
/// possible sunshine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Share of the possible sunshine, January to December.
    pub sunshine: [f64; 12],
}

impl Sky {
    /// Every day clear.
    pub fn clear(latitude: f64) -> Sky {
        Sky {
            latitude,
            sunshine: [1.0; 12],
        }
    }

    /// A region's sky: its latitude, and its sunshine where the table has it (else clear, which
    /// the table's test rules out for every built-in region).
    pub fn of(climate: &Climate) -> Sky {
        let mut sky = Sky::clear(climate.latitude);
        if let Some(s) = crate::street::energy::climate::sunshine(climate.region) {
            sky.sunshine = s.share;
        }
        sky
    }
}

/// Share of the solar heat on a square metre of wall that enters the rooms, for walls whose
/// share `glass` is window.
pub fn heat_gain_share(glass: f64) -> f64 {
    glass * SHGC + (1.0 - glass) * WALL_U * WALL_ALPHA_OVER_HO
}

/// Sky directions in front of a wall, with their weights for isotropic diffuse light (cosine
/// of incidence times solid angle, summing to 1): 4 elevations by 8 azimuths, each at the
/// middle of its band.
fn sky_directions() -> [(DVec3, f64); 32] {
    use std::f64::consts::FRAC_PI_2;
    let mut out = [(DVec3::ZERO, 0.0); 32];
    let (de, da) = (FRAC_PI_2 / 4.0, std::f64::consts::PI / 8.0);
    let mut sum = 0.0;
    for i in 0..4 {
        let e = (i as f64 + 0.5) * de;
        for j in 0..8 {
            let a = -FRAC_PI_2 + (j as f64 + 0.5) * da;
            let dir = DVec3::new(a.sin() * e.cos(), -a.cos() * e.cos(), e.sin());
            // cos(incidence) = a.cos() * e.cos(); solid angle = e.cos() de da.
            let w = a.cos() * e.cos() * e.cos() * de * da;
            out[i * 8 + j] = (dir, w);
            sum += w;
        }
    }
    for d in &mut out {
        d.1 /= sum;
    }
    out
}

/// Sunlight on the wall through a season.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FacadeSun {
    /// Solar energy (beam and diffuse sky) the bare wall would receive, kWh.
    pub incident_kwh: f64,
    /// The part the crown stops, kWh.
    pub blocked_kwh: f64,
    /// Of `blocked_kwh`, the diffuse sky light the crown hides, kWh.
    pub diffuse_blocked_kwh: f64,
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

/// Sun on the façade over the months `months` under `sky`, with the crown in front of it.
/// The trunk stands at the origin; the wall is the plane y = `facade.setback`.
pub fn facade_sun(crown: &Crown, facade: &Facade, sky: &Sky, months: &[usize]) -> FacadeSun {
    wall_sun(crown, &Wall::of(facade), sky, months)
}

/// Sample points over a wall, at most `spacing` apart (and at most `MAX_SAMPLES` a side), just
/// in front of it, each the centre of a cell; and the cells' area, m².
fn wall_points(wall: &Wall, spacing: f64) -> (Vec<DVec3>, f64) {
    let width = wall.x[1] - wall.x[0];
    let nx = ((width / spacing).ceil() as usize).clamp(1, MAX_SAMPLES);
    let nz = ((wall.height / spacing).ceil() as usize).clamp(1, MAX_SAMPLES);
    let (dx, dz) = (width / nx as f64, wall.height / nz as f64);
    let points = (0..nx)
        .flat_map(|i| {
            (0..nz).map(move |k| {
                DVec3::new(
                    wall.x[0] + (i as f64 + 0.5) * dx,
                    wall.setback - 1e-3,
                    (k as f64 + 0.5) * dz,
                )
            })
        })
        .collect();
    (points, dx * dz)
}

/// Sun on a wall over the months `months` under `sky`, with the crown in front of it.
pub fn wall_sun(crown: &Crown, wall: &Wall, sky: &Sky, months: &[usize]) -> FacadeSun {
    wall_sun_hidden(
        crown,
        wall,
        sky,
        months,
        hidden_sky_m2(crown, wall, true),
        true,
    )
}

/// The share of the wall's sky the crown hides, summed over the wall (m²): the same in every
/// hour and season, since diffuse light comes evenly from the whole sky, so a wall's seasons
/// share it (those the crown is in leaf in, or bare: `leaves`). It changes slowly along the
/// wall, so it is sampled on a coarser grid.
fn hidden_sky_m2(crown: &Crown, wall: &Wall, leaves: bool) -> f64 {
    if crown.leaf_area <= 0.0 {
        return 0.0;
    }
    let dirs = sky_directions();
    let (coarse, coarse_area) = wall_points(wall, SKY_SPACING);
    coarse
        .iter()
        .map(|&p| {
            let hidden: f64 = dirs
                .iter()
                .map(|&(d, w)| w * (1.0 - crown.transmittance_in(p, d, leaves)))
                .sum();
            hidden * coarse_area
        })
        .sum()
}

/// [`wall_sun`] with the hidden sky already measured, through the crown in leaf or bare
/// (`leaves`).
fn wall_sun_hidden(
    crown: &Crown,
    wall: &Wall,
    sky: &Sky,
    months: &[usize],
    hidden_m2: f64,
    leaves: bool,
) -> FacadeSun {
    let (points, cell_area) = wall_points(wall, SPACING);
    let mut out = FacadeSun::default();
    let wall_area = cell_area * points.len() as f64;
    for &m in months {
        let days = (MONTH_STARTS[m + 1] - MONTH_STARTS[m]) as f64;
        let day = MONTH_STARTS[m] as f64 + 14.0;
        let sunny = sky.sunshine[m];
        let mut hour = STEP_H * 0.5;
        while hour < 24.0 {
            let sun = position(sky.latitude, day, hour);
            hour += STEP_H;
            let beam = beam_irradiance(sun.elevation);
            if beam <= 0.0 {
                continue;
            }
            // A vertical wall sees half the sky: half the horizontal diffuse, kWh per m².
            let diffuse = diffuse_horizontal(m, sun.elevation) * 0.5 * STEP_H * days / 1000.0;
            out.incident_kwh += diffuse * wall_area;
            out.blocked_kwh += diffuse * hidden_m2;
            out.diffuse_blocked_kwh += diffuse * hidden_m2;
            let rel = (sun.azimuth - wall.faces).to_radians();
            let (e, cos_e) = (sun.elevation.to_radians(), sun.elevation.to_radians().cos());
            let dir = DVec3::new(-rel.sin() * cos_e, -rel.cos() * cos_e, e.sin());
            // The wall looks out along -y: lit only while the sun is on that side.
            let incidence = -dir.y;
            if incidence <= 0.0 {
                continue;
            }
            // kWh per m² of beam, in the month's share of sunny hours.
            let on_wall = beam * incidence * STEP_H * days / 1000.0 * sunny;
            for &p in &points {
                let stopped = 1.0 - crown.transmittance_in(p, dir, leaves);
                out.incident_kwh += on_wall * cell_area;
                out.blocked_kwh += on_wall * cell_area * stopped;
                out.shaded_m2h += stopped * cell_area * STEP_H * days * sunny;
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
    /// Winter sun on the wall, through the crown's leaves or, bare, its wood.
    pub winter: FacadeSun,
    /// Air-conditioning electricity the shade saves, kWh.
    pub shade_cooling_kwh: f64,
    /// Extra furnace gas if all the winter sun kept out had been useful heat, kBtu (>= 0;
    /// a deciduous tree's from its bare wood).
    pub heating_penalty_kbtu: f64,
    /// The share of that penalty counted: the region's useful share of winter sun
    /// (`climate_effect`), 1 until a caller sets it.
    pub useful_winter_share: f64,
    /// The region's climate effect on this crown, wherever it stands (`climate_effect`):
    /// electricity and natural gas saved, kWh and kBtu. `None` where the caller adds none (the
    /// calibration, which fits it).
    pub climate: Option<(f64, f64)>,
}

impl Energy {
    /// Electricity saved in all, kWh: the shade's and the climate effect's.
    pub fn electricity_kwh(&self) -> f64 {
        self.shade_cooling_kwh + self.climate.map_or(0.0, |c| c.0)
    }

    /// The winter shade's penalty counted, kBtu: its useful share.
    pub fn counted_penalty_kbtu(&self) -> f64 {
        self.useful_winter_share * self.heating_penalty_kbtu
    }

    /// Natural gas saved in all, kBtu (negative: more is burnt): the climate effect's saving
    /// less the winter shade's counted penalty.
    pub fn natural_gas_kbtu(&self) -> f64 {
        self.climate.map_or(0.0, |c| c.1) - self.counted_penalty_kbtu()
    }
}

impl FacadeSun {
    /// Adds `o` divided by `n` (1: a second wall; n: one of n positions averaged).
    pub(in crate::street) fn add_share(&mut self, o: FacadeSun, n: f64) {
        self.incident_kwh += o.incident_kwh / n;
        self.blocked_kwh += o.blocked_kwh / n;
        self.diffuse_blocked_kwh += o.diffuse_blocked_kwh / n;
        self.shaded_m2h += o.shaded_m2h / n;
    }
}

/// The energy a crown's shade saves and costs the walls of a building whose walls are `glass`
/// windows (a share, 0..1), under `sky`. `evergreen` trees keep their leaves in winter; a
/// deciduous tree's bare winter wood stops what it stops where the crown has its wood
/// ([`Crown::with_wood`]).
pub fn energy_of_walls(
    crown: &Crown,
    walls: &[Wall],
    glass: f64,
    sky: &Sky,
    evergreen: bool,
) -> Energy {
    let (mut summer, mut winter) = (FacadeSun::default(), FacadeSun::default());
    for w in walls {
        let hidden = hidden_sky_m2(crown, w, true);
        summer.add_share(wall_sun_hidden(crown, w, sky, &SUMMER, hidden, true), 1.0);
        if evergreen {
            winter.add_share(wall_sun_hidden(crown, w, sky, &WINTER, hidden, true), 1.0);
        } else if crown.has_wood() {
            // A deciduous crown's bare wood still stops some of the winter sun.
            let bare = hidden_sky_m2(crown, w, false);
            winter.add_share(wall_sun_hidden(crown, w, sky, &WINTER, bare, false), 1.0);
        }
    }
    let gain = heat_gain_share(glass);
    Energy {
        summer,
        winter,
        shade_cooling_kwh: summer.blocked_kwh * gain / COOLING_COP,
        heating_penalty_kbtu: winter.blocked_kwh * gain / FURNACE_AFUE * KBTU_PER_KWH,
        useful_winter_share: 1.0,
        climate: None,
    }
}

/// The energy a crown's shade saves and costs a site's façade.
pub fn energy(crown: &Crown, facade: &Facade, sky: &Sky, evergreen: bool) -> Energy {
    energy_of_walls(
        crown,
        &[Wall::of(facade)],
        facade.window_share,
        sky,
        evergreen,
    )
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
        let south = facade_sun(&crown, &wall(180.0), &Sky::clear(37.64), &SUMMER);
        assert!(south.incident_kwh > 0.0);
        assert_eq!(south.blocked_kwh, 0.0);
        let north = facade_sun(&crown, &wall(0.0), &Sky::clear(37.64), &SUMMER);
        let west = facade_sun(&crown, &wall(270.0), &Sky::clear(37.64), &SUMMER);
        // In a mid-latitude summer a west wall takes more beam than a south wall (the noon sun
        // is high), and a north wall the least.
        assert!(west.incident_kwh > south.incident_kwh, "{west:?} {south:?}");
        assert!(
            north.incident_kwh < south.incident_kwh,
            "{north:?} {south:?}"
        );
        // In winter the south wall takes far more than in summer.
        let winter = facade_sun(&crown, &wall(180.0), &Sky::clear(37.64), &WINTER);
        assert!(
            winter.incident_kwh > south.incident_kwh,
            "{winter:?} {south:?}"
        );
    }

    #[test]
    fn energy_follows_the_blocked_heat() {
        // A dense block of leaves between trunk and wall, 2-6 m up.
        let crown_tree = crate::street::energy::crown::leaf_block(
            glam::Vec3::new(-4.0, 1.0, 2.0),
            [16, 8, 8],
            glam::Vec3::new(0.5, 0.35, 0.5),
        );
        let crown = Crown::of(&crown_tree);
        let e = energy(&crown, &wall(180.0), &Sky::clear(37.64), true);
        assert!(e.summer.blocked_kwh > 0.0 && e.summer.blocked_kwh < e.summer.incident_kwh);
        let expected = e.summer.blocked_kwh * heat_gain_share(0.5) / COOLING_COP;
        assert!((e.shade_cooling_kwh - expected).abs() < 1e-9);
        assert_eq!(e.electricity_kwh(), e.shade_cooling_kwh);
        assert_eq!(e.natural_gas_kbtu(), -e.heating_penalty_kbtu);
        let with = Energy {
            climate: Some((10.0, 20.0)),
            useful_winter_share: 0.25,
            ..e
        };
        assert!((with.electricity_kwh() - e.shade_cooling_kwh - 10.0).abs() < 1e-9);
        let gas = 20.0 - 0.25 * e.heating_penalty_kbtu;
        assert!((with.natural_gas_kbtu() - gas).abs() < 1e-9);
        assert!(e.heating_penalty_kbtu > 0.0);
        let bare = energy(&crown, &wall(180.0), &Sky::clear(37.64), false);
        assert_eq!(bare.heating_penalty_kbtu, 0.0);
        assert_eq!(bare.shade_cooling_kwh, e.shade_cooling_kwh);
    }

    #[test]
    fn cloud_takes_beam_but_not_the_sky_and_the_crown_hides_sky() {
        let crown = Crown::of(&crate::street::energy::crown::leaf_block(
            glam::Vec3::new(-4.0, 1.0, 2.0),
            [16, 8, 8],
            glam::Vec3::new(0.5, 0.35, 0.5),
        ));
        let clear = Sky::clear(37.64);
        let half = Sky {
            sunshine: [0.5; 12],
            ..clear
        };
        let (a, b) = (
            facade_sun(&crown, &wall(180.0), &clear, &SUMMER),
            facade_sun(&crown, &wall(180.0), &half, &SUMMER),
        );
        // The diffuse part is the same; the beam part halves.
        assert!(a.diffuse_blocked_kwh > 0.0);
        assert!((a.diffuse_blocked_kwh - b.diffuse_blocked_kwh).abs() < 1e-9);
        let beam = |f: FacadeSun| f.blocked_kwh - f.diffuse_blocked_kwh;
        assert!(
            (beam(b) - 0.5 * beam(a)).abs() < 1e-9 * beam(a).max(1.0),
            "{a:?} {b:?}"
        );
        assert!((b.shaded_m2h - 0.5 * a.shaded_m2h).abs() < 1e-9 * a.shaded_m2h);
        // With no crown, no sky is hidden; the wall still gets its diffuse light.
        let none = facade_sun(
            &Crown::of(&Skeleton::default()),
            &wall(0.0),
            &clear,
            &SUMMER,
        );
        assert_eq!((none.blocked_kwh, none.diffuse_blocked_kwh), (0.0, 0.0));
        assert!(none.incident_kwh > 0.0);
        // The sky's weights sum to one and every direction looks out of the wall, upwards.
        let dirs = sky_directions();
        assert!((dirs.iter().map(|d| d.1).sum::<f64>() - 1.0).abs() < 1e-12);
        assert!(dirs.iter().all(|(d, w)| d.y < 0.0 && d.z > 0.0 && *w > 0.0));
        // Opaque wall passes a small share: 0.466 W/m²K x 0.039 m²K/W = 1.8%.
        assert!((heat_gain_share(0.0) - 0.0182).abs() < 1e-4);
        assert!((heat_gain_share(1.0) - SHGC).abs() < 1e-12);
    }
}
