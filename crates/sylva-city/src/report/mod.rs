//! The city's report (issue T), as i-Tree Streets reports an inventory: the resource's
//! structure (species and genus composition with i-Tree's diversity guidelines, DBH classes,
//! importance values), its yearly benefits by species, and each epoch beside the first. Every
//! figure says which model gives it; what Sylva does not compute is listed as such.
//!
//! Read from a planned and grown city (`tasks::CityJob`): each tree's species and DBH from the
//! inventory, its leaf area and crown from the grown tree of its class scaled to it, its
//! benefits from `benefits::tree_year` (Sylva's own carbon and rain, and i-Tree Streets'
//! typical position at its DBH).

pub(crate) mod html;
pub mod observed;
pub mod pavement;
pub mod predicted;
pub mod published;

use crate::trees::benefits::{NO_DATA, tree_year};
use crate::trees::plan::{Kind, Plan, ProtoKey};
use crate::trees::prototypes::Prototype;
use published::Comparison;
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use sylva::growth::DBH_CLASS_EDGES_CM;
use sylva::street::Survival;

/// i-Tree's guideline for one species: at most this share of the trees (Santamour 1990's
/// 10-20-30 rule, as i-Tree Streets flags it).
pub const SPECIES_GUIDELINE: f64 = 0.10;
/// ...and for one genus.
pub const GENUS_GUIDELINE: f64 = 0.20;

/// The report's age classes, years since planting: Sylva's choice, as the Urban Tree Database
/// publishes no age classes (its sampled trees reach some 40 to 110 years).
pub const AGE_CLASS_EDGES_YEARS: [f64; 4] = [10.0, 20.0, 40.0, 60.0];

/// One species of the city at the first epoch.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpeciesRow {
    /// Urban Tree Database code it is grown as.
    pub code: String,
    /// Scientific and common name.
    pub scientific: String,
    pub common: String,
    /// Genus: the scientific name's first word.
    pub genus: String,
    /// Plant family (APG IV; `families`), if the table has the genus.
    pub family: Option<String>,
    /// Trees.
    pub trees: usize,
    /// Share of the city's trees.
    pub share: f64,
    /// Trees in each of the Urban Tree Database's nine DBH classes (cm: under 7.6, 7.6-15.2,
    /// ... , 106.7 and over).
    pub dbh_classes: [usize; 9],
    /// Trees by estimated age, years since planting (`AGE_CLASS_EDGES_YEARS`: under 10, 10-20,
    /// 20-40, 40-60, 60 and over).
    pub age_classes: [usize; 5],
    /// Mean estimated age, years.
    pub mean_age_years: f64,
    /// Trees at least as old as the oldest the Urban Tree Database measured of the species in
    /// its region: their age is that oldest age, and their DBH may be larger than its data.
    pub at_oldest_measured: usize,
    /// One-sided leaf area, m².
    pub leaf_area_m2: f64,
    /// Importance value: share of the trees plus share of the leaf area (i-Tree Streets'),
    /// in percent (0 to 200).
    pub importance: f64,
    /// Sylva's own benefits of the categories it computes here (carbon, stormwater, air
    /// quality, aesthetics; energy is not: no façades), $ a year; none where no tree of it has
    /// a model.
    pub benefits_usd: Option<f64>,
    /// Sylva's own by category (`benefits::CATEGORIES`: energy, carbon, stormwater, air quality,
    /// aesthetics), $ a year; none where not computed.
    pub own_usd: [Option<f64>; 5],
    /// i-Tree Streets' typical position at each tree's DBH: energy, carbon, stormwater, air
    /// quality, aesthetics, $ a year.
    pub typical_usd: [Option<f64>; 5],
    /// Every priced typical benefit, $ a year.
    pub typical_total_usd: Option<f64>,
}

/// One epoch of the city.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct EpochRow {
    /// Years after the inventory's year.
    pub years: u32,
    /// Trees standing (stumps aside).
    pub trees: usize,
    /// Canopy: the crowns' projections summed (overlaps counted twice), m².
    pub canopy_m2: f64,
    /// Leaf area, m².
    pub leaf_area_m2: f64,
    /// Sylva's own benefits, $ a year.
    pub benefits_usd: f64,
    /// i-Tree Streets' typical-position benefits, $ a year.
    pub typical_total_usd: f64,
    /// The share of the first epoch's trees expected to be standing, each by its estimated
    /// age through its region's survival (`sylva::street::accounts::survival`); the tiles draw them all.
    pub expected_alive_share: f64,
    /// Sylva's own benefits with each tree weighted by its chance of standing, $ a year.
    pub expected_benefits_usd: f64,
}

