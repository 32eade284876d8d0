//! Where a lobe tree comes from: its rules (a built-in species or a rules file) and its trunk
//! and lobes (a `.tree` file's, fitted to a point cloud, given one by one, or placed
//! automatically), resolved once for every caller (`sylva lobes`, the editor, Python).

use super::points::{Up, coverage, fit, read_points};
use super::{Lobe, Placement, TreeFile, TreeRules, auto_placement, placement_for_lobes};
use crate::ParamsError;
use std::path::Path;

/// A lobe species by name: a built-in one, else a rules file (`.toml`).
pub fn rules_named(name: &str) -> Result<TreeRules, ParamsError> {
    if let Some(r) = super::builtin(name) {
        return Ok(r);
    }
    let path = Path::new(name);
    if (path.extension()).is_some_and(|e| e.eq_ignore_ascii_case("toml")) {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ParamsError::Combination(format!("cannot read {name}: {e}")))?;
        return super::from_toml(&text, name);
    }
    let known: Vec<&str> = super::rules::builtin_names().collect();
    Err(ParamsError::Combination(format!(
        "no lobe species `{name}` and no such rules file; built in: {}",
        known.join(", ")
    )))
}

/// A lobe as `X,Y,Z,R` in metres (`--lobe`), above the ground.
pub fn parse_lobe(text: &str) -> Result<Lobe, ParamsError> {
    let v: Vec<f32> = (text.split(','))
        .map(|s| s.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .ok()
        .filter(|v: &Vec<f32>| v.len() == 4 && v.iter().all(|x| x.is_finite()))
        .ok_or_else(|| {
            ParamsError::Combination(format!("--lobe {text}: expected X,Y,Z,R in metres"))
        })?;
    if v[3] <= 0.0 || v[2] - v[3] < -1e-6 {
        return Err(ParamsError::Combination(format!(
            "--lobe {text}: the radius must be positive and the lobe above the ground"
        )));
    }
    Ok(Lobe {
        centre: glam::Vec3::new(v[0], v[1], v[2]),
        radius: v[3],
    })
}

/// Where a tree's trunk and lobes come from.
pub enum Lobes<'a> {
    /// Placed automatically from the rules.
    Automatic,
    /// Given one by one.
    Given(Vec<Lobe>),
    /// Fitted to a point cloud (PLY or XYZ): its file name and bytes, which axis is up, and
    /// how many lobes (`None`: as the crown's shape chooses).
    Points {
        #[allow(missing_docs)]
        name: &'a str,
        #[allow(missing_docs)]
        bytes: &'a [u8],
        #[allow(missing_docs)]
        up: Up,
        #[allow(missing_docs)]
        count: Option<usize>,
    },
}

/// A lobe tree resolved: its rules, seed, trunk and lobes, and where they came from in words.
pub struct Planted {
    /// The species' rules.
    pub rules: TreeRules,
    /// The growth's seed.
    pub seed: u64,
    /// The trunk hierarchy and lobes.
    pub placement: Placement,
    /// Where the lobes came from (`placed automatically`, `fitted to 812 points: ...`).
    pub source: String,
}

impl Planted {
    /// A tree of species `name` (built in or a rules file), its lobes from `lobes`; seed 0
    /// unless given.
    pub fn new(name: &str, lobes: Lobes, seed: Option<u64>) -> Result<Planted, ParamsError> {
        let rules = rules_named(name)?;
        let seed = seed.unwrap_or(0);
        let (placement, source) = match lobes {
            Lobes::Automatic => (auto_placement(&rules, seed), "placed automatically".into()),
            Lobes::Given(lobes) => (
                placement_for_lobes(&rules, seed, lobes),
                "lobes as given".into(),
            ),
            Lobes::Points {
                name,
                bytes,
                up,
                count,
            } => {
                if count.is_some_and(|k| !(1..=32).contains(&k)) {
                    return Err(ParamsError::Combination(format!(
                        "--fit-lobes {}: expected 1..32",
                        count.unwrap_or(0)
                    )));
                }
                let points = read_points(name, bytes, up)?;
                let fitted = fit(&points, count, seed);
                let cover = coverage(&fitted.canopy, &fitted.placement.lobes);
                let note = format!(
                    "fitted to {} points: crown base {:.2} m, {} lobes holding {:.0}% of the \
                     canopy's points",
                    points.len(),
                    fitted.crown_base,
                    fitted.placement.lobes.len(),
                    100.0 * cover
                );
                (fitted.placement, note)
            }
        };
        Ok(Planted {
            rules,
            seed,
            placement,
            source,
        })
    }

    /// The tree a `.tree` file (`name`, its `text`) describes, its seed unless `seed` is given.
    pub fn from_tree_file(
        name: &str,
        text: &str,
        seed: Option<u64>,
    ) -> Result<Planted, ParamsError> {
        let file = TreeFile::parse(text, name)?;
        let kind = file.tree_type.trim();
        let rules = match super::builtin(kind) {
            Some(r) => r,
            None => rules_named(kind).map_err(|e| {
                ParamsError::Combination(format!(
                    "{name}: tree type `{kind}` is neither a built-in lobe species nor a rules \
                     file: {e}"
                ))
            })?,
        };
        Ok(Planted {
            rules,
            seed: seed.unwrap_or(file.seed as u64),
            placement: file.placement(),
            source: "from the .tree file".into(),
        })
    }
}
