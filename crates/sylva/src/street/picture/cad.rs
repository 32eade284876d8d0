//! A planting site and its tree at each age as DXF, for landscape CAD (`grow --site`): the
//! section across the street, looking along it (y across to the right, z up: roadway, curb,
//! sidewalk, the wall with its awnings and signs, the lines and lamps with their clearances,
//! the clear heights, a 1.8 m person), and the plan beside it (x along the street, y across:
//! the same fixtures from above, the sight triangle). Each age's tree is a block in each view
//! (its trunk and scaffold limbs, and its crown's outline; `PLAC-AGE-030-SECTION`) inserted
//! at the trunk's place on a layer of its own, `TREE-AGE-030`: a CAD user shows one age, or several over each other,
//! by their layers. Metres; the trunk stands at the origin of the section and of the plan.

use super::super::site::Site;
use crate::ExportError;
use crate::Skeleton;
use crate::drawing::cad::{
    PlanSymbol, Units, add_layers, closed, crown_points, fine, finish, hull, new_drawing, on,
    polyline, to_bytes,
};
use dxf::entities::{Circle, Entity, EntityType, Insert, Line, Text};
use dxf::{Block, Drawing, Point};
use glam::Vec2;

/// The site's layers and their ACI colours.
const SITE_LAYERS: [(&str, u8); 7] = [
    ("SITE-GROUND", 8),
    ("SITE-CLEARANCE", 30),
    ("SITE-BUILDING", 33),
    ("SITE-WIRES", 250),
    ("SITE-LIGHTS", 50),
    ("SITE-SIGHT", 150),
    ("SITE-NOTES", 7),
];

/// How far right of the section the plan is drawn, beyond both views' extents, m.
const GAP: f32 = 4.0;

/// One age of a tree, as the section and plan draw it.
#[derive(Clone, Debug)]
pub struct SectionTree {
    /// Age, years since planting.
    pub age: f64,
    /// Trunk and scaffold limbs across the street (y, z), each a polyline.
    pub limbs: Vec<Vec<Vec2>>,
    /// The crown's outline across the street (y, z).
    pub crown: Vec<Vec2>,
    /// The tree from above.
    pub plan: PlanSymbol,
    /// The trunk and limbs from above (x, y).
    pub limbs_plan: Vec<Vec<Vec2>>,
}

impl SectionTree {
    /// `skeleton` at `age`: its trunk and first branches (levels 0 and 1, as a CAD elevation
    /// draws a tree's structure), and its crown's outline, in both views.
    pub fn of(skeleton: &Skeleton, age: f64) -> Self {
        let limbs = |project: fn(glam::Vec3) -> Vec2| -> Vec<Vec<Vec2>> {
            (skeleton.stems.iter().filter(|s| s.level <= 2))
                .map(|stem| {
                    let s = &skeleton.sections
                        [stem.sections.start as usize..stem.sections.end as usize];
                    s.iter().map(|c| project(c.position)).collect()
                })
                .collect()
        };
        SectionTree {
            age,
            limbs: limbs(|p| Vec2::new(p.y, p.z)),
            crown: hull(crown_points(skeleton, |p| Vec2::new(p.y, p.z))),
            plan: PlanSymbol::of(skeleton),
            limbs_plan: limbs(|p| Vec2::new(p.x, p.y)),
        }
    }

    /// Its layer: `TREE-AGE-030` (tenths where the age has them: `TREE-AGE-002.5`).
    fn layer(&self) -> String {
        if self.age.fract() == 0.0 {
            format!("TREE-AGE-{:03}", self.age as u32)
        } else {
            format!("TREE-AGE-{:05.1}", self.age)
        }
    }
}

fn line(layer: &str, a: (f32, f32), b: (f32, f32)) -> Entity {
    let (a, b) = (Vec2::from(a), Vec2::from(b));
    let l = Line::new(
        Point::new(fine(a.x), fine(a.y), 0.0),
        Point::new(fine(b.x), fine(b.y), 0.0),
    );
    on(layer, EntityType::Line(l))
}

