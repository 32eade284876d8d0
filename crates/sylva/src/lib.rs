//! Sylva: realistic trees from parameters.
//!
//! The pipeline has one intermediate form, the [`Skeleton`]:
//!
//! ```text
//! species file (TOML, Arbaro XML) -> TreeParams -> weber_penn::generate -> Skeleton
//!                                                                            |
//!                              mesh::mesh_tree -> TreeMesh -> export::{to_glb, write_obj}
//! ```
//!
//! Every model family ends in the same Skeleton: [`weber_penn`], [`growth`] (street trees over
//! the years), [`nagel`] (fractal, whisk and stick trees) and [`fields`] (lobe-driven trees), so
//! meshes, exports, [`drawing`]s (vector files, SVG and PNG views) and the renderer take them all.
//!
//! Whole pipelines are plain functions over plain data, each a few lines to call:
//!
//! - [`forest::grow_meshes`] (or [`forest::grow_lod`] for range rendering) plants a
//!   [`forest::ForestSpec`] and grows its variants in parallel; [`forest::Forest::to_glb`]
//!   writes it with every tree a node sharing its variant's mesh.
//! - [`growth::survey::report::Cohort`] grows street trees side by side through a run of ages and
//!   records each against the Urban Tree Database's equations ([`growth::survey::report::csv`], the
//!   chart data in [`growth::survey::report::CHARTED`]).
//! - [`lod::LodTree`] stores a tree for range rendering (Weber & Penn section 5);
//!   [`lod::LodTree::engine_chain`] makes an engine's LOD meshes.
//! - [`drawing::write_outputs`] writes any line-drawable tree to every file asked for, by
//!   extension (Nagel's vector files, SVG, PNG, GLB, OBJ).
//! - [`bench`](mod@bench) runs the measurements `sylva bench` prints.
//!
//! Pictures are drawn by the `sylva-render` crate, windows by `sylva-viewer`; this crate has no
//! GPU or window code. Runnable programs are in `crates/sylva/examples` (`generate`,
//! `grow_street_tree`, `plant_forest`).
//!
//! Conventions: metres; Z up in the model with the trunk base at the origin (exporters convert
//! to Y up); degrees in parameter files, radians inside. The same parameters and seed always give
//! the same bytes.
//!
//! A tree from a species, as a GLB:
//!
//! ```
//! let params = sylva::species::builtin("quaking_aspen").unwrap();
//! let options = sylva::GenerateOptions { seed: 7, ..Default::default() };
//! let skeleton = sylva::generate(&params, &options).unwrap();
//! let mesh = sylva::mesh::mesh_tree(&skeleton, &Default::default());
//! assert!(mesh.triangle_count() > 10_000);
//! let glb = sylva::export::to_glb(&mesh, &params.name, &Default::default()).unwrap();
//! assert_eq!(&glb[..4], b"glTF");
//! ```
#![deny(missing_docs)]

pub mod bench;
pub mod colour;
pub mod drawing;
pub mod error;
pub mod export;
pub mod fields;
pub mod forest;
pub mod growth;
pub mod lod;
pub mod mesh;
pub mod nagel;
pub mod params;
pub mod preview;
pub mod record;
pub mod rng;
pub mod skeleton;
pub mod species;
pub mod street;
pub mod weber_penn;
pub mod whole;

pub use error::{ExportError, GenerateError, ParamsError};
pub use params::TreeParams;
pub use skeleton::{CrossSection, Leaf, LeafShape, Skeleton, SkeletonStats, Stem, StemId};
pub use weber_penn::{GenerateOptions, Wind, generate, generate_into};
