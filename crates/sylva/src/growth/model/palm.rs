//! Palms: one unbranched trunk crowned by a rosette of fronds (growth-architecture spec: a palm
//! does not branch). With no buds there is nothing to self-organise, so each step the trunk
//! rises to where the fronds leave it and the rosette is laid out from the measured crown:
//! the fronds reach out to half the crown diameter, the youngest rise above the apex, the
//! oldest droop below it (and, in a fan palm's skirt, hang straight down), and their blades
//! add up to the measured leaf area.

use super::*;

/// Share of the crown height the youngest fronds rise above the trunk's apex; the rest of the
/// crown hangs below it.
const PALM_RISE: f32 = 0.4;
/// Steepest frond, degrees above the horizontal.
const FROND_STEEPEST: f32 = 70.0;
/// A frond's blade width as a share of its length, from which the number of fronds follows.
const FROND_WIDTH: f32 = 0.7;
/// Fewest and most fronds in a crown.
const FRONDS: (usize, usize) = (8, 40);
/// Narrowest blade, as a share of the frond's length: where a region's leaf-area equation
/// gives a big crown almost no leaves (it turns over inside the measured trunks, as the
/// Canary Island date palm's of southern California does), the fronds stay fronds and the
/// leaf area comes out above the equation's, which the run reports.
const FROND_NARROWEST: f32 = 0.15;

impl Grower {
    /// A palm's step: the trunk rises to where the fronds leave it, one segment a year, as
    /// thick as the measured DBH (a palm's trunk does not taper).
    pub(super) fn grow_palm(&mut self) {
        let t = self.targets_now();
        let apex = palm_apex(&t);
        if self.age - self.apex_segment(0).born >= 1.0 {
            self.extend(0, Vec3::Z, 0.0);
        }
        let last = *self.branches[0].segments.last().expect("a trunk") as usize;
        let seg = &mut self.segments[last];
        seg.length = (apex - seg.start.z).max(0.0);
        seg.goal = seg.length;
        self.refresh_radii();
        self.leaves_on.clear();
        self.leaves_on.resize(self.segments.len(), 0);
    }

    /// The fronds of the crown now, as leaves of the trunk added to `out`: youngest (steepest)
    /// first, turned by the golden angle.
    pub(super) fn fronds_into(&self, out: &mut Vec<Leaf>) {
        let t = self.targets_now();
        let (length, rise) = frond_reach(&t);
        let droop = (t.crown_height as f32 - rise).min(length);
        let (high, low) = ((rise / length).asin(), -(droop / length).asin());
        let area = crate::mesh::leaf_template(LeafShape::Palm).area();
        let count = (t.leaf_area as f32 / (area * length * length * FROND_WIDTH))
            .round()
            .clamp(FRONDS.0 as f32, FRONDS.1 as f32) as usize;
        let width =
            (t.leaf_area as f32 / (count as f32 * area * length)).max(FROND_NARROWEST * length);
        let apex = Vec3::new(0.0, 0.0, palm_apex(&t));
        let mut rng = self.key.child(3000).stream();
        for k in 0..count {
            let share = k as f32 / (count - 1) as f32;
            let elevation = high + (low - high) * share + rng.var(0.05) as f32;
            let azimuth = (k as f32 * DIVERGENCE).to_radians() + rng.var(0.1) as f32;
            let z = Vec3::new(
                elevation.cos() * azimuth.cos(),
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
            );
            out.push(Leaf {
                light: self.light.light_at(apex + z * length * 0.5),
                position: apex,
                // The blade faces the sky as far as the frond lets it.
                orientation: leaves::facing_sky(z, || Vec3::X),
                length,
                width,
                shape: LeafShape::Palm,
                stem: StemId(0),
            });
        }
    }
}

/// A frond's length (it reaches out to half the crown diameter) and how far the youngest rise
/// above the apex, m.
fn frond_reach(t: &Targets) -> (f32, f32) {
    let length = (t.crown_diameter as f32 / 2.0).max(0.1);
    let steepest = length * FROND_STEEPEST.to_radians().sin();
    (length, (PALM_RISE * t.crown_height as f32).min(steepest))
}

/// Height of the trunk's apex: the crown's top less the youngest fronds' rise.
fn palm_apex(t: &Targets) -> f32 {
    (t.height as f32 - frond_reach(t).1).max(0.1)
}
