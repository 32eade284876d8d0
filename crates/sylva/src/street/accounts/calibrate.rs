//! The site model held to the reference: the grown tree placed around a standard house at
//! i-Tree Streets' distance classes and eight directions, its shade's energy averaged, and set
//! beside i-Tree's own figures for the species at the same DBH.
//!
//! i-Tree's energy figures are for a tree at its usual spread of positions around a building:
//! three distance classes (adjacent, up to 6 m from the wall; near, 6 to 12 m; far, 12 to 18
//! m; McPherson and Simpson 1999, PSW-GTR-171) and the compass directions. Its position
//! frequencies by region were not reachable, so the 24 positions (each class's middle
//! distance, eight directions) are weighted evenly; the report says so.
//!
//! The standard house (`STANDARD_HOUSE`) is the median new single-family house of 1999, 2,030
//! sq ft (U.S. Census Bureau, Characteristics of New Housing, in the Statistical Abstract's
//! table 1197), on one floor with 8 ft walls (the standard US stud wall), square; its windows
//! are 15% of the floor area, spread evenly over the four walls, as the International Energy
//! Conservation Code's standard reference design for residential performance rating sets them
//! (IRC N1102 / IECC R405, "Specifications for the standard reference and proposed designs").

use crate::growth::Measured;
use crate::growth::survey::report::Cohort;
use crate::street::accounts::typical::Reference;
use crate::street::energy::climate_effect::{ClimateEffect, Point, fit};
use crate::street::energy::crown::Crown;
use crate::street::energy::shade::{Energy, Sky, Wall, energy_of_walls};

/// A square one-storey house.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct House {
    /// Side of the square footprint, m.
    pub side: f64,
    /// Wall height, m.
    pub height: f64,
    /// Share of every wall that is window.
    pub glass: f64,
}

const FT: f64 = 0.3048;

/// 2,030 sq ft on one floor, 8 ft walls, windows 15% of the floor area on four walls.
pub const STANDARD_HOUSE: House = {
    let floor = 2030.0 * FT * FT;
    // sqrt is not const: 13.7331 m is the side of 188.59 m², checked by a test.
    let side = 13.7331;
    let height = 8.0 * FT;
    House {
        side,
        height,
        glass: 0.15 * floor / (4.0 * side * height),
    }
};

/// i-Tree's distance classes, each by its middle distance from the wall, m.
pub const DISTANCES: [(&str, f64); 3] = [("adjacent", 3.0), ("near", 9.0), ("far", 15.0)];

/// The eight compass directions a tree stands in from the house, degrees.
pub const BEARINGS: [f64; 8] = [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0];

/// The house's walls as a tree at compass `bearing` from it, `distance` m from its nearest
/// point, sees them: only walls the tree stands in front of.
pub fn walls_seen(house: &House, bearing: f64, distance: f64) -> Vec<Wall> {
    let half = house.side / 2.0;
    let (s, c) = bearing.to_radians().sin_cos();
    // Off a side, the distance is from the wall; off a corner, from the corner.
    let diagonal = (bearing / 45.0).round() as i64 % 2 == 1;
    let r = if diagonal {
        half * std::f64::consts::SQRT_2 + distance
    } else {
        half + distance
    };
    let tree = (r * s, r * c); // east, north of the house's centre
    let mut out = Vec::new();
    for faces in [0.0f64, 90.0, 180.0, 270.0] {
        let (sf, cf) = faces.to_radians().sin_cos();
        // The tree's distance in front of the wall's plane.
        let setback = tree.0 * sf + tree.1 * cf - half;
        if setback < 0.3 {
            continue;
        }
        // Along the wall: x = -(v · t) with t = (cos f, -sin f), v from the tree to the
        // wall's centre (shade.rs's frame: the sun at azimuth a lies along
        // (-sin(a - f), -cos(a - f))).
        let centre = (half * sf - tree.0, half * cf - tree.1);
        let x = -(centre.0 * cf - centre.1 * sf);
        out.push(Wall {
            setback,
            height: house.height,
            x: [x - half, x + half],
            faces,
        });
    }
    out
}

