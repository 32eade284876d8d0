//! A city's planting plan at each epoch as DXF (`sylva city … --dxf`), for landscape CAD:
//! every tree an INSERT of its grown tree's plan symbol (crown outline and trunk, one block per
//! grown tree), at its place, scaled to its height and turned as the tiles draw it, on its
//! species' layer; stumps a circle on their own layer. Laid over a base plan, the epochs'
//! files show the canopy at +0, +10, +20 years.
//!
//! Coordinates: a projected inventory's own (x, y in its system's unit, `$INSUNITS` saying
//! which), so the plan lands on a base plan drawn in that system. An inventory given in
//! longitude and latitude has no plane coordinates a CAD program can use; its plan is drawn
//! in the city's local frame (x east, y north, metres from the frame's origin), and a note at
//! the origin says where that is.

use crate::error::CityError;
use crate::geo::Projection;
use crate::inventory::{Inventory, Position};
use crate::trees::plan::{Epoch, Kind, Plan, Planned, ProtoKey};
use crate::trees::prototypes::Prototype;
use std::collections::{BTreeMap, HashMap};
use sylva::drawing::cad::{MAX_INSERTS, PlanSymbol, PlantingPlan, Units, over_budget};

/// The file each epoch's plan is written to, in its tileset's folder.
pub const PLAN_FILE: &str = "planting-plan.dxf";

/// ACI colours the species' layers take in turn (greens and blue-greens, then warmer hues),
/// so that neighbouring species read apart.
const COLOURS: [u8; 12] = [3, 84, 114, 94, 134, 62, 154, 44, 122, 74, 104, 32];

/// Refuses a plan no file may hold: an epoch of more trees than [`MAX_INSERTS`].
pub fn check(plan: &Plan) -> Result<(), CityError> {
    match plan.epochs.iter().map(|e| e.trees.len()).max() {
        Some(n) if n > MAX_INSERTS => Err(CityError::setting("--dxf", over_budget(n).to_string())),
        _ => Ok(()),
    }
}

/// The coordinates a plan is drawn in: the inventory's own, or the local frame's.
enum Frame {
    /// A projected system's x and y, in a unit of this many metres.
    Projected(Units, f64),
    /// The city's local frame, metres east and north of its origin.
    Local,
}

fn frame_of(inventory: &Inventory) -> Frame {
    let projected =
        (inventory.trees.first()).is_some_and(|t| matches!(t.position, Position::Projected(..)));
    let unit = inventory
        .crs
        .filter(|_| projected)
        .and_then(|c| Projection::epsg(c).ok())
        .and_then(|p| p.unit());
    match unit {
        Some((name, metres)) => {
            let units = match name {
                "m" => Units::Meters,
                "km" => Units::Kilometers,
                "cm" => Units::Centimeters,
                "mm" => Units::Millimeters,
                "ft" => Units::Feet,
                "us-ft" => Units::USSurveyFeet,
                "yd" => Units::Yards,
                "us-yd" => Units::USSurveyYard,
                "mi" => Units::Miles,
                _ => Units::USSurveyMile,
            };
            Frame::Projected(units, metres)
        }
        None => Frame::Local,
    }
}

/// How much larger than its grown tree a tree is drawn: its height over the grown tree's, as
/// the tiles scale it (`tiles::content`).
pub fn drawn_scale(tree: &Planned, grown_height: Option<f32>) -> f32 {
    match grown_height {
        Some(h) => (tree.height / h.max(0.01)).clamp(0.05, 20.0),
        None => tree.scale,
    }
}

