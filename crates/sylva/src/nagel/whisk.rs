//! Whisk and stick trees (Nagel 1986, chapter IV): a drawn canopy profile, or a drawn set of
//! branches, rotated about the trunk into evenly spaced copies ("ribs").
//!
//! Nagel rotated each profile point by 360°/N per rib (X = R cos I, Z = R sin I, the height
//! unchanged) and offered densities 1–5, that is 6, 9, 12, 15 or 18 ribs. His conclusions add
//! latitudinal rings around the canopy (figure 25) and spokes from the trunk out to the canopy's
//! edge (figure 26), suggested for conifers; both are here.

use super::profile::Profile;
use crate::error::ParamsError;
use crate::skeleton::{Skeleton, StemId};
use glam::Vec3;
use std::f64::consts::TAU;

/// How a profile becomes a whisk tree.
#[derive(Clone, Debug, PartialEq)]
pub struct WhiskParams {
    /// Copies of the profile around the trunk, 360/N degrees apart.
    pub ribs: u32,
    /// Horizontal rings around the canopy, evenly spaced along the profile.
    pub rings: u32,
    /// Spokes per rib from the trunk's axis out to the rib, evenly spaced along the profile.
    pub spokes: u32,
    /// Radius of the wires (ribs, rings, spokes), metres; `None`: the tree's height / 400.
    pub wire_radius: Option<f64>,
    /// Trunk radius, metres; `None`: the tree's height / 60.
    pub trunk_radius: Option<f64>,
}

impl Default for WhiskParams {
    fn default() -> Self {
        Self {
            ribs: 8,
            rings: 0,
            spokes: 0,
            wire_radius: None,
            trunk_radius: None,
        }
    }
}

/// Ribs for Nagel's density setting 1–5 (his program's 6, 9, 12, 15, 18).
pub fn density_ribs(density: u32) -> Option<u32> {
    (1..=5).contains(&density).then_some(3 * density + 3)
}

fn check_counts(p: &WhiskParams) -> Result<(), ParamsError> {
    if !(1..=360).contains(&p.ribs) {
        return Err(ParamsError::out_of_range("ribs", p.ribs as f64, "1..360"));
    }
    if p.rings > 500 {
        return Err(ParamsError::out_of_range("rings", p.rings as f64, "0..500"));
    }
    if p.spokes > 500 {
        return Err(ParamsError::out_of_range(
            "spokes",
            p.spokes as f64,
            "0..500 per rib",
        ));
    }
    for (name, v) in [
        ("wire-radius", p.wire_radius),
        ("trunk-radius", p.trunk_radius),
    ] {
        if let Some(v) = v
            && !(v.is_finite() && (0.0..=10.0).contains(&v))
        {
            return Err(ParamsError::out_of_range(name, v, "0..10 metres"));
        }
    }
    Ok(())
}

/// A point of the profile plane (radius, height) turned `angle` radians about the trunk.
fn turn([r, h]: [f64; 2], angle: f64) -> Vec3 {
    Vec3::new((r * angle.cos()) as f32, (r * angle.sin()) as f32, h as f32)
}

/// Appends a wire of one radius through `points`.
fn push_polyline(
    skeleton: &mut Skeleton,
    points: &[Vec3],
    level: u8,
    parent: Option<StemId>,
    radius: f32,
) -> StemId {
    skeleton.push_polyline(points, &vec![radius; points.len()], level, parent)
}

/// The point at `t` (0..1) of the profile's length.
fn along_profile(points: &[[f64; 2]], t: f64) -> [f64; 2] {
    let lengths: Vec<f64> = points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .collect();
    let mut left = t * lengths.iter().sum::<f64>();
    for (w, l) in points.windows(2).zip(&lengths) {
        if left <= *l && *l > 0.0 {
            let s = left / l;
            return [
                w[0][0] + (w[1][0] - w[0][0]) * s,
                w[0][1] + (w[1][1] - w[0][1]) * s,
            ];
        }
        left -= l;
    }
    points[points.len() - 1]
}

