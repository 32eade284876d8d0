//! What a street tree gives, costs and runs into, year by year (Linsen et al. 2005's benefit
//! and cost bars; Rudnick et al. 2007's conflicts with the street).
//!
//! Every "this site" figure is driven by the grown tree itself, read from its
//! [`Skeleton`](crate::Skeleton) and its measured dimensions; the typical-position account
//! beside it reads i-Tree's tables:
//!
//! - [`carbon`]: CO2 stored and taken up, from the grown DBH by Jenkins et al. (2003).
//! - [`climate`]: each region's latitude, sunshine and rain; rainfall interception by leaf and
//!   bark storage.
//! - [`sun`] and [`shade`]: the sun's path, beam and sky light, and the crown's shadow on the
//!   site's façade ([`crown`] holds the crown's leaf area density and wood), turned into
//!   cooling saved and the winter shade's heating penalty (an evergreen's leaves, a deciduous
//!   tree's bare wood); [`climate_effect`]: the canopy's effect on air
//!   and wind, which does not depend on the tree's position, calibrated against i-Tree.
//! - [`prices`] and [`costs`]: what each unit is worth and what a tree costs, built in or
//!   from TOML.
//! - [`site`] and [`conflicts`]: a planting site and where the tree runs into it;
//!   [`pruning`]: how often the street cuts it back, and why; [`pruner`]: those cycles cut on
//!   the grown tree, their cost and the conflicts they resolve.
//! - [`itree`] and [`typical`]: i-Tree Streets' per-tree tables, and the typical-position
//!   account they give a species at the grown DBH; [`calibrate`]: the site model's shade
//!   around a standard house beside them.
//! - [`opacity`]: how much of a beam the grown crown stops, in leaf and bare (`sylva sweep
//!   --beam`).
//! - [`money`]: a year's dollars in i-Tree's categories; [`ledger`]: one year's account of all
//!   of these, the grown tree's own and the typical position's; [`rank`]: a region's species side by
//!   side over the years; [`wires`]: the wire model against the database's own records;
//!   [`picture`]: the site drawn with the tree and its conflicts.
//!
//! A benefit without a sourced model or input is reported as missing, with the reason, never
//! as zero. `docs/benefits.md` gives every formula and source.

pub mod aesthetics;
pub mod calibrate;
pub mod carbon;
pub mod climate;
pub mod climate_effect;
pub mod conflicts;
pub mod costs;
pub mod crown;
pub mod itree;
pub mod ledger;
pub mod money;
pub mod opacity;
pub mod picture;
pub mod prices;
pub mod pruner;
pub mod pruning;
pub mod published;
pub mod rank;
pub mod shade;
pub mod site;
pub mod sun;
pub mod survival;
pub mod table;
pub mod typical;
pub mod wires;

pub use conflicts::{Conflict, Kind, Part};
pub use costs::Costs;
pub use ledger::{Assessor, YearAccount};
pub use money::{Basis, Money};
pub use prices::Prices;
pub use site::Site;
pub use survival::Survival;

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
