//! A grown street tree dressed for a month: its leaves as they are that month (unfolding,
//! summer green, its own autumn colour, falling, or gone), its showy flowers in their months,
//! and its bark's colour and pattern. Growth never depends on the season: dressing reads a
//! grown tree and changes only what is drawn.
//!
//! One calendar serves every region, that of a temperate Northern street:
//! - **leaf-out in April.** Buds break from late April across the Midwest and about 3 May in
//!   northern Vermont (long-term average for sugar maple, Vermont Forest Health, 2022);
//! - **full leaf May to September;**
//! - **autumn colour in October,** peaking in the second to fourth week in Ohio (Ohio
//!   Department of Natural Resources and the Holden Arboretum, in The News-Herald, 8 October
//!   2010);
//! - **leaf fall through November.** "By mid-November ... everything is pretty much wrapped up"
//!   (same source);
//! - **bare December to March.**
//!
//! Warmer regions (Modesto, Florida) leaf out earlier and colour later; a calendar per region
//! is left for later. Evergreens keep their leaves all year. Flowers follow each species'
//! months in `foliage.csv`.
//!
//! How much is drawn is Sylva's choice, not a measurement:
//! - unfolding leaves at 60% of their grown length in a lighter green;
//! - half the leaves kept in November;
//! - flowers as five-lobed rosettes (a flower or a cluster) as long as a leaf, at one in two
//!   of the lit leaves' places on a bare or unfolding tree and one in five among full leaves.

use crate::export::Materials;
use crate::growth::data::foliage::{self, BarkPattern, Persistence};
use crate::growth::data::measured::Measured;
use crate::mesh::{MeshOptions, TreeMesh, mesh_tree};
use crate::rng::mix64;
use crate::skeleton::{Leaf, LeafShape, Skeleton};
use glam::Vec3;
use std::borrow::Cow;

/// The months' names, January first.
const MONTH_NAMES: [&str; 12] = [
    "january",
    "february",
    "march",
    "april",
    "may",
    "june",
    "july",
    "august",
    "september",
    "october",
    "november",
    "december",
];

/// A month of the year, 1 (January) to 12.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Month(u8);

impl Month {
    /// April: leaves unfolding, spring flowers.
    pub const SPRING: Month = Month(4);
    /// July: full leaf.
    pub const SUMMER: Month = Month(7);
    /// October: autumn colour.
    pub const AUTUMN: Month = Month(10);
    /// January: deciduous trees bare.
    pub const WINTER: Month = Month(1);

    /// Month `n` (1 to 12).
    pub fn new(n: u8) -> Option<Month> {
        (1..=12).contains(&n).then_some(Month(n))
    }

    /// 1 to 12.
    pub fn number(self) -> u8 {
        self.0
    }

    /// A season (`spring`, `summer`, `autumn` or `fall`, `winter`), a month's number (1 to
    /// 12) or its English name or first three letters.
    pub fn parse(text: &str) -> Result<Month, String> {
        let t = text.trim().to_ascii_lowercase();
        let by_name = MONTH_NAMES
            .iter()
            .position(|n| t.len() >= 3 && n.starts_with(&t))
            .map(|i| Month(i as u8 + 1));
        match t.as_str() {
            "spring" => Ok(Month::SPRING),
            "summer" => Ok(Month::SUMMER),
            "autumn" | "fall" => Ok(Month::AUTUMN),
            "winter" => Ok(Month::WINTER),
            _ => by_name
                .or_else(|| t.parse::<u8>().ok().and_then(Month::new))
                .ok_or_else(|| {
                    format!(
                        "`{text}` is not a season or month: give spring, summer, autumn (or \
                         fall), winter, a month 1-12 or a month's name"
                    )
                }),
        }
    }

