//! The growth model (Rudnick et al. 2007 with Linsen et al. 2005): branches made of annual
//! segments, grown in steps of 1/n year. In its first year a segment elongates (primary
//! growth); after that it only thickens (secondary growth). At the end of a year the apical
//! bud continues every branch that still has room to grow, and lateral buds start branches of
//! the next order with a probability from light, local density and chance. Lengths come from
//! the crown shape function and the measured crown, radii from f_DBH, angles from f_CD / f_CH.
//!
//! The model is fitted to the data the way the seeds' title says, by inverse modelling: one
//! gain on branch length is corrected every step so that the crown's measured diameter follows
//! f_CD; the trunk follows f_H; lower branches are shed as the crown base (monotone) rises;
//! the leaves on young, thin, lit shoots add up to f_LA.

use super::light::{LightGrid, Ray, daylight};
use super::measured::Measured;
use crate::rng::{Random, StreamKey};
use crate::skeleton::{CrossSection, Leaf, LeafShape, Skeleton, Stem, StemId};
use glam::{Quat, Vec3};
use std::f32::consts::PI;

/// Height at which DBH is measured, m.
pub const BREAST_HEIGHT: f32 = 1.37;
/// Most light cells along an axis.
const MAX_LIGHT_CELLS: usize = 28;
/// Divergence between successive laterals of a branch, degrees (scaffolds spiral evenly).
const DIVERGENCE: f32 = 130.0;
/// Years before the first fitted age in which the tree is brought up from a small sapling.
const NURSERY_YEARS: f64 = 3.0;
/// Leaves grow on shoots at most this many years old...
const LEAF_SHOOT_YEARS: f64 = 2.0;
/// ...thinner than this (radius, m)...
const LEAF_MAX_RADIUS: f32 = 0.02;
/// ...with at least this much light.
const LEAF_MIN_LIGHT: f32 = 0.12;

/// The shape of a crown: the relative length c(p) of a branch starting at relative position p
/// along its parent (0 base, 1 tip), at most 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CrownShape {
    /// Widest at mid-height (Rudnick's figure 2).
    Ellipse,
    /// Widest at the base, as conifers and the southern magnolia.
    Cone,
    /// Widest a third of the way up, a rounded dome.
    Dome,
    /// Widest near the top, narrow at the base: vase-shaped.
    Vase,
}

impl CrownShape {
    /// c(p).
    pub fn relative_length(self, p: f32) -> f32 {
        let p = p.clamp(0.0, 1.0);
        match self {
            CrownShape::Ellipse => 2.0 * (p * (1.0 - p)).sqrt(),
            CrownShape::Cone => (1.0 - p).powf(0.9),
            CrownShape::Dome => {
                let q = ((p - 0.33) / if p < 0.33 { 0.45 } else { 0.67 }).clamp(-1.0, 1.0);
                (1.0 - q * q).sqrt()
            }
            CrownShape::Vase => {
                let q = ((p - 0.72) / if p < 0.72 { 0.8 } else { 0.28 }).clamp(-1.0, 1.0);
                (1.0 - q * q).sqrt()
            }
        }
    }

    /// The shape for a species: a few known street trees by code, otherwise by the database's
    /// tree type (conifers conical, the rest elliptical).
    pub fn for_species(code: &str, tree_type: &str) -> CrownShape {
        match code {
            "MAGR" => CrownShape::Cone,
            "PICH" | "KOPA" | "PLAC" => CrownShape::Dome,
            "CESI4" | "ZESE" | "ULPA" => CrownShape::Vase,
            _ if tree_type.starts_with('C') => CrownShape::Cone,
            _ => CrownShape::Ellipse,
        }
    }

    /// How far the crown's top falls from the leader to the crown's edge, as a share of the
    /// crown height: a rounded top for broadleaves. A cone needs none: the reach of its
    /// scaffolds already narrows to the top (a roof there made its branches dive).
    pub fn roof(self) -> f32 {
        match self {
            CrownShape::Ellipse => 0.4,
            CrownShape::Cone => 0.0,
            CrownShape::Dome => 0.35,
            CrownShape::Vase => 0.2,
        }
    }

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            CrownShape::Ellipse => "ellipse",
            CrownShape::Cone => "cone",
            CrownShape::Dome => "dome",
            CrownShape::Vase => "vase",
        }
    }
}

/// Settings of a growth run.
#[derive(Clone, Debug, PartialEq)]
pub struct GrowthOptions {
    /// Seed: the same seed gives the same tree at every age.
    pub seed: u64,
    /// Growth steps per year (Rudnick: 20).
    pub steps_per_year: u32,
    /// Most branch segments the tree may hold; past it lateral buds stay dormant.
    pub max_segments: usize,
    /// Most leaves the skeleton may carry; a larger leaf area is drawn with larger leaves.
    pub max_leaves: usize,
    /// Light cell size, m.
    pub light_cell: f32,
}

impl Default for GrowthOptions {
    fn default() -> Self {
        GrowthOptions {
            seed: 0,
            steps_per_year: 20,
            max_segments: 60_000,
            max_leaves: 120_000,
            light_cell: 0.5,
        }
    }
}

