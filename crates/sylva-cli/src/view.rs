//! `sylva view`: the editor on a species, or a window flying through a forest file, or one
//! looking at a GLB. The windows live in `sylva-viewer`.

use crate::args::ViewArgs;
use crate::shared::{grow_for_range, load_params};
use anyhow::{Context, Result};
use std::path::Path;
use sylva::forest::{ForestSpec, is_forest_file};

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
    let params = load_params(&args.species, &[])?;
    sylva_viewer::edit(params, args.species.clone(), self_test)
}
