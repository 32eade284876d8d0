//! The reference: i-Tree Streets' resource units, a tree's yearly benefits by species and trunk
//! diameter for a tree at i-Tree's typical spread of positions around buildings.
//!
//! i-Tree Streets (USDA Forest Service; the STRATUM model of McPherson et al.) tabulates, for each
//! of its 16 climate regions, each species it measured in the region's reference city and twelve
//! "OTHER" classes by tree type, the benefit of one tree at nine DBH classes. The tables are read
//! from the copy OpenTreeMap ships with its benefit service (otm-ecoservice, `data/`), converted
//! to one long-form CSV per region by `tools/itree-streets-import.py` (the values as published).
//! `crates/sylva/data/itree-streets/README.md` says which commit and what every factor means.
//!
//! Between class midpoints a value is interpolated linearly in DBH, as i-Tree and
//! otm-ecoservice do. Outside them (under 3.81 cm, over 114.3 cm) otm-ecoservice holds the end
//! class's value; so does this module, and it says so ([`Lookup::held`]).

use std::collections::HashMap;
use std::sync::OnceLock;

/// The DBH class midpoints of every table, cm.
pub const DBH_CLASSES_CM: [f64; 9] = [
    3.81, 11.43, 22.86, 38.10, 53.34, 68.58, 83.82, 99.06, 114.30,
];

/// What a table gives, per tree per year unless said otherwise.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Factor {
    /// Cooling saved, kWh.
    Electricity,
    /// Heating saved, kBtu (negative: winter shade costs more gas than wind shelter saves).
    NaturalGas,
    /// Rainfall intercepted, m³.
    HydroInterception,
    /// CO2 sequestered, kg.
    Co2Sequestered,
    /// CO2 emissions avoided at power plants by the energy saved, kg.
    Co2Avoided,
    /// CO2 stored in the tree (a stock, not a yearly flow), kg.
    Co2Storage,
    /// Ozone taken up, kg.
    AqOzoneDep,
    /// NOx taken up, kg.
    AqNoxDep,
    /// PM10 taken up, kg.
    AqPm10Dep,
    /// SO2 taken up, kg.
    AqSoxDep,
    /// NOx emissions avoided by the energy saved, kg.
    AqNoxAvoided,
    /// PM10 emissions avoided, kg.
    AqPm10Avoided,
    /// SO2 emissions avoided, kg.
    AqSoxAvoided,
    /// VOC emissions avoided, kg.
    AqVocAvoided,
    /// Biogenic VOCs the tree emits, kg (negative).
    Bvoc,
    /// The yearly figure i-Tree Streets prices aesthetics and property value from (the table's
    /// own name; docs/benefits.md says how it is read).
    PropertyValue,
    /// Leaf surface area, m² (a stock).
    Lsa,
}

impl Factor {
    /// Every factor, in the order the data files hold them.
    pub const ALL: [Factor; 17] = [
        Factor::Electricity,
        Factor::NaturalGas,
        Factor::HydroInterception,
        Factor::Co2Sequestered,
        Factor::Co2Avoided,
        Factor::Co2Storage,
        Factor::AqOzoneDep,
        Factor::AqNoxDep,
        Factor::AqPm10Dep,
        Factor::AqSoxDep,
        Factor::AqNoxAvoided,
        Factor::AqPm10Avoided,
        Factor::AqSoxAvoided,
        Factor::AqVocAvoided,
        Factor::Bvoc,
        Factor::PropertyValue,
        Factor::Lsa,
    ];

