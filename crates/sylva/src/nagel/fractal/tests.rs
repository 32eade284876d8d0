use super::*;
use crate::drawing::write_vec;

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).abs().max_element() <= tol
}

#[test]
// The expected values are worked by hand to six places, √2/2 among them.
#[allow(clippy::approx_constant)]
fn honda_equations_match_hand_computed_points() {
    // Mother (0,0,0)→(1,0,1): U=1, V=0, W=1, L=√2, √(U²+V²)=1.
    let (a, b) = (DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0));
    // θ=90°, R=0.5: X = 1 + 0.5(0 − √2·0·1) = 1, Y = 0 + 0.5(0 + √2·1·1) = 0.70711, Z = 1 + 0.
    let c = honda_daughter(a, b, 90f64.to_radians(), 0.5);
    assert!(close(c, DVec3::new(1.0, 0.707107, 1.0), 1e-6), "{c}");
    // θ=30°, R=1: X = 1 + cos30 = 1.866025, Y = √2·sin30 = 0.707107, Z = 1 + cos30.
    let c = honda_daughter(a, b, 30f64.to_radians(), 1.0);
    assert!(
        close(c, DVec3::new(1.866025, 0.707107, 1.866025), 1e-6),
        "{c}"
    );
    // Nagel's listing starts from A=(139,104,5), B=(140,105,48): U=V=1, W=43, L=√1851=43.02325,
    // √2=1.414214. θ1=−35°, R1=0.73: cos=0.819152, sin=−0.573576.
    // X = 140 + 0.73(0.819152 + 43.02325·0.573576/1.414214) = 140 + 0.73·18.268575 = 153.33606
    // Y = 105 + 0.73(0.819152 − 17.449423) = 92.86000
    // Z = 48 + 0.73·43·0.819152 = 73.71320
    let c = honda_daughter(
        DVec3::new(139.0, 104.0, 5.0),
        DVec3::new(140.0, 105.0, 48.0),
        (-35f64).to_radians(),
        0.73,
    );
    assert!(
        close(c, DVec3::new(153.33606, 92.86000, 73.71320), 2e-4),
        "{c}"
    );
    // θ=0 continues straight on, R times as long.
    let c = honda_daughter(a, b, 0.0, 0.5);
    assert!(close(c, DVec3::new(1.5, 0.0, 1.5), 1e-12));
}

#[test]
fn daughters_are_r_times_as_long_and_turned_by_theta() {
    let mut random = StreamKey::from_seed(3).stream();
    for _ in 0..500 {
        let a = DVec3::new(random.var(5.0), random.var(5.0), random.var(5.0));
        let b = a + DVec3::new(random.var(2.0), random.var(2.0), random.var(2.0) + 0.01);
        let theta = random.var(3.0);
        let r = random.unit() * 1.4 + 0.05;
        let c = honda_daughter(a, b, theta, r);
        let (m, d) = (b - a, c - b);
        assert!((d.length() - r * m.length()).abs() < 1e-9 * (1.0 + m.length()));
        let angle = m.angle_between(d);
        assert!((angle - theta.abs()).abs() < 1e-6, "{angle} vs {theta}");
    }
    // A vertical mother turns its daughters toward +X.
    let c = honda_daughter(DVec3::ZERO, DVec3::Z, 90f64.to_radians(), 1.0);
    assert!(close(c, DVec3::new(1.0, 0.0, 1.0), 1e-12));
}

fn segments(params: &FractalParams) -> Vec<FractalSegment> {
    let fractal = params.build().unwrap();
    let mut out = Vec::new();
    fractal.stream(&mut |s: &FractalSegment| out.push(*s));
    out
}

