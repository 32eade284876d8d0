//! Trees for landscape CAD (Nagel 1986's aim) as DXF, the one format AutoCAD, Vectorworks,
//! BricsCAD and QCAD all import, written with the `dxf` crate:
//!
//! - [`tree_dxf`]: one tree's plan symbol and two elevations, each a named BLOCK on four
//!   layers (`sylva draw … -o tree.dxf`);
//! - [`PlanSymbol`] and [`PlantingPlan`]: a grown tree's crown outline and trunk in plan as a
//!   block, inserted at every tree's place of a city (`sylva city … --dxf`) on a layer per
//!   species;
//! - the street section of a planting site with its tree at each age is drawn by
//!   `street::picture::section_dxf` with these pieces.
//!
//! Every file is DXF R2000 (AC1015), in metres unless a plan's coordinates say otherwise, and
//! the same input gives the same bytes: the header's dates and GUIDs are fixed, and
//! [`to_bytes`] completes the handles and owners the crate leaves out (`handles`).

mod handles;
mod plan;
mod tree;

/// The drawing units a plan's coordinates may be in.
pub use dxf::enums::Units;
pub use plan::{MAX_INSERTS, PlanSymbol, PlantingPlan, over_budget};
pub use tree::{LAYERS, MAX_SEGMENTS, tree_dxf};

use crate::ExportError;
use dxf::entities::{Entity, EntityType, LwPolyline};
use dxf::enums::{AcadVersion, DrawingUnits};
use dxf::tables::Layer;
use dxf::{Color, Drawing, LwPolylineVertex, Point};
use glam::{Vec2, Vec3};

/// A new drawing in `units`: DXF R2000, with the header's dates and GUIDs fixed.
///
/// R2000 rather than a later version: it holds everything drawn here (blocks, layers,
/// lightweight polylines, `$INSUNITS`), every CAD program of the last twenty years reads it,
/// and the crate writes a transparency of 0, which readers take as invalid, on every entity
/// of R2004 and later. The dates are 1 January 2000 (a drawing's content, not the time it was
/// written, decides its bytes); the local dates are converted with the machine's time zone
/// from a local midnight, so they too read the same everywhere.
pub fn new_drawing(units: Units) -> Drawing {
    use chrono::TimeZone;
    let mut drawing = Drawing::new();
    let h = &mut drawing.header;
    h.version = AcadVersion::R2000;
    h.default_drawing_units = units;
    h.drawing_units = if matches!(
        units,
        Units::Feet | Units::Inches | Units::USSurveyFeet | Units::Yards | Units::Miles
    ) {
        DrawingUnits::English
    } else {
        DrawingUnits::Metric
    };
    if let Some(local) = chrono::Local
        .with_ymd_and_hms(2000, 1, 1, 0, 0, 0)
        .earliest()
    {
        h.creation_date = local;
        h.update_date = local;
    }
    let utc = chrono::Utc.with_ymd_and_hms(2000, 1, 1, 0, 0, 0).unwrap();
    h.creation_date_universal = utc;
    h.update_date_universal = utc;
    h.fingerprint_guid = uuid::Uuid::nil();
    h.version_guid = uuid::Uuid::nil();
    drawing
}

/// Adds `layers` (name, ACI colour) to `drawing`.
pub fn add_layers<'a>(drawing: &mut Drawing, layers: impl IntoIterator<Item = (&'a str, u8)>) {
    for (name, colour) in layers {
        drawing.add_layer(Layer {
            name: name.to_string(),
            color: Color::from_index(colour),
            ..Default::default()
        });
    }
}

/// `drawing` as the bytes of an ASCII DXF file, its handles and owners complete.
pub fn to_bytes(drawing: &Drawing) -> Result<Vec<u8>, ExportError> {
    let mut bytes = Vec::new();
    drawing
        .save(&mut bytes)
        .map_err(|e| ExportError::Output(format!("writing DXF: {e}")))?;
    let text = String::from_utf8(bytes)
        .map_err(|e| ExportError::Output(format!("writing DXF: not ASCII text: {e}")))?;
    Ok(handles::complete(&text).into_bytes())
}

