//! The CPU backend: draws a [`Frame`] with no graphics driver at all, as the GPU draws it.
//!
//! A shadow map is rasterised from the sun; then every triangle, line and point is rasterised
//! into a visibility buffer of 4 samples per pixel (depth, and which primitive won), and each
//! pixel is shaded once per primitive it shows, at the pixel's centre, as 4x multisampling
//! does. Far stems and leaves (lines and points) are shaded as they are rasterised, since each
//! covers only the samples its share of the pixel chooses.

mod flat;
mod impostor;
mod raster;
mod shade;

use crate::frame::{Draw, Frame, InstanceData, Part, Primitive, SHADOW_SIZE};
use crate::props::Vertex;
use crate::tree::MeshData;
use flat::FlatDraw;
use glam::{Mat4, Vec2, Vec3, Vec4};
use raster::{Grid, SAMPLE_POSITIONS, Setup};
use rayon::prelude::*;
use shade::{Fragment, Light, ShadowMap};
use std::ops::Range;
use sylva::lod::expand::{Card, Tube};

pub(super) const SAMPLES: usize = 4;
/// A sample no primitive covers.
const EMPTY: u64 = u64::MAX;
/// Keys with this bit hold the index of a colour shaded while rasterising (lines, points);
/// others hold a batch (draw and copy) and a triangle.
pub(super) const FLAT: u64 = 1 << 63;

/// A line or point vertex: position, the size of what it stands for (stem diameter or blade
/// area) and a unit direction for lighting (stem axis or blade normal).
#[derive(Clone, Copy, Debug)]
struct FlatVertex {
    position: [f32; 3],
    size: f32,
    normal: [i8; 4],
}

/// The vertices (and indices) one draw reads.
#[derive(Clone, Copy)]
enum Geometry<'a> {
    Mesh {
        vertices: &'a [Vertex],
        indices: &'a [u32],
    },
    Flat(&'a [FlatVertex]),
}

/// A stored tree's draw unpacked on the CPU, as the GPU's vertex shader unpacks it: its
/// records' triangles, or their lines or points, in the tree's own frame, with the draw's
/// ranges in the geometry's own units (indices, or line and point vertices).
#[derive(Default)]
struct Expanded {
    mesh: MeshData,
    flat: Vec<FlatVertex>,
    range: Range<u32>,
    shadow: Range<u32>,
}

fn snorm(v: Vec3) -> [i8; 4] {
    let s = |v: f32| (v.clamp(-1.0, 1.0) * 127.0).round() as i8;
    [s(v.x), s(v.y), s(v.z), 0]
}

