//! `sylva serve`: the web page for planners (the `sylva-serve` crate), on localhost unless
//! `--host` says otherwise.

use crate::args::ServeArgs;
use anyhow::Result;

pub fn run(args: &ServeArgs) -> Result<()> {
    let options = sylva_serve::Options {
        host: args.host.clone(),
        port: args.port,
        cache_bytes: (args.cache_mib as usize) << 20,
        ..Default::default()
    };
    let open = args.open;
    sylva_serve::run(&options, |url| {
        println!("sylva serve: the page is at {url} (Ctrl-C stops)");
        if open && let Err(e) = open::that_detached(url) {
            eprintln!("sylva serve: could not open a browser ({e}); open {url} yourself");
        }
    })?;
    Ok(())
}