    /// The factor's name in the source files (`output__REGION__NAME.csv`).
    pub fn name(self) -> &'static str {
        match self {
            Factor::Electricity => "electricity",
            Factor::NaturalGas => "natural_gas",
            Factor::HydroInterception => "hydro_interception",
            Factor::Co2Sequestered => "co2_sequestered",
            Factor::Co2Avoided => "co2_avoided",
            Factor::Co2Storage => "co2_storage",
            Factor::AqOzoneDep => "aq_ozone_dep",
            Factor::AqNoxDep => "aq_nox_dep",
            Factor::AqPm10Dep => "aq_pm10_dep",
            Factor::AqSoxDep => "aq_sox_dep",
            Factor::AqNoxAvoided => "aq_nox_avoided",
            Factor::AqPm10Avoided => "aq_pm10_avoided",
            Factor::AqSoxAvoided => "aq_sox_avoided",
            Factor::AqVocAvoided => "aq_voc_avoided",
            Factor::Bvoc => "bvoc",
            Factor::PropertyValue => "property_value",
            Factor::Lsa => "lsa",
        }
    }

    fn parse(name: &str) -> Option<Factor> {
        Factor::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// A species row of a region's list (`species.csv`).
#[derive(Clone, Debug, PartialEq)]
pub struct Species {
    /// i-Tree's species code (the USDA PLANTS code, with the region's own suffixes).
    pub code: String,
    /// Latin name as i-Tree writes it.
    pub scientific_name: String,
    /// Common name.
    pub common_name: String,
    /// Tree type: B(roadleaf), C(onifer) or P(alm); D(eciduous) or E(vergreen); L, M or S
    /// (large, medium, small at maturity), e.g. `BDL`.
    pub tree_type: String,
    /// The code whose table rows this species takes (its own, a close relative's, or its
    /// type's `OTHER` class).
    pub values_from: String,
}

/// One region's tables.
#[derive(Debug, Default)]
pub struct Region {
    values: HashMap<(Factor, String), [Option<f64>; 9]>,
    species: Vec<Species>,
}

/// How a value was found.
#[derive(Clone, Debug, PartialEq)]
pub struct Lookup {
    /// The value at the DBH asked for.
    pub value: f64,
    /// The table row it came from.
    pub row: String,
    /// The DBH lay outside the class midpoints and the end class's value was held.
    pub held: bool,
}

impl Region {
    /// The species list of the region.
    pub fn species(&self) -> &[Species] {
        &self.species
    }

    /// The table row a species code reads: its own row, else the row its species entry
    /// names, else `None` (the caller falls back by tree type with [`Region::other`]).
    pub fn row_for(&self, code: &str) -> Option<String> {
        let has = |c: &str| self.has_row(c);
        if has(code) {
            return Some(code.to_string());
        }
        let s = self.species.iter().find(|s| s.code == code)?;
        has(&s.values_from).then(|| s.values_from.clone())
    }

    /// Every table row's name (species codes and `OTHER` classes), in no set order.
    pub fn rows(&self) -> impl Iterator<Item = &str> {
        self.values
            .keys()
            .filter(|(f, _)| *f == Factor::Electricity)
            .map(|(_, row)| row.as_str())
    }

    /// Whether the tables hold a row of that name (every row has every factor, as the tests
    /// check, so electricity stands for all).
    fn has_row(&self, row: &str) -> bool {
        self.values
            .contains_key(&(Factor::Electricity, row.to_string()))
    }

    /// The `OTHER` row of a tree type (`BDL OTHER` …).
    pub fn other(tree_type: &str) -> String {
        format!("{tree_type} OTHER")
    }

    /// The factor for a table row at `dbh_cm`, interpolated linearly between class midpoints;
    /// `None` where the row or the value is missing (never a zero).
    pub fn value(&self, factor: Factor, row: &str, dbh_cm: f64) -> Option<Lookup> {
        let v = self.values.get(&(factor, row.to_string()))?;
        let c = &DBH_CLASSES_CM;
        let at = |i: usize| v[i];
        let (value, held) = if dbh_cm <= c[0] {
            (at(0)?, dbh_cm < c[0])
        } else if dbh_cm >= c[8] {
            (at(8)?, dbh_cm > c[8])
        } else {
            let i = c.iter().rposition(|&m| m <= dbh_cm)?;
            let t = (dbh_cm - c[i]) / (c[i + 1] - c[i]);
            (at(i)? + t * (at(i + 1)? - at(i)?), false)
        };
        Some(Lookup {
            value,
            row: row.to_string(),
            held,
        })
    }
}

/// How a species found its table row.
#[derive(Clone, Debug, PartialEq)]
pub enum Match {
    /// The region measured the species: its own row.
    Species,
    /// The region lists the species and assigns it another row (a relative's, or its type's
    /// `OTHER` class): i-Tree's own choice.
    Assigned,
    /// The region does not list the species; a listed species of the same genus and tree type
    /// gives its row (the species named).
    Genus(String),
    /// Neither: the `OTHER` class of the species' tree type, as i-Tree Streets assigns
    /// species it has no data for.
    TreeType,
}

impl Region {
    /// The table row for a species (code, Latin name and tree type as the Urban Tree Database
    /// gives them), and how it was found; `None` when the region has not even the tree type's
    /// `OTHER` class (Boise has no broadleaf evergreens).
    pub fn resolve(
        &self,
        code: &str,
        scientific_name: &str,
        tree_type: &str,
    ) -> Option<(String, Match)> {
        let has = |c: &str| self.has_row(c);
        if has(code) {
            return Some((code.to_string(), Match::Species));
        }
        if let Some(row) = self.row_for(code) {
            return Some((row, Match::Assigned));
        }
        let genus = |name: &str| name.split_whitespace().next().unwrap_or("").to_lowercase();
        let g = genus(scientific_name);
        let relative = self.species.iter().find(|s| {
            !g.is_empty()
                && genus(&s.scientific_name) == g
                && s.tree_type == tree_type
                && !s.values_from.ends_with("OTHER")
                && has(&s.values_from)
        });
        if let Some(s) = relative {
            return Some((s.values_from.clone(), Match::Genus(s.code.clone())));
        }
        let other = Region::other(tree_type);
        has(&other).then_some((other, Match::TreeType))
    }
}

/// The i-Tree Streets region whose tables stand for a Sylva region, and why when it is not the
/// region itself: the Sacramento Valley has none, and Modesto's Inland Valleys, the same
/// Central Valley climate 120 km south, is the nearest.
pub fn reference_region(name: &str) -> Option<(&'static str, Option<&'static str>)> {
    if name == "SacVal" {
        return Some((
            "InlVal",
            Some(
                "i-Tree Streets has no Sacramento Valley region: the Inland Valleys' (Modesto) tables stand in",
            ),
        ));
    }
    regions().get_key_value(name).map(|(k, _)| (*k, None))
}

/// The 16 regions' tables, keyed by Sylva's short region name (`InlVal`); parsed once.
pub fn regions() -> &'static HashMap<&'static str, Region> {
    static ALL: OnceLock<HashMap<&'static str, Region>> = OnceLock::new();
    ALL.get_or_init(|| {
        let mut all: HashMap<&'static str, Region> = FILES
            .iter()
            .map(|&(name, text)| (name, parse_values(name, text)))
            .collect();
        for line in SPECIES.lines().skip(1) {
            let f: Vec<&str> = line.split(',').collect();
            // The built-in file is checked by the tests; a short row would be a broken build.
            let region = all
                .get_mut(f[0])
                .expect("species.csv names a region with a table");
            region.species.push(Species {
                code: f[1].into(),
                scientific_name: f[2].into(),
                common_name: f[3].into(),
                tree_type: f[4].into(),
                values_from: f[5].into(),
            });
        }
        all
    })
}

/// The region's tables, or `None` for a region i-Tree Streets does not cover (`SacVal`).
pub fn region(name: &str) -> Option<&'static Region> {
    regions().get(name)
}

