//! What each subcommand does: load and check inputs, call the library, write files, report.

use crate::args::{BenchArgs, Cli, Command, GenerateArgs, RenderView, SpeciesCommand};
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::time::Instant;
use sylva::export::{Materials, to_glb, write_atomically, write_obj};
use sylva::mesh::{TreeMesh, mesh_tree};
use sylva::params::{PARAMS, format_value};
use sylva::{GenerateOptions, TreeParams};

use crate::shared::{APPENDIX_SPECIES, fastest_ms, load_params, mesh_options};

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Generate(args) => generate(&args),
        Command::Species(SpeciesCommand::List) => species_list(),
        Command::Species(SpeciesCommand::Show { name, toml }) => species_show(&name, toml),
        Command::Render(args) => crate::render::render(&args),
        Command::View(args) => crate::viewer::run(&args),
        Command::Forest(args) => crate::forest::forest(&args),
        Command::Grow(args) => crate::grow::grow(&args),
        Command::Fractal(args) => crate::nagel::fractal(&args),
        Command::Whisk(args) => crate::nagel::whisk(&args),
        Command::Stick(args) => crate::nagel::stick(&args),
        Command::Draw(args) => crate::lines::draw(&args),
        Command::Lobes(args) => crate::lobes::lobes(&args),
        Command::Bench(args) => bench(&args),
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Glb,
    Obj,
}

fn output_format(path: &Path) -> Result<Format> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("glb") => Ok(Format::Glb),
        Some("obj") => Ok(Format::Obj),
        _ => bail!(
            "output {}: unknown format; use a .glb or .obj file name",
            path.display()
        ),
    }
}

fn generate(args: &GenerateArgs) -> Result<()> {
    let format = output_format(&args.output)?;
    if let Some(png) = &args.preview
        && !png
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        bail!(
            "--preview {}: the picture is written as PNG; use a .png file name",
            png.display()
        );
    }
    let params = load_params(&args.species, &args.tree.set)?;
    let options = GenerateOptions {
        max_triangles: args.max_triangles,
        ..args.tree.options()
    };
    if args.tree.levels == Some(0) {
        bail!("--levels 0: expected 1 (trunk only) or more");
    }
    let t0 = Instant::now();
    let skeleton =
        sylva::generate(&params, &options).with_context(|| format!("species {}", args.species))?;
    let generate_ms = t0.elapsed().as_secs_f64() * 1e3;
    let t1 = Instant::now();
    let mesh = mesh_tree(&skeleton, &mesh_options(&params, args.tree.quality));
    let mesh_ms = t1.elapsed().as_secs_f64() * 1e3;
    if mesh.triangle_count() as u64 > args.max_triangles {
        bail!(
            "the mesh has {} triangles, over the budget of {} (--max-triangles)",
            mesh.triangle_count(),
            args.max_triangles
        );
    }
    let materials = Materials::from_srgb(params.bark_color, params.leaf_color);
    match format {
        Format::Glb if args.lod_chain => {
            let lod =
                sylva::lod::LodTree::build(&skeleton, &mesh_options(&params, args.tree.quality));
            let levels = crate::lod_chain::write_lod_chain(&args.output, &lod, &params)?;
            if !args.json {
                println!("LOD chain: {levels}");
            }
        }
        Format::Glb => {
            let bytes = to_glb(&mesh, &params.name, &materials)?;
            write_atomically(&args.output, &bytes)?;
        }
        Format::Obj if args.lod_chain => {
            bail!("--lod-chain: LOD chains are written as GLB; use a .glb file name")
        }
        Format::Obj => write_obj(&args.output, &mesh, &params.name, &materials)?,
    }
    // The model and its summary come first: a picture that fails cannot take them away.
    let stats = skeleton.stats();
    if args.json {
        let summary = serde_json::json!({
            "species": params.name,
            "seed": args.tree.seed,
            "stems_per_level": stats.stems_per_level,
            "leaves": stats.leaves,
            "vertices": mesh.vertex_count(),
            "triangles": mesh.triangle_count(),
            "height_m": round3(stats.height),
            "crown_width_m": round3(stats.crown_width),
            "generate_ms": round3(generate_ms as f32),
            "mesh_ms": round3(mesh_ms as f32),
            "output": args.output.display().to_string(),
        });
        println!("{summary}");
    } else {
        print_summary(&params, args, &stats, &mesh, generate_ms, mesh_ms);
    }
    if let Some(png) = &args.preview {
        write_preview(png, &mesh, &params, args.view)?;
        if !args.json {
            println!("  picture          {}", png.display());
        }
    }
    Ok(())
}

