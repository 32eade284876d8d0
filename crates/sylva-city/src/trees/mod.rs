//! The city's trees: where each stands at each epoch and what it is grown as (`plan`), the
//! shared trees grown once and meshed at three levels of detail (`prototypes`), and each
//! tree's yearly benefits by the street's models (`benefits`), and each epoch's planting plan
//! for CAD (`cad`).

pub mod benefits;
pub mod cad;
pub mod plan;
pub mod prototypes;
