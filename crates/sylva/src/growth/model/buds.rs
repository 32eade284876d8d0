//! Buds and shoots at the end of a year: the apical bud continues every branch that still
//! has room, lateral buds start branches of the next order by light, density and chance, and
//! branches past the segment budget make room or die.

use super::*;

impl Grower {
    /// Apical and lateral buds at the end of a year.
    pub(super) fn end_of_year(&mut self) {
        let t = self.targets_now();
        self.make_room();
        let live_segments = self.segment_count();
        let mut budget = self.options.max_segments.saturating_sub(live_segments);
        let bifurcation = (t.crown_diameter / t.crown_height.max(0.1)).atan() as f32;
        let n = self.branches.len();
        for b in 0..n {
            if !self.branches[b].alive {
                continue;
            }
            let last = *self.branches[b]
                .segments
                .last()
                .expect("a branch has a segment");
            let seg = self.segments[last as usize];
            let order = self.branches[b].order;
            if order == 0 {
                self.leader_buds(&mut budget, &t);
            } else if order < 4 {
                // Lateral buds 0.25 m apart along the year's shoot, at most four; each breaks
                // with a probability from light, crowding and chance.
                let buds = ((seg.length / 0.25).round() as usize).clamp(1, 4);
                for k in 0..buds {
                    if budget == 0 {
                        break;
                    }
                    let along = (k as f32 + 0.3 + 0.6 * self.rng.unit() as f32) / buds as f32;
                    let at = seg.start + seg.direction * seg.length * along;
                    let light = self.light.light_at(at);
                    let open = self.light.density_at(at);
                    let p = 0.95 * light.powf(1.5) * open.sqrt();
                    if self.rng.unit() as f32 >= p {
                        continue;
                    }
                    self.add_lateral(b, last, seg.length * along, bifurcation);
                    budget -= 1;
                }
            }
            // The apical bud always continues the branch. A bud that made no shoot this year
            // (the branch had reached its length) is the same bud next year.
            let branch = &self.branches[b];
            if seg.length <= 1e-4 {
                self.segments[last as usize].born = self.age;
            } else if branch.alive && budget > 0 {
                let light_dir = self.light.gradient_at(seg.end());
                let wobble = Vec3::new(
                    self.rng.var(1.0) as f32,
                    self.rng.var(1.0) as f32,
                    self.rng.var(1.0) as f32,
                ) * 0.12;
                let mut d = seg.direction + wobble;
                if order > 0 {
                    d += light_dir.normalize_or_zero() * 0.15;
                } else {
                    d = Vec3::Z + wobble * 0.1;
                }
                let d = d.normalize_or(seg.direction);
                self.segments.push(Segment {
                    branch: b as u32,
                    start: seg.end(),
                    direction: d,
                    aim: d,
                    length: 0.0,
                    born: self.age,
                    budded: 0.0,
                });
                let id = self.segments.len() as u32 - 1;
                self.branches[b].segments.push(id);
                self.branches[b].finished += seg.length;
                budget = budget.saturating_sub(1);
            }
            // Deep shade for years on end kills a side branch: the interior thins out.
            if order >= 2 {
                let dark = self.light.light_at(seg.end()) < 0.05;
                let br = &mut self.branches[b];
                br.shaded_years = if dark { br.shaded_years + 1 } else { 0 };
                if br.shaded_years >= 3 {
                    self.kill(b);
                }
            }
        }
    }

    /// Lateral buds on the leader's shoot grown since its last buds were set: a fourteenth of
    /// the crown height apart, at most 0.35 m, so the crown base can be matched closely. The
    /// leader's buds are the tree's scaffolds: apical control makes them break regularly
    /// wherever there is light. A vigorous leader also branches in mid-season (sylleptic
    /// shoots), so this runs at mid-year too.
    pub(super) fn leader_buds(&mut self, budget: &mut usize, t: &Targets) {
        let last = *self.branches[0]
            .segments
            .last()
            .expect("the trunk has a segment");
        let seg = self.segments[last as usize];
        let fresh = seg.length - seg.budded;
        let node = (t.crown_height as f32 / 14.0).clamp(0.1, 0.35);
        if fresh < node * 0.5 {
            return;
        }
        let bifurcation = (t.crown_diameter / t.crown_height.max(0.1)).atan() as f32;
        let buds = ((fresh / node).round() as usize).clamp(1, 12);
        for k in 0..buds {
            if *budget == 0 {
                break;
            }
            let along =
                seg.budded + fresh * (k as f32 + 0.3 + 0.6 * self.rng.unit() as f32) / buds as f32;
            let at = seg.start + seg.direction * along;
            if (at.z as f64) < t.crown_base() {
                continue;
            }
            let p = 0.95 * self.light.light_at(at).sqrt();
            if self.rng.unit() as f32 >= p {
                continue;
            }
            self.add_lateral(0, last, along, bifurcation);
            *budget -= 1;
        }
        self.segments[last as usize].budded = seg.length;
    }

