//! What the subcommands share: a species loaded with its `--set` overrides, the headless
//! renderer with its notices, pictures written as PNG, forests grown with a progress bar,
//! line-drawable trees written by extension, the growth database and a street's site, prices
//! and costs. Imports no subcommand, so that none of them
//! imports another through it.

use crate::args::{LineOutputArgs, LineView, RibArgs, StreetArgs};
use anyhow::{Context, Result, bail};
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use sylva::drawing::{DrawOptions, MeshLook, Meshable, Planned, View, write_outputs};
use sylva::export::write_atomically;
use sylva::forest::{Forest, ForestSpec, ForestSpecies};
use sylva::growth::Database;
use sylva::lod::LodTree;
use sylva::nagel::WhiskParams;
use sylva::street::study::{Pruning, Study};
use sylva::street::{Costs, Prices, Site, Survival};
use sylva::{Skeleton, TreeParams};
use sylva_render::{Picture, Renderer};

/// Loads the species and applies `--set` overrides.
pub fn load_params(species: &str, overrides: &[String]) -> Result<TreeParams> {
    let mut params = sylva::species::load(species)?;
    warn_notes(species, &params);
    for item in overrides {
        let (name, value) = item.split_once('=').with_context(|| {
            format!("--set {item}: expected NAME=VALUE, e.g. --set 1Branches=30")
        })?;
        let value: f64 = value
            .trim()
            .parse()
            .with_context(|| format!("--set {item}: `{value}` is not a number"))?;
        params
            .set(name.trim(), value)
            .with_context(|| format!("--set {item}"))?;
    }
    params
        .validate()
        .with_context(|| format!("species {species}"))?;
    Ok(params)
}

/// What reading a species noticed (an Arbaro value clamped), as warnings.
fn warn_notes(species: &str, params: &TreeParams) {
    for note in &params.notes {
        eprintln!("sylva: warning: {species}: {note}");
    }
}

/// The headless renderer `SYLVA_RENDERER` asks for (by default the first that works: Vulkan,
/// OpenGL, the CPU), saying on stderr when pictures are drawn on the CPU instead of a GPU.
pub fn headless() -> Result<Renderer> {
    let choice = sylva_render::Choice::from_env()?;
    Ok(Renderer::headless(choice, |note| {
        eprintln!("sylva: {note}")
    })?)
}

/// One tree mesh drawn lit and shadowed beside the person, as `generate --preview` and
/// `lobes -o t.png` draw it.
pub fn picture_of(
    mesh: &sylva::mesh::TreeMesh,
    (bark, leaves): ([f32; 3], [f32; 3]),
    view: &sylva_render::View,
    (width, height): (u32, u32),
) -> Result<Picture> {
    let renderer = headless()?;
    let tree = renderer.upload(mesh);
    let scene = sylva_render::Scene::new(&tree, bark, leaves);
    Ok(renderer.render(&scene, view, width, height)?)
}

/// Writes a picture as a PNG file.
pub fn save_picture(path: &Path, picture: &Picture) -> Result<()> {
    write_atomically(path, &picture.to_png()?)?;
    Ok(())
}

/// A forest's species, loaded with their warnings told.
pub fn forest_species(spec: &ForestSpec) -> Result<Vec<ForestSpecies>> {
    let species = spec.load_species()?;
    for (name, s) in spec.species.iter().zip(&species) {
        for note in s.notes() {
            eprintln!("sylva: warning: {name}: {note}");
        }
    }
    Ok(species)
}

/// A progress bar on stderr (hidden when stderr is not a terminal), restarted at each stage
/// a library run reports.
pub struct StageBar {
    bar: indicatif::ProgressBar,
    stage: std::sync::Mutex<String>,
}

impl StageBar {
    pub fn new() -> StageBar {
        let bar = indicatif::ProgressBar::new(0);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} [{elapsed}<{eta}]")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        StageBar {
            bar,
            stage: Default::default(),
        }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl sylva_city::Progress for StageBar {
    fn step(&self, stage: &str, done: usize, total: usize) {
        let mut s = self.stage.lock().unwrap_or_else(|e| e.into_inner());
        if *s != stage {
            *s = stage.to_string();
            self.bar.reset();
            self.bar.set_message(stage.to_string());
        }
        self.bar
            .set_length(if total > 0 { total } else { done } as u64);
        self.bar.set_position(done as u64);
    }
}

