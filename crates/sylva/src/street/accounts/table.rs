//! Yearly accounts as CSV columns, for `sylva grow`, `sylva rank` and anything that
//! serves them (an empty cell or `null` where a model or a price is missing, never a zero).

use crate::growth::CutKind;
use crate::street::accounts::items::{Benefit, Cost};
use crate::street::accounts::ledger::YearAccount;
use crate::street::accounts::money::Basis;
use crate::street::accounts::pruner::PruningYear;
use crate::street::accounts::typical::Typical;
use crate::street::work::conflicts::{Conflict, Kind};
use std::fmt::Write as _;
use std::sync::OnceLock;

/// A column: its name and how a cell is written from an account.
struct Column {
    name: String,
    cell: Box<dyn Fn(&YearAccount) -> String + Send + Sync>,
}

/// A column of a fixed name.
fn column(name: &str, cell: impl Fn(&YearAccount) -> String + Send + Sync + 'static) -> Column {
    Column {
        name: name.to_string(),
        cell: Box::new(cell),
    }
}

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or(String::new(), |v| format!("{v:.digits$}"))
}

fn typical(a: &YearAccount, f: fn(&Typical) -> Option<f64>, digits: usize) -> String {
    cell(a.typical.as_ref().and_then(f), digits)
}

/// Every column after a growth report's own: the grown tree on this site, then i-Tree's
/// typical position, then costs and both nets. The benefits' and costs' columns are one per
/// item of `items.rs`, named by its key.
fn columns() -> &'static [Column] {
    static COLUMNS: OnceLock<Vec<Column>> = OnceLock::new();
    COLUMNS.get_or_init(|| {
        let mut out = vec![
            column("co2_stored_kg", |a| cell(a.co2_stored_kg, 1)),
            column("co2_sequestered_kg", |a| cell(a.co2_sequestered_kg, 2)),
            column("co2_avoided_kg", |a| cell(a.co2_avoided_kg, 2)),
            column("interception_m3", |a| cell(a.interception_m3, 3)),
            column("cooling_kwh", |a| {
                cell(a.energy.map(|e| e.electricity_kwh()), 1)
            }),
            column("natural_gas_kbtu", |a| {
                cell(a.energy.map(|e| e.natural_gas_kbtu()), 1)
            }),
            column("shade_cooling_kwh", |a| {
                cell(a.energy.map(|e| e.shade_cooling_kwh), 1)
            }),
            column("heating_penalty_kbtu", |a| {
                cell(a.energy.map(|e| e.heating_penalty_kbtu), 1)
            }),
            column("useful_winter_share", |a| {
                cell(a.energy.map(|e| e.useful_winter_share), 3)
            }),
            column("climate_cooling_kwh", |a| {
                cell(a.energy.and_then(|e| e.climate).map(|c| c.0), 1)
            }),
            column("climate_heating_kbtu", |a| {
                cell(a.energy.and_then(|e| e.climate).map(|c| c.1), 1)
            }),
            column("facade_shaded_m2h", |a| {
                cell(a.energy.map(|e| e.summer.shaded_m2h), 0)
            }),
            column("air_removed_kg", |a| cell(a.air.map(|q| q.removed_kg()), 3)),
            column("bvoc_kg", |a| cell(a.air.map(|q| q.bvoc_kg), 3)),
            column("leaf_gain_m2", |a| format!("{:.1}", a.leaf_gain_m2)),
        ];
        for b in Benefit::ALL {
            let key = b.item().key;
            out.push(column(&format!("value_{key}_usd"), move |a| {
                cell(a.money.get(b), 2)
            }));
        }
        out.extend([
            column("typical_row", |a| {
                a.typical.as_ref().map_or(String::new(), |t| t.row.clone())
            }),
            column("typical_held", |a| {
                a.typical
                    .as_ref()
                    .map_or(String::new(), |t| t.held.to_string())
            }),
            column("typical_electricity_kwh", |a| {
                typical(a, |t| Some(t.amounts.electricity_kwh), 1)
            }),
            column("typical_natural_gas_kbtu", |a| {
                typical(a, |t| Some(t.amounts.natural_gas_kbtu), 1)
            }),
            column("typical_stormwater_m3", |a| {
                typical(a, |t| Some(t.amounts.stormwater_m3), 3)
            }),
            column("typical_co2_sequestered_kg", |a| {
                typical(a, |t| Some(t.amounts.co2_sequestered_kg), 2)
            }),
            column("typical_co2_avoided_kg", |a| {
                typical(a, |t| Some(t.amounts.co2_avoided_kg), 2)
            }),
            column("typical_air_removed_kg", |a| {
                typical(a, |t| Some(t.amounts.air.removed_kg()), 3)
            }),
            column("typical_bvoc_kg", |a| {
                typical(a, |t| Some(t.amounts.air.bvoc_kg), 3)
            }),
            column("typical_leaf_gain_m2", |a| {
                typical(a, |t| Some(t.amounts.leaf_gain_m2), 1)
            }),
        ]);
        for b in Benefit::ALL {
            let key = b.item().key;
            out.push(column(&format!("typical_value_{key}_usd"), move |a| {
                cell(a.typical.as_ref().and_then(|t| t.money.get(b)), 2)
            }));
        }
        for c in Cost::ALL {
            let key = c.item().key;
            out.push(column(&format!("cost_{key}_usd"), move |a| {
                cell(a.costs.map(|y| y[c]), 2)
            }));
        }
        out.extend([
            column("net_usd", |a| format!("{:.2}", a.net(Basis::Site))),
            column("typical_net_usd", |a| {
                a.typical
                    .as_ref()
                    .map_or(String::new(), |_| format!("{:.2}", a.net(Basis::Typical)))
            }),
            // Per tree planted: the living tree's figures weighted by the share standing.
            column("alive_share", |a| format!("{:.4}", a.cohort.alive)),
            column("died_share", |a| format!("{:.4}", a.cohort.died)),
            column("planted_net_usd", |a| {
                format!("{:.2}", a.planted_net(Basis::Site))
            }),
            column("typical_planted_net_usd", |a| {
                a.typical.as_ref().map_or(String::new(), |_| {
                    format!("{:.2}", a.planted_net(Basis::Typical))
                })
            }),
            column("conflicts", |a| conflicts_cell(&a.conflicts)),
            // The site's lines, before the year's cuts: the nearest any wood or leaf came, the
            // most of the leaf inside a line's clearance at cutting, and whether any entered
            // a line's minimum; empty without a line (or where the tree was not pruned).
            column("line_closest_m", |a| {
                let near = (a.lines.iter())
                    .map(|l| l.check.closest_m)
                    .filter(|d| d.is_finite())
                    .fold(f64::INFINITY, f64::min);
                cell(near.is_finite().then_some(near), 2)
            }),
            column("line_leaf_share_in_clearance", |a| {
                let share = (a.lines.iter()).map(|l| l.check.leaf_share_in_clearance);
                cell(share.reduce(f64::max), 3)
            }),
            column("line_breach", |a| {
                if a.lines.is_empty() {
                    String::new()
                } else {
                    a.lines.iter().any(|l| l.breach).to_string()
                }
            }),
            // This year's pruning, empty where no cycle fell due (or the tree was not pruned).
            column("pruning", |a| {
                pruning_cell(a, |p| {
                    let reasons: Vec<&str> = p.reasons.iter().map(|r| r.name()).collect();
                    reasons.join(";")
                })
            }),
            column("pruning_removal_cuts", |a| {
                pruning_cell(a, |p| p.count(CutKind::Removal).to_string())
            }),
            column("pruning_reduction_cuts", |a| {
                pruning_cell(a, |p| p.count(CutKind::Reduction).to_string())
            }),
            column("pruning_heading_cuts", |a| {
                pruning_cell(a, |p| p.count(CutKind::Heading).to_string())
            }),
            column("pruning_hot_spots", |a| {
                pruning_cell(a, |p| p.hot_spots.to_string())
            }),
            column("pruning_largest_cut_cm", |a| {
                pruning_cell(a, |p| format!("{:.1}", 100.0 * p.cuts.largest_diameter()))
            }),
            column("pruning_wood_m3", |a| {
                pruning_cell(a, |p| format!("{:.4}", p.wood_m3()))
            }),
            column("pruning_leaf_m2", |a| {
                pruning_cell(a, |p| format!("{:.1}", p.leaf_m2()))
            }),
            column("pruning_visits", |a| {
                pruning_cell(a, |p| p.visits.to_string())
            }),
            column("pruning_cost_usd", |a| {
                pruning_cell(a, |p| format!("{:.2}", p.cost))
            }),
            column("pruning_resolved", |a| {
                pruning_cell(a, |p| kinds_cell(&p.resolved()))
            }),
            column("pruning_unresolved", |a| {
                pruning_cell(a, |p| kinds_cell(&p.unresolved))
            }),
        ]);
        out
    })
}

