//! Flags of `sylva city` and `sylva city-demo`.

use clap::{Args, ValueEnum};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct CityArgs {
    /// The inventory: a CSV file, GeoJSON points (.geojson) or a GeoPackage (.gpkg).
    #[arg(value_name = "INVENTORY")]
    pub inventory: PathBuf,

    /// Folder of the tileset(s): tileset.json, content/, prototypes/ and summary.json.
    #[arg(short, long, value_name = "DIR")]
    pub output: PathBuf,

    /// The Urban Tree Database region of every tree (default: each tree's nearest reference
    /// city).
    #[arg(long)]
    pub region: Option<String>,

    /// Years after the inventory's year at which to draw the city, one tileset each, e.g.
    /// `0,10,20,40`.
    #[arg(long, value_delimiter = ',', default_value = "0")]
    pub years: Vec<u32>,

    /// The year the inventory describes (planted years after it are future plantings).
    #[arg(long, default_value_t = 2026)]
    pub year: i32,

    /// Draw dead trees and stumps as stumps (default: counted and skipped).
    #[arg(long)]
    pub stumps: bool,

    /// Seed variants grown of each species and age.
    #[arg(long, default_value_t = 2)]
    pub variants: u32,

    /// Seed of the variants and of each tree's turn.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// Ground height above the WGS84 ellipsoid, m, of rows without a ground column.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub ground: f64,

    /// Where grown trees are kept between runs, so a second run (or an inventory with a few
    /// rows changed) grows only what is new (default: $XDG_CACHE_HOME/sylva/city-trees, else
    /// ~/.cache/sylva/city-trees).
    #[arg(long, value_name = "DIR")]
    pub cache: Option<PathBuf>,

    /// Most the cache of grown trees may hold, MiB (the least recently used go first).
    #[arg(long, default_value_t = 2048)]
    pub cache_mib: u64,

    /// Grow every tree, and keep none.
    #[arg(long, conflicts_with = "cache")]
    pub no_cache: bool,

    /// Also write the city's report beside the tiles (report.html, report.csv, report.json):
    /// composition by species and genus with i-Tree's diversity guidelines, DBH classes,
    /// importance values, yearly benefits by species, and each epoch's canopy, leaf area and
    /// benefits.
    #[arg(long)]
    pub report: bool,

    /// Also write each epoch's planting plan for CAD beside its tileset (planting-plan.dxf):
    /// every tree an INSERT of its grown tree's plan symbol (crown outline and trunk) at its
    /// place, in a projected inventory's own coordinates and unit, on a layer per species; at
    /// most 250,000 trees an epoch.
    #[arg(long)]
    pub dxf: bool,

    /// The GeoPackage layer (default: its first features layer).
    #[arg(long, help_heading = "Columns")]
    pub layer: Option<String>,

    /// The inventory's id column.
    #[arg(long, help_heading = "Columns")]
    pub id_col: Option<String>,

    /// Species columns, tried in order (UTD code, scientific or common name).
    #[arg(long, value_delimiter = ',', help_heading = "Columns")]
    pub species_col: Vec<String>,

    /// DBH column.
    #[arg(long, help_heading = "Columns")]
    pub dbh_col: Option<String>,

    /// DBH unit: in or cm (default: inches, or cm where the column's name ends in cm).
    #[arg(long, help_heading = "Columns")]
    pub dbh_unit: Option<String>,

    /// Trunk circumference column, where there is no DBH.
    #[arg(long, help_heading = "Columns")]
    pub circumference_col: Option<String>,

    /// Circumference unit: in or cm (default: the DBH's).
    #[arg(long, help_heading = "Columns")]
    pub circumference_unit: Option<String>,

    /// Longitude and latitude columns, e.g. `--lon-col lng --lat-col lat`.
    #[arg(long, help_heading = "Columns", requires = "lat_col")]
    pub lon_col: Option<String>,
    #[arg(long, help_heading = "Columns", requires = "lon_col")]
    pub lat_col: Option<String>,

    /// Projected x and y columns, in the system --crs names.
    #[arg(long, help_heading = "Columns", requires = "y_col")]
    pub x_col: Option<String>,
    #[arg(long, help_heading = "Columns", requires = "x_col")]
    pub y_col: Option<String>,

    /// The projected coordinates' system, e.g. EPSG:2263.
    #[arg(long, help_heading = "Columns")]
    pub crs: Option<String>,

    /// Height column, and its unit (m or ft).
    #[arg(long, help_heading = "Columns")]
    pub height_col: Option<String>,
    #[arg(long, help_heading = "Columns")]
    pub height_unit: Option<String>,

    /// Planting year column.
    #[arg(long, help_heading = "Columns")]
    pub planted_col: Option<String>,

    /// Status column (alive, dead, stump, planting site).
    #[arg(long, help_heading = "Columns")]
    pub status_col: Option<String>,

    /// Ground height column (m above the WGS84 ellipsoid).
    #[arg(long, help_heading = "Columns")]
    pub ground_col: Option<String>,

    /// Condition column (default: the census's `health`, else `condition`): Good, Fair, Poor,
    /// or i-Tree's Excellent, Very Good, Critical, Dying; for the report's condition and
    /// relative performance by species, and each tree's property in the tiles.
    #[arg(long, help_heading = "Columns")]
    pub condition_col: Option<String>,
}

/// The column layout of a demo CSV.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum DemoLayoutArg {
    /// Census style: Latin and common names, DBH in inches, latitude and longitude.
    Census,
    /// GIS export: projected POINT_X/POINT_Y (UTM, m), DBH in cm.
    Gis,
}

#[derive(Args, Debug)]
pub struct CityDemoArgs {
    /// The file to write: .csv, .geojson or .gpkg.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,

    /// Rows (trees, stumps, sites and a few broken rows).
    #[arg(long, default_value_t = 1000)]
    pub trees: usize,

    /// The region whose species mix and DBH classes it takes, around its reference city.
    #[arg(long, default_value = "PacfNW")]
    pub region: String,

    /// Column layout of a CSV file.
    #[arg(long, value_enum, default_value = "census")]
    pub layout: DemoLayoutArg,

    /// Random seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// The inventory's year.
    #[arg(long, default_value_t = 2026)]
    pub year: i32,
}
