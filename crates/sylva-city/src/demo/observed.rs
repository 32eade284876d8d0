//! What the demo's surveyors "saw": each living tree's condition and the census's problems,
//! so that the report's condition, relative performance and problems have something to show.
//!
//! **Synthetic, not measured.** The shares below are Sylva's choice for a demo, made to look
//! like a street inventory (most trees good, a few poor, sidewalk damage rising with trunk
//! size); no published survey stands behind them. A real inventory's come from its own
//! surveyors. Each value is drawn from a hash of the tree's id, not the demo's random stream,
//! so the demo's trees are the same with these columns as without them.

use super::{DemoLayout, DemoStatus, DemoTree};

/// A number in [0, 1) from the tree's id and what is drawn (FNV-1a, then its top 53 bits).
fn unit(id: &str, what: &str) -> f64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in id.bytes().chain([0]).chain(what.bytes()) {
        h ^= b as u64;
        h = h.wrapping_mul(0x100_0000_01b3);
    }
    h ^= h >> 33;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// The tree's condition class (0 good, 1 fair, 2 poor): a species does better or worse than
/// the rest by up to 15 points of its share in good condition, so that species' relative
/// performance differs.
fn class(t: &DemoTree) -> usize {
    let lean = 0.3 * (unit(&t.scientific, "species") - 0.5);
    let good = 0.72 + lean;
    let roll = unit(&t.id, "condition");
    if roll < good {
        0
    } else if roll < good + 0.7 * (1.0 - good) {
        1
    } else {
        2
    }
}

/// The cells `layout` adds after a row's `planted`: the census's `health`, `sidewalk`,
/// `brch_light`, `trunk_wire`, `trnk_light`, `root_stone`, `root_grate`; a GIS export's
/// `CONDITION` in i-Tree's finer classes. Empty for a dead tree, a stump or a site, as the
/// census leaves them.
pub(super) fn cells(t: &DemoTree, layout: DemoLayout) -> Vec<String> {
    let alive = t.status == DemoStatus::Alive;
    let c = class(t);
    match layout {
        DemoLayout::Census => {
            if !alive {
                return vec![String::new(); 7];
            }
            let yes =
                |what: &str, p: f64| if unit(&t.id, what) < p { "Yes" } else { "No" }.to_string();
            // Sidewalk damage from 2% of saplings to some 60% of trees of 75 cm and over.
            let sidewalk = (0.02 + 0.008 * t.dbh_cm).min(0.6);
            vec![
                ["Good", "Fair", "Poor"][c].to_string(),
                if unit(&t.id, "sidewalk") < sidewalk {
                    "Damage"
                } else {
                    "NoDamage"
                }
                .to_string(),
                yes("brch_light", 0.04),
                yes("trunk_wire", 0.02),
                yes("trnk_light", 0.01),
                yes("root_stone", 0.12),
                yes("root_grate", 0.02),
            ]
        }
        DemoLayout::Gis => {
            if !alive {
                return vec![String::new()];
            }
            // The same class, in i-Tree's words: good trees some excellent or very good,
            // poor ones some critical.
            let fine = unit(&t.id, "fine");
            let word = match c {
                0 if fine < 0.2 => "Excellent",
                0 if fine < 0.5 => "Very Good",
                0 => "Good",
                1 => "Fair",
                _ if fine < 0.2 => "Critical",
                _ => "Poor",
            };
            vec![word.to_string()]
        }
    }
}
