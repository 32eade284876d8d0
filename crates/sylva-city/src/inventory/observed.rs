//! What an inventory's surveyors saw of each tree: its condition, and the street's problems
//! around it (issue Z2). Read by column name, as the layouts name them; a value Sylva cannot
//! place is kept as written, counted as "not recorded" and listed in the report, never
//! guessed.
//!
//! **Condition**, onto i-Tree Streets' three report classes, good, fair and poor (the
//! classes its condition and relative performance reports give by species: CUFR, "What are
//! your trees' relative performance index?", Urban Forest Research, Summer 2004):
//!
//! | layout | column | good | fair | poor |
//! |---|---|---|---|---|
//! | census (NYC 2015 Street Tree Census) | `health` | Good | Fair | Poor |
//! | others (GIS exports, i-Tree Streets and Eco inventories) | `condition`, `health`, `tree_condition`, `cond` | Excellent, Very Good, Good | Fair | Poor, Critical, Dying |
//!
//! The finer classes are i-Tree Eco's dieback scale (Excellent under 1% dieback, Good 1-10%,
//! Fair 11-25%, Poor 26-50%, Critical 51-75%, Dying 76-99%, Dead 100%: i-Tree forum, "Tree
//! condition classes", 2011), grouped as the reports' three. "Dead" is a status (a dead tree
//! is counted apart), not a condition. A column of numbers (a condition percentage or score)
//! is refused: its classes are the inventory's own, and Sylva does not guess them.
//!
//! **Problems** (the census's columns, NYC Open Data "2015 Street Tree Census - Tree Data",
//! data dictionary): `sidewalk` (Damage / NoDamage: a sidewalk flag next to the tree cracked
//! or lifted), `brch_light` (lights, usually string lights, or wires in the branches),
//! `trunk_wire` and `trnk_light` (wire or rope, or lights, on the trunk), `root_stone` and
//! `root_grate` (paving stones or a metal grate on the roots): Yes / No. Other layouts may
//! name a sidewalk-damage column `sidewalk_damage`.

use super::find;
use crate::error::CityError;
use std::path::Path;

/// A tree's condition, as i-Tree Streets' reports class it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Condition {
    /// Good (or excellent, very good).
    Good,
    /// Fair.
    Fair,
    /// Poor (or critical, dying).
    Poor,
}

impl Condition {
    /// The three, best first.
    pub const ALL: [Condition; 3] = [Condition::Good, Condition::Fair, Condition::Poor];

    /// Its name in the report and the tiles.
    pub fn name(self) -> &'static str {
        match self {
            Condition::Good => "good",
            Condition::Fair => "fair",
            Condition::Poor => "poor",
        }
    }

    /// The class of a value as written (any case, spaces or underscores), if it is one.
    pub fn parse(value: &str) -> Option<Condition> {
        let v: String = value
            .trim()
            .to_ascii_lowercase()
            .chars()
            .filter(|c| c.is_ascii_alphabetic())
            .collect();
        match v.as_str() {
            "excellent" | "verygood" | "good" => Some(Condition::Good),
            "fair" => Some(Condition::Fair),
            "poor" | "critical" | "dying" => Some(Condition::Poor),
            _ => None,
        }
    }
}

/// Where a tree's bed lies against the curb, as the census records it (`curb_loc`: OnCurb,
/// OffsetFromCurb): the place Sylva's roots model reads (`sylva::street::work::roots`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Curb {
    /// Along the curb (the census maps it 2.5 ft from it).
    Along,
    /// Offset from the curb (mapped 12 ft from it).
    Offset,
}

impl Curb {
    /// The place of a value as written (any case, spaces or underscores), if it is one.
    pub fn parse(value: &str) -> Option<Curb> {
        let v: String = (value.trim().to_ascii_lowercase().chars())
            .filter(|c| c.is_ascii_alphabetic())
            .collect();
        match v.as_str() {
            "oncurb" | "curb" | "along" | "alongcurb" => Some(Curb::Along),
            "offsetfromcurb" | "offset" => Some(Curb::Offset),
            _ => None,
        }
    }

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Curb::Along => "along the curb",
            Curb::Offset => "offset from the curb",
        }
    }

    /// The trunk's distance from the pavement the roots model reads for it, m: the census's
    /// own placing of its points.
    pub fn distance_m(self) -> f64 {
        match self {
            Curb::Along => sylva::street::work::roots::ON_CURB_M,
            Curb::Offset => sylva::street::work::roots::OFFSET_M,
        }
    }
}

