//! A grown tree on a typical narrow street (`sites/narrow-under-wires.toml`: a 1.2 m strip
//! between curb and sidewalk, distribution lines over it at 8.5 m): whether its trunk's flare
//! reaches the curb or the sidewalk, and whether its crown enters the lines' clearance. Each
//! prototype is checked as it is grown (`prototypes`), unpruned, so the report can set the
//! first age class with each conflict beside what an inventory's surveyors recorded
//! (`report::predicted`) at no extra growth.

use std::sync::OnceLock;
use sylva::Skeleton;
use sylva::street::work::conflicts::conflicts;
use sylva::street::{Kind, Site};

/// The street: its name, and its `site.toml`.
pub const SITE: (&str, &str) = (
    "sites/narrow-under-wires.toml",
    include_str!("../../../../sites/narrow-under-wires.toml"),
);

/// The conflicts a tree has on the typical street.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct OnTypicalStreet {
    /// Its trunk's flare reaches the curb or the sidewalk.
    pub flare: bool,
    /// Its crown enters the lines' clearance.
    pub wire: bool,
}

/// `skeleton`'s conflicts on the typical street (none if its file cannot be read, which the
/// tests rule out).
pub fn on_typical_street(skeleton: &Skeleton) -> OnTypicalStreet {
    static STREET: OnceLock<Option<Site>> = OnceLock::new();
    let Some(site) = STREET.get_or_init(|| Site::parse(SITE.1, SITE.0).ok()) else {
        return OnTypicalStreet::default();
    };
    let found = conflicts(skeleton, site);
    OnTypicalStreet {
        flare: found.iter().any(|c| c.kind == Kind::TrunkFlare),
        wire: found.iter().any(|c| c.kind == Kind::Wire),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::growth::{Database, Grower, GrowthOptions};

    #[test]
    fn a_young_plane_clears_the_lines_and_a_grown_one_reaches_into_them() {
        Site::parse(SITE.1, SITE.0).unwrap();
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut grower = Grower::new(plane, GrowthOptions::default());
        grower.advance_to(2.0);
        // A two-year-old whip stays below the lines' clearance (from 5.5 m up) and its trunk
        // inside the 1.2 m strip.
        assert_eq!(
            on_typical_street(&grower.skeleton()),
            OnTypicalStreet::default()
        );
        grower.advance_to(20.0);
        // At 20 its crown reaches into the clearance about the lines 8.5 m up over the strip;
        // its trunk's flare is still inside the strip's 0.6 m either side.
        let grown = on_typical_street(&grower.skeleton());
        assert!(grown.wire && !grown.flare, "{grown:?}");
    }
}
