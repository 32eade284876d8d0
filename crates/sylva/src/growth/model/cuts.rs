//! Cuts the street makes (issue U), and the tree growing back from them.
//!
//! What lies in a cleared zone is cut off at a branch union, as ANSI A300 (Part 1, Pruning)
//! asks: a *removal cut* takes a branch back to the stem it grows from; a *reduction cut*
//! takes a stem back to a lateral at least a third of the stem's diameter where it is cut,
//! and the lateral carries the stem on. Never a heading cut between unions (topping): a trunk
//! with no such lateral below the zone is left as it is, and the cut reports that the zone
//! could not be cleared.
//!
//! The tree then grows back by its own rules. The cut opens space and light that the buds
//! below it now see; latent buds just below a cut break, more below a larger cut, (the
//! sprouts a cut releases, `sprouts.rs`); a stem cut back to a lateral grows on from the lateral; and the
//! leaf area the cut took comes back as the tree grows back the young shoots it lost
//! ([`Regrowth`]). While it does, the leader climbs back no faster than a vigorous shoot
//! grows (`buds.rs`, `hold_height`).

use super::*;
use rayon::prelude::*;

/// Spacing of the points a segment is tested at against a zone, m: finer than any zone
/// (a street light's 1 m ball is the smallest a site has).
const SAMPLE: f32 = 0.1;
/// Least diameter of the lateral a stem is cut back to, as a share of the stem's where it is
/// cut: ANSI A300 (Part 1) 2017, the reduction cut's definition (a lateral "large enough to
/// assume apical dominance", typically at least one third of the stem's diameter).
const LATERAL_SHARE: f32 = 1.0 / 3.0;
/// Most a trained young tree's lateral may be across, as a share of the trunk's where it
/// leaves it: thicker, it competes with the leader and is subordinated (Gilman, "An
/// Illustrated Guide to Pruning", 3rd ed. 2012: branches kept under half the trunk's
/// diameter; ANSI A300 Part 1's structural pruning, subordination).
const SUBORDINATE_SHARE: f32 = 0.5;

/// Which kind of cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CutKind {
    /// A branch taken back to the stem it grows from.
    Removal,
    /// A stem taken back to a lateral.
    Reduction,
    /// A stem cut between unions (topping, a utility's round-over): only line clearance makes
    /// it, where a trunk or leader in the line's clearance has no lateral to be cut back to,
    /// since the line's minimum clearance must hold. It leaves a stub whose decay A300
    /// forbids it for (80% of headed silver maple leaders decayed from the cut: Dahle et al.
    /// 2006, Arboric. Urban For. 32(6):260-264).
    Heading,
}

/// Where one cut was made: for pictures and accounts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutMark {
    /// The cut's centre, in the tree's frame, m.
    pub at: Vec3,
    /// Radius of the stem cut, m.
    pub radius: f32,
    /// Its kind.
    pub kind: CutKind,
}

/// What one pruning took from a tree.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cuts {
    /// Every cut made.
    pub marks: Vec<CutMark>,
    /// Wood removed, m³ (each annual segment a cylinder at its base radius).
    pub wood_volume: f64,
    /// Leaf area removed, m².
    pub leaf_area: f64,
    /// Wood the cuts could not clear: a trunk or stem with no lateral to be cut back to below
    /// the zone.
    pub left_in_zone: bool,
    /// Cuts left for a later visit because they would have taken more foliage than one visit
    /// may ([`Grower::cut_within`]).
    pub deferred: usize,
}

impl Cuts {
    /// How many cuts of a kind.
    pub fn count(&self, kind: CutKind) -> usize {
        self.marks.iter().filter(|m| m.kind == kind).count()
    }

    /// Diameter of the largest cut, m.
    pub fn largest_diameter(&self) -> f32 {
        self.marks
            .iter()
            .map(|m| 2.0 * m.radius)
            .fold(0.0, f32::max)
    }

    /// Adds another pruning's cuts to these.
    pub fn merge(&mut self, other: Cuts) {
        self.marks.extend(other.marks);
        self.wood_volume += other.wood_volume;
        self.leaf_area += other.leaf_area;
        self.left_in_zone |= other.left_in_zone;
        self.deferred += other.deferred;
    }
}

