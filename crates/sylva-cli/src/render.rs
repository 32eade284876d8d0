//! `sylva render`: pictures of a tree (a species, species file or GLB) with the renderer: one
//! view, a turntable contact sheet, or wind animation frames; and of a forest file, drawn with
//! the paper's range degradation, alone or side by side with full detail.

use crate::args::{LodMode, RenderArgs, parse_size};
use crate::shared::{database, grow_for_range, headless, load_params, save_picture};
use anyhow::{Context, Result, bail};
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::time::Instant;
use sylva::forest::{ForestSpec, is_forest_file};
use sylva::growth::dressed_mesh;
use sylva::growth::survey::report;
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};
use sylva::street::study::{Pruning, Spread, StreetTree, Study};
use sylva::{GenerateOptions, Wind};
use sylva_render::caption::{grouped, lod_comparison};
use sylva_render::glb_scene::{UploadedScene, read_glb_scene};
use sylva_render::{Camera, ForestOnGpu, Picture, Renderer, Scene, View};

/// `out.png` -> `out-0007.png`.
fn numbered(path: &Path, index: u32) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!("{stem}-{index:04}.png"))
}

/// The wind the flags ask for at `time`.
fn wind_at(args: &RenderArgs, time: f64) -> Result<Wind> {
    for (flag, v) in [("--wind", args.wind), ("--gust", args.gust)] {
        if !(v.is_finite() && v.abs() <= 1000.0) {
            bail!("{flag} {v}: expected a number from -1000 to 1000 (2 to 10 is a breeze)");
        }
    }
    if !(time.is_finite() && time.abs() <= 1e9) {
        bail!("--time {time}: expected seconds, a finite number");
    }
    Ok(Wind {
        speed: args.wind,
        gust: args.gust,
        time,
    })
}

/// The tree a species makes at a moment of the wind.
fn species_mesh(params: &sylva::TreeParams, args: &RenderArgs, time: f64) -> Result<TreeMesh> {
    let options = GenerateOptions {
        wind: wind_at(args, time)?,
        ..args.tree.options()
    };
    let skeleton =
        sylva::generate(params, &options).with_context(|| format!("species {}", args.input))?;
    Ok(mesh_tree(
        &skeleton,
        &MeshOptions::for_species(params, args.tree.quality),
    ))
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let (width, height) = parse_size(&args.size, 8192).map_err(anyhow::Error::msg)?;
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        bail!(
            "output {}: pictures are written as PNG; use a .png file name",
            args.output.display()
        );
    }
    if args.turntable == Some(0) || args.frames == Some(0) {
        bail!("--turntable and --frames need at least 1");
    }
    if !(1.0..=170.0).contains(&args.fov) {
        bail!("--fov {}: expected 1..170 degrees", args.fov);
    }
    if !(args.fps > 0.0 && args.fps <= 1000.0) {
        bail!("--fps {}: expected 0..1000", args.fps);
    }
    let is_glb = Path::new(&args.input)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if is_glb && (args.frames.is_some() || args.wind != 0.0 || args.gust != 0.0) {
        bail!("wind needs the species, not a finished .glb: render the species instead");
    }
    if let Some(age) = args.age {
        if is_glb || args.frames.is_some() || args.wind != 0.0 || args.gust != 0.0 {
            bail!(
                "--age grows a street tree of the database: give its species code or name (not a \
                 .glb), without wind"
            );
        }
        let (mesh, dress) = street_tree(args, age)?;
        let renderer = headless()?;
        let tree = renderer.upload(&mesh);
        let flowers = renderer.upload_flowers(&mesh);
        let flowers = flowers.as_ref().zip(dress.flowers);
        let scene = Scene::flowering(&tree, flowers, dress.bark, dress.leaves);
        let picture = draw(&renderer, args, scene, (width, height))?;
        return write_picture(&args.output, &picture, mesh.triangle_count(), &renderer);
    }
    let renderer = headless()?;
    if is_forest_file(Path::new(&args.input)) {
        return render_forest(args, &renderer, args.view.to_view(), (width, height));
    }
    // A GLB as it is; a species regenerated for each moment of the wind.
    if is_glb {
        let uploaded = UploadedScene::new(&renderer, read_glb_scene(Path::new(&args.input))?);
        let scene = uploaded.scene();
        let picture = draw(&renderer, args, scene, (width, height))?;
        return write_picture(&args.output, &picture, uploaded.triangles(), &renderer);
    }
    let params = load_params(&args.input, &args.tree.set)?;
    for frame in 0..args.frames.unwrap_or(1) {
        let time = args.time + frame as f64 / args.fps;
        let mesh = species_mesh(&params, args, time)?;
        let tree = renderer.upload(&mesh);
        let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
        let picture = draw(&renderer, args, scene, (width, height))?;
        let path = if args.frames.is_some() {
            numbered(&args.output, frame)
        } else {
            args.output.clone()
        };
        write_picture(&path, &picture, tree.triangles, &renderer)?;
    }
    Ok(())
}

