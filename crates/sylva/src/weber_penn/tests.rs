//! Structure tests of the generator on the paper's appendix species and on small hand-made
//! parameter sets.

use super::equations::{Envelope, inside_envelope, shape_ratio};
use super::*;
use crate::skeleton::CrossSection;
use crate::species::builtin;

pub(super) fn opts(seed: u64) -> GenerateOptions {
    GenerateOptions {
        seed,
        ..Default::default()
    }
}

fn polyline_length(sk: &Skeleton, id: StemId) -> f32 {
    sk.sections_of(id)
        .windows(2)
        .map(|w| w[0].position.distance(w[1].position))
        .sum()
}

fn children_of(sk: &Skeleton, id: StemId) -> impl Iterator<Item = &Stem> {
    sk.stems
        .iter()
        .filter(move |s| s.parent == Some(id) && s.clone_of.is_none())
}

const NO_ENVELOPE: Envelope = Envelope {
    peak: 0.5,
    power_low: 0.5,
    power_high: 0.5,
};

#[test]
fn error_diffusion_hits_the_total() {
    let mut e = 0.0;
    let ks: Vec<usize> = (0..100).map(|_| diffuse(0.37, &mut e)).collect();
    let total: usize = ks.iter().sum();
    assert!((36..=38).contains(&total), "{total}");
    assert!(ks.iter().all(|&k| k <= 1));
    // Rates above one give every step at least the floor.
    let mut e = 0.0;
    let ks: Vec<usize> = (0..10).map(|_| diffuse(2.5, &mut e)).collect();
    assert!(ks.iter().all(|&k| k == 2 || k == 3));
    assert_eq!(ks.iter().sum::<usize>(), 25);
}

#[test]
fn quaking_aspen_structure() {
    let mut p = builtin("quaking_aspen").unwrap();
    p.scale_v = 0.0; // S = Scale exactly, so the trunk length is known
    let sk = generate(&p, &opts(3)).unwrap();
    let stats = sk.stats();
    assert_eq!(stats.stems_per_level[0], 1, "one trunk");
    let l1 = stats.stems_per_level[1];
    assert!(
        (49..=51).contains(&l1),
        "about 50 level-1 branches, got {l1}"
    );
    let trunk = &sk.stems[0];
    assert!(
        (trunk.length - 13.0).abs() < 1e-4,
        "trunk length S * 0Length = 13, got {}",
        trunk.length
    );
    let along = polyline_length(&sk, StemId(0));
    assert!((along - 13.0).abs() < 1e-3, "trunk polyline length {along}");
    // Branches start above the bare base (BaseSize 0.4).
    for c in children_of(&sk, StemId(0)) {
        assert!(
            c.offset >= 0.4 * 13.0 - 1e-4,
            "branch at {} below the base",
            c.offset
        );
    }
}

#[test]
fn child_lengths_and_counts_follow_the_formulas() {
    let mut p = builtin("quaking_aspen").unwrap();
    p.scale_v = 0.0;
    let sk = generate(&p, &opts(11)).unwrap();
    let l0 = 13.0f64;
    let lmax1 = p.level[1].length; // 1LengthV = 0
    let lmax2 = p.level[2].length;
    let b2 = p.level[2].branches as f64;
    let mut checked = 0;
    for (i, s) in sk.stems.iter().enumerate() {
        let id = StemId(i as u32);
        match s.level {
            1 => {
                let o = s.offset as f64;
                let want = l0
                    * lmax1
                    * shape_ratio(p.shape, (l0 - o) / (l0 - p.base_size * l0), &NO_ENVELOPE);
                assert!(
                    (s.length as f64 - want).abs() < 1e-3,
                    "level-1 length {} vs {want}",
                    s.length
                );
                // Level-2 count: B (0.2 + 0.8 (L / L_parent) / lmax_parent), error-diffused.
                let want = b2 * (0.2 + 0.8 * (s.length as f64 / l0) / lmax1);
                let got = children_of(&sk, id).count() as f64;
                assert!(
                    (got - want).abs() < 1.0 + 1e-9,
                    "level-2 count {got} vs {want}"
                );
                checked += 1;
            }
            2 => {
                let parent = &sk.stems[s.parent.unwrap().0 as usize];
                let want = lmax2 * (parent.length as f64 - 0.6 * s.offset as f64);
                assert!(
                    (s.length as f64 - want).abs() < 1e-3,
                    "level-2 length {} vs {want}",
                    s.length
                );
            }
            _ => {}
        }
    }
    assert!(checked >= 49);
}

