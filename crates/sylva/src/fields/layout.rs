//! Sylva's `[layout]` table in a rules file, beside the paper's 25 rules: where automatic
//! placement puts the tree and, for a built-in species, the mature tree's size with its source.

use super::values::{as_number, within};
use crate::error::ParamsError;

/// Where automatic placement puts the tree, in metres (Sylva's, not among the 25 rules).
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Radius of the one lobe automatic placement creates when the file gives no [`Crown`]
    /// (the paper's button L: one lobe of radius 1).
    pub lobe_radius: f64,
    /// Height of the crown's bottom (the lowest lobe's) above the ground.
    pub crown_base: f64,
    /// Length of a leaf.
    pub leaf_size: f64,
    /// The mature tree's size, when the species gives it: automatic placement then fills this
    /// crown with lobes, and the width rules are scaled to its trunk.
    pub crown: Option<Crown>,
}

/// A mature tree's size, as a rules file's `[layout]` gives it (with its source in a comment).
#[derive(Clone, Debug, PartialEq)]
pub struct Crown {
    /// Height of the tree's top above the ground.
    pub height: f64,
    /// Width of the crown.
    pub width: f64,
    /// Width of the trunk at the ground. The paper's width rules were drawn for a lobe of radius
    /// 1; every width rule is scaled by `trunk_width / TrunkStartWidth` to match (in
    /// proportion for a tree of another height, see [`crate::fields::TreeRules::width_scale`]).
    pub trunk_width: f64,
    /// How many lobes automatic placement puts in the crown.
    pub lobes: u32,
}

/// Reads a rules file's `[layout]` table (absent: the paper's defaults). `place` names the
/// file and the line a key is on, for errors.
pub(super) fn read(
    table: Option<&toml::Value>,
    place: &dyn Fn(&str) -> String,
) -> Result<Layout, ParamsError> {
    let syntax = |key: &str, message: String| ParamsError::Syntax {
        source_name: place(key),
        message,
    };
    let layout_table = match table {
        Some(toml::Value::Table(t)) => Some(t),
        None => None,
        Some(_) => return Err(syntax("layout", "`layout` must be a table".into())),
    };
    let layout_value = |key: &str, default: f64, lo: f64, hi: f64| -> Result<f64, ParamsError> {
        let Some(v) = layout_table.and_then(|t| t.get(key)) else {
            return Ok(default);
        };
        let Some(v) = as_number(v) else {
            return Err(syntax(key, format!("`{key}` is {v}, expected a number")));
        };
        let unit = if key == "lobes" { "" } else { " metres" };
        within(key, v, (lo, hi), &format!("{lo}..{hi}{unit}"), place(key))
    };
    const LAYOUT_KEYS: [&str; 7] = [
        "lobe_radius",
        "crown_base",
        "leaf_size",
        "height",
        "crown_width",
        "trunk_width",
        "lobes",
    ];
    if let Some(t) = layout_table
        && let Some(key) = t.keys().find(|k| !LAYOUT_KEYS.contains(&k.as_str()))
    {
        return Err(syntax(
            key,
            format!(
                "unknown `{key}` in [layout]: expected {}",
                LAYOUT_KEYS.join(", ")
            ),
        ));
    }
    let has = |key: &str| layout_table.is_some_and(|t| t.contains_key(key));
    let crown_keys = ["height", "crown_width", "trunk_width", "lobes"];
    let crown = if crown_keys.iter().any(|k| has(k)) {
        if let Some(missing) = crown_keys[..3].iter().find(|k| !has(k)) {
            return Err(syntax(
                missing,
                format!(
                    "[layout] gives part of a mature crown but not `{missing}`: give height, \
                     crown_width and trunk_width together (lobes is optional)"
                ),
            ));
        }
        if has("lobe_radius") {
            return Err(syntax(
                "lobe_radius",
                "[layout] gives both lobe_radius and a crown (height, crown_width): the crown \
                 sets the lobes' size, so leave lobe_radius out"
                    .into(),
            ));
        }
        let lobes = layout_value("lobes", 1.0, 1.0, 32.0)?;
        if lobes.fract() != 0.0 {
            return Err(ParamsError::OutOfRange {
                name: "lobes".into(),
                value: lobes,
                allowed: "a whole number 1..32".into(),
                source_name: Some(place("lobes")),
            });
        }
        Some(Crown {
            height: layout_value("height", 0.0, 0.5, 150.0)?,
            width: layout_value("crown_width", 0.0, 0.1, 100.0)?,
            trunk_width: layout_value("trunk_width", 0.0, 0.01, 10.0)?,
            lobes: lobes as u32,
        })
    } else {
        None
    };
    let layout = Layout {
        lobe_radius: layout_value("lobe_radius", 1.0, 0.01, 100.0)?,
        crown_base: layout_value("crown_base", 1.0, 0.0, 200.0)?,
        leaf_size: layout_value("leaf_size", 0.05, 0.001, 2.0)?,
        crown,
    };
    if let Some(c) = &layout.crown
        && c.height <= layout.crown_base + 0.1
    {
        return Err(ParamsError::OutOfRange {
            name: "height".into(),
            value: c.height,
            allowed: format!(
                "more than crown_base ({} m) + 0.1 m: the crown lies between them",
                layout.crown_base
            ),
            source_name: Some(place("height")),
        });
    }
    // One lobe is stretched to the crown's proportions, within LobeShape::of's 0.2..20: a crown
    // 0.2 to 10 times as deep as wide stays inside it for any taper (widest 1 to 2 radii out).
    if let Some(c) = layout.crown.as_ref().filter(|c| c.lobes == 1)
        && !(0.2..=10.0).contains(&((c.height - layout.crown_base) / c.width))
    {
        let (base, w) = (layout.crown_base, c.width);
        return Err(ParamsError::OutOfRange {
            name: "height".into(),
            value: c.height,
            allowed: format!(
                "{:.2} to {:.2} m for a one-lobe crown: from crown_base ({base} m), 0.2 to 10 \
                 times as deep as crown_width ({w} m); give more lobes for other shapes",
                base + 0.2 * w,
                base + 10.0 * w
            ),
            source_name: Some(place("height")),
        });
    }
    Ok(layout)
}
