//! Pictures put together: text (captions, labels) in the Ubuntu Light font that egui ships,
//! rasterised with ab_glyph and blended over the RGBA pixels; pictures side by side or in a
//! grid; numbers as captions write them.

use crate::Picture;
use ab_glyph::{Font, FontRef, PxScale, ScaleFont};

fn font() -> FontRef<'static> {
    // The font is compiled in and known good; a failure here is a build defect.
    FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).expect("bundled font parses")
}

/// The bundled font's bytes (Ubuntu Light), for callers that draw text with other tools
/// (charts) and should match the captions.
pub const FONT: &[u8] = epaint_default_fonts::UBUNTU_LIGHT;

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

/// Width in pixels of `text` at `size` pixels.
pub fn text_width(text: &str, size: f32) -> f32 {
    let font = font();
    let scaled = font.as_scaled(PxScale::from(size));
    let mut width = 0.0;
    let mut previous = None;
    for c in text.chars() {
        let id = scaled.glyph_id(c);
        if let Some(p) = previous {
            width += scaled.kern(p, id);
        }
        width += scaled.h_advance(id);
        previous = Some(id);
    }
    width
}

/// Draws `text` with its top-left corner at (`x`, `y`), `size` pixels tall, in `colour`.
pub fn draw_text(picture: &mut Picture, x: f32, y: f32, size: f32, text: &str, colour: [u8; 3]) {
    let font = font();
    let scaled = font.as_scaled(PxScale::from(size));
    let mut caret = ab_glyph::point(x, y + scaled.ascent());
    let mut previous = None;
    for c in text.chars() {
        let id = scaled.glyph_id(c);
        if let Some(p) = previous {
            caret.x += scaled.kern(p, id);
        }
        let glyph = id.with_scale_and_position(PxScale::from(size), caret);
        caret.x += scaled.h_advance(id);
        previous = Some(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let px = bounds.min.x as i64 + gx as i64;
            let py = bounds.min.y as i64 + gy as i64;
            if px < 0 || py < 0 || px >= picture.width as i64 || py >= picture.height as i64 {
                return;
            }
            let i = ((py as u32 * picture.width + px as u32) * 4) as usize;
            let a = coverage.clamp(0.0, 1.0);
            for (k, &c) in colour.iter().enumerate() {
                let under = picture.rgba[i + k] as f32;
                picture.rgba[i + k] = (under + (c as f32 - under) * a).round() as u8;
            }
        });
    }
}

/// `line` broken at spaces into lines no wider than `width` pixels at `size` (a word wider
/// than that stands alone on its line).
fn wrapped(line: &str, width: f32, size: f32) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in line.split(' ') {
        let longer = if current.is_empty() {
            word.to_string()
        } else {
            format!("{current} {word}")
        };
        if !current.is_empty() && text_width(&longer, size) > width {
            out.push(std::mem::replace(&mut current, word.to_string()));
        } else {
            current = longer;
        }
    }
    out.push(current);
    out
}

/// A copy of `picture` with a white band of `lines` below it, each line centred; a line wider
/// than the picture goes on over as many lines as it needs.
pub fn with_caption(picture: &Picture, lines: &[String], size: f32) -> Picture {
    let margin = 4.0;
    let room = picture.width as f32 - 2.0 * margin;
    let lines: Vec<String> = (lines.iter())
        .flat_map(|l| wrapped(l, room, size))
        .collect();
    let line_height = (size * 1.35).ceil() as u32;
    let band = line_height * lines.len() as u32 + (size * 0.6) as u32;
    let mut out = Picture {
        width: picture.width,
        height: picture.height + band,
        rgba: vec![255; (picture.width * (picture.height + band) * 4) as usize],
        stats: picture.stats,
    };
    out.rgba[..picture.rgba.len()].copy_from_slice(&picture.rgba);
    for (k, line) in lines.iter().enumerate() {
        let x = ((picture.width as f32 - text_width(line, size)) / 2.0).max(margin);
        let y = picture.height as f32 + (size * 0.3) + (k as u32 * line_height) as f32;
        draw_text(&mut out, x, y, size, line, [20, 20, 20]);
    }
    out
}

/// Pictures side by side, with a white gap between them.
pub fn side_by_side(pictures: &[Picture], gap: u32) -> Picture {
    tile(pictures, pictures.len().max(1) as u32, gap, 255)
}

