//! Writes points with columns of text as a GeoPackage (OGC 12-128r18): the SQLite tables a
//! reader needs (`gpkg_spatial_ref_sys`, `gpkg_contents`, `gpkg_geometry_columns`) and a
//! features layer `trees` whose points are GeoPackage binary geometries (a `GP` header and
//! WKB). The demo city's GeoPackage form.

use crate::error::CityError;
use rusqlite::Connection;
use std::path::Path;

/// The layer's name.
pub const LAYER: &str = "trees";

/// A layer to write: its coordinate system, the year it describes, its columns and rows, and
/// each row's point (none: an empty geometry).
pub struct Layer<'a> {
    pub epsg: u32,
    pub year: i32,
    pub columns: &'a [&'a str],
    pub rows: &'a [Vec<String>],
    pub points: &'a [Option<(f64, f64)>],
}

/// Writes `layer` to `path` (through a file beside it, renamed into place).
pub fn write(path: &Path, layer: &Layer<'_>) -> Result<(), CityError> {
    let err = |e: &dyn std::fmt::Display| CityError::write(path, e);
    let partial = path.with_extension("gpkg.partial");
    let _ = std::fs::remove_file(&partial);
    {
        let db = Connection::open(&partial).map_err(|e| err(&e))?;
        let def = u16::try_from(layer.epsg)
            .ok()
            .and_then(crs_definitions::from_code)
            .ok_or_else(|| err(&format!("EPSG:{} unknown", layer.epsg)))?;
        let srs = layer.epsg as i64;
        let quoted: Vec<String> = layer
            .columns
            .iter()
            .map(|c| format!("\"{}\"", c.replace('"', "")))
            .collect();
        let columns: String = quoted.iter().map(|c| format!(", {c} TEXT")).collect();
        db.execute_batch(&format!(
            "PRAGMA application_id = 1196444487;
             PRAGMA user_version = 10300;
             CREATE TABLE gpkg_spatial_ref_sys (srs_name TEXT NOT NULL, srs_id INTEGER PRIMARY KEY,
               organization TEXT NOT NULL, organization_coordsys_id INTEGER NOT NULL,
               definition TEXT NOT NULL, description TEXT);
             CREATE TABLE gpkg_contents (table_name TEXT NOT NULL PRIMARY KEY, data_type TEXT NOT NULL,
               identifier TEXT UNIQUE, description TEXT DEFAULT '', last_change DATETIME NOT NULL,
               min_x DOUBLE, min_y DOUBLE, max_x DOUBLE, max_y DOUBLE, srs_id INTEGER,
               CONSTRAINT fk_gc_r_srs_id FOREIGN KEY (srs_id) REFERENCES gpkg_spatial_ref_sys(srs_id));
             CREATE TABLE gpkg_geometry_columns (table_name TEXT NOT NULL, column_name TEXT NOT NULL,
               geometry_type_name TEXT NOT NULL, srs_id INTEGER NOT NULL, z TINYINT NOT NULL,
               m TINYINT NOT NULL, CONSTRAINT pk_geom_cols PRIMARY KEY (table_name, column_name));
             CREATE TABLE \"{LAYER}\" (fid INTEGER PRIMARY KEY AUTOINCREMENT, geom POINT{columns});"
        ))
        .map_err(|e| err(&e))?;
        let wgs84 = crs_definitions::from_code(4326).map_or("", |d| d.wkt);
        let mut put = db
            .prepare("INSERT INTO gpkg_spatial_ref_sys VALUES (?1, ?2, ?3, ?4, ?5, ?6)")
            .map_err(|e| err(&e))?;
        for (name, id, org, code, definition) in [
            ("Undefined Cartesian SRS", -1i64, "NONE", -1i64, "undefined"),
            ("Undefined geographic SRS", 0, "NONE", 0, "undefined"),
            ("WGS 84 geodetic", 4326, "EPSG", 4326, wgs84),
            ("WGS 84 / UTM", srs, "EPSG", srs, def.wkt),
        ] {
            put.execute(rusqlite::params![name, id, org, code, definition, ""])
                .map_err(|e| err(&e))?;
        }
        drop(put);
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for &(x, y) in layer.points.iter().flatten() {
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
        db.execute(
            "INSERT INTO gpkg_contents VALUES (?1, 'features', ?1, 'street trees', ?2, ?3, ?4, ?5, ?6, ?7)",
            rusqlite::params![
                LAYER,
                format!("{}-01-01T00:00:00.000Z", layer.year),
                lo[0],
                lo[1],
                hi[0],
                hi[1],
                srs
            ],
        )
        .map_err(|e| err(&e))?;
        db.execute(
            "INSERT INTO gpkg_geometry_columns VALUES (?1, 'geom', 'POINT', ?2, 0, 0)",
            rusqlite::params![LAYER, srs],
        )
        .map_err(|e| err(&e))?;
        db.execute_batch("BEGIN").map_err(|e| err(&e))?;
        let marks: Vec<String> = (2..=layer.columns.len() + 1)
            .map(|k| format!("?{k}"))
            .collect();
        let mut insert = db
            .prepare(&format!(
                "INSERT INTO \"{LAYER}\" (geom, {}) VALUES (?1, {})",
                quoted.join(", "),
                marks.join(", ")
            ))
            .map_err(|e| err(&e))?;
        for (row, point) in layer.rows.iter().zip(layer.points) {
            let geom = point.map(|(x, y)| blob(srs as i32, x, y));
            let mut values: Vec<Box<dyn rusqlite::ToSql>> = vec![Box::new(geom)];
            // Empty cells as NULL, as GIS exports leave them.
            for v in row {
                values.push(if v.is_empty() {
                    Box::new(Option::<String>::None)
                } else {
                    Box::new(v.clone())
                });
            }
            insert
                .execute(rusqlite::params_from_iter(values.iter()))
                .map_err(|e| err(&e))?;
        }
        drop(insert);
        db.execute_batch("COMMIT").map_err(|e| err(&e))?;
    }
    std::fs::rename(&partial, path).map_err(|e| err(&e))
}

/// A point as a GeoPackage binary geometry: `GP`, version 0, flags (little-endian, no
/// envelope), the SRS id, then the point as little-endian WKB.
fn blob(srs: i32, x: f64, y: f64) -> Vec<u8> {
    let mut b = Vec::with_capacity(29);
    b.extend_from_slice(b"GP");
    b.push(0);
    b.push(0b0000_0001);
    b.extend_from_slice(&srs.to_le_bytes());
    b.push(1);
    b.extend_from_slice(&1u32.to_le_bytes());
    b.extend_from_slice(&x.to_le_bytes());
    b.extend_from_slice(&y.to_le_bytes());
    b
}
