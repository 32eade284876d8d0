//! Which of an inventory's columns hold what, and in which units. Every column can be named by
//! a flag; those left unnamed come from the well-known layout the file's header matches:
//!
//! - **census**: the street-tree census style of New York City's 2015 census (NYC Open Data,
//!   "2015 Street Tree Census - Tree Data": `tree_id`, `spc_latin`, `spc_common`, `tree_dbh` in
//!   inches, `status` Alive/Dead/Stump, `latitude`, `longitude`, and state-plane `x_sp`,
//!   `y_sp` in EPSG:2263), and files like it (`species`, `dbh`, `lat`/`lon`);
//! - **GIS export**: a layer exported from a GIS with projected coordinates (`POINT_X` and
//!   `POINT_Y`, as ArcGIS's Add XY Coordinates writes them, or `X`/`Y`, `EASTING`/`NORTHING`),
//!   in the system `--crs` names.
//!
//! DBH is in inches, the unit of US inventories, unless its column's name says cm (`dbh_cm`)
//! or `--dbh-unit cm` says so; a trunk circumference may stand in for it.

use super::find;
use super::observed::ObservedColumns;
use super::{Inventory, Position, Record, Records, Rejected, Status, Tree};
use crate::error::CityError;
use std::path::Path;

/// A unit of length in an inventory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LengthUnit {
    /// Centimetres.
    Cm,
    /// Inches.
    Inches,
    /// Metres.
    Metres,
    /// Feet.
    Feet,
}

impl LengthUnit {
    /// The unit of a flag's value: `cm`, `in`, `m`, `ft`.
    pub fn parse(flag: &str, s: &str) -> Result<LengthUnit, CityError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "cm" => Ok(LengthUnit::Cm),
            "in" | "inch" | "inches" => Ok(LengthUnit::Inches),
            "m" | "metres" | "meters" => Ok(LengthUnit::Metres),
            "ft" | "feet" | "foot" => Ok(LengthUnit::Feet),
            _ => Err(CityError::setting(
                flag,
                format!("`{s}` is no unit; expected cm, in, m or ft"),
            )),
        }
    }

    /// Metres in one of this unit.
    pub fn metres(self) -> f64 {
        match self {
            LengthUnit::Cm => 0.01,
            LengthUnit::Inches => 0.0254,
            LengthUnit::Metres => 1.0,
            LengthUnit::Feet => 0.3048,
        }
    }

    fn name(self) -> &'static str {
        match self {
            LengthUnit::Cm => "cm",
            LengthUnit::Inches => "inches",
            LengthUnit::Metres => "m",
            LengthUnit::Feet => "ft",
        }
    }
}

/// Which columns hold what. A column left `None` is taken from the layout the header matches.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layout {
    /// The inventory's id of a tree.
    pub id: Option<String>,
    /// The species: columns tried in order (a scientific name, then a common name).
    pub species: Vec<String>,
    /// Trunk diameter at breast height...
    pub dbh: Option<String>,
    /// ...in this unit (inches if none is named or implied).
    pub dbh_unit: Option<LengthUnit>,
    /// Trunk circumference at breast height, where there is no DBH...
    pub circumference: Option<String>,
    /// ...in this unit (the DBH's if none).
    pub circumference_unit: Option<LengthUnit>,
    /// Longitude and latitude, degrees.
    pub lon_lat: Option<(String, String)>,
    /// Projected x and y, in the system `crs` names.
    pub xy: Option<(String, String)>,
    /// EPSG code of the projected coordinates (and of a file's geometry where the file does
    /// not name one).
    pub crs: Option<u32>,
    /// Tree height...
    pub height: Option<String>,
    /// ...in this unit (metres if none; feet in a census layout).
    pub height_unit: Option<LengthUnit>,
    /// Year planted.
    pub planted: Option<String>,
    /// Alive, dead, stump or planting site.
    pub status: Option<String>,
    /// Ground height above the ellipsoid, m.
    pub ground: Option<String>,
    /// What the surveyors saw: condition and problems.
    pub observed: ObservedColumns,
    /// The layout in words, once completed.
    pub name: String,
}

