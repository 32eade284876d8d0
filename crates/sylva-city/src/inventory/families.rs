//! The plant family of a genus (`data/genus-family.csv`: APG IV for flowering plants,
//! Christenhusz et al. 2011 for conifers and Ginkgo), for the report's composition by family.

use std::collections::HashMap;
use std::sync::OnceLock;

const TABLE: &str = include_str!("../../data/genus-family.csv");

fn table() -> &'static HashMap<&'static str, &'static str> {
    static TABLE_BY_GENUS: OnceLock<HashMap<&'static str, &'static str>> = OnceLock::new();
    TABLE_BY_GENUS.get_or_init(|| {
        TABLE
            .lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .skip(1)
            .filter_map(|l| l.split_once(','))
            .map(|(g, f)| (g.trim(), f.trim()))
            .collect()
    })
}

/// The family of `genus`, if the table has it.
pub fn family(genus: &str) -> Option<&'static str> {
    table().get(genus).copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::growth::Database;

    #[test]
    fn every_genus_of_the_database_has_its_family() {
        assert_eq!(family("Platanus"), Some("Platanaceae"));
        assert_eq!(family("Acer"), Some("Sapindaceae"));
        assert_eq!(family("Ginkgo"), Some("Ginkgoaceae"));
        assert_eq!(family("Nonesuch"), None);
        let db = Database::builtin();
        let mut missing: Vec<String> = Vec::new();
        for s in db.species() {
            let genus = s.scientific.split_whitespace().next().unwrap_or("");
            if family(genus).is_none() && !missing.iter().any(|g| g == genus) {
                missing.push(genus.to_string());
            }
        }
        assert!(missing.is_empty(), "genera without a family: {missing:?}");
    }
}
