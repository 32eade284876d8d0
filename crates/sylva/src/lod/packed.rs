//! The records a tree is stored in for range rendering, and the arithmetic that packs and
//! unpacks them.
//!
//! A full mesh spends 32 bytes on every vertex and 12 on every triangle; a Black Tupelo holds
//! 480,000 vertices. The stored form keeps only what the meshes are made from, quantised to what
//! a picture can show, and lets the GPU rebuild the triangles every frame:
//!
//! - a stem segment is two rings (centre, radius, frame): 24 bytes for what the mesher turns
//!   into `2 (n + 1)` vertices and `2 n` triangles;
//! - a leaf is a card (base, frame, size, light): 12 bytes for what the mesher turns into a
//!   template's 5 to 20 vertices.
//!
//! Positions are 16-bit fractions of the tree's box (0.5 mm steps on a 30 m tree); radii are
//! 16-bit fractions of the thickest; frames are unit quaternions packed as their three smallest
//! components (10 bits each, about 0.1 degree). [`Quantiser`] holds the scales; the CPU's
//! unpacking here and the shader's in `sylva-render` must agree, and a test pins both to the
//! values below.

use glam::{Quat, Vec3};

/// One end of a stem segment: centre and radius as 16-bit fractions of the tree's box and
/// thickest radius (x, y, z, radius), and the ring's frame (local z along the stem) packed by
/// [`pack_frame`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Ring {
    /// Centre x, y, z and radius, as fractions of 65535.
    pub xyzr: [u16; 4],
    /// Frame, [`pack_frame`].
    pub frame: u32,
}

/// A stem segment: the rings at its two ends. The GPU draws it as `sides` quads between them
/// (a cone where the far ring has no radius), or from afar as a line between their centres.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Segment {
    /// The ring nearer the stem's base.
    pub a: Ring,
    /// The ring nearer its tip.
    pub b: Ring,
}

/// A leaf: its base as 16-bit fractions of the tree's box, its size and light packed in the
/// fourth half-word (bits 0-5 length, 6-11 width, as fractions of 63 of the tree's longest and
/// widest; 12-15 the luminance class, 1-10), and its blade frame packed by [`pack_frame`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Leaf {
    /// Base x, y, z, and the packed size and light.
    pub xyzs: [u16; 4],
    /// Blade frame: z along the blade, y its normal, [`pack_frame`].
    pub frame: u32,
}

/// The scales of one tree's records.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quantiser {
    /// Lowest corner of the box holding every ring centre and leaf base, metres.
    pub lo: Vec3,
    /// Size of that box (at least 1 mm along each axis), metres.
    pub size: Vec3,
    /// The thickest radius, metres.
    pub radius: f32,
    /// The longest leaf, metres.
    pub leaf_length: f32,
    /// The widest leaf, metres.
    pub leaf_width: f32,
}

const FULL: f32 = 65535.0;
/// Steps of a leaf's length and width.
const LEAF_STEPS: f32 = 63.0;

fn fraction(v: f32, scale: f32) -> u16 {
    (v / scale * FULL).round().clamp(0.0, FULL) as u16
}

impl Quantiser {
    /// Scales that hold `centres` (ring centres and leaf bases), radii up to `radius` and
    /// leaves up to `leaf_length` by `leaf_width`.
    pub fn around(
        centres: impl Iterator<Item = Vec3>,
        radius: f32,
        leaf_length: f32,
        leaf_width: f32,
    ) -> Self {
        let (lo, hi) = centres.fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(l, h), p| (l.min(p), h.max(p)),
        );
        let (lo, hi) = if lo.x <= hi.x {
            (lo, hi)
        } else {
            (Vec3::ZERO, Vec3::ZERO)
        };
        Self {
            lo,
            size: (hi - lo).max(Vec3::splat(1e-3)),
            radius: radius.max(1e-6),
            leaf_length: leaf_length.max(1e-6),
            leaf_width: leaf_width.max(1e-6),
        }
    }

    /// A point of the box as three fractions.
    pub fn position(&self, p: Vec3) -> [u16; 3] {
        let f = (p - self.lo) / self.size;
        [f.x, f.y, f.z].map(|v| (v * FULL).round().clamp(0.0, FULL) as u16)
    }

    /// The point three fractions stand for.
    pub fn unpack_position(&self, q: [u16; 3]) -> Vec3 {
        self.lo + Vec3::new(q[0] as f32, q[1] as f32, q[2] as f32) / FULL * self.size
    }

    /// A ring of a stem.
    pub fn ring(&self, centre: Vec3, radius: f32, frame: Quat) -> Ring {
        let [x, y, z] = self.position(centre);
        Ring {
            xyzr: [x, y, z, fraction(radius, self.radius)],
            frame: pack_frame(frame),
        }
    }

    /// A ring's centre, radius and frame.
    pub fn unpack_ring(&self, r: &Ring) -> (Vec3, f32, Quat) {
        let [x, y, z, q] = r.xyzr;
        (
            self.unpack_position([x, y, z]),
            q as f32 / FULL * self.radius,
            unpack_frame(r.frame),
        )
    }

    /// A leaf with its base, frame, size and light class (1-10).
    pub fn leaf(&self, base: Vec3, frame: Quat, length: f32, width: f32, class: u32) -> Leaf {
        let steps =
            |v: f32, max: f32| ((v / max * LEAF_STEPS).round().clamp(1.0, LEAF_STEPS)) as u16;
        let [x, y, z] = self.position(base);
        let size = steps(length, self.leaf_length)
            | steps(width, self.leaf_width) << 6
            | (class.clamp(1, 10) as u16) << 12;
        Leaf {
            xyzs: [x, y, z, size],
            frame: pack_frame(frame),
        }
    }

    /// A leaf's base, frame, length, width and light class.
    pub fn unpack_leaf(&self, l: &Leaf) -> (Vec3, Quat, f32, f32, u32) {
        let [x, y, z, s] = l.xyzs;
        (
            self.unpack_position([x, y, z]),
            unpack_frame(l.frame),
            (s & 63) as f32 / LEAF_STEPS * self.leaf_length,
            (s >> 6 & 63) as f32 / LEAF_STEPS * self.leaf_width,
            (s >> 12) as u32,
        )
    }

    /// The box every vertex of the tree lies in: the centres' box grown by the thickest
    /// radius and the longest leaf.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let grow = Vec3::splat(self.radius + self.leaf_length);
        (self.lo - grow, self.lo + self.size + grow)
    }
}

