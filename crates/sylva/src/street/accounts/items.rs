//! The account's items, each defined once: its key, label, unit, colour and who pays it.
//!
//! Every place that shows a year's account reads this table: the output records
//! (`records.rs`: `value_usd` and `cost_usd` keyed by [`Item::key`]), the CSV
//! (`table.rs`: `value_<key>_usd` and `cost_<key>_usd`), a ranking's sums by item
//! (`street::rank`), the benefit and cost bars (`sylva_render::chart`) and the planners' page
//! (`/api/items`, read by `charts.js`). A new cost is one more [`Cost`] and its row here; a test
//! in each of those places fails if it leaves an item out.

use serde::Serialize;

/// Which side of the account an item is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// A benefit: drawn up, added to the net (a negative one, a winter heating penalty or
    /// BVOCs emitted, is drawn down).
    Benefit,
    /// A cost: drawn down, taken from the net.
    Cost,
}

/// Who pays a cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Payer {
    /// The city: its forestry and public works budgets.
    City,
    /// The electric utility whose lines cross the tree.
    Utility,
    /// The owners of the property beside the tree (their share of sidewalk repair).
    Owners,
}

impl Payer {
    /// Every payer, in report order.
    pub const ALL: [Payer; 3] = [Payer::City, Payer::Utility, Payer::Owners];

    /// Name in reports and records.
    pub fn name(self) -> &'static str {
        match self {
            Payer::City => "city",
            Payer::Utility => "utility",
            Payer::Owners => "owners",
        }
    }
}

/// One item of the account.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Item {
    /// Its key in records (`value_usd`, `cost_usd`) and CSV columns.
    pub key: &'static str,
    /// Its name in charts, tables and the page.
    pub label: &'static str,
    /// What a figure of it is.
    pub unit: &'static str,
    /// Its colour in charts, `#rrggbb`.
    pub colour: &'static str,
    /// Benefit or cost.
    pub side: Side,
    /// Who pays it (costs only).
    pub payer: Option<Payer>,
}

impl Item {
    /// Its colour as sRGB bytes.
    pub fn rgb(&self) -> [u8; 3] {
        let c = self.colour.trim_start_matches('#');
        let byte = |i: usize| u8::from_str_radix(&c[i..i + 2], 16).unwrap_or(0);
        [byte(0), byte(2), byte(4)]
    }
}

/// The year's dollars of a benefit.
const BENEFIT_UNIT: &str = "$ a year";
/// The year's dollars of a cost: a visit, a repair or a planting is charged in its year, a
/// chance of one as its expected cost.
const COST_UNIT: &str = "$ a year";

const fn benefit(key: &'static str, label: &'static str, colour: &'static str) -> Item {
    Item {
        key,
        label,
        unit: BENEFIT_UNIT,
        colour,
        side: Side::Benefit,
        payer: None,
    }
}

const fn cost(key: &'static str, label: &'static str, colour: &'static str, payer: Payer) -> Item {
    Item {
        key,
        label,
        unit: COST_UNIT,
        colour,
        side: Side::Cost,
        payer: Some(payer),
    }
}

/// i-Tree Streets' benefit categories, in [`Benefit`]'s order.
pub const BENEFITS: [Item; Benefit::COUNT] = [
    benefit("carbon", "CO₂ taken up", "#5b8c5a"),
    benefit("co2_avoided", "CO₂ avoided", "#8fb58a"),
    benefit("stormwater", "Rain held", "#4a87b5"),
    benefit("cooling", "Cooling", "#e0a43a"),
    benefit("heating", "Heating", "#b5654a"),
    benefit("air_quality", "Air quality", "#78bed2"),
    benefit("bvoc", "BVOCs emitted", "#5a9696"),
    benefit("aesthetics", "Aesthetics", "#c878be"),
];

/// The costs, in [`Cost`]'s order.
pub const COSTS: [Item; Cost::COUNT] = [
    cost("planting", "Planting", "#8c6d9e", Payer::City),
    cost("pruning", "Pruning", "#a07a52", Payer::City),
    cost("removal", "Removal", "#7d7d7d", Payer::City),
    cost(
        "sidewalk",
        "Sidewalk and curb (city)",
        "#b09a70",
        Payer::City,
    ),
    cost(
        "sidewalk_owners",
        "Sidewalk and curb (owners)",
        "#d8c49a",
        Payer::Owners,
    ),
    cost("sewer", "Sewer repair", "#6e7c5a", Payer::City),
    cost("mitigation", "Root mitigation", "#4f8f7a", Payer::City),
    cost("cleanup", "Clean-up", "#6f8f8f", Payer::City),
    cost(
        "liability_administration",
        "Trip-and-fall, repair admin",
        "#8a8fc0",
        Payer::City,
    ),
    cost("pest", "Pest management", "#6a7fa0", Payer::City),
    cost("average", "Programme average", "#9c5b5b", Payer::City),
    cost("cycles", "Pruning cycles (city)", "#d08a2e", Payer::City),
    cost(
        "line_clearance_utility",
        "Line clearance (utility)",
        "#5a5aa0",
        Payer::Utility,
    ),
];

