//! `sylva rank`: a region's species grown side by side on one site and listed by net benefit
//! over the years, with the year each first runs into the street.

use crate::args::{RankArgs, RankBy};
use crate::shared::{database, load_street, with_progress};
use anyhow::{Result, bail};
use sylva::growth::Measured;
use sylva::street::rank::{Pruning, Study, first_conflicts, rank};
use sylva::street::{Basis, Kind};

pub fn run(args: &RankArgs) -> Result<()> {
    if !(1.0..=sylva::growth::report::MAX_AGE).contains(&args.years) {
        bail!(
            "--years {}: expected 1 to {} years",
            args.years,
            sylva::growth::report::MAX_AGE
        );
    }
    let (site, prices, costs) = load_street(&args.street)?;
    let survival = crate::shared::survival(&args.street)?;
    let basis = match args.by {
        Some(RankBy::Typical) => Basis::Typical,
        Some(RankBy::Site) => Basis::Site,
        None => Basis::default_for(site.is_some()),
    };
    let db = database(args.database.as_ref())?;
    let mut species: Vec<Measured> = db
        .growable(&args.region)
        .iter()
        .map(|s| db.find(&args.region, &s.code))
        .collect::<Result<_, _>>()?;
    for code in &args.species {
        if !species
            .iter()
            .any(|m| m.species.code.eq_ignore_ascii_case(code))
        {
            bail!(
                "--species {code}: not a growable species of {}; see `sylva species --region {}`",
                args.region,
                args.region
            );
        }
    }
    if !args.species.is_empty() {
        species.retain(|m| {
            args.species
                .iter()
                .any(|c| c.eq_ignore_ascii_case(&m.species.code))
        });
    }
    if species.is_empty() {
        let known: Vec<&str> = db.regions().iter().map(|r| r.code.as_str()).collect();
        bail!(
            "--region {}: no such region with growable species; regions: {}",
            args.region,
            known.join(", ")
        );
    }
    if args.calibrate {
        return calibration(&species, args);
    }
    let count = species.len();
    let ranked = with_progress(count, |tick| {
        let study = Study {
            years: args.years,
            seed: args.seed,
            site: site.clone(),
            prices: prices.clone(),
            costs: costs.clone(),
            survival: survival.clone(),
            pruning: match (args.street.no_pruning, args.pruning_losses) {
                (true, _) => Pruning::Off,
                (false, true) => Pruning::Compare,
                (false, false) => Pruning::Regime,
            },
        };
        rank(species, &study, basis, &|_| tick())
    });
    if args.json {
        for r in &ranked {
            let first: Vec<serde_json::Value> = first_conflicts(&r.accounts)
                .iter()
                .map(|(age, c)| {
                    serde_json::json!({"kind": c.kind.name(), "age": age, "part": c.part.name(),
                        "leaf_share": (c.leaf_share * 1e3).round() / 1e3})
                })
                .collect();
            println!(
                "{}",
                serde_json::json!({
                    "species": r.species.species.code,
                    "name": r.species.species.common,
                    "years": r.last_age(),
                    "ranked_by": basis.name(),
                    "benefits_usd": (r.benefits(basis) * 100.0).round() / 100.0,
                    "costs_usd": r.accounts.iter().any(|a| a.costs.is_some())
                        .then(|| (r.costs() * 100.0).round() / 100.0),
                    "net_usd": (r.net(basis) * 100.0).round() / 100.0,
                    "per_tree_planted": true,
                    "alive_at_end": (r.alive_at_end() * 1e4).round() / 1e4,
                    "survival": r.survival,
                    "costs_by_item_usd": rounded(&r.costs_by_item()),
                    "typical": {
                        "benefits_usd": (r.benefits(Basis::Typical) * 100.0).round() / 100.0,
                        "net_usd": (r.net(Basis::Typical) * 100.0).round() / 100.0,
                        "by_category_usd": rounded(&r.by_category(Basis::Typical)),
                    },
                    "site": {
                        "benefits_usd": (r.benefits(Basis::Site) * 100.0).round() / 100.0,
                        "net_usd": (r.net(Basis::Site) * 100.0).round() / 100.0,
                        "by_category_usd": rounded(&r.by_category(Basis::Site)),
                    },
                    "first_conflicts": first,
                    "pruning": pruning_json(r),
                    "not_computed": r.missing,
                })
            );
        }
        return Ok(());
    }
    let place = &ranked[0].species.region;
    println!(
        "{} species of {} ({}), grown yearly to {} years{}; dollars per tree planted summed \
         over the years, undiscounted ({:.0}% alive at the end: {}); ranked by the net at {}",
        ranked.len(),
        place.name,
        place.city,
        args.years,
        args.street
            .site
            .as_ref()
            .map(|p| format!(" on {}", p.display()))
            .unwrap_or_default(),
        100.0 * ranked[0].alive_at_end(),
        ranked[0].survival,
        basis.name()
    );
    println!(
        "  {:<4} {:<34} {:>5} {:>10} {:>10} {:>10} {:>10} {:>10}  {:<22} first conflict with a fixture",
        "rank",
        "species",
        "years",
        "benefits",
        "(typical)",
        "costs",
        "net",
        "(typical)",
        "clearance pruning from"
    );
    println!(
        "  {:<4} {:<34} {:>5} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "", "", "", "this site", "position", "", "this site", "position"
    );
    for (i, r) in ranked.iter().enumerate() {
        // Growing into the clear heights over roadway and sidewalk is met by raising the
        // crown; fixtures (wall, awnings, signs, lines, lamps, sight lines, curb) are not.
        let first = first_conflicts(&r.accounts);
        let earliest = |clearance: bool| {
            first
                .iter()
                .filter(|(_, c)| matches!(c.kind, Kind::Roadway | Kind::Sidewalk) == clearance)
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(age, c)| format!("{} at {age:.0}", c.kind.name()))
                .unwrap_or_else(|| {
                    if site.is_some() {
                        "none".into()
                    } else {
                        "(no --site)".into()
                    }
                })
        };
        let (pruning, conflict) = (earliest(true), earliest(false));
        let carbon_missing = if r.accounts.iter().any(|a| a.co2_stored_kg.is_none()) {
            "  (carbon not computed)"
        } else {
            ""
        };
        // Without a site there is no façade: the grown tree's own column lacks energy and
        // is shown only where there is a site.
        let own = |v: f64| {
            if site.is_some() {
                format!("{v:.0}")
            } else {
                "-".into()
            }
        };
        println!(
            "  {:<4} {:<34} {:>5.0} {:>10} {:>10.0} {:>10} {:>10} {:>10.0}  {pruning:<22} {conflict}{carbon_missing}",
            i + 1,
            r.species.label(),
            r.last_age(),
            own(r.benefits(Basis::Site)),
            r.benefits(Basis::Typical),
            if r.accounts.iter().any(|a| a.costs.is_some()) {
                format!("{:.0}", r.costs())
            } else {
                "-".into()
            },
            own(r.net(Basis::Site)),
            r.net(Basis::Typical)
        );
    }
    // What every species lacks alike, said once.
    let common: Vec<&String> = ranked[0]
        .missing
        .iter()
        .filter(|m| ranked.iter().all(|r| r.missing.contains(m)))
        .collect();
    for m in common {
        println!("not counted: {m}");
    }
    Ok(())
}