#[test]
fn black_tupelo_reaches_four_levels_and_level3_counts_follow_the_formula() {
    let p = builtin("black_tupelo").unwrap();
    let sk = generate(&p, &opts(1)).unwrap();
    let stats = sk.stats();
    assert_eq!(stats.stems_per_level.len(), 4);
    assert!(
        stats.stems_per_level.iter().all(|&n| n > 0),
        "{:?}",
        stats.stems_per_level
    );
    assert!(stats.leaves > 1000);
    let b3 = p.level[3].branches as f64;
    for (i, s) in sk
        .stems
        .iter()
        .enumerate()
        .filter(|(_, s)| s.level == 2 && s.clone_of.is_none())
    {
        let parent = &sk.stems[s.parent.unwrap().0 as usize];
        let want = b3 * (1.0 - 0.5 * s.offset as f64 / parent.length as f64);
        let got = children_of(&sk, StemId(i as u32)).count() as f64;
        assert!(
            (got - want).abs() < 1.0 + 1e-9,
            "level-3 count {got} vs {want}"
        );
    }
    // Tupelo is 23 +- 5 m.
    assert!(
        (18.0..=29.0).contains(&sk.stems[0].length),
        "{}",
        sk.stems[0].length
    );
}

#[test]
fn same_seed_same_tree_and_seeds_differ() {
    let p = builtin("ca_black_oak").unwrap();
    let a = generate(&p, &opts(5)).unwrap();
    let b = generate(&p, &opts(5)).unwrap();
    let c = generate(&p, &opts(6)).unwrap();
    assert_eq!(a, b);
    assert_ne!(a.sections, c.sections);
}

#[test]
fn a_tree_is_the_same_grown_and_meshed_on_one_thread_or_three() {
    // The oak's trunk splits at its base, so its main branches hang from clones too; the
    // tupelo reaches four levels. One thread takes the plain path, three grow the main
    // branches apart and join them (apart.rs) and mesh bark and leaves at once.
    let on = |threads: usize, id: &str| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        pool.install(|| {
            let params = builtin(id).expect("built-in");
            let options = GenerateOptions {
                quality: 0.3,
                ..opts(3)
            };
            let skeleton = generate(&params, &options).expect("grows");
            let mesh = crate::mesh::mesh_tree(
                &skeleton,
                &crate::mesh::MeshOptions::for_species(&params, 0.3),
            );
            (skeleton, mesh)
        })
    };
    for id in ["ca_black_oak", "black_tupelo"] {
        let (one, one_mesh) = on(1, id);
        let (three, three_mesh) = on(3, id);
        assert!(one.stems.len() > 1000 && !one.leaves.is_empty(), "{id}");
        if id == "ca_black_oak" {
            assert!(
                one.stems
                    .iter()
                    .any(|s| s.level == 0 && s.clone_of.is_some())
            );
        }
        assert!(one == three, "{id}: the skeletons differ");
        assert!(one_mesh == three_mesh, "{id}: the meshes differ");
    }
}

