//! Tracing one stem's axis: segments, curvature (spec 6), splits into clones (spec 7), helices,
//! vertical attraction (spec 11), wind sway (spec 12), and the cross-sections that carry the
//! radius profile (spec 8).

use super::equations::{flare_factor, taper_radius};
use super::{Wind, deg};
use crate::params::TreeParams;
use crate::rng::{Random, StreamKey};
use crate::skeleton::{CrossSection, StemId};
use glam::{DQuat, DVec3};
use std::f64::consts::TAU;

/// Samples per helical segment.
const HELIX_SAMPLES: usize = 10;
/// Most extra profile sections per stem (beads, flare, rounded tips).
const MAX_PROFILE_SAMPLES: usize = 240;

/// Everything needed to trace a stem, or a clone from its split point on.
#[derive(Clone, Debug)]
pub(crate) struct StemStart {
    pub level: usize,
    pub parent: Option<StemId>,
    pub clone_of: Option<StemId>,
    /// Distance along the parent where the stem attaches, metres.
    pub offset: f64,
    pub length: f64,
    pub radius: f64,
    pub position: DVec3,
    pub orientation: DQuat,
    pub key: StreamKey,
    /// First segment this stem traces (0, or the segment after a split for a clone).
    pub first_segment: usize,
    /// Accumulated counter-curve from splits, degrees per segment.
    pub curve_correction: f64,
    /// Split error-diffusion state.
    pub split_error: f64,
    /// Fraction of the children this stem keeps after splits (1/(k+1) per split).
    pub share: f64,
    /// Parent's length (0 for trunks) and the maximum child length drawn for the parent.
    pub parent_length: f64,
    pub parent_lmax: f64,
    /// Where children may start, as a unit position (bare trunk base, or the part inside the parent).
    pub z_min: f64,
    /// Azimuth where child placement starts (a clone turns 180 degrees from its original).
    pub rotate_start: f64,
}

/// Read-only context of a tree being traced.
#[derive(Clone, Copy)]
pub(crate) struct Tracer<'a> {
    pub p: &'a TreeParams,
    pub wind: Wind,
}

