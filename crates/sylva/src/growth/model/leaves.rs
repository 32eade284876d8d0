//! Leaves and light: the leaf area f_LA asks for, spread over young, thin, lit shoots and
//! drawn as fewer, larger leaves past the leaf budget; and the light grid refreshed from the
//! branches and leaves that shade it.

use super::*;
use rayon::prelude::*;

/// Mean share of a cylinder's silhouette (diameter x length) it shows to light from a random
/// direction: pi/4, the projection of a randomly oriented cylinder.
const WOOD_G: f32 = std::f32::consts::FRAC_PI_4;

/// Segments whose shade one task works out.
const SHADE_RUN: usize = 2048;

/// What `Grower::leaf_room` needs to know of the shoots beside the tree: each one's light, and
/// whether it is its branch's outermost; the lowest a leafy shoot may be; and the weight of
/// spurs in the sharing out.
struct Shoots<'a> {
    lights: &'a [f32],
    tip_shoot: &'a [bool],
    floor: f32,
    spur_weight: f32,
}

impl Grower {
    /// Leaves on young, thin, lit shoots, adding up to f_LA.
    pub(super) fn allocate_leaves(&mut self) {
        let t = self.targets_now();
        // Shoots low enough for their leaves to hang below the crown base carry none (see
        // `for_each_leaf`).
        let floor = t.crown_base() as f32 + 0.5 * self.drawn_leaf_size().0;
        let area = self.leaf_area_each();
        // A tree the street has cut carries what it kept and has grown back since.
        let leaf_area = (t.leaf_area - self.leaf_deficit()).max(0.0);
        let wanted = (leaf_area / area as f64).round() as usize;
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
        let lights: Vec<f32> = self
            .segments
            .par_iter()
            .map(|s| self.light.light_at(s.start + s.direction * s.length * 0.5))
            .collect();
        // Spurs come with a mature crown: a sapling leafs out on its long shoots, and its few
        // branches set its width. They fade in as the crown grows from 3 to 6 m tall.
        let spur_weight = SPUR_WEIGHT * ((t.crown_height as f32 - 3.0) / 3.0).clamp(0.0, 1.0);
        let shoots = Shoots {
            lights: &lights,
            tip_shoot: &tip_shoot,
            floor,
            spur_weight,
        };
        let mut weights = vec![0.0f32; self.segments.len()];
        let mut capacity = vec![0u32; self.segments.len()];
        let room = self.leaf_room(&shoots, wanted, 1.0, &mut weights, &mut capacity);
        // A sapling's few shoots hold fewer of a small leaf than of the generic one: rather
        // than draw its leaves larger than life, each node carries more of them, up to as
        // many as carry the generic leaf's area. Across woody species, leaves per unit of
        // shoot fall in proportion as each leaf's size rises (an isometric trade-off: Kleiman
        // & Aarssen 2007, J. Ecol. 95:376-382; Yang, Li & Sun 2008, Ann. Bot.,
        // doi:10.1093/aob/mcn135, over 107 species), so a shoot carries about the same leaf
        // area whatever its leaves' size. Trees whose shoots hold their leaf area one leaf a
        // node are unchanged.
        let crowding = self.crowding(area);
        if room > 0 && room < wanted && crowding > 1.0 {
            let per_node = (wanted as f32 / room as f32).min(crowding);
            self.leaf_room(&shoots, wanted, per_node, &mut weights, &mut capacity);
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
            let n = (share as u32).min(capacity[i]).min(u16::MAX as u32);
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
        // (at most sixteen times the area), but none longer than its crown allows: leaves that
        // outgrow the crown would hang above the top or below the base and be left off, and a
        // whip whose data ask for more leaf than its shoots can hold would stand bare.
        self.leaf_boost = 1.0;
        if placed > 0 && placed < wanted {
            let fits = (self.longest_leaf() / self.drawn_leaf_size().0).powi(2);
            self.leaf_boost = (wanted as f32 / placed as f32).min(16.0).min(fits).max(1.0);
        }
    }

    /// Each shoot's leaf slots (`capacity`, `per_node` leaves at each of its nodes) and its
    /// weight in the sharing out: young, thin, lit shoots first; where they cannot hold the
    /// `wanted` leaves, older and thicker shoots carry leaves too, step by step. Returns the
    /// room at the step it stopped at.
    fn leaf_room(
        &self,
        shoots: &Shoots,
        wanted: usize,
        per_node: f32,
        weights: &mut [f32],
        capacity: &mut [u32],
    ) -> usize {
        let levels = [
            (LEAF_SHOOT_YEARS, LEAF_MAX_RADIUS, LEAF_MIN_LIGHT),
            (4.0, 0.03, 0.08),
            (8.0, 0.05, 0.04),
            (f64::INFINITY, f32::INFINITY, 0.0),
        ];
        let (radii, lights) = (&self.radii, shoots.lights);
        let mut room = 0;
        // Each shoot's room and weight depend on that shoot alone, so they are worked out on
        // every core; the sums over them below stay in shoot order.
        for &(years, radius, min_light) in &levels {
            room = (self.segments.par_iter().enumerate())
                .zip(weights.par_iter_mut().zip(capacity.par_iter_mut()))
                .map(|((i, s), (weight_i, capacity_i))| {
                    let b = &self.branches[s.branch as usize];
                    // The leader's young shoot is leafy too, or it would stand bare above
                    // the crown.
                    let leader = b.order == 0 && self.age - s.born <= LEAF_SHOOT_YEARS;
                    let placed_ok = b.alive
                        && (b.order > 0 || leader)
                        && s.start.z.min(s.end().z) >= shoots.floor;
                    let eligible = placed_ok
                        && (self.age - s.born <= years || shoots.tip_shoot[i])
                        && radii[i] <= radius
                        && lights[i] >= min_light;
                    // Short shoots (spurs) on older lit limbs: each bears a rosette of leaves
                    // a year, so the crown is leafy along its limbs inside, not only at its
                    // rim.
                    let spur = !eligible
                        && shoots.spur_weight > 0.0
                        && placed_ok
                        && radii[i] <= SPUR_MAX_RADIUS
                        && lights[i] >= LEAF_MIN_LIGHT;
                    let nodes = s.length / self.leaf_spacing;
                    let (slots, weight) = if eligible {
                        (nodes * per_node, 1.0)
                    } else if spur {
                        (nodes * SPUR_DENSITY * per_node, shoots.spur_weight)
                    } else {
                        (0.0, 0.0)
                    };
                    // Truncation is the floor here: `as u32` takes anything below zero to 0.
                    *capacity_i = slots as u32;
                    *weight_i = if *capacity_i > 0 {
                        weight * s.length * lights[i].max(0.01).sqrt()
                    } else {
                        0.0
                    };
                    *capacity_i as usize
                })
                .sum();
            if room >= wanted {
                break;
            }
        }
        room
    }

    /// How many of the species' own leaves one node may carry before they are drawn larger
    /// (see `allocate_leaves`): as many as hold the generic leaf's area. 1 for the generic
    /// leaf itself, and for leaves as large as it or larger.
    pub(super) fn crowding(&self, area: f32) -> f32 {
        match self.leaf_vertex_cap {
            Some((_, generic_area)) if area > 0.0 => (generic_area / area).max(1.0),
            _ => 1.0,
        }
    }

    /// Length and width of a leaf as drawn, m.
    pub(super) fn drawn_leaf_size(&self) -> (f32, f32) {
        self.leaf_size_boosted(self.leaf_boost)
    }

    /// Length and width of a leaf as drawn were it drawn `boost` times its area for want of
    /// shoots to carry the leaf area, m.
    pub(super) fn leaf_size_boosted(&self, boost: f32) -> (f32, f32) {
        let (l, w) = self.leaf_size_now();
        let natural = l * w * crate::mesh::template_area(self.leaf_shape);
        let k = (self.leaf_area_each() * boost / natural).sqrt();
        (l * k, w * k)
    }

    /// The species' leaf, on a sapling no longer than the generic 14 cm leaf or a sixteenth of
    /// the crown's measured width, whichever is longer: a goldenrain tree's 28 cm leaves on a
    /// crown 1.5 m wide would hang a tenth of its width outside it, so a young tree's leaves
    /// grow to their full size as its crown widens (a drawing rule, not a measurement). Nor is
    /// it longer than the crown's height allows ([`Grower::longest_leaf`]).
    fn leaf_size_now(&self) -> (f32, f32) {
        let (l, w) = self.leaf_size;
        let longest = (self.targets_now().crown_diameter as f32 / 16.0)
            .max(0.14)
            .min(self.longest_leaf());
        let k = (longest / l).min(1.0);
        (l * k, w * k)
    }

    /// The longest leaf a crown of the measured height can wear: two fifths of it. Tilted off
    /// a shoot in the crown's upper part, such a leaf still ends between the crown base and
    /// the top; one much longer would be left off (see `for_each_leaf`), and a whip whose
    /// data ask for more leaf than its few shoots can hold would stand bare (a drawing rule,
    /// not a measurement: it binds only on crowns under about a metre tall).
    fn longest_leaf(&self) -> f32 {
        (self.targets_now().crown_height as f32 * 0.4).max(0.01)
    }

    /// Area of one leaf as drawn, m² (larger than life when the leaf budget is reached, or
    /// when leaves this small would take more vertices than the tree's allowance).
    pub(super) fn leaf_area_each(&self) -> f32 {
        let t = crate::mesh::leaf_template(self.leaf_shape);
        let (l, w) = self.leaf_size_now();
        let mut natural = l * w * crate::mesh::template_area(self.leaf_shape);
        if let Some((cap, generic_area)) = self.leaf_vertex_cap {
            // Vertices allowed: the cap's density over the crown (or over the free area),
            // but over no more leaf than the generic tree draws at its own size: past the leaf
            // budget the generic leaves are drawn larger, not more, and a species' own leaves
            // must follow, or a large conifer in needle sprays would cost five times its
            // generic model (a Douglas fir at 30).
            let leaf_area = self.targets_now().leaf_area as f32;
            let covered = (leaf_area.max(super::LEAF_VERTEX_FREE_AREA))
                .min(self.options.max_leaves as f32 * generic_area);
            let allowed = cap * covered;
            natural = natural.max(t.positions.len() as f32 * leaf_area / allowed);
        }
        let t = self.targets_now();
        let needed = t.leaf_area as f32 / self.options.max_leaves as f32;
        natural.max(needed)
    }

    /// Densities from every live segment and its leaves, then the rays.
    pub(super) fn update_light(&mut self) {
        let live = |s: &&Segment| self.branches[s.branch as usize].alive;
        // Minima and maxima are exact whatever order they are taken in.
        let (lo, hi) = self
            .segments
            .par_iter()
            .filter(live)
            .fold(
                || (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |(lo, hi), s| (lo.min(s.start.min(s.end())), hi.max(s.start.max(s.end()))),
            )
            .reduce(
                || (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
                |a, b| (a.0.min(b.0), a.1.max(b.1)),
            );
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
        // Each segment's pieces are found on any core, and their shade is laid on the cells
        // after, in segment order: a cell's density is a product of factors, and the same
        // factors in the same order give the same bits on any number of cores.
        let grid = &self.light;
        let cell = grid.cell;
        let runs: Vec<Vec<(usize, f32)>> = self
            .segments
            .par_chunks(SHADE_RUN)
            .enumerate()
            .map(|(run, segments)| {
                let mut out = Vec::new();
                for (j, s) in segments.iter().enumerate() {
                    let i = run * SHADE_RUN + j;
                    let b = &self.branches[s.branch as usize];
                    if !b.alive || s.length <= 0.0 {
                        continue;
                    }
                    let r = self.radii[i];
                    let pieces = crate::whole::pieces(s.length / (cell * 0.5));
                    let piece = s.length / pieces as f32;
                    let leaves = self.leaves_on.get(i).copied().unwrap_or(0) as f32;
                    // Leaves lie at all angles: on average half their area faces up.
                    let leaf_share = leaves * leaf_area * 0.5 / pieces as f32;
                    // Light comes from the whole sky, as it does to the leaves: a cylinder piece
                    // shows it pi/4 of its silhouette (diameter x length) on average over
                    // directions, as the shade model's crown counts it (`street::energy::crown::G_WOOD`).
                    let covered = WOOD_G * 2.0 * r * piece;
                    let passing = grid.passing(covered, leaf_share);
                    out.extend((0..pieces).filter_map(|k| {
                        let p = s.start + s.direction * piece * (k as f32 + 0.5);
                        Some((grid.index_of(p)?, passing))
                    }));
                }
                out
            })
            .collect();
        for (i, passing) in runs.iter().flatten() {
            self.light.density[*i] *= passing;
        }
        self.light.illuminate(&self.sky);
    }
}

impl Grower {
    /// The lowest a leaf may hang: just below the crown base (the survey's crown base is
    /// where the lowest foliage is). Worked out once for all branches: it evaluates the
    /// growth equations.
    pub(super) fn leaf_floor(&self) -> f32 {
        self.targets_now().crown_base() as f32 - 0.02
    }

    /// The leaves of branch `b`, spiralling at a fixed divergence, tilted 50 degrees off the
    /// shoot, none above the tree's top or below `floor` ([`Grower::leaf_floor`]): each one's
    /// position, its frame rolled to the sky ([`leaf_frame`]) and its [`Blade`], whose frame as
    /// drawn has the same axis and is worked out only by those that draw it.
    ///
    /// The growth measures its crown by the first (`Grower::crown_above`) and the skeleton draws
    /// the second. The roll is a drawing choice, and the crown's fit is chaotic: measured by the
    /// drawn frame, whose axis differs from the first's in its last bits, two of the sweep's 346
    /// species-regions crossed their bounds and two others came back, with nothing grown
    /// differently.
    pub(super) fn for_each_leaf(
        &self,
        b: usize,
        dims: (f32, f32, f32),
        f: impl FnMut(Vec3, Quat, Blade),
    ) {
        self.for_each_leaf_on(b, dims, |_| true, f);
    }

    /// [`Grower::for_each_leaf`] on the segments `wanted` keeps: the others' leaves are
    /// passed over, their turns and random draws taken as if placed, so the leaves that are
    /// placed come out exactly as `for_each_leaf` places them.
    pub(super) fn for_each_leaf_on(
        &self,
        b: usize,
        (length, top, floor): (f32, f32, f32),
        wanted: impl Fn(&Segment) -> bool,
        mut f: impl FnMut(Vec3, Quat, Blade),
    ) {
        let mut turn = 0.0f32;
        let mut turns = leaf_turns().iter();
        let mut rng = self.key.child(1000 + self.branches[b].id as u64).stream();
        for &si in &self.branches[b].segments {
            let s = &self.segments[si as usize];
            let n = self.leaves_on.get(si as usize).copied().unwrap_or(0) as usize;
            if n == 0 {
                continue;
            }
            if !wanted(s) {
                for _ in 0..n {
                    turn += DIVERGENCE;
                    turns.next();
                    rng.var(10.0);
                }
                continue;
            }
            let base = frame(s.direction);
            for k in 0..n {
                let along = (k as f32 + 0.5) / n as f32;
                let p = s.start + s.direction * s.length * along;
                turn += DIVERGENCE;
                let turned = (turns.next().copied()).unwrap_or_else(|| turn.to_radians().sin_cos());
                let tilt_degrees = 50.0 + rng.var(10.0) as f32;
                let mut tilt = tilt_degrees.to_radians();
                let mut q = leaf_frame(base, turned, tilt);
                let mut tip = (q * Vec3::Z).z * length + p.z;
                // A leaf that would reach past the top hangs down from its node instead, as
                // the top leaves of a whip do; one that fits neither way is left off.
                if tip > top {
                    tilt = (180.0 - tilt_degrees).to_radians();
                    q = leaf_frame(base, turned, tilt);
                    tip = (q * Vec3::Z).z * length + p.z;
                }
                if tip <= top && tip.min(p.z) >= floor {
                    f(
                        p,
                        q,
                        Blade {
                            shoot: base,
                            turn: turned,
                            tilt,
                        },
                    );
                }
            }
        }
    }
}

/// How many leaves of a branch find their turn about it in [`leaf_turns`].
const TURNS_TABLED: usize = 1024;

/// The sine and cosine of the turn of a branch's first [`TURNS_TABLED`] leaves about it: every
/// branch's k-th leaf turns by the same angle, so the sines are worked out once, not once per
/// leaf (the same numbers, from the same angles).
fn leaf_turns() -> &'static [(f32, f32)] {
    static TURNS: std::sync::OnceLock<Vec<(f32, f32)>> = std::sync::OnceLock::new();
    TURNS.get_or_init(|| {
        let mut turn = 0.0f32;
        (0..TURNS_TABLED)
            .map(|_| {
                turn += DIVERGENCE;
                turn.to_radians().sin_cos()
            })
            .collect()
    })
}

/// The frame of a leaf on a shoot whose frame is `shoot`: turned about the shoot by the angle
/// whose sine and cosine are `turn`, tilted `tilt` off it (radians), then rolled about its own axis so the blade faces the sky (local y
/// as near to up as it can be). Built from its axes: the leaf's axis is the shoot frame applied
/// to z turned and tilted, and the roll leaves that axis alone, so there is no need to compose
/// the three rotations and measure the roll's angle.
pub(super) fn leaf_frame(shoot: Quat, turn: (f32, f32), tilt: f32) -> Quat {
    let (z, y) = turned_tilted(shoot, turn, tilt);
    // A leaf standing upright keeps the roll it came with.
    facing_sky(z, || y)
}

/// The axis (z) and normal (y) of the frame `shoot` turned about its axis by the angle whose
/// sine and cosine are `turn`, then tilted `tilt` off it (radians).
fn turned_tilted(shoot: Quat, (sin_turn, cos_turn): (f32, f32), tilt: f32) -> (Vec3, Vec3) {
    let (sin_tilt, cos_tilt) = tilt.sin_cos();
    let z = shoot * Vec3::new(sin_turn * sin_tilt, -cos_turn * sin_tilt, cos_tilt);
    let y = shoot * Vec3::new(-cos_tilt * sin_turn, cos_tilt * cos_turn, sin_tilt);
    (z, y)
}

/// Where a blade leaves its shoot, for its frame as drawn ([`Blade::frame`]).
#[derive(Clone, Copy)]
pub(super) struct Blade {
    shoot: Quat,
    turn: (f32, f32),
    tilt: f32,
}

impl Blade {
    /// The blade's frame as drawn ([`blade_frame`]).
    pub(super) fn frame(self) -> Quat {
        blade_frame(self.shoot, self.turn, self.tilt)
    }
}

/// The frame of a blade as drawn, on a shoot whose frame is `shoot`: the axis of
/// [`leaf_frame`] (turned by `turn`, tilted `tilt` off the shoot), the blade left in the plane
/// of the shoot and its own axis, as it leaves the node with no twist of the petiole, upper
/// side to the sky's half of the sphere.
///
/// Why not rolled flat to the sky, as [`leaf_frame`] is: over a crown's shoots this frame
/// spreads the blades' normals nearly evenly over the sphere, the spherical leaf angle
/// distribution (projection G = 1/2 from every side) that the shade model
/// (`street::energy::crown::G`) and the growth's light grid assume. Blades rolled flat showed a side
/// view a third of their area (G 0.32 on a London plane at 30 years): the crown drawn from the
/// street was thinner than the crown that casts the shade, and its twigs showed through (a
/// third of the picture's covered outline was wood). Measured broadleaf crowns run from
/// planophile to spherical (Chianucci et al. 2018, Ann. For. Sci. 75:50, 138 species);
/// Sylva's species data hold no leaf angles.
pub(super) fn blade_frame(shoot: Quat, turn: (f32, f32), tilt: f32) -> Quat {
    let (z, y) = turned_tilted(shoot, turn, tilt);
    // Turned over, a blade keeps its projection from every side: only its upper side's colour
    // tells, and that faces up.
    let y = if y.z < 0.0 { -y } else { y };
    Quat::from_mat3(&glam::Mat3::from_cols(y.cross(z), y, z)).normalize()
}

/// The frame of a blade lying along `z` (unit) and rolled about it so that its normal (local
/// y) points as near to the sky as it can; `upright` gives the normal where `z` is vertical
/// and any roll would do.
pub(super) fn facing_sky(z: Vec3, upright: impl FnOnce() -> Vec3) -> Quat {
    let up = Vec3::Z - z * z.z;
    let y = if up.length_squared() > 1e-12 {
        up.normalize()
    } else {
        upright()
    };
    Quat::from_mat3(&glam::Mat3::from_cols(y.cross(z), y, z)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 500 random shoots, each with a leaf's turn and tilt (radians) and the frame the two
    /// rotations give it, unrolled.
    fn leaves_on_random_shoots(seed: u64) -> Vec<(Quat, f32, f32, Quat)> {
        let mut rng = crate::rng::StreamKey::from_seed(seed).stream();
        (0..500)
            .map(|_| {
                let d = Vec3::new(
                    rng.var(1.0) as f32,
                    rng.var(1.0) as f32,
                    rng.var(1.0) as f32,
                );
                let shoot = frame(d);
                let turn = (rng.var(180.0) as f32).to_radians();
                let tilt = (50.0 + rng.var(10.0) as f32).to_radians();
                let q = shoot * Quat::from_rotation_z(turn) * Quat::from_rotation_x(tilt);
                (shoot, turn, tilt, q)
            })
            .collect()
    }

    fn assert_same_frame(got: Quat, want: Quat) {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            let miss = (got * axis - want * axis).length();
            assert!(miss < 1e-4, "{got} vs {want}: {axis} off by {miss}");
        }
    }

    /// The frame built from its axes is the one three rotations and a roll to the sky give.
    #[test]
    fn a_leaf_frame_is_the_turned_tilted_frame_rolled_to_the_sky() {
        for (shoot, turn, tilt, q) in leaves_on_random_shoots(3) {
            // Roll about the leaf's own axis until its y points as far up as it can.
            let z = q * Vec3::Z;
            let y = q * Vec3::Y;
            let up = (Vec3::Z - z * z.z).normalize_or(y);
            let want = Quat::from_axis_angle(z, y.cross(up).dot(z).atan2(y.dot(up))) * q;
            assert_same_frame(leaf_frame(shoot, turn.sin_cos(), tilt), want);
        }
    }

    /// The drawn blade is the turned, tilted frame, turned over where its upper side would
    /// face down, about the same axis as the frame rolled to the sky.
    #[test]
    fn a_blade_is_the_turned_tilted_frame_upper_side_up() {
        for (shoot, turn, tilt, q) in leaves_on_random_shoots(4) {
            // Half a turn about the leaf's own axis turns it over.
            let over = Quat::from_axis_angle(q * Vec3::Z, std::f32::consts::PI) * q;
            let want = if (q * Vec3::Y).z < 0.0 { over } else { q };
            let got = blade_frame(shoot, turn.sin_cos(), tilt);
            assert_same_frame(got, want);
            let sky = leaf_frame(shoot, turn.sin_cos(), tilt);
            assert!((sky * Vec3::Z - got * Vec3::Z).length() < 1e-5);
        }
    }
}
