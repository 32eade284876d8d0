//! Growing a planted forest: every variant generated in parallel (each has its own seed, so
//! the order does not matter), turned into whatever the caller stores per tree (a mesh, a tree
//! stored for range) under a memory budget, and written as one GLB.

use super::{ForestError, ForestSpec, ForestSpecies, Planting, plant};
use crate::export::{Instance, Materials, to_glb_scene};
use crate::lod::LodTree;
use crate::mesh::{TreeMesh, mesh_tree};
use crate::{ExportError, Skeleton};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The most bytes the distinct trees of one forest may hold: a GLB cannot exceed 4 GiB, and a
/// forest drawn on the GPU should leave room for the rest of the machine.
pub const MAX_FOREST_BYTES: usize = 3_500_000_000;

/// A planted forest with its variants grown into `T`s (meshes, or trees stored for range).
pub struct Forest<T> {
    /// The species of the spec, loaded, in its order.
    pub species: Vec<ForestSpecies>,
    /// Where every copy stands.
    pub planting: Planting,
    /// One `T` per variant, in the planting's order.
    pub grown: Vec<T>,
    /// Wall-clock seconds spent growing.
    pub seconds: f64,
}

impl ForestSpec {
    /// Loads and checks every species the spec names (Weber-Penn or lobe species, built in or
    /// from files; see [`ForestSpecies::load`]).
    pub fn load_species(&self) -> Result<Vec<ForestSpecies>, ForestError> {
        self.species
            .iter()
            .map(|name| ForestSpecies::load(name))
            .collect()
    }
}

