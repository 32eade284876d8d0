//! What a street tree costs to plant and keep, year by year, sized by the tree: planting,
//! pruning visits priced by DBH on a cycle, removal by DBH when the tree dies, and the yearly
//! items (sidewalk repair, clean-up, pest management, liability, administration) a city's own
//! table gives; or a programme's published average per tree.
//!
//! Built in for every region is `data/street/costs.toml`, in the same format as `--costs`:
//! each item the nearest published source found (planting in Davis, CA; pruning time per inch
//! of DBH from Churack et al. 1994 at a 2012 California contract's hourly rate; removal by DBH
//! from four Midwest states; sidewalk repair from Berkeley), named in the file and in every
//! report. Modesto's programme average, $28.77 a tree a year in fiscal 1997-98 (McPherson,
//! Simpson, Peper & Xiao 1999, Journal of Arboriculture 25(5):235-248), stays available as
//! [`Costs::modesto_average`]: about half of it was pruning (McPherson & Simpson 2002, Urban
//! Forestry & Urban Greening 1(2)), so where a site's cycles are charged the average drops that
//! share and no cut is paid for twice.
//!
//! Every figure is per *living* tree: a tree that dies costs its removal, charged as the
//! year's chance of dying (street::accounts::survival) times the removal price at its DBH, so that
//! weighting a year by the share alive gives the cost per tree planted.

use crate::street::accounts::items::{Cost, Payer};
use crate::street::accounts::prices::{non_negative, parse, read, value};
use crate::street::error::StreetError;
use crate::street::site::{Access, Mitigation};
use serde::Deserialize;
use std::path::Path;

/// One DBH class of a cost table.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Class {
    /// The class starts at this DBH, cm (default: where the class before it ends, or 0).
    pub from_dbh_cm: Option<f64>,
    /// The class holds trees up to this DBH, cm.
    pub up_to_dbh_cm: f64,
    /// Price of one visit (pruning) or of the job (removal), $.
    pub price: Option<f64>,
    /// Or a price per cm of the tree's DBH, $.
    pub price_per_cm_dbh: Option<f64>,
    /// Years between prunings (pruning classes only).
    pub cycle_years: Option<f64>,
    /// A utility's price of a tree worked from behind buildings, by a climbing crew
    /// (line-clearance classes only; `price` is then the street crew's).
    pub backyard_price: Option<f64>,
}

impl Class {
    /// The price for a tree of `dbh_cm`.
    fn price_at(&self, dbh_cm: f64) -> f64 {
        self.price.unwrap_or(0.0) + self.price_per_cm_dbh.unwrap_or(0.0) * dbh_cm
    }
}

/// A city's costs, item by item, dollars.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Itemised {
    /// The file the table was read from (errors name it).
    #[serde(skip)]
    pub file: String,
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
    /// Pruning by DBH class, smallest first, each with its cycle.
    pub pruning: Vec<Class>,
    /// Removal and stump by DBH class, smallest first (or `removal_per_cm_dbh`).
    #[serde(default)]
    pub removal: Vec<Class>,
    /// Removal and stump grinding, $ per cm of DBH (where no `[[removal]]` classes are given).
    pub removal_per_cm_dbh: Option<f64>,
    /// The utility's price of one line-clearance visit to a tree (a tree worked), by DBH
    /// class; the built-in table's where a table gives none (the utility's price is not the
    /// city's).
    #[serde(default)]
    pub line_clearance: Vec<Class>,
    /// A fixed chance a year that a living tree must come out (storm, decline). Without it the
    /// chance is the run's survival's.
    pub removal_chance_per_year: Option<f64>,
    /// Sidewalk, curb and sewer repair charged to the tree per year, a flat figure (a city's
    /// own average): where the tree's place is not known, or the table has no
    /// `[sidewalk_damage]`.
    pub sidewalk_repair_per_year: Option<f64>,
    /// Sidewalk and curb damage priced per repair, by the tree's chance of damaging the
    /// pavement each year (`street::work::roots`), where the tree's site is known.
    pub sidewalk_damage: Option<SidewalkDamage>,
    /// Sewer repair charged to the tree per year where `[sidewalk_damage]` prices the
    /// sidewalk and curb (the flat figure holds it otherwise).
    pub sewer_repair_per_year: Option<f64>,
    /// Prices of what a site may do at planting to spare its pavement (`[mitigation]` of the
    /// site); the built-in table's where a table gives none.
    pub mitigation: Option<MitigationPrices>,
    /// Leaf, litter and storm clean-up per year.
    pub cleanup_per_year: Option<f64>,
    /// Pest and disease management per year.
    pub pest_per_year: Option<f64>,
    /// Liability and legal per year.
    pub liability_per_year: Option<f64>,
    /// Administration and inspection per year.
    pub administration_per_year: Option<f64>,
}