    /// Lower-case name (`april`).
    pub fn name(self) -> &'static str {
        MONTH_NAMES[usize::from(self.0 - 1)]
    }

    /// The season's name for the four months `spring`, `summer`, `autumn` and `winter`
    /// stand for, the month's name otherwise: what file names and captions say.
    pub fn label(self) -> &'static str {
        match self {
            Month::SPRING => "spring",
            Month::SUMMER => "summer",
            Month::AUTUMN => "autumn",
            Month::WINTER => "winter",
            other => other.name(),
        }
    }

    /// Whether this month lies in `from..=to`, a run that may wrap past December.
    fn within(self, (from, to): (u8, u8)) -> bool {
        if from <= to {
            (from..=to).contains(&self.0)
        } else {
            self.0 >= from || self.0 <= to
        }
    }
}

impl std::str::FromStr for Month {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Month::parse(s)
    }
}

/// A deciduous tree's leaves in a month (an evergreen's are always `Full`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LeafState {
    /// No leaves.
    Bare,
    /// Leaves unfolding, smaller and lighter.
    Unfolding,
    /// Summer leaves.
    Full,
    /// Every leaf in autumn colour.
    Turning,
    /// Half the leaves fallen, the rest in autumn colour.
    Falling,
}

/// The leaves of a tree of `persistence` in `month` (see the module's calendar).
pub fn leaf_state(persistence: Persistence, month: Month) -> LeafState {
    if persistence == Persistence::Evergreen {
        return LeafState::Full;
    }
    match month.0 {
        4 => LeafState::Unfolding,
        5..=9 => LeafState::Full,
        10 => LeafState::Turning,
        11 => LeafState::Falling,
        _ => LeafState::Bare,
    }
}

/// What a tree wears in a month: colours (sRGB 0..1), the bark's pattern, and the state of
/// its leaves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dress {
    /// Bark colour.
    pub bark: [f32; 3],
    /// The bark's pattern.
    pub bark_pattern: BarkPattern,
    /// The young shoots' bark's luminance as a share of the bark's (`Foliage::young_bark_shade`).
    pub young_bark: f32,
    /// Leaf colour this month.
    pub leaves: [f32; 3],
    /// The leaves this month.
    pub state: LeafState,
    /// Flower colour, in the species' flowering months.
    pub flowers: Option<[f32; 3]>,
}

impl Dress {
    /// `base` with the bark this tree wears: its pattern and its young shoots' shade.
    pub fn mesh_options(&self, base: &MeshOptions) -> MeshOptions {
        MeshOptions {
            bark: self.bark_pattern,
            young_bark: self.young_bark,
            ..*base
        }
    }

    /// The GLB materials of a tree so dressed.
    pub fn materials(&self) -> Materials {
        let m = Materials::from_srgb(self.bark, self.leaves);
        match self.flowers {
            Some(f) => m.with_flowers(f),
            None => m,
        }
    }
}

/// Unfolding leaves' share of their grown length.
const UNFOLDING_SIZE: f32 = 0.6;
/// Flowers' length (and width) as a share of the leaf whose place they take.
const FLOWER_SIZE: f32 = 1.0;

impl Measured {
    /// What this species wears in `month`; `None`: summer leaves and no flowers, as trees were
    /// drawn before seasons (species without a row in `foliage.csv` wear Sylva's generic
    /// colours and smooth bark; their autumn colour is not known, so it stays green).
    pub fn dress(&self, month: Option<Month>) -> Dress {
        let (bark, summer) = self.colours();
        let row = foliage::of(&self.species.code);
        let persistence = match row {
            Some(f) => f.persistence,
            None if self.species.tree_type.get(1..2) == Some("E") => Persistence::Evergreen,
            None => Persistence::Deciduous,
        };
        let state = month.map_or(LeafState::Full, |m| leaf_state(persistence, m));
        let autumn = row.and_then(|f| f.autumn).map_or(summer, |c| c.srgb);
        let leaves = match state {
            LeafState::Unfolding => {
                let fresh = foliage::colour("light green").map_or(summer, |c| c.srgb);
                std::array::from_fn(|k| (summer[k] + fresh[k]) / 2.0)
            }
            LeafState::Turning | LeafState::Falling => autumn,
            LeafState::Full | LeafState::Bare => summer,
        };
        let flowers = match (row.and_then(|f| f.flowers), month) {
            (Some((colour, months)), Some(m)) if m.within(months) => Some(colour.srgb),
            _ => None,
        };
        Dress {
            bark,
            bark_pattern: row.map_or(BarkPattern::Smooth, |f| f.bark_pattern),
            young_bark: row.map_or(1.0, |f| f.young_bark_shade()),
            leaves,
            state,
            flowers,
        }
    }
}

