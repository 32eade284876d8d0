//! `sylva generate`: a Weber-Penn tree as a GLB or OBJ model (or an engine's LOD chain), a
//! summary of what was made, and optionally a picture of it.

use crate::args::{GenerateArgs, RenderView};
use crate::shared::{headless, load_params, picture_of, save_picture};
use anyhow::{Context, Result, bail};
use std::path::Path;
use sylva::export::{Materials, write_atomically, write_glb, write_obj};
use sylva::mesh::TreeMesh;
use sylva::record::to_json;
use sylva::weber_penn::made::{Made, MakeError, make};
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
    let made = match make(&params, &options, args.tree.quality) {
        Err(MakeError::OverBudget(e)) => bail!("{e} (--max-triangles)"),
        made => made.with_context(|| format!("species {}", args.species))?,
    };
    let (skeleton, mesh) = (&made.skeleton, &made.mesh);
    let materials = Materials::from_srgb(params.bark_color, params.leaf_color);
    match format {
        Format::Glb if args.lod_chain => {
            let lod = sylva::lod::LodTree::build(skeleton, &made.mesh_options);
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
        Format::Glb => write_glb(&args.output, mesh, &params.name, &materials)?,
        Format::Obj if args.lod_chain => {
            bail!("--lod-chain: LOD chains are written as GLB; use a .glb file name")
        }
        Format::Obj => write_obj(&args.output, mesh, &params.name, &materials)?,
    }
    // The model and its summary come first: a picture that fails cannot take them away.
    if args.json {
        let mut summary = to_json(&made.record(&params, args.tree.seed));
        summary["output"] = args.output.display().to_string().into();
        println!("{summary}");
    } else {
        print_summary(&params, args, &made);
    }
    if let Some(png) = &args.preview {
        write_preview(png, mesh, &params, args.view)?;
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

fn print_summary(params: &TreeParams, args: &GenerateArgs, made: &Made) {
    let (stats, mesh) = (made.skeleton.stats(), &made.mesh);
    let (generate_ms, mesh_ms) = (made.generate_ms, made.mesh_ms);
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
