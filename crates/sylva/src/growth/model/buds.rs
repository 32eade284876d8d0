//! Buds and shoots at the end of a year, after Palubicki et al. (2009): every bud's exposure
//! comes from space colonisation of the coming year's crown envelope and the light grid; the
//! tree's vigour is allocated to the buds by Borchert-Honda with the habit's apical control; a
//! bud given at least one metamer's worth makes a shoot of that many metamers, steered by its
//! markers and the habit's tropism, with a lateral bud at every node. The leader is held to
//! the measured height; shaded branches die; past the segment budget the darkest make room.

use super::colonise::{LOBE_DEPTH, Markers, Space};
use super::*;

/// Dormant lateral buds older than this die, years.
const BUD_YEARS: f64 = 4.0;
/// Highest branch order.
const MAX_ORDER: u8 = 4;
/// Most metamers one shoot makes in a year.
const MAX_METAMERS: f32 = 8.0;
/// Weight of the direction toward a bud's markers in a new shoot's direction (xi).
const ENVIRONMENT_WEIGHT: f32 = 0.3;
/// How much wider than next year's crown the markers are scattered: buds at the crown's
/// edge see the open space beyond it (where the shoots that reach out will be stopped at the
/// crown), and a young crown, filled by its own shoots, still has buds that do.
const MARKER_MARGIN: f32 = 1.3;
/// Height over which a decurrent trunk hands its lead to its laterals, m: the buds in it
/// become the tree's few codominant scaffolds.
const FORK_ZONE: f32 = 1.0;
/// Most lateral buds of one annual shoot of a branch that may break in a year: those most
/// exposed. A shoot has a bud at every node, but a tree's side shoots come from a few of
/// them (the rest stay dormant, and die after `BUD_YEARS`), so the year's resource makes a
/// few strong laterals instead of a broom of weak ones (issue G2: fewer, stronger laterals).
/// Sylva's choice; the trunk's buds (and a multi-stem tree's stems'), its scaffolds, are not limited.
const LATERALS_PER_SHOOT: usize = 2;
/// Longest shoot regrowth after a cut makes in a year, m: the most yearly length growth
/// measured on pruned street trees, in the first year after pruning (about 1.5 m in green ash,
/// Norway and silver maple: Follett et al. 2016, Arboric. Urban For. 42(3):133-145).
const LONGEST_REGROWTH: f32 = 1.5;
/// Share of the season in which a shoot elongates.
pub(super) const GROWING_SEASON: f64 = 0.5;

/// A lateral bud waiting in a leaf axil.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bud {
    pub branch: u32,
    pub segment: u32,
    /// Where on the segment, as a share of its length.
    pub at: f32,
    /// The direction a shoot from it sets out in.
    pub direction: Vec3,
    pub born: f64,
    /// Released by a cut (`sprouts.rs`): it may break whatever its shoot's other buds do.
    pub sprout: bool,
}

/// A shoot to be made this year.
pub(super) struct Plan {
    /// Terminal: the branch it continues; lateral: the bud's index in `Grower::buds`.
    from: usize,
    lateral: bool,
    pub start: Vec3,
    pub direction: Vec3,
    pub length: f32,
}

