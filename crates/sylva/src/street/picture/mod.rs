//! The site and the tree in two panels: across the street looking along it (roadway, curb,
//! sidewalk, the building's wall with its awnings and signs, lines and lamps with their
//! clearances, the clear heights, a 1.8 m person), and from above (the same fixtures in plan,
//! the sight triangle, the crown's spread). Whatever is in the way is red; the zones entered
//! this year are outlined in red. A pruning cycle is drawn across the street, before and
//! after its cuts, each cut ringed in blue.

pub mod cad;
mod canvas;
mod plan;

use super::energy::crown::leaf_centre;
use super::site::Site;
use super::work::conflicts::{Kind, Zones, flare_radius};
use crate::Skeleton;
use crate::growth::CutMark;
use canvas::{Canvas, paint};
use tiny_skia::{Color, Pixmap};

/// An opaque picture: width, height, and 4 bytes (RGBA) per pixel.
pub type Rgba = (u32, u32, Vec<u8>);

/// The cross-street extent the panels share: from beyond the curb to past the wall, and
/// whatever of the tree and the lines reaches further, metres.
fn across(skeleton: &Skeleton, site: &Site) -> (f64, f64) {
    let s = &site.street;
    let (mut y0, mut y1) = (s.curb - 4.0, s.sidewalk[1] + 1.0);
    if let Some(f) = &site.facade {
        y1 = y1.max(f.setback + 1.5);
    }
    for wire in &site.wire {
        y0 = y0.min(wire.offset - wire.clearance - 0.5);
        y1 = y1.max(wire.offset + wire.clearance + 0.5);
    }
    let points = skeleton.sections.iter().map(|c| c.position);
    for p in points.chain(skeleton.leaves.iter().map(|l| l.position)) {
        y0 = y0.min(p.y as f64 - 0.5);
        y1 = y1.max(p.y as f64 + 0.5);
    }
    (y0, y1)
}

/// Draws the site and the tree, `size` pixels (each side 64 to 8192): the section on the left
/// half, the plan on the right. `marked` kinds have their zones outlined in red.
pub fn site_picture(skeleton: &Skeleton, site: &Site, marked: &[Kind], size: (u32, u32)) -> Rgba {
    let zones = Zones::new(site);
    two_panels(size, |pixmap, [left, right]| {
        section(
            pixmap,
            left,
            (skeleton, skeleton),
            site,
            &zones,
            (marked, &[]),
        );
        plan::plan(pixmap, right, skeleton, site, &zones, marked);
    })
}

/// A pruning cycle across the street, `size` pixels (each side 64 to 8192): the tree before
/// the cuts on the left, after them on the right, at one scale (the tree before sets it).
/// Every cut is ringed in blue, on both.
pub fn pruning_picture(
    before: &Skeleton,
    after: &Skeleton,
    site: &Site,
    cuts: &[CutMark],
    size: (u32, u32),
) -> Rgba {
    let zones = Zones::new(site);
    two_panels(size, |pixmap, panels| {
        for (panel, tree) in panels.into_iter().zip([before, after]) {
            section(pixmap, panel, (tree, before), site, &zones, (&[], cuts));
        }
    })
}

/// A picture `size` pixels (each side 64 to 8192) of two panels side by side, each drawn by
/// `draw` into its rectangle (x, y, width, height), with a grey line between them.
fn two_panels(size: (u32, u32), draw: impl FnOnce(&mut Pixmap, [(f64, f64, f64, f64); 2])) -> Rgba {
    let (w, h) = (size.0.clamp(64, 8192), size.1.clamp(64, 8192));
    let mut pixmap = Pixmap::new(w, h).expect("64 to 8192 pixels a side is a valid size");
    pixmap.fill(Color::from_rgba8(246, 246, 242, 255));
    let half = w as f64 / 2.0;
    draw(
        &mut pixmap,
        [(0.0, 0.0, half, h as f64), (half, 0.0, half, h as f64)],
    );
    let mut c = Canvas::fit(
        &mut pixmap,
        (0.0, 0.0, w as f64, h as f64),
        (0.0, 1.0),
        (0.0, 1.0),
    );
    c.segment((0.5, -0.1), (0.5, 1.1), 1.0, &paint(160, 160, 160, 255));
    // Every pixel is opaque (the background is), so premultiplied is straight RGBA.
    (w, h, pixmap.take())
}

