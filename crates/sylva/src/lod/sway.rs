//! Wind sway of a tree stored for range, the same at every range: a displacement of every
//! point by its height, which the GPU applies to whatever it rebuilds from the records (tubes,
//! leaf cards, lines, points) and the CPU reproduces here.
//!
//! Weber & Penn's sway (spec section 12) turns each segment of a stem by
//! `(a1 sin b + a2 sin 0.7 b) / N` degrees about x and y, with `a0 = 4 L (1 - Z) / rho_Z`,
//! `a1 = speed / 50 a0`, `a2 = gust / 50 a0 + a1 / 2` and `b = o + r / L t / 15`. On a trunk
//! that tapers to a point, `rho_Z = r (1 - Z)`, so `a0 = 4 L / r` at every segment: the trunk
//! bends by the same angle per unit of length, its tilt grows linearly with height, and a
//! point at height `z` moves by `theta z^2 / (2 L)` where `theta` is the whole trunk's turn.
//! Everything above rides on it. The turn is computed once per copy and frame; each copy has
//! its own phases, so a stand does not sway in step.

use super::LodTree;
use crate::Wind;
use glam::Vec3;

/// A copy's sway at one moment: the trunk's whole turn about x and y, radians, and its length.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sway {
    /// Turn about x (moves the crown towards -y) and about y (towards +x), radians.
    pub turn: [f32; 2],
    /// Trunk length, metres: below it the tree bends, above it the crown tilts as a whole.
    pub length: f32,
}

impl LodTree {
    /// The trunk's length and base radius, metres, from its stored rings: the lowest and
    /// highest ring centre, and the thickest ring.
    pub fn trunk_size(&self) -> (f32, f32) {
        let q = &self.quantiser;
        let (mut lo, mut hi, mut radius) = (f32::MAX, f32::MIN, 0.0f32);
        for run in &self.lists[0].runs {
            for s in &self.segments[run.items.start as usize..run.items.end as usize] {
                for ring in [&s.a, &s.b] {
                    let (c, r, _) = q.unpack_ring(ring);
                    (lo, hi, radius) = (lo.min(c.z), hi.max(c.z), radius.max(r));
                }
            }
        }
        if lo > hi {
            (0.0, 0.0)
        } else {
            (hi - lo, radius)
        }
    }

    /// The sway of a copy whose random phases are `phase` (radians), in `wind`.
    pub fn sway(&self, wind: &Wind, phase: [f32; 2]) -> Sway {
        let (length, radius) = self.trunk_size();
        if !wind.is_active() || length <= 0.0 || radius <= 0.0 {
            return Sway::default();
        }
        let a0 = 4.0 * length as f64 / radius as f64;
        let a1 = wind.speed / 50.0 * a0;
        let a2 = wind.gust / 50.0 * a0 + a1 / 2.0;
        // The generator's phase rate (`weber_penn::trace`): the radius read in millimetres.
        let tb = 1000.0 * radius as f64 / length as f64 * wind.time / 15.0;
        let turn = phase.map(|o| {
            let b = o as f64 + tb;
            ((a1 * b.sin() + a2 * (0.7 * b).sin()).to_radians()) as f32
        });
        Sway { turn, length }
    }
}

impl Sway {
    /// How far a point of the tree (its own frame, base at the origin) moves.
    pub fn displacement(&self, p: Vec3) -> Vec3 {
        if self.length <= 0.0 {
            return Vec3::ZERO;
        }
        let s = (p.z / self.length).max(0.0);
        // Bent along the trunk, straight above it.
        let along = if s <= 1.0 { s * s / 2.0 } else { s - 0.5 };
        let (dx, dy) = (
            self.length * self.turn[1] * along,
            -self.length * self.turn[0] * along,
        );
        // Sideways motion shortens the height so that the trunk keeps its length.
        let dz = -(dx * dx + dy * dy) / (2.0 * p.z.max(0.5));
        Vec3::new(dx, dy, dz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshOptions;
    use crate::{GenerateOptions, generate, species::builtin};

    #[test]
    fn the_base_stays_and_the_top_moves_with_the_phase_and_the_wind() {
        let p = builtin("black_tupelo").unwrap();
        let sk = generate(&p, &GenerateOptions::default()).unwrap();
        let t = LodTree::build(&sk, &MeshOptions::default());
        let (length, radius) = t.trunk_size();
        assert!(length > 10.0 && radius > 0.1, "{length} {radius}");
        let wind = |time| Wind {
            speed: 10.0,
            gust: 5.0,
            time,
        };
        let top = Vec3::new(0.0, 0.0, length);
        let a = t.sway(&wind(0.0), [0.3, 1.1]);
        assert_eq!(a.displacement(Vec3::ZERO), Vec3::ZERO);
        assert!(a.displacement(top).length() > 0.05);
        // Quadratic along the trunk.
        let half = a.displacement(top / 2.0).truncate().length();
        let whole = a.displacement(top).truncate().length();
        assert!((half / whole - 0.25).abs() < 1e-3);
        // Another phase or another moment sways differently; no wind, no sway.
        assert_ne!(t.sway(&wind(0.0), [2.0, 0.1]).turn, a.turn);
        assert_ne!(t.sway(&wind(1.5), [0.3, 1.1]).turn, a.turn);
        let calm = Wind::default();
        assert_eq!(t.sway(&calm, [0.3, 1.1]).displacement(top), Vec3::ZERO);
    }
}
