//! A GeoJSON inventory: a FeatureCollection with a Point feature per tree and its columns as
//! properties. Coordinates are longitude and latitude (RFC 7946), unless the file names
//! another system in the `crs` member that the 2008 GeoJSON specification had (GIS exports
//! still write it: `urn:ogc:def:crs:EPSG::2263`).

use super::{MAX_ROWS, Record, Records, Rejected};
use crate::error::CityError;
use std::path::Path;

/// Largest GeoJSON file read, bytes: it is parsed whole, and a city of 10^6 trees writes some
/// 500 MB.
const MAX_BYTES: u64 = 2 << 30;

/// Reads every feature of the GeoJSON file at `path`.
pub fn read(path: &Path) -> Result<Records, CityError> {
    let size = std::fs::metadata(path)
        .map_err(|e| CityError::inventory(path, e.to_string()))?
        .len();
    if size > MAX_BYTES {
        return Err(CityError::inventory(
            path,
            format!(
                "{size} bytes is over the {MAX_BYTES}-byte limit of a GeoJSON inventory; write a GeoPackage or CSV"
            ),
        ));
    }
    let text =
        std::fs::read_to_string(path).map_err(|e| CityError::inventory(path, e.to_string()))?;
    let value: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| CityError::inventory(path, format!("not JSON: {e}")))?;
    let crs = legacy_crs(&value);
    let collection: geojson::FeatureCollection = serde_json::from_value(value)
        .map_err(|e| CityError::inventory(path, format!("not a GeoJSON FeatureCollection: {e}")))?;
    if collection.features.len() > MAX_ROWS {
        return Err(CityError::inventory(
            path,
            format!("more than {MAX_ROWS} features"),
        ));
    }
    let mut out = Records {
        crs,
        ..Default::default()
    };
    for (k, feature) in collection.features.iter().enumerate() {
        let line = k + 1;
        let fields: Vec<(String, String)> = feature
            .properties
            .iter()
            .flatten()
            .map(|(name, v)| {
                let text = match v {
                    serde_json::Value::String(s) => s.clone(),
                    serde_json::Value::Null => String::new(),
                    other => other.to_string(),
                };
                (name.clone(), text)
            })
            .collect();
        for (name, _) in &fields {
            if !out.header.contains(name) {
                out.header.push(name.clone());
            }
        }
        let point = match feature.geometry.as_ref().map(|g| &g.value) {
            Some(geojson::GeometryValue::Point { coordinates: p }) if p.len() >= 2 => {
                Some((p[0], p[1]))
            }
            None => None,
            Some(other) => {
                out.rejected.push(Rejected {
                    line,
                    reason: format!("feature {line} is a {}, not a Point", other.type_name()),
                });
                continue;
            }
        };
        out.rows.push(Record {
            line,
            fields,
            point,
        });
    }
    Ok(out)
}

/// The EPSG code of a 2008-style `crs` member (`urn:ogc:def:crs:EPSG::2263`, `EPSG:2263`),
/// where it names one other than longitude and latitude (`urn:ogc:def:crs:OGC:1.3:CRS84`,
/// EPSG:4326).
fn legacy_crs(v: &serde_json::Value) -> Option<u32> {
    let name = v.get("crs")?.get("properties")?.get("name")?.as_str()?;
    let code: u32 = name.rsplit(':').next()?.trim().parse().ok()?;
    (code != 4326).then_some(code)
}
