//! How much light a grown crown stops, in leaf and bare: the measure issue R holds the crowns
//! to (`sylva sweep --beam`).
//!
//! Published figures: Heisler (1986, Urban Ecology 9) measured the share of the sun's beam
//! stopped inside street trees' shadows, about 80% in leaf for sugar maple and 65-75% for Norway
//! maple and London plane, 30-40% leafless. The model's figure is the mean share stopped over
//! the crown's outline seen along a beam ([`Crown::beam`]): from the side (level), as a
//! picture's covered outline is measured, and along a high sun (60 degrees up), as a shadow is.

use crate::growth::Measured;
use crate::growth::survey::report::Cohort;
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

/// The share of a beam a crown stops, in leaf and bare, as output (`sylva sweep --beam
/// --json`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BeamRecord {
    /// Mean share of the beam stopped over the outline, 0..1.
    pub stopped: f64,
    /// The outline's area, m².
    pub outline_m2: f64,
}

impl From<BeamStop> for BeamRecord {
    fn from(s: BeamStop) -> BeamRecord {
        BeamRecord {
            stopped: s.stopped,
            outline_m2: s.outline_m2,
        }
    }
}

/// What a picture of the crown from the side covers (the renderer measures it).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CoverageRecord {
    /// Share of the outline covered.
    pub covered: f64,
    /// Share of what is covered that is leaf.
    pub leaf_share: f64,
    /// Share of what is covered that is bare wood outside the leaves.
    pub bare_tips: f64,
    /// The outline's area, m².
    pub outline_m2: f64,
}

/// In leaf and bare.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LeafAndBare<T> {
    #[allow(missing_docs)]
    pub leaf: T,
    #[allow(missing_docs)]
    pub bare: T,
}

/// One species and age of `sylva sweep --beam`, as output.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[allow(missing_docs)]
pub struct OpacityRecord {
    pub region: String,
    pub species: String,
    pub age: f64,
    pub leaf_area_m2: f64,
    pub bark_area_m2: f64,
    /// Seen from the side, and along a sun 60 degrees up.
    pub side: LeafAndBare<BeamRecord>,
    pub sun: LeafAndBare<BeamRecord>,
    /// What the renderer's picture from the side covers, where it was asked for.
    pub picture: Option<LeafAndBare<CoverageRecord>>,
}

impl OpacityRecord {
    /// The record of `o`, with its picture's coverage where measured.
    pub fn of(o: &Opacity, picture: Option<LeafAndBare<CoverageRecord>>) -> OpacityRecord {
        let pair = |p: (BeamStop, BeamStop)| LeafAndBare {
            leaf: p.0.into(),
            bare: p.1.into(),
        };
        OpacityRecord {
            region: o.region.clone(),
            species: o.code.clone(),
            age: o.age,
            leaf_area_m2: o.leaf_area_m2,
            bark_area_m2: o.bark_area_m2,
            side: pair(o.side),
            sun: pair(o.sun),
            picture,
        }
    }
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
