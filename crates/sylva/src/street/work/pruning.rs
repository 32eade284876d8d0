//! How the street prunes a tree: a site's `[pruning]` regime (issue U). A regime says, for each
//! reason a street cuts a tree, how many years pass between cuts:
//!
//! - **line clearance**: each `[[wire]]` is cleared to its own `clearance` every `cycle` years;
//! - **crown raising** over the roadway and the sidewalk, to `[street]`'s clear heights;
//! - **building clearance**: the façade, awnings, signs and street lights' lamps;
//! - **structural pruning** of a young tree (one leader, spaced scaffolds) while its DBH is
//!   under a size.
//!
//! ```toml
//! [pruning]
//! standard = "us-street"     # the defaults below; "none": the street never cuts the tree
//! line_cycle = 4             # years; a [[wire]]'s own `cycle` overrides it for that wire
//! raise_cycle = 5
//! building_cycle = 5
//! structural_cycle = 3
//! structural_until = 15.2    # DBH, cm
//! ```
//!
//! A site without `[pruning]` is pruned by the default standard: a street prunes. The keys are
//! read and checked with the rest of the site (`site.rs`: every cycle a whole number of years
//! from 1 to 20, and no wire's or lamp's clearance reaching the ground, which would have the
//! tree cut to a stump); this module resolves them into a [`Regime`]. The clearances are the
//! site's own: its wires' and lamps' radii, its clear heights.

use crate::street::site::{Site, Standard};

/// Years between line-clearance cycles under [`Standard::UsStreet`]: the middle of the
/// utilities' 3 to 5.
pub const US_LINE_CYCLE: u32 = 4;
/// Years between routine prunings (crown raising, building clearance) under
/// [`Standard::UsStreet`].
pub const US_ROUTINE_CYCLE: u32 = 5;
/// Years between structural prunings of a young tree under [`Standard::UsStreet`].
pub const US_STRUCTURAL_CYCLE: u32 = 3;
/// DBH below which a tree is young enough for structural pruning, cm (6 in).
pub const US_STRUCTURAL_UNTIL_CM: f64 = 15.24;

/// A regime resolved from a site: each reason's cycle in years, `None` where the street does
/// not cut for it.
#[derive(Clone, Debug, PartialEq)]
pub struct Regime {
    /// Each of the site's wires' cycle, in the site's order.
    pub lines: Vec<Option<u32>>,
    /// Crown raising over the roadway and the sidewalk.
    pub raise: Option<u32>,
    /// Clearance from the façade, awnings, signs and lamps.
    pub building: Option<u32>,
    /// Structural pruning: its cycle, and the DBH (cm) it stops at.
    pub structural: Option<(u32, f64)>,
}

impl Regime {
    /// No pruning, for a site of `wires` wires.
    pub fn none(wires: usize) -> Regime {
        Regime {
            lines: vec![None; wires],
            raise: None,
            building: None,
            structural: None,
        }
    }

    /// The regime of a site as `Site::parse` checked it: its `[pruning]`, or the default
    /// standard where it has none.
    pub fn of(site: &Site) -> Regime {
        let spec = site.pruning.clone().unwrap_or_default();
        if spec.standard == Standard::None {
            return Regime::none(site.wire.len());
        }
        let years = |given: Option<i64>, default: u32| given.map_or(default, |y| y as u32);
        let line = years(spec.line_cycle, US_LINE_CYCLE);
        Regime {
            lines: site
                .wire
                .iter()
                .map(|w| Some(years(w.cycle, line)))
                .collect(),
            raise: Some(years(spec.raise_cycle, US_ROUTINE_CYCLE)),
            building: Some(years(spec.building_cycle, US_ROUTINE_CYCLE)),
            structural: Some((
                years(spec.structural_cycle, US_STRUCTURAL_CYCLE),
                spec.structural_until.unwrap_or(US_STRUCTURAL_UNTIL_CM),
            )),
        }
    }

    /// Whether the street prunes at all.
    pub fn prunes(&self) -> bool {
        self.lines.iter().any(Option::is_some)
            || self.raise.is_some()
            || self.building.is_some()
            || self.structural.is_some()
    }
}

