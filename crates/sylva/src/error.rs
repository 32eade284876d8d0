//! Error types, one per stage. Each message names the parameter or file, the offending value and
//! what is allowed, so that a user can fix the input without reading the code.

use std::path::PathBuf;

/// Where a parameter came from: a file name and, when known, a line.
fn location(source_name: &Option<String>) -> String {
    match source_name {
        Some(s) => format!(" ({s})"),
        None => String::new(),
    }
}

/// A value as a message shows it: exponent form when it is huge or tiny, so `1e308` reads as
/// written rather than as 309 digits.
fn number(v: &f64) -> String {
    if v.is_finite() && *v != 0.0 && !(1e-4..1e9).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A species file or parameter set that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ParamsError {
    /// A parameter name the model does not know.
    #[error("unknown parameter `{name}`{}; `sylva species show NAME` lists the parameters", location(.source_name))]
    Unknown {
        /// The name as written.
        name: String,
        /// File and line, when read from a file.
        source_name: Option<String>,
    },
    /// A value outside the documented range (or a fraction for a whole-number parameter).
    #[error("parameter `{name}` is {}, expected {allowed}{}", number(.value), location(.source_name))]
    OutOfRange {
        /// Full parameter name (`1DownAngle`).
        name: String,
        /// The value given.
        value: f64,
        /// The allowed range, as text.
        allowed: String,
        /// File and line, when read from a file.
        source_name: Option<String>,
    },
    /// Values each in range but impossible together.
    #[error("{0}")]
    Combination(String),
    /// A file that does not parse.
    #[error("{source_name}: {message}")]
    Syntax {
        /// File (and line, when the parser knows it).
        source_name: String,
        /// What is wrong.
        message: String,
    },
    /// A built-in species name that does not exist.
    #[error(
        "no built-in species `{0}` and no such file; `sylva species list` shows the built-in ones"
    )]
    NoSuchSpecies(String),
}

impl ParamsError {
    /// A value outside `allowed`, for parameters given directly (no file).
    pub fn out_of_range(name: &str, value: f64, allowed: &str) -> Self {
        ParamsError::OutOfRange {
            name: name.into(),
            value,
            allowed: allowed.into(),
            source_name: None,
        }
    }

    /// Adds a file/line location to errors that carry one.
    pub fn at(mut self, place: impl Into<String>) -> Self {
        match &mut self {
            ParamsError::Unknown { source_name, .. }
            | ParamsError::OutOfRange { source_name, .. } => {
                *source_name = Some(place.into());
            }
            ParamsError::Combination(msg) => *msg = format!("{msg} ({})", place.into()),
            _ => {}
        }
        self
    }
}

/// Generation stopped before producing a tree.
#[derive(Debug, thiserror::Error)]
pub enum GenerateError {
    /// The parameters failed validation.
    #[error(transparent)]
    Params(#[from] ParamsError),
    /// The tree would exceed a budget; the message says which and how to raise it.
    #[error(
        "the tree would exceed the budget of {limit} {what} (reached {reached} while generating level {level}); \
         lower the counts (nBranches, Leaves, Levels, nCurveRes) or raise the budget (--max-triangles)"
    )]
    Budget {
        /// What is counted ("triangles").
        what: &'static str,
        /// The limit in force.
        limit: u64,
        /// The count when generation stopped.
        reached: u64,
        /// The stem level being generated.
        level: usize,
    },
}

/// Writing a model file failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The file could not be written.
    #[error("cannot write {}: {cause}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause, told in the message (not chained, or it would be told twice).
        cause: std::io::Error,
    },
    /// The mesh cannot be represented in the format.
    #[error("cannot export: {0}")]
    Format(String),
    /// An output named so that nothing can be written to it (an unknown extension, a folder,
    /// a file named twice, a mesh asked of lines); the message names it and what is allowed.
    #[error("{0}")]
    Output(String),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_and_tiny_values_read_as_written() {
        let e = |v: f64| ParamsError::out_of_range("Scale", v, "0.001..500").to_string();
        assert_eq!(e(1e308), "parameter `Scale` is 1e308, expected 0.001..500");
        assert_eq!(
            e(-2.5e-7),
            "parameter `Scale` is -2.5e-7, expected 0.001..500"
        );
        assert_eq!(e(600.0), "parameter `Scale` is 600, expected 0.001..500");
        assert_eq!(e(f64::NAN), "parameter `Scale` is NaN, expected 0.001..500");
        assert_eq!(
            e(f64::NEG_INFINITY),
            "parameter `Scale` is -inf, expected 0.001..500"
        );
    }
}
