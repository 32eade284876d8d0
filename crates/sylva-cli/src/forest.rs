//! `sylva forest`: many trees of several species on a plot, generated in parallel and written
//! as one GLB in which every tree is a node referring to its variant's mesh.

use crate::args::ForestArgs;
use crate::commands::{load_params, mesh_options};
use anyhow::{Context, Result, bail};
use rayon::prelude::*;
use std::time::Instant;
use sylva::export::{Instance, Materials, to_glb_scene, write_atomically};
use sylva::mesh::{TreeMesh, mesh_tree};
use sylva::rng::StreamKey;
use sylva::{GenerateOptions, TreeParams};

/// The most trees one command plants.
const MAX_TREES: u32 = 100_000;

fn parse_area(text: &str) -> Result<(f32, f32)> {
    let (w, d) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--area {text}: expected WIDTHxDEPTH in metres, e.g. 200x100"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite() && *v > 0.0 && *v <= 100_000.0)
            .with_context(|| format!("--area {text}: sides must be 0..100000 m"))
    };
    Ok((parse(w)?, parse(d)?))
}

/// Positions on the plot, kept apart by dart throwing (a few tries each, then accepted anyway
/// so a crowded plot still gets all its trees).
fn place(count: usize, (w, d): (f32, f32), key: StreamKey) -> Vec<[f32; 2]> {
    let mut rng = key.child(1).stream();
    let spacing = (w * d / count.max(1) as f32).sqrt() * 0.6;
    let mut cells: std::collections::HashMap<(i64, i64), Vec<[f32; 2]>> = Default::default();
    let cell = |p: [f32; 2]| {
        (
            (p[0] / spacing).floor() as i64,
            (p[1] / spacing).floor() as i64,
        )
    };
    let mut points = Vec::with_capacity(count);
    for _ in 0..count {
        let mut best = [0.0, 0.0];
        for _ in 0..12 {
            best = [
                rng.var(w as f64 / 2.0) as f32,
                rng.var(d as f64 / 2.0) as f32,
            ];
            let (cx, cy) = cell(best);
            let crowded = (-1..=1).any(|dx| {
                (-1..=1).any(|dy| {
                    cells.get(&(cx + dx, cy + dy)).is_some_and(|ps| {
                        ps.iter()
                            .any(|q| (q[0] - best[0]).hypot(q[1] - best[1]) < spacing)
                    })
                })
            });
            if !crowded {
                break;
            }
        }
        cells.entry(cell(best)).or_default().push(best);
        points.push(best);
    }
    points
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
    if args.count == 0 || args.count > MAX_TREES {
        bail!("--count {}: expected 1..{MAX_TREES}", args.count);
    }
    if !(args.quality > 0.0 && args.quality <= 4.0) {
        bail!("--quality {}: expected 0..4", args.quality);
    }
    let area = parse_area(&args.area)?;
    let species: Vec<TreeParams> = args
        .species
        .iter()
        .map(|s| load_params(s, &[]))
        .collect::<Result<_>>()?;
    let key = StreamKey::from_seed(args.seed);
    let count = args.count as usize;
    let positions = place(count, area, key);
    // Which species and variant each tree is, and how it is turned and scaled.
    let mut rng = key.child(2).stream();
    let per_species = if args.variants == 0 {
        count
    } else {
        args.variants as usize
    };
    let mut variants: Vec<(usize, u64)> = Vec::new();
    let mut variant_of = std::collections::HashMap::new();
    let mut instances = Vec::with_capacity(count);
    for (i, p) in positions.iter().enumerate() {
        let s = (rng.unit() * species.len() as f64) as usize % species.len();
        let v = if args.variants == 0 {
            i
        } else {
            (rng.unit() * per_species as f64) as usize % per_species
        };
        let mesh = *variant_of.entry((s, v)).or_insert_with(|| {
            variants.push((s, key.child(3).child(s as u64).child(v as u64).0));
            variants.len() - 1
        });
        let turn = rng.unit() as f32 * std::f32::consts::TAU;
        let scale = 0.85 + 0.3 * rng.unit() as f32;
        instances.push(Instance {
            mesh,
            position: [p[0], p[1], 0.0],
            turn,
            scale,
        });
    }
    let bar = indicatif::ProgressBar::new(variants.len() as u64).with_message("growing trees");
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} [{elapsed}<{eta}]")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let t = Instant::now();
    let meshes: Vec<TreeMesh> = variants
        .par_iter()
        .map(|&(s, seed)| {
            let params = &species[s];
            let options = GenerateOptions {
                seed,
                quality: args.quality,
                ..Default::default()
            };
            let skeleton = sylva::generate(params, &options)?;
            let mesh = mesh_tree(&skeleton, &mesh_options(params, args.quality));
            bar.inc(1);
            Ok(mesh)
        })
        .collect::<Result<_>>()?;
    bar.finish_and_clear();
    let grow_s = t.elapsed().as_secs_f64();
    let names: Vec<String> = variants
        .iter()
        .map(|&(s, _)| species[s].name.clone())
        .collect();
    let scene: Vec<(&str, &TreeMesh, Materials)> = variants
        .iter()
        .zip(&meshes)
        .zip(&names)
        .map(|((&(s, _), m), n)| {
            (
                n.as_str(),
                m,
                Materials::from_srgb(species[s].bark_color, species[s].leaf_color),
            )
        })
        .collect();
    let bytes = to_glb_scene(&scene, &instances)?;
    write_atomically(&args.output, &bytes)?;
    let stored: usize = meshes.iter().map(TreeMesh::triangle_count).sum();
    let placed: usize = instances
        .iter()
        .map(|i| meshes[i.mesh].triangle_count())
        .sum();
    let per_second = variants.len() as f64 / grow_s;
    if args.json {
        println!(
            "{}",
            serde_json::json!({
                "trees": count,
                "variants": variants.len(),
                "triangles_stored": stored,
                "triangles_placed": placed,
                "grow_ms": (grow_s * 1e3).round(),
                "trees_per_second": (per_second * 10.0).round() / 10.0,
                "threads": rayon::current_num_threads(),
                "output": args.output.display().to_string(),
            })
        );
    } else {
        println!(
            "{count} trees ({} distinct) on {}x{} m: {stored} triangles stored, {placed} placed",
            variants.len(),
            area.0,
            area.1
        );
        println!(
            "  grown in {:.1} s on {} threads ({per_second:.1} trees/s); wrote {}",
            grow_s,
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
    fn placement_stays_on_the_plot_and_keeps_trees_apart() {
        let pts = place(200, (100.0, 50.0), StreamKey::from_seed(1));
        assert_eq!(pts.len(), 200);
        assert!(pts.iter().all(|p| p[0].abs() <= 50.0 && p[1].abs() <= 25.0));
        let spacing = (100.0f32 * 50.0 / 200.0).sqrt() * 0.6;
        let close = pts
            .iter()
            .enumerate()
            .flat_map(|(i, a)| {
                pts[i + 1..]
                    .iter()
                    .map(move |b| (a[0] - b[0]).hypot(a[1] - b[1]))
            })
            .filter(|&d| d < spacing * 0.5)
            .count();
        assert!(close < 10, "{close} pairs closer than half the spacing");
        assert!(parse_area("10x").is_err() && parse_area("-1x5").is_err());
        assert_eq!(parse_area("20x30").unwrap(), (20.0, 30.0));
    }
}
