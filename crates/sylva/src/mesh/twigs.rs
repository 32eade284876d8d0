//! A bare crown's short twigs as copies of one twig mesh (`MeshOptions::twig_copies`).
//!
//! A grown crown carries tens of thousands of short twigs (`growth/model/short_shoots.rs`), each
//! a straight tapered stem a few centimetres long. Meshed one by one, each costs sixteen
//! vertices and twelve triangles, and a bare 30-year plane's model grew from 3 MB of frame to
//! over 20 MB. Every twig is the same shape at another size and turn, so a model file can hold
//! one twig and a placement per copy instead (glTF's `EXT_mesh_gpu_instancing`: 40 bytes a
//! copy), and the GPU draws them all at once.

use super::{Mesh, MeshOptions, stems};
use crate::skeleton::{CrossSection, Skeleton, Stem};
use glam::{Mat3, Mat4, Quat, Vec3};

/// One twig and where each of its copies stands.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TwigCopies {
    /// One twig in its own frame: its base at the origin, its axis along +Z.
    pub twig: Mesh,
    /// Each copy's placement.
    pub copies: Vec<TwigCopy>,
}

/// Where one copy of the twig stands: scaled, then turned, then moved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwigCopy {
    /// The twig's base, metres, Z up.
    pub position: [f32; 3],
    /// Its turn, a unit quaternion (x, y, z, w).
    pub rotation: [f32; 4],
    /// Its scale along the twig's own x, y (across) and z (along).
    pub scale: [f32; 3],
}

impl TwigCopy {
    /// The copy's transform.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(
            Vec3::from(self.scale),
            Quat::from_array(self.rotation),
            Vec3::from(self.position),
        )
    }
}

impl TwigCopies {
    /// Whether there is nothing to draw.
    pub fn is_empty(&self) -> bool {
        self.copies.is_empty() || self.twig.indices.is_empty()
    }

    /// Vertices drawn: the twig's, once per copy.
    pub fn vertex_count(&self) -> usize {
        self.twig.vertex_count() * self.copies.len()
    }

    /// Triangles drawn: the twig's, once per copy.
    pub fn triangle_count(&self) -> usize {
        self.twig.triangle_count() * self.copies.len()
    }

    /// Appends every copy, placed, to `bark`: the twigs as the bark would hold them, for what
    /// draws a mesh without instancing (pictures, OBJ).
    pub fn place_into(&self, bark: &mut Mesh) {
        if !self.is_empty() {
            place_copies(&self.twig, self.copies.iter().map(TwigCopy::matrix), bark);
        }
    }
}

/// Appends `part` to `out` once for each of `copies`, its vertices moved by the copy's matrix
/// and its normals by the inverse transpose (a copy's scale need not be uniform). Where either
/// side carries shades, the vertices of the other count as fully lit.
pub fn place_copies(part: &Mesh, copies: impl ExactSizeIterator<Item = Mat4>, out: &mut Mesh) {
    let shaded = !out.shades.is_empty() || !part.shades.is_empty();
    if shaded {
        out.shades.resize(out.positions.len(), 1.0);
    }
    out.reserve(
        part.vertex_count() * copies.len(),
        part.indices.len() * copies.len(),
    );
    for m in copies {
        let normals = Mat3::from_mat4(m).inverse().transpose();
        let base = out.positions.len() as u32;
        for (k, (p, n)) in part.positions.iter().zip(&part.normals).enumerate() {
            let p = m.transform_point3(Vec3::from(*p));
            let n = (normals * Vec3::from(*n)).normalize_or(Vec3::Z);
            out.push(p, n, part.uvs.get(k).copied().unwrap_or_default());
        }
        out.indices.extend(part.indices.iter().map(|&i| i + base));
        if shaded {
            match part.shades.len() == part.positions.len() {
                true => out.shades.extend_from_slice(&part.shades),
                false => out.shades.resize(out.positions.len(), 1.0),
            }
        }
    }
}