/// The share of its measured leaf area a cut tree lacks until it grows back. It comes back as
/// the leaf-bearing wood does: the share of the leaf-bearing wood the cuts took that has grown
/// again is the share of the leaf area back. (Thin, lit wood carries a crown's leaves,
/// `allocate_leaves`; a cut tree has lost that wood, not the means to carry leaves on it.)
#[derive(Clone, Copy, Debug)]
pub(super) struct Regrowth {
    /// Share of the measured leaf area missing just after the last cut.
    share: f32,
    /// Leaf-bearing wood (m) the tree had just before the last cut, and just after it.
    before: f32,
    after: f32,
}

impl Grower {
    /// Cuts off, at branch unions, every branch with wood or leaves where `zone(point, order)`
    /// says the street keeps clear (`order`: the wood's branch order, 0 for the trunk and a
    /// multi-stem tree's stems). Removal cuts where a branch has no lateral to be cut back to;
    /// reduction cuts to the highest lateral below the zone otherwise. The tree is then ready
    /// to be drawn and to grow on.
    pub fn cut(&mut self, zone: &(dyn Fn(Vec3, u8) -> bool + Sync)) -> Cuts {
        self.cut_within(zone, f64::INFINITY)
    }

    /// Like [`Grower::cut`], but taking at most `most_leaf` m² of leaf: a cut that would take
    /// the visit past it is left for a later visit ([`Cuts::deferred`]), and smaller cuts
    /// further out on the same branch are made instead where they fit. Routine pruning takes
    /// no more than a quarter of a tree's foliage at one visit (`street::accounts::pruner`).
    pub fn cut_within(&mut self, zone: &(dyn Fn(Vec3, u8) -> bool + Sync), most_leaf: f64) -> Cuts {
        self.cut_with(zone, most_leaf, None)
    }

    /// Like [`Grower::cut`], by directional pruning (ANSI A300 Part 7's line clearance;
    /// utilities' specifications: branches growing toward the conductor are cut back, those
    /// growing away are kept): a stem is cut back to the highest lateral below the zone that
    /// does not grow toward it, `away(point)` being the direction away from the zone there;
    /// only where it has none, to the highest lateral of any direction.
    /// A trunk or stem in the zone with no lateral below it to be cut back to is headed back
    /// to below the zone ([`CutKind::Heading`]): a line's minimum clearance must hold.
    pub fn cut_directional(
        &mut self,
        zone: &(dyn Fn(Vec3, u8) -> bool + Sync),
        away: &dyn Fn(Vec3) -> Vec3,
    ) -> Cuts {
        self.cut_with(zone, f64::INFINITY, Some(away))
    }

    fn cut_with(
        &mut self,
        zone: &(dyn Fn(Vec3, u8) -> bool + Sync),
        most_leaf: f64,
        away: Option<&dyn Fn(Vec3) -> Vec3>,
    ) -> Cuts {
        let inside = self.in_zone(zone);
        let mut cuts = Cuts::default();
        let (before, missing) = (self.young_shoot(), self.missing_share());
        let mut stack = vec![0usize];
        while let Some(b) = stack.pop() {
            if !self.branches[b].alive {
                continue;
            }
            let segs = self.branches[b].segments.clone();
            match segs.iter().position(|&s| inside[s as usize]) {
                None => {}
                Some(k) => match self.lateral_below(b, &segs, k, away) {
                    Some((j, c)) if cuts.leaf_area + self.reduction_takes(b, j, c) > most_leaf => {
                        cuts.deferred += 1;
                    }
                    Some((j, c)) => self.reduce(b, j, c, &mut cuts),
                    None if self.branches[b].order == 0 && away.is_some() => {
                        self.head(b, k, &|p| zone(p, 0), &mut cuts);
                    }
                    None if self.branches[b].order > 0 => {
                        let mut takes = Cuts::default();
                        self.take(b, &mut takes);
                        if cuts.leaf_area + takes.leaf_area > most_leaf {
                            cuts.deferred += 1;
                        } else {
                            self.remove(b, &mut cuts);
                            continue;
                        }
                    }
                    None => cuts.left_in_zone = true,
                },
            }
            stack.extend(self.branches[b].children.iter().map(|&c| c as usize));
        }
        self.regrow_from(&cuts, before, missing);
        cuts
    }