/// A benefit category.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum Benefit {
    Carbon,
    Co2Avoided,
    Stormwater,
    Cooling,
    Heating,
    AirQuality,
    Bvoc,
    Aesthetics,
}

impl Benefit {
    /// How many there are.
    pub const COUNT: usize = 8;
    /// Every category, in report order.
    pub const ALL: [Benefit; Benefit::COUNT] = [
        Benefit::Carbon,
        Benefit::Co2Avoided,
        Benefit::Stormwater,
        Benefit::Cooling,
        Benefit::Heating,
        Benefit::AirQuality,
        Benefit::Bvoc,
        Benefit::Aesthetics,
    ];

    /// Its row of the table.
    pub fn item(self) -> &'static Item {
        &BENEFITS[self as usize]
    }
}

/// A cost item.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Cost {
    /// Buying and planting, and establishment care.
    Planting,
    /// Pruning on the cost table's own cycle (none where a site's cycles are charged).
    Pruning,
    /// Removal: the year's chance of coming out times its price.
    Removal,
    /// The city's share of sidewalk and curb repair.
    Sidewalk,
    /// The property owners' share of sidewalk and curb repair.
    SidewalkOwners,
    /// Sewer repair.
    Sewer,
    /// What the site does at planting to spare its pavement from the roots.
    Mitigation,
    /// Clean-up.
    Cleanup,
    /// Trip-and-fall claims and the inspection and administration of sidewalk repairs.
    Liability,
    /// Pest management.
    Pest,
    /// A programme's average, where no items are known.
    Average,
    /// The city's pruning cycles the site's regime cut this year.
    Cycles,
    /// The utility's line clearance.
    LineClearance,
}

impl Cost {
    /// How many there are.
    pub const COUNT: usize = 13;
    /// Every item, in report order.
    pub const ALL: [Cost; Cost::COUNT] = [
        Cost::Planting,
        Cost::Pruning,
        Cost::Removal,
        Cost::Sidewalk,
        Cost::SidewalkOwners,
        Cost::Sewer,
        Cost::Mitigation,
        Cost::Cleanup,
        Cost::Liability,
        Cost::Pest,
        Cost::Average,
        Cost::Cycles,
        Cost::LineClearance,
    ];

    /// Its row of the table.
    pub fn item(self) -> &'static Item {
        &COSTS[self as usize]
    }

    /// Whether it is paid at planting, for every tree planted (the rest are paid for the
    /// trees standing).
    pub fn at_planting(self) -> bool {
        matches!(self, Cost::Planting | Cost::Mitigation)
    }

    /// Who pays it.
    pub fn payer(self) -> Payer {
        self.item().payer.unwrap_or(Payer::City)
    }
}

/// The whole table, benefits first, as the page reads it (`/api/items`).
pub fn all() -> impl Iterator<Item = &'static Item> {
    BENEFITS.iter().chain(COSTS.iter())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_has_one_key_a_colour_and_costs_a_payer() {
        let mut keys: Vec<&str> = all().map(|i| i.key).collect();
        keys.sort();
        let n = keys.len();
        keys.dedup();
        assert_eq!(keys.len(), n, "keys are unique");
        for (i, b) in Benefit::ALL.iter().enumerate() {
            assert_eq!(*b as usize, i);
            assert_eq!(b.item().side, Side::Benefit);
            assert!(b.item().payer.is_none());
        }
        for (i, c) in Cost::ALL.iter().enumerate() {
            assert_eq!(*c as usize, i);
            assert_eq!(c.item().side, Side::Cost);
            assert!(c.item().payer.is_some(), "{}", c.item().key);
        }
        for item in all() {
            assert!(item.colour.len() == 7 && item.colour.starts_with('#'));
            assert!(u32::from_str_radix(&item.colour[1..], 16).is_ok());
            assert!(!item.label.is_empty() && !item.unit.is_empty());
        }
        assert_eq!(Cost::Planting.item().rgb(), [0x8c, 0x6d, 0x9e]);
        assert_eq!(Cost::LineClearance.payer(), Payer::Utility);
    }
}
