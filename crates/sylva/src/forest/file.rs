//! Forest files: a TOML file whose `[forest]` table holds a [`ForestSpec`]'s fields. Species
//! files named in it are found beside it, so a folder of forest and species files moves as one.

use super::{ForestError, ForestSpec};
use std::path::Path;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ForestFile {
    forest: ForestSpec,
}

/// Whether `path` is a forest file (a `.toml` file with a `[forest]` table) rather than a
/// species file.
pub fn is_forest_file(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        && std::fs::read_to_string(path)
            .ok()
            .and_then(|t| t.parse::<toml::Table>().ok())
            .is_some_and(|t| t.contains_key("forest"))
}

impl ForestSpec {
    /// Reads and checks a forest file; species files named in it are taken relative to it.
    pub fn from_file(path: &Path) -> Result<Self, ForestError> {
        let fail = |message: String| ForestError::File {
            path: path.display().to_string(),
            message,
        };
        let text = std::fs::read_to_string(path).map_err(|e| fail(format!("cannot read: {e}")))?;
        let file: ForestFile =
            toml::from_str(&text).map_err(|e| fail(format!("not a forest file: {e}")))?;
        let mut spec = file.forest;
        let dir = path.parent().unwrap_or(Path::new("."));
        for s in &mut spec.species {
            if s.ends_with(".toml") || s.ends_with(".xml") {
                *s = dir.join(&*s).to_string_lossy().into_owned();
            }
        }
        spec.validate().map_err(|e| fail(format!("[forest] {e}")))?;
        Ok(spec)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forest_files_are_read_beside_their_species() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.toml");
        std::fs::write(
            &path,
            "[forest]\nspecies = [\"quaking_aspen\", \"mine.toml\"]\ncount = 12\narea = [30, 20]\n",
        )
        .unwrap();
        assert!(is_forest_file(&path));
        let spec = ForestSpec::from_file(&path).unwrap();
        assert_eq!(spec.count, 12);
        assert_eq!(spec.variants, 4);
        assert!(spec.species[1].ends_with("mine.toml") && spec.species[1].len() > 9);
        std::fs::write(
            &path,
            "[forest]\nspecies = [\"quaking_aspen\"]\ncount = 0\n",
        )
        .unwrap();
        let e = ForestSpec::from_file(&path).unwrap_err().to_string();
        assert!(e.contains("f.toml") && e.contains("count"), "{e}");
        std::fs::write(&path, "[forest]\nspecies = [\"a\"]\ncolour = 3\n").unwrap();
        assert!(ForestSpec::from_file(&path).is_err());
        assert!(!is_forest_file(&dir.path().join("none.toml")));
    }
}
