//! The `sylva` command: generate, export and inspect trees.

mod args;
mod bench_forest;
mod bench_growth;
mod caption;
mod commands;
mod forest;
mod glb_scene;
mod grow;
mod lines;
mod lobes;
mod lod_chain;
mod nagel;
mod render;
mod render_forest;
mod shared;
mod viewer;

use clap::Parser;

fn main() {
    // Rust ignores SIGPIPE, which turns a closed pipe (`sylva species list | head -1`) into a
    // panic in println!; the default action ends the process quietly instead.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to its default before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // Mesa's drivers complain on stderr when XDG_RUNTIME_DIR is unset (root shells, CI) even
    // though headless rendering never needs it; give them the temp directory instead.
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        // SAFETY: nothing else runs yet: no threads exist that could read the environment.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir()) };
    }
    let cli = args::Cli::parse();
    if let Err(err) = commands::run(cli) {
        eprintln!("sylva: {err:#}");
        std::process::exit(1);
    }
}
