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
    /// Render a tree (species, species file or GLB) to a PNG: lit, shadowed, with a 1.8 m person.
    Render(RenderArgs),
    /// Plant a forest: many trees of several species, generated in parallel, as one GLB.
    Forest(ForestArgs),
    /// Grow a street tree from the USDA Urban Tree Database year by year: a GLB and a picture
    /// per age, modelled against measured dimensions (CSV and charts), species side by side.
    Grow(GrowArgs),
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

/// Where line-drawable trees go: files by extension, and the drawing's view and size.
#[derive(Args, Debug)]
pub struct LineOutputArgs {
    /// Output file, by extension: .vec (Nagel's P/L vector file), .svg or .png (a line drawing),
    /// .glb or .obj (a mesh); for `lobes` also .tree. Repeat to write several.
    #[arg(
        short,
        long = "output",
        value_name = "FILE",
        required = true,
        help_heading = "Output"
    )]
    pub outputs: Vec<PathBuf>,

    /// View of .svg and .png drawings.
    #[arg(long, value_enum, default_value_t = LineView::Front, help_heading = "Output")]
    pub view: LineView,

    /// Size of .svg and .png drawings in pixels.
    #[arg(long, value_name = "WxH", default_value = "1024x1024", value_parser = drawing_size, help_heading = "Output")]
    pub size: (u32, u32),
}

/// The size of a line drawing: pictures of lines may be larger than rendered ones.
fn drawing_size(text: &str) -> Result<(u32, u32), String> {
    parse_size(text, 16384)
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

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineView {
    /// Looking north: X across, Z up.
    Front,
    /// Looking west: Y across, Z up.
    Side,
    /// Plan view from above.
    Top,
    /// From the south-east, 20 degrees up, far strokes fainter.
    Perspective,
    /// Front and side drawn on top of each other (Nagel's fuller figure).
    Overlay,
}

#[derive(Args, Debug)]
pub struct FractalArgs {
    /// Divergence of the first daughter from its mother's direction, degrees.
    #[arg(long, default_value_t = -35.0, help_heading = "Branching")]
    pub theta1: f64,
    /// Divergence of the second daughter, degrees.
    #[arg(long, default_value_t = 10.0, help_heading = "Branching")]
    pub theta2: f64,
    /// Length ratio of the first daughter to its mother.
    #[arg(long, default_value_t = 0.73, help_heading = "Branching")]
    pub r1: f64,
    /// Length ratio of the second daughter.
    #[arg(long, default_value_t = 0.83, help_heading = "Branching")]
    pub r2: f64,
    /// Branching generations after the trunk (depth d gives 2^d tips).
    #[arg(long, default_value_t = 12, help_heading = "Branching")]
    pub depth: u32,
    /// Daughters of each last-generation branch, fanned from theta1 to theta2 (10-15 suggest
    /// needles).
    #[arg(
        long,
        default_value_t = 2,
        value_name = "N",
        help_heading = "Branching"
    )]
    pub tip_daughters: u32,
    /// Random variation of each length ratio, as a fraction (0.1 = ±10%).
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "FRACTION",
        help_heading = "Variation"
    )]
    pub vary_length: f64,
    /// Random variation of each angle, ± degrees.
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "DEGREES",
        help_heading = "Variation"
    )]
    pub vary_angle: f64,
    /// Seed of the variations.
    #[arg(long, default_value_t = 0, help_heading = "Variation")]
    pub seed: u64,
    /// Trunk length, metres.
    #[arg(long, default_value_t = 2.0, value_name = "M", help_heading = "Size")]
    pub trunk_length: f64,
    /// Trunk radius, metres (branches follow the pipe model).
    #[arg(long, default_value_t = 0.12, value_name = "M", help_heading = "Size")]
    pub trunk_radius: f64,
    /// Put a leaf at the end of every tip.
    #[arg(long, help_heading = "Size")]
    pub leaves: bool,
    /// Refuse trees of more segments than this.
    #[arg(long, default_value_t = 1 << 22, value_name = "N", help_heading = "Size")]
    pub max_segments: u64,
    #[command(flatten)]
    pub out: LineOutputArgs,
}

