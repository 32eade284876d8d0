//! Command-line arguments (parsing only; no I/O here).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Sylva creates realistic trees (Weber & Penn 1995) and writes them as GLB or OBJ.
#[derive(Parser, Debug)]
#[command(name = "sylva", version, about, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Generate a tree and write it as a model file (.glb or .obj), printing a summary.
    Generate(GenerateArgs),
    /// List or describe the built-in species.
    #[command(subcommand)]
    Species(SpeciesCommand),
    /// Time generation and meshing of the paper's four appendix species.
    Bench(BenchArgs),
}

#[derive(Args, Debug)]
pub struct GenerateArgs {
    /// Built-in species name (see `sylva species list`), a Sylva .toml file or an Arbaro .xml file.
    #[arg(help_heading = "Input")]
    pub species: String,

    /// Override a parameter, e.g. `--set 1Branches=30` (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE", help_heading = "Input")]
    pub set: Vec<String>,

    /// Random seed: the same species and seed always give the same tree.
    #[arg(long, default_value_t = 0, help_heading = "Generation")]
    pub seed: u64,

    /// Show only stem levels below K (1 = trunk only); leaves appear only with all levels.
    #[arg(long, value_name = "K", help_heading = "Generation")]
    pub levels: Option<u32>,

    /// Detail: scales leaf count (1/size) and mesh ring resolution; 1 is the default.
    #[arg(long, default_value_t = 1.0, help_heading = "Generation")]
    pub quality: f64,

    /// Leave the leaves off.
    #[arg(long, help_heading = "Generation")]
    pub no_leaves: bool,

    /// Stop with an error if the mesh would exceed this many triangles.
    #[arg(
        long,
        default_value_t = 10_000_000,
        value_name = "N",
        help_heading = "Generation"
    )]
    pub max_triangles: u64,

    /// Output file: .glb (glTF binary) or .obj (with a .mtl beside it).
    #[arg(short, long, value_name = "FILE", help_heading = "Output")]
    pub output: PathBuf,

    /// Also draw a quick picture of the tree (PNG, CPU rasteriser, no GPU needed).
    #[arg(long, value_name = "FILE.png", help_heading = "Output")]
    pub preview: Option<PathBuf>,

    /// Camera of the preview picture.
    #[arg(long, value_enum, default_value_t = ViewArg::Front, help_heading = "Output")]
    pub view: ViewArg,

    /// Print the summary as one JSON object instead of text.
    #[arg(long, help_heading = "Output")]
    pub json: bool,
}

#[derive(Subcommand, Debug)]
pub enum SpeciesCommand {
    /// List the built-in species.
    List,
    /// Print every parameter of a species with its value, unit, range and meaning.
    Show {
        /// Built-in name or species file.
        name: String,
        /// Print a complete species TOML file instead (a starting point for your own species).
        #[arg(long)]
        toml: bool,
    },
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Repetitions per species (the fastest is reported).
    #[arg(long, default_value_t = 10)]
    pub runs: u32,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewArg {
    Front,
    Side,
    Top,
}
