//! Property tests: random valid parameters give finite geometry with counts inside the budget,
//! the same seed gives the same bytes, and meshes are well formed.

use proptest::prelude::*;
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva::params::PARAMS;
use sylva::{GenerateError, GenerateOptions, TreeParams, generate};

const BUDGET: u64 = 150_000;

/// Random parameters: each one uniform over a modest slice of its documented range, so that
/// trees stay small enough to test by the hundred.
fn params() -> impl Strategy<Value = TreeParams> {
    let values = proptest::collection::vec(0.0f64..1.0, PARAMS.len() * 4);
    (values, 1u32..=4).prop_map(|(u, levels)| {
        let mut p = TreeParams::default();
        let mut k = 0;
        for def in PARAMS {
            for level in def.levels() {
                let t = u[k];
                k += 1;
                let (lo, hi) = match (def.name, level) {
                    ("Branches", _) => (-4.0, 25.0),
                    ("CurveRes", _) => (1.0, 12.0),
                    ("Leaves", _) => (-6.0, 30.0),
                    ("0Branches", _) => (1.0, 4.0),
                    ("Lobes", _) => (0.0, 9.0),
                    ("0BaseSplits", _) => (0.0, 3.0),
                    ("SegSplits", _) => (0.0, 1.0),
                    ("Length", _) => (0.05, 1.2),
                    ("Scale", _) => (0.5, 30.0),
                    ("Ratio", _) => (0.005, 0.1),
                    ("LeafScale", _) => (0.01, 1.0),
                    ("LeafScaleX", _) => (0.1, 2.0),
                    ("LeafQuality", _) => (0.2, 2.0),
                    ("Taper", _) => (0.0, 3.0),
                    ("LobeDepth", _) => (0.0, 0.5),
                    (_, _) => (def.min.max(-200.0), def.max.min(200.0)),
                };
                let mut v = lo + (hi - lo) * t;
                if def.kind == sylva::params::ParamKind::Integer {
                    v = v.round();
                }
                (def.set)(&mut p, level, v.clamp(def.min, def.max));
            }
        }
        p.levels = levels;
        // Keep variations below their base values so every drawn size is positive.
        p.scale_v = p.scale_v.min(p.scale * 0.9);
        p.z_scale_v = p.z_scale_v.min(p.z_scale * 0.9);
        p.trunk_scale_v = p.trunk_scale_v.min(p.trunk_scale * 0.9);
        p.level[0].length_v = p.level[0].length_v.min(p.level[0].length * 0.9);
        p
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn random_trees_are_finite_and_within_budget(p in params(), seed in 0u64..1000) {
        prop_assume!(p.validate().is_ok());
        let options = GenerateOptions { seed, max_triangles: BUDGET, ..Default::default() };
        match generate(&p, &options) {
            Err(GenerateError::Budget { limit, .. }) => prop_assert_eq!(limit, BUDGET),
            Err(e) => return Err(TestCaseError::fail(format!("unexpected error: {e}"))),
            Ok(sk) => {
                prop_assert!(sk.sections.iter().all(|c| c.position.is_finite() && c.radius.is_finite() && c.radius >= 0.0));
                prop_assert!(sk.sections.iter().all(|c| c.orientation.is_normalized()));
                prop_assert!(sk.leaves.iter().all(|l| l.position.is_finite() && l.length > 0.0));
                let mesh = mesh_tree(&sk, &MeshOptions::default());
                prop_assert!(mesh.triangle_count() as u64 <= 2 * BUDGET, "{} triangles", mesh.triangle_count());
                for part in [&mesh.bark, &mesh.leaves] {
                    let n = part.vertex_count() as u32;
                    prop_assert!(part.indices.iter().all(|&i| i < n));
                    prop_assert!(part.positions.iter().flatten().all(|v| v.is_finite()));
                    prop_assert!(part.uvs.iter().flatten().all(|v| v.is_finite()));
                    for nrm in &part.normals {
                        let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
                        prop_assert!((len - 1.0).abs() < 1e-3, "normal length {}", len);
                    }
                }
                let again = generate(&p, &options).unwrap();
                prop_assert_eq!(again, sk);
            }
        }
    }
}