    /// Structural pruning of a young tree (ANSI A300 Part 1; Gilman 2012): while its trunk
    /// still leads (a decurrent tree until it forks where it was meant to), every lateral of
    /// the trunk more than half the trunk's diameter where it leaves it competes with the
    /// leader and is subordinated: cut back by half its length to a lateral of its own, or
    /// removed where it has none. A multi-stem tree's stems are its form, not competitors.
    pub fn train(&mut self) -> Cuts {
        self.train_within(f64::INFINITY)
    }

    /// Like [`Grower::train`], taking at most `most_leaf` m² of leaf (see
    /// [`Grower::cut_within`]).
    pub fn train_within(&mut self, most_leaf: f64) -> Cuts {
        let mut cuts = Cuts::default();
        if self.habit.stems > 1
            || self.habit.form == TreeForm::Palm
            || self.apical_control() < 0.5
            || self.branches[0].headed
        {
            return cuts;
        }
        let (before, missing) = (self.young_shoot(), self.missing_share());
        let rivals: Vec<usize> = self.branches[0]
            .children
            .iter()
            .map(|&c| c as usize)
            .filter(|&c| {
                let child = &self.branches[c];
                let Some((_, from)) = child.parent else {
                    return false;
                };
                child.alive
                    && self.radius_of(child.segments[0]) > SUBORDINATE_SHARE * self.radius_of(from)
            })
            .collect();
        for c in rivals {
            let segs = self.branches[c].segments.clone();
            let total: f32 = segs.iter().map(|&s| self.segments[s as usize].length).sum();
            // The first segment past half its length is where it must be cut back from.
            let mut run = 0.0;
            let k = segs
                .iter()
                .position(|&s| {
                    run += self.segments[s as usize].length;
                    run > 0.5 * total
                })
                .unwrap_or(segs.len() - 1);
            let takes = |g: &Grower, cut: Option<(usize, usize)>| match cut {
                Some((j, lateral)) => g.reduction_takes(c, j, lateral),
                None => {
                    let mut takes = Cuts::default();
                    g.take(c, &mut takes);
                    takes.leaf_area
                }
            };
            let cut = (k > 0)
                .then(|| self.lateral_below(c, &segs, k, None))
                .flatten();
            if cuts.leaf_area + takes(self, cut) > most_leaf {
                cuts.deferred += 1;
                continue;
            }
            match cut {
                Some((j, lateral)) => self.reduce(c, j, lateral, &mut cuts),
                None => self.remove(c, &mut cuts),
            }
        }
        self.regrow_from(&cuts, before, missing);
        cuts
    }

