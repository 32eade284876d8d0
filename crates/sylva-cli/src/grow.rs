//! `sylva grow`: a street tree grown year by year from the Urban Tree Database, written as one
//! GLB and one picture per age (fixed camera, so ages compare), a CSV and charts of modelled
//! against measured dimensions, and species side by side; or watched growing in a window.

use crate::args::{GrowArgs, parse_size};
use crate::shared::{database, headless, load_street, save_picture};
use anyhow::{Context, Result, bail};
use sylva::export::{to_glb, write_atomically};
use sylva::growth::report::{self, Cohort, age_label, run_ages};
use sylva::growth::{CutKind, Grower};
use sylva::growth::{Measured, dressed_mesh};
use sylva::mesh::MeshOptions;
use sylva::street::accounts::pruner::{Pruner, PruningYear};
use sylva::street::picture::{pruning_picture, site_picture};
use sylva::street::rank::first_conflicts;
use sylva::street::work::conflicts::conflicts;
use sylva::street::{Assessor, Basis, Kind, Site, YearAccount, accounts::table};
use sylva_render::Picture;
use sylva_render::caption::with_caption;
use sylva_render::street::{comparison_picture, tree_picture};

pub fn run(args: &GrowArgs) -> Result<()> {
    let (width, height) = parse_size(&args.size, 8192).map_err(anyhow::Error::msg)?;
    let db = database(args.database.as_ref())?;
    let mut names = vec![args.species.clone()];
    names.extend(args.compare.iter().cloned());
    let species: Vec<Measured> = names
        .iter()
        .map(|n| db.find(&args.region, n))
        .collect::<Result<_, _>>()?;
    let first = &species[0];
    let ages = run_ages(first, args.from, args.to, args.step).map_err(anyhow::Error::msg)?;
    // Every input is read and checked before anything is written.
    let (site, prices, costs) = load_street(&args.street)?;
    let survival = crate::shared::survival(&args.street)?;
    let mut assessors: Vec<Assessor> = species
        .iter()
        .map(|m| {
            let a = Assessor::new(m, site.clone(), prices.clone(), costs.clone());
            match &survival {
                Some(s) => a.with_survival(s.clone()),
                None => a,
            }
        })
        .collect();
    if args.street.prices.is_some() || args.street.costs.is_some() {
        // Money was asked for: every benefit model must be there.
        for a in &assessors {
            a.require_carbon()?;
        }
    }
    if args.view {
        return sylva_viewer::watch_growth(
            species,
            ages,
            args.seed,
            args.season,
            args.self_test.clone(),
        );
    }
    let output = args
        .output
        .as_ref()
        .context("-o DIR: where to write the models, pictures and charts")?;
    if output.exists() && !output.is_dir() {
        bail!(
            "-o {}: that is a file; give a folder (it is created if missing)",
            output.display()
        );
    }
    std::fs::create_dir_all(output).with_context(|| format!("creating {}", output.display()))?;
    let renderer = if args.no_pictures {
        None
    } else {
        Some(headless()?)
    };
    if !args.json {
        println!(
            "{} in {} ({}), ages {} to {}",
            names.join(", "),
            first.region.name,
            first.region.city,
            ages[0],
            args.to.unwrap_or(first.ages.1.floor())
        );
    }
    let mut cohort = Cohort::new(species, args.seed);
    // A season names the files and captions: `PLAC-age-30-winter.glb`, "age 30 in winter".
    let season = args
        .season
        .map_or(String::new(), |m| format!("-{}", m.label()));
    let in_season = args
        .season
        .map_or(String::new(), |m| format!(" in {}", m.label()));
    // One frame for every age and species: the tallest and widest they reach.
    let extent = cohort.extent(&ages);
    let mut accounts: Vec<Vec<YearAccount>> = cohort.species.iter().map(|_| Vec::new()).collect();
    let mut seen: Vec<Vec<Kind>> = cohort.species.iter().map(|_| Vec::new()).collect();
    // The site's pruning regime cuts every tree as its cycles fall due, year by year.
    let pruner = (site.as_ref())
        .filter(|_| !args.street.no_pruning)
        .and_then(|s| Pruner::new(s, costs.as_ref()));
    if pruner.is_some() {
        assessors.iter_mut().for_each(Assessor::charge_cycles);
    }
    // Each record's cycles are those since the record before (since planting for the first):
    // with --step 10 ten years' visits, charged as a tenth a year beside one year's benefits.
    let mut last_age: Option<f64> = None;
    for &age in &ages {
        let span = last_age.map_or(age, |a| age - a);
        last_age = Some(age);
        let mut cycles: Vec<Option<PruningYear>> = cohort.species.iter().map(|_| None).collect();
        if let (Some(pruner), Some(site)) = (&pruner, &site) {
            for (i, grower) in cohort.growers.iter_mut().enumerate() {
                let m = &cohort.species[i];
                let mut failed = None;
                cycles[i] = pruner.advance(grower, age, |year, cycle, before, after| {
                    if !args.no_pictures && failed.is_none() && !cycle.cuts.marks.is_empty() {
                        let size = (width * 2, height);
                        let picture = cycle_picture(m, year, cycle, &before, after, site, size);
                        let name = format!("{}-pruned-age-{}.png", m.species.code, age_label(year));
                        failed = save_picture(&output.join(name), &picture).err();
                    }
                });
                if let Some(e) = failed {
                    return Err(e);
                }
            }
        }
        let skeletons = cohort.advance_to(age);
        let (mut meshes, mut dresses) = (Vec::new(), Vec::new());
        for (i, skeleton) in skeletons.iter().enumerate() {
            let m = &cohort.species[i];
            let grown = cohort.history[i].last().context("an age was recorded")?;
            let mut account = assessors[i].year(age, &grown.model, skeleton);
            if pruner.is_some() {
                account.record_pruning(cycles[i].take(), span);
            }
            // A bare crown's short twigs go into the model as copies of one twig.
            let options = MeshOptions {
                twig_copies: !args.twigs_in_bark,
                ..report::MESH
            };
            let (mesh, dress) = dressed_mesh(skeleton, m, args.season, &options);
            let stem = format!("{}-age-{}{season}", m.species.code, age_label(age));
            // The site at the year each kind of conflict first happens, marked.
            let new: Vec<_> = account
                .conflicts
                .iter()
                .filter(|c| !seen[i].contains(&c.kind))
                .copied()
                .collect();
            seen[i].extend(new.iter().map(|c| c.kind));
            if let (Some(site), false, false) = (&site, new.is_empty(), args.no_pictures) {
                let kinds: Vec<Kind> = new.iter().map(|c| c.kind).collect();
                let (w, h, rgba) = site_picture(skeleton, site, &kinds, (width * 2, height));
                let picture = Picture {
                    width: w,
                    height: h,
                    rgba,
                    stats: Default::default(),
                };
                let said: Vec<String> = new.iter().map(|c| c.describe()).collect();
                let lines = [
                    format!(
                        "{}, age {}: first {}",
                        m.label(),
                        age_label(age),
                        said.join(", ")
                    ),
                    "left: across the street; right: from above (bar: 5 m); a 1.8 m person"
                        .to_string(),
                    "red: in the way; red outline: the zone entered this year; shaded: clear \
                     heights; circles and bands: wire and lamp clearances"
                        .to_string(),
                ];
                let picture = with_caption(&picture, &lines, 18.0);
                let name = format!("{}-site-age-{}.png", m.species.code, age_label(age));
                save_picture(&output.join(name), &picture)?;
            }
            let glb = to_glb(&mesh, &m.label(), &dress.materials())?;
            write_atomically(&output.join(format!("{stem}.glb")), &glb)?;
            let model = &grown.model;
            if let Some(r) = &renderer {
                let picture = tree_picture(r, &mesh, &dress, (width, height), extent)?;
                let lines = [format!(
                    "{}, age {}{in_season}: height {:.1} m (measured {:.1}), crown {:.1} m",
                    m.label(),
                    age_label(age),
                    model.height,
                    grown.measured.height,
                    model.crown_diameter
                )];
                let picture = with_caption(&picture, &lines, 18.0);
                save_picture(&output.join(format!("{stem}.png")), &picture)?;
            }
            if args.json {
                let mut record = report::record_json(m, grown);
                record["street"] = table::json(&account);
                println!("{record}");
            } else {
                let conflicts = if new.is_empty() {
                    String::new()
                } else {
                    let said: Vec<String> = new.iter().map(|c| c.describe()).collect();
                    format!("  new conflicts: {}", said.join(", "))
                };
                let pruned = account.pruning.as_ref().map_or(String::new(), |p| {
                    format!(
                        "  pruned ({}): {} cuts, {:.0} m2 of leaf, ${:.0}",
                        p.reasons
                            .iter()
                            .map(|r| r.name())
                            .collect::<Vec<_>>()
                            .join(", "),
                        p.cuts.marks.len(),
                        p.leaf_m2(),
                        p.cost
                    )
                });
                println!(
                    "  {:<28} age {:>5}  H {:5.1} m  CD {:5.1} m  DBH {:5.1} cm  LA {:6.0} m2  {} segments  {}{conflicts}{pruned}",
                    m.label(),
                    age_label(age),
                    model.height,
                    model.crown_diameter,
                    model.dbh,
                    model.leaf_area,
                    cohort.growers[i].segment_count(),
                    nets(&account, site.is_some())
                );
            }
            accounts[i].push(account);
            meshes.push(mesh);
            dresses.push(dress);
        }
        if cohort.species.len() > 1
            && let Some(r) = &renderer
        {
            let picture = comparison_picture(
                r,
                &meshes,
                &dresses,
                &cohort.species,
                (width, height),
                extent,
            )?;
            let heights: Vec<String> = cohort
                .species
                .iter()
                .zip(&cohort.history)
                .zip(&accounts)
                .map(|((m, h), a)| {
                    format!(
                        "{} {:.1} m, {}",
                        m.species.common,
                        h.last().map_or(0.0, |g| g.model.height),
                        a.last().map_or(String::new(), |a| nets(a, site.is_some()))
                    )
                })
                .collect();
            let lines = [format!(
                "age {}{in_season}: {}",
                age_label(age),
                heights.join(", ")
            )];
            let picture = with_caption(&picture, &lines, 18.0);
            let name = format!("compare-age-{}{season}.png", age_label(age));
            save_picture(&output.join(name), &picture)?;
        }
    }
    for (i, (m, h)) in cohort.species.iter().zip(&cohort.history).enumerate() {
        let code = &m.species.code;
        let csv = table::join_csv(&report::csv(h), &accounts[i]);
        write_atomically(&output.join(format!("{code}.csv")), csv.as_bytes())?;
        let chart = crate::chart::growth_chart(m, h)?;
        save_picture(&output.join(format!("{code}-chart.png")), &chart)?;
        let missing = assessors[i].missing();
        let basis = Basis::default_for(site.is_some());
        let bars = crate::chart::benefit_chart(m, &accounts[i], missing, basis)?;
        save_picture(&output.join(format!("{code}-benefits.png")), &bars)?;
        if basis == Basis::Site {
            // The reference beside the site's own figures.
            let bars = crate::chart::benefit_chart(m, &accounts[i], missing, Basis::Typical)?;
            save_picture(&output.join(format!("{code}-benefits-typical.png")), &bars)?;
        }
        if args.json {
            continue;
        }
        if site.is_some() {
            let mut first = first_conflicts(&accounts[i]);
            first.sort_by(|a, b| a.0.total_cmp(&b.0));
            let first: Vec<String> = first
                .iter()
                .map(|(age, c)| format!("at {}: {}", age_label(*age), c.describe()))
                .collect();
            println!(
                "{}: first conflicts: {}",
                m.label(),
                if first.is_empty() {
                    "none".to_string()
                } else {
                    first.join(", ")
                }
            );
        }
        if let Some(r) = assessors[i].reference() {
            println!("{}: typical position from {}", m.species.code, r.describe());
        }
        for note in missing {
            println!("{}: not counted: {note}", m.species.code);
        }
        let worst = report::worst_errors(h);
        println!(
            "{}: worst error against the equations: height {:+.1}%, DBH {:+.1}%, crown diameter \
             {:+.1}%, crown height {:+.1}%, leaf area {:+.1}%",
            m.label(),
            worst[0] * 100.0,
            worst[1] * 100.0,
            worst[2] * 100.0,
            worst[3] * 100.0,
            worst[4] * 100.0
        );
    }
    if !args.json {
        println!("wrote {}", output.display());
    }
    Ok(())
}

