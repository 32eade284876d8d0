//! `sylva view`: the editor on a species, or a window flying through a forest file, or one
//! looking at a GLB or a lobe species grown at its natural size. The windows live in
//! `sylva-viewer`.

use crate::args::ViewArgs;
use crate::shared::{grow_for_range, load_params};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use sylva::Skeleton;
use sylva::export::{Materials, to_glb};
use sylva::forest::{ForestSpec, ForestSpecies, LOBES_PREFIX, is_forest_file};
use sylva::mesh::mesh_tree;
use sylva_render::glb_scene::glb_scene_from_bytes;

pub fn run(args: &ViewArgs) -> Result<()> {
    let path = Path::new(&args.species);
    let self_test = args.self_test.clone();
    if is_forest_file(path) {
        let spec = ForestSpec::from_file(path)?;
        let forest = grow_for_range(&spec).with_context(|| path.display().to_string())?;
        return sylva_viewer::fly_through(forest, &path.display().to_string(), self_test);
    }
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"))
    {
        return sylva_viewer::look_at(path, self_test);
    }
    // A lobe species (by a name only Fields' species carry, or `lobes:NAME`) has no
    // parameters for the editor's sliders: grow it and look at it.
    match ForestSpecies::load(&args.species) {
        Ok(species @ ForestSpecies::Lobes(_)) => {
            return look_at_grown(&species, &args.species, self_test);
        }
        Err(e) if args.species.starts_with(LOBES_PREFIX) => return Err(e.into()),
        _ => {}
    }
    let params = load_params(&args.species, &[])?;
    sylva_viewer::edit(params, args.species.clone(), self_test)
}

/// Grows `species` (seed 0, full detail) and opens the model window on it.
fn look_at_grown(species: &ForestSpecies, name: &str, self_test: Option<PathBuf>) -> Result<()> {
    let mut skeleton = Skeleton::default();
    species
        .grow_into(0, 1.0, &mut skeleton)
        .with_context(|| format!("growing {name}"))?;
    let mesh = mesh_tree(&skeleton, &species.mesh_options(1.0));
    let (bark, leaves) = species.colours();
    let glb = to_glb(&mesh, species.name(), &Materials::from_srgb(bark, leaves))?;
    let scene = glb_scene_from_bytes(glb, name)?;
    sylva_viewer::look_at_scene(scene, name, self_test)
}
