//! A tree for landscape CAD (Nagel 1986's aim): its plan symbol and two elevations as DXF, the
//! one format AutoCAD, Vectorworks, BricsCAD and QCAD all import. Each view is a named BLOCK
//! (`NAME-PLAN`, `NAME-FRONT`, `NAME-SIDE`) with its base point at the trunk's base, drawn in
//! metres on four layers (trunk, branches, crown outline, leaves), and inserted side by side in
//! model space. Written with the `dxf` crate.
//!
//! Issue Z's first step: `sylva draw`, `lobes`, `fractal`, `whisk` and `stick` write it (`-o
//! tree.dxf`), and `sylva-py/tests/test_cad.py` reads a grown plane's back with ezdxf in CI.
//! ezdxf reads the `dxf` crate's files, but logs that a BLOCK and its ENDBLK share a handle (the
//! crate gives both the block's); its audit mends that. Planting plans (`city --dxf`) and the
//! street sections (`grow --site`) are the next steps.

use crate::ExportError;
use crate::skeleton::Skeleton;
use dxf::entities::{Circle, Entity, EntityType, Insert, Line, LwPolyline};
use dxf::enums::{AcadVersion, DrawingUnits, Units};
use dxf::tables::Layer;
use dxf::{Block, Color, Drawing, LwPolylineVertex, Point};
use glam::{Vec2, Vec3};

/// The layers, with their ACI colours: brown trunk, olive branches, green crown, light-green
/// leaves.
pub const LAYERS: [(&str, u8); 4] = [
    ("TREE-TRUNK", 34),
    ("TREE-BRANCHES", 52),
    ("TREE-CROWN", 3),
    ("TREE-LEAVES", 82),
];

/// Most line segments one file may hold (stems' chords and leaf outlines, in every view): a
/// runaway model meets this budget with an error instead of filling the disk.
pub const MAX_SEGMENTS: usize = 3_000_000;

/// A view's projection of a point in metres onto its drawing plane.
type Projection = fn(Vec3) -> Vec2;

/// The three views: plan (x, y), front (x, z), side (y, z).
const VIEWS: [(&str, Projection); 3] = [
    ("PLAN", |p| Vec2::new(p.x, p.y)),
    ("FRONT", |p| Vec2::new(p.x, p.z)),
    ("SIDE", |p| Vec2::new(p.y, p.z)),
];

fn point(p: Vec2) -> Point {
    Point::new(f64::from(p.x), f64::from(p.y), 0.0)
}

fn on(layer: &str, kind: EntityType) -> Entity {
    let mut e = Entity::new(kind);
    e.common.layer = layer.to_string();
    e
}

