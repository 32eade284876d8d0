//! Each tree's year of benefits, by the models `sylva grow` accounts with (`sylva::street`):
//! CO2 stored from its own DBH (Jenkins et al. 2003's biomass groups), CO2 taken up this year
//! from the DBH its species' measured growth gives it a year earlier, rain held back by its
//! crown (the grown tree of its class, its leaf and bark areas and crown projection scaled by
//! the square of the tree's scale to it), air quality (i-Tree's uptake per m² of leaf on that
//! leaf area) and aesthetics (its yearly leaf gain), at the region's built-in prices. No
//! energy figures from the crown: an inventory has no façades. Beside them, the typical
//! position's account (`sylva::street::accounts::typical`): i-Tree Streets' figures for the species at
//! the tree's own inventory DBH, in its categories, at the region's prices, as i-Tree Streets
//! itself values an inventory. A figure with no model or price is -1 (the property's no-data
//! value).

use crate::trees::plan::{Kind, Planned};
use crate::trees::prototypes::Prototype;
use std::collections::HashMap;
use sylva::growth::Measured;
use sylva::street::Prices;
use sylva::street::accounts::carbon::{BiomassGroup, co2_sequestered_kg, co2_stored_kg};
use sylva::street::accounts::typical::Reference;
use sylva::street::energy::climate::{climate, interception_m3};

/// A figure no model or price gives.
pub const NO_DATA: f32 = -1.0;

/// The benefit categories of a tree's year, in report order.
pub const CATEGORIES: [&str; 5] = [
    "energy",
    "carbon",
    "stormwater",
    "air_quality",
    "aesthetics",
];

/// One tree's year.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TreeYear {
    /// CO2 held in the tree, kg.
    pub co2_stored_kg: f32,
    /// CO2 taken up this year, kg.
    pub co2_sequestered_kg: f32,
    /// Rain held back this year, m³.
    pub rain_intercepted_m3: f32,
    /// Sylva's own computed categories summed (carbon, stormwater, air quality, aesthetics;
    /// energy is not computed: an inventory has no façades), dollars.
    pub benefits_usd: f32,
    /// Sylva's own by category ([`CATEGORIES`]): energy (not computed), carbon taken up,
    /// stormwater held by the grown crown, air quality (i-Tree's uptake per m² of leaf at this
    /// DBH on the grown crown's leaf, BVOCs subtracted), aesthetics (the crown's yearly leaf
    /// gain, by its species' measured leaf-area curve), dollars.
    pub own_usd: [f32; 5],
    /// At typical position: energy (cooling and heating), carbon (sequestered and avoided),
    /// stormwater, air quality (BVOCs subtracted), aesthetics, dollars.
    pub typical_usd: [f32; 5],
    /// At typical position: every priced benefit, dollars.
    pub typical_benefits_usd: f32,
}

/// The year of `tree` (drawn as `p`, grown by `m`).
pub fn tree_year(tree: &Planned, m: Option<&Measured>, p: Option<&Prototype>) -> TreeYear {
    let none = TreeYear {
        co2_stored_kg: NO_DATA,
        co2_sequestered_kg: NO_DATA,
        rain_intercepted_m3: NO_DATA,
        benefits_usd: NO_DATA,
        own_usd: [NO_DATA; 5],
        typical_usd: [NO_DATA; 5],
        typical_benefits_usd: NO_DATA,
    };
    let (Kind::Tree(key), Some(p), Some(m)) = (&tree.kind, p, m) else {
        return none;
    };
    let dbh = tree.dbh as f64;
    let age = tree.age as f64;
    let group = BiomassGroup::of(&m.species.scientific);
    let stored = group.map(|g| co2_stored_kg(g, dbh));
    let sequestered = group.map(|g| co2_sequestered_kg(g, m, age, dbh));
    let s = (tree.height / p.height.max(0.01)) as f64;
    let (leaf, bark, projection) = p.surfaces;
    let rain = climate(&key.region)
        .and_then(|c| c.rain)
        .map(|r| interception_m3(&r, (leaf + bark) * s * s, projection * s * s));
    let prices = Prices::builtin_shared(&key.region);
    let valued = |amount: Option<f64>, per: Option<f64>| amount.zip(per).map(|(a, b)| a * b);
    let carbon = valued(sequestered, prices.and_then(|p| p.co2_per_kg));
    let water = valued(rain, prices.and_then(|p| p.stormwater_per_m3));
    let f = |x: Option<f64>| x.map_or(NO_DATA, |v| v as f32);
    let typical = Reference::of(m).ok().map(|r| r.at(dbh, prices));
    let sum = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (None, None) => None,
        (a, b) => Some(a.unwrap_or(0.0) + b.unwrap_or(0.0)),
    };
    // The grown crown's own air quality: i-Tree's uptake and BVOC emission per m² of leaf at
    // this DBH, on its own leaf area (as `sylva grow` accounts it).
    let own_leaf = leaf * s * s;
    let air = typical.as_ref().and_then(|t| {
        let i_tree = t.amounts.leaf_area_m2;
        let share = if i_tree > 0.0 { own_leaf / i_tree } else { 0.0 };
        sum(t.money.air_quality, t.money.bvoc).map(|v| v * share)
    });
    // Its aesthetics: the leaf it gains this year, the grown crown's leaf times its species'
    // measured yearly rise in leaf area, at the region's price per m².
    let gain = (m.leaf_area(age) > 0.0)
        .then(|| own_leaf * (1.0 - m.leaf_area(age - 1.0) / m.leaf_area(age)).max(0.0));
    let aesthetics = valued(gain, prices.and_then(|p| p.leaf_gain_per_m2));
    let own = [None, carbon, water, air, aesthetics];
    let money = own.iter().fold(None, |a, &v| sum(a, v));
    let typical_usd = typical.as_ref().map_or([NO_DATA; 5], |t| {
        let t = &t.money;
        [
            f(sum(t.cooling, t.heating)),
            f(sum(t.carbon, t.co2_avoided)),
            f(t.stormwater),
            f(sum(t.air_quality, t.bvoc)),
            f(t.aesthetics),
        ]
    });
    TreeYear {
        co2_stored_kg: f(stored),
        co2_sequestered_kg: f(sequestered),
        rain_intercepted_m3: f(rain),
        benefits_usd: f(money),
        own_usd: own.map(f),
        typical_usd,
        typical_benefits_usd: f(typical.map(|t| t.money.total())),
    }
}

