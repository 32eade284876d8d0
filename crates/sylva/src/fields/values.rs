//! Numbers read from a rules file's TOML, shared by its `[rules]` and `[layout]` tables: an
//! integer or a float, finite and within the range a key allows.

use crate::error::ParamsError;

/// `v` as a number, if it is one (TOML writes `2` and `2.0` as different types).
pub(super) fn as_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(f) => Some(*f),
        _ => None,
    }
}

/// `v` if it is finite and within `lo..=hi`; else an error naming `key`, what is `allowed`, and
/// where (`place`: the file and line).
pub(super) fn within(
    key: &str,
    v: f64,
    (lo, hi): (f64, f64),
    allowed: &str,
    place: String,
) -> Result<f64, ParamsError> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(ParamsError::OutOfRange {
            name: key.into(),
            value: v,
            allowed: allowed.into(),
            source_name: Some(place),
        })
    }
}