impl Grower {
    /// The apex of every live branch and every waiting bud have their say; shoots are made.
    /// At the end of a year every bud may break. In a young tree's mid-season (`sylleptic`)
    /// only this year's buds on the leader may, for half a season's growth: a vigorous leader
    /// branches the year it grows, so its crown keeps up with a crown base rising fast.
    pub(super) fn flush(&mut self, sylleptic: bool) {
        let next = self.targets((self.age + 0.25).floor() + 1.0);
        if !sylleptic {
            self.make_room();
            self.shade_deaths();
            self.grow_short_shoots(next.crown_base() as f32);
        }
        let space = self.space(&next, self.spread as f32 * MARKER_MARGIN);
        self.prune_buds(next.crown_base() as f32);
        if !sylleptic {
            self.compact();
        }
        // A branch cut back to a lateral has no apex left: the lateral grows on for it.
        let terminals: Vec<u32> = (0..self.branches.len() as u32)
            .filter(|&b| self.branches[b as usize].alive && !self.branches[b as usize].headed)
            .collect();
        let mut sites: Vec<(Vec3, Vec3)> = terminals
            .iter()
            .map(|&b| {
                let s = self.apex_segment(b as usize);
                (s.end(), s.direction)
            })
            .collect();
        sites.extend(
            self.buds
                .iter()
                .map(|b| (self.bud_position(b), b.direction)),
        );
        // Space is taken by the leafy shoots of the last years: old limbs inside the crown
        // leave room for foliage around them.
        let age = self.age;
        let wood: Vec<(Vec3, Vec3)> = self
            .segments
            .iter()
            .filter(|s| {
                self.branches[s.branch as usize].alive
                    && s.length > 1e-4
                    && age - s.born <= LEAF_SHOOT_YEARS + 1.0
            })
            .map(|s| (s.start, s.end()))
            .collect();
        // One stream per half year (a sapling's ages are negative).
        let half_year = (self.age * 2.0).round() as i64;
        let mut rng = self.key.child((1_000_000 + half_year) as u64).stream();
        let markers = Markers::scatter(&space, self.metamer_now(), &mut rng, &wood);
        let (owned, towards) = markers.perceive(&sites);
        let mut q: Vec<f32> = sites
            .iter()
            .zip(&owned)
            .map(|(&(p, _), &n)| {
                (n as f32 / markers.saturation).min(1.0) * self.light.light_at(p).sqrt()
            })
            .collect();
        self.hold_dormant(&mut q[terminals.len()..]);
        let lambda = self.apical_control();
        let v = self.allocate(&terminals, &q, lambda);
        let mut plans = Vec::new();
        let leader_holds = lambda >= 0.5;
        for (i, &b) in terminals.iter().enumerate() {
            // The trunk's apex grows only as the held leader. Once a decurrent tree forks its
            // terminal bud stops (sympodial growth), and the laterals below it take the top
            // between them: the trunk ends in a fork instead of running on through the crown.
            if sylleptic || b == 0 {
                continue;
            }
            let n = v[i].min(MAX_METAMERS);
            if n < 1.0 {
                continue;
            }
            // A multi-stem tree's stems steer as its scaffolds do (the habit's pull, not the
            // trunk's), so they keep opening into a vase.
            let order = self.branches[b as usize].order.max(1);
            let (start, d) = sites[i];
            let direction = self.steer(d, towards[i], order);
            let direction = self.zigzag(direction, b as usize);
            plans.push(Plan {
                from: b as usize,
                lateral: false,
                start,
                direction,
                length: n * self.metamer_now(),
            });
        }
        for (k, bud) in self.buds.iter().enumerate() {
            let site = terminals.len() + k;
            let n = v[site].min(MAX_METAMERS);
            let order = self.branches[bud.branch as usize].order + 1;
            // A sprout on wood of the highest order still breaks (`start_branch` ranks it as
            // a scaffold): a cut grows back from whatever wood it leaves.
            let rank = self.branches[bud.branch as usize].rank + 1;
            if n < 1.0 || (rank > MAX_ORDER && !bud.sprout) {
                continue;
            }
            if sylleptic && !self.breaks_sylleptic(bud, order, age) {
                continue;
            }
            plans.push(Plan {
                from: k,
                lateral: true,
                start: sites[site].0,
                direction: Vec3::ZERO,
                length: n * self.metamer_now(),
            });
        }
        for p in plans.iter_mut().filter(|p| p.lateral) {
            let bud = self.buds[p.from];
            let order = self.branches[bud.branch as usize].order + 1;
            p.direction = self.steer(bud.direction, towards[terminals.len() + p.from], order);
        }
        // Nothing leaves next year's envelope: a shoot stops where it would.
        // Branches whose scaffold the rising crown base passes this year are shed: they grow
        // no more.
        let floor = next.crown_base() as f32;
        plans.retain(|p| {
            let b = if p.lateral {
                self.buds[p.from].branch as usize
            } else {
                p.from
            };
            let branch = &self.branches[b];
            let anchor = if p.lateral && branch.order == 0 {
                p.start.z
            } else {
                branch.anchor
            };
            // The trunk and stems are never shed, nor are shoots from them cut at the floor
            // here (`prune_buds` has already dropped their buds below it). On a tree the
            // street has cut, limbs leaving the trunk below the crown base carry the crown
            // around the cleared zone (`sheds_below`), and grow on: held to their anchors,
            // a plane under a wire made a tenth of its twin's shoots.
            let anchored = self.regrowth.is_some() || anchor >= floor;
            branch.order == 0 || (anchored && !self.sheds_below(b, floor))
        });
        // Shoots low in the crown sag as far as the crown must reach down.
        let sag = self.fit_sag(&plans, &next);
        let (base, top) = (next.crown_base() as f32, next.height as f32);
        for p in &mut plans {
            p.direction = sag_down(p.direction, sag_at(sag, p.start.z, base, top));
        }
        // Nothing leaves next year's envelope, scaled so the crown comes out as wide as
        // measured: a shoot stops where it would leave it.
        let (scale, stretch) = self.fit_reach(&plans, &next);
        let reach = self.space(&next, scale);
        for p in &mut plans {
            p.length = within(&reach, p.start, p.direction, p.length * stretch);
            // Regrowth after a cut is vigorous, but no shoot of it grows longer in a year
            // than the longest measured on pruned street trees.
            let sprung = if p.lateral {
                let bud = &self.buds[p.from];
                bud.sprout || self.branches[bud.branch as usize].sprung
            } else {
                self.branches[p.from].sprung
            };
            if sprung {
                p.length = p.length.min(LONGEST_REGROWTH);
            }
        }
        plans.retain(|p| p.length > 0.02);
        if !sylleptic {
            self.hold_height(&mut plans, &next, leader_holds);
        }
        let mut budget = self
            .options
            .max_segments
            .saturating_sub(self.segment_count());
        let mut broken = Vec::new();
        for p in plans {
            if budget == 0 {
                break;
            }
            budget -= 1;
            if p.lateral {
                let bud = self.buds[p.from];
                broken.push(p.from);
                self.start_branch(&bud, p.direction, p.length);
            } else {
                self.extend(p.from, p.direction, p.length);
            }
        }
        broken.sort_unstable();
        let mut k = 0;
        let mut index = 0;
        self.buds.retain(|_| {
            let keep = broken.get(k) != Some(&index);
            if !keep {
                k += 1;
            }
            index += 1;
            keep
        });
    }

