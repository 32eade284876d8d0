//! `sylva wires`: the site's wire model against the Urban Tree Database's own records.

use crate::args::WiresArgs;
use anyhow::{Result, bail};
use sylva::street::work::wires::{ENOUGH, agreement, read_ts3};

pub fn run(args: &WiresArgs) -> Result<()> {
    for (flag, v) in [("--height", args.height), ("--clearance", args.clearance)] {
        if !(v.is_finite() && (0.0..=100.0).contains(&v)) {
            bail!("{flag} {v}: expected 0 to 100 m");
        }
    }
    let path = if args.table.is_dir() {
        args.table.join("TS3_Raw_tree_data.csv")
    } else {
        args.table.clone()
    };
    let trees = read_ts3(&path)?;
    let rows = agreement(&trees, args.height, args.clearance);
    if rows.is_empty() {
        bail!(
            "{}: no region has {ENOUGH} trees with overhead lines recorded",
            path.display()
        );
    }
    println!(
        "line {} m up, {} m clearance (reach {:.1} m): the model against TS3's wire records \
         (trees with lines beside them; conflict = code 2)",
        args.height,
        args.clearance,
        args.height - args.clearance
    );
    println!(
        "  {:<8} {:>6} {:>11} {:>9} {:>16} {:>14}",
        "region", "trees", "conflicting", "agreement", "always 'no' gets", "best reach"
    );
    let (mut right, mut no, mut all) = (0.0, 0.0, 0usize);
    for r in &rows {
        println!(
            "  {:<8} {:>6} {:>11} {:>8.1}% {:>15.1}% {:>7.2} m {:>4.1}%",
            r.region,
            r.trees,
            r.conflicting,
            r.agreement * 100.0,
            r.baseline * 100.0,
            r.best.0,
            r.best.1 * 100.0
        );
        right += r.agreement * r.trees as f64;
        no += r.baseline * r.trees as f64;
        all += r.trees;
    }
    println!(
        "  all      {all:>6} {:>21.1}% {:>15.1}%",
        right / all as f64 * 100.0,
        no / all as f64 * 100.0
    );
    Ok(())
}
