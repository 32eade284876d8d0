//! What a forest plants: a Weber-Penn species or a Fields lobe species, each grown into the
//! same Skeleton, so meshes, range storage, GLBs and the renderer need not know which.

use super::ForestError;
use crate::fields::{self, TreeRules};
use crate::mesh::MeshOptions;
use crate::{GenerateError, GenerateOptions, Skeleton, TreeParams};

/// The prefix that asks for a lobe species where a Weber-Penn species has the same name
/// (`lobes:balsam_fir`).
pub const LOBES_PREFIX: &str = "lobes:";

/// A species a forest can plant.
// A forest holds a handful of species: the parametric variant's size costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum ForestSpecies {
    /// Weber & Penn's parametric model.
    Parametric(TreeParams),
    /// Fields' lobe-driven trees, each variant placed automatically at its natural size.
    Lobes(TreeRules),
}

impl ForestSpecies {
    /// A species by name: a Weber-Penn species (built-in or a species file) first; a name
    /// only Fields' built-ins or a rules file carry, or any name after `lobes:`, is a lobe
    /// species.
    pub fn load(name: &str) -> Result<Self, ForestError> {
        if let Some(lobe) = name.strip_prefix(LOBES_PREFIX) {
            return lobe_species(lobe, name);
        }
        match crate::species::load(name) {
            Ok(params) => {
                params.validate().map_err(|cause| ForestError::Species {
                    name: name.to_string(),
                    cause,
                })?;
                Ok(Self::Parametric(params))
            }
            Err(e) => match fields::builtin(name) {
                Some(rules) => Ok(Self::Lobes(rules)),
                None => Err(ForestError::Load(e)),
            },
        }
    }

    /// The species' name.
    pub fn name(&self) -> &str {
        match self {
            Self::Parametric(p) => &p.name,
            Self::Lobes(r) => &r.name,
        }
    }

    /// Bark and leaf colours, sRGB 0..1.
    pub fn colours(&self) -> ([f32; 3], [f32; 3]) {
        match self {
            Self::Parametric(p) => (p.bark_color, p.leaf_color),
            Self::Lobes(r) => (fields::BARK_COLOR, r.leaf_texture.color),
        }
    }

    /// Warnings the species file raised (a Weber-Penn file read with defaults).
    pub fn notes(&self) -> &[String] {
        match self {
            Self::Parametric(p) => &p.notes,
            Self::Lobes(_) => &[],
        }
    }

    /// Grows the variant with `seed` into `skeleton` at `quality` (a lobe species' leaves do
    /// not thin with quality; its cylinders do, see [`ForestSpecies::mesh_options`]).
    pub fn grow_into(
        &self,
        seed: u64,
        quality: f64,
        skeleton: &mut Skeleton,
    ) -> Result<(), GenerateError> {
        match self {
            Self::Parametric(params) => {
                let options = GenerateOptions {
                    seed,
                    quality,
                    ..Default::default()
                };
                crate::generate_into(params, &options, skeleton)
            }
            Self::Lobes(rules) => {
                let placement = fields::auto_placement(rules, seed);
                *skeleton = fields::grow(rules, seed, &placement)?.skeleton();
                Ok(())
            }
        }
    }

    /// How the species' stems are meshed at `quality`: a Weber-Penn species by its Smooth, a
    /// lobe species with its Tessellation rule scaled by the quality (at least 3 sides).
    pub fn mesh_options(&self, quality: f64) -> MeshOptions {
        match self {
            Self::Parametric(params) => MeshOptions::for_species(params, quality),
            Self::Lobes(rules) => MeshOptions {
                sides: Some(((rules.tessellation as f64 * quality).round() as u32).max(3)),
                ..Default::default()
            },
        }
    }
}

fn lobe_species(lobe: &str, asked: &str) -> Result<ForestSpecies, ForestError> {
    if let Some(rules) = fields::builtin(lobe) {
        return Ok(ForestSpecies::Lobes(rules));
    }
    let unknown = || {
        let known: Vec<&str> = fields::rules::builtin_names().collect();
        ForestError::Spec(format!(
            "species {asked}: no lobe species `{lobe}` and no such rules file; built in: {}",
            known.join(", ")
        ))
    };
    let path = std::path::Path::new(lobe);
    if !path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
    {
        return Err(unknown());
    }
    let text = std::fs::read_to_string(path).map_err(|e| ForestError::File {
        path: lobe.to_string(),
        message: format!("cannot read: {e}"),
    })?;
    let rules = fields::from_toml(&text, lobe)?;
    Ok(ForestSpecies::Lobes(rules))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_resolve_to_either_model() {
        let wp = ForestSpecies::load("balsam_fir").unwrap();
        assert!(matches!(wp, ForestSpecies::Parametric(_)));
        let fir = ForestSpecies::load("lobes:balsam_fir").unwrap();
        assert!(matches!(fir, ForestSpecies::Lobes(_)));
        assert_eq!(fir.name(), "Balsam Fir");
        // Names only Fields' species carry need no prefix.
        let cherry = ForestSpecies::load("weeping_cherry").unwrap();
        assert!(matches!(cherry, ForestSpecies::Lobes(_)));
        let e = ForestSpecies::load("lobes:baobab").unwrap_err().to_string();
        assert!(e.contains("lobes:baobab") && e.contains("black_oak"), "{e}");
        let e = ForestSpecies::load("baobab").unwrap_err().to_string();
        assert!(e.contains("baobab"), "{e}");
        // A lobe species grows at its natural size, seed by seed.
        let mut a = Skeleton::default();
        let mut b = Skeleton::default();
        fir.grow_into(1, 0.5, &mut a).unwrap();
        fir.grow_into(2, 0.5, &mut b).unwrap();
        assert!((10.0..20.0).contains(&a.stats().height));
        assert_ne!(a, b);
        assert_eq!(fir.mesh_options(0.5).sides, Some(18));
    }
}
