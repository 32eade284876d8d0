//! `sylva bench`: how fast trees are generated, meshed, chosen for range and drawn, each
//! figure beside a baseline timed in the same run (these machines are shared and noisy).
//! `--forest`, `--throughput` and `--growth` are in `forest.rs` and `growth.rs` beside this.

mod forest;
mod growth;

use crate::args::BenchArgs;
use crate::shared::headless;
use anyhow::{Context, Result};
use std::time::Instant;
use sylva::GenerateOptions;
use sylva::bench::{APPENDIX_SPECIES, edit_ms, fastest_ms, generate_times, lod_times};
use sylva::lod::Viewer;
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};

pub fn run(args: &BenchArgs) -> Result<()> {
    let runs = args.runs.max(1);
    println!(
        "{:<15} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8} {:>7}",
        "species", "triangles", "cold ms", "gen ms", "mesh ms", "warm ms", "Mtri/s", "x copy"
    );
    let mut tupelo_ms = None;
    for id in APPENDIX_SPECIES {
        let params = sylva::species::builtin(id).context("built-in species")?;
        let t = generate_times(&params, runs)?;
        let warm = t.warm_ms();
        if id == "black_tupelo" {
            tupelo_ms = Some(warm);
        }
        println!(
            "{:<15} {:>9} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>8.1} {:>7.1}",
            id,
            t.triangles,
            t.cold_ms,
            t.generate_ms,
            t.mesh_ms,
            warm,
            t.triangles as f64 / warm / 1e3,
            warm / t.copy_ms
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
        forest::bench_forest(runs.min(3))?;
    }
    if let Some(n) = args.throughput {
        forest::bench_throughput(n)?;
    }
    if args.growth {
        growth::bench_growth(runs.min(3))?;
    }
    Ok(())
}

/// Range degradation (Weber & Penn section 5) for the Black Tupelo: what a frame draws at each
/// range, what choosing that costs, and what the stored lists weigh.
fn bench_lod() -> Result<()> {
    let params = sylva::species::builtin("black_tupelo").context("built-in species")?;
    let skeleton = sylva::generate(&params, &GenerateOptions::default())?;
    let viewer = Viewer {
        image_height: 1000.0,
        fov_y: 60.0,
        quality: 1.0,
    };
    let (lod, times) = lod_times(&skeleton, &MeshOptions::for_species(&params, 1.0), &viewer);
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
    println!(
        "LOD selection: {:.0} ns per tree per frame (target: under 1000 ns); lists built in {:.1} ms",
        times.select_ns, times.build_ms,
    );
    println!(
        "stored for range: {:.3} MB per tree (packed segments and leaf cards; target: at most 1 MB), x{:.1} smaller than its full mesh ({:.1} MB, same run)",
        times.stored_bytes as f64 / 1e6,
        times.mesh_bytes as f64 / times.stored_bytes.max(1) as f64,
        times.mesh_bytes as f64 / 1e6,
    );
    Ok(())
}

/// Frame times at 1280x720 and the cost of an edit: what the viewer feels.
fn bench_render(runs: u32) -> Result<()> {
    use sylva_render::{Scene, View, ViewKind};
    let renderer = headless()?;
    let view = View::named(ViewKind::Front);
    // Baseline in the same run: a frame of an empty tree (ground, person, shadow pass, readback).
    let empty = renderer.upload(&TreeMesh::default());
    let empty_scene = Scene::new(&empty, [0.5; 3], [0.5; 3]);
    let base = fastest_ms(runs, || {
        renderer.render(&empty_scene, &view, 1280, 720).map(drop)
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
            &MeshOptions::for_species(&params, 1.0),
        );
        let t = Instant::now();
        let tree = renderer.upload(&mesh);
        let upload = t.elapsed().as_secs_f64() * 1e3;
        let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
        let frame = fastest_ms(runs, || renderer.render(&scene, &view, 1280, 720).map(drop))?;
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
    let params = sylva::species::builtin("black_tupelo").context("built-in species")?;
    let edit = edit_ms(&params, runs)?;
    println!(
        "black_tupelo: 1DownAngle changed, regenerated and re-meshed in {edit:.1} ms (target: under 50 ms)"
    );
    Ok(())
}
