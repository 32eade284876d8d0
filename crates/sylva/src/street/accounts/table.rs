//! Yearly accounts as CSV columns, for `sylva grow`, `sylva rank` and anything that
//! serves them (an empty cell or `null` where a model or a price is missing, never a zero).

use crate::growth::CutKind;
use crate::street::accounts::ledger::YearAccount;
use crate::street::accounts::money::Basis;
use crate::street::accounts::pruner::PruningYear;
use crate::street::accounts::typical::Typical;
use crate::street::work::conflicts::{Conflict, Kind};
use std::fmt::Write as _;

/// A column: its name and how a cell is written from an account.
type Column = (&'static str, fn(&YearAccount) -> String);

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or(String::new(), |v| format!("{v:.digits$}"))
}

fn typical(a: &YearAccount, f: fn(&Typical) -> Option<f64>, digits: usize) -> String {
    cell(a.typical.as_ref().and_then(f), digits)
}

/// Every column after a growth report's own: the grown tree on this site, then i-Tree's
/// typical position, then costs and both nets.
const COLUMNS: &[Column] = &[
    ("co2_stored_kg", |a| cell(a.co2_stored_kg, 1)),
    ("co2_sequestered_kg", |a| cell(a.co2_sequestered_kg, 2)),
    ("co2_avoided_kg", |a| cell(a.co2_avoided_kg, 2)),
    ("interception_m3", |a| cell(a.interception_m3, 3)),
    ("cooling_kwh", |a| {
        cell(a.energy.map(|e| e.electricity_kwh()), 1)
    }),
    ("natural_gas_kbtu", |a| {
        cell(a.energy.map(|e| e.natural_gas_kbtu()), 1)
    }),
    ("shade_cooling_kwh", |a| {
        cell(a.energy.map(|e| e.shade_cooling_kwh), 1)
    }),
    ("heating_penalty_kbtu", |a| {
        cell(a.energy.map(|e| e.heating_penalty_kbtu), 1)
    }),
    ("useful_winter_share", |a| {
        cell(a.energy.map(|e| e.useful_winter_share), 3)
    }),
    ("climate_cooling_kwh", |a| {
        cell(a.energy.and_then(|e| e.climate).map(|c| c.0), 1)
    }),
    ("climate_heating_kbtu", |a| {
        cell(a.energy.and_then(|e| e.climate).map(|c| c.1), 1)
    }),
    ("facade_shaded_m2h", |a| {
        cell(a.energy.map(|e| e.summer.shaded_m2h), 0)
    }),
    ("air_removed_kg", |a| cell(a.air.map(|q| q.removed_kg()), 3)),
    ("bvoc_kg", |a| cell(a.air.map(|q| q.bvoc_kg), 3)),
    ("leaf_gain_m2", |a| format!("{:.1}", a.leaf_gain_m2)),
    ("value_carbon_usd", |a| cell(a.money.carbon, 2)),
    ("value_co2_avoided_usd", |a| cell(a.money.co2_avoided, 2)),
    ("value_stormwater_usd", |a| cell(a.money.stormwater, 2)),
    ("value_cooling_usd", |a| cell(a.money.cooling, 2)),
    ("value_heating_usd", |a| cell(a.money.heating, 2)),
    ("value_air_quality_usd", |a| cell(a.money.air_quality, 2)),
    ("value_bvoc_usd", |a| cell(a.money.bvoc, 2)),
    ("value_aesthetics_usd", |a| cell(a.money.aesthetics, 2)),
    ("typical_row", |a| {
        a.typical.as_ref().map_or(String::new(), |t| t.row.clone())
    }),
    ("typical_held", |a| {
        a.typical
            .as_ref()
            .map_or(String::new(), |t| t.held.to_string())
    }),
    ("typical_electricity_kwh", |a| {
        typical(a, |t| Some(t.amounts.electricity_kwh), 1)
    }),
    ("typical_natural_gas_kbtu", |a| {
        typical(a, |t| Some(t.amounts.natural_gas_kbtu), 1)
    }),
    ("typical_stormwater_m3", |a| {
        typical(a, |t| Some(t.amounts.stormwater_m3), 3)
    }),
    ("typical_co2_sequestered_kg", |a| {
        typical(a, |t| Some(t.amounts.co2_sequestered_kg), 2)
    }),
    ("typical_co2_avoided_kg", |a| {
        typical(a, |t| Some(t.amounts.co2_avoided_kg), 2)
    }),
    ("typical_air_removed_kg", |a| {
        typical(a, |t| Some(t.amounts.air.removed_kg()), 3)
    }),
    ("typical_bvoc_kg", |a| {
        typical(a, |t| Some(t.amounts.air.bvoc_kg), 3)
    }),
    ("typical_leaf_gain_m2", |a| {
        typical(a, |t| Some(t.amounts.leaf_gain_m2), 1)
    }),
    ("typical_value_carbon_usd", |a| {
        typical(a, |t| t.money.carbon, 2)
    }),
    ("typical_value_co2_avoided_usd", |a| {
        typical(a, |t| t.money.co2_avoided, 2)
    }),
    ("typical_value_stormwater_usd", |a| {
        typical(a, |t| t.money.stormwater, 2)
    }),
    ("typical_value_cooling_usd", |a| {
        typical(a, |t| t.money.cooling, 2)
    }),
    ("typical_value_heating_usd", |a| {
        typical(a, |t| t.money.heating, 2)
    }),
    ("typical_value_air_quality_usd", |a| {
        typical(a, |t| t.money.air_quality, 2)
    }),
    ("typical_value_bvoc_usd", |a| {
        typical(a, |t| t.money.bvoc, 2)
    }),
    ("typical_value_aesthetics_usd", |a| {
        typical(a, |t| t.money.aesthetics, 2)
    }),
    ("cost_planting_usd", |a| {
        cell(a.costs.map(|c| c.planting), 2)
    }),
    ("cost_pruning_usd", |a| cell(a.costs.map(|c| c.pruning), 2)),
    ("cost_removal_usd", |a| cell(a.costs.map(|c| c.removal), 2)),
    ("cost_sidewalk_usd", |a| {
        cell(a.costs.map(|c| c.sidewalk), 2)
    }),
    ("cost_cleanup_usd", |a| cell(a.costs.map(|c| c.cleanup), 2)),
    ("cost_average_usd", |a| cell(a.costs.map(|c| c.average), 2)),
    ("cost_cycles_usd", |a| cell(a.costs.map(|c| c.cycles), 2)),
    ("cost_other_usd", |a| cell(a.costs.map(|c| c.other), 2)),
    ("cost_line_clearance_utility_usd", |a| {
        cell(a.costs.map(|c| c.utility), 2)
    }),
    ("net_usd", |a| format!("{:.2}", a.net(Basis::Site))),
    ("typical_net_usd", |a| {
        a.typical
            .as_ref()
            .map_or(String::new(), |_| format!("{:.2}", a.net(Basis::Typical)))
    }),
    // Per tree planted: the living tree's figures weighted by the share standing.
    ("alive_share", |a| format!("{:.4}", a.cohort.alive)),
    ("died_share", |a| format!("{:.4}", a.cohort.died)),
    ("planted_net_usd", |a| {
        format!("{:.2}", a.planted_net(Basis::Site))
    }),
    ("typical_planted_net_usd", |a| {
        a.typical.as_ref().map_or(String::new(), |_| {
            format!("{:.2}", a.planted_net(Basis::Typical))
        })
    }),
    ("conflicts", |a| conflicts_cell(&a.conflicts)),
    // This year's pruning, empty where no cycle fell due (or the tree was not pruned).
    ("pruning", |a| {
        pruning_cell(a, |p| {
            let reasons: Vec<&str> = p.reasons.iter().map(|r| r.name()).collect();
            reasons.join(";")
        })
    }),
    ("pruning_removal_cuts", |a| {
        pruning_cell(a, |p| p.count(CutKind::Removal).to_string())
    }),
    ("pruning_reduction_cuts", |a| {
        pruning_cell(a, |p| p.count(CutKind::Reduction).to_string())
    }),
    ("pruning_largest_cut_cm", |a| {
        pruning_cell(a, |p| format!("{:.1}", 100.0 * p.cuts.largest_diameter()))
    }),
    ("pruning_wood_m3", |a| {
        pruning_cell(a, |p| format!("{:.4}", p.wood_m3()))
    }),
    ("pruning_leaf_m2", |a| {
        pruning_cell(a, |p| format!("{:.1}", p.leaf_m2()))
    }),
    ("pruning_visits", |a| {
        pruning_cell(a, |p| p.visits.to_string())
    }),
    ("pruning_cost_usd", |a| {
        pruning_cell(a, |p| format!("{:.2}", p.cost))
    }),
    ("pruning_resolved", |a| {
        pruning_cell(a, |p| kinds_cell(&p.resolved()))
    }),
    ("pruning_unresolved", |a| {
        pruning_cell(a, |p| kinds_cell(&p.unresolved))
    }),
];

