//! Flags of `sylva sweep`.

use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct SweepArgs {
    /// Regions to sweep, comma-separated (default: all 17).
    #[arg(long, value_delimiter = ',')]
    pub region: Vec<String>,

    /// Only these species codes (default: every species with its five equations).
    #[arg(long, value_delimiter = ',')]
    pub species: Vec<String>,

    /// Grow no further than this age (default: the last age each species' data cover).
    #[arg(long, value_name = "YEARS")]
    pub to: Option<u32>,

    /// Random seed of every tree.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,

    /// Print one JSON object per species and region instead of the table.
    #[arg(long)]
    pub json: bool,

    /// Also write the summary, misses and data-limited targets as Markdown tables.
    #[arg(long, value_name = "FILE.md")]
    pub markdown: Option<PathBuf>,
}
