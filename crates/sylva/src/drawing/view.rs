//! Where the drawing's eye is.

use glam::{Vec2, Vec3};

/// A projection of the tree onto the page. Plan, elevations and perspective are the views a
/// landscape drawing set uses; `Overlay` is Nagel's fuller-looking figure, the front and side
/// elevations plotted on top of each other at the same place.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum View {
    /// Looking north (+Y): X to the right, Z up.
    Front,
    /// Looking west (-X): Y to the right, Z up.
    Side,
    /// Plan: looking down, X to the right, Y up the page.
    Top,
    /// A camera south-east of the tree, 20° above its middle, 35° off the front.
    Perspective,
    /// Front and side on top of each other.
    Overlay,
}

impl View {
    /// All views, in the order a drawing sheet lists them.
    pub const ALL: [View; 5] = [
        View::Front,
        View::Side,
        View::Top,
        View::Perspective,
        View::Overlay,
    ];

    /// Lower-case name, as the command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
            View::Perspective => "perspective",
            View::Overlay => "overlay",
        }
    }

    /// The view named `name` (case-insensitive).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|v| v.name().eq_ignore_ascii_case(name))
    }
}

/// A set-up projection: maps model points to page points (y up) and a depth in 0..1 (0 nearest),
/// for depth cueing.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Projector {
    view: View,
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
    focal: f32,
    near: f32,
    far: f32,
}

impl Projector {
    /// A projector for a tree inside the box `lo..hi`.
    pub fn new(view: View, lo: Vec3, hi: Vec3) -> Self {
        let centre = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).length()).max(1e-6);
        let (az, el) = (35f32.to_radians(), 20f32.to_radians());
        // The camera looks north-west-ish at the crown's middle from 3 radii away.
        let forward = Vec3::new(-az.sin() * el.cos(), az.cos() * el.cos(), -el.sin());
        let distance = 3.0 * radius;
        let eye = centre - forward * distance;
        let right = forward.cross(Vec3::Z).normalize();
        let up = right.cross(forward);
        let (near, far) = match view {
            View::Perspective => (distance - radius, distance + radius),
            View::Front => (lo.y, hi.y),
            View::Side => (-hi.x, -lo.x),
            View::Top => (-hi.z, -lo.z),
            View::Overlay => (0.0, 1.0),
        };
        Self {
            view,
            eye,
            forward,
            right,
            up,
            focal: distance,
            near,
            far: far.max(near + 1e-6),
        }
    }

    /// Page positions of `p`: one for most views, two for the overlay.
    pub fn project(&self, p: Vec3) -> ([(Vec2, f32); 2], usize) {
        let depth = |d: f32| ((d - self.near) / (self.far - self.near)).clamp(0.0, 1.0);
        let none = (Vec2::ZERO, 0.0);
        match self.view {
            View::Front => ([(Vec2::new(p.x, p.z), depth(p.y)), none], 1),
            View::Side => ([(Vec2::new(p.y, p.z), depth(-p.x)), none], 1),
            View::Top => ([(Vec2::new(p.x, p.y), depth(-p.z)), none], 1),
            View::Perspective => {
                let v = p - self.eye;
                let z = v.dot(self.forward).max(1e-3 * self.focal);
                let s = self.focal / z;
                (
                    [
                        (
                            Vec2::new(v.dot(self.right) * s, v.dot(self.up) * s),
                            depth(z),
                        ),
                        none,
                    ],
                    1,
                )
            }
            View::Overlay => ([(Vec2::new(p.x, p.z), 0.0), (Vec2::new(p.y, p.z), 0.0)], 2),
        }
    }

    /// How much a width in metres at depth `depth` shrinks on the page (perspective only).
    pub fn width_scale(&self, depth: f32) -> f32 {
        match self.view {
            View::Perspective => {
                let z = self.near + depth * (self.far - self.near);
                self.focal / z.max(1e-6)
            }
            _ => 1.0,
        }
    }
}
