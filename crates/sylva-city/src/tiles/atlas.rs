//! Every impostor of a city packed into one picture (or a few): its coarse tiles then refer to
//! one image, so that a client fetches and decodes it once, makes its mipmaps once and draws
//! every far tree with one texture and material.
//!
//! Each impostor was its own PNG before; CesiumJS in software WebGL (Mesa's llvmpipe) spent
//! some 50 ms making each picture's mipmaps, whatever its size: a 1,000-tree city's 196
//! impostors took its load from 27 s without them to 42 s (`tests/cesium/view.mjs`).

use crate::error::CityError;
use crate::trees::plan::ProtoKey;
use crate::trees::prototypes::Prototype;
use image::codecs::png::{CompressionType, FilterType};
use image::{ExtendedColorType, ImageEncoder, RgbaImage};
use std::collections::HashMap;
use std::path::Path;

/// Most pixels along either side of a picture: every WebGL implementation takes textures of
/// 4,096 (the WebGL 2 minimum is 2,048, but no browser's renderer offers less than 4,096:
/// webglreport's survey), and a city of some 600 impostors fits in one.
pub const MAX_SIDE: u32 = 4096;

/// Clear pixels between two impostors, so that one's mipmaps take little of its neighbour's:
/// at the fourth mipmap a tree is drawn from, the gutter is still a quarter of a pixel wide.
const GUTTER: u32 = 4;

/// The pictures' file names (in the prototypes' folder): `impostors-0.png`, `impostors-1.png`.
pub fn file_name(page: usize) -> String {
    format!("impostors-{page}.png")
}

/// Where one picture lies: which page, and its top left corner there.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Place {
    page: usize,
    x: u32,
    y: u32,
}

/// Places pictures of `sizes` (width, height) in shelves, left to right and top to bottom,
/// each page at most [`MAX_SIDE`] square (a picture wider than that lies alone on its shelf,
/// its page as wide as it is). Returns each picture's place and each page's size.
fn shelve(sizes: &[(u32, u32)]) -> (Vec<Place>, Vec<(u32, u32)>) {
    let mut places = Vec::with_capacity(sizes.len());
    let mut pages: Vec<(u32, u32)> = Vec::new();
    // The open page's shelf: where it starts, how tall it is, and where the next picture goes.
    let (mut shelf_y, mut shelf_h, mut x) = (0u32, 0u32, 0u32);
    for &(w, h) in sizes {
        if pages.is_empty() {
            pages.push((0, 0));
        }
        if x > 0 && x + w > MAX_SIDE {
            shelf_y += shelf_h + GUTTER;
            (shelf_h, x) = (0, 0);
        }
        if shelf_y > 0 && shelf_y + h > MAX_SIDE {
            pages.push((0, 0));
            (shelf_y, shelf_h, x) = (0, 0, 0);
        }
        let page = pages.len() - 1;
        places.push(Place {
            page,
            x,
            y: shelf_y,
        });
        let size = &mut pages[page];
        size.0 = size.0.max(x + w);
        size.1 = size.1.max(shelf_y + h);
        shelf_h = shelf_h.max(h);
        x += w + GUTTER;
    }
    (places, pages)
}

