//! Flags of the street's commands: `grow`, `rank`, `serve` and `wires`, and the site, prices
//! and costs `grow` and `rank` share.

use clap::Args;
use std::path::PathBuf;

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

    /// Dress the trees for a season or month: spring (April: leaves unfolding, spring
    /// flowers), summer (July), autumn (October: the species' autumn colour), winter (January:
    /// deciduous trees bare), a month 1-12 or a month's name. Without it, summer leaves and no
    /// flowers. Growth is the same whatever the season.
    #[arg(long, value_name = "SEASON|MONTH", value_parser = sylva::growth::Month::parse)]
    pub season: Option<sylva::growth::Month>,

    /// Picture size in pixels.
    #[arg(long, default_value = "900x900", value_name = "WxH")]
    pub size: String,

    /// Write models, CSV and charts, but no pictures (no renderer needed).
    #[arg(long)]
    pub no_pictures: bool,

    /// Mesh a bare crown's short twigs into the bark of the GLB, one by one, instead of as
    /// copies of one twig (EXT_mesh_gpu_instancing): for readers without that extension.
    #[arg(long)]
    pub twigs_in_bark: bool,

    /// Print one JSON object per species and age (the grown tree's dimensions beside the
    /// equations', and its form: leaf share near the axis, leaders, scaffold angle, pipe
    /// exponent, live and shed branches) instead of the table.
    #[arg(long, conflicts_with = "view")]
    pub json: bool,

    /// Watch the trees grow in a window instead (an age slider, play and pause, the species
    /// side by side); nothing is written.
    #[arg(long, conflicts_with_all = ["output", "no_pictures"])]
    pub view: bool,

    /// Scripted run of the window for tests: pictures at three ages, a report into DIR, close.
    #[arg(long, value_name = "DIR", hide = true, requires = "view")]
    pub self_test: Option<PathBuf>,

    #[command(flatten)]
    pub street: StreetArgs,

    /// Output folder (created if missing).
    #[arg(short, long, value_name = "DIR", required_unless_present = "view")]
    pub output: Option<PathBuf>,
}

/// Where a street tree stands and what its benefits are worth: flags shared by `grow` and
/// `rank`.
#[derive(Args, Debug, Clone, Default)]
pub struct StreetArgs {
    /// A planting site (site.toml: street, façade, awnings, signs, wires, lights, sight
    /// triangle): the façade's shade is turned into energy, and every year's conflicts are
    /// reported.
    #[arg(long, value_name = "SITE.toml")]
    pub site: Option<PathBuf>,

    /// Prices of the benefits (source, year, electricity_per_kwh, natural_gas_per_kbtu,
    /// stormwater_per_m3, co2_per_kg, ozone_per_kg, nox_per_kg, pm10_per_kg, so2_per_kg,
    /// voc_per_kg; optionally median_home_price and location_factor, or leaf_gain_per_m2, for
    /// aesthetics) instead of i-Tree's regional defaults and the region's median home price.
    #[arg(long, value_name = "PRICES.toml")]
    pub prices: Option<PathBuf>,

    /// Costs of planting and keeping a tree (planting, establishment, pruning by DBH class
    /// and cycle, removal by DBH, sidewalk repair, clean-up, pest, liability, administration;
    /// or a programme's per_tree_per_year) instead of the built-in sized table.
    #[arg(long, value_name = "COSTS.toml")]
    pub costs: Option<PathBuf>,

    /// The share of living trees that survive each year, over 0 and at most 1 (default: the
    /// region's: 5% die a year while establishing, then fewer, to the tree guides' share alive
    /// at 40 years). Figures are per tree planted; 1 keeps every tree alive.
    #[arg(long, value_name = "SHARE", allow_negative_numbers = true)]
    pub survival: Option<f64>,

    /// Never cut the trees: they grow on through the site's zones (default: with --site, the
    /// site's [pruning] regime, or the us-street standard's, cuts them as its cycles fall due).
    #[arg(long)]
    pub no_pruning: bool,
}

