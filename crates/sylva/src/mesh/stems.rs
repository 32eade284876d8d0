//! Stem tubes: one ring per cross-section, rings joined by quads, a point or a cap at the tip.

use super::apart::{Sink, mesh_apart};
use super::bark::young_bark_shade;
use super::{BarkPattern, Mesh, MeshOptions};
use crate::skeleton::{CrossSection, Skeleton, Stem};
use glam::{Quat, Vec3};
use std::f32::consts::TAU;

/// Bark vertices one task meshes, at least (a run ends at a whole stem).
const RUN_VERTICES: usize = 16_384;

/// Below this many bark vertices one thread is quicker than sharing out.
const APART_FROM: usize = 4 * RUN_VERTICES;

/// Vertices around a stem of `level` at mesh `quality` (at least 3). A lobed trunk gets at least
/// four vertices per lobe so the lobes show.
pub fn ring_vertices(level: usize, quality: f64, lobes: u32) -> usize {
    const BASE: [f64; 4] = [20.0, 10.0, 6.0, 4.0];
    let n = (BASE[level.min(3)] * quality).round().max(3.0) as usize;
    if lobes > 0 {
        n.max((4 * lobes as usize).min(256))
    } else {
        n
    }
}

/// Rings of this many sides or fewer carry no seam vertex. A ring's seam vertex repeats its
/// first with u = 1, so that a bark texture wraps once round the stem without a jump. A stem
/// meshed with three sides is a crown's thinnest wood (a grown tree's third and fourth orders
/// of shoots: 91,942 of a 30-year plane's 108,551 bark vertices), where a texture's one
/// backward face cannot be seen and the repeat would be a quarter of the vertices.
const SEAMLESS_SIDES: usize = 3;

/// Vertices a ring of `n` sides is written with: `n`, and the seam's repeat above
/// [`SEAMLESS_SIDES`].
fn ring_len(n: usize) -> usize {
    if n > SEAMLESS_SIDES { n + 1 } else { n }
}

/// Unit circle for a ring of `n` sides ([`ring_len`] entries).
fn circle(n: usize, out: &mut Vec<(f32, f32)>) {
    out.clear();
    out.extend((0..ring_len(n)).map(|i| {
        let t = TAU * i as f32 / n as f32;
        (t.cos(), t.sin())
    }));
}

/// The stems meshed into the bark: [`Skeleton::meshed_stems`], less the short twigs where they
/// are drawn as copies (`twigs.rs`).
fn meshed<'a>(skeleton: &'a Skeleton, options: &MeshOptions) -> &'a [Stem] {
    if options.twig_copies {
        skeleton.frame_stems()
    } else {
        skeleton.meshed_stems()
    }
}

/// Vertices and indices that [`mesh_stems`] will write.
pub(super) fn count(skeleton: &Skeleton, options: &MeshOptions) -> (usize, usize) {
    meshed(skeleton, options)
        .iter()
        .fold((0, 0), |(v, i), stem| {
            let (sv, si) = stem_size(skeleton, stem, options);
            (v + sv, i + si)
        })
}

/// Vertices and indices one stem's mesh takes.
fn stem_size(skeleton: &Skeleton, stem: &Stem, options: &MeshOptions) -> (usize, usize) {
    let sections = sections_of(skeleton, stem);
    if sections.len() < 2 {
        return (0, 0);
    }
    let n = ring_count(options, stem, sections);
    let m = refine(sections, options.bark, None);
    let (rings, tip_vertices) = if tip_is_point(sections) {
        (m - 1, n)
    } else {
        (m, ring_len(n) + 1)
    };
    (
        rings * ring_len(n) + tip_vertices,
        (rings - 1) * n * 6 + n * 3,
    )
}

/// Stems at least this thick (radius, m) show a bark pattern, meshed finely enough to draw it.
const PATTERN_RADIUS: f32 = 0.05;
/// Most distance between a patterned stem's rings, m.
const PATTERN_ALONG: f32 = 0.08;
/// Most distance between a patterned stem's vertices around, m (up to 48 around).
const PATTERN_AROUND: f32 = 0.06;