/// Packs every prototype's impostor picture (`Prototype::impostor_png`, taken) into the
/// city's pictures, points each impostor at its picture and place, and returns the pictures'
/// files (names in the prototypes' folder, and bytes). The order is the keys', so the same
/// prototypes give the same bytes however they were grown.
pub fn pack(
    prototypes: &mut HashMap<ProtoKey, Prototype>,
) -> Result<Vec<(String, Vec<u8>)>, CityError> {
    let mut keys: Vec<ProtoKey> = prototypes
        .iter()
        .filter(|(_, p)| p.impostor.is_some() && p.impostor_png.is_some())
        .map(|(k, _)| k.clone())
        .collect();
    keys.sort();
    let mut pictures = Vec::with_capacity(keys.len());
    for k in &keys {
        let png = prototypes[k].impostor_png.as_deref().unwrap_or_default();
        let picture = image::load_from_memory_with_format(png, image::ImageFormat::Png)
            .map_err(|e| CityError::Growth(format!("the impostor of {}: {e}", k.file_stem())))?
            .to_rgba8();
        pictures.push(picture);
    }
    let sizes: Vec<(u32, u32)> = pictures.iter().map(|p| p.dimensions()).collect();
    let (places, page_sizes) = shelve(&sizes);
    let mut pages: Vec<RgbaImage> = page_sizes
        .iter()
        .map(|&(w, h)| RgbaImage::new(w, h))
        .collect();
    for ((k, picture), place) in keys.iter().zip(&pictures).zip(&places) {
        let page = &mut pages[place.page];
        let (pw, ph) = page.dimensions();
        image::imageops::replace(page, picture, place.x.into(), place.y.into());
        let p = prototypes.get_mut(k).expect("a key of the map");
        p.impostor_png = None;
        if let Some(imp) = p.impostor.as_mut() {
            let (w, h) = picture.dimensions();
            imp.uri = file_name(place.page);
            imp.rect = [
                place.x as f32 / pw as f32,
                place.y as f32 / ph as f32,
                w as f32 / pw as f32,
                h as f32 / ph as f32,
            ];
        }
    }
    pages
        .iter()
        .enumerate()
        .map(|(i, page)| {
            let name = file_name(i);
            let mut bytes = Vec::new();
            // The 100,000-tree demo's atlas (4,072 x 2,108): 11.1 MB in 0.3 s at the fast
            // level, 8.6 MB in 1.2 s at this one, 8.6 MB in 2.8 s at the best.
            image::codecs::png::PngEncoder::new_with_quality(
                &mut bytes,
                CompressionType::Default,
                FilterType::Adaptive,
            )
            .write_image(
                page.as_raw(),
                page.width(),
                page.height(),
                ExtendedColorType::Rgba8,
            )
            .map_err(|e| CityError::write(Path::new(&name), e))?;
            Ok((name, bytes))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two young trees' impostors packed: each one's picture lies in the atlas at its rect,
    /// pixel for pixel, and its quads' texture points stay inside that rect.
    #[test]
    fn each_impostor_lies_in_the_atlas_where_its_rect_says() {
        let keys: Vec<ProtoKey> = [("PYCA_B", 4), ("PLAC", 3)]
            .map(|(code, age)| ProtoKey {
                region: "InlVal".into(),
                code: code.into(),
                age,
                variant: 0,
            })
            .to_vec();
        let dir = tempfile::tempdir().unwrap();
        let mut grown = crate::trees::prototypes::grow_all(&keys, 0, dir.path()).unwrap();
        let own: Vec<RgbaImage> = keys
            .iter()
            .map(|k| {
                let png = grown[k].impostor_png.as_deref().unwrap();
                image::load_from_memory(png).unwrap().to_rgba8()
            })
            .collect();
        let files = pack(&mut grown).unwrap();
        assert_eq!(files.len(), 1);
        assert_eq!(files[0].0, "impostors-0.png");
        let atlas = image::load_from_memory(&files[0].1).unwrap().to_rgba8();
        let (aw, ah) = (atlas.width() as f32, atlas.height() as f32);
        for (k, picture) in keys.iter().zip(&own) {
            let p = &grown[k];
            assert!(p.impostor_png.is_none(), "the atlas takes the picture");
            let imp = p.impostor.as_ref().unwrap();
            assert_eq!(imp.uri, "impostors-0.png");
            let [left, top, width, height] = imp.rect;
            let (x0, y0) = ((left * aw).round() as u32, (top * ah).round() as u32);
            assert_eq!((width * aw).round() as u32, picture.width());
            assert_eq!((height * ah).round() as u32, picture.height());
            let opaque = picture.pixels().filter(|px| px[3] > 0).count();
            assert!(opaque > 100, "{}: {opaque} opaque pixels", k.file_stem());
            for (x, y, px) in picture.enumerate_pixels() {
                assert_eq!(
                    atlas.get_pixel(x0 + x, y0 + y),
                    px,
                    "{} at {x},{y}",
                    k.file_stem()
                );
            }
            let quads = imp.frame.quads_within(imp.rect);
            assert!(quads.uvs.iter().all(|&[u, v]| {
                u >= left - 1e-6
                    && u <= left + width + 1e-6
                    && v >= top - 1e-6
                    && v <= top + height + 1e-6
            }));
        }
        // Packed again, nothing is left to pack.
        assert!(pack(&mut grown).unwrap().is_empty());
    }

    #[test]
    fn shelves_fill_a_page_then_open_the_next_and_never_overlap() {
        // 80 pictures 1,000 wide: four to a shelf (4 x 1,004 - 4 = 4,012), 31 shelves of 132
        // to a page (31 x 132 - 4 = 4,088).
        let sizes = vec![(1000, 128); 150];
        let (places, pages) = shelve(&sizes);
        assert_eq!(pages.len(), 2);
        assert_eq!(
            places[3],
            Place {
                page: 0,
                x: 3012,
                y: 0
            }
        );
        assert_eq!(
            places[4],
            Place {
                page: 0,
                x: 0,
                y: 132
            }
        );
        assert_eq!(
            places[124],
            Place {
                page: 1,
                x: 0,
                y: 0
            }
        );
        assert!(pages.iter().all(|&(w, h)| w <= MAX_SIDE && h <= MAX_SIDE));
        for (i, a) in places.iter().enumerate() {
            for b in &places[i + 1..] {
                let apart = a.page != b.page
                    || a.x + 1000 + GUTTER <= b.x
                    || b.x + 1000 + GUTTER <= a.x
                    || a.y + 128 + GUTTER <= b.y
                    || b.y + 128 + GUTTER <= a.y;
                assert!(apart, "{a:?} {b:?}");
            }
        }
        // A picture wider than a page lies alone on its shelf.
        let (places, pages) = shelve(&[(100, 10), (5000, 10), (100, 10)]);
        let at: Vec<(usize, u32, u32)> = places.iter().map(|p| (p.page, p.x, p.y)).collect();
        assert_eq!(at, [(0, 0, 0), (0, 0, 14), (0, 0, 28)]);
        assert_eq!(pages, [(5000, 38)]);
    }
}
