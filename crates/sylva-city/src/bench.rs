//! How a city's run grows with its number of trees (`sylva bench --city N`): a demo city of
//! N/10 trees tiled first as the baseline, then one of N, in the same process.

use crate::demo::{DemoLayout, demo_city};
use crate::error::CityError;
use crate::inventory::Layout;
use crate::run::{Quiet, tile_city};
use crate::trees::plan::CityOptions;
use std::time::Instant;

/// One city tiled.
#[derive(Clone, Debug)]
pub struct CitySize {
    /// Trees in the inventory.
    pub trees: usize,
    /// Seconds the whole run took.
    pub seconds: f64,
    /// Trees drawn at the first epoch.
    pub drawn: usize,
    /// Tiles, and shared grown trees.
    pub tiles: usize,
    #[allow(missing_docs)]
    pub shared: usize,
    /// Bytes written: the shared trees and the tiles' content.
    pub bytes: u64,
    /// The process's peak resident memory so far, MB (Linux's VmHWM; 0 elsewhere).
    pub peak_mb: f64,
}

/// The process's peak resident memory so far, MB.
fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// Demo cities of `n / 10` and `n` trees (`n` held to 100..=2,000,000) in PacfNW, each tiled
/// in a fresh folder under the system's temporary folder and removed after; `each` is shown
/// each as it is done.
pub fn city_sizes(n: usize, mut each: impl FnMut(&CitySize)) -> Result<(), CityError> {
    let n = n.clamp(100, 2_000_000);
    let dir = std::env::temp_dir().join(format!("sylva-bench-city-{}", std::process::id()));
    let io = |e: std::io::Error| CityError::Write {
        path: dir.clone(),
        message: e.to_string(),
    };
    std::fs::create_dir_all(&dir).map_err(io)?;
    for trees in [n / 10, n] {
        let inventory = dir.join(format!("city-{trees}.csv"));
        demo_city("PacfNW", trees, 0, 2026)?.write(&inventory, DemoLayout::Census)?;
        let out = dir.join(format!("tiles-{trees}"));
        let t = Instant::now();
        let options = CityOptions::default();
        let run = tile_city(&inventory, None, &Layout::default(), &options, &out, &Quiet)?;
        let epoch = &run.epochs[0].2;
        each(&CitySize {
            trees,
            seconds: t.elapsed().as_secs_f64(),
            drawn: epoch.trees,
            tiles: epoch.tiles,
            shared: run.prototypes,
            bytes: run.prototype_bytes + epoch.content_bytes,
            peak_mb: peak_mb(),
        });
        std::fs::remove_dir_all(&out).map_err(io)?;
    }
    std::fs::remove_dir_all(&dir).map_err(io)
}