/// Vertices around a stem's rings: the options' count, more on a thick stem whose bark is
/// patterned, since the pattern is drawn at the vertices.
fn ring_count(options: &MeshOptions, stem: &Stem, sections: &[CrossSection]) -> usize {
    let n = options.ring_vertices(stem);
    let r = max_radius(sections);
    if options.bark == BarkPattern::Smooth || r < PATTERN_RADIUS {
        return n;
    }
    n.max(((TAU * r / PATTERN_AROUND).ceil() as usize).min(48))
}

/// The number of rings a stem is meshed with, writing them into `out` when given: its
/// sections, with rings added between those of a thick, patterned stretch so that none is
/// more than [`PATTERN_ALONG`] apart (each added ring on the straight segment, in its frame).
fn refine(
    sections: &[CrossSection],
    bark: BarkPattern,
    mut out: Option<&mut Vec<CrossSection>>,
) -> usize {
    if let Some(out) = out.as_deref_mut() {
        out.clear();
    }
    let mut rings = 0;
    for (j, c) in sections.iter().enumerate() {
        let next = sections.get(j + 1);
        let extra = match next {
            Some(d) if bark != BarkPattern::Smooth && c.radius.max(d.radius) >= PATTERN_RADIUS => {
                let gaps = (c.position.distance(d.position) / PATTERN_ALONG).ceil() as usize;
                gaps.clamp(1, 64) - 1
            }
            _ => 0,
        };
        rings += 1 + extra;
        if let Some(out) = out.as_deref_mut() {
            out.push(*c);
            if let Some(d) = next {
                for k in 1..=extra {
                    let t = k as f32 / (extra + 1) as f32;
                    out.push(CrossSection {
                        position: c.position.lerp(d.position, t),
                        orientation: c.orientation,
                        radius: c.radius + (d.radius - c.radius) * t,
                        z: c.z + (d.z - c.z) * t,
                    });
                }
            }
        }
    }
    rings
}

fn sections_of<'a>(skeleton: &'a Skeleton, stem: &Stem) -> &'a [CrossSection] {
    &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize]
}

/// The largest radius of a stem (its base, or its flare).
fn max_radius(sections: &[CrossSection]) -> f32 {
    sections
        .iter()
        .map(|c| c.radius)
        .fold(0.0f32, f32::max)
        .max(1e-6)
}

/// Whether a stem ends in a point (a cone's tip) rather than an open ring to cap.
fn tip_is_point(sections: &[CrossSection]) -> bool {
    sections[sections.len() - 1].radius <= max_radius(sections) * 1e-4
}

pub(super) fn mesh_stems(skeleton: &Skeleton, options: &MeshOptions, mesh: &mut Mesh) {
    if !mesh_stems_apart(skeleton, options, mesh) {
        mesh_run(skeleton, meshed(skeleton, options), options, mesh);
    }
}

/// Meshes the stems on every core, in runs of whole stems, straight into `mesh`'s buffers
/// (see `apart`), where that pays: enough bark, more than one thread, `mesh` empty. False,
/// with `mesh` as it was, otherwise.
fn mesh_stems_apart(skeleton: &Skeleton, options: &MeshOptions, mesh: &mut Mesh) -> bool {
    let empty = mesh.positions.is_empty() && mesh.indices.is_empty() && mesh.shades.is_empty();
    if !empty || rayon::current_num_threads() < 2 {
        return false;
    }
    let mut runs: Vec<(&[Stem], (usize, usize))> = Vec::new();
    let (mut start, mut size, mut total) = (0, (0, 0), 0);
    let stems = meshed(skeleton, options);
    for (k, stem) in stems.iter().enumerate() {
        let (v, i) = stem_size(skeleton, stem, options);
        size = (size.0 + v, size.1 + i);
        if size.0 >= RUN_VERTICES || k + 1 == stems.len() {
            runs.push((&stems[start..=k], size));
            total += size.0;
            (start, size) = (k + 1, (0, 0));
        }
    }
    if total < APART_FROM {
        return false;
    }
    let shaded = options.shaded_bark();
    mesh_apart(mesh, runs, shaded, |run, out| {
        mesh_run(skeleton, run, options, out)
    })
}

