//! Fields' `TreeRules` (section 3.2): the 25 rules that make a species, read from TOML files
//! keyed by the paper's names, plus Sylva's `[layout]` table (`layout.rs`).

use super::layout;
pub use super::layout::{Crown, Layout};
use super::values::{as_number, within};
use crate::error::ParamsError;
use crate::skeleton::LeafShape;

/// How control points are spread over a lobe's surface (rules 21 and 22).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointSpread {
    /// Independent uniform random points on the sphere (the paper's default).
    Uniform,
    /// A golden-angle spiral: evenly spaced, no clumps or gaps.
    Even,
    /// Rings of three at evenly spaced heights, each ring turned half a step from the one below:
    /// the whorls of a conifer (the paper leaves "some other algorithm" open).
    Whorls,
}

/// How a species puts leaves on its branches (rule 23, `CreateLeaves`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LeafStyle {
    /// Leaves kept close to their branches, in clusters on twigs toward the leaf points (oak).
    Clusters,
    /// Short needles all along every branch (fir).
    Needles,
    /// Strands falling from the lobe's top along its surface, leaves along them (weeping cherry).
    Hanging,
}

/// The look of a leaf (rule 24, `LeafTexture`): outline, colour and proportions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeafLook {
    /// The name as written in a rules file.
    pub name: &'static str,
    /// Outline.
    pub shape: LeafShape,
    /// sRGB colour, 0..1.
    pub color: [f32; 3],
    /// Width / length.
    pub aspect: f32,
}

/// The leaf looks a rules file can name.
pub const LEAF_LOOKS: [LeafLook; 6] = [
    LeafLook {
        name: "oak",
        shape: LeafShape::Oak,
        color: [0.24, 0.40, 0.14],
        aspect: 0.6,
    },
    LeafLook {
        // A needled shoot seen whole: a conifer's two-ranked needles make a flat spray, drawn
        // with the pinnate outline.
        name: "needles",
        shape: LeafShape::Palm,
        color: [0.13, 0.30, 0.16],
        aspect: 0.3,
    },
    LeafLook {
        name: "cherry-blossom",
        shape: LeafShape::Oval,
        color: [0.96, 0.72, 0.80],
        aspect: 0.9,
    },
    LeafLook {
        name: "oval",
        shape: LeafShape::Oval,
        color: [0.30, 0.52, 0.20],
        aspect: 0.5,
    },
    LeafLook {
        name: "maple",
        shape: LeafShape::Maple5,
        color: [0.32, 0.50, 0.18],
        aspect: 1.0,
    },
    LeafLook {
        name: "birch",
        shape: LeafShape::Triangle,
        color: [0.36, 0.55, 0.20],
        aspect: 0.7,
    },
];

impl TreeRules {
    /// The factor every width rule is multiplied by for a tree `height` metres tall: 1 at the
    /// paper's own scale; for a species that gives its mature crown, the natural trunk over
    /// `TrunkStartWidth`, in proportion to the tree's height against the mature one's (a
    /// scanned sapling or the appendix's 5 m cherry gets a trunk to match its size).
    pub fn width_scale(&self, height: f32) -> f32 {
        match &self.layout.crown {
            Some(c) if self.trunk_start_width > 0.0 => {
                let natural = c.trunk_width / self.trunk_start_width;
                (natural * (height as f64 / c.height).clamp(0.01, 100.0)) as f32
            }
            _ => 1.0,
        }
    }
}

