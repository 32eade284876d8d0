//! `sylva whisk`: Nagel's (1986) whisk tree, a drawn canopy profile turned about the trunk
//! into ribs, with rings and spokes.

use crate::args::WhiskArgs;
use crate::shared::{finish_ribbed, read_text, rib_params};
use anyhow::Result;
use sylva::drawing::plan;
use sylva::nagel::{read_profile, whisk_tree};

pub fn run(args: &WhiskArgs) -> Result<()> {
    let planned = plan(&args.out.outputs)?;
    let params = rib_params(&args.ribs, args.rings, args.spokes)?;
    let name = args.profile.display().to_string();
    let profile = read_profile(&name, &read_text(&args.profile)?, args.ribs.height)?;
    let skeleton = whisk_tree(&profile, &params)?;
    let summary = format!(
        "whisk tree: {} ribs, {} rings, {} spokes per rib",
        params.ribs, params.rings, params.spokes
    );
    finish_ribbed(&planned, &args.out, &skeleton, "whisk tree", summary)
}
