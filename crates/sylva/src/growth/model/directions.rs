//! Where a new shoot points and how far it may reach: leaving its axis at an angle, sagging
//! with its height in the crown, and stopped where it would leave the crown's space.

use super::colonise::Space;
use super::*;

/// The direction of a shoot leaving an axis along `axis`: turned `azimuth` degrees about it
/// and tilted `tilt` radians off it, never steeper than 20 degrees below the horizontal.
pub(super) fn leaning_out(axis: Vec3, azimuth: f32, tilt: f32) -> Vec3 {
    let side = Quat::from_axis_angle(axis, azimuth.to_radians())
        * axis.any_orthogonal_vector().normalize();
    let direction = (Quat::from_axis_angle(axis.cross(side).normalize(), tilt) * axis).normalize();
    if direction.z < -0.34 {
        Vec3::new(direction.x, direction.y, -0.34).normalize()
    } else {
        direction
    }
}

/// How far a shoot starting at height z sags, radians: `sag` at the crown base, none at
/// the top.
pub(super) fn sag_at(sag: f32, z: f32, base: f32, top: f32) -> f32 {
    let rel = ((z - base) / (top - base).max(0.1)).clamp(0.0, 1.0);
    sag * (1.0 - rel) * (1.0 - rel)
}

/// `d` turned `sag` radians further down in its vertical plane, never steeper than 40 degrees
/// below the horizontal.
pub(super) fn sag_down(d: Vec3, sag: f32) -> Vec3 {
    if sag <= 0.0 {
        return d;
    }
    let horizontal = d.truncate().normalize_or(glam::Vec2::X);
    let elevation = (d.z.clamp(-1.0, 1.0).asin() - sag).max(-0.7);
    (horizontal * elevation.cos()).extend(elevation.sin())
}

/// The longest length up to `length` at which a shoot from `start` along `direction` ends
/// inside `space` (0 if it starts outside).
pub(super) fn within(space: &Space, start: Vec3, direction: Vec3, length: f32) -> f32 {
    let tip = |l: f32| start + direction * l;
    if space.contains(tip(length)) {
        return length;
    }
    if !space.contains(tip(0.0)) {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, length);
    for _ in 0..16 {
        let mid = 0.5 * (lo + hi);
        if space.contains(tip(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}