/// The crown's energy effect on `house`, averaged evenly over the 24 positions.
pub fn typical_energy(crown: &Crown, house: &House, sky: &Sky, evergreen: bool) -> Energy {
    let mut sum = Energy::default();
    let n = (DISTANCES.len() * BEARINGS.len()) as f64;
    for (_, d) in DISTANCES {
        for b in BEARINGS {
            let e = energy_of_walls(crown, &walls_seen(house, b, d), house.glass, sky, evergreen);
            sum.shade_cooling_kwh += e.shade_cooling_kwh / n;
            sum.heating_penalty_kbtu += e.heating_penalty_kbtu / n;
            sum.summer.add_share(e.summer, n);
            sum.winter.add_share(e.winter, n);
        }
    }
    sum
}

/// One species at one DBH: Sylva's shade at typical position beside i-Tree's figures.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Region code.
    pub region: String,
    /// Species code.
    pub code: String,
    /// The DBH asked for, cm.
    pub target_cm: f64,
    /// The age the grown tree first reached it, and its DBH then; `None` if its data end first.
    pub reached: Option<(f64, f64)>,
    /// The grown crown's projection, m².
    pub projection_m2: f64,
    /// Whether the species is a deciduous broadleaf (its tree type `BD*`).
    pub deciduous_broadleaf: bool,
    /// Whether it keeps its leaves in winter (its tree type `?E?`).
    pub evergreen: bool,
    /// Sylva's shade alone: electricity saved, kWh, and natural gas saved (negative), kBtu.
    pub shade: (f64, f64),
    /// The region's climate effect added to it, fitted without this species
    /// ([`add_climate_left_out`]); `None` until then, or where it cannot be fitted.
    pub climate: Option<(f64, f64)>,
    /// The useful share of winter sun the shade's penalty was counted at, fitted likewise.
    pub useful_share: Option<f64>,
    /// Sylva: electricity saved, kWh (shade and climate effect).
    pub cooling_kwh: f64,
    /// Sylva: natural gas saved, kBtu (negative: the winter penalty exceeds the climate effect).
    pub gas_kbtu: f64,
    /// i-Tree at the same DBH: electricity, kWh, and natural gas, kBtu.
    pub itree: (f64, f64),
}

impl Row {
    /// Cooling within ±35% of i-Tree's electricity.
    pub fn cooling_in_bounds(&self) -> bool {
        (self.cooling_kwh - self.itree.0).abs() <= 0.35 * self.itree.0.abs()
    }

    /// Heating within ±50% or ±30 kBtu of i-Tree's natural gas, whichever is wider, with the
    /// same sign.
    pub fn heating_in_bounds(&self) -> bool {
        let (ours, theirs) = (self.gas_kbtu, self.itree.1);
        let bound = (0.5 * theirs.abs()).max(30.0);
        let same_sign = ours * theirs >= 0.0 || ours.abs() < 1e-9 || theirs.abs() < 1e-9;
        (ours - theirs).abs() <= bound && same_sign
    }
}

