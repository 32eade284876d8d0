//! Growing street trees from measured data (Linsen et al. 2005; Rudnick, Linsen & McPherson
//! 2007): the USDA Urban Tree Database's equations as functions of age, an annual-segment
//! growth model steered by them and by light inside the crown, and measurement of the result
//! the way the data were measured. Three rooms, each reading only those before it:
//!
//! - [`data`]: what the sources say of each species. The Urban Tree Database's regions,
//!   species and equations (`database`, `equations`, `measured`), palms' ages fitted to its
//!   measured palms (`palm_ages`), each form's architecture (`habit`) and what each species
//!   wears (`foliage`, with `foliage.csv`).
//! - [`model`]: the growing tree (`Grower`): buds, light inside the crown (`light`),
//!   colonisation, allocation, shedding, cuts and regrowth, and its Skeleton.
//! - [`survey`]: the grown tree measured as the survey measured trees (`measure`, `form`,
//!   `twigs`), a run's records and CSV (`report`), and every species swept against its data
//!   (`sweep`).
//!
//! [`season`] dresses a grown tree for a month: leaf colour, bare crowns, flowers.

pub mod data;
pub mod model;
pub mod season;
pub mod survey;

pub use data::database::{DBH_CLASS_EDGES_CM, Database, Quantity, Region, SpeciesEntry};
pub use data::equations::{Equation, Form};
pub use data::habit::{Envelope, Habit, TreeForm, habit_of};
pub use data::measured::Measured;
pub use model::{CutKind, CutMark, Cuts, Grower, GrowthOptions, Targets};
pub use season::{Dress, LeafState, Month, dressed_mesh};
pub use survey::form::{FormMeasures, measure_form};
pub use survey::measure::{Dimensions, measure};

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

#[cfg(test)]
mod tests;
