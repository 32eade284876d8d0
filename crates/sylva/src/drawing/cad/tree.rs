//! One tree's plan symbol and two elevations: each view a named BLOCK (`NAME-PLAN`,
//! `NAME-FRONT`, `NAME-SIDE`) with its base point at the trunk's base, drawn in metres on four
//! layers (trunk, branches, crown outline, leaves), and inserted side by side in model space.
//! The plan draws the branches inside the crown's outline and the trunk's circle, as a CAD
//! tree symbol does; the leaves' outlines are drawn in the elevations only, where they give
//! the crown its texture (in plan they would triple a file of some 30 MB for a grown tree
//! and hide the branches).

use super::{
    add_layers, closed, crown_points, fine, finish, hull, leaf_outline, name as fit, new_drawing,
    on, point, polyline,
};
use crate::ExportError;
use crate::skeleton::Skeleton;
use dxf::entities::{Circle, Entity, EntityType, Insert};
use dxf::enums::Units;
use dxf::{Block, Drawing, Point};
use glam::Vec2;

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
type Projection = fn(glam::Vec3) -> Vec2;

/// The three views: plan (x, y), front (x, z), side (y, z).
const VIEWS: [(&str, Projection); 3] = [
    ("PLAN", |p| Vec2::new(p.x, p.y)),
    ("FRONT", |p| Vec2::new(p.x, p.z)),
    ("SIDE", |p| Vec2::new(p.y, p.z)),
];

/// `skeleton` as a DXF drawing named `name`: three blocks and their inserts.
pub fn tree_dxf(skeleton: &Skeleton, name: &str) -> Result<Drawing, ExportError> {
    let segments = 3 * skeleton.sections.len() + 2 * 4 * skeleton.leaves.len();
    if segments > MAX_SEGMENTS {
        return Err(ExportError::Output(format!(
            "a DXF of {name} would hold {segments} segments, over the budget of {MAX_SEGMENTS}"
        )));
    }
    let mut drawing = new_drawing(Units::Meters);
    add_layers(&mut drawing, LAYERS);
    let name = fit(name);
    let mut across = 0.0f32;
    for (view, project) in VIEWS {
        let mut block = Block {
            name: format!("{name}-{view}"),
            ..Default::default()
        };
        for stem in &skeleton.stems {
            let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
            if s.len() < 2 {
                continue;
            }
            let layer = if stem.level == 0 {
                "TREE-TRUNK"
            } else {
                "TREE-BRANCHES"
            };
            // One polyline a stem; the trunk and scaffold limbs as wide as they are (each
            // vertex's width its section's diameter), as an elevation draws a tree's
            // structure. Finer stems are hairlines: drawn at width their many small fills
            // would slow every CAD program's regeneration for a texture the leaves give.
            let mut e = polyline(
                layer,
                &s.iter().map(|c| project(c.position)).collect::<Vec<_>>(),
                false,
            );
            if stem.level <= 1
                && let EntityType::LwPolyline(poly) = &mut e.specific
            {
                for (v, pair) in poly.vertices.iter_mut().zip(s.windows(2)) {
                    v.starting_width = fine(2.0 * pair[0].radius);
                    v.ending_width = fine(2.0 * pair[1].radius);
                }
            }
            block.entities.push(e);
        }
        if view != "PLAN" {
            for leaf in &skeleton.leaves {
                let outline = leaf_outline(leaf, project);
                block.entities.push(closed("TREE-LEAVES", &outline));
            }
        }
        let outline = hull(crown_points(skeleton, project));
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
            let circle = Circle::new(point(project(base.position)), fine(base.radius));
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
            location: Point::new(fine(across - left), 0.0, 0.0),
            ..Default::default()
        };
        drawing.add_entity(Entity::new(EntityType::Insert(insert)));
        across += width + 2.0;
    }
    finish(&mut drawing);
    Ok(drawing)
}
