//! The USDA Urban Tree Database's growth equations (tables TS1, TS2 and TS6), built in or read
//! from a folder, and the lookup of a species in a region by code, scientific or common name.

use crate::growth::data::equations::{Equation, Form};
use crate::growth::error::GrowthError;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::OnceLock;

/// A quantity the database relates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// Years since planting.
    Age,
    /// Trunk diameter at breast height (1.37 m), cm.
    Dbh,
    /// Tree height, m.
    Height,
    /// Crown diameter, m.
    CrownDiameter,
    /// Crown height (tree height minus height to crown base), m.
    CrownHeight,
    /// One-sided leaf area, m².
    LeafArea,
}

impl Quantity {
    /// The database's spelling of this quantity in the "Independent variable" and "Predicts
    /// component" columns (`cdia` is the crown diameter as an input).
    fn parse(s: &str) -> Option<Quantity> {
        Some(match s.trim().to_ascii_lowercase().as_str() {
            "age" => Quantity::Age,
            "dbh" => Quantity::Dbh,
            "tree ht" => Quantity::Height,
            "crown dia" | "cdia" => Quantity::CrownDiameter,
            "crown ht" => Quantity::CrownHeight,
            "leaf area" => Quantity::LeafArea,
            _ => return None,
        })
    }

    /// Name for messages.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Age => "age",
            Quantity::Dbh => "DBH",
            Quantity::Height => "height",
            Quantity::CrownDiameter => "crown diameter",
            Quantity::CrownHeight => "crown height",
            Quantity::LeafArea => "leaf area",
        }
    }
}

/// One fitted equation of table TS6.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Region code (`InlVal`).
    pub region: String,
    /// Scientific name.
    pub scientific: String,
    /// Species code (`PLAC`).
    pub code: String,
    /// What the equation takes.
    pub input: Quantity,
    /// What it predicts.
    pub output: Quantity,
    /// The equation.
    pub equation: Equation,
    /// `Some(n)` for an equation the database does not publish, fitted by Sylva to `n` of its
    /// raw measured trees (a palm's age→DBH: see `palm_ages.rs`).
    pub fitted_to: Option<usize>,
}

/// A species as table TS2 lists it in one region.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeciesEntry {
    /// Region code.
    pub region: String,
    /// Species code.
    pub code: String,
    /// Scientific name.
    pub scientific: String,
    /// Common name.
    pub common: String,
    /// The database's tree type: B/C (broadleaf, conifer), D/E (deciduous, evergreen), S/M/L
    /// (mature size); palms are `PES`, `PEM`, ...
    pub tree_type: String,
    /// Trees the survey measured in each of the nine DBH classes ([`DBH_CLASS_EDGES_CM`]);
    /// all 0 for a species with equations but no line in TS2.
    pub trees_by_dbh_class: [u32; 9],
}

/// Upper edges of table TS2's nine DBH classes, cm: 3, 6, 12, 18, 24, 30, 36 and 42 inches,
/// the last class open. (Checked against the raw data: TS3's London planes of Modesto binned at
/// these edges give TS2's counts, 2, 0, 10, 7, 5, 3.)
pub const DBH_CLASS_EDGES_CM: [f64; 8] = [7.62, 15.24, 30.48, 45.72, 60.96, 76.2, 91.44, 106.68];

/// A climate region of table TS1.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Code as the equations use it (spaces removed: TS1 writes `Cen Fla`, TS6 `CenFla`).
    pub code: String,
    /// Name (`Inland Valleys`).
    pub name: String,
    /// Reference city (`Modesto`).
    pub city: String,
}

/// The growth equations of every region and species.
#[derive(Clone, Debug, Default)]
pub struct Database {
    rows: Vec<Row>,
    species: Vec<SpeciesEntry>,
    regions: Vec<Region>,
}

const TS6: &str = "TS6_Growth_coefficients.csv";
const TS2: &str = "TS2_Regional_species_and_counts.csv";
const TS1: &str = "TS1_Regional_information.csv";
/// The raw measurements, whole (as published) or only their palm rows (as built in).
const TS3: [&str; 2] = ["TS3_Raw_tree_data.csv", "TS3_palm_ages.csv"];