#[test]
fn a_deep_parameter_does_not_reshuffle_the_trunk() {
    let p = builtin("black_tupelo").unwrap();
    let mut q = p.clone();
    q.level[3].down_angle = 80.0;
    q.level[3].curve_v = 10.0;
    let a = generate(&p, &opts(2)).unwrap();
    let b = generate(&q, &opts(2)).unwrap();
    let upper = |sk: &Skeleton| -> Vec<CrossSection> {
        sk.stems
            .iter()
            .filter(|s| s.level <= 2)
            .flat_map(|s| sk.sections[s.sections.start as usize..s.sections.end as usize].to_vec())
            .collect()
    };
    assert_eq!(upper(&a), upper(&b), "levels 0-2 must not change");
    assert_ne!(a.sections, b.sections, "level 3 did change");
}

#[test]
fn truncated_levels_show_the_same_stems() {
    let p = builtin("black_tupelo").unwrap();
    let full = generate(&p, &opts(4)).unwrap();
    let o = GenerateOptions {
        max_levels: Some(2),
        ..opts(4)
    };
    let cut = generate(&p, &o).unwrap();
    assert_eq!(cut.stats().stems_per_level.len(), 2);
    assert!(cut.leaves.is_empty());
    assert_eq!(cut.sections_of(StemId(0)), full.sections_of(StemId(0)));
}

#[test]
fn children_start_inside_their_parent() {
    let p = builtin("black_tupelo").unwrap();
    let sk = generate(&p, &opts(9)).unwrap();
    for s in sk
        .stems
        .iter()
        .filter(|s| s.clone_of.is_none() && s.parent.is_some())
    {
        let parent = s.parent.unwrap();
        let pl = sk.stems[parent.0 as usize].length;
        let (axis, _, r) = sk.sample(parent, s.offset / pl);
        let base = sk.sections[s.sections.start as usize];
        assert!(base.position.distance(axis) <= r + 1e-4);
        assert!(
            base.radius <= r + 1e-5,
            "child thicker than its parent there"
        );
    }
}

#[test]
fn trunk_has_flare_rings_near_the_ground() {
    let p = builtin("black_tupelo").unwrap();
    let sk = generate(&p, &opts(0)).unwrap();
    let trunk = sk.sections_of(StemId(0));
    let low = trunk.iter().filter(|c| c.z < 0.125).count();
    assert!(low >= 5, "{low} rings in the flare zone");
    let r0 = trunk[0].radius as f64;
    let r_above = sk.sample(StemId(0), 0.125).2 as f64;
    // Flare 1: the ground radius is (1 + Flare * 0.99) times the tapered radius there.
    let taper = |z| super::equations::taper_radius(1.0, 10.0, p.level[0].taper, z);
    let want = (1.0 + p.flare * 0.99) * taper(0.0) / taper(0.125);
    assert!(
        (r0 / r_above - want).abs() < 1e-3,
        "{} vs {want}",
        r0 / r_above
    );
}

#[test]
fn splits_make_clones_that_keep_the_level() {
    let mut p = TreeParams {
        levels: 1,
        leaves: 0,
        ..TreeParams::default()
    };
    p.level[0].curve_res = 11;
    p.level[0].seg_splits = 0.5;
    p.level[0].split_angle = 20.0;
    let sk = generate(&p, &opts(2)).unwrap();
    let clones: Vec<_> = sk.stems.iter().filter(|s| s.clone_of.is_some()).collect();
    assert!(!clones.is_empty());
    assert!(
        clones
            .iter()
            .all(|c| c.level == 0 && c.length == sk.stems[0].length)
    );
    // The original splits about 0.5 per segment over its 10 testable segments.
    let of_original = clones
        .iter()
        .filter(|c| c.clone_of == Some(StemId(0)))
        .count();
    assert!((4..=6).contains(&of_original), "{of_original}");
    // Base splits: exactly 0BaseSplits clones at the end of the first segment.
    let mut p = TreeParams {
        levels: 1,
        base_splits: 3,
        ..TreeParams::default()
    };
    p.level[0].curve_res = 5;
    let sk = generate(&p, &opts(2)).unwrap();
    assert_eq!(sk.stems.len(), 4);
    assert!(sk.stems[1..].iter().all(|s| s.clone_of == Some(StemId(0))));
}