/// What one branch is.
#[derive(Clone, Debug)]
struct Branch {
    order: u8,
    /// Parent branch and the segment it grows from.
    parent: Option<(u32, u32)>,
    /// Where on the parent segment it starts, m from the segment's start.
    along: f32,
    /// Length scale s_l and the cumulated c_l.
    s_l: f32,
    c_l: f32,
    /// Diameter factor c_d.
    c_d: f32,
    /// Segments, oldest first.
    segments: Vec<u32>,
    /// Azimuth of this branch's next lateral, degrees.
    next_azimuth: f32,
    alive: bool,
    /// Branches growing from this one.
    children: Vec<u32>,
    /// Length of its finished segments (all but the last), m.
    finished: f32,
    /// Distance along the parent to where it starts, m (fixed: it starts on a finished
    /// segment).
    offset: f32,
    /// Height where its scaffold (its order-1 ancestor, or itself) leaves the trunk, m: the
    /// crown shape function is read there.
    anchor: f32,
    /// Consecutive years its apex has been deep in shade.
    shaded_years: u8,
}

/// One annual segment.
#[derive(Clone, Copy, Debug)]
struct Segment {
    branch: u32,
    start: Vec3,
    direction: Vec3,
    /// Direction the bud set out in: while the shoot elongates it sags from here, and bends
    /// to stay under the crown's top and above its base.
    aim: Vec3,
    length: f32,
    /// Age of the tree when it started.
    born: f64,
    /// Length of it on which lateral buds have been set, m.
    budded: f32,
}

impl Segment {
    fn end(&self) -> Vec3 {
        self.start + self.direction * self.length
    }
}

/// Targets at an age: the measured functions, ramped up from a sapling before the first
/// fitted age.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Targets {
    /// Height, m.
    pub height: f64,
    /// Crown diameter, m.
    pub crown_diameter: f64,
    /// Crown height (monotone crown base), m.
    pub crown_height: f64,
    /// DBH, cm.
    pub dbh: f64,
    /// Leaf area, m².
    pub leaf_area: f64,
}

impl Targets {
    /// The measured functions at age `t`, as they are.
    pub fn of(m: &Measured, t: f64) -> Targets {
        Targets {
            height: m.height(t),
            crown_diameter: m.crown_diameter(t),
            crown_height: m.crown_height(t),
            dbh: m.dbh(t),
            leaf_area: m.leaf_area(t),
        }
    }

    /// Height to the crown base, m.
    pub fn crown_base(&self) -> f64 {
        self.height - self.crown_height
    }
}

/// Time spent in the last step, seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepTimes {
    /// Production rules.
    pub growth: f64,
    /// Densities and rays.
    pub light: f64,
}

/// A tree growing over the years.
pub struct Grower {
    measured: Measured,
    shape: CrownShape,
    options: GrowthOptions,
    age: f64,
    key: StreamKey,
    rng: Random,
    branches: Vec<Branch>,
    segments: Vec<Segment>,
    light: LightGrid,
    sky: Vec<Ray>,
    /// Inverse-modelling gain on branch length (fits the crown diameter).
    gain: f64,
    /// Inverse-modelling sag of young shoots in the lower crown, radians (fits the crown
    /// height).
    droop: f64,
    /// Inverse-modelling scale of the crown envelope, about 1.
    spread: f64,
    /// Leaf blade length and width, m, and area of one leaf, m².
    leaf_size: (f32, f32),
    leaf_shape: LeafShape,
    /// Least distance between leaves along a shoot, m.
    leaf_spacing: f32,
    /// Leaves per segment, from the last allocation.
    leaves_on: Vec<u16>,
    /// f_DBH (cm) of the ramped curve, by steps from the nursery's start.
    dbh_by_step: Vec<f32>,
    /// Base radius of every segment this step (0 for dead ones): leaf allocation and the
    /// light's densities both need them.
    radii: Vec<f32>,
    /// Area factor of each leaf where shoots are too few to carry the leaf area.
    leaf_boost: f32,
    /// Time spent in the last step.
    pub times: StepTimes,
}

impl Grower {
    /// A sapling of the species, `NURSERY_YEARS` before its first fitted age, brought up to
    /// that age.
    pub fn new(measured: Measured, options: GrowthOptions) -> Self {
        let mut g = Self::sapling(measured, options);
        let first = g.measured.ages.0;
        g.advance_to(first);
        g
    }