/// Every tree's year.
pub fn years(
    trees: &[Planned],
    measured: &HashMap<(String, String), Measured>,
    prototypes: &HashMap<crate::trees::plan::ProtoKey, Prototype>,
) -> Vec<TreeYear> {
    trees
        .iter()
        .map(|t| match &t.kind {
            Kind::Tree(k) => tree_year(
                t,
                measured.get(&(k.region.clone(), k.code.clone())),
                prototypes.get(k),
            ),
            Kind::Stump => tree_year(t, None, None),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trees::plan::ProtoKey;
    use glam::DVec3;

    #[test]
    fn a_tree_s_year_follows_its_own_dbh_and_its_scaled_crown() {
        let m = sylva::growth::Database::builtin()
            .find("InlVal", "PLAC")
            .unwrap();
        let key = ProtoKey {
            region: "InlVal".into(),
            code: "PLAC".into(),
            age: 10,
            variant: 0,
        };
        let dir = tempfile::tempdir().unwrap();
        let protos =
            crate::trees::prototypes::grow_all(std::slice::from_ref(&key), 0, dir.path()).unwrap();
        let p = &protos[&key];
        let tree = |height: f32| Planned {
            row: 0,
            at: DVec3::ZERO,
            kind: Kind::Tree(key.clone()),
            turn: 0.0,
            scale: 1.0,
            age: 10.0,
            dbh: m.dbh(10.0) as f32,
            height,
            crown_diameter: m.crown_diameter(10.0) as f32,
        };
        let y = tree_year(&tree(p.height), Some(&m), Some(p));
        let group = BiomassGroup::of("Platanus x acerifolia").unwrap();
        assert!((y.co2_stored_kg as f64 - co2_stored_kg(group, m.dbh(10.0))).abs() < 1e-3);
        assert!(
            y.co2_sequestered_kg > 0.0 && y.co2_sequestered_kg < y.co2_stored_kg,
            "{y:?}"
        );
        assert!(y.rain_intercepted_m3 > 0.0 && y.benefits_usd > 0.0, "{y:?}");
        // A tree drawn twice as tall holds back four times the rain (until storms fill it).
        let big = tree_year(&tree(2.0 * p.height), Some(&m), Some(p));
        assert!(
            big.rain_intercepted_m3 > 2.0 * y.rain_intercepted_m3,
            "{big:?} {y:?}"
        );
        // At typical position: i-Tree's London plane row at this DBH, every category priced
        // and summed (the plane emits isoprene, so its air quality is net of a BVOC cost).
        let t = Reference::of(&m)
            .unwrap()
            .at(m.dbh(10.0), Prices::builtin("InlVal").as_ref());
        assert!(
            (y.typical_benefits_usd as f64 - t.money.total()).abs() < 1e-3,
            "{y:?}"
        );
        assert!(y.typical_usd.iter().all(|&v| v > 0.0), "{y:?}");
        // Sylva's own: every category but energy (no façade), summed as its benefits.
        assert_eq!(y.own_usd[0], NO_DATA);
        assert!(y.own_usd[1..].iter().all(|&v| v > 0.0), "{y:?}");
        let own: f32 = y.own_usd[1..].iter().sum();
        assert!((own - y.benefits_usd).abs() < 1e-3, "{y:?}");
        let sum: f32 = y.typical_usd.iter().sum();
        assert!((sum - y.typical_benefits_usd).abs() < 1e-3, "{y:?}");
        // A stump gives nothing: every figure is the no-data value.
        let stump = Planned {
            kind: Kind::Stump,
            ..tree(0.3)
        };
        let gone = tree_year(&stump, None, None);
        assert_eq!(gone.benefits_usd, NO_DATA);
        assert_eq!(gone.typical_benefits_usd, NO_DATA);
    }
}