/// The report.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CityReport {
    /// Trees at the first epoch.
    pub trees: usize,
    /// Every species, most trees first.
    pub species: Vec<SpeciesRow>,
    /// Every genus and its trees and share, most first.
    pub genera: Vec<(String, usize, f64)>,
    /// Every family and its trees and share, most first (`unknown` for a genus the table
    /// lacks).
    pub families: Vec<(String, usize, f64)>,
    /// What breaks i-Tree's diversity guidelines.
    pub flags: Vec<String>,
    /// Each epoch.
    pub epochs: Vec<EpochRow>,
    /// The model behind each figure.
    pub models: Vec<String>,
    /// What is not computed, and why.
    pub not_computed: Vec<String>,
    /// What the inventory's surveyors saw: condition and RPI by species, problems by species
    /// and DBH class.
    pub observed: observed::Observations,
    /// Sylva's site model on a typical street beside the problems recorded: each species'
    /// first age in the lines' clearance (`predicted`), where problems were recorded.
    pub predicted: Vec<predicted::Predicted>,
    /// Sylva's roots model beside the sidewalk damage recorded (`pavement`), where any was.
    pub pavement: Option<pavement::Pavement>,
    /// Per tree at the first epoch: i-Tree Streets' typical-position energy, carbon,
    /// stormwater, air quality and aesthetics, $ a year.
    pub typical_per_tree_usd: [Option<f64>; 5],
    /// Per tree at the first epoch: Sylva's own, by the same categories (energy not
    /// computed), $ a year.
    pub own_per_tree_usd: [Option<f64>; 5],
    /// Sylva's own benefits per tree, the computed categories summed, $ a year.
    pub benefits_per_tree_usd: Option<f64>,
    /// The published figures per tree of the city that the region most of the trees are grown
    /// in stands for, beside this city's, where the table has one.
    pub published: Option<Comparison>,
}

/// What one tree adds up to.
struct Tree {
    leaf: f64,
    canopy: f64,
    benefits: Option<f64>,
    own: [Option<f64>; 5],
    typical: [Option<f64>; 5],
    typical_total: Option<f64>,
}

fn tree_of(
    t: &crate::trees::plan::Planned,
    key: &ProtoKey,
    plan: &Plan,
    prototypes: &HashMap<ProtoKey, Prototype>,
) -> Tree {
    let p = prototypes.get(key);
    let m = plan.measured.get(&(key.region.clone(), key.code.clone()));
    let year = tree_year(t, m, p);
    let s = p.map_or(0.0, |p| (t.height / p.height.max(0.01)) as f64);
    let some = |v: f32| (v != NO_DATA).then_some(v as f64);
    Tree {
        leaf: p.map_or(0.0, |p| p.surfaces.0 * s * s),
        canopy: std::f64::consts::PI * (t.crown_diameter as f64 / 2.0).powi(2),
        benefits: some(year.benefits_usd),
        own: year.own_usd.map(some),
        typical: year.typical_usd.map(some),
        typical_total: some(year.typical_benefits_usd),
    }
}

fn add(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (None, None) => None,
        (a, b) => Some(a.unwrap_or(0.0) + b.unwrap_or(0.0)),
    }
}

/// The species' trees summed by `group` (genus, family), with their share of the city's
/// `trees`, most first.
fn shares_by(
    species: &[SpeciesRow],
    trees: usize,
    group: impl Fn(&SpeciesRow) -> String,
) -> Vec<(String, usize, f64)> {
    let mut sums: BTreeMap<String, usize> = BTreeMap::new();
    for s in species {
        *sums.entry(group(s)).or_default() += s.trees;
    }
    let mut rows: Vec<(String, usize, f64)> = sums
        .into_iter()
        .map(|(name, n)| (name, n, n as f64 / trees.max(1) as f64))
        .collect();
    rows.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    rows
}