impl Layout {
    /// This layout with every column it leaves unnamed taken from the well-known layout
    /// `header` matches, where the header has such a column.
    pub fn completed(&self, header: &[String]) -> Layout {
        let f = |names: &[&str]| find(header, names);
        let census = f(&["tree_dbh"]).is_some() && f(&["spc_latin"]).is_some();
        let mut l = self.clone();
        l.name = if census {
            "census (New York City 2015 street tree census)".into()
        } else if f(&["point_x", "x", "easting"]).is_some() {
            "GIS export (projected x/y)".into()
        } else {
            "census style (latitude/longitude)".into()
        };
        l.id = l.id.or_else(|| {
            f(&[
                "tree_id",
                "treeid",
                "id",
                "objectid",
                "fid",
                "inventory_id",
                "asset_id",
            ])
        });
        if l.species.is_empty() {
            l.species = [
                &[
                    "spc_latin",
                    "species_latin",
                    "botanical",
                    "botanical_name",
                    "scientific",
                ][..],
                &["species", "qspecies", "spp", "species_name"][..],
                &["spc_common", "common", "common_name", "commonname"][..],
            ]
            .iter()
            .filter_map(|names| f(names))
            .collect();
        }
        if l.dbh.is_none() && l.circumference.is_none() {
            l.dbh = f(&[
                "tree_dbh",
                "dbh",
                "dbh_in",
                "dbh_inches",
                "dbh_cm",
                "diameter",
            ]);
            if l.dbh.is_none() {
                l.circumference = f(&["circumference", "girth", "circumference_cm", "girth_cm"]);
            }
        }
        let says_cm = |c: &Option<String>| {
            c.as_deref()
                .is_some_and(|c| c.to_ascii_lowercase().ends_with("cm"))
        };
        if l.dbh_unit.is_none() && says_cm(&l.dbh) {
            l.dbh_unit = Some(super::LengthUnit::Cm);
        }
        if l.circumference_unit.is_none() && says_cm(&l.circumference) {
            l.circumference_unit = Some(super::LengthUnit::Cm);
        }
        if l.lon_lat.is_none() {
            l.lon_lat = f(&["longitude", "lon", "long", "lng"]).zip(f(&["latitude", "lat"]));
        }
        if l.xy.is_none() {
            l.xy = f(&["x_sp", "point_x", "x", "easting"])
                .zip(f(&["y_sp", "point_y", "y", "northing"]));
            // The census's state-plane columns are in New York's Long Island zone, US feet.
            if census
                && l.crs.is_none()
                && l.xy
                    .as_ref()
                    .is_some_and(|xy| xy.0.eq_ignore_ascii_case("x_sp"))
            {
                l.crs = Some(2263);
            }
        }
        l.height = l
            .height
            .or_else(|| f(&["height", "height_m", "tree_height", "height_ft"]));
        if l.height_unit.is_none() {
            let h = l.height.as_deref().unwrap_or("").to_ascii_lowercase();
            l.height_unit = Some(if h.ends_with("ft") || census {
                super::LengthUnit::Feet
            } else {
                super::LengthUnit::Metres
            });
        }
        l.planted = l
            .planted
            .or_else(|| f(&["planted", "planted_year", "year_planted", "plantyear"]));
        l.status = l
            .status
            .or_else(|| f(&["status", "condition", "tree_status"]));
        l.ground = l
            .ground
            .or_else(|| f(&["ground", "ground_m", "elevation", "z"]));
        l.observed = l.observed.completed(header);
        l
    }