/// Named dollar figures as a JSON object, to the cent (`null` where not computed).
fn rounded(items: &[(&'static str, Option<f64>)]) -> serde_json::Value {
    let mut out = serde_json::Map::new();
    for (name, v) in items {
        out.insert(
            name.to_string(),
            serde_json::json!(v.map(|x| (x * 100.0).round() / 100.0)),
        );
    }
    out.into()
}

/// `--calibrate`: the site model around the standard house beside i-Tree's figures.
fn calibration(species: &[Measured], args: &RankArgs) -> Result<()> {
    use sylva::street::accounts::calibrate::{
        STANDARD_HOUSE, TARGETS_CM, add_climate_left_out, calibrate_all, fit_region,
    };
    let mut rows: Vec<_> = calibrate_all(species, &TARGETS_CM, args.seed)
        .into_iter()
        .flatten()
        .collect();
    if args.fit {
        let Some(c) = fit_region(&args.region, &rows) else {
            bail!(
                "--fit: {} has no grown crown beside an i-Tree row, or no deciduous broadleaf, \
                 to fit its climate effect to",
                args.region
            );
        };
        println!(
            "{},{:.4},{:.4},{},{},{},{}",
            c.region,
            c.cooling_kwh_per_m2,
            c.heating_kbtu_per_m2,
            c.useful_winter_share
                .map_or(String::new(), |u| format!("{u:.4}")),
            c.points.0,
            c.points.1,
            c.points.2
        );
        return Ok(());
    }
    add_climate_left_out(&mut rows);
    if args.json {
        for r in &rows {
            println!(
                "{}",
                serde_json::json!({
                    "species": r.code, "dbh_target_cm": r.target_cm,
                    "age": r.reached.map(|x| x.0), "dbh_cm": r.reached.map(|x| x.1),
                    "projection_m2": r.reached.map(|_| r.projection_m2),
                    "shade_cooling_kwh": r.reached.map(|_| r.shade.0),
                    "shade_gas_kbtu": r.reached.map(|_| r.shade.1),
                    "climate_cooling_kwh": r.climate.map(|c| c.0),
                    "climate_gas_kbtu": r.climate.map(|c| c.1),
                    "useful_winter_share": r.useful_share,
                    "cooling_kwh": r.reached.map(|_| r.cooling_kwh),
                    "itree_electricity_kwh": r.reached.map(|_| r.itree.0),
                    "gas_kbtu": r.reached.map(|_| r.gas_kbtu),
                    "itree_natural_gas_kbtu": r.reached.map(|_| r.itree.1),
                    "cooling_in_bounds": r.reached.map(|_| r.cooling_in_bounds()),
                    "heating_in_bounds": r.reached.map(|_| r.heating_in_bounds()),
                })
            );
        }
        return Ok(());
    }
    let h = STANDARD_HOUSE;
    println!(
        "The site model at typical position: each tree around a {:.1} m square one-storey house \
         ({:.0}% of each wall glass), at 3, 9 and 15 m and eight directions, weighted evenly \
         (i-Tree's position frequencies were not reachable); its shade (the winter shade's \
         penalty, an evergreen's leaves or a deciduous tree's bare wood, at the region's useful \
         share of winter sun), plus the region's climate effect \
         per m² of crown projection (+clim), both fitted to the region's other species, beside \
         i-Tree Streets' figures at the same DBH. Bounds: cooling within 35% of \
         i-Tree's; gas within 50% or 30 kBtu, same sign.",
        h.side,
        h.glass * 100.0
    );
    if let Some((_, Some(why))) = sylva::street::accounts::itree::reference_region(&args.region) {
        println!("{why}.");
    }
    println!(
        "  {:<8} {:>4} {:>4} {:>6} {:>6}  {:>7} {:>7} {:>7} {:>7} {:>5}  {:>7} {:>7} {:>7} {:>7} {:>5}",
        "species",
        "DBH",
        "age",
        "grown",
        "m2",
        "shade",
        "+clim",
        "kWh",
        "i-Tree",
        "",
        "shade",
        "+clim",
        "kBtu",
        "i-Tree",
        ""
    );
    let (mut cool, mut heat, mut n) = (0, 0, 0);
    for r in &rows {
        let Some((age, dbh)) = r.reached else {
            println!(
                "  {:<8} {:>4.0} its data end before it reaches this DBH",
                r.code, r.target_cm
            );
            continue;
        };
        n += 1;
        cool += usize::from(r.cooling_in_bounds());
        heat += usize::from(r.heating_in_bounds());
        let mark = |ok: bool| if ok { "in" } else { "MISS" };
        let clim = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
        println!(
            "  {:<8} {:>4.0} {:>4.0} {:>6.1} {:>6.1}  {:>7.1} {:>7} {:>7.1} {:>7.1} {:>5}  {:>7.1} {:>7} {:>7.1} {:>7.1} {:>5}",
            r.code,
            r.target_cm,
            age,
            dbh,
            r.projection_m2,
            r.shade.0,
            clim(r.climate.map(|c| c.0)),
            r.cooling_kwh,
            r.itree.0,
            mark(r.cooling_in_bounds()),
            r.shade.1 * r.useful_share.unwrap_or(1.0),
            clim(r.climate.map(|c| c.1)),
            r.gas_kbtu,
            r.itree.1,
            mark(r.heating_in_bounds())
        );
    }
    println!("in bounds: cooling {cool} of {n}, heating {heat} of {n}");
    Ok(())
}

/// A run's pruning as JSON: its totals and each year a cycle fell due (`null` where the run
/// was not pruned: no site, `--no-pruning`, or a regime that cuts nothing).
fn pruning_json(r: &sylva::street::rank::Ranked) -> serde_json::Value {
    let Some(total) = r.pruning() else {
        return serde_json::Value::Null;
    };
    let kinds = |k: &[Kind]| k.iter().map(|k| k.name()).collect::<Vec<_>>();
    let round = |v: f64, places: i32| (v * 10f64.powi(places)).round() / 10f64.powi(places);
    let lost = |i: usize| r.benefits_lost.as_ref().map(|l| round(l[i], 2));
    let years: Vec<serde_json::Value> = r
        .accounts
        .iter()
        .enumerate()
        .filter_map(|(i, a)| {
            let mut year = sylva::street::accounts::table::pruning_json(a.pruning.as_ref()?);
            year["age"] = a.age.into();
            year["leaf_area_m2"] = round(a.surfaces.0, 1).into();
            year["benefits_lost_usd"] = lost(i).into();
            Some(year)
        })
        .collect();
    serde_json::json!({
        "cycles_with_cuts": total.cycles,
        "visits": total.visits,
        "wood_removed_m3": round(total.wood_m3, 4),
        "leaf_removed_m2": round(total.leaf_m2, 1),
        "cost_usd": round(total.cost, 2),
        "benefits_lost_usd": total.benefits_lost.map(|v| round(v, 2)),
        "resolved": kinds(&total.resolved),
        "unresolved": kinds(&total.unresolved),
        "years": years,
    })
}
