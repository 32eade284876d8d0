//! Range degradation held to a budget of primitives, per tree and per frame.
//!
//! The paper's rules ([`super::LodList::levels_of_detail`]) choose from each item's projected
//! size, so a tree some hundreds of pixels tall still draws every leaf as a point or polygon:
//! 100,000 primitives or more, most of them smaller than the pixels they land in. Here a tree
//! draws at most [`PER_SQUARE_PIXEL`] primitives per pixel of its projected box (5,000 for a
//! tree 50 pixels tall), and a frame shares a budget among its trees in proportion to the
//! pixels each covers. A tree over its share keeps its trunk and branches and draws fewer twigs
//! and leaves, the same rank-major prefixes the paper drops with range, and its leaves grow
//! about their centres so that the crown keeps its leaf area and so its density and colour.

use super::order::prefix_len;
use super::{LodTree, Run, Viewer};
use crate::mesh::leaf_triangles;
use crate::skeleton::LeafShape;

/// Primitives a tree may draw per pixel of its projected box (its height in pixels, squared).
pub const PER_SQUARE_PIXEL: f32 = 2.0;

/// The outline a thinned crown draws its leaves with: a kite of two triangles (an oval blade
/// takes six), grown to the same area. At a few pixels a blade's outline does not show, and
/// three kites cost what one oval does.
pub const THINNED_OUTLINE: LeafShape = LeafShape::Triangle;

/// The factor on the length and width of a leaf of outline `own` drawn with `outline` so that
/// its area grows by `leaf_grow`.
pub fn card_scale(own: LeafShape, outline: LeafShape, leaf_grow: f32) -> f32 {
    let area = crate::mesh::template_area;
    if own == outline {
        leaf_grow.sqrt()
    } else {
        (leaf_grow * area(own) / area(outline)).sqrt()
    }
}

/// The longest a thinned crown's blades grow, pixels: past it a blade would read as a sheet
/// (on a near tree it would be larger than the shoot it hangs from), and the crown thins
/// instead. A far tree's blades, a fraction of a pixel, may grow many times over.
pub const MAX_BLADE_PIXELS: f32 = 16.0;

/// What a tree draws at one range: per list, the x of meshes and of all drawn items, and how
/// its meshed leaves are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// Per list (trunk, branches, twigs, leaves): (x of meshes, x of meshes, lines and points).
    pub x: [(f64, f64); 4],
    /// Leaf area factor of every meshed leaf (1: as grown): its length and width grow by the
    /// square root.
    pub leaf_grow: f32,
    /// The outline meshed leaves are drawn with instead of their own ([`THINNED_OUTLINE`] in a
    /// thinned crown), grown to their own outline's area.
    pub outline: Option<LeafShape>,
    /// The leaves' mean length on screen, pixels, where the choice was made for a range
    /// (`None`: for no range, and blades grow without bound).
    pub blade_pixels: Option<f32>,
}

impl Choice {
    /// The outline a leaf of `run` is drawn with, and the factor on its length and width.
    pub fn card(&self, run: &Run) -> (LeafShape, f32) {
        let outline = self.outline.unwrap_or(run.shape);
        (outline, card_scale(run.shape, outline, self.leaf_grow))
    }

    /// Triangles a meshed item of `run` draws with this choice.
    pub fn triangles_per_item(&self, run: &Run) -> usize {
        if run.sides > 0 {
            run.triangles_per_item()
        } else {
            leaf_triangles(self.card(run).0)
        }
    }
}

impl LodTree {
    /// The paper's choice at `range`.
    pub fn paper_choice(&self, range: f32, viewer: &Viewer) -> Choice {
        Choice {
            x: std::array::from_fn(|i| self.lists[i].levels_of_detail(i == 3, range, viewer)),
            leaf_grow: 1.0,
            outline: None,
            blade_pixels: Some(self.lists[3].length * viewer.pixels_per_metre(range)),
        }
    }

    /// Everything meshed.
    pub fn full_choice(&self) -> Choice {
        Choice {
            x: std::array::from_fn(|i| (self.lists[i].mass as f64, self.lists[i].mass as f64)),
            leaf_grow: 1.0,
            outline: None,
            blade_pixels: None,
        }
    }

    /// Primitives per list a choice draws.
    pub fn primitives_per_list(&self, choice: &Choice) -> [usize; 4] {
        std::array::from_fn(|i| {
            let list = &self.lists[i];
            let (x_mesh, x_drawn) = choice.x[i];
            list.runs
                .iter()
                .map(|r| {
                    let d = r.draw(list.mass, x_mesh, x_drawn);
                    d.meshed.len() * choice.triangles_per_item(r) + d.flat.len()
                })
                .sum()
        })
    }

