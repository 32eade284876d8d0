//! Command-line arguments (parsing only; no I/O here).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

mod city;
mod lines;
mod street;
mod sweep;

pub use city::{CityArgs, CityDemoArgs, DemoLayoutArg};
pub use lines::*;
pub use street::*;
pub use sweep::SweepArgs;

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
    /// Render a tree (species, species file or GLB) to a PNG: lit, shadowed, with a 1.8 m person.
    Render(RenderArgs),
    /// Plant a forest: many trees of several species, generated in parallel, as one GLB.
    Forest(ForestArgs),
    /// Grow a street tree from the USDA Urban Tree Database year by year: a GLB and a picture
    /// per age, modelled against measured dimensions (CSV and charts), species side by side.
    Grow(GrowArgs),
    /// Rank a region's street tree species by net benefit over the years (grown in parallel on
    /// one site), with the year each first runs into the street.
    Rank(RankArgs),
    /// Grow every species of every region of the database through the ages its data cover and
    /// measure each against its equations: the count within bounds, every miss, and the
    /// targets the data themselves limit.
    Sweep(SweepArgs),
    /// A city's street-tree inventory (CSV, GeoJSON or GeoPackage) grown and written as OGC 3D
    /// Tiles: every tree instanced from shared grown trees, with its attributes, one tileset
    /// per epoch.
    City(Box<CityArgs>),
    /// Write a synthetic street-tree inventory (a region's species mix and DBH classes along a
    /// street grid, with dead trees, stumps, sites and a few broken rows) for `sylva city`.
    CityDemo(CityDemoArgs),
    /// Check the site's wire model against the Urban Tree Database's own records of wire
    /// conflicts (table TS3), per region.
    Wires(WiresArgs),
    /// A local web page on which planners compare street trees growing side by side over the
    /// years: 3-D trees, growth charts, benefits, costs, conflicts and downloads, with the
    /// JSON API under it.
    Serve(ServeArgs),
    /// Open the interactive editor: every parameter live, orbit camera, wind, load/save/export;
    /// or fly through a forest file, or look at a .glb.
    View(ViewArgs),
    /// Honda's fractal tree (Nagel 1986): every branch forks into two daughters turned by
    /// theta and shortened by R. Vector files and drawings stream in constant memory.
    #[command(allow_negative_numbers = true)]
    Fractal(FractalArgs),
    /// Whisk tree (Nagel 1986): a canopy profile (CSV or SVG polyline) turned about the trunk
    /// into ribs, with optional rings and spokes.
    Whisk(WhiskArgs),
    /// Stick tree (Nagel 1986): drawn branches (CSV) turned about the trunk.
    Stick(StickArgs),
    /// Lobe-driven tree (Fields 2012): branches grown toward control points on leaf lobes,
    /// leaves filling the lobes; lobes placed automatically, given, read from a .tree file or
    /// fitted to a point cloud.
    Lobes(LobesArgs),
    /// Line drawing of any tree: Nagel's P/L vector file, or a front, side, top, perspective or
    /// front-and-side overlay view as SVG or PNG.
    Draw(DrawArgs),
    /// Time generation and meshing of the paper's four appendix species.
    Bench(BenchArgs),
}

/// How to grow the tree: flags shared by `generate` and `render`.
#[derive(Args, Debug)]
pub struct TreeArgs {
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
}

impl TreeArgs {
    /// The generation options these flags ask for (calm air, default budget).
    pub fn options(&self) -> sylva::GenerateOptions {
        sylva::GenerateOptions {
            seed: self.seed,
            max_levels: self.levels,
            quality: self.quality,
            leaves: !self.no_leaves,
            ..Default::default()
        }
    }
}

#[derive(Args, Debug)]
pub struct GenerateArgs {
    /// Built-in species name (see `sylva species list`), a Sylva .toml file or an Arbaro .xml file.
    #[arg(help_heading = "Input")]
    pub species: String,

    #[command(flatten)]
    pub tree: TreeArgs,

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

    /// Also render a picture of the tree (PNG, 1024x768; a GPU or Mesa's software driver).
    #[arg(long, value_name = "FILE.png", help_heading = "Output")]
    pub preview: Option<PathBuf>,

    /// GLB only: write a chain of levels of detail for engines (MSFT_lod with screen coverages:
    /// full tree, half, quarter, and a baked 8-view billboard impostor), named NAME_LOD0..3.
    #[arg(long, help_heading = "Output")]
    pub lod_chain: bool,

