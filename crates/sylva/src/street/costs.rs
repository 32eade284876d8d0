//! What a street tree costs to plant and keep, year by year: a city's itemised costs from a
//! TOML file, or a programme's published average per tree.
//!
//! Built in is one published municipal figure: Modesto spent $2.6 million on its urban forest
//! in fiscal year 1997-98, $28.77 per public tree, 74% of it on the care of mature trees
//! (McPherson, Simpson, Peper & Xiao 1999, "Benefit-cost analysis of Modesto's municipal urban
//! forest", Journal of Arboriculture 25(5):235-248). It is a population's average, not sized
//! by the tree, and charged as such every year; the community tree guides' itemised tables
//! (planting, pruning by size class and cycle, removal, sidewalk repair, clean-up) could not be
//! read for this release, so itemised costs come from `--costs costs.toml` (docs/benefits.md).

use super::StreetError;
use super::prices::{non_negative, parse, read, value};
use serde::Deserialize;
use std::path::Path;

/// Pruning price of one size class.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Pruning {
    /// The class holds trees up to this DBH, cm.
    pub up_to_dbh_cm: f64,
    /// Price of one pruning, $.
    pub price: f64,
    /// Years between prunings.
    pub cycle_years: f64,
}

/// A city's costs, item by item, dollars.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Itemised {
    /// Where the costs come from.
    pub source: String,
    /// The year of the dollars.
    pub year: u32,
    /// Buying and planting, once, in the first year.
    pub planting: f64,
    /// Watering and care per year while the tree establishes.
    pub establishment_per_year: f64,
    /// How many years establishment lasts.
    pub establishment_years: f64,
    /// Pruning by size class, smallest first.
    pub pruning: Vec<Pruning>,
    /// Removal and stump grinding, $ per cm of DBH.
    pub removal_per_cm_dbh: f64,
    /// Chance a year that the tree must come out (storm, decline): the yearly removal cost is
    /// this chance times the removal price.
    pub removal_chance_per_year: f64,
    /// Sidewalk and curb repair charged to the tree per year.
    pub sidewalk_repair_per_year: f64,
    /// Leaf, litter and storm clean-up per year.
    pub cleanup_per_year: f64,
}

/// A programme's average cost per tree and year.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Average {
    /// Where the figure comes from.
    pub source: String,
    /// The year of the dollars.
    pub year: u32,
    /// Dollars per tree per year.
    pub per_tree_per_year: f64,
}

/// What a tree costs.
#[derive(Clone, Debug, PartialEq)]
pub enum Costs {
    /// Item by item.
    Itemised(Itemised),
    /// A programme's average, the same every year.
    Average(Average),
}

/// One year's costs of one tree, dollars.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct YearCosts {
    /// Planting and establishment.
    pub planting: f64,
    /// Pruning.
    pub pruning: f64,
    /// Expected removal.
    pub removal: f64,
    /// Sidewalk repair.
    pub sidewalk: f64,
    /// Clean-up.
    pub cleanup: f64,
    /// A programme's average, where no items are known.
    pub average: f64,
    /// The pruning cycles the site's regime cut this year, where the tree was grown with it
    /// (`street::pruner`); with itemised costs they replace `pruning`.
    pub cycles: f64,
}

impl YearCosts {
    /// All of them.
    pub fn total(&self) -> f64 {
        self.planting
            + self.pruning
            + self.removal
            + self.sidewalk
            + self.cleanup
            + self.average
            + self.cycles
    }
}

impl Costs {
    /// The built-in costs of a region: Modesto's programme average for the Inland Valleys,
    /// none elsewhere.
    pub fn builtin(region: &str) -> Option<Costs> {
        (region == "InlVal").then(|| {
            Costs::Average(Average {
                source: "Modesto's urban forestry spending per public tree, fiscal year \
                         1997-98 (McPherson, Simpson, Peper & Xiao 1999)"
                    .into(),
                year: 1998,
                per_tree_per_year: 28.77,
            })
        })
    }

    /// Where the costs come from.
    pub fn source(&self) -> &str {
        match self {
            Costs::Itemised(c) => &c.source,
            Costs::Average(a) => &a.source,
        }
    }

    /// Reads and checks a costs file: itemised, or `per_tree_per_year` with its source and
    /// year.
    pub fn load(path: &Path) -> Result<Costs, StreetError> {
        let file = path.display().to_string();
        let text = read(path)?;
        let average = text
            .parse::<toml::Table>()
            .is_ok_and(|t| t.contains_key("per_tree_per_year"));
        if average {
            let a: Average = parse(&text, &file)?;
            non_negative(&file, "per_tree_per_year", a.per_tree_per_year)?;
            return Ok(Costs::Average(a));
        }
        let costs: Itemised = parse(&text, &file)?;
        for (key, v) in [
            ("planting", costs.planting),
            ("establishment_per_year", costs.establishment_per_year),
            ("establishment_years", costs.establishment_years),
            ("removal_per_cm_dbh", costs.removal_per_cm_dbh),
            ("sidewalk_repair_per_year", costs.sidewalk_repair_per_year),
            ("cleanup_per_year", costs.cleanup_per_year),
        ] {
            non_negative(&file, key, v)?;
        }
        if !(0.0..=1.0).contains(&costs.removal_chance_per_year) {
            return Err(value(
                &file,
                "removal_chance_per_year",
                costs.removal_chance_per_year,
                "a chance, 0 to 1",
            ));
        }
        if costs.pruning.is_empty() {
            return Err(value(
                &file,
                "pruning",
                0.0,
                "at least one [[pruning]] class",
            ));
        }
        let mut last = 0.0;
        for p in &costs.pruning {
            non_negative(&file, "pruning.price", p.price)?;
            if !(1.0..=100.0).contains(&p.cycle_years) {
                return Err(value(
                    &file,
                    "pruning.cycle_years",
                    p.cycle_years,
                    "1 to 100 years",
                ));
            }
            if !(p.up_to_dbh_cm > last && p.up_to_dbh_cm.is_finite()) {
                return Err(value(
                    &file,
                    "pruning.up_to_dbh_cm",
                    p.up_to_dbh_cm,
                    "classes in rising order of DBH, cm",
                ));
            }
            last = p.up_to_dbh_cm;
        }
        Ok(Costs::Itemised(costs))
    }