/// Meshes `stems` (of `skeleton`) in order into `out`.
pub(super) fn mesh_run(
    skeleton: &Skeleton,
    stems: &[Stem],
    options: &MeshOptions,
    out: &mut impl Sink,
) {
    // Stems come parent before children, so the ring size changes from one stem to the next:
    // each size's circle is worked out once and kept.
    let mut circles: Vec<Vec<(f32, f32)>> = Vec::new();
    let mut rim = Vec::new();
    let mut finer = Vec::new();
    for stem in stems {
        let stored = sections_of(skeleton, stem);
        if stored.len() < 2 {
            continue;
        }
        let n = ring_count(options, stem, stored);
        let sections = if options.bark == BarkPattern::Smooth {
            stored
        } else {
            refine(stored, options.bark, Some(&mut finer));
            &finer[..]
        };
        if circles.len() <= n {
            circles.resize(n + 1, Vec::new());
        }
        if circles[n].is_empty() {
            circle(n, &mut circles[n]);
        }
        mesh_stem(stem, sections, (n, &circles[n]), options, &mut rim, out);
    }
}

/// Ring frame at section `j`: the bisector of the segments meeting there, so joints don't pinch.
pub(crate) fn ring_frame(sections: &[CrossSection], j: usize) -> Quat {
    if j == 0 || j + 1 == sections.len() {
        sections[j].orientation
    } else {
        let a = sections[j - 1].orientation;
        let b = sections[j].orientation;
        let b = if a.dot(b) < 0.0 { -b } else { b };
        a.lerp(b, 0.5).normalize()
    }
}