    /// Camera of the preview picture.
    #[arg(long, value_enum, default_value_t = RenderView::Front, help_heading = "Output")]
    pub view: RenderView,

    /// Print the summary as one JSON object instead of text.
    #[arg(long, help_heading = "Output")]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Built-in species, a .toml or Arbaro .xml species file, a .glb written by `sylva generate`
    /// or `sylva forest`, or a forest file (.toml with a `[forest]` table).
    #[arg(help_heading = "Input")]
    pub input: String,

    /// Generation flags (ignored for .glb input).
    #[command(flatten)]
    pub tree: TreeArgs,

    /// Wind speed (the paper's units: 50 doubles the base sway).
    #[arg(long, default_value_t = 0.0, help_heading = "Wind")]
    pub wind: f64,

    /// Gust strength on top of the wind.
    #[arg(long, default_value_t = 0.0, help_heading = "Wind")]
    pub gust: f64,

    /// Time in seconds (the tree sways with time; same seed and time = same picture).
    #[arg(long, default_value_t = 0.0, help_heading = "Wind")]
    pub time: f64,

    /// Write an animation: N frames from --time on, as OUT-0000.png, OUT-0001.png, ...
    #[arg(long, value_name = "N", help_heading = "Wind")]
    pub frames: Option<u32>,

    /// Frames per second of the animation.
    #[arg(long, default_value_t = 12.0, help_heading = "Wind")]
    pub fps: f64,

    /// Camera.
    #[arg(long, value_enum, default_value_t = RenderView::Front, help_heading = "Rendering")]
    pub view: RenderView,

    /// Picture size.
    #[arg(
        long,
        default_value = "1024x768",
        value_name = "WxH",
        help_heading = "Rendering"
    )]
    pub size: String,

    /// Render N views around the tree into one contact sheet.
    #[arg(long, value_name = "N", help_heading = "Rendering")]
    pub turntable: Option<u32>,

    /// Leave out the ground and the 1.8 m person.
    #[arg(long, help_heading = "Rendering")]
    pub bare: bool,

    /// Forests: camera distance from the forest's centre, metres, along the --view direction
    /// (default: frame the whole forest).
    #[arg(
        long,
        value_name = "METRES",
        allow_negative_numbers = true,
        help_heading = "Forest"
    )]
    pub range: Option<f32>,

    /// Forests: camera position X,Y,Z in metres (Z up), with --target.
    #[arg(
        long,
        value_name = "X,Y,Z",
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "target",
        help_heading = "Forest"
    )]
    pub eye: Option<Vec<f32>>,

    /// Forests: the point the camera looks at, X,Y,Z in metres.
    #[arg(
        long,
        value_name = "X,Y,Z",
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "eye",
        help_heading = "Forest"
    )]
    pub target: Option<Vec<f32>>,

    /// Forests: range degradation on, off, or both side by side with their primitive counts.
    #[arg(long, value_enum, default_value_t = LodMode::On, help_heading = "Forest")]
    pub lod: LodMode,

    /// Forests with range degradation: the most primitives a frame's trees draw together,
    /// shared by the pixels each covers; 0 for no frame budget (each tree still draws at most
    /// 2 per pixel of its box).
    #[arg(
        long,
        value_name = "PRIMITIVES",
        default_value_t = 2_000_000,
        help_heading = "Forest"
    )]
    pub lod_budget: usize,

    /// Vertical field of view, degrees.
    #[arg(
        long,
        default_value_t = 30.0,
        allow_negative_numbers = true,
        help_heading = "Rendering"
    )]
    pub fov: f32,

    /// Grow INPUT as a street tree of the Urban Tree Database (a species code such as PLAC,
    /// or its name) to this age, years since planting, and render that.
    #[arg(long, value_name = "YEARS", help_heading = "Street tree")]
    pub age: Option<f64>,

    /// The database's climate region for --age (default InlVal: Modesto, California).
    #[arg(long, requires = "age", help_heading = "Street tree")]
    pub region: Option<String>,

    /// Dress the street tree for a season or month (spring, summer, autumn, winter, 1-12 or a
    /// month's name), as `sylva grow --season` does.
    #[arg(
        long,
        requires = "age",
        value_name = "SEASON|MONTH",
        value_parser = sylva::growth::Month::parse,
        help_heading = "Street tree"
    )]
    pub season: Option<sylva::growth::Month>,

    /// Output PNG.
    #[arg(short, long, value_name = "FILE.png", help_heading = "Output")]
    pub output: PathBuf,
}

