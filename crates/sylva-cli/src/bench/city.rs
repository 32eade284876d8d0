//! `sylva bench --city N`: a demo city of N trees tiled (`sylva city`), beside one of N/10
//! tiled first in the same process as the baseline: how time, bytes and memory grow with the
//! number of trees.

use anyhow::Result;
use std::time::Instant;
use sylva_city::demo::{DemoLayout, demo_city};
use sylva_city::{CityOptions, Layout, Quiet, tile_city};

/// The process's peak resident memory so far, MB (Linux's VmHWM; 0 elsewhere).
fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

pub fn bench_city(n: usize) -> Result<()> {
    let n = n.clamp(100, 2_000_000);
    let dir = tempfile_dir()?;
    println!(
        "\n{:>9} {:>9} {:>9} {:>7} {:>8} {:>10} {:>9} {:>8}",
        "trees", "seconds", "trees/s", "tiles", "shared", "MB", "B/tree", "peak MB"
    );
    let mut first: Option<(f64, f64, f64)> = None;
    for trees in [n / 10, n] {
        let inventory = dir.join(format!("city-{trees}.csv"));
        demo_city("PacfNW", trees, 0, 2026)?.write(&inventory, DemoLayout::Census)?;
        let out = dir.join(format!("tiles-{trees}"));
        let t = Instant::now();
        let run = tile_city(
            &inventory,
            None,
            &Layout::default(),
            &CityOptions::default(),
            &out,
            &Quiet,
        )?;
        let seconds = t.elapsed().as_secs_f64();
        let drawn = run.epochs[0].2.trees as f64;
        let bytes = (run.prototype_bytes + run.epochs[0].2.content_bytes) as f64;
        let peak = peak_mb();
        println!(
            "{:>9} {:>9.1} {:>9.0} {:>7} {:>8} {:>10.1} {:>9.0} {:>8.0}",
            trees,
            seconds,
            drawn / seconds,
            run.epochs[0].2.tiles,
            run.prototypes,
            bytes / 1e6,
            bytes / drawn,
            peak
        );
        match first {
            None => first = Some((seconds, bytes, peak)),
            Some((s0, b0, _)) => println!(
                "  x{:.1} the trees: x{:.2} the time, x{:.2} the bytes (baseline: the first line)",
                (n as f64) / (n / 10) as f64,
                seconds / s0,
                bytes / b0
            ),
        }
        std::fs::remove_dir_all(&out)?;
    }
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}

/// A fresh folder under the system's temporary folder.
fn tempfile_dir() -> Result<std::path::PathBuf> {
    let dir = std::env::temp_dir().join(format!("sylva-bench-city-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    Ok(dir)
}