#[derive(Args, Debug)]
pub struct RankArgs {
    /// Climate region of the database.
    #[arg(long, default_value = "InlVal")]
    pub region: String,

    /// Years each species is grown (or as long as its data reach).
    #[arg(long, default_value_t = 40.0)]
    pub years: f64,

    /// Random seed: the same seed grows the same trees.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,

    #[command(flatten)]
    pub street: StreetArgs,

    /// A folder holding the database's CSV tables instead of the built-in copy.
    #[arg(long, value_name = "DIR")]
    pub database: Option<PathBuf>,

    /// Rank by the net benefit at i-Tree Streets' typical position, or by the grown tree's
    /// own on the site given (default: `site` when --site is given, else `typical`).
    #[arg(long, value_enum)]
    pub by: Option<RankBy>,

    /// Only these species codes (default: every growable species of the region).
    #[arg(long, value_delimiter = ',')]
    pub species: Vec<String>,

    /// Instead of ranking: grow each species to 20, 30 and 40 cm DBH, place it around a
    /// standard house at i-Tree Streets' 24 positions (three distance classes, eight
    /// directions, weighted evenly), and print its shade's cooling and heating, plus the
    /// region's climate effect fitted to the other species, beside i-Tree's figures at the
    /// same DBH.
    #[arg(long)]
    pub calibrate: bool,

    /// With --calibrate: print only the region's climate effect fitted to all the species, as
    /// a row of data/itree-streets/climate-effect.csv (tools/fit-climate-effect.sh).
    #[arg(long, requires = "calibrate")]
    pub fit: bool,

    /// Print one JSON object per species instead of the table.
    #[arg(long)]
    pub json: bool,

    /// Also grow every tree uncut beside its pruned self, and report the benefits pruning
    /// cost each year (twice the growth's time).
    #[arg(long, conflicts_with = "no_pruning")]
    pub pruning_losses: bool,
}

/// What `sylva rank` ranks by.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RankBy {
    /// i-Tree Streets' figures for the species at the grown DBH, at its usual positions.
    Typical,
    /// The grown tree's own crown on the site given (--site).
    Site,
}

#[derive(Args, Debug)]
pub struct ServeArgs {
    /// Port to listen on (0: any free one).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,

    /// Address to listen on: this computer only unless told otherwise (0.0.0.0: every
    /// network the computer is on).
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,

    /// Open the page in the default browser.
    #[arg(long)]
    pub open: bool,

    /// Most memory kept between requests, MiB: grown trees of every age, and the answers last
    /// sent (an eighth of it, at most 128). Never passed: least recently used trees go first;
    /// a species that cannot fit yet is answered 503 with a time to ask again, one that alone
    /// outgrows it 507. Resident memory runs above it by what requests and growths build
    /// while they run (measured in the README).
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u64).range(64..=65536))]
    pub cache_mib: u64,

    /// A folder `sylva city` wrote, shown in the page's city view (at /city.html): its tiles at
    /// every epoch, each tree's card, and its report. Give it again for more cities; each is
    /// named by its folder.
    #[arg(long = "city", value_name = "DIR")]
    pub cities: Vec<PathBuf>,

    /// An XYZ map tile source drawn under the cities, e.g.
    /// https://tile.openstreetmap.org/{z}/{x}/{y}.png (fetched by the browser; without it the
    /// ground is plain).
    #[arg(long, value_name = "URL", requires = "cities")]
    pub basemap: Option<String>,
}

#[derive(Args, Debug)]
pub struct WiresArgs {
    /// The database's raw tree table, TS3_Raw_tree_data.csv (or the folder holding it).
    #[arg(value_name = "TS3.csv|DIR")]
    pub table: PathBuf,

    /// Height of the line the model checks against, m.
    #[arg(long, default_value_t = 8.5)]
    pub height: f64,

    /// Clearance the utility requires around it, m.
    #[arg(long, default_value_t = 1.5)]
    pub clearance: f64,
}
