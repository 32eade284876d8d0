//! One year's account of a street tree: what it gave, what it cost, and what it ran into.
//!
//! ```
//! use sylva::growth::{Database, measure};
//! use sylva::growth::survey::report::Cohort;
//! use sylva::street::Assessor;
//! let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
//! let mut assessor = Assessor::new(&plane, None, None, None);
//! let mut cohort = Cohort::new(vec![plane], 0);
//! let skeleton = cohort.advance_to(10.0).remove(0);
//! let year = assessor.year(10.0, &measure(&skeleton), &skeleton);
//! assert!(year.co2_stored_kg.unwrap() > 0.0);
//! assert!(year.interception_m3.unwrap() > 0.0);
//! assert!(year.energy.is_none()); // no site, no façade to shade
//! ```

use crate::Skeleton;
use crate::growth::{Dimensions, Measured};
use crate::street::accounts::carbon::{BiomassGroup, co2_sequestered_kg, co2_stored_kg};
use crate::street::accounts::costs::{Costs, YearCosts};
use crate::street::accounts::items::Cost;
use crate::street::accounts::money::{Basis, Money};
use crate::street::accounts::prices::Prices;
use crate::street::accounts::survival::{Cohort, Survival};
use crate::street::accounts::typical::{AirQuality, EmissionFactors, Reference, Typical};
use crate::street::energy::climate::{Climate, climate, interception_m3};
use crate::street::energy::climate_effect::climate_effect;
use crate::street::energy::crown::{Crown, leaves_of};
use crate::street::energy::shade::{Energy, Sky, energy};
use crate::street::error::StreetError;
use crate::street::site::Site;
use crate::street::work::conflicts::{Conflict, conflicts_with, leaf_outside_zones};
use crate::street::work::roots::{RootDamage, Rooting, distance_to_pavement, mitigated_share};

/// One year of one tree.
#[derive(Clone, Debug, PartialEq)]
pub struct YearAccount {
    /// Age, years since planting.
    pub age: f64,
    /// The grown trunk diameter, cm.
    pub dbh_cm: f64,
    /// Leaf area, bark area and crown projection of the grown tree, m².
    pub surfaces: (f64, f64, f64),
    /// CO2 held in the tree, kg.
    pub co2_stored_kg: Option<f64>,
    /// CO2 taken up this year, kg.
    pub co2_sequestered_kg: Option<f64>,
    /// Rain held back this year, m³.
    pub interception_m3: Option<f64>,
    /// Shade on the façade and its energy effects.
    pub energy: Option<Energy>,
    /// CO2 not emitted thanks to the energy the façade's shade saves, kg.
    pub co2_avoided_kg: Option<f64>,
    /// Pollutants taken up by the grown crown (i-Tree's uptake per square metre of leaf at
    /// this DBH, times the crown's own leaf area), and not emitted thanks to its energy
    /// savings, where there is a façade.
    pub air: Option<AirQuality>,
    /// Leaf area gained this year by the grown crown, m².
    pub leaf_gain_m2: f64,
    /// The benefits of the grown tree on this site, in dollars.
    pub money: Money,
    /// i-Tree Streets' figures for the species at this DBH, where the region's tables have
    /// its row or class.
    pub typical: Option<Typical>,
    /// The costs in dollars, where a cost table was given.
    pub costs: Option<YearCosts>,
    /// Conflicts with the site this year (after this year's pruning, where there was one).
    pub conflicts: Vec<Conflict>,
    /// Leaf area outside every zone the site keeps clear, m² (none without a site).
    pub leaf_outside_zones_m2: Option<f64>,
    /// This year's pruning, where a cycle fell due and the tree was grown with the site's
    /// regime ([`crate::street::accounts::pruner`]).
    pub pruning: Option<crate::street::accounts::pruner::PruningYear>,
    /// Each of the site's lines in every whole year since the account before, where the tree
    /// was grown with the site's regime: how near the tree came before the year's cuts, and
    /// the utility's visit.
    pub lines: Vec<crate::street::accounts::pruner::LineYear>,
    /// The share of the trees planted that stand through this year, and that die in it
    /// ([`crate::street::accounts::survival`]): every other figure is a living tree's.
    pub cohort: Cohort,
}

impl YearAccount {
    /// The benefits of an account, dollars: the typical position's where asked for and known,
    /// else the grown tree's own.
    pub fn money(&self, basis: Basis) -> &Money {
        match (basis, &self.typical) {
            (Basis::Typical, Some(t)) => &t.money,
            _ => &self.money,
        }
    }

