//! `sylva grow`: a street tree grown year by year from the Urban Tree Database, written as one
//! GLB and one picture per age (fixed camera, so ages compare), a CSV and charts of modelled
//! against measured dimensions, and species side by side; or watched growing in a window.

use crate::args::{GrowArgs, parse_size};
use crate::shared::{headless, save_picture};
use anyhow::{Context, Result, bail};
use sylva::export::{Materials, to_glb, write_atomically};
use sylva::growth::report::{self, AgeRecord, Cohort, age_label, run_ages};
use sylva::growth::{Database, Measured};
use sylva::mesh::mesh_tree;
use sylva_render::caption::with_caption;
use sylva_render::street::{comparison_picture, tree_picture};

pub fn run(args: &GrowArgs) -> Result<()> {
    let (width, height) = parse_size(&args.size, 8192).map_err(anyhow::Error::msg)?;
    let owned;
    let db = match &args.database {
        Some(dir) => {
            owned = Database::from_dir(dir)?;
            &owned
        }
        None => Database::builtin(),
    };
    let mut names = vec![args.species.clone()];
    names.extend(args.compare.iter().cloned());
    let species: Vec<Measured> = names
        .iter()
        .map(|n| db.find(&args.region, n))
        .collect::<Result<_, _>>()?;
    let first = &species[0];
    let ages = run_ages(first, args.from, args.to, args.step).map_err(anyhow::Error::msg)?;
    if args.view {
        return sylva_viewer::watch_growth(species, ages, args.seed, args.self_test.clone());
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
    // One frame for every age and species: the tallest and widest they reach.
    let extent = cohort.extent(&ages);
    for &age in &ages {
        let skeletons = cohort.advance_to(age);
        let mut meshes = Vec::new();
        for (i, skeleton) in skeletons.iter().enumerate() {
            let m = &cohort.species[i];
            let grown = cohort.history[i].last().context("an age was recorded")?;
            let mesh = mesh_tree(skeleton, &report::MESH);
            let stem = format!("{}-age-{}", m.species.code, age_label(age));
            let (bark, leaves) = m.colours();
            let glb = to_glb(&mesh, &m.label(), &Materials::from_srgb(bark, leaves))?;
            write_atomically(&output.join(format!("{stem}.glb")), &glb)?;
            let model = &grown.model;
            if let Some(r) = &renderer {
                let picture = tree_picture(r, &mesh, m, (width, height), extent)?;
                let lines = [format!(
                    "{}, age {}: height {:.1} m (measured {:.1}), crown {:.1} m",
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
                println!("{}", record_json(m, grown));
            } else {
                println!(
                    "  {:<28} age {:>5}  H {:5.1} m  CD {:5.1} m  DBH {:5.1} cm  LA {:6.0} m2  {} segments",
                    m.label(),
                    age_label(age),
                    model.height,
                    model.crown_diameter,
                    model.dbh,
                    model.leaf_area,
                    cohort.growers[i].segment_count()
                );
            }
            meshes.push(mesh);
        }
        if cohort.species.len() > 1
            && let Some(r) = &renderer
        {
            let picture = comparison_picture(r, &meshes, &cohort.species, (width, height), extent)?;
            let heights: Vec<String> = cohort
                .species
                .iter()
                .zip(&cohort.history)
                .map(|(m, h)| {
                    format!(
                        "{} {:.1} m",
                        m.species.common,
                        h.last().map_or(0.0, |g| g.model.height)
                    )
                })
                .collect();
            let lines = [format!("age {}: {}", age_label(age), heights.join(", "))];
            let picture = with_caption(&picture, &lines, 18.0);
            let name = format!("compare-age-{}.png", age_label(age));
            save_picture(&output.join(name), &picture)?;
        }
    }
    for (m, h) in cohort.species.iter().zip(&cohort.history) {
        let code = &m.species.code;
        write_atomically(
            &output.join(format!("{code}.csv")),
            report::csv(h).as_bytes(),
        )?;
        let chart = crate::chart::growth_chart(m, h)?;
        save_picture(&output.join(format!("{code}-chart.png")), &chart)?;
        if args.json {
            continue;
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

/// One age of one species as a JSON line.
fn record_json(m: &Measured, r: &AgeRecord) -> serde_json::Value {
    let (d, t, f) = (&r.model, &r.measured, &r.form);
    let round = |v: f64, k: f64| (v * k).round() / k;
    serde_json::json!({
        "species": m.species.code,
        "age": r.age,
        "height_m": round(d.height, 1e3),
        "height_measured_m": round(t.height, 1e3),
        "crown_height_m": round(d.crown_height, 1e3),
        "crown_height_measured_m": round(t.crown_height, 1e3),
        "crown_diameter_m": round(d.crown_diameter, 1e3),
        "crown_diameter_measured_m": round(t.crown_diameter, 1e3),
        "dbh_cm": round(d.dbh, 1e2),
        "dbh_measured_cm": round(t.dbh, 1e2),
        "leaf_area_m2": round(d.leaf_area, 10.0),
        "leaf_area_measured_m2": round(t.leaf_area, 10.0),
        "inner_leaf_share": round(f.inner_leaf_share, 1e3),
        "leaders": f.leaders,
        "scaffold_angle_deg": f.scaffold_angle.map(|a| round(a, 10.0)),
        "pipe_exponent": f.pipe_exponent.map(|n| round(n, 1e2)),
        "live_branches": r.branches.0,
        "shed_branches": r.branches.1,
    })
}
