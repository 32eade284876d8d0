//! `sylva bench --forest` and `--throughput`: what range degradation saves when drawing a tree
//! and a forest, what a stand of Fields' firs costs with and without leaves, and how fast
//! unique trees grow.

use crate::shared::{grow_for_range, headless, with_progress};
use anyhow::{Context, Result};
use glam::Vec3;
use std::time::Instant;
use sylva::GenerateOptions;
use sylva::bench::APPENDIX_SPECIES;
use sylva::forest::ForestSpec;
use sylva::lod::LodTree;
use sylva::mesh::MeshOptions;
use sylva_render::bench::{FOV, SIZE, empty_frame_ms, range_frames, stand_frames};
use sylva_render::caption::grouped;
use sylva_render::{ForestOnGpu, Renderer, Scene};

/// Frames of `scene` from each range along a low view towards `target`, with and without LOD.
fn table(renderer: &Renderer, scene: &mut Scene, target: Vec3, runs: u32) -> Result<()> {
    println!(
        "{:>8} {:>13} {:>10} {:>10} {:>9} | {:>13} {:>9} | {:>8}",
        "range m", "LOD prims", "lines", "points", "frame ms", "full prims", "frame ms", "x faster"
    );
    for f in range_frames(renderer, scene, target, runs)? {
        let ((lod, lod_ms), (full, full_ms)) = (f.lod, f.full);
        println!(
            "{:>8} {:>13} {:>10} {:>10} {:>9.1} | {:>13} {:>9.1} | {:>8.1}",
            f.range,
            grouped(lod.primitives()),
            grouped(lod.lines),
            grouped(lod.points),
            lod_ms,
            grouped(full.primitives()),
            full_ms,
            full_ms / lod_ms
        );
    }
    Ok(())
}

pub fn bench_forest(runs: u32) -> Result<()> {
    let renderer = headless()?;
    println!();
    println!(
        "drawing with and without range degradation on {} ({}x{}, {FOV} degree lens; frames \
         include shadow pass and read-back; x faster = full / LOD frame time)",
        renderer.adapter_name(),
        SIZE.0,
        SIZE.1
    );
    // Baseline in the same run: an empty scene.
    let base = empty_frame_ms(&renderer, runs)?;
    println!("empty frame (ground, shadow pass, read-back): {base:.1} ms");
    fir_stand(&renderer, runs, base)?;

    let params = sylva::species::builtin("black_tupelo").context("built-in species")?;
    let skeleton = sylva::generate(&params, &GenerateOptions::default())?;
    let lod = LodTree::build(&skeleton, &MeshOptions::for_species(&params, 1.0));
    let tree = renderer.upload_lod(&lod);
    let mut scene = Scene::new(&tree, params.bark_color, params.leaf_color);
    scene.show_person = false;
    println!();
    println!(
        "black_tupelo, {} triangles, {:.1} MB stored for range",
        grouped(lod.triangle_count()),
        lod.heap_bytes() as f64 / 1e6
    );
    table(&renderer, &mut scene, Vec3::new(0.0, 0.0, 12.0), runs)?;
    drop(scene);
    drop(tree);

    // 1,000 trees of the four appendix species, four variants each.
    let spec = ForestSpec {
        species: APPENDIX_SPECIES.iter().map(|s| s.to_string()).collect(),
        count: 1000,
        area: [600.0, 600.0],
        seed: 1,
        variants: 4,
        quality: 0.5,
    };
    let forest = ForestOnGpu::upload(&renderer, &grow_for_range(&spec)?);
    let mut scene = forest.scene();
    let variants = forest.trees.len();
    let stored = forest.stored_bytes as f64 / 1e6;
    println!();
    println!(
        "mixed forest: 1,000 trees ({variants} variants of the 4 appendix species at quality 0.5) \
         on 600x600 m, {} triangles placed; grown in {:.1} s; {stored:.1} MB stored = {:.1} MB \
         per variant, {:.2} MB per tree placed",
        grouped(forest.triangles_placed),
        forest.grow_seconds,
        stored / variants as f64,
        stored / 1000.0
    );
    table(&renderer, &mut scene, Vec3::new(0.0, 0.0, 8.0), runs)?;
    Ok(())
}

/// Fields' forests (section 4.1): a stand of 100 lobe balsam firs, drawn with and without their
/// leaves, at full detail and with range degradation, against the empty frame of this run.
fn fir_stand(renderer: &Renderer, runs: u32, empty_ms: f64) -> Result<()> {
    let spec = ForestSpec {
        species: vec![format!("{}balsam_fir", sylva::forest::LOBES_PREFIX)],
        count: 100,
        area: [60.0, 60.0],
        seed: 2,
        variants: 4,
        quality: 0.5,
    };
    let forest = ForestOnGpu::upload(renderer, &grow_for_range(&spec)?);
    let mut scene = forest.scene();
    println!();
    println!(
        "100 Balsam Firs (Fields' lobe species, 4 variants at quality 0.5, 15 m tall) on 60x60 m, \
         {} triangles placed, seen whole from 70 m; x empty = frame / empty frame",
        grouped(forest.triangles_placed)
    );
    println!(
        "{:>12} {:>13} {:>9} {:>8}",
        "", "primitives", "frame ms", "x empty"
    );
    for (label, stats, ms) in stand_frames(renderer, &mut scene, runs)? {
        println!(
            "{label:>12} {:>13} {ms:>9.1} {:>8.1}",
            grouped(stats.primitives()),
            ms / empty_ms
        );
    }
    Ok(())
}

/// Grows `n` unique trees of the appendix species (quality 0.5, as `sylva forest`), each
/// stored for range and then released, on every core.
pub fn bench_throughput(n: u32) -> Result<()> {
    let spec = ForestSpec {
        species: APPENDIX_SPECIES.iter().map(|s| s.to_string()).collect(),
        count: n.max(1),
        area: [1000.0, 1000.0],
        seed: 7,
        variants: 0,
        quality: 0.5,
    };
    spec.validate()
        .map_err(|e| anyhow::anyhow!("--throughput: {e}"))?;
    // Each tree is stored for range and released at once: it holds nothing against the
    // forest's memory budget.
    let t = Instant::now();
    let species = spec.load_species()?;
    let variants = sylva::forest::plant(&spec).variants.len();
    let forest = with_progress(variants, |tick| {
        sylva::forest::grow(
            &spec,
            species,
            |species, skeleton| {
                let options = species.mesh_options(spec.quality);
                (LodTree::build(skeleton, &options).triangle_count(), 0)
            },
            tick,
        )
    })?;
    let s = t.elapsed().as_secs_f64();
    let triangles: usize = forest.grown.iter().sum();
    let planting = forest.planting;
    println!();
    println!(
        "{} unique trees of the appendix species (quality 0.5) grown and stored for range in \
         {s:.1} s on {} threads: {:.1} trees/s, {:.1} M triangles/s (target: 10,000 in under 60 s)",
        grouped(planting.variants.len()),
        rayon::current_num_threads(),
        planting.variants.len() as f64 / s,
        triangles as f64 / s / 1e6
    );
    Ok(())
}