/// What was seen of one tree. `None`: not recorded (no column, an empty cell, or a value
/// Sylva cannot place, kept in `unread`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Observed {
    /// Its condition.
    pub condition: Option<Condition>,
    /// A sidewalk flag beside it damaged.
    pub sidewalk_damage: Option<bool>,
    /// Lights or wires in its branches.
    pub branch_lights: Option<bool>,
    /// Wire, rope or lights on its trunk.
    pub trunk_wire_or_lights: Option<bool>,
    /// Paving stones or a grate on its roots.
    pub root_paving: Option<bool>,
    /// Where its bed lies against the curb.
    pub curb: Option<Curb>,
    /// Values that could not be placed: (column, value).
    pub unread: Vec<(String, String)>,
}

/// Which columns hold what was seen. A column left `None` is taken from the layout the header
/// matches ([`ObservedColumns::completed`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObservedColumns {
    /// Condition.
    pub condition: Option<String>,
    /// Sidewalk damage.
    pub sidewalk: Option<String>,
    /// Lights or wires in the branches.
    pub branch_lights: Option<String>,
    /// Wire or rope, and lights, on the trunk.
    pub trunk: [Option<String>; 2],
    /// Paving stones, and grates, on the roots.
    pub roots: [Option<String>; 2],
    /// The bed's place against the curb.
    pub curb: Option<String>,
}

/// A yes/no value as the census writes it (Yes/No, Damage/NoDamage) or as others do
/// (true/false, 1/0, Y/N).
fn yes_no(value: &str) -> Option<bool> {
    match value.trim().to_ascii_lowercase().as_str() {
        "yes" | "y" | "true" | "1" | "damage" | "damaged" => Some(true),
        "no" | "n" | "false" | "0" | "nodamage" | "none" => Some(false),
        _ => None,
    }
}

impl ObservedColumns {
    /// These columns, each one left unnamed taken from the header where it has one.
    pub fn completed(&self, header: &[String]) -> ObservedColumns {
        let f = |names: &[&str]| find(header, names);
        let or = |c: &Option<String>, names: &[&str]| c.clone().or_else(|| f(names));
        ObservedColumns {
            condition: or(
                &self.condition,
                &["health", "condition", "tree_condition", "cond"],
            ),
            sidewalk: or(&self.sidewalk, &["sidewalk", "sidewalk_damage"]),
            branch_lights: or(&self.branch_lights, &["brch_light"]),
            trunk: [
                or(&self.trunk[0], &["trunk_wire"]),
                or(&self.trunk[1], &["trnk_light"]),
            ],
            roots: [
                or(&self.roots[0], &["root_stone"]),
                or(&self.roots[1], &["root_grate"]),
            ],
            curb: or(&self.curb, &["curb_loc", "curb_location"]),
        }
    }

    /// Refuses a condition column of numbers (a percentage or a score): `values` are its
    /// cells. Sylva places classes by name only.
    pub fn check(&self, values: &[&str], path: &Path) -> Result<(), CityError> {
        let Some(column) = &self.condition else {
            return Ok(());
        };
        let filled: Vec<&&str> = values.iter().filter(|v| !v.trim().is_empty()).collect();
        if !filled.is_empty() && filled.iter().all(|v| v.trim().parse::<f64>().is_ok()) {
            return Err(CityError::inventory(
                path,
                format!(
                    "column `{column}` holds numbers (e.g. `{}`), not condition classes: Sylva \
                     reads Good, Fair, Poor (or Excellent, Very Good, Critical, Dying); name \
                     another column with --condition-col",
                    filled[0].trim()
                ),
            ));
        }
        Ok(())
    }