impl Tracer<'_> {
    /// Radius at unit position `z` of a stem (taper, and flare on trunks).
    pub fn radius_at(&self, level: usize, radius: f64, length: f64, z: f64) -> f64 {
        let taper = self.p.level(level).taper;
        let r = taper_radius(radius, length, taper, z);
        if level == 0 {
            r * flare_factor(self.p.flare, z)
        } else {
            r
        }
    }

    /// Unit positions, strictly inside (0, 1), where the radius profile needs extra sections:
    /// the trunk's flare zone, a rounded tip, periodic beads. Sorted.
    pub fn profile_samples(&self, st: &StemStart, out: &mut Vec<f64>) {
        out.clear();
        let taper = self.p.level(st.level).taper;
        if st.level == 0 && self.p.flare != 0.0 {
            out.extend((1..=6).map(|j| j as f64 / 48.0));
        }
        if st.length > 0.0 && st.radius > 0.0 {
            if taper > 2.0 {
                // Beads of length 2r counted from the tip, six sections each.
                let step = (2.0 * st.radius / 6.0).max(st.length / MAX_PROFILE_SAMPLES as f64);
                let mut d = step;
                while d < st.length {
                    out.push(1.0 - d / st.length);
                    d += step;
                }
            } else if taper > 1.0 {
                // The rounded tip spans about one tip radius.
                let unit = if taper < 2.0 { 2.0 - taper } else { 0.0 };
                let tip = st.radius * (1.0 - unit);
                for f in [1.0, 0.7, 0.45, 0.25, 0.1] {
                    out.push(1.0 - (tip * f / st.length).min(1.0));
                }
            }
        }
        out.retain(|z| *z > 0.0 && *z < 1.0);
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    }

    /// Traces a stem from `st.first_segment` to its tip, appending its sections to `sections`
    /// and the clones it splits off to `clones`. `shares` receives, per segment, the share of
    /// children the stem keeps there (indexed by segment; earlier entries are untouched).
    /// The draws come from `rng` in a fixed order, so a probe with a copy of `rng` sees exactly
    /// the stem that the real pass builds.
    pub fn trace(
        &self,
        st: &StemStart,
        rng: &mut Random,
        profile: &[f64],
        sections: &mut Vec<CrossSection>,
        clones: &mut Vec<StemStart>,
        shares: &mut Vec<f64>,
    ) {
        let lp = self.p.level(st.level);
        let n = lp.curve_res.max(1) as usize;
        let nf = n as f64;
        let seg_len = st.length / nf;
        let mut pos = st.position;
        let mut q = st.orientation;
        let mut correction = st.curve_correction;
        let mut split_error = st.split_error;
        let mut share = st.share;
        let helix_radius = if lp.curve_v < 0.0 {
            seg_len * deg(lp.curve_v.abs()).tan() / TAU
        } else {
            0.0
        };
        let wind_phase = if self.wind.is_active() {
            let mut w = st.key.child(super::KEY_WIND).stream();
            Some((w.var(std::f64::consts::PI), w.var(std::f64::consts::PI)))
        } else {
            None
        };
        // Each turn of a helix is sampled at the same places; they are worked out once.
        let mut helix = [(DVec3::ZERO, DQuat::IDENTITY); HELIX_SAMPLES];
        if helix_radius > 0.0 {
            for (j, h) in helix.iter_mut().enumerate() {
                *h = helix_point(helix_radius, seg_len, j as f64 / HELIX_SAMPLES as f64);
            }
        }
        shares.resize(n, 0.0);
        let mut samples: Vec<f64> = Vec::with_capacity(HELIX_SAMPLES + 8);
        #[allow(clippy::needless_range_loop)]
        // `s` is the segment index of the model, not just a position
        for s in st.first_segment..n {
            if s > 0 {
                q = self.bend(st, q, s, n, correction, rng, wind_phase);
            }
            shares[s] = share;
            let z0 = s as f64 / nf;
            let z1 = (s + 1) as f64 / nf;
            // Sections inside this segment: its start, helix samples, profile samples.
            samples.clear();
            samples.push(0.0);
            if helix_radius > 0.0 {
                samples.extend((1..HELIX_SAMPLES).map(|j| j as f64 / HELIX_SAMPLES as f64));
            }
            let lo = profile.partition_point(|z| *z <= z0);
            let hi = profile.partition_point(|z| *z < z1);
            samples.extend(profile[lo..hi].iter().map(|z| (z - z0) * nf));
            samples.sort_by(f64::total_cmp);
            samples.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
            for &t in &samples {
                let (offset, frame) = if helix_radius > 0.0 {
                    // The helix's own samples are the same in every segment of the stem.
                    let j = (t * HELIX_SAMPLES as f64).round();
                    let (local, turn) = if j < HELIX_SAMPLES as f64 && j / HELIX_SAMPLES as f64 == t
                    {
                        helix[j as usize]
                    } else {
                        helix_point(helix_radius, seg_len, t)
                    };
                    (q * local, q * turn)
                } else {
                    (q * DVec3::new(0.0, 0.0, t * seg_len), q)
                };
                let z = z0 + t / nf;
                sections.push(section(
                    pos + offset,
                    frame,
                    self.radius_at(st.level, st.radius, st.length, z),
                    z,
                ));
            }
            pos += q * DVec3::new(0.0, 0.0, seg_len);
            if s + 1 < n {
                let k = if st.level == 0 && s == 0 && self.p.base_splits > 0 {
                    self.p.base_splits as usize
                } else {
                    super::diffuse(lp.seg_splits, &mut split_error)
                };
                if k > 0 {
                    share /= (k + 1) as f64;
                    let remaining = (n - s - 1) as f64;
                    let base_split = st.level == 0 && s == 0 && self.p.base_splits > 0;
                    let declination = q.mul_vec3(DVec3::Z).z.clamp(-1.0, 1.0).acos().to_degrees();
                    let sign = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
                    let mut turned = Vec::with_capacity(k + 1);
                    for i in 0..=k {
                        let angle = if base_split {
                            lp.split_angle + rng.var(lp.split_angle_v)
                        } else {
                            (lp.split_angle + rng.var(lp.split_angle_v) - declination).max(0.0)
                        };
                        let spin = if base_split {
                            360.0 * i as f64 / (k + 1) as f64 + rng.var(lp.split_angle_v)
                        } else {
                            let u = rng.unit();
                            let side = if i % 2 == 0 { sign } else { -sign };
                            side * (20.0 + 0.75 * (30.0 + (declination - 90.0).abs()) * u * u)
                        };
                        let tilted = DQuat::from_rotation_z(deg(spin))
                            * q
                            * DQuat::from_rotation_x(deg(angle));
                        turned.push((tilted.normalize(), correction - angle / remaining));
                    }
                    let (q0, c0) = turned[0];
                    q = q0;
                    correction = c0;
                    for (i, &(qc, cc)) in turned.iter().enumerate().skip(1) {
                        clones.push(StemStart {
                            clone_of: None, // filled in by the caller, who knows the id
                            position: pos,
                            orientation: qc,
                            key: st.key.child(super::KEY_CLONE).child((s * 64 + i) as u64),
                            first_segment: s + 1,
                            curve_correction: cc,
                            split_error,
                            share,
                            rotate_start: st.rotate_start + 180.0,
                            ..st.clone()
                        });
                    }
                }
            }
        }
        sections.push(section(
            pos,
            q,
            self.radius_at(st.level, st.radius, st.length, 1.0),
            1.0,
        ));
    }

    /// Turns the frame at the start of segment `s`: curvature, split counter-curve, random
    /// bend, vertical attraction and wind.
    #[allow(clippy::too_many_arguments)]
    fn bend(
        &self,
        st: &StemStart,
        mut q: DQuat,
        s: usize,
        n: usize,
        correction: f64,
        rng: &mut Random,
        wind_phase: Option<(f64, f64)>,
    ) -> DQuat {
        let lp = self.p.level(st.level);
        let nf = n as f64;
        let curve = if lp.curve_back == 0.0 {
            lp.curve / nf
        } else if s < n.div_ceil(2) {
            2.0 * lp.curve / nf
        } else {
            2.0 * lp.curve_back / nf
        };
        q *= DQuat::from_rotation_x(deg(curve + correction));
        if lp.curve_v > 0.0 {
            let psi = deg(180.0 + rng.var(180.0));
            let tilt = deg(rng.var(lp.curve_v) / nf);
            q *= DQuat::from_axis_angle(DVec3::new(psi.cos(), psi.sin(), 0.0), tilt);
        }
        if st.level >= 2 && self.p.attraction_up != 0.0 {
            let z = q * DVec3::Z;
            let declination = z.z.clamp(-1.0, 1.0).acos();
            let axis = z.cross(DVec3::Z);
            if axis.length_squared() > 1e-12 {
                let k = self.p.attraction_up * declination * declination.sin() / nf;
                // Never swing past the vertical, up or down.
                let k = k.clamp(declination - std::f64::consts::PI, declination);
                q = DQuat::from_axis_angle(axis.normalize(), k) * q;
            }
        }
        if let Some((ox, oy)) = wind_phase {
            let z = s as f64 / nf;
            let rho = self.radius_at(st.level, st.radius, st.length, z).max(1e-6);
            let a0 = 4.0 * st.length * (1.0 - z) / rho;
            let a1 = self.wind.speed / 50.0 * a0;
            let a2 = self.wind.gust / 50.0 * a0 + a1 / 2.0;
            // The paper's phase rate, radius / length * time / 15, gives a believable sway
            // (a 13 m trunk of 0.2 m radius about 0.16 Hz, twigs a little slower) only with the
            // radius in millimetres and the length in metres; in metres alone nothing would
            // visibly move for hours. So the radius is read in millimetres here.
            let tb = 1000.0 * st.radius / st.length * self.wind.time / 15.0;
            let sway = |o: f64| (a1 * (o + tb).sin() + a2 * (0.7 * (o + tb)).sin()) / nf;
            q = q * DQuat::from_rotation_x(deg(sway(ox))) * DQuat::from_rotation_y(deg(sway(oy)));
        }
        q.normalize()
    }
}

/// The point of one turn of a helix of `radius` rising `rise` a turn at unit position `t` of the
/// turn, relative to the turn's start, and the frame of its tangent.
fn helix_point(radius: f64, rise: f64, t: f64) -> (DVec3, DQuat) {
    let a = TAU * t;
    let local = DVec3::new(radius * (a.cos() - 1.0), radius * a.sin(), t * rise);
    let tangent = DVec3::new(-TAU * radius * a.sin(), TAU * radius * a.cos(), rise);
    (
        local,
        DQuat::from_rotation_arc(DVec3::Z, tangent.normalize()),
    )
}

fn section(position: DVec3, orientation: DQuat, radius: f64, z: f64) -> CrossSection {
    CrossSection {
        position: position.as_vec3(),
        orientation: orientation.as_quat(),
        radius: radius.max(0.0) as f32,
        z: z as f32,
    }
}
