//! `sylva lobes`: Fields' lobe-driven trees.

use crate::args::{LineView, LobesArgs, UpAxis};
use crate::shared::{draw_options, picture_of, print_written, save_picture};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use sylva::drawing::{MeshLook, Meshable, plan, write_outputs};
use sylva::export::{Materials, write_atomically};
use sylva::fields::TreeFile;
use sylva::fields::points::Up;
use sylva::fields::source::{Lobes, Planted, parse_lobe};
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva_render::{View, ViewKind};

fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

pub fn run(args: &LobesArgs) -> Result<()> {
    // `.tree` files and rendered `.png` pictures are written here; the rest by extension as
    // for every line-drawable tree.
    let (tree_outputs, others): (Vec<PathBuf>, Vec<PathBuf>) = args
        .out
        .outputs
        .iter()
        .cloned()
        .partition(|p| has_extension(p, "tree"));
    let (pictures, others): (Vec<PathBuf>, Vec<PathBuf>) =
        others.into_iter().partition(|p| has_extension(p, "png"));
    let planned = plan(&others)?;
    for p in tree_outputs.iter().chain(&pictures) {
        if p.is_dir() {
            bail!("output {}: is a folder; give a file name", p.display());
        }
    }
    let camera = picture_view(args, !pictures.is_empty())?;
    if !(args.scale.is_finite() && args.scale > 0.0 && args.scale <= 100.0) {
        bail!("--scale {}: expected more than 0, at most 100", args.scale);
    }
    let planted = if has_extension(Path::new(&args.input), "tree") {
        if args.points.is_some() || !args.lobes.is_empty() {
            bail!(
                "{}: a .tree file brings its own trunk and lobes; leave out --points and --lobe",
                args.input
            );
        }
        let text = std::fs::read_to_string(&args.input)
            .with_context(|| format!("cannot read {}", args.input))?;
        Planted::from_tree_file(&args.input, &text, args.seed)?
    } else if let Some(cloud) = &args.points {
        if !args.lobes.is_empty() {
            bail!("--points and --lobe: choose one way of placing lobes");
        }
        let name = cloud.display().to_string();
        let bytes = std::fs::read(cloud).with_context(|| format!("cannot read {name}"))?;
        let up = match args.up {
            UpAxis::Z => Up::Z,
            UpAxis::Y => Up::Y,
        };
        let lobes = Lobes::Points {
            name: &name,
            bytes: &bytes,
            up,
            count: args.fit_lobes,
        };
        Planted::new(&args.input, lobes, args.seed)?
    } else if args.lobes.is_empty() {
        Planted::new(&args.input, Lobes::Automatic, args.seed)?
    } else {
        let lobes = (args.lobes.iter())
            .map(|l| parse_lobe(l))
            .collect::<Result<Vec<_>, _>>()?;
        Planted::new(&args.input, Lobes::Given(lobes), args.seed)?
    };
    let Planted {
        rules,
        seed,
        placement,
        source,
    } = planted;
    let sides = match args.tessellation {
        Some(t) if !(3..=64).contains(&t) => bail!("--tessellation {t}: expected 3..64 sides"),
        Some(t) => t,
        None => rules.tessellation,
    };
    // Budgets hit while growing depend on the lobes: say which input brought them.
    let from = match &args.points {
        Some(cloud) => format!("{} fitted to {}", args.input, cloud.display()),
        None => args.input.clone(),
    };
    let tree =
        sylva::fields::grow(&rules, seed, &placement).with_context(|| format!("growing {from}"))?;
    let mut skeleton = tree.skeleton();
    skeleton.scale(args.scale as f32);
    let look = MeshLook {
        options: MeshOptions {
            sides: Some(sides),
            ..Default::default()
        },
        materials: Materials::from_srgb(sylva::fields::BARK_COLOR, rules.leaf_texture.color),
    };
    let options = draw_options(&args.out);
    // A picture needs the mesh too: make it once for the picture and any mesh file.
    let meshed = (!pictures.is_empty()).then(|| mesh_tree(&skeleton, &look.options));
    let mesh = match &meshed {
        Some(m) => Meshable::Mesh(&skeleton, m),
        None => Meshable::Skeleton(&skeleton),
    };
    let mut written = write_outputs(&planned, &options, &skeleton, mesh, &rules.name, &look)?;
    if let (Some(mesh), Some((view, width, height))) = (&meshed, camera) {
        let colours = (sylva::fields::BARK_COLOR, rules.leaf_texture.color);
        let picture = picture_of(mesh, colours, &view, (width, height))?;
        for path in &pictures {
            save_picture(path, &picture)?;
            written.push(format!(
                "{} (rendered, {width}x{height}, {} triangles)",
                path.display(),
                mesh.triangle_count()
            ));
        }
    }
    for path in &tree_outputs {
        let scaled = placement.scaled(args.scale as f32);
        let file = TreeFile::from_placement(&rules.name, seed as i64, &scaled);
        write_atomically(path, file.to_text().as_bytes())?;
        written.push(format!(
            "{} (.tree: {} trunk branches, {} lobes)",
            path.display(),
            file.branches.len(),
            file.lobes.len()
        ));
    }
    let stats = skeleton.stats();
    println!(
        "{} (seed {seed}), {source}: {} lobes, {} stems, {} leaves, {:.2} m tall, crown {:.2} m across",
        rules.name,
        tree.lobes.len(),
        skeleton.stems.len(),
        skeleton.leaves.len(),
        stats.height,
        stats.crown_width
    );
    print_written(written);
    Ok(())
}

/// The camera and size of rendered `.png` outputs (`None` without any): `--view` as the line
/// drawings read it, perspective drawn from the renderer's raised corner view, and `--size`,
/// else the size `generate --preview` draws.
fn picture_view(args: &LobesArgs, wanted: bool) -> Result<Option<(View, u32, u32)>> {
    if !wanted {
        return Ok(None);
    }
    let kind = match args.out.view {
        LineView::Front => ViewKind::Front,
        LineView::Side => ViewKind::Side,
        LineView::Top => ViewKind::Top,
        LineView::Perspective => ViewKind::Iso,
        LineView::Overlay => bail!(
            "--view overlay is a line drawing: write it as .svg (a .png from `lobes` is rendered)"
        ),
    };
    let (width, height) = args.out.size.unwrap_or((1024, 768));
    if width > 8192 || height > 8192 {
        bail!("--size {width}x{height}: a rendered picture is at most 8192 pixels a side");
    }
    Ok(Some((View::named(kind), width, height)))
}