fn parse_values(name: &str, text: &str) -> Region {
    let mut region = Region::default();
    for line in text.lines().skip(1) {
        let mut f = line.split(',');
        let factor = f.next().and_then(Factor::parse);
        let factor = factor.unwrap_or_else(|| panic!("{name}.csv: unknown factor in {line}"));
        let row = f.next().unwrap_or_default().to_string();
        let mut values = [None; 9];
        for (slot, cell) in values.iter_mut().zip(f) {
            *slot = (!cell.is_empty()).then(|| {
                cell.parse::<f64>()
                    .unwrap_or_else(|_| panic!("{name}.csv: {line}"))
            });
        }
        region.values.insert((factor, row), values);
    }
    region
}

macro_rules! region_files {
    ($($name:literal),*) => {
        [$(($name, include_str!(concat!("../../../data/itree-streets/", $name, ".csv")))),*]
    };
}

const FILES: [(&str, &str); 16] = region_files!(
    "CenFla", "GulfCo", "InlEmp", "InlVal", "InterW", "LoMidW", "MidWst", "NMtnPr", "NoCalC",
    "NoEast", "PacfNW", "Piedmt", "SWDsrt", "SoCalC", "TpIntW", "Tropic"
);
const SPECIES: &str = include_str!("../../../data/itree-streets/species.csv");

