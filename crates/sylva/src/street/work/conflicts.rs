//! Where a grown tree runs into its site: each kind of conflict, how much of the crown is in
//! the way, and which part of the tree causes it.
//!
//! The tree is read as points: every cross-section of every stem (with its order: trunk,
//! scaffold limb, branch) and every leaf's centre (with its area). A point inside a fixture's
//! zone is in the way; the zones are the fixtures of `site.rs` grown by the clearance each
//! asks for.

use crate::Skeleton;
use crate::street::energy::crown::leaves_of;
use crate::street::site::Site;
use glam::Vec3;

/// The kinds of conflict a site can hold, in report order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    /// The crown grows into the building's wall.
    Facade,
    /// Into an awning.
    Awning,
    /// Into a sign.
    Sign,
    /// Inside an overhead line's clearance at cutting: due for line clearance.
    Wire,
    /// Inside an overhead line's minimum clearance, which no leaf or wood may enter at any
    /// time (GO 95's Rule 35): a breach, not a routine conflict.
    WireMinimum,
    /// Around a street light's lamp.
    Light,
    /// Into a sight triangle's clear band.
    SightTriangle,
    /// Below the clear height over the roadway.
    Roadway,
    /// Below the clear height over the sidewalk.
    Sidewalk,
    /// The trunk's base reaches the curb or the sidewalk.
    TrunkFlare,
}

impl Kind {
    /// Every kind, in report order.
    pub const ALL: [Kind; 10] = [
        Kind::Facade,
        Kind::Awning,
        Kind::Sign,
        Kind::Wire,
        Kind::WireMinimum,
        Kind::Light,
        Kind::SightTriangle,
        Kind::Roadway,
        Kind::Sidewalk,
        Kind::TrunkFlare,
    ];

    /// Name in reports and CSV columns.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Facade => "facade",
            Kind::Awning => "awning",
            Kind::Sign => "sign",
            Kind::Wire => "wire",
            Kind::WireMinimum => "wire_minimum",
            Kind::Light => "light",
            Kind::SightTriangle => "sight_triangle",
            Kind::Roadway => "roadway",
            Kind::Sidewalk => "sidewalk",
            Kind::TrunkFlare => "trunk_flare",
        }
    }
}

/// The part of a tree that causes a conflict: the lowest order of wood in the zone, or leaves
/// alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Part {
    /// The trunk.
    Trunk,
    /// A scaffold limb (a branch of the trunk).
    Limb,
    /// A smaller branch.
    Branch,
    /// Only leaves.
    Leaves,
}

impl Part {
    /// Name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Part::Trunk => "trunk",
            Part::Limb => "scaffold limb",
            Part::Branch => "branch",
            Part::Leaves => "leaves",
        }
    }
}

/// One kind of conflict in one year.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conflict {
    /// What the tree runs into.
    pub kind: Kind,
    /// Leaf area in the way, m².
    pub leaf_area: f64,
    /// Its share of the tree's leaf area.
    pub leaf_share: f64,
    /// The part that causes it.
    pub part: Part,
    /// Lowest and highest point in the way, m.
    pub heights: (f64, f64),
}

impl Conflict {
    /// For people: `wire (trunk, 19% of leaf area, 5.6-11.2 m)`.
    pub fn describe(&self) -> String {
        if self.kind == Kind::TrunkFlare {
            return "trunk flare (at the curb or sidewalk edge)".into();
        }
        format!(
            "{} ({}, {:.1}% of leaf area, {:.1}-{:.1} m up)",
            self.kind.name().replace('_', " "),
            self.part.name(),
            self.leaf_share * 100.0,
            self.heights.0,
            self.heights.1
        )
    }
}

/// A fixture's zone, in the tree's frame, in `f32` like the skeleton.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// An axis-aligned box.
    Box { lo: Vec3, hi: Vec3 },
    /// A line along x at (y, z), and the squared radius kept clear around it.
    Line { y: f32, z: f32, r2: f32 },
    /// A ball.
    Ball { at: Vec3, r2: f32 },
    /// A triangle in plan, between two heights.
    Prism {
        corners: [[f64; 2]; 3],
        low: f32,
        high: f32,
    },
}

