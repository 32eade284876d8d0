//! Pictures of grown street trees: one camera for every age of a run, framed on the tallest
//! and widest tree the run reaches, so that ages and species compare by eye.

use crate::caption::{draw_text, text_width};
use crate::{Picture, Placement, RenderError, Renderer, Scene, Stand, View};
use glam::Vec3;
use std::borrow::Cow;
use sylva::growth::{Dress, Measured};
use sylva::mesh::TreeMesh;

/// The camera every age of a run shares: looking from the south at a frame that holds a tree
/// `tallest` metres high, `across` metres of ground, and the person.
pub fn fixed_view(tallest: f64, across: f64, aspect: f32) -> View {
    let fov = 30.0f32;
    let half = (fov / 2.0).to_radians().tan();
    let h = tallest as f32 * 1.1 + 0.5;
    let w = across as f32 + 2.0;
    let distance = (h / 2.0 / half).max(w / 2.0 / (half * aspect)) * 1.05;
    let target = Vec3::new(0.0, 0.0, h / 2.0);
    View::look_at(target + Vec3::new(0.0, -distance, h * 0.08), target, fov)
}

/// One grown tree, dressed as `dress` says, in the run's frame (`extent`: tallest height and
/// widest crown, metres).
pub fn tree_picture(
    r: &Renderer,
    mesh: &TreeMesh,
    dress: &Dress,
    (width, height): (u32, u32),
    (tallest, widest): (f64, f64),
) -> Result<Picture, RenderError> {
    let tree = r.upload(mesh);
    let flowers = r.upload_flowers(mesh);
    let flowers = flowers.as_ref().zip(dress.flowers);
    let scene = Scene::flowering(&tree, flowers, dress.bark, dress.leaves);
    let view = fixed_view(tallest, widest + 2.0, width as f32 / height as f32);
    r.render(&scene, &view, width, height)
}

/// Species side by side at one age, each dressed as `dresses` says and named under its trunk,
/// in the run's frame. The picture widens to give each tree room.
pub fn comparison_picture(
    r: &Renderer,
    meshes: &[TreeMesh],
    dresses: &[Dress],
    species: &[Measured],
    (width, height): (u32, u32),
    (tallest, widest): (f64, f64),
) -> Result<Picture, RenderError> {
    let spacing = widest as f32 * 1.1 + 1.0;
    let n = meshes.len() as f32;
    let trees: Vec<_> = meshes.iter().map(|m| r.upload(m)).collect();
    let flowers: Vec<_> = meshes.iter().map(|m| r.upload_flowers(m)).collect();
    let placements: Vec<Placement> = (0..meshes.len())
        .map(|i| Placement {
            position: Vec3::new((i as f32 - (n - 1.0) / 2.0) * spacing, 0.0, 0.0),
            ..Placement::ORIGIN
        })
        .collect();
    let stands = trees
        .iter()
        .zip(&flowers)
        .zip(dresses)
        .zip(&placements)
        .flat_map(|(((t, f), d), p)| {
            let tree = Stand {
                tree: t,
                bark: d.bark,
                leaves: d.leaves,
                placements: Cow::Owned(vec![*p]),
            };
            tree.with_flowers(f.as_ref().zip(d.flowers))
        })
        .collect();
    let mut scene = Scene::forest(stands);
    scene.show_person = true;
    let across = spacing * n + 2.0;
    let w = width.max(height * meshes.len() as u32 * 2 / 3);
    let view = fixed_view(tallest, across as f64, w as f32 / height as f32);
    let mut picture = r.render(&scene, &view, w, height)?;
    let camera = scene.camera(&view, w as f32 / height as f32);
    for (m, p) in species.iter().zip(&placements) {
        let x = camera
            .project(p.position, w, height)
            .map_or(w as f32 / 2.0, |(x, _)| x);
        let name = &m.species.common;
        let size = 20.0;
        draw_text(
            &mut picture,
            x - text_width(name, size) / 2.0,
            height as f32 - 30.0,
            size,
            name,
            [20, 20, 20],
        );
    }
    Ok(picture)
}
