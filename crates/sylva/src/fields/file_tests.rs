//! Fields' files: `.tree` files round-trip byte for byte and name a malformed line, point
//! clouds (PLY, XYZ) give a known tree's trunk and lobes, and runaway rules stop at a budget.

use super::pipeline::Kind;
use super::points::{Up, coverage, fit, read_points};
use super::tests::{APPENDIX, oak};
use super::*;
use crate::rng::StreamKey;
use glam::Vec3;

#[test]
fn tree_files_round_trip_byte_for_byte() {
    let file = TreeFile::parse(APPENDIX, "cherry.tree").unwrap();
    assert_eq!(file.tree_type, "Cherry Tree");
    assert_eq!(file.seed, 100);
    assert_eq!(file.branches.len(), 4);
    assert_eq!(file.branches[3].parent, 2);
    assert_eq!(file.branches[1].end, [1.800362, -0.3780254, 4.764441]);
    assert_eq!(file.lobes[1].radius, 1.0);
    assert_eq!(file.to_text(), APPENDIX);
    // Windows line endings, no final newline, and spacing of its own survive too.
    let crlf = APPENDIX
        .replace('\n', "\r\n")
        .replace("1.110022 ", "1.110022   ");
    let crlf = crlf.trim_end().to_string();
    assert_eq!(TreeFile::parse(&crlf, "c.tree").unwrap().to_text(), crlf);
    // A changed value is written fresh; the rest stays as read.
    let mut edited = TreeFile::parse(APPENDIX, "cherry.tree").unwrap();
    edited.lobes[0].radius = 1.5;
    let text = edited.to_text();
    assert!(
        text.contains("\n2.307282 0.5082518 4.534246 1.5\n"),
        "{text}"
    );
    assert_eq!(text.lines().count(), APPENDIX.lines().count());
    // What Sylva saves reads back to the same placement and the same bytes.
    let rules = oak();
    let placement = auto_placement(&rules, 9);
    let saved = TreeFile::from_placement(&rules.name, 9, &placement).to_text();
    let again = TreeFile::parse(&saved, "oak.tree").unwrap();
    assert_eq!(again.to_text(), saved);
    let back = again.placement();
    for (a, b) in back.trunks.iter().zip(&placement.trunks) {
        assert!(a.start.distance(b.start) < 1e-6 && a.end.distance(b.end) < 1e-6);
        assert_eq!(a.parent, b.parent);
    }
    assert_eq!(back.lobes, placement.lobes);
}

#[test]
fn the_appendix_tree_grows_with_its_species() {
    let file = TreeFile::parse(APPENDIX, "cherry.tree").unwrap();
    let rules = builtin(file.tree_type.trim()).unwrap();
    let placement = file.placement();
    // Y-up room coordinates become Z-up, the first trunk starting at the origin and rising.
    assert_eq!(placement.trunks[0].start, Vec3::ZERO);
    assert!(placement.trunks[0].end.z > 0.5);
    let t = grow(&rules, file.seed as u64, &placement).unwrap();
    assert_eq!(t.lobes.len(), 2);
    // Neither lobe holds a trunk, so each gets one connected to the nearest trunk end.
    let trunks = t.branches.iter().filter(|b| b.kind == Kind::Trunk).count();
    assert_eq!(trunks, 4 + 2);
    for (i, lobe) in t.lobes.iter().enumerate() {
        let reached = t
            .branches
            .iter()
            .filter(|b| b.lobe == Some(i) && b.target.is_some())
            .count();
        assert_eq!(reached, 6, "lobe {i}");
        assert!(
            t.leaves
                .iter()
                .any(|l| l.position.distance(lobe.centre) <= lobe.radius * 1.01)
        );
    }
}