/// The report of a planned city whose trees are grown (`prototypes`).
pub fn report(plan: &Plan, prototypes: &HashMap<ProtoKey, Prototype>) -> CityReport {
    let mut species: BTreeMap<String, SpeciesRow> = BTreeMap::new();
    let mut regions: BTreeMap<&str, usize> = BTreeMap::new();
    let first = plan.epochs.first();
    for t in first.map_or(&[][..], |e| &e.trees) {
        let Kind::Tree(key) = &t.kind else { continue };
        *regions.entry(key.region.as_str()).or_default() += 1;
        let tree = tree_of(t, key, plan, prototypes);
        let m = plan.measured.get(&(key.region.clone(), key.code.clone()));
        let row = species.entry(key.code.clone()).or_insert_with(|| {
            let scientific = m.map_or(String::new(), |m| m.species.scientific.clone());
            let genus = scientific
                .split_whitespace()
                .next()
                .unwrap_or("")
                .to_string();
            SpeciesRow {
                code: key.code.clone(),
                family: crate::inventory::families::family(&genus).map(str::to_string),
                genus,
                common: m.map_or(String::new(), |m| m.species.common.clone()),
                scientific,
                trees: 0,
                share: 0.0,
                dbh_classes: [0; 9],
                age_classes: [0; 5],
                mean_age_years: 0.0,
                at_oldest_measured: 0,
                leaf_area_m2: 0.0,
                importance: 0.0,
                benefits_usd: None,
                own_usd: [None; 5],
                typical_usd: [None; 5],
                typical_total_usd: None,
            }
        });
        row.trees += 1;
        let class = DBH_CLASS_EDGES_CM.partition_point(|&edge| edge <= t.dbh as f64);
        row.dbh_classes[class] += 1;
        // Each tree's age is from its DBH by the Urban Tree Database's equations (`plan`),
        // held within the ages the database measured.
        let age = t.age as f64;
        row.age_classes[AGE_CLASS_EDGES_YEARS.partition_point(|&edge| edge <= age)] += 1;
        row.mean_age_years += age;
        if m.is_some_and(|m| age >= m.ages.1 - 1e-3) {
            row.at_oldest_measured += 1;
        }
        row.leaf_area_m2 += tree.leaf;
        row.benefits_usd = add(row.benefits_usd, tree.benefits);
        for (sum, v) in row.typical_usd.iter_mut().zip(tree.typical) {
            *sum = add(*sum, v);
        }
        for (sum, v) in row.own_usd.iter_mut().zip(tree.own) {
            *sum = add(*sum, v);
        }
        row.typical_total_usd = add(row.typical_total_usd, tree.typical_total);
    }
    let observed = observed::observations(plan);
    // The species whose problems were recorded, grown on the typical street.
    let mut grown: Vec<(String, String)> = (first.map_or(&[][..], |e| &e.trees).iter())
        .filter_map(|t| match &t.kind {
            Kind::Tree(k) if observed.problems.iter().any(|p| p.code == k.code) => {
                Some((k.region.clone(), k.code.clone()))
            }
            _ => None,
        })
        .collect();
    grown.sort();
    grown.dedup();
    let predicted = predicted::predicted(plan, prototypes, &grown);
    let pavement = pavement::pavement(plan);
    let trees: usize = species.values().map(|s| s.trees).sum();
    let per_tree = |v: Option<f64>| v.map(|v| v / trees.max(1) as f64);
    let typical_per_tree_usd: [Option<f64>; 5] = std::array::from_fn(|k| {
        per_tree(species.values().fold(None, |a, s| add(a, s.typical_usd[k])))
    });
    let own_per_tree_usd: [Option<f64>; 5] =
        std::array::from_fn(|k| per_tree(species.values().fold(None, |a, s| add(a, s.own_usd[k]))));
    let benefits_per_tree_usd =
        per_tree(species.values().fold(None, |a, s| add(a, s.benefits_usd)));
    // The region most trees are grown in (the first of equals).
    let region = regions
        .iter()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0)))
        .map(|(r, _)| *r);
    let published = region
        .and_then(published::for_region)
        .map(|p| published::compare(p, typical_per_tree_usd));
    let leaf: f64 = species.values().map(|s| s.leaf_area_m2).sum();
    let mut species: Vec<SpeciesRow> = species.into_values().collect();
    for s in &mut species {
        s.mean_age_years /= s.trees.max(1) as f64;
        s.share = s.trees as f64 / trees.max(1) as f64;
        s.importance = 100.0 * (s.share + s.leaf_area_m2 / leaf.max(1e-9));
    }
    species.sort_by(|a, b| b.trees.cmp(&a.trees).then(a.code.cmp(&b.code)));
    let genera = shares_by(&species, trees, |s| s.genus.clone());
    let families = shares_by(&species, trees, |s| {
        s.family.clone().unwrap_or_else(|| "unknown".into())
    });
    let mut flags: Vec<String> = species
        .iter()
        .filter(|s| s.share > SPECIES_GUIDELINE)
        .map(|s| {
            format!(
                "species {} ({}) is {:.1}% of the trees: over i-Tree's 10% guideline",
                s.common,
                s.code,
                100.0 * s.share
            )
        })
        .collect();
    flags.extend(genera.iter().filter(|g| g.2 > GENUS_GUIDELINE).map(|g| {
        format!(
            "genus {} is {:.1}% of the trees: over i-Tree's 20% guideline",
            g.0,
            100.0 * g.2
        )
    }));
    // Each inventory row's age and region at the first epoch: its chance of standing later.
    let planted: HashMap<usize, (f64, &str)> = (first.map_or(&[][..], |e| &e.trees).iter())
        .filter_map(|t| match &t.kind {
            Kind::Tree(key) => Some((t.row, (t.age as f64, key.region.as_str()))),
            Kind::Stump => None,
        })
        .collect();
    let years0 = first.map_or(0, |e| e.years);
    // Each region's survival, made once rather than for every tree.
    let mut survivals: HashMap<&str, Survival> = HashMap::new();
    let epochs = plan
        .epochs
        .iter()
        .map(|e| {
            let mut row = EpochRow {
                years: e.years,
                trees: 0,
                canopy_m2: 0.0,
                leaf_area_m2: 0.0,
                benefits_usd: 0.0,
                typical_total_usd: 0.0,
                expected_alive_share: 0.0,
                expected_benefits_usd: 0.0,
            };
            let later = f64::from(e.years.saturating_sub(years0));
            for t in &e.trees {
                let Kind::Tree(key) = &t.kind else { continue };
                let tree = tree_of(t, key, plan, prototypes);
                row.trees += 1;
                row.canopy_m2 += tree.canopy;
                row.leaf_area_m2 += tree.leaf;
                row.benefits_usd += tree.benefits.unwrap_or(0.0);
                row.typical_total_usd += tree.typical_total.unwrap_or(0.0);
                let standing = planted.get(&t.row).map_or(1.0, |&(age, region)| {
                    let s = (survivals.entry(region)).or_insert_with(|| Survival::builtin(region));
                    s.alive_after(age + later) / s.alive_after(age)
                });
                row.expected_alive_share += standing;
                row.expected_benefits_usd += standing * tree.benefits.unwrap_or(0.0);
            }
            row.expected_alive_share /= row.trees.max(1) as f64;
            row
        })
        .collect();
    CityReport {
        trees,
        species,
        genera,
        families,
        flags,
        epochs,
        models: vec![
            "composition, DBH classes: the inventory's rows as planned (species by their Urban \
             Tree Database code, genus the scientific name's first word, family by APG IV \
             (2016), conifers by Christenhusz et al. (2011))"
                .into(),
            "relative age: as i-Tree Streets shows it, the trees of each species by DBH class; \
             beside it each tree's age estimated from its DBH by the Urban Tree Database's \
             age-DBH equation for its species and region (McPherson et al. 2016), held within \
             the ages the database measured (trees beyond are counted as at the data's oldest)"
                .into(),
            "leaf area and canopy: each tree's grown tree of its age class scaled to its \
             height; canopy the crowns' projected discs summed"
                .into(),
            "importance value: share of trees plus share of leaf area (i-Tree Streets)".into(),
            "condition, as the inventory recorded it, in i-Tree Streets' report classes: the \
             census's health Good, Fair, Poor as written; other layouts' condition Excellent, \
             Very Good and Good as good, Fair as fair, Poor, Critical and Dying as poor (i-Tree \
             Eco's dieback classes); any other value not recorded, and listed; relative \
             performance index: a species' share in good condition over the city's (CUFR, \
             Urban Forest Research, Summer 2004)"
                .into(),
            "benefits: Sylva's own CO2 taken up (Jenkins et al. 2003), rain held back by the \
             grown crown, its air quality (i-Tree's uptake per m² of leaf on the crown's own \
             leaf) and aesthetics (its yearly leaf gain at the region's price per m², McPherson \
             2007's method), at the region's prices; typical: i-Tree Streets' per-tree tables \
             at each tree's DBH (energy, carbon, stormwater, air quality, aesthetics)"
                .into(),
            "survival: each epoch's trees weighted by their chance of standing, from their \
             estimated age by the region's yearly survival (5% die a year while establishing, \
             then fewer, to the Community Tree Guides' share alive at 40 years)"
                .into(),
        ],
        not_computed: vec![
            "age as a share of life expectancy: the Urban Tree Database gives no species' \
             expected life span"
                .into(),
            replacement_missing(&observed),
            "Sylva's own energy: an inventory has no façades, so the grown crowns' shade on \
             buildings is not computed (the typical position's energy is i-Tree's); Sylva's \
             own total is of the other four categories"
                .into(),
        ],
        typical_per_tree_usd,
        own_per_tree_usd,
        benefits_per_tree_usd,
        published,
        observed,
        predicted,
        pavement,
    }
}