/// Steps of a packed frame's components: an even number, so that 0 is one of them.
const STEPS: f32 = 1022.0;

/// Packs a unit quaternion into 32 bits: the index of its largest component (2 bits), then the
/// other three in order, each 10 bits (0..=1022) over -1/sqrt(2)..1/sqrt(2) (the largest is recovered from
/// unit length, its sign made positive: q and -q are the same rotation).
pub fn pack_frame(q: Quat) -> u32 {
    let c = q.normalize().to_array();
    let k = (0..4)
        .max_by(|&a, &b| c[a].abs().total_cmp(&c[b].abs()))
        .unwrap_or(3);
    let sign = if c[k] < 0.0 { -1.0 } else { 1.0 };
    let mut bits = (k as u32) << 30;
    let mut shift = 20;
    for (i, &v) in c.iter().enumerate() {
        if i == k {
            continue;
        }
        let u = ((v * sign * std::f32::consts::SQRT_2 + 1.0) * 0.5 * STEPS)
            .round()
            .clamp(0.0, STEPS) as u32;
        bits |= u << shift;
        shift -= 10;
    }
    bits
}

/// The quaternion [`pack_frame`] packed.
pub fn unpack_frame(bits: u32) -> Quat {
    let k = (bits >> 30) as usize;
    let small = [20, 10, 0]
        .map(|s| ((bits >> s & 1023) as f32 / STEPS * 2.0 - 1.0) / std::f32::consts::SQRT_2);
    let largest = (1.0 - small.iter().map(|v| v * v).sum::<f32>())
        .max(0.0)
        .sqrt();
    let mut c = [0.0f32; 4];
    let mut next = small.iter();
    for (i, v) in c.iter_mut().enumerate() {
        *v = if i == k {
            largest
        } else {
            *next.next().unwrap_or(&0.0)
        };
    }
    Quat::from_array(c).normalize()
}

/// The shade (luminance factor) of a light class, as the mesher draws it.
pub fn class_shade(class: u32) -> f32 {
    0.3 + 0.7 * class.clamp(1, 10) as f32 / 10.0
}

/// The light class (1-10) of a leaf receiving `light`.
pub fn light_class(light: f32) -> u32 {
    (light.clamp(0.0, 1.0) * 10.0).ceil().max(1.0) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_within_a_third_of_a_degree() {
        let mut worst = 0.0f32;
        for i in 0..2000 {
            let t = i as f32 * 0.7391;
            let axis = Vec3::new(t.sin(), (t * 1.7).cos(), (t * 0.31).sin() + 0.2).normalize();
            let q = Quat::from_axis_angle(axis, t * 2.3 % std::f32::consts::TAU);
            let back = unpack_frame(pack_frame(q));
            worst = worst.max(q.angle_between(back).to_degrees());
        }
        assert!(worst < 0.3, "worst {worst} degrees");
        // Exact for the identity and quarter turns, whatever the sign.
        for q in [
            Quat::IDENTITY,
            -Quat::IDENTITY,
            Quat::from_rotation_z(1.5707964),
        ] {
            assert!(q.angle_between(unpack_frame(pack_frame(q))) < 2e-3);
        }
    }

    #[test]
    fn positions_radii_and_leaves_round_trip_to_their_steps() {
        let q = Quantiser::around(
            [Vec3::new(-10.0, -5.0, 0.0), Vec3::new(10.0, 5.0, 30.0)].into_iter(),
            0.6,
            0.3,
            0.15,
        );
        let p = Vec3::new(1.234, -2.345, 17.89);
        let r = q.ring(p, 0.123, Quat::IDENTITY);
        let (back, radius, _) = q.unpack_ring(&r);
        // Half a step of a 30 m box in 65535 is 0.23 mm.
        assert!((back - p).abs().max_element() < 2.3e-4, "{back}");
        assert!((radius - 0.123).abs() < 0.6 / 65535.0);
        let leaf = q.leaf(p, Quat::IDENTITY, 0.3, 0.1, 7);
        let (_, _, length, width, class) = q.unpack_leaf(&leaf);
        assert_eq!(length, 0.3);
        assert!((width - 0.1).abs() <= 0.15 / 126.0 + 1e-6, "{width}");
        assert_eq!(class, 7);
        assert_eq!(class_shade(light_class(1.0)), 1.0);
        assert_eq!(class_shade(light_class(0.25)), crate::mesh::luminance(0.25));
        assert_eq!(std::mem::size_of::<Segment>(), 24);
        assert_eq!(std::mem::size_of::<Leaf>(), 12);
    }
}
