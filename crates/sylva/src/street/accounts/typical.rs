//! The typical-position account: what i-Tree Streets says a tree of this species and trunk
//! diameter yields in a year, standing at its usual spread of distances and directions from
//! buildings, priced at the region's prices.
//!
//! This is the reference Sylva's own figures are held to, and the account shown wherever no
//! site is given. The tables are [`crate::street::accounts::itree`]'s; a species finds its row as i-Tree
//! does (its own, i-Tree's assignment, a relative of the same genus and tree type, or its tree
//! type's `OTHER` class), and the values are interpolated at the grown tree's DBH.
//!
//! [`EmissionFactors`] recovers, from the same tables, what each kWh and kBtu saved keeps out of
//! the air in the region, so that energy Sylva computes on a site's façade can be turned into
//! avoided emissions the way i-Tree turns its own.

use crate::growth::Measured;
use crate::street::accounts::itree::{self, DBH_CLASSES_CM, Factor, Match, Region};
use crate::street::accounts::money::Money;
use crate::street::accounts::prices::Prices;

/// Pollutants taken up by the leaves or not emitted by power plants and furnaces, and the
/// biogenic VOCs the leaves emit, kg a year.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AirQuality {
    /// Ozone taken up.
    pub ozone_kg: f64,
    /// NOx taken up.
    pub nox_kg: f64,
    /// PM10 taken up.
    pub pm10_kg: f64,
    /// SO2 taken up.
    pub so2_kg: f64,
    /// NOx, PM10, SO2 and VOC not emitted thanks to the energy saved.
    pub avoided_kg: [f64; 4],
    /// Biogenic VOCs emitted (a cost; zero or more).
    pub bvoc_kg: f64,
}

impl AirQuality {
    /// Everything taken up or not emitted, kg (BVOCs not subtracted).
    pub fn removed_kg(&self) -> f64 {
        self.ozone_kg
            + self.nox_kg
            + self.pm10_kg
            + self.so2_kg
            + self.avoided_kg.iter().sum::<f64>()
    }

    /// Its worth at `p`: (pollutants removed, BVOCs emitted as a negative), dollars; `None`
    /// where a price is missing.
    pub fn value(&self, p: &Prices) -> Option<(f64, f64)> {
        let [nox_a, pm10_a, so2_a, voc_a] = self.avoided_kg;
        let removed = self.ozone_kg * p.ozone_per_kg?
            + (self.nox_kg + nox_a) * p.nox_per_kg?
            + (self.pm10_kg + pm10_a) * p.pm10_per_kg?
            + (self.so2_kg + so2_a) * p.so2_per_kg?
            + voc_a * p.voc_per_kg?;
        Some((removed, -self.bvoc_kg * p.voc_per_kg?))
    }
}

/// One year at typical position, in i-Tree's units.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Amounts {
    /// Cooling saved, kWh.
    pub electricity_kwh: f64,
    /// Heating saved, kBtu; negative where winter shade costs more than wind shelter saves.
    pub natural_gas_kbtu: f64,
    /// Rain held back, m³.
    pub stormwater_m3: f64,
    /// CO2 taken up, net of decomposition and care, kg.
    pub co2_sequestered_kg: f64,
    /// CO2 not emitted thanks to the energy saved, kg.
    pub co2_avoided_kg: f64,
    /// Air quality.
    pub air: AirQuality,
    /// Leaf area gained this year, m² (i-Tree's `property_value` table: what it prices
    /// aesthetics and property value from).
    pub leaf_gain_m2: f64,
    /// Leaf area of the tree, m² (a stock).
    pub leaf_area_m2: f64,
}

/// The typical-position account of one year.
#[derive(Clone, Debug, PartialEq)]
pub struct Typical {
    /// The i-Tree region whose tables were read.
    pub region: &'static str,
    /// The table row read, and how the species found it.
    pub row: String,
    /// How the row was found.
    pub matched: Match,
    /// The DBH lay outside the class midpoints (3.81 to 114.3 cm) and the end class was held.
    pub held: bool,
    /// The figures.
    pub amounts: Amounts,
    /// Their worth.
    pub money: Money,
}