/// Grows `m` yearly and, as it first reaches each DBH of `targets` (cm, rising), sets its
/// shade at typical position around the standard house beside i-Tree's figures.
pub fn calibrate(m: &Measured, targets: &[f64], seed: u64, sky: &Sky) -> Vec<Row> {
    let reference = Reference::of(m).ok();
    let evergreen = m.species.tree_type.get(1..2) == Some("E");
    let deciduous_broadleaf = m.species.tree_type.starts_with("BD");
    let mut cohort = Cohort::new(vec![m.clone()], seed);
    let mut out = Vec::new();
    let mut next = 0;
    let last = m.ages.1.floor();
    let mut age = m.ages.0.ceil().max(1.0);
    while next < targets.len() && age <= last {
        let skeleton = cohort.advance_to(age).remove(0);
        let dbh = cohort.history[0].last().map_or(0.0, |r| r.model.dbh);
        while next < targets.len() && dbh >= targets[next] {
            let crown = Crown::of(&skeleton);
            let e = typical_energy(&crown, &STANDARD_HOUSE, sky, evergreen);
            let t = reference.as_ref().map(|r| r.at(dbh, None).amounts);
            out.push(Row {
                region: m.region.code.clone(),
                code: m.species.code.clone(),
                target_cm: targets[next],
                reached: Some((age, dbh)),
                projection_m2: crown.projection,
                deciduous_broadleaf,
                evergreen,
                shade: (e.shade_cooling_kwh, -e.heating_penalty_kbtu),
                climate: None,
                useful_share: None,
                cooling_kwh: e.shade_cooling_kwh,
                gas_kbtu: -e.heating_penalty_kbtu,
                itree: t.map_or((f64::NAN, f64::NAN), |t| {
                    (t.electricity_kwh, t.natural_gas_kbtu)
                }),
            });
            next += 1;
        }
        age += 1.0;
    }
    for &t in &targets[next..] {
        out.push(Row {
            region: m.region.code.clone(),
            code: m.species.code.clone(),
            target_cm: t,
            reached: None,
            projection_m2: f64::NAN,
            deciduous_broadleaf,
            evergreen,
            shade: (f64::NAN, f64::NAN),
            climate: None,
            useful_share: None,
            cooling_kwh: f64::NAN,
            gas_kbtu: f64::NAN,
            itree: (f64::NAN, f64::NAN),
        });
    }
    out
}

/// [`calibrate`] for many species at once, in parallel, at the latitude of each one's region
/// (species whose region has no latitude are left out).
pub fn calibrate_all(species: &[Measured], targets: &[f64], seed: u64) -> Vec<Vec<Row>> {
    use rayon::prelude::*;
    species
        .par_iter()
        .filter_map(|m| {
            let c = crate::street::energy::climate::climate(&m.region.code)?;
            Some(calibrate(m, targets, seed, &Sky::of(c)))
        })
        .collect()
}

fn points<'a>(rows: impl Iterator<Item = &'a Row>) -> Vec<Point> {
    rows.filter(|r| r.reached.is_some() && r.itree.0.is_finite())
        .map(|r| Point {
            projection_m2: r.projection_m2,
            shade: r.shade,
            itree: r.itree,
            deciduous_broadleaf: r.deciduous_broadleaf,
            evergreen: r.evergreen,
        })
        .collect()
}

/// The climate effect of `region` fitted to all its rows (`sylva rank --calibrate --fit`).
pub fn fit_region(region: &str, rows: &[Row]) -> Option<ClimateEffect> {
    fit(region, &points(rows.iter().filter(|r| r.region == region)))
}

/// Adds to each row its region's climate effect fitted to the region's other species, so
/// that no species is held to a figure fitted to itself (leave-one-species-out).
pub fn add_climate_left_out(rows: &mut [Row]) {
    for i in 0..rows.len() {
        if rows[i].reached.is_none() {
            continue;
        }
        let (region, code) = (rows[i].region.clone(), rows[i].code.clone());
        let others = points(rows.iter().filter(|r| r.region == region && r.code != code));
        let Some(c) = fit(&region, &others) else {
            continue;
        };
        let r = &mut rows[i];
        let (kwh, kbtu) = c.of(r.projection_m2);
        r.climate = Some((kwh, kbtu));
        r.useful_share = Some(c.useful_share());
        r.cooling_kwh = r.shade.0 + kwh;
        r.gas_kbtu = c.useful_share() * r.shade.1 + kbtu;
    }
}