/// The 25 rules of Fields' section 3.2. Angles in degrees, widths and lengths in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeRules {
    /// Species name (also the `.tree` file's tree type).
    pub name: String,
    /// One line about the species.
    pub description: String,
    /// Rule 1: Interior angle between the trunks of one trunk split.
    pub trunk_angle: f64,
    /// Rule 2: Angle of a first branch up from the perpendicular to the trunk. Section 3.2.2 says
    /// 90 makes a branch perpendicular; section 4.1.2 reads the fir's 20 as "20 degrees up
    /// from perpendicular". The readings agree at 45 (the oak and the cherry); only the second
    /// gives the fir spreading whorls instead of a broom of branches from the lobe's bottom, so
    /// Sylva follows it.
    pub branch_angle: f64,
    /// Rule 3: Interior angle between the branches of one branch split.
    pub subsequent_angle: f64,
    /// Rule 4: Trunk splits.
    pub num_trunk_iterations: u32,
    /// Rule 5: Branch generations from the trunk to a control point.
    pub branch_iterations: u32,
    /// Rule 6: 0: control points fill the sphere; 1: they make a cone.
    pub leaf_taper: f64,
    /// Rule 7: Trunks from each trunk split.
    pub num_trunk_branches_off_split: u32,
    /// Rule 8: Branches from each branch split, and its random variation (the cherry's "2 +- 1").
    pub num_branches_off_split: (u32, u32),
    /// Rule 9: Straight pieces per branch.
    pub num_segments_in_branch: u32,
    /// Rule 10: Largest random offset of each piece's end, per axis, as a fraction of its length.
    pub segment_offset: [f64; 3],
    /// Rule 11: A child's length over its parent's.
    pub length_reduction_factor: f64,
    /// Rule 12: Width where a branch starts.
    pub branch_start_width: f64,
    /// Rule 13: Width of the trunk at the ground.
    pub trunk_start_width: f64,
    /// Rule 14: Width where a twig (branch to leaf) starts.
    pub twig_start_width: f64,
    /// Rule 15: No stem ends thinner than this.
    pub min_branch_width: f64,
    /// Rule 16: A branch's end width over its start width.
    pub branch_taper_percent: f64,
    /// Rule 17: The trunk's end width over its start width.
    pub trunk_taper_percent: f64,
    /// Rule 18: Branch control points per lobe.
    pub num_branch_control_points_on_lobe: u32,
    /// Rule 19: Leaf control points per lobe.
    pub num_leaf_points_on_lobe: u32,
    /// Rule 20: How far the trunk goes into its lobe: 0 to the near surface, 1 to the far one.
    pub max_trunk_height_percent: f64,
    /// Rule 21: Spread of the branch control points.
    pub create_branch_control_points: PointSpread,
    /// Rule 22: Spread of the leaf control points.
    pub create_leaf_control_points: PointSpread,
    /// Rule 23: How leaves are made.
    pub create_leaves: LeafStyle,
    /// Rule 24: What a leaf looks like.
    pub leaf_texture: LeafLook,
    /// Rule 25: Sides of every branch's cylinder.
    pub tessellation: u32,
    /// Automatic placement and leaf size.
    pub layout: Layout,
}

/// Names of the 25 rules in section 3.2's order, as rules files spell them.
pub const RULE_NAMES: [&str; 25] = [
    "TrunkAngle",
    "BranchAngle",
    "SubsequentAngle",
    "NumTrunkIterations",
    "BranchIterations",
    "LeafTaper",
    "NumTrunkBranchesOffSplit",
    "NumBranchesOffSplit",
    "NumSegmentsInBranch",
    "SegmentOffset",
    "LengthReductionFactor",
    "BranchStartWidth",
    "TrunkStartWidth",
    "TwigStartWidth",
    "MinBranchWidth",
    "BranchTaperPercent",
    "TrunkTaperPercent",
    "NumBranchControlPointsOnLobe",
    "NumLeafPointsOnLobe",
    "MaxTrunkHeightPercent",
    "CreateBranchControlPoints",
    "CreateLeafControlPoints",
    "CreateLeaves",
    "LeafTexture",
    "Tessellation",
];

const BUILTIN: [(&str, &str); 3] = [
    (
        "black_oak",
        include_str!("../../../../species/fields/black_oak.toml"),
    ),
    (
        "balsam_fir",
        include_str!("../../../../species/fields/balsam_fir.toml"),
    ),
    (
        "weeping_cherry",
        include_str!("../../../../species/fields/weeping_cherry.toml"),
    ),
];

/// Ids of the built-in lobe species.
pub fn builtin_names() -> impl Iterator<Item = &'static str> {
    BUILTIN.iter().map(|(id, _)| *id)
}

fn squash(name: &str) -> String {
    name.chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect()
}

/// A built-in species by id (`black_oak`), by its name (`Black Oak`), or by the names the
/// paper's files use (`Cherry Tree`); case, spaces and underscores do not matter.
pub fn builtin(name: &str) -> Option<TreeRules> {
    let key = squash(name);
    let alias = match key.as_str() {
        "oak" | "blackoak" => "black_oak",
        "fir" | "balsamfir" => "balsam_fir",
        "cherry" | "cherrytree" | "weepingcherry" | "weepingcherrytree" => "weeping_cherry",
        _ => return None,
    };
    let (id, text) = BUILTIN.iter().find(|(id, _)| *id == alias)?;
    Some(from_toml(text, id).expect("built-in rules are valid"))
}

