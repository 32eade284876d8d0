//! `sylva render forest.toml`: a planted forest drawn with the paper's range degradation, from
//! a chosen range or eye, and side by side with full detail to show what it saves.

use crate::args::{LodMode, RenderArgs};
use crate::caption::{side_by_side, with_caption};
use crate::forest::{grow, read_forest_file};
use crate::shared::mesh_options;
use anyhow::{Context, Result, bail};
use glam::Vec3;
use std::borrow::Cow;
use std::path::Path;
use std::time::Instant;
use sylva::forest::ForestSpec;
use sylva::lod::LodTree;
use sylva_render::{
    Camera, FrameStats, Picture, Placement, RenderTree, Renderer, Scene, Stand, View,
};

/// Thousands separators: 1234567 -> "1,234,567".
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// One line describing a frame: what it drew and how long it took.
pub fn describe(stats: &FrameStats, ms: f64) -> String {
    format!(
        "{} triangles, {} lines, {} points ({} primitives) in {} of {} trees; {:.0} ms",
        grouped(stats.triangles),
        grouped(stats.lines),
        grouped(stats.points),
        grouped(stats.primitives()),
        grouped(stats.trees_drawn),
        grouped(stats.trees),
        ms
    )
}

/// GPU trees for every variant of a forest file, and where their copies stand.
pub struct ForestOnGpu {
    pub trees: Vec<RenderTree>,
    pub colours: Vec<([f32; 3], [f32; 3])>,
    pub placements: Vec<Vec<Placement>>,
    pub stored_bytes: usize,
    pub triangles_placed: usize,
    pub grow_seconds: f64,
}

impl ForestOnGpu {
    /// Plants and grows `path`'s forest, stores every variant for range and uploads it.
    pub fn load(renderer: &Renderer, path: &Path) -> Result<Self> {
        Self::grow(renderer, &read_forest_file(path)?).with_context(|| path.display().to_string())
    }

    /// Plants and grows `spec`, stores every variant for range and uploads it.
    pub fn grow(renderer: &Renderer, spec: &ForestSpec) -> Result<Self> {
        let quality = spec.quality;
        let forest = grow(spec, |params, skeleton| {
            let tree = LodTree::build(skeleton, &mesh_options(params, quality));
            let bytes = tree.heap_bytes();
            (tree, bytes)
        })?;
        let mut placements = vec![Vec::new(); forest.planting.variants.len()];
        for t in &forest.planting.trees {
            placements[t.variant].push(Placement {
                position: Vec3::from(t.position),
                turn: t.turn,
                scale: t.scale,
            });
        }
        let colours = forest
            .planting
            .variants
            .iter()
            .map(|v| {
                let s = &forest.species[v.species];
                (s.bark_color, s.leaf_color)
            })
            .collect();
        Ok(Self {
            trees: forest
                .grown
                .iter()
                .map(|t| renderer.upload_lod(t))
                .collect(),
            stored_bytes: forest.grown.iter().map(LodTree::heap_bytes).sum(),
            triangles_placed: forest
                .planting
                .trees
                .iter()
                .map(|t| forest.grown[t.variant].triangle_count())
                .sum(),
            colours,
            placements,
            grow_seconds: forest.seconds,
        })
    }

    /// The scene of every copy.
    pub fn scene(&self) -> Scene<'_> {
        let stands = self
            .trees
            .iter()
            .zip(&self.colours)
            .zip(&self.placements)
            .map(|((tree, &(bark, leaves)), p)| Stand {
                tree,
                bark,
                leaves,
                placements: Cow::Borrowed(p),
            })
            .collect();
        Scene::forest(stands)
    }
}

/// The camera a render asks for: an explicit eye, a range along the view's direction, or the
/// view framing the whole forest from no lower than 12 degrees.
pub fn forest_view(args: &RenderArgs, scene: &Scene, base: View) -> Result<View> {
    let (lo, hi) = scene.tree_bounds();
    let centre = Vec3::new(
        (lo.x + hi.x) / 2.0,
        (lo.y + hi.y) / 2.0,
        (hi.z - lo.z) / 3.0,
    );
    if let (Some(eye), Some(target)) = (&args.eye, &args.target) {
        if eye.len() != 3 || target.len() != 3 {
            bail!(
                "--eye and --target take three numbers each, X,Y,Z in metres, e.g. --eye 0,-80,2"
            );
        }
        let (eye, target) = (Vec3::from_slice(eye), Vec3::from_slice(target));
        if !eye.is_finite() || !target.is_finite() || eye.distance(target) < 1e-3 {
            bail!("--eye and --target must be finite and apart");
        }
        return Ok(View::look_at(eye, target, args.fov));
    }
    let elevation = base.elevation.max(12.0);
    if let Some(range) = args.range {
        if !(range.is_finite() && range > 0.5 && range <= 100_000.0) {
            bail!("--range {range}: expected 0.5..100000 metres");
        }
        let eye = centre + Camera::direction(base.azimuth, elevation) * range;
        return Ok(View::look_at(eye, centre, args.fov));
    }
    let mut view = View::orbit(base.azimuth, elevation);
    view.fov_y = args.fov;
    Ok(view)
}

pub fn render_forest(
    args: &RenderArgs,
    renderer: &Renderer,
    base: View,
    (width, height): (u32, u32),
) -> Result<()> {
    if args.frames.is_some() || args.turntable.is_some() || args.wind != 0.0 {
        bail!(
            "forests are rendered one picture at a time: leave out --frames, --turntable and --wind"
        );
    }
    let forest = ForestOnGpu::load(renderer, Path::new(&args.input))?;
    let mut scene = forest.scene();
    scene.show_leaves = !args.tree.no_leaves;
    scene.show_ground = !args.bare;
    let view = forest_view(args, &scene, base)?;
    let mut frame = |use_lod: bool| -> Result<(Picture, f64)> {
        scene.use_lod = use_lod;
        let t = Instant::now();
        let picture = renderer.render(&scene, &view, width, height)?;
        Ok((picture, t.elapsed().as_secs_f64() * 1e3))
    };
    let picture = match args.lod {
        LodMode::On | LodMode::Off => {
            let (p, ms) = frame(args.lod == LodMode::On)?;
            println!("{}", describe(&p.stats, ms));
            p
        }
        LodMode::Compare => {
            let (with, with_ms) = frame(true)?;
            let (without, without_ms) = frame(false)?;
            let size = (width as f32 / 48.0).clamp(11.0, 22.0);
            let caption =
                |title: &str, p: &Picture, ms: f64| vec![title.to_string(), describe(&p.stats, ms)];
            let left = with_caption(
                &with,
                &caption("with range degradation (LOD)", &with, with_ms),
                size,
            );
            let right = with_caption(
                &without,
                &caption("full detail (no LOD)", &without, without_ms),
                size,
            );
            println!("with LOD:    {}", describe(&with.stats, with_ms));
            println!("without LOD: {}", describe(&without.stats, without_ms));
            side_by_side(&[left, right], 8)
        }
    };
    crate::shared::encode_png(&args.output, picture.width, picture.height, &picture.rgba)?;
    println!(
        "wrote {} ({}x{}; {} trees of {} variants grown in {:.1} s, {:.1} MB stored; {})",
        args.output.display(),
        picture.width,
        picture.height,
        grouped(forest.placements.iter().map(Vec::len).sum()),
        forest.trees.len(),
        forest.grow_seconds,
        forest.stored_bytes as f64 / 1e6,
        renderer.adapter_name()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_grouped() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(1234567), "1,234,567");
    }
}
