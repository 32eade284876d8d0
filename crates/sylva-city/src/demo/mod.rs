//! A synthetic city for trying `sylva city` offline: street trees along a grid of streets
//! around a region's reference city, in the species mix and DBH classes the Urban Tree
//! Database counted there (table TS2), with the dead trees, stumps, empty sites, planned
//! plantings and broken rows that real inventories carry. Written in each supported form and
//! layout, all describing the same trees.

mod gpkg_write;
mod observed;

use crate::error::CityError;
use crate::geo::Projection;
use crate::inventory::regions::city_of;
use std::path::Path;
use sylva::growth::{DBH_CLASS_EDGES_CM, Database};
use sylva::rng::{Random, StreamKey};

/// Distance between trees along a street, m, and between street centrelines: blocks 100 m
/// square, trees 8 m apart on both sides, 6 m from the centreline (Sylva's choice of a
/// typical US residential street).
const SPACING: f64 = 8.0;
const BLOCK: f64 = 100.0;
const SETBACK: f64 = 6.0;
/// Upper edge of the open ninth DBH class, cm (Sylva's choice).
const LAST_CLASS_TOP: f64 = 130.0;

/// What a demo row is.
#[derive(Clone, Debug, PartialEq)]
pub enum DemoStatus {
    /// A living tree.
    Alive,
    /// A dead tree.
    Dead,
    /// A stump.
    Stump,
    /// An empty planting site.
    Site,
}

/// One row of the demo city.
#[derive(Clone, Debug, PartialEq)]
pub struct DemoTree {
    /// Its id.
    pub id: String,
    /// Scientific and common name (empty for a site).
    pub scientific: String,
    pub common: String,
    /// DBH, cm.
    pub dbh_cm: f64,
    /// Easting and northing in the city's UTM zone, m.
    pub x: f64,
    pub y: f64,
    /// Longitude and latitude, degrees.
    pub lon: f64,
    pub lat: f64,
    /// Height, m, where measured.
    pub height_m: Option<f64>,
    /// Year planted, where known.
    pub planted: Option<i32>,
    /// What it is.
    pub status: DemoStatus,
    /// A fault written into this row instead of a good value (`None`: a good row).
    pub fault: Option<Fault>,
}

/// A broken value, as real inventories have them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// The DBH is text.
    DbhText,
    /// No position.
    NoPosition,
    /// A living tree with no DBH.
    NoDbh,
}

/// A demo city.
#[derive(Clone, Debug, PartialEq)]
pub struct DemoCity {
    /// Its region.
    pub region: String,
    /// EPSG code of its projected coordinates (WGS84 / UTM north).
    pub epsg: u32,
    /// Its rows.
    pub trees: Vec<DemoTree>,
    /// The inventory's year.
    pub year: i32,
}

