//! Impostors at range: a tree stored for range that is under `sylva::lod::IMPOSTOR_PIXELS`
//! tall is drawn as a picture of itself on one quad, the last step of Weber & Penn's
//! degradation. The pictures are baked here, by the renderer itself, for a scene's trees
//! under its sun: [`VIEWS`] level views round each tree, each [`CELL`] texels tall, in one
//! atlas. The frame plan draws a quad per far copy (`frame::Part::Impostor`); the shader
//! (`impostor.wgsl`) and the CPU rasteriser (`cpu::impostor`) cross-fade the two views either
//! side of the eye and dissolve the tree into its impostor over a band of sizes.
//!
//! The views are lit by the scene's sun and baked with the same range degradation a tree of
//! that size draws, so the switch changes little: the tree's own crown shadows and leaf
//! colours are in the picture. What it leaves out: shadows other trees cast on a far tree
//! (its own are in the bake), and views from above the canopy (the quad stays upright).

use crate::scene::{Placement, Scene, Stand, View};
use crate::{RenderError, Renderer};
use glam::{Vec2, Vec3, Vec4};
use std::borrow::Cow;

/// Views baked round each tree, level, view 0 from the south as
/// `sylva::lod::impostor::ImpostorFrame::direction` takes them (the shader's `VIEWS`).
pub(crate) const VIEWS: u32 = 8;
/// Texel rows of a view: more than the pixels of the tallest tree drawn as an impostor, so
/// that a texel is never larger than a pixel (the shader's `CELL`).
pub(crate) const CELL: u32 = 64;
/// The widest and tallest atlas, texels (the least WebGPU guarantees).
const MAX_ATLAS: u32 = 2048;

/// Where one tree's views lie in the atlas, and what they span.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Cell {
    /// Left column and the top row of view 0, texels; view k lies `k * CELL` rows lower.
    pub x0: u32,
    pub y0: u32,
    /// Width, texels.
    pub width: u32,
    /// Half the width the cell spans and its lowest and highest point, metres, in the tree's
    /// own frame about its trunk axis.
    pub half_width: f32,
    pub bottom: f32,
    pub top: f32,
}

/// The baked views of a scene's trees.
#[derive(Debug)]
pub(crate) struct Atlas {
    /// Unique among the atlases of this process (the GPU keeps its texture under it).
    pub id: u64,
    pub width: u32,
    pub height: u32,
    /// Colour times alpha (premultiplied, so that filtering weighs each texel's colour by
    /// its cover), sRGB-encoded, and alpha; rows from the top.
    pub rgba: Vec<u8>,
    /// Per stand of the scene: its cell, when its tree is stored for range and found room.
    pub cells: Vec<Option<Cell>>,
}

impl Atlas {
    /// The colour at a point in texels (linear, premultiplied), filtered bilinearly with
    /// clamping at the edges, as the GPU's sampler reads the sRGB texture.
    pub fn sample(&self, texel: Vec2) -> Vec4 {
        let p = texel - 0.5;
        let (x0, y0) = (p.x.floor(), p.y.floor());
        let (fx, fy) = (p.x - x0, p.y - y0);
        let at = |x: f32, y: f32| {
            let x = (x as i64).clamp(0, self.width as i64 - 1) as usize;
            let y = (y as i64).clamp(0, self.height as i64 - 1) as usize;
            let t = &self.rgba[(y * self.width as usize + x) * 4..][..4];
            let c = |v: u8| sylva::colour::srgb_to_linear(v as f32 / 255.0);
            Vec4::new(c(t[0]), c(t[1]), c(t[2]), t[3] as f32 / 255.0)
        };
        let top = at(x0, y0).lerp(at(x0 + 1.0, y0), fx);
        let bottom = at(x0, y0 + 1.0).lerp(at(x0 + 1.0, y0 + 1.0), fx);
        top.lerp(bottom, fy)
    }
}

/// What a bake depends on: the trees (and their colours), the sun and the leaves. Not the
/// degradation's quality, which a viewer's slider may sweep through many values: the views are
/// baked at the paper's quality 1, which under 50 pixels looks the same as any other.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Key {
    trees: Vec<(u64, [u32; 6])>,
    sun: [u32; 3],
    leaves: bool,
}

