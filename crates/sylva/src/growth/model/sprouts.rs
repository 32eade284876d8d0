//! Sprouts after a cut: the latent buds just below a pruning cut break, and the wood grows
//! back from them.
//!
//! A broadleaf's stems carry latent (and epicormic) buds along their old wood; a cut releases
//! those below it. The sprouts are many where the cut is large: in green ash the number, height
//! and volume of epicormic branches rose with the intensity of the reduction (Perrette,
//! Delagrange & Messier 2020, Arboric. Urban For. 46(6):432-449), and branch samples carried 3
//! to 34 of them. Species differ: hackberry (*Celtis occidentalis*) made fewer epicormic
//! branches than green ash after the same reductions (Perrette et al. 2021, Urban For. Urban
//! Green. 127139). Pines and most other conifers have no latent buds on old wood and do not
//! grow back from it (Clemson Cooperative Extension's pruning guidance for needled
//! evergreens); coast redwood (O'Hara & Berrill 2009, Ann. For. Sci. 66:409), Douglas fir
//! (Collier & Turnblom 2001, West. J. Appl. For. 16(2):80-86) and yews do.
//!
//! Every sprout bud may break (none is held dormant as a shoot's extra laterals are), and its
//! shoot branches as any other does, so a cut grows back as branched shoots, not as whips.

use super::cuts::CutKind;
use super::*;

/// Diameter of cut wood per sprout bud it releases, m (Sylva's choice: a 4 cm stem's cut gives
/// two, a 20 cm limb's ten; the published counts rise with the cut and reach tens per branch).
const CUT_PER_SPROUT: f32 = 0.02;
/// Least radius of a cut stem whose latent buds break below the cut, m (Sylva's choice: a
/// twig's cut leaves nothing to sprout from that its own buds do not already give).
const SPROUTING_RADIUS: f32 = 0.01;
/// Most sprout buds one cut releases.
const MOST_SPROUTS: f32 = 12.0;
/// The rank (`Branch::rank`) a sprout's branch takes: a scaffold's, whatever the order of the
/// wood it grew from. Sprouts after pruning are reiterations, shoots that repeat the tree's
/// architecture from the start (traumatic reiteration: Barthélémy & Caraglio 2007, Ann. Bot.
/// 99:375-407), so a sprout on a twig grows branches of branches as a young limb does.
pub(super) const SPROUT_RANK: u8 = 1;
/// How far below a cut its sprouts break, m (Sylva's choice: the wood just below the wound,
/// where the latent buds the cut released sit).
const SPROUT_REACH: f32 = 0.5;

/// How readily a species sprouts from old wood: its sprouts per cut as a share of a broadleaf's.
pub(super) fn sprouting(scientific: &str, tree_type: &str) -> f32 {
    let genus = scientific.split_whitespace().next().unwrap_or("");
    match genus {
        // Conifers that do grow back from old wood.
        "Sequoia" | "Pseudotsuga" | "Taxus" => 1.0,
        // Hackberries make fewer epicormic branches than ash (Perrette et al. 2021); how many
        // fewer is not given: half is Sylva's choice.
        "Celtis" => 0.5,
        _ if tree_type.starts_with('C') || tree_type.starts_with('P') => 0.0,
        _ => 1.0,
    }
}

