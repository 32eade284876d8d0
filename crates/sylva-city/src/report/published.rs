//! Published yearly benefits per tree of whole municipal tree populations
//! (`data/published-per-tree.csv`, each with its source), which a city's report sets beside its
//! own per-tree figures by category, with why they differ.

use serde::Serialize;

/// The table as shipped.
const TABLE: &str = include_str!("../../data/published-per-tree.csv");

/// The categories, in the report's order: the four the report computes (i-Tree Streets'
/// typical position: energy, carbon, stormwater, air quality), then what it does not, then the
/// total.
pub const CATEGORIES: [&str; 6] = [
    "energy",
    "carbon",
    "stormwater",
    "air_quality",
    "aesthetics_other",
    "total",
];

/// One city's published figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Published {
    /// The Urban Tree Database region it stands for, and the city.
    pub region: String,
    pub city: String,
    /// The year of its dollars.
    pub year: u32,
    /// Trees in the population.
    pub trees: u64,
    /// $ a tree a year, by category (those of [`CATEGORIES`] it gives).
    pub per_tree: Vec<(String, f64)>,
    /// The source, as the table's comment gives it.
    pub source: String,
}

impl Published {
    /// Its figure for `category`.
    pub fn get(&self, category: &str) -> Option<f64> {
        self.per_tree
            .iter()
            .find(|(c, _)| c == category)
            .map(|&(_, v)| v)
    }
}

/// Every city in the table.
pub fn all() -> Vec<Published> {
    let mut out: Vec<Published> = Vec::new();
    for line in TABLE
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1)
    {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        let (Some(&region), Some(&city), Some(year), Some(trees), Some(&category), Some(usd)) = (
            f.first(),
            f.get(1),
            f.get(2).and_then(|v| v.parse().ok()),
            f.get(3).and_then(|v| v.parse().ok()),
            f.get(4),
            f.get(5).and_then(|v| v.parse::<f64>().ok()),
        ) else {
            continue;
        };
        if !CATEGORIES.contains(&category) {
            continue;
        }
        match out
            .iter_mut()
            .find(|p| p.region == region && p.city == city)
        {
            Some(p) => p.per_tree.push((category.to_string(), usd)),
            None => out.push(Published {
                region: region.to_string(),
                city: city.to_string(),
                year,
                trees,
                per_tree: vec![(category.to_string(), usd)],
                source: source_of(region),
            }),
        }
    }
    out
}

/// The comment paragraph that begins `REGION:`: where that region's figures come from.
fn source_of(region: &str) -> String {
    let head = format!("{region}:");
    TABLE
        .lines()
        .filter_map(|l| l.strip_prefix('#'))
        .map(str::trim)
        .skip_while(|l| !l.starts_with(&head))
        .take_while(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
        .trim_start_matches(&head)
        .trim()
        .to_string()
}

/// The published city of `region`, if the table has one.
pub fn for_region(region: &str) -> Option<Published> {
    all().into_iter().find(|p| p.region == region)
}

/// A report's figures per tree beside a published city's.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comparison {
    /// The published city.
    pub published: Published,
    /// Each category of [`CATEGORIES`]: its name, this city's figure ($ a tree a year, none
    /// where not computed) and the published one.
    pub rows: Vec<(String, Option<f64>, Option<f64>)>,
    /// Why the two differ, beyond the figures themselves.
    pub differences: Vec<String>,
}

/// This city's i-Tree Streets typical-position figures per tree (energy, carbon, stormwater,
/// air quality, aesthetics) beside `published`'s.
pub fn compare(published: Published, typical_per_tree: [Option<f64>; 5]) -> Comparison {
    let computed: f64 = typical_per_tree.iter().flatten().sum();
    let rows = CATEGORIES
        .iter()
        .enumerate()
        .map(|(k, &c)| {
            let ours = match k {
                // Aesthetics stands for the published "aesthetics and other".
                0..5 => typical_per_tree[k],
                _ => Some(computed),
            };
            (c.to_string(), ours, published.get(c))
        })
        .collect();
    let differences = vec![
        format!(
            "population: {}'s figures are for its {} street and park trees of {}, which the \
             paper finds even-aged and led by mature Modesto ash; this city's are for its own \
             inventory's trees at their own DBH",
            published.city, published.trees, published.year
        ),
        format!(
            "aesthetics: the yearly leaf-area gain priced by i-Tree Streets' method; {}; the \
             published category also holds 'other' benefits",
            sylva::street::accounts::aesthetics::home_price(&published.region)
                .map_or("no home price".into(), |h| h.describe()),
        ),
        "energy: i-Tree Streets prices each tree at its species' usual distances and directions \
         from buildings (typical position); the published figure was modelled for the city's \
         own trees"
            .into(),
        format!(
            "prices: i-Tree Streets' {} prices come from the same research group's regional tree \
             guide, whose dollars' year i-Tree does not state; the published figures are {} \
             dollars",
            published.region, published.year
        ),
    ];
    Comparison {
        published,
        rows,
        differences,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modesto_reads_as_published() {
        let m = for_region("InlVal").unwrap();
        assert_eq!(
            (m.city.as_str(), m.year, m.trees),
            ("Modesto", 1998, 91_179)
        );
        // The abstract's whole-dollar categories add to within a dollar of its total.
        let parts: f64 = CATEGORIES[..5].iter().map(|c| m.get(c).unwrap()).sum();
        assert!((parts - m.get("total").unwrap()).abs() <= 1.0, "{parts}");
        assert!(
            m.source.contains("Journal of Arboriculture 25(5)"),
            "{}",
            m.source
        );
        assert!(for_region("PacfNW").is_none());
    }
}
