//! `sylva bench`: how fast trees are generated, meshed, chosen for range and drawn, each
//! figure beside a baseline timed in the same run (these machines are shared and noisy).
//! `--forest`, `--throughput` and `--growth` are in `forest.rs` and `growth.rs` beside this.

mod city;
mod forest;
mod growth;

use crate::args::BenchArgs;
use crate::shared::headless;
use anyhow::{Context, Result};
use sylva::GenerateOptions;
use sylva::bench::{APPENDIX_SPECIES, edit_ms, generate_times, lod_times};
use sylva::lod::Viewer;
use sylva::mesh::{MeshOptions, mesh_tree};

pub fn run(args: &BenchArgs) -> Result<()> {
    // The README's build (dev profile) optimises the engine but not the GPU, window and HTTP
    // stacks, and checks overflow: figures to quote come from `--release`.
    if cfg!(debug_assertions) {
        eprintln!(
            "note: this sylva is the dev build (`cargo run`); for figures to compare or quote, \
             run `cargo run --release --bin sylva -- bench`"
        );
    }
    let runs = args.runs.max(1);
    let threads = rayon::current_num_threads();
    println!(
        "{:<15} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8} {:>7} {:>9} {:>6}",
        "species",
        "triangles",
        "cold ms",
        "gen ms",
        "mesh ms",
        "warm ms",
        "Mtri/s",
        "x copy",
        "1-thr ms",
        "x thr"
    );
    let mut tupelo = None;
    for id in APPENDIX_SPECIES {
        let params = sylva::species::builtin(id).context("built-in species")?;
        let t = generate_times(&params, runs)?;
        let warm = t.warm_ms();
        if id == "black_tupelo" {
            tupelo = Some((params.clone(), warm));
        }
        let one = t.one_thread_ms.unwrap_or(f64::NAN);
        println!(
            "{:<15} {:>9} {:>9.2} {:>9.2} {:>9.2} {:>9.2} {:>8.1} {:>7.1} {:>9.2} {:>6.2}",
            id,
            t.triangles,
            t.cold_ms,
            t.generate_ms,
            t.mesh_ms,
            warm,
            t.triangles as f64 / warm / 1e3,
            warm / t.copy_ms,
            one,
            one / warm
        );
    }
    println!(
        "fastest of {runs} runs on {threads} threads (a tree's main branches grow apart; bark and \
         leaves mesh at once). cold: fresh buffers; gen/mesh/warm: buffers reused \
         (generate_into, mesh_tree_into); x copy: warm time / time to copy the finished mesh; \
         1-thr: warm on one thread, same run; x thr: its ratio to warm."
    );
    if let Some((params, ms)) = tupelo {
        println!("black_tupelo warm generate + mesh: {ms:.2} ms (target: at most 10 ms)");
        bench_writers(&params, runs)?;
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
        // The skeleton and mesh take milliseconds against the seconds spent growing the tree to
        // each size: ten tries of them cost nothing and steady the figure on a shared machine.
        growth::bench_growth(runs.max(10))?;
    }
    if args.street {
        growth::bench_street()?;
    }
    if args.twigs {
        growth::bench_twigs()?;
    }
    if let Some(n) = args.city {
        city::bench_city(n)?;
    }
    Ok(())
}

/// The OBJ and GLB writers on the Black Tupelo's mesh, each beside its baseline.
fn bench_writers(params: &sylva::TreeParams, runs: u32) -> Result<()> {
    let skeleton = sylva::generate(params, &GenerateOptions::default())?;
    let mesh = mesh_tree(&skeleton, &MeshOptions::for_species(params, 1.0));
    let w = sylva::bench::writer_times(&mesh, runs)?;
    let mb = |bytes: usize| bytes as f64 / 1e6;
    let rate = |bytes: usize, ms: f64| mb(bytes) / ms * 1e3;
    println!();
    println!(
        "writers, black_tupelo ({} vertices), into memory, fastest of {runs}:",
        mesh.vertex_count()
    );
    println!(
        "  OBJ {:.1} MB in {:.1} ms = {:.0} MB/s; plain fmt writer {:.1} MB in {:.1} ms: x{:.1} \
         faster, {:.0}% of its size",
        mb(w.obj_bytes),
        w.obj_ms,
        rate(w.obj_bytes, w.obj_ms),
        mb(w.plain_obj_bytes),
        w.plain_obj_ms,
        w.plain_obj_ms / w.obj_ms,
        100.0 * w.obj_bytes as f64 / w.plain_obj_bytes as f64
    );
    println!(
        "  GLB {:.1} MB in {:.1} ms = {:.0} MB/s; copying as many bytes: {:.1} ms ({:.0} MB/s), \
         x{:.2} of the writer's time",
        mb(w.glb_bytes),
        w.glb_ms,
        rate(w.glb_bytes, w.glb_ms),
        w.copy_ms,
        rate(w.glb_bytes, w.copy_ms),
        w.copy_ms / w.glb_ms
    );
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
    let renderer = headless()?;
    let (base, frames) = sylva_render::bench::species_frames(&renderer, runs)?;
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
    for f in frames {
        println!(
            "{:<15} {:>9} {:>10.1} {:>9.1} {:>9.1}",
            f.id,
            f.triangles,
            f.upload_ms,
            f.frame_ms,
            f.frame_ms / base
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
