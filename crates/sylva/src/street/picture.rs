//! The site drawn across the street, looking along it: roadway, curb, sidewalk, the building's
//! wall with its awnings and signs, lines with their clearance, lamps, the clear heights, a
//! 1.8 m person on the sidewalk, and the tree with whatever is in the way marked red.

use super::conflicts::{Kind, Zones, flare_radius};
use super::crown::leaf_centre;
use super::site::Site;
use crate::Skeleton;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

/// An opaque picture: width, height, and 4 bytes (RGBA) per pixel.
pub type Rgba = (u32, u32, Vec<u8>);

/// Draws the site and the tree, `size` pixels (each side 64 to 8192). `marked` kinds have
/// their zones outlined in red.
pub fn site_picture(skeleton: &Skeleton, site: &Site, marked: &[Kind], size: (u32, u32)) -> Rgba {
    let (w, h) = (size.0.clamp(64, 8192), size.1.clamp(64, 8192));
    let mut pixmap = Pixmap::new(w, h).expect("64 to 8192 pixels a side is a valid size");
    pixmap.fill(Color::from_rgba8(246, 246, 242, 255));
    // The frame: y across, z up.
    let s = &site.street;
    let (mut y0, mut y1) = (s.curb - 4.0, s.sidewalk[1] + 1.0);
    let mut top = s.roadway_clearance.max(s.sidewalk_clearance) + 1.0;
    if let Some(f) = &site.facade {
        y1 = y1.max(f.setback + 1.5);
        top = top.max(f.height + 1.0);
    }
    for wire in &site.wire {
        y0 = y0.min(wire.offset - wire.clearance - 0.5);
        y1 = y1.max(wire.offset + wire.clearance + 0.5);
        top = top.max(wire.height + wire.clearance + 0.5);
    }
    for l in &site.light {
        top = top.max(l.height + l.clearance + 0.5);
    }
    for c in &skeleton.sections {
        y0 = y0.min(c.position.y as f64 - 0.5);
        y1 = y1.max(c.position.y as f64 + 0.5);
        top = top.max(c.position.z as f64 + 0.5);
    }
    for l in &skeleton.leaves {
        y0 = y0.min(l.position.y as f64 - 0.5);
        y1 = y1.max(l.position.y as f64 + 0.5);
        top = top.max(l.position.z as f64 + 0.5);
    }
    let ground = h as f64 * 0.92;
    let scale = ((w as f64 * 0.96) / (y1 - y0)).min((ground - h as f64 * 0.03) / top);
    let left = (w as f64 - (y1 - y0) * scale) / 2.0;
    let px = |y: f64, z: f64| {
        (
            (left + (y - y0) * scale) as f32,
            (ground - z * scale) as f32,
        )
    };
    let paint = |r: u8, g: u8, b: u8, a: u8| {
        let mut p = Paint::default();
        p.set_color_rgba8(r, g, b, a);
        p.anti_alias = true;
        p
    };
    let rect = |pm: &mut Pixmap, ya: f64, za: f64, yb: f64, zb: f64, p: &Paint| {
        let (xa, ta) = px(ya.min(yb), za.max(zb));
        let (xb, tb) = px(ya.max(yb), za.min(zb));
        if let Some(r) = Rect::from_ltrb(xa, ta, xb.max(xa + 1.0), tb.max(ta + 1.0)) {
            pm.fill_rect(r, p, Transform::identity(), None);
        }
    };
    let outline = |pm: &mut Pixmap, ya: f64, za: f64, yb: f64, zb: f64, p: &Paint| {
        let (xa, ta) = px(ya.min(yb), za.max(zb));
        let (xb, tb) = px(ya.max(yb), za.min(zb));
        if let Some(r) = Rect::from_ltrb(xa, ta, xb.max(xa + 1.0), tb.max(ta + 1.0)) {
            let path = PathBuilder::from_rect(r);
            let stroke = Stroke {
                width: 2.0,
                ..Stroke::default()
            };
            pm.stroke_path(&path, p, &stroke, Transform::identity(), None);
        }
    };
    let circle = |pm: &mut Pixmap, y: f64, z: f64, r: f32, p: &Paint, fill: bool| {
        let (x, t) = px(y, z);
        if let Some(path) = PathBuilder::from_circle(x, t, r.max(0.5)) {
            if fill {
                pm.fill_path(&path, p, FillRule::Winding, Transform::identity(), None);
            } else {
                let stroke = Stroke {
                    width: 1.5,
                    ..Stroke::default()
                };
                pm.stroke_path(&path, p, &stroke, Transform::identity(), None);
            }
        }
    };
    let zones = Zones::new(site);
    let red = paint(215, 30, 30, 255);
    let zone = paint(200, 120, 40, 40);
    // Ground: roadway, curb, strip, sidewalk.
    rect(&mut pixmap, y0, -0.3, s.curb, 0.0, &paint(80, 80, 84, 255));
    rect(
        &mut pixmap,
        s.curb,
        -0.3,
        s.sidewalk[0].max(s.curb),
        0.0,
        &paint(120, 100, 70, 255),
    );
    rect(
        &mut pixmap,
        s.sidewalk[0],
        -0.3,
        s.sidewalk[1],
        0.0,
        &paint(190, 190, 185, 255),
    );
    rect(
        &mut pixmap,
        s.sidewalk[1],
        -0.3,
        y1,
        0.0,
        &paint(150, 140, 120, 255),
    );
    // Clear heights over the roadway and the sidewalk.
    rect(&mut pixmap, y0, 0.0, s.curb, s.roadway_clearance, &zone);
    rect(
        &mut pixmap,
        s.sidewalk[0],
        0.0,
        s.sidewalk[1],
        s.sidewalk_clearance,
        &zone,
    );
    if marked.contains(&Kind::Roadway) {
        outline(&mut pixmap, y0, 0.0, s.curb, s.roadway_clearance, &red);
    }
    if marked.contains(&Kind::Sidewalk) {
        outline(
            &mut pixmap,
            s.sidewalk[0],
            0.0,
            s.sidewalk[1],
            s.sidewalk_clearance,
            &red,
        );
    }
    if let Some(t) = &site.sight_triangle {
        // Seen from the side, the triangle's band across its y range.
        let ys = t.corners.map(|c| c[1]);
        let (a, b) = (
            ys.iter().copied().fold(f64::INFINITY, f64::min),
            ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        rect(&mut pixmap, a, t.low, b, t.high, &paint(60, 120, 200, 40));
        if marked.contains(&Kind::SightTriangle) {
            outline(&mut pixmap, a, t.low, b, t.high, &red);
        }
    }
    if let Some(f) = &site.facade {
        rect(
            &mut pixmap,
            f.setback,
            0.0,
            y1,
            f.height,
            &paint(205, 190, 170, 255),
        );
        if marked.contains(&Kind::Facade) {
            outline(&mut pixmap, f.setback, 0.0, y1, f.height, &red);
        }
        for (kind, boxes, colour) in [
            (Kind::Awning, &site.awning, paint(150, 60, 50, 255)),
            (Kind::Sign, &site.sign, paint(60, 90, 150, 255)),
        ] {
            for b in boxes {
                rect(
                    &mut pixmap,
                    f.setback - b.reach,
                    b.bottom,
                    f.setback,
                    b.top,
                    &colour,
                );
                if marked.contains(&kind) {
                    outline(
                        &mut pixmap,
                        f.setback - b.reach,
                        b.bottom,
                        f.setback,
                        b.top,
                        &red,
                    );
                }
            }
        }
    }
    for wire in &site.wire {
        let r = (wire.clearance * scale) as f32;
        circle(
            &mut pixmap,
            wire.offset,
            wire.height,
            r,
            &paint(40, 40, 40, 120),
            false,
        );
        circle(
            &mut pixmap,
            wire.offset,
            wire.height,
            3.0,
            &paint(20, 20, 20, 255),
            true,
        );
        if marked.contains(&Kind::Wire) {
            circle(&mut pixmap, wire.offset, wire.height, r, &red, false);
        }
    }
    for l in &site.light {
        rect(
            &mut pixmap,
            l.y - 0.06,
            0.0,
            l.y + 0.06,
            l.height,
            &paint(70, 70, 75, 255),
        );
        circle(
            &mut pixmap,
            l.y,
            l.height,
            (l.clearance * scale) as f32,
            &paint(200, 170, 40, 160),
            false,
        );
        circle(
            &mut pixmap,
            l.y,
            l.height,
            4.0,
            &paint(240, 200, 40, 255),
            true,
        );
        if marked.contains(&Kind::Light) {
            circle(
                &mut pixmap,
                l.y,
                l.height,
                (l.clearance * scale) as f32,
                &red,
                false,
            );
        }
    }
    // A 1.8 m person on the sidewalk, beside the tree.
    let py = (s.sidewalk[0] + s.sidewalk[1]) / 2.0;
    let body = paint(60, 60, 70, 255);
    rect(&mut pixmap, py - 0.18, 0.0, py + 0.18, 1.55, &body);
    circle(&mut pixmap, py, 1.67, (0.13 * scale) as f32, &body, true);
    // The tree: stems by order, then leaves; anything in the way in red.
    let bark = paint(95, 75, 60, 255);
    for stem in &skeleton.stems {
        let sec = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        for pair in sec.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let mut path = PathBuilder::new();
            let (xa, ta) = px(a.position.y as f64, a.position.z as f64);
            let (xb, tb) = px(b.position.y as f64, b.position.z as f64);
            path.move_to(xa, ta);
            path.line_to(xb, tb);
            let Some(path) = path.finish() else { continue };
            let width = ((a.radius + b.radius) as f64 * scale).max(0.8) as f32;
            let hit = zones.kind_of(a.position, Some(stem.level)).is_some();
            let stroke = Stroke {
                width,
                ..Stroke::default()
            };
            pixmap.stroke_path(
                &path,
                if hit { &red } else { &bark },
                &stroke,
                Transform::identity(),
                None,
            );
        }
    }
    let leaf = paint(70, 120, 45, 150);
    let leaf_hit = paint(230, 40, 40, 200);
    for l in &skeleton.leaves {
        let c = leaf_centre(l);
        let r = (l.length.max(l.width) as f64 * scale * 0.5).clamp(0.7, 6.0) as f32;
        let hit = zones.kind_of(c, None).is_some();
        circle(
            &mut pixmap,
            c.y as f64,
            c.z as f64,
            r,
            if hit { &leaf_hit } else { &leaf },
            true,
        );
    }
    if marked.contains(&Kind::TrunkFlare) {
        let r = flare_radius(skeleton);
        outline(&mut pixmap, -r, 0.0, r, 0.5, &red);
    }
    // Every pixel is opaque (the background is), so premultiplied is straight RGBA.
    (w, h, pixmap.take())
}
