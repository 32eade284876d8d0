//! `sylva forest`: many trees of several species on a plot, grown in parallel and written as
//! one GLB in which every tree is a node referring to its variant's mesh. The planting and
//! growing here also serve `sylva render forest.toml` and the viewer.

use crate::args::ForestArgs;
use crate::shared::{load_params, mesh_options};
use anyhow::{Context, Result, bail};
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;
use sylva::export::{Instance, Materials, to_glb_scene, write_atomically};
use sylva::forest::{ForestSpec, Planting, plant};
use sylva::mesh::{TreeMesh, mesh_tree};
use sylva::{GenerateOptions, Skeleton, TreeParams};

fn parse_area(text: &str) -> Result<[f32; 2]> {
    let (w, d) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--area {text}: expected WIDTHxDEPTH in metres, e.g. 200x100"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f32>()
            .with_context(|| format!("--area {text}: `{v}` is not a number of metres"))
    };
    Ok([parse(w)?, parse(d)?])
}

/// A forest file: a `[forest]` table with the fields of [`ForestSpec`].
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ForestFile {
    forest: ForestSpec,
}

/// Whether `path` is a forest file (a TOML file with a `[forest]` table) rather than a species.
pub fn is_forest_file(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        && std::fs::read_to_string(path)
            .ok()
            .and_then(|t| t.parse::<toml::Table>().ok())
            .is_some_and(|t| t.contains_key("forest"))
}

/// Reads a forest file; species files named in it are found relative to it.
pub fn read_forest_file(path: &Path) -> Result<ForestSpec> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    let file: ForestFile =
        toml::from_str(&text).with_context(|| format!("{}: not a forest file", path.display()))?;
    let mut spec = file.forest;
    let dir = path.parent().unwrap_or(Path::new("."));
    for s in &mut spec.species {
        if s.ends_with(".toml") || s.ends_with(".xml") {
            *s = dir.join(&*s).to_string_lossy().into_owned();
        }
    }
    spec.validate()
        .map_err(|e| anyhow::anyhow!("{}: [forest] {e}", path.display()))?;
    Ok(spec)
}

/// A planted forest with its variants grown into `T`s (meshes, or trees stored for range).
pub struct Forest<T> {
    pub species: Vec<TreeParams>,
    pub planting: Planting,
    pub grown: Vec<T>,
    /// Wall-clock seconds spent growing.
    pub seconds: f64,
}

/// The most bytes the distinct trees of one forest may hold: a GLB cannot exceed 4 GiB, and a
/// forest drawn on the GPU should leave room for the rest of the machine.
pub const MAX_FOREST_BYTES: usize = 3_500_000_000;

/// Plants `spec` and grows every variant in parallel (with a progress bar on a terminal),
/// turning each skeleton into a `T` with `build`, which also says how many bytes it holds.
/// Stops with an error when the trees would hold more than [`MAX_FOREST_BYTES`].
pub fn grow<T: Send>(
    spec: &ForestSpec,
    build: impl Fn(&TreeParams, &Skeleton) -> (T, usize) + Sync + Send,
) -> Result<Forest<T>> {
    spec.validate()
        .map_err(|e| anyhow::anyhow!("forest: {e}"))?;
    let species: Vec<TreeParams> = spec
        .species
        .iter()
        .map(|s| load_params(s, &[]))
        .collect::<Result<_>>()?;
    let planting = plant(spec);
    let bar =
        indicatif::ProgressBar::new(planting.variants.len() as u64).with_message("growing trees");
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} [{elapsed}<{eta}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let t = Instant::now();
    let held = std::sync::atomic::AtomicUsize::new(0);
    let over_budget = || {
        anyhow::anyhow!(
            "forest: its {} distinct trees would hold more than {:.1} GB (after {} trees); use \
             fewer --variants or a lower --quality",
            planting.variants.len(),
            MAX_FOREST_BYTES as f64 / 1e9,
            bar.position()
        )
    };
    let grown = planting
        .variants
        .par_iter()
        // One skeleton buffer per worker, reused tree after tree: a fresh one per tree costs
        // more in page faults and regrowth than generating into a warm one.
        .map_init(Skeleton::default, |skeleton, v| {
            if held.load(std::sync::atomic::Ordering::Relaxed) > MAX_FOREST_BYTES {
                return Err(over_budget());
            }
            let params = &species[v.species];
            let options = GenerateOptions {
                seed: v.seed,
                quality: spec.quality,
                ..Default::default()
            };
            sylva::generate_into(params, &options, skeleton)
                .with_context(|| format!("growing {} (seed {})", params.name, v.seed))?;
            let (made, bytes) = build(params, skeleton);
            if held.fetch_add(bytes, std::sync::atomic::Ordering::Relaxed) + bytes
                > MAX_FOREST_BYTES
            {
                return Err(over_budget());
            }
            bar.inc(1);
            Ok(made)
        })
        .collect::<Result<Vec<T>>>()?;
    bar.finish_and_clear();
    Ok(Forest {
        species,
        planting,
        grown,
        seconds: t.elapsed().as_secs_f64(),
    })
}

