//! Fields' (2012) lobe-driven trees: a species is 25 rules (`TreeRules`), a tree is a trunk
//! hierarchy and leaf lobes (placed automatically, by the user, from a `.tree` file, or fitted
//! to a point cloud), grown into branches that reach control points on the lobes' surfaces and
//! leaves that fill them.

mod grow;
mod layout;
mod leaves;
pub mod lobe;
pub mod pipeline;
pub mod points;
pub mod rules;
pub mod source;
pub mod tree_file;
mod values;
mod widths;

pub use grow::grow;
pub use lobe::Lobe;
pub use pipeline::{LobeTree, Placement, TrunkPiece, auto_placement, placement_for_lobes};
pub use rules::{TreeRules, builtin, from_toml};
pub use tree_file::TreeFile;

/// Bark colour of every lobe species (sRGB 0..1): the paper's rules give none.
pub const BARK_COLOR: [f32; 3] = [0.36, 0.28, 0.22];

#[cfg(test)]
mod file_tests;
#[cfg(test)]
mod form_tests;
#[cfg(test)]
mod tests;