#[test]
fn malformed_tree_files_name_the_line() {
    let cases = [
        (
            APPENDIX.replace("#BRANCHES", "#BRANCH"),
            "line 3",
            "#BRANCHES",
        ),
        (APPENDIX.replace("100", "ten"), "line 2", "seed"),
        (
            APPENDIX.replace("3 2 0.7252637", "3 9 0.7252637"),
            "line 7",
            "parent 9",
        ),
        (
            APPENDIX.replace("4.99926 1\n3", "4.99926 x\n3"),
            "line 6",
            "ninth value",
        ),
        (
            APPENDIX.replace(
                "0.4439276 1.201943 4.939856 1",
                "0.4439276 1.201943 4.939856 0",
            ),
            "line 10",
            "radius",
        ),
        (
            APPENDIX.replace(
                "1 0 1.14952 -0.8700994 4.896452 1.800362 -0.3780254",
                "1 0 1.14952 -0.8700994 4.896452",
            ),
            "line 5",
            "found 7 values",
        ),
        (
            APPENDIX.replace(
                "#LEAF LOBES\n2.307282 0.5082518 4.534246 1\n0.4439276 1.201943 4.939856 1\n",
                "",
            ),
            "line 8",
            "LEAF LOBES",
        ),
        ("Cherry Tree\n".to_string(), "line 2", "seed"),
    ];
    for (text, line, what) in cases {
        let e = TreeFile::parse(&text, "t.tree").unwrap_err().to_string();
        assert!(
            e.contains(&format!("t.tree, {line}")) && e.contains(what),
            "{line}: {e}"
        );
    }
}

/// Points filling a sphere.
fn ball(centre: Vec3, r: f32, n: usize, seed: u64) -> Vec<Vec3> {
    let mut random = StreamKey::from_seed(seed).stream();
    let mut out = Vec::new();
    while out.len() < n {
        let v = Vec3::new(
            random.var(1.0) as f32,
            random.var(1.0) as f32,
            random.var(1.0) as f32,
        );
        if v.length() <= 1.0 {
            out.push(centre + v * r);
        }
    }
    out
}

#[test]
fn a_known_tree_s_point_cloud_gives_its_trunk_and_lobes() {
    // A trunk 2 m tall and 0.2 m across, three lobes of crown above it.
    let truth = [
        Lobe {
            centre: Vec3::new(0.0, 0.0, 3.0),
            radius: 1.0,
        },
        Lobe {
            centre: Vec3::new(1.6, 0.3, 3.7),
            radius: 0.8,
        },
        Lobe {
            centre: Vec3::new(-1.4, 0.5, 3.6),
            radius: 0.7,
        },
    ];
    let mut random = StreamKey::from_seed(1).stream();
    let mut cloud: Vec<Vec3> = (0..600)
        .map(|i| {
            let a = random.unit() as f32 * std::f32::consts::TAU;
            Vec3::new(
                5.0 + 0.1 * a.cos(),
                -2.0 + 0.1 * a.sin(),
                2.0 * i as f32 / 600.0,
            )
        })
        .collect();
    for (i, l) in truth.iter().enumerate() {
        let n = (3000.0 * l.radius.powi(3)) as usize;
        cloud.extend(ball(
            l.centre + Vec3::new(5.0, -2.0, 0.0),
            l.radius,
            n,
            i as u64,
        ));
    }
    let f = fit(&cloud, None, 0);
    assert!(
        (f.crown_base - 2.0).abs() < 0.25,
        "crown base {}",
        f.crown_base
    );
    let trunk = f.placement.trunks[0];
    assert_eq!(trunk.start, Vec3::ZERO);
    assert!(trunk.end.truncate().length() < 0.05 && (trunk.end.z - f.crown_base).abs() < 1e-4);
    let lobes = &f.placement.lobes;
    let cover = coverage(&f.canopy, lobes);
    assert!(cover >= 0.9, "lobes cover {cover} of the canopy");
    assert_eq!(lobes.len(), 3, "{lobes:?}");
    for l in &truth {
        let nearest = lobes
            .iter()
            .map(|m| m.centre.distance(l.centre))
            .fold(f32::MAX, f32::min);
        assert!(nearest < 0.35 * l.radius, "{l:?}: {nearest}");
    }
    let volume: f32 = lobes.iter().map(|l| l.radius.powi(3)).sum();
    assert!(volume < 1.5 * truth.iter().map(|l| l.radius.powi(3)).sum::<f32>());

    // A grown lobe tree sampled at its leaves: the fitted lobes hold at least 90% of them.
    let rules = oak();
    let t = grow(&rules, 3, &placement_for_lobes(&rules, 3, truth.to_vec())).unwrap();
    let mut cloud: Vec<Vec3> = t.leaves.iter().map(|l| l.position).collect();
    for b in t
        .branches
        .iter()
        .filter(|b| b.kind == Kind::Trunk && b.parent.is_none())
    {
        for k in 0..200 {
            cloud.push(b.points[0].lerp(b.points[1], k as f32 / 200.0));
        }
    }
    let f = fit(&cloud, None, 0);
    let leaves: Vec<Vec3> = t.leaves.iter().map(|l| l.position).collect();
    let cover = coverage(&leaves, &f.placement.lobes);
    assert!(cover >= 0.9, "{cover}: {:?}", f.placement.lobes);
}

