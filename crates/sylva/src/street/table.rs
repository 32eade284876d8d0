//! Yearly accounts as CSV columns and JSON, for `sylva grow`, `sylva rank` and anything that
//! serves them (an empty cell or `null` where a model or a price is missing, never a zero).

use super::conflicts::Conflict;
use super::ledger::YearAccount;
use std::fmt::Write as _;

/// The account's CSV columns, after a growth report's own.
pub const HEADER: &str = "co2_stored_kg,co2_sequestered_kg,interception_m3,cooling_kwh,\
heating_penalty_kbtu,facade_shaded_m2h,value_carbon_usd,value_stormwater_usd,\
value_cooling_usd,value_heating_usd,cost_planting_usd,cost_pruning_usd,cost_removal_usd,\
cost_sidewalk_usd,cost_cleanup_usd,cost_average_usd,net_usd,conflicts";

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or(String::new(), |v| format!("{v:.digits$}"))
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

/// One account's cells, in [`HEADER`]'s order.
pub fn row(a: &YearAccount) -> String {
    let e = a.energy;
    let c = a.costs;
    let m = &a.money;
    [
        cell(a.co2_stored_kg, 1),
        cell(a.co2_sequestered_kg, 2),
        cell(a.interception_m3, 3),
        cell(e.map(|e| e.cooling_kwh), 1),
        cell(e.map(|e| e.heating_penalty_kbtu), 1),
        cell(e.map(|e| e.summer.shaded_m2h), 0),
        cell(m.carbon, 2),
        cell(m.stormwater, 2),
        cell(m.cooling, 2),
        cell(m.heating, 2),
        cell(c.map(|c| c.planting), 2),
        cell(c.map(|c| c.pruning), 2),
        cell(c.map(|c| c.removal), 2),
        cell(c.map(|c| c.sidewalk), 2),
        cell(c.map(|c| c.cleanup), 2),
        cell(c.map(|c| c.average), 2),
        format!("{:.2}", a.net()),
        conflicts_cell(&a.conflicts),
    ]
    .join(",")
}

/// A growth report's CSV (one header line, then one row per age) with each age's account
/// appended to its row.
pub fn join_csv(growth_csv: &str, accounts: &[YearAccount]) -> String {
    let mut out = String::with_capacity(growth_csv.len() * 2);
    for (i, line) in growth_csv.lines().enumerate() {
        let extra = match i {
            0 => HEADER.to_string(),
            _ => accounts
                .get(i - 1)
                .map(row)
                .unwrap_or_else(|| ",".repeat(17)),
        };
        // Writing into a String cannot fail.
        let _ = writeln!(out, "{line},{extra}");
    }
    out
}

/// One account as JSON.
pub fn json(a: &YearAccount) -> serde_json::Value {
    let round = |v: Option<f64>, k: f64| v.map(|v| (v * k).round() / k);
    let e = a.energy;
    serde_json::json!({
        "co2_stored_kg": round(a.co2_stored_kg, 10.0),
        "co2_sequestered_kg": round(a.co2_sequestered_kg, 100.0),
        "interception_m3": round(a.interception_m3, 1e3),
        "cooling_kwh": round(e.map(|e| e.cooling_kwh), 10.0),
        "heating_penalty_kbtu": round(e.map(|e| e.heating_penalty_kbtu), 10.0),
        "facade_shaded_m2h": round(e.map(|e| e.summer.shaded_m2h), 1.0),
        "value_usd": {
            "carbon": round(a.money.carbon, 100.0),
            "stormwater": round(a.money.stormwater, 100.0),
            "cooling": round(a.money.cooling, 100.0),
            "heating": round(a.money.heating, 100.0),
        },
        "cost_usd": a.costs.map(|c| serde_json::json!({
            "planting": (c.planting * 100.0).round() / 100.0,
            "pruning": (c.pruning * 100.0).round() / 100.0,
            "removal": (c.removal * 100.0).round() / 100.0,
            "sidewalk": (c.sidewalk * 100.0).round() / 100.0,
            "cleanup": (c.cleanup * 100.0).round() / 100.0,
            "average": (c.average * 100.0).round() / 100.0,
        })),
        "net_usd": (a.net() * 100.0).round() / 100.0,
        "conflicts": a.conflicts.iter().map(|c| serde_json::json!({
            "kind": c.kind.name(),
            "part": c.part.name(),
            "leaf_area_m2": (c.leaf_area * 10.0).round() / 10.0,
            "leaf_share": (c.leaf_share * 1e3).round() / 1e3,
            "from_m": (c.heights.0 * 100.0).round() / 100.0,
            "to_m": (c.heights.1 * 100.0).round() / 100.0,
        })).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;
    use crate::growth::report::{Cohort, csv};
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
        assert_eq!(header.len(), 17 + 18);
        let rows: Vec<_> = reader.records().map(|r| r.unwrap()).collect();
        assert_eq!(rows.len(), 2);
        let col = |name: &str| header.iter().position(|h| h == name).unwrap();
        // No façade: energy cells are empty, not zero; Modesto's average cost is charged.
        assert_eq!(&rows[0][col("cooling_kwh")], "");
        assert_eq!(&rows[0][col("cost_pruning_usd")], "0.00");
        assert_eq!(&rows[0][col("cost_average_usd")], "28.77");
        let stored: f64 = rows[1][col("co2_stored_kg")].parse().unwrap();
        assert!((stored - accounts[1].co2_stored_kg.unwrap()).abs() < 0.1);
        // The low wire is hit by the leader.
        assert!(
            rows[1][col("conflicts")].contains("wire:"),
            "{:?}",
            &rows[1]
        );
        let j = json(&accounts[1]);
        assert!(j["cooling_kwh"].is_null());
        assert_eq!(j["conflicts"][0]["kind"], "wire");
    }
}
