//! Light and climate at the street: the sun and the crown's shadow, the region's climate and
//! rain, the canopy's effect on air and wind, and what a crown stops of a beam. It reads the
//! planting site (`street::site`) and nothing of the other rooms.

pub mod climate;
pub mod climate_effect;
pub mod crown;
pub mod opacity;
pub mod shade;
pub mod sun;
