//! What a street tree gives, costs and runs into, year by year (Linsen et al. 2005's benefit
//! and cost bars; Rudnick et al. 2007's conflicts with the street).
//!
//! Every "this site" figure is driven by the grown tree itself, read from its
//! [`Skeleton`](crate::Skeleton) and its measured dimensions; the typical-position account
//! beside it reads i-Tree's tables. The street lies in three rooms by concern, each reading
//! only the rooms above it in this list:
//!
//! - [`site`]: the planting site (`site.toml`), which every room reads.
//! - [`energy`]: light and climate. The sun's path and the crown's shadow on the site's façade
//!   (`sun`, `shade`, `crown`), turned into cooling saved and the winter shade's heating
//!   penalty; each region's climate and rainfall interception (`climate`); the canopy's effect
//!   on air and wind (`climate_effect`); how much of a beam the grown crown stops (`opacity`,
//!   `sylva sweep --beam`).
//! - [`work`]: the street's own. Where the tree runs into its site (`conflicts`), how often
//!   the street cuts it back and why (`pruning`), and the wire model against the database's
//!   records (`wires`).
//! - [`accounts`]: money. What each unit is worth and what a tree costs (`prices`, `costs`),
//!   CO2 stored and taken up (`carbon`), aesthetics and property value (`aesthetics`), the share
//!   of trees alive (`survival`), the pruning cycles carried out on the grown tree and priced
//!   (`pruner`), a year's dollars in i-Tree's categories (`money`), one year's account of all
//!   of these (`ledger`) and its table (`table`); i-Tree Streets' per-tree tables and the
//!   typical-position account they give (`itree`, `typical`), the site model's shade calibrated
//!   against them (`calibrate`); McPherson (2003)'s published figures (`published`).
//!
//! On top of them, [`rank`] sets a region's species side by side over the years, and
//! [`picture`] draws the site with the tree and its conflicts.
//!
//! A benefit without a sourced model or input is reported as missing, with the reason, never
//! as zero. `docs/benefits.md` gives every formula and source.

pub mod accounts;
pub mod energy;
pub mod picture;
pub mod rank;
pub mod records;
pub mod site;
pub mod study;
pub mod work;

pub use accounts::costs::Costs;
pub use accounts::ledger::{Assessor, YearAccount};
pub use accounts::money::{Basis, Money};
pub use accounts::prices::Prices;
pub use accounts::survival::Survival;
pub use site::Site;
pub use work::conflicts::{Conflict, Kind, Part};

/// What can go wrong reading a site, prices or costs, or assessing a species.
#[derive(Debug, thiserror::Error)]
pub enum StreetError {
    /// A file that cannot be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// A file that does not parse, or has a key missing or unknown.
    #[error("{file}: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// What is wrong (the parser names the key).
        message: String,
    },
    /// A value outside what the key allows.
    #[error("{file}: `{key}` is {value}, expected {allowed}")]
    Value {
        /// The file.
        file: String,
        /// The key, with its table (`wire.height`).
        key: String,
        /// The value given.
        value: f64,
        /// What is allowed.
        allowed: String,
    },
    /// A species whose benefits were asked for but a model lacks an input.
    #[error("{0}")]
    Missing(String),
    /// Growth data that cannot be found or read.
    #[error(transparent)]
    Growth(#[from] crate::growth::GrowthError),
}
