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
mod error;
pub mod model;
pub mod season;
pub mod survey;

pub use data::database::{DBH_CLASS_EDGES_CM, Database, Quantity, Region, SpeciesEntry};
pub use data::equations::{Equation, Form};
pub use data::habit::{Envelope, Habit, TreeForm, habit_of};
pub use data::measured::Measured;
pub use error::GrowthError;
pub use model::{
    CutKind, CutMark, Cuts, Grower, GrowthOptions, LONGEST_REGROWTH, STEPS_PER_YEAR, Targets,
};
pub use season::{Dress, LeafState, Month, dressed_mesh};
pub use survey::form::{FormMeasures, measure_form};
pub use survey::measure::{Dimensions, measure};

#[cfg(test)]
mod tests;