/// Pictures in a grid of `columns`, left to right and top to bottom, each in a cell as large
/// as the largest, `gap` pixels apart, on a background of `fill` bytes (255: white; 0:
/// transparent).
pub fn tile(pictures: &[Picture], columns: u32, gap: u32, fill: u8) -> Picture {
    let columns = columns.max(1);
    let rows = (pictures.len() as u32).div_ceil(columns).max(1);
    let cell_w = pictures.iter().map(|p| p.width).max().unwrap_or(16);
    let cell_h = pictures.iter().map(|p| p.height).max().unwrap_or(16);
    let width = columns * cell_w + gap * (columns - 1);
    let height = rows * cell_h + gap * (rows - 1);
    let mut out = Picture {
        width,
        height,
        rgba: vec![fill; (width * height * 4) as usize],
        stats: Default::default(),
    };
    for (i, p) in pictures.iter().enumerate() {
        let (left, top) = (
            (i as u32 % columns) * (cell_w + gap),
            (i as u32 / columns) * (cell_h + gap),
        );
        for y in 0..p.height {
            let src = &p.rgba[(y * p.width * 4) as usize..((y + 1) * p.width * 4) as usize];
            let dst = (((top + y) * width + left) * 4) as usize;
            out.rgba[dst..dst + src.len()].copy_from_slice(src);
        }
    }
    out
}

/// Two frames of one forest side by side, captioned: with range degradation (LOD) on the left,
/// at full detail on the right, each with what it drew and how long it took.
pub fn lod_comparison(with: (&Picture, f64), without: (&Picture, f64), width: u32) -> Picture {
    let size = (width as f32 / 48.0).clamp(11.0, 22.0);
    let side = |title: &str, (p, ms): (&Picture, f64)| {
        with_caption(p, &[title.to_string(), p.stats.describe(ms)], size)
    };
    side_by_side(
        &[
            side("with range degradation (LOD)", with),
            side("full detail (no LOD)", without),
        ],
        8,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn captions_put_dark_ink_in_the_band_only() {
        let p = Picture {
            width: 200,
            height: 50,
            rgba: vec![255; 200 * 50 * 4],
            stats: Default::default(),
        };
        let c = with_caption(&p, &["LOD 123".to_string()], 16.0);
        assert!(c.height > 50);
        let dark = |y0: u32, y1: u32| {
            (y0..y1)
                .flat_map(|y| (0..c.width).map(move |x| (x, y)))
                .filter(|&(x, y)| c.pixel(x, y)[0] < 128)
                .count()
        };
        assert_eq!(dark(0, 50), 0, "the picture itself is untouched");
        assert!(dark(50, c.height) > 30, "the caption is drawn");
        assert!(text_width("wide text", 16.0) > text_width("w", 16.0));
        let both = side_by_side(&[p.clone(), p], 10);
        assert_eq!((both.width, both.height), (410, 50));
    }

    /// A caption wider than its picture goes on over more lines, none cut off at the edge.
    #[test]
    fn a_long_caption_is_wrapped_within_the_picture() {
        let p = Picture {
            width: 300,
            height: 20,
            rgba: vec![255; 300 * 20 * 4],
            stats: Default::default(),
        };
        let long = "a plane on a narrow street: first facade, awning, sign, roadway and sidewalk";
        assert!(text_width(long, 16.0) > 300.0);
        let one = with_caption(&p, &["short".to_string()], 16.0);
        let c = with_caption(&p, &[long.to_string()], 16.0);
        assert!(c.height > one.height, "{} {}", c.height, one.height);
        // No ink in the last columns: nothing runs off the right edge.
        let edge = (20..c.height)
            .flat_map(|y| (c.width - 3..c.width).map(move |x| (x, y)))
            .filter(|&(x, y)| c.pixel(x, y)[0] < 200)
            .count();
        assert_eq!(edge, 0);
        let lines = wrapped(long, 292.0, 16.0);
        assert!(lines.len() >= 2 && lines.iter().all(|l| text_width(l, 16.0) <= 292.0));
        assert_eq!(lines.join(" "), long);
    }

    #[test]
    fn numbers_are_grouped() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(1000), "1,000");
        assert_eq!(grouped(1234567), "1,234,567");
    }
}
