//! Leaf outlines. Each shape is a template of unit length (local z from 0 to 1) and unit width
//! (local x from -0.5 to 0.5), lying in the local x-z plane with its upper side facing +y;
//! leaves are instances of it, scaled and placed by the skeleton's leaf frames.

use super::Mesh;
use crate::skeleton::{Leaf, LeafShape, Skeleton};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;
use std::sync::OnceLock;

/// A leaf shape ready to instance.
#[derive(Clone, Debug, PartialEq)]
pub struct LeafTemplate {
    /// Local positions (x across, y off the blade, z along).
    pub positions: Vec<Vec3>,
    /// Local unit normals.
    pub normals: Vec<Vec3>,
    /// Texture coordinates 0..1.
    pub uvs: Vec<[f32; 2]>,
    /// Triangles, counter-clockwise seen from the normal side.
    pub indices: Vec<u32>,
}

impl LeafTemplate {
    /// Area of the outline for a leaf of unit length and width.
    pub fn area(&self) -> f32 {
        self.indices
            .chunks(3)
            .map(|t| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| self.positions[i as usize]);
                (b - a).cross(c - a).length() / 2.0
            })
            .sum()
    }
}

/// The template of a shape (every one built once, shared; a count out of its bounds takes the
/// nearest's).
pub fn leaf_template(shape: LeafShape) -> &'static LeafTemplate {
    static TEMPLATES: OnceLock<Vec<LeafTemplate>> = OnceLock::new();
    let all = TEMPLATES.get_or_init(|| LeafShape::every().map(build).collect());
    &all[shape.slot().min(all.len() - 1)]
}

/// The area of a shape's template ([`LeafTemplate::area`]), worked out once per shape: what a
/// leaf of unit length and width covers, read for every leaf of a tree by the measures and the
/// crown's surfaces.
pub fn template_area(shape: LeafShape) -> f32 {
    static AREAS: OnceLock<Vec<f32>> = OnceLock::new();
    let all = AREAS.get_or_init(|| {
        LeafShape::every()
            .map(|s| leaf_template(s).area())
            .collect()
    });
    all[shape.slot().min(all.len() - 1)]
}

/// Triangles per leaf of a shape.
pub fn leaf_triangles(shape: LeafShape) -> usize {
    leaf_template(shape).indices.len() / 3
}

/// Vertices and indices that [`mesh_leaves`] will write for `leaves`.
pub(super) fn count(leaves: &[Leaf]) -> (usize, usize) {
    leaves.iter().fold((0, 0), |(v, i), leaf| {
        let t = leaf_template(leaf.shape);
        (v + t.positions.len(), i + t.indices.len())
    })
}

pub(super) fn mesh_leaves(skeleton: &Skeleton, mesh: &mut Mesh) {
    let mut base = mesh.positions.len() as u32;
    leaf_vertices(skeleton, mesh);
    for leaf in &skeleton.leaves {
        let t = leaf_template(leaf.shape);
        mesh.indices.extend(t.indices.iter().map(|i| base + i));
        base += t.positions.len() as u32;
    }
}

/// Every leaf's vertices, in skeleton order, without triangles; their shades too where any
/// leaf is out of full light.
pub(super) fn leaf_vertices(skeleton: &Skeleton, mesh: &mut Mesh) {
    if skeleton.leaves.iter().any(|l| l.light < 1.0) {
        mesh.shades.resize(mesh.positions.len(), 1.0);
        for leaf in &skeleton.leaves {
            let n = leaf_template(leaf.shape).positions.len();
            mesh.shades
                .extend(std::iter::repeat_n(luminance(leaf.light), n));
        }
    }
    let mut templates = Templates::default();
    for leaf in &skeleton.leaves {
        for (p, n, uv) in corners(leaf, templates.of(leaf.shape)) {
            mesh.push(p, n, uv);
        }
    }
}