    /// Whether `bud` (of a shoot of `order`) breaks in the mid-season flush: only a bud of
    /// this year's shoot, and only on a young tree's leader and scaffolds (so its crown keeps up
    /// with a crown base rising fast) or on regrowth after a cut. Vigorous shoots branch in
    /// the year they grow (sylleptic branching: Barthélémy & Caraglio 2007, Annals of Botany
    /// 99:375), and a cut's sprouts are a tree's most vigorous shoots; so its regrowth is
    /// branched in its first season (pruned crowns regained their volume within a year:
    /// Lecigne et al. 2018, Urban For. Urban Green., from laser scans), not a year of whips.
    fn breaks_sylleptic(&self, bud: &Bud, order: u8, age: f64) -> bool {
        let this_year = age - bud.born <= 0.5 + 1e-6;
        let young_leader = order <= 1 && self.targets_now().crown_height < SYLLEPTIC_CROWN;
        let regrowth = bud.sprout || self.branches[bud.branch as usize].sprung;
        this_year && (young_leader || regrowth)
    }

    /// The leader follows the measured height: while the tree is excurrent the trunk's apex
    /// grows straight to next year's height; once it has forked, the highest shoot near the
    /// axis is lifted to reach it, so one of the codominant limbs holds the top.
    fn hold_height(&mut self, plans: &mut Vec<Plan>, next: &Targets, leader_holds: bool) {
        let top = next.height as f32;
        if self.habit.stems > 1 {
            self.hold_stems(plans, next);
        }
        // A trunk cut back to a lateral hands the top to its highest limb, as a forked one does.
        if (leader_holds && !self.branches[0].headed) || self.habit.form == TreeForm::Palm {
            let apex = self.apex_segment(0);
            let rise = top - apex.end().z;
            if rise > 0.02 {
                plans.insert(
                    0,
                    Plan {
                        from: 0,
                        lateral: false,
                        start: apex.end(),
                        direction: Vec3::Z,
                        length: rise,
                    },
                );
            }
            return;
        }
        let highest = plans
            .iter()
            .map(|p| p.start.z + p.direction.z * p.length)
            .fold(self.apex_segment(0).end().z, f32::max);
        // A tree whose leader the street has cut back is no longer held to the measured
        // height: its top grows as its shoots do, wherever the cuts left them room (lifting
        // the highest shoot near the axis would send it into the wire's zone every year).
        if highest >= top - 0.02 || (self.regrowth.is_some() && self.branches[0].headed) {
            return;
        }
        // The apex that is high and near the axis: the one a forester would call the leader.
        // Not the trunk's: it has handed the top to its codominant limbs.
        let score = |p: Vec3| p.z - 0.5 * p.truncate().length();
        let best = (1..self.branches.len())
            .filter(|&b| self.branches[b].alive && !self.branches[b].headed)
            .max_by(|&a, &b| {
                let (sa, sb) = (
                    score(self.apex_segment(a).end()),
                    score(self.apex_segment(b).end()),
                );
                sa.total_cmp(&sb).then(b.cmp(&a))
            })
            .unwrap_or(0);
        let apex = self.apex_segment(best);
        let start = apex.end();
        let i = match plans.iter().position(|p| !p.lateral && p.from == best) {
            Some(i) => i,
            None => {
                plans.push(Plan {
                    from: best,
                    lateral: false,
                    start,
                    direction: apex.direction,
                    length: 0.0,
                });
                plans.len() - 1
            }
        };
        // It climbs steeply: a shoot that rose gently would reach far out of the crown first.
        let p = &mut plans[i];
        let rise = 0.9f32;
        p.length = (top - start.z) / rise;
        // On a tree the street has cut, the leader climbs back no faster than the most
        // vigorous shoot grows in a year: it is held to the measured height again only when
        // it gets there (a tree cut below a wire would otherwise be back at full height in a
        // season).
        if self.regrowth.is_some() {
            p.length = p.length.min(MAX_METAMERS * self.metamer_now());
        }
        let heading = p.direction.truncate().normalize_or(glam::Vec2::X);
        p.direction = (heading * (1.0 - rise * rise).sqrt()).extend(rise);
    }