#[test]
fn depth_d_gives_two_to_the_d_tips() {
    for depth in 0..=10 {
        let params = FractalParams {
            depth,
            ..Default::default()
        };
        let all = segments(&params);
        let tips = all.iter().filter(|s| s.generation == depth).count();
        assert_eq!(tips, 1 << depth, "depth {depth}");
        assert_eq!(all.len(), (1 << (depth + 1)) - 1);
        let fractal = params.build().unwrap();
        assert_eq!(fractal.tip_count(), 1 << depth);
        assert_eq!(fractal.segment_count() as usize, all.len());
    }
    // Ten daughters on each of the 8 last mothers at depth 4: 80 tips.
    let params = FractalParams {
        depth: 4,
        tip_daughters: 10,
        ..Default::default()
    };
    let all = segments(&params);
    assert_eq!(all.iter().filter(|s| s.generation == 4).count(), 80);
    assert_eq!(all.len(), 1 + 2 + 4 + 8 + 80);
}

/// The obvious way: hold each generation in a list and derive the next from it.
fn in_memory(params: &FractalParams) -> Vec<FractalSegment> {
    let fractal = params.build().unwrap();
    let mut out = Vec::new();
    let trunk = (DVec3::ZERO, DVec3::new(0.0, 0.0, params.trunk_length));
    let mut generation = vec![trunk];
    let push = |out: &mut Vec<FractalSegment>, g: u32, gen_: &[(DVec3, DVec3)]| {
        for (i, s) in gen_.iter().enumerate() {
            out.push(FractalSegment {
                generation: g,
                index: i as u64,
                start: s.0.as_vec3(),
                end: s.1.as_vec3(),
                radius: fractal.radius(g),
                end_radius: fractal.end_radius(g),
            });
        }
    };
    push(&mut out, 0, &generation);
    for g in 1..=params.depth {
        let per = if g == params.depth {
            params.tip_daughters
        } else {
            2
        };
        let mut next = Vec::new();
        for &(a, b) in &generation {
            for _ in 0..per {
                let idx = next.len() as u64;
                next.push((b, fractal.daughter(a, b, g, idx)));
            }
        }
        push(&mut out, g, &next);
        generation = next;
    }
    out
}

#[test]
fn streaming_equals_the_in_memory_tree() {
    for params in [
        FractalParams {
            depth: 9,
            ..Default::default()
        },
        FractalParams {
            depth: 7,
            theta1: -45.0,
            theta2: 20.0,
            r1: 0.76,
            r2: 0.6,
            tip_daughters: 6,
            length_variation: 0.2,
            angle_variation: 12.0,
            seed: 5,
            ..Default::default()
        },
    ] {
        assert_eq!(segments(&params), in_memory(&params));
    }
}

#[test]
fn streamed_vector_file_equals_the_skeletons() {
    let params = FractalParams {
        depth: 8,
        angle_variation: 5.0,
        leaves: true,
        ..Default::default()
    };
    let fractal = params.build().unwrap();
    let streamed = write_vec(&fractal, Vec::new()).unwrap();
    let skeleton = fractal.skeleton();
    let stored = write_vec(&skeleton, Vec::new()).unwrap();
    assert_eq!(streamed, stored);
    // The drawings agree too, stroke widths included.
    let options = crate::drawing::DrawOptions::default();
    assert_eq!(
        crate::drawing::draw_svg(&fractal, &options),
        crate::drawing::draw_svg(&skeleton, &options)
    );
    let text = String::from_utf8(streamed).unwrap();
    // Every segment is an `L`; the 256 leaves are closed 4-sided loops.
    let l = text.lines().filter(|l| l.starts_with('L')).count();
    assert_eq!(l, 511 + 256 * 4);
}

