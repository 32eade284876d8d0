//! Leaf lobes: the bounding volumes a Fields tree grows into, and the control points on them.

use super::rules::PointSpread;
use crate::rng::Random;
use glam::Vec3;

/// A leaf lobe: a sphere (as the `.tree` format stores it), which `LeafTaper` narrows toward a
/// cone with its apex at the top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// Centre, metres.
    pub centre: Vec3,
    /// Radius, metres.
    pub radius: f32,
}

impl Lobe {
    /// Largest distance from the lobe's vertical axis at height `z` above its centre
    /// (−R ≤ z ≤ R): the sphere's √(R² − z²) blended by `taper` toward the cone's R − z, which
    /// keeps the top, the middle circle, and pushes the bottom out to twice the radius (the
    /// paper's rule 6).
    pub fn reach(&self, z: f32, taper: f32) -> f32 {
        let r = self.radius;
        let z = z.clamp(-r, r);
        (1.0 - taper) * (r * r - z * z).max(0.0).sqrt() + taper * (r - z)
    }

    /// Moves a point of the sphere's surface where `taper` puts it: same height, distance from
    /// the axis scaled to the tapered outline.
    pub fn taper_point(&self, p: Vec3, taper: f32) -> Vec3 {
        let d = p - self.centre;
        let rho = d.truncate().length();
        let target = self.reach(d.z, taper);
        if rho <= 1e-9 {
            return p;
        }
        let s = target / rho;
        self.centre + Vec3::new(d.x * s, d.y * s, d.z)
    }

    /// How far `p` lies outside the tapered lobe (0 inside): the excess above or below it and
    /// the excess beyond its outline at that height, combined.
    pub fn outside(&self, p: Vec3, taper: f32) -> f32 {
        let d = p - self.centre;
        let vertical = (d.z.abs() - self.radius).max(0.0);
        let across = (d.truncate().length() - self.reach(d.z, taper)).max(0.0);
        vertical.hypot(across)
    }

    /// The nearest point inside the tapered lobe along the same height and bearing (a point
    /// already inside is returned as it is).
    pub fn clamp_inside(&self, p: Vec3, taper: f32) -> Vec3 {
        let d = p - self.centre;
        let z = d.z.clamp(-self.radius, self.radius);
        let rho = d.truncate().length();
        let reach = self.reach(z, taper) * 0.999;
        let s = if rho > reach { reach / rho } else { 1.0 };
        self.centre + Vec3::new(d.x * s, d.y * s, z)
    }

    /// `n` points on the sphere's surface, then tapered.
    pub fn surface_points(
        &self,
        n: usize,
        spread: PointSpread,
        taper: f32,
        random: &mut Random,
    ) -> Vec<Vec3> {
        let mut out = Vec::with_capacity(n);
        let turn = random.unit() as f32 * std::f32::consts::TAU;
        for i in 0..n {
            let u = match spread {
                PointSpread::Uniform => loop {
                    // Rejection from the cube gives directions uniform on the sphere.
                    let v = Vec3::new(
                        random.var(1.0) as f32,
                        random.var(1.0) as f32,
                        random.var(1.0) as f32,
                    );
                    let l = v.length();
                    if l > 1e-3 && l <= 1.0 {
                        break v / l;
                    }
                },
                PointSpread::Even => {
                    // Golden-angle spiral: equal areas per point.
                    let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let a = turn + i as f32 * 2.399_963;
                    Vec3::new(r * a.cos(), r * a.sin(), z)
                }
            };
            out.push(self.taper_point(self.centre + u * self.radius, taper));
        }
        out
    }

    /// Where the segment from `a` along unit `dir` (length `len`) is inside the sphere, as
    /// distances from `a`; `None` if it misses.
    pub fn chord(&self, a: Vec3, dir: Vec3, len: f32) -> Option<(f32, f32)> {
        let m = a - self.centre;
        let b = m.dot(dir);
        let c = m.length_squared() - self.radius * self.radius;
        let disc = b * b - c;
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let (t0, t1) = ((-b - root).max(0.0), (-b + root).min(len));
        (t0 <= t1).then_some((t0, t1))
    }
}