/// `skeleton` (grown as `m`) dressed for `month` and meshed with `options` (their bark pattern
/// replaced by the species'): bark, the month's leaves, and flowers in their months.
pub fn dressed_mesh(
    skeleton: &Skeleton,
    m: &Measured,
    month: Option<Month>,
    options: &MeshOptions,
) -> (TreeMesh, Dress) {
    let dress = m.dress(month);
    let options = dress.mesh_options(options);
    let tree = dressed_skeleton(skeleton, dress.state);
    let mut mesh = mesh_tree(&tree, &options);
    if dress.flowers.is_some() {
        let flowers = Skeleton {
            leaves: flowers(&skeleton.leaves, dress.state),
            ..Default::default()
        };
        mesh.flowers = mesh_tree(&flowers, &options).leaves;
    }
    (mesh, dress)
}

/// The skeleton with its leaves as they are in `state` (borrowed where they are unchanged).
pub fn dressed_skeleton(skeleton: &Skeleton, state: LeafState) -> Cow<'_, Skeleton> {
    let keep = |leaves: Vec<Leaf>| {
        Cow::Owned(Skeleton {
            stems: skeleton.stems.clone(),
            sections: skeleton.sections.clone(),
            leaves,
            short_twigs: skeleton.short_twigs,
        })
    };
    match state {
        LeafState::Full | LeafState::Turning => Cow::Borrowed(skeleton),
        LeafState::Bare => keep(Vec::new()),
        LeafState::Unfolding => keep(
            skeleton
                .leaves
                .iter()
                .map(|l| Leaf {
                    length: l.length * UNFOLDING_SIZE,
                    width: l.width * UNFOLDING_SIZE,
                    ..*l
                })
                .collect(),
        ),
        LeafState::Falling => keep(
            skeleton
                .leaves
                .iter()
                .enumerate()
                .filter(|(i, _)| mix64(*i as u64) & 1 == 0)
                .map(|(_, l)| *l)
                .collect(),
        ),
    }
}

