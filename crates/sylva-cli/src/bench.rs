//! `sylva bench`: how fast trees are generated, meshed, chosen for range and drawn, each
//! figure beside a baseline timed in the same run (these machines are shared and noisy).
//! `--forest`, `--throughput` and `--growth` are in `bench_forest.rs` and `bench_growth.rs`.

use crate::args::BenchArgs;
use crate::shared::{APPENDIX_SPECIES, fastest_ms, headless};
use anyhow::{Context, Result};
use std::time::Instant;
use sylva::GenerateOptions;
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
        let options = GenerateOptions::default();
        let mesh_opts = MeshOptions::for_species(&params, 1.0);
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
    let lod = LodTree::build(&skeleton, &MeshOptions::for_species(&params, 1.0));
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
    let renderer = headless()?;
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
            &MeshOptions::for_species(&params, 1.0),
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
    let mesh_opts = MeshOptions::for_species(&params, 1.0);
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
