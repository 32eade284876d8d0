//! `sylva rank`: a region's species grown side by side on one site and listed by net benefit
//! over the years, with the year each first runs into the street.

use crate::args::{RankArgs, RankBy};
use crate::shared::{database, with_progress};
use anyhow::{Result, bail};
use sylva::growth::Measured;
use sylva::street::Basis;
use sylva::street::accounts::items::Payer;
use sylva::street::rank::{Pruning, RankRequest, rank};
use sylva::street::records::{CalibrationRecord, RankRow, to_json};

pub fn run(args: &RankArgs) -> Result<()> {
    if !(1.0..=sylva::growth::survey::report::MAX_AGE).contains(&args.years) {
        bail!(
            "--years {}: expected 1 to {} years",
            args.years,
            sylva::growth::survey::report::MAX_AGE
        );
    }
    let mut study = crate::shared::study(&args.street, args.years, args.seed)?;
    if study.pruning == Pruning::Regime && args.pruning_losses {
        study.pruning = Pruning::Compare;
    }
    let site = study.site.clone();
    let request = RankRequest {
        region: args.region.clone(),
        species: args.species.clone(),
        study,
        basis: args.by.map(|b| match b {
            RankBy::Typical => Basis::Typical,
            RankBy::Site => Basis::Site,
        }),
    };
    let basis = request.basis();
    let db = database(args.database.as_ref())?;
    let species = request.species(&db)?;
    if args.calibrate {
        return calibration(&species, args);
    }
    let ranked = with_progress(species.len(), |tick| rank(&request, &db, &|_| tick()))?;
    if args.json {
        for r in &ranked {
            println!("{}", to_json(&RankRow::of(r, basis)));
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
        "  {:<4} {:<34} {:>5} {:>10} {:>10} {:>8} {:>8} {:>8} {:>10} {:>10} {:<5}  {:<22} first conflict with a fixture",
        "rank",
        "species",
        "years",
        "benefits",
        "(typical)",
        "city",
        "utility",
        "owners",
        "net",
        "(typical)",
        "suits",
        "clearance pruning from"
    );
    println!(
        "  {:<4} {:<34} {:>5} {:>10} {:>10} {:>8} {:>8} {:>8} {:>10} {:>10}",
        "", "", "", "this site", "position", "costs", "costs", "costs", "this site", "position"
    );
    for (i, r) in ranked.iter().enumerate() {
        let earliest = |clearance: bool| match r.earliest(clearance) {
            Some((age, kind)) => format!("{} at {age:.0}", kind.name()),
            None if site.is_some() => "none".into(),
            None => "(no --site)".into(),
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
        let has_costs = r.accounts.iter().any(|a| a.costs.is_some());
        let paid = |p: Payer| {
            if has_costs {
                let v = (r.costs_by_payer().iter())
                    .find(|(q, _)| *q == p)
                    .map_or(0.0, |x| x.1);
                format!("{v:.0}")
            } else {
                "-".into()
            }
        };
        let suits = match (site.is_some(), r.unsuited().is_empty()) {
            (false, _) => "-",
            (true, true) => "yes",
            (true, false) => "no",
        };
        println!(
            "  {:<4} {:<34} {:>5.0} {:>10} {:>10.0} {:>8} {:>8} {:>8} {:>10} {:>10.0} {suits:<5}  {pruning:<22} {conflict}{carbon_missing}",
            i + 1,
            r.species.label(),
            r.last_age(),
            own(r.benefits(Basis::Site)),
            r.benefits(Basis::Typical),
            paid(Payer::City),
            paid(Payer::Utility),
            paid(Payer::Owners),
            own(r.net(Basis::Site)),
            r.net(Basis::Typical)
        );
    }
    // Where a species does not suit the site, and why; and what its conflicts cost, by who
    // paid.
    if site.is_some() {
        let unsuited: Vec<&sylva::street::rank::Ranked> =
            ranked.iter().filter(|r| !r.unsuited().is_empty()).collect();
        if !unsuited.is_empty() {
            println!("does not suit the site:");
        }
        for r in unsuited {
            println!("  {}: {}", r.species.label(), r.unsuited().join("; "));
        }
        println!("the street's conflicts, over the years per tree planted, by who paid:");
        for r in &ranked {
            let costs: Vec<String> = (r.conflict_costs().iter())
                .map(|(what, payer, usd)| format!("{what} ${usd:.0} ({})", payer.name()))
                .collect();
            if !costs.is_empty() {
                println!("  {}: {}", r.species.label(), costs.join(", "));
            }
        }
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
            println!("{}", to_json(&CalibrationRecord::of(r)));
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