    /// Benefits less costs of what is computed, dollars: a living tree's.
    pub fn net(&self, basis: Basis) -> f64 {
        self.money(basis).total() - self.costs.map_or(0.0, |c| c.total())
    }

    /// Benefits per tree planted: a living tree's, weighted by the share standing.
    pub fn planted_benefits(&self, basis: Basis) -> f64 {
        self.cohort.alive * self.money(basis).total()
    }

    /// Costs per tree planted: planting for every tree, the rest for those standing (a dying
    /// tree's removal is in a living tree's costs as its chance of dying).
    pub fn planted_costs(&self) -> f64 {
        self.costs.map_or(0.0, |c| c.per_planted(self.cohort.alive))
    }

    /// Benefits less costs per tree planted.
    pub fn planted_net(&self, basis: Basis) -> f64 {
        self.planted_benefits(basis) - self.planted_costs()
    }

    /// Puts the pruning of the `span` years this account stands for (1 in a yearly run) into
    /// the account of a tree grown under a pruning regime: the conflicts it resolved, and its
    /// cost where the account has costs, a year's share of it, the city's crews apart from
    /// the utility's line clearance. The cycles replace the cost table's own pruning
    /// ([`Assessor::charge_cycles`]).
    pub fn record_pruning(
        &mut self,
        cycle: Option<crate::street::accounts::pruner::PruningYear>,
        span: f64,
    ) {
        if let Some(costs) = &mut self.costs {
            let span = span.max(1.0);
            let (all, line) = cycle.as_ref().map_or((0.0, 0.0), |c| (c.cost, c.line_cost));
            costs[Cost::Cycles] = (all - line) / span;
            costs[Cost::LineClearance] = line / span;
        }
        self.pruning = cycle.map(|mut c| {
            c.settle(&self.conflicts);
            c
        });
    }
}

/// Keeps a tree's account from year to year.
pub struct Assessor {
    measured: Measured,
    group: Option<BiomassGroup>,
    evergreen: bool,
    climate: Option<&'static Climate>,
    site: Option<Site>,
    prices: Option<Prices>,
    costs: Option<Costs>,
    reference: Option<Reference>,
    factors: Option<EmissionFactors>,
    last: Option<(f64, f64)>,
    /// The most leaf area the crown has held so far, m².
    most_leaf: f64,
    /// The age of the last account, years.
    last_age: Option<f64>,
    /// The grown DBH of the last account, cm.
    last_dbh: Option<f64>,
    /// Where there is a site: how far the trunk stands from the pavement, m, the species'
    /// rooting habit, and the share of the damage and its repairs the site's mitigations
    /// leave: the roots' chance of damaging it (`street::work::roots`).
    pavement: Option<(f64, Rooting, f64)>,
    /// What the site's mitigations cost at planting, $.
    mitigation: f64,
    survival: Survival,
    cycles_charged: bool,
    missing: Vec<String>,
}

