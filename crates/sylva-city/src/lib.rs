//! A city's street trees: an inventory in, OGC 3D Tiles out. The crate lies in rooms by
//! concern, each reading only the rooms before it in this list:
//!
//! - [`error`](CityError) and [`geo`]: what can go wrong, and the city's coordinates (WGS84,
//!   UTM, the local east-north-up frame), which every room reads.
//! - [`inventory`]: an inventory's rows read (CSV, GeoJSON, GeoPackage, by layout), its
//!   species matched to the Urban Tree Database (`species`), each tree's region (`regions`)
//!   and plant family (`families`).
//! - [`demo`]: a synthetic inventory in a region's species mix, written in each layout.
//! - [`trees`]: the city's trees at each epoch (`plan`), the shared trees grown once per
//!   species, region, variant and age class (`prototypes`), and each tree's yearly benefits
//!   (`benefits`).
//! - [`tiles`]: the 3D Tiles: the quadtree, each tile's content, the impostors' atlas
//!   (`atlas`) and the checks every tileset passes.
//! - [`report`]: the city's report (HTML, CSV, JSON) beside published per-tree figures.
//!
//! On top: [`tasks`] splits a run into independent tasks (one machine's threads or a
//! cluster's workers), [`cache`] keeps grown trees between runs, and [`run`] is the whole job.

pub mod bench;
pub mod cache;
pub mod demo;
mod error;
pub mod geo;
pub mod inventory;
pub mod report;
pub mod run;
pub mod tasks;
pub mod tiles;
pub mod trees;

pub use error::CityError;
pub use inventory::{Layout, LengthUnit};
pub use run::{Progress, Quiet, tile_city};
pub use tasks::{CityRun, summary_json};
pub use trees::plan::CityOptions;