    /// A multi-stem tree's stems are its trunk: each is held on up to the fork zone above
    /// next year's crown base, as a decurrent trunk is held to its fork, and only there opens
    /// into the crown. Left to the allocation, a stem whose tip the rising crown base passes
    /// sees nothing of the crown's space and stops, and one stem carries the whole crown.
    fn hold_stems(&mut self, plans: &mut Vec<Plan>, next: &Targets) {
        let fork = (next.crown_base() as f32 + FORK_ZONE).min(next.height as f32);
        for b in 1..self.branches.len() {
            let branch = &self.branches[b];
            if !branch.alive || branch.order != 0 || branch.headed {
                continue;
            }
            let apex = self.apex_segment(b);
            let start = apex.end();
            if fork - start.z <= 0.02 {
                continue;
            }
            // On in the stem's own lean, straight: its first shoot's direction.
            let direction = self.segments[branch.segments[0] as usize].direction;
            let length = (fork - start.z) / direction.z.max(0.2);
            match plans.iter_mut().find(|p| !p.lateral && p.from == b) {
                Some(p) => {
                    p.direction = direction;
                    p.length = p.length.max(length);
                }
                None => plans.push(Plan {
                    from: b,
                    lateral: false,
                    start,
                    direction,
                    length,
                }),
            }
        }
    }

    /// Apical control now. A decurrent species keeps a leader until its trunk reaches the
    /// grown tree's crown base (street trees are trained so), then forks within `FORK_ZONE`:
    /// its codominant limbs then leave the trunk where pruning never reaches.
    pub(super) fn apical_control(&self) -> f32 {
        let own = self.habit.apical_control;
        // A multi-stem tree has no leader to hand over: its stems share the top from the start.
        if own >= 0.5 || self.habit.stems > 1 {
            return own;
        }
        let young = 0.56;
        let top = self.apex_segment(0).end().z;
        let grown = ((top - self.fork_height) / FORK_ZONE).clamp(0.0, 1.0);
        young + (own - young) * grown
    }

