//! `sylva species`: the built-in species, and every parameter of one with its unit, range and
//! meaning (or the species as a TOML file to start from).

use crate::args::SpeciesCommand;
use anyhow::{Context, Result};
use sylva::params::{LEVEL_SETS, PARAMS, ParamDef, format_value};

pub fn run(command: SpeciesCommand) -> Result<()> {
    match command {
        SpeciesCommand::List => list(),
        SpeciesCommand::Show { name, toml } => show(&name, toml),
    }
}

fn list() -> Result<()> {
    for id in sylva::species::builtin_ids() {
        let p = sylva::species::builtin(id).context("built-in species")?;
        println!("{id:<18} {:<22} {}", p.name, p.description);
    }
    Ok(())
}

fn show(name: &str, toml: bool) -> Result<()> {
    let params = sylva::species::load(name)?;
    if toml {
        print!("{}", sylva::params::to_toml(&params));
        return Ok(());
    }
    println!("{}", params.name);
    if !params.description.is_empty() {
        println!("{}", params.description);
    }
    println!();
    println!(
        "{:<16} {:>9}  {:<13} {:<22} meaning",
        "parameter", "value", "unit", "range"
    );
    let row = |def: &ParamDef, level: usize| {
        println!(
            "{:<16} {:>9}  {:<13} {:<22} {}",
            def.name_at(level),
            format_value((def.get)(&params, level)),
            def.unit,
            def.range_text(),
            def.doc
        );
    };
    for def in PARAMS.iter().filter(|d| !d.per_level) {
        row(def, 0);
    }
    for level in 0..LEVEL_SETS {
        for def in PARAMS
            .iter()
            .filter(|d| d.per_level && d.levels().contains(&level))
        {
            row(def, level);
        }
    }
    Ok(())
}
