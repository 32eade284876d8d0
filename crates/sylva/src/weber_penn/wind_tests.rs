//! Wind on the generator: calm is no wind to the byte, gusts move only the geometry, thin
//! outer branches sway more than the trunk, and the sway oscillates over seconds.

use super::tests::opts;
use super::*;
use crate::species::builtin;

fn windy(speed: f64, gust: f64, time: f64) -> GenerateOptions {
    GenerateOptions {
        wind: Wind { speed, gust, time },
        ..opts(4)
    }
}

/// Mean angle (degrees) between each stem's tip direction in `a` and in `b`, per level.
fn tip_turn_per_level(a: &Skeleton, b: &Skeleton) -> Vec<f32> {
    let mut sums = [(0.0f32, 0usize); 8];
    for (i, s) in a.stems.iter().enumerate() {
        let id = StemId(i as u32);
        let da = a.sections_of(id).last().unwrap().orientation * Vec3::Z;
        let db = b.sections_of(id).last().unwrap().orientation * Vec3::Z;
        let e = &mut sums[s.level as usize];
        e.0 += da.dot(db).clamp(-1.0, 1.0).acos().to_degrees();
        e.1 += 1;
    }
    sums.iter()
        .filter(|(_, n)| *n > 0)
        .map(|(t, n)| t / *n as f32)
        .collect()
}

#[test]
fn calm_wind_is_byte_identical_to_no_wind() {
    let p = builtin("quaking_aspen").unwrap();
    let still = generate(&p, &opts(4)).unwrap();
    assert_eq!(generate(&p, &windy(0.0, 0.0, 12.5)).unwrap(), still);
}

#[test]
fn wind_moves_only_the_geometry_and_grows_with_speed() {
    let p = builtin("quaking_aspen").unwrap();
    let still = generate(&p, &opts(4)).unwrap();
    let mut previous = 0.0;
    for speed in [1.0, 3.0, 9.0] {
        let blown = generate(&p, &windy(speed, 0.0, 2.0)).unwrap();
        // Same tree: the same stems and leaves, only bent.
        assert_eq!(blown.stems.len(), still.stems.len());
        assert_eq!(blown.leaves.len(), still.leaves.len());
        let moved: f32 = blown
            .leaves
            .iter()
            .zip(&still.leaves)
            .map(|(a, b)| a.position.distance(b.position))
            .sum::<f32>()
            / still.leaves.len() as f32;
        assert!(
            moved > previous,
            "speed {speed}: mean leaf displacement {moved} <= {previous}"
        );
        previous = moved;
    }
    // Same seed and time: same geometry.
    assert_eq!(
        generate(&p, &windy(3.0, 1.0, 7.0)).unwrap(),
        generate(&p, &windy(3.0, 1.0, 7.0)).unwrap()
    );
    // Another moment: another pose.
    assert_ne!(
        generate(&p, &windy(3.0, 1.0, 7.0)).unwrap().sections,
        generate(&p, &windy(3.0, 1.0, 8.0)).unwrap().sections
    );
}

#[test]
fn thin_outer_branches_sway_more_than_the_trunk() {
    let p = builtin("black_tupelo").unwrap();
    let still = generate(&p, &opts(4)).unwrap();
    let blown = generate(&p, &windy(4.0, 2.0, 3.0)).unwrap();
    let turn = tip_turn_per_level(&still, &blown);
    assert!(turn.len() == 4, "{turn:?}");
    assert!(
        turn[2] > turn[0] && turn[3] > turn[0],
        "tip turn per level {turn:?}"
    );
}

#[test]
fn the_sway_oscillates_over_seconds() {
    // The pose changes visibly within a second (not over hours) and comes back, bounded.
    let p = builtin("quaking_aspen").unwrap();
    let still = generate(&p, &opts(4)).unwrap();
    let at = |t| tip_turn_per_level(&still, &generate(&p, &windy(5.0, 0.0, t)).unwrap())[1];
    let poses: Vec<f32> = (0..8).map(|i| at(i as f64 * 0.5)).collect();
    let (lo, hi) = poses
        .iter()
        .fold((f32::MAX, 0.0f32), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(hi - lo > 0.5, "branch tips barely move over 4 s: {poses:?}");
    assert!(hi < 90.0, "{poses:?}");
}

#[test]
fn fast_atan2_matches_libm_all_around_the_circle() {
    let mut worst = 0.0f32;
    for i in 0..3600 {
        let a = (i as f32 / 3600.0 - 0.5) * std::f32::consts::TAU;
        for r in [1e-3f32, 0.7, 1.0, 250.0] {
            let (y, x) = (r * a.sin(), r * a.cos());
            worst = worst.max((super::children::atan2(y, x) - y.atan2(x)).abs());
        }
    }
    assert!(worst < 2e-5, "worst error {worst} rad");
    assert_eq!(super::children::atan2(0.0, 0.0), 0.0);
    assert!((super::children::atan2(0.0, -1.0) - std::f32::consts::PI).abs() < 1e-6);
}