    /// A new shoot's direction from its bud's: toward its markers, pulled by the habit's
    /// tropism (up; level for a conifer's laterals; down where tips weep), a little at random.
    fn steer(&mut self, d: Vec3, towards: Vec3, order: u8) -> Vec3 {
        let tropism = if order == 0 {
            Vec3::Z * 0.5
        } else if self.habit.form == TreeForm::ExcurrentConifer {
            Vec3::new(0.0, 0.0, -d.z * self.habit.tropism)
        } else {
            Vec3::Z * self.habit.tropism
        };
        let wobble = Vec3::new(
            self.rng.var(1.0) as f32,
            self.rng.var(1.0) as f32,
            self.rng.var(1.0) as f32,
        ) * 0.08;
        let mut out = (d + towards * ENVIRONMENT_WEIGHT + tropism + wobble).normalize_or(d);
        // Only weeping tips hang steeply.
        let lowest = if self.habit.tropism < 0.0 {
            -0.8
        } else {
            -0.34
        };
        if out.z < lowest {
            out = Vec3::new(out.x, out.y, lowest).normalize();
        }
        out
    }

    /// Buds beyond the `LATERALS_PER_SHOOT` most exposed of their shoot stay dormant this
    /// year: their exposure `q` (the buds' part of the sites) is set to nothing, so Borchert-
    /// Honda hands their share to the axis and the buds that do break.
    fn hold_dormant(&self, q: &mut [f32]) {
        let mut order: Vec<usize> = (0..self.buds.len())
            .filter(|&k| {
                let branch = &self.branches[self.buds[k].branch as usize];
                !self.buds[k].sprout && branch.order != 0 && !branch.sprung
            })
            .collect();
        order.sort_by(|&a, &b| {
            self.buds[a]
                .segment
                .cmp(&self.buds[b].segment)
                .then(q[b].total_cmp(&q[a]))
                .then(a.cmp(&b))
        });
        let mut run = 0;
        for (i, &k) in order.iter().enumerate() {
            let same = i > 0 && self.buds[order[i - 1]].segment == self.buds[k].segment;
            run = if same { run + 1 } else { 0 };
            if run >= LATERALS_PER_SHOOT {
                q[k] = 0.0;
            }
        }
    }

    /// A branch's new shoot turned aside from the one before it, the other way each year
    /// (by the habit's `zigzag`): a limb that zig-zags at every year's growth, as a tree's
    /// do where each year's shoot grows on from a bud beside the last one's tip (sympodial
    /// growth) or is bent by the bud's side.
    fn zigzag(&mut self, d: Vec3, b: usize) -> Vec3 {
        let turn = self.habit.zigzag;
        if turn <= 0.0 {
            return d;
        }
        // Aside in the horizontal: a level limb's shoots turn left and right, a rising one's
        // lean from side to side.
        let side = d.cross(Vec3::Z);
        let side = if side.length_squared() > 0.04 {
            side.normalize()
        } else {
            d.any_orthogonal_vector().normalize()
        };
        let sign = if self.branches[b].segments.len().is_multiple_of(2) {
            1.0
        } else {
            -1.0
        };
        let angle = (turn + self.rng.var(turn as f64 * 0.3) as f32).to_radians();
        (d + side * sign * angle.tan()).normalize_or(d)
    }

    /// Length of a metamer this year: a sapling's internodes are short, so its small crown
    /// still branches; they lengthen with the crown to the species' own.
    fn metamer_now(&self) -> f32 {
        let crown = self.targets_now().crown_diameter as f32;
        (crown / 6.0).clamp(0.1, self.metamer)
    }

    /// The segment at a branch's apex.
    pub(super) fn apex_segment(&self, b: usize) -> Segment {
        let last = *self.branches[b]
            .segments
            .last()
            .expect("a branch has a segment");
        self.segments[last as usize]
    }

