//! A Weber & Penn tree made whole: generated, meshed for its species, held to a triangle
//! budget, with what was made as one output record. `sylva generate` and the Python wheel's
//! `generate` make their trees here.

use crate::mesh::{MeshOptions, TreeMesh, mesh_tree};
use crate::{GenerateError, GenerateOptions, Skeleton, TreeParams, generate};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// A tree generated and meshed.
pub struct Made {
    /// The tree.
    pub skeleton: Skeleton,
    /// Its mesh.
    pub mesh: TreeMesh,
    /// How it was meshed (an LOD chain meshes the same way).
    pub mesh_options: MeshOptions,
    /// Milliseconds generating and meshing took.
    pub generate_ms: f64,
    #[allow(missing_docs)]
    pub mesh_ms: f64,
}

/// A mesh over the triangle budget `options.max_triangles`.
#[derive(Debug, thiserror::Error)]
#[error("the mesh has {triangles} triangles, over the budget of {budget}")]
pub struct OverBudget {
    /// Triangles the mesh has.
    pub triangles: usize,
    /// The budget.
    pub budget: u64,
}

/// What can stop a tree being made.
#[derive(Debug, thiserror::Error)]
pub enum MakeError {
    /// The generator refused or hit its budget.
    #[error(transparent)]
    Generate(#[from] GenerateError),
    /// The mesh exceeds the triangle budget.
    #[error(transparent)]
    OverBudget(#[from] OverBudget),
}

/// Generates `params` as `options` say and meshes it at `quality`, within
/// `options.max_triangles`.
pub fn make(
    params: &TreeParams,
    options: &GenerateOptions,
    quality: f64,
) -> Result<Made, MakeError> {
    let t0 = Instant::now();
    let skeleton = generate(params, options)?;
    let generate_ms = t0.elapsed().as_secs_f64() * 1e3;
    let t1 = Instant::now();
    let mesh_options = MeshOptions::for_species(params, quality);
    let mesh = mesh_tree(&skeleton, &mesh_options);
    let mesh_ms = t1.elapsed().as_secs_f64() * 1e3;
    if mesh.triangle_count() as u64 > options.max_triangles {
        return Err(OverBudget {
            triangles: mesh.triangle_count(),
            budget: options.max_triangles,
        }
        .into());
    }
    Ok(Made {
        skeleton,
        mesh,
        mesh_options,
        generate_ms,
        mesh_ms,
    })
}

fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// What was made (`sylva generate --json`, the wheel's `Model.summary`): the tree's stems,
/// leaves and size, its mesh, and the time each took.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[allow(missing_docs)]
pub struct TreeRecord {
    pub species: String,
    pub seed: u64,
    pub stems_per_level: Vec<usize>,
    pub leaves: usize,
    pub vertices: usize,
    pub triangles: usize,
    /// Metres, to the millimetre.
    pub height_m: f64,
    pub crown_width_m: f64,
    /// Milliseconds, to the microsecond.
    pub generate_ms: f64,
    pub mesh_ms: f64,
}

impl Made {
    /// The record of this tree of `params` from `seed`.
    pub fn record(&self, params: &TreeParams, seed: u64) -> TreeRecord {
        let stats = self.skeleton.stats();
        TreeRecord {
            species: params.name.clone(),
            seed,
            stems_per_level: stats.stems_per_level,
            leaves: stats.leaves,
            vertices: self.mesh.vertex_count(),
            triangles: self.mesh.triangle_count(),
            height_m: round3(f64::from(stats.height)),
            crown_width_m: round3(f64::from(stats.crown_width)),
            generate_ms: round3(f64::from(self.generate_ms as f32)),
            mesh_ms: round3(f64::from(self.mesh_ms as f32)),
        }
    }
}
