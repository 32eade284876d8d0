//! `sylva draw`: line drawings of a Weber-Penn species, a street tree grown to an age, or a
//! vector file: Nagel's P/L files, SVG and PNG views, and meshes of the same skeleton.

use crate::args::DrawArgs;
use crate::shared::{draw_options, load_params, print_written, write_skeleton};
use anyhow::{Context, Result, bail};
use std::path::Path;
use sylva::drawing::{MeshLook, Meshable, plan, wants_mesh, write_outputs};
use sylva::export::Materials;
use sylva::growth::survey::report::{MAX_AGE, MESH};
use sylva::growth::{Database, Grower, GrowthOptions};
use sylva::mesh::MeshOptions;

pub fn run(args: &DrawArgs) -> Result<()> {
    let planned = plan(&args.out.outputs)?;
    let is_vec = Path::new(&args.input)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("vec"));
    if is_vec && args.age.is_some() {
        bail!(
            "{}: --age grows a street tree; a vector file is drawn as it is",
            args.input
        );
    }
    if is_vec {
        if wants_mesh(&planned) {
            bail!(
                "{}: a vector file has lines but no stem radii; write .vec, .svg or .png",
                args.input
            );
        }
        let text = std::fs::read_to_string(&args.input)
            .with_context(|| format!("cannot read {}", args.input))?;
        let lines = sylva::drawing::read_vec(&text, &args.input)?;
        if lines.iter().all(|l| l.len() < 2) {
            bail!("{}: no lines to draw (no `L` after a `P`)", args.input);
        }
        let options = draw_options(&args.out);
        let look = MeshLook::default();
        let written = write_outputs(
            &planned,
            &options,
            &lines,
            Meshable::Nothing,
            &args.input,
            &look,
        )?;
        print_written(written);
        Ok(())
    } else if let Some(age) = args.age {
        let measured = Database::builtin().find(&args.region, &args.input)?;
        if !(0.0..=MAX_AGE).contains(&age) {
            bail!(
                "--age {age}: expected 0..{MAX_AGE} years (the data for {} cover {:.0} to {:.0})",
                measured.label(),
                measured.ages.0,
                measured.ages.1
            );
        }
        let (bark, leaves) = measured.colours();
        let name = format!("{} at {age} years", measured.species.common);
        let options = GrowthOptions {
            seed: args.tree.seed,
            ..Default::default()
        };
        let mut grower = Grower::new(measured, options);
        grower.advance_to(age);
        let mut skeleton = grower.skeleton();
        if args.tree.no_leaves {
            skeleton.leaves.clear();
        }
        let look = MeshLook {
            options: MESH,
            materials: Materials::from_srgb(bark, leaves),
        };
        write_skeleton(&planned, &args.out, &skeleton, &name, &look)
    } else {
        let params = load_params(&args.input, &args.tree.set)?;
        let skeleton = sylva::generate(&params, &args.tree.options())?;
        let look = MeshLook {
            options: MeshOptions::for_species(&params, args.tree.quality),
            materials: Materials::from_srgb(params.bark_color, params.leaf_color),
        };
        write_skeleton(&planned, &args.out, &skeleton, &params.name, &look)
    }
}
