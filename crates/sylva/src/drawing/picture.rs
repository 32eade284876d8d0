//! Projected line drawings as SVG text or PNG pixels.
//!
//! A drawing replays its source three times: the model's extent, the page's extent in the chosen
//! view, and the strokes. Nothing is buffered but the stroke being drawn, so the memory a drawing
//! needs depends on the page, not on the tree.

use super::view::{Projector, View};
use super::{LineSink, LineSource, Part, Stroke};
use glam::{Vec2, Vec3};
use std::io::{self, Write};

/// Page settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawOptions {
    /// Projection.
    pub view: View,
    /// Page width in pixels (SVG user units).
    pub width: u32,
    /// Page height in pixels.
    pub height: u32,
    /// Empty border around the tree, pixels.
    pub margin: f32,
    /// Thinnest stroke drawn, pixels (twigs narrower than this are widened to it).
    pub min_stroke: f32,
    /// Wood colour (sRGB bytes).
    pub wood: [u8; 3],
    /// Leaf outline colour.
    pub leaf: [u8; 3],
    /// Paper colour.
    pub paper: [u8; 3],
    /// Fade far strokes toward the paper, as the PS-300 dimmed distant lines.
    pub depth_cue: bool,
}

impl Default for DrawOptions {
    fn default() -> Self {
        Self {
            view: View::Front,
            width: 1024,
            height: 1024,
            margin: 24.0,
            min_stroke: 0.6,
            wood: [58, 44, 33],
            leaf: [46, 110, 40],
            paper: [255, 255, 255],
            depth_cue: true,
        }
    }
}

/// How model points land on the page.
struct Layout {
    projector: Projector,
    scale: f32,
    offset: Vec2,
    height: f32,
}

impl Layout {
    fn new(source: &(impl LineSource + ?Sized), options: &DrawOptions) -> Self {
        let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        source.lines(&mut |a: Vec3, b: Vec3, _: Stroke| {
            lo = lo.min(a).min(b);
            hi = hi.max(a).max(b);
        });
        if lo.x > hi.x {
            (lo, hi) = (Vec3::ZERO, Vec3::ONE);
        }
        let projector = Projector::new(options.view, lo, hi);
        let (mut lo2, mut hi2) = (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN));
        source.lines(&mut |a: Vec3, b: Vec3, _: Stroke| {
            for p in [a, b] {
                let (pts, n) = projector.project(p);
                for (q, _) in &pts[..n] {
                    lo2 = lo2.min(*q);
                    hi2 = hi2.max(*q);
                }
            }
        });
        if lo2.x > hi2.x {
            (lo2, hi2) = (Vec2::ZERO, Vec2::ONE);
        }
        let size = (hi2 - lo2).max(Vec2::splat(1e-6));
        let room = Vec2::new(options.width as f32, options.height as f32) - 2.0 * options.margin;
        let scale = (room.x / size.x).min(room.y / size.y).max(1e-9);
        // Centred across, standing on the bottom margin.
        let offset = Vec2::new(
            options.margin + 0.5 * (room.x - size.x * scale) - lo2.x * scale,
            options.margin - lo2.y * scale,
        );
        Self {
            projector,
            scale,
            offset,
            height: options.height as f32,
        }
    }

    /// Page pixel (y down) of a projected point.
    fn pixel(&self, q: Vec2) -> Vec2 {
        let p = q * self.scale + self.offset;
        Vec2::new(p.x, self.height - p.y)
    }
}

/// A stroke's look on the page, after width and depth cueing (quantised so neighbours group).
#[derive(Clone, Copy, PartialEq)]
struct Pen {
    rgb: [u8; 3],
    width: f32,
}

/// Turns model segments into page segments and hands them to `draw`.
struct Projecting<'a, F: FnMut(Vec2, Vec2, Pen)> {
    layout: &'a Layout,
    options: &'a DrawOptions,
    draw: F,
}

impl<F: FnMut(Vec2, Vec2, Pen)> LineSink for Projecting<'_, F> {
    fn segment(&mut self, a: Vec3, b: Vec3, stroke: Stroke) {
        let (pa, n) = self.layout.projector.project(a);
        let (pb, _) = self.layout.projector.project(b);
        for k in 0..n {
            let depth = 0.5 * (pa[k].1 + pb[k].1);
            let base = match stroke.part {
                Part::Wood => self.options.wood,
                Part::Leaf => self.options.leaf,
            };
            let fade = if self.options.depth_cue {
                // Eight steps of fading, up to 55% of the way to the paper.
                (depth * 8.0).round() / 8.0 * 0.55
            } else {
                0.0
            };
            let mut rgb = base;
            for (c, p) in rgb.iter_mut().zip(self.options.paper) {
                *c = (*c as f32 + (p as f32 - *c as f32) * fade).round() as u8;
            }
            let w = stroke.width * self.layout.scale * self.layout.projector.width_scale(depth);
            let width = ((w.max(self.options.min_stroke)) * 10.0).round() / 10.0;
            (self.draw)(
                self.layout.pixel(pa[k].0),
                self.layout.pixel(pb[k].0),
                Pen { rgb, width },
            );
        }
    }
}