fn pruning_cell(a: &YearAccount, f: impl Fn(&PruningYear) -> String) -> String {
    a.pruning.as_ref().map_or(String::new(), f)
}

fn kinds_cell(kinds: &[Kind]) -> String {
    kinds.iter().map(|k| k.name()).collect::<Vec<_>>().join(";")
}

/// The account's CSV columns, after a growth report's own: `net_usd` is the grown tree's on
/// this site, `typical_net_usd` i-Tree's typical position's.
pub fn header() -> String {
    COLUMNS.iter().map(|c| c.0).collect::<Vec<_>>().join(",")
}

/// Conflicts as one cell: `kind:part:share%` joined by `;`.
pub fn conflicts_cell(conflicts: &[Conflict]) -> String {
    conflicts
        .iter()
        .map(|c| {
            format!(
                "{}:{}:{:.1}%",
                c.kind.name(),
                c.part.name(),
                c.leaf_share * 100.0
            )
        })
        .collect::<Vec<_>>()
        .join(";")
}

/// One account's cells, in [`header`]'s order.
pub fn row(a: &YearAccount) -> String {
    COLUMNS
        .iter()
        .map(|c| (c.1)(a))
        .collect::<Vec<_>>()
        .join(",")
}

/// A growth report's CSV (one header line, then one row per age) with each age's account
/// appended to its row.
pub fn join_csv(growth_csv: &str, accounts: &[YearAccount]) -> String {
    let mut out = String::with_capacity(growth_csv.len() * 3);
    for (i, line) in growth_csv.lines().enumerate() {
        let extra = match i {
            0 => header(),
            _ => accounts
                .get(i - 1)
                .map(row)
                .unwrap_or_else(|| ",".repeat(COLUMNS.len() - 1)),
        };
        // Writing into a String cannot fail.
        let _ = writeln!(out, "{line},{extra}");
    }
    out
}