impl Assessor {
    /// An account for a species: `prices` default to the region's built-in ones; without a
    /// site there is no façade to shade and no conflict; without costs none are charged.
    pub fn new(
        m: &Measured,
        site: Option<Site>,
        prices: Option<Prices>,
        costs: Option<Costs>,
    ) -> Assessor {
        let region = &m.region.code;
        let group = BiomassGroup::of(&m.species.scientific);
        let climate = climate(region);
        let prices = prices.or_else(|| Prices::builtin(region));
        let costs = costs.or_else(|| Costs::builtin(region));
        let mut missing = Vec::new();
        if group.is_none() {
            missing.push(format!(
                "carbon: {} ({}) has no species group in Jenkins et al. (2003)",
                m.species.code, m.species.scientific
            ));
        }
        let has_rain = climate.and_then(|c| c.rain).is_some();
        // Without a site the account is the typical position's, whose energy i-Tree's tables
        // give; a site without a façade leaves its own account without energy.
        if site.as_ref().is_some_and(|s| s.facade.is_none()) {
            missing.push("energy: the site has no façade to shade (give it a [facade])".into());
        }
        // What the utility's cuts do to the tree is measured only as decay, not as years of
        // life or value lost: Dahle et al. (2006, AUF 32(6)) found 80% of headed silver
        // maple leaders decayed, the columns some 2.5 times longer than the decay seen from
        // outside, and gave no loss of life. So the harm is named, not charged; each headed
        // leader is counted in the pruning record, and `rank` says such a species does not
        // suit the site.
        if site.as_ref().is_some_and(|s| !s.wire.is_empty()) {
            missing.push(
                "harm of repeated line clearance to the tree (decay from heading cuts, a \
                 shorter life): no source quantifies it as life or value lost (Dahle et al. \
                 2006 measured the decay only); the headed leaders are counted, not charged"
                    .into(),
            );
        }
        match &prices {
            None => missing.push(format!(
                "money: no built-in prices for {region} (give --prices)"
            )),
            Some(p) if p.electricity_per_kwh.is_none() => missing.push(format!(
                "money for electricity: no usable built-in price for {region} (give --prices)"
            )),
            _ => {}
        }
        match &costs {
            // Every region has the built-in sized table.
            None => {}
            Some(Costs::Average(a)) => missing.push(format!(
                "itemised costs: each year is charged {}: ${:.2} a tree, not sized by the tree",
                a.source, a.per_tree_per_year
            )),
            Some(c @ Costs::Itemised(_)) => missing.extend(c.not_computed()),
        }
        let reference = Reference::of(m)
            .map_err(|why| {
                missing.push(format!(
                    "typical position: {why}; the grown tree's own figures stand in, and its air \
                     quality, which is scaled from i-Tree's rates, is not computed"
                ))
            })
            .ok();
        // Without a sourced rainfall, i-Tree's own rain (in its interception per m² of leaf)
        // stands in; without either, interception is not computed.
        if !has_rain && reference.is_none() {
            missing.push(format!(
                "rainfall interception: no sourced rainfall for {} ({}), and no i-Tree row",
                region, m.region.city
            ));
        }
        if prices.as_ref().and_then(|p| p.leaf_gain_per_m2).is_none() {
            missing.push(
                "aesthetics and property value: the leaf area gained is counted (m²) but not \
                 priced: no median home price for the region (give --prices with \
                 median_home_price or leaf_gain_per_m2)"
                    .into(),
            );
        }
        let pavement = site.as_ref().map(|s| {
            (
                distance_to_pavement(s),
                RootDamage::builtin().rooting(&m.species.scientific),
                mitigated_share(s),
            )
        });
        let mitigation = match (site.as_ref().and_then(|s| s.mitigation.as_ref()), &costs) {
            (Some(m), Some(c)) => c.mitigation(m).unwrap_or_else(|e| {
                missing.push(format!("root mitigation: {e}"));
                0.0
            }),
            _ => 0.0,
        };
        Assessor {
            measured: m.clone(),
            group,
            evergreen: m.species.tree_type.get(1..2) == Some("E"),
            climate,
            site,
            prices,
            costs,
            factors: reference.as_ref().map(|r| EmissionFactors::of(r.region())),
            reference,
            last: None,
            most_leaf: 0.0,
            last_age: None,
            last_dbh: None,
            pavement,
            mitigation,
            survival: Survival::builtin(region),
            cycles_charged: false,
            missing,
        }
    }

    /// The same account with another survival (`--survival`).
    pub fn with_survival(mut self, survival: Survival) -> Assessor {
        self.survival = survival;
        self
    }

    /// The survival the account weighs its years by.
    pub fn survival(&self) -> &Survival {
        &self.survival
    }

    /// Says the tree is grown under a site's pruning regime whose cycles are charged as they
    /// fall ([`YearAccount::record_pruning`]): the cost table's own pruning is then not
    /// charged, nor a programme average's pruning share, so no cut is paid for twice.
    pub fn charge_cycles(&mut self) {
        self.cycles_charged = true;
    }

    /// Where the typical-position figures come from, where they do.
    pub fn reference(&self) -> Option<&Reference> {
        self.reference.as_ref()
    }

    /// The benefits and costs not computed for this species, each with its reason.
    pub fn missing(&self) -> &[String] {
        &self.missing
    }

    /// An error naming what is missing for a species whose every model was asked for (the
    /// carbon model needs a biomass group).
    pub fn require_carbon(&self) -> Result<(), StreetError> {
        if self.group.is_some() {
            return Ok(());
        }
        Err(StreetError::Missing(format!(
            "{} ({}): no biomass group: Jenkins et al. (2003) place no species of the genus \
             `{}`; allowed: hardwood genera and the conifers Abies, Calocedrus, \
             Chamaecyparis, Cupressus, Juniperus, Larix, Picea, Pinus, Platycladus, \
             Pseudotsuga, Sequoia, Thuja, Tsuga (docs/benefits.md)",
            self.measured.species.code,
            self.measured.species.scientific,
            self.measured
                .species
                .scientific
                .split_whitespace()
                .next()
                .unwrap_or("")
        )))
    }