    /// The sapling `NURSERY_YEARS` before the first fitted age: a trunk alone.
    pub(crate) fn sapling(measured: Measured, options: GrowthOptions) -> Self {
        let shape = CrownShape::for_species(&measured.species.code, &measured.species.tree_type);
        let conifer = measured.species.tree_type.starts_with('C');
        // A conifer's "leaf" is a tuft of needles, set far closer along the shoot than a
        // broadleaf's leaves.
        let (leaf_size, leaf_shape, leaf_spacing) = if conifer {
            ((0.12, 0.03), LeafShape::Palm, 0.004)
        } else {
            ((0.14, 0.1), LeafShape::Oval, 0.012)
        };
        // Refitted to the tree's bounds every step: cells outside a crown are empty, so
        // light there needs no walking.
        let light = LightGrid::new(Vec3::ZERO, Vec3::ONE, options.light_cell, MAX_LIGHT_CELLS);
        let key = StreamKey::from_seed(options.seed);
        let start = measured.ages.0 - NURSERY_YEARS;
        let mut g = Grower {
            shape,
            age: start,
            rng: key.child(1).stream(),
            key,
            branches: Vec::new(),
            segments: Vec::new(),
            light,
            sky: daylight(),
            gain: 1.0,
            droop: 0.3,
            spread: 1.0,
            leaf_size,
            leaf_shape,
            leaf_spacing,
            leaves_on: Vec::new(),
            radii: Vec::new(),
            dbh_by_step: Vec::new(),
            leaf_boost: 1.0,
            times: StepTimes::default(),
            options,
            measured,
        };
        let t = g.targets(start);
        // The gain at which an average scaffold (s_l and c(p) about 0.8) leaving the trunk at
        // the bifurcation angle reaches the measured crown radius.
        let angle = (t.crown_diameter / t.crown_height.max(0.1)).atan();
        g.gain = t.crown_diameter / (1.28 * angle.sin() * t.crown_height.max(0.3));
        // The trunk: order 0, one segment, growing straight up.
        g.branches.push(Branch {
            order: 0,
            parent: None,
            along: 0.0,
            s_l: 1.0,
            c_l: 1.0,
            c_d: 1.0,
            segments: vec![0],
            next_azimuth: 0.0,
            alive: true,
            children: Vec::new(),
            finished: 0.0,
            offset: 0.0,
            anchor: 0.0,
            shaded_years: 0,
        });
        g.segments.push(Segment {
            branch: 0,
            start: Vec3::ZERO,
            direction: Vec3::Z,
            aim: Vec3::Z,
            length: t.height as f32,
            born: start,
            budded: 0.0,
        });
        g.refresh_radii();
        g.update_light();
        g
    }

    /// The measured functions this tree follows.
    pub fn measured(&self) -> &Measured {
        &self.measured
    }

    /// The inverse-modelling gain on scaffold length now.
    pub fn gain(&self) -> f64 {
        self.gain
    }

    /// The crown shape used.
    pub fn shape(&self) -> CrownShape {
        self.shape
    }

    /// Current age, years since planting.
    pub fn age(&self) -> f64 {
        self.age
    }

    /// Live branch segments.
    pub fn segment_count(&self) -> usize {
        self.branches
            .iter()
            .filter(|b| b.alive)
            .map(|b| b.segments.len())
            .sum()
    }

    /// The light grid after the last step.
    pub fn light(&self) -> &LightGrid {
        &self.light
    }

    /// The targets at age `t`: the measured functions inside their range; before it, a
    /// sapling ramping up to them.
    pub fn targets(&self, t: f64) -> Targets {
        let first = self.measured.ages.0;
        let ramp = if t < first {
            (0.4 + 0.6 * (1.0 - (first - t) / NURSERY_YEARS)).clamp(0.4, 1.0)
        } else {
            1.0
        };
        // Before the fitted range the equations mean nothing (a log-log fit runs to zero at
        // age 0): the sapling is the tree at the first age, scaled down.
        let m = Targets::of(&self.measured, t.max(first));
        Targets {
            height: m.height * ramp,
            crown_diameter: m.crown_diameter * ramp,
            crown_height: m.crown_height * ramp,
            dbh: m.dbh * ramp,
            leaf_area: m.leaf_area * ramp,
        }
    }

    /// Grows until `age` (never backwards: a tree that is older stays as it is).
    pub fn advance_to(&mut self, age: f64) {
        let dt = self.step_length();
        while self.age + dt * 0.5 < age {
            self.step_once(dt);
        }
    }

    /// One growth step of `dt` years.
    pub fn step_once(&mut self, dt: f64) {
        let t0 = std::time::Instant::now();
        let before = self.age;
        self.age += dt;
        // End of a year: primary growth of this year's segments ends; buds break.
        if (before + 1e-9).floor() < (self.age + 1e-9).floor() {
            self.end_of_year();
        } else if (before + 0.5 + 1e-9).floor() < (self.age + 0.5 + 1e-9).floor() {
            let t = self.targets_now();
            let mut budget = self
                .options
                .max_segments
                .saturating_sub(self.segment_count());
            self.leader_buds(&mut budget, &t);
        }
        self.elongate();
        self.shed();
        self.fit_crown();
        self.refresh_radii();
        self.allocate_leaves();
        let t1 = std::time::Instant::now();
        self.update_light();
        self.times = StepTimes {
            growth: (t1 - t0).as_secs_f64(),
            light: t1.elapsed().as_secs_f64(),
        };
    }

    fn targets_now(&self) -> Targets {
        self.targets(self.age)
    }

