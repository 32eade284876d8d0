//! The growth model (Rudnick et al. 2007 with Linsen et al. 2005): branches made of annual
//! segments, grown in steps of 1/n year. In its first year a segment elongates (primary
//! growth); after that it only thickens (secondary growth). At the end of a year the apical
//! bud continues every branch that still has room to grow, and lateral buds start branches of
//! the next order with a probability from light, local density and chance. Lengths come from
//! the crown shape function and the measured crown, radii from the pipe model held to f_DBH,
//! angles from f_CD / f_CH.
//!
//! The model is fitted to the data the way the seeds' title says, by inverse modelling: one
//! gain on branch length is corrected every step so that the crown's measured diameter follows
//! f_CD; the trunk follows f_H; lower branches are shed as the crown base (monotone) rises;
//! the leaves on young, thin, lit shoots add up to f_LA.
//!
//! This file holds the tree's state and the order of a step; the steps live beside it:
//! `buds.rs` (buds and shoots at the end of a year), `wood.rs` (elongation and thickening),
//! `fit.rs` (shedding and fitting the crown to the measured targets), `leaves.rs` (leaf area
//! and light) and `skeleton.rs` (the tree as a Skeleton).

use super::light::{LightGrid, Ray, daylight};
use super::measured::Measured;
use crate::rng::{Random, StreamKey};
use crate::skeleton::{CrossSection, Leaf, LeafShape, Skeleton, Stem, StemId};
use glam::{Quat, Vec3};
use std::f32::consts::PI;

mod buds;
mod fit;
mod leaves;
mod skeleton;
mod wood;

/// Exponent of the pipe model: parent^n = sum of children^n (2 is da Vinci's area rule;
/// measured trees lie around 2 to 3).
const PIPE_EXPONENT: f32 = 2.5;
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
    /// Radius of a live tip, m: what makes the pipe model's trunk f_DBH at breast height.
    tip_radius: f32,
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
            tip_radius: 0.001,
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

    /// Branches (the trunk aside) alive, and shed since planting.
    pub fn branch_counts(&self) -> (usize, usize) {
        let live = self.branches[1..].iter().filter(|b| b.alive).count();
        (live, self.branches.len() - 1 - live)
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

    pub(super) fn targets_now(&self) -> Targets {
        self.targets(self.age)
    }
}

/// A frame whose local z is `d` (local y as near the world's up as can be).
pub(super) fn frame(d: Vec3) -> Quat {
    Quat::from_rotation_arc(Vec3::Z, d.normalize_or(Vec3::Z))
}