fn write_preview(
    path: &Path,
    mesh: &TreeMesh,
    params: &TreeParams,
    view: RenderView,
) -> Result<()> {
    let picture =
        crate::render::picture(mesh, params.bark_color, params.leaf_color, view, 1024, 768)?;
    crate::shared::encode_png(path, picture.width, picture.height, &picture.rgba)
}

fn round3(x: f32) -> f64 {
    (x as f64 * 1000.0).round() / 1000.0
}

fn print_summary(
    params: &TreeParams,
    args: &GenerateArgs,
    stats: &sylva::SkeletonStats,
    mesh: &TreeMesh,
    generate_ms: f64,
    mesh_ms: f64,
) {
    let levels: Vec<String> = stats
        .stems_per_level
        .iter()
        .map(|n| n.to_string())
        .collect();
    println!("{} (seed {})", params.name, args.tree.seed);
    println!("  stems per level  {}", levels.join(" / "));
    println!("  leaves           {}", stats.leaves);
    println!("  height           {:.2} m", stats.height);
    println!("  crown width      {:.2} m", stats.crown_width);
    println!(
        "  mesh             {} vertices, {} triangles (bark {}, leaves {})",
        mesh.vertex_count(),
        mesh.triangle_count(),
        mesh.bark.triangle_count(),
        mesh.leaves.triangle_count()
    );
    println!("  time             generate {generate_ms:.1} ms, mesh {mesh_ms:.1} ms");
    println!("  wrote            {}", args.output.display());
}

fn species_list() -> Result<()> {
    for id in sylva::species::builtin_ids() {
        let p = sylva::species::builtin(id).context("built-in species")?;
        println!("{id:<18} {:<22} {}", p.name, p.description);
    }
    Ok(())
}

fn species_show(name: &str, toml: bool) -> Result<()> {
    let params = sylva::species::load(name)?;
    if toml {
        print!("{}", sylva::params::to_toml(&params));
        return Ok(());
    }
    println!("{}", params.name);
    if !params.description.is_empty() {
        println!("{}", params.description);
    }
    println!();
    println!(
        "{:<16} {:>9}  {:<13} {:<22} meaning",
        "parameter", "value", "unit", "range"
    );
    let row = |def: &sylva::params::ParamDef, level: usize| {
        println!(
            "{:<16} {:>9}  {:<13} {:<22} {}",
            def.name_at(level),
            format_value((def.get)(&params, level)),
            def.unit,
            def.range_text(),
            def.doc
        );
    };
    for def in PARAMS.iter().filter(|d| !d.per_level) {
        row(def, 0);
    }
    for level in 0..sylva::params::LEVEL_SETS {
        for def in PARAMS
            .iter()
            .filter(|d| d.per_level && d.levels().contains(&level))
        {
            row(def, level);
        }
    }
    Ok(())
}