    /// What was seen of a row, each column's cell from `get`.
    pub fn read(&self, get: impl Fn(&Option<String>) -> Option<String>) -> Observed {
        let mut o = Observed::default();
        // Values not placed, gathered apart from `o` (the closure below borrows them).
        let mut kept: Vec<(String, String)> = Vec::new();
        if let Some(v) = get(&self.condition) {
            o.condition = Condition::parse(&v);
            // A dead tree's condition is its status; anything else unplaced is listed.
            if o.condition.is_none() && !v.to_ascii_lowercase().contains("dead") {
                kept.push((self.condition.clone().unwrap_or_default(), v));
            }
        }
        let mut flag = |c: &Option<String>| -> Option<bool> {
            let v = get(c)?;
            let b = yes_no(&v);
            if b.is_none() {
                kept.push((c.clone().unwrap_or_default(), v));
            }
            b
        };
        o.sidewalk_damage = flag(&self.sidewalk);
        o.branch_lights = flag(&self.branch_lights);
        let either = |a: Option<bool>, b: Option<bool>| match (a, b) {
            (None, None) => None,
            (a, b) => Some(a.unwrap_or(false) || b.unwrap_or(false)),
        };
        let trunk = [flag(&self.trunk[0]), flag(&self.trunk[1])];
        o.trunk_wire_or_lights = either(trunk[0], trunk[1]);
        let roots = [flag(&self.roots[0]), flag(&self.roots[1])];
        o.root_paving = either(roots[0], roots[1]);
        if let Some(v) = get(&self.curb) {
            o.curb = Curb::parse(&v);
            if o.curb.is_none() {
                kept.push((self.curb.clone().unwrap_or_default(), v));
            }
        }
        o.unread = kept;
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(names: &[&str]) -> Vec<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn each_layouts_condition_values_map_onto_the_reports_classes() {
        // The census's `health`.
        for (v, c) in [
            ("Good", Condition::Good),
            ("Fair", Condition::Fair),
            ("Poor", Condition::Poor),
        ] {
            assert_eq!(Condition::parse(v), Some(c), "{v}");
        }
        // i-Tree's finer classes, as GIS exports and i-Tree inventories write them.
        for (v, c) in [
            ("Excellent", Condition::Good),
            ("Very Good", Condition::Good),
            ("very_good", Condition::Good),
            ("GOOD", Condition::Good),
            ("fair", Condition::Fair),
            ("Critical", Condition::Poor),
            ("Dying", Condition::Poor),
        ] {
            assert_eq!(Condition::parse(v), Some(c), "{v}");
        }
        for v in ["Dead", "OK", "3", ""] {
            assert_eq!(Condition::parse(v), None, "{v}");
        }
        // The census's header finds `health` and its problems; a GIS export's `Condition`.
        let census = ObservedColumns::default().completed(&header(&[
            "tree_id",
            "health",
            "sidewalk",
            "brch_light",
            "trunk_wire",
            "trnk_light",
            "root_stone",
            "root_grate",
        ]));
        assert_eq!(census.condition.as_deref(), Some("health"));
        assert_eq!(census.sidewalk.as_deref(), Some("sidewalk"));
        let gis = ObservedColumns::default().completed(&header(&["OBJECTID", "Condition"]));
        assert_eq!(gis.condition.as_deref(), Some("Condition"));
        assert_eq!(gis.sidewalk, None);
    }

    #[test]
    fn a_row_reads_its_condition_and_problems_and_keeps_what_it_cannot_place() {
        let columns = ObservedColumns::default().completed(&header(&[
            "health",
            "sidewalk",
            "brch_light",
            "trunk_wire",
            "trnk_light",
            "root_stone",
        ]));
        let row = |cells: &[(&str, &str)]| {
            let cells: Vec<(String, String)> = cells
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect();
            columns.read(|c| {
                let c = c.as_deref()?;
                cells.iter().find(|(k, _)| k == c).map(|(_, v)| v.clone())
            })
        };
        let o = row(&[
            ("health", "Fair"),
            ("sidewalk", "Damage"),
            ("brch_light", "No"),
            ("trunk_wire", "No"),
            ("trnk_light", "Yes"),
        ]);
        assert_eq!(o.condition, Some(Condition::Fair));
        assert_eq!(o.sidewalk_damage, Some(true));
        assert_eq!(o.branch_lights, Some(false));
        assert_eq!(o.trunk_wire_or_lights, Some(true));
        assert_eq!(o.root_paving, None, "root_stone's cell is empty");
        assert!(o.unread.is_empty());
        let o = row(&[("health", "Splendid"), ("sidewalk", "maybe")]);
        assert_eq!((o.condition, o.sidewalk_damage), (None, None));
        assert_eq!(
            o.unread,
            vec![
                ("health".to_string(), "Splendid".to_string()),
                ("sidewalk".to_string(), "maybe".to_string())
            ]
        );
        // A dead tree's "Dead" is its status, not an unplaced condition.
        assert!(row(&[("health", "Dead")]).unread.is_empty());
    }

    #[test]
    fn a_condition_column_of_numbers_is_refused_naming_it() {
        let columns = ObservedColumns {
            condition: Some("COND_PCT".into()),
            ..Default::default()
        };
        let e = columns
            .check(&["80", "", "65.5"], Path::new("trees.csv"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("trees.csv") && e.contains("`COND_PCT`") && e.contains("80"),
            "{e}"
        );
        assert!(columns.check(&["Good", "80"], Path::new("t.csv")).is_ok());
    }
}