/// Flowers at some of the grown leaves' places (before any fell): lit places only, one in
/// two on a bare or unfolding tree, one in five among full leaves.
fn flowers(leaves: &[Leaf], state: LeafState) -> Vec<Leaf> {
    let every = match state {
        LeafState::Bare | LeafState::Unfolding => 2,
        _ => 5,
    };
    leaves
        .iter()
        .enumerate()
        .filter(|(i, l)| l.light >= 0.5 && mix64(*i as u64 ^ 0xF10E).is_multiple_of(every))
        .map(|(_, l)| {
            let size = l.length * FLOWER_SIZE;
            // Centred where the blade was, facing as it faced.
            let middle = l.orientation * Vec3::Z * (l.length - size) / 2.0;
            Leaf {
                position: l.position + middle,
                length: size,
                width: size,
                shape: LeafShape::Lobed5,
                ..*l
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::data::database::Database;
    use crate::growth::model::{Grower, GrowthOptions};

    #[test]
    fn months_parse_from_seasons_numbers_and_names() {
        assert_eq!(Month::parse("spring"), Ok(Month::SPRING));
        assert_eq!(Month::parse("Fall"), Ok(Month::AUTUMN));
        assert_eq!(Month::parse("winter").unwrap().number(), 1);
        assert_eq!(Month::parse("11").unwrap().name(), "november");
        assert_eq!(Month::parse("Sep").unwrap().number(), 9);
        assert_eq!(Month::parse("december").unwrap().number(), 12);
        for bad in ["0", "13", "ma", "smarch", ""] {
            let e = Month::parse(bad).unwrap_err();
            assert!(e.contains("spring, summer"), "{bad}: {e}");
        }
        assert!(Month(12).within((11, 2)) && Month(1).within((11, 2)));
        assert!(!Month(3).within((11, 2)) && Month(5).within((4, 5)));
    }

    #[test]
    fn the_calendar_bares_deciduous_trees_and_keeps_evergreens() {
        let states: Vec<LeafState> = (1..=12)
            .map(|n| leaf_state(Persistence::Deciduous, Month(n)))
            .collect();
        use LeafState::*;
        assert_eq!(
            states,
            [
                Bare, Bare, Bare, Unfolding, Full, Full, Full, Full, Full, Turning, Falling, Bare
            ]
        );
        assert!((1..=12).all(|n| leaf_state(Persistence::Evergreen, Month(n)) == Full));
    }

    #[test]
    fn each_species_wears_its_own_colours_through_the_year() {
        let db = Database::builtin();
        let pistache = db.find("InlVal", "PICH").unwrap();
        let row = foliage::of("PICH").unwrap();
        let summer = pistache.dress(Some(Month::SUMMER));
        assert_eq!(summer.leaves, row.summer.srgb);
        assert_eq!(summer.bark, row.bark.srgb);
        // Chinese pistache turns orange to orange-red (its row's autumn colour).
        let autumn = pistache.dress(Some(Month::AUTUMN));
        assert_eq!(autumn.leaves, row.autumn.unwrap().srgb);
        assert_eq!(pistache.dress(Some(Month::WINTER)).state, LeafState::Bare);
        // No month: today's summer tree, no flowers.
        assert_eq!(pistache.dress(None).state, LeafState::Full);
        // Southern magnolia: evergreen, white flowers in May and June only.
        let magnolia = db.find("InlVal", "MAGR").unwrap();
        assert_eq!(magnolia.dress(Some(Month::WINTER)).state, LeafState::Full);
        assert!(magnolia.dress(Month::new(5)).flowers.is_some());
        assert!(magnolia.dress(Some(Month::AUTUMN)).flowers.is_none());
        assert!(magnolia.dress(None).flowers.is_none());
        // The plane's bark is drawn in patches.
        let plane = db.find("InlVal", "PLAC").unwrap();
        assert_eq!(plane.dress(None).bark_pattern, BarkPattern::Patches);
    }

    #[test]
    fn a_white_birch_in_winter_is_white_on_its_trunk_and_limbs_and_dark_in_its_twigs() {
        // The sources: bark white once it has formed, twigs purplish-brown. Drawn white to
        // the tips, the birch's bare crown was a white ghost beside the pistache's.
        let birch = Database::builtin().find("InlVal", "BEPE").unwrap();
        let dress = birch.dress(Some(Month::WINTER));
        assert!(dress.young_bark < 0.15, "{}", dress.young_bark);
        // Species whose sources name no twig colour are drawn as before.
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        assert_eq!(plane.dress(None).young_bark, 1.0);
        let mut grower = Grower::new(birch.clone(), GrowthOptions::default());
        grower.advance_to(12.0);
        let skeleton = grower.skeleton();
        let options = crate::growth::survey::report::MESH;
        let (mesh, _) = dressed_mesh(&skeleton, &birch, Some(Month::WINTER), &options);
        let bark = &mesh.bark;
        assert_eq!(bark.shades.len(), bark.vertex_count());
        // Most of its bark is twigs, dark; the trunk's base ring is white but for the
        // lenticels' dashes (0.45).
        let dark = bark.shades.iter().filter(|&&s| s < 0.2).count();
        assert!(
            dark > bark.vertex_count() / 4,
            "{dark} of {}",
            bark.vertex_count()
        );
        assert!(
            bark.shades[..8].iter().all(|&s| s >= 0.45),
            "{:?}",
            &bark.shades[..8]
        );
        // So does the range-rendering tree that the page and the tiles draw.
        let lod = crate::lod::LodTree::build(&skeleton, &dress.mesh_options(&options));
        let far = lod.engine_mesh([16.0, 16.0, 16.0, 4.0]);
        assert_eq!(far.bark.shades.len(), far.bark.vertex_count());
        assert!(far.bark.shades.iter().any(|&s| s < 0.2));
        assert!(far.bark.shades.iter().any(|&s| s > 0.99));
    }

    #[test]
    fn a_winter_tree_is_bare_wood_and_a_spring_cherry_flowers_on_it() {
        let db = Database::builtin();
        let cherry = db.find("NoEast", "PRSE2").unwrap();
        let mut grower = Grower::new(cherry.clone(), GrowthOptions::default());
        grower.advance_to(8.0);
        let skeleton = grower.skeleton();
        let summer = dressed_mesh(
            &skeleton,
            &cherry,
            None,
            &crate::growth::survey::report::MESH,
        )
        .0;
        let winter = dressed_mesh(
            &skeleton,
            &cherry,
            Some(Month::WINTER),
            &crate::growth::survey::report::MESH,
        )
        .0;
        assert!(summer.leaves.triangle_count() > 1000);
        assert_eq!(winter.leaves.triangle_count(), 0);
        assert!(winter.flowers.indices.is_empty());
        // The bark is the same wood, with its bands of lenticels as shades on every vertex,
        // and the short twigs the leaves hid after it.
        assert!(skeleton.short_twigs > 100, "{}", skeleton.short_twigs);
        let n = summer.bark.vertex_count();
        assert!(winter.bark.vertex_count() > n);
        assert_eq!(winter.bark.positions[..n], summer.bark.positions[..]);
        assert_eq!(winter.bark.shades[..n], summer.bark.shades[..]);
        assert_eq!(
            winter.bark.indices[..summer.bark.indices.len()],
            summer.bark.indices[..]
        );
        assert_eq!(winter.bark.shades.len(), winter.bark.vertex_count());
        assert!(winter.bark.shades.iter().any(|&s| s < 0.6));
        // Kwanzan cherry flowers in April, among unfolding leaves 0.6 of their size.
        let (spring, dress) = dressed_mesh(
            &skeleton,
            &cherry,
            Some(Month::SPRING),
            &crate::growth::survey::report::MESH,
        );
        assert_eq!(dress.state, LeafState::Unfolding);
        assert!(dress.flowers.is_some());
        let lit = skeleton.leaves.iter().filter(|l| l.light >= 0.5).count();
        let rosettes = spring.flowers.triangle_count() as f32
            / crate::mesh::leaf_triangles(LeafShape::Lobed5) as f32;
        // One in two of the lit places, give or take the hash's luck.
        assert!(
            (rosettes / lit as f32 - 0.5).abs() < 0.05,
            "{rosettes} of {lit}"
        );
        let area = |m: &crate::mesh::Mesh| -> f32 {
            m.indices
                .chunks(3)
                .map(|t| {
                    let p: Vec<Vec3> = t
                        .iter()
                        .map(|&i| Vec3::from(m.positions[i as usize]))
                        .collect();
                    (p[1] - p[0]).cross(p[2] - p[0]).length() / 2.0
                })
                .sum()
        };
        let ratio = area(&spring.leaves) / area(&summer.leaves);
        assert!((ratio - 0.36).abs() < 0.01, "{ratio}");
    }
}
