//! Leaf lobes: the bounding volumes a Fields tree grows into, and the control points on them.

use super::rules::{PointSpread, TreeRules};
use crate::rng::Random;
use glam::Vec3;

/// A leaf lobe: a sphere (as the `.tree` format stores it), which the species' [`LobeShape`]
/// stretches upward and narrows toward a cone with its apex at the top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// Centre, metres.
    pub centre: Vec3,
    /// Radius (across), metres.
    pub radius: f32,
}

/// How a species shapes every one of its lobes.
///
/// The paper's lobes are spheres, and LeafTaper 1 turns a sphere into a cone as wide at its base
/// as it is tall (rule 6). A balsam fir's crown is a spire about three times as tall as it is
/// wide, which no sphere tapers into, so a species may stretch its lobes upward. The stretch
/// belongs to the species, not to a lobe, so `.tree` files keep storing plain spheres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LobeShape {
    /// LeafTaper: 0 keeps the (stretched) sphere, 1 makes a cone.
    pub taper: f32,
    /// Height over width: the lobe reaches `stretch * radius` above and below its centre.
    pub stretch: f32,
}

impl LobeShape {
    /// How `rules` shape a species' lobes: its LeafTaper, and, for a species whose crown is one
    /// lobe, the stretch that makes that lobe as tall as the crown when it is as wide.
    pub fn of(rules: &TreeRules) -> LobeShape {
        let mut shape = LobeShape::tapered(rules.leaf_taper as f32);
        if let Some(c) = &rules.layout.crown
            && c.lobes == 1
        {
            let radius = (0.5 * c.width) as f32 / shape.widest();
            let half_height = (0.5 * (c.height - rules.layout.crown_base)) as f32;
            shape.stretch = (half_height / radius.max(1e-6)).clamp(0.2, 20.0);
        }
        shape
    }

    /// A sphere narrowed by `taper`, not stretched.
    pub fn tapered(taper: f32) -> LobeShape {
        LobeShape {
            taper,
            stretch: 1.0,
        }
    }

    /// The widest the shape reaches from its axis, over its radius: 1 for a sphere, 2 for a
    /// cone (its base), and in between the larger of the two ends of the blend.
    pub fn widest(&self) -> f32 {
        // (1 - t) sqrt(1 - u^2) + t (1 - u) over u in [-1, 1]: at u = -1 it is 2t; inside, the
        // maximum lies where the derivative vanishes, u = -t / sqrt((1 - t)^2 + t^2).
        let t = self.taper.clamp(0.0, 1.0);
        let u = -t / ((1.0 - t).powi(2) + t * t).sqrt();
        let inside = (1.0 - t) * (1.0 - u * u).max(0.0).sqrt() + t * (1.0 - u);
        inside.max(2.0 * t)
    }
}

impl Lobe {
    /// Half the lobe's height.
    pub fn half_height(&self, shape: LobeShape) -> f32 {
        self.radius * shape.stretch
    }

    /// Largest distance from the lobe's vertical axis at height `z` above its centre: the
    /// (stretched) sphere's outline blended by the taper toward the cone's, which keeps the top,
    /// the middle circle, and pushes the bottom out to twice the radius (the paper's rule 6).
    pub fn reach(&self, z: f32, shape: LobeShape) -> f32 {
        let r = self.radius;
        let z = (z / shape.stretch).clamp(-r, r);
        let t = shape.taper;
        (1.0 - t) * (r * r - z * z).max(0.0).sqrt() + t * (r - z)
    }

    /// Moves a point of the lobe's surface where the taper puts it: same height, distance from
    /// the axis scaled to the tapered outline.
    pub fn taper_point(&self, p: Vec3, shape: LobeShape) -> Vec3 {
        let d = p - self.centre;
        let rho = d.truncate().length();
        let target = self.reach(d.z, shape);
        if rho <= 1e-9 {
            return p;
        }
        let s = target / rho;
        self.centre + Vec3::new(d.x * s, d.y * s, d.z)
    }