/// Unpacks the records a stored tree's draw reads (both its colour and its shadow range).
fn expand(frame: &Frame, d: &Draw) -> Option<Expanded> {
    let instance = &frame.instances[d.instances.start as usize];
    let grow = instance.stands_for[1];
    let [tx, ty, length, _] = instance.sway;
    let sway = sylva::lod::sway::Sway {
        turn: [tx, ty],
        length,
    };
    let swayed = |p: glam::Vec3| p + sway.displacement(p);
    let (lod, run) = d.part.run()?;
    let Part::Run {
        list, flat, card, ..
    } = d.part
    else {
        return None;
    };
    let scale = sylva::lod::card_scale(run.shape, card, grow);
    let spans: Vec<&Range<u32>> = [&d.range, &d.shadow]
        .into_iter()
        .filter(|r| !r.is_empty())
        .collect();
    let mut out = Expanded::default();
    let (Some(lo), Some(hi)) = (
        spans.iter().map(|r| r.start).min(),
        spans.iter().map(|r| r.end).max(),
    ) else {
        return Some(out);
    };
    let q = &lod.quantiser;
    let area = sylva::mesh::leaf_template(run.shape).area();
    // Where each record's geometry starts: indices for meshes, vertices for lines and points.
    let mut starts = Vec::with_capacity((hi - lo) as usize + 1);
    let mut mesh = sylva::mesh::Mesh::default();
    for k in lo as usize..hi as usize {
        starts.push(if flat {
            out.flat.len()
        } else {
            mesh.indices.len()
        } as u32);
        match (list == 3, flat) {
            (false, false) => Tube::of(q, &lod.segments[k]).mesh_into(run, &mut mesh),
            (true, false) => Card::of(q, &lod.leaves[k]).mesh_into(card, scale, true, &mut mesh),
            (false, true) => {
                let (ends, diameters, direction) = Tube::of(q, &lod.segments[k]).line();
                for (p, size) in ends.into_iter().zip(diameters) {
                    out.flat.push(FlatVertex {
                        position: swayed(p).to_array(),
                        size,
                        normal: snorm(direction),
                    });
                }
            }
            (true, true) => {
                let card = Card::of(q, &lod.leaves[k]);
                out.flat.push(FlatVertex {
                    position: swayed(card.centre()).to_array(),
                    size: card.length * card.width * area,
                    normal: snorm(card.normal()),
                });
            }
        }
    }
    starts.push(if flat {
        out.flat.len()
    } else {
        mesh.indices.len()
    } as u32);
    let map = |r: &Range<u32>| {
        if r.is_empty() {
            0..0
        } else {
            starts[(r.start - lo) as usize]..starts[(r.end - lo) as usize]
        }
    };
    out.range = map(&d.range);
    out.shadow = map(&d.shadow);
    if sway.length > 0.0 {
        for p in &mut mesh.positions {
            *p = swayed(glam::Vec3::from(*p)).to_array();
        }
    }
    out.mesh = crate::tree::mesh_data(&mesh);
    Some(out)
}

/// What one draw reads and draws: its geometry, and its colour and shadow ranges in it.
struct DrawView<'a> {
    geometry: Geometry<'a>,
    range: Range<u32>,
    shadow: Range<u32>,
}

fn view<'a>(frame: &'a Frame<'a>, d: &Draw<'a>, expanded: &'a Option<Expanded>) -> DrawView<'a> {
    let mesh = |m: &'a MeshData| Geometry::Mesh {
        vertices: &m.vertices,
        indices: &m.indices,
    };
    let geometry = match (d.part, expanded) {
        (_, Some(e)) => {
            return DrawView {
                geometry: if e.flat.is_empty() {
                    mesh(&e.mesh)
                } else {
                    Geometry::Flat(&e.flat)
                },
                range: e.range.clone(),
                shadow: e.shadow.clone(),
            };
        }
        (Part::Mesh { tree, leaves }, _) => mesh(if leaves {
            &tree.data.leaves
        } else {
            &tree.data.bark
        }),
        (Part::Run { .. } | Part::Impostor { .. }, None) => Geometry::Flat(&[]),
        (Part::Ground, _) => Geometry::Mesh {
            vertices: &frame.ground.vertices,
            indices: &frame.ground.indices,
        },
        (Part::Person, _) => Geometry::Mesh {
            vertices: &frame.person.vertices,
            indices: &frame.person.indices,
        },
    };
    DrawView {
        geometry,
        range: d.range.clone(),
        shadow: d.shadow.clone(),
    }
}

/// Clip positions of one copy's vertices, computed on first use.
struct ClipCache {
    clip: Vec<Vec4>,
    stamp: Vec<u32>,
    now: u32,
}

impl ClipCache {
    fn new() -> Self {
        Self {
            clip: Vec::new(),
            stamp: Vec::new(),
            now: 0,
        }
    }

    /// Forgets the last copy; `n` vertices follow.
    fn reset(&mut self, n: usize) {
        if self.stamp.len() < n {
            self.stamp.resize(n, 0);
            self.clip.resize(n, Vec4::ZERO);
        }
        self.now = self.now.wrapping_add(1);
        if self.now == 0 {
            self.stamp.fill(0);
            self.now = 1;
        }
    }

    #[inline]
    fn get(&mut self, i: usize, f: impl FnOnce() -> Vec4) -> Vec4 {
        if self.stamp[i] != self.now {
            self.stamp[i] = self.now;
            self.clip[i] = f();
        }
        self.clip[i]
    }
}

