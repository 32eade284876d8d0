//! What stands around a tree in a picture: the ground, and a 1.8 m person for scale (Linsen et
//! al. show a person beside the tree for the same reason).

use glam::Vec3;

/// Interleaved vertex as the GPU reads it: position, normal, shade.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Metres, Z up.
    pub position: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Luminance factor (a leaf's light class; 1 for everything else).
    pub shade: f32,
}

/// A small indexed mesh of [`Vertex`].
#[derive(Clone, Debug, Default)]
pub struct PropMesh {
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Triangles.
    pub indices: Vec<u32>,
}

impl PropMesh {
    fn quad(&mut self, corners: [Vec3; 4], normal: Vec3) {
        let base = self.vertices.len() as u32;
        for c in corners {
            self.vertices.push(Vertex {
                position: c.to_array(),
                normal: normal.to_array(),
                shade: 1.0,
            });
        }
        self.indices
            .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// An axis-aligned box from `lo` to `hi`, faces outwards.
    fn cuboid(&mut self, lo: Vec3, hi: Vec3) {
        let p = |x: bool, y: bool, z: bool| {
            Vec3::new(
                if x { hi.x } else { lo.x },
                if y { hi.y } else { lo.y },
                if z { hi.z } else { lo.z },
            )
        };
        let (f, t) = (false, true);
        self.quad([p(f, f, f), p(t, f, f), p(t, f, t), p(f, f, t)], -Vec3::Y);
        self.quad([p(t, t, f), p(f, t, f), p(f, t, t), p(t, t, t)], Vec3::Y);
        self.quad([p(t, f, f), p(t, t, f), p(t, t, t), p(t, f, t)], Vec3::X);
        self.quad([p(f, t, f), p(f, f, f), p(f, f, t), p(f, t, t)], -Vec3::X);
        self.quad([p(f, f, t), p(t, f, t), p(t, t, t), p(f, t, t)], Vec3::Z);
        self.quad([p(f, t, f), p(t, t, f), p(t, f, f), p(f, f, f)], -Vec3::Z);
    }
}

/// A square of ground centred under the tree, `half` metres from the centre to each edge.
pub fn ground(centre: Vec3, half: f32) -> PropMesh {
    let mut m = PropMesh::default();
    let c = Vec3::new(centre.x, centre.y, 0.0);
    m.quad(
        [
            c + Vec3::new(-half, -half, 0.0),
            c + Vec3::new(half, -half, 0.0),
            c + Vec3::new(half, half, 0.0),
            c + Vec3::new(-half, half, 0.0),
        ],
        Vec3::Z,
    );
    m
}

/// Height of the scale figure, metres.
pub const PERSON_HEIGHT: f32 = 1.8;

/// A blocky 1.8 m person standing at `feet`, facing a camera at `azimuth` degrees (0: facing
/// -Y, towards the front view).
pub fn person(feet: Vec3, azimuth: f32) -> PropMesh {
    let mut m = PropMesh::default();
    let at = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    // Legs, torso, arms, neck, head: proportions of an adult, 1.8 m to the top of the head.
    m.cuboid(at(-0.17, -0.09, 0.0), at(-0.03, 0.09, 0.86));
    m.cuboid(at(0.03, -0.09, 0.0), at(0.17, 0.09, 0.86));
    m.cuboid(at(-0.21, -0.11, 0.84), at(0.21, 0.11, 1.48));
    m.cuboid(at(-0.29, -0.06, 0.82), at(-0.21, 0.06, 1.46));
    m.cuboid(at(0.21, -0.06, 0.82), at(0.29, 0.06, 1.46));
    m.cuboid(at(-0.05, -0.05, 1.48), at(0.05, 0.05, 1.56));
    m.cuboid(at(-0.1, -0.11, 1.56), at(0.1, 0.11, PERSON_HEIGHT));
    let turn = glam::Quat::from_rotation_z(azimuth.to_radians());
    for v in &mut m.vertices {
        v.position = (feet + turn * Vec3::from(v.position)).to_array();
        v.normal = (turn * Vec3::from(v.normal)).to_array();
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn person_is_1_8_m_and_faces_outwards() {
        let p = person(Vec3::new(2.0, 0.0, 0.0), 30.0);
        let top = p
            .vertices
            .iter()
            .map(|v| v.position[2])
            .fold(f32::MIN, f32::max);
        assert!((top - PERSON_HEIGHT).abs() < 1e-6);
        for t in p.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(p.vertices[i as usize].position));
            let n = Vec3::from(p.vertices[t[0] as usize].normal);
            assert!(
                (b - a).cross(c - a).dot(n) > 0.0,
                "triangle winds against its normal"
            );
        }
    }
}
