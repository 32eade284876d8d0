//! Shoots made and placed: a new shoot's direction (its markers, the habit's tropism, a
//! zigzag), the dormant buds held back, the space buds colonise, and the branches, segments
//! and lateral buds a year's plans become.

use super::buds::{BUD_YEARS, Bud, ENVIRONMENT_WEIGHT, LATERALS_PER_SHOOT, MAX_ORDER};
use super::colonise::{LOBE_DEPTH, Space};
use super::directions::leaning_out;
use super::*;

impl Grower {
    /// A new shoot's direction from its bud's: toward its markers, pulled by the habit's
    /// tropism (up; level for a conifer's laterals; down where tips weep), a little at random.
    pub(super) fn steer(&mut self, d: Vec3, towards: Vec3, order: u8) -> Vec3 {
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
    pub(super) fn hold_dormant(&self, q: &mut [f32]) {
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
    pub(super) fn zigzag(&mut self, d: Vec3, b: usize) -> Vec3 {
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
    pub(super) fn metamer_now(&self) -> f32 {
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
    pub(super) fn prune_buds(&mut self, floor: f32) {
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
    pub(super) fn start_branch(&mut self, bud: &Bud, direction: Vec3, length: f32) {
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