fn rect(layer: &str, lo: (f32, f32), hi: (f32, f32)) -> Entity {
    let corners = [lo, (hi.0, lo.1), hi, (lo.0, hi.1)].map(Vec2::from);
    closed(layer, &corners)
}

fn circle(layer: &str, at: (f32, f32), r: f32) -> Entity {
    let c = Circle::new(Point::new(fine(at.0), fine(at.1), 0.0), fine(r));
    on(layer, EntityType::Circle(c))
}

fn text(layer: &str, at: (f32, f32), height: f32, value: &str) -> Entity {
    let t = Text {
        location: Point::new(fine(at.0), fine(at.1), 0.0),
        text_height: f64::from(height),
        value: value.to_string(),
        ..Default::default()
    };
    on(layer, EntityType::Text(t))
}

/// The site's extent across the street (y) and along it (x), holding every tree, m.
fn extents(site: &Site, trees: &[SectionTree]) -> ((f32, f32), (f32, f32)) {
    let s = &site.street;
    let (mut y0, mut y1) = (s.curb as f32 - 4.0, s.sidewalk[1] as f32 + 1.0);
    let (mut x0, mut x1) = (-5.0f32, 5.0f32);
    if let Some(f) = &site.facade {
        y1 = y1.max(f.setback as f32 + 1.5);
    }
    for w in &site.wire {
        y0 = y0.min((w.offset - w.clearance) as f32 - 0.5);
        y1 = y1.max((w.offset + w.clearance) as f32 + 0.5);
    }
    for l in &site.light {
        x0 = x0.min((l.x - l.clearance) as f32 - 1.0);
        x1 = x1.max((l.x + l.clearance) as f32 + 1.0);
    }
    if let Some(t) = &site.sight_triangle {
        for c in t.corners {
            x0 = x0.min(c[0] as f32 - 1.0);
            x1 = x1.max(c[0] as f32 + 1.0);
        }
    }
    for t in trees {
        for p in &t.crown {
            y0 = y0.min(p.x - 0.5);
            y1 = y1.max(p.x + 0.5);
        }
        for p in &t.plan.crown {
            x0 = x0.min(p[0] - 1.0);
            x1 = x1.max(p[0] + 1.0);
        }
    }
    ((y0, y1), (x0, x1))
}

/// The section across the street of `site`, its fixtures in model space.
fn section(d: &mut Drawing, site: &Site, (y0, y1): (f32, f32)) {
    let s = &site.street;
    let f = |v: f64| v as f32;
    let (curb, walk) = (f(s.curb), [f(s.sidewalk[0]), f(s.sidewalk[1])]);
    let mut add = |e: Entity| {
        d.add_entity(e);
    };
    // The ground: the roadway 0.15 m below the curb's top, the curb face, the strip and
    // sidewalk at grade, and what lies behind.
    add(line("SITE-GROUND", (y0, -0.15), (curb, -0.15)));
    add(line("SITE-GROUND", (curb, -0.15), (curb, 0.0)));
    add(line("SITE-GROUND", (curb, 0.0), (y1, 0.0)));
    for y in walk {
        add(line("SITE-GROUND", (y, 0.0), (y, -0.1)));
    }
    add(rect(
        "SITE-CLEARANCE",
        (y0, 0.0),
        (curb, f(s.roadway_clearance)),
    ));
    add(rect(
        "SITE-CLEARANCE",
        (walk[0], 0.0),
        (walk[1], f(s.sidewalk_clearance)),
    ));
    if let Some(t) = &site.sight_triangle {
        let ys = t.corners.map(|c| c[1] as f32);
        let (a, b) = (
            ys.iter().copied().fold(f32::MAX, f32::min),
            ys.iter().copied().fold(f32::MIN, f32::max),
        );
        add(rect("SITE-SIGHT", (a, f(t.low)), (b, f(t.high))));
    }
    if let Some(w) = &site.facade {
        add(rect(
            "SITE-BUILDING",
            (f(w.setback), 0.0),
            (y1, f(w.height)),
        ));
        for b in site.awning.iter().chain(&site.sign) {
            let lo = (f(w.setback - b.reach), f(b.bottom));
            add(rect("SITE-BUILDING", lo, (f(w.setback), f(b.top))));
        }
    }
    // Each line, its clearance at cutting and the minimum kept at all times.
    for w in &site.wire {
        for r in [0.05, w.clearance, w.minimum] {
            add(circle("SITE-WIRES", (f(w.offset), f(w.height)), f(r)));
        }
    }
    for l in &site.light {
        add(line("SITE-LIGHTS", (f(l.y), 0.0), (f(l.y), f(l.height))));
        add(circle("SITE-LIGHTS", (f(l.y), f(l.height)), f(l.clearance)));
    }
    // A 1.8 m person on the sidewalk: body and head.
    let py = (walk[0] + walk[1]) / 2.0;
    add(rect("SITE-NOTES", (py - 0.18, 0.0), (py + 0.18, 1.55)));
    add(circle("SITE-NOTES", (py, 1.67), 0.13));
}

