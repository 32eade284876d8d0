//! How many of the trees planted are still standing, year by year: a street's benefits and
//! costs per tree *planted* are each year's figures for a living tree weighted by the share
//! alive, with the dead trees' removal charged as they go.
//!
//! Street trees die young. Published rates:
//! - annual survival of street trees 94.9-96.5% in a meta-analysis of 16 studies (Roman &
//!   Scatena 2011, Urban Forestry & Urban Greening 10(4):269-274);
//! - planted cohorts' median annual mortality 4.4-6.5%, highest in the first five years after
//!   planting (Hilbert, Roman, Koeser, Vogt & van Doorn 2019, Arboriculture & Urban Forestry
//!   45(5):167-200, the quartiles of 56 studies);
//! - the USDA Community Tree Guides assume a share alive after 40 years, from a survey of
//!   municipal and commercial arborists: 60% in the Midwest (PSW-GTR-199), 65% on the Coastal
//!   Plain (PSW-GTR-201), 55% in the Piedmont (PSW-GTR-200);
//! - the Center for Urban Forest Research's Los Angeles study (McPherson, Simpson, Xiao & Wu
//!   2008, PSW-GTR-207) wrote mortality as two rates: one for the five establishment years,
//!   another after (1% then 0.5% a year in its low scenario, 5% then 2% in its high one).
//!
//! Sylva's default keeps that two-rate form. The establishment years lose 5% a year: the Los
//! Angeles study's high scenario, and within the middle quartile of Hilbert et al.'s planted
//! cohorts. The later rate is what brings the cohort to the tree guide's share at 40 years:
//! a region's own guide where one was read (Midwest, Coastal Plain, Piedmont), else 60%, the
//! middle of the three. The guides' own year-by-year schedules were not reachable, so this is
//! the published method with the nearest citable inputs, and every report says so.

use crate::street::error::StreetError;

/// The years after planting that count as establishment (PSW-GTR-207's five).
pub const ESTABLISHMENT_YEARS: u32 = 5;
/// Yearly survival in those years: 5% die a year (PSW-GTR-207's high scenario; Hilbert et al.
/// 2019's middle quartile for planted cohorts is 4.4-6.5%).
pub const ESTABLISHMENT_SURVIVAL: f64 = 0.95;

/// The share alive after 40 years that a region's Community Tree Guide assumes, and which
/// guide says so; `None` where no guide's figure was read.
fn guide_share(region: &str) -> Option<(f64, &'static str)> {
    match region {
        "MidWst" => Some((0.60, "Midwest Community Tree Guide, PSW-GTR-199 (2006)")),
        "GulfCo" => Some((
            0.65,
            "Coastal Plain Community Tree Guide, PSW-GTR-201 (2006)",
        )),
        "Piedmt" => Some((0.55, "Piedmont Community Tree Guide, PSW-GTR-200 (2005)")),
        _ => None,
    }
}

/// A cohort's yearly survival: one rate while the trees establish, another after.
#[derive(Clone, Debug, PartialEq)]
pub struct Survival {
    /// Years of establishment.
    pub establishment_years: u32,
    /// Share of the living trees that survive each establishment year, 0 to 1.
    pub establishment: f64,
    /// Share that survive each later year, 0 to 1.
    pub later: f64,
    /// Where the rates come from.
    pub source: String,
}

/// One year of a cohort: the share of the trees planted alive through it, and the share that
/// died in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cohort {
    /// Share of the planted trees standing, on average over the year (what the year's
    /// benefits and upkeep are weighted by).
    pub alive: f64,
    /// Share of the planted trees alive at the year's end.
    pub alive_at_end: f64,
    /// Share of the planted trees that died during the year (each one removed).
    pub died: f64,
}

impl Survival {
    /// The built-in survival of a region's street trees (see the module's notes).
    pub fn builtin(region: &str) -> Survival {
        let (at_40, guide) = guide_share(region).unwrap_or((
            0.60,
            "no guide's figure read for this region: 60%, the middle of the Midwest, Coastal \
             Plain and Piedmont guides' 55-65%",
        ));
        let after = ESTABLISHMENT_SURVIVAL.powi(ESTABLISHMENT_YEARS as i32);
        let later = (at_40 / after).powf(1.0 / (40 - ESTABLISHMENT_YEARS) as f64);
        Survival {
            establishment_years: ESTABLISHMENT_YEARS,
            establishment: ESTABLISHMENT_SURVIVAL,
            later,
            source: format!(
                "{:.0}% die a year in the first {ESTABLISHMENT_YEARS} years (PSW-GTR-207's high \
                 scenario; Hilbert et al. 2019), then {:.2}%, so that {:.0}% are alive at 40 \
                 years ({guide})",
                100.0 * (1.0 - ESTABLISHMENT_SURVIVAL),
                100.0 * (1.0 - later),
                100.0 * at_40
            ),
        }
    }

