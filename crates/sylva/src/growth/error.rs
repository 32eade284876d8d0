//! What can go wrong finding or reading growth data, or growing a tree: every room reads
//! this, none is read by it.

/// What can go wrong finding or reading growth data.
#[derive(Debug, thiserror::Error)]
pub enum GrowthError {
    /// A region code the database does not have.
    #[error("no region `{region}` in the Urban Tree Database; regions: {known}")]
    UnknownRegion {
        /// As given.
        region: String,
        /// The regions there are.
        known: String,
    },
    /// No species of that code or name in the region.
    #[error("no species `{query}` in region {region}; try one of: {candidates}")]
    UnknownSpecies {
        /// As given.
        query: String,
        /// Region searched.
        region: String,
        /// Close or all names.
        candidates: String,
    },
    /// The species lacks one of the five equations growth needs.
    #[error(
        "{code} in {region} has no {which} equation, so it cannot be grown (a palm's age -> DBH is fitted to the database's measured palms of its region; this region measured none)"
    )]
    MissingEquation {
        /// Species code.
        code: String,
        /// Region code.
        region: String,
        /// The missing relation.
        which: String,
    },
    /// A table that does not parse.
    #[error("{file}, line {line}: {message}")]
    Syntax {
        /// File.
        file: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A tree that stopped growing before the size asked of it.
    #[error("the {label} stopped at {segments} segments by age {age:.0}")]
    Stalled {
        /// The species.
        label: String,
        /// Segments it reached.
        segments: usize,
        /// The oldest age grown, years.
        age: f64,
    },
    /// A file that cannot be read.
    #[error("{path}: {message}")]
    Io {
        /// File.
        path: String,
        /// The system's message.
        message: String,
    },
}