fn spec_of(args: &ForestArgs) -> Result<ForestSpec> {
    if let Some(file) = &args.file {
        return read_forest_file(file);
    }
    let spec = ForestSpec {
        species: args.species.clone(),
        count: args.count,
        area: parse_area(&args.area)?,
        seed: args.seed,
        variants: args.variants,
        quality: args.quality,
    };
    spec.validate().map_err(|e| anyhow::anyhow!("--{e}"))?;
    Ok(spec)
}

pub fn forest(args: &ForestArgs) -> Result<()> {
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"))
    {
        bail!(
            "output {}: a forest is written as GLB; use a .glb file name",
            args.output.display()
        );
    }
    let spec = spec_of(args)?;
    let quality = spec.quality;
    let forest = grow(&spec, |params, skeleton| {
        let mesh = mesh_tree(skeleton, &mesh_options(params, quality));
        // Position, normal and texture coordinate per vertex, and the triangles, in the GLB.
        let bytes = mesh.vertex_count() * 32 + mesh.triangle_count() * 12;
        (mesh, bytes)
    })
    .with_context(|| match &args.file {
        Some(f) => f.display().to_string(),
        None => "sylva forest".into(),
    })?;
    let (planting, meshes) = (&forest.planting, &forest.grown);
    let names: Vec<&str> = planting
        .variants
        .iter()
        .map(|v| forest.species[v.species].name.as_str())
        .collect();
    let scene: Vec<(&str, &TreeMesh, Materials)> = planting
        .variants
        .iter()
        .zip(meshes)
        .zip(&names)
        .map(|((v, m), n)| {
            let s = &forest.species[v.species];
            (*n, m, Materials::from_srgb(s.bark_color, s.leaf_color))
        })
        .collect();
    let instances: Vec<Instance> = planting
        .trees
        .iter()
        .map(|t| Instance {
            mesh: t.variant,
            position: t.position,
            turn: t.turn,
            scale: t.scale,
        })
        .collect();
    let bytes = to_glb_scene(&scene, &instances)?;
    write_atomically(&args.output, &bytes)?;
    let stored: usize = meshes.iter().map(TreeMesh::triangle_count).sum();
    let placed: usize = instances
        .iter()
        .map(|i| meshes[i.mesh].triangle_count())
        .sum();
    let count = planting.trees.len();
    let per_second = planting.variants.len() as f64 / forest.seconds;
    if args.json {
        println!(
            "{}",
            serde_json::json!({
                "trees": count,
                "variants": planting.variants.len(),
                "triangles_stored": stored,
                "triangles_placed": placed,
                "grow_ms": (forest.seconds * 1e3).round(),
                "trees_per_second": (per_second * 10.0).round() / 10.0,
                "threads": rayon::current_num_threads(),
                "output": args.output.display().to_string(),
            })
        );
    } else {
        println!(
            "{count} trees ({} distinct) on {}x{} m: {stored} triangles stored, {placed} placed",
            planting.variants.len(),
            spec.area[0],
            spec.area[1]
        );
        println!(
            "  grown in {:.1} s on {} threads ({per_second:.1} trees/s); wrote {}",
            forest.seconds,
            rayon::current_num_threads(),
            args.output.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn areas_and_forest_files() {
        assert!(parse_area("10x").is_err());
        assert_eq!(parse_area("20x30").unwrap(), [20.0, 30.0]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.toml");
        std::fs::write(
            &path,
            "[forest]\nspecies = [\"quaking_aspen\", \"mine.toml\"]\ncount = 12\narea = [30, 20]\n",
        )
        .unwrap();
        assert!(is_forest_file(&path));
        let spec = read_forest_file(&path).unwrap();
        assert_eq!(spec.count, 12);
        assert_eq!(spec.variants, 4);
        assert!(spec.species[1].ends_with("mine.toml") && spec.species[1].len() > 9);
        std::fs::write(
            &path,
            "[forest]\nspecies = [\"quaking_aspen\"]\ncount = 0\n",
        )
        .unwrap();
        let e = read_forest_file(&path).unwrap_err().to_string();
        assert!(e.contains("f.toml") && e.contains("count"), "{e}");
        std::fs::write(&path, "[forest]\nspecies = [\"a\"]\ncolour = 3\n").unwrap();
        assert!(read_forest_file(&path).is_err());
    }
}