/// Wires shared by whisk and stick trees.
#[derive(Args, Debug)]
pub struct RibArgs {
    /// Copies around the trunk, 360/N degrees apart.
    #[arg(
        long,
        value_name = "N",
        conflicts_with = "density",
        help_heading = "Ribs"
    )]
    pub ribs: Option<u32>,
    /// Nagel's density 1-5: 6, 9, 12, 15 or 18 ribs.
    #[arg(long, value_name = "1-5", help_heading = "Ribs")]
    pub density: Option<u32>,
    /// Scale the drawing so its top is this many metres high (an SVG profile without it is
    /// scaled to 10 m; CSV is read in metres).
    #[arg(long, value_name = "M", help_heading = "Ribs")]
    pub height: Option<f64>,
    /// Radius of the wires, metres (default: height / 400).
    #[arg(long, value_name = "M", help_heading = "Ribs")]
    pub wire_radius: Option<f64>,
    /// Trunk radius, metres (default: height / 60).
    #[arg(long, value_name = "M", help_heading = "Ribs")]
    pub trunk_radius: Option<f64>,
}

#[derive(Args, Debug)]
pub struct WhiskArgs {
    /// Canopy profile: a .csv of `radius,height` rows (metres) from the canopy's base on the
    /// trunk to its top, or an .svg whose first polyline is the profile (first point on the
    /// trunk, ground at the bottom of the viewBox).
    #[arg(long, value_name = "FILE", help_heading = "Input")]
    pub profile: PathBuf,
    #[command(flatten)]
    pub ribs: RibArgs,
    /// Horizontal rings around the canopy (Nagel's figure 25).
    #[arg(long, default_value_t = 0, value_name = "K", help_heading = "Ribs")]
    pub rings: u32,
    /// Spokes per rib from the trunk out to the canopy's edge (figure 26; for conifers).
    #[arg(long, default_value_t = 0, value_name = "K", help_heading = "Ribs")]
    pub spokes: u32,
    #[command(flatten)]
    pub out: LineOutputArgs,
}

#[derive(Args, Debug)]
pub struct StickArgs {
    /// Branches: a .csv of `branch,radius,height` rows (metres); the rows of one branch, in
    /// order, run from its base on the trunk to its tip.
    #[arg(long, value_name = "FILE", help_heading = "Input")]
    pub branches: PathBuf,
    #[command(flatten)]
    pub ribs: RibArgs,
    #[command(flatten)]
    pub out: LineOutputArgs,
}

#[derive(Args, Debug)]
pub struct LobesArgs {
    /// A built-in lobe species (black_oak, balsam_fir, weeping_cherry), a rules .toml file, or a
    /// .tree file (Fields' format: its tree type names the species).
    #[arg(help_heading = "Input")]
    pub input: String,
    /// Fit the trunk and lobes to a point cloud (.ply or .xyz) instead of placing them.
    #[arg(long, value_name = "FILE", help_heading = "Input")]
    pub points: Option<PathBuf>,
    /// The point cloud's up axis.
    #[arg(long, value_enum, default_value_t = UpAxis::Z, help_heading = "Input")]
    pub up: UpAxis,
    /// Number of lobes to fit to the point cloud (default: chosen from 1 to 8).
    #[arg(long, value_name = "K", help_heading = "Input")]
    pub fit_lobes: Option<usize>,
    /// A lobe of your own, centre and radius in metres (Z up); repeat for several. The trunk
    /// grows to them.
    #[arg(
        long = "lobe",
        value_name = "X,Y,Z,R",
        allow_hyphen_values = true,
        help_heading = "Input"
    )]
    pub lobes: Vec<String>,
    /// Random seed (a .tree file carries its own; this overrides it).
    #[arg(long, help_heading = "Generation")]
    pub seed: Option<u64>,
    /// Scale the finished tree (lengths and widths).
    #[arg(long, default_value_t = 1.0, help_heading = "Generation")]
    pub scale: f64,
    /// Sides of every branch's cylinder, instead of the species' Tessellation rule (the paper
    /// compares 36 with 5 and 10).
    #[arg(long, value_name = "N", help_heading = "Generation")]
    pub tessellation: Option<u32>,
    #[command(flatten)]
    pub out: LineOutputArgs,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum UpAxis {
    /// Z is up (most scanners and CAD).
    Z,
    /// Y is up (Kinect, game engines).
    Y,
}

