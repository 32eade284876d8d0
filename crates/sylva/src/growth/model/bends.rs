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
/// about 11 degrees at either end of it. Sylva's drawing choice: enough that a crown's long
/// shoots read as the crooked twigs of a bare crown, small enough that a limb's course still
/// follows its chord. The drawn wood is a little longer than its chords (2%), and a bare crown
/// stops a little more of a beam: at 0.12 the hackberry's bare crown stopped 46% from the
/// side, past issue R's 45%; at 0.10 it stops 45%, as before the kinks.
pub(super) const BEND: f32 = 0.10;
/// Stretches shorter than this are drawn straight, m: a short shoot's nodes are too close for
/// a kink to show.
const SHORTEST_BENT: f32 = 0.2;
/// Most metamers (the grower's internodes, `Grower::metamer`, up to 35 cm) in one kinked
/// stretch: a kink at every node would draw a 30-year plane's model 1.25 times as large in
/// leaf (21.6 MB against 17.3 MB); at every second node it is 1.15 times (19.9 MB), and the
/// crown reads the same at 3000 px.
const KINK_METAMERS: f32 = 2.0;

/// The bends of the drawn segments, filled in as the wood is traced (`Bends::trace`): per
/// segment, its nodes along it (its ends, its live side branches' points and the metamers
/// between), read again by the short twigs that stand on it.
pub(super) struct Bends {
    /// Whether the tree's axes are drawn kinked at all (not a conifer's or a palm's).
    kinked: bool,
    /// The most metamers one stretch spans, m.
    longest: f32,
    /// Per segment: the range of its nodes in `nodes` (empty: drawn straight), and the side
    /// its first kink leans to (worked out once: the twigs on it ask again).
    ranges: Vec<(u32, u32)>,
    sides: Vec<Vec3>,
    nodes: Vec<f32>,
}

impl Bends {
    /// The side a segment's first kink leans to: turned about the chord by the golden angle
    /// from segment to segment, so that neighbours lean different ways.
    fn side(segment: u32, s: &Segment) -> Vec3 {
        let turn = ((segment as f32 * DIVERGENCE) % 360.0).to_radians();
        Quat::from_axis_angle(s.direction, turn) * s.direction.any_orthogonal_vector().normalize()
    }

    /// Lays out the nodes of segment `id` of a branch of `order`, whose live side branches
    /// leave it at `branches` m along it (in order), and appends its kinks to `kinks`.
    pub(super) fn trace(
        &mut self,
        (id, s, order): (u32, &Segment, u8),
        branches: impl Iterator<Item = f32>,
        kinks: &mut Vec<f32>,
    ) {
        if !self.kinked || order == 0 || s.length < SHORTEST_BENT {
            return;
        }
        let lo = self.nodes.len() as u32;
        let mut last = 0.0f32;
        self.nodes.push(last);
        let inner = branches.filter(|&a| a > 1e-4 && a < s.length - 1e-4);
        for node in inner.chain(std::iter::once(s.length)) {
            // A stretch longer than `KINK_METAMERS` metamers is split into equal pieces no
            // longer than that: a shoot turns at its nodes, not only where a branch has grown
            // from one.
            let pieces = crate::whole::pieces((node - last) / self.longest);
            let piece = (node - last) / pieces as f32;
            self.nodes
                .extend((1..pieces).map(|k| last + piece * k as f32));
            self.nodes.push(node);
            last = node;
        }
        self.ranges[id as usize] = (lo, self.nodes.len() as u32);
        self.sides[id as usize] = Self::side(s.id, s);
        let nodes = &self.nodes[lo as usize..];
        kinks.extend(
            nodes
                .windows(2)
                .filter(|w| w[1] - w[0] >= SHORTEST_BENT)
                .map(|w| 0.5 * (w[0] + w[1])),
        );
    }

    /// How far the drawn wood at `along` m up segment `id` stands off its chord.
    pub(super) fn offset(&self, id: u32, along: f32) -> Vec3 {
        let Some(&(lo, hi)) = self.ranges.get(id as usize) else {
            return Vec3::ZERO;
        };
        if hi <= lo {
            return Vec3::ZERO;
        }
        let nodes = &self.nodes[lo as usize..hi as usize];
        let i = nodes
            .partition_point(|&n| n <= along)
            .clamp(1, nodes.len() - 1);
        let (a, b) = (nodes[i - 1], nodes[i]);
        let stretch = b - a;
        if stretch < SHORTEST_BENT {
            return Vec3::ZERO;
        }
        let u = ((along - a) / stretch).clamp(0.0, 1.0);
        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
        self.sides[id as usize] * (sign * BEND * stretch * (1.0 - (2.0 * u - 1.0).abs()))
    }
}

impl Grower {
    /// Empty bends for this tree, to be traced with its wood: kinked on a tree whose form
    /// zig-zags (`Habit::zigzag`), not on a conifer's or a palm's straight axes.
    pub(super) fn bends(&self) -> Bends {
        let kinked = self.habit.zigzag > 0.0;
        Bends {
            kinked,
            longest: self.metamer * KINK_METAMERS,
            ranges: vec![(0, 0); if kinked { self.segments.len() } else { 0 }],
            sides: vec![Vec3::ZERO; if kinked { self.segments.len() } else { 0 }],
            nodes: Vec::new(),
        }
    }
}
