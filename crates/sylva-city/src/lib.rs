//! A city's street trees: an inventory in, OGC 3D Tiles out.

mod atlas;
pub mod benefits;
pub mod cache;
mod error;
pub mod families;
pub mod geo;
pub mod inventory;
pub mod regions;
pub mod species;

pub use error::CityError;
pub mod plan;
pub mod prototypes;
pub mod published;
pub mod report;
mod report_html;
pub mod run;
pub mod tasks;
pub mod tiles;

pub use inventory::{Layout, LengthUnit};
pub use plan::CityOptions;
pub use run::{Progress, Quiet, tile_city};
pub use tasks::{CityRun, summary_json};
pub mod demo;
mod gpkg_write;