/// Runs `grow` with a progress bar, passing it the tick to call as each of `count` trees is
/// done.
pub fn with_progress<T>(count: usize, grow: impl FnOnce(&(dyn Fn() + Sync)) -> T) -> T {
    let bar = StageBar::new();
    sylva_city::Progress::step(&bar, "growing trees", 0, count);
    let grown = grow(&|| bar.bar.inc(1));
    bar.finish();
    grown
}

/// Plants and grows `spec` stored for range rendering, with a progress bar.
pub fn grow_for_range(spec: &ForestSpec) -> Result<Forest<LodTree>> {
    let species = forest_species(spec)?;
    let variants = sylva::forest::plant(spec).variants.len();
    Ok(with_progress(variants, |tick| {
        sylva::forest::grow_lod(spec, species, tick)
    })?)
}

/// A line drawing's size when `--size` is not given.
const DRAWING_SIZE: (u32, u32) = (1024, 1024);

/// The drawing settings the line-output flags ask for.
pub fn draw_options(out: &LineOutputArgs) -> DrawOptions {
    DrawOptions {
        view: match out.view {
            LineView::Front => View::Front,
            LineView::Side => View::Side,
            LineView::Top => View::Top,
            LineView::Perspective => View::Perspective,
            LineView::Overlay => View::Overlay,
        },
        width: out.size.unwrap_or(DRAWING_SIZE).0,
        height: out.size.unwrap_or(DRAWING_SIZE).1,
        ..Default::default()
    }
}

/// Writes a skeleton's planned line and mesh outputs; prints a line per file.
pub fn write_skeleton(
    planned: &[Planned],
    out: &LineOutputArgs,
    skeleton: &Skeleton,
    name: &str,
    look: &MeshLook,
) -> Result<()> {
    let options = draw_options(out);
    let mesh = Meshable::Skeleton(skeleton);
    print_written(write_outputs(
        planned, &options, skeleton, mesh, name, look,
    )?);
    Ok(())
}

/// One line per file written.
pub fn print_written(written: Vec<String>) {
    for line in written {
        println!("wrote {line}");
    }
}

/// A text file's contents; the error names the file.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

/// The rib settings of a whisk or stick tree: `--ribs`, or ribs for a `--density`.
pub fn rib_params(ribs: &RibArgs, rings: u32, spokes: u32) -> Result<WhiskParams> {
    let count = match (ribs.ribs, ribs.density) {
        (Some(n), _) => n,
        (None, Some(d)) => sylva::nagel::whisk::density_ribs(d)
            .with_context(|| format!("--density {d}: expected 1 (least dense) to 5 (most)"))?,
        (None, None) => 8,
    };
    if let Some(h) = ribs.height
        && !(h.is_finite() && h > 0.0 && h <= 200.0)
    {
        bail!("--height {h}: expected 0..200 metres");
    }
    Ok(WhiskParams {
        ribs: count,
        rings,
        spokes,
        wire_radius: ribs.wire_radius,
        trunk_radius: ribs.trunk_radius,
    })
}

/// Writes a whisk or stick tree's outputs and prints what was made.
pub fn finish_ribbed(
    planned: &[Planned],
    out: &LineOutputArgs,
    skeleton: &Skeleton,
    name: &str,
    summary: String,
) -> Result<()> {
    let stats = skeleton.stats();
    println!(
        "{summary}: {} stems, {:.2} m tall, crown {:.2} m across",
        skeleton.stems.len(),
        stats.height,
        stats.crown_width
    );
    write_skeleton(planned, out, skeleton, name, &MeshLook::default())
}

/// The growth database: `--database DIR` or the built-in copy.
pub fn database(dir: Option<&PathBuf>) -> Result<Cow<'static, Database>> {
    Ok(match dir {
        Some(dir) => Cow::Owned(Database::from_dir(dir)?),
        None => Cow::Borrowed(Database::builtin()),
    })
}

/// The street's flags as a study of `years` from `seed`: the site, prices, costs and survival
/// read and checked, and the site's pruning regime carried out unless `--no-pruning`.
pub fn study(args: &StreetArgs, years: f64, seed: u64) -> Result<Study> {
    let study = Study {
        years,
        seed,
        site: args.site.as_deref().map(Site::load).transpose()?,
        prices: args.prices.as_deref().map(Prices::load).transpose()?,
        costs: args.costs.as_deref().map(Costs::load).transpose()?,
        survival: (args.survival)
            .map(|s| Survival::constant(s, "--survival"))
            .transpose()?,
        pruning: if args.no_pruning {
            Pruning::Off
        } else {
            Pruning::Regime
        },
    };
    study.check()?;
    Ok(study)
}