/// Where a species' typical-position figures come from.
#[derive(Clone, Debug)]
pub struct Reference {
    region_name: &'static str,
    region: &'static Region,
    row: String,
    matched: Match,
    /// Why another region's tables stand in, where they do.
    pub stand_in: Option<&'static str>,
}

impl Reference {
    /// The reference row of a grown species, or why there is none.
    pub fn of(m: &Measured) -> Result<Reference, String> {
        let name = &m.region.code;
        let (region_name, stand_in) = itree::reference_region(name)
            .ok_or_else(|| format!("i-Tree Streets has no tables for the region {name}"))?;
        let region = itree::region(region_name).expect("reference_region names a table");
        let s = &m.species;
        let (row, matched) = region
            .resolve(&s.code, &s.scientific, &s.tree_type)
            .ok_or_else(|| {
                format!(
                    "{region_name}'s tables have neither {} nor an OTHER class of its tree type \
                     {}",
                    s.code, s.tree_type
                )
            })?;
        Ok(Reference {
            region_name,
            region,
            row,
            matched,
            stand_in,
        })
    }

    /// The table row read.
    pub fn row(&self) -> &str {
        &self.row
    }

    /// How the row was found, in words.
    pub fn describe(&self) -> String {
        let how = match &self.matched {
            Match::Species => "the species' own row".to_string(),
            Match::Assigned => "the row i-Tree assigns the species".to_string(),
            Match::Genus(code) => {
                format!("the row of {code}, a listed relative of the same genus and tree type")
            }
            Match::TreeType => "its tree type's OTHER class".to_string(),
        };
        format!(
            "i-Tree Streets {} `{}`: {how}{}",
            self.region_name,
            self.row,
            self.stand_in.map(|w| format!(" ({w})")).unwrap_or_default()
        )
    }

    /// The region's tables.
    pub fn region(&self) -> &'static Region {
        self.region
    }

    /// The account at `dbh_cm`, priced at `prices` where given.
    pub fn at(&self, dbh_cm: f64, prices: Option<&Prices>) -> Typical {
        let mut held = false;
        let mut v = |f: Factor| match self.region.value(f, &self.row, dbh_cm) {
            Some(l) => {
                held |= l.held;
                l.value
            }
            // Every row holds every factor (itree's tests check all 16 regions).
            None => unreachable!("{} {} has no {}", self.region_name, self.row, f.name()),
        };
        let amounts = Amounts {
            electricity_kwh: v(Factor::Electricity),
            natural_gas_kbtu: v(Factor::NaturalGas),
            stormwater_m3: v(Factor::HydroInterception),
            co2_sequestered_kg: v(Factor::Co2Sequestered),
            co2_avoided_kg: v(Factor::Co2Avoided),
            air: AirQuality {
                ozone_kg: v(Factor::AqOzoneDep),
                nox_kg: v(Factor::AqNoxDep),
                pm10_kg: v(Factor::AqPm10Dep),
                so2_kg: v(Factor::AqSoxDep),
                avoided_kg: [
                    v(Factor::AqNoxAvoided),
                    v(Factor::AqPm10Avoided),
                    v(Factor::AqSoxAvoided),
                    v(Factor::AqVocAvoided),
                ],
                // Published as a negative; kept here as the amount emitted.
                bvoc_kg: -v(Factor::Bvoc),
            },
            leaf_gain_m2: v(Factor::PropertyValue),
            leaf_area_m2: v(Factor::Lsa),
        };
        Typical {
            region: self.region_name,
            row: self.row.clone(),
            matched: self.matched.clone(),
            held,
            money: price(&amounts, prices),
            amounts,
        }
    }
}