    /// Apical and lateral buds at the end of a year.
    fn end_of_year(&mut self) {
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
    fn leader_buds(&mut self, budget: &mut usize, t: &Targets) {
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

    fn add_lateral(&mut self, parent: usize, segment: u32, along: f32, bifurcation: f32) {
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
    fn make_room(&mut self) {
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
    fn kill(&mut self, b: usize) -> usize {
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

    /// Primary growth: the last segment of every growing branch reaches for the branch's
    /// target length.
    fn elongate(&mut self) {
        let t = self.targets_now();
        let top = t.height as f32;
        let base = t.crown_base() as f32;
        let leaf = self.drawn_leaf_size().0;
        for b in 0..self.branches.len() {
            let branch = &self.branches[b];
            if !branch.alive {
                continue;
            }
            let finished = branch.finished;
            let last = *branch.segments.last().expect("a segment") as usize;
            let seg = self.segments[last];
            let target = if branch.order == 0 {
                top
            } else {
                let (parent, pseg) = branch.parent.expect("a side branch has a parent");
                let pb = &self.branches[parent as usize];
                // Relative position p_r along the parent; for the trunk, within the crown.
                let (p_r, l_p) = if pb.order == 0 {
                    let z = self.segments[pseg as usize].start.z
                        + self.segments[pseg as usize].direction.z * branch.along;
                    ((z - base) / (top - base).max(0.1), (top - base).max(0.1))
                } else {
                    let last = *pb.segments.last().expect("a segment") as usize;
                    let l_p = pb.finished + self.segments[last].length;
                    (branch.offset / l_p.max(1e-3), l_p)
                };
                // Little light at the apex: the branch reaches further, out of the shade.
                let apex_light = self.light.light_at(seg.end());
                let reach = 1.0 + 0.5 * (1.0 - apex_light).clamp(0.0, 1.0);
                let order_factor = 0.5 + 0.5 * branch.order as f32;
                let gain = if branch.order == 1 {
                    self.gain as f32
                } else {
                    1.0
                };
                gain * branch.s_l * reach * self.shape.relative_length(p_r) * l_p / order_factor
            };
            let mut length = (target - finished).max(seg.length);
            if branch.order == 0 {
                length = target - finished;
            } else if length > seg.length {
                let rel = (branch.anchor - base) / (top - base).max(0.1);
                // A shoot in its first year sags from where its bud aimed, the more the lower
                // in the crown its scaffold leaves the trunk; the sag is fitted to the crown
                // height. It bends rather than pass above the leader or below the crown base
                // (where its leaves would hang out of the measured crown).
                let direction = if self.age - seg.born < 1.0 {
                    let sag = self.droop as f32 * (1.0 - rel).clamp(0.0, 1.0).powi(2);
                    let floor = base + leaf;
                    // The crown's top is rounded: the ceiling falls away from the leader by
                    // the shape's roof over the crown's radius (once more, for where the bent
                    // tip ends up).
                    let radius = (t.crown_diameter * 0.5 * self.spread) as f32;
                    let roof = self.shape.roof() * (top - base);
                    let ceiling =
                        |r: f32| top - 0.05 - roof * (r / radius.max(0.1)).min(1.0).powi(2);
                    let aimed = sag_down(seg.aim, sag);
                    let mut d = aimed;
                    for _ in 0..2 {
                        let r = (seg.start + d * length).truncate().length();
                        d = within_heights(aimed, seg.start, length, floor, ceiling(r).max(floor));
                    }
                    d
                } else {
                    seg.direction
                };
                self.segments[last].direction = direction;
                // Nothing leaves the crown's envelope: the measured crown diameter shaped by
                // c(p) at each height. Break-outs may go 15% past it.
                let slack = if branch.s_l > 1.0 { 1.15 } else { 1.0 };
                let half = (t.crown_diameter * 0.5 * self.spread) as f32 * slack;
                let reach = half * self.shape.relative_length(rel).max(0.15);
                let inside = |p: Vec3| p.z <= top - 0.04 && p.truncate().length() <= reach;
                let tip = |l: f32| seg.start + direction * l;
                if !inside(tip(length)) {
                    // The longest length whose tip is inside, by bisection from the current
                    // one (which may itself be outside if the crown base rose: then no growth).
                    let (mut lo, mut hi) = (seg.length, length);
                    if inside(tip(lo)) {
                        for _ in 0..20 {
                            let mid = 0.5 * (lo + hi);
                            if inside(tip(mid)) {
                                lo = mid;
                            } else {
                                hi = mid;
                            }
                        }
                    }
                    length = lo;
                }
            }
            self.segments[last].length = length.max(0.0);
        }
    }

    /// Sheds what the rising crown base leaves below it.
    fn shed(&mut self) {
        let base = self.targets_now().crown_base() as f32;
        for b in 1..self.branches.len() {
            if !self.branches[b].alive {
                continue;
            }
            // Scaffolds go when the crown base passes where they leave the trunk; smaller
            // branches as soon as any of them hangs below it.
            let branch = &self.branches[b];
            let lowest = if branch.order == 1 {
                self.segments[branch.segments[0] as usize].start.z
            } else {
                branch
                    .segments
                    .iter()
                    .map(|&s| {
                        let s = &self.segments[s as usize];
                        s.start.z.min(s.end().z)
                    })
                    .fold(f32::INFINITY, f32::min)
            };
            if lowest < base - 0.02 {
                self.kill(b);
            }
        }
    }

    /// The crown's diameter and height now, measured as `measure` measures the skeleton: the
    /// mean of the x and y extents of the branches and their leaves, and the top of the tree
    /// less the lowest point of either.
    pub(crate) fn crown_now(&self) -> (f64, f64) {
        self.crown_above(f32::NEG_INFINITY)
    }

    /// `crown_now` of the branches whose scaffolds leave the trunk at or above `base`.
    fn crown_above(&self, base: f32) -> (f64, f64) {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        let mut top = f32::NEG_INFINITY;
        let counted = |b: &Branch| b.alive && b.order > 0 && b.anchor >= base;
        for s in &self.segments {
            let b = &self.branches[s.branch as usize];
            if b.alive {
                top = top.max(s.end().z);
            }
            if counted(b) && s.length > 1e-4 {
                lo = lo.min(s.start.min(s.end()));
                hi = hi.max(s.start.max(s.end()));
            }
        }
        if lo.x > hi.x {
            return (0.0, 0.0);
        }
        // Leaves widen the crown only where a shoot comes within a leaf's length of its
        // bounds: those branches' leaves are placed exactly as the skeleton places them.
        let leaf = self.drawn_leaf_size().0;
        let tree_top = self.targets_now().height as f32;
        let (wood_lo, wood_hi) = (lo, hi);
        let near_edge = |p: Vec3| {
            p.x - leaf < wood_lo.x
                || p.y - leaf < wood_lo.y
                || p.z - leaf < wood_lo.z
                || p.x + leaf > wood_hi.x
                || p.y + leaf > wood_hi.y
        };
        for (i, b) in self.branches.iter().enumerate() {
            // The leader's young shoot carries leaves too: always look at those.
            if (i > 0 && !counted(b))
                || !b.segments.iter().any(|&si| {
                    let s = &self.segments[si as usize];
                    self.leaves_on.get(si as usize).is_some_and(|&n| n > 0)
                        && (near_edge(s.start) || near_edge(s.end()))
                })
            {
                continue;
            }
            self.for_each_leaf(i, leaf, tree_top, |p, q| {
                let tip = p + q * Vec3::new(0.0, 0.0, leaf);
                lo = lo.min(p.min(tip));
                hi = hi.max(p.max(tip));
            });
        }
        (
            (((hi.x - lo.x) + (hi.y - lo.y)) / 2.0) as f64,
            (top - lo.z).max(0.0) as f64,
        )
    }

    /// Inverse modelling: corrects the length gain toward the measured crown diameter and the
    /// sag toward the measured crown height.
    fn fit_crown(&mut self) {
        let t = self.targets_now();
        let (diameter, height) = self.crown_now();
        // The gain steers the crown that will still be there in a year: scaffolds the crown
        // base is about to pass are shed soon whatever their length.
        let coming_base = self.targets(self.age + 1.0).crown_base() as f32;
        let (mut coming, _) = self.crown_above(coming_base);
        if coming <= 1e-3 {
            coming = diameter;
        }
        if diameter > 1e-3 {
            // Two corrections. The gain lets branches reach for a crown a fifth wider than
            // measured, so their tips meet the envelope; the envelope's scale then holds the
            // crown to the measured diameter. It also widens where a sparse crown (a
            // sapling's few scaffolds) meets its envelope in only a few directions. Both move
            // a little every step: the crown answers a year late, so haste overshoots.
            let ratio = (1.2 * t.crown_diameter / coming)
                .powf(0.5)
                .clamp(0.95, 1.05);
            self.gain = (self.gain * ratio).clamp(0.05, 20.0);
            let ratio = (t.crown_diameter / diameter).clamp(0.97, 1.03);
            self.spread = (self.spread * ratio).clamp(0.8, 1.6);
        }
        if height > 1e-3 {
            let short = (t.crown_height - height) / t.crown_height.max(0.1);
            self.droop = (self.droop + (0.5 * short).clamp(-0.03, 0.03)).clamp(0.0, 1.5);
        }
    }

    fn refresh_radii(&mut self) {
        // f_DBH along the sapling-ramped curve, by whole steps from the nursery's start: a
        // segment's radius depends only on its age, and ages come in steps.
        let dt = self.step_length();
        let start = self.measured.ages.0 - NURSERY_YEARS;
        let steps = ((self.age - start) / dt).round().max(0.0) as usize + 1;
        for k in self.dbh_by_step.len()..steps {
            let d = self.targets(start + k as f64 * dt).dbh;
            self.dbh_by_step.push(d as f32);
        }
        let radii: Vec<f32> = self
            .segments
            .iter()
            .map(|s| {
                if self.branches[s.branch as usize].alive {
                    self.radius_at_base(s)
                } else {
                    0.0
                }
            })
            .collect();
        self.radii = radii;
    }

    fn step_length(&self) -> f64 {
        1.0 / self.options.steps_per_year.max(1) as f64
    }

    /// Radius of a segment's base section now, m.
    fn radius_at_base(&self, s: &Segment) -> f32 {
        let b = &self.branches[s.branch as usize];
        if b.order == 0 {
            self.trunk_radius(s.start.z)
        } else {
            // f_DBH of the segment's own age, read on the sapling-ramped curve.
            let age = (self.age - s.born).max(0.0);
            let k = (age / self.step_length()).round() as usize;
            let d = match self.dbh_by_step.get(k) {
                Some(&d) => d as f64,
                None => self.targets(self.measured.ages.0 - NURSERY_YEARS + age).dbh,
            };
            (b.c_d as f64 * d / 200.0) as f32
        }
    }

    /// Trunk radius at height z, m: the DBH of the tree when the leader passed breast height,
    /// shifted by how much later the leader passed z, so the trunk tapers and is f_DBH(t)
    /// exactly at 1.37 m.
    fn trunk_radius(&self, z: f32) -> f32 {
        let passed = |z: f32| -> f64 {
            // The age at which the target height first reached z (bisection on the ramped,
            // rising height).
            let (mut lo, mut hi) = (self.measured.ages.0 - NURSERY_YEARS, self.age);
            if self.targets(lo).height >= z as f64 {
                return lo;
            }
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if self.targets(mid).height < z as f64 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            hi
        };
        let shift = passed(z) - passed(BREAST_HEIGHT);
        let d = self.targets(self.age - shift).dbh;
        let top = self.targets_now().height as f32;
        // Thin to a point over the leader's last half metre (less on a sapling, never down
        // to breast height).
        let zone = ((top - BREAST_HEIGHT) * 0.9).clamp(0.05, 0.5);
        let tip = ((top - z) / zone).clamp(0.05, 1.0);
        (d / 200.0) as f32 * tip
    }

    /// Leaves on young, thin, lit shoots, adding up to f_LA.
    fn allocate_leaves(&mut self) {
        let t = self.targets_now();
        // Shoots low enough for their leaves to hang below the crown base carry none (see
        // `for_each_leaf`).
        let floor = t.crown_base() as f32 + 0.5 * self.drawn_leaf_size().0;
        let area = self.leaf_area_each();
        let wanted = (t.leaf_area / area as f64).round() as usize;
        // A branch's outermost shoot stays leafy however old it is: its bud renews it.
        let mut tip_shoot = vec![false; self.segments.len()];
        for b in self.branches.iter().filter(|b| b.alive && b.order > 0) {
            if let Some(&s) = b
                .segments
                .iter()
                .rev()
                .find(|&&s| self.segments[s as usize].length > 1e-4)
            {
                tip_shoot[s as usize] = true;
            }
        }
        let radii = &self.radii;
        let lights: Vec<f32> = self
            .segments
            .iter()
            .map(|s| self.light.light_at(s.start + s.direction * s.length * 0.5))
            .collect();
        // Young, thin, lit shoots first; where they cannot hold the measured leaf area, older
        // and thicker wood carries leaves too (spurs), step by step.
        let levels = [
            (LEAF_SHOOT_YEARS, LEAF_MAX_RADIUS, LEAF_MIN_LIGHT),
            (4.0, 0.03, 0.08),
            (8.0, 0.05, 0.04),
            (f64::INFINITY, f32::INFINITY, 0.0),
        ];
        let mut weights = vec![0.0f32; self.segments.len()];
        let mut capacity = vec![0u32; self.segments.len()];
        for (k, &(years, radius, min_light)) in levels.iter().enumerate() {
            let mut room = 0usize;
            for (i, s) in self.segments.iter().enumerate() {
                let b = &self.branches[s.branch as usize];
                // The leader's young shoot is leafy too, or it would stand bare above the
                // crown.
                let leader = b.order == 0 && self.age - s.born <= LEAF_SHOOT_YEARS;
                let eligible = b.alive
                    && (b.order > 0 || leader)
                    && s.start.z.min(s.end().z) >= floor
                    && (self.age - s.born <= years || tip_shoot[i])
                    && radii[i] <= radius
                    && lights[i] >= min_light;
                capacity[i] = if eligible {
                    (s.length / self.leaf_spacing).floor() as u32
                } else {
                    0
                };
                weights[i] = if eligible {
                    s.length * lights[i].max(0.01)
                } else {
                    0.0
                };
                room += capacity[i] as usize;
            }
            if room >= wanted || k == levels.len() - 1 {
                break;
            }
        }
        let total: f32 = weights.iter().sum();
        self.leaves_on.clear();
        self.leaves_on.resize(self.segments.len(), 0);
        if total <= 0.0 {
            return;
        }
        let mut carry = 0.0f32;
        let mut placed = 0usize;
        for i in 0..self.segments.len() {
            if weights[i] == 0.0 {
                continue;
            }
            let share = wanted as f32 * weights[i] / total + carry;
            let n = (share.floor() as u32).min(capacity[i]).min(u16::MAX as u32);
            carry = share - n as f32;
            self.leaves_on[i] = n as u16;
            placed += n as usize;
        }
        // What full shoots could not take goes to shoots with room left.
        for (on, &cap) in self.leaves_on.iter_mut().zip(&capacity) {
            if placed >= wanted {
                break;
            }
            let spare = cap.min(u16::MAX as u32) - *on as u32;
            let n = (spare as usize).min(wanted - placed);
            *on += n as u16;
            placed += n;
        }
        // A sapling with too little shoot for its measured leaf area carries larger leaves
        // (at most five times the area).
        self.leaf_boost = if placed > 0 && placed < wanted {
            (wanted as f32 / placed as f32).min(5.0)
        } else {
            1.0
        };
    }

    /// Length and width of a leaf as drawn, m.
    fn drawn_leaf_size(&self) -> (f32, f32) {
        let natural = self.leaf_size.0
            * self.leaf_size.1
            * crate::mesh::leaf_template(self.leaf_shape).area();
        let k = (self.leaf_area_each() * self.leaf_boost / natural).sqrt();
        (self.leaf_size.0 * k, self.leaf_size.1 * k)
    }

    /// Area of one leaf as drawn, m² (larger than life when the leaf budget is reached).
    fn leaf_area_each(&self) -> f32 {
        let template = crate::mesh::leaf_template(self.leaf_shape).area();
        let natural = self.leaf_size.0 * self.leaf_size.1 * template;
        let t = self.targets_now();
        let needed = t.leaf_area as f32 / self.options.max_leaves as f32;
        natural.max(needed)
    }

    /// Densities from every live segment and its leaves, then the rays.
    fn update_light(&mut self) {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for s in &self.segments {
            if self.branches[s.branch as usize].alive {
                lo = lo.min(s.start.min(s.end()));
                hi = hi.max(s.start.max(s.end()));
            }
        }
        let margin = Vec3::splat(self.leaf_size.0 + self.options.light_cell);
        self.light.reshape(
            lo - margin,
            hi + margin,
            self.options.light_cell,
            MAX_LIGHT_CELLS,
        );
        let leaf_area = if self.segments.is_empty() {
            0.0
        } else {
            self.leaf_area_each() * self.leaf_boost
        };
        let cell = self.light.cell;
        for (i, s) in self.segments.iter().enumerate() {
            let b = &self.branches[s.branch as usize];
            if !b.alive || s.length <= 0.0 {
                continue;
            }
            let r = self.radii[i];
            let pieces = (s.length / (cell * 0.5)).ceil().max(1.0) as usize;
            let piece = s.length / pieces as f32;
            let leaves = self.leaves_on.get(i).copied().unwrap_or(0) as f32;
            // Leaves lie at all angles: on average half their area faces up.
            let leaf_share = leaves * leaf_area * 0.5 / pieces as f32;
            for k in 0..pieces {
                let p = s.start + s.direction * piece * (k as f32 + 0.5);
                // A cylinder piece seen from above covers about its diameter times its
                // horizontal length (its end disc when it stands upright).
                let horizontal = piece * (1.0 - s.direction.z * s.direction.z).sqrt();
                let covered = 2.0 * r * horizontal + PI * r * r * s.direction.z.abs();
                self.light.occlude(p, covered, leaf_share);
            }
        }
        self.light.illuminate(&self.sky);
    }

    /// The tree now as a Skeleton: one stem per live branch, sections at the segment joints
    /// (the trunk also at breast height and every half metre), leaves spiralled along the
    /// young shoots.
    pub fn skeleton(&self) -> Skeleton {
        let mut sk = Skeleton::default();
        self.skeleton_into(&mut sk);
        sk
    }

    /// Like [`Grower::skeleton`], but reuses `sk`'s buffers (cleared first), so showing the
    /// tree after every step allocates nothing once the buffers have grown.
    pub fn skeleton_into(&self, sk: &mut Skeleton) {
        sk.stems.clear();
        sk.sections.clear();
        sk.leaves.clear();
        let mut stem_of = vec![u32::MAX; self.branches.len()];
        let mut segs: Vec<&Segment> = Vec::new();
        let mut points: Vec<(Vec3, Vec3, f32)> = Vec::new();
        let (leaf_len, leaf_width) = self.drawn_leaf_size();
        let top = self.targets_now().height as f32;
        for (b, branch) in self.branches.iter().enumerate() {
            if !branch.alive {
                continue;
            }
            let parent = branch.parent.map(|(p, _)| StemId(stem_of[p as usize]));
            if parent.is_some_and(|p| p.0 == u32::MAX) {
                continue;
            }
            let first = sk.sections.len() as u32;
            segs.clear();
            segs.extend(
                branch
                    .segments
                    .iter()
                    .map(|&s| &self.segments[s as usize])
                    .filter(|s| s.length > 1e-4),
            );
            if segs.is_empty() {
                continue;
            }
            let total: f32 = segs.iter().map(|s| s.length).sum();
            points.clear();
            let mut run = 0.0f32;
            for s in &segs {
                let pieces = if branch.order == 0 {
                    (s.length / 0.5).ceil().max(1.0) as usize
                } else {
                    1
                };
                for k in 0..pieces {
                    let f = k as f32 / pieces as f32;
                    let p = s.start + s.direction * s.length * f;
                    points.push((p, s.direction, run + s.length * f));
                }
                run += s.length;
            }
            let last = segs[segs.len() - 1];
            points.push((last.end(), last.direction, total));
            if branch.order == 0 {
                // A section exactly at breast height, so DBH reads the trunk there.
                if let Some(i) = points.iter().position(|p| p.0.z > BREAST_HEIGHT)
                    && i > 0
                    && (points[i - 1].0.z - BREAST_HEIGHT).abs() > 1e-3
                {
                    let (a, b) = (points[i - 1], points[i]);
                    let f = (BREAST_HEIGHT - a.0.z) / (b.0.z - a.0.z);
                    points.insert(i, (a.0.lerp(b.0, f), a.1, a.2 + (b.2 - a.2) * f));
                }
            }
            for (k, &(p, d, at)) in points.iter().enumerate() {
                // Side branches: one section per segment (its base radius, older and thicker
                // toward the base), then a thin tip.
                let radius = if branch.order == 0 {
                    self.trunk_radius(p.z)
                } else if k < segs.len() {
                    self.radius_at_base(segs[k])
                } else {
                    (self.radius_at_base(last) * 0.35).max(0.001)
                };
                sk.sections.push(CrossSection {
                    position: p,
                    orientation: frame(d),
                    radius: radius.max(0.0008),
                    z: if total > 0.0 { at / total } else { 0.0 },
                });
            }
            let id = sk.stems.len() as u32;
            stem_of[b] = id;
            let offset = branch.offset;
            sk.stems.push(Stem {
                level: branch.order,
                parent,
                clone_of: None,
                offset,
                length: total,
                sections: first..sk.sections.len() as u32,
                lobes: 0,
                lobe_depth: 0.0,
            });
            self.for_each_leaf(b, leaf_len, top, |position, orientation| {
                sk.leaves.push(Leaf {
                    light: self.light.light_at(position),
                    position,
                    orientation,
                    length: leaf_len,
                    width: leaf_width,
                    shape: self.leaf_shape,
                    stem: StemId(id),
                })
            });
        }
    }
}

impl Grower {
    /// The leaves of branch `b` (position and orientation), spiralling at a fixed divergence,
    /// tilted 50 degrees off the shoot, none above the tree's top or below the crown base
    /// (the survey's crown base is where the lowest foliage is).
    fn for_each_leaf(&self, b: usize, length: f32, top: f32, mut f: impl FnMut(Vec3, Quat)) {
        let floor = self.targets_now().crown_base() as f32 - 0.02;
        let mut turn = 0.0f32;
        let mut rng = self.key.child(1000 + b as u64).stream();
        for &si in &self.branches[b].segments {
            let s = &self.segments[si as usize];
            let n = self.leaves_on.get(si as usize).copied().unwrap_or(0) as usize;
            for k in 0..n {
                let along = (k as f32 + 0.5) / n as f32;
                let p = s.start + s.direction * s.length * along;
                turn += 137.5;
                let q = frame(s.direction)
                    * Quat::from_rotation_z(turn.to_radians())
                    * Quat::from_rotation_x((50.0 + rng.var(10.0) as f32).to_radians());
                // Blade faces the sky where it can: roll it about its own axis.
                let q = face_up(q);
                let tip = (q * Vec3::Z).z * length + p.z;
                if tip <= top && tip.min(p.z) >= floor {
                    f(p, q);
                }
            }
        }
    }
}

/// `aim` turned `sag` radians further down in its vertical plane, never steeper than 40 degrees
/// below the horizontal.
fn sag_down(aim: Vec3, sag: f32) -> Vec3 {
    let horizontal = aim.truncate().normalize_or(glam::Vec2::X);
    let elevation = (aim.z.clamp(-1.0, 1.0).asin() - sag).max(-0.7);
    (horizontal * elevation.cos()).extend(elevation.sin())
}

/// `direction` tilted in its vertical plane so that a shoot of `length` from `start` ends
/// between the heights `floor` and `ceiling`.
fn within_heights(direction: Vec3, start: Vec3, length: f32, floor: f32, ceiling: f32) -> Vec3 {
    let end = start.z + direction.z * length;
    let rise = if end > ceiling {
        (ceiling - start.z) / length.max(1e-6)
    } else if end < floor {
        (floor - start.z) / length.max(1e-6)
    } else {
        return direction;
    };
    let rise = rise.clamp(-1.0, 1.0);
    let horizontal = direction.truncate().normalize_or(glam::Vec2::X);
    (horizontal * (1.0 - rise * rise).sqrt()).extend(rise)
}

/// A frame whose local z is `d` (local y as near the world's up as can be).
fn frame(d: Vec3) -> Quat {
    Quat::from_rotation_arc(Vec3::Z, d.normalize_or(Vec3::Z))
}

/// Rolls a leaf frame about its own z so its normal (local y) points as far up as it can.
fn face_up(q: Quat) -> Quat {
    let z = q * Vec3::Z;
    let y = q * Vec3::Y;
    let up = (Vec3::Z - z * z.dot(Vec3::Z)).normalize_or(y);
    let angle = y.cross(up).dot(z).atan2(y.dot(up));
    Quat::from_axis_angle(z, angle) * q
}
