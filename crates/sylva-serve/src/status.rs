//! `GET /api/status`: every byte the server keeps against its bound, and what it refused.
//!
//! The bound (`--cache-mib`) covers what the server keeps between requests: the grown trees
//! of every age ([`crate::cache`], counted while anything holds them) and the answers kept
//! for asking again ([`crate::recent`]). `cache_bytes`, their sum, never passes
//! `cache_bound`. What a request builds while it runs (a mesh, a picture; at most one per
//! core at once) and what a growth builds before it publishes an age (the tree it grows on)
//! are not kept, and are the overhead above the bound that resident memory shows
//! (`rss_bytes`; the README states it as measured).

use crate::State;
use axum::Json;
use axum::extract::State as AxumState;
use std::sync::Arc;
use std::sync::atomic::Ordering;

/// `GET /api/status`.
pub async fn status(AxumState(state): AxumState<Arc<State>>) -> Json<serde_json::Value> {
    Json(status_json(&state))
}

/// The status as JSON (also what `sylva serve` and the soak read).
pub fn status_json(state: &State) -> serde_json::Value {
    let c = &state.cache;
    let h = c.holding();
    let recent = state.recent.bytes();
    let r = &c.refusals;
    serde_json::json!({
        "cache_bytes": h.bytes + recent,
        "cache_bound": state.bound,
        "growth_bytes": h.bytes,
        "growth_bound": c.bound(),
        "held_bytes": h.held,
        "in_use_bytes": h.in_use,
        "expected_bytes": h.expected,
        "recent_bytes": recent,
        "recent_bound": state.recent.bound(),
        "growths": h.growths,
        "growing": h.growing,
        "growing_limit": c.growing_limit(),
        "growths_started": r.started.load(Ordering::Relaxed),
        "wait_limit_s": state.wait_limit.as_secs(),
        "refused": {
            "busy": r.busy.load(Ordering::Relaxed),
            "full": r.full.load(Ordering::Relaxed),
            "too_large": r.too_large.load(Ordering::Relaxed),
            "stopped": r.stopped.load(Ordering::Relaxed),
            "waited": r.waited.load(Ordering::Relaxed),
        },
        "rss_bytes": resident_bytes(),
        "allocator": state.allocator,
    })
}

/// How often free memory is handed back to the system ([`give_back_free_memory`]).
pub const GIVE_BACK_EVERY: std::time::Duration = std::time::Duration::from_secs(5);

/// Hands the memory the allocator holds free back to the system. glibc's malloc keeps what a
/// thread freed in that thread's arena for its next allocation, and the server's many threads
/// (growths, meshing, pictures) each free hundreds of megabytes when they finish. Measured in
/// half-hour soaks at 256 MiB: resident memory over the cache averaged 463 MiB with this and
/// 532 MiB without; the peaks, set by what is in the making at once, were no lower. Elsewhere
/// nothing; under mimalloc it trims only glibc's own heap.
pub fn give_back_free_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim takes a plain integer and only returns the allocator's free pages.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// The process's resident memory, bytes (Linux: `/proc/self/statm`'s second field, in pages);
/// `None` elsewhere.
pub fn resident_bytes() -> Option<u64> {
    #[cfg(target_os = "linux")]
    {
        let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
        let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
        // SAFETY: sysconf reads a constant of the system and touches no memory of ours.
        let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
        Some(pages * u64::try_from(page).ok()?)
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}
