use super::pipeline::Kind;
use super::*;
use glam::Vec3;

/// A built-in species at the paper's own scale: one lobe of radius 1 and the widths as the
/// appendix gives them (the rules' geometry is easiest to check there).
pub(super) fn paper(id: &str) -> TreeRules {
    let mut r = builtin(id).unwrap();
    r.layout.crown = None;
    r.layout.lobe_radius = 1.0;
    r.layout.crown_base = 1.0;
    r.layout.leaf_size = 0.05;
    r
}

pub(super) fn oak() -> TreeRules {
    paper("black_oak")
}

fn grown(rules: &TreeRules, seed: u64) -> LobeTree {
    grow(rules, seed, &auto_placement(rules, seed)).unwrap()
}

#[test]
fn built_in_species_carry_the_appendix_values() {
    // (TrunkAngle, BranchAngle, SubsequentAngle, NumTrunkIterations, BranchIterations,
    //  LeafTaper, NumTrunkBranchesOffSplit, NumBranchesOffSplit (n, ±v), NumSegmentsInBranch,
    //  LengthReductionFactor, BranchStartWidth, TrunkStartWidth, TwigStartWidth,
    //  MinBranchWidth, BranchTaperPercent, TrunkTaperPercent, NumBranchControlPointsOnLobe,
    //  NumLeafPointsOnLobe, MaxTrunkHeightPercent), appendix 8.2.
    let table: [(&str, &str, [f64; 20]); 3] = [
        (
            "black_oak",
            "Black Oak",
            [
                10.0, 45.0, 15.0, 1.0, 3.0, 0.0, 1.0, 2.0, 0.0, 25.0, 0.9, 0.1, 0.2, 0.005, 0.005,
                0.05, 0.4, 15.0, 30.0, 0.5,
            ],
        ),
        (
            "balsam_fir",
            "Balsam Fir",
            [
                0.0, 20.0, 15.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 25.0, 0.9, 0.1, 0.2, 0.005, 0.005,
                0.05, 0.4, 55.0, 30.0, 1.0,
            ],
        ),
        (
            "weeping_cherry",
            "Weeping Cherry Tree",
            [
                3.0, 45.0, 15.0, 2.0, 1.0, 0.0, 1.0, 2.0, 1.0, 4.0, 0.2, 0.1, 0.25, 0.005, 0.005,
                0.2, 0.3, 6.0, 50.0, 1.0,
            ],
        ),
    ];
    for (id, name, row) in table {
        let r = builtin(id).unwrap();
        assert_eq!(r.name, name);
        let got = [
            r.trunk_angle,
            r.branch_angle,
            r.subsequent_angle,
            r.num_trunk_iterations as f64,
            r.branch_iterations as f64,
            r.leaf_taper,
            r.num_trunk_branches_off_split as f64,
            r.num_branches_off_split.0 as f64,
            r.num_branches_off_split.1 as f64,
            r.num_segments_in_branch as f64,
            r.length_reduction_factor,
            r.branch_start_width,
            r.trunk_start_width,
            r.twig_start_width,
            r.min_branch_width,
            r.branch_taper_percent,
            r.trunk_taper_percent,
            r.num_branch_control_points_on_lobe as f64,
            r.num_leaf_points_on_lobe as f64,
            r.max_trunk_height_percent,
        ];
        assert_eq!(got, row, "{id}");
        assert_eq!(r.segment_offset, [0.4, 0.4, 0.4]);
        assert_eq!(r.tessellation, 36);
    }
    // The paper's names and its file's "Cherry Tree" find them too.
    assert_eq!(builtin("Cherry Tree").unwrap().name, "Weeping Cherry Tree");
    assert_eq!(builtin("Balsam Fir").unwrap().name, "Balsam Fir");
    assert!(builtin("birch").is_none());
}