/// A closed outline through `points` on `layer`.
fn closed(layer: &str, points: &[Vec2]) -> Entity {
    let mut poly = LwPolyline::default();
    poly.set_is_closed(true);
    poly.vertices = (points.iter())
        .map(|p| LwPolylineVertex {
            x: f64::from(p.x),
            y: f64::from(p.y),
            ..Default::default()
        })
        .collect();
    on(layer, EntityType::LwPolyline(poly))
}

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise.
fn hull(mut points: Vec<Vec2>) -> Vec<Vec2> {
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

/// `skeleton` as a DXF drawing named `name`: three blocks and their inserts.
pub fn tree_dxf(skeleton: &Skeleton, name: &str) -> Result<Drawing, ExportError> {
    let leaf_segments = 4 * skeleton.leaves.len();
    let segments = 3 * (skeleton.sections.len() + leaf_segments);
    if segments > MAX_SEGMENTS {
        return Err(ExportError::Output(format!(
            "a DXF of {name} would hold {segments} segments, over the budget of {MAX_SEGMENTS}"
        )));
    }
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2013;
    drawing.header.default_drawing_units = Units::Meters;
    drawing.header.drawing_units = DrawingUnits::Metric;
    for (layer, colour) in LAYERS {
        drawing.add_layer(Layer {
            name: layer.to_string(),
            color: Color::from_index(colour),
            ..Default::default()
        });
    }
    let name = name.replace(|c: char| !c.is_ascii_alphanumeric() && c != '_', "_");
    let mut across = 0.0f32;
    for (view, project) in VIEWS {
        let mut block = Block {
            name: format!("{name}-{view}"),
            ..Default::default()
        };
        let mut crown: Vec<Vec2> = Vec::new();
        for stem in &skeleton.stems {
            let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
            let layer = if stem.level == 0 {
                "TREE-TRUNK"
            } else {
                "TREE-BRANCHES"
            };
            for w in s.windows(2) {
                let (a, b) = (project(w[0].position), project(w[1].position));
                if stem.level > 0 {
                    crown.extend([a, b]);
                }
                block
                    .entities
                    .push(on(layer, EntityType::Line(Line::new(point(a), point(b)))));
            }
        }
        for leaf in &skeleton.leaves {
            // The blade's outline as every drawing draws it (`leaf_lines`: base, widest point
            // on each side, tip), each segment's start one corner.
            let mut outline: Vec<Vec2> = Vec::with_capacity(4);
            super::leaf_lines(leaf, &mut |a: Vec3, _: Vec3, _: super::Stroke| {
                outline.push(project(a));
            });
            crown.extend(&outline);
            block.entities.push(closed("TREE-LEAVES", &outline));
        }
        let outline = hull(crown);
        if outline.len() >= 3 {
            block.entities.push(closed("TREE-CROWN", &outline));
        }
        // In plan the trunk is its circle at the ground.
        if view == "PLAN"
            && let Some(base) = skeleton
                .stems
                .first()
                .and_then(|s| skeleton.sections.get(s.sections.start as usize))
        {
            let circle = Circle::new(point(project(base.position)), f64::from(base.radius));
            block
                .entities
                .push(on("TREE-TRUNK", EntityType::Circle(circle)));
        }
        let (lo, hi) = outline.iter().fold(
            (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let width = if outline.is_empty() { 1.0 } else { hi.x - lo.x };
        let block_name = block.name.clone();
        drawing.add_block(block);
        // Side by side, a crown's width apart, the trunk's base on the x axis.
        let left = if outline.is_empty() { 0.0 } else { lo.x };
        let insert = Insert {
            name: block_name,
            location: Point::new(f64::from(across - left), 0.0, 0.0),
            ..Default::default()
        };
        drawing.add_entity(Entity::new(EntityType::Insert(insert)));
        across += width + 2.0;
    }
    // Entities inside a block need handles of their own (the crate gives the block one, and
    // the tables and model space theirs): a reader finds every entity by its handle. Theirs
    // start past every handle the crate has given.
    let mut next = drawing.header.next_available_handle.0.max(0x1000);
    for block in drawing.blocks_mut() {
        for e in &mut block.entities {
            e.common.handle = dxf::Handle(next);
            next += 1;
        }
    }
    drawing.header.next_available_handle = dxf::Handle(next);
    drawing.normalize();
    Ok(drawing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_generated_tree_reads_back_with_its_blocks_layers_and_units() {
        let params = crate::species::builtin("black_tupelo").unwrap();
        let options = crate::GenerateOptions {
            max_levels: Some(2),
            ..Default::default()
        };
        let skeleton = crate::generate(&params, &options).unwrap();
        let drawing = tree_dxf(&skeleton, "Black Tupelo").unwrap();
        let mut bytes = Vec::new();
        drawing.save(&mut bytes).unwrap();
        let back = Drawing::load(&mut bytes.as_slice()).unwrap();
        let names: Vec<String> = back.blocks().map(|b| b.name.clone()).collect();
        for view in ["PLAN", "FRONT", "SIDE"] {
            assert!(names.contains(&format!("Black_Tupelo-{view}")), "{names:?}");
        }
        let layers: Vec<String> = back.layers().map(|l| l.name.clone()).collect();
        for (layer, _) in LAYERS {
            assert!(layers.iter().any(|l| l == layer), "{layers:?}");
        }
        assert_eq!(back.header.default_drawing_units, Units::Meters);
        let inserts = (back.entities())
            .filter(|e| matches!(e.specific, EntityType::Insert(_)))
            .count();
        assert_eq!(inserts, 3);
        // The front elevation is as tall as the tree.
        let front = back.blocks().find(|b| b.name.ends_with("-FRONT")).unwrap();
        let top = (front.entities.iter())
            .filter_map(|e| match &e.specific {
                EntityType::Line(l) => Some(l.p1.y.max(l.p2.y)),
                EntityType::LwPolyline(p) => p.vertices.iter().map(|v| v.y).reduce(f64::max),
                _ => None,
            })
            .fold(0.0f64, f64::max);
        let stats = skeleton.stats();
        assert!(
            (top / f64::from(stats.height) - 1.0).abs() < 0.05,
            "front elevation {top:.2} m, tree {:.2} m",
            stats.height
        );
    }

    #[test]
    fn the_hull_of_a_square_and_its_centre_is_the_square() {
        let h = hull(vec![
            Vec2::ZERO,
            Vec2::X,
            Vec2::ONE,
            Vec2::Y,
            Vec2::splat(0.5),
        ]);
        assert_eq!(h.len(), 4);
    }
}
