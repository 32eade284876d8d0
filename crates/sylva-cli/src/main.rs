//! The `sylva` command: generate, export and inspect trees.

mod args;
mod commands;

use clap::Parser;

fn main() {
    let cli = args::Cli::parse();
    if let Err(err) = commands::run(cli) {
        eprintln!("sylva: {err:#}");
        std::process::exit(1);
    }
}
