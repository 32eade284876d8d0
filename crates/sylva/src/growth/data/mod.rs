//! What the sources say of each species: the Urban Tree Database's regions, species and
//! equations, palms' ages, each form's architecture and what each species wears.

pub mod database;
pub mod equations;
pub mod foliage;
pub mod habit;
pub mod measured;
pub(crate) mod palm_ages;

#[cfg(test)]
mod tests;
