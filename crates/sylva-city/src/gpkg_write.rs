//! Writes a demo city as a GeoPackage (OGC 12-128r18): the SQLite tables a reader needs
//! (`gpkg_spatial_ref_sys`, `gpkg_contents`, `gpkg_geometry_columns`) and a features layer
//! `trees` whose points are GeoPackage binary geometries (a `GP` header and WKB).

use crate::CityError;
use crate::demo::{DemoCity, Fault};
use rusqlite::Connection;
use std::path::Path;

/// The layer's name.
pub const LAYER: &str = "trees";

pub fn write(path: &Path, city: &DemoCity) -> Result<(), CityError> {
    let err = |e: &dyn std::fmt::Display| CityError::Write {
        path: path.into(),
        message: e.to_string(),
    };
    let partial = path.with_extension("gpkg.partial");
    let _ = std::fs::remove_file(&partial);
    {
        let db = Connection::open(&partial).map_err(|e| err(&e))?;
        let def = crs_definitions::from_code(city.epsg as u16)
            .ok_or_else(|| err(&format!("EPSG:{} unknown", city.epsg)))?;
        let srs = city.epsg as i64;
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
             CREATE TABLE \"{LAYER}\" (fid INTEGER PRIMARY KEY AUTOINCREMENT, geom POINT,
               OBJECTID TEXT, BOTANICAL TEXT, COMMON TEXT, DBH_CM TEXT, STATUS TEXT,
               HEIGHT_M REAL, PLANTED INTEGER);"
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
        let placed = city
            .trees
            .iter()
            .filter(|t| t.fault != Some(Fault::NoPosition));
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for t in placed {
            lo = [lo[0].min(t.x), lo[1].min(t.y)];
            hi = [hi[0].max(t.x), hi[1].max(t.y)];
        }
        db.execute(
            "INSERT INTO gpkg_contents VALUES (?1, 'features', ?1, 'street trees', ?2, ?3, ?4, ?5, ?6, ?7)",
            rusqlite::params![
                LAYER,
                format!("{}-01-01T00:00:00.000Z", city.year),
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
        let (_, rows) = city.gis_rows();
        db.execute_batch("BEGIN").map_err(|e| err(&e))?;
        let mut insert = db
            .prepare(&format!(
                "INSERT INTO \"{LAYER}\" (geom, OBJECTID, BOTANICAL, COMMON, DBH_CM, STATUS, HEIGHT_M, PLANTED)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)"
            ))
            .map_err(|e| err(&e))?;
        for (t, r) in city.trees.iter().zip(&rows) {
            let geom = (t.fault != Some(Fault::NoPosition)).then(|| blob(srs as i32, t.x, t.y));
            insert
                .execute(rusqlite::params![
                    geom, r[0], r[1], r[2], r[3], r[4], t.height_m, t.planted
                ])
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