/// A year's net as a line of text: at typical position, and on the site where there is one.
fn nets(a: &YearAccount, has_site: bool) -> String {
    let typical = a
        .typical
        .as_ref()
        .map(|_| format!("net ${:.0}/yr at typical position", a.net(Basis::Typical)));
    let site = has_site.then(|| format!("${:.0}/yr on this site", a.net(Basis::Site)));
    match (typical, site) {
        (Some(t), Some(s)) => format!("{t}, {s}"),
        (Some(t), None) => t,
        (None, Some(s)) => format!("net {s}"),
        (None, None) => format!("net ${:.0}/yr (own crown, no site)", a.net(Basis::Site)),
    }
}

/// A pruning cycle's picture, captioned: the tree across the street before and after the
/// year's cuts.
fn cycle_picture(
    m: &Measured,
    year: f64,
    cycle: &PruningYear,
    before: &sylva::Skeleton,
    after: &Grower,
    site: &Site,
    size: (u32, u32),
) -> Picture {
    let after = after.skeleton();
    let (w, h, rgba) = pruning_picture(before, &after, site, cycle.marks(), size);
    let left: Vec<Kind> = conflicts(&after, site).iter().map(|c| c.kind).collect();
    let picture = Picture {
        width: w,
        height: h,
        rgba,
        stats: Default::default(),
    };
    let kinds = |k: &[Kind]| {
        let names: Vec<&str> = k.iter().map(|k| k.name()).collect();
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    };
    let reasons: Vec<&str> = cycle.reasons.iter().map(|r| r.name()).collect();
    let lines = [
        format!(
            "{}, age {}: {}: {} removal and {} reduction cuts (largest {:.0} cm across), \
             {:.1} m2 of leaf and {:.3} m3 of wood taken, {} visit(s), ${:.2}",
            m.label(),
            age_label(year),
            reasons.join(", "),
            cycle.count(CutKind::Removal),
            cycle.count(CutKind::Reduction),
            100.0 * cycle.cuts.largest_diameter(),
            cycle.leaf_m2(),
            cycle.wood_m3(),
            cycle.visits,
            cycle.cost
        ),
        format!(
            "in the way before the cuts: {}; after: {}{}",
            kinds(&cycle.before),
            kinds(&left),
            if cycle.cuts.left_in_zone {
                " (a trunk with no lateral to cut back to is left)"
            } else {
                ""
            }
        ),
        "left: before the cuts; right: after, at one scale; blue rings: the cuts; red: in the \
         way; circles: wire and lamp clearances; a 1.8 m person"
            .to_string(),
    ];
    with_caption(&picture, &lines, 18.0)
}
