//! A street-tree inventory as cities publish it: a CSV file, GeoJSON points or a GeoPackage
//! layer, one row per tree (or stump, or empty planting site). Each format is read into
//! records of named fields and an optional point geometry ([`Record`]); a [`Layout`] says which
//! fields hold what, and in which units, and turns records into [`Tree`]s. Rows that cannot be
//! read are kept with their line and the reason ([`Rejected`]), never dropped silently.

mod csv_file;
pub mod families;
mod geojson_file;
mod gpkg_file;
mod layout;
pub mod observed;
pub mod regions;
pub mod species;

pub use layout::{Layout, LengthUnit};
pub use observed::{Condition, Observed, ObservedColumns};

use crate::error::CityError;
use std::path::Path;

/// One row of an inventory file, before its layout is known: its fields by name (names as the
/// file writes them) and the point of its geometry, if it has one.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Where the row is: its line in a CSV file (the header is line 1), its feature's number
    /// in a GeoJSON file, its row's number in a GeoPackage layer.
    pub line: usize,
    /// Its fields, in the file's order.
    pub fields: Vec<(String, String)>,
    /// Its point geometry: longitude and latitude, or x and y in `crs`.
    pub point: Option<(f64, f64)>,
}

/// What a file holds, before its layout is applied.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Records {
    /// Its rows, in order.
    pub rows: Vec<Record>,
    /// Rows that could not be read at all (a broken line, a feature that is not a point).
    pub rejected: Vec<Rejected>,
    /// The EPSG code of its points' coordinate system where the file names one (a GeoPackage's
    /// layer, a GeoJSON `crs`); longitude and latitude otherwise.
    pub crs: Option<u32>,
    /// Its field names, for messages and for guessing its layout.
    pub header: Vec<String>,
}

/// A file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values with a header line.
    Csv,
    /// A GeoJSON FeatureCollection of points.
    GeoJson,
    /// A GeoPackage (SQLite) features layer.
    GeoPackage,
}

impl Format {
    /// The format a file's name says: `.csv`, `.geojson`/`.json`, `.gpkg`.
    pub fn of(path: &Path) -> Result<Format, CityError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        match ext.as_str() {
            "csv" | "txt" => Ok(Format::Csv),
            "geojson" | "json" => Ok(Format::GeoJson),
            "gpkg" => Ok(Format::GeoPackage),
            _ => Err(CityError::inventory(
                path,
                format!(
                    "the extension `.{ext}` names no inventory format; expected .csv, \
                     .geojson (or .json) or .gpkg"
                ),
            )),
        }
    }
}

/// Most rows an inventory may hold: a large city has 10^6 street trees; ten times that is a
/// mistake, not a city, and would take memory without bound.
pub const MAX_ROWS: usize = 10_000_000;

/// Reads every row of the inventory at `path` (in the format its extension names), and from a
/// GeoPackage the layer `layer` (or its only, or first, features layer).
pub fn read(path: &Path, layer: Option<&str>) -> Result<Records, CityError> {
    match Format::of(path)? {
        Format::Csv => csv_file::read(path),
        Format::GeoJson => geojson_file::read(path),
        Format::GeoPackage => gpkg_file::read(path, layer),
    }
}

/// What a row is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Status {
    /// A living tree.
    Alive,
    /// A dead tree still standing.
    Dead,
    /// A stump.
    Stump,
    /// A planting site with no tree.
    Site,
}

impl Status {
    /// In words, for the summary.
    pub fn words(self) -> &'static str {
        match self {
            Status::Alive => "living trees",
            Status::Dead => "dead trees",
            Status::Stump => "stumps",
            Status::Site => "empty planting sites",
        }
    }
}

/// Where a row's tree stands, as the file gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Position {
    /// Longitude and latitude, degrees (WGS84).
    LonLat(f64, f64),
    /// x and y in a projected coordinate system.
    Projected(f64, f64),
}

/// A row of an inventory, read.
#[derive(Clone, Debug, PartialEq)]
pub struct Tree {
    /// Where the row is in its file ([`Record::line`]).
    pub line: usize,
    /// The inventory's id for it, or its line.
    pub id: String,
    /// Its species as the file names it (empty for a planting site).
    pub species: String,
    /// Trunk diameter at breast height, cm (none for a stump or site without one).
    pub dbh: Option<f64>,
    /// Where it stands.
    pub position: Position,
    /// Its height, m, where the file gives one.
    pub height: Option<f64>,
    /// The year it was planted, where the file gives one.
    pub planted: Option<i32>,
    /// Ground height above the ellipsoid, m, where the file gives one.
    pub ground: Option<f64>,
    /// What it is.
    pub status: Status,
    /// What the surveyors saw of it: condition and problems.
    pub observed: Observed,
}

/// A row that cannot be used, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rejected {
    /// Where it is in its file.
    pub line: usize,
    /// Why it cannot be used: the column, its value and what was expected.
    pub reason: String,
}

/// An inventory, read and laid out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Inventory {
    /// Its usable rows, in order.
    pub trees: Vec<Tree>,
    /// Rows that cannot be used.
    pub rejected: Vec<Rejected>,
    /// The coordinate system of its projected positions (EPSG code), if any.
    pub crs: Option<u32>,
    /// The layout it was read with, in words.
    pub layout: String,
}

/// The header's name among `names` (any case), if it has one: how the layouts find their
/// columns.
fn find(header: &[String], names: &[&str]) -> Option<String> {
    names.iter().find_map(|n| {
        header
            .iter()
            .find(|h| h.trim().eq_ignore_ascii_case(n))
            .cloned()
    })
}

/// Reads the inventory at `path` with `layout` (each column it leaves unnamed taken from the
/// layout its header matches: see [`Layout::completed`]).
pub fn load(path: &Path, layer: Option<&str>, layout: &Layout) -> Result<Inventory, CityError> {
    let records = read(path, layer)?;
    let layout = layout.completed(&records.header);
    layout.apply(records, path)
}