#[derive(Args, Debug)]
pub struct ForestArgs {
    /// A forest file (a `[forest]` table of species, count, area, seed, variants, quality)
    /// instead of the flags below.
    #[arg(value_name = "FOREST.toml")]
    pub file: Option<PathBuf>,

    /// Species, comma-separated (built-in names or species files); by default the paper's
    /// four appendix species.
    #[arg(
        long,
        value_delimiter = ',',
        default_values = sylva::bench::APPENDIX_SPECIES
    )]
    pub species: Vec<String>,

    /// Number of trees.
    #[arg(long, default_value_t = 100)]
    pub count: u32,

    /// Size of the plot, metres (width along X, depth along Y), centred on the origin.
    #[arg(long, default_value = "100x100", value_name = "WxD")]
    pub area: String,

    /// Random seed of the whole forest.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// Distinct trees per species, shared by instances turned and scaled at random; 0 makes
    /// every tree unique.
    #[arg(long, default_value_t = 4)]
    pub variants: u32,

    /// Detail of each tree (leaf count and mesh resolution); forests usually need less than 1.
    #[arg(long, default_value_t = 0.5)]
    pub quality: f64,

    /// Output GLB.
    #[arg(short, long, value_name = "FILE.glb")]
    pub output: PathBuf,

    /// Print the summary as one JSON object.
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Built-in species or species file to start from; a lobe species to look at (black_oak,
    /// weeping_cherry, lobes:balsam_fir); a forest file to fly through; or a .glb to look at
    /// (any model Sylva wrote: fractal, whisk, lobes, grown, generated).
    #[arg(default_value = "quaking_aspen")]
    pub species: String,

    /// Scripted run for tests: screenshot, edit a parameter, screenshot, write a report into DIR, close.
    #[arg(long, value_name = "DIR", hide = true)]
    pub self_test: Option<PathBuf>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LodMode {
    /// Trees degrade with range (Weber & Penn section 5).
    On,
    /// Every tree at full detail.
    Off,
    /// Both, side by side, from the same camera.
    Compare,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RenderView {
    Front,
    Side,
    Top,
    Iso,
}

impl RenderView {
    /// The renderer's camera for this view.
    pub fn to_view(self) -> sylva_render::View {
        use sylva_render::ViewKind;
        sylva_render::View::named(match self {
            RenderView::Front => ViewKind::Front,
            RenderView::Side => ViewKind::Side,
            RenderView::Top => ViewKind::Top,
            RenderView::Iso => ViewKind::Iso,
        })
    }
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

    /// Also time rendering (1280x720 frames) and regeneration after a parameter change.
    #[arg(long)]
    pub render: bool,

    /// Also report range degradation: primitives per frame from 10 m to 3 km, selection cost.
    #[arg(long)]
    pub lod: bool,

    /// Also draw a Black Tupelo and a 1,000-tree mixed forest from 10 m to 3 km with and
    /// without range degradation (primitives, frame time, memory per tree).
    #[arg(long)]
    pub forest: bool,

    /// Also time growth steps (production rules, light, mesh) of a street tree at 5k to 30k
    /// branch segments.
    #[arg(long)]
    pub growth: bool,

    /// Also time a street tree's yearly accounts (benefits, shade, conflicts) against its
    /// growth.
    #[arg(long)]
    pub street: bool,
    /// Also measure how the crowns branch (twig lengths, Horton-Strahler orders and
    /// bifurcation ratio) of the Modesto seven and three NoEast species at 10, 20 and 30
    /// years, beside the published figures.
    #[arg(long)]
    pub twigs: bool,

    /// Also grow this many unique trees of the appendix species in parallel (stored for
    /// range, then released) and report trees per second.
    #[arg(long, value_name = "N")]
    pub throughput: Option<u32>,

    /// Also tile a demo city of this many trees, and one of a tenth as many as the baseline:
    /// trees per second, tiles, bytes per tree and peak memory of each, and how they grow.
    #[arg(long, value_name = "TREES")]
    pub city: Option<usize>,
}

/// Parses `WxH`, each side 16..=`max` pixels.
pub fn parse_size(text: &str, max: u32) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("--size {text}: expected WIDTHxHEIGHT, e.g. 1280x720"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (16..=max).contains(v))
            .ok_or_else(|| {
                format!("--size {text}: each side must be a whole number of pixels, 16..{max}")
            })
    };
    Ok((parse(w)?, parse(h)?))
}
