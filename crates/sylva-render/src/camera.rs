//! Cameras that frame a tree: named views (front, side, top, iso) or any orbit angle, fitted so
//! the whole tree shows. World space is the model's: metres, Z up.

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use glam::{Mat4, Vec3, Vec4};

/// A named viewing direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewKind {
    /// From the south (-Y), looking north, level.
    Front,
    /// From the east (+X), looking west, level.
    Side,
    /// From above, north up the picture.
    Top,
    /// From the south-west, 25 degrees up.
    Iso,
}

impl ViewKind {
    /// (azimuth, elevation) in degrees: azimuth 0 looks north from the south, 90 looks west
    /// from the east.
    pub fn angles(self) -> (f32, f32) {
        match self {
            ViewKind::Front => (0.0, 0.0),
            ViewKind::Side => (90.0, 0.0),
            ViewKind::Top => (0.0, 89.9),
            ViewKind::Iso => (-45.0, 25.0),
        }
    }
}

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: Vec3,
    /// Point looked at.
    pub target: Vec3,
    /// Vertical field of view, radians.
    pub fov_y: f32,
    /// Width / height of the picture.
    pub aspect: f32,
    /// Distance to the far clipping plane, metres; `None`: from the eye-target distance, for
    /// cameras framing one tree.
    pub far: Option<f32>,
    /// Distance to the near clipping plane where it may lie farther out than `far`'s
    /// 1:100,000 (a camera far outside what it sees, as the impostors' bake).
    pub near: Option<f32>,
}

impl Camera {
    /// The unit vector from the target towards the eye for an azimuth and elevation (degrees).
    pub fn direction(azimuth: f32, elevation: f32) -> Vec3 {
        let (a, e) = (azimuth.to_radians(), elevation.to_radians());
        Vec3::new(a.sin() * e.cos(), -a.cos() * e.cos(), e.sin())
    }

    /// Frames the box `lo..hi` seen from `azimuth`/`elevation` (degrees) so that all of it
    /// shows, with `margin` (0.05 = 5%) to spare.
    pub fn framing(
        lo: Vec3,
        hi: Vec3,
        azimuth: f32,
        elevation: f32,
        fov_y_deg: f32,
        aspect: f32,
        margin: f32,
    ) -> Self {
        let back = Self::direction(azimuth, elevation);
        let up_hint = if elevation.abs() > 80.0 {
            Vec3::Y
        } else {
            Vec3::Z
        };
        let right = up_hint.cross(back).normalize();
        let up = back.cross(right);
        let centre = (lo + hi) / 2.0;
        let fov_y = fov_y_deg.to_radians();
        let (tan_y, tan_x) = ((fov_y / 2.0).tan(), (fov_y / 2.0).tan() * aspect);
        // Smallest distance at which every corner of the box lies inside the frustum.
        let mut distance = 0.0f32;
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            ) - centre;
            let (x, y, z) = (corner.dot(right), corner.dot(up), corner.dot(back));
            distance = distance
                .max(x.abs() * (1.0 + margin) / tan_x + z)
                .max(y.abs() * (1.0 + margin) / tan_y + z);
        }
        let distance = distance.max(0.1);
        Self {
            eye: centre + back * distance,
            target: centre,
            fov_y,
            aspect,
            far: None,
            near: None,
        }
    }

    /// World-to-clip matrix (wgpu's depth range 0..1).
    pub fn view_proj(&self) -> Mat4 {
        let back = (self.eye - self.target).normalize();
        let up = if back.z.abs() > 0.98 {
            Vec3::Y
        } else {
            Vec3::Z
        };
        let view = look_at_mat4(self.eye, self.target, up);
        let distance = self.eye.distance(self.target);
        let (near, far) = match self.far {
            // A 32-bit float depth buffer keeps a 1:100,000 near:far ratio free of fighting.
            Some(far) => (
                self.near
                    .unwrap_or(0.0)
                    .max(far * 1e-5)
                    .max(0.02)
                    .min(far * 0.5),
                far,
            ),
            None => ((distance * 0.01).max(0.01), distance * 20.0 + 100.0),
        };
        let proj = directx::perspective(self.fov_y, self.aspect, near, far);
        proj * view
    }

    /// Pixel position (x right, y down, in a `width` x `height` picture) of a world point.
    pub fn project(&self, p: Vec3, width: u32, height: u32) -> Option<(f32, f32)> {
        let c = self.view_proj() * Vec4::new(p.x, p.y, p.z, 1.0);
        if c.w <= 0.0 {
            return None;
        }
        let ndc = c.truncate() / c.w;
        Some((
            (ndc.x * 0.5 + 0.5) * width as f32,
            (0.5 - ndc.y * 0.5) * height as f32,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framing_keeps_every_corner_in_view() {
        let (lo, hi) = (Vec3::new(-3.0, -2.0, 0.0), Vec3::new(4.0, 2.0, 15.0));
        for kind in [
            ViewKind::Front,
            ViewKind::Side,
            ViewKind::Top,
            ViewKind::Iso,
        ] {
            let (a, e) = kind.angles();
            let cam = Camera::framing(lo, hi, a, e, 30.0, 1.5, 0.05);
            for i in 0..8 {
                let p = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                let (x, y) = cam.project(p, 300, 200).unwrap();
                assert!(
                    (0.0..=300.0).contains(&x) && (0.0..=200.0).contains(&y),
                    "{kind:?} {p} -> {x},{y}"
                );
            }
        }
        // The front view of a tall box is limited by its height: it fills most of the picture.
        let cam = Camera::framing(lo, hi, 0.0, 0.0, 30.0, 1.0, 0.05);
        let (_, top) = cam.project(Vec3::new(0.0, 0.0, 15.0), 100, 100).unwrap();
        assert!(top < 10.0, "{top}");
    }
}