/// The worth of a year's amounts at `prices`; each category `None` where its price is.
pub fn price(a: &Amounts, prices: Option<&Prices>) -> Money {
    let p = |f: fn(&Prices) -> Option<f64>| prices.and_then(f);
    let air = prices.and_then(|p| a.air.value(p));
    Money {
        carbon: p(|p| p.co2_per_kg).map(|c| a.co2_sequestered_kg * c),
        co2_avoided: p(|p| p.co2_per_kg).map(|c| a.co2_avoided_kg * c),
        stormwater: p(|p| p.stormwater_per_m3).map(|c| a.stormwater_m3 * c),
        cooling: p(|p| p.electricity_per_kwh).map(|c| a.electricity_kwh * c),
        heating: p(|p| p.natural_gas_per_kbtu).map(|c| a.natural_gas_kbtu * c),
        air_quality: air.map(|a| a.0),
        bvoc: air.map(|a| a.1),
        aesthetics: p(|p| p.leaf_gain_per_m2).map(|c| a.leaf_gain_m2 * c),
    }
}

/// What a kWh of electricity and a kBtu of natural gas saved keep out of the air in a region,
/// kg: CO2, NOx, PM10, SO2 and VOC, each as (per kWh, per kBtu).
///
/// i-Tree does not publish its regional emission factors beside the tables, but its avoided
/// emissions are linear in the energy saved, so a least-squares fit over every row and DBH
/// class of the region's electricity and natural-gas tables recovers them. The fit is exact to
/// a few per cent of the largest value in every region but Boise's CO2 (see the test).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissionFactors {
    /// CO2, NOx, PM10, SO2 and VOC: (kg per kWh, kg per kBtu).
    pub per: [(f64, f64); 5],
}

impl EmissionFactors {
    /// The factors of a region's tables.
    pub fn of(region: &Region) -> EmissionFactors {
        const TARGETS: [Factor; 5] = [
            Factor::Co2Avoided,
            Factor::AqNoxAvoided,
            Factor::AqPm10Avoided,
            Factor::AqSoxAvoided,
            Factor::AqVocAvoided,
        ];
        // Normal equations of y = a·kWh + b·kBtu, summed over every row and class.
        let (mut ee, mut eg, mut gg) = (0.0, 0.0, 0.0);
        let mut ey = [0.0; 5];
        let mut gy = [0.0; 5];
        for row in region.rows() {
            for &d in &DBH_CLASSES_CM {
                let at = |f: Factor| region.value(f, row, d).map(|l| l.value);
                let (Some(e), Some(g)) = (at(Factor::Electricity), at(Factor::NaturalGas)) else {
                    continue;
                };
                ee += e * e;
                eg += e * g;
                gg += g * g;
                for (i, &f) in TARGETS.iter().enumerate() {
                    let y = at(f).unwrap_or(0.0);
                    ey[i] += e * y;
                    gy[i] += g * y;
                }
            }
        }
        let det = ee * gg - eg * eg;
        let mut per = [(0.0, 0.0); 5];
        for i in 0..5 {
            per[i] = if det.abs() > 1e-9 * ee * gg.max(1.0) && gg > 0.0 {
                (
                    (gg * ey[i] - eg * gy[i]) / det,
                    (ee * gy[i] - eg * ey[i]) / det,
                )
            } else if ee > 0.0 {
                // No heating in the region (Hawaii's tables hold no gas): electricity alone.
                (ey[i] / ee, 0.0)
            } else {
                (0.0, 0.0)
            };
        }
        EmissionFactors { per }
    }

