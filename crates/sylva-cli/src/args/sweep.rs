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

    /// Instead of the sweep: grow each species and, at these ages (comma-separated years),
    /// report the share of a beam its crown stops over its outline, in leaf and bare, seen from
    /// the side and along a sun 60 degrees up (street::energy::opacity).
    #[arg(long, value_delimiter = ',', value_name = "AGES")]
    pub beam: Vec<f64>,

    /// With --beam: also draw each crown level from the south with the renderer, in a square
    /// picture of this many pixels (3000 puts 5 mm in a pixel of a 15 m tree), in leaf (its
    /// summer dress) and bare, and report the share of the outline the picture covers, the
    /// leaf share of what it covers, and the share that is bare wood past the leaves (tips%).
    #[arg(long, value_name = "PX", requires = "beam")]
    pub picture: Option<u32>,

    /// With --picture: write the pictures into this folder, as REGION-SPECIES-AGE-leaf.png
    /// and -bare.png.
    #[arg(long, value_name = "DIR", requires = "picture")]
    pub pictures: Option<PathBuf>,

    /// Also write the summary, misses and data-limited targets as Markdown tables.
    #[arg(long, value_name = "FILE.md")]
    pub markdown: Option<PathBuf>,
}