/// The section across the street, looking along it: y to the right, z up. It draws `tree`,
/// framed to hold `frame` (the same tree, or a larger one drawn beside it), with `marked`
/// kinds' zones outlined in red and `cuts` ringed in blue.
fn section(
    pixmap: &mut Pixmap,
    panel: (f64, f64, f64, f64),
    (skeleton, frame): (&Skeleton, &Skeleton),
    site: &Site,
    zones: &Zones,
    (marked, cuts): (&[Kind], &[CutMark]),
) {
    let s = &site.street;
    let (y0, y1) = across(frame, site);
    let mut top = s.roadway_clearance.max(s.sidewalk_clearance) + 1.0;
    if let Some(f) = &site.facade {
        top = top.max(f.height + 1.0);
    }
    for wire in &site.wire {
        top = top.max(wire.height + wire.clearance + 0.5);
    }
    for l in &site.light {
        top = top.max(l.height + l.clearance + 0.5);
    }
    let points = frame.sections.iter().map(|c| c.position);
    for p in points.chain(frame.leaves.iter().map(|l| l.position)) {
        top = top.max(p.z as f64 + 0.5);
    }
    let mut c = Canvas::fit(pixmap, panel, (y0, y1), (0.0, top));
    let red = paint(215, 30, 30, 255);
    let zone = paint(200, 120, 40, 40);
    let mark = |c: &mut Canvas, kind: Kind, a: (f64, f64), b: (f64, f64)| {
        if marked.contains(&kind) {
            c.outline(a, b, &red);
        }
    };
    // Ground: roadway, strip, sidewalk, and what lies behind it.
    c.rect((y0, -0.3), (s.curb, 0.0), &paint(80, 80, 84, 255));
    c.rect(
        (s.curb, -0.3),
        (s.sidewalk[0].max(s.curb), 0.0),
        &paint(120, 100, 70, 255),
    );
    c.rect(
        (s.sidewalk[0], -0.3),
        (s.sidewalk[1], 0.0),
        &paint(190, 190, 185, 255),
    );
    c.rect((s.sidewalk[1], -0.3), (y1, 0.0), &paint(150, 140, 120, 255));
    // Clear heights over the roadway and the sidewalk.
    c.rect((y0, 0.0), (s.curb, s.roadway_clearance), &zone);
    c.rect(
        (s.sidewalk[0], 0.0),
        (s.sidewalk[1], s.sidewalk_clearance),
        &zone,
    );
    mark(
        &mut c,
        Kind::Roadway,
        (y0, 0.0),
        (s.curb, s.roadway_clearance),
    );
    mark(
        &mut c,
        Kind::Sidewalk,
        (s.sidewalk[0], 0.0),
        (s.sidewalk[1], s.sidewalk_clearance),
    );
    if let Some(t) = &site.sight_triangle {
        // Seen from the side, the triangle's band across its y range.
        let ys = t.corners.map(|c| c[1]);
        let a = ys.iter().copied().fold(f64::INFINITY, f64::min);
        let b = ys.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        c.rect((a, t.low), (b, t.high), &paint(60, 120, 200, 40));
        mark(&mut c, Kind::SightTriangle, (a, t.low), (b, t.high));
    }
    if let Some(f) = &site.facade {
        c.rect((f.setback, 0.0), (y1, f.height), &paint(205, 190, 170, 255));
        mark(&mut c, Kind::Facade, (f.setback, 0.0), (y1, f.height));
        for (kind, boxes, colour) in [
            (Kind::Awning, &site.awning, paint(150, 60, 50, 255)),
            (Kind::Sign, &site.sign, paint(60, 90, 150, 255)),
        ] {
            for b in boxes {
                let (lo, hi) = ((f.setback - b.reach, b.bottom), (f.setback, b.top));
                c.rect(lo, hi, &colour);
                mark(&mut c, kind, lo, hi);
            }
        }
    }
    for wire in &site.wire {
        let at = (wire.offset, wire.height);
        let r = c.pixels(wire.clearance);
        c.circle(at, r, &paint(40, 40, 40, 120), false);
        // The minimum the utility keeps at all times, inside the clearance it cuts to.
        c.circle(at, c.pixels(wire.minimum), &paint(160, 40, 40, 160), false);
        c.circle(at, 3.0, &paint(20, 20, 20, 255), true);
        if marked.contains(&Kind::Wire) {
            c.circle(at, r, &red, false);
        }
    }
    for l in &site.light {
        let at = (l.y, l.height);
        let r = c.pixels(l.clearance);
        c.rect(
            (l.y - 0.06, 0.0),
            (l.y + 0.06, l.height),
            &paint(70, 70, 75, 255),
        );
        c.circle(at, r, &paint(200, 170, 40, 160), false);
        c.circle(at, 4.0, &paint(240, 200, 40, 255), true);
        if marked.contains(&Kind::Light) {
            c.circle(at, r, &red, false);
        }
    }
    // A 1.8 m person on the sidewalk.
    let py = (s.sidewalk[0] + s.sidewalk[1]) / 2.0;
    let body = paint(60, 60, 70, 255);
    c.rect((py - 0.18, 0.0), (py + 0.18, 1.55), &body);
    let head = c.pixels(0.13);
    c.circle((py, 1.67), head, &body, true);
    // The tree: stems, then leaves; anything in the way in red.
    let bark = paint(95, 75, 60, 255);
    for stem in &skeleton.stems {
        let sec = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        for pair in sec.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let width = c.pixels((a.radius + b.radius) as f64).max(0.8);
            let hit = zones.kind_of(a.position, Some(stem.level)).is_some();
            let (pa, pb) = (a.position.as_dvec3(), b.position.as_dvec3());
            c.segment(
                (pa.y, pa.z),
                (pb.y, pb.z),
                width,
                if hit { &red } else { &bark },
            );
        }
    }
    leaves(&mut c, skeleton, zones, (150, 200), |p| {
        (p.y as f64, p.z as f64)
    });
    if marked.contains(&Kind::TrunkFlare) {
        let r = flare_radius(skeleton);
        c.outline((-r, 0.0), (r, 0.5), &red);
    }
    let ring = paint(40, 80, 230, 255);
    for cut in cuts {
        let r = c.pixels(cut.radius as f64 * 4.0).max(4.0);
        c.circle((cut.at.y as f64, cut.at.z as f64), r, &ring, false);
    }
}