impl Key {
    /// The key of `scene`'s impostors; `None` when it draws none.
    pub fn of(scene: &Scene) -> Option<Self> {
        let stored = scene.stands.iter().any(|s| s.tree.data.lod.is_some());
        if !(scene.use_lod && scene.impostors && stored) {
            return None;
        }
        let bits = |c: [f32; 3]| c.map(f32::to_bits);
        Some(Self {
            trees: scene
                .stands
                .iter()
                .map(|s| {
                    let [a, b, c] = bits(s.bark);
                    let [d, e, f] = bits(s.leaves);
                    (s.tree.id, [a, b, c, d, e, f])
                })
                .collect(),
            sun: bits(scene.sun.to_array()),
            leaves: scene.show_leaves,
        })
    }
}

/// A tree's reach from its trunk axis and its lowest and highest point, metres.
fn extent(stand: &Stand) -> (f32, f32, f32) {
    let (lo, hi) = (stand.tree.lo, stand.tree.hi);
    let reach = lo.x.abs().max(hi.x.abs()).hypot(lo.y.abs().max(hi.y.abs()));
    (reach.max(0.05), lo.z.min(0.0), hi.z.max(0.1))
}

/// The baked pictures of a group of trees: one per view, the trees side by side, level, far
/// enough apart that none shades another.
struct Row {
    /// Stands of the scene, left to right, each scaled to the row's height so that every tree
    /// fills its cell.
    stands: Vec<(usize, f32)>,
    bottom: f32,
    top: f32,
    /// Pixels per metre, and pixels from one trunk to the next (even, so trunks fall on
    /// pixel edges).
    scale: f32,
    spacing: u32,
}

impl Row {
    fn width(&self) -> u32 {
        (self.stands.len() as u32 * self.spacing).max(16)
    }

    /// Texels of a tree's cell: its reach either side of the trunk and a clear texel beyond
    /// (even, so that the cell is centred on the trunk).
    fn cell_width(&self, reach: f32) -> u32 {
        (2 * ((reach * self.scale).ceil() as u32 + 1)).min(self.spacing)
    }
}

/// Groups the scene's stored trees into rows no wider than `max_side` pixels.
fn rows(scene: &Scene, max_side: u32) -> Vec<Row> {
    let stored: Vec<usize> = (0..scene.stands.len())
        .filter(|&s| scene.stands[s].tree.data.lod.is_some())
        .collect();
    let mut rows: Vec<Row> = Vec::new();
    let mut chunk: Vec<usize> = Vec::new();
    let row_of = |stands: &[usize]| {
        let tallest = stands
            .iter()
            .map(|&s| extent(&scene.stands[s]))
            .fold(0.1f32, |h, (_, b, t)| h.max(t - b));
        let (mut reach, mut bottom, mut top) = (0.0f32, 0.0f32, 0.1f32);
        let stands = stands
            .iter()
            .map(|&s| {
                let (r, b, t) = extent(&scene.stands[s]);
                let scale = tallest / (t - b);
                reach = reach.max(r * scale);
                bottom = bottom.min(b * scale);
                top = top.max(t * scale);
                (s, scale)
            })
            .collect();
        let top = top + 0.01 * (top - bottom);
        let scale = CELL as f32 / (top - bottom);
        // A tree's shadow reaches about its height beyond its crown when the sun is over 40
        // degrees up (it is 41 in the default scene).
        let gap = 2.0 * reach + 1.2 * (top - bottom);
        let spacing = 2 * ((gap * scale / 2.0).ceil() as u32).max(4);
        Row {
            stands,
            bottom,
            top,
            scale,
            spacing,
        }
    };
    for s in stored {
        chunk.push(s);
        if chunk.len() > 1 && row_of(&chunk).width() > max_side {
            chunk.pop();
            rows.push(row_of(&chunk));
            chunk = vec![s];
        }
    }
    if !chunk.is_empty() {
        rows.push(row_of(&chunk));
    }
    rows
}