/// The street tree `--age` asks for, grown from the database and dressed for `--season`.
fn street_tree(args: &RenderArgs, age: f64) -> Result<(TreeMesh, sylva::growth::Dress)> {
    let region = args.region.as_deref().unwrap_or("InlVal");
    let m = database(None)?.find(region, &args.input)?;
    let (first, last) = m.ages;
    if !(age.is_finite() && age >= first && age <= last.floor()) {
        bail!(
            "--age {age}: {} in {region} is grown from {first} to {} years (the ages its data \
             cover)",
            m.label(),
            last.floor()
        );
    }
    // Grown straight to its age, never cut, through the street's study pipeline.
    let study = Study {
        seed: args.tree.seed,
        pruning: Pruning::Off,
        ..Study::new(age)
    };
    let year = StreetTree::new(&m, &study).grow_to(age, Spread::Whole, |_, _, _, _| {});
    Ok(dressed_mesh(&year.skeleton, &m, args.season, &report::MESH))
}

/// One view of `scene`, or a turntable sheet of several, as the flags ask.
fn draw(
    renderer: &Renderer,
    args: &RenderArgs,
    mut scene: Scene,
    (width, height): (u32, u32),
) -> Result<Picture> {
    scene.show_leaves = !args.tree.no_leaves;
    scene.show_ground = !args.bare;
    scene.show_person = !args.bare;
    let mut base = args.view.to_view();
    base.fov_y = args.fov;
    Ok(match args.turntable {
        Some(n) => renderer.turntable(&scene, &base, n, (width, height))?,
        None => renderer.render(&scene, &base, width, height)?,
    })
}

fn write_picture(
    path: &Path,
    picture: &Picture,
    triangles: usize,
    renderer: &Renderer,
) -> Result<()> {
    save_picture(path, picture)?;
    println!(
        "wrote {} ({}x{}, {} triangles, {})",
        path.display(),
        picture.width,
        picture.height,
        triangles,
        renderer.adapter_name()
    );
    Ok(())
}

/// The camera a render asks for: an explicit eye, a range along the view's direction, or the
/// view framing the whole forest from no lower than 12 degrees.
fn forest_view(args: &RenderArgs, scene: &Scene, base: View) -> Result<View> {
    let (lo, hi) = scene.tree_bounds();
    let centre = Vec3::new(
        (lo.x + hi.x) / 2.0,
        (lo.y + hi.y) / 2.0,
        (hi.z - lo.z) / 3.0,
    );
    if let (Some(eye), Some(target)) = (&args.eye, &args.target) {
        if eye.len() != 3 || target.len() != 3 {
            bail!(
                "--eye and --target take three numbers each, X,Y,Z in metres, e.g. --eye 0,-80,2"
            );
        }
        let (eye, target) = (Vec3::from_slice(eye), Vec3::from_slice(target));
        if !eye.is_finite() || !target.is_finite() || eye.distance(target) < 1e-3 {
            bail!("--eye and --target must be finite and apart");
        }
        return Ok(View::look_at(eye, target, args.fov));
    }
    let elevation = base.elevation.max(12.0);
    if let Some(range) = args.range {
        if !(range.is_finite() && range > 0.5 && range <= 100_000.0) {
            bail!("--range {range}: expected 0.5..100000 metres");
        }
        let eye = centre + Camera::direction(base.azimuth, elevation) * range;
        return Ok(View::look_at(eye, centre, args.fov));
    }
    let mut view = View::orbit(base.azimuth, elevation);
    view.fov_y = args.fov;
    Ok(view)
}