#[test]
fn bad_rules_files_name_the_rule_and_line() {
    let text = include_str!("../../../../species/fields/black_oak.toml");
    let cases = [
        (
            text.replace("BranchAngle = 45", "BranchAngle = 400"),
            "BranchAngle",
            "line 6",
        ),
        (
            text.replace("Tessellation = 36", "Tessellation = 2"),
            "Tessellation",
            "line 29",
        ),
        (
            text.replace("TrunkAngle = 10\n", ""),
            "TrunkAngle",
            "lacks 1 of the 25",
        ),
        (
            text.replace("LeafTaper = 0", "LeafTapper = 0"),
            "LeafTapper",
            "line 10",
        ),
        (
            text.replace("\"oak\"", "\"palm\""),
            "LeafTexture",
            "line 28",
        ),
        (
            text.replace("= 2\nNumSegments", "= \"2 +- 2\"\nNumSegments"),
            "NumBranchesOffSplit",
            "line 12",
        ),
        (
            text.replace("[0.4, 0.4, 0.4]", "[0.4, 0.4]"),
            "SegmentOffset",
            "line 14",
        ),
        (
            text.replace("height = 21", "height = -1"),
            "height",
            "line 39",
        ),
        (text.replace("lobes = 6", "lobes = 2.5"), "lobes", "line 43"),
        (
            text.replace("trunk_width = 0.85\n", ""),
            "trunk_width",
            "give height, crown_width and trunk_width together",
        ),
        (
            text.replace("[layout]\n", "[layout]\nlobe_radius = 2\n"),
            "lobe_radius",
            "leave lobe_radius out",
        ),
        (
            text.replace("crown_base = 5", "crown_base = 30"),
            "height",
            "more than crown_base",
        ),
        (
            text.replace("lobes = 6", "lobes = 1")
                .replace("crown_width = 16", "crown_width = 1.5"),
            "height",
            "times as deep as crown_width",
        ),
    ];
    for (t, rule, place) in cases {
        let e = from_toml(&t, "oak.toml").unwrap_err().to_string();
        assert!(e.contains(rule) && e.contains(place), "{rule}: {e}");
    }
    let e = from_toml("[rules\n", "x.toml").unwrap_err().to_string();
    assert!(e.contains("x.toml") && e.contains("line 1"), "{e}");
}

#[test]
fn trunks_split_at_the_trunk_angle_and_reach_into_their_lobe() {
    let cherry = paper("weeping_cherry");
    let p = auto_placement(&cherry, 0);
    // The trunk and two iterations of one trunk each, each turned half of 3 degrees.
    assert_eq!(p.trunks.len(), 3);
    for w in p.trunks.windows(2) {
        let (a, b) = (
            (w[0].end - w[0].start).normalize(),
            (w[1].end - w[1].start).normalize(),
        );
        assert!((a.angle_between(b).to_degrees() - 1.5).abs() < 1e-3);
        assert_eq!(w[1].start, w[0].end);
    }
    // Two trunks off each split stand TrunkAngle apart.
    let mut two = oak();
    two.num_trunk_branches_off_split = 2;
    two.trunk_angle = 40.0;
    let p = auto_placement(&two, 3);
    let (a, b) = (p.trunks[1], p.trunks[2]);
    let angle = (a.end - a.start)
        .angle_between(b.end - b.start)
        .to_degrees();
    assert!((angle - 40.0).abs() < 1e-3, "{angle}");
    // MaxTrunkHeightPercent: the oak's trunk stops at its lobe's centre, the fir's and the
    // cherry's at the far side.
    for (rules, depth) in [
        (oak(), 0.5f32),
        (paper("balsam_fir"), 1.0),
        (paper("weeping_cherry"), 1.0),
    ] {
        let t = grown(&rules, 1);
        let lobe = t.lobes[0];
        let connector = t.branches.iter().rfind(|b| b.kind == Kind::Trunk).unwrap();
        let end = *connector.points.last().unwrap();
        let entry = lobe.centre - Vec3::Z * lobe.radius;
        let went = (end - entry).dot(Vec3::Z) / (2.0 * lobe.radius);
        assert!((went - depth).abs() < 0.02, "{}: {went}", rules.name);
    }
}

#[test]
fn first_branches_leave_the_trunk_at_the_branch_angle() {
    let mut rules = oak();
    rules.segment_offset = [0.0; 3];
    rules.num_segments_in_branch = 40;
    let t = grown(&rules, 2);
    let trunk = t.branches.iter().rfind(|b| b.kind == Kind::Trunk).unwrap();
    let axis = (trunk.points[1] - trunk.points[0]).normalize();
    let mut checked = 0;
    for b in t
        .branches
        .iter()
        .filter(|b| b.kind == Kind::Branch && b.level == 1)
    {
        let first = (b.points[1] - b.points[0]).normalize();
        // BranchAngle 45 up from the perpendicular: 45 degrees from the trunk.
        let angle = axis.angle_between(first).to_degrees();
        assert!((angle - 45.0).abs() < 3.0, "{angle}");
        checked += 1;
    }
    // 15 control points in groups of 2^(3-1) = 4: four first branches.
    assert_eq!(checked, 4);
}

