//! Planting plans: a grown tree's plan symbol (its crown's outline and its trunk, seen from
//! above) as a BLOCK, and a drawing of many trees, each an INSERT of its symbol at its place,
//! scaled and turned, on its species' layer. The symbol's entities lie on layer 0 with the
//! layer's colour, so each insert takes its own layer's colour and visibility: a CAD user
//! turns a species on or off, or recolours it, by its layer.

use super::{add_layers, closed, crown_points, fine, finish, hull, name, new_drawing, on, point};
use crate::ExportError;
use crate::skeleton::Skeleton;
use dxf::entities::{Circle, EntityType, Insert};
use dxf::enums::Units;
use dxf::{Block, Drawing, Point};
use glam::Vec2;
use std::collections::BTreeSet;

/// Most trees one planting plan may hold (Sylva's choice): each INSERT takes some 250 bytes,
/// so a plan of 250,000 trees is some 60 MB, as large as CAD programs open without a wait;
/// a larger city is drawn in parts (a smaller inventory, or fewer epochs' trees).
pub const MAX_INSERTS: usize = 250_000;

/// A tree seen from above: its crown's outline and its trunk at the ground, m, about the
/// trunk's base.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PlanSymbol {
    /// The crown's outline (its convex hull from above), counter-clockwise.
    pub crown: Vec<[f32; 2]>,
    /// The trunk's centre at the ground.
    pub trunk: [f32; 2],
    /// The trunk's radius at the ground.
    pub trunk_radius: f32,
}

impl PlanSymbol {
    /// `skeleton` seen from above.
    pub fn of(skeleton: &Skeleton) -> Self {
        let crown = hull(crown_points(skeleton, |p| Vec2::new(p.x, p.y)));
        let base =
            (skeleton.stems.first()).and_then(|s| skeleton.sections.get(s.sections.start as usize));
        PlanSymbol {
            crown: crown.iter().map(|p| p.to_array()).collect(),
            trunk: base.map_or([0.0; 2], |b| [b.position.x, b.position.y]),
            trunk_radius: base.map_or(0.0, |b| b.radius),
        }
    }

    /// The symbol as a block named `name`, its entities on `layer`.
    pub fn block(&self, name: &str, layer: &str) -> Block {
        let mut block = Block {
            name: name.to_string(),
            ..Default::default()
        };
        let crown: Vec<Vec2> = self.crown.iter().map(|p| Vec2::from_array(*p)).collect();
        if crown.len() >= 3 {
            block.entities.push(closed(layer, &crown));
        }
        if self.trunk_radius > 0.0 {
            let circle = Circle::new(point(Vec2::from_array(self.trunk)), fine(self.trunk_radius));
            block.entities.push(on(layer, EntityType::Circle(circle)));
        }
        block
    }

    /// The crown's widest extent from the trunk, m.
    pub fn reach(&self) -> f32 {
        let trunk = Vec2::from_array(self.trunk);
        (self.crown.iter())
            .map(|p| Vec2::from_array(*p).distance(trunk))
            .fold(self.trunk_radius, f32::max)
    }
}

/// A drawing of many trees, each an INSERT of its plan symbol.
pub struct PlantingPlan {
    drawing: Drawing,
    blocks: BTreeSet<String>,
    layers: BTreeSet<String>,
    inserts: usize,
    /// The drawing's units in metres: symbols, drawn in metres, are scaled by its inverse.
    metres_per_unit: f64,
}

impl PlantingPlan {
    /// An empty plan whose coordinates are in `units`, `metres_per_unit` metres each.
    pub fn new(units: Units, metres_per_unit: f64) -> Self {
        PlantingPlan {
            drawing: new_drawing(units),
            blocks: BTreeSet::new(),
            layers: BTreeSet::new(),
            inserts: 0,
            metres_per_unit,
        }
    }

    /// Adds the layer `layer` in ACI colour `colour`, once.
    pub fn layer(&mut self, layer: &str, colour: u8) -> String {
        // Layer names may hold spaces (R2000), not `<>/\":;?*|='`.
        let layer = layer.replace(
            |c: char| !c.is_ascii_alphanumeric() && !" -_.".contains(c),
            "_",
        );
        if self.layers.insert(layer.clone()) {
            add_layers(&mut self.drawing, [(layer.as_str(), colour)]);
        }
        layer
    }

    /// Adds `symbol` as the block `block`, once; returns the block's name as written.
    pub fn symbol(&mut self, block: &str, symbol: &PlanSymbol) -> String {
        let block = name(block);
        if self.blocks.insert(block.clone()) {
            self.drawing.add_block(symbol.block(&block, "0"));
        }
        block
    }

    /// Places the block `block` (from [`PlantingPlan::symbol`]) on `layer` at `at` (the
    /// plan's units), scaled by `scale` and turned `turn` radians anticlockwise.
    pub fn place(
        &mut self,
        block: &str,
        layer: &str,
        at: (f64, f64),
        scale: f64,
        turn: f64,
    ) -> Result<(), ExportError> {
        if self.inserts >= MAX_INSERTS {
            return Err(over_budget(self.inserts + 1));
        }
        let s = scale / self.metres_per_unit;
        let insert = Insert {
            name: block.to_string(),
            location: Point::new(at.0, at.1, 0.0),
            x_scale_factor: s,
            y_scale_factor: s,
            z_scale_factor: s,
            rotation: turn.to_degrees(),
            ..Default::default()
        };
        self.drawing
            .add_entity(on(layer, EntityType::Insert(insert)));
        self.inserts += 1;
        Ok(())
    }

    /// Writes `text` at the origin on `layer`, 1 m high: what the coordinates are.
    pub fn note(&mut self, layer: &str, text: &str) {
        let layer = self.layer(layer, 7);
        let t = dxf::entities::Text {
            value: text.to_string(),
            text_height: 1.0 / self.metres_per_unit,
            ..Default::default()
        };
        self.drawing.add_entity(on(&layer, EntityType::Text(t)));
    }

    /// Trees placed.
    pub fn inserts(&self) -> usize {
        self.inserts
    }

    /// The plan as the bytes of a DXF file.
    pub fn to_bytes(mut self) -> Result<Vec<u8>, ExportError> {
        finish(&mut self.drawing);
        super::to_bytes(&self.drawing)
    }
}

/// The error for a plan of `trees` trees, over [`MAX_INSERTS`].
pub fn over_budget(trees: usize) -> ExportError {
    ExportError::Output(format!(
        "a planting plan of {trees} trees is over the {MAX_INSERTS} one DXF file holds; draw a \
         smaller inventory"
    ))
}
