//! The wire model against the Urban Tree Database's own records.
//!
//! Table TS3 notes, for most measured street trees outside California, whether overhead lines
//! run by the tree and whether the tree is in conflict with them (`WireConf`: 0 no lines, 1
//! lines with no potential conflict, 2 conflicting, 3 potential conflict; McPherson, van Doorn &
//! Peper 2016, PSW-GTR-253, field codes). The site's wire model says a crown conflicts with a
//! line when any part of it comes within the line's clearance; for a measured tree the crown is
//! the cylinder from its crown base to its top, and the line runs over the planting strip, so
//! the tree conflicts when its top reaches `wire height - clearance` (the reach height) and its
//! crown base is below `wire height + clearance`.
//!
//! The survey does not record the lines' heights, so agreement is reported at a given reach
//! height and at the reach height that agrees best in each region (a one-number fit, said as
//! such), beside the agreement of always answering "no conflict".

use crate::street::error::StreetError;
use std::collections::BTreeMap;
use std::path::Path;

/// Fewest trees under lines for a region to be reported.
pub const ENOUGH: usize = 50;

/// One measured tree under lines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnderLines {
    /// Tree height, m.
    pub height: f64,
    /// Height of the crown base, m.
    pub crown_base: f64,
    /// Recorded as conflicting (code 2).
    pub conflicting: bool,
}

/// How the model agrees with one region's records.
#[derive(Clone, Debug, PartialEq)]
pub struct Agreement {
    /// Region code.
    pub region: String,
    /// Trees with lines recorded beside them.
    pub trees: usize,
    /// Of which recorded as conflicting.
    pub conflicting: usize,
    /// Share the model gets right at the given wire.
    pub agreement: f64,
    /// Share right by always answering "no conflict".
    pub baseline: f64,
    /// The reach height that agrees best, m, and its agreement.
    pub best: (f64, f64),
}

/// Reads TS3's trees under lines, by region.
pub fn read_ts3(path: &Path) -> Result<BTreeMap<String, Vec<UnderLines>>, StreetError> {
    let file = path.display().to_string();
    let io = |e: &dyn std::fmt::Display| StreetError::Io {
        path: file.clone(),
        message: e.to_string(),
    };
    let mut reader = csv::Reader::from_path(path).map_err(|e| io(&e))?;
    let headers = reader.headers().map_err(|e| io(&e))?.clone();
    let column = |name: &str| {
        headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| StreetError::Syntax {
                file: file.clone(),
                message: format!("no column `{name}` (is this TS3_Raw_tree_data.csv?)"),
            })
    };
    let (region, wire, height, base) = (
        column("Region")?,
        column("WireConf")?,
        column("TreeHt (m)")?,
        column("CrnBase")?,
    );
    let mut out: BTreeMap<String, Vec<UnderLines>> = BTreeMap::new();
    for record in reader.records() {
        let r = record.map_err(|e| io(&e))?;
        let number = |i: usize| r.get(i).and_then(|v| v.trim().parse::<f64>().ok());
        let (Some(code), Some(h), Some(b)) = (number(wire), number(height), number(base)) else {
            continue;
        };
        // Lines present (1, 2, 3) and a measured tree (-1 marks a missing value).
        if !(1.0..=3.0).contains(&code) || h <= 0.0 || b < 0.0 || b > h {
            continue;
        }
        out.entry(r.get(region).unwrap_or("").to_string())
            .or_default()
            .push(UnderLines {
                height: h,
                crown_base: b,
                conflicting: code == 2.0,
            });
    }
    Ok(out)
}

/// Whether the model puts a tree in conflict with a line at `height` with `clearance`.
pub fn model_conflict(tree: &UnderLines, height: f64, clearance: f64) -> bool {
    tree.height > height - clearance && tree.crown_base < height + clearance
}

fn share(trees: &[UnderLines], height: f64, clearance: f64) -> f64 {
    let right = trees
        .iter()
        .filter(|t| model_conflict(t, height, clearance) == t.conflicting)
        .count();
    right as f64 / trees.len().max(1) as f64
}

/// Agreement per region with at least [`ENOUGH`] trees under lines, for a line at `height`
/// with `clearance`.
pub fn agreement(
    trees: &BTreeMap<String, Vec<UnderLines>>,
    height: f64,
    clearance: f64,
) -> Vec<Agreement> {
    trees
        .iter()
        .filter(|(_, t)| t.len() >= ENOUGH)
        .map(|(region, t)| {
            let conflicting = t.iter().filter(|t| t.conflicting).count();
            // Sweep the reach height (the line `clearance` above it), 2 to 20 m.
            let best = (0..=72)
                .map(|i| {
                    let reach = 2.0 + i as f64 * 0.25;
                    (reach, share(t, reach + clearance, clearance))
                })
                .fold((0.0, -1.0), |a, b| if b.1 > a.1 { b } else { a });
            Agreement {
                region: region.clone(),
                trees: t.len(),
                conflicting,
                agreement: share(t, height, clearance),
                baseline: 1.0 - conflicting as f64 / t.len() as f64,
                best,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_and_its_sweep() {
        let tree = |h: f64, c: bool| UnderLines {
            height: h,
            crown_base: 2.0,
            conflicting: c,
        };
        // Tall trees conflict, short ones do not: a reach of 8 m separates them exactly.
        let mut trees: Vec<UnderLines> =
            (0..30).map(|i| tree(4.0 + i as f64 * 0.1, false)).collect();
        trees.extend((0..30).map(|i| tree(9.0 + i as f64 * 0.1, true)));
        assert!(model_conflict(&trees[40], 9.0, 1.5));
        assert!(!model_conflict(&trees[0], 9.0, 1.5));
        let map = BTreeMap::from([("X".to_string(), trees)]);
        let a = &agreement(&map, 9.5, 1.5)[0];
        assert_eq!(a.trees, 60);
        assert_eq!(a.conflicting, 30);
        assert!((a.baseline - 0.5).abs() < 1e-12);
        assert_eq!(a.agreement, 1.0);
        assert_eq!(a.best.1, 1.0);
        assert!(a.best.0 > 6.9 && a.best.0 <= 9.0, "{:?}", a.best);
    }

    #[test]
    fn the_database_records() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../../shared/data/urban-tree-database/TS3_Raw_tree_data.csv");
        if !path.exists() {
            // The raw table is not shipped; CI and developers have it beside the clone.
            eprintln!("skipped: {} not found", path.display());
            return;
        }
        let trees = read_ts3(&path).unwrap();
        let rows = agreement(&trees, 8.5, 1.5);
        // Regions that recorded lines: GulfCo, NoEast and others, each with 50+ trees.
        assert!(rows.len() >= 8, "{rows:?}");
        for r in &rows {
            assert!(r.trees >= ENOUGH && r.conflicting <= r.trees);
            assert!((0.0..=1.0).contains(&r.agreement));
            assert!(r.best.1 >= r.agreement - 1e-12);
        }
        let gulf = rows.iter().find(|r| r.region == "GulfCo").unwrap();
        // 297 conflicting of 501 under lines (codes 1-3) in Charleston, fewer if heights lack.
        assert!(gulf.conflicting > 250 && gulf.trees > 450, "{gulf:?}");
    }
}
