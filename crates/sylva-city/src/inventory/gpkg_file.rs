//! A GeoPackage inventory (OGC 12-128r18): an SQLite file whose features layer holds a row per
//! tree, its point in a geometry column as a GeoPackage binary blob (a `GP` header, an
//! optional envelope, then standard WKB), in the spatial reference system the layer names.

use super::{MAX_ROWS, Record, Records, Rejected};
use crate::error::CityError;
use geo_traits::{CoordTrait, GeometryTrait, GeometryType, PointTrait};
use rusqlite::types::ValueRef;
use rusqlite::{Connection, OpenFlags};
use std::path::Path;

/// Reads every row of `layer` (or the file's only, or first, features layer).
pub fn read(path: &Path, layer: Option<&str>) -> Result<Records, CityError> {
    let err = |m: String| CityError::inventory(path, m);
    let db = Connection::open_with_flags(path, OpenFlags::SQLITE_OPEN_READ_ONLY)
        .map_err(|e| err(format!("cannot be opened as a GeoPackage: {e}")))?;
    let sql = |e: rusqlite::Error| err(format!("not a GeoPackage: {e}"));
    let layers: Vec<String> = db
        .prepare(
            "SELECT table_name FROM gpkg_contents WHERE data_type = 'features' ORDER BY table_name",
        )
        .and_then(|mut s| s.query_map([], |r| r.get(0))?.collect())
        .map_err(sql)?;
    let table = match layer {
        Some(l) => layers.iter().find(|t| *t == l).cloned().ok_or_else(|| {
            err(format!(
                "has no features layer `{l}`; its layers are {}",
                layers.join(", ")
            ))
        })?,
        None => layers
            .first()
            .cloned()
            .ok_or_else(|| err("has no features layer".into()))?,
    };
    let (geometry, srs): (String, i64) = db
        .query_row(
            "SELECT column_name, srs_id FROM gpkg_geometry_columns WHERE table_name = ?1",
            [&table],
            |r| Ok((r.get(0)?, r.get(1)?)),
        )
        .map_err(sql)?;
    // The layer's system as an EPSG code; longitude and latitude (4326) need no projection.
    let crs: Option<u32> = db
        .query_row(
            "SELECT organization, organization_coordsys_id FROM gpkg_spatial_ref_sys WHERE srs_id = ?1",
            [srs],
            |r| Ok((r.get::<_, String>(0)?, r.get::<_, i64>(1)?)),
        )
        .ok()
        .filter(|(org, _)| org.eq_ignore_ascii_case("epsg"))
        .and_then(|(_, code)| u32::try_from(code).ok())
        .filter(|&c| c != 4326);
    let quoted = format!("\"{}\"", table.replace('"', "\"\""));
    let mut statement = db
        .prepare(&format!("SELECT * FROM {quoted}"))
        .map_err(sql)?;
    let names: Vec<String> = statement.column_names().map(|s| s.to_string()).collect();
    let at_geometry = names.iter().position(|n| n.eq_ignore_ascii_case(&geometry));
    let mut out = Records {
        crs,
        header: names
            .iter()
            .filter(|n| !n.eq_ignore_ascii_case(&geometry))
            .cloned()
            .collect(),
        ..Default::default()
    };
    let mut rows = statement.query([]).map_err(sql)?;
    let mut line = 0;
    while let Some(row) = rows.next().map_err(sql)? {
        line += 1;
        if line > MAX_ROWS {
            return Err(err(format!(
                "layer `{table}` has more than {MAX_ROWS} rows"
            )));
        }
        let mut fields = Vec::with_capacity(names.len());
        let mut point = None;
        let mut bad = None;
        for (k, name) in names.iter().enumerate() {
            let value = row.get_ref(k).map_err(sql)?;
            if Some(k) == at_geometry {
                match value {
                    ValueRef::Blob(b) => match point_of(b) {
                        Ok(p) => point = p,
                        Err(reason) => bad = Some(reason),
                    },
                    ValueRef::Null => {}
                    _ => bad = Some(format!("column `{name}` holds no geometry")),
                }
                continue;
            }
            let text = match value {
                ValueRef::Null => String::new(),
                ValueRef::Integer(i) => i.to_string(),
                ValueRef::Real(f) => f.to_string(),
                ValueRef::Text(t) => String::from_utf8_lossy(t).into_owned(),
                ValueRef::Blob(_) => String::new(),
            };
            fields.push((name.clone(), text));
        }
        match bad {
            Some(reason) => out.rejected.push(Rejected { line, reason }),
            None => out.rows.push(Record {
                line,
                fields,
                point,
            }),
        }
    }
    Ok(out)
}

/// The point of a GeoPackage geometry blob, none for an empty geometry.
fn point_of(blob: &[u8]) -> Result<Option<(f64, f64)>, String> {
    if blob.len() < 8 || &blob[..2] != b"GP" {
        return Err("the geometry is not a GeoPackage blob (no `GP` header)".into());
    }
    let flags = blob[3];
    if flags & 0b1_0000 != 0 {
        return Ok(None);
    }
    // The envelope: none, xy, xyz, xym or xyzm (flags bits 1-3).
    let envelope = match (flags >> 1) & 0b111 {
        0 => 0,
        1 => 32,
        2 | 3 => 48,
        4 => 64,
        e => return Err(format!("envelope code {e} is not 0-4")),
    };
    let wkb = blob
        .get(8 + envelope..)
        .ok_or("the geometry blob is cut short")?;
    let geometry = wkb::reader::read_wkb(wkb).map_err(|e| format!("the geometry's WKB: {e}"))?;
    match geometry.as_type() {
        GeometryType::Point(p) => Ok(p.coord().map(|c| (c.x(), c.y()))),
        _ => Err("the geometry is not a point".into()),
    }
}