/// The short twigs of a bare `skeleton` (those [`Skeleton::meshed_stems`] would mesh beyond the
/// frame) as copies of one. The twig is the first one's mesh, in its own frame, so its bark
/// shades are a real twig's; each copy is that twig scaled across by its base radius and along
/// by its length. Every tip is drawn at the same share of its base radius (0.35, from
/// `short_shoots.rs`), where the thinnest twigs' tips are held at 0.8 mm when meshed one by
/// one: those tips come out a fraction of a millimetre narrower.
pub(super) fn twig_copies(skeleton: &Skeleton, options: &MeshOptions) -> TwigCopies {
    let frame = skeleton.frame_stems().len();
    if !skeleton.leaves.is_empty() || frame == skeleton.stems.len() {
        return TwigCopies::default();
    }
    let twigs = &skeleton.stems[frame..];
    let ends = |stem: &Stem| -> Option<(CrossSection, CrossSection)> {
        let s = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        (s.len() >= 2).then(|| (s[0], s[s.len() - 1]))
    };
    // The first twig whose tip is drawn at its share of the base (not held at the least
    // radius), or else the first.
    let drawn = |t: &Stem| Some((t.clone(), ends(t)?));
    let Some((first, (base, tip))) = (twigs.iter())
        .filter_map(drawn)
        .find(|(_, (b, t))| t.radius > 0.0009 && t.radius < b.radius * 0.5)
        .or_else(|| twigs.iter().find_map(drawn))
    else {
        return TwigCopies::default();
    };
    let length = base.position.distance(tip.position).max(1e-6);
    let radius = base.radius.max(1e-6);
    // The first twig, moved to the origin and turned to stand along +Z.
    let own = Skeleton {
        stems: vec![Stem {
            parent: None,
            offset: 0.0,
            sections: 0..2,
            ..first
        }],
        sections: vec![
            CrossSection {
                position: Vec3::ZERO,
                orientation: Quat::IDENTITY,
                ..base
            },
            CrossSection {
                position: Vec3::Z * length,
                orientation: Quat::IDENTITY,
                ..tip
            },
        ],
        ..Default::default()
    };
    let mut twig = Mesh::default();
    stems::mesh_run(&own, &own.stems, options, &mut twig);
    let copies = twigs
        .iter()
        .filter_map(ends)
        .map(|(b, t)| {
            let across = b.radius / radius;
            TwigCopy {
                position: b.position.to_array(),
                rotation: b.orientation.normalize().to_array(),
                scale: [across, across, b.position.distance(t.position) / length],
            }
        })
        .collect();
    TwigCopies { twig, copies }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::{TreeMesh, mesh_tree};
    use crate::skeleton::StemId;

    /// A bare stem with three short twigs of different sizes and directions, each tip at 0.35
    /// of its base as the grower draws them.
    pub(crate) fn bare_stem_with_twigs() -> Skeleton {
        let section = |position: Vec3, direction: Vec3, radius: f32, z: f32| CrossSection {
            position,
            orientation: Quat::from_rotation_arc(Vec3::Z, direction.normalize()),
            radius,
            z,
        };
        let mut sk = Skeleton {
            stems: vec![Stem {
                level: 0,
                parent: None,
                clone_of: None,
                offset: 0.0,
                length: 2.0,
                sections: 0..2,
                lobes: 0,
                lobe_depth: 0.0,
            }],
            sections: vec![
                section(Vec3::ZERO, Vec3::Z, 0.05, 0.0),
                section(Vec3::Z * 2.0, Vec3::Z, 0.02, 1.0),
            ],
            ..Default::default()
        };
        let twigs = [
            (0.5, Vec3::new(1.0, 0.2, 0.5), 0.03, 0.003),
            (1.0, Vec3::new(-0.3, 1.0, 0.1), 0.05, 0.004),
            (1.5, Vec3::new(0.1, -0.7, 1.0), 0.02, 0.0025),
        ];
        for (z, d, length, radius) in twigs {
            let first = sk.sections.len() as u32;
            let base = Vec3::new(0.0, 0.0, z);
            sk.sections.push(section(base, d, radius, 0.0));
            let tip = base + d.normalize() * length;
            sk.sections.push(section(tip, d, radius * 0.35, 1.0));
            sk.stems.push(Stem {
                level: 3,
                parent: Some(StemId(0)),
                clone_of: None,
                offset: z,
                length,
                sections: first..first + 2,
                lobes: 0,
                lobe_depth: 0.0,
            });
        }
        sk.short_twigs = 3;
        sk
    }

    fn copied(sk: &Skeleton) -> TreeMesh {
        let options = MeshOptions {
            twig_copies: true,
            ..Default::default()
        };
        mesh_tree(sk, &options)
    }

    #[test]
    fn twig_copies_placed_are_the_twigs_meshed_one_by_one() {
        let sk = bare_stem_with_twigs();
        let direct = mesh_tree(&sk, &MeshOptions::default());
        let copies = copied(&sk);
        assert_eq!(copies.twigs.copies.len(), 3);
        // The bark holds the frame alone; placed, the copies give back every twig vertex.
        let frame = mesh_tree(
            &Skeleton {
                stems: sk.stems[..1].to_vec(),
                sections: sk.sections[..2].to_vec(),
                ..Default::default()
            },
            &MeshOptions::default(),
        );
        assert_eq!(copies.bark, frame.bark);
        let placed = copies.bark_with_twigs();
        assert_eq!(placed.vertex_count(), direct.bark.vertex_count());
        assert_eq!(placed.indices, direct.bark.indices);
        assert_eq!(copies.triangle_count(), direct.triangle_count());
        for (k, (a, b)) in placed
            .positions
            .iter()
            .zip(&direct.bark.positions)
            .enumerate()
        {
            let gap = Vec3::from(*a).distance(Vec3::from(*b));
            assert!(gap < 1e-5, "vertex {k} is {gap} m off");
        }
        for (k, (a, b)) in placed.normals.iter().zip(&direct.bark.normals).enumerate() {
            let turn = Vec3::from(*a).dot(Vec3::from(*b));
            assert!(turn > 0.999, "normal {k} is turned ({turn})");
        }
    }

    #[test]
    fn a_crown_in_leaf_or_options_without_copies_keep_their_twigs_in_the_bark() {
        let sk = bare_stem_with_twigs();
        assert!(mesh_tree(&sk, &MeshOptions::default()).twigs.is_empty());
        let mut leafy = sk.clone();
        leafy.leaves.push(crate::skeleton::Leaf {
            position: Vec3::Z,
            orientation: Quat::IDENTITY,
            length: 0.1,
            width: 0.05,
            shape: crate::skeleton::LeafShape::Oval,
            stem: StemId(0),
            light: 1.0,
        });
        let mesh = copied(&leafy);
        assert!(mesh.twigs.is_empty());
        // Under leaves the twigs are not drawn at all, copies or not.
        assert_eq!(mesh.bark, mesh_tree(&leafy, &MeshOptions::default()).bark);
    }
}
