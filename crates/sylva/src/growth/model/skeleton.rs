//! The growing tree as a Skeleton, the form every output reads.

use super::*;
use rayon::prelude::*;

/// Branches whose leaves one task lays out.
const LEAF_RUN: usize = 64;

/// The trunk's flare at the ground, Weber & Penn's (1995) `Flare` with their quaking aspen's
/// value (appendix): the radius grows towards the ground by their exponential profile, to
/// 1.6 times at the ground.
const FLARE: f64 = 0.6;
/// Shares of the flare's height the trunk gets sections at, to draw its curve (most of it
/// lies in the lowest quarter).
const FLARE_SECTIONS: [f32; 5] = [0.0, 0.1, 0.25, 0.5, 0.75];

/// Where a trunk of `length` m read for DBH at `dbh_at` m flares: its lowest eighth, as
/// Weber & Penn's, but never above four fifths of the height DBH is read at, so the DBH the
/// survey would read is the trunk's own.
fn flare_height(length: f32, dbh_at: f32) -> f32 {
    (length / 8.0).min(0.8 * dbh_at)
}

/// The flare's multiplier at `h` m above the ground on a trunk flaring up to `top` m.
fn flare_at(h: f32, top: f32) -> f32 {
    if top <= 0.0 || h >= top {
        return 1.0;
    }
    crate::weber_penn::equations::flare_factor(FLARE, f64::from(h.max(0.0) / top) / 8.0) as f32
}

impl Grower {
    /// The tree now as a Skeleton: one stem per live branch, sections at the segment joints
    /// and just past every side branch (the trunk also where DBH is read and every half metre),
    /// leaves spiralled along the young shoots.
    pub fn skeleton(&self) -> Skeleton {
        let mut sk = Skeleton::default();
        self.skeleton_into(&mut sk);
        sk
    }

    /// Like [`Grower::skeleton`], but reuses `sk`'s buffers (cleared first), so showing the
    /// tree after every step allocates only small lists once the buffers have grown.
    pub fn skeleton_into(&self, sk: &mut Skeleton) {
        sk.stems.clear();
        sk.sections.clear();
        sk.leaves.clear();
        sk.short_twigs = 0;
        // Which branches are drawn, and as which stems, is known before any is traced; so
        // the wood and the leaves (each branch's from its own random stream) are laid out at
        // once, into the skeleton's separate lists.
        let (stem_of, leafy) = self.drawn_branches();
        let Skeleton {
            stems,
            sections,
            leaves,
            short_twigs,
        } = sk;
        rayon::join(
            || *short_twigs = self.wood_into(&stem_of, stems, sections),
            || self.leaves_into(&leafy, leaves),
        );
        if self.habit.form == TreeForm::Palm && !sk.stems.is_empty() {
            self.fronds_into(&mut sk.leaves);
        }
    }

    /// The branches drawn (live, on a drawn parent, with a segment of some length) as stem
    /// ids per branch (`u32::MAX`: not drawn), and the drawn branches with their stems, in
    /// order.
    fn drawn_branches(&self) -> (Vec<u32>, Vec<(usize, u32)>) {
        let mut stem_of = vec![u32::MAX; self.branches.len()];
        let mut drawn = Vec::new();
        for (b, branch) in self.branches.iter().enumerate() {
            let parent_drawn = branch
                .parent
                .is_none_or(|(p, _)| stem_of[p as usize] != u32::MAX);
            let long = || {
                branch
                    .segments
                    .iter()
                    .any(|&s| self.segments[s as usize].length > 1e-4)
            };
            if branch.alive && parent_drawn && long() {
                stem_of[b] = drawn.len() as u32;
                drawn.push((b, drawn.len() as u32));
            }
        }
        (stem_of, drawn)
    }

