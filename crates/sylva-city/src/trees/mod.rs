//! The city's trees: where each stands at each epoch and what it is grown as (`plan`), the
//! shared trees grown once and meshed at three levels of detail (`prototypes`), and each
//! tree's yearly benefits by the street's models (`benefits`), each epoch's planting plan
//! for CAD (`cad`), and each grown tree's conflicts on a typical street (`typical`).

pub mod benefits;
pub mod cad;
pub mod plan;
pub mod prototypes;
pub mod typical;