/// The scene that bakes view `k` of `row`: its trees side by side across the view, calm, on
/// a transparent background, degraded as trees of that size are.
fn view_scene<'a>(scene: &Scene<'a>, row: &Row, k: u32) -> (Scene<'a>, View) {
    let a = (360.0 * k as f32 / VIEWS as f32).to_radians();
    let towards_eye = Vec3::new(a.sin(), -a.cos(), 0.0);
    let right = (-towards_eye).cross(Vec3::Z).normalize();
    let spacing = row.spacing as f32 / row.scale;
    let half = row.stands.len() as f32 * spacing / 2.0;
    let stands = row
        .stands
        .iter()
        .enumerate()
        .map(|(i, &(s, scale))| {
            // A tree scaled up is degraded as the same tree nearer: as it looks at the
            // cell's size.
            let placement = Placement {
                position: right * ((i as f32 + 0.5) * spacing - half),
                scale,
                ..Placement::ORIGIN
            };
            Stand {
                placements: Cow::Owned(vec![placement]),
                ..scene.stands[s].clone()
            }
        })
        .collect();
    let bake = Scene {
        show_ground: false,
        show_person: false,
        transparent: true,
        impostors: false,
        primitive_budget: None,
        use_lod: true,
        lod_quality: 1.0,
        show_leaves: scene.show_leaves,
        sun: scene.sun,
        ..Scene::forest(stands)
    };
    // Far away with a narrow lens: nearly parallel rays, as the quad shows the picture.
    let height = row.top - row.bottom;
    let distance = height * 1000.0;
    let target = Vec3::new(0.0, 0.0, (row.top + row.bottom) / 2.0);
    let fov = (2.0 * (height / 2.0 / distance).atan()).to_degrees();
    let view = View::look_at(target + towards_eye * distance, target, fov);
    (bake, view)
}

/// Turns a transparent picture's pixels, each its trees' colour blended over `clear` by
/// their cover, into the trees' colour times their cover.
fn premultiply(rgba: &mut [u8], clear: [f32; 4]) {
    use sylva::colour::{linear_to_srgb, srgb_to_linear};
    for px in rgba.chunks_exact_mut(4) {
        let a = px[3] as f32 / 255.0;
        for (c, back) in px[..3].iter_mut().zip(clear) {
            let v = srgb_to_linear(*c as f32 / 255.0) - (1.0 - a) * back;
            *c = (linear_to_srgb(v.clamp(0.0, a)) * 255.0).round() as u8;
        }
    }
}