    /// The site, if any.
    pub fn site(&self) -> Option<&Site> {
        self.site.as_ref()
    }

    /// Whether a cost table was given.
    pub fn has_costs(&self) -> bool {
        self.costs.is_some()
    }

    /// The account of the year that ends at `age`, for the tree grown to `dims` and
    /// `skeleton`. Call in rising order of age.
    pub fn year(&mut self, age: f64, dims: &Dimensions, skeleton: &Skeleton) -> YearAccount {
        let leaves = leaves_of(skeleton);
        // The crown and its shade on the façade, and the site's conflicts, read the same leaves
        // and nothing of each other: on two threads they take the longer one's time, not the
        // sum (`sylva bench --street`).
        let ((crown, energy), conflicts) = rayon::join(
            || {
                let crown = Crown::with_leaves(skeleton, &leaves).with_wood(skeleton);
                let energy = self.energy_on(&crown);
                (crown, energy)
            },
            || self.conflicts_on(skeleton, &leaves),
        );
        self.account(age, dims, &crown, energy, conflicts)
    }

    /// [`Assessor::year`] on the tree's leaves ([`leaves_of`]) and crown (with its leaves and
    /// wood) already made: they are the same on every site, so a tree accounted on several
    /// (the page's) makes them once a year, not once a site.
    pub fn year_on(
        &mut self,
        age: f64,
        dims: &Dimensions,
        skeleton: &Skeleton,
        (leaves, crown): (&[(glam::Vec3, f64)], &Crown),
    ) -> YearAccount {
        let (energy, conflicts) = rayon::join(
            || self.energy_on(crown),
            || self.conflicts_on(skeleton, leaves),
        );
        self.account(age, dims, crown, energy, conflicts)
    }

    /// The crown's shade on the site's façade, as energy, where the site has a façade and
    /// the region a climate.
    fn energy_on(&self, crown: &Crown) -> Option<Energy> {
        let facade = self.site.as_ref().and_then(|s| s.facade.as_ref());
        match (facade, self.climate) {
            (Some(f), Some(c)) => {
                let mut e = energy(crown, f, &Sky::of(c), self.evergreen);
                if let Some(k) = climate_effect(c.region) {
                    e.climate = Some(k.of(crown.projection));
                    e.useful_winter_share = k.useful_share();
                }
                Some(e)
            }
            _ => None,
        }
    }

    /// The site's conflicts with the tree, and its leaf outside the site's zones, m².
    fn conflicts_on(
        &self,
        skeleton: &Skeleton,
        leaves: &[(glam::Vec3, f64)],
    ) -> (Vec<Conflict>, Option<f64>) {
        let conflicts = (self.site.as_ref())
            .map(|s| conflicts_with(skeleton, leaves, s))
            .unwrap_or_default();
        let outside = (self.site.as_ref()).map(|s| leaf_outside_zones(leaves, s));
        (conflicts, outside)
    }

