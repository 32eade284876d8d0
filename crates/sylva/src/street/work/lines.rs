//! A tree under an overhead line, measured as the utility's crew sees it: how close its wood
//! and leaves come to the conductor, and how much of its leaf lies inside the line's clearance
//! at cutting and inside the minimum kept at all times (`site.rs`'s [`Wire`]; GO 95's Rule 35).
//!
//! Distances are radial, in the plane across the street (the line runs along x): a section of
//! wood is as near as its surface (centre less radius), a leaf as near as its centre, as the
//! conflicts count them (`conflicts.rs`).

use crate::Skeleton;
use crate::street::site::Wire;
use glam::Vec3;

/// One line's check of a tree in one year, before that year's cuts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LineCheck {
    /// The nearest wood or leaf to the conductor, m (infinite for a tree with neither).
    pub closest_m: f64,
    /// The nearest wood, m.
    pub closest_wood_m: f64,
    /// Leaf area inside the clearance at cutting, m², and its share of the tree's.
    pub leaf_in_clearance_m2: f64,
    /// Its share of the tree's leaf area.
    pub leaf_share_in_clearance: f64,
    /// Leaf area inside the minimum clearance, m².
    pub leaf_in_minimum_m2: f64,
}

impl LineCheck {
    /// Whether any leaf or wood is inside the minimum clearance of `wire`: a breach.
    pub fn breaches(&self, wire: &Wire) -> bool {
        self.closest_m < wire.minimum
    }
}

/// The radial distance of `p` from `wire`'s conductor, m.
pub fn distance(p: Vec3, wire: &Wire) -> f64 {
    let dy = p.y as f64 - wire.offset;
    let dz = p.z as f64 - wire.height;
    (dy * dy + dz * dz).sqrt()
}

/// The direction away from `wire`'s conductor at `p`, across the street (the line runs along
/// x); straight down where `p` lies on it.
pub fn away(p: Vec3, wire: &Wire) -> Vec3 {
    let d = Vec3::new(0.0, p.y - wire.offset as f32, p.z - wire.height as f32);
    d.try_normalize().unwrap_or(-Vec3::Z)
}

/// How close `skeleton` (with its `leaves`, as [`crate::street::energy::crown::leaves_of`]
/// lists them) comes to `wire`.
pub fn check(skeleton: &Skeleton, leaves: &[(Vec3, f64)], wire: &Wire) -> LineCheck {
    let wood = (skeleton.sections.iter())
        .map(|c| distance(c.position, wire) - c.radius as f64)
        .fold(f64::INFINITY, f64::min);
    let mut out = LineCheck {
        closest_m: wood,
        closest_wood_m: wood,
        ..Default::default()
    };
    let mut total = 0.0;
    for &(at, area) in leaves {
        total += area;
        let d = distance(at, wire);
        out.closest_m = out.closest_m.min(d);
        if d < wire.clearance {
            out.leaf_in_clearance_m2 += area;
        }
        if d < wire.minimum {
            out.leaf_in_minimum_m2 += area;
        }
    }
    if total > 0.0 {
        out.leaf_share_in_clearance = out.leaf_in_clearance_m2 / total;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::CrossSection;
    use glam::Quat;

    #[test]
    fn distances_are_radial_across_the_street() {
        let wire = Wire {
            height: 8.0,
            offset: -1.0,
            clearance: 1.2,
            minimum: 0.5,
            voltage_kv: None,
            access: Default::default(),
            cycle: None,
        };
        // Along the street makes no difference; across and up does.
        assert!((distance(Vec3::new(50.0, -1.0, 7.0), &wire) - 1.0).abs() < 1e-6);
        assert!((distance(Vec3::new(0.0, 2.0, 12.0), &wire) - 5.0).abs() < 1e-6);
        assert!((away(Vec3::new(3.0, -1.0, 6.0), &wire) - -Vec3::Z).length() < 1e-6);
        let mut s = Skeleton::default();
        s.sections.push(CrossSection {
            position: Vec3::new(0.0, -1.0, 7.0),
            orientation: Quat::IDENTITY,
            radius: 0.1,
            z: 0.0,
        });
        let leaves = [
            (Vec3::new(0.0, -1.0, 7.6), 2.0),
            (Vec3::new(0.0, -1.0, 3.0), 2.0),
        ];
        let c = check(&s, &leaves, &wire);
        assert!((c.closest_wood_m - 0.9).abs() < 1e-6);
        assert!((c.closest_m - 0.4).abs() < 1e-6);
        assert!(c.breaches(&wire));
        assert_eq!(c.leaf_in_clearance_m2, 2.0);
        assert_eq!(c.leaf_in_minimum_m2, 2.0);
        assert!((c.leaf_share_in_clearance - 0.5).abs() < 1e-12);
    }
}
