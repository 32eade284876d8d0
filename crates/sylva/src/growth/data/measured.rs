//! A species' measured growth as functions of age: f_DBH, f_H, f_CD, f_CH and f_LA, composed
//! from the database's age→DBH and DBH→X equations and kept inside the ranges they were fitted
//! for.

use crate::growth::data::database::{Database, Region, SpeciesEntry};
use crate::growth::data::equations::Equation;
use crate::growth::error::GrowthError;

/// Longest life the age search looks at, years.
const MAX_AGE: f64 = 300.0;
/// Resolution of the crown-base table, years.
const BASE_STEP: f64 = 0.05;

/// Measured growth functions of one species in one region.
#[derive(Clone, Debug)]
pub struct Measured {
    /// The species as listed in the region.
    pub species: SpeciesEntry,
    /// The region.
    pub region: Region,
    /// age→DBH, DBH→height, DBH→crown diameter, DBH→crown height, DBH→leaf area.
    pub equations: [Equation; 5],
    /// Ages (years since planting) the age→DBH fit covers: from 0 (1 for a log-log fit, later
    /// if its prediction starts below its range) to where the DBH leaves its range or stops
    /// rising.
    pub ages: (f64, f64),
    /// For every DBH→X equation, the DBH past which it stops rising (a quadratic's vertex).
    dbh_caps: [f64; 4],
    /// Height to crown base, made monotone: max over s <= t of f_H(s) - f_CH(s), sampled every
    /// `BASE_STEP` years from `ages.0`.
    crown_base: Vec<f64>,
}

impl Measured {
    pub(super) fn new(species: SpeciesEntry, region: Region, equations: [Equation; 5]) -> Self {
        let age_dbh = equations[0];
        let (dbh_min, dbh_max) = age_dbh.range;
        let mut start = if age_dbh.form.is_log_log() { 1.0 } else { 0.0 };
        // A few cubics fall before they rise (InlEmp PIBR2): growth starts at the trough.
        start = age_dbh.rise_start(start, MAX_AGE);
        // A fit that predicts below its range at the start begins where it enters the range.
        if age_dbh.raw(start) < dbh_min {
            let mut t = start;
            while t < MAX_AGE && age_dbh.raw(t) < dbh_min {
                t += 0.01;
            }
            start = t;
        }
        let mut end = age_dbh.rise_end(start, MAX_AGE);
        if age_dbh.raw(end) > dbh_max {
            // Bisect for the age where the DBH reaches its range's top.
            let (mut lo, mut hi) = (start, end);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if age_dbh.raw(mid) < dbh_max {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            end = lo;
        }
        let dbh_top = age_dbh.raw(end).clamp(dbh_min, dbh_max);
        let dbh_bottom = age_dbh.raw(start).clamp(dbh_min, dbh_max);
        let dbh_caps = [1, 2, 3, 4].map(|i| equations[i].rise_end(dbh_bottom, dbh_top));
        let mut m = Measured {
            species,
            region,
            equations,
            ages: (start, end.max(start)),
            dbh_caps,
            crown_base: Vec::new(),
        };
        let steps = ((m.ages.1 - m.ages.0) / BASE_STEP).ceil() as usize + 1;
        let mut highest = 0.0f64;
        for i in 0..steps {
            let t = (m.ages.0 + i as f64 * BASE_STEP).min(m.ages.1);
            let h = m.height(t);
            let base = (h - m.crown_height_fitted(t)).clamp(0.0, h);
            highest = highest.max(base);
            m.crown_base.push(highest);
        }
        m
    }

    /// Whole ages inside the fitted range.
    pub fn whole_ages(&self) -> std::ops::RangeInclusive<u32> {
        (self.ages.0.ceil() as u32)..=(self.ages.1.floor() as u32)
    }

    fn age(&self, t: f64) -> f64 {
        t.clamp(self.ages.0, self.ages.1)
    }

    /// f_DBH: trunk diameter at breast height, cm.
    pub fn dbh(&self, t: f64) -> f64 {
        let e = &self.equations[0];
        e.raw(self.age(t)).clamp(e.range.0, e.range.1)
    }

    /// The age at which f_DBH reaches `dbh` cm: f_DBH inverted by bisection (it rises over
    /// the fitted ages), clamped to those ages: a trunk thinner than the data's first age is
    /// that age, one thicker than its last is the last.
    pub fn age_at_dbh(&self, dbh: f64) -> f64 {
        let (mut lo, mut hi) = self.ages;
        // A NaN is no DBH: the first age.
        if dbh.is_nan() || dbh <= self.dbh(lo) {
            return lo;
        }
        if dbh >= self.dbh(hi) {
            return hi;
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.dbh(mid) < dbh {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    fn of_dbh(&self, which: usize, t: f64) -> f64 {
        let e = &self.equations[which];
        let dbh = self.dbh(t).min(self.dbh_caps[which - 1]);
        e.raw(dbh).clamp(e.range.0, e.range.1)
    }

    /// f_H: tree height, m.
    pub fn height(&self, t: f64) -> f64 {
        self.of_dbh(1, t)
    }

    /// f_CD: crown diameter, m.
    pub fn crown_diameter(&self, t: f64) -> f64 {
        self.of_dbh(2, t)
    }

    /// f_CH as fitted: crown height, m (its crown base may sink with age).
    pub fn crown_height_fitted(&self, t: f64) -> f64 {
        self.of_dbh(3, t).min(self.height(t))
    }

    /// Height to the crown base, m: never lower than at any earlier age (a crown base only
    /// rises as lower branches die).
    pub fn crown_base(&self, t: f64) -> f64 {
        let i = ((self.age(t) - self.ages.0) / BASE_STEP).floor() as usize;
        let i = i.min(self.crown_base.len().saturating_sub(1));
        // Between samples, the fitted base is still a lower bound.
        let h = self.height(t);
        self.crown_base
            .get(i)
            .copied()
            .unwrap_or(0.0)
            .max((h - self.crown_height_fitted(t)).clamp(0.0, h))
    }

    /// Crown height with the monotone crown base: f_H - crown base, m. This is what a grown
    /// tree can match.
    pub fn crown_height(&self, t: f64) -> f64 {
        self.height(t) - self.crown_base(t)
    }

    /// f_LA: one-sided leaf area, m².
    pub fn leaf_area(&self, t: f64) -> f64 {
        self.of_dbh(4, t)
    }

    /// Display name: common name (code).
    pub fn label(&self) -> String {
        format!("{} ({})", self.species.common, self.species.code)
    }
}

// Here rather than in `database.rs`, so that the database knows nothing of `Measured` and the
// two modules do not import each other.
impl Database {
    /// The measured functions of a species in a region. `query` is a species code (`PLAC`), a
    /// scientific name (`Platanus x acerifolia`) or a common name (`London planetree`), in any
    /// case, with `_` or `-` for spaces.
    pub fn find(&self, region: &str, query: &str) -> Result<Measured, GrowthError> {
        let (entry, region, equations) = self.lookup(region, query)?;
        Ok(Measured::new(entry, region, equations))
    }
}
