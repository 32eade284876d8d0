//! The grown tree measured as the survey measured street trees: its dimensions and form, its
//! branching, a run's records and CSV, and every species swept against its data.

pub mod form;
pub mod measure;
pub mod report;
pub mod sweep;
pub mod twigs;