    /// Turns `records` into trees: each row's columns read by this layout, converted to
    /// metres, centimetres and degrees, and checked. Rows that fail are kept as rejected.
    pub fn apply(&self, records: Records, path: &Path) -> Result<Inventory, CityError> {
        // A column named that the file does not have would read as empty on every row.
        if let Some((flag, column)) = self
            .named()
            .into_iter()
            .find(|(_, c)| !records.header.iter().any(|h| h == c))
        {
            return Err(CityError::inventory(
                path,
                format!(
                    "{flag} {column}: no such column (the header has {})",
                    records.header.join(", ")
                ),
            ));
        }
        if self.species.is_empty() {
            return Err(CityError::inventory(
                path,
                format!(
                    "no species column: name one with --species-col (the header has {})",
                    records.header.join(", ")
                ),
            ));
        }
        if self.dbh.is_none() && self.circumference.is_none() {
            return Err(CityError::inventory(
                path,
                format!(
                    "no DBH or circumference column: name one with --dbh-col or \
                     --circumference-col (the header has {})",
                    records.header.join(", ")
                ),
            ));
        }
        if let Some(column) = &self.observed.condition {
            let cells: Vec<&str> = (records.rows.iter())
                .filter_map(|r| r.fields.iter().find(|(k, _)| k == column))
                .map(|(_, v)| v.as_str())
                .collect();
            self.observed.check(&cells, path)?;
        }
        let crs = records.crs.or(self.crs);
        let has_points = records.rows.iter().any(|r| r.point.is_some());
        if !has_points && self.lon_lat.is_none() && self.xy.is_none() {
            // A file of features none of which is a point says so first.
            let first = records.rejected.first().map_or(String::new(), |r| {
                format!(
                    "; {} rows unusable, the first: {}",
                    records.rejected.len(),
                    r.reason
                )
            });
            return Err(CityError::inventory(
                path,
                format!(
                    "no position columns: name them with --lon-col and --lat-col, or --x-col \
                     and --y-col with --crs (the header has {}){first}",
                    records.header.join(", ")
                ),
            ));
        }
        if self.lon_lat.is_none() && self.xy.is_some() && crs.is_none() {
            return Err(CityError::setting(
                "--crs",
                format!(
                    "{}: x and y are projected coordinates; name their system, e.g. --crs \
                     EPSG:2263",
                    path.display()
                ),
            ));
        }
        let mut out = Inventory {
            crs,
            layout: self.name.clone(),
            rejected: records.rejected,
            ..Default::default()
        };
        for record in &records.rows {
            match self.tree(record, records.crs.is_some()) {
                Ok(t) => out.trees.push(t),
                Err(reason) => out.rejected.push(Rejected {
                    line: record.line,
                    reason,
                }),
            }
        }
        out.rejected.sort_by_key(|r| r.line);
        Ok(out)
    }