fn top(points: &[[f64; 2]]) -> f64 {
    points.iter().map(|p| p[1]).fold(0.0, f64::max)
}

/// The trunk from the ground to `height`, when it has any length.
fn push_trunk(skeleton: &mut Skeleton, height: f64, radius: f64) -> Option<StemId> {
    (height > 0.0).then(|| {
        push_polyline(
            skeleton,
            &[Vec3::ZERO, Vec3::new(0.0, 0.0, height as f32)],
            0,
            None,
            radius as f32,
        )
    })
}

/// A whisk tree: trunk from the ground to the profile's first point, `ribs` turned copies of the
/// profile (stems of level 1, rib j at 360·j/N degrees from +X), then the rings and the spokes
/// (level 2).
pub fn whisk_tree(profile: &Profile, p: &WhiskParams) -> Result<Skeleton, ParamsError> {
    check_counts(p)?;
    let points = &profile.points;
    if points.len() < 2 {
        return Err(ParamsError::Combination(
            "a whisk profile needs at least 2 points".into(),
        ));
    }
    let height = top(points);
    let wire = p.wire_radius.unwrap_or(height / 400.0) as f32;
    let mut skeleton = Skeleton::default();
    let trunk = push_trunk(
        &mut skeleton,
        points[0][1],
        p.trunk_radius.unwrap_or(height / 60.0),
    );
    let n = p.ribs as usize;
    let mut rib: Vec<Vec3> = Vec::with_capacity(points.len());
    for j in 0..n {
        let angle = TAU * j as f64 / n as f64;
        rib.clear();
        rib.extend(points.iter().map(|&q| turn(q, angle)));
        push_polyline(&mut skeleton, &rib, 1, trunk, wire);
    }
    // Rings pass through every rib: their vertex count is a multiple of the ribs'.
    let around = n * 32usize.div_ceil(n);
    for k in 1..=p.rings {
        let q = along_profile(points, k as f64 / (p.rings + 1) as f64);
        let mut ring: Vec<Vec3> = (0..around)
            .map(|m| turn(q, TAU * m as f64 / around as f64))
            .collect();
        ring.push(ring[0]);
        push_polyline(&mut skeleton, &ring, 2, trunk, wire);
    }
    for j in 0..n {
        let angle = TAU * j as f64 / n as f64;
        for s in 1..=p.spokes {
            let q = along_profile(points, s as f64 / (p.spokes + 1) as f64);
            let spoke = [turn([0.0, q[1]], 0.0), turn(q, angle)];
            push_polyline(&mut skeleton, &spoke, 2, trunk, wire);
        }
    }
    Ok(skeleton)
}

/// A stick tree: every drawn branch (points in the profile plane, from its base to its tip)
/// turned into `ribs` copies about a trunk that reaches the highest branch base.
pub fn stick_tree(branches: &[Vec<[f64; 2]>], p: &WhiskParams) -> Result<Skeleton, ParamsError> {
    check_counts(p)?;
    if branches.is_empty() || branches.iter().any(|b| b.len() < 2) {
        return Err(ParamsError::Combination(
            "a stick tree needs branches of at least 2 points each".into(),
        ));
    }
    let height = branches.iter().map(|b| top(b)).fold(0.0, f64::max);
    let wire = p.wire_radius.unwrap_or(height / 400.0) as f32;
    let base = branches.iter().map(|b| b[0][1]).fold(0.0, f64::max);
    let mut skeleton = Skeleton::default();
    let trunk = push_trunk(&mut skeleton, base, p.trunk_radius.unwrap_or(height / 60.0));
    let n = p.ribs as usize;
    for j in 0..n {
        let angle = TAU * j as f64 / n as f64;
        for branch in branches {
            let mut points: Vec<Vec3> = branch.iter().map(|&q| turn(q, angle)).collect();
            points.dedup();
            if points.len() >= 2 {
                push_polyline(&mut skeleton, &points, 1, trunk, wire);
            }
        }
    }
    Ok(skeleton)
}