#[test]
fn skeleton_links_each_branch_to_its_mother_tip() {
    let fractal = FractalParams {
        depth: 6,
        tip_daughters: 3,
        ..Default::default()
    }
    .build()
    .unwrap();
    let s = fractal.skeleton();
    assert_eq!(s.stems.len() as u64, fractal.segment_count());
    assert_eq!(s.stats().stems_per_level, vec![1, 2, 4, 8, 16, 32, 96]);
    for (i, stem) in s.stems.iter().enumerate().skip(1) {
        let parent = stem.parent.unwrap();
        assert!(parent.0 < i as u32);
        let mother_tip = s.sections_of(parent)[1].position;
        let base = s.sections_of(StemId(i as u32))[0].position;
        assert_eq!(mother_tip, base);
        assert_eq!(s.stems[parent.0 as usize].level + 1, stem.level);
    }
}

#[test]
fn pipe_model_keeps_area_across_forks() {
    let fractal = FractalParams {
        depth: 5,
        tip_daughters: 4,
        ..Default::default()
    }
    .build()
    .unwrap();
    for g in 0..5 {
        let per = if g == 4 { 4.0 } else { 2.0 };
        let mother = fractal.radius(g).powi(2);
        let daughters = per * fractal.radius(g + 1).powi(2);
        assert!((mother - daughters).abs() < 1e-6 * mother, "generation {g}");
    }
    assert!((fractal.radius(0) - 0.12).abs() < 1e-7);
}

#[test]
fn variation_is_seeded_and_bounded() {
    let base = FractalParams {
        depth: 6,
        length_variation: 0.2,
        angle_variation: 10.0,
        ..Default::default()
    };
    let a = segments(&base);
    assert_eq!(a, segments(&base));
    let b = segments(&FractalParams {
        seed: 1,
        ..base.clone()
    });
    assert_ne!(a, b);
    let plain = segments(&FractalParams {
        length_variation: 0.0,
        angle_variation: 0.0,
        ..base.clone()
    });
    // Each daughter's ratio stays within ±20% of R1 or R2.
    for (s, p) in a.iter().zip(&plain).skip(1) {
        assert_eq!(s.generation, p.generation);
        let parent = a
            .iter()
            .find(|m| m.end == s.start && m.generation + 1 == s.generation)
            .unwrap();
        let ratio = s.start.distance(s.end) / parent.start.distance(parent.end);
        let r = if s.index % 2 == 0 { 0.73 } else { 0.83 };
        assert!(
            ratio >= r * 0.8 - 1e-4 && ratio <= r * 1.2 + 1e-4,
            "{ratio}"
        );
    }
}

#[test]
fn bad_controls_are_refused_by_name() {
    let err = |p: FractalParams| p.build().unwrap_err().to_string();
    let e = err(FractalParams {
        r1: -0.5,
        ..Default::default()
    });
    assert!(e.contains("r1") && e.contains("-0.5"), "{e}");
    let e = err(FractalParams {
        theta2: f64::NAN,
        ..Default::default()
    });
    assert!(e.contains("theta2"), "{e}");
    let e = err(FractalParams {
        depth: 25,
        ..Default::default()
    });
    assert!(e.contains("budget") && e.contains("--max-segments"), "{e}");
    let e = err(FractalParams {
        depth: 41,
        max_segments: u64::MAX,
        ..Default::default()
    });
    assert!(e.contains("depth") && e.contains("0..40"), "{e}");
    let e = err(FractalParams {
        tip_daughters: 1,
        ..Default::default()
    });
    assert!(e.contains("tip-daughters"), "{e}");
}

#[test]
fn zero_ratio_daughters_collapse_onto_their_mothers_tip() {
    let all = segments(&FractalParams {
        depth: 4,
        r2: 0.0,
        ..Default::default()
    });
    // Every second daughter has no length, and its own daughters none either.
    let zero = all.iter().filter(|s| s.start == s.end).count();
    assert_eq!(zero, 1 + 3 + 7 + 15);
    let fractal = FractalParams {
        depth: 4,
        r2: 0.0,
        ..Default::default()
    }
    .build()
    .unwrap();
    let mesh = crate::mesh::mesh_tree(&fractal.skeleton(), &Default::default());
    assert!(mesh.bark.positions.iter().flatten().all(|v| v.is_finite()));
}