/// The plan of `site`, its fixtures in model space, shifted `dx` to the right.
fn plan(d: &mut Drawing, site: &Site, (y0, y1): (f32, f32), (x0, x1): (f32, f32), dx: f32) {
    let s = &site.street;
    let f = |v: f64| v as f32;
    let mut add = |e: Entity| {
        d.add_entity(e);
    };
    let along = |layer: &str, y: f32| line(layer, (x0 + dx, y), (x1 + dx, y));
    for y in [f(s.curb), f(s.sidewalk[0]), f(s.sidewalk[1])] {
        add(along("SITE-GROUND", y));
    }
    add(rect("SITE-GROUND", (x0 + dx, y0), (x1 + dx, y1)));
    if let Some(w) = &site.facade {
        let half = f(w.width) / 2.0;
        add(rect(
            "SITE-BUILDING",
            (dx - half, f(w.setback)),
            (dx + half, y1),
        ));
        for b in site.awning.iter().chain(&site.sign) {
            add(rect(
                "SITE-BUILDING",
                (dx + f(b.along[0]), f(w.setback - b.reach)),
                (dx + f(b.along[1]), f(w.setback)),
            ));
        }
    }
    for w in &site.wire {
        add(along("SITE-WIRES", f(w.offset)));
    }
    for l in &site.light {
        add(circle("SITE-LIGHTS", (dx + f(l.x), f(l.y)), 0.1));
        add(circle("SITE-LIGHTS", (dx + f(l.x), f(l.y)), f(l.clearance)));
    }
    if let Some(t) = &site.sight_triangle {
        let corners = t.corners.map(|c| Vec2::new(dx + c[0] as f32, c[1] as f32));
        add(closed("SITE-SIGHT", &corners));
    }
}