#[derive(Args, Debug)]
pub struct DrawArgs {
    /// Built-in species, a .toml or Arbaro .xml species file, or a .vec vector file; with
    /// --age, a street tree of the Urban Tree Database (code or name, as `sylva grow`).
    #[arg(help_heading = "Input")]
    pub input: String,
    /// Grow the street tree to this age (years) and draw it, as `sylva grow` grows it.
    #[arg(long, value_name = "YEARS", help_heading = "Input")]
    pub age: Option<f64>,
    /// Climate region of the street tree (with --age).
    #[arg(
        long,
        default_value = "InlVal",
        requires = "age",
        help_heading = "Input"
    )]
    pub region: String,
    /// Generation flags (species input only).
    #[command(flatten)]
    pub tree: TreeArgs,
    #[command(flatten)]
    pub out: LineOutputArgs,
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

    /// Vertical field of view, degrees.
    #[arg(
        long,
        default_value_t = 30.0,
        allow_negative_numbers = true,
        help_heading = "Rendering"
    )]
    pub fov: f32,

    /// Output PNG.
    #[arg(short, long, value_name = "FILE.png", help_heading = "Output")]
    pub output: PathBuf,
}

#[derive(Args, Debug)]
pub struct GrowArgs {
    /// Species: code (PLAC), scientific name or common name (`london_planetree`).
    pub species: String,

    /// Climate region of the database (InlVal: Modesto, California, where the seeds' data were
    /// measured).
    #[arg(long, default_value = "InlVal")]
    pub region: String,

    /// First age written, years since planting (default: the first age the data cover).
    #[arg(long)]
    pub from: Option<f64>,

    /// Last age written (default: the last age the data cover).
    #[arg(long)]
    pub to: Option<f64>,

    /// Years between written ages.
    #[arg(long, default_value_t = 1.0)]
    pub step: f64,

    /// Random seed: the same seed grows the same tree.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    /// Other species grown beside this one, comma-separated: one picture per age with all of
    /// them, named, with their ages and heights.
    #[arg(long, value_delimiter = ',')]
    pub compare: Vec<String>,

    /// A folder holding the database's CSV tables (TS1, TS2, TS6) instead of the built-in copy.
    #[arg(long, value_name = "DIR")]
    pub database: Option<PathBuf>,

    /// Picture size in pixels.
    #[arg(long, default_value = "900x900", value_name = "WxH")]
    pub size: String,

    /// Write models, CSV and charts, but no pictures (no renderer needed).
    #[arg(long)]
    pub no_pictures: bool,

    /// Watch the trees grow in a window instead (an age slider, play and pause, the species
    /// side by side); nothing is written.
    #[arg(long, conflicts_with_all = ["output", "no_pictures"])]
    pub view: bool,

    /// Scripted run of the window for tests: pictures at three ages, a report into DIR, close.
    #[arg(long, value_name = "DIR", hide = true, requires = "view")]
    pub self_test: Option<PathBuf>,

    /// Output folder (created if missing).
    #[arg(short, long, value_name = "DIR", required_unless_present = "view")]
    pub output: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ForestArgs {
    /// A forest file (a `[forest]` table of species, count, area, seed, variants, quality)
    /// instead of the flags below.
    #[arg(value_name = "FOREST.toml")]
    pub file: Option<PathBuf>,

    /// Species, comma-separated (built-in names or species files).
    #[arg(long, value_delimiter = ',', required_unless_present = "file")]
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
    /// Built-in species or species file to start from; a forest file to fly through; or a .glb
    /// to look at (any model Sylva wrote: fractal, whisk, lobes, grown, generated).
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

    /// Also grow this many unique trees of the appendix species in parallel (stored for
    /// range, then released) and report trees per second.
    #[arg(long, value_name = "N")]
    pub throughput: Option<u32>,
}