fn bench(args: &BenchArgs) -> Result<()> {
    let runs = args.runs.max(1);
    println!(
        "{:<15} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8} {:>7}",
        "species", "triangles", "cold ms", "gen ms", "mesh ms", "warm ms", "Mtri/s", "x copy"
    );
    let mut tupelo_ms = None;
    for id in APPENDIX_SPECIES {
        let params = sylva::species::builtin(id).context("built-in species")?;
        let options = GenerateOptions::default();
        let mesh_opts = mesh_options(&params, 1.0);
        // Cold: fresh buffers every time, as a one-shot command line run.
        let cold = fastest_ms(runs, || {
            let skeleton = sylva::generate(&params, &options)?;
            std::hint::black_box(mesh_tree(&skeleton, &mesh_opts));
            Ok(())
        })?;
        // Warm: buffers reused across runs, as an editor regenerating on every change.
        let mut skeleton = sylva::Skeleton::default();
        let mut mesh = TreeMesh::default();
        let gen_ms = fastest_ms(runs, || {
            Ok(sylva::generate_into(&params, &options, &mut skeleton)?)
        })?;
        let mesh_ms = fastest_ms(runs, || {
            sylva::mesh::mesh_tree_into(&skeleton, &mesh_opts, &mut mesh);
            Ok(())
        })?;
        // Baseline, same run: copying the finished mesh's buffers into warm buffers.
        let mut copy = TreeMesh::default();
        let copy_ms = fastest_ms(runs, || {
            copy.clone_from(&mesh);
            Ok(())
        })?;
        let warm = gen_ms + mesh_ms;
        let triangles = mesh.triangle_count();
        if id == "black_tupelo" {
            tupelo_ms = Some(warm);
        }
        println!(
            "{:<15} {:>9} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>8.1} {:>7.1}",
            id,
            triangles,
            cold,
            gen_ms,
            mesh_ms,
            warm,
            triangles as f64 / warm / 1e3,
            warm / copy_ms
        );
    }
    println!(
        "fastest of {runs} runs, one thread. cold: fresh buffers; gen/mesh/warm: buffers reused \
         (generate_into, mesh_tree_into); x copy: warm time / time to copy the finished mesh."
    );
    if let Some(ms) = tupelo_ms {
        println!("black_tupelo warm generate + mesh: {ms:.2} ms (target: at most 20 ms)");
    }
    if args.render {
        bench_render(runs.min(5))?;
    }
    if args.lod {
        bench_lod()?;
    }
    if args.forest {
        crate::bench_forest::bench_forest(runs.min(3))?;
    }
    if let Some(n) = args.throughput {
        crate::bench_forest::bench_throughput(n)?;
    }
    if args.growth {
        crate::bench_growth::bench_growth(runs.min(3))?;
    }
    Ok(())
}

/// Range degradation (Weber & Penn section 5) for the Black Tupelo: what a frame draws at each
/// range, what choosing that costs, and what the stored lists weigh.
fn bench_lod() -> Result<()> {
    use sylva::lod::{LodTree, Viewer};
    let params = sylva::species::builtin("black_tupelo").context("built-in species")?;
    let skeleton = sylva::generate(&params, &GenerateOptions::default())?;
    let t = Instant::now();
    let lod = LodTree::build(&skeleton, &mesh_options(&params, 1.0));
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    let viewer = Viewer {
        image_height: 1000.0,
        fov_y: 60.0,
        quality: 1.0,
    };
    let full = lod.triangle_count();
    println!();
    println!(
        "range degradation, black_tupelo ({full} triangles), 1000-pixel picture, 60 degree lens"
    );
    println!(
        "{:>8} {:>10} {:>8} {:>8} {:>11} {:>9}",
        "range m", "triangles", "lines", "points", "primitives", "x full"
    );
    for range in [10.0, 30.0, 100.0, 300.0, 1000.0, 2000.0, 3000.0] {
        let c = lod.counts(range, &viewer);
        let total = c.triangles + c.lines + c.points;
        println!(
            "{:>8} {:>10} {:>8} {:>8} {:>11} {:>9.4}",
            range,
            c.triangles,
            c.lines,
            c.points,
            total,
            total as f64 / full as f64
        );
    }
    // Selection cost per tree and frame: ranges of a forest's worth of trees.
    let ranges: Vec<f32> = (0..100_000)
        .map(|i| 10.0 + (i as f32 * 7.31) % 3000.0)
        .collect();
    let mut best = f64::MAX;
    for _ in 0..5 {
        let t = Instant::now();
        let mut sink = 0u32;
        for &r in &ranges {
            let d = lod.select(r, &viewer);
            sink = sink.wrapping_add(d[0].triangles.end ^ d[3].points.end);
        }
        std::hint::black_box(sink);
        best = best.min(t.elapsed().as_secs_f64());
    }
    let per_tree_ns = best / ranges.len() as f64 * 1e9;
    let bytes: usize = lod
        .lists
        .iter()
        .map(|l| l.indices.len() * 4 + l.index_prefix.len() * 4 + l.points.len() * 12)
        .sum::<usize>()
        + lod.mesh.vertex_count() * 32;
    println!(
        "LOD selection: {per_tree_ns:.0} ns per tree per frame (target: under 1000 ns); lists built in {build_ms:.1} ms; {:.1} MB per tree (vertices + rank-major lists)",
        bytes as f64 / 1e6
    );
    Ok(())
}

