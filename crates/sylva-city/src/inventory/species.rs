//! An inventory's species, however a city spells it, matched to the Urban Tree Database: its
//! code (`PLAC`), its scientific name (cultivars, `var.` and hybrid signs tolerated) or its
//! common name; then, where the tree's region has no equations for it, the same species in the
//! nearest region that has them, then its genus, then its tree type's most common species.

use crate::inventory::regions::by_distance_from;
use std::collections::HashMap;
use sylva::growth::{Database, SpeciesEntry};

/// How a row's species name was recognised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Named {
    /// By its database code.
    Code,
    /// By its scientific name as the database writes it.
    Scientific,
    /// By genus and species, its cultivar, variety or hybrid sign set aside.
    Binomial,
    /// By its common name.
    Common,
    /// By its genus alone: the species is not in the database.
    GenusOnly,
    /// Not at all.
    Unknown,
}

/// How a tree came to the species it is grown as.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Fallback {
    /// Its own species, measured in its region.
    Own,
    /// Its own species, measured in another region (the nearest that has it).
    OtherRegion,
    /// Another species of its genus.
    Genus,
    /// The most common species of its tree type in its region.
    TreeType,
}

impl Fallback {
    /// In words, for the summary.
    pub fn words(&self) -> &'static str {
        match self {
            Fallback::Own => "its own species in its region",
            Fallback::OtherRegion => "its own species from the nearest region measuring it",
            Fallback::Genus => "a species of its genus",
            Fallback::TreeType => "its tree type's most common species",
        }
    }
}

/// A tree's species as it will be grown.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Resolved {
    /// Region whose equations grow it.
    pub region: String,
    /// Species code there.
    pub code: String,
    /// How the name was recognised.
    pub named: Named,
    /// How its species and region were chosen.
    pub fallback: Fallback,
}

/// The database's species by every spelling, and the resolutions made so far (a city names a
/// few hundred species over 10^5 rows).
pub struct SpeciesIndex {
    db: &'static Database,
    codes: HashMap<String, String>,
    scientific: HashMap<String, String>,
    binomial: HashMap<String, String>,
    common: HashMap<String, String>,
    genera: HashMap<String, String>,
    /// Trees surveyed per (region, code), to pick a genus's or a type's most common species.
    counts: HashMap<(String, String), u32>,
    cache: HashMap<(String, String), Option<Resolved>>,
}

impl SpeciesIndex {
    /// The index of the built-in database.
    pub fn new() -> Self {
        let db = Database::builtin();
        let mut index = SpeciesIndex {
            db,
            codes: HashMap::new(),
            scientific: HashMap::new(),
            binomial: HashMap::new(),
            common: HashMap::new(),
            genera: HashMap::new(),
            counts: HashMap::new(),
            cache: HashMap::new(),
        };
        // Entries without a cultivar go first, so that a bare binomial finds the species and
        // not one of its cultivars.
        let mut entries: Vec<&SpeciesEntry> = db.species().iter().collect();
        entries.sort_by_key(|s| (s.code.contains('_'), s.code.clone(), s.region.clone()));
        for s in entries {
            let code = s.code.clone();
            index
                .codes
                .entry(s.code.to_lowercase())
                .or_insert(code.clone());
            index
                .scientific
                .entry(words(&s.scientific))
                .or_insert(code.clone());
            if let Some(b) = binomial(&s.scientific) {
                index.binomial.entry(b).or_insert(code.clone());
            }
            index.common.entry(words(&s.common)).or_insert(code.clone());
            if let Some(g) = genus(&s.scientific) {
                index.genera.entry(g).or_insert(code.clone());
            }
            *index.counts.entry((s.region.clone(), code)).or_default() +=
                s.trees_by_dbh_class.iter().sum::<u32>();
        }
        index
    }

