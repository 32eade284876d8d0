//! Nagel's (1986) trees for landscape CAD: Honda's fractal branching, whisk trees (a canopy
//! profile rotated about the trunk) and stick trees (a set of drawn branches rotated the same
//! way). All three give a [`Skeleton`](crate::Skeleton), so every exporter and the renderer take
//! them; the fractal tree can also stream its segments to a drawing without being stored.

pub mod fractal;
pub mod profile;
pub mod whisk;

pub use fractal::{Fractal, FractalParams, FractalSegment, honda_daughter};
pub use profile::{Profile, read_profile, read_sticks};
pub use whisk::{WhiskParams, stick_tree, whisk_tree};

#[cfg(test)]
mod tests;