/// The demo city of `n` rows around `region`'s reference city.
pub fn demo_city(region: &str, n: usize, seed: u64, year: i32) -> Result<DemoCity, CityError> {
    let db = Database::builtin();
    let region = db
        .regions()
        .iter()
        .find(|r| r.code.eq_ignore_ascii_case(region))
        .map(|r| r.code.clone())
        .ok_or_else(|| {
            CityError::setting(
                "--region",
                format!("`{region}` is no region of the Urban Tree Database"),
            )
        })?;
    let (lon0, lat0) =
        city_of(&region).ok_or_else(|| CityError::setting("--region", "no reference city"))?;
    let zone = ((lon0 + 180.0) / 6.0).floor() as u32 + 1;
    let epsg = 32600 + zone;
    let utm = Projection::epsg(epsg)?;
    // The city's centre in UTM, by inverting the projection near its central meridian:
    // a few Newton steps on the forward difference.
    let (x0, y0) = utm_of(&utm, lon0, lat0);
    let species: Vec<(&sylva::growth::SpeciesEntry, u32)> = db
        .growable(&region)
        .into_iter()
        .map(|s| (s, s.trees_by_dbh_class.iter().sum::<u32>()))
        .filter(|s| s.1 > 0)
        .collect();
    let total: u32 = species.iter().map(|s| s.1).sum();
    let mut rng: Random = StreamKey::from_seed(seed).child(7).stream();
    // Street-side spots, square grid outward from the centre until there are enough.
    let per_block = 4 * (BLOCK / SPACING) as usize;
    let blocks = (n / per_block + 1) as f64;
    let side = blocks.sqrt().ceil() as i64;
    let mut spots = Vec::with_capacity(n);
    'fill: for bx in 0..side {
        for by in 0..side {
            let (ox, oy) = (
                x0 + (bx - side / 2) as f64 * BLOCK,
                y0 + (by - side / 2) as f64 * BLOCK,
            );
            let along = (BLOCK / SPACING) as usize;
            for k in 0..along {
                let s = k as f64 * SPACING + SPACING / 2.0;
                for (x, y) in [
                    (ox + s, oy + SETBACK),
                    (ox + s, oy + BLOCK - SETBACK),
                    (ox + SETBACK, oy + s),
                    (ox + BLOCK - SETBACK, oy + s),
                ] {
                    spots.push((x, y));
                    if spots.len() >= n {
                        break 'fill;
                    }
                }
            }
        }
    }
    let mut trees = Vec::with_capacity(n);
    let mut measured = std::collections::HashMap::new();
    for (i, &(x, y)) in spots.iter().enumerate() {
        let (lon, lat) = utm
            .lon_lat(x, y)
            .ok_or_else(|| CityError::Growth("UTM".into()))?;
        let mut pick = rng.unit() * total as f64;
        let mut chosen = species[0].0;
        for (s, w) in &species {
            if pick < *w as f64 {
                chosen = s;
                break;
            }
            pick -= *w as f64;
        }
        let classes = chosen.trees_by_dbh_class;
        let mut c = rng.unit() * classes.iter().sum::<u32>() as f64;
        let mut class = 0;
        for (k, &w) in classes.iter().enumerate() {
            if c < w as f64 {
                class = k;
                break;
            }
            c -= w as f64;
        }
        let lo = if class == 0 {
            2.5
        } else {
            DBH_CLASS_EDGES_CM[class - 1]
        };
        let hi = DBH_CLASS_EDGES_CM
            .get(class)
            .copied()
            .unwrap_or(LAST_CLASS_TOP);
        let dbh = lo + rng.unit() * (hi - lo);
        let roll = rng.unit();
        let status = if roll < 0.01 {
            DemoStatus::Dead
        } else if roll < 0.015 {
            DemoStatus::Stump
        } else if roll < 0.025 {
            DemoStatus::Site
        } else {
            DemoStatus::Alive
        };
        let mut t = DemoTree {
            id: format!("T{:06}", i + 1),
            scientific: chosen.scientific.clone(),
            common: chosen.common.clone(),
            dbh_cm: (dbh * 10.0).round() / 10.0,
            x: (x * 100.0).round() / 100.0,
            y: (y * 100.0).round() / 100.0,
            lon,
            lat,
            height_m: None,
            planted: None,
            status,
            fault: None,
        };
        let m = match measured.entry(chosen.code.clone()) {
            std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(
                db.find(&region, &chosen.code)
                    .map_err(|e| CityError::Growth(e.to_string()))?,
            ),
        };
        let age = m.age_at_dbh(t.dbh_cm);
        let roll = rng.unit();
        if t.status == DemoStatus::Alive && roll < 0.2 {
            // Measured heights scatter about the equation's.
            t.height_m = Some(((m.height(age) * (0.9 + 0.2 * rng.unit())) * 10.0).round() / 10.0);
        } else if t.status == DemoStatus::Alive && roll < 0.3 {
            t.planted = Some(year - age.round() as i32);
        } else if t.status == DemoStatus::Alive && roll < 0.31 {
            // A planting the city has planned: a nursery tree, in a few years.
            t.planted = Some(year + 1 + (rng.unit() * 9.0) as i32);
            t.dbh_cm = 2.5;
        }
        if matches!(t.status, DemoStatus::Site) {
            t.scientific.clear();
            t.common = "Vacant site".into();
        }
        trees.push(t);
    }
    // Five broken rows in a thousand.
    let faults = [Fault::DbhText, Fault::NoPosition, Fault::NoDbh];
    let n = trees.len();
    let broken = (n / 200).max(if n >= 20 { 3 } else { 0 });
    for k in 0..broken {
        let i = (rng.unit() * n as f64) as usize % n.max(1);
        if trees[i].status == DemoStatus::Alive && trees[i].fault.is_none() {
            trees[i].fault = Some(faults[k % faults.len()]);
        }
    }
    Ok(DemoCity {
        region,
        epsg,
        trees,
        year,
    })
}