#[cfg(test)]
mod tests {
    use super::*;

    fn at(region: &str, factor: Factor, code: &str, dbh: f64) -> f64 {
        let r = super::region(region).unwrap();
        r.value(factor, &r.row_for(code).unwrap_or_else(|| code.into()), dbh)
            .unwrap()
            .value
    }

    #[test]
    fn every_region_has_every_factor_for_every_row_it_lists() {
        assert_eq!(regions().len(), 16);
        for (name, r) in regions() {
            assert!(r.species.len() > 20, "{name}: {} species", r.species.len());
            let rows: Vec<&String> = r
                .values
                .keys()
                .filter(|k| k.0 == Factor::Electricity)
                .map(|k| &k.1)
                .collect();
            // OTHER classes by tree type, and the region's measured species. Every region has
            // the deciduous broadleaf and conifer classes; broadleaf evergreens and palms only
            // where the reference city grows them (not Boise's Temperate Interior West).
            assert!(rows.len() >= 25, "{name}: {} rows", rows.len());
            for t in ["BDL", "BDM", "BDS", "CEL", "CEM", "CES"] {
                assert!(rows.contains(&&Region::other(t)), "{name}: no {t} OTHER");
            }
            for row in &rows {
                for f in Factor::ALL {
                    let v = r.values.get(&(f, (*row).clone()));
                    assert!(v.is_some(), "{name}: {} has no {}", row, f.name());
                }
            }
            for s in &r.species {
                assert!(
                    r.row_for(&s.code).is_some() || s.values_from.ends_with("OTHER"),
                    "{name}: {s:?}"
                );
            }
        }
        assert!(region("SacVal").is_none());
    }

    /// otm-ecoservice's README works one tree by hand: a 20-inch (50.8 cm) common fig in the
    /// Inland Empire, which i-Tree lists under `BDS OTHER`.
    #[test]
    fn the_worked_example_of_otm_ecoservice_s_readme() {
        let r = region("InlEmp").unwrap();
        let fig = |f: Factor| r.value(f, "BDS OTHER", 50.8).unwrap().value;
        assert!((fig(Factor::Electricity) - 189.2).abs() < 1e-9);
        assert!((fig(Factor::NaturalGas) - -81.4).abs() < 1e-9);
        assert!((fig(Factor::HydroInterception) - 3.16).abs() < 1e-9);
        assert!((fig(Factor::Co2Storage) - 569.6).abs() < 1e-9);
        assert!((fig(Factor::Co2Avoided) - 55.7).abs() < 1e-9);
        // Between 24.6 kg at 38.10 cm and 0 at 53.34 cm: the README's 4.1 kg.
        assert!((fig(Factor::Co2Sequestered) - 4.1).abs() < 1e-3);
    }

    /// The figure issue Q quotes against Sylva's winter shade: a 38 cm camphor in the Inland
    /// Valleys saves about -46 kBtu of gas a year, under a dollar.
    #[test]
    fn a_camphor_s_winter_is_under_a_dollar_of_gas() {
        let gas = at("InlVal", Factor::NaturalGas, "CICA", 38.1);
        assert!((gas - -46.2).abs() < 1e-9, "{gas}");
        assert!((gas * 0.0125278).abs() < 1.0);
    }

