//! Measuring a grown tree the way the Urban Tree Database's trees were measured.

use crate::growth::model::diameter_height;
use crate::skeleton::Skeleton;
use glam::Vec3;

/// A tree's dimensions as the survey measured them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dimensions {
    /// Highest point of wood or leaf, m.
    pub height: f64,
    /// Height minus the lowest point of the live crown (side branches and leaves), m.
    pub crown_height: f64,
    /// Mean of the crown's x and y extents, m.
    pub crown_diameter: f64,
    /// Trunk diameter at 1.37 m (at 0.15 m, caliper height, on a tree not that tall), cm.
    pub dbh: f64,
    /// Sum of one side of every leaf, m².
    pub leaf_area: f64,
}

impl Dimensions {
    /// Relative errors against the measured functions, in the order height, DBH, crown
    /// diameter, crown height, leaf area (0 where a target is 0).
    pub fn relative_errors(&self, t: &crate::growth::model::Targets) -> [f64; 5] {
        let rel = |a: f64, b: f64| if b > 0.0 { a / b - 1.0 } else { 0.0 };
        [
            rel(self.height, t.height),
            rel(self.dbh, t.dbh),
            rel(self.crown_diameter, t.crown_diameter),
            rel(self.crown_height, t.crown_height),
            rel(self.leaf_area, t.leaf_area),
        ]
    }
}

/// Measures a skeleton whose first stem is the trunk, standing at the origin: its crown's
/// frame and leaves (a grown tree's short twigs lie within them, under its leaves).
pub fn measure(skeleton: &Skeleton) -> Dimensions {
    let mut top = f32::NEG_INFINITY;
    let mut bottom = f32::INFINITY;
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for stem in skeleton.frame_stems() {
        let crown = stem.level > 0;
        for c in &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize] {
            top = top.max(c.position.z);
            if crown {
                bottom = bottom.min(c.position.z);
                lo = lo.min(c.position);
                hi = hi.max(c.position);
            }
        }
    }
    let mut leaf_area = 0.0f64;
    for l in &skeleton.leaves {
        leaf_area += (crate::mesh::template_area(l.shape) * l.length * l.width) as f64;
        for p in [
            l.position,
            l.position + l.orientation * Vec3::new(0.0, 0.0, l.length),
        ] {
            top = top.max(p.z);
            bottom = bottom.min(p.z);
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let dbh = trunk_diameter(skeleton, diameter_height(top));
    let crown_diameter = if lo.x <= hi.x {
        ((hi.x - lo.x) + (hi.y - lo.y)) as f64 / 2.0
    } else {
        0.0
    };
    Dimensions {
        height: top.max(0.0) as f64,
        crown_height: if bottom.is_finite() {
            (top - bottom).max(0.0) as f64
        } else {
            0.0
        },
        crown_diameter,
        dbh: dbh as f64 * 100.0,
        leaf_area,
    }
}

/// The trunk's diameter at height `at`, m: on a multi-stem tree (several level-0 stems
/// crossing `at`), the diameter of one stem with their basal area together, as the Urban Tree
/// Database measured such trees and the growth model holds them to f_DBH
/// (`Grower::diameter_carried`). A trunk that does not reach `at` is read at its base.
fn trunk_diameter(skeleton: &Skeleton, at: f32) -> f32 {
    let read = |stem: &crate::skeleton::Stem| {
        let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        let i = s.partition_point(|c| c.position.z < at);
        if i == 0 || i >= s.len() {
            return None;
        }
        let (a, b) = (s[i - 1], s[i]);
        let f = (at - a.position.z) / (b.position.z - a.position.z).max(1e-6);
        Some((a.radius + (b.radius - a.radius) * f) * 2.0)
    };
    let mut read = skeleton
        .stems
        .iter()
        .filter(|s| s.level == 0)
        .filter_map(read);
    let Some(first) = read.next() else {
        return skeleton.sections.first().map_or(0.0, |c| c.radius) * 2.0;
    };
    match read.next() {
        None => first,
        Some(second) => {
            let squares: f32 = read.map(|d| d * d).sum();
            (first * first + second * second + squares).sqrt()
        }
    }
}