fn every_stem_end_inside(p: &TreeParams, sk: &Skeleton, scale: f64) -> bool {
    let env = Envelope {
        peak: p.prune_width_peak,
        power_low: p.prune_power_low,
        power_high: p.prune_power_high,
    };
    sk.stems.iter().filter(|s| s.level >= 1).all(|s| {
        let c = sk.sections[s.sections.end as usize - 1].position;
        inside_envelope(
            (c.x as f64).hypot(c.y as f64),
            c.z as f64,
            scale,
            p.base_size,
            p.prune_width,
            &env,
        )
    })
}

#[test]
fn full_pruning_keeps_every_stem_end_inside_the_envelope() {
    let mut p = builtin("weeping_willow").unwrap();
    p.scale_v = 0.0;
    p.z_scale_v = 0.0;
    p.levels = 3;
    let sk = generate(&p, &opts(1)).unwrap();
    assert!(every_stem_end_inside(&p, &sk, p.scale));
    p.prune_ratio = 0.0;
    let unpruned = generate(&p, &opts(1)).unwrap();
    assert!(
        !every_stem_end_inside(&p, &unpruned, p.scale),
        "without pruning some stems stick out"
    );
}

#[test]
fn zero_prune_ratio_changes_nothing() {
    let mut p = builtin("quaking_aspen").unwrap();
    let a = generate(&p, &opts(8)).unwrap();
    p.prune_width = 0.01;
    p.prune_width_peak = 0.9;
    let b = generate(&p, &opts(8)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn leaf_quality_trades_count_for_size() {
    let p = builtin("quaking_aspen").unwrap();
    let a = generate(&p, &opts(1)).unwrap();
    let o = GenerateOptions {
        quality: 0.5,
        ..opts(1)
    };
    let b = generate(&p, &o).unwrap();
    let ratio = b.leaves.len() as f64 / a.leaves.len() as f64;
    assert!((ratio - 0.5).abs() < 0.05, "{ratio}");
    let size = b.leaves[0].length / a.leaves[0].length;
    assert!((size - 2f32.sqrt()).abs() < 1e-4);
    assert!((a.leaves[0].length - 0.17).abs() < 1e-6);
    assert!((a.leaves[0].width - 0.17).abs() < 1e-6);
}

#[test]
fn negative_modes_make_fans_helices_and_alternation() {
    // Leaf fan: Leaves = -5 puts five leaves at every leaf-bearing stem's tip.
    let mut p = TreeParams {
        levels: 2,
        leaves: -5,
        ..TreeParams::default()
    };
    p.level[1].branches = 4;
    let sk = generate(&p, &opts(0)).unwrap();
    let bearing = sk.stems.iter().filter(|s| s.level == 1).count();
    assert_eq!(sk.leaves.len(), 5 * bearing);
    // Helix: a negative CurveV winds the stem around its axis.
    let mut h = TreeParams {
        levels: 1,
        ..TreeParams::default()
    };
    h.level[0].curve_v = -30.0;
    let sk = generate(&h, &opts(0)).unwrap();
    let trunk = sk.sections_of(StemId(0));
    assert!(trunk.len() >= 3 * 10);
    let off_axis = trunk
        .iter()
        .map(|c| c.position.truncate().length())
        .fold(0.0, f32::max);
    assert!(off_axis > 0.05, "{off_axis}");
    // Branch fan: negative nBranches puts the children at the parent's tip.
    let mut f = TreeParams {
        levels: 2,
        ..TreeParams::default()
    };
    f.level[1].branches = -3;
    let sk = generate(&f, &opts(0)).unwrap();
    let kids: Vec<_> = children_of(&sk, StemId(0)).collect();
    assert_eq!(kids.len(), 3);
    assert!(
        kids.iter()
            .all(|k| (k.offset - sk.stems[0].length).abs() < 1e-4)
    );
}

#[test]
fn runaway_parameters_hit_the_budget() {
    let mut p = builtin("quaking_aspen").unwrap();
    p.level[1].branches = 100_000;
    p.level[2].branches = 100_000;
    let o = GenerateOptions {
        max_triangles: 200_000,
        ..opts(0)
    };
    let err = generate(&p, &o).unwrap_err();
    assert!(matches!(err, GenerateError::Budget { .. }), "{err}");
    assert!(err.to_string().contains("--max-triangles"));
    let mut q = builtin("quaking_aspen").unwrap();
    q.levels = 50;
    assert!(generate(&q, &opts(0)).is_err());
}

#[test]
fn every_builtin_species_generates_at_its_real_size() {
    for id in crate::species::builtin_ids() {
        let p = builtin(id).unwrap();
        let sk = generate(&p, &opts(0)).unwrap();
        let h = sk.stats().height as f64;
        // Heights within the species' range: Scale +- ScaleV, with room for curvature and crowns.
        let lo = (p.scale - p.scale_v) * p.level[0].length * 0.5;
        let hi = (p.scale + p.scale_v) * 1.5;
        assert!(h >= lo && h <= hi, "{id}: height {h} outside {lo}..{hi}");
    }
}

/// Angle (degrees) between a child's initial direction and its parent's axis where it attaches.
fn down_angle_of(sk: &Skeleton, child: &Stem) -> f32 {
    let parent = child.parent.unwrap();
    let (_, q_parent, _) = sk.sample(parent, child.offset / sk.stems[parent.0 as usize].length);
    let d = sk.sections[child.sections.start as usize].orientation * Vec3::Z;
    (q_parent * Vec3::Z)
        .dot(d)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

#[test]
fn negative_down_angle_variation_spreads_along_the_parent() {
    // Black Tupelo: 1DownAngle 60, 1DownAngleV -40: about 100 degrees at the crown base,
    // 36 at the top (spec section 5), with no random term.
    let p = builtin("black_tupelo").unwrap();
    let sk = generate(&p, &opts(3)).unwrap();
    let l0 = sk.stems[0].length as f64;
    for child in children_of(&sk, StemId(0)) {
        let r = ((l0 - child.offset as f64) / (l0 * (1.0 - p.base_size))).clamp(0.0, 1.0);
        let want = 60.0 - 40.0 * (1.0 - 2.0 * shape_ratio(0, r, &NO_ENVELOPE));
        let got = down_angle_of(&sk, child) as f64;
        assert!(
            (got - want).abs() < 0.5,
            "at {} m: {got} vs {want}",
            child.offset
        );
    }
}

#[test]
fn negative_rotate_alternates_sides() {
    let mut p = TreeParams {
        levels: 2,
        ..TreeParams::default()
    };
    p.level[0].curve_v = 0.0;
    p.level[1].rotate = -90.0; // azimuth +-90: children on alternating sides, in one plane
    p.level[1].rotate_v = 0.0;
    p.level[1].down_angle = 90.0;
    let sk = generate(&p, &opts(0)).unwrap();
    let dirs: Vec<Vec3> = children_of(&sk, StemId(0))
        .map(|c| sk.sections[c.sections.start as usize].orientation * Vec3::Z)
        .collect();
    assert!(dirs.len() >= 5);
    for w in dirs.windows(2) {
        assert!(
            w[0].dot(w[1]) < -0.99,
            "consecutive children on opposite sides: {} {}",
            w[0],
            w[1]
        );
    }
    // A positive rotate spirals instead: 140 degrees between successive children.
    p.level[1].rotate = 140.0;
    let sk = generate(&p, &opts(0)).unwrap();
    let dirs: Vec<Vec3> = children_of(&sk, StemId(0))
        .map(|c| sk.sections[c.sections.start as usize].orientation * Vec3::Z)
        .collect();
    for w in dirs.windows(2) {
        let angle = w[0].dot(w[1]).clamp(-1.0, 1.0).acos().to_degrees();
        assert!((angle - 140.0).abs() < 0.5, "{angle}");
    }
}
