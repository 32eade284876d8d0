//! Stem widths of a grown lobe tree: the rules' start widths and tapers (rules 12-17), scaled to
//! the tree's size, with Leonardo's rule where stems split or carry limbs.

use super::pipeline::{Branch, Kind, length};
use super::rules::TreeRules;
use glam::Vec3;

/// Widths: the trunk tapers from `TrunkStartWidth` at the ground by `TrunkTaperPercent` over
/// its longest path; each limb (a first branch and all it carries) from `BranchStartWidth` (no
/// wider than the trunk where it starts) by `BranchTaperPercent` over its longest path; twigs
/// from `TwigStartWidth`. Nothing is thinner than `MinBranchWidth`. Every width rule is scaled
/// by `scale` (the species' [`TreeRules::width_scale`] for this tree). Where a trunk splits into k trunks (several
/// lobes fed from one trunk end), each is 1/√k as wide, so their cross-sections add up to
/// their parent's (Leonardo's rule; the paper gives every trunk the same start).
pub(super) fn set_widths(rules: &TreeRules, scale: f32, branches: &mut [Branch]) {
    let n = branches.len();
    // Path length from the root of each branch's run (trunk: ground; limb: first branch base).
    let mut base = vec![0.0f32; n];
    let mut root = vec![0usize; n];
    let mut share = vec![1.0f32; n];
    let mut trunk_children = vec![0u32; n];
    for b in branches.iter() {
        if let Some(p) = b.parent
            && b.kind == Kind::Trunk
            && branches[p].kind == Kind::Trunk
        {
            trunk_children[p] += 1;
        }
    }
    for i in 0..n {
        let b = &branches[i];
        let parent = b.parent.filter(|&p| branches[p].kind == b.kind);
        match parent {
            Some(p) => {
                base[i] = base[p] + length(&branches[p].points);
                root[i] = root[p];
                share[i] = share[p];
                if b.kind == Kind::Trunk && trunk_children[p] > 1 {
                    share[i] /= (trunk_children[p] as f32).sqrt();
                }
            }
            None => root[i] = i,
        }
    }
    // Limbs (branch runs of another kind) leaving each stem. Twigs are not counted: they start
    // at TwigStartWidth whatever carries them, and a cherry's hundred strands on its trunk must
    // not thin its six branches.
    let mut limbs = vec![0u32; n];
    for b in branches.iter() {
        if let Some(p) = b.parent
            && branches[p].kind != b.kind
            && b.kind != Kind::Twig
        {
            limbs[p] += 1;
        }
    }
    let mut longest = vec![0.0f32; n];
    for i in 0..n {
        let end = base[i] + length(&branches[i].points);
        longest[root[i]] = longest[root[i]].max(end);
    }
    let min = rules.min_branch_width as f32 * scale;
    for i in 0..n {
        let (start, taper) = match branches[i].kind {
            Kind::Trunk => (
                rules.trunk_start_width as f32,
                rules.trunk_taper_percent as f32,
            ),
            Kind::Branch => (
                rules.branch_start_width as f32,
                rules.branch_taper_percent as f32,
            ),
            Kind::Twig => (
                rules.twig_start_width as f32,
                rules.branch_taper_percent as f32,
            ),
        };
        let start = start * scale * share[i];
        // A limb is never wider than what it grows from, and the limbs leaving one stem share
        // the cross-section of that stem's run at its start (Leonardo's rule again): with k of
        // them, each is at most 1/√k as wide. A fir's 55 branches are then a few centimetres
        // thick, not half the trunk.
        let start = match branches[root[i]].parent {
            Some(p) if branches[i].kind != Kind::Trunk => {
                let r = root[i];
                let here = width_near(&branches[p], branches[r].points[0]);
                let run = branches[root[p]].widths[0];
                let k = limbs[p].max(1) as f32;
                start.min(here).min((run / k.sqrt()).max(min))
            }
            _ => start,
        };
        let total = longest[root[i]].max(1e-6);
        let mut along = base[i];
        let points = branches[i].points.clone();
        let widths = &mut branches[i].widths;
        for (k, w) in widths.iter_mut().enumerate() {
            if k > 0 {
                along += points[k].distance(points[k - 1]);
            }
            *w = (start * (1.0 - (1.0 - taper) * along / total)).max(min);
        }
    }
    carry_what_grows_above(branches, min);
}

/// Leonardo's rule on the trunks: a trunk is never wider than the stems it carries above each
/// point need (the square root of the sum of their squared widths, children's before parents'),
/// so a fir's trunk narrows whorl by whorl to a thin leader instead of ending as a pole at
/// TrunkTaperPercent of its base.
fn carry_what_grows_above(branches: &mut [Branch], min: f32) {
    let n = branches.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, b) in branches.iter().enumerate() {
        if let Some(p) = b.parent {
            children[p].push(i);
        }
    }
    let mut carried = vec![0.0f32; n];
    for i in (0..n).rev() {
        if branches[i].kind != Kind::Trunk {
            continue;
        }
        let mut at_point = vec![0.0f32; branches[i].points.len()];
        for &c in &children[i] {
            if branches[c].kind == Kind::Trunk {
                continue;
            }
            let start = branches[c].points[0];
            let k = nearest_point(&branches[i].points, start);
            at_point[k] += branches[c].widths[0].powi(2);
        }
        let mut sum = carried[i];
        let b = &mut branches[i];
        for k in (0..b.points.len()).rev() {
            sum += at_point[k];
            b.widths[k] = b.widths[k].min(sum.sqrt().max(min));
        }
        if let Some(p) = b.parent {
            carried[p] += b.widths[0].powi(2);
        }
    }
}

fn nearest_point(points: &[Vec3], p: Vec3) -> usize {
    (0..points.len())
        .min_by(|&a, &b| {
            points[a]
                .distance_squared(p)
                .total_cmp(&points[b].distance_squared(p))
        })
        .unwrap_or(0)
}

/// A stem's width at its point nearest `p`.
fn width_near(b: &Branch, p: Vec3) -> f32 {
    b.widths
        .get(nearest_point(&b.points, p))
        .copied()
        .unwrap_or(0.0)
}