    /// The stems and sections of the branches `stem_of` draws, kinked between their nodes
    /// (`bends.rs`), then of their short twigs; returns how many short twigs.
    fn wood_into(
        &self,
        stem_of: &[u32],
        stems: &mut Vec<Stem>,
        sections: &mut Vec<CrossSection>,
    ) -> u32 {
        let mut segs: Vec<(u32, &Segment)> = Vec::new();
        // (position, direction, distance along the stem, radius)
        let mut points: Vec<(Vec3, Vec3, f32, f32)> = Vec::new();
        let mut junctions: Vec<(u32, f32, f32, u32)> = Vec::new();
        // Per segment, reused: its side branches (distance, radius), its radius profile and
        // the distances its sections sit at.
        let (mut children, mut profile, mut at) = (Vec::new(), Vec::new(), Vec::new());
        // This segment's kinks, and which of the branch's points are kinks.
        let (mut kinks, mut is_kink) = (Vec::new(), Vec::new());
        // Where each branch leaves its parent, m along the parent's stem.
        let mut offsets = vec![0.0f32; self.branches.len()];
        // Where each long shoot starts along its branch's stem, m (for its short twigs).
        let mut shoot_starts = vec![0.0f32; self.segments.len()];
        // The kinks of each segment's stretches between its nodes, traced with it.
        let mut bends = self.bends();
        // Where DBH is read (breast height, or caliper height on a tree too short for it).
        let dbh_at = self.dbh_read_at();
        for (b, branch) in self.branches.iter().enumerate() {
            if stem_of[b] == u32::MAX {
                continue;
            }
            let parent = branch.parent.map(|(p, _)| StemId(stem_of[p as usize]));
            let first = sections.len() as u32;
            segs.clear();
            segs.extend(
                branch
                    .segments
                    .iter()
                    .map(|&s| (s, &self.segments[s as usize]))
                    .filter(|(_, s)| s.length > 1e-4),
            );
            debug_assert!(
                !segs.is_empty(),
                "drawn_branches draws only branches of some length"
            );
            // Where each live side branch leaves this one: (segment, distance along it, its
            // base radius), in order.
            junctions.clear();
            for &c in &branch.children {
                let child = &self.branches[c as usize];
                if let (true, Some((_, from))) = (child.alive, child.parent) {
                    let s = &self.segments[from as usize];
                    let first = child.segments[0];
                    let along = self.segments[first as usize].start.distance(s.start);
                    junctions.push((from, along, self.radius_of(first), c));
                }
            }
            junctions.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
            let total: f32 = segs.iter().map(|(_, s)| s.length).sum();
            // The trunk flares at the ground; a multi-stem tree's stems leave its collar.
            let flare_top = if b == 0 {
                flare_height(total, dbh_at)
            } else {
                0.0
            };
            points.clear();
            is_kink.clear();
            let mut run = 0.0f32;
            for &(id, s) in &segs {
                let lo = junctions.partition_point(|j| j.0 < id);
                let hi = junctions.partition_point(|j| j.0 <= id);
                children.clear();
                children.extend(junctions[lo..hi].iter().map(|j| (j.1.min(s.length), j.2)));
                for j in &junctions[lo..hi] {
                    offsets[j.3 as usize] = run + j.1.min(s.length);
                }
                shoot_starts[id as usize] = run;
                self.radii_along(id, &children, &mut profile);
                // The trunk also every half metre and where DBH is read, so it is read from a
                // section.
                at.clear();
                at.extend(profile.iter().map(|p| p.0));
                if branch.order == 0 {
                    let pieces = crate::whole::pieces(s.length / 0.5);
                    at.extend((1..pieces).map(|k| s.length * k as f32 / pieces as f32));
                    let up = s.direction.z.max(1e-6);
                    let reading = (dbh_at - s.start.z) / up;
                    if reading > 1e-3 && reading < s.length - 1e-3 {
                        at.push(reading);
                    }
                    // Sections up the flare, so its curve shows.
                    for f in FLARE_SECTIONS {
                        let along = (flare_top * f - s.start.z) / up;
                        if along > 1e-3 && along < s.length - 1e-3 {
                            at.push(along);
                        }
                    }
                }
                // A limb's kinks between its nodes (`bends.rs`).
                let branches = junctions[lo..hi].iter().map(|j| j.1.min(s.length));
                kinks.clear();
                bends.trace((id, s, branch.order), branches, &mut kinks);
                at.extend(&kinks);
                at.sort_by(f32::total_cmp);
                at.dedup_by(|a, b| (*a - *b).abs() < 1e-4);
                for &along in &at {
                    let k = profile.partition_point(|p| p.0 <= along + 1e-5).max(1);
                    // Only a kink stands off the chord: the nodes are on it.
                    let kink = kinks.contains(&along);
                    let bend = if kink {
                        bends.offset(id, along)
                    } else {
                        Vec3::ZERO
                    };
                    let p = s.start + s.direction * along + bend;
                    let r = profile[k - 1].1 * flare_at(p.z, flare_top);
                    points.push((p, s.direction, run + along, r));
                    is_kink.push(kink);
                }
                run += s.length;
            }
            let (last_id, last) = segs[segs.len() - 1];
            let tip_radius = if branch.order == 0 {
                self.tip_radius * 0.5
            } else {
                self.radius_of(last_id) * 0.35
            };
            points.push((last.end(), last.direction, total, tip_radius));
            is_kink.push(false);
            taper_through_kinks(&mut points, &is_kink);
            // A segment's sections share its direction, and so its frame: worked out once a
            // segment (the same quaternion from the same direction), not once a section.
            let mut framed: Option<(Vec3, Quat)> = None;
            for &(p, d, at, radius) in &points {
                let orientation = match framed {
                    Some((was, q)) if was == d => q,
                    _ => {
                        let q = frame(d);
                        framed = Some((d, q));
                        q
                    }
                };
                sections.push(CrossSection {
                    position: p,
                    orientation,
                    radius: radius.max(0.0008),
                    z: if total > 0.0 { at / total } else { 0.0 },
                });
            }
            debug_assert_eq!(stem_of[b], stems.len() as u32);
            let offset = if b == 0 { 0.0 } else { offsets[b] };
            stems.push(Stem {
                level: branch.order,
                parent,
                clone_of: None,
                offset,
                length: total,
                sections: first..sections.len() as u32,
                lobes: 0,
                lobe_depth: 0.0,
            });
        }
        let branches = stems.len();
        self.short_shoots_into(stem_of, (&shoot_starts, &bends), stems, sections);
        (stems.len() - branches) as u32
    }