    /// Emissions avoided by saving `kwh` and `kbtu` (negative where energy is added): CO2, and
    /// NOx, PM10, SO2, VOC.
    pub fn avoided(&self, kwh: f64, kbtu: f64) -> (f64, [f64; 4]) {
        let f = |i: usize| self.per[i].0 * kwh + self.per[i].1 * kbtu;
        (f(0), [f(1), f(2), f(3), f(4)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::Database;

    fn species(region: &str, code: &str) -> Measured {
        Database::builtin().find(region, code).unwrap()
    }

    #[test]
    fn camphor_in_modesto_at_typical_position_is_a_net_benefit() {
        let camphor = species("InlVal", "CICA");
        let r = Reference::of(&camphor).unwrap();
        assert_eq!(r.row(), "CICA");
        let prices = Prices::builtin("InlVal").unwrap();
        let t = r.at(38.1, Some(&prices));
        // The published row at the 38.1 cm class: 154.6 kWh, -46.2 kBtu, 4.18 m³.
        assert!((t.amounts.electricity_kwh - 154.6).abs() < 1e-9);
        assert!((t.amounts.natural_gas_kbtu + 46.2).abs() < 1e-9);
        assert!((t.amounts.stormwater_m3 - 4.18).abs() < 1e-9);
        // The winter penalty is 58 cents, not hundreds of dollars.
        let heating = t.money.heating.unwrap();
        assert!((heating + 46.2 * 0.0125278).abs() < 1e-9, "{heating}");
        assert!(t.money.total() > 30.0, "{:?}", t.money);
        assert!(!t.held);
        // Aesthetics: the leaf gain priced per m² from Stanislaus County's median sale price.
        assert!((t.amounts.leaf_gain_m2 - 11.6).abs() < 1e-9);
        let aesthetics = t.money.aesthetics.unwrap();
        assert!((aesthetics - 11.6 * 0.0088 * 140_000.0 / 675.0).abs() < 1e-9);
    }

    /// i-Tree's `property_value` table, which Streets prices aesthetics from, is the yearly
    /// gain in leaf area: its `lsa` table's rise per cm of DBH times how fast the trunk grows
    /// there (the Urban Tree Database's age-DBH curve for the same species and region).
    #[test]
    fn property_value_is_the_yearly_gain_of_the_lsa_table() {
        use crate::growth::Database;
        use crate::street::accounts::itree::{DBH_CLASSES_CM, Factor, region};
        let db = Database::builtin();
        for name in ["InlVal", "NoEast", "Piedmt"] {
            let tables = region(name).unwrap();
            let mut ratios = Vec::new();
            for s in db.growable(name) {
                let m = db.find(name, &s.code).unwrap();
                let Some(row) = tables.row_for(&m.species.code) else {
                    continue;
                };
                if row != m.species.code {
                    continue;
                }
                for i in 1..8 {
                    let (a, x, b) = (
                        DBH_CLASSES_CM[i - 1],
                        DBH_CLASSES_CM[i],
                        DBH_CLASSES_CM[i + 1],
                    );
                    let v = |f: Factor, d: f64| tables.value(f, &row, d).map(|l| l.value);
                    let (Some(la), Some(lb), Some(gain)) = (
                        v(Factor::Lsa, a),
                        v(Factor::Lsa, b),
                        v(Factor::PropertyValue, x),
                    ) else {
                        continue;
                    };
                    // Only where the measured curve reaches the class.
                    let age = m.age_at_dbh(x);
                    if age <= m.ages.0 + 1.0 || age >= m.ages.1 - 1.0 || gain <= 0.0 {
                        continue;
                    }
                    let growth = m.dbh(age + 0.5) - m.dbh(age - 0.5);
                    ratios.push(gain / ((lb - la) / (b - a) * growth));
                }
            }
            ratios.sort_by(f64::total_cmp);
            let median = ratios[ratios.len() / 2];
            assert!(ratios.len() > 20, "{name}: {}", ratios.len());
            assert!(
                (0.8..1.25).contains(&median),
                "{name}: median {median} of {}",
                ratios.len()
            );
        }
    }

    #[test]
    fn bvoc_is_a_cost_at_the_voc_price() {
        // London plane emits isoprene: 0.636 kg at 38.1 cm in Modesto.
        let plane = species("InlVal", "PLAC");
        let prices = Prices::builtin("InlVal").unwrap();
        let t = Reference::of(&plane).unwrap().at(38.1, Some(&prices));
        assert!((t.amounts.air.bvoc_kg - 0.636).abs() < 1e-9);
        let bvoc = t.money.bvoc.unwrap();
        assert!(
            (bvoc + 0.636 * prices.voc_per_kg.unwrap()).abs() < 1e-9,
            "{bvoc}"
        );
        assert!(t.money.air_quality.unwrap() > -bvoc);
    }

    #[test]
    fn a_tree_past_the_classes_is_held_and_says_so() {
        let plane = species("InlVal", "PLAC");
        let r = Reference::of(&plane).unwrap();
        assert!(r.at(2.0, None).held);
        assert!(r.at(120.0, None).held);
        assert!(!r.at(50.0, None).held);
        // Unpriced: every dollar is missing, not zero.
        assert_eq!(r.at(50.0, None).money, Money::default());
    }

    #[test]
    fn emission_factors_reproduce_the_tables() {
        for (name, region) in itree::regions() {
            let ef = EmissionFactors::of(region);
            let mut worst: [f64; 5] = [0.0; 5];
            let mut largest: [f64; 5] = [0.0; 5];
            for row in region.rows() {
                for &d in &DBH_CLASSES_CM {
                    let at = |f: Factor| region.value(f, row, d).unwrap().value;
                    let (co2, aq) = ef.avoided(at(Factor::Electricity), at(Factor::NaturalGas));
                    let fitted = [co2, aq[0], aq[1], aq[2], aq[3]];
                    let published = [
                        at(Factor::Co2Avoided),
                        at(Factor::AqNoxAvoided),
                        at(Factor::AqPm10Avoided),
                        at(Factor::AqSoxAvoided),
                        at(Factor::AqVocAvoided),
                    ];
                    for i in 0..5 {
                        worst[i] = worst[i].max((fitted[i] - published[i]).abs());
                        largest[i] = largest[i].max(published[i].abs());
                    }
                }
            }
            for i in 0..5 {
                // Boise's BDM OTHER row has zero energy but not zero CO2 avoided, which pulls
                // its fit (CO2 most).
                let bound = match (*name, i) {
                    ("TpIntW", 0) => 0.3,
                    ("TpIntW", _) => 0.1,
                    _ => 0.07,
                };
                assert!(
                    worst[i] <= bound * largest[i],
                    "{name} factor {i}: off by {} of {}",
                    worst[i],
                    largest[i]
                );
            }
        }
        // Modesto's CO2: 0.43 kg a kWh (a Californian mix of gas and hydro plants).
        let modesto = EmissionFactors::of(itree::region("InlVal").unwrap());
        assert!(
            (modesto.per[0].0 - 0.426).abs() < 0.005,
            "{:?}",
            modesto.per[0]
        );
    }

    #[test]
    fn every_region_prices_every_category() {
        let db = Database::builtin();
        for region in db.regions() {
            let region = region.code.as_str();
            let m = db.find(region, &db.growable(region)[0].code).unwrap();
            let Ok(r) = Reference::of(&m) else { continue };
            let prices = Prices::builtin(region).unwrap();
            let t = r.at(30.0, Some(&prices));
            let money = t.money;
            for (name, v) in [
                ("carbon", money.carbon),
                ("stormwater", money.stormwater),
                ("heating", money.heating),
                ("air quality", money.air_quality),
                ("bvoc", money.bvoc),
            ] {
                assert!(v.is_some_and(f64::is_finite), "{region} {name}");
            }
            // North's electricity price is left out as a slip (prices.rs).
            assert_eq!(money.cooling.is_some(), region != "NMtnPr", "{region}");
        }
    }
}
