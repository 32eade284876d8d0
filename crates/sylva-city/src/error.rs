//! What can go wrong in a city's run, each message naming the file, the column or flag, and
//! what is allowed.

use std::path::PathBuf;

/// A city run that cannot go on. Rows that cannot be read are not errors: they are counted and
/// reported in the run's summary, and the run goes on without them.
#[derive(Debug, thiserror::Error)]
pub enum CityError {
    /// The inventory cannot be opened or read at all.
    #[error("{}: {message}", .path.display())]
    Inventory {
        /// The inventory file.
        path: PathBuf,
        /// What is wrong, and what is allowed.
        message: String,
    },
    /// A flag or setting that cannot be used.
    #[error("{name}: {message}")]
    Setting {
        /// The flag (`--crs`) or setting.
        name: String,
        /// What is wrong, and what is allowed.
        message: String,
    },
    /// Writing the tiles failed.
    #[error("{}: {message}", .path.display())]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// Growing or meshing a tree failed.
    #[error("{0}")]
    Growth(String),
}

impl CityError {
    /// A setting error.
    pub fn setting(name: &str, message: impl Into<String>) -> Self {
        CityError::Setting {
            name: name.into(),
            message: message.into(),
        }
    }

    /// A write error: the file or folder and what went wrong.
    pub fn write(path: &std::path::Path, e: impl std::fmt::Display) -> Self {
        CityError::Write {
            path: path.into(),
            message: e.to_string(),
        }
    }

    /// An inventory error.
    pub fn inventory(path: &std::path::Path, message: impl Into<String>) -> Self {
        CityError::Inventory {
            path: path.into(),
            message: message.into(),
        }
    }
}
