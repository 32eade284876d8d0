//! What a street tree gives, costs and runs into, year by year (Linsen et al. 2005's benefit
//! and cost bars; Rudnick et al. 2007's conflicts with the street).
//!
//! Every "this site" figure is driven by the grown tree itself, read from its
//! [`Skeleton`](crate::Skeleton) and its measured dimensions; the typical-position account
//! beside it reads i-Tree's tables. The street lies in rooms by concern, each reading only
//! the rooms above it in this list:
//!
//! - [`StreetError`] and [`site`], the planting site (`site.toml`), which every room reads.
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
//!   against them (`calibrate`); McPherson (2003)'s published figures (`published`); a year's
//!   account as an output record (`records`).
//!
//! On top of them, in this order: [`study`], the one study pipeline (a street tree grown year
//! by year on its site, pruned and accounted at every age); [`rank`], a region's species side
//! by side over the years; [`records`], the output records every JSON writes; and [`picture`],
//! the site drawn with the tree and its conflicts.
//!
//! A benefit without a sourced model or input is reported as missing, with the reason, never
//! as zero. `docs/benefits.md` gives every formula and source.

pub mod accounts;
pub mod energy;
mod error;
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
pub use error::StreetError;
pub use site::Site;
pub use work::conflicts::{Conflict, Kind, Part};