/// Every leaf as a dot its size (0.7 to 6 pixels), green, or red where it is in the way; the
/// alphas of the two paints, and where `view` puts a point on the canvas, are the view's own.
fn leaves(
    c: &mut Canvas,
    skeleton: &Skeleton,
    zones: &Zones,
    (alpha, alpha_hit): (u8, u8),
    view: impl Fn(glam::Vec3) -> (f64, f64),
) {
    let leaf = paint(70, 120, 45, alpha);
    let leaf_hit = paint(230, 40, 40, alpha_hit);
    for l in &skeleton.leaves {
        let at = leaf_centre(l);
        let r = c.pixels(l.length.max(l.width) as f64 * 0.5).clamp(0.7, 6.0);
        let hit = zones.kind_of(at, None).is_some();
        c.circle(view(at), r, if hit { &leaf_hit } else { &leaf }, true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::growth::survey::report::Cohort;

    fn red_pixels(rgba: &[u8], w: u32, half: std::ops::Range<u32>) -> usize {
        rgba.chunks(4)
            .enumerate()
            .filter(|(i, p)| {
                half.contains(&(*i as u32 % w)) && p[0] > 180 && p[1] < 90 && p[2] < 90
            })
            .count()
    }

    #[test]
    fn what_is_in_the_way_is_red_in_both_panels_and_nothing_else_is() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let tree = Cohort::new(vec![plane], 0).advance_to(8.0).remove(0);
        let street = "[street]\ncurb = -3.5\nsidewalk = [3.0, 5.0]\nroadway_clearance = 0.5\nsidewalk_clearance = 0.5\n";
        let clear = Site::parse(street, "clear").unwrap();
        let (w, h, rgba) = site_picture(&tree, &clear, &[], (400, 300));
        assert_eq!((w, h, rgba.len()), (400, 300, 400 * 300 * 4));
        assert_eq!(
            red_pixels(&rgba, w, 0..w),
            0,
            "a wide strip and no fixtures: nothing red"
        );
        // A line through the crown: red in the section and in the plan.
        let wired = Site::parse(
            &format!(
                "{street}[[wire]]\nheight = 4.0\noffset = 0.0\nclearance = 1.0\nminimum = 0.46\n"
            ),
            "wired",
        )
        .unwrap();
        let (w, _, rgba) = site_picture(&tree, &wired, &[Kind::Wire], (400, 300));
        assert!(red_pixels(&rgba, w, 0..w / 2) > 100);
        assert!(red_pixels(&rgba, w, w / 2..w) > 100);
    }

    #[test]
    fn a_pruning_picture_shows_the_wire_cleared_and_rings_the_cuts() {
        use crate::growth::{Grower, GrowthOptions};
        use crate::street::accounts::pruner::Pruner;
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, GrowthOptions::default());
        let street = "[street]\ncurb = -3.5\nsidewalk = [3.0, 5.0]\nroadway_clearance = 0.5\nsidewalk_clearance = 0.5\n";
        let site = Site::parse(
            &format!(
                "{street}[[wire]]\nheight = 6.0\noffset = 0.0\nclearance = 1.5\nminimum = 0.46\n"
            ),
            "wired",
        )
        .unwrap();
        let mut pruner = Pruner::new(&site, None).unwrap();
        grower.advance_to(8.0);
        let (year, before) = pruner
            .year(&mut grower, 8.0)
            .expect("the line cycle falls at 8");
        let after = grower.skeleton();
        let (w, h, rgba) = pruning_picture(&before, &after, &site, year.marks(), (600, 300));
        assert_eq!((w, h), (600, 300));
        // Before: the crown in the wire's clearance is red; after: none is.
        assert!(red_pixels(&rgba, w, 0..w / 2) > 100);
        assert_eq!(red_pixels(&rgba, w, w / 2..w), 0);
        // The cuts are ringed in blue on both sides.
        let blue = |half: std::ops::Range<u32>| {
            rgba.chunks(4)
                .enumerate()
                .filter(|(i, p)| {
                    half.contains(&(*i as u32 % w)) && p[2] > 180 && p[0] < 90 && p[1] < 120
                })
                .count()
        };
        assert!(blue(0..w / 2) > 20 && blue(w / 2..w) > 20);
    }
}
