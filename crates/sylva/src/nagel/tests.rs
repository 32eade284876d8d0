//! Whisk and stick trees, and reading what the user drew.

use super::whisk::density_ribs;
use super::*;
use crate::skeleton::Skeleton;
use std::f32::consts::TAU;

/// A round canopy from 2 m to 8 m, 3 m across at its widest (radius, height).
const PROFILE_CSV: &str = "radius,height\n0,2\n1.5,2.6\n2.6,4\n3,5.5\n2.2,7.2\n0,8\n";

fn profile() -> Profile {
    read_profile("p.csv", PROFILE_CSV, None).unwrap()
}

fn polylines(s: &Skeleton, level: u8) -> Vec<Vec<glam::Vec3>> {
    s.stems
        .iter()
        .enumerate()
        .filter(|(_, st)| st.level == level)
        .map(|(i, _)| {
            s.sections_of(crate::StemId(i as u32))
                .iter()
                .map(|c| c.position)
                .collect()
        })
        .collect()
}

#[test]
fn n_ribs_are_copies_of_the_profile_360_over_n_apart() {
    let p = profile();
    for ribs in [1, 3, 8, 13] {
        let s = whisk_tree(
            &p,
            &WhiskParams {
                ribs,
                ..Default::default()
            },
        )
        .unwrap();
        let ribs_drawn = polylines(&s, 1);
        assert_eq!(ribs_drawn.len(), ribs as usize);
        for (j, rib) in ribs_drawn.iter().enumerate() {
            assert_eq!(rib.len(), p.points.len());
            let angle = TAU * j as f32 / ribs as f32;
            for (q, [r, h]) in rib.iter().zip(&p.points) {
                // Same radius and height as the profile point...
                assert!((q.truncate().length() - *r as f32).abs() < 1e-5);
                assert!((q.z - *h as f32).abs() < 1e-6);
                // ...turned by 360·j/N degrees.
                if *r > 0.0 {
                    let a = q.y.atan2(q.x).rem_euclid(TAU);
                    let d = (a - angle).abs();
                    assert!(d.min(TAU - d) < 1e-4, "rib {j}: {a} vs {angle}");
                }
            }
        }
        // The trunk stands from the ground to the canopy's base.
        let trunk = &polylines(&s, 0)[0];
        assert_eq!(
            trunk,
            &vec![glam::Vec3::ZERO, glam::Vec3::new(0.0, 0.0, 2.0)]
        );
    }
}

#[test]
fn rings_and_spokes_come_as_asked() {
    let p = profile();
    let s = whisk_tree(
        &p,
        &WhiskParams {
            ribs: 6,
            rings: 4,
            spokes: 3,
            ..Default::default()
        },
    )
    .unwrap();
    let extra = polylines(&s, 2);
    let (rings, spokes): (Vec<_>, Vec<_>) = extra.into_iter().partition(|l| l.len() > 2);
    assert_eq!(rings.len(), 4);
    assert_eq!(spokes.len(), 6 * 3);
    let ribs = polylines(&s, 1);
    for ring in &rings {
        // Closed, level, and passing through every rib.
        assert_eq!(ring.first(), ring.last());
        assert!(ring.iter().all(|q| (q.z - ring[0].z).abs() < 1e-6));
        for rib in &ribs {
            let near = rib
                .windows(2)
                .map(|w| distance_to_segment(ring[0].z, w, ring))
                .fold(f32::MAX, f32::min);
            assert!(near < 1e-3, "a ring misses a rib by {near} m");
        }
    }
    for spoke in &spokes {
        // From the axis, level, out to the canopy's edge.
        assert!(spoke[0].truncate().length() < 1e-6);
        assert!((spoke[0].z - spoke[1].z).abs() < 1e-6);
        assert!(spoke[1].truncate().length() > 0.5);
    }
}

/// Distance from the rib segment's point at height `z` (if it crosses it) to the nearest ring
/// vertex.
fn distance_to_segment(z: f32, w: &[glam::Vec3], ring: &[glam::Vec3]) -> f32 {
    let (a, b) = (w[0], w[1]);
    if (a.z - z) * (b.z - z) > 0.0 || a.z == b.z {
        return f32::MAX;
    }
    let t = (z - a.z) / (b.z - a.z);
    let q = a.lerp(b, t);
    ring.iter().map(|r| r.distance(q)).fold(f32::MAX, f32::min)
}