    /// Every column this layout names, with the flag that names it.
    fn named(&self) -> Vec<(&'static str, &str)> {
        let one = [
            ("--id-col", &self.id),
            ("--dbh-col", &self.dbh),
            ("--circumference-col", &self.circumference),
            ("--height-col", &self.height),
            ("--planted-col", &self.planted),
            ("--status-col", &self.status),
            ("--ground-col", &self.ground),
            ("--condition-col", &self.observed.condition),
        ];
        let mut out: Vec<(&'static str, &str)> = (one.into_iter())
            .filter_map(|(flag, c)| Some((flag, c.as_deref()?)))
            .collect();
        if let Some((a, b)) = &self.lon_lat {
            out.extend([("--lon-col", a.as_str()), ("--lat-col", b.as_str())]);
        }
        if let Some((a, b)) = &self.xy {
            out.extend([("--x-col", a.as_str()), ("--y-col", b.as_str())]);
        }
        out.extend(self.species.iter().map(|c| ("--species-col", c.as_str())));
        out
    }

    /// One row as a tree, or why it cannot be one.
    fn tree(&self, r: &Record, projected_geometry: bool) -> Result<Tree, String> {
        let get = |c: &Option<String>| -> Option<&str> {
            let c = c.as_deref()?;
            r.fields
                .iter()
                .find(|(k, _)| k == c)
                .map(|(_, v)| v.trim())
                .filter(|v| !v.is_empty())
        };
        let number = |c: &Option<String>, what: &str| -> Result<Option<f64>, String> {
            match get(c) {
                None => Ok(None),
                Some(v) => v
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .map(Some)
                    .ok_or_else(|| {
                        format!(
                            "column `{}` is `{v}`, expected {what}",
                            c.as_deref().unwrap_or("")
                        )
                    }),
            }
        };
        let species = self
            .species
            .iter()
            .find_map(|c| get(&Some(c.clone())))
            .unwrap_or("")
            .to_string();
        let status = status_of(get(&self.status).unwrap_or(""), &species);
        let dbh_unit = self.dbh_unit.unwrap_or(LengthUnit::Inches);
        let dbh = match number(&self.dbh, &format!("a number ({})", dbh_unit.name()))? {
            Some(d) => Some(d * dbh_unit.metres() * 100.0),
            None => {
                let unit = self.circumference_unit.unwrap_or(dbh_unit);
                number(&self.circumference, &format!("a number ({})", unit.name()))?
                    .map(|c| c * unit.metres() * 100.0 / std::f64::consts::PI)
            }
        };
        if status == Status::Alive {
            match dbh {
                None => return Err("no DBH or circumference".into()),
                // The largest street trees measured are some 250 cm across (UTD's largest
                // DBH classes stop at 42 in and above); 1,000 cm is no street tree.
                Some(d) if !(d > 0.0 && d <= 1000.0) => {
                    return Err(format!("DBH {d:.1} cm is outside 0-1000 cm"));
                }
                _ => {}
            }
        }
        let pair =
            |c: &Option<(String, String)>, what: &str| -> Result<Option<(f64, f64)>, String> {
                let Some((a, b)) = c else { return Ok(None) };
                let a = number(&Some(a.clone()), what)?;
                let b = number(&Some(b.clone()), what)?;
                Ok(a.zip(b))
            };
        let position = if let Some((lon, lat)) = pair(&self.lon_lat, "a number (degrees)")? {
            Position::LonLat(lon, lat)
        } else if let Some((x, y)) = pair(&self.xy, "a number")? {
            Position::Projected(x, y)
        } else if let Some((x, y)) = r.point {
            if projected_geometry {
                Position::Projected(x, y)
            } else {
                Position::LonLat(x, y)
            }
        } else {
            return Err("no position".into());
        };
        if let Position::LonLat(lon, lat) = position {
            // Missing positions are often written as 0, 0 ("Null Island").
            if !(-180.0..=180.0).contains(&lon)
                || !(-90.0..=90.0).contains(&lat)
                || (lon == 0.0 && lat == 0.0)
            {
                return Err(format!(
                    "position {lon}, {lat} is not a longitude (-180 to 180) and latitude (-90 to 90)"
                ));
            }
        }
        let height_unit = self.height_unit.unwrap_or(LengthUnit::Metres);
        let height = number(&self.height, &format!("a number ({})", height_unit.name()))?
            .map(|h| h * height_unit.metres())
            .filter(|&h| h > 0.0);
        if let Some(h) = height
            && h > 150.0
        {
            return Err(format!("height {h:.1} m is over 150 m"));
        }
        let planted = match number(&self.planted, "a year")? {
            None => None,
            Some(y) if (1000.0..=9999.0).contains(&y) => Some(y as i32),
            Some(y) => return Err(format!("planting year {y} is not a year")),
        };
        let ground = number(&self.ground, "a number (m)")?;
        Ok(Tree {
            line: r.line,
            id: get(&self.id).map_or_else(|| r.line.to_string(), str::to_string),
            species,
            dbh,
            position,
            height,
            planted,
            ground,
            status,
            observed: self.observed.read(|c| get(c).map(str::to_string)),
        })
    }
}

/// What a row is from its status and species: dead, a stump, an empty planting site, or a
/// living tree.
fn status_of(status: &str, species: &str) -> Status {
    let s = status.to_ascii_lowercase();
    let sp = species.to_ascii_lowercase();
    if s.contains("stump") || sp.contains("stump") {
        Status::Stump
    } else if s.contains("dead") || sp.starts_with("dead") {
        Status::Dead
    } else if ["vacant", "site", "empty", "planting"]
        .iter()
        .any(|w| s.contains(w) || sp.contains(w))
    {
        Status::Site
    } else {
        Status::Alive
    }
}