    pub(super) fn bud_position(&self, bud: &Bud) -> Vec3 {
        let s = &self.segments[bud.segment as usize];
        s.start + s.direction * s.length * bud.at
    }

    /// The crown's space next year: the measured crown, scaled by the fitted spread, less
    /// the reach of the leaves beyond the shoots that carry them (a sapling's few leaves are
    /// drawn large, and they count in its measured crown).
    pub(super) fn space(&self, t: &Targets, scale: f32) -> Space {
        let radius = t.crown_diameter as f32 * 0.5 * scale;
        let overhang = self.leaf_reach * self.drawn_leaf_size().0;
        Space {
            top: t.height as f32,
            base: t.crown_base() as f32,
            radius: (radius - overhang).max(radius * 0.5),
            envelope: self.habit.envelope,
            // Next year's crown, as the targets are.
            grown: self.habit.envelope.grown(self.age + 1.0),
            lobes: self.lobes,
            twist: [self.lobes[2].sin(), self.lobes[2].cos()],
            // A young crown of a few shoots has no limbs to lobe it.
            lobe_depth: LOBE_DEPTH * ((t.crown_diameter as f32 - 3.0) / 3.0).clamp(0.0, 1.0),
        }
    }

    /// Buds below the coming crown base are pruned; buds on dead wood and old dormant ones die.
    fn prune_buds(&mut self, floor: f32) {
        let age = self.age;
        // Once a decurrent trunk has forked, its scaffolds hold back the trunk's buds below
        // the fork for good: the crown is carried by the limbs of the fork, not a broom of
        // shoots from the trunk beneath it.
        let forked = self.apical_control() < 0.5;
        let fork = self.fork_height;
        let keep: Vec<bool> = self
            .buds
            .iter()
            .map(|b| {
                // Until then the trunk's buds stay dormant for good: they sprout again where
                // shed limbs leave light near the crown base (epicormic shoots).
                // A multi-stem tree's stems keep theirs the same way, at any height: they
                // have no fork above which the crown is carried.
                let trunk = self.branches[b.branch as usize].order == 0;
                self.branches[b.branch as usize].alive
                    && (if trunk {
                        b.branch != 0 || !forked || b.sprout || self.bud_position(b).z >= fork
                    } else {
                        age - b.born <= BUD_YEARS
                    })
                    && self.bud_position(b).z >= floor
            })
            .collect();
        let mut it = keep.into_iter();
        self.buds.retain(|_| it.next().unwrap_or(false));
    }

    /// A branch's apex makes this year's shoot.
    pub(super) fn extend(&mut self, b: usize, direction: Vec3, length: f32) {
        let apex = self.apex_segment(b);
        let done = apex.length;
        let id = self.next_segment_id();
        self.segments.push(Segment {
            id,
            branch: b as u32,
            start: apex.end(),
            direction,
            length: 0.0,
            goal: length,
            born: self.age,
        });
        let id = self.segments.len() as u32 - 1;
        let branch = &mut self.branches[b];
        branch.segments.push(id);
        branch.finished += done;
        self.set_buds(b, id);
    }

    /// A lateral bud breaks: a branch of the next order.
    fn start_branch(&mut self, bud: &Bud, direction: Vec3, length: f32) {
        let parent = bud.branch as usize;
        let start = self.bud_position(bud);
        let seg = self.segments[bud.segment as usize];
        let offset = {
            let p = &self.branches[parent];
            let before: f32 = p
                .segments
                .iter()
                .take_while(|&&s| s != bud.segment)
                .map(|&s| self.segments[s as usize].length)
                .sum();
            before + seg.length * bud.at
        };
        let order = (self.branches[parent].order + 1).min(MAX_ORDER);
        // Traumatic reiteration: a sprout starts the architecture again (`Branch::rank`).
        let rank = if bud.sprout {
            sprouts::SPROUT_RANK
        } else {
            self.branches[parent].rank + 1
        }
        .min(MAX_ORDER);
        let anchor = if order == 1 {
            start.z
        } else {
            self.branches[parent].anchor
        };
        let id = self.branches.len() as u32;
        self.branches[parent].children.push(id);
        let branch_id = self.next_branch_id();
        self.branches.push(Branch {
            id: branch_id,
            order,
            rank,
            parent: Some((bud.branch, bud.segment)),
            segments: vec![self.segments.len() as u32],
            next_azimuth: (self.rng.unit() * 360.0) as f32,
            alive: true,
            children: Vec::new(),
            finished: 0.0,
            offset,
            anchor,
            shaded_years: 0,
            headed: false,
            sprung: bud.sprout || self.branches[parent].sprung,
        });
        let segment_id = self.next_segment_id();
        self.segments.push(Segment {
            id: segment_id,
            branch: id,
            start,
            direction,
            length: 0.0,
            goal: length,
            born: self.age,
        });
        self.set_buds(id as usize, self.segments.len() as u32 - 1);
    }