/// What the CTLA trunk formula still lacks, named exactly.
fn replacement_missing(observed: &observed::Observations) -> String {
    format!(
        "replacement value: the CTLA trunk formula (Council of Tree and Landscape Appraisers, \
         Guide for Plant Appraisal, 9th ed., 2000) multiplies a basic value (a replacement tree's \
         installed cost, plus a regional price per unit of trunk area for the rest of the \
         tree's trunk area) by species, condition and location ratings. {} Still missing: each \
         species' rating and the region's price per unit of trunk area and installed cost (set \
         by each ISA chapter: for California the Western Chapter's Species Classification and \
         Group Assignment, 2004), which neither i-Tree Streets' published reference-city \
         reports nor any other source Sylva could reach tabulate; McPherson (2007, \
         Arboriculture & Urban Forestry 33(1), Table 2) gives one species' (Chinese pistache in \
         Davis: $11.94 per cm² of trunk area, $345 installed, species rating 90%), not a \
         region's table; a condition rating as a percentage, which a class (good, fair, \
         poor) does not give and no source Sylva reached converts (McPherson's three trees \
         were rated 56 to 64%); and a location rating, which an inventory does not record \
         (McPherson's street trees: 66.7%)",
        if observed.has_condition() {
            "The inventory records condition (above)."
        } else {
            "Condition: this inventory records none."
        }
    )
}

