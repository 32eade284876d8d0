//! Frame timings for `sylva bench --forest` and `--render`: what range degradation saves
//! drawing a tree or a forest from near to far, and a stand with and without its leaves, each
//! the fastest of several frames beside an empty frame of the same run.

use crate::{Camera, FrameStats, RenderError, Renderer, Scene, View};
use glam::Vec3;
use sylva::bench::fastest_ms;

/// The ranges a scene is drawn from, metres.
pub const RANGES: [f32; 7] = [10.0, 30.0, 100.0, 300.0, 1000.0, 2000.0, 3000.0];
/// The frame's size, pixels.
pub const SIZE: (u32, u32) = (1280, 720);
/// The lens, degrees.
pub const FOV: f32 = 45.0;

/// The fastest of `runs` frames of `view`, and what it drew.
pub fn frame(
    renderer: &Renderer,
    scene: &Scene,
    view: &View,
    runs: u32,
) -> Result<(FrameStats, f64), RenderError> {
    let mut stats = FrameStats::default();
    let ms = fastest_ms(runs, || {
        stats = renderer.render(scene, view, SIZE.0, SIZE.1)?.stats;
        Ok::<_, RenderError>(())
    })?;
    Ok((stats, ms))
}

/// An empty frame (ground, shadow pass, read-back): the baseline, ms.
pub fn empty_frame_ms(renderer: &Renderer, runs: u32) -> Result<f64, RenderError> {
    let empty = renderer.upload(&Default::default());
    let mut scene = Scene::new(&empty, [0.5; 3], [0.5; 3]);
    scene.show_person = false;
    Ok(frame(renderer, &scene, &View::orbit(0.0, 10.0), runs)?.1)
}

/// One range's frames, with range degradation and at full detail.
pub struct RangeFrame {
    /// Metres from the target.
    pub range: f32,
    /// With LOD: what was drawn, and the fastest frame, ms.
    pub lod: (FrameStats, f64),
    /// At full detail (once: a whole forest takes seconds on a CPU rasteriser).
    pub full: (FrameStats, f64),
}

/// `scene` from each of [`RANGES`] along a low view towards `target`, with and without LOD
/// (its impostors baked first, once, as trees are grown once: not part of a frame).
pub fn range_frames(
    renderer: &Renderer,
    scene: &mut Scene,
    target: Vec3,
    runs: u32,
) -> Result<Vec<RangeFrame>, RenderError> {
    renderer.prepare(scene)?;
    let mut out = Vec::new();
    for range in RANGES {
        let eye = target + Camera::direction(30.0, 8.0) * range;
        let view = View::look_at(eye, target, FOV);
        scene.use_lod = true;
        let lod = frame(renderer, scene, &view, runs)?;
        scene.use_lod = false;
        let full = frame(renderer, scene, &view, 1)?;
        out.push(RangeFrame { range, lod, full });
    }
    Ok(out)
}

/// A stand seen whole from 70 m at full detail and with LOD, in leaf and bare: each with its
/// label, what it drew and its fastest frame, ms.
pub fn stand_frames(
    renderer: &Renderer,
    scene: &mut Scene,
    runs: u32,
) -> Result<Vec<(&'static str, FrameStats, f64)>, RenderError> {
    let target = Vec3::new(0.0, 0.0, 6.0);
    let view = View::look_at(target + Camera::direction(30.0, 12.0) * 70.0, target, FOV);
    let mut out = Vec::new();
    for (use_lod, leaves, label) in [
        (false, true, "full, leaves"),
        (false, false, "full, bare"),
        (true, true, "LOD, leaves"),
        (true, false, "LOD, bare"),
    ] {
        scene.use_lod = use_lod;
        scene.show_leaves = leaves;
        let (stats, ms) = frame(renderer, scene, &view, runs)?;
        out.push((label, stats, ms));
    }
    Ok(out)
}

/// One species drawn whole at 1280x720 from the front.
pub struct SpeciesFrame {
    /// The built-in species.
    pub id: &'static str,
    /// Its mesh's triangles.
    pub triangles: usize,
    /// Milliseconds uploading the mesh took, and the fastest frame.
    pub upload_ms: f64,
    #[allow(missing_docs)]
    pub frame_ms: f64,
}

/// Frames of each of Weber & Penn's appendix species from the front, and of an empty tree
/// (ground, person, shadow pass, read-back) as the baseline, ms: what the editor feels.
pub fn species_frames(
    renderer: &Renderer,
    runs: u32,
) -> Result<(f64, Vec<SpeciesFrame>), RenderError> {
    use sylva::mesh::{MeshOptions, mesh_tree};
    let view = View::named(crate::ViewKind::Front);
    let (w, h) = SIZE;
    let empty = renderer.upload(&Default::default());
    let empty_scene = Scene::new(&empty, [0.5; 3], [0.5; 3]);
    let base = fastest_ms(runs, || {
        renderer.render(&empty_scene, &view, w, h).map(drop)
    })?;
    let mut out = Vec::new();
    for id in sylva::bench::APPENDIX_SPECIES {
        // The appendix species are built in and generate within the default budget.
        let params = sylva::species::builtin(id).expect("a built-in species");
        let skeleton = sylva::generate(&params, &Default::default())
            .map_err(|e| RenderError::Tree(format!("{id}: {e}")))?;
        let mesh = mesh_tree(&skeleton, &MeshOptions::for_species(&params, 1.0));
        let t = std::time::Instant::now();
        let tree = renderer.upload(&mesh);
        let upload_ms = t.elapsed().as_secs_f64() * 1e3;
        let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
        let frame_ms = fastest_ms(runs, || renderer.render(&scene, &view, w, h).map(drop))?;
        out.push(SpeciesFrame {
            id,
            triangles: mesh.triangle_count(),
            upload_ms,
            frame_ms,
        });
    }
    Ok((base, out))
}