/// Sidewalk and curb damage priced per repair: the yearly chance that the tree's roots damage
/// the pavement (`street::work::roots`) times what a repair costs, split between the city and
/// the property owners, with the trip-and-fall claims and the administration that come with
/// repairs.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SidewalkDamage {
    /// One repair of the sidewalk beside a tree, $.
    pub repair_per_incident: f64,
    /// Curb and gutter repair per dollar of sidewalk repair.
    pub curb_per_sidewalk: f64,
    /// The share of sidewalk repair the property owners pay, 0 to 1.
    pub owners_share_sidewalk: f64,
    /// The share of curb and gutter repair the property owners pay, 0 to 1.
    pub owners_share_curb: f64,
    /// Trip-and-fall payments and legal staff per dollar of repair (the city's).
    pub liability_per_repair: f64,
    /// Inspection and administration of repairs per dollar of repair (the city's).
    pub administration_per_repair: f64,
}

impl SidewalkDamage {
    /// Sidewalk and curb repair per incident, the city's and the owners', and the city's
    /// liability and administration with it, $.
    fn split(&self) -> (f64, f64, f64) {
        let sidewalk = self.repair_per_incident;
        let curb = sidewalk * self.curb_per_sidewalk;
        let owners = sidewalk * self.owners_share_sidewalk + curb * self.owners_share_curb;
        let city = sidewalk + curb - owners;
        let with = (sidewalk + curb) * (self.liability_per_repair + self.administration_per_repair);
        (city, owners, with)
    }
}

/// Prices of the mitigations a site may choose (`site.rs`'s `Mitigation`), $.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MitigationPrices {
    /// A linear root barrier installed, per metre.
    pub root_barrier_per_m: Option<f64>,
    /// Pavement removed for a larger bed, a cut-out or a curving sidewalk, per m².
    pub cutout_per_m2: Option<f64>,
    /// Rubber or modular pavers laid instead of concrete, more per m² than concrete.
    pub flexible_pavement_per_m2: Option<f64>,
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
    /// The share of it spent on pruning (0 to 1), dropped where a site's cycles are charged.
    #[serde(default)]
    pub pruning_share: f64,
}

/// What a tree costs.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // a run holds one, read every year: no box to chase
pub enum Costs {
    /// Item by item.
    Itemised(Itemised),
    /// A programme's average, the same every year.
    Average(Average),
}

/// One year's costs of one living tree, dollars, by item (`items.rs`'s [`Cost`]: its key,
/// label and who pays it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct YearCosts([f64; Cost::COUNT]);

impl std::ops::Index<Cost> for YearCosts {
    type Output = f64;
    fn index(&self, item: Cost) -> &f64 {
        &self.0[item as usize]
    }
}

impl std::ops::IndexMut<Cost> for YearCosts {
    fn index_mut(&mut self, item: Cost) -> &mut f64 {
        &mut self.0[item as usize]
    }
}

impl YearCosts {
    /// Every item with its dollars, in report order.
    pub fn items(&self) -> impl Iterator<Item = (Cost, f64)> + '_ {
        Cost::ALL.into_iter().map(|c| (c, self[c]))
    }

    /// All of them, whoever pays.
    pub fn total(&self) -> f64 {
        self.0.iter().sum()
    }

    /// What `payer` pays.
    pub fn paid_by(&self, payer: Payer) -> f64 {
        self.items()
            .filter(|(c, _)| c.payer() == payer)
            .map(|(_, v)| v)
            .sum()
    }

    /// Per tree planted, where `alive` of the trees planted stand through the year: planting
    /// (and what is done at planting) is paid for every tree planted, the rest for the living.
    pub fn per_planted(&self, alive: f64) -> f64 {
        let planting: f64 = (self.items())
            .filter(|(c, _)| c.at_planting())
            .map(|(_, v)| v)
            .sum();
        planting + alive * (self.total() - planting)
    }
}