/// A leaf's vertices (position, normal, texture coordinate) from its template and whether the
/// template is flat ([`Templates::of`]): the one place both leaf meshers take them from, so
/// meshing on one thread or many gives the same bytes.
#[inline]
pub(super) fn corners<'a>(
    leaf: &'a Leaf,
    (t, flat): (&'static LeafTemplate, bool),
) -> impl Iterator<Item = (Vec3, Vec3, [f32; 2])> + 'a {
    let scale = Vec3::new(leaf.width, leaf.width, leaf.length);
    let shared = (flat && !t.normals.is_empty()).then(|| leaf.orientation * t.normals[0]);
    t.positions
        .iter()
        .zip(&t.normals)
        .zip(&t.uvs)
        .map(move |((p, n), uv)| {
            (
                leaf.position + leaf.orientation * (*p * scale),
                shared.unwrap_or_else(|| leaf.orientation * *n),
                *uv,
            )
        })
}

/// Leaf templates looked up in turn. The leaves of a tree mostly share one shape, so its
/// template is looked up once per run of them; and a flat template's one normal can be turned
/// once per leaf, not once per vertex.
#[derive(Default)]
pub(super) struct Templates {
    current: Option<(LeafShape, &'static LeafTemplate, bool)>,
}

impl Templates {
    /// The template of `shape`, and whether all its normals are one.
    pub(super) fn of(&mut self, shape: LeafShape) -> (&'static LeafTemplate, bool) {
        match self.current {
            Some((s, t, flat)) if s == shape => (t, flat),
            _ => {
                let t = leaf_template(shape);
                let flat = t.normals.windows(2).all(|w| w[0] == w[1]);
                self.current = Some((shape, t, flat));
                (t, flat)
            }
        }
    }
}

/// Number of luminance classes leaves are drawn in (Rudnick et al.: ten).
pub const LUMINANCE_CLASSES: u32 = 10;

/// The luminance factor of a leaf receiving `light` (0..1): its class, 1 (darkest) to 10
/// (open sky), scaled so the darkest class still shows its colour in the sky's ambient.
pub fn luminance(light: f32) -> f32 {
    let classes = LUMINANCE_CLASSES as f32;
    let class = crate::whole::pieces(light.clamp(0.0, 1.0) * classes) as f32;
    0.3 + 0.7 * class / classes
}

/// Flat outline in the (x, z) plane, counter-clockwise, triangulated as a fan from `centre`
/// (the outline must be star-shaped about it) or, with `centre = None`, from its first point
/// (the outline must be convex).
fn flat(parts: &[(Option<Vec2>, Vec<Vec2>)]) -> LeafTemplate {
    let mut t = LeafTemplate {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    let push = |t: &mut LeafTemplate, p: Vec2| {
        t.positions.push(Vec3::new(p.x, 0.0, p.y));
        t.normals.push(Vec3::Y);
        t.uvs.push([p.x + 0.5, p.y]);
        t.positions.len() as u32 - 1
    };
    for (centre, outline) in parts {
        let first = t.positions.len() as u32;
        let k = outline.len() as u32;
        for &p in outline {
            push(&mut t, p);
        }
        // Outlines run counter-clockwise in (x, z), which faces -y; emit (a, c, b) to face +y.
        match centre {
            Some(c) => {
                let ci = push(&mut t, *c);
                for i in 0..k {
                    t.indices
                        .extend_from_slice(&[ci, first + (i + 1) % k, first + i]);
                }
            }
            None => {
                for i in 1..k - 1 {
                    t.indices
                        .extend_from_slice(&[first, first + i + 1, first + i]);
                }
            }
        }
    }
    t
}

/// A blade symmetric about its midrib with half-width `half_width(z)` at each of `steps + 1`
/// heights, meshed as a strip of quads: any width profile, however lobed, without overlaps.
fn ribbon(steps: usize, half_width: impl Fn(f32) -> f32) -> LeafTemplate {
    let mut t = LeafTemplate {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    for i in 0..=steps {
        let z = i as f32 / steps as f32;
        let w = half_width(z).clamp(0.0, 0.5);
        for x in [-w, w] {
            t.positions.push(Vec3::new(x, 0.0, z));
            t.normals.push(Vec3::Y);
            t.uvs.push([x + 0.5, z]);
        }
    }
    for i in 0..steps as u32 {
        let (l0, r0, l1, r1) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        // Counter-clockwise seen from +y: (left, up-left, right), (right, up-left, up-right).
        t.indices.extend_from_slice(&[l0, l1, r0, r0, l1, r1]);
    }
    t
}

/// Outline from a polar radius function about `(0, cz)`, `samples` points, counter-clockwise,
/// then fitted to the unit box (x in -0.5..0.5, z in 0..1).
fn polar(samples: usize, radius: impl Fn(f32) -> f32) -> (Option<Vec2>, Vec<Vec2>) {
    let pts: Vec<Vec2> = (0..samples)
        .map(|i| {
            let a = -PI / 2.0 + 2.0 * PI * i as f32 / samples as f32;
            Vec2::new(a.cos(), a.sin()) * radius(a)
        })
        .collect();
    let lo = pts.iter().fold(Vec2::splat(f32::MAX), |m, p| m.min(*p));
    let hi = pts.iter().fold(Vec2::splat(f32::MIN), |m, p| m.max(*p));
    let size = (hi - lo).max(Vec2::splat(1e-6));
    let fit = |p: Vec2| Vec2::new((p.x - lo.x) / size.x - 0.5, (p.y - lo.y) / size.y);
    (Some(fit(Vec2::ZERO)), pts.into_iter().map(fit).collect())
}

/// Sum of lobes: each `(direction, reach)` adds a bump of reach `reach` around `direction`
/// (radians from +x), sharper with larger `power`.
fn lobed(lobes: &[(f32, f32)], core: f32, power: i32) -> impl Fn(f32) -> f32 + '_ {
    move |a| {
        core + lobes
            .iter()
            .map(|&(dir, reach)| reach * (a - dir).cos().max(0.0).powi(power))
            .sum::<f32>()
    }
}

fn ellipse(width: f32) -> Vec<Vec2> {
    // Base, three points up each side, tip: an octagon close to an ellipse.
    let side = |z: f32| width * (1.0 - (2.0 * z - 1.0).powi(2)).sqrt();
    vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(side(0.2), 0.2),
        Vec2::new(side(0.5), 0.5),
        Vec2::new(side(0.8), 0.8),
        Vec2::new(0.0, 1.0),
        Vec2::new(-side(0.8), 0.8),
        Vec2::new(-side(0.5), 0.5),
        Vec2::new(-side(0.2), 0.2),
    ]
}

fn build(shape: LeafShape) -> LeafTemplate {
    if let Some(t) = super::compound::build(shape) {
        return t;
    }
    let up = PI / 2.0;
    match shape {
        LeafShape::Oval => flat(&[(None, ellipse(0.5))]),
        LeafShape::Triangle => flat(&[(
            None,
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(0.5, 0.25),
                Vec2::new(0.0, 1.0),
                Vec2::new(-0.5, 0.25),
            ],
        )]),
        LeafShape::Square => flat(&[(
            None,
            vec![
                Vec2::new(-0.5, 0.0),
                Vec2::new(0.5, 0.0),
                Vec2::new(0.5, 1.0),
                Vec2::new(-0.5, 1.0),
            ],
        )]),
        LeafShape::Palm => flat(&[(
            None,
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(0.5, 0.25),
                Vec2::new(0.35, 0.7),
                Vec2::new(0.0, 1.0),
                Vec2::new(-0.35, 0.7),
                Vec2::new(-0.5, 0.25),
            ],
        )]),
        LeafShape::Oak => ribbon(16, |z| {
            // Rounded lobes along both sides of an elongated blade, narrow at the base.
            let envelope = (std::f32::consts::PI * z).sin().max(0.0).powf(0.7)
                * (0.35 + 0.65 * z.min(0.75) / 0.75);
            0.5 * envelope * (0.55 + 0.45 * (3.5 * std::f32::consts::PI * z).sin().abs())
        }),
        LeafShape::Maple3 => flat(&[polar(
            30,
            lobed(
                &[(up, 0.78), (up + 1.05, 0.62), (up - 1.05, 0.62)],
                0.22,
                10,
            ),
        )]),
        LeafShape::Maple5 => flat(&[polar(
            40,
            lobed(
                &[
                    (up, 0.8),
                    (up + 0.85, 0.7),
                    (up - 0.85, 0.7),
                    (up + 1.8, 0.45),
                    (up - 1.8, 0.45),
                ],
                0.2,
                14,
            ),
        )]),
        LeafShape::ThreeLeaflets => {
            // Three small ovals from the petiole tip: one straight on, two at +-55 degrees.
            let leaflet = |angle: f32, length: f32| {
                let (s, c) = angle.sin_cos();
                let outline = ellipse(0.22)
                    .into_iter()
                    .map(|p| {
                        let p = p * length;
                        Vec2::new(p.x * c + p.y * s, -p.x * s + p.y * c)
                    })
                    .collect();
                (None, outline)
            };
            let mut t = flat(&[leaflet(0.0, 0.6), leaflet(1.15, 0.5), leaflet(-1.15, 0.5)]);
            // Fit to the unit box.
            let lo = t
                .positions
                .iter()
                .fold(Vec3::splat(f32::MAX), |m, p| m.min(*p));
            let hi = t
                .positions
                .iter()
                .fold(Vec3::splat(f32::MIN), |m, p| m.max(*p));
            let w = (hi.x - lo.x).max(1e-6);
            let h = (hi.z - lo.z).max(1e-6);
            for (p, uv) in t.positions.iter_mut().zip(&mut t.uvs) {
                *p = Vec3::new((p.x - lo.x) / w - 0.5, 0.0, (p.z - lo.z) / h);
                *uv = [p.x + 0.5, p.z];
            }
            t
        }
        LeafShape::Sphere => sphere(),
        // The outlines grown street trees wear, drawn with few corners: a crown carries tens
        // of thousands of them (see growth::data::foliage). Palmately five-lobed, as a plane's or a
        // maple's: two basal lobes, two side lobes, the middle lobe.
        LeafShape::Lobed5 => star(
            Vec2::new(0.0, 0.42),
            &[
                (0.0, 0.15),
                (0.38, 0.12),
                (0.17, 0.33),
                (0.5, 0.62),
                (0.14, 0.6),
                (0.0, 1.0),
                (-0.14, 0.6),
                (-0.5, 0.62),
                (-0.17, 0.33),
                (-0.38, 0.12),
            ],
        ),
        // A heart: the notch where the petiole joins, the basal lobes, full sides, the tip.
        LeafShape::Cordate => star(
            Vec2::new(0.0, 0.45),
            &[
                (0.0, 0.14),
                (0.32, 0.02),
                (0.5, 0.38),
                (0.0, 1.0),
                (-0.5, 0.38),
                (-0.32, 0.02),
            ],
        ),
        // A fan on a narrow base, its broad edge notched in the middle.
        LeafShape::Fan => star(
            Vec2::new(0.0, 0.55),
            &[
                (0.0, 0.0),
                (0.1, 0.12),
                (0.5, 0.78),
                (0.3, 0.97),
                (0.05, 0.92),
                (0.0, 0.82),
                (-0.05, 0.92),
                (-0.3, 0.97),
                (-0.5, 0.78),
                (-0.1, 0.12),
            ],
        ),
        // Seven lobes to points, the sinuses cut nearly to the midrib: a strip along the
        // midrib, widest at each lobe's tip.
        LeafShape::PointedLobes => strip(&[
            (0.0, 0.03),
            (0.2, 0.3),
            (0.3, 0.06),
            (0.48, 0.5),
            (0.57, 0.07),
            (0.78, 0.36),
            (0.87, 0.05),
            (1.0, 0.0),
        ]),
        // Built by `compound` above.
        LeafShape::Pinnate(_)
        | LeafShape::Bipinnate(_)
        | LeafShape::Palmate(_)
        | LeafShape::Needles(_)
        | LeafShape::NeedleSpray
        | LeafShape::ScaleSpray => flat(&[(None, ellipse(0.5))]),
    }
}

