//! A year's benefits in dollars, in i-Tree Streets' categories, and which account (the typical
//! position or this site) a net is read from. Shared by the typical-position account
//! (`typical.rs`) and the year's ledger (`ledger.rs`). The categories' keys, labels and colours
//! are `items.rs`'s [`Benefit`]s.

use crate::street::accounts::items::Benefit;

/// A year's benefits in dollars, in i-Tree Streets' categories; `None` where a model or a
/// price is missing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Money {
    /// CO2 taken up this year.
    pub carbon: Option<f64>,
    /// CO2 not emitted at power plants thanks to the energy saved.
    pub co2_avoided: Option<f64>,
    /// Stormwater held back.
    pub stormwater: Option<f64>,
    /// Air conditioning saved.
    pub cooling: Option<f64>,
    /// Heating saved; negative where winter shade costs more than the tree saves.
    pub heating: Option<f64>,
    /// Pollutants taken up by the leaves or not emitted thanks to the energy saved.
    pub air_quality: Option<f64>,
    /// Biogenic VOCs emitted (negative or zero).
    pub bvoc: Option<f64>,
    /// Aesthetics and property value.
    pub aesthetics: Option<f64>,
}

impl Money {
    /// Sum of what is known.
    pub fn total(&self) -> f64 {
        self.categories().iter().flat_map(|c| c.1).sum()
    }

    /// One category's dollars, where computed.
    pub fn get(&self, b: Benefit) -> Option<f64> {
        match b {
            Benefit::Carbon => self.carbon,
            Benefit::Co2Avoided => self.co2_avoided,
            Benefit::Stormwater => self.stormwater,
            Benefit::Cooling => self.cooling,
            Benefit::Heating => self.heating,
            Benefit::AirQuality => self.air_quality,
            Benefit::Bvoc => self.bvoc,
            Benefit::Aesthetics => self.aesthetics,
        }
    }

    /// Each category with its key, in report order.
    pub fn categories(&self) -> [(&'static str, Option<f64>); Benefit::COUNT] {
        Benefit::ALL.map(|b| (b.item().key, self.get(b)))
    }
}

/// Which account a net benefit is read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Basis {
    /// i-Tree Streets' figures for the species at the grown DBH, at its usual spread of
    /// positions around buildings (`typical::Typical`).
    Typical,
    /// The grown tree's own crown on the site given (without a site: no façade, no energy).
    Site,
}

impl Basis {
    /// The basis a run reads by default: the site's own figures where there is a site, else
    /// the typical position.
    pub fn default_for(has_site: bool) -> Basis {
        if has_site {
            Basis::Site
        } else {
            Basis::Typical
        }
    }

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Basis::Typical => "typical position",
            Basis::Site => "this site",
        }
    }
}
