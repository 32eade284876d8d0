//! Stages 3 to 5 in order: trunks connected to their lobes, branches grown back from the
//! control points, leaves. The steps live in `pipeline` (the grower) and `leaves`; this module
//! only sequences them, so that neither of those imports the other.

use super::lobe::LobeShape;
use super::pipeline::{Branch, Grower, Kind, LobeTree, Placement, group};
use super::rules::TreeRules;
use super::widths::set_widths;
use crate::error::GenerateError;
use crate::rng::StreamKey;
use glam::Vec3;

/// Stages 3 to 5: connects trunks to lobes, grows branches to the control points and adds the
/// leaves. Stage 6 is [`LobeTree::skeleton`] and the mesher.
pub fn grow(
    rules: &TreeRules,
    seed: u64,
    placement: &Placement,
) -> Result<LobeTree, GenerateError> {
    let shape = LobeShape::of(rules);
    let key = StreamKey::from_seed(seed);
    let mut g = Grower {
        rules,
        shape,
        width_scale: rules.width_scale(placement.height(shape)),
        branches: Vec::new(),
        random: key.child(4).stream(),
    };
    for t in &placement.trunks {
        g.push(Branch {
            parent: t.parent,
            kind: Kind::Trunk,
            level: 0,
            points: vec![t.start, t.end],
            widths: vec![0.0; 2],
            lobe: None,
            target: None,
        })?;
    }
    // Stage 3: every lobe gets a trunk through it.
    let mut lobe_trunk = Vec::with_capacity(placement.lobes.len());
    for lobe in &placement.lobes {
        let inside = |b: &Branch| {
            let (a, e) = (b.points[0], tip(b));
            let len = a.distance(e);
            let dir = (e - a).try_normalize()?;
            lobe.chord(a, dir, len, shape).map(|(t0, t1)| t1 - t0)
        };
        let existing = g
            .branches
            .iter()
            .enumerate()
            .filter_map(|(i, b)| inside(b).map(|l| (i, l)))
            .filter(|(_, l)| *l > 1e-4 * lobe.radius)
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .map(|(i, _)| i);
        let index = match existing {
            Some(i) => i,
            None => {
                // The nearest trunk end grows a trunk toward the lobe's centre, entering at
                // the near surface and going MaxTrunkHeightPercent of its chord through.
                let from = g
                    .branches
                    .iter()
                    .enumerate()
                    .min_by(|x, y| {
                        let dx = tip(x.1).distance(lobe.centre);
                        let dy = tip(y.1).distance(lobe.centre);
                        dx.total_cmp(&dy)
                    })
                    .map(|(i, b)| (Some(i), tip(b)))
                    .unwrap_or((None, Vec3::new(lobe.centre.x, lobe.centre.y, 0.0)));
                let dir = (lobe.centre - from.1).try_normalize().unwrap_or(Vec3::Z);
                let far = from.1.distance(lobe.centre) + 2.0 * lobe.half_height(shape);
                let (t0, t1) = lobe.chord(from.1, dir, far, shape).unwrap_or((0.0, far));
                let entry = from.1 + dir * t0;
                let through = (t1 - t0) * rules.max_trunk_height_percent as f32;
                let end = entry + dir * through.max(1e-3 * lobe.radius);
                g.push(Branch {
                    parent: from.0,
                    kind: Kind::Trunk,
                    level: 0,
                    // In NumSegmentsInBranch straight pieces, so that its width can narrow
                    // past each limb it carries (see `set_widths`).
                    points: straight(from.1, end, rules.num_segments_in_branch),
                    widths: vec![0.0; rules.num_segments_in_branch.max(1) as usize + 1],
                    lobe: None,
                    target: None,
                })?
            }
        };
        lobe_trunk.push(index);
    }
    // Stage 4: control points and the branches grown toward them.
    let mut control_points = Vec::new();
    let mut leaf_points = Vec::new();
    for (li, lobe) in placement.lobes.iter().enumerate() {
        let mut random = key.child(2).child(li as u64).stream();
        let points = lobe.surface_points(
            rules.num_branch_control_points_on_lobe as usize,
            rules.create_branch_control_points,
            shape,
            &mut random,
        );
        let mut random = key.child(3).child(li as u64).stream();
        leaf_points.push(lobe.surface_points(
            rules.num_leaf_points_on_lobe as usize,
            rules.create_leaf_control_points,
            shape,
            &mut random,
        ));
        let trunk = &g.branches[lobe_trunk[li]];
        let (a, e) = (trunk.points[0], tip(trunk));
        let len = a.distance(e);
        let d = (e - a).try_normalize().unwrap_or(Vec3::Z);
        let range = lobe.chord(a, d, len, shape).unwrap_or((len, len));
        let per_group = (rules.num_branches_off_split.0 as usize)
            .saturating_pow(rules.branch_iterations.saturating_sub(1))
            .max(1);
        let mut groups = Vec::new();
        group(points.clone(), per_group, &mut groups);
        // BranchAngle is read as section 4.1.2 reads the fir's 20: degrees up from the
        // perpendicular to the trunk (see `TreeRules::branch_angle`).
        let angle = (90.0 - rules.branch_angle as f32).to_radians();
        for grp in groups {
            g.grow(
                lobe_trunk[li],
                (a, d, range),
                grp,
                rules.branch_iterations,
                angle,
                1,
                li,
                lobe,
            )?;
        }
        control_points.push(points);
    }
    set_widths(rules, g.width_scale, &mut g.branches);
    // Stage 5: leaves.
    let mut leaves = Vec::new();
    let mut leaf_random = key.child(5).stream();
    super::leaves::add_leaves(
        rules,
        &placement.lobes,
        &leaf_points,
        shape,
        &mut g,
        &mut leaves,
        &mut leaf_random,
    )?;
    Ok(LobeTree {
        lobes: placement.lobes.clone(),
        control_points,
        leaf_points,
        branches: g.branches,
        leaves,
        tessellation: rules.tessellation,
        shape,
    })
}

/// `pieces` equal straight pieces from `a` to `b`, as their `pieces + 1` ends.
fn straight(a: Vec3, b: Vec3, pieces: u32) -> Vec<Vec3> {
    let n = pieces.max(1);
    (0..=n).map(|i| a.lerp(b, i as f32 / n as f32)).collect()
}

/// Where a stem ends.
fn tip(b: &Branch) -> Vec3 {
    *b.points.last().unwrap_or(&Vec3::ZERO)
}