    /// Whether each segment must be cleared: a point of its wood (as long as this season's
    /// shoot will grow) in the zone, or, on a leafy shoot, a point within a leaf's length of
    /// it.
    fn in_zone(&self, zone: &(dyn Fn(Vec3, u8) -> bool + Sync)) -> Vec<bool> {
        let reach = self.drawn_leaf_size().0;
        let around = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].map(|d| d * reach);
        self.segments
            .par_iter()
            .enumerate()
            .map(|(i, s)| {
                let b = &self.branches[s.branch as usize];
                let length = s.length.max(s.goal);
                if !b.alive || length <= 1e-4 {
                    return false;
                }
                let leafy = self.leaves_on.get(i).is_some_and(|&n| n > 0);
                let n = (length / SAMPLE).ceil() as usize;
                (0..=n).any(|k| {
                    let p = s.start + s.direction * (length * k as f32 / n as f32);
                    zone(p, b.order) || (leafy && around.iter().any(|&d| zone(p + d, b.order)))
                })
            })
            .collect()
    }

    /// The lateral branch `b` may be cut back to, clear of the zone that its segment `k`
    /// (of `segs`) is the first to reach: the highest live child on a segment below `k`
    /// whose diameter is at least `LATERAL_SHARE` of `b`'s just above it. Its segment's
    /// index in `segs`, and the child. With `away` (directional pruning), the highest such
    /// child that does not grow toward the zone, where there is one.
    fn lateral_below(
        &self,
        b: usize,
        segs: &[u32],
        k: usize,
        away: Option<&dyn Fn(Vec3) -> Vec3>,
    ) -> Option<(usize, usize)> {
        if let Some(away) = away {
            let growing_away = |c: &Branch| {
                let first = &self.segments[c.segments[0] as usize];
                first.direction.dot(away(first.start)) >= 0.0
            };
            let kept = self.lateral_where(b, segs, k, &growing_away);
            if kept.is_some() {
                return kept;
            }
        }
        self.lateral_where(b, segs, k, &|_| true)
    }

    /// [`Grower::lateral_below`] among the children `take` accepts.
    fn lateral_where(
        &self,
        b: usize,
        segs: &[u32],
        k: usize,
        take: &dyn Fn(&Branch) -> bool,
    ) -> Option<(usize, usize)> {
        let mut best: Option<(usize, f32, f32, usize)> = None;
        for &c in &self.branches[b].children {
            let child = &self.branches[c as usize];
            let Some((_, from)) = child.parent else {
                continue;
            };
            let Some(j) = segs[..k].iter().position(|&s| s == from) else {
                continue;
            };
            if !child.alive || !take(child) {
                continue;
            }
            // The stem just above the union is the next segment's base.
            let stem = self.radius_of(segs[j + 1]);
            let radius = self.radius_of(child.segments[0]);
            if radius < LATERAL_SHARE * stem {
                continue;
            }
            let along = self.segments[child.segments[0] as usize]
                .start
                .distance(self.segments[from as usize].start);
            let better = best
                .is_none_or(|(bj, balong, bradius, _)| (j, along, radius) > (bj, balong, bradius));
            if better {
                best = Some((j, along, radius, c as usize));
            }
        }
        best.map(|(j, _, _, c)| (j, c))
    }

    /// A removal cut: branch `b` and everything on it, at its union.
    fn remove(&mut self, b: usize, cuts: &mut Cuts) {
        let first = self.branches[b].segments[0];
        let radius = self.radius_of(first);
        cuts.marks.push(CutMark {
            at: self.segments[first as usize].start,
            radius,
            kind: CutKind::Removal,
        });
        self.take(b, cuts);
        self.kill(b);
        if let Some((p, from)) = self.branches[b].parent {
            let at =
                (self.segments[first as usize].start).distance(self.segments[from as usize].start);
            self.set_sprouts(p as usize, from, at, radius, CutKind::Removal);
        }
    }

    /// A heading cut: stem `b` cut where its segment `k`, the first to reach the zone
    /// (`inside(point)`), enters it, having no lateral to be cut back to below it.
    fn head(&mut self, b: usize, k: usize, inside: &dyn Fn(Vec3) -> bool, cuts: &mut Cuts) {
        let segs = self.branches[b].segments.clone();
        let seg = self.segments[segs[k] as usize];
        let n = (seg.length / SAMPLE).ceil().max(1.0) as usize;
        let enter = (0..=n)
            .map(|i| seg.length * i as f32 / n as f32)
            .find(|&t| inside(seg.start + seg.direction * t))
            .unwrap_or(0.0);
        // Where the segment enters at its start, the cut is at the end of the one before.
        let (j, keep) = if enter > SAMPLE || k == 0 {
            (k, enter.max(1e-3))
        } else {
            (k - 1, self.segments[segs[k - 1] as usize].length)
        };
        let sj = segs[j];
        let gone = (self.branches[b].children.iter())
            .copied()
            .filter(|&ch| {
                let child = &self.branches[ch as usize];
                child.parent.is_some_and(|(_, from)| {
                    segs[j + 1..].contains(&from)
                        || (from == sj
                            && self.segments[child.segments[0] as usize]
                                .start
                                .distance(self.segments[sj as usize].start)
                                > keep)
                })
            })
            .collect();
        self.truncate(b, j, keep, gone, CutKind::Heading, cuts);
    }

    /// A reduction cut: branch `b` taken back to its child `c`, which grows from `b`'s
    /// segment `j`. What lies beyond the union becomes a dead branch of its own, so every
    /// pass that asks whether wood is alive leaves it out.
    fn reduce(&mut self, b: usize, j: usize, c: usize, cuts: &mut Cuts) {
        let (keep, gone) = self.cut_back(b, j, c);
        self.truncate(b, j, keep, gone, CutKind::Reduction, cuts);
    }

    /// Branch `b` cut `keep` m along its segment `j`, with its children `gone`: what lies
    /// beyond becomes a dead branch of its own.
    fn truncate(
        &mut self,
        b: usize,
        j: usize,
        keep: f32,
        gone: Vec<u32>,
        kind: CutKind,
        cuts: &mut Cuts,
    ) {
        let sj = self.branches[b].segments[j];
        let seg = self.segments[sj as usize];
        // The stem where it is cut: just above the union a reduction cut leaves, or the
        // segment itself where a heading cut falls within its last one.
        let stem = self.radius_of(*self.branches[b].segments.get(j + 1).unwrap_or(&sj));
        cuts.marks.push(CutMark {
            at: seg.start + seg.direction * keep,
            radius: stem,
            kind,
        });
        // What goes: the segments past `j`, and the children beyond the cut.
        let moved: Vec<u32> = self.branches[b].segments[j + 1..].to_vec();
        let kept: Vec<u32> = (self.branches[b].children.iter())
            .copied()
            .filter(|ch| !gone.contains(ch))
            .collect();
        let dead = self.branches.len() as u32;
        for &s in &moved {
            self.segments[s as usize].branch = dead;
        }
        for &ch in &gone {
            if let Some((_, from)) = self.branches[ch as usize].parent {
                self.branches[ch as usize].parent = Some((dead, from));
            }
        }
        let id = self.next_branch_id();
        let branch = &self.branches[b];
        self.branches.push(Branch {
            id,
            order: branch.order,
            rank: branch.rank,
            parent: Some((b as u32, sj)),
            segments: moved,
            next_azimuth: 0.0,
            alive: true,
            children: gone,
            finished: 0.0,
            offset: 0.0,
            anchor: branch.anchor,
            shaded_years: 0,
            headed: false,
            sprung: false,
        });
        // The stub of segment `j` past the collar goes too.
        let share = 1.0 - keep / seg.length.max(1e-6);
        let r = self.radius_of(sj);
        cuts.wood_volume += (PI * r * r * (seg.length - keep)) as f64;
        cuts.leaf_area += (self.leaves_on.get(sj as usize).copied().unwrap_or(0) as f32
            * share
            * self.leaf_area_drawn()) as f64;
        self.take(dead as usize, cuts);
        self.kill(dead as usize);
        let s = &mut self.segments[sj as usize];
        s.length = keep;
        s.goal = keep;
        let branch = &mut self.branches[b];
        branch.children = kept;
        branch.segments.truncate(j + 1);
        branch.headed = true;
        branch.finished = branch.segments[..j]
            .iter()
            .map(|&s| self.segments[s as usize].length)
            .sum();
        // Buds on what went go with it; those left on segment `j` keep their places on it.
        let (segments, branches) = (&self.segments, &self.branches);
        self.buds.retain(|bud| {
            let alive = branches[segments[bud.segment as usize].branch as usize].alive;
            alive && (bud.segment != sj || bud.at * seg.length <= keep)
        });
        for bud in self.buds.iter_mut().filter(|bud| bud.segment == sj) {
            bud.at = (bud.at * seg.length / keep.max(1e-6)).min(1.0);
        }
        self.set_sprouts(b, sj, keep, stem, kind);
    }

    /// Where cutting branch `b` back to its child `c` on its segment `j` leaves its collar
    /// (m along segment `j`, as wide as the lateral beyond the union), and the children that
    /// go with what lies beyond it.
    fn cut_back(&self, b: usize, j: usize, c: usize) -> (f32, Vec<u32>) {
        let segs = &self.branches[b].segments;
        let sj = segs[j];
        let seg = &self.segments[sj as usize];
        let union = self.segments[self.branches[c].segments[0] as usize].start;
        let keep = (union.distance(seg.start) + self.radius_of(self.branches[c].segments[0]))
            .min(seg.length);
        let gone = (self.branches[b].children.iter())
            .copied()
            .filter(|&ch| {
                let child = &self.branches[ch as usize];
                match child.parent {
                    Some((_, from)) if segs[j + 1..].contains(&from) => true,
                    Some((_, from)) if from == sj => {
                        let start = self.segments[child.segments[0] as usize].start;
                        start.distance(seg.start) > keep
                    }
                    _ => false,
                }
            })
            .collect();
        (keep, gone)
    }

    /// The leaf area [`Grower::reduce`] would take cutting branch `b` back to its child `c`
    /// on its segment `j`, m²: the leaves past the collar, and those of the children beyond.
    fn reduction_takes(&self, b: usize, j: usize, c: usize) -> f64 {
        let segs = &self.branches[b].segments;
        let seg = &self.segments[segs[j] as usize];
        let (keep, gone) = self.cut_back(b, j, c);
        let each = self.leaf_area_drawn();
        let mut taken = Cuts::default();
        for &s in &segs[j + 1..] {
            taken.leaf_area +=
                self.leaves_on.get(s as usize).copied().unwrap_or(0) as f64 * each as f64;
        }
        for &ch in &gone {
            self.take(ch as usize, &mut taken);
        }
        let share = 1.0 - keep / seg.length.max(1e-6);
        taken.leaf_area
            + (self.leaves_on.get(segs[j] as usize).copied().unwrap_or(0) as f32 * share * each)
                as f64
    }

    /// Adds the wood and leaves of branch `b` and everything on it (alive) to `cuts`.
    fn take(&self, b: usize, cuts: &mut Cuts) {
        let each = self.leaf_area_drawn();
        let mut stack = vec![b];
        while let Some(b) = stack.pop() {
            let branch = &self.branches[b];
            if !branch.alive {
                continue;
            }
            for &s in &branch.segments {
                let r = self.radius_of(s);
                cuts.wood_volume += (PI * r * r * self.segments[s as usize].length) as f64;
                cuts.leaf_area +=
                    (self.leaves_on.get(s as usize).copied().unwrap_or(0) as f32 * each) as f64;
            }
            stack.extend(branch.children.iter().map(|&c| c as usize));
        }
    }

    /// Area of one leaf as drawn now, m².
    fn leaf_area_drawn(&self) -> f32 {
        self.leaf_area_each() * self.leaf_boost
    }

    /// Leaf-bearing wood on the tree: the length of every live shoot thin enough to bear
    /// leaves (young shoots, and the spurs of older wood up to `SPUR_MAX_RADIUS`), each at
    /// the length it grows to this season, m.
    fn young_shoot(&self) -> f32 {
        self.segments
            .iter()
            .enumerate()
            .filter(|(i, s)| {
                self.branches[s.branch as usize].alive
                    && self.radius_of(*i as u32) <= SPUR_MAX_RADIUS
            })
            .map(|(_, s)| s.goal.max(s.length))
            .sum()
    }

    /// After cuts: the share of the leaf area they took, with what earlier cuts took that had
    /// not grown back (`missing`, a share), is missing until the leaf-bearing wood (`before`
    /// the cuts, m) grows back; the tree's wood, leaves and light are brought up to date.
    fn regrow_from(&mut self, cuts: &Cuts, before: f32, missing: f32) {
        if cuts.marks.is_empty() {
            return;
        }
        let carried = self.leaf_carried();
        let took = (cuts.leaf_area as f32 / carried.max(1e-6)).min(1.0);
        self.regrowth = Some(Regrowth {
            share: 1.0 - (1.0 - missing) * (1.0 - took),
            before,
            after: self.young_shoot(),
        });
        self.cut_top = self.top_after_cuts();
        self.refresh_radii();
        self.allocate_leaves();
        self.update_light();
    }

    /// The top of the live wood of a tree the street has cut; none on a tree never cut.
    pub(super) fn top_after_cuts(&self) -> Option<f32> {
        self.regrowth.is_some().then(|| {
            (self.segments.iter())
                .filter(|s| self.branches[s.branch as usize].alive)
                .map(|s| s.end().z)
                .fold(0.0, f32::max)
        })
    }

    /// Leaf area the tree carries now, m².
    pub fn leaf_carried(&self) -> f32 {
        self.leaves_on.iter().map(|&n| n as f32).sum::<f32>() * self.leaf_area_drawn()
    }

    /// Share of the measured leaf area the cuts took that is not yet grown back.
    fn missing_share(&self) -> f32 {
        let Some(r) = self.regrowth else {
            return 0.0;
        };
        let lost = r.before - r.after;
        if lost <= 1e-3 {
            return 0.0;
        }
        r.share * ((r.before - self.young_shoot()) / lost).clamp(0.0, 1.0)
    }

    /// Leaf area the cuts took that is not yet grown back, m².
    pub(super) fn leaf_deficit(&self) -> f64 {
        self.targets_now().leaf_area * self.missing_share() as f64
    }
}
