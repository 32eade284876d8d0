//! The site from above: x along the street to the right, y across it upwards (roadway at the
//! bottom, buildings at the top).

use super::canvas::{Canvas, paint};
use super::{across, leaves};
use crate::Skeleton;
use crate::street::site::Site;
use crate::street::work::conflicts::{Kind, Zones, flare_radius};
use tiny_skia::Pixmap;

/// Draws the plan into `panel` of `pixmap`.
pub(super) fn plan(
    pixmap: &mut Pixmap,
    panel: (f64, f64, f64, f64),
    skeleton: &Skeleton,
    site: &Site,
    zones: &Zones,
    marked: &[Kind],
) {
    let s = &site.street;
    let (y0, y1) = across(skeleton, site);
    // Along the street: the crown, the lamps and the sight triangle, at least 10 m.
    let (mut x0, mut x1) = (-5.0f64, 5.0f64);
    let points = skeleton.sections.iter().map(|c| c.position);
    for p in points.chain(skeleton.leaves.iter().map(|l| l.position)) {
        x0 = x0.min(p.x as f64 - 1.0);
        x1 = x1.max(p.x as f64 + 1.0);
    }
    for l in &site.light {
        x0 = x0.min(l.x - l.clearance - 1.0);
        x1 = x1.max(l.x + l.clearance + 1.0);
    }
    if let Some(t) = &site.sight_triangle {
        for corner in t.corners {
            x0 = x0.min(corner[0] - 1.0);
            x1 = x1.max(corner[0] + 1.0);
        }
    }
    let mut c = Canvas::fit(pixmap, panel, (x0, x1), (y0, y1));
    // Fixtures longer than the view are cut at its ends.
    let clip = |a: f64, b: f64| (a.clamp(x0, x1), b.clamp(x0, x1));
    let red = paint(215, 30, 30, 255);
    c.rect((x0, y0), (x1, s.curb), &paint(80, 80, 84, 255));
    c.rect(
        (x0, s.curb),
        (x1, s.sidewalk[0].max(s.curb)),
        &paint(120, 100, 70, 255),
    );
    c.rect(
        (x0, s.sidewalk[0]),
        (x1, s.sidewalk[1]),
        &paint(190, 190, 185, 255),
    );
    c.rect((x0, s.sidewalk[1]), (x1, y1), &paint(150, 140, 120, 255));
    if let Some(t) = &site.sight_triangle {
        let corners: Vec<(f64, f64)> = t.corners.iter().map(|p| (p[0], p[1])).collect();
        let edge = marked.contains(&Kind::SightTriangle).then_some(&red);
        c.polygon(&corners, &paint(60, 120, 200, 70), edge);
    }
    if let Some(f) = &site.facade {
        let (a, b) = clip(-f.width / 2.0, f.width / 2.0);
        let (lo, hi) = ((a, f.setback), (b, y1));
        c.rect(lo, hi, &paint(205, 190, 170, 255));
        if marked.contains(&Kind::Facade) {
            c.outline(lo, hi, &red);
        }
        for (kind, boxes, colour) in [
            (Kind::Awning, &site.awning, paint(150, 60, 50, 200)),
            (Kind::Sign, &site.sign, paint(60, 90, 150, 200)),
        ] {
            for b in boxes {
                let (a, e) = clip(b.along[0], b.along[1]);
                let (lo, hi) = ((a, f.setback - b.reach), (e, f.setback));
                c.rect(lo, hi, &colour);
                if marked.contains(&kind) {
                    c.outline(lo, hi, &red);
                }
            }
        }
    }
    for wire in &site.wire {
        let band = (
            (x0, wire.offset - wire.clearance),
            (x1, wire.offset + wire.clearance),
        );
        c.rect(band.0, band.1, &paint(40, 40, 40, 30));
        c.segment(
            (x0, wire.offset),
            (x1, wire.offset),
            2.0,
            &paint(20, 20, 20, 255),
        );
        if marked.contains(&Kind::Wire) {
            c.outline(band.0, band.1, &red);
        }
    }
    // The tree from above: leaves, then stems over them.
    leaves(&mut c, skeleton, zones, (110, 170), |p| {
        (p.x as f64, p.y as f64)
    });
    let bark = paint(95, 75, 60, 255);
    for stem in skeleton.stems.iter().filter(|s| s.level <= 1) {
        let sec = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        for pair in sec.windows(2) {
            let (pa, pb) = (pair[0].position.as_dvec3(), pair[1].position.as_dvec3());
            let width = c.pixels((pair[0].radius + pair[1].radius) as f64).max(0.8);
            c.segment((pa.x, pa.y), (pb.x, pb.y), width, &bark);
        }
    }
    let flare = flare_radius(skeleton);
    let trunk = if marked.contains(&Kind::TrunkFlare) {
        &red
    } else {
        &bark
    };
    let r = c.pixels(flare);
    c.circle((0.0, 0.0), r, trunk, true);
    for l in &site.light {
        let r = c.pixels(l.clearance);
        c.circle((l.x, l.y), r, &paint(200, 170, 40, 160), false);
        c.circle((l.x, l.y), 4.0, &paint(240, 200, 40, 255), true);
        if marked.contains(&Kind::Light) {
            c.circle((l.x, l.y), r, &red, false);
        }
    }
    // The person, from above, on the sidewalk a little along from the tree.
    let py = (s.sidewalk[0] + s.sidewalk[1]) / 2.0;
    let r = c.pixels(0.25);
    c.circle((1.5, py), r, &paint(60, 60, 70, 255), true);
    // A 5 m scale bar in the lower left corner, with ticks every metre.
    let (bx, by) = (x0 + 0.5, y0 + 0.5);
    let ink = paint(20, 20, 20, 255);
    c.segment((bx, by), (bx + 5.0, by), 2.0, &ink);
    for m in 0..=5 {
        let tick = if m % 5 == 0 { 0.4 } else { 0.2 };
        c.segment((bx + m as f64, by), (bx + m as f64, by + tick), 1.5, &ink);
    }
}
