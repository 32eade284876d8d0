//! Aesthetics and property value: what a street tree adds to the homes beside it, priced as
//! i-Tree Streets and the USDA Community Tree Guides price it (McPherson 2007, "Benefit-based
//! tree valuation", Arboriculture & Urban Forestry 33(1):1-11, p. 4):
//!
//! ```text
//! benefit = L x P,   P = T x C / M,   T = 0.88% x the median home sale price
//! ```
//!
//! - L, the leaf area the tree gains in the year, m²: the grown crown's own gain for Sylva's
//!   account; i-Tree's `property_value` table at typical position (its yearly leaf-area gain,
//!   held to i-Tree's `lsa` table by a test).
//! - T: a large front-yard tree adds 0.88% to a home's sale price (Anderson & Cordell 1988, as
//!   McPherson 2007 gives it).
//! - C, the location factor: 1.0 in McPherson's worked example for street trees in Fort Collins
//!   and Boulder; it is there to lower the benefit of trees in side or back yards or away from
//!   homes. Sylva's trees stand on residential streets, so 1.0; `--prices` may set another.
//! - M = 675 m², the leaf area of the large tree that adds T (McPherson 2007's example).
//!
//! The median price is each region's from `data/street/home-prices.csv`: the guides' own
//! figures were not reachable, so the most local published figure stands in (the reference
//! city's or its county's sale price, else its state's or Census region's Census 2000 median
//! value), and the prices' source says which.

use std::sync::OnceLock;

/// The share of a home's sale price a large front-yard tree adds (Anderson & Cordell 1988).
pub const SHARE_OF_SALE_PRICE: f64 = 0.0088;
/// The leaf area of that large tree, m² (McPherson 2007: 7,290 ft²).
pub const LARGE_TREE_LEAF_M2: f64 = 675.0;
/// The location factor of a street tree before homes (McPherson 2007's worked example).
pub const STREET_LOCATION_FACTOR: f64 = 1.0;

/// A region's median home price and where it comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct HomePrice {
    /// Sylva's region code.
    pub region: String,
    /// The place the figure is for (a city, a state, a Census region).
    pub place: String,
    /// Dollars.
    pub price: f64,
    /// The year of the figure.
    pub year: u32,
    /// How local it is: `city`, `county`, `state` or `census-region`.
    pub basis: String,
}

/// Dollars of aesthetic benefit per m² of leaf area gained in a year.
pub fn price_per_m2(median_home_price: f64, location_factor: f64) -> f64 {
    SHARE_OF_SALE_PRICE * median_home_price * location_factor / LARGE_TREE_LEAF_M2
}

/// The built-in median home price of a region, if the table has one.
pub fn home_price(region: &str) -> Option<&'static HomePrice> {
    static TABLE: OnceLock<Vec<HomePrice>> = OnceLock::new();
    TABLE
        .get_or_init(|| parse(include_str!("../../../data/street/home-prices.csv")))
        .iter()
        .find(|h| h.region == region)
}

impl HomePrice {
    /// How the price was found, for a report.
    pub fn describe(&self) -> String {
        format!(
            "aesthetics: 0.88% of ${:.0} ({}, {}{}) x {} / {} m² = ${:.2} per m² of leaf gained \
             (McPherson 2007's method)",
            self.price,
            self.place,
            self.year,
            match self.basis.as_str() {
                "city" => "",
                "county" => ", the reference city's county",
                _ => ", nearest published figure to the reference city",
            },
            STREET_LOCATION_FACTOR,
            LARGE_TREE_LEAF_M2,
            price_per_m2(self.price, STREET_LOCATION_FACTOR)
        )
    }
}

fn parse(text: &str) -> Vec<HomePrice> {
    (text.lines())
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            // The built-in file is checked by a test; a bad row would be a broken build.
            HomePrice {
                region: f[0].into(),
                place: f[1].into(),
                price: f[2].parse().expect("a price"),
                year: f[3].parse().expect("a year"),
                basis: f[4].into(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::street::accounts::itree::regions;

    #[test]
    fn every_region_has_a_sourced_home_price() {
        for region in regions().keys().copied().chain(["SacVal"]) {
            let h = home_price(region).unwrap_or_else(|| panic!("{region}"));
            assert!(h.price > 50_000.0 && h.price < 1e6, "{h:?}");
            assert!(["city", "county", "state", "census-region"].contains(&h.basis.as_str()));
        }
        // McPherson 2007's worked example: Fort Collins, $212,000, about $2.76 a m².
        let fc = home_price("NMtnPr").unwrap();
        assert!((price_per_m2(fc.price, 1.0) - 2.764).abs() < 1e-3);
        assert!(home_price("Modesto").is_none());
        // Modesto's county's own sale price, not California's Census value.
        let modesto = home_price("InlVal").unwrap();
        assert_eq!(
            (modesto.price, modesto.basis.as_str()),
            (140_000.0, "county")
        );
    }
}
