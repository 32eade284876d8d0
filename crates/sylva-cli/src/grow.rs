//! `sylva grow`: a street tree grown year by year from the Urban Tree Database, written as one
//! GLB and one picture per age (fixed camera, so ages compare), a CSV and charts of modelled
//! against measured dimensions, and species side by side.

use crate::args::GrowArgs;
use crate::caption::{draw_text, text_width, with_caption};
use crate::shared::{encode_png, parse_size, street_tree_colours};
use anyhow::{Context, Result, bail};
use glam::Vec3;
use std::borrow::Cow;
use std::fmt::Write as _;
use std::path::Path;
use sylva::export::{Materials, to_glb, write_atomically};
use sylva::growth::{Database, Dimensions, Grower, GrowthOptions, Measured, Targets, measure};
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree};
use sylva_render::{Picture, Placement, Renderer, Scene, Stand, View};

/// Most ages one run writes.
const MAX_AGES: usize = 400;
/// Oldest age asked for, years.
pub const MAX_AGE: f64 = 300.0;

/// One age of one species.
struct Grown {
    age: f64,
    model: Dimensions,
    measured: Targets,
}

pub fn grow(args: &GrowArgs) -> Result<()> {
    if !(args.step > 0.0 && args.step.is_finite()) {
        bail!("--step {}: expected a positive number of years", args.step);
    }
    let (width, height) = parse_size(&args.size)?;
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
    let from = args.from.unwrap_or(first.ages.0.ceil());
    let to = args.to.unwrap_or(first.ages.1.floor());
    if !(0.0..=MAX_AGE).contains(&from) || !(0.0..=MAX_AGE).contains(&to) || from > to {
        bail!(
            "--from {from} --to {to}: expected 0 <= from <= to <= {MAX_AGE} years (the data for \
             {} cover ages {:.0} to {:.0})",
            first.label(),
            first.ages.0,
            first.ages.1
        );
    }
    let count = ((to - from) / args.step + 1e-9).floor() as usize + 1;
    if count > MAX_AGES {
        bail!(
            "--from {from} --to {to} --step {}: {count} ages, at most {MAX_AGES}",
            args.step
        );
    }
    let ages: Vec<f64> = (0..count).map(|i| from + i as f64 * args.step).collect();
    if args.view {
        return crate::viewer::growth::run(species, ages, args.seed, args.self_test.clone());
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
        Some(crate::render::headless()?)
    };
    // One frame for every age and species: the tallest and widest they reach.
    let mut tallest = 2.0f64;
    let mut widest = 1.0f64;
    for m in &species {
        for &a in &ages {
            tallest = tallest.max(m.height(a));
            widest = widest.max(m.crown_diameter(a));
        }
    }
    let mut growers: Vec<Grower> = species
        .iter()
        .map(|m| {
            Grower::new(
                m.clone(),
                GrowthOptions {
                    seed: args.seed,
                    ..Default::default()
                },
            )
        })
        .collect();
    let mut history: Vec<Vec<Grown>> = species.iter().map(|_| Vec::new()).collect();
    println!(
        "{} in {} ({}), ages {from} to {to}",
        names.join(", "),
        first.region.name,
        first.region.city
    );
    for &age in &ages {
        let mut meshes = Vec::new();
        for (i, g) in growers.iter_mut().enumerate() {
            let m = &species[i];
            g.advance_to(age);
            let skeleton = g.skeleton();
            let model = measure(&skeleton);
            let measured = g.targets(age);
            let mesh = mesh_tree(
                &skeleton,
                &MeshOptions {
                    quality: 0.6,
                    ..Default::default()
                },
            );
            let stem = format!("{}-age-{}", m.species.code, age_label(age));
            let (bark, leaves) = street_tree_colours(m);
            let glb = to_glb(&mesh, &m.label(), &Materials::from_srgb(bark, leaves))?;
            write_atomically(&output.join(format!("{stem}.glb")), &glb)?;
            if let Some(r) = &renderer {
                let picture = single_picture(r, &mesh, m, (width, height), tallest, widest)?;
                let lines = [format!(
                    "{}, age {}: height {:.1} m (measured {:.1}), crown {:.1} m",
                    m.label(),
                    age_label(age),
                    model.height,
                    measured.height,
                    model.crown_diameter
                )];
                let picture = with_caption(&picture, &lines, 18.0);
                save(&output.join(format!("{stem}.png")), &picture)?;
            }
            println!(
                "  {:<28} age {:>5}  H {:5.1} m  CD {:5.1} m  DBH {:5.1} cm  LA {:6.0} m2  {} segments",
                m.label(),
                age_label(age),
                model.height,
                model.crown_diameter,
                model.dbh,
                model.leaf_area,
                g.segment_count()
            );
            history[i].push(Grown {
                age,
                model,
                measured,
            });
            meshes.push(mesh);
        }
        if species.len() > 1
            && let Some(r) = &renderer
        {
            let picture = compare_picture(r, &meshes, &species, (width, height), tallest, widest)?;
            let heights: Vec<String> = species
                .iter()
                .zip(&history)
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
            save(
                &output.join(format!("compare-age-{}.png", age_label(age))),
                &picture,
            )?;
        }
    }
    for (m, h) in species.iter().zip(&history) {
        write_csv(&output.join(format!("{}.csv", m.species.code)), h)?;
        write_chart(&output.join(format!("{}-chart.png", m.species.code)), m, h)?;
        let worst = worst_errors(h);
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
    println!("wrote {}", output.display());
    Ok(())
}

/// `5` for whole ages, `5.5` otherwise, padded so files sort by age.
fn age_label(age: f64) -> String {
    if age.fract().abs() < 1e-9 {
        format!("{:02}", age as u32)
    } else {
        format!("{age:04.1}")
    }
}

fn save(path: &Path, p: &Picture) -> Result<()> {
    encode_png(path, p.width, p.height, &p.rgba)
}

/// The camera every age of a run shares: looking from the south at a frame that holds the
/// tallest and widest tree of the run, and the person.
fn fixed_view(tallest: f64, across: f64, aspect: f32) -> View {
    let fov = 30.0f32;
    let half = (fov / 2.0).to_radians().tan();
    let h = tallest as f32 * 1.1 + 0.5;
    let w = across as f32 + 2.0;
    let distance = (h / 2.0 / half).max(w / 2.0 / (half * aspect)) * 1.05;
    let target = Vec3::new(0.0, 0.0, h / 2.0);
    View::look_at(target + Vec3::new(0.0, -distance, h * 0.08), target, fov)
}

fn single_picture(
    r: &Renderer,
    mesh: &TreeMesh,
    m: &Measured,
    (width, height): (u32, u32),
    tallest: f64,
    widest: f64,
) -> Result<Picture> {
    let tree = r.upload(mesh);
    let (bark, leaves) = street_tree_colours(m);
    let scene = Scene::new(&tree, bark, leaves);
    let view = fixed_view(tallest, widest + 2.0, width as f32 / height as f32);
    Ok(r.render(&scene, &view, width, height)?)
}

fn compare_picture(
    r: &Renderer,
    meshes: &[TreeMesh],
    species: &[Measured],
    (width, height): (u32, u32),
    tallest: f64,
    widest: f64,
) -> Result<Picture> {
    let spacing = widest as f32 * 1.1 + 1.0;
    let n = meshes.len() as f32;
    let trees: Vec<_> = meshes.iter().map(|m| r.upload(m)).collect();
    let placements: Vec<Placement> = (0..meshes.len())
        .map(|i| Placement {
            position: Vec3::new((i as f32 - (n - 1.0) / 2.0) * spacing, 0.0, 0.0),
            ..Placement::ORIGIN
        })
        .collect();
    let stands = trees
        .iter()
        .zip(species)
        .zip(&placements)
        .map(|((t, m), p)| {
            let (bark, leaves) = street_tree_colours(m);
            Stand {
                tree: t,
                bark,
                leaves,
                placements: Cow::Owned(vec![*p]),
            }
        })
        .collect();
    let mut scene = Scene::forest(stands);
    scene.show_person = true;
    let across = spacing * n + 2.0;
    let w = width.max(height * meshes.len() as u32 * 2 / 3);
    let view = fixed_view(tallest, across as f64, w as f32 / height as f32);
    let mut picture = r.render(&scene, &view, w, height)?;
    // Each tree's name under its trunk.
    let camera = scene.camera(&view, w as f32 / height as f32);
    for (m, p) in species.iter().zip(&placements) {
        let x = camera
            .project(p.position, w, height)
            .map_or(w as f32 / 2.0, |(x, _)| x);
        let name = &m.species.common;
        let size = 20.0;
        draw_text(
            &mut picture,
            x - text_width(name, size) / 2.0,
            height as f32 - 30.0,
            size,
            name,
            [20, 20, 20],
        );
    }
    Ok(picture)
}

/// Worst signed relative error per quantity: height, DBH, crown diameter, crown height, leaf
/// area.
fn worst_errors(history: &[Grown]) -> [f64; 5] {
    let mut worst = [0.0f64; 5];
    for g in history {
        let e = g.model.relative_errors(&g.measured);
        for k in 0..5 {
            if e[k].abs() > worst[k].abs() {
                worst[k] = e[k];
            }
        }
    }
    worst
}

fn write_csv(path: &Path, history: &[Grown]) -> Result<()> {
    let mut s = String::from(
        "age,height_model_m,height_measured_m,crown_height_model_m,crown_height_measured_m,\
         crown_diameter_model_m,crown_diameter_measured_m,dbh_model_cm,dbh_measured_cm,\
         leaf_area_model_m2,leaf_area_measured_m2\n",
    );
    for g in history {
        let (m, t) = (&g.model, &g.measured);
        writeln!(
            s,
            "{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.2},{:.2},{:.1},{:.1}",
            g.age,
            m.height,
            t.height,
            m.crown_height,
            t.crown_height,
            m.crown_diameter,
            t.crown_diameter,
            m.dbh,
            t.dbh,
            m.leaf_area,
            t.leaf_area
        )?;
    }
    write_atomically(path, s.as_bytes())?;
    Ok(())
}

/// Five panels (height, crown height, crown diameter, DBH, leaf area against age): the
/// equations as a curve, the grown tree as points.
fn write_chart(path: &Path, m: &Measured, history: &[Grown]) -> Result<()> {
    use plotters::prelude::*;
    crate::caption::register_chart_font();
    let (w, h) = (1500u32, 900u32);
    let mut buffer = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(
            &format!(
                "{} in {}: grown (points) against the equations (line)",
                m.label(),
                m.region.code
            ),
            ("sans-serif", 26),
        )?;
        let panels = root.split_evenly((2, 3));
        let a0 = history.first().map_or(0.0, |g| g.age);
        let a1 = history.last().map_or(1.0, |g| g.age).max(a0 + 1.0);
        type Get = fn(&Dimensions) -> f64;
        type Want = fn(&Targets) -> f64;
        let quantities: [(&str, Get, Want); 5] = [
            ("height (m)", |d| d.height, |t| t.height),
            ("crown height (m)", |d| d.crown_height, |t| t.crown_height),
            (
                "crown diameter (m)",
                |d| d.crown_diameter,
                |t| t.crown_diameter,
            ),
            ("DBH (cm)", |d| d.dbh, |t| t.dbh),
            ("leaf area (m²)", |d| d.leaf_area, |t| t.leaf_area),
        ];
        for (panel, (name, get, want)) in panels.iter().zip(quantities) {
            let top = history
                .iter()
                .map(|g| get(&g.model).max(want(&g.measured)))
                .fold(0.0f64, f64::max)
                * 1.1
                + 1e-6;
            let mut chart = ChartBuilder::on(panel)
                .caption(name, ("sans-serif", 22))
                .margin(12)
                .x_label_area_size(36)
                .y_label_area_size(56)
                .build_cartesian_2d(a0..a1, 0.0..top)?;
            chart
                .configure_mesh()
                .x_desc("age (years)")
                .label_style(("sans-serif", 15))
                .draw()?;
            let steps = 200;
            let curve = (0..=steps).map(|i| {
                let a = a0 + (a1 - a0) * i as f64 / steps as f64;
                (a, want(&Targets::of(m, a)))
            });
            chart.draw_series(LineSeries::new(curve, BLUE.stroke_width(2)))?;
            chart.draw_series(
                history
                    .iter()
                    .map(|g| Circle::new((g.age, get(&g.model)), 4, RED.filled())),
            )?;
        }
        root.present()?;
    }
    let rgba: Vec<u8> = buffer
        .chunks(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    encode_png(path, w, h, &rgba)
}
