//! What can go wrong in the street's rooms: every room reads this, none is read by it.

/// What can go wrong reading a site, prices or costs, or assessing a species.
#[derive(Debug, thiserror::Error)]
pub enum StreetError {
    /// A file that cannot be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// A file that does not parse, or has a key missing or unknown.
    #[error("{file}: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// What is wrong (the parser names the key).
        message: String,
    },
    /// A value outside what the key allows.
    #[error("{file}: `{key}` is {value}, expected {allowed}")]
    Value {
        /// The file.
        file: String,
        /// The key, with its table (`wire.height`).
        key: String,
        /// The value given.
        value: f64,
        /// What is allowed.
        allowed: String,
    },
    /// A species whose benefits were asked for but a model lacks an input.
    #[error("{0}")]
    Missing(String),
    /// Growth data that cannot be found or read.
    #[error(transparent)]
    Growth(#[from] crate::growth::GrowthError),
}
