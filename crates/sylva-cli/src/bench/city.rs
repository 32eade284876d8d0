//! `sylva bench --city N`: a demo city of N trees tiled (`sylva city`), beside one of N/10
//! tiled first in the same process as the baseline: how time, bytes and memory grow with the
//! number of trees.

use anyhow::Result;
use sylva_city::bench::city_sizes;

pub fn bench_city(n: usize) -> Result<()> {
    println!(
        "\n{:>9} {:>9} {:>9} {:>7} {:>8} {:>10} {:>9} {:>8}",
        "trees", "seconds", "trees/s", "tiles", "shared", "MB", "B/tree", "peak MB"
    );
    let mut first: Option<(usize, f64, f64)> = None;
    city_sizes(n, |c| {
        let (drawn, bytes) = (c.drawn as f64, c.bytes as f64);
        println!(
            "{:>9} {:>9.1} {:>9.0} {:>7} {:>8} {:>10.1} {:>9.0} {:>8.0}",
            c.trees,
            c.seconds,
            drawn / c.seconds,
            c.tiles,
            c.shared,
            bytes / 1e6,
            bytes / drawn,
            c.peak_mb
        );
        match first {
            None => first = Some((c.trees, c.seconds, bytes)),
            Some((n0, s0, b0)) => println!(
                "  x{:.1} the trees: x{:.2} the time, x{:.2} the bytes (baseline: the first line)",
                c.trees as f64 / n0 as f64,
                c.seconds / s0,
                bytes / b0
            ),
        }
    })?;
    Ok(())
}