    /// What the name `name` is in the database: a species code and how it was recognised, or
    /// (`GenusOnly`) a code of the same genus.
    pub fn name(&self, name: &str) -> (Option<String>, Named) {
        // Some inventories write "Latin :: Common" in one column: each part is tried.
        for part in name.split("::") {
            let key = words(part);
            if key.is_empty() {
                continue;
            }
            let found = [
                (self.codes.get(&key), Named::Code),
                (self.scientific.get(&key), Named::Scientific),
                (
                    binomial(part).and_then(|b| self.binomial.get(&b)),
                    Named::Binomial,
                ),
                (self.common.get(&key), Named::Common),
            ]
            .into_iter()
            .find_map(|(code, how)| code.map(|c| (c.clone(), how)));
            if let Some((code, how)) = found {
                return (Some(code), how);
            }
        }
        for part in name.split("::") {
            if let Some(code) = genus(part).and_then(|g| self.genera.get(&g)) {
                return (Some(code.clone()), Named::GenusOnly);
            }
        }
        (None, Named::Unknown)
    }

    /// The species and region a tree named `name` in `region` is grown as, or none where the
    /// region has no growable species at all.
    pub fn resolve(&mut self, name: &str, region: &str) -> Option<Resolved> {
        let key = (name.to_string(), region.to_string());
        if let Some(r) = self.cache.get(&key) {
            return r.clone();
        }
        let r = self.resolve_uncached(name, region);
        self.cache.insert(key, r.clone());
        r
    }

    fn resolve_uncached(&self, name: &str, region: &str) -> Option<Resolved> {
        let (code, named) = self.name(name);
        let growable = |r: &str, c: &str| self.db.growable(r).iter().any(|s| s.code == c);
        let done = |region: &str, code: &str, fallback| {
            Some(Resolved {
                region: region.into(),
                code: code.into(),
                named,
                fallback,
            })
        };
        if let Some(c) = code.as_deref().filter(|_| named != Named::GenusOnly) {
            if growable(region, c) {
                return done(region, c, Fallback::Own);
            }
            if let Some(r) = by_distance_from(region)
                .into_iter()
                .find(|r| growable(r, c))
            {
                return done(r, c, Fallback::OtherRegion);
            }
        }
        let entry_of = |c: &str| self.db.species().iter().find(|s| s.code == c);
        let genus_of = code
            .as_deref()
            .and_then(entry_of)
            .and_then(|s| genus(&s.scientific));
        if let Some(g) = &genus_of {
            for r in by_distance_from(region) {
                if let Some(c) = self.most_common(r, |s| genus(&s.scientific).as_ref() == Some(g)) {
                    return done(r, &c, Fallback::Genus);
                }
            }
        }
        // The tree type's first two letters: broadleaf or conifer, deciduous or evergreen
        // (palms, P); broadleaf deciduous where nothing is known of the tree.
        let kind: String = code
            .as_deref()
            .and_then(entry_of)
            .map(|s| s.tree_type.chars().take(2).collect())
            .filter(|k: &String| k.len() == 2)
            .unwrap_or_else(|| "BD".into());
        let c = self
            .most_common(region, |s| s.tree_type.starts_with(&kind))
            .or_else(|| self.most_common(region, |_| true))?;
        done(region, &c, Fallback::TreeType)
    }

    /// The growable species of `region` passing `keep` that the survey measured most of.
    fn most_common(&self, region: &str, keep: impl Fn(&SpeciesEntry) -> bool) -> Option<String> {
        self.db
            .growable(region)
            .into_iter()
            .filter(|s| keep(s))
            .max_by_key(|s| {
                let n = self.counts.get(&(s.region.clone(), s.code.clone()));
                (n.copied().unwrap_or(0), std::cmp::Reverse(s.code.clone()))
            })
            .map(|s| s.code.clone())
    }
}

impl Default for SpeciesIndex {
    fn default() -> Self {
        Self::new()
    }
}