/// Easting and northing of `lon`, `lat` in `utm`: the inverse of `Projection::lon_lat` by
/// Newton's method (the forward projection is not exposed; ten steps reach a millimetre).
fn utm_of(utm: &Projection, lon: f64, lat: f64) -> (f64, f64) {
    let (mut x, mut y) = (500_000.0, lat * 110_900.0);
    for _ in 0..10 {
        let Some((l, p)) = utm.lon_lat(x, y) else {
            break;
        };
        let (lx, px) = utm.lon_lat(x + 1.0, y).unwrap_or((l, p));
        let (ly, py) = utm.lon_lat(x, y + 1.0).unwrap_or((l, p));
        // Jacobian of (lon, lat) over (x, y), per metre.
        let (a, b, c, d) = (lx - l, ly - l, px - p, py - p);
        let det = a * d - b * c;
        if det.abs() < 1e-18 {
            break;
        }
        let (dl, dp) = (lon - l, lat - p);
        x += (d * dl - b * dp) / det;
        y += (-c * dl + a * dp) / det;
    }
    (x, y)
}

/// A layout of the demo's files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DemoLayout {
    /// Census style: `tree_id, spc_latin, spc_common, tree_dbh` (inches), `status`,
    /// `latitude, longitude`, `height_ft`, `planted`.
    Census,
    /// GIS export: `OBJECTID, BOTANICAL, COMMON, DBH_CM, STATUS, POINT_X, POINT_Y` (UTM, m),
    /// `HEIGHT_M`, `PLANTED`.
    Gis,
}

impl DemoCity {
    /// The rows as (column, value) pairs in `layout`.
    fn rows(&self, layout: DemoLayout) -> (Vec<&'static str>, Vec<Vec<String>>) {
        let header = match layout {
            DemoLayout::Census => vec![
                "tree_id",
                "spc_latin",
                "spc_common",
                "tree_dbh",
                "status",
                "latitude",
                "longitude",
                "height_ft",
                "planted",
                "health",
                "sidewalk",
                "brch_light",
                "trunk_wire",
                "trnk_light",
                "root_stone",
                "root_grate",
            ],
            DemoLayout::Gis => vec![
                "OBJECTID",
                "BOTANICAL",
                "COMMON",
                "DBH_CM",
                "STATUS",
                "POINT_X",
                "POINT_Y",
                "HEIGHT_M",
                "PLANTED",
                "CONDITION",
            ],
        };
        let rows = self
            .trees
            .iter()
            .map(|t| {
                let status = match t.status {
                    DemoStatus::Alive => "Alive",
                    DemoStatus::Dead => "Dead",
                    DemoStatus::Stump => "Stump",
                    DemoStatus::Site => "Planting site",
                };
                let dbh = match (t.fault, layout) {
                    (Some(Fault::DbhText), _) => "big".to_string(),
                    (Some(Fault::NoDbh), _) => String::new(),
                    (_, DemoLayout::Census) => format!("{:.2}", t.dbh_cm / 2.54),
                    (_, DemoLayout::Gis) => format!("{:.1}", t.dbh_cm),
                };
                let no_pos = t.fault == Some(Fault::NoPosition);
                let (a, b) = match layout {
                    DemoLayout::Census => (format!("{:.8}", t.lat), format!("{:.8}", t.lon)),
                    DemoLayout::Gis => (format!("{:.2}", t.x), format!("{:.2}", t.y)),
                };
                let (a, b) = if no_pos {
                    (String::new(), String::new())
                } else {
                    (a, b)
                };
                let height = t.height_m.map_or(String::new(), |h| match layout {
                    DemoLayout::Census => format!("{:.2}", h / 0.3048),
                    DemoLayout::Gis => format!("{h:.2}"),
                });
                let mut row = vec![
                    t.id.clone(),
                    t.scientific.clone(),
                    t.common.clone(),
                    dbh,
                    status.into(),
                    a,
                    b,
                    height,
                    t.planted.map_or(String::new(), |p| p.to_string()),
                ];
                row.extend(observed::cells(t, layout));
                row
            })
            .collect();
        (header, rows)
    }