/// `epoch`'s planting plan as the bytes of a DXF file.
pub fn planting_plan(
    inventory: &Inventory,
    plan: &Plan,
    epoch: &Epoch,
    prototypes: &HashMap<ProtoKey, Prototype>,
) -> Result<Vec<u8>, CityError> {
    let flag = |e: sylva::ExportError| CityError::setting("--dxf", e.to_string());
    let frame = frame_of(inventory);
    let mut dxf = match frame {
        Frame::Projected(units, metres) => PlantingPlan::new(units, metres),
        Frame::Local => PlantingPlan::new(Units::Meters, 1.0),
    };
    // Layers in the order of the species' codes, so a plan's colours do not depend on the
    // order its rows came in.
    let mut codes: BTreeMap<(String, String), String> = BTreeMap::new();
    for t in &epoch.trees {
        if let Kind::Tree(k) = &t.kind {
            codes.entry((k.code.clone(), k.region.clone())).or_default();
        }
    }
    for (i, ((code, region), layer)) in codes.iter_mut().enumerate() {
        let scientific = (plan.measured.get(&(region.clone(), code.clone())))
            .map_or(String::new(), |m| format!(" {}", m.species.scientific));
        *layer = dxf.layer(
            &format!("TREE-{code}{scientific}"),
            COLOURS[i % COLOURS.len()],
        );
    }
    let stumps = dxf.layer("STUMPS", 8);
    // A stump's symbol is its cut: a circle 1 m across, scaled to its DBH; added at the first.
    let mut stump: Option<String> = None;
    for t in &epoch.trees {
        let at = match (&frame, inventory.trees.get(t.row).map(|r| r.position)) {
            (Frame::Projected(..), Some(Position::Projected(x, y))) => (x, y),
            _ => (t.at.x, t.at.y),
        };
        match &t.kind {
            Kind::Tree(k) => {
                let Some(p) = prototypes.get(k) else {
                    return Err(CityError::Growth(format!(
                        "the grown tree {} of row {} is missing",
                        k.file_stem(),
                        t.row
                    )));
                };
                let block = dxf.symbol(&k.file_stem(), &p.plan);
                let layer = &codes[&(k.code.clone(), k.region.clone())];
                let scale = drawn_scale(t, Some(p.height));
                dxf.place(&block, layer, at, f64::from(scale), f64::from(t.turn))
                    .map_err(flag)?;
            }
            Kind::Stump => {
                let diameter = f64::from((t.dbh / 100.0).max(0.1));
                let block = stump.get_or_insert_with(|| {
                    let cut = PlanSymbol {
                        trunk_radius: 0.5,
                        ..Default::default()
                    };
                    dxf.symbol("STUMP", &cut)
                });
                dxf.place(block, &stumps, at, diameter, 0.0).map_err(flag)?;
            }
        }
    }
    if let Frame::Local = frame {
        let (lon, lat) = plan.frame.lon_lat();
        dxf.note(
            "NOTES",
            &format!(
                "Origin: longitude {lon:.7}, latitude {lat:.7} (WGS84); x east, y north, metres"
            ),
        );
    }
    dxf.to_bytes().map_err(flag)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geo::LocalFrame;
    use glam::DVec3;

    #[test]
    fn a_city_past_one_files_bound_is_refused_before_anything_grows() {
        let tree = Planned {
            row: 0,
            at: DVec3::ZERO,
            kind: Kind::Stump,
            turn: 0.0,
            scale: 1.0,
            age: 10.0,
            dbh: 20.0,
            height: 8.0,
            crown_diameter: 6.0,
        };
        let mut plan = Plan {
            frame: LocalFrame::at(-121.0, 37.6),
            epochs: vec![Epoch {
                years: 0,
                trees: vec![tree; MAX_INSERTS],
                not_yet_planted: 0,
            }],
            summary: Default::default(),
            measured: HashMap::new(),
            observed: Vec::new(),
        };
        assert!(check(&plan).is_ok(), "at the bound");
        let one = plan.epochs[0].trees[0].clone();
        plan.epochs[0].trees.push(one);
        let e = check(&plan).unwrap_err().to_string();
        assert!(
            e.starts_with("--dxf: ") && e.contains("250001 trees") && e.contains("250000"),
            "{e}"
        );
    }
}
