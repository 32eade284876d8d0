//! Short twigs: the lateral shoots that stay short, which make most of a real crown's twigs.
//!
//! In red maple and scarlet oak most twigs are 1-4 cm long, their number falling steeply
//! through the 6-10 cm class, and old branches carry only twigs under 5 cm ("Tree branches as
//! populations of twigs", abstract); a black birch long shoot carries 3-9 short shoots at its
//! base, more the longer it is (Wilson 1991, Can. J. For. Res., doi 10.1139/x91-207). The
//! model's long shoots (its segments) make the crown's frame, steered by light and space; the
//! short twigs sit on them, a population of their own:
//! - each long shoot lit at the end of its first season puts out its short twigs along its
//!   lower part, by Wilson's count;
//! - a twig's first year's length is drawn from a distribution fitted to the published shape,
//!   and each later year adds a short shoot's growth;
//! - deep shade for three years sheds a twig, as it does a branch (`shade_deaths`), and so do
//!   the rising crown base, the wood thickening past the size that carries spurs, a cut, or its
//!   branch's death.
//!
//! They draw their own random streams, keyed by their long shoot, and take no part in the
//! growth's light or pipe model: the growth is the same with them or without, and a crown of
//! them is drawn and measured (the street's shade model counts their wood from the Skeleton).
//! Their wood would weigh little in the growth's light: a 30-year plane's 27,000 short twigs
//! show 3.7 m² of silhouette (diameter x length x pi/4) against its 364 m² of leaf, a
//! pistache's 15,000 1.1 m² against 250 m² (measured on the grown trees of seed 0).

use super::*;
use rayon::prelude::*;

/// Fewest and most short twigs on one long shoot (Wilson 1991: 3-9 basal short shoots per
/// parent long shoot, more on longer parents)...
const PER_SHOOT: (f32, f32) = (3.0, 9.0);
/// ...from a long shoot this long or shorter, m, to one this long or longer (Sylva's choice:
/// the parents Wilson measured were young birch shoots, a few cm to tens of cm).
const PER_SHOOT_LENGTHS: (f32, f32) = (0.1, 1.0);
/// Median length of a short twig's first year, m, and the spread of its logarithm: a
/// log-normal whose mode (1.5 cm) lies in the published modal class (1-4 cm by species), with
/// 2% of twigs longer than 6 cm and 0.2% longer than 10 cm (numbers falling steeply through
/// 6-10 cm). Sylva's fit to the abstract's shape; the paper's histograms were out of reach.
const FIRST_YEAR: (f32, f32) = (0.02, 0.55);
/// What a short twig adds each later year, m: a short shoot's year, well under the 1 cm by
/// which Wilson (1991) tells short shoots from long (Sylva's choice of a few millimetres).
const LATER_YEARS: f32 = 0.003;
/// Years of deep shade that shed a short twig, as they do a branch.
const SHADED_YEARS: u8 = 3;

/// A short twig on a long shoot.
#[derive(Clone, Copy, Debug)]
pub(super) struct ShortShoot {
    /// The long shoot (segment) it stands on.
    pub(super) segment: u32,
    /// Where along it, m from its start.
    along: f32,
    direction: Vec3,
    /// Its first year's length, m.
    first: f32,
    /// Age of the tree when it broke.
    born: f64,
    shaded_years: u8,
}

impl Grower {
    /// At the end of a year: the short twigs age (shade, the crown base and thick wood shed
    /// them), and the long shoots grown this past year put out theirs.
    pub(super) fn grow_short_shoots(&mut self, floor: f32) {
        let mut shoots = std::mem::take(&mut self.short_shoots);
        shoots.retain_mut(|t| {
            let s = &self.segments[t.segment as usize];
            let p = s.start + s.direction * t.along;
            t.shaded_years = if self.light.light_at(p) < LEAF_MIN_LIGHT {
                t.shaded_years + 1
            } else {
                0
            };
            self.carries_short_shoot(t) && p.z >= floor && t.shaded_years < SHADED_YEARS
        });
        self.short_shoots = shoots;
        if self.habit.form == TreeForm::Palm {
            return;
        }
        let age = self.age;
        let fresh: Vec<u32> = (0..self.segments.len() as u32)
            .filter(|&i| {
                let s = &self.segments[i as usize];
                let grown = age - s.born;
                self.branches[s.branch as usize].alive && grown > 0.25 && grown <= 1.25
            })
            .collect();
        for i in fresh {
            self.put_out_short_shoots(i, floor);
        }
        self.shed_leafless_short_shoots();
    }