/// Widest horizontal reach of leaves in `bins` slices of the lobe's height, from the bottom.
fn profile(t: &LobeTree, bins: usize) -> Vec<f32> {
    let lobe = t.lobes[0];
    let mut reach = vec![0.0f32; bins];
    for leaf in &t.leaves {
        let d = leaf.position - lobe.centre;
        let k = (((d.z + lobe.radius) / (2.0 * lobe.radius)) * bins as f32) as usize;
        let k = k.min(bins - 1);
        reach[k] = reach[k].max(d.truncate().length());
    }
    reach
}

#[test]
fn leaf_taper_one_makes_a_cone() {
    let mut rules = oak();
    rules.num_leaf_points_on_lobe = 200;
    rules.num_branch_control_points_on_lobe = 60;
    let bins = 10;
    rules.leaf_taper = 1.0;
    let cone = profile(&grown(&rules, 4), bins);
    rules.leaf_taper = 0.0;
    let round = profile(&grown(&rules, 4), bins);
    // A cone: the crown's reach falls in a straight line from the bottom to the apex. Fit a
    // line through the bins' reach against height.
    let xs: Vec<f32> = (0..bins).map(|k| (k as f32 + 0.5) / bins as f32).collect();
    let (mx, my) = (
        xs.iter().sum::<f32>() / bins as f32,
        cone.iter().sum::<f32>() / bins as f32,
    );
    let sxy: f32 = xs.iter().zip(&cone).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f32 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    let syy: f32 = cone.iter().map(|y| (y - my).powi(2)).sum();
    let slope = sxy / sxx;
    let r2 = sxy * sxy / (sxx * syy);
    // Reach 2R at the bottom to 0 at the top: slope -2R per lobe height (R = 1).
    assert!(r2 > 0.95, "cone profile {cone:?}: r² {r2}");
    assert!((slope + 2.0).abs() < 0.4, "slope {slope}, {cone:?}");
    assert!(cone[0] > 1.6 && cone[bins - 1] < 0.4, "{cone:?}");
    // Without taper the crown is round: widest in the middle, narrow at both ends.
    let widest = (0..bins)
        .max_by(|a, b| round[*a].total_cmp(&round[*b]))
        .unwrap();
    assert!((3..=6).contains(&widest), "{round:?}");
    assert!(
        round[0] < 0.7 * round[widest] && round[bins - 1] < 0.7 * round[widest],
        "{round:?}"
    );
}

#[test]
fn tessellation_sets_the_sides_of_every_branch() {
    let t = grown(&builtin("weeping_cherry").unwrap(), 0);
    let skeleton = t.skeleton();
    let tris = |sides| {
        let options = crate::mesh::MeshOptions {
            sides: Some(sides),
            ..Default::default()
        };
        crate::mesh::mesh_tree(&skeleton, &options)
            .bark
            .triangle_count() as f64
    };
    let (high, low) = (tris(36), tris(5));
    assert!(
        (high / low - 36.0 / 5.0).abs() < 0.01 * 36.0 / 5.0,
        "{high} / {low}"
    );
}

#[test]
fn growth_is_seeded() {
    let rules = oak();
    assert_eq!(grown(&rules, 5), grown(&rules, 5));
    assert_ne!(grown(&rules, 5).branches, grown(&rules, 6).branches);
}

pub(super) const APPENDIX: &str = "Cherry Tree
100
#BRANCHES
0 -1 1.110022 -1.582516 4.728205 1.14952 -0.8700994 4.896452 1
1 0 1.14952 -0.8700994 4.896452 1.800362 -0.3780254 4.764441 1
2 0 1.14952 -0.8700994 4.896452 0.7252637 -0.7159721 4.99926 1
3 2 0.7252637 -0.7159721 4.99926 0.5519101 0.02624928 5.070594 1
#LEAF LOBES
2.307282 0.5082518 4.534246 1
0.4439276 1.201943 4.939856 1
";
