//! How much light a grown crown stops, in leaf and bare: the measure issue R holds the crowns
//! to (`sylva sweep --beam`).
//!
//! Published figures: Heisler (1986, Urban Ecology 9) measured the share of the sun's beam
//! stopped inside street trees' shadows, about 80% in leaf for sugar maple and 65-75% for Norway
//! maple and London plane, 30-40% leafless. The model's figure is the mean share stopped over
//! the crown's outline seen along a beam ([`Crown::beam`]): from the side (level), as a
//! picture's covered outline is measured, and along a high sun (60 degrees up), as a shadow is.

use crate::growth::Measured;
use crate::growth::report::Cohort;
use crate::skeleton::Skeleton;
use crate::street::energy::crown::{BeamStop, Crown, leaves_of};
use glam::DVec3;

/// One species at one age.
#[derive(Clone, Debug, PartialEq)]
pub struct Opacity {
    /// Region code.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Age, years.
    pub age: f64,
    /// Leaf area, m².
    pub leaf_area_m2: f64,
    /// Wood's silhouette, m² (diameter x length, summed).
    pub bark_area_m2: f64,
    /// Seen from the side: in leaf, and bare.
    pub side: (BeamStop, BeamStop),
    /// Along a sun 60 degrees up: in leaf, and bare.
    pub sun: (BeamStop, BeamStop),
}

/// The level beam of a side view, and a sun 60 degrees up (from the south).
pub fn beams() -> [DVec3; 2] {
    let e = 60f64.to_radians();
    [DVec3::Y, DVec3::new(0.0, e.cos(), -e.sin())]
}

/// Grows `m` yearly and measures its crown at each of `ages` (rising; ages its data do not
/// reach are left out), with `also`'s own measure of the same tree at that age (a picture of it,
/// say).
pub fn opacity<T>(
    m: &Measured,
    ages: &[f64],
    seed: u64,
    also: &(dyn Fn(&Measured, f64, &Skeleton) -> T + Sync),
) -> Vec<(Opacity, T)> {
    let mut cohort = Cohort::new(vec![m.clone()], seed);
    let mut out = Vec::new();
    for &age in ages.iter().filter(|&&a| a >= 1.0 && a <= m.ages.1) {
        let skeleton = cohort.advance_to(age).remove(0);
        let crown = Crown::with_leaves(&skeleton, &leaves_of(&skeleton)).with_wood(&skeleton);
        let [side, sun] = beams();
        let row = Opacity {
            region: m.region.code.clone(),
            code: m.species.code.clone(),
            age,
            leaf_area_m2: crown.leaf_area,
            bark_area_m2: crown.bark_area,
            side: (crown.beam(side, true), crown.beam(side, false)),
            sun: (crown.beam(sun, true), crown.beam(sun, false)),
        };
        out.push((row, also(m, age, &skeleton)));
    }
    out
}

/// [`opacity`] for many species at once, in parallel; `tick` after each.
pub fn opacity_all<T: Send>(
    species: &[Measured],
    ages: &[f64],
    seed: u64,
    also: &(dyn Fn(&Measured, f64, &Skeleton) -> T + Sync),
    tick: &(dyn Fn() + Sync),
) -> Vec<Vec<(Opacity, T)>> {
    use rayon::prelude::*;
    species
        .par_iter()
        .map(|m| {
            let rows = opacity(m, ages, seed, also);
            tick();
            rows
        })
        .collect()
}