/// Plants `spec` and grows every variant of `species` (from [`ForestSpec::load_species`]) in
/// parallel, turning each skeleton into a `T` with `build`, which also says how many bytes it
/// holds; `on_tree` is called as each variant is done (a progress bar). Stops with
/// [`ForestError::Budget`] when the trees would hold more than [`MAX_FOREST_BYTES`].
pub fn grow<T: Send>(
    spec: &ForestSpec,
    species: Vec<ForestSpecies>,
    build: impl Fn(&ForestSpecies, &Skeleton) -> (T, usize) + Sync + Send,
    on_tree: &(dyn Fn() + Sync),
) -> Result<Forest<T>, ForestError> {
    spec.validate().map_err(ForestError::Spec)?;
    if species.len() != spec.species.len() {
        return Err(ForestError::Spec(format!(
            "species: {} named but {} loaded",
            spec.species.len(),
            species.len()
        )));
    }
    let planting = plant(spec);
    let t = Instant::now();
    let held = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let over_budget = || ForestError::Budget {
        variants: planting.variants.len(),
        grown: done.load(Ordering::Relaxed),
    };
    let grown = planting
        .variants
        .par_iter()
        // One skeleton buffer per worker, reused tree after tree: a fresh one per tree costs
        // more in page faults and regrowth than generating into a warm one.
        .map_init(Skeleton::default, |skeleton, v| {
            if held.load(Ordering::Relaxed) > MAX_FOREST_BYTES {
                return Err(over_budget());
            }
            let s = &species[v.species];
            s.grow_into(v.seed, spec.quality, skeleton)
                .map_err(|cause| ForestError::Grow {
                    name: s.name().to_string(),
                    seed: v.seed,
                    cause,
                })?;
            let (made, bytes) = build(s, skeleton);
            if held.fetch_add(bytes, Ordering::Relaxed) + bytes > MAX_FOREST_BYTES {
                return Err(over_budget());
            }
            done.fetch_add(1, Ordering::Relaxed);
            on_tree();
            Ok(made)
        })
        .collect::<Result<Vec<T>, ForestError>>()?;
    Ok(Forest {
        species,
        planting,
        grown,
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// Grows `spec` as meshes, the form a GLB stores: [`grow`] with every variant meshed at the
/// spec's quality.
pub fn grow_meshes(
    spec: &ForestSpec,
    species: Vec<ForestSpecies>,
    on_tree: &(dyn Fn() + Sync),
) -> Result<Forest<TreeMesh>, ForestError> {
    let quality = spec.quality;
    grow(
        spec,
        species,
        |s, skeleton| {
            let mesh = mesh_tree(skeleton, &s.mesh_options(quality));
            // Position, normal and texture coordinate per vertex, and the triangles, in a GLB.
            let bytes = mesh.vertex_count() * 32 + mesh.triangle_count() * 12;
            (mesh, bytes)
        },
        on_tree,
    )
}

/// Grows `spec` stored for range rendering (Weber & Penn section 5): [`grow`] with every
/// variant built into a [`LodTree`] at the spec's quality.
pub fn grow_lod(
    spec: &ForestSpec,
    species: Vec<ForestSpecies>,
    on_tree: &(dyn Fn() + Sync),
) -> Result<Forest<LodTree>, ForestError> {
    let quality = spec.quality;
    grow(
        spec,
        species,
        |s, skeleton| {
            let tree = LodTree::build(skeleton, &s.mesh_options(quality));
            let bytes = tree.heap_bytes();
            (tree, bytes)
        },
        on_tree,
    )
}

impl Forest<TreeMesh> {
    /// The forest as one GLB: each variant's mesh once, every tree a node referring to it.
    pub fn to_glb(&self) -> Result<Vec<u8>, ExportError> {
        let scene: Vec<(&str, &TreeMesh, Materials)> = self
            .planting
            .variants
            .iter()
            .zip(&self.grown)
            .map(|(v, m)| {
                let s = &self.species[v.species];
                let (bark, leaves) = s.colours();
                (s.name(), m, Materials::from_srgb(bark, leaves))
            })
            .collect();
        let instances: Vec<Instance> = self
            .planting
            .trees
            .iter()
            .map(|t| Instance {
                mesh: t.variant,
                position: t.position,
                turn: t.turn,
                scale: t.scale,
            })
            .collect();
        to_glb_scene(&scene, &instances)
    }

    /// Triangles stored (each variant once) and placed (every copy counted).
    pub fn triangles(&self) -> (usize, usize) {
        let stored = self.grown.iter().map(TreeMesh::triangle_count).sum();
        let placed = self
            .planting
            .trees
            .iter()
            .map(|t| self.grown[t.variant].triangle_count())
            .sum();
        (stored, placed)
    }

    /// What was grown (`sylva forest --json`).
    pub fn record(&self) -> ForestRecord {
        let (stored, placed) = self.triangles();
        let variants = self.planting.variants.len();
        ForestRecord {
            trees: self.planting.trees.len(),
            variants,
            triangles_stored: stored,
            triangles_placed: placed,
            grow_ms: (self.seconds * 1e3).round(),
            trees_per_second: (variants as f64 / self.seconds * 10.0).round() / 10.0,
            threads: rayon::current_num_threads(),
        }
    }
}

/// A forest grown, as output: trees placed and distinct, triangles stored and placed, and how
/// fast it grew on how many threads.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[allow(missing_docs)]
pub struct ForestRecord {
    pub trees: usize,
    pub variants: usize,
    pub triangles_stored: usize,
    pub triangles_placed: usize,
    pub grow_ms: f64,
    pub trees_per_second: f64,
    pub threads: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_forest_grows_and_writes_one_mesh_per_variant() {
        let spec = ForestSpec {
            species: vec!["quaking_aspen".into(), "hazel".into()],
            count: 10,
            area: [30.0, 30.0],
            seed: 3,
            variants: 1,
            quality: 0.2,
        };
        let ticks = AtomicUsize::new(0);
        let forest = grow_meshes(&spec, spec.load_species().unwrap(), &|| {
            ticks.fetch_add(1, Ordering::Relaxed);
        })
        .unwrap();
        assert_eq!(forest.grown.len(), 2);
        assert_eq!(ticks.load(Ordering::Relaxed), 2);
        let (stored, placed) = forest.triangles();
        assert!(stored > 0 && placed > stored, "{stored} {placed}");
        let glb = forest.to_glb().unwrap();
        let doc = gltf::Gltf::from_slice(&glb).unwrap();
        assert_eq!(doc.meshes().count(), 2);
        assert_eq!(doc.nodes().filter(|n| n.mesh().is_some()).count(), 10);
    }

    #[test]
    fn errors_name_the_species() {
        let spec = ForestSpec {
            species: vec!["no such tree".into()],
            count: 1,
            area: [10.0, 10.0],
            seed: 0,
            variants: 1,
            quality: 0.5,
        };
        let e = spec.load_species().unwrap_err().to_string();
        assert!(e.contains("no such tree"), "{e}");
    }
}