impl Database {
    /// The database shipped inside the library (2,402 equations, 17 regions).
    pub fn builtin() -> &'static Database {
        static DB: OnceLock<Database> = OnceLock::new();
        DB.get_or_init(|| {
            let dir = "data/urban-tree-database";
            let mut db = Database::parse(
                include_str!("../../../data/urban-tree-database/TS6_Growth_coefficients.csv"),
                include_str!(
                    "../../../data/urban-tree-database/TS2_Regional_species_and_counts.csv"
                ),
                include_str!("../../../data/urban-tree-database/TS1_Regional_information.csv"),
                dir,
            )
            .expect("the built-in Urban Tree Database parses (tested)");
            db.fit_palm_ages(
                include_str!("../../../data/urban-tree-database/TS3_palm_ages.csv"),
                &format!("{dir}/{}", TS3[1]),
            )
            .expect("the built-in palm measurements parse (tested)");
            db
        })
    }

    /// Reads the three tables from a folder holding the database's CSV files.
    pub fn from_dir(dir: &Path) -> Result<Database, GrowthError> {
        let read = |name: &str| {
            let path = dir.join(name);
            std::fs::read_to_string(&path).map_err(|e| GrowthError::Io {
                path: path.display().to_string(),
                message: e.to_string(),
            })
        };
        let mut db = Database::parse(
            &read(TS6)?,
            &read(TS2)?,
            &read(TS1)?,
            &dir.display().to_string(),
        )?;
        // The raw trees are optional: without them the palms cannot be grown.
        if let Some(name) = TS3.iter().find(|n| dir.join(n).is_file()) {
            db.fit_palm_ages(&read(name)?, &dir.join(name).display().to_string())?;
        }
        Ok(db)
    }

    /// Adds an age→DBH for every palm that has none, fitted to its raw measured trees
    /// (`raw`: TS3 or its palm rows, read from `source`).
    fn fit_palm_ages(&mut self, raw: &str, source: &str) -> Result<(), GrowthError> {
        for fit in super::palm_ages::fit_palm_ages(raw, source)? {
            let published = self.rows.iter().any(|r| {
                r.region == fit.region
                    && r.code == fit.code
                    && (r.input, r.output) == (Quantity::Age, Quantity::Dbh)
            });
            // A palm without DBH equations could not be grown by its age anyway.
            let Some(scientific) = self
                .rows
                .iter()
                .find(|r| r.region == fit.region && r.code == fit.code)
                .map(|r| r.scientific.clone())
            else {
                continue;
            };
            if !published {
                self.rows.push(Row {
                    region: fit.region,
                    scientific,
                    code: fit.code,
                    input: Quantity::Age,
                    output: Quantity::Dbh,
                    equation: fit.equation,
                    fitted_to: Some(fit.trees),
                });
            }
        }
        Ok(())
    }

    /// Parses the tables' text; `source` names the folder in messages.
    pub fn parse(ts6: &str, ts2: &str, ts1: &str, source: &str) -> Result<Database, GrowthError> {
        let mut db = Database::default();
        for (line, record) in records(ts6, &format!("{source}/{TS6}"))? {
            let at = |message: String| GrowthError::Syntax {
                file: format!("{source}/{TS6}"),
                line,
                message,
            };
            let field = |i: usize| record.get(i).map(str::trim).unwrap_or("");
            let number = |i: usize, name: &str| -> Result<f64, GrowthError> {
                let s = field(i);
                if s.is_empty() {
                    return Ok(0.0);
                }
                s.parse::<f64>()
                    .map_err(|_| at(format!("column {name} is `{s}`, expected a number")))
            };
            let quantity = |i: usize, name: &str| {
                Quantity::parse(field(i)).ok_or_else(|| {
                    at(format!(
                        "column {name} is `{}`, expected age, dbh, cdia, tree ht, crown dia, \
                         crown ht or leaf area",
                        field(i)
                    ))
                })
            };
            let form = Form::from_name(field(7)).ok_or_else(|| {
                at(format!(
                    "EqName is `{}`, expected one of {}",
                    field(7),
                    Form::ALL.map(Form::name).join(", ")
                ))
            })?;
            let coefficients = [
                number(8, "a")?,
                number(9, "b")?,
                number(10, "c")?,
                number(11, "d")?,
                number(12, "e")?,
            ];
            // The bias term of the log and exponential forms is column c, except in the rows
            // that fill column d too (some SacVal dbh->age fits): then it is d.
            let mse = if form.is_polynomial() {
                0.0
            } else if !field(11).is_empty() {
                coefficients[3]
            } else {
                coefficients[2]
            };
            db.rows.push(Row {
                region: field(0).replace(' ', ""),
                scientific: field(1).to_string(),
                code: field(2).to_string(),
                input: quantity(3, "Independent variable")?,
                output: quantity(4, "Predicts component")?,
                equation: Equation {
                    form,
                    coefficients,
                    mse,
                    range: (number(13, "Apps min")?, number(14, "Apps max")?),
                },
                fitted_to: None,
            });
        }
        for (line, r) in records(ts2, &format!("{source}/{TS2}"))? {
            let f = |i: usize| r.get(i).map(str::trim).unwrap_or("").to_string();
            // Empty class cells hold no trees; a count that is not a whole number is an error.
            let mut trees_by_dbh_class = [0u32; 9];
            for (k, n) in trees_by_dbh_class.iter_mut().enumerate() {
                let cell = f(5 + k);
                if !cell.is_empty() {
                    *n = cell.parse().map_err(|_| GrowthError::Syntax {
                        file: format!("{source}/{TS2}"),
                        line,
                        message: format!("Dbh_class{} is `{cell}`, expected a count", k + 1),
                    })?;
                }
            }
            db.species.push(SpeciesEntry {
                region: f(0).replace(' ', ""),
                scientific: f(1),
                common: f(2),
                code: f(3),
                tree_type: f(4),
                trees_by_dbh_class,
            });
        }
        // A few species have equations but no TS2 line (the palm WARO in InlVal): list them
        // under their scientific name so that they can still be found.
        let mut listed: std::collections::HashSet<(String, String)> = db
            .species
            .iter()
            .map(|s| (s.region.clone(), s.code.clone()))
            .collect();
        for r in &db.rows {
            if listed.insert((r.region.clone(), r.code.clone())) {
                db.species.push(SpeciesEntry {
                    region: r.region.clone(),
                    code: r.code.clone(),
                    scientific: r.scientific.clone(),
                    common: r.scientific.clone(),
                    tree_type: String::new(),
                    trees_by_dbh_class: [0; 9],
                });
            }
        }
        for (_, r) in records(ts1, &format!("{source}/{TS1}"))? {
            let f = |i: usize| r.get(i).map(str::trim).unwrap_or("").to_string();
            db.regions.push(Region {
                code: f(0).replace(' ', ""),
                name: f(1),
                city: f(2),
            });
        }
        if db.rows.is_empty() {
            return Err(GrowthError::Syntax {
                file: format!("{source}/{TS6}"),
                line: 1,
                message: "no equations".into(),
            });
        }
        Ok(db)
    }

    /// Every equation.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The regions.
    pub fn regions(&self) -> &[Region] {
        &self.regions
    }

    /// Every species of every region.
    pub fn species(&self) -> &[SpeciesEntry] {
        &self.species
    }

    /// Species of a region that have the five equations growth needs (age→DBH and DBH→height,
    /// crown diameter, crown height, leaf area).
    pub fn growable(&self, region: &str) -> Vec<&SpeciesEntry> {
        self.species
            .iter()
            .filter(|s| s.region.eq_ignore_ascii_case(region))
            .filter(|s| self.equations(&s.region, &s.code).is_ok())
            .collect()
    }

    /// A species' entry, its region and its five equations: what [`Database::find`] makes a
    /// [`crate::growth::Measured`] of. `query` is a species code (`PLAC`), a scientific name
    /// (`Platanus x acerifolia`) or a common name (`London planetree`), in any case, with `_`
    /// or `-` for spaces.
    pub(super) fn lookup(
        &self,
        region: &str,
        query: &str,
    ) -> Result<(SpeciesEntry, Region, [Equation; 5]), GrowthError> {
        let region = self
            .regions
            .iter()
            .find(|r| r.code.eq_ignore_ascii_case(&region.replace(' ', "")))
            .ok_or_else(|| GrowthError::UnknownRegion {
                region: region.to_string(),
                known: self
                    .regions
                    .iter()
                    .map(|r| format!("{} ({})", r.code, r.city))
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
        let key = normalise(query);
        let in_region: Vec<&SpeciesEntry> = self
            .species
            .iter()
            .filter(|s| s.region == region.code)
            .collect();
        // Suggestions name only species that can be grown (all five equations).
        let growable: Vec<&SpeciesEntry> = in_region
            .iter()
            .copied()
            .filter(|s| self.equations(&s.region, &s.code).is_ok())
            .collect();
        let entry = in_region
            .iter()
            .find(|s| {
                normalise(&s.code) == key
                    || normalise(&s.scientific) == key
                    || normalise(&s.common) == key
            })
            .ok_or_else(|| {
                let mut close: Vec<String> = growable
                    .iter()
                    .filter(|s| {
                        [&s.code, &s.scientific, &s.common]
                            .iter()
                            .any(|n| normalise(n).contains(&key) || key.contains(&normalise(n)))
                    })
                    .map(|s| format!("{} ({})", s.code, s.common))
                    .collect();
                if close.is_empty() {
                    close = growable
                        .iter()
                        .map(|s| format!("{} ({})", s.code, s.common))
                        .collect();
                }
                GrowthError::UnknownSpecies {
                    query: query.to_string(),
                    region: region.code.clone(),
                    candidates: close.join(", "),
                }
            })?;
        let eqs = self.equations(&entry.region, &entry.code)?;
        Ok(((*entry).clone(), region.clone(), eqs))
    }

    /// The five equations growth needs, in the order age→DBH, DBH→height, DBH→crown diameter,
    /// DBH→crown height, DBH→leaf area.
    fn equations(&self, region: &str, code: &str) -> Result<[Equation; 5], GrowthError> {
        let wanted = [
            (Quantity::Age, Quantity::Dbh),
            (Quantity::Dbh, Quantity::Height),
            (Quantity::Dbh, Quantity::CrownDiameter),
            (Quantity::Dbh, Quantity::CrownHeight),
            (Quantity::Dbh, Quantity::LeafArea),
        ];
        let mut found: BTreeMap<(Quantity, Quantity), Equation> = BTreeMap::new();
        for r in self
            .rows
            .iter()
            .filter(|r| r.region == region && r.code == code)
        {
            found.entry((r.input, r.output)).or_insert(r.equation);
        }
        let mut out = Vec::with_capacity(5);
        for (i, o) in wanted {
            out.push(
                *found
                    .get(&(i, o))
                    .ok_or_else(|| GrowthError::MissingEquation {
                        code: code.to_string(),
                        region: region.to_string(),
                        which: format!("{} -> {}", i.name(), o.name()),
                    })?,
            );
        }
        Ok([out[0], out[1], out[2], out[3], out[4]])
    }
}

/// Lower case, with `_`, `-` and runs of spaces as one space, and quotes dropped.
fn normalise(s: &str) -> String {
    s.to_lowercase()
        .replace(['_', '-'], " ")
        .replace(['\'', '"'], "")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Data records of a CSV text (header skipped) with their 1-based line numbers.
fn records(text: &str, source: &str) -> Result<Vec<(usize, csv::StringRecord)>, GrowthError> {
    let text = text.trim_start_matches('\u{feff}');
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut out = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| GrowthError::Syntax {
            file: source.to_string(),
            line: e.position().map_or(0, |p| p.line() as usize),
            message: e.to_string(),
        })?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        if record.iter().all(|f| f.trim().is_empty()) {
            continue;
        }
        out.push((line, record));
    }
    Ok(out)
}