fn render_forest(
    args: &RenderArgs,
    renderer: &Renderer,
    base: View,
    (width, height): (u32, u32),
) -> Result<()> {
    if args.frames.is_some() || args.turntable.is_some() {
        bail!("forests are rendered one picture at a time: leave out --frames and --turntable");
    }
    let wind = wind_at(args, args.time)?;
    let path = Path::new(&args.input);
    let spec = ForestSpec::from_file(path)?;
    let forest = grow_for_range(&spec).with_context(|| path.display().to_string())?;
    let forest = ForestOnGpu::upload(renderer, &forest);
    let mut scene = forest.scene();
    scene.show_leaves = !args.tree.no_leaves;
    scene.show_ground = !args.bare;
    scene.primitive_budget = (args.lod_budget > 0).then_some(args.lod_budget);
    // Each copy sways on the GPU, by its own phases, the same at every range.
    scene.wind = wind;
    let view = forest_view(args, &scene, base)?;
    let t = Instant::now();
    renderer.prepare(&scene)?;
    println!(
        "impostors baked in {:.0} ms",
        t.elapsed().as_secs_f64() * 1e3
    );
    let mut frame = |use_lod: bool| -> Result<(Picture, f64)> {
        scene.use_lod = use_lod;
        let t = Instant::now();
        let picture = renderer.render(&scene, &view, width, height)?;
        Ok((picture, t.elapsed().as_secs_f64() * 1e3))
    };
    let picture = match args.lod {
        LodMode::On | LodMode::Off => {
            let (p, ms) = frame(args.lod == LodMode::On)?;
            println!("{}", p.stats.describe(ms));
            p
        }
        LodMode::Compare => {
            let (with, with_ms) = frame(true)?;
            let (without, without_ms) = frame(false)?;
            println!("with LOD:    {}", with.stats.describe(with_ms));
            println!("without LOD: {}", without.stats.describe(without_ms));
            if let Some(d) = with.mean_difference(&without) {
                println!(
                    "mean pixel difference: {d:.2} of 255 per channel; with LOD x{:.1} fewer primitives, x{:.1} faster",
                    without.stats.primitives() as f64 / with.stats.primitives().max(1) as f64,
                    without_ms / with_ms.max(1e-3)
                );
            }
            lod_comparison((&with, with_ms), (&without, without_ms), width)
        }
    };
    save_picture(&args.output, &picture)?;
    println!(
        "wrote {} ({}x{}; {} trees of {} variants grown in {:.1} s, {:.1} MB stored; {})",
        args.output.display(),
        picture.width,
        picture.height,
        grouped(forest.placements.iter().map(Vec::len).sum()),
        forest.trees.len(),
        forest.grow_seconds,
        forest.stored_bytes as f64 / 1e6,
        renderer.adapter_name()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_names() {
        assert_eq!(parse_size("1280x720", 8192).unwrap(), (1280, 720));
        assert!(parse_size("12x720", 8192).is_err());
        assert!(parse_size("9000x720", 8192).is_err());
        assert!(parse_size("wide", 8192).is_err());
        assert_eq!(
            numbered(Path::new("dir/sway.png"), 3),
            PathBuf::from("dir/sway-0003.png")
        );
    }
}