    /// The same yearly survival every year (`--survival`); 1 keeps every tree alive.
    pub fn constant(share: f64, what: &str) -> Result<Survival, StreetError> {
        if !(share.is_finite() && share > 0.0 && share <= 1.0) {
            return Err(StreetError::Value {
                file: what.to_string(),
                key: "survival".into(),
                value: share,
                allowed: "a yearly survival over 0 and at most 1 (0.96: 4% die a year; 1: none)"
                    .into(),
            });
        }
        Ok(Survival {
            establishment_years: 0,
            establishment: share,
            later: share,
            source: format!("{:.2}% survive each year (given)", 100.0 * share),
        })
    }

    /// Whether every tree lives.
    pub fn is_immortal(&self) -> bool {
        self.establishment == 1.0 && self.later == 1.0
    }

    /// The share of the planted trees alive `years` after planting (fractions of a year at
    /// that year's rate).
    pub fn alive_after(&self, years: f64) -> f64 {
        let years = years.max(0.0);
        let early = years.min(self.establishment_years as f64);
        let late = (years - early).max(0.0);
        self.establishment.powf(early) * self.later.powf(late)
    }

    /// The year that ends `age` years after planting and began `span` years before (1 for a
    /// yearly run; more where a run records every few years and a record stands for them).
    pub fn year(&self, age: f64, span: f64) -> Cohort {
        let start = (age - span.max(0.0)).max(0.0);
        let (a0, a1) = (self.alive_after(start), self.alive_after(age));
        Cohort {
            // Deaths spread evenly over the year: its living trees average the two ends.
            alive: 0.5 * (a0 + a1),
            alive_at_end: a1,
            died: (a0 - a1) / span.max(1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_reaches_the_guides_share_at_40_years() {
        for (region, at_40) in [("InlVal", 0.60), ("MidWst", 0.60), ("GulfCo", 0.65)] {
            let s = Survival::builtin(region);
            assert!((s.alive_after(40.0) - at_40).abs() < 1e-9, "{region}");
            assert!((s.alive_after(5.0) - 0.95f64.powi(5)).abs() < 1e-12);
            // Establishment loses more a year than later life.
            assert!(s.later > s.establishment && s.later < 1.0, "{s:?}");
        }
        let piedmont = Survival::builtin("Piedmt");
        assert!((piedmont.alive_after(40.0) - 0.55).abs() < 1e-9);
        // Within Roman & Scatena's 94.9-96.5% a year over the first 10 years taken together.
        let s = Survival::builtin("InlVal");
        let mean = s.alive_after(10.0).powf(0.1);
        assert!((0.949..=0.975).contains(&mean), "{mean}");
    }

    #[test]
    fn a_year_weighs_the_living_and_counts_the_dead() {
        let s = Survival::builtin("InlVal");
        let y = s.year(1.0, 1.0);
        assert!((y.alive - 0.975).abs() < 1e-12);
        assert!((y.died - 0.05).abs() < 1e-12);
        assert!((y.alive_at_end - 0.95).abs() < 1e-12);
        // The deaths of the years add up to the trees lost.
        let died: f64 = (1..=40).map(|a| s.year(a as f64, 1.0).died).sum();
        assert!((died - (1.0 - s.alive_after(40.0))).abs() < 1e-9);
        let all = Survival::constant(1.0, "--survival").unwrap();
        assert!(all.is_immortal());
        let y = all.year(30.0, 1.0);
        assert_eq!((y.alive, y.died), (1.0, 0.0));
    }

    #[test]
    fn a_survival_out_of_range_is_an_error_naming_it() {
        for bad in [0.0, -0.5, 1.01, f64::NAN, f64::INFINITY] {
            let e = Survival::constant(bad, "--survival")
                .unwrap_err()
                .to_string();
            assert!(e.contains("--survival") && e.contains("survival"), "{e}");
        }
        assert!(Survival::constant(0.96, "--survival").is_ok());
    }
}
