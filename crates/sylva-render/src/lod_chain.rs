//! A tree as an engine's chain of levels of detail: the meshes of [`LodTree::engine_chain`],
//! and last a billboard impostor whose views are baked with the renderer.

use crate::{Picture, RenderError, Renderer, Scene, View};
use glam::Vec3;
use sylva::TreeParams;
use sylva::export::{Materials, to_glb_lod};
use sylva::lod::LodTree;
use sylva::lod::impostor::{Impostor, ImpostorFrame};
use sylva::mesh::TreeMesh;

/// Height of one view in the atlas, pixels.
const CELL_HEIGHT: u32 = 256;
/// Screen coverage below which the impostor replaces the meshes.
pub const IMPOSTOR_COVERAGE: f32 = 0.04;

/// Bakes the views of `mesh` into an atlas: each view a near-orthographic picture (a long lens
/// from far away) with a transparent background, lit by the same sun as every render.
pub fn bake_impostor(
    renderer: &Renderer,
    mesh: &TreeMesh,
    bark: [f32; 3],
    leaves: [f32; 3],
) -> Result<Impostor, RenderError> {
    let frame = ImpostorFrame::around(mesh);
    let (w, h) = frame.cell_size(CELL_HEIGHT);
    let tree = renderer.upload(mesh);
    let mut scene = Scene::new(&tree, bark, leaves);
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
            renderer.render(&scene, &View::look_at(eye, centre, fov), w, h)
        })
        .collect::<Result<Vec<Picture>, RenderError>>()?;
    // Cells in the order the quads read them, on a transparent background.
    let atlas = crate::caption::tile(&views, frame.columns, 0, 0);
    Ok(Impostor {
        png: atlas.to_png()?,
        frame,
    })
}

/// An LOD chain written as GLB.
pub struct LodChain {
    /// The GLB file's bytes.
    pub glb: Vec<u8>,
    /// One line describing its levels.
    pub summary: String,
}

/// The chain of `lod` as GLB (`MSFT_lod`), with an impostor baked on `renderer` when there is
/// one.
pub fn lod_chain(
    renderer: Option<&Renderer>,
    lod: &LodTree,
    params: &TreeParams,
) -> Result<LodChain, RenderError> {
    let chain = lod.engine_chain();
    let impostor = match renderer {
        Some(r) => Some(bake_impostor(
            r,
            &chain[0].0,
            params.bark_color,
            params.leaf_color,
        )?),
        None => None,
    };
    let materials = Materials::from_srgb(params.bark_color, params.leaf_color);
    let name = params.name.replace(' ', "_");
    let glb = to_glb_lod(
        &name,
        &chain,
        impostor.as_ref().map(|i| (i, IMPOSTOR_COVERAGE)),
        &materials,
    )?;
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
    Ok(LodChain {
        glb,
        summary: parts.join("; "),
    })
}