impl Shape {
    // Inlined into the per-point loops: a call per point and zone cost a third of
    // `conflicts_with`'s time (2.55 against 1.72 ms for a 40-year plane's 44,000 points).
    #[inline]
    fn holds(&self, p: Vec3) -> bool {
        match *self {
            Shape::Box { lo, hi } => p.cmpge(lo).all() && p.cmple(hi).all(),
            Shape::Line { y, z, r2 } => (p.y - y).powi(2) + (p.z - z).powi(2) < r2,
            Shape::Ball { at, r2 } => p.distance_squared(at) < r2,
            Shape::Prism { corners, low, high } => {
                (low..=high).contains(&p.z) && in_triangle([p.x as f64, p.y as f64], corners)
            }
        }
    }
}

/// Every zone of a site, compiled once, each with its kind.
pub struct Zones {
    zones: Vec<(Kind, Shape)>,
}

impl Zones {
    /// The zones of `site` (the trunk flare has none: it is measured, not found).
    pub fn new(site: &Site) -> Zones {
        let f32 = |v: f64| v as f32;
        let big = 1.0e6f32;
        let s = &site.street;
        let mut zones = vec![
            (
                Kind::Roadway,
                Shape::Box {
                    lo: Vec3::new(-big, -big, -big),
                    hi: Vec3::new(
                        big,
                        f32(s.curb).next_down(),
                        f32(s.roadway_clearance).next_down(),
                    ),
                },
            ),
            (
                Kind::Sidewalk,
                Shape::Box {
                    lo: Vec3::new(-big, f32(s.sidewalk[0]), -big),
                    hi: Vec3::new(
                        big,
                        f32(s.sidewalk[1]),
                        f32(s.sidewalk_clearance).next_down(),
                    ),
                },
            ),
        ];
        if let Some(f) = &site.facade {
            let half = f32(f.width / 2.0);
            zones.push((
                Kind::Facade,
                Shape::Box {
                    lo: Vec3::new(-half, f32(f.setback), -big),
                    hi: Vec3::new(half, big, f32(f.height)),
                },
            ));
            for (kind, boxes) in [(Kind::Awning, &site.awning), (Kind::Sign, &site.sign)] {
                for b in boxes {
                    zones.push((
                        kind,
                        Shape::Box {
                            lo: Vec3::new(f32(b.along[0]), f32(f.setback - b.reach), f32(b.bottom)),
                            hi: Vec3::new(f32(b.along[1]), f32(f.setback), f32(b.top)),
                        },
                    ));
                }
            }
        }
        for w in &site.wire {
            for (kind, r) in [(Kind::Wire, w.clearance), (Kind::WireMinimum, w.minimum)] {
                zones.push((
                    kind,
                    Shape::Line {
                        y: f32(w.offset),
                        z: f32(w.height),
                        r2: f32(r * r),
                    },
                ));
            }
        }
        for l in &site.light {
            zones.push((
                Kind::Light,
                Shape::Ball {
                    at: Vec3::new(f32(l.x), f32(l.y), f32(l.height)),
                    r2: f32(l.clearance * l.clearance),
                },
            ));
        }
        if let Some(t) = &site.sight_triangle {
            zones.push((
                Kind::SightTriangle,
                Shape::Prism {
                    corners: t.corners,
                    low: f32(t.low),
                    high: f32(t.high),
                },
            ));
        }
        zones.sort_by_key(|z| z.0);
        Zones { zones }
    }

    /// Only the zones of the kinds `keep` accepts (a pruning cycle clears some, not all).
    pub fn only(mut self, keep: impl Fn(Kind) -> bool) -> Zones {
        self.zones.retain(|(k, _)| keep(*k));
        self
    }

    /// The first kind of conflict a point of the tree is in, if any (`level`: its stem's
    /// order, `None` for a leaf). The trunk may stand in the sidewalk band: only what hangs
    /// over it counts.
    pub fn kind_of(&self, p: Vec3, level: Option<u8>) -> Option<Kind> {
        self.zones
            .iter()
            .find(|(k, z)| !(*k == Kind::Sidewalk && level == Some(0)) && z.holds(p))
            .map(|z| z.0)
    }