    /// Lateral buds at the nodes of a new shoot, one a metamer, turned about it by the
    /// divergence and leaning out by the habit's branch angle. A palm's trunk has none, and a
    /// branch of the highest rank makes none.
    pub(super) fn set_buds(&mut self, b: usize, segment: u32) {
        let order = self.branches[b].order;
        let rank = self.branches[b].rank;
        if rank >= MAX_ORDER || (order == 0 && self.habit.form == TreeForm::Palm) {
            return;
        }
        let seg = self.segments[segment as usize];
        let n = (seg.goal / self.metamer_now()).round().clamp(1.0, 12.0) as usize;
        let angle = if order == 0 {
            self.habit.branch_angle
        } else {
            self.habit.branch_angle.min(50.0)
        };
        for k in 0..n {
            let azimuth = self.branches[b].next_azimuth;
            self.branches[b].next_azimuth = (azimuth + DIVERGENCE) % 360.0;
            let tilt = (angle + self.rng.var(5.0) as f32).to_radians();
            let direction = leaning_out(seg.direction, azimuth, tilt);
            self.buds.push(Bud {
                branch: b as u32,
                segment,
                at: (k as f32 + 0.5 + 0.3 * self.rng.var(1.0) as f32) / n as f32,
                direction,
                born: self.age,
                sprout: false,
            });
        }
    }
}

/// The direction of a shoot leaving an axis along `axis`: turned `azimuth` degrees about it
/// and tilted `tilt` radians off it, never steeper than 20 degrees below the horizontal.
pub(super) fn leaning_out(axis: Vec3, azimuth: f32, tilt: f32) -> Vec3 {
    let side = Quat::from_axis_angle(axis, azimuth.to_radians())
        * axis.any_orthogonal_vector().normalize();
    let direction = (Quat::from_axis_angle(axis.cross(side).normalize(), tilt) * axis).normalize();
    if direction.z < -0.34 {
        Vec3::new(direction.x, direction.y, -0.34).normalize()
    } else {
        direction
    }
}

/// How far a shoot starting at height z sags, radians: `sag` at the crown base, none at
/// the top.
pub(super) fn sag_at(sag: f32, z: f32, base: f32, top: f32) -> f32 {
    let rel = ((z - base) / (top - base).max(0.1)).clamp(0.0, 1.0);
    sag * (1.0 - rel) * (1.0 - rel)
}

/// `d` turned `sag` radians further down in its vertical plane, never steeper than 40 degrees
/// below the horizontal.
pub(super) fn sag_down(d: Vec3, sag: f32) -> Vec3 {
    if sag <= 0.0 {
        return d;
    }
    let horizontal = d.truncate().normalize_or(glam::Vec2::X);
    let elevation = (d.z.clamp(-1.0, 1.0).asin() - sag).max(-0.7);
    (horizontal * elevation.cos()).extend(elevation.sin())
}

/// The longest length up to `length` at which a shoot from `start` along `direction` ends
/// inside `space` (0 if it starts outside).
pub(super) fn within(space: &Space, start: Vec3, direction: Vec3, length: f32) -> f32 {
    let tip = |l: f32| start + direction * l;
    if space.contains(tip(length)) {
        return length;
    }
    if !space.contains(tip(0.0)) {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, length);
    for _ in 0..16 {
        let mid = 0.5 * (lo + hi);
        if space.contains(tip(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}
