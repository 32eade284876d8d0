//! `sylva stick`: Nagel's (1986) stick tree, drawn branches turned about the trunk.

use crate::args::StickArgs;
use crate::shared::{finish_ribbed, read_text, rib_params};
use anyhow::Result;
use sylva::drawing::plan;
use sylva::nagel::{read_sticks, stick_tree};

pub fn run(args: &StickArgs) -> Result<()> {
    let planned = plan(&args.out.outputs)?;
    let params = rib_params(&args.ribs, 0, 0)?;
    let name = args.branches.display().to_string();
    let branches = read_sticks(&name, &read_text(&args.branches)?, args.ribs.height)?;
    let skeleton = stick_tree(&branches, &params)?;
    let summary = format!(
        "stick tree: {} branches x {} ribs",
        branches.len(),
        params.ribs
    );
    finish_ribbed(&planned, &args.out, &skeleton, "stick tree", summary)
}