    /// The year's account from what the tree's crown and the site made of it.
    fn account(
        &mut self,
        age: f64,
        dims: &Dimensions,
        crown: &Crown,
        energy: Option<Energy>,
        (conflicts, leaf_outside_zones_m2): (Vec<Conflict>, Option<f64>),
    ) -> YearAccount {
        let dbh = dims.dbh;
        let stored = self.group.map(|g| co2_stored_kg(g, dbh));
        let sequestered = stored.map(|now| {
            let g = self.group.expect("stored implies a group");
            match self.last {
                Some((a, before)) if age > a => (now - before) / (age - a),
                // The first year of a run.
                _ => co2_sequestered_kg(g, &self.measured, age, dbh),
            }
        });
        if let Some(now) = stored {
            self.last = Some((age, now));
        }
        let p = self.prices.as_ref();
        let typical = self.reference.as_ref().map(|r| r.at(dbh, p));
        // i-Tree's per-tree amounts that scale with leaf (air quality, and rain where no
        // rainfall is sourced) are carried over per m² of leaf at this DBH to the grown crown.
        let per_leaf = typical.as_ref().map(|t| {
            if t.amounts.leaf_area_m2 > 0.0 {
                crown.leaf_area / t.amounts.leaf_area_m2
            } else {
                0.0
            }
        });
        let interception = match self.climate.and_then(|c| c.rain) {
            Some(r) => Some(interception_m3(
                &r,
                crown.leaf_area + crown.bark_area,
                crown.projection,
            )),
            None => typical
                .as_ref()
                .zip(per_leaf)
                .map(|(t, k)| t.amounts.stormwater_m3 * k),
        };
        // The leaf area gained over the most the crown has held: leaf regrown after a cut
        // only restores what it had, and is not a gain again (aesthetics price the gain).
        let leaf_gain = match self.last_age {
            Some(a) if age > a => ((crown.leaf_area - self.most_leaf) / (age - a)).max(0.0),
            // The first year of a run: the mean gain since planting.
            _ => crown.leaf_area / age.max(1.0),
        };
        self.most_leaf = self.most_leaf.max(crown.leaf_area);
        // Energy saved on the façade, as i-Tree counts it: kWh, and kBtu of gas (negative).
        let saved = energy.map(|e| (e.electricity_kwh(), e.natural_gas_kbtu()));
        let avoided = saved
            .zip(self.factors)
            .map(|((kwh, kbtu), f)| f.avoided(kwh, kbtu));
        // i-Tree's uptake and BVOC emission per square metre of leaf at this DBH, on the
        // grown crown's own leaf area.
        let air = typical.as_ref().zip(per_leaf).map(|(t, k)| {
            let a = &t.amounts;
            AirQuality {
                ozone_kg: a.air.ozone_kg * k,
                nox_kg: a.air.nox_kg * k,
                pm10_kg: a.air.pm10_kg * k,
                so2_kg: a.air.so2_kg * k,
                avoided_kg: avoided.map_or([0.0; 4], |a| a.1),
                bvoc_kg: a.air.bvoc_kg * k,
            }
        });
        let price = |amount: Option<f64>, per: Option<f64>| amount.zip(per).map(|(a, p)| a * p);
        let air_value = air.zip(p).and_then(|(a, p)| a.value(p));
        let money = Money {
            carbon: price(sequestered, p.and_then(|p| p.co2_per_kg)),
            co2_avoided: price(avoided.map(|a| a.0), p.and_then(|p| p.co2_per_kg)),
            stormwater: price(interception, p.and_then(|p| p.stormwater_per_m3)),
            cooling: price(
                energy.map(|e| e.electricity_kwh()),
                p.and_then(|p| p.electricity_per_kwh),
            ),
            heating: price(
                energy.map(|e| e.natural_gas_kbtu()),
                p.and_then(|p| p.natural_gas_per_kbtu),
            ),
            air_quality: air_value.map(|v| v.0),
            bvoc: air_value.map(|v| v.1),
            aesthetics: price(Some(leaf_gain), p.and_then(|p| p.leaf_gain_per_m2)),
        };
        // The years this account stands for: one in a yearly run, more where a run records
        // every few years.
        let first = self.last_age.is_none();
        let span = self.last_age.map_or(1.0, |a| (age - a).max(1e-9));
        self.last_age = Some(age);
        let cohort = self.survival.year(age, span);
        let death_chance = if cohort.alive > 0.0 {
            cohort.died / cohort.alive
        } else {
            0.0
        };
        // The roots' chance of damaging the pavement this year, as a yearly rate over the
        // years this account stands for; the first year of a run grows from last year's DBH
        // by the measured curve.
        let before = (self.last_dbh).unwrap_or_else(|| self.measured.dbh((age - 1.0).max(0.0)));
        self.last_dbh = Some(dbh);
        let damage_chance = self.pavement.as_ref().map(|(distance, rooting, share)| {
            share * RootDamage::builtin().chance(before, dbh, *distance, rooting) / span.max(1.0)
        });
        YearAccount {
            age,
            dbh_cm: dbh,
            surfaces: (crown.leaf_area, crown.bark_area, crown.projection),
            co2_stored_kg: stored,
            co2_sequestered_kg: sequestered,
            interception_m3: interception,
            energy,
            co2_avoided_kg: avoided.map(|a| a.0),
            air,
            leaf_gain_m2: leaf_gain,
            money,
            typical,
            costs: self.costs.as_ref().map(|c| {
                let mut y = c.year(age, dbh, death_chance, damage_chance, self.cycles_charged);
                // A species whose data begin after its first year is planted in the first year
                // of its run all the same.
                if first && age > 1.0 {
                    y[Cost::Planting] += c.planting_price();
                }
                // The site's mitigations are made at planting.
                if first {
                    y[Cost::Mitigation] = self.mitigation;
                }
                y
            }),
            pruning: None,
            lines: Vec::new(),
            conflicts,
            leaf_outside_zones_m2,
            cohort,
        }
    }
}