fn pruning_cell(a: &YearAccount, f: impl Fn(&PruningYear) -> String) -> String {
    a.pruning.as_ref().map_or(String::new(), f)
}

fn kinds_cell(kinds: &[Kind]) -> String {
    kinds.iter().map(|k| k.name()).collect::<Vec<_>>().join(";")
}

/// The account's CSV columns, after a growth report's own: `net_usd` is the grown tree's on
/// this site, `typical_net_usd` i-Tree's typical position's.
pub fn header() -> String {
    (columns().iter())
        .map(|c| c.name.as_str())
        .collect::<Vec<_>>()
        .join(",")
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
    (columns().iter())
        .map(|c| (c.cell)(a))
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
                .unwrap_or_else(|| ",".repeat(columns().len() - 1)),
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
            "[street]\ncurb = -1.0\nsidewalk = [0.8, 3.2]\nroadway_clearance = 4.3\nsidewalk_clearance = 2.4\n[[wire]]\nheight = 5.0\noffset = 0.0\nclearance = 2.0\nminimum = 0.46\n",
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
        assert_eq!(header.len(), 18 + columns().len());
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
        // Every item of the one table is in the record and the CSV, by its key, and
        // nothing else is.
        use crate::street::accounts::items::{BENEFITS, COSTS};
        let keys = |v: &serde_json::Value| -> Vec<String> {
            let mut k: Vec<String> = v.as_object().unwrap().keys().cloned().collect();
            k.sort();
            k
        };
        let sorted = |items: &[crate::street::accounts::items::Item]| -> Vec<String> {
            let mut k: Vec<String> = items.iter().map(|i| i.key.to_string()).collect();
            k.sort();
            k
        };
        assert_eq!(keys(&j["value_usd"]), sorted(&BENEFITS));
        assert_eq!(keys(&j["typical"]["value_usd"]), sorted(&BENEFITS));
        assert_eq!(keys(&j["cost_usd"]), sorted(&COSTS));
        for item in &COSTS {
            assert!(header.iter().any(|h| h == format!("cost_{}_usd", item.key)));
        }
        for item in &BENEFITS {
            assert!(
                header
                    .iter()
                    .any(|h| h == format!("value_{}_usd", item.key))
            );
            assert!(
                header
                    .iter()
                    .any(|h| h == format!("typical_value_{}_usd", item.key))
            );
        }
        let costs = header.iter().filter(|h| h.starts_with("cost_")).count();
        assert_eq!(costs, COSTS.len());
    }
}
