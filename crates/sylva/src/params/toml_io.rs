//! Sylva's species files: TOML with a `[species]` table (name, description) and a `[params]`
//! table keyed by the paper's parameter names. Missing parameters take Arbaro's defaults.
//!
//! ```toml
//! [species]
//! name = "Quaking Aspen"
//! description = "Weber & Penn 1995, appendix"
//!
//! [params]
//! Shape = 7
//! 0Length = 1.0
//! 1DownAngle = 60
//! ```

use super::{LEVEL_SETS, PARAMS, TreeParams};
use crate::error::ParamsError;
use std::fmt::Write;

/// Line number (1-based) of the first line that defines `key`, for error messages.
fn line_of(text: &str, key: &str) -> Option<usize> {
    text.lines()
        .position(|line| {
            let t = line.trim_start();
            let t = t
                .strip_prefix('"')
                .and_then(|r| r.strip_prefix(key))
                .and_then(|r| r.strip_prefix('"'))
                .or_else(|| t.strip_prefix(key));
            t.is_some_and(|rest| rest.trim_start().starts_with('='))
        })
        .map(|i| i + 1)
}

fn place(source_name: &str, text: &str, key: &str) -> String {
    match line_of(text, key) {
        Some(line) => format!("{source_name}, line {line}"),
        None => source_name.to_string(),
    }
}

/// Reads a species TOML file's text. `source_name` (usually the file name) goes into errors.
/// The result is validated.
pub fn from_toml(text: &str, source_name: &str) -> Result<TreeParams, ParamsError> {
    let table: toml::Table = toml::from_str(text).map_err(|e| ParamsError::Syntax {
        source_name: source_name.to_string(),
        message: format!("not valid TOML: {}", e.to_string().trim_end()),
    })?;
    let mut params = TreeParams {
        name: source_name.to_string(),
        ..TreeParams::default()
    };
    for (key, value) in &table {
        match (key.as_str(), value) {
            ("species", toml::Value::Table(meta)) => {
                for (k, v) in meta {
                    match (k.as_str(), v) {
                        ("name", toml::Value::String(s)) => params.name = s.clone(),
                        ("description", toml::Value::String(s)) => params.description = s.clone(),
                        ("bark_color" | "leaf_color", toml::Value::String(s)) => {
                            let colour =
                                super::parse_color(s).ok_or_else(|| ParamsError::Syntax {
                                    source_name: place(source_name, text, k),
                                    message: format!(
                                        "`{k}` is \"{s}\", expected a colour \"#RRGGBB\""
                                    ),
                                })?;
                            if k == "bark_color" {
                                params.bark_color = colour;
                            } else {
                                params.leaf_color = colour;
                            }
                        }
                        _ => {
                            return Err(ParamsError::Syntax {
                                source_name: place(source_name, text, k),
                                message: format!(
                                    "unexpected `{k}` in [species]: expected `name`, `description`, `bark_color` or `leaf_color`, as text"
                                ),
                            });
                        }
                    }
                }
            }
            ("params", toml::Value::Table(values)) => {
                for (k, v) in values {
                    let value = match v {
                        toml::Value::Integer(i) => *i as f64,
                        toml::Value::Float(f) => *f,
                        _ => {
                            return Err(ParamsError::Syntax {
                                source_name: place(source_name, text, k),
                                message: format!("parameter `{k}` must be a number, found {v}"),
                            });
                        }
                    };
                    params
                        .set(k, value)
                        .map_err(|e| e.at(place(source_name, text, k)))?;
                }
            }
            _ => {
                return Err(ParamsError::Syntax {
                    source_name: place(source_name, text, key),
                    message: format!(
                        "unexpected top-level `{key}`: a species file has a [species] table and a [params] table"
                    ),
                });
            }
        }
    }
    params.validate().map_err(|e| e.at(source_name))?;
    Ok(params)
}

/// Writes parameters as a species TOML file, every parameter with its meaning as a comment.
pub fn to_toml(params: &TreeParams) -> String {
    let mut out = String::new();
    let quote = |s: &str| toml::Value::String(s.to_string()).to_string();
    let _ = writeln!(out, "[species]\nname = {}", quote(&params.name));
    if !params.description.is_empty() {
        let _ = writeln!(out, "description = {}", quote(&params.description));
    }
    let _ = writeln!(
        out,
        "bark_color = {}",
        quote(&super::format_color(params.bark_color))
    );
    let _ = writeln!(
        out,
        "leaf_color = {}",
        quote(&super::format_color(params.leaf_color))
    );
    out.push_str("\n[params]\n");
    let mut write_def = |def: &super::ParamDef, level: usize| {
        let value = (def.get)(params, level);
        let _ = writeln!(
            out,
            "{:<16} = {:<10} # {} [{}]",
            def.name_at(level),
            format_value(value),
            def.doc,
            def.unit
        );
    };
    for def in PARAMS.iter().filter(|d| !d.per_level) {
        write_def(def, 0);
    }
    for level in 0..LEVEL_SETS {
        for def in PARAMS
            .iter()
            .filter(|d| d.per_level && d.levels().contains(&level))
        {
            write_def(def, level);
        }
    }
    out
}

/// Shortest text that reads back as the same number.
pub fn format_value(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_keeps_every_value() {
        let mut p = TreeParams {
            name: "Round \"trip\"".into(),
            description: "a test".into(),
            ..TreeParams::default()
        };
        p.set("2CurveV", -12.5).unwrap();
        p.bark_color = [1.0, 0.2, 0.0];
        p.set("Leaves", -7.0).unwrap();
        let text = to_toml(&p);
        let back = from_toml(&text, "rt.toml").unwrap();
        assert_eq!(back, p);
    }

    #[test]
    fn errors_name_the_file_line_and_parameter() {
        let text = "[species]\nname = \"x\"\n\n[params]\nShape = 7\n1DownAngle = 240\n";
        let err = from_toml(text, "oak.toml").unwrap_err().to_string();
        assert!(
            err.contains("1DownAngle") && err.contains("240") && err.contains("oak.toml, line 6"),
            "{err}"
        );
        assert!(err.contains("-180..180"), "{err}");

        let err = from_toml("[params]\nBogus = 1\n", "b.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("Bogus") && err.contains("line 2"), "{err}");

        let err = from_toml("[params\nShape = 1", "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("bad.toml") && err.contains("TOML"), "{err}");

        let err = from_toml("[params]\nShape = \"round\"\n", "s.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("must be a number"), "{err}");
    }
}