/// A year's net in words, at typical position and on the site where there is one (`sylva grow`'s
/// lines and captions).
pub fn net_words(a: &YearAccount, has_site: bool) -> String {
    let typical = (a.typical.as_ref())
        .map(|_| format!("net ${:.0}/yr at typical position", a.net(Basis::Typical)));
    let site = has_site.then(|| format!("${:.0}/yr on this site", a.net(Basis::Site)));
    match (typical, site) {
        (Some(t), Some(s)) => format!("{t}, {s}"),
        (Some(t), None) => t,
        (None, Some(s)) => format!("net {s}"),
        (None, None) => format!("net ${:.0}/yr (own crown, no site)", a.net(Basis::Site)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::growth::survey::report::{Cohort, csv};
    use crate::record::to_json;
    use crate::street::accounts::records::AccountRecord;
    use crate::street::{Assessor, Site};

    #[test]
    fn columns_line_up_and_missing_is_empty() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let site = Site::parse(
            "[street]\ncurb = -1.0\nsidewalk = [0.8, 3.2]\nroadway_clearance = 4.3\nsidewalk_clearance = 2.4\n[[wire]]\nheight = 5.0\noffset = 0.0\nclearance = 2.0\n",
            "t",
        )
        .unwrap();
        let mut assessor = Assessor::new(&plane, Some(site), None, None);
        let mut cohort = Cohort::new(vec![plane], 0);
        let mut accounts = Vec::new();
        for age in [6.0, 7.0] {
            let s = cohort.advance_to(age).remove(0);
            let dims = cohort.history[0].last().unwrap().model;
            accounts.push(assessor.year(age, &dims, &s));
        }
        let text = join_csv(&csv(&cohort.history[0]), &accounts);
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let header = reader.headers().unwrap().clone();
        assert_eq!(header.len(), 18 + COLUMNS.len());
        let rows: Vec<_> = reader.records().map(|r| r.unwrap()).collect();
        assert_eq!(rows.len(), 2);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap();
        // No façade: energy cells are empty, not zero; the built-in sized costs are charged:
        // a visit at $3.90 a cm of DBH every 4 years, 8 from 15 cm; no programme average.
        assert_eq!(&rows[0][col("cooling_kwh")], "");
        let pruning: f64 = rows[0][col("cost_pruning_usd")].parse().unwrap();
        let dbh = accounts[0].dbh_cm;
        let cycle = if dbh <= 15.0 { 4.0 } else { 8.0 };
        assert!(
            (pruning - 3.90 * dbh / cycle).abs() < 0.006,
            "{pruning} at {dbh} cm"
        );
        assert_eq!(&rows[0][col("cost_average_usd")], "0.00");
        // Per tree planted: 5% die a year while establishing.
        let alive: f64 = rows[0][col("alive_share")].parse().unwrap();
        let later = crate::street::Survival::builtin("InlVal").later;
        let five = 0.95f64.powi(5);
        assert!(
            (alive - 0.5 * (five + five * later)).abs() < 1e-4,
            "{alive}"
        );
        let stored: f64 = rows[1][col("co2_stored_kg")].parse().unwrap();
        assert!((stored - accounts[1].co2_stored_kg.unwrap()).abs() < 0.1);
        // The low wire is hit by the leader.
        assert!(
            rows[1][col("conflicts")].contains("wire:"),
            "{:?}",
            &rows[1]
        );
        // Typical position: the plane's own Modesto row, with energy where the grown tree
        // without a façade has none, and its net written.
        assert_eq!(&rows[1][col("typical_row")], "PLAC");
        let t = &accounts[1];
        assert!(
            t.money(Basis::Typical).cooling.is_some() && t.money(Basis::Site).cooling.is_none()
        );
        let typical: f64 = rows[1][col("typical_net_usd")].parse().unwrap();
        assert!((typical - t.net(Basis::Typical)).abs() < 0.006, "{typical}");
        let j = to_json(&AccountRecord::of(&accounts[1]));
        assert!(j["cooling_kwh"].is_null());
        assert_eq!(j["typical"]["row"], "PLAC");
        assert!(j["typical"]["value_usd"]["air_quality"].as_f64().unwrap() > 0.0);
        // Aesthetics priced from California's median home value (McPherson 2007's method).
        assert!(j["typical"]["value_usd"]["aesthetics"].as_f64().unwrap() > 0.0);
        assert!(j["value_usd"]["aesthetics"].as_f64().unwrap() > 0.0);
        assert_eq!(j["conflicts"][0]["kind"], "wire");
    }
}
