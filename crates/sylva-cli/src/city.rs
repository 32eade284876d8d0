//! `sylva city` and `sylva city-demo`: flags to a layout and options, the library's run, a
//! progress bar and the summary.

use crate::args::{CityArgs, CityDemoArgs, DemoLayoutArg};
use crate::shared::StageBar;
use anyhow::{Result, bail};
use sylva_city::cache::GrowthCache;
use sylva_city::demo::{DemoLayout, demo_city};
use sylva_city::{CityOptions, Layout, LengthUnit, tile_city};

pub fn run(args: &CityArgs) -> Result<()> {
    let unit = |flag: &str, v: &Option<String>| -> Result<Option<LengthUnit>> {
        Ok(v.as_deref()
            .map(|s| LengthUnit::parse(flag, s))
            .transpose()?)
    };
    let crs = args
        .crs
        .as_deref()
        .map(sylva_city::geo::Projection::parse_epsg)
        .transpose()?;
    let layout = Layout {
        id: args.id_col.clone(),
        species: args.species_col.clone(),
        dbh: args.dbh_col.clone(),
        dbh_unit: unit("--dbh-unit", &args.dbh_unit)?,
        circumference: args.circumference_col.clone(),
        circumference_unit: unit("--circumference-unit", &args.circumference_unit)?,
        lon_lat: args.lon_col.clone().zip(args.lat_col.clone()),
        xy: args.x_col.clone().zip(args.y_col.clone()),
        crs,
        height: args.height_col.clone(),
        height_unit: unit("--height-unit", &args.height_unit)?,
        planted: args.planted_col.clone(),
        status: args.status_col.clone(),
        ground: args.ground_col.clone(),
        observed: sylva_city::inventory::ObservedColumns {
            condition: args.condition_col.clone(),
            ..Default::default()
        },
        name: String::new(),
    };
    if let Some(dir) = args.cache.as_ref().filter(|d| d.exists() && !d.is_dir()) {
        bail!(
            "--cache {}: that is a file; give a folder for the grown trees (it is made if missing)",
            dir.display()
        );
    }
    let options = CityOptions {
        region: args.region.clone(),
        variants: args.variants,
        stumps: args.stumps,
        years: args.years.clone(),
        base_year: args.year,
        ground: args.ground,
        seed: args.seed,
        cache: if args.no_cache {
            None
        } else {
            (args.cache.clone())
                .or_else(GrowthCache::default_dir)
                .map(|dir| (dir, args.cache_mib))
        },
        report: args.report,
        dxf: args.dxf,
    };
    let bar = StageBar::new();
    let started = std::time::Instant::now();
    let run = tile_city(
        &args.inventory,
        args.layer.as_deref(),
        &layout,
        &options,
        &args.output,
        &bar,
    )?;
    bar.finish();
    let seconds = started.elapsed().as_secs_f64();
    let s = &run.summary;
    println!(
        "{}: {} rows read as {}",
        args.inventory.display(),
        s.rows,
        s.layout
    );
    println!("  {} trees drawn, {} stumps drawn", s.trees, s.stumps);
    for (why, n) in &s.skipped {
        println!("  {n} {why}");
    }
    println!("  {} rows unreadable:", s.rejected.len());
    for r in s.rejected.iter().take(10) {
        println!("    line {}: {}", r.line, r.reason);
    }
    if s.rejected.len() > 10 {
        println!("    ... (all of them in summary.json)");
    }
    let mut by_fallback = std::collections::BTreeMap::new();
    for line in s.species.values() {
        for ((_, how), n) in &line.grown_as {
            *by_fallback.entry(how.words()).or_insert(0usize) += n;
        }
    }
    println!("  {} species names; trees grown as:", s.species.len());
    for (how, n) in by_fallback {
        println!("    {n} {how}");
    }
    if let Some((dir, _)) = &options.cache {
        println!(
            "  {} of {} growths from the cache of grown trees ({})",
            run.from_cache,
            run.growths,
            dir.display()
        );
    }
    let trees: usize = run.epochs.first().map_or(0, |e| e.2.trees);
    let bytes: u64 =
        run.prototype_bytes + run.epochs.iter().map(|e| e.2.content_bytes).sum::<u64>();
    for (years, dir, r, later) in &run.epochs {
        println!(
            "  year +{years}: {} ({} tiles, depth {}, {} trees, {:.1} MB of tiles{})",
            dir.join("tileset.json").display(),
            r.tiles,
            r.depth,
            r.trees,
            r.content_bytes as f64 / 1e6,
            if *later > 0 {
                format!(", {later} not yet planted")
            } else {
                String::new()
            }
        );
        if args.dxf {
            let path = dir.join(sylva_city::trees::cad::PLAN_FILE);
            println!("    planting plan for CAD: {}", path.display());
        }
    }
    println!(
        "  {} grown trees shared ({:.1} MB); {:.0} trees/s; {:.0} bytes per tree; {:.1} s \
         (plan {:.1}, grow {:.1}, tiles {:.1})",
        run.prototypes,
        run.prototype_bytes as f64 / 1e6,
        trees as f64 / seconds,
        bytes as f64 / trees.max(1) as f64 / run.epochs.len().max(1) as f64,
        seconds,
        run.seconds[0],
        run.seconds[1],
        run.seconds[2]
    );
    Ok(())
}

pub fn demo(args: &CityDemoArgs) -> Result<()> {
    if args.trees == 0 || args.trees > 2_000_000 {
        bail!("--trees {}: expected 1 to 2,000,000", args.trees);
    }
    let city = demo_city(&args.region, args.trees, args.seed, args.year)?;
    let layout = match args.layout {
        DemoLayoutArg::Census => DemoLayout::Census,
        DemoLayoutArg::Gis => DemoLayout::Gis,
    };
    city.write(&args.output, layout)?;
    println!(
        "wrote {}: {} rows around {} ({}), positions also in EPSG:{}",
        args.output.display(),
        city.trees.len(),
        sylva_city::inventory::regions::REFERENCE_CITIES
            .iter()
            .find(|r| r.0 == city.region)
            .map_or("", |r| r.1),
        city.region,
        city.epsg
    );
    Ok(())
}
