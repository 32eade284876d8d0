//! `sylva grow`: a street tree grown year by year from the Urban Tree Database, written as one
//! GLB and one picture per age (fixed camera, so ages compare), a CSV and charts of modelled
//! against measured dimensions, and species side by side; or watched growing in a window.

use crate::args::{GrowArgs, parse_size};
use crate::shared::{database, headless, save_picture};
use anyhow::{Context, Result, bail};
use sylva::export::{to_glb, write_atomically};
use sylva::growth::survey::report::{self, age_label, extent, run_ages};
use sylva::growth::{Measured, dressed_mesh};
use sylva::mesh::MeshOptions;
use sylva::street::accounts::table::{self, net_words};
use sylva::street::picture::cad::{SectionTree, street_section_dxf};
use sylva::street::rank::first_conflicts;
use sylva::street::records::{YearRecord, to_json};
use sylva::street::study::{Spread, StreetTree};
use sylva::street::{Basis, YearAccount};
use sylva_render::caption::with_caption;
use sylva_render::chart::{benefit_chart, growth_chart};
use sylva_render::site::{first_conflicts_picture, grown_tree_picture, pruning_cycle_picture};
use sylva_render::street::comparison_picture;

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
    let study = crate::shared::study(&args.street, ages[ages.len() - 1], args.seed)?;
    if args.street.prices.is_some() || args.street.costs.is_some() {
        // Money was asked for: every benefit model must be there.
        for m in &species {
            study.assessor(m).require_carbon()?;
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
    let site = study.site.as_ref();
    let mut trees: Vec<StreetTree> = species.iter().map(|m| StreetTree::new(m, &study)).collect();
    // A season names the files and captions: `PLAC-age-30-winter.glb`, "age 30 in winter".
    let season = args
        .season
        .map_or(String::new(), |m| format!("-{}", m.label()));
    let in_season = args
        .season
        .map_or(String::new(), |m| format!(" in {}", m.label()));
    // One frame for every age and species: the tallest and widest they reach.
    let extent = extent(&species, &ages);
    let mut accounts: Vec<Vec<YearAccount>> = species.iter().map(|_| Vec::new()).collect();
    // With a site, each age's tree for the street section in DXF.
    let mut sections: Vec<Vec<SectionTree>> = species.iter().map(|_| Vec::new()).collect();
    for &age in &ages {
        let (mut meshes, mut dresses) = (Vec::new(), Vec::new());
        for (i, tree) in trees.iter_mut().enumerate() {
            let m = &species[i];
            // Each record's cycles are those since the record before (since planting for the
            // first): with --step 10 ten years' visits, charged as a tenth a year beside one
            // year's benefits.
            let mut failed = None;
            let mut year = tree.grow_to(age, Spread::PerYear, |year, cycle, before, after| {
                if !args.no_pictures && failed.is_none() && !cycle.cuts.marks.is_empty() {
                    let (after, site) = (after.skeleton(), site.expect("a pruned tree has a site"));
                    let size = (width * 2, height);
                    let picture =
                        pruning_cycle_picture(m, year, cycle, &before, &after, site, size);
                    let name = format!("{}-pruned-age-{}.png", m.species.code, age_label(year));
                    failed = save_picture(&output.join(name), &picture).err();
                }
            });
            if let Some(e) = failed {
                return Err(e);
            }
            // A bare crown's short twigs go into the model as copies of one twig.
            let options = MeshOptions {
                twig_copies: !args.twigs_in_bark,
                ..report::MESH
            };
            let (mesh, dress) = dressed_mesh(&year.skeleton, m, args.season, &options);
            let stem = format!("{}-age-{}{season}", m.species.code, age_label(age));
            // The site at the year each kind of conflict first happens, marked.
            let new = &year.new_conflicts;
            if let (Some(site), false, false) = (site, new.is_empty(), args.no_pictures) {
                let size = (width * 2, height);
                let picture = first_conflicts_picture(m, age, &year.skeleton, site, new, size);
                let name = format!("{}-site-age-{}.png", m.species.code, age_label(age));
                save_picture(&output.join(name), &picture)?;
            }
            let glb = to_glb(&mesh, &m.label(), &dress.materials())?;
            write_atomically(&output.join(format!("{stem}.glb")), &glb)?;
            let model = &year.record.model;
            if let Some(r) = &renderer {
                let drawn = (&mesh, &dress);
                let size = (width, height);
                let picture =
                    grown_tree_picture(r, drawn, m, &year.record, &in_season, size, extent)?;
                save_picture(&output.join(format!("{stem}.png")), &picture)?;
            }
            if args.json {
                println!("{}", to_json(&YearRecord::of(m, &year)));
            } else {
                println!(
                    "  {:<28} age {:>5}  H {:5.1} m  CD {:5.1} m  DBH {:5.1} cm  LA {:6.0} m2  {} segments  {}{}{}",
                    m.label(),
                    age_label(age),
                    model.height,
                    model.crown_diameter,
                    model.dbh,
                    model.leaf_area,
                    tree.segment_count(),
                    net_words(&year.accounts[0], site.is_some()),
                    said_conflicts(new),
                    said_pruning(&year.accounts[0]),
                );
            }
            if site.is_some() {
                sections[i].push(SectionTree::of(&year.skeleton, age));
            }
            accounts[i].push(year.accounts.remove(0));
            meshes.push(mesh);
            dresses.push(dress);
        }
        if species.len() > 1
            && let Some(r) = &renderer
        {
            let picture =
                comparison_picture(r, &meshes, &dresses, &species, (width, height), extent)?;
            let heights: Vec<String> = (species.iter().zip(&trees).zip(&accounts))
                .map(|((m, t), a)| {
                    format!(
                        "{} {:.1} m, {}",
                        m.species.common,
                        t.history().last().map_or(0.0, |g| g.model.height),
                        a.last()
                            .map_or(String::new(), |a| net_words(a, site.is_some()))
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
    for (i, (m, tree)) in species.iter().zip(&trees).enumerate() {
        let (code, h) = (&m.species.code, tree.history());
        let csv = table::join_csv(&report::csv(h), &accounts[i]);
        write_atomically(&output.join(format!("{code}.csv")), csv.as_bytes())?;
        save_picture(
            &output.join(format!("{code}-chart.png")),
            &growth_chart(m, h)?,
        )?;
        let missing = tree.assessor(0).missing();
        let basis = Basis::default_for(site.is_some());
        let bars = benefit_chart(m, &accounts[i], missing, basis)?;
        save_picture(&output.join(format!("{code}-benefits.png")), &bars)?;
        if basis == Basis::Site {
            // The reference beside the site's own figures.
            let bars = benefit_chart(m, &accounts[i], missing, Basis::Typical)?;
            save_picture(&output.join(format!("{code}-benefits-typical.png")), &bars)?;
        }
        let section = output.join(format!("{code}-street-section.dxf"));
        if let Some(site) = site {
            let dxf = street_section_dxf(site, &sections[i], code, &m.label())?;
            write_atomically(&section, &dxf)?;
        }
        if args.json {
            continue;
        }
        if site.is_some() {
            println!(
                "{}: the street section and plan at each age for CAD: {}",
                m.label(),
                section.display()
            );
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
        if let Some(r) = tree.assessor(0).reference() {
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

/// The conflicts met for the first time this year, as the end of a line.
fn said_conflicts(new: &[sylva::street::Conflict]) -> String {
    if new.is_empty() {
        return String::new();
    }
    let said: Vec<String> = new.iter().map(|c| c.describe()).collect();
    format!("  new conflicts: {}", said.join(", "))
}

/// The year's pruning, as the end of a line.
fn said_pruning(a: &YearAccount) -> String {
    a.pruning.as_ref().map_or(String::new(), |p| {
        let reasons: Vec<&str> = p.reasons.iter().map(|r| r.name()).collect();
        format!(
            "  pruned ({}): {} cuts, {:.0} m2 of leaf, ${:.0}",
            reasons.join(", "),
            p.cuts.marks.len(),
            p.leaf_m2(),
            p.cost
        )
    })
}
