//! Built-in species (TOML files under `species/`, embedded in the binary) and loading species
//! from files by extension.

use crate::error::ParamsError;
use crate::params::{TreeParams, from_arbaro_xml, from_toml};
use std::path::Path;

macro_rules! builtin {
    ($($id:literal),* $(,)?) => {
        /// Built-in species: (id, TOML text).
        pub static BUILTIN: &[(&str, &str)] = &[
            $(($id, include_str!(concat!("../../../species/", $id, ".toml")))),*
        ];
    };
}

builtin!(
    "quaking_aspen",
    "black_tupelo",
    "weeping_willow",
    "ca_black_oak",
    "balsam_fir",
    "austrian_pine",
    "queen_palm",
    "saguaro",
    "hazel",
    "lombardy_poplar",
    "golden_bamboo",
    "weeping_birch",
);

/// Normalises a species name for lookup: case-insensitive, spaces and dashes as underscores.
fn normalise(name: &str) -> String {
    name.trim().to_lowercase().replace([' ', '-'], "_")
}

/// Ids of the built-in species, in catalogue order.
pub fn builtin_ids() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|(id, _)| *id)
}

/// A built-in species by id or display name (`quaking_aspen`, `Quaking Aspen`).
pub fn builtin(name: &str) -> Option<TreeParams> {
    let wanted = normalise(name);
    BUILTIN.iter().find_map(|(id, text)| {
        let params =
            from_toml(text, &format!("built-in {id}")).expect("built-in species are valid");
        (*id == wanted || normalise(&params.name) == wanted).then_some(params)
    })
}

/// Loads a species: a built-in name, or a `.toml` (Sylva) or `.xml` (Arbaro) file.
pub fn load(name_or_path: &str) -> Result<TreeParams, ParamsError> {
    let path = Path::new(name_or_path);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let is_file_name = matches!(ext.as_deref(), Some("toml" | "xml"));
    if !is_file_name && let Some(params) = builtin(name_or_path) {
        return Ok(params);
    }
    if !path.exists() {
        return Err(if is_file_name {
            ParamsError::Syntax {
                source_name: name_or_path.to_string(),
                message: "no such file".into(),
            }
        } else {
            ParamsError::NoSuchSpecies(name_or_path.to_string())
        });
    }
    let text = std::fs::read_to_string(path).map_err(|e| ParamsError::Syntax {
        source_name: name_or_path.to_string(),
        message: format!("cannot read: {e}"),
    })?;
    match ext.as_deref() {
        Some("xml") => from_arbaro_xml(&text, name_or_path),
        Some("toml") => from_toml(&text, name_or_path),
        _ => Err(ParamsError::Syntax {
            source_name: name_or_path.to_string(),
            message: "unknown file type: expected a .toml species file or an Arbaro .xml file"
                .into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_loads_by_id_and_by_name() {
        for (id, _) in BUILTIN {
            let p = builtin(id).unwrap();
            assert_eq!(builtin(&p.name).unwrap(), p);
            assert!(!p.description.is_empty(), "{id} needs a description");
        }
        assert!(builtin("no such tree").is_none());
        assert!(matches!(
            load("no such tree"),
            Err(ParamsError::NoSuchSpecies(_))
        ));
        assert!(
            load("missing.toml")
                .unwrap_err()
                .to_string()
                .contains("missing.toml")
        );
    }
}