#[test]
fn density_one_to_five_gives_nagels_rib_counts() {
    let counts: Vec<u32> = (1..=5).map(|d| density_ribs(d).unwrap()).collect();
    assert_eq!(counts, [6, 9, 12, 15, 18]);
    assert_eq!(density_ribs(0), None);
    assert_eq!(density_ribs(6), None);
}

#[test]
fn stick_trees_turn_every_branch() {
    let text = "branch,radius,height\n1,0,3\n1,1.5,4\n1,2.5,4.2\n2,0,5\n2,1,6\n";
    let branches = read_sticks("b.csv", text, None).unwrap();
    assert_eq!(branches.len(), 2);
    let s = stick_tree(
        &branches,
        &WhiskParams {
            ribs: 5,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(polylines(&s, 1).len(), 10);
    // The trunk reaches the highest branch base, 5 m.
    assert_eq!(polylines(&s, 0)[0][1].z, 5.0);
    let scaled = read_sticks("b.csv", text, Some(12.0)).unwrap();
    assert_eq!(scaled[1][1], [2.0, 12.0]);
}

#[test]
fn svg_profiles_are_read_from_the_trunk_axis_and_the_ground() {
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 200">
  <polyline points="50,150 80,120 90,60 50,20" fill="none" stroke="black"/>
</svg>"#;
    let p = read_profile("p.svg", svg, Some(9.0)).unwrap();
    // Ground at y=200, axis at x=50; top point 180 units up becomes 9 m (0.05 m per unit).
    assert_eq!(p.points.len(), 4);
    let expect = [[0.0, 2.5], [1.5, 4.0], [2.0, 7.0], [0.0, 9.0]];
    for (q, e) in p.points.iter().zip(expect) {
        assert!(
            (q[0] - e[0]).abs() < 1e-9 && (q[1] - e[1]).abs() < 1e-9,
            "{q:?}"
        );
    }
}

#[test]
fn malformed_profiles_name_the_file_and_line() {
    let cases: [(&str, &str, &str); 6] = [
        ("p.csv", "radius,height\n0,2\n1.5,x\n", "p.csv, line 3"),
        ("p.csv", "0,2\n1.5\n", "p.csv, line 2"),
        ("p.csv", "0,2\n\n-1,3\n", "p.csv, line 3"),
        ("p.csv", "0,2\n", "at least 2 points"),
        (
            "p.svg",
            "<svg>\n<polyline points=\"10,10 5,5\"/>\n</svg>",
            "p.svg, line 2",
        ),
        (
            "p.svg",
            "<svg>\n<polyline points=\"10,10 5\"/>\n</svg>",
            "x,y pairs",
        ),
    ];
    for (name, text, expect) in cases {
        let e = read_profile(name, text, None).unwrap_err().to_string();
        assert!(e.contains(expect), "{name} {text:?}: {e}");
    }
    let e = read_profile("p.svg", "<svg><rect/></svg>", None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no <polyline>"), "{e}");
    let e = read_sticks("b.csv", "1,0,1\n1,1,2\n2,0,1\n2,1,1\n1,2,2\n", None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("b.csv, line 5") && e.contains("branch 1"), "{e}");
    let e = whisk_tree(
        &profile(),
        &WhiskParams {
            ribs: 0,
            ..Default::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("ribs") && e.contains("1..360"), "{e}");
}

#[test]
fn whisk_trees_mesh_and_export() {
    let s = whisk_tree(
        &profile(),
        &WhiskParams {
            ribs: 8,
            rings: 3,
            spokes: 2,
            ..Default::default()
        },
    )
    .unwrap();
    let stats = s.stats();
    assert!((stats.height - 8.0).abs() < 0.05, "{}", stats.height);
    assert!(
        (stats.crown_width - 6.0).abs() < 0.1,
        "{}",
        stats.crown_width
    );
    let mesh = crate::mesh::mesh_tree(&s, &Default::default());
    let glb = crate::export::to_glb(&mesh, "whisk", &Default::default()).unwrap();
    let (doc, buffers, _) = gltf::import_slice(&glb).unwrap();
    let reader = doc.meshes().next().unwrap().primitives().next().unwrap();
    let positions = reader
        .reader(|b| Some(&buffers[b.index()]))
        .read_positions()
        .unwrap()
        .count();
    assert!(positions > 1000);
}