/// The built-in table, embedded.
const BUILTIN: &str = include_str!("../../../data/street/costs.toml");

impl Costs {
    /// The built-in costs, the same table for every region (see the module's notes).
    pub fn builtin(_region: &str) -> Option<Costs> {
        Some(Costs::sized().clone())
    }

    /// The built-in sized table, parsed once.
    pub fn sized() -> &'static Costs {
        static TABLE: std::sync::OnceLock<Costs> = std::sync::OnceLock::new();
        TABLE.get_or_init(|| {
            Costs::parse(BUILTIN, "data/street/costs.toml")
                .expect("the built-in cost table is checked by a test")
        })
    }

    /// Modesto's programme average, half of it pruning.
    pub fn modesto_average() -> Costs {
        Costs::Average(Average {
            source: "Modesto's urban forestry spending per public tree, fiscal year 1997-98 \
                     (McPherson, Simpson, Peper & Xiao 1999); about half of it pruning \
                     (McPherson & Simpson 2002)"
                .into(),
            year: 1998,
            per_tree_per_year: 28.77,
            pruning_share: 0.5,
        })
    }

    /// Where the costs come from.
    pub fn source(&self) -> &str {
        match self {
            Costs::Itemised(c) => &c.source,
            Costs::Average(a) => &a.source,
        }
    }

    /// The items a table leaves out, each said as not computed.
    pub fn not_computed(&self) -> Vec<String> {
        let Costs::Itemised(c) = self else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (name, v) in [
            ("clean-up", c.cleanup_per_year),
            ("pest management", c.pest_per_year),
            ("liability", c.liability_per_year),
            ("administration", c.administration_per_year),
            ("sewer repair", c.sewer_repair_per_year),
        ] {
            if v.is_none() {
                out.push(name);
            }
        }
        if c.removal.is_empty() && c.removal_per_cm_dbh.is_none() {
            out.push("removal");
        }
        if c.sidewalk_repair_per_year.is_none() && c.sidewalk_damage.is_none() {
            out.push("sidewalk repair");
        }
        if out.is_empty() {
            return Vec::new();
        }
        vec![format!(
            "costs of {}: no figure in {} (give --costs with them)",
            out.join(", "),
            c.source.split(':').next().unwrap_or(&c.source)
        )]
    }

    /// Reads and checks a costs file: itemised, or `per_tree_per_year` with its source and
    /// year.
    pub fn load(path: &Path) -> Result<Costs, StreetError> {
        Costs::parse(&read(path)?, &path.display().to_string())
    }

    /// Parses and checks a cost table's text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Costs, StreetError> {
        let average = text
            .parse::<toml::Table>()
            .is_ok_and(|t| t.contains_key("per_tree_per_year"));
        if average {
            let a: Average = parse(text, file)?;
            non_negative(file, "per_tree_per_year", a.per_tree_per_year)?;
            if !(0.0..=1.0).contains(&a.pruning_share) {
                return Err(value(
                    file,
                    "pruning_share",
                    a.pruning_share,
                    "a share, 0 to 1",
                ));
            }
            return Ok(Costs::Average(a));
        }
        let mut costs: Itemised = parse(text, file)?;
        costs.file = file.to_string();
        for (key, v) in [
            ("planting", Some(costs.planting)),
            ("establishment_per_year", Some(costs.establishment_per_year)),
            ("establishment_years", Some(costs.establishment_years)),
            ("removal_per_cm_dbh", costs.removal_per_cm_dbh),
            ("sidewalk_repair_per_year", costs.sidewalk_repair_per_year),
            ("sewer_repair_per_year", costs.sewer_repair_per_year),
            ("cleanup_per_year", costs.cleanup_per_year),
            ("pest_per_year", costs.pest_per_year),
            ("liability_per_year", costs.liability_per_year),
            ("administration_per_year", costs.administration_per_year),
        ] {
            if let Some(v) = v {
                non_negative(file, key, v)?;
            }
        }
        if let Some(chance) = costs.removal_chance_per_year
            && !(0.0..=1.0).contains(&chance)
        {
            return Err(value(
                file,
                "removal_chance_per_year",
                chance,
                "a chance, 0 to 1",
            ));
        }
        if let Some(m) = &costs.mitigation {
            for (key, v) in [
                ("mitigation.root_barrier_per_m", m.root_barrier_per_m),
                ("mitigation.cutout_per_m2", m.cutout_per_m2),
                (
                    "mitigation.flexible_pavement_per_m2",
                    m.flexible_pavement_per_m2,
                ),
            ] {
                if let Some(v) = v {
                    non_negative(file, key, v)?;
                }
            }
        }
        if let Some(d) = &costs.sidewalk_damage {
            for (key, v) in [
                ("sidewalk_damage.repair_per_incident", d.repair_per_incident),
                ("sidewalk_damage.curb_per_sidewalk", d.curb_per_sidewalk),
                (
                    "sidewalk_damage.liability_per_repair",
                    d.liability_per_repair,
                ),
                (
                    "sidewalk_damage.administration_per_repair",
                    d.administration_per_repair,
                ),
            ] {
                non_negative(file, key, v)?;
            }
            for (key, v) in [
                (
                    "sidewalk_damage.owners_share_sidewalk",
                    d.owners_share_sidewalk,
                ),
                ("sidewalk_damage.owners_share_curb", d.owners_share_curb),
            ] {
                if !(0.0..=1.0).contains(&v) {
                    return Err(value(file, key, v, "a share, 0 to 1"));
                }
            }
        }
        if costs.pruning.is_empty() {
            return Err(value(
                file,
                "pruning",
                0.0,
                "at least one [[pruning]] class",
            ));
        }
        check_classes(file, "pruning", &costs.pruning, Table::Pruning)?;
        check_classes(file, "removal", &costs.removal, Table::Removal)?;
        check_classes(file, "line_clearance", &costs.line_clearance, Table::Line)?;
        if !costs.removal.is_empty() && costs.removal_per_cm_dbh.is_some() {
            return Err(StreetError::Syntax {
                file: file.to_string(),
                message: "give removal either as [[removal]] classes or as \
                          removal_per_cm_dbh, not both"
                    .into(),
            });
        }
        Ok(Costs::Itemised(costs))
    }

    /// The price of a pruning visit to a tree of `dbh_cm`, and its cycle in years; none for a
    /// programme average.
    pub fn pruning_visit(&self, dbh_cm: f64) -> Option<(f64, f64)> {
        let Costs::Itemised(c) = self else {
            return None;
        };
        let class = class_of(&c.pruning, dbh_cm)?;
        Some((class.price_at(dbh_cm), class.cycle_years.unwrap_or(1.0)))
    }

    /// The utility's price of one line-clearance visit to a tree of `dbh_cm` that its crew
    /// reaches by `access`: this table's `[[line_clearance]]` classes, else the built-in
    /// table's.
    pub fn line_visit(&self, dbh_cm: f64, access: Access) -> f64 {
        let own = match self {
            Costs::Itemised(c) if !c.line_clearance.is_empty() => Some(&c.line_clearance),
            _ => None,
        };
        let classes = match (own, Costs::sized()) {
            (Some(classes), _) => classes,
            (None, Costs::Itemised(c)) => &c.line_clearance,
            (None, Costs::Average(_)) => return 0.0,
        };
        class_of(classes, dbh_cm).map_or(0.0, |k| match access {
            Access::Backyard => k.backyard_price.unwrap_or_else(|| k.price_at(dbh_cm)),
            Access::Street => k.price_at(dbh_cm),
        })
    }

    /// What a site's mitigations `m` cost at planting, $: each priced by this table, else by
    /// the built-in one. An error names the site's key that asks for a mitigation neither
    /// table prices, the price's key, and the file this table was read from.
    pub fn mitigation(&self, m: &Mitigation) -> Result<f64, String> {
        let price = |asks: &str, key: &str, pick: fn(&MitigationPrices) -> Option<f64>| {
            let table = |c: &Costs| match c {
                Costs::Itemised(c) => c.mitigation.as_ref().and_then(pick),
                Costs::Average(_) => None,
            };
            table(self).or(table(Costs::sized())).ok_or_else(|| {
                let file = match self {
                    Costs::Itemised(c) => c.file.clone(),
                    Costs::Average(a) => a.source.clone(),
                };
                format!(
                    "`mitigation.{asks}` asks for what no price is given for: \
                     `mitigation.{key}` is neither in {file} nor sourced in the built-in \
                     table; give it in a costs file's [mitigation] (--costs)"
                )
            })
        };
        let mut total = 0.0;
        if let Some(length) = m.root_barrier_m {
            total += length
                * price("root_barrier_m", "root_barrier_per_m", |p| {
                    p.root_barrier_per_m
                })?;
        }
        if let Some(area) = m.cutout_m2 {
            total += area * price("cutout_m2", "cutout_per_m2", |p| p.cutout_per_m2)?;
        }
        if let Some(area) = m.flexible_pavement_m2 {
            total += area
                * price("flexible_pavement_m2", "flexible_pavement_per_m2", |p| {
                    p.flexible_pavement_per_m2
                })?;
        }
        Ok(total)
    }

    /// The price of buying and planting a tree; none in a programme average.
    pub fn planting_price(&self) -> f64 {
        match self {
            Costs::Itemised(c) => c.planting,
            Costs::Average(_) => 0.0,
        }
    }

    /// The price of removing a tree of `dbh_cm`; none where the table has none.
    pub fn removal_price(&self, dbh_cm: f64) -> Option<f64> {
        let Costs::Itemised(c) = self else {
            return None;
        };
        match c.removal_per_cm_dbh {
            Some(per_cm) => Some(per_cm * dbh_cm),
            None => class_of(&c.removal, dbh_cm).map(|k| k.price_at(dbh_cm)),
        }
    }

    /// The costs of one living tree of `dbh_cm` in the year that ends at `age`, whose chance
    /// of dying in that year is `death_chance` (street::accounts::survival; a table's own
    /// `removal_chance_per_year` takes its place) and, where its site is known, of damaging
    /// the pavement beside it `damage_chance` (`street::work::roots`: the table's
    /// `[sidewalk_damage]` prices it, else its flat figures stand). `cycles_charged`: a site's
    /// pruning cycles are charged apart, so the table's own pruning (or the average's pruning
    /// share) is not.
    pub fn year(
        &self,
        age: f64,
        dbh_cm: f64,
        death_chance: f64,
        damage_chance: Option<f64>,
        cycles_charged: bool,
    ) -> YearCosts {
        let c = match self {
            Costs::Average(a) => {
                let share = if cycles_charged { a.pruning_share } else { 0.0 };
                let mut y = YearCosts::default();
                y[Cost::Average] = a.per_tree_per_year * (1.0 - share);
                return y;
            }
            Costs::Itemised(c) => c,
        };
        let planting = if age <= 1.0 { c.planting } else { 0.0 }
            + if age <= c.establishment_years {
                c.establishment_per_year
            } else {
                0.0
            };
        let pruning = match self.pruning_visit(dbh_cm) {
            Some((price, cycle)) if !cycles_charged => price / cycle,
            _ => 0.0,
        };
        let chance = c.removal_chance_per_year.unwrap_or(death_chance);
        let yearly = |v: Option<f64>| v.unwrap_or(0.0);
        let mut y = YearCosts::default();
        y[Cost::Planting] = planting;
        y[Cost::Pruning] = pruning;
        y[Cost::Removal] = chance * self.removal_price(dbh_cm).unwrap_or(0.0);
        y[Cost::Cleanup] = yearly(c.cleanup_per_year);
        match (&c.sidewalk_damage, damage_chance) {
            (Some(d), Some(chance)) => {
                let (city, owners, with) = d.split();
                y[Cost::Sidewalk] = chance * city;
                y[Cost::SidewalkOwners] = chance * owners;
                y[Cost::Sewer] = yearly(c.sewer_repair_per_year);
                y[Cost::Liability] = chance * with;
            }
            _ => {
                y[Cost::Sidewalk] = yearly(c.sidewalk_repair_per_year);
                y[Cost::Liability] =
                    yearly(c.liability_per_year) + yearly(c.administration_per_year);
            }
        }
        y[Cost::Pest] = yearly(c.pest_per_year);
        y
    }
}