    /// The leaves of `leafy` (live branches and their stems) into `out`, in branch order.
    /// Each branch's leaves depend on that branch alone (their own random stream), so runs of
    /// branches are laid out in parallel, each into its own part of `out`, and closed up
    /// after: the same skeleton on any number of cores, and `out`'s buffer is reused.
    fn leaves_into(&self, leafy: &[(usize, u32)], out: &mut Vec<Leaf>) {
        // At most the leaves the segments carry (those that would hang above the top or
        // below the crown base are left out).
        let most: Vec<usize> = leafy
            .chunks(LEAF_RUN)
            .map(|run| {
                run.iter()
                    .flat_map(|&(b, _)| &self.branches[b].segments)
                    .map(|&s| self.leaves_on.get(s as usize).copied().unwrap_or(0) as usize)
                    .sum()
            })
            .collect();
        out.clear();
        out.resize(most.iter().sum(), NO_LEAF);
        let mut parts = Vec::with_capacity(most.len());
        let mut rest = &mut out[..];
        for (run, &n) in leafy.chunks(LEAF_RUN).zip(&most) {
            let (part, tail) = rest.split_at_mut(n);
            parts.push((run, part));
            rest = tail;
        }
        let (leaf_len, leaf_width) = self.drawn_leaf_size();
        let top = self.targets_now().height as f32;
        let floor = self.leaf_floor();
        let written: Vec<usize> = parts
            .into_par_iter()
            .map(|(run, part)| {
                let mut k = 0;
                for &(b, id) in run {
                    self.for_each_leaf(b, (leaf_len, top, floor), |position, _, blade| {
                        part[k] = Leaf {
                            light: self.light.light_at(position),
                            position,
                            orientation: blade.frame(),
                            length: leaf_len,
                            width: leaf_width,
                            shape: self.leaf_shape,
                            stem: StemId(id),
                        };
                        k += 1;
                    });
                }
                k
            })
            .collect();
        let (mut to, mut from) = (0, 0);
        for (&n, &room) in written.iter().zip(&most) {
            out.copy_within(from..from + n, to);
            to += n;
            from += room;
        }
        out.truncate(to);
    }
}

/// A kink's radius, tapered between the sections either side of it, as the tube tapers there
/// without it: the pipe model's radius steps down at each side branch, and a tube drawn
/// between the steps tapers from one to the next; a kink holding the step's radius would draw
/// half of each stretch thicker (6% more bare wood on a 30-year hackberry).
fn taper_through_kinks(points: &mut [(Vec3, Vec3, f32, f32)], is_kink: &[bool]) {
    let mut before = 0;
    for i in 1..points.len() {
        if is_kink[i] {
            continue;
        }
        let (a, b) = (points[before], points[i]);
        for p in &mut points[before + 1..i] {
            let t = ((p.2 - a.2) / (b.2 - a.2).max(1e-9)).clamp(0.0, 1.0);
            p.3 = a.3 + (b.3 - a.3) * t;
        }
        before = i;
    }
}

/// A blank leaf, written over before it is read.
const NO_LEAF: Leaf = Leaf {
    position: Vec3::ZERO,
    orientation: Quat::IDENTITY,
    length: 0.0,
    width: 0.0,
    shape: LeafShape::Oval,
    stem: StemId(0),
    light: 0.0,
};