fn shadow_map(frame: &Frame, views: &[DrawView], light: Mat4) -> ShadowMap {
    let size = SHADOW_SIZE;
    let grid = Grid {
        width: size,
        height: size,
        samples: 1,
    };
    let mut depth = vec![1.0f32; (size * size) as usize];
    let mut cache = ClipCache::new();
    for (d, view) in frame.draws.iter().zip(views) {
        if view.shadow.is_empty() {
            continue;
        }
        let geometry = view.geometry;
        for copy in d.instances.clone() {
            let instance = &frame.instances[copy as usize];
            let mut write = |i: usize, z: f32| {
                if z < depth[i] {
                    depth[i] = z;
                }
            };
            match geometry {
                Geometry::Mesh { vertices, indices } => {
                    cache.reset(vertices.len());
                    let range = clamp_range(&view.shadow, indices.len());
                    for t in indices[range].chunks_exact(3) {
                        let c = [t[0], t[1], t[2]].map(|i| {
                            cache.get(i as usize, || {
                                let p = Vec3::from(vertices[i as usize].position);
                                light * instance.place(p).extend(1.0)
                            })
                        });
                        let Some(setup) = Setup::new(c) else { continue };
                        // The pipeline's slope bias: 2 units of the depth format's precision
                        // at this depth, plus twice the plane's steepest slope per texel.
                        let zmax = c.iter().map(|v| v.z.abs()).fold(0.0f32, f32::max);
                        let unit = (2.0f32).powi(exponent(zmax) - 23);
                        let slope = setup.depth_slope() * (2.0 / size as f32);
                        let bias = 2.0 * unit + 2.0 * slope.x.abs().max(slope.y.abs());
                        grid.triangle(&setup, &c, |i, z, _| write(i, z + bias));
                    }
                }
                Geometry::Flat(points) => {
                    let range = clamp_range(&view.shadow, points.len());
                    let clip =
                        |v: &FlatVertex| light * instance.place(Vec3::from(v.position)).extend(1.0);
                    let size = size as usize;
                    if d.primitive == Primitive::Lines {
                        for pair in points[range].chunks_exact(2) {
                            grid.line(clip(&pair[0]), clip(&pair[1]), |x, y, z, _, _| {
                                write(y as usize * size + x as usize, z)
                            });
                        }
                    } else {
                        for p in &points[range] {
                            grid.point(clip(p), |x, y, z, _| {
                                write(y as usize * size + x as usize, z)
                            });
                        }
                    }
                }
            }
        }
    }
    ShadowMap { size, depth }
}

/// The binary exponent of a positive float (0 for 0).
fn exponent(x: f32) -> i32 {
    if x <= 0.0 {
        0
    } else {
        ((x.to_bits() >> 23) & 0xff) as i32 - 127
    }
}

/// `range` cut to a list of `len` items (a stale range never reads past the end).
fn clamp_range(range: &std::ops::Range<u32>, len: usize) -> std::ops::Range<usize> {
    let end = (range.end as usize).min(len);
    (range.start as usize).min(end)..end
}

/// The visibility buffer: per sample, the nearest depth and what lies there.
pub(super) struct Samples {
    depth: Vec<f32>,
    key: Vec<u64>,
}

impl Samples {
    #[inline]
    pub(super) fn test(&mut self, i: usize, z: f32, key: u64) {
        if z < self.depth[i] {
            self.depth[i] = z;
            self.key[i] = key;
        }
    }
}