    /// How far `p` lies outside the tapered lobe (0 inside): the excess above or below it and
    /// the excess beyond its outline at that height, combined.
    pub fn outside(&self, p: Vec3, shape: LobeShape) -> f32 {
        let d = p - self.centre;
        let vertical = (d.z.abs() - self.half_height(shape)).max(0.0);
        let across = (d.truncate().length() - self.reach(d.z, shape)).max(0.0);
        vertical.hypot(across)
    }

    /// How deep `p` lies inside the lobe, as a fraction: 0 on its outline, 1 on its axis at
    /// the height of `p` (negative outside).
    pub fn depth(&self, p: Vec3, shape: LobeShape) -> f32 {
        let d = p - self.centre;
        let reach = self.reach(d.z, shape);
        if d.z.abs() > self.half_height(shape) || reach <= 1e-9 {
            return -1.0;
        }
        1.0 - d.truncate().length() / reach
    }

    /// The nearest point inside the tapered lobe along the same height and bearing (a point
    /// already inside is returned as it is).
    pub fn clamp_inside(&self, p: Vec3, shape: LobeShape) -> Vec3 {
        let d = p - self.centre;
        let h = self.half_height(shape);
        let z = d.z.clamp(-h, h);
        let rho = d.truncate().length();
        let reach = self.reach(z, shape) * 0.999;
        let s = if rho > reach { reach / rho } else { 1.0 };
        self.centre + Vec3::new(d.x * s, d.y * s, z)
    }

    /// `n` points on the lobe's surface, then tapered.
    pub fn surface_points(
        &self,
        n: usize,
        spread: PointSpread,
        shape: LobeShape,
        random: &mut Random,
    ) -> Vec<Vec3> {
        let mut out = Vec::with_capacity(n);
        let turn = random.unit() as f32 * std::f32::consts::TAU;
        // Whorls: rings of this many points (a fir puts three to six branches round each node;
        // three make the most tiers of the rule's 55 branches).
        let per_whorl = 3usize;
        let whorls = n.div_ceil(per_whorl).max(1);
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
                PointSpread::Whorls => {
                    // Rings evenly spaced in height from near the bottom to near the top, each
                    // turned half a step from the one below, with a little scatter.
                    let (w, k) = (i / per_whorl, i % per_whorl);
                    let z = -0.94
                        + 1.84 * (w as f32 + 0.5) / whorls as f32
                        + random.var(0.25 / whorls as f64) as f32;
                    let z = z.clamp(-0.98, 0.98);
                    let a = turn
                        + std::f32::consts::TAU
                            * (k as f32 + 0.5 * (w % 2) as f32 + random.var(0.12) as f32)
                            / per_whorl as f32;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    Vec3::new(r * a.cos(), r * a.sin(), z)
                }
            };
            let on = Vec3::new(u.x, u.y, u.z * shape.stretch) * self.radius;
            out.push(self.taper_point(self.centre + on, shape));
        }
        out
    }

    /// Where the segment from `a` along unit `dir` (length `len`) is inside the (stretched)
    /// sphere, as distances from `a`; `None` if it misses.
    pub fn chord(&self, a: Vec3, dir: Vec3, len: f32, shape: LobeShape) -> Option<(f32, f32)> {
        // Squash the stretch out of the picture: the lobe becomes a sphere, the line stays a
        // line with the same parameter.
        let squash = Vec3::new(1.0, 1.0, 1.0 / shape.stretch);
        let m = (a - self.centre) * squash;
        let d = dir * squash;
        let dd = d.length_squared();
        if dd <= 1e-12 {
            return None;
        }
        let b = m.dot(d) / dd;
        let c = (m.length_squared() - self.radius * self.radius) / dd;
        let disc = b * b - c;
        if disc < 0.0 {
            return None;
        }
        let root = disc.sqrt();
        let (t0, t1) = ((-b - root).max(0.0), (-b + root).min(len));
        (t0 <= t1).then_some((t0, t1))
    }
}
