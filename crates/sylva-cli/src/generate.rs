//! `sylva generate`: a Weber-Penn tree as a GLB or OBJ model (or an engine's LOD chain), a
//! summary of what was made, and optionally a picture of it.

use crate::args::{GenerateArgs, RenderView};
use crate::shared::{headless, load_params, picture_of, save_picture};
use anyhow::{Context, Result, bail};
use std::path::Path;
use std::time::Instant;
use sylva::export::{Materials, write_atomically, write_glb, write_obj};
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};
use sylva::{GenerateOptions, TreeParams};

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

pub fn run(args: &GenerateArgs) -> Result<()> {
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
    let mesh_options = MeshOptions::for_species(&params, args.tree.quality);
    let mesh = mesh_tree(&skeleton, &mesh_options);
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
            let lod = sylva::lod::LodTree::build(&skeleton, &mesh_options);
            let renderer = headless()
                .inspect_err(|e| {
                    eprintln!("sylva: warning: {e}; writing the LOD chain without its impostor")
                })
                .ok();
            let chain = sylva_render::lod_chain(renderer.as_ref(), &lod, &params)?;
            write_atomically(&args.output, &chain.glb)?;
            if !args.json {
                println!("LOD chain: {}", chain.summary);
            }
        }
        Format::Glb => write_glb(&args.output, &mesh, &params.name, &materials)?,
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
    let colours = (params.bark_color, params.leaf_color);
    let picture = picture_of(mesh, colours, &view.to_view(), (1024, 768))?;
    save_picture(path, &picture)
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
