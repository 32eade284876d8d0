//! The drawn course of a year's shoot between its nodes. The grower keeps each year's shoot as
//! one straight segment: its light, its pipe model and its crown read that chord. A real
//! shoot is not a ruler line: it turns a little at every node where a leaf and its bud sit,
//! and its side branches leave from those nodes (Barthélémy & Caraglio 2007, Annals of
//! Botany 99:375, on the articulated, zig-zag axes of sympodial and many monopodial trees).
//! Drawn straight, a crown's long shoots read as straw (issue W). So the Skeleton draws each
//! stretch of a segment between two of its nodes (its ends, the points its live side branches
//! leave from, and every second metamer between) as two straight pieces meeting at a kink
//! halfway, set aside from the chord by `BEND` of the stretch, the other way at the next
//! stretch. The kinks fall between nodes, so every side branch still leaves its parent's drawn
//! wood where it leaves the chord, and no point of the tree moves but the kinks (and the short
//! twigs on the stretch, which move with it).

use super::*;

/// How far a stretch's kink stands off its chord, as a share of the stretch: a turn of
/// about 13 degrees at either end of it. Sylva's drawing choice: enough that a crown's long
/// shoots read as the crooked twigs of a bare crown, small enough that a limb's course still
/// follows its chord.
pub(super) const BEND: f32 = 0.12;
/// Stretches shorter than this are drawn straight, m: a short shoot's nodes are too close for
/// a kink to show.
const SHORTEST_BENT: f32 = 0.2;
/// Most metamers (the grower's internodes, `Grower::metamer`, up to 35 cm) in one kinked
/// stretch: a kink at every node would draw a 30-year plane's model 1.25 times as large in
/// leaf (21.6 MB against 17.3 MB); at every second node it is 1.15 times (19.9 MB), and the
/// crown reads the same at 3000 px.
const KINK_METAMERS: f32 = 2.0;

/// The bends of the drawn segments: per segment, its nodes along it (its ends and its live
/// side branches' points) and the side its kinks lean to.
#[derive(Default)]
pub(super) struct Bends {
    /// Per segment: the range of its nodes in `nodes` (empty: drawn straight).
    ranges: Vec<(u32, u32)>,
    nodes: Vec<f32>,
    sides: Vec<Vec3>,
}

impl Bends {
    /// No bends: every segment drawn as its chord (a palm, a conifer).
    pub(super) fn none() -> Self {
        Self::default()
    }

    /// The nodes of `segment`, when it is bent.
    fn nodes_of(&self, segment: u32) -> Option<(&[f32], Vec3)> {
        let &(lo, hi) = self.ranges.get(segment as usize)?;
        (hi > lo).then(|| {
            (
                &self.nodes[lo as usize..hi as usize],
                self.sides[segment as usize],
            )
        })
    }

    /// How far the drawn wood at `along` m up `segment` stands off its chord.
    pub(super) fn offset(&self, segment: u32, along: f32) -> Vec3 {
        let Some((nodes, side)) = self.nodes_of(segment) else {
            return Vec3::ZERO;
        };
        let i = nodes
            .partition_point(|&n| n <= along)
            .clamp(1, nodes.len() - 1);
        let (lo, hi) = (nodes[i - 1], nodes[i]);
        let stretch = hi - lo;
        if stretch < SHORTEST_BENT {
            return Vec3::ZERO;
        }
        let u = ((along - lo) / stretch).clamp(0.0, 1.0);
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        side * (sign * BEND * stretch * (1.0 - (2.0 * u - 1.0).abs()))
    }

    /// The kinks of `segment`, m along it: one halfway along each stretch long enough to bend.
    pub(super) fn kinks(&self, segment: u32, out: &mut Vec<f32>) {
        if let Some((nodes, _)) = self.nodes_of(segment) {
            out.extend(
                nodes
                    .windows(2)
                    .filter(|w| w[1] - w[0] >= SHORTEST_BENT)
                    .map(|w| 0.5 * (w[0] + w[1])),
            );
        }
    }
}

impl Grower {
    /// The bends of the branches `stem_of` draws: every one but the trunk, on a tree whose
    /// form zig-zags (`Habit::zigzag`: not a conifer's or a palm's straight axes).
    pub(super) fn bends(&self, stem_of: &[u32]) -> Bends {
        if self.habit.zigzag <= 0.0 {
            return Bends::none();
        }
        let mut bends = Bends {
            ranges: vec![(0, 0); self.segments.len()],
            nodes: Vec::new(),
            sides: vec![Vec3::ZERO; self.segments.len()],
        };
        // Each drawn segment's side branches, m along it, as (segment, distance) sorted: one
        // list for the tree, not one per segment (the skeleton is drawn at every step).
        let mut along: Vec<(u32, f32)> = Vec::new();
        for (b, branch) in self.branches.iter().enumerate() {
            if stem_of[b] == u32::MAX || b == 0 {
                continue;
            }
            if let Some((_, from)) = branch.parent {
                let s = &self.segments[from as usize];
                let first = self.segments[branch.segments[0] as usize].start;
                along.push((from, first.distance(s.start).min(s.length)));
            }
        }
        along.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        for (b, branch) in self.branches.iter().enumerate() {
            if stem_of[b] == u32::MAX || branch.order == 0 {
                continue;
            }
            for &id in &branch.segments {
                let s = &self.segments[id as usize];
                if s.length < SHORTEST_BENT {
                    continue;
                }
                let from = along.partition_point(|a| a.0 < id);
                let to = along.partition_point(|a| a.0 <= id);
                let lo = bends.nodes.len() as u32;
                let mut last = 0.0f32;
                bends.nodes.push(last);
                let inner = along[from..to]
                    .iter()
                    .map(|a| a.1)
                    .filter(|&a| a > 1e-4 && a < s.length - 1e-4);
                for node in inner.chain(std::iter::once(s.length)) {
                    // A stretch longer than `KINK_METAMERS` metamers is split into equal
                    // pieces no longer than that: a shoot turns at its nodes, not only where
                    // a branch has grown from one.
                    let pieces =
                        crate::whole::pieces((node - last) / (self.metamer * KINK_METAMERS));
                    let piece = (node - last) / pieces as f32;
                    bends
                        .nodes
                        .extend((1..pieces).map(|k| last + piece * k as f32));
                    bends.nodes.push(node);
                    last = node;
                }
                bends.ranges[id as usize] = (lo, bends.nodes.len() as u32);
                // The side the segment's first kink leans to, turned about the chord by the
                // golden angle from segment to segment, so neighbours lean different ways.
                let turn = (id as f32 * DIVERGENCE).to_radians();
                bends.sides[id as usize] = Quat::from_axis_angle(s.direction, turn)
                    * s.direction.any_orthogonal_vector().normalize();
            }
        }
        bends
    }
}
