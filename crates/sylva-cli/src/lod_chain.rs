//! `sylva generate --lod-chain`: a tree as an engine's chain of levels of detail, the last a
//! billboard impostor baked with the renderer.

use anyhow::Result;
use glam::Vec3;
use std::path::Path;
use sylva::TreeParams;
use sylva::export::{Materials, to_glb_lod, write_atomically};
use sylva::lod::LodTree;
use sylva::lod::impostor::{Impostor, ImpostorFrame};
use sylva::mesh::TreeMesh;
use sylva_render::{Picture, Renderer, Scene, View};

/// Height of one view in the atlas, pixels.
const CELL_HEIGHT: u32 = 256;
/// Screen coverage below which the impostor replaces the meshes.
const IMPOSTOR_COVERAGE: f32 = 0.04;

/// Bakes the views of `mesh` into an atlas: each view a near-orthographic picture (a long lens
/// from far away) with a transparent background, lit by the same sun as every render.
pub fn bake_impostor(
    renderer: &Renderer,
    mesh: &TreeMesh,
    params: &TreeParams,
) -> Result<Impostor> {
    let frame = ImpostorFrame::around(mesh);
    let (w, h) = frame.cell_size(CELL_HEIGHT);
    let tree = renderer.upload(mesh);
    let mut scene = Scene::new(&tree, params.bark_color, params.leaf_color);
    scene.show_ground = false;
    scene.show_person = false;
    scene.transparent = true;
    let height = frame.top - frame.bottom;
    let centre = Vec3::new(0.0, 0.0, (frame.top + frame.bottom) / 2.0);
    let distance = height * 200.0;
    let fov = (2.0 * (height / 2.0 / distance).atan()).to_degrees();
    let views = (0..frame.views)
        .map(|k| {
            let eye = centre + frame.direction(k) * distance;
            Ok(renderer.render(&scene, &View::look_at(eye, centre, fov), w, h)?)
        })
        .collect::<Result<Vec<Picture>>>()?;
    // Cells in the order the quads read them, on a transparent background.
    let atlas = crate::caption::tile(&views, frame.columns, 0, 0);
    let mut png = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut png),
        &atlas.rgba,
        atlas.width,
        atlas.height,
        image::ExtendedColorType::Rgba8,
    )?;
    Ok(Impostor { png, frame })
}

/// Writes the chain of `lod` to `path`; returns a one-line description of its levels.
pub fn write_lod_chain(path: &Path, lod: &LodTree, params: &TreeParams) -> Result<String> {
    let chain = lod.engine_chain();
    let impostor = match crate::render::headless() {
        Ok(renderer) => Some(bake_impostor(&renderer, &chain[0].0, params)?),
        Err(e) => {
            eprintln!("sylva: warning: {e}; writing the LOD chain without its impostor");
            None
        }
    };
    let materials = Materials::from_srgb(params.bark_color, params.leaf_color);
    let name = params.name.replace(' ', "_");
    let bytes = to_glb_lod(
        &name,
        &chain,
        impostor.as_ref().map(|i| (i, IMPOSTOR_COVERAGE)),
        &materials,
    )?;
    write_atomically(path, &bytes)?;
    let mut parts: Vec<String> = chain
        .iter()
        .enumerate()
        .map(|(k, (m, c))| {
            format!(
                "LOD{k} {} triangles (above {c} of the screen)",
                m.triangle_count()
            )
        })
        .collect();
    if let Some(i) = &impostor {
        parts.push(format!(
            "LOD{} impostor {} quads, {} KB atlas (above {IMPOSTOR_COVERAGE})",
            chain.len(),
            i.frame.views,
            i.png.len() / 1024
        ));
    }
    Ok(parts.join("; "))
}
