//! `sylva lobes`: Fields' lobe-driven trees.

use crate::args::{LineView, LobesArgs, UpAxis};
use crate::shared::{draw_options, picture_of, print_written, save_picture};
use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use sylva::drawing::{MeshLook, Meshable, plan, write_outputs};
use sylva::export::{Materials, write_atomically};
use sylva::fields::points::Up;
use sylva::fields::{Lobe, TreeFile, TreeRules};
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva_render::{View, ViewKind};

fn rules_for(name: &str) -> Result<TreeRules> {
    if let Some(r) = sylva::fields::builtin(name) {
        return Ok(r);
    }
    let path = Path::new(name);
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
    {
        let text = std::fs::read_to_string(path).with_context(|| format!("cannot read {name}"))?;
        return Ok(sylva::fields::from_toml(&text, name)?);
    }
    let known: Vec<&str> = sylva::fields::rules::builtin_names().collect();
    bail!(
        "no lobe species `{name}` and no such rules file; built in: {}",
        known.join(", ")
    )
}

fn parse_lobe(text: &str) -> Result<Lobe> {
    let v: Vec<f32> = text
        .split(',')
        .map(|s| s.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .ok()
        .filter(|v: &Vec<f32>| v.len() == 4 && v.iter().all(|x| x.is_finite()))
        .with_context(|| format!("--lobe {text}: expected X,Y,Z,R in metres"))?;
    if v[3] <= 0.0 || v[2] - v[3] < -1e-6 {
        bail!("--lobe {text}: the radius must be positive and the lobe above the ground");
    }
    Ok(Lobe {
        centre: glam::Vec3::new(v[0], v[1], v[2]),
        radius: v[3],
    })
}

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
    let is_tree_file = Path::new(&args.input)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tree"));
    let (rules, seed, placement, source) = if is_tree_file {
        if args.points.is_some() || !args.lobes.is_empty() {
            bail!(
                "{}: a .tree file brings its own trunk and lobes; leave out --points and --lobe",
                args.input
            );
        }
        let text = std::fs::read_to_string(&args.input)
            .with_context(|| format!("cannot read {}", args.input))?;
        let file = TreeFile::parse(&text, &args.input)?;
        let kind = file.tree_type.trim();
        let rules = match sylva::fields::builtin(kind) {
            Some(r) => r,
            None => rules_for(kind).with_context(|| {
                format!(
                    "{}: tree type `{kind}` is neither a built-in lobe species nor a rules file",
                    args.input
                )
            })?,
        };
        let seed = args.seed.unwrap_or(file.seed as u64);
        (
            rules,
            seed,
            file.placement(),
            "from the .tree file".to_string(),
        )
    } else {
        let rules = rules_for(&args.input)?;
        let seed = args.seed.unwrap_or(0);
        if let Some(cloud) = &args.points {
            if !args.lobes.is_empty() {
                bail!("--points and --lobe: choose one way of placing lobes");
            }
            if args.fit_lobes.is_some_and(|k| !(1..=32).contains(&k)) {
                bail!("--fit-lobes {}: expected 1..32", args.fit_lobes.unwrap());
            }
            let name = cloud.display().to_string();
            let bytes = std::fs::read(cloud).with_context(|| format!("cannot read {name}"))?;
            let up = match args.up {
                UpAxis::Z => Up::Z,
                UpAxis::Y => Up::Y,
            };
            let points = sylva::fields::points::read_points(&name, &bytes, up)?;
            let fit = sylva::fields::points::fit(&points, args.fit_lobes, seed);
            let cover = sylva::fields::points::coverage(&fit.canopy, &fit.placement.lobes);
            let note = format!(
                "fitted to {} points: crown base {:.2} m, {} lobes holding {:.0}% of the canopy's points",
                points.len(),
                fit.crown_base,
                fit.placement.lobes.len(),
                100.0 * cover
            );
            (rules, seed, fit.placement, note)
        } else if args.lobes.is_empty() {
            let p = sylva::fields::auto_placement(&rules, seed);
            (rules, seed, p, "placed automatically".to_string())
        } else {
            let lobes = args
                .lobes
                .iter()
                .map(|l| parse_lobe(l))
                .collect::<Result<Vec<_>>>()?;
            let p = sylva::fields::placement_for_lobes(&rules, seed, lobes);
            (rules, seed, p, "lobes as given".to_string())
        }
    };
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
        Some(m) => Meshable::Mesh(m),
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