/// Draws `frame` into a `width` x `height` picture (RGBA, sRGB, rows from the top).
pub(crate) fn render(frame: &Frame, width: u32, height: u32) -> Vec<u8> {
    let g = &frame.globals;
    let view_proj = Mat4::from_cols_array_2d(&g.view_proj);
    let light_view_proj = Mat4::from_cols_array_2d(&g.light_view_proj);
    // Stored trees' draws unpacked once, in parallel: the passes below and the shading read
    // them as they read meshes.
    let expanded: Vec<Option<Expanded>> =
        frame.draws.par_iter().map(|d| expand(frame, d)).collect();
    let views: Vec<DrawView> = frame
        .draws
        .iter()
        .zip(&expanded)
        .map(|(d, e)| view(frame, d, e))
        .collect();
    let shadow = shadow_map(frame, &views, light_view_proj);
    let light = Light {
        globals: g,
        light_view_proj,
        shadow: &shadow,
    };
    let grid = Grid {
        width,
        height,
        samples: SAMPLES,
    };
    let n = (width * height) as usize * SAMPLES;
    let mut samples = Samples {
        depth: vec![1.0; n],
        key: vec![EMPTY; n],
    };
    let mut flat_colours: Vec<Vec3> = Vec::new();
    let mut batches: Vec<(usize, u32)> = Vec::new();
    let mut cache = ClipCache::new();
    for (draw_index, (d, view)) in frame.draws.iter().zip(&views).enumerate() {
        if view.range.is_empty() {
            continue;
        }
        if let (Part::Impostor { cell, .. }, Some(atlas)) = (d.part, frame.atlas) {
            let draw = impostor::ImpostorDraw {
                atlas,
                view_proj,
                eye: Vec3::from_slice(&g.eye[..3]),
                grid,
            };
            for copy in d.instances.clone() {
                let instance = &frame.instances[copy as usize];
                draw.draw(instance, &cell, &mut samples, &mut flat_colours);
            }
            continue;
        }
        let geometry = view.geometry;
        let material = &frame.materials[d.material];
        for copy in d.instances.clone() {
            let instance = &frame.instances[copy as usize];
            // A copy dissolving into its impostor leaves it the pixels it has taken.
            let fade = match d.part {
                Part::Run { fading: true, .. } => instance.sway[3],
                _ => 0.0,
            };
            let given_up = |i: usize| {
                let pixel = (i / SAMPLES) as u32;
                fade > 0.0 && shade::dither(pixel % width, pixel / width).0 < fade
            };
            let batch = batches.len() as u64;
            batches.push((draw_index, copy));
            match geometry {
                Geometry::Mesh { vertices, indices } => {
                    cache.reset(vertices.len());
                    let range = clamp_range(&view.range, indices.len());
                    let first = range.start / 3;
                    for (k, t) in indices[range].chunks_exact(3).enumerate() {
                        let c = [t[0], t[1], t[2]].map(|i| {
                            cache.get(i as usize, || {
                                let p = Vec3::from(vertices[i as usize].position);
                                view_proj * instance.place(p).extend(1.0)
                            })
                        });
                        let Some(setup) = Setup::new(c) else { continue };
                        let key = batch << 32 | (first + k) as u64;
                        grid.triangle(&setup, &c, |i, z, _| {
                            if !given_up(i) {
                                samples.test(i, z, key)
                            }
                        });
                    }
                }
                Geometry::Flat(points) => {
                    let range = clamp_range(&view.range, points.len());
                    let flat = FlatDraw {
                        light: &light,
                        material,
                        instance,
                        view_proj,
                        grid,
                        fade,
                    };
                    let mut out = (&mut samples, &mut flat_colours);
                    if d.primitive == Primitive::Lines {
                        for pair in points[range].chunks_exact(2) {
                            flat.line(&pair[0], &pair[1], &mut out);
                        }
                    } else {
                        for p in &points[range] {
                            flat.point(p, &mut out);
                        }
                    }
                }
            }
        }
    }
    let shader = Shader {
        frame,
        views: &views,
        light: &light,
        view_proj,
        grid,
        batches: &batches,
        flat_colours: &flat_colours,
    };
    let mut rgba = vec![0u8; (width * height * 4) as usize];
    rgba.par_chunks_mut(width as usize * 4)
        .enumerate()
        .for_each(|(y, row)| {
            for x in 0..width {
                let base = (y * width as usize + x as usize) * SAMPLES;
                let colour = shader.pixel(x, y as u32, &samples.key[base..base + SAMPLES]);
                row[x as usize * 4..][..4].copy_from_slice(&encode_srgb(colour));
            }
        });
    rgba
}