/// Line (1-based) of the first `key =` in `text`.
fn line_of(text: &str, key: &str) -> Option<usize> {
    text.lines()
        .position(|l| {
            l.trim_start()
                .strip_prefix(key)
                .is_some_and(|r| r.trim_start().starts_with('='))
        })
        .map(|i| i + 1)
}

/// Reads a rules file's text; every one of the 25 rules must be present.
pub fn from_toml(text: &str, source_name: &str) -> Result<TreeRules, ParamsError> {
    let place = |key: &str| match line_of(text, key) {
        Some(line) => format!("{source_name}, line {line}"),
        None => source_name.to_string(),
    };
    let syntax = |key: &str, message: String| ParamsError::Syntax {
        source_name: place(key),
        message,
    };
    let table: toml::Table = toml::from_str(text).map_err(|e| ParamsError::Syntax {
        source_name: source_name.to_string(),
        message: format!("not valid TOML: {}", e.to_string().trim_end()),
    })?;
    for key in table.keys() {
        if key != "rules" && key != "layout" {
            return Err(syntax(
                key,
                format!("unexpected `{key}`: a rules file has a [rules] and a [layout] table"),
            ));
        }
    }
    let rules = match table.get("rules") {
        Some(toml::Value::Table(t)) => t,
        _ => {
            return Err(ParamsError::Syntax {
                source_name: source_name.to_string(),
                message: "no [rules] table with the 25 TreeRules".into(),
            });
        }
    };
    for key in rules.keys() {
        if key != "name" && key != "description" && !RULE_NAMES.contains(&key.as_str()) {
            return Err(syntax(
                key,
                format!(
                    "unknown rule `{key}`; the rules are {}",
                    RULE_NAMES.join(", ")
                ),
            ));
        }
    }
    let missing: Vec<&str> = RULE_NAMES
        .iter()
        .copied()
        .filter(|k| !rules.contains_key(*k))
        .collect();
    if !missing.is_empty() {
        return Err(ParamsError::Syntax {
            source_name: source_name.to_string(),
            message: format!(
                "[rules] lacks {} of the 25 rules: {}",
                missing.len(),
                missing.join(", ")
            ),
        });
    }
    let get = |key: &str| {
        rules
            .get(key)
            .ok_or_else(|| syntax("[rules]", format!("rule `{key}` is missing")))
    };
    let number = |key: &str, lo: f64, hi: f64, allowed: &str| -> Result<f64, ParamsError> {
        let v = get(key)?;
        let Some(v) = as_number(v) else {
            return Err(syntax(
                key,
                format!("`{key}` is {v}, expected a number ({allowed})"),
            ));
        };
        within(key, v, (lo, hi), allowed, place(key))
    };
    let count = |key: &str, lo: u32, hi: u32| -> Result<u32, ParamsError> {
        let allowed = format!("a whole number {lo}..{hi}");
        let v = number(key, lo as f64, hi as f64, &allowed)?;
        if v.fract() != 0.0 {
            return Err(ParamsError::OutOfRange {
                name: key.into(),
                value: v,
                allowed,
                source_name: Some(place(key)),
            });
        }
        Ok(v as u32)
    };
    let text_of = |key: &str| -> Result<&str, ParamsError> {
        match get(key)? {
            toml::Value::String(s) => Ok(s.as_str()),
            other => Err(syntax(key, format!("`{key}` is {other}, expected text"))),
        }
    };
    let spread = |key: &str| -> Result<PointSpread, ParamsError> {
        match text_of(key)? {
            "uniform" => Ok(PointSpread::Uniform),
            "even" => Ok(PointSpread::Even),
            "whorls" => Ok(PointSpread::Whorls),
            s => Err(syntax(
                key,
                format!("`{key}` is \"{s}\", expected \"uniform\", \"even\" or \"whorls\""),
            )),
        }
    };
    let branches_off_split = match get("NumBranchesOffSplit")? {
        toml::Value::String(s) => {
            let parsed = s.split_once("+-").and_then(|(n, v)| {
                Some((n.trim().parse::<u32>().ok()?, v.trim().parse::<u32>().ok()?))
            });
            match parsed {
                Some((n, v)) if (1..=8).contains(&n) && v < n => (n, v),
                _ => {
                    return Err(syntax(
                        "NumBranchesOffSplit",
                        format!(
                            "`NumBranchesOffSplit` is \"{s}\", expected a whole number 1..8 or \"N +- V\" with V < N"
                        ),
                    ));
                }
            }
        }
        _ => (count("NumBranchesOffSplit", 1, 8)?, 0),
    };
    let segment_offset = match get("SegmentOffset")? {
        toml::Value::Array(a) if a.len() == 3 => {
            let mut out = [0.0; 3];
            for (slot, v) in out.iter_mut().zip(a) {
                *slot = match v {
                    toml::Value::Integer(i) => *i as f64,
                    toml::Value::Float(f) => *f,
                    _ => f64::NAN,
                };
                if !(0.0..=1.0).contains(slot) {
                    return Err(syntax(
                        "SegmentOffset",
                        format!("`SegmentOffset` is {v} in {a:?}: expected three numbers 0..1"),
                    ));
                }
            }
            out
        }
        other => {
            return Err(syntax(
                "SegmentOffset",
                format!("`SegmentOffset` is {other}, expected [x, y, z], each 0..1"),
            ));
        }
    };
    let texture = text_of("LeafTexture")?;
    let leaf_texture = *LEAF_LOOKS
        .iter()
        .find(|l| l.name == texture)
        .ok_or_else(|| {
            let names: Vec<&str> = LEAF_LOOKS.iter().map(|l| l.name).collect();
            syntax(
                "LeafTexture",
                format!(
                    "`LeafTexture` is \"{texture}\", expected one of {}",
                    names.join(", ")
                ),
            )
        })?;
    let create_leaves = match text_of("CreateLeaves")? {
        "clusters" => LeafStyle::Clusters,
        "needles" => LeafStyle::Needles,
        "hanging" => LeafStyle::Hanging,
        s => {
            return Err(syntax(
                "CreateLeaves",
                format!(
                    "`CreateLeaves` is \"{s}\", expected \"clusters\", \"needles\" or \"hanging\""
                ),
            ));
        }
    };
    let layout = layout::read(table.get("layout"), &place)?;
    let text_or = |key: &str, default: &str| match rules.get(key) {
        Some(toml::Value::String(s)) => s.clone(),
        _ => default.to_string(),
    };
    let rules = TreeRules {
        name: text_or("name", source_name),
        description: text_or("description", ""),
        trunk_angle: number("TrunkAngle", 0.0, 180.0, "0..180 degrees")?,
        branch_angle: number("BranchAngle", 0.0, 180.0, "0..180 degrees")?,
        subsequent_angle: number("SubsequentAngle", 0.0, 180.0, "0..180 degrees")?,
        num_trunk_iterations: count("NumTrunkIterations", 0, 6)?,
        branch_iterations: count("BranchIterations", 1, 8)?,
        leaf_taper: number("LeafTaper", 0.0, 1.0, "0..1")?,
        num_trunk_branches_off_split: count("NumTrunkBranchesOffSplit", 1, 8)?,
        num_branches_off_split: branches_off_split,
        num_segments_in_branch: count("NumSegmentsInBranch", 1, 100)?,
        segment_offset,
        length_reduction_factor: number("LengthReductionFactor", 0.01, 1.0, "0.01..1")?,
        branch_start_width: number("BranchStartWidth", 0.0, 10.0, "0..10 metres")?,
        trunk_start_width: number("TrunkStartWidth", 0.0, 10.0, "0..10 metres")?,
        twig_start_width: number("TwigStartWidth", 0.0, 10.0, "0..10 metres")?,
        min_branch_width: number("MinBranchWidth", 0.0, 10.0, "0..10 metres")?,
        branch_taper_percent: number("BranchTaperPercent", 0.0, 1.0, "0..1")?,
        trunk_taper_percent: number("TrunkTaperPercent", 0.0, 1.0, "0..1")?,
        num_branch_control_points_on_lobe: count("NumBranchControlPointsOnLobe", 1, 5000)?,
        num_leaf_points_on_lobe: count("NumLeafPointsOnLobe", 0, 5000)?,
        max_trunk_height_percent: number("MaxTrunkHeightPercent", 0.0, 1.0, "0..1")?,
        create_branch_control_points: spread("CreateBranchControlPoints")?,
        create_leaf_control_points: spread("CreateLeafControlPoints")?,
        create_leaves,
        leaf_texture,
        tessellation: count("Tessellation", 3, 64)?,
        layout,
    };
    Ok(rules)
}