    /// Calls `hit` with every kind a point is in (each once).
    fn each_kind(&self, p: Vec3, level: Option<u8>, mut hit: impl FnMut(Kind)) {
        let mut last = None;
        for (k, z) in &self.zones {
            if last == Some(*k) || (*k == Kind::Sidewalk && level == Some(0)) {
                continue;
            }
            if z.holds(p) {
                hit(*k);
                last = Some(*k);
            }
        }
    }
}

fn in_triangle(p: [f64; 2], [a, b, c]: [[f64; 2]; 3]) -> bool {
    let side =
        |u: [f64; 2], v: [f64; 2]| (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]);
    let (d1, d2, d3) = (side(a, b), side(b, c), side(c, a));
    let neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(neg && pos)
}

/// Radius of the trunk at its base (the widest section in the lowest 0.5 m: the flare), m.
pub fn flare_radius(skeleton: &Skeleton) -> f64 {
    skeleton
        .stems
        .iter()
        .filter(|s| s.level == 0 && s.clone_of.is_none())
        .flat_map(|s| &skeleton.sections[s.sections.start as usize..s.sections.end as usize])
        .filter(|c| c.position.z < 0.5)
        .map(|c| c.radius as f64)
        .fold(0.0, f64::max)
}

/// Every conflict the grown tree has with the site this year (kinds without one are absent).
pub fn conflicts(skeleton: &Skeleton, site: &Site) -> Vec<Conflict> {
    conflicts_with(skeleton, &leaves_of(skeleton), site)
}

/// Leaf area outside every zone the site keeps clear, m², of the leaves listed by
/// [`leaves_of`]: what a cut tree can keep, set beside its uncut twin's (issue W).
pub fn leaf_outside_zones(leaves: &[(Vec3, f64)], site: &Site) -> f64 {
    let zones = Zones::new(site);
    (leaves.iter())
        .filter(|(at, _)| zones.kind_of(*at, None).is_none())
        .map(|(_, area)| area)
        .sum()
}

