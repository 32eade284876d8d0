//! The closed-form pieces of the Weber–Penn model (spec sections 2, 8 and 10): ShapeRatio, the
//! taper profile, flare, lobes and the pruning envelope. Pure functions, tested at known values.

use std::f64::consts::PI;

/// The pruning envelope's shape, used by ShapeRatio index 8.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Envelope {
    /// `PruneWidthPeak`: where the widest point sits, 0 (bottom) .. 1 (top).
    pub peak: f64,
    /// `PrunePowerLow`: curvature below the peak.
    pub power_low: f64,
    /// `PrunePowerHigh`: curvature above the peak.
    pub power_high: f64,
}

/// ShapeRatio(k, r): the relative length of a first-level branch at relative height `r`
/// (r = 1 at the crown base, 0 at the top), for shape `k` (0..8).
///
/// Index 8 uses the envelope; its lower half is written `((1 - r)/W)^PL` so that the two halves
/// meet at the peak (the paper's `(1 - W)` there jumps unless W = 0.5).
pub fn shape_ratio(shape: u32, r: f64, envelope: &Envelope) -> f64 {
    match shape {
        0 => 0.2 + 0.8 * r,
        1 => 0.2 + 0.8 * (PI * r).sin(),
        2 => 0.2 + 0.8 * (PI * r / 2.0).sin(),
        3 => 1.0,
        4 => 0.5 + 0.5 * r,
        5 => {
            if r <= 0.7 {
                r / 0.7
            } else {
                (1.0 - r) / 0.3
            }
        }
        6 => 1.0 - 0.8 * r,
        7 => {
            if r <= 0.7 {
                0.5 + 0.5 * r / 0.7
            } else {
                0.5 + 0.5 * (1.0 - r) / 0.3
            }
        }
        _ => {
            if !(0.0..=1.0).contains(&r) {
                return 0.0;
            }
            let w = envelope.peak;
            if r < 1.0 - w {
                (r / (1.0 - w)).powf(envelope.power_high)
            } else if w > 0.0 {
                ((1.0 - r) / w).powf(envelope.power_low)
            } else {
                1.0
            }
        }
    }
}

/// Radius at unit position `z` (0 base .. 1 tip) of a stem of length `length` and base radius
/// `radius` with taper `taper` (0 cylinder, 1 cone, 2 spherical end, 2..3 periodic beads).
pub fn taper_radius(radius: f64, length: f64, taper: f64, z: f64) -> f64 {
    let unit_taper = if taper < 1.0 {
        taper
    } else if taper < 2.0 {
        2.0 - taper
    } else {
        0.0
    };
    let tapered = radius * (1.0 - unit_taper * z);
    if taper < 1.0 {
        return tapered;
    }
    let z2 = (1.0 - z) * length;
    let depth = if taper < 2.0 || z2 < tapered {
        1.0
    } else {
        taper - 2.0
    };
    let z3 = if taper < 2.0 {
        z2
    } else {
        // Distance from the nearest bead joint: beads are spheres of diameter 2 * tapered.
        (z2 - 2.0 * tapered * (z2 / (2.0 * tapered) + 0.5).floor()).abs()
    };
    if taper < 2.0 && z3 >= tapered {
        return tapered;
    }
    let under = (tapered * tapered - (z3 - tapered) * (z3 - tapered)).max(0.0);
    (1.0 - depth) * tapered + depth * under.sqrt()
}

/// Flare multiplier at unit position `z` of the trunk: 1 above the lowest eighth, up to
/// `1 + flare` at the ground.
pub fn flare_factor(flare: f64, z: f64) -> f64 {
    let y = (1.0 - 8.0 * z).max(0.0);
    flare * (100f64.powf(y) - 1.0) / 100.0 + 1.0
}

/// Lobe multiplier at angle `angle` (radians from the stem's x axis) for `lobes` lobes.
pub fn lobe_factor(lobes: u32, depth: f64, angle: f64) -> f64 {
    1.0 + depth * (lobes as f64 * angle).sin()
}