    /// Primitives a choice draws.
    pub fn primitives(&self, choice: &Choice) -> usize {
        self.primitives_per_list(choice).iter().sum()
    }

    /// `choice` cut to at most `allowance` primitives, cheapest losses first:
    ///
    /// 1. the leaves that are drawn are all drawn as blades (a point covers at most its
    ///    pixel, so points cannot stand for many leaves), and twigs and branches trade their
    ///    meshes for lines (one primitive for `2 sides`), whose coverage stands for them;
    /// 2. then twigs and leaves thin out by the same share of their items, the leaves that
    ///    remain growing about their centres to keep the crown's leaf area;
    /// 3. then every list, the trunk too.
    pub fn within(&self, choice: Choice, allowance: usize) -> Choice {
        if self.primitives(&choice) <= allowance {
            return choice;
        }
        // Stage 1 at share g of the stems' meshes, stage 2 at share f of twigs and leaves,
        // stage 3 at share t of everything.
        let cut = |g: f64, f: f64, t: f64| {
            let mut out = Choice {
                outline: Some(THINNED_OUTLINE),
                ..choice
            };
            for (i, x) in out.x.iter_mut().enumerate() {
                let (m, d) = choice.x[i];
                *x = match i {
                    0 => (m * t, d * t),
                    1 => (m * g * t, d * t),
                    2 => (m * g * f * t, d * f * t),
                    _ => (d * f * t, d * f * t),
                };
            }
            out
        };
        let fits = |c: &Choice| self.primitives(c) <= allowance;
        // The largest share in 0..1 for which `make` fits, by bisection (primitives grow with
        // every share).
        let largest = |make: &dyn Fn(f64) -> Choice| {
            let (mut lo, mut hi) = (0.0f64, 1.0f64);
            for _ in 0..24 {
                let mid = (lo + hi) / 2.0;
                if fits(&make(mid)) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            make(lo)
        };
        let mut out = if fits(&cut(0.0, 1.0, 1.0)) {
            largest(&|g| cut(g, 1.0, 1.0))
        } else if fits(&cut(0.0, 0.0, 1.0)) {
            largest(&|f| cut(0.0, f, 1.0))
        } else {
            largest(&|t| cut(0.0, 0.0, t))
        };
        let leaves = &self.lists[3];
        let meshed: usize = leaves
            .runs
            .iter()
            .map(|r| prefix_len(r.len(), leaves.mass, out.x[3].0))
            .sum();
        if meshed > 0 {
            let most = choice.blade_pixels.map_or(f32::INFINITY, |px| {
                (MAX_BLADE_PIXELS / px.max(1e-6)).powi(2).max(1.0)
            });
            out.leaf_grow = (leaves.items as f32 / meshed as f32).min(most);
        }
        out
    }
}

/// Each tree's allowance of primitives in a frame: what it asks for (`wish`, already held to
/// [`PER_SQUARE_PIXEL`]) when the frame's trees fit in `budget` together, and otherwise
/// `min(wish, share * pixels)` with one `share` for all, found so that the allowances add up
/// to the budget: trees that need little keep it, the rest give up detail in proportion to
/// `pixels`. Callers weigh trees by their height in pixels rather than their area: a crown
/// drawn with `n` blades shows blades of `area / n` pixels, and sharing by height keeps those
/// a few pixels wide on near and far trees alike (by area, far trees would be left bare).
pub fn share_out(wishes: &[(usize, f32)], budget: usize) -> Vec<usize> {
    let total: usize = wishes.iter().map(|w| w.0).sum();
    if total <= budget {
        return wishes.iter().map(|w| w.0).collect();
    }
    let given = |share: f64| -> f64 {
        wishes
            .iter()
            .map(|&(wish, pixels)| (wish as f64).min(share * pixels.max(0.0) as f64))
            .sum()
    };
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    while given(hi) < budget as f64 && hi < 1e12 {
        hi *= 2.0;
    }
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if given(mid) > budget as f64 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    wishes
        .iter()
        .map(|&(wish, pixels)| (wish as f64).min(lo * pixels.max(0.0) as f64) as usize)
        .collect()
}

/// The most primitives a tree `pixels` tall may draw.
pub fn tree_cap(pixels: f32) -> usize {
    (PER_SQUARE_PIXEL * pixels * pixels).min(1e12) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::MeshOptions;
    use crate::{GenerateOptions, generate, species::builtin};

    #[test]
    fn a_tree_50_pixels_tall_may_draw_5000_primitives() {
        assert_eq!(tree_cap(50.0), 5000);
    }

    #[test]
    fn blades_grow_to_at_most_sixteen_pixels() {
        let p = builtin("weeping_willow").unwrap();
        let sk = generate(
            &p,
            &GenerateOptions {
                quality: 0.3,
                ..Default::default()
            },
        )
        .unwrap();
        let t = LodTree::build(&sk, &MeshOptions::for_species(&p, 0.3));
        // Seen where its leaves are 4 pixels long: they may grow four times as long.
        let viewer = Viewer {
            image_height: 1000.0,
            fov_y: 60.0,
            quality: 1.0,
        };
        let range = t.lists[3].length * viewer.pixels_per_metre(1.0) / 4.0;
        let full = Choice {
            blade_pixels: t.paper_choice(range, &viewer).blade_pixels,
            ..t.full_choice()
        };
        // Enough for the trunk, the branches' lines and a few hundred blades: far fewer than
        // a sixteenth of the willow's leaves.
        let mut bare = full;
        bare.x[1] = (0.0, full.x[1].1);
        bare.x[2] = (0.0, 0.0);
        bare.x[3] = (0.0, 0.0);
        let fixed = t.primitives(&bare);
        let c = t.within(full, fixed + 1000);
        assert!(t.primitives(&c) <= fixed + 1000);
        assert!((c.leaf_grow - 16.0).abs() < 1e-3, "{}", c.leaf_grow);
        let (_, scale) = c.card(&t.lists[3].runs[0]);
        let kite = card_scale(LeafShape::Oval, THINNED_OUTLINE, 1.0);
        assert!((scale - 4.0 * kite).abs() < 1e-4, "{scale}");
    }

    #[test]
    fn shares_add_up_to_the_budget_and_spare_small_trees() {
        let wishes = [(1000, 100.0), (100_000, 10_000.0), (50_000, 40_000.0)];
        assert_eq!(share_out(&wishes, 1_000_000), vec![1000, 100_000, 50_000]);
        let s = share_out(&wishes, 60_000);
        let sum: usize = s.iter().sum();
        assert!((59_900..=60_000).contains(&sum), "{s:?}");
        // One share per pixel for all three (none reaches its wish).
        for (k, &(_, pixels)) in wishes.iter().enumerate() {
            let share = s[k] as f32 / pixels;
            assert!(
                (share / (s[2] as f32 / 40_000.0) - 1.0).abs() < 0.01,
                "{s:?}"
            );
        }
        // A tree that wishes for less than its share keeps its wish.
        let s = share_out(&[(10, 100.0), (100_000, 10_000.0)], 50_000);
        assert_eq!(s[0], 10);
        assert!((49_980..=49_990).contains(&s[1]), "{s:?}");
    }

    #[test]
    fn a_tree_over_its_allowance_draws_about_that_and_keeps_its_leaf_area() {
        let p = builtin("black_tupelo").unwrap();
        let sk = generate(&p, &GenerateOptions::default()).unwrap();
        let t = LodTree::build(&sk, &MeshOptions::for_species(&p, 1.0));
        let full = t.full_choice();
        let all = t.primitives(&full);
        for allowance in [200_000, 50_000, 20_000] {
            let c = t.within(full, allowance);
            let n = t.primitives(&c);
            assert!(
                n <= allowance && n * 10 >= allowance * 9,
                "{n} for {allowance} of {all}"
            );
            // The trunk whole while the rest can pay; every branch still drawn, as a mesh
            // or a line.
            assert_eq!(c.x[0], full.x[0]);
            assert_eq!(c.x[1].1, full.x[1].1);
            // Fewer leaves, each larger by the square root of the share dropped.
            let leaves: usize = t.lists[3]
                .runs
                .iter()
                .map(|r| r.draw(4, c.x[3].0, c.x[3].1).meshed.len())
                .sum();
            let kept_area = leaves as f32 * c.leaf_grow;
            assert!((kept_area / t.leaves.len() as f32 - 1.0).abs() < 1e-3);
            // Drawn as kites of the oval's area, grown by the square root of the share.
            let (outline, scale) = c.card(&t.lists[3].runs[0]);
            assert_eq!(outline, THINNED_OUTLINE);
            let area = crate::mesh::template_area;
            let drawn = leaves as f32 * scale * scale * area(outline);
            let own = t.leaves.len() as f32 * area(LeafShape::Oval);
            assert!((drawn / own - 1.0).abs() < 1e-3, "{drawn} vs {own}");
        }
    }
}