/// Frame times at 1280x720 and the cost of an edit: what the viewer feels.
fn bench_render(runs: u32) -> Result<()> {
    use sylva_render::{Scene, View, ViewKind};
    let renderer = crate::render::headless()?;
    let view = View::named(ViewKind::Front);
    // Baseline in the same run: a frame of an empty tree (ground, person, shadow pass, readback).
    let empty = renderer.upload(&TreeMesh::default());
    let empty_scene = Scene::new(&empty, [0.5; 3], [0.5; 3]);
    let base = fastest_ms(runs, || {
        renderer.render(&empty_scene, &view, 1280, 720)?;
        Ok(())
    })?;
    println!();
    println!(
        "rendering on {} at 1280x720 (fastest of {runs}; frame includes read-back)",
        renderer.adapter_name()
    );
    println!(
        "{:<15} {:>9} {:>10} {:>9} {:>9}",
        "species", "triangles", "upload ms", "frame ms", "x empty"
    );
    println!(
        "{:<15} {:>9} {:>10} {:>9.1} {:>9.1}",
        "(empty)", 0, "-", base, 1.0
    );
    for id in APPENDIX_SPECIES {
        let params = sylva::species::builtin(id).context("built-in species")?;
        let mesh = mesh_tree(
            &sylva::generate(&params, &GenerateOptions::default())?,
            &mesh_options(&params, 1.0),
        );
        let t = Instant::now();
        let tree = renderer.upload(&mesh);
        let upload = t.elapsed().as_secs_f64() * 1e3;
        let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
        let frame = fastest_ms(runs, || {
            renderer.render(&scene, &view, 1280, 720)?;
            Ok(())
        })?;
        println!(
            "{:<15} {:>9} {:>10.1} {:>9.1} {:>9.1}",
            id,
            mesh.triangle_count(),
            upload,
            frame,
            frame / base
        );
    }
    // An edit in the editor: change one parameter, regenerate and re-mesh into warm buffers.
    let mut params = sylva::species::builtin("black_tupelo").context("built-in species")?;
    let options = GenerateOptions::default();
    let mesh_opts = mesh_options(&params, 1.0);
    let mut skeleton = sylva::Skeleton::default();
    let mut mesh = TreeMesh::default();
    sylva::generate_into(&params, &options, &mut skeleton)?;
    sylva::mesh::mesh_tree_into(&skeleton, &mesh_opts, &mut mesh);
    let mut angle = params.level[1].down_angle;
    let edit = fastest_ms(runs, || {
        angle = if angle > 60.0 { 55.0 } else { angle + 1.0 };
        params.level[1].down_angle = angle;
        sylva::generate_into(&params, &options, &mut skeleton)?;
        sylva::mesh::mesh_tree_into(&skeleton, &mesh_opts, &mut mesh);
        Ok(())
    })?;
    println!(
        "black_tupelo: 1DownAngle changed, regenerated and re-meshed in {edit:.1} ms (target: under 50 ms)"
    );
    Ok(())
}