fn encode_srgb(c: Vec4) -> [u8; 4] {
    let s = |c: f32| (sylva::colour::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8;
    [
        s(c.x),
        s(c.y),
        s(c.z),
        (c.w.clamp(0.0, 1.0) * 255.0).round() as u8,
    ]
}

/// Shades the visibility buffer.
struct Shader<'a> {
    frame: &'a Frame<'a>,
    views: &'a [DrawView<'a>],
    light: &'a Light<'a>,
    view_proj: Mat4,
    grid: Grid,
    batches: &'a [(usize, u32)],
    flat_colours: &'a [Vec3],
}

impl Shader<'_> {
    /// A pixel's linear colour: the mean of its samples, each distinct primitive shaded once.
    fn pixel(&self, x: u32, y: u32, keys: &[u64]) -> Vec4 {
        let mut sum = Vec4::ZERO;
        for (s, &key) in keys.iter().enumerate() {
            if keys[..s].contains(&key) {
                continue;
            }
            let count = keys[s..].iter().filter(|&&k| k == key).count() as f32;
            let colour = match key {
                EMPTY => Vec4::from(self.frame.clear),
                k if k & FLAT != 0 => self.flat_colours[(k & !FLAT) as usize].extend(1.0),
                k => self.triangle(x, y, s, k).extend(1.0),
            };
            sum += colour * count;
        }
        sum / SAMPLES as f32
    }

    /// The colour of triangle `key` at the centre of pixel (x, y), or at its sample `s` where
    /// the centre lies behind the eye in the triangle's plane.
    fn triangle(&self, x: u32, y: u32, s: usize, key: u64) -> Vec3 {
        let (draw, copy) = self.batches[(key >> 32) as usize];
        let d = &self.frame.draws[draw];
        let instance: &InstanceData = &self.frame.instances[copy as usize];
        let Geometry::Mesh { vertices, indices } = self.views[draw].geometry else {
            return Vec3::ZERO;
        };
        let t = (key & 0xffff_ffff) as usize * 3;
        let v = [0, 1, 2].map(|k| &vertices[indices[t + k] as usize]);
        let world = v.map(|v| instance.place(Vec3::from(v.position)));
        let clip = world.map(|w| self.view_proj * w.extend(1.0));
        let Some(setup) = Setup::new(clip) else {
            return Vec3::ZERO;
        };
        let pixel = Vec2::new(x as f32, y as f32);
        let at = |p: Vec2| setup.barycentric(self.grid.ndc(p));
        let (centre, b) = match at(pixel + 0.5) {
            Some(b) => (pixel + 0.5, b),
            None => {
                let p = pixel + SAMPLE_POSITIONS[s];
                (p, at(p).unwrap_or(Vec3::splat(1.0 / 3.0)))
            }
        };
        let interpolate = |b: Vec3| world[0] * b.x + world[1] * b.y + world[2] * b.z;
        let position = interpolate(b);
        let material = &self.frame.materials[d.material];
        let fwidth = if shade::is_ground(material) {
            // fwidth: the ground's movement to the next pixel across and down.
            let step = |o: Vec2| at(centre + o).map_or(Vec3::ZERO, |b| interpolate(b) - position);
            let (dx, dy) = (step(Vec2::X), step(Vec2::Y));
            Vec2::new(dx.x.abs() + dy.x.abs(), dx.y.abs() + dy.y.abs())
        } else {
            Vec2::ZERO
        };
        let normal = v
            .iter()
            .zip([b.x, b.y, b.z])
            .map(|(v, w)| instance.turn(Vec3::from(v.normal)) * w)
            .sum();
        let fragment = Fragment {
            world: position,
            normal,
            shade: v[0].shade * b.x + v[1].shade * b.y + v[2].shade * b.z,
            front: setup.front,
            fwidth,
        };
        self.light.surface(material, &fragment)
    }
}