/// Gives every entity inside `drawing`'s blocks a handle of its own (the crate gives the
/// blocks theirs, and the tables and model space theirs), past every handle given: a reader
/// finds every entity by its handle. Then orders the drawing as the crate writes it.
pub fn finish(drawing: &mut Drawing) {
    let mut next = drawing.header.next_available_handle.0.max(0x100);
    for block in drawing.blocks_mut() {
        for e in &mut block.entities {
            e.common.handle = dxf::Handle(next);
            next += 1;
        }
    }
    drawing.header.next_available_handle = dxf::Handle(next);
    drawing.normalize();
}

/// `v` metres to a tenth of a millimetre, finer than any CAD plan of a tree is drawn: the
/// crate writes a coordinate with up to 12 digits, and an `f32` widened to `f64` has them
/// all (`1.2345678806304932`), which would double a file's size for no line a user sees.
pub fn fine(v: f32) -> f64 {
    (f64::from(v) * 1e4).round() / 1e4
}

pub(crate) fn point(p: Vec2) -> Point {
    Point::new(fine(p.x), fine(p.y), 0.0)
}

/// An entity of `kind` on `layer`, its colour and line weight the layer's.
pub fn on(layer: &str, kind: EntityType) -> Entity {
    let mut e = Entity::new(kind);
    e.common.layer = layer.to_string();
    // ByLayer (-1), where the crate would write 0 (the thinnest line).
    e.common.lineweight_enum_value = -1;
    e
}

/// A closed outline through `points` on `layer`.
pub fn closed(layer: &str, points: &[Vec2]) -> Entity {
    polyline(layer, points, true)
}

/// An outline through `points` on `layer`, closed or open.
pub fn polyline(layer: &str, points: &[Vec2], closed: bool) -> Entity {
    let mut poly = LwPolyline::default();
    poly.set_is_closed(closed);
    poly.vertices = (points.iter())
        .map(|p| LwPolylineVertex {
            x: fine(p.x),
            y: fine(p.y),
            ..Default::default()
        })
        .collect();
    on(layer, EntityType::LwPolyline(poly))
}

/// A name fit for a block or layer: ASCII letters, digits, `_` and `-`; anything else `_`.
pub fn name(text: &str) -> String {
    text.replace(
        |c: char| !c.is_ascii_alphanumeric() && c != '_' && c != '-',
        "_",
    )
}

/// A leaf blade's outline in a view (`project`): base, widest point on each side, tip, as
/// every drawing draws it (`leaf_lines`, whose segments each start at one corner).
pub(crate) fn leaf_outline(leaf: &crate::skeleton::Leaf, project: fn(Vec3) -> Vec2) -> Vec<Vec2> {
    let mut outline: Vec<Vec2> = Vec::with_capacity(4);
    super::leaf_lines(leaf, &mut |a: Vec3, _: Vec3, _: super::Stroke| {
        outline.push(project(a));
    });
    outline
}

/// The points the crown's outline in a view (`project`) closes around: every branch's
/// sections (not the trunk's, which stands inside it or below it) and every blade's corners.
pub(crate) fn crown_points(skeleton: &crate::Skeleton, project: fn(Vec3) -> Vec2) -> Vec<Vec2> {
    let mut points: Vec<Vec2> = Vec::new();
    for stem in skeleton.stems.iter().filter(|s| s.level > 0) {
        let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        points.extend(s.iter().map(|c| project(c.position)));
    }
    for leaf in &skeleton.leaves {
        points.extend(leaf_outline(leaf, project));
    }
    points
}

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise.
pub fn hull(mut points: Vec<Vec2>) -> Vec<Vec2> {
    points.retain(|p| p.is_finite());
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut out: Vec<Vec2> = Vec::with_capacity(points.len() * 2);
    for pass in 0..2 {
        let start = out.len();
        let iter: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in iter {
            while out.len() >= start + 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0
            {
                out.pop();
            }
            out.push(p);
        }
        out.pop();
    }
    out
}

#[cfg(test)]
mod tests;