impl CityReport {
    /// As JSON.
    pub fn json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }

    /// One row per species, as CSV.
    pub fn csv(&self) -> String {
        let mut out = String::from(
            "code,scientific,common,genus,family,trees,share,importance,leaf_area_m2,\
             dbh_lt_7_6,dbh_7_6_15_2,dbh_15_2_30_5,dbh_30_5_45_7,dbh_45_7_61,dbh_61_76_2,\
             dbh_76_2_91_4,dbh_91_4_106_7,dbh_ge_106_7,age_lt_10,age_10_20,age_20_40,\
             age_40_60,age_ge_60,mean_age_years,at_oldest_measured,benefits_usd,own_energy_usd,\
             own_carbon_usd,own_stormwater_usd,own_air_quality_usd,own_aesthetics_usd,\
             typical_energy_usd,typical_carbon_usd,typical_stormwater_usd,typical_air_quality_usd,\
             typical_aesthetics_usd,typical_total_usd,condition_good,condition_fair,\
             condition_poor,condition_not_recorded,rpi\n",
        );
        let cell = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.2}"));
        for s in &self.species {
            let classes: Vec<String> = s.dbh_classes.iter().map(|n| n.to_string()).collect();
            let ages: Vec<String> = s.age_classes.iter().map(|n| n.to_string()).collect();
            let typical: Vec<String> = (s.own_usd.iter().chain(&s.typical_usd))
                .map(|&v| cell(v))
                .collect();
            let seen = self.observed.condition.iter().find(|c| c.code == s.code);
            let condition = seen.map_or(",,,,".to_string(), |c| {
                let [g, f, p] = c.good_fair_poor;
                format!(
                    "{g},{f},{p},{},{}",
                    c.not_recorded,
                    c.rpi.map_or(String::new(), |r| format!("{r:.3}"))
                )
            });
            let _ = writeln!(
                out,
                "{},\"{}\",\"{}\",{},{},{},{:.4},{:.2},{:.1},{},{},{:.1},{},{},{},{},{}",
                s.code,
                s.scientific,
                s.common,
                s.genus,
                s.family.as_deref().unwrap_or(""),
                s.trees,
                s.share,
                s.importance,
                s.leaf_area_m2,
                classes.join(","),
                ages.join(","),
                s.mean_age_years,
                s.at_oldest_measured,
                cell(s.benefits_usd),
                typical.join(","),
                cell(s.typical_total_usd),
                condition
            );
        }
        out
    }
}