/// [`conflicts`] with the leaves already listed by [`leaves_of`].
pub fn conflicts_with(skeleton: &Skeleton, leaves: &[(Vec3, f64)], site: &Site) -> Vec<Conflict> {
    let zones = Zones::new(site);
    /// What one kind has found so far: leaf area, lowest part, lowest and highest point.
    #[derive(Clone, Copy)]
    struct Found {
        area: f64,
        part: Part,
        lo: f32,
        hi: f32,
    }
    let mut found: [Option<Found>; Kind::ALL.len()] = [None; Kind::ALL.len()];
    let mut note = |kind: Kind, at: Vec3, part: Part, area: f64| {
        let f = found[kind as usize].get_or_insert(Found {
            area: 0.0,
            part,
            lo: at.z,
            hi: at.z,
        });
        f.area += area;
        f.part = f.part.min(part);
        f.lo = f.lo.min(at.z);
        f.hi = f.hi.max(at.z);
    };
    for stem in &skeleton.stems {
        let part = match stem.level {
            0 => Part::Trunk,
            1 => Part::Limb,
            _ => Part::Branch,
        };
        for c in &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize] {
            zones.each_kind(c.position, Some(stem.level), |k| {
                note(k, c.position, part, 0.0)
            });
        }
    }
    let mut total = 0.0;
    for &(at, area) in leaves {
        total += area;
        zones.each_kind(at, None, |k| note(k, at, Part::Leaves, area));
    }
    let mut out: Vec<Conflict> = Kind::ALL
        .iter()
        .filter_map(|&kind| {
            found[kind as usize].map(|f| Conflict {
                kind,
                leaf_area: f.area,
                leaf_share: if total > 0.0 { f.area / total } else { 0.0 },
                part: f.part,
                heights: (f.lo as f64, f.hi as f64),
            })
        })
        .collect();
    // The flare may reach neither the curb nor the sidewalk's edge; a trunk standing inside
    // the sidewalk band is checked against the curb alone.
    let s = &site.street;
    let mut room = -s.curb;
    if s.sidewalk[0] > 0.0 {
        room = room.min(s.sidewalk[0]);
    }
    if flare_radius(skeleton) >= room {
        out.push(Conflict {
            kind: Kind::TrunkFlare,
            leaf_area: 0.0,
            leaf_share: 0.0,
            part: Part::Trunk,
            heights: (0.0, 0.5),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{CrossSection, Leaf, LeafShape, Stem, StemId};
    use glam::Quat;

    /// A 6 m trunk (radius 0.3 at the base) with one limb out to y = -3 at 5 m, and a leaf at
    /// its tip.
    fn tree() -> Skeleton {
        let mut s = Skeleton::default();
        let sec = |z: f32, y: f32, r: f32| CrossSection {
            position: Vec3::new(0.0, y, z),
            orientation: Quat::IDENTITY,
            radius: r,
            z: 0.0,
        };
        s.sections = vec![
            sec(0.0, 0.0, 0.3),
            sec(6.0, 0.0, 0.1),
            sec(5.0, 0.0, 0.05),
            sec(5.0, -3.0, 0.02),
        ];
        s.stems = vec![
            Stem {
                level: 0,
                parent: None,
                clone_of: None,
                offset: 0.0,
                length: 6.0,
                sections: 0..2,
                lobes: 0,
                lobe_depth: 0.0,
            },
            Stem {
                level: 1,
                parent: Some(StemId(0)),
                clone_of: None,
                offset: 5.0,
                length: 3.0,
                sections: 2..4,
                lobes: 0,
                lobe_depth: 0.0,
            },
        ];
        s.leaves.push(Leaf {
            position: Vec3::new(0.0, -3.0, 5.0),
            orientation: Quat::IDENTITY,
            length: 0.2,
            width: 0.1,
            shape: LeafShape::Oval,
            stem: StemId(1),
            light: 1.0,
        });
        s
    }

    fn site(extra: &str) -> Site {
        Site::parse(
            &format!("[street]\ncurb = -1.0\nsidewalk = [0.8, 3.2]\nroadway_clearance = 4.3\nsidewalk_clearance = 2.4\n{extra}"),
            "t.toml",
        )
        .unwrap()
    }

    #[test]
    fn a_wire_over_the_limb_is_hit_by_the_limb() {
        let s = site("[[wire]]\nheight = 6.0\noffset = -2.5\nclearance = 1.5\nminimum = 0.46\n");
        let c = conflicts(&tree(), &s);
        let wire = c
            .iter()
            .find(|c| c.kind == Kind::Wire)
            .expect("wire conflict");
        assert_eq!(wire.part, Part::Limb);
        assert!((wire.leaf_share - 1.0).abs() < 1e-9);
        // Raise the wire out of reach: no conflict.
        let s = site("[[wire]]\nheight = 9.0\noffset = -2.5\nclearance = 1.5\nminimum = 0.46\n");
        assert!(conflicts(&tree(), &s).iter().all(|c| c.kind != Kind::Wire));
    }

    #[test]
    fn roadway_clearance_and_the_flare() {
        // The limb reaches over the roadway (y < -1) at 5 m: clear of 4.3 m, not of 5.5 m.
        let c = conflicts(&tree(), &site(""));
        assert!(c.iter().all(|c| c.kind != Kind::Roadway), "{c:?}");
        let s = site("").street;
        let high = Site {
            street: crate::street::site::Street {
                roadway_clearance: 5.5,
                ..s
            },
            ..site("")
        };
        let c = conflicts(&tree(), &high);
        assert!(
            c.iter()
                .any(|c| c.kind == Kind::Roadway && c.part == Part::Limb),
            "{c:?}"
        );
        // A 0.3 m flare in a 1 m strip fits; in a 0.25 m one it does not.
        assert!(c.iter().all(|c| c.kind != Kind::TrunkFlare));
        let narrow = Site::parse("[street]\ncurb = -0.25\nsidewalk = [0.8, 3.2]\nroadway_clearance = 4.3\nsidewalk_clearance = 2.4\n", "t").unwrap();
        assert!(
            conflicts(&tree(), &narrow)
                .iter()
                .any(|c| c.kind == Kind::TrunkFlare)
        );
    }

    #[test]
    fn triangles() {
        let t = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        assert!(in_triangle([1.0, 1.0], t));
        assert!(!in_triangle([3.0, 3.0], t));
    }
}