/// Writes the drawing as SVG to `out`, stroke by stroke (memory does not grow with the tree).
pub fn write_svg<W: Write>(
    source: &(impl LineSource + ?Sized),
    options: &DrawOptions,
    mut out: W,
) -> io::Result<W> {
    let layout = Layout::new(source, options);
    let [r, g, b] = options.paper;
    writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">",
        w = options.width,
        h = options.height
    )?;
    writeln!(
        out,
        "<title>Sylva tree, {} view</title>",
        options.view.name()
    )?;
    writeln!(
        out,
        "<rect width=\"100%\" height=\"100%\" fill=\"#{r:02x}{g:02x}{b:02x}\"/>"
    )?;
    writeln!(
        out,
        "<g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">"
    )?;
    let mut error: Option<io::Error> = None;
    let mut pen: Option<Pen> = None;
    let mut last = Vec2::NAN;
    let mut in_path = 0usize;
    {
        let out = &mut out;
        let mut sink = Projecting {
            layout: &layout,
            options,
            draw: |a: Vec2, b: Vec2, p: Pen| {
                if error.is_some() {
                    return;
                }
                let result = (|| -> io::Result<()> {
                    // A path per pen, its subpaths joined while they touch; long paths are
                    // closed so that no single element grows without bound.
                    if pen != Some(p) || in_path >= 2000 {
                        if pen.is_some() {
                            writeln!(out, "\"/>")?;
                        }
                        let [r, g, b] = p.rgb;
                        write!(
                            out,
                            "<path stroke=\"#{r:02x}{g:02x}{b:02x}\" stroke-width=\"{}\" d=\"",
                            p.width
                        )?;
                        pen = Some(p);
                        last = Vec2::NAN;
                        in_path = 0;
                    }
                    if a != last {
                        write!(out, "M{:.2} {:.2}", a.x, a.y)?;
                    }
                    write!(out, "L{:.2} {:.2}", b.x, b.y)?;
                    last = b;
                    in_path += 1;
                    Ok(())
                })();
                if let Err(e) = result {
                    error = Some(e);
                }
            },
        };
        source.lines(&mut sink);
    }
    if let Some(e) = error {
        return Err(e);
    }
    if pen.is_some() {
        writeln!(out, "\"/>")?;
    }
    writeln!(out, "</g>")?;
    write_scale_bar(&mut out, &layout, options)?;
    writeln!(out, "</svg>")?;
    out.flush()?;
    Ok(out)
}

/// A bar of a round number of metres in the bottom-left corner, for orthographic views.
fn write_scale_bar(out: &mut impl Write, layout: &Layout, options: &DrawOptions) -> io::Result<()> {
    if options.view == View::Perspective {
        return Ok(());
    }
    // The largest 1-2-5 length that fits in a fifth of the page.
    let most = 0.2 * options.width as f32 / layout.scale;
    let mut metres = 10f32.powf(most.log10().floor());
    for step in [2.0, 2.5, 2.0] {
        if metres * step <= most {
            metres *= step;
        }
    }
    let px = metres * layout.scale;
    let (x, y) = (options.margin, options.height as f32 - 0.4 * options.margin);
    writeln!(
        out,
        "<g stroke=\"#000\" stroke-width=\"1.5\"><path d=\"M{x:.1} {y:.1}h{px:.1}M{x:.1} {:.1}v6M{:.1} {:.1}v6\"/></g>",
        y - 3.0,
        x + px,
        y - 3.0
    )?;
    writeln!(
        out,
        "<text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"12\">{} m</text>",
        x + px + 6.0,
        y + 4.0,
        metres
    )
}

/// The drawing as SVG text.
pub fn draw_svg(source: &(impl LineSource + ?Sized), options: &DrawOptions) -> String {
    let bytes = write_svg(source, options, Vec::new()).expect("writing to memory cannot fail");
    String::from_utf8(bytes).expect("the SVG writer writes UTF-8")
}

/// The drawing as a PNG file's bytes.
pub fn draw_png(source: &(impl LineSource + ?Sized), options: &DrawOptions) -> Vec<u8> {
    raster(source, options)
        .encode_png()
        .expect("encoding an in-memory picture cannot fail")
}

/// The drawing as RGBA pixels (anti-aliased, opaque), row-major from the top-left.
pub fn draw_rgba(source: &(impl LineSource + ?Sized), options: &DrawOptions) -> Vec<u8> {
    // The paper is opaque, so tiny-skia's premultiplied pixels are plain RGBA.
    raster(source, options).take()
}

fn raster(source: &(impl LineSource + ?Sized), options: &DrawOptions) -> tiny_skia::Pixmap {
    use tiny_skia::{Color, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Transform};
    let layout = Layout::new(source, options);
    let mut pixmap = Pixmap::new(options.width.max(1), options.height.max(1))
        .expect("the page size is positive");
    let [r, g, b] = options.paper;
    pixmap.fill(Color::from_rgba8(r, g, b, 255));
    let mut path = PathBuilder::new();
    let mut pen: Option<Pen> = None;
    let mut last = Vec2::NAN;
    let mut count = 0usize;
    let flush = |path: &mut PathBuilder, pen: Pen, pixmap: &mut Pixmap| {
        let builder = std::mem::take(path);
        if let Some(p) = builder.finish() {
            let mut paint = Paint::default();
            let [r, g, b] = pen.rgb;
            paint.set_color_rgba8(r, g, b, 255);
            paint.anti_alias = true;
            let stroke = tiny_skia::Stroke {
                width: pen.width,
                line_cap: LineCap::Round,
                line_join: LineJoin::Round,
                ..Default::default()
            };
            pixmap.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
        }
    };
    {
        let mut sink = Projecting {
            layout: &layout,
            options,
            draw: |a: Vec2, b: Vec2, p: Pen| {
                if pen != Some(p) || count >= 2000 {
                    if let Some(old) = pen {
                        flush(&mut path, old, &mut pixmap);
                    }
                    pen = Some(p);
                    last = Vec2::NAN;
                    count = 0;
                }
                if a != last {
                    path.move_to(a.x, a.y);
                }
                path.line_to(b.x, b.y);
                last = b;
                count += 1;
            },
        };
        source.lines(&mut sink);
    }
    if let Some(old) = pen {
        flush(&mut path, old, &mut pixmap);
    }
    pixmap
}