/// Is the point (horizontal distance `rho` from the trunk axis, height `z`) inside the pruning
/// envelope of a tree of scale `scale`?
pub fn inside_envelope(
    rho: f64,
    z: f64,
    scale: f64,
    base_size: f64,
    width: f64,
    envelope: &Envelope,
) -> bool {
    let ratio = (scale - z) / (scale * (1.0 - base_size));
    rho / scale < width * shape_ratio(8, ratio, envelope)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ENV: Envelope = Envelope {
        peak: 0.5,
        power_low: 0.5,
        power_high: 0.5,
    };

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn shape_ratio_table() {
        // (shape, r, expected), values worked out by hand from the table in the spec.
        let cases = [
            (0, 0.0, 0.2),
            (0, 0.5, 0.6),
            (0, 1.0, 1.0),
            (1, 0.5, 1.0),
            (1, 0.0, 0.2),
            (2, 1.0, 1.0),
            (2, 1.0 / 3.0, 0.6),
            (3, 0.3, 1.0),
            (4, 0.5, 0.75),
            (5, 0.35, 0.5),
            (5, 0.7, 1.0),
            (5, 0.85, 0.5),
            (6, 0.5, 0.6),
            (7, 0.0, 0.5),
            (7, 0.7, 1.0),
            (7, 1.0, 0.5),
            (8, 0.5, 1.0),
            (8, 0.125, 0.5),
            (8, 1.5, 0.0),
            (8, -0.1, 0.0),
        ];
        for (k, r, want) in cases {
            let got = shape_ratio(k, r, &ENV);
            assert!(close(got, want), "SR({k}, {r}) = {got}, want {want}");
        }
    }

    #[test]
    fn envelope_is_continuous_at_its_peak() {
        let env = Envelope {
            peak: 0.6,
            power_low: 0.001,
            power_high: 0.5,
        };
        let below = shape_ratio(8, 0.4 - 1e-9, &env);
        let above = shape_ratio(8, 0.4 + 1e-9, &env);
        assert!((below - above).abs() < 1e-3, "{below} vs {above}");
    }

    #[test]
    fn taper_profiles() {
        // Cylinder and cone.
        assert!(close(taper_radius(1.0, 10.0, 0.0, 0.7), 1.0));
        assert!(close(taper_radius(1.0, 10.0, 1.0, 0.5), 0.5));
        assert!(close(taper_radius(1.0, 10.0, 1.0, 1.0), 0.0));
        assert!(close(taper_radius(2.0, 10.0, 0.5, 1.0), 1.0));
        // Spherical end (taper 2): a cylinder ending in a hemisphere of the stem's radius.
        let r = 1.0;
        let len = 10.0;
        assert!(close(taper_radius(r, len, 2.0, 0.5), 1.0));
        assert!(close(taper_radius(r, len, 2.0, 1.0), 0.0));
        // 0.5 m below the tip of a 1 m radius: sqrt(1 - 0.5^2).
        assert!(close(
            taper_radius(r, len, 2.0, 0.95),
            (1.0f64 - 0.25).sqrt()
        ));
        // Periodic beads (taper 3): radius 0 at each joint (every 2 r) and r midway.
        assert!(taper_radius(r, len, 3.0, 0.8).abs() < 1e-6); // z2 = 2
        assert!(close(taper_radius(r, len, 3.0, 0.9), 1.0)); // z2 = 1: bead centre
        // Taper 2.5: beads only half deep, never below half the radius.
        let shallow = taper_radius(r, len, 2.5, 0.8);
        assert!((shallow - 0.5).abs() < 1e-6, "{shallow}");
    }

    #[test]
    fn flare_and_lobes() {
        assert!(close(flare_factor(0.6, 0.0), 1.0 + 0.6 * 99.0 / 100.0));
        assert!(close(flare_factor(0.6, 0.125), 1.0));
        assert!(close(flare_factor(0.6, 0.5), 1.0));
        // Halfway through the flare zone: 100^0.5 = 10.
        assert!(close(flare_factor(1.0, 0.0625), 1.0 + 9.0 / 100.0));
        let quarter = std::f64::consts::FRAC_PI_2 / 5.0;
        assert!(close(lobe_factor(5, 0.07, quarter), 1.07));
        assert!(close(lobe_factor(5, 0.07, 0.0), 1.0));
        assert!(close(lobe_factor(0, 0.5, 1.0), 1.0));
    }

    #[test]
    fn envelope_inside_test() {
        // Scale 10, BaseSize 0.2: envelope from z = 2 to 10, widest (0.5 * 10 = 5 m) at z = 6.
        let inside = |rho, z| inside_envelope(rho, z, 10.0, 0.2, 0.5, &ENV);
        assert!(inside(4.9, 6.0));
        assert!(!inside(5.1, 6.0));
        assert!(!inside(0.1, 10.5));
        assert!(!inside(0.1, 1.0));
        assert!(inside(0.1, 9.9));
    }
}