    /// The costs of the year that ends at `age`, for a tree of `dbh_cm`.
    pub fn year(&self, age: f64, dbh_cm: f64) -> YearCosts {
        let c = match self {
            Costs::Average(a) => {
                return YearCosts {
                    average: a.per_tree_per_year,
                    ..Default::default()
                };
            }
            Costs::Itemised(c) => c,
        };
        let planting = if age <= 1.0 { c.planting } else { 0.0 }
            + if age <= c.establishment_years {
                c.establishment_per_year
            } else {
                0.0
            };
        let class = c
            .pruning
            .iter()
            .find(|p| dbh_cm <= p.up_to_dbh_cm)
            .or(c.pruning.last());
        YearCosts {
            planting,
            pruning: class.map_or(0.0, |p| p.price / p.cycle_years),
            removal: c.removal_chance_per_year * c.removal_per_cm_dbh * dbh_cm,
            sidewalk: c.sidewalk_repair_per_year,
            cleanup: c.cleanup_per_year,
            average: 0.0,
            cycles: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn itemised_costs_by_year_and_their_errors() {
        let dir = tempfile::tempdir().unwrap();
        let costs = dir.path().join("costs.toml");
        let good = "source = \"test\"\nyear = 2024\nplanting = 200.0\nestablishment_per_year = 50.0\nestablishment_years = 3\nremoval_per_cm_dbh = 20.0\nremoval_chance_per_year = 0.01\nsidewalk_repair_per_year = 4.0\ncleanup_per_year = 3.0\n[[pruning]]\nup_to_dbh_cm = 15.0\nprice = 30.0\ncycle_years = 3\n[[pruning]]\nup_to_dbh_cm = 200.0\nprice = 300.0\ncycle_years = 5\n";
        std::fs::write(&costs, good).unwrap();
        let c = Costs::load(&costs).unwrap();
        assert!(matches!(c, Costs::Itemised(_)));
        let y = c.year(1.0, 2.0);
        assert_eq!(y.planting, 250.0);
        assert_eq!(y.pruning, 10.0);
        let y = c.year(20.0, 40.0);
        assert_eq!(y.planting, 0.0);
        assert_eq!(y.pruning, 60.0);
        assert!((y.removal - 8.0).abs() < 1e-12);
        assert!((y.total() - (60.0 + 8.0 + 4.0 + 3.0)).abs() < 1e-12);
        std::fs::write(&costs, good.replace("cycle_years = 5", "cycle_years = 0")).unwrap();
        let e = Costs::load(&costs).unwrap_err().to_string();
        assert!(e.contains("pruning.cycle_years"), "{e}");
        std::fs::write(&costs, good.replace("cleanup_per_year = 3.0\n", "")).unwrap();
        let e = Costs::load(&costs).unwrap_err().to_string();
        assert!(
            e.contains("costs.toml") && e.contains("cleanup_per_year"),
            "{e}"
        );
    }

    #[test]
    fn an_average_is_charged_every_year_and_modesto_has_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("avg.toml");
        std::fs::write(
            &path,
            "source = \"x\"\nyear = 2020\nper_tree_per_year = 40.0\n",
        )
        .unwrap();
        let c = Costs::load(&path).unwrap();
        assert_eq!(c.year(1.0, 2.0).total(), 40.0);
        assert_eq!(c.year(30.0, 50.0).total(), 40.0);
        std::fs::write(
            &path,
            "source = \"x\"\nyear = 2020\nper_tree_per_year = -4.0\n",
        )
        .unwrap();
        let e = Costs::load(&path).unwrap_err().to_string();
        assert!(
            e.contains("avg.toml") && e.contains("per_tree_per_year"),
            "{e}"
        );
        std::fs::write(&path, "source = \"x\"\nper_tree_per_year = 4.0\n").unwrap();
        let e = Costs::load(&path).unwrap_err().to_string();
        assert!(e.contains("year"), "{e}");
        let modesto = Costs::builtin("InlVal").unwrap();
        assert_eq!(modesto.year(10.0, 20.0).average, 28.77);
        assert!(modesto.source().contains("1997-98"));
        assert!(Costs::builtin("GulfCo").is_none());
    }
}
