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
    #[error("parameter `{name}` is {value}, expected {allowed}{}", location(.source_name))]
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
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The mesh cannot be represented in the format.
    #[error("cannot export: {0}")]
    Format(String),
}