/// The DBHs the site model is calibrated at, cm (inside i-Tree's class midpoints,
/// `itree::DBH_CLASSES_CM`, so no end class is held).
pub const TARGETS_CM: [f64; 3] = [20.0, 30.0, 40.0];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_standard_house_is_the_census_median_with_the_iecc_windows() {
        let h = STANDARD_HOUSE;
        let floor = 2030.0 * FT * FT;
        assert!(
            (h.side * h.side - floor).abs() < 0.01,
            "{}",
            h.side * h.side
        );
        // 15% of 188.6 m² is 28.3 m² of glass, 7.1 m² a wall of 33.5 m².
        assert!((h.glass * 4.0 * h.side * h.height - 0.15 * floor).abs() < 1e-9);
        assert!((h.glass - 0.211).abs() < 0.001, "{}", h.glass);
    }

    #[test]
    fn a_tree_off_a_side_sees_one_wall_and_off_a_corner_two() {
        let h = STANDARD_HOUSE;
        let south = walls_seen(&h, 180.0, 3.0);
        assert_eq!(south.len(), 1);
        assert_eq!(south[0].faces, 180.0);
        assert!((south[0].setback - 3.0).abs() < 1e-9);
        // Centred on the tree.
        assert!((south[0].x[0] + south[0].x[1]).abs() < 1e-9);
        let corner = walls_seen(&h, 225.0, 3.0);
        let faces: Vec<f64> = corner.iter().map(|w| w.faces).collect();
        assert_eq!(faces, vec![180.0, 270.0]);
        for w in &corner {
            assert!((w.setback - 3.0 / std::f64::consts::SQRT_2).abs() < 1e-9);
            // The wall lies wholly to one side of the tree.
            assert!(w.x[0] * w.x[1] >= -1e-9, "{w:?}");
        }
    }

    #[test]
    fn a_west_tree_saves_more_cooling_than_a_north_tree() {
        // A block of leaves in front of the tree's trunk, towards the wall.
        let tree = crate::street::energy::crown::leaf_block(
            glam::Vec3::new(-3.0, -1.5, 1.0),
            [12, 6, 8],
            glam::Vec3::splat(0.5),
        );
        let crown = Crown::of(&tree);
        let h = STANDARD_HOUSE;
        let at = |b: f64| {
            energy_of_walls(
                &crown,
                &walls_seen(&h, b, 3.0),
                h.glass,
                &Sky::clear(37.64),
                false,
            )
        };
        // The afternoon sun is low in the west; a low crown 3 m off a south wall is under
        // the high noon sun's rays, so only west against north is asserted.
        let (west, north) = (at(270.0), at(0.0));
        assert!(
            west.shade_cooling_kwh > 2.0 * north.shade_cooling_kwh,
            "{west:?} {north:?}"
        );
    }

    #[test]
    fn a_camphor_is_set_beside_its_itree_row_at_each_dbh() {
        let camphor = crate::growth::Database::builtin()
            .find("InlVal", "CICA")
            .unwrap();
        let rows = calibrate(&camphor, &[20.0, 500.0], 0, &Sky::clear(37.64));
        assert_eq!(rows.len(), 2);
        let (age, dbh) = rows[0].reached.unwrap();
        assert!(dbh >= 20.0 && age > 5.0, "{:?}", rows[0]);
        let t = Reference::of(&camphor).unwrap().at(dbh, None).amounts;
        assert_eq!(rows[0].itree, (t.electricity_kwh, t.natural_gas_kbtu));
        // An evergreen's winter shade costs gas; its summer shade saves electricity.
        assert!(
            rows[0].cooling_kwh > 0.0 && rows[0].gas_kbtu < 0.0,
            "{:?}",
            rows[0]
        );
        // 500 cm is never reached: said, not guessed.
        assert!(rows[1].reached.is_none() && rows[1].cooling_kwh.is_nan());
        // The bounds: ±35% of electricity; gas within ±50% or ±30 kBtu, same sign.
        let mut r = rows[0].clone();
        r.itree = (100.0, -46.0);
        r.cooling_kwh = 134.0;
        r.gas_kbtu = -70.0;
        assert!(r.cooling_in_bounds() && r.heating_in_bounds());
        r.cooling_kwh = 136.0;
        r.gas_kbtu = 10.0;
        assert!(!r.cooling_in_bounds() && !r.heating_in_bounds());
    }
}