/// A blade symmetric about its midrib, `rows` of (z, half width) from base to tip, meshed as a
/// strip of quads.
fn strip(rows: &[(f32, f32)]) -> LeafTemplate {
    let mut t = LeafTemplate {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    for &(z, w) in rows {
        for x in [-w, w] {
            t.positions.push(Vec3::new(x, 0.0, z));
            t.normals.push(Vec3::Y);
            t.uvs.push([x + 0.5, z]);
        }
    }
    for i in 0..rows.len() as u32 - 1 {
        let (l0, r0, l1, r1) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        // Counter-clockwise seen from +y.
        t.indices.extend_from_slice(&[l0, l1, r0, r0, l1, r1]);
    }
    t
}

/// A flat outline of `corners` (x, z), counter-clockwise, fanned from `centre`.
fn star(centre: Vec2, corners: &[(f32, f32)]) -> LeafTemplate {
    let outline = corners.iter().map(|&(x, z)| Vec2::new(x, z)).collect();
    flat(&[(Some(centre), outline)])
}

/// An octahedron subdivided once and pushed onto the sphere inscribed in the unit box.
fn sphere() -> LeafTemplate {
    let v = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let mut t = LeafTemplate {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    for f in faces {
        let [a, b, c] = f.map(|i| v[i]);
        let (ab, bc, ca) = (
            (a + b).normalize(),
            (b + c).normalize(),
            (c + a).normalize(),
        );
        for tri in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
            for p in tri {
                let i = t.positions.len() as u32;
                t.positions.push(p * 0.5 + Vec3::new(0.0, 0.0, 0.5));
                t.normals.push(p);
                t.uvs.push([0.5 + 0.5 * p.x, 0.5 + 0.5 * p.z]);
                t.indices.push(i);
            }
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_template_fits_the_unit_box_and_faces_its_normal() {
        for shape in LeafShape::every() {
            let t = leaf_template(shape);
            assert!(!t.indices.is_empty(), "{shape:?}");
            for p in &t.positions {
                assert!(p.x >= -0.5 - 1e-4 && p.x <= 0.5 + 1e-4, "{shape:?} {p}");
                assert!(p.z >= -1e-4 && p.z <= 1.0 + 1e-4, "{shape:?} {p}");
            }
            for uv in &t.uvs {
                assert!(
                    uv.iter().all(|c| (-1e-4..=1.0 + 1e-4).contains(c)),
                    "{shape:?} {uv:?}"
                );
            }
            let mut area = 0.0;
            for tri in t.indices.chunks(3) {
                let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| t.positions[i as usize]);
                let n = (b - a).cross(c - a);
                let vertex_normal = t.normals[tri[0] as usize];
                assert!(
                    n.dot(vertex_normal) >= -1e-6,
                    "{shape:?}: triangle faces away from its normal"
                );
                area += n.length() / 2.0;
            }
            // A bundle of two needles is mostly air; every blade elsewhere fills a tenth.
            let least = if matches!(shape, LeafShape::Needles(_)) {
                0.02
            } else {
                0.1
            };
            assert!(area > least, "{shape:?} area {area}");
        }
    }

    /// Each shape finds its own template: the slot a shape names is where `every` builds it,
    /// and a compound leaf draws as many blades as it has leaflets, pinnae or needles.
    #[test]
    fn every_shape_draws_its_own_template() {
        for (i, shape) in LeafShape::every().enumerate() {
            assert_eq!(shape.slot(), i, "{shape:?}");
        }
        let blades = |s| leaf_template(s).indices.len() / 3;
        assert_eq!(blades(LeafShape::Pinnate(5)), 5);
        assert_eq!(blades(LeafShape::Needles(2)), 2);
        assert_eq!(blades(LeafShape::Bipinnate(7)), 7);
        let fan = build(LeafShape::Fan);
        assert_eq!(leaf_template(LeafShape::Fan).positions, fan.positions);
    }

    #[test]
    fn lobed_shapes_are_not_convex_and_oval_is() {
        // A lobed leaf covers clearly less of its bounding box than an oval does.
        let area = |s| {
            let t = leaf_template(s);
            t.indices
                .chunks(3)
                .map(|tri| {
                    let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| t.positions[i as usize]);
                    (b - a).cross(c - a).length() / 2.0
                })
                .sum::<f32>()
        };
        let oval = area(LeafShape::Oval);
        assert!((oval - PI / 4.0).abs() < 0.12, "oval area {oval}");
        for s in [LeafShape::Maple5, LeafShape::Maple3, LeafShape::Oak] {
            assert!(area(s) < oval, "{s:?}: {} vs oval {oval}", area(s));
        }
    }
}
