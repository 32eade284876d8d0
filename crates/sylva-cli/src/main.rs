//! The `sylva` command: generate, export and inspect trees. This file parses the flags and
//! hands them to the subcommand's module; each module turns flags into library calls and
//! prints what was made. What several of them need lives in `shared.rs`.

mod allocator;
mod args;
mod bench;
mod city;
mod draw;
mod forest;
mod fractal;
mod generate;
mod grow;
mod lobes;
mod rank;
mod render;
mod serve;
mod shared;
mod species;
mod stick;
mod sweep;
mod view;
mod whisk;
mod wires;

use args::{Cli, Command};
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
    let done = match Cli::parse().command {
        Command::Generate(args) => generate::run(&args),
        Command::Species(command) => species::run(command),
        Command::Render(args) => render::run(&args),
        Command::View(args) => view::run(&args),
        Command::Forest(args) => forest::run(&args),
        Command::Grow(args) => grow::run(&args),
        Command::Rank(args) => rank::run(&args),
        Command::Sweep(args) => sweep::run(&args),
        Command::City(args) => city::run(&args),
        Command::CityDemo(args) => city::demo(&args),
        Command::Wires(args) => wires::run(&args),
        Command::Serve(args) => serve::run(&args),
        Command::Fractal(args) => fractal::run(&args),
        Command::Whisk(args) => whisk::run(&args),
        Command::Stick(args) => stick::run(&args),
        Command::Draw(args) => draw::run(&args),
        Command::Lobes(args) => lobes::run(&args),
        Command::Bench(args) => bench::run(&args),
    };
    if let Err(err) = done {
        eprintln!("sylva: {err:#}");
        std::process::exit(1);
    }
}