    /// Every short twig bears leaves: the crown holds no more of them than it carries leaves,
    /// and past that the darkest are shed first.
    fn shed_leafless_short_shoots(&mut self) {
        let leaves: usize = self.leaves_on.iter().map(|&n| n as usize).sum();
        let n = self.short_shoots.len();
        if n <= leaves {
            return;
        }
        let lights: Vec<f32> = (self.short_shoots.iter())
            .map(|t| {
                let s = &self.segments[t.segment as usize];
                self.light.light_at(s.start + s.direction * t.along)
            })
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| lights[a].total_cmp(&lights[b]).then(a.cmp(&b)));
        let mut keep = vec![true; n];
        for &i in &order[..n - leaves] {
            keep[i] = false;
        }
        let mut it = keep.into_iter();
        self.short_shoots.retain(|_| it.next().unwrap_or(false));
    }

    /// A long shoot's short twigs, along its lower two thirds, turned about it by the
    /// divergence and leaning out by the habit's branch angle; none on a shoot in deep shade.
    fn put_out_short_shoots(&mut self, segment: u32, floor: f32) {
        let s = self.segments[segment as usize];
        if s.length < 0.02
            || self.light.light_at(s.start + s.direction * s.length * 0.5) < LEAF_MIN_LIGHT
        {
            return;
        }
        let (lo, hi) = PER_SHOOT_LENGTHS;
        let share = ((s.length - lo) / (hi - lo)).clamp(0.0, 1.0);
        let n = (PER_SHOOT.0 + share * (PER_SHOOT.1 - PER_SHOOT.0)).round() as usize;
        let mut rng = self.key.child(SHORT_SHOOT_KEYS + s.id as u64).stream();
        let angle = self.habit.branch_angle.min(50.0);
        let axis = s.direction;
        let mut azimuth = (rng.unit() * 360.0) as f32;
        for k in 0..n {
            azimuth = (azimuth + DIVERGENCE) % 360.0;
            let along =
                s.length * (0.1 + 0.6 * (k as f32 + 0.5 + 0.3 * rng.var(1.0) as f32) / n as f32);
            let tilt = (angle + rng.var(10.0) as f32).to_radians();
            let direction = directions::leaning_out(axis, azimuth, tilt);
            // Log-normal by Box-Muller from two uniform draws.
            let (u1, u2) = (rng.unit().max(1e-12), rng.unit());
            let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
            let first = FIRST_YEAR.0 * (FIRST_YEAR.1 * z as f32).exp();
            if (s.start + s.direction * along).z < floor {
                continue;
            }
            self.short_shoots.push(ShortShoot {
                segment,
                along,
                direction,
                first,
                born: self.age,
                shaded_years: 0,
            });
        }
    }

    /// Whether a short twig's wood still carries it: its branch lives, a cut has left the
    /// long shoot as long, and the wood has not thickened past the size that bears spurs.
    fn carries_short_shoot(&self, t: &ShortShoot) -> bool {
        let s = &self.segments[t.segment as usize];
        self.branches[s.branch as usize].alive
            && t.along < s.length
            && self.radius_of(t.segment) <= SPUR_MAX_RADIUS
    }

    /// A short twig's length now, m.
    fn short_shoot_length(&self, t: &ShortShoot) -> f32 {
        let later = (self.age - t.born - 1.0).max(0.0) as f32;
        t.first + LATER_YEARS * later
    }

    /// Short twigs alive on the tree.
    pub fn short_shoot_count(&self) -> usize {
        self.short_shoots
            .iter()
            .filter(|t| self.carries_short_shoot(t))
            .count()
    }

    /// The short twigs as stems of their own, after the branches' stems (`stem_of`: each
    /// branch's stem, `u32::MAX` where it is not drawn), and where each long shoot starts
    /// along its branch's stem (`shoot_starts`, m). Each twig is two sections and a stem,
    /// worked out from its own data alone: the twigs are laid out on every core, each into
    /// its own place in the lists, the same lists on any number of cores.
    pub(super) fn short_shoots_into(
        &self,
        stem_of: &[u32],
        (shoot_starts, bends): (&[f32], &Bends),
        stems: &mut Vec<Stem>,
        sections: &mut Vec<CrossSection>,
    ) {
        let drawn: Vec<&ShortShoot> = (self.short_shoots.iter())
            .filter(|t| {
                let b = self.segments[t.segment as usize].branch as usize;
                stem_of[b] != u32::MAX && self.carries_short_shoot(t)
            })
            .collect();
        let (first_stem, first_section) = (stems.len(), sections.len());
        let blank = CrossSection {
            position: Vec3::ZERO,
            orientation: Quat::IDENTITY,
            radius: 0.0,
            z: 0.0,
        };
        sections.resize(first_section + 2 * drawn.len(), blank);
        stems.resize(
            first_stem + drawn.len(),
            Stem {
                level: 0,
                parent: None,
                clone_of: None,
                offset: 0.0,
                length: 0.0,
                sections: 0..0,
                lobes: 0,
                lobe_depth: 0.0,
            },
        );
        (drawn.par_iter().enumerate())
            .zip(sections[first_section..].par_chunks_mut(2))
            .zip(stems[first_stem..].par_iter_mut())
            .for_each(|(((k, t), ends), stem)| {
                let s = &self.segments[t.segment as usize];
                let b = s.branch as usize;
                let length = self.short_shoot_length(t);
                // On the drawn wood: where its stretch's kink has set it (`bends.rs`).
                let base = s.start + s.direction * t.along + bends.offset(t.segment, t.along);
                // A current-year twig's radius: the pipe model's tip, never thicker than half
                // the wood it stands on.
                let radius = self
                    .tip_radius
                    .min(self.radius_of(t.segment) * 0.5)
                    .max(0.0008);
                let orientation = frame(t.direction);
                ends[0] = CrossSection {
                    position: base,
                    orientation,
                    radius,
                    z: 0.0,
                };
                ends[1] = CrossSection {
                    position: base + t.direction * length,
                    orientation,
                    radius: (radius * 0.35).max(0.0008),
                    z: 1.0,
                };
                let first = (first_section + 2 * k) as u32;
                *stem = Stem {
                    // Drawn as the finest stems are, whatever wood they stand on: a few
                    // vertices around, the fewest a twig reads with.
                    level: (self.branches[b].order + 1).max(3),
                    parent: Some(StemId(stem_of[b])),
                    clone_of: None,
                    offset: shoot_starts[t.segment as usize] + t.along,
                    length,
                    sections: first..first + 2,
                    lobes: 0,
                    lobe_depth: 0.0,
                };
            });
    }
}

/// Child keys of the tree's stream from which each long shoot's short twigs draw (one key a
/// segment, far above the keys the growth itself uses).
const SHORT_SHOOT_KEYS: u64 = 1 << 40;
