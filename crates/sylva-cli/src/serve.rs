//! `sylva serve`: the web page for planners (the `sylva-serve` crate), on localhost unless
//! `--host` says otherwise.

use crate::args::ServeArgs;
use anyhow::Result;

pub fn run(args: &ServeArgs) -> Result<()> {
    let options = sylva_serve::Options {
        host: args.host.clone(),
        port: args.port,
        cache_bytes: (args.cache_mib as usize) << 20,
        cities: args.cities.clone(),
        basemap: args.basemap.clone(),
        allocator: crate::allocator::NAME,
        ..Default::default()
    };
    let open = args.open;
    sylva_serve::run(&options, |url, cities| {
        for c in &cities.list {
            match &c.problem {
                Some(why) => eprintln!("sylva serve: city `{}` cannot be shown: {why}", c.name),
                None => println!(
                    "sylva serve: city `{}` ({} epochs) at {url}city.html?city={}",
                    c.name,
                    c.epochs.len(),
                    c.name
                ),
            }
        }
        println!("sylva serve: the page is at {url} (Ctrl-C stops)");
        // With cities, the page opened is the city view.
        let page = if cities.list.is_empty() {
            url.to_string()
        } else {
            format!("{url}city.html")
        };
        if open && let Err(e) = open::that_detached(&page) {
            eprintln!("sylva serve: could not open a browser ({e}); open {page} yourself");
        }
    })?;
    Ok(())
}