/// Lower case words, quotes and punctuation dropped: `Platanus x acerifolia 'Bloodgood'` is
/// `platanus x acerifolia bloodgood`.
fn words(s: &str) -> String {
    s.to_lowercase()
        .replace(['_', '-', ',', '(', ')'], " ")
        .replace(['\'', '"', '‘', '’', '“', '”'], "")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Genus and species epithet, lower case, with a hybrid sign, a cultivar (quoted or after
/// `cv.`), a variety, subspecies or form set aside: `Gleditsia triacanthos var. inermis
/// 'Shademaster'` is `gleditsia triacanthos`.
fn binomial(s: &str) -> Option<String> {
    let lower = s.to_lowercase();
    let mut parts = lower
        .split(['\'', '"', '‘', '’'])
        .next()
        .unwrap_or("")
        .split_whitespace()
        .filter(|w| !matches!(*w, "x" | "×"))
        .map(|w| w.trim_start_matches('×'));
    let genus = parts.next()?;
    let species = parts.next()?;
    if matches!(
        species,
        "var." | "subsp." | "ssp." | "cv." | "spp." | "sp." | "f."
    ) {
        return None;
    }
    Some(format!("{genus} {species}"))
}

/// The genus, lower case: the first word of a scientific name.
fn genus(s: &str) -> Option<String> {
    let g = s.split_whitespace().next()?.to_lowercase();
    (g.len() > 2 && g.chars().all(|c| c.is_alphabetic())).then_some(g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_as_cities_spell_them_find_their_species() {
        let index = SpeciesIndex::new();
        let code = |n: &str| index.name(n);
        assert_eq!(code("PLAC"), (Some("PLAC".into()), Named::Code));
        assert_eq!(code("plac").0.as_deref(), Some("PLAC"));
        assert_eq!(
            code("Platanus x acerifolia"),
            (Some("PLAC".into()), Named::Scientific)
        );
        assert_eq!(
            code("Platanus × acerifolia 'Bloodgood'").0.as_deref(),
            Some("PLAC")
        );
        assert_eq!(
            code("London planetree"),
            (Some("PLAC".into()), Named::Common)
        );
        assert_eq!(
            code("Gleditsia triacanthos var. inermis").0.as_deref(),
            Some("GLTR")
        );
        assert_eq!(
            code("GLEDITSIA TRIACANTHOS"),
            (Some("GLTR".into()), Named::Scientific)
        );
        assert_eq!(
            code("Platanus x hispanica :: Sycamore: London Plane").1,
            Named::GenusOnly
        );
        assert_eq!(code("Quercus imaginaria").1, Named::GenusOnly);
        assert_eq!(code("Vacant Site"), (None, Named::Unknown));
        assert_eq!(code(""), (None, Named::Unknown));
    }

    #[test]
    fn a_species_not_measured_in_its_region_falls_back_in_order() {
        let mut index = SpeciesIndex::new();
        let r = index.resolve("PLAC", "InlVal").unwrap();
        assert_eq!(
            (r.region.as_str(), r.code.as_str(), &r.fallback),
            ("InlVal", "PLAC", &Fallback::Own)
        );
        // Honolulu measured no London planes: the nearest region that did grows it.
        let r = index.resolve("Platanus x acerifolia", "Tropic").unwrap();
        assert_eq!(r.code, "PLAC");
        assert_eq!(r.fallback, Fallback::OtherRegion);
        assert_ne!(r.region, "Tropic");
        // An oak the database never measured: the most measured oak of the nearest region
        // that grows one.
        let r = index.resolve("Quercus imaginaria", "NoEast").unwrap();
        assert!(r.code.starts_with("QU"), "{r:?}");
        assert_eq!(r.fallback, Fallback::Genus);
        // Nothing known: the region's most measured broadleaf deciduous species.
        let r = index.resolve("mystery tree", "NoEast").unwrap();
        assert_eq!(r.fallback, Fallback::TreeType);
        assert_eq!(r.region, "NoEast");
        let db = Database::builtin();
        let entry = db
            .species()
            .iter()
            .find(|s| s.region == "NoEast" && s.code == r.code)
            .unwrap();
        assert!(entry.tree_type.starts_with("BD"), "{entry:?}");
    }
}