/// The class holding `dbh_cm`; the last class beyond the table.
fn class_of(classes: &[Class], dbh_cm: f64) -> Option<&Class> {
    (classes.iter())
        .find(|k| dbh_cm <= k.up_to_dbh_cm)
        .or(classes.last())
}

/// Which table a run of DBH classes is: what else its classes take.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Table {
    /// Pruning: each class its cycle.
    Pruning,
    /// Removal.
    Removal,
    /// The utility's line clearance: a street crew's price and, optionally, a backyard
    /// crew's.
    Line,
}

/// DBH classes must run from 0 upwards with no gap or overlap, each with one price.
fn check_classes(
    file: &str,
    table: &str,
    classes: &[Class],
    kind: Table,
) -> Result<(), StreetError> {
    let pruning = kind == Table::Pruning;
    let mut last = 0.0;
    for k in classes {
        let from = k.from_dbh_cm.unwrap_or(last);
        if from != last {
            return Err(value(
                file,
                &format!("{table}.from_dbh_cm"),
                from,
                &format!("{last} cm, where the class before ends: DBH classes leave no gap"),
            ));
        }
        if !(k.up_to_dbh_cm > from && k.up_to_dbh_cm.is_finite()) {
            return Err(value(
                file,
                &format!("{table}.up_to_dbh_cm"),
                k.up_to_dbh_cm,
                "classes in rising order of DBH, cm",
            ));
        }
        match (k.price, k.price_per_cm_dbh) {
            (Some(v), None) => non_negative(file, &format!("{table}.price"), v)?,
            (None, Some(v)) => non_negative(file, &format!("{table}.price_per_cm_dbh"), v)?,
            _ => {
                return Err(StreetError::Syntax {
                    file: file.to_string(),
                    message: format!(
                        "each [[{table}]] class needs one of `price` or `price_per_cm_dbh`"
                    ),
                });
            }
        }
        match (pruning, k.cycle_years) {
            (true, Some(c)) if !(1.0..=100.0).contains(&c) => {
                return Err(value(
                    file,
                    &format!("{table}.cycle_years"),
                    c,
                    "1 to 100 years",
                ));
            }
            (true, None) => {
                return Err(StreetError::Syntax {
                    file: file.to_string(),
                    message: format!("each [[{table}]] class needs `cycle_years`"),
                });
            }
            (false, Some(_)) => {
                return Err(StreetError::Syntax {
                    file: file.to_string(),
                    message: format!("[[{table}]] classes take no `cycle_years`"),
                });
            }
            _ => {}
        }
        match (kind, k.backyard_price) {
            (Table::Line, Some(v)) => {
                non_negative(file, &format!("{table}.backyard_price"), v)?;
            }
            (_, Some(_)) => {
                return Err(StreetError::Syntax {
                    file: file.to_string(),
                    message: format!(
                        "[[{table}]] classes take no `backyard_price` (only [[line_clearance]])"
                    ),
                });
            }
            _ => {}
        }
        last = k.up_to_dbh_cm;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "source = \"test\"\nyear = 2024\nplanting = 200.0\nestablishment_per_year = 50.0\nestablishment_years = 3\nremoval_per_cm_dbh = 20.0\nremoval_chance_per_year = 0.01\nsidewalk_repair_per_year = 4.0\ncleanup_per_year = 3.0\n[[pruning]]\nup_to_dbh_cm = 15.0\nprice = 30.0\ncycle_years = 3\n[[pruning]]\nup_to_dbh_cm = 200.0\nprice = 300.0\ncycle_years = 5\n";

    #[test]
    fn itemised_costs_by_year_and_their_errors() {
        let dir = tempfile::tempdir().unwrap();
        let costs = dir.path().join("costs.toml");
        std::fs::write(&costs, GOOD).unwrap();
        let c = Costs::load(&costs).unwrap();
        assert!(matches!(c, Costs::Itemised(_)));
        let y = c.year(1.0, 2.0, 0.0, None, false);
        assert_eq!(y[Cost::Planting], 250.0);
        assert_eq!(y[Cost::Pruning], 10.0);
        let y = c.year(20.0, 40.0, 0.0, None, false);
        assert_eq!(y[Cost::Planting], 0.0);
        assert_eq!(y[Cost::Pruning], 60.0);
        assert!((y[Cost::Removal] - 8.0).abs() < 1e-12);
        assert!((y.total() - (60.0 + 8.0 + 4.0 + 3.0)).abs() < 1e-12);
        // A site's cycles replace the table's own pruning.
        assert_eq!(c.year(20.0, 40.0, 0.0, None, true)[Cost::Pruning], 0.0);
        std::fs::write(&costs, GOOD.replace("cycle_years = 5", "cycle_years = 0")).unwrap();
        let e = Costs::load(&costs).unwrap_err().to_string();
        assert!(e.contains("pruning.cycle_years"), "{e}");
        std::fs::write(&costs, GOOD.replace("planting = 200.0\n", "")).unwrap();
        let e = Costs::load(&costs).unwrap_err().to_string();
        assert!(e.contains("costs.toml") && e.contains("planting"), "{e}");
    }

    #[test]
    fn a_gap_between_dbh_classes_is_an_error_naming_the_key() {
        let gap = GOOD.replace(
            "[[pruning]]\nup_to_dbh_cm = 200.0",
            "[[pruning]]\nfrom_dbh_cm = 20.0\nup_to_dbh_cm = 200.0",
        );
        let e = Costs::parse(&gap, "gap.toml").unwrap_err().to_string();
        assert!(
            e.contains("gap.toml") && e.contains("pruning.from_dbh_cm") && e.contains("no gap"),
            "{e}"
        );
        let both = GOOD.replace("price = 30.0\n", "price = 30.0\nprice_per_cm_dbh = 2.0\n");
        let e = Costs::parse(&both, "both.toml").unwrap_err().to_string();
        assert!(e.contains("price_per_cm_dbh"), "{e}");
        let negative = GOOD.replace(
            "sidewalk_repair_per_year = 4.0",
            "sidewalk_repair_per_year = -4.0",
        );
        let e = Costs::parse(&negative, "n.toml").unwrap_err().to_string();
        assert!(
            e.contains("sidewalk_repair_per_year") && e.contains(">= 0"),
            "{e}"
        );
    }

    #[test]
    fn the_builtin_table_sizes_pruning_and_removal_by_the_tree() {
        let c = Costs::builtin("InlVal").unwrap();
        // Churack et al.'s 7.5 minutes per inch at $79.20 an hour: 12 in (30.48 cm) is the
        // contract's grid price per tree, $118.80, within the rounding of $3.90 a cm.
        let (visit, cycle) = c.pruning_visit(30.48).unwrap();
        assert!((visit - 118.8).abs() < 0.5, "{visit}");
        assert_eq!(cycle, 8.0);
        assert_eq!(c.pruning_visit(10.0).unwrap().1, 4.0);
        // A crapemyrtle's visit costs a fraction of a plane's.
        assert!(c.pruning_visit(10.0).unwrap().0 * 5.0 < c.pruning_visit(60.0).unwrap().0);
        // Removal by Sydnor et al.'s classes.
        assert_eq!(c.removal_price(20.0), Some(184.0));
        assert_eq!(c.removal_price(70.0), Some(670.0));
        assert_eq!(c.removal_price(150.0), Some(1563.0));
        // A dying tree's removal is its chance times the price.
        let y = c.year(10.0, 20.0, 0.05, None, false);
        assert!((y[Cost::Removal] - 0.05 * 184.0).abs() < 1e-9);
        assert_eq!(c.year(1.0, 1.0, 0.0, None, false)[Cost::Planting], 75.0);
        let missing = c.not_computed().join(" ");
        assert!(
            missing.contains("clean-up") && missing.contains("pest"),
            "{missing}"
        );
    }

    #[test]
    fn an_average_drops_its_pruning_share_where_cycles_are_charged() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("avg.toml");
        std::fs::write(
            &path,
            "source = \"x\"\nyear = 2020\nper_tree_per_year = 40.0\n",
        )
        .unwrap();
        let c = Costs::load(&path).unwrap();
        assert_eq!(c.year(1.0, 2.0, 0.0, None, false).total(), 40.0);
        assert_eq!(c.year(30.0, 50.0, 0.1, None, true).total(), 40.0);
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
        let e = Costs::parse(
            "source = \"x\"\nyear = 2020\nper_tree_per_year = 4.0\npruning_share = 1.5\n",
            "s.toml",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("pruning_share"), "{e}");
        let modesto = Costs::modesto_average();
        assert_eq!(
            modesto.year(10.0, 20.0, 0.0, None, false)[Cost::Average],
            28.77
        );
        assert!((modesto.year(10.0, 20.0, 0.0, None, true)[Cost::Average] - 14.385).abs() < 1e-9);
        assert!(modesto.source().contains("1997-98"));
    }
}
