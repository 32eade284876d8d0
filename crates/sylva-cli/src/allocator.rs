//! The memory allocator the binary runs on: the system's (glibc's malloc on Linux) unless
//! built with `--features mimalloc`. `sylva serve` names it in `/api/status`, so that a soak
//! (`crates/sylva-serve/tests/web/soak.mjs`) can set the two side by side.

#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The allocator's name.
pub const NAME: &str = if cfg!(feature = "mimalloc") {
    "mimalloc"
} else {
    "the system's"
};
