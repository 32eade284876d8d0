//! Flags of the trees that can be drawn as lines (`fractal`, `whisk`, `stick`, `lobes`,
//! `draw`): where their files go, and each model's own settings.

use super::TreeArgs;
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Where line-drawable trees go: files by extension, and the drawing's view and size.
#[derive(Args, Debug)]
pub struct LineOutputArgs {
    /// Output file, by extension: .vec (Nagel's P/L vector file), .svg or .png (a line drawing),
    /// .glb or .obj (a mesh); for `lobes` also .tree, and there .png is a rendered picture
    /// (lit and shadowed, beside a 1.8 m person) while .svg stays a line drawing. Repeat to
    /// write several.
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

    /// Size of .svg and .png drawings in pixels [default: 1024x1024; a rendered picture
    /// 1024x768].
    #[arg(long, value_name = "WxH", value_parser = drawing_size, help_heading = "Output")]
    pub size: Option<(u32, u32)>,
}

/// The size of a line drawing: pictures of lines may be larger than rendered ones.
fn drawing_size(text: &str) -> Result<(u32, u32), String> {
    super::parse_size(text, 16384)
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