/// Meshes one stem with rings of `n` sides (`unit`: their circle, [`circle`]); `rim` is room
/// for its last ring, which an open tip's cap repeats.
fn mesh_stem(
    stem: &Stem,
    sections: &[CrossSection],
    (n, unit): (usize, &[(f32, f32)]),
    options: &MeshOptions,
    rim: &mut Vec<Vec3>,
    mesh: &mut impl Sink,
) {
    let (bark, young) = (options.bark, options.young_bark);
    let patterned = options.shaded_bark();
    let stem_key = stem.sections.start;
    // The bark's shade at ring vertex `i` of a ring of `radius` `along` metres up the stem;
    // the seam's repeated vertex takes the first's, so the pattern has no seam.
    let shade_at = |i: usize, radius: f32, along: f32| {
        let around = (i % n) as f32 / n as f32 * TAU * radius;
        bark.shade(around, along, radius, stem_key) * young_bark_shade(radius, young)
    };
    let m = sections.len();
    let base_radius = max_radius(sections);
    let v_scale = 1.0 / (TAU * base_radius);
    let lobed = stem.lobes > 0 && stem.lobe_depth != 0.0;
    let (lobes, depth) = (stem.lobes as f32, stem.lobe_depth);
    let tip_is_point = tip_is_point(sections);
    let rings = if tip_is_point { m - 1 } else { m };
    let mut distance = 0.0f32;
    let first_ring = mesh.next_vertex();
    rim.clear();
    for j in 0..rings {
        let c = &sections[j];
        if j > 0 {
            distance += c.position.distance(sections[j - 1].position);
        }
        let q = ring_frame(sections, j);
        let (x, y, z) = (q * Vec3::X, q * Vec3::Y, q * Vec3::Z);
        // Radius slope along the stem, for normals on tapering and flaring stems.
        let (a, b) = (sections[j.saturating_sub(1)], sections[(j + 1).min(m - 1)]);
        let ds = a.position.distance(b.position);
        let slope = if ds > 1e-9 {
            (b.radius - a.radius) / ds
        } else {
            0.0
        };
        let v = distance * v_scale;
        for (i, &(cos, sin)) in unit.iter().enumerate() {
            let radial = x * cos + y * sin;
            let (r, normal_in_plane) = if lobed {
                let t = TAU * i as f32 / n as f32;
                let (ls, lc) = (lobes * t).sin_cos();
                let r = c.radius * (1.0 + depth * ls);
                let dr = c.radius * depth * lobes * lc;
                let tangent = y * cos - x * sin;
                (r, (radial * r - tangent * dr).normalize_or(radial))
            } else {
                (c.radius, radial)
            };
            let normal = (normal_in_plane - z * slope).normalize_or(radial);
            let position = c.position + radial * r;
            mesh.vertex(position, normal, [i as f32 / n as f32, v]);
            if patterned {
                mesh.shade(shade_at(i, c.radius, distance));
            }
            if j + 1 == rings && !tip_is_point {
                rim.push(position);
            }
        }
    }
    let stride = unit.len() as u32;
    // The ring vertex after `i` (the first again where the ring has no seam vertex).
    let next = |i: u32| (i + 1) % stride;
    // Quad strips between rings; with a pointed tip the last segment is the apex fan.
    let strips = rings.saturating_sub(1) as u32;
    for j in 0..strips {
        let a = first_ring + j * stride;
        let b = a + stride;
        for i in 0..n as u32 {
            let k = next(i);
            mesh.indices(&[a + i, a + k, b + k, a + i, b + k, b + i]);
        }
    }
    let last_ring = first_ring + (rings as u32 - 1) * stride;
    let tip = sections[m - 1];
    let axis = tip.orientation * Vec3::Z;
    if tip_is_point {
        distance += tip.position.distance(sections[m - 2].position);
        let apex = mesh.next_vertex();
        // One apex vertex per quad column keeps the u coordinate continuous.
        for i in 0..n {
            mesh.vertex(
                tip.position,
                axis,
                [(i as f32 + 0.5) / n as f32, distance * v_scale],
            );
            if patterned {
                // A twig's tip is the youngest bark of all.
                mesh.shade(young_bark_shade(0.0, young));
            }
        }
        for i in 0..n as u32 {
            mesh.indices(&[last_ring + i, last_ring + next(i), apex + i]);
        }
    } else {
        // Close the open end with a flat cap.
        let centre = mesh.vertex(tip.position, axis, [0.5, 0.5]);
        let first_rim = mesh.next_vertex();
        for (&p, &(cos, sin)) in rim.iter().zip(unit) {
            mesh.vertex(p, axis, [0.5 + 0.5 * cos, 0.5 + 0.5 * sin]);
        }
        // A cut end shows pale wood, as the centre and rim draw it: fully lit.
        if patterned {
            for _ in 0..=unit.len() {
                mesh.shade(1.0);
            }
        }
        for i in 0..n as u32 {
            mesh.indices(&[centre, first_rim + i, first_rim + next(i)]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::StemId;

    /// A straight vertical cone of height 2 and base radius 0.5:
    ///
    /// ```text
    ///   .  z = 2, r = 0
    ///  / \
    /// /___\ z = 0, r = 0.5
    /// ```
    fn cone(lobes: u32) -> Skeleton {
        let sec = |z: f32, r: f32| CrossSection {
            position: Vec3::new(0.0, 0.0, z),
            orientation: Quat::IDENTITY,
            radius: r,
            z: z / 2.0,
        };
        Skeleton {
            stems: vec![Stem {
                level: 0,
                parent: None,
                clone_of: None,
                offset: 0.0,
                length: 2.0,
                sections: 0..3,
                lobes,
                lobe_depth: if lobes > 0 { 0.1 } else { 0.0 },
            }],
            sections: vec![sec(0.0, 0.5), sec(1.0, 0.25), sec(2.0, 0.0)],
            leaves: vec![],
            short_twigs: 0,
        }
    }

    #[test]
    fn cone_counts_and_normals() {
        let mut mesh = Mesh::default();
        mesh_stems(
            &cone(0),
            &MeshOptions {
                quality: 1.0,
                ..Default::default()
            },
            &mut mesh,
        );
        let n = ring_vertices(0, 1.0, 0);
        // Two rings of n + 1, then n apex vertices; n quads and n tip triangles.
        assert_eq!(mesh.vertex_count(), 2 * (n + 1) + n);
        assert_eq!(mesh.triangle_count(), 2 * n + n);
        // The cone's side normal tilts up by atan(0.5 / 2).
        let nz = mesh.normals[0][2];
        let want = (0.25f32).atan().sin();
        assert!((nz - want).abs() < 1e-3, "{nz} vs {want}");
        for t in mesh.indices.chunks(3) {
            // Every triangle faces outwards: its normal points away from the axis.
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(mesh.positions[i as usize]));
            let normal = (b - a).cross(c - a);
            let centre = (a + b + c) / 3.0;
            let out = Vec3::new(centre.x, centre.y, 0.0);
            assert!(normal.dot(out) > 0.0, "inward triangle at {centre}");
        }
        // Seam: u runs 0..1 on every ring.
        assert_eq!(mesh.uvs[0][0], 0.0);
        assert_eq!(mesh.uvs[n][0], 1.0);
        let _ = StemId(0);
    }

    #[test]
    fn lobes_change_the_radius_around_the_ring() {
        let mut mesh = Mesh::default();
        mesh_stems(
            &cone(5),
            &MeshOptions {
                quality: 1.0,
                ..Default::default()
            },
            &mut mesh,
        );
        let n = ring_vertices(0, 1.0, 5);
        assert!(n >= 20);
        let radii: Vec<f32> = mesh.positions[..n]
            .iter()
            .map(|p| p[0].hypot(p[1]))
            .collect();
        let (lo, hi) = radii
            .iter()
            .fold((f32::MAX, 0.0f32), |(l, h), &r| (l.min(r), h.max(r)));
        assert!(
            (hi - 0.55).abs() < 0.01 && (lo - 0.45).abs() < 0.01,
            "{lo}..{hi}"
        );
    }

    #[test]
    fn open_tip_gets_a_cap() {
        let mut sk = cone(0);
        sk.sections[2].radius = 0.1;
        let mut mesh = Mesh::default();
        mesh_stems(
            &sk,
            &MeshOptions {
                quality: 1.0,
                ..Default::default()
            },
            &mut mesh,
        );
        let n = ring_vertices(0, 1.0, 0);
        assert_eq!(mesh.triangle_count(), 2 * 2 * n + n);
    }

    /// An oak's bark, every third stem cut open at its tip so caps are meshed too, meshed in
    /// runs on three threads straight into the buffers and in order on one: the same bytes.
    #[test]
    fn stems_meshed_apart_are_the_stems_meshed_in_order() {
        let params = crate::species::builtin("ca_black_oak").expect("built-in");
        let options = crate::GenerateOptions {
            quality: 0.4,
            ..Default::default()
        };
        let mut skeleton = crate::generate(&params, &options).expect("grows");
        for stem in skeleton.stems.iter().step_by(3) {
            let last = stem.sections.end as usize - 1;
            skeleton.sections[last].radius = skeleton.sections[last].radius.max(0.01);
        }
        // Patterned bark adds rings and vertices to thick stems and a shade to every vertex.
        let mut smooth_vertices = 0;
        for bark in [BarkPattern::Smooth, BarkPattern::Plates] {
            let mesh_options = MeshOptions {
                bark,
                ..MeshOptions::for_species(&params, 0.4)
            };
            let mut in_order = Mesh::default();
            mesh_run(&skeleton, &skeleton.stems, &mesh_options, &mut in_order);
            let mut apart = Mesh::default();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(3)
                .build()
                .expect("a pool");
            assert!(pool.install(|| mesh_stems_apart(&skeleton, &mesh_options, &mut apart)));
            assert!(in_order.vertex_count() > 2 * APART_FROM);
            assert_eq!(
                (in_order.vertex_count(), in_order.indices.len()),
                count(&skeleton, &mesh_options)
            );
            assert!(apart == in_order, "{bark:?}: the bark meshes differ");
            if bark == BarkPattern::Smooth {
                assert!(in_order.shades.is_empty());
                smooth_vertices = in_order.vertex_count();
            } else {
                assert_eq!(in_order.shades.len(), in_order.vertex_count());
                assert!(in_order.vertex_count() > smooth_vertices);
                assert!(in_order.shades.iter().any(|&s| s < 0.6));
            }
        }
    }

    #[test]
    fn degenerate_stems_do_not_panic() {
        let mut sk = cone(0);
        sk.sections.iter_mut().for_each(|c| {
            c.position = Vec3::ZERO;
            c.radius = 0.0;
        });
        let mut mesh = Mesh::default();
        mesh_stems(
            &sk,
            &MeshOptions {
                quality: 0.01,
                ..Default::default()
            },
            &mut mesh,
        );
        assert!(mesh.positions.iter().flatten().all(|v| v.is_finite()));
        assert!(mesh.normals.iter().flatten().all(|v| v.is_finite()));
    }
}