/// Bakes the views of `scene`'s stored trees on `renderer`, in pictures at most `max_side`
/// pixels wide.
pub(crate) fn bake(
    renderer: &Renderer,
    scene: &Scene,
    max_side: u32,
) -> Result<Atlas, RenderError> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    let max_side = max_side.min(MAX_ATLAS);
    let band = VIEWS * CELL;
    let mut cells = vec![None; scene.stands.len()];
    let (mut x, mut y, mut width) = (0u32, 0u32, 16u32);
    let mut pieces: Vec<(Vec<u8>, u32, Row)> = Vec::new();
    for row in rows(scene, max_side) {
        let mut pictures = Vec::with_capacity(VIEWS as usize);
        for k in 0..VIEWS {
            let (bake, view) = view_scene(scene, &row, k);
            let clear = bake.transparent_clear();
            let mut rgba = renderer.render(&bake, &view, row.width(), CELL)?.rgba;
            premultiply(&mut rgba, clear);
            pictures.extend(rgba);
        }
        pieces.push((pictures, row.width(), row));
    }
    let mut rgba = Vec::new();
    let mut copies = Vec::new();
    for (pictures, picture_width, row) in &pieces {
        for (i, &(s, scale)) in row.stands.iter().enumerate() {
            let w = row.cell_width(extent(&scene.stands[s]).0 * scale);
            if x + w > max_side {
                (x, y) = (0, y + band);
            }
            if y + band > max_side {
                break;
            }
            let centre = (2 * i as u32 + 1) * row.spacing / 2;
            copies.push((pictures, *picture_width, centre - w / 2, (x, y), w));
            cells[s] = Some(Cell {
                x0: x,
                y0: y,
                width: w,
                half_width: w as f32 / 2.0 / row.scale / scale,
                bottom: row.bottom / scale,
                top: row.top / scale,
            });
            x += w;
            width = width.max(x);
        }
    }
    let height = if copies.is_empty() { 16 } else { y + band };
    rgba.resize((width * height * 4) as usize, 0);
    for (pictures, picture_width, from, (x0, y0), w) in copies {
        for row in 0..band {
            let src = ((row * picture_width + from) * 4) as usize;
            let dst = (((y0 + row) * width + x0) * 4) as usize;
            rgba[dst..dst + (w * 4) as usize]
                .copy_from_slice(&pictures[src..src + (w * 4) as usize]);
        }
    }
    Ok(Atlas {
        id: NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        width,
        height,
        rgba,
        cells,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stored(species: &str) -> (sylva::lod::LodTree, sylva::TreeParams) {
        let params = sylva::species::builtin(species).unwrap();
        let options = sylva::GenerateOptions {
            quality: 0.3,
            ..Default::default()
        };
        let skeleton = sylva::generate(&params, &options).unwrap();
        (
            sylva::lod::LodTree::build(&skeleton, &Default::default()),
            params,
        )
    }

    #[test]
    fn every_view_frames_its_tree_about_the_trunk() {
        let renderer = Renderer::cpu();
        let trees: Vec<_> = ["quaking_aspen", "black_tupelo"].map(stored).into();
        let uploaded: Vec<_> = trees.iter().map(|(l, _)| renderer.upload_lod(l)).collect();
        let stands = trees
            .iter()
            .zip(&uploaded)
            .map(|((_, p), t)| Stand {
                tree: t,
                bark: p.bark_color,
                leaves: p.leaf_color,
                placements: Cow::Owned(vec![Placement::ORIGIN]),
            })
            .collect();
        let scene = Scene::forest(stands);
        let atlas = bake(&renderer, &scene, 2048).unwrap();
        if let Ok(dir) = std::env::var("SYLVA_DUMP_ATLAS") {
            let picture = crate::Picture {
                width: atlas.width,
                height: atlas.height,
                rgba: atlas.rgba.clone(),
                stats: Default::default(),
            };
            std::fs::write(format!("{dir}/atlas.png"), picture.to_png().unwrap()).unwrap();
        }
        assert_eq!(atlas.rgba.len(), (atlas.width * atlas.height * 4) as usize);
        for (s, cell) in atlas.cells.iter().enumerate() {
            let cell = cell.expect("both trees are stored for range");
            let tree = scene.stands[s].tree;
            assert!(cell.top >= tree.hi.z && cell.bottom <= tree.lo.z.min(0.0));
            let mut covers = Vec::new();
            for k in 0..VIEWS {
                // Covered texels, and their mean column and lowest and highest row.
                let (mut n, mut columns, mut rows) = (0.0f64, 0.0f64, (CELL, 0));
                for y in 0..CELL {
                    for x in 0..cell.width {
                        let at = ((cell.y0 + k * CELL + y) * atlas.width + cell.x0 + x) * 4 + 3;
                        let alpha = atlas.rgba[at as usize];
                        if alpha > 0 {
                            rows = (rows.0.min(y), rows.1.max(y));
                        }
                        if alpha > 127 {
                            n += 1.0;
                            columns += x as f64 + 0.5;
                        }
                    }
                }
                let centre = columns / n / cell.width as f64;
                // Crowns are not symmetric; the trunk is the axis they gather about.
                assert!(
                    (centre - 0.5).abs() < 0.12,
                    "tree {s} view {k}: centre {centre}"
                );
                assert!(
                    rows.0 < 6 && rows.1 >= CELL - 4,
                    "tree {s} view {k}: rows {rows:?}"
                );
                covers.push(n);
            }
            let (lo, hi) = covers
                .iter()
                .fold((f64::MAX, 0.0f64), |(a, b), &c| (a.min(c), b.max(c)));
            assert!(
                lo > 0.25 * (CELL * cell.width) as f64,
                "tree {s}: {covers:?}"
            );
            assert!(
                hi < 1.5 * lo,
                "every side shows the crown alike: {covers:?}"
            );
        }
    }
}