impl Grower {
    /// The sprout buds a cut of `kind` through wood `radius` m releases on segment `segment`
    /// of branch `b`, below `at` m along it: spread over the `SPROUT_REACH` below the cut,
    /// turned about the stem by the divergence and leaning out by the habit's branch angle.
    /// A removal cut leaves the stem its own apex, which holds the buds below it back (apical
    /// control); a reduction takes the stem's apex, and releases twice as many (Sylva's
    /// choice of the ratio).
    pub(super) fn set_sprouts(
        &mut self,
        b: usize,
        segment: u32,
        at: f32,
        radius: f32,
        kind: CutKind,
    ) {
        let per_kind = match kind {
            CutKind::Reduction | CutKind::Heading => 1.0,
            CutKind::Removal => 0.5,
        };
        if radius < SPROUTING_RADIUS {
            return;
        }
        let n = (2.0 * radius / CUT_PER_SPROUT * self.sprouting * per_kind)
            .min(MOST_SPROUTS)
            .round() as usize;
        if n == 0 || (self.branches[b].order == 0 && self.habit.form == TreeForm::Palm) {
            return;
        }
        let seg = self.segments[segment as usize];
        let length = seg.length.max(1e-6);
        let from = (at - SPROUT_REACH).max(0.0);
        let angle = self.habit.branch_angle.min(50.0);
        for k in 0..n {
            let azimuth = self.branches[b].next_azimuth;
            self.branches[b].next_azimuth = (azimuth + DIVERGENCE) % 360.0;
            let tilt = (angle + self.rng.var(5.0) as f32).to_radians();
            let direction = directions::leaning_out(seg.direction, azimuth, tilt);
            let along = from + (at - from) * (k as f32 + 0.5) / n as f32;
            self.buds.push(buds::Bud {
                branch: b as u32,
                segment,
                at: (along / length).clamp(0.0, 1.0),
                direction,
                born: self.age,
                sprout: true,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::grown;
    use super::*;

    #[test]
    fn regrowth_on_twigs_branches_as_a_young_limb_does_and_low_limbs_keep_it() {
        // The plane's crown cleared through its middle, as a wire's zone would be, and grown on
        // for two years.
        let mut g = grown("InlVal", "PLAC", 12.0);
        let h = g.targets_now().height as f32;
        g.cut(&|p, order| order > 0 && p.z > 0.55 * h && p.z < 0.75 * h);
        g.advance_to(g.age() + 2.0);
        // Regrowth of the highest order: a twig's own shoots make no buds, but a sprout repeats
        // the architecture from a scaffold's rank, so regrowth branches to the highest order
        // and beyond it (before, none of these made a bud).
        let highest: Vec<&Branch> = g
            .branches
            .iter()
            .filter(|b| b.alive && b.sprung && b.order == 4 && b.segments.len() >= 2)
            .collect();
        let branched = highest.iter().filter(|b| !b.children.is_empty()).count();
        eprintln!(
            "{} regrowth branches of order 4, {branched} branched",
            highest.len()
        );
        assert!(
            highest.len() >= 10 && branched * 2 >= highest.len(),
            "{branched} of {} regrowth branches of the highest order branched",
            highest.len()
        );
        // A cut tree keeps a limb whose own axis is below the crown base while what grows on it
        // reaches above; it sheds the limb once all of it is below, or once nothing on it grows.
        let (limb, z) = (1..g.branches.len())
            .filter(|&b| g.branches[b].alive && g.branches[b].order == 1)
            .find_map(|b| {
                let top = |b: usize| {
                    g.branches[b]
                        .segments
                        .iter()
                        .map(|&s| {
                            g.segments[s as usize]
                                .start
                                .z
                                .max(g.segments[s as usize].end().z)
                        })
                        .fold(f32::NEG_INFINITY, f32::max)
                };
                let above = g.branches[b]
                    .children
                    .iter()
                    .map(|&c| top(c as usize))
                    .fold(f32::NEG_INFINITY, f32::max);
                (above > top(b) + 0.5).then(|| (b, top(b) + 0.25))
            })
            .expect("a limb with branches reaching above it");
        assert!(!g.cut_tree_sheds(limb, z));
        assert!(g.cut_tree_sheds(limb, 1e3));
        // Without a leaf on it (and no shoot of this step, not yet leafed), it goes.
        let age = g.age;
        let grown_before = |g: &mut Grower, years: f64| {
            for s in g.segments.iter_mut() {
                s.born = s.born.min(age - years);
            }
        };
        grown_before(&mut g, 0.5);
        let leaves = std::mem::take(&mut g.leaves_on);
        assert!(g.cut_tree_sheds(limb, z));
        g.leaves_on = leaves;
        assert!(!g.cut_tree_sheds(limb, z));
        // With its leaves, but nothing grown on it for over three years, it goes.
        grown_before(&mut g, 3.5);
        assert!(g.cut_tree_sheds(limb, z));
    }
}