/// `site` with `trees` (one species' ages, rising) as the bytes of a DXF file: the section
/// and, to its right, the plan, each age a block per view on its own layer. `label` names
/// the drawing (species and region); `code` (the species' code) begins its blocks' names, so
/// that two species' files inserted into one drawing keep their trees apart.
pub fn street_section_dxf(
    site: &Site,
    trees: &[SectionTree],
    code: &str,
    label: &str,
) -> Result<Vec<u8>, ExportError> {
    let mut d = new_drawing(Units::Meters);
    add_layers(&mut d, SITE_LAYERS);
    let (across, along) = extents(site, trees);
    // The plan's x = 0 (the trunk) lies right of the section's widest point and of the plan's
    // own left end.
    let dx = across.1 - along.0 + GAP;
    section(&mut d, site, across);
    plan(&mut d, site, across, along, dx);
    let top = trees
        .iter()
        .flat_map(|t| t.crown.iter().map(|p| p.y))
        .fold(10.0f32, f32::max);
    d.add_entity(text(
        "SITE-NOTES",
        (across.0, top + 1.0),
        0.5,
        &format!("{label}: section across the street (left) and plan (right), metres"),
    ));
    let count = trees.len().max(1) as f32;
    for (i, t) in trees.iter().enumerate() {
        let layer = t.layer();
        // Young ages light green, old ones dark (ACI 80s to 100s: greens by shade).
        let colour = [82u8, 92, 102, 94, 104, 96, 106][((i as f32 / count) * 7.0) as usize % 7];
        add_layers(&mut d, [(layer.as_str(), colour)]);
        for (view, limbs, crown, at) in [
            ("SECTION", &t.limbs, t.crown.clone(), 0.0),
            (
                "PLAN",
                &t.limbs_plan,
                t.plan.crown.iter().map(|p| Vec2::from_array(*p)).collect(),
                dx,
            ),
        ] {
            let name = crate::drawing::cad::name(&format!(
                "{code}-{}-{view}",
                layer.trim_start_matches("TREE-")
            ));
            let mut block = Block {
                name: name.clone(),
                ..Default::default()
            };
            for l in limbs.iter().filter(|l| l.len() >= 2) {
                block.entities.push(polyline("0", l, false));
            }
            if crown.len() >= 3 {
                block.entities.push(closed("0", &crown));
            }
            if view == "PLAN" && t.plan.trunk_radius > 0.0 {
                let [x, y] = t.plan.trunk;
                block
                    .entities
                    .push(circle("0", (x, y), t.plan.trunk_radius));
            }
            d.add_block(block);
            let insert = Insert {
                name,
                location: Point::new(fine(at), 0.0, 0.0),
                ..Default::default()
            };
            d.add_entity(on(&layer, EntityType::Insert(insert)));
        }
    }
    finish(&mut d);
    to_bytes(&d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::growth::survey::report::Cohort;
    use dxf::entities::EntityType;

    #[test]
    fn the_section_holds_the_site_and_each_age_on_its_layer_as_tall_as_the_tree() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut cohort = Cohort::new(vec![plane], 0);
        let trees: Vec<(SectionTree, f64)> = [5.0, 15.0]
            .map(|age| {
                let s = cohort.advance_to(age).remove(0);
                (SectionTree::of(&s, age), crate::growth::measure(&s).height)
            })
            .into();
        let site = Site::parse(
            "[street]\ncurb = -1.0\nsidewalk = [0.8, 3.2]\nroadway_clearance = 4.3\n\
             sidewalk_clearance = 2.4\n[[wire]]\nheight = 8.5\noffset = -0.6\nclearance = 3.0\nminimum = 0.46\n",
            "test",
        )
        .unwrap();
        let sections: Vec<SectionTree> = trees.iter().map(|t| t.0.clone()).collect();
        let bytes = street_section_dxf(&site, &sections, "PLAC", "London planetree").unwrap();
        let d = Drawing::load(&mut bytes.as_slice()).unwrap();
        assert_eq!(d.header.default_drawing_units, Units::Meters);
        let layers: Vec<String> = d.layers().map(|l| l.name.clone()).collect();
        for l in ["TREE-AGE-005", "TREE-AGE-015", "SITE-GROUND", "SITE-WIRES"] {
            assert!(layers.iter().any(|x| x == l), "{l} in {layers:?}");
        }
        // The wire's clearance, a circle about the line.
        assert!(d.entities().any(|e| e.common.layer == "SITE-WIRES"
            && matches!(&e.specific, EntityType::Circle(c) if (c.radius - 3.0).abs() < 1e-9
                && (c.center.x + 0.6).abs() < 1e-9 && (c.center.y - 8.5).abs() < 1e-9)));
        for (age, height) in [(5, trees[0].1), (15, trees[1].1)] {
            let name = format!("PLAC-AGE-{age:03}-SECTION");
            let block = d.blocks().find(|b| b.name == name).unwrap();
            let top = (block.entities.iter())
                .filter_map(|e| match &e.specific {
                    EntityType::LwPolyline(p) => p.vertices.iter().map(|v| v.y).reduce(f64::max),
                    _ => None,
                })
                .fold(0.0, f64::max);
            assert!(
                (top / height - 1.0).abs() < 0.05,
                "{name}: {top:.2} m, tree {height:.2} m"
            );
            let insert = (d.entities())
                .find_map(|e| match &e.specific {
                    EntityType::Insert(i) if i.name == name => {
                        Some((e.common.layer.clone(), i.location.clone()))
                    }
                    _ => None,
                })
                .unwrap();
            assert_eq!(insert.0, format!("TREE-AGE-{age:03}"));
            assert_eq!((insert.1.x, insert.1.y), (0.0, 0.0));
        }
    }
}