    pub(super) fn add_lateral(
        &mut self,
        parent: usize,
        segment: u32,
        along: f32,
        bifurcation: f32,
    ) {
        let seg = self.segments[segment as usize];
        let p = &mut self.branches[parent];
        let azimuth = p.next_azimuth;
        p.next_azimuth = (p.next_azimuth + DIVERGENCE) % 360.0;
        let order = p.order + 1;
        let (c_l_parent, c_d_parent) = (p.c_l, p.c_d);
        let breakout = order >= 2 && self.rng.unit() < 0.05;
        let s_l = if breakout {
            1.2 + 0.3 * self.rng.unit() as f32
        } else {
            0.6 + 0.4 * self.rng.unit() as f32
        };
        let c_l = if order == 1 { s_l } else { c_l_parent * s_l };
        let c_d = c_l.min(1.0) * c_d_parent * (1.0 - 0.7 * c_d_parent);
        // Bifurcation angle from the crown's proportions, a few degrees either way, turned
        // about the parent by the divergence.
        let angle = bifurcation + (self.rng.var(5.0) as f32).to_radians();
        let axis = seg.direction;
        let side = axis.any_orthogonal_vector().normalize();
        let side = Quat::from_axis_angle(axis, azimuth.to_radians()) * side;
        let mut direction =
            (Quat::from_axis_angle(axis.cross(side).normalize(), angle) * axis).normalize();
        // Laterals of side branches keep out of the ground's way: never steeper than 20
        // degrees below the horizontal.
        if direction.z < -0.34 {
            direction = Vec3::new(direction.x, direction.y, -0.34).normalize();
        }
        let start = seg.start + seg.direction * along;
        let id = self.branches.len() as u32;
        let offset = {
            let p = &self.branches[parent];
            let mut before = 0.0;
            for &s in &p.segments {
                if s == segment {
                    break;
                }
                before += self.segments[s as usize].length;
            }
            before + along
        };
        let anchor = if order == 1 {
            start.z
        } else {
            self.branches[parent].anchor
        };
        self.branches[parent].children.push(id);
        self.branches.push(Branch {
            order,
            parent: Some((parent as u32, segment)),
            along,
            s_l,
            c_l,
            c_d,
            segments: vec![self.segments.len() as u32],
            next_azimuth: (self.rng.unit() * 360.0) as f32,
            alive: true,
            children: Vec::new(),
            finished: 0.0,
            offset,
            anchor,
            shaded_years: 0,
        });
        self.segments.push(Segment {
            branch: self.branches.len() as u32 - 1,
            start,
            direction,
            aim: direction,
            length: 0.0,
            born: self.age,
            budded: 0.0,
        });
    }

    /// Near the segment budget, the darkest side branches die, so the crown keeps renewing
    /// itself at its lit surface instead of freezing when the budget is spent: the interior
    /// turnover of a real crown, hastened.
    pub(super) fn make_room(&mut self) {
        let max = self.options.max_segments;
        let live = self.segment_count();
        if live * 20 < max * 17 {
            return;
        }
        let goal = max * 4 / 5;
        let mut dark: Vec<(f32, usize)> = self
            .branches
            .iter()
            .enumerate()
            .filter(|(_, b)| b.alive && b.order >= 2)
            .map(|(i, b)| {
                let last = &self.segments[*b.segments.last().expect("a segment") as usize];
                (self.light.light_at(last.end()), i)
            })
            .collect();
        dark.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut left = live;
        for (_, b) in dark {
            if left <= goal {
                break;
            }
            if self.branches[b].alive {
                left -= self.kill(b);
            }
        }
    }

    /// Marks a branch and everything on it dead.
    /// Returns how many live segments died.
    pub(super) fn kill(&mut self, b: usize) -> usize {
        let mut stack = vec![b];
        let mut segments = 0;
        while let Some(b) = stack.pop() {
            if !self.branches[b].alive {
                continue;
            }
            self.branches[b].alive = false;
            segments += self.branches[b].segments.len();
            stack.extend(self.branches[b].children.iter().map(|&c| c as usize));
        }
        segments
    }
}