    /// Writes the city as a CSV file in `layout`.
    pub fn write_csv(&self, path: &Path, layout: DemoLayout) -> Result<(), CityError> {
        let (header, rows) = self.rows(layout);
        let mut w = csv::Writer::from_writer(Vec::new());
        let err = |e: &dyn std::fmt::Display| CityError::write(path, e);
        w.write_record(&header).map_err(|e| err(&e))?;
        for r in rows {
            w.write_record(&r).map_err(|e| err(&e))?;
        }
        let bytes = w.into_inner().map_err(|e| err(&e))?;
        sylva::export::write_atomically(path, &bytes).map_err(|e| err(&e))
    }

    /// Writes the city as GeoJSON points (longitude, latitude) with the census layout's
    /// columns as properties (positions in the geometry only).
    pub fn write_geojson(&self, path: &Path) -> Result<(), CityError> {
        let (header, rows) = self.rows(DemoLayout::Census);
        let features: Vec<serde_json::Value> = rows
            .iter()
            .zip(&self.trees)
            .map(|(r, t)| {
                let mut props = serde_json::Map::new();
                for (h, v) in header.iter().zip(r) {
                    if matches!(*h, "latitude" | "longitude") {
                        continue;
                    }
                    // Numbers as numbers, as GIS exports write them.
                    let value = match v.parse::<f64>() {
                        Ok(x) if *h != "tree_id" => serde_json::json!(x),
                        _ if v.is_empty() => serde_json::Value::Null,
                        _ => serde_json::json!(v),
                    };
                    props.insert(h.to_string(), value);
                }
                let geometry = if t.fault == Some(Fault::NoPosition) {
                    serde_json::Value::Null
                } else {
                    serde_json::json!({ "type": "Point", "coordinates": [t.lon, t.lat] })
                };
                serde_json::json!({ "type": "Feature", "geometry": geometry, "properties": props })
            })
            .collect();
        let doc = serde_json::json!({ "type": "FeatureCollection", "features": features });
        let bytes = serde_json::to_vec(&doc).map_err(|e| CityError::write(path, e))?;
        sylva::export::write_atomically(path, &bytes).map_err(|e| CityError::write(path, e))
    }

    /// Writes the city as a GeoPackage layer `trees`: UTM points and the GIS layout's
    /// columns (positions in the geometry only).
    pub fn write_gpkg(&self, path: &Path) -> Result<(), CityError> {
        let (header, rows) = self.rows(DemoLayout::Gis);
        // Positions in the geometry only.
        let keep: Vec<usize> = (0..header.len())
            .filter(|&k| !matches!(header[k], "POINT_X" | "POINT_Y"))
            .collect();
        let columns: Vec<&str> = keep.iter().map(|&k| header[k]).collect();
        let rows: Vec<Vec<String>> = rows
            .iter()
            .map(|r| keep.iter().map(|&k| r[k].clone()).collect())
            .collect();
        let points: Vec<Option<(f64, f64)>> = self
            .trees
            .iter()
            .map(|t| (t.fault != Some(Fault::NoPosition)).then_some((t.x, t.y)))
            .collect();
        crate::demo::gpkg_write::write(
            path,
            &crate::demo::gpkg_write::Layer {
                epsg: self.epsg,
                year: self.year,
                columns: &columns,
                rows: &rows,
                points: &points,
            },
        )
    }
}

impl DemoCity {
    /// Writes the city to `path` in the form its extension names (`.csv` in `layout`,
    /// `.geojson`, `.gpkg`).
    pub fn write(&self, path: &Path, layout: DemoLayout) -> Result<(), CityError> {
        match crate::inventory::Format::of(path)? {
            crate::inventory::Format::Csv => self.write_csv(path, layout),
            crate::inventory::Format::GeoJson => self.write_geojson(path),
            crate::inventory::Format::GeoPackage => self.write_gpkg(path),
        }
    }
}