    #[test]
    fn a_species_finds_its_row_by_code_assignment_genus_or_tree_type() {
        let r = region("InlVal").unwrap();
        assert_eq!(
            r.resolve("CICA", "Cinnamomum camphora", "BEM").unwrap(),
            ("CICA".into(), Match::Species)
        );
        // Not measured in Modesto: another Pyrus of the same type, else its type's class.
        let (row, how) = r.resolve("PYXX", "Pyrus imaginaria", "BDM").unwrap();
        assert_eq!(
            (row.as_str(), how),
            ("PYCA_B", Match::Genus("PYCA_B".into()))
        );
        let (row, how) = r.resolve("ZZZZ", "Nullus nemo", "BES").unwrap();
        assert_eq!((row.as_str(), how), ("BES OTHER", Match::TreeType));
        // Boise lists no broadleaf evergreens at all: nothing, not a guess.
        assert!(
            region("TpIntW")
                .unwrap()
                .resolve("ZZZZ", "Nullus nemo", "BEM")
                .is_none()
        );
        // Every species of every region resolves to a row with every factor.
        for (name, r) in regions() {
            for s in r.species() {
                let (row, _) = r
                    .resolve(&s.code, &s.scientific_name, &s.tree_type)
                    .unwrap();
                assert!(
                    r.value(Factor::Co2Storage, &row, 30.0).is_some(),
                    "{name} {s:?}"
                );
            }
        }
        assert_eq!(reference_region("SacVal").unwrap().0, "InlVal");
        assert_eq!(reference_region("NoEast").unwrap(), ("NoEast", None));
        assert!(reference_region("Atlantis").is_none());
    }

    /// Every species Sylva can grow finds a row in its region's reference (the Sacramento Valley
    /// through the Inland Valleys), and most of them their own.
    #[test]
    fn every_growable_species_has_a_reference_row() {
        let db = crate::growth::Database::builtin();
        let mut counts = [0usize; 4];
        for region in db.regions() {
            let (name, _) = reference_region(&region.code).unwrap();
            let r = super::region(name).unwrap();
            for s in db.growable(&region.code) {
                let (_, how) = r
                    .resolve(&s.code, &s.scientific, &s.tree_type)
                    .unwrap_or_else(|| {
                        panic!("{} {} ({}): no row", region.code, s.code, s.tree_type)
                    });
                counts[match how {
                    Match::Species => 0,
                    Match::Assigned => 1,
                    Match::Genus(_) => 2,
                    Match::TreeType => 3,
                }] += 1;
            }
        }
        eprintln!("own row, assigned, genus, tree type: {counts:?}");
        assert!(counts[0] > counts[2] + counts[3], "{counts:?}");
    }

    #[test]
    fn outside_the_classes_the_end_value_is_held_and_said() {
        let r = region("InlVal").unwrap();
        let small = r.value(Factor::Electricity, "PLAC", 1.0).unwrap();
        let first = r.value(Factor::Electricity, "PLAC", 3.81).unwrap();
        assert!(small.held && !first.held && small.value == first.value);
        let big = r.value(Factor::Electricity, "PLAC", 150.0).unwrap();
        let last = r.value(Factor::Electricity, "PLAC", 114.3).unwrap();
        assert!(big.held && !last.held && big.value == last.value);
        // Halfway between two midpoints, halfway between their values.
        let a = r.value(Factor::Lsa, "PLAC", 22.86).unwrap().value;
        let b = r.value(Factor::Lsa, "PLAC", 38.10).unwrap().value;
        let mid = r
            .value(Factor::Lsa, "PLAC", (22.86 + 38.10) / 2.0)
            .unwrap()
            .value;
        assert!((mid - (a + b) / 2.0).abs() < 1e-9);
        assert!(r.value(Factor::Lsa, "NO SUCH", 20.0).is_none());
    }
}
