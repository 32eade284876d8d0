//! Sylva's own site model beside what the inventory recorded (issue Z2): each species with
//! problems recorded, as grown for the city (its age classes, unpruned), set on a typical
//! narrow street (`trees::typical`: a 1.2 m strip between curb and sidewalk, distribution
//! lines over it at 8.5 m). The first age class whose crown enters the lines' clearance is set
//! beside the trees the surveyors found with lights or wires in their branches, under and over
//! that DBH. (Sidewalk damage is the roots model's, `pavement`: the age a trunk's flare reaches
//! the curb says nothing of the flags roots lift well beyond it, years before.)
//!
//! The two are not the same event, and the report says so: the census's "lights or wires in
//! the branches" are mostly string lights and wires hung in the tree (its data dictionary),
//! not the utility lines Sylva's site model clears.

use crate::trees::plan::{Plan, ProtoKey};
use crate::trees::prototypes::Prototype;
pub use crate::trees::typical::SITE;
use serde::Serialize;
use std::collections::HashMap;

/// When a conflict first appears: the age class, years, and the equations' DBH then, cm.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct First {
    /// Age, years since planting.
    pub age: f64,
    /// DBH at that age, cm.
    pub dbh_cm: f64,
}

/// One species on the typical street.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Predicted {
    /// Species code it is grown as.
    pub code: String,
    /// The oldest age class grown for the city, years: nothing is said beyond it.
    pub years: f64,
    /// The crown first enters the lines' clearance.
    pub wire: Option<First>,
}

/// `species` (region, code), each from its grown age classes (first seed variant), in the
/// order given.
pub fn predicted(
    plan: &Plan,
    prototypes: &HashMap<ProtoKey, Prototype>,
    species: &[(String, String)],
) -> Vec<Predicted> {
    species
        .iter()
        .filter_map(|key| {
            let m = plan.measured.get(key)?;
            let mut classes: Vec<&Prototype> = (prototypes.values())
                .filter(|p| p.key.region == key.0 && p.key.code == key.1 && p.key.variant == 0)
                .collect();
            classes.sort_by_key(|p| p.key.age);
            let first = |has: &dyn Fn(&Prototype) -> bool| {
                classes.iter().find(|p| has(p)).map(|p| First {
                    age: f64::from(p.key.age),
                    dbh_cm: m.dbh(f64::from(p.key.age)),
                })
            };
            Some(Predicted {
                code: key.1.clone(),
                years: classes.last().map_or(0.0, |p| f64::from(p.key.age)),
                wire: first(&|p| p.typical_street.wire),
            })
        })
        .collect()
}