/// Whether a cycle of `cycle` years, counted from planting, falls in year `age` (a whole
/// number of years since planting; the first cut is `cycle` years after planting).
pub fn due(cycle: u32, age: u32) -> bool {
    cycle > 0 && age > 0 && age.is_multiple_of(cycle)
}

#[cfg(test)]
mod tests {
    use super::*;

    const STREET: &str = "[street]\ncurb = -1.0\nsidewalk = [0.8, 3.2]\n\
                          roadway_clearance = 4.3\nsidewalk_clearance = 2.4\n";
    const WIRE: &str = "[[wire]]\nheight = 8.5\noffset = -0.6\nclearance = 3.0\nminimum = 0.46\n";

    fn site(extra: &str) -> Result<Site, String> {
        Site::parse(&format!("{STREET}{extra}"), "site.toml").map_err(|e| e.to_string())
    }

    #[test]
    fn a_site_is_pruned_by_the_default_standard_unless_it_says_otherwise() {
        let regime = Regime::of(&site(WIRE).unwrap());
        assert_eq!(regime.lines, vec![Some(US_LINE_CYCLE)]);
        assert_eq!(regime.raise, Some(US_ROUTINE_CYCLE));
        assert_eq!(regime.building, Some(US_ROUTINE_CYCLE));
        assert_eq!(
            regime.structural,
            Some((US_STRUCTURAL_CYCLE, US_STRUCTURAL_UNTIL_CM))
        );
        assert!(regime.prunes());
        // Keys override the standard; a wire's own cycle overrides the line cycle.
        let two = format!(
            "{WIRE}{}[pruning]\nline_cycle = 2\nraise_cycle = 7\nstructural_until = 10.0\n",
            WIRE.replace("clearance = 3.0", "clearance = 3.0\ncycle = 6")
        );
        let regime = Regime::of(&site(&two).unwrap());
        assert_eq!(regime.lines, vec![Some(2), Some(6)]);
        assert_eq!(regime.raise, Some(7));
        assert_eq!(regime.structural, Some((US_STRUCTURAL_CYCLE, 10.0)));
        // "none" prunes nothing.
        let none = Regime::of(&site(&format!("{WIRE}[pruning]\nstandard = \"none\"\n")).unwrap());
        assert_eq!(none, Regime::none(1));
        assert!(!none.prunes());
    }

    #[test]
    fn cycles_fall_every_so_many_years_after_planting() {
        let years: Vec<u32> = (0..=12).filter(|&a| due(4, a)).collect();
        assert_eq!(years, vec![4, 8, 12]);
        assert!(!due(0, 4));
    }

    #[test]
    fn bad_regimes_name_the_key_and_what_is_allowed() {
        for (text, key) in [
            ("[pruning]\nline_cycle = 0\n", "pruning.line_cycle"),
            ("[pruning]\nraise_cycle = -3\n", "pruning.raise_cycle"),
            ("[pruning]\nbuilding_cycle = 21\n", "pruning.building_cycle"),
            (
                "[pruning]\nstructural_cycle = 0\n",
                "pruning.structural_cycle",
            ),
            (
                "[pruning]\nstructural_until = -1.0\n",
                "pruning.structural_until",
            ),
            (
                &WIRE.replace("clearance = 3.0", "clearance = 3.0\ncycle = 0"),
                "wire.cycle",
            ),
            (
                &WIRE.replace("clearance = 3.0", "clearance = 9.0"),
                "wire.clearance",
            ),
            (
                "[[light]]\nx = 6.0\ny = -0.7\nheight = 7.0\nclearance = 7.5\n",
                "light.clearance",
            ),
        ] {
            let e = site(text).unwrap_err();
            assert!(e.contains("site.toml") && e.contains(key), "{key}: {e}");
        }
        let e = site("[pruning]\nline_cycle = 0\n").unwrap_err();
        assert!(e.contains("whole years, 1 to 20"), "{e}");
        // An unknown standard, or an unknown key, is named with what is allowed.
        let e = site("[pruning]\nstandard = \"topping\"\n").unwrap_err();
        assert!(e.contains("topping") && e.contains("us-street"), "{e}");
        let e = site("[pruning]\ncycle = 3\n").unwrap_err();
        assert!(e.contains("cycle") && e.contains("line_cycle"), "{e}");
    }
}