#[test]
fn point_files_read_ply_and_xyz_and_report_bad_lines() {
    let pts: Vec<[f32; 3]> = (0..12).map(|i| [i as f32, 2.0 * i as f32, 0.5]).collect();
    let ascii = format!(
        "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nend_header\n{}",
        pts.iter()
            .map(|p| format!("{} {} {} 200\n", p[0], p[1], p[2]))
            .collect::<String>()
    );
    let a = read_points("c.ply", ascii.as_bytes(), Up::Z).unwrap();
    assert_eq!(a[3], Vec3::new(3.0, 6.0, 0.5));
    let mut binary = b"ply\nformat binary_little_endian 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for p in &pts {
        for c in p {
            binary.extend(c.to_le_bytes());
        }
        binary.push(7);
    }
    assert_eq!(read_points("c.ply", &binary, Up::Z).unwrap(), a);
    // Y up becomes Z up.
    let y = read_points("c.ply", &binary, Up::Y).unwrap();
    assert_eq!(y[3], Vec3::new(3.0, -0.5, 6.0));
    let xyz: String = pts
        .iter()
        .map(|p| format!("{} {} {}\n", p[0], p[1], p[2]))
        .collect();
    assert_eq!(read_points("c.xyz", xyz.as_bytes(), Up::Z).unwrap(), a);
    // Bad input.
    let e = read_points("c.ply", &binary[..binary.len() - 5], Up::Z)
        .unwrap_err()
        .to_string();
    assert!(e.contains("ends early"), "{e}");
    let bad = ascii.replace("5 10 0.5 200", "5 ten 0.5 200");
    let e = read_points("c.ply", bad.as_bytes(), Up::Z)
        .unwrap_err()
        .to_string();
    assert!(e.contains("c.ply, line 14") && e.contains("`ten`"), "{e}");
    let e = read_points("c.xyz", b"1 2 3\n4 5\n", Up::Z)
        .unwrap_err()
        .to_string();
    assert!(e.contains("c.xyz, line 2"), "{e}");
    let e = read_points(
        "c.ply",
        b"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nend_header\n1\n2\n",
        Up::Z,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("`x`, `y` and `z`"), "{e}");
}

#[test]
fn runaway_rules_stop_at_a_budget_with_a_message() {
    let mut r = oak();
    r.num_leaf_points_on_lobe = 5000;
    r.layout.leaf_size = 0.002;
    let e = grow(&r, 0, &auto_placement(&r, 0)).unwrap_err().to_string();
    assert!(
        e.contains("2000000 leaves") && e.contains("leaf_size"),
        "{e}"
    );
}
