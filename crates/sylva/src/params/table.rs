//! The parameter table: one entry per parameter, used by validation, both file formats and
//! `sylva species show`, so that a name, its range and its documentation live in one place.

use super::{LEVEL_SETS, TreeParams};
use crate::error::ParamsError;

/// Whether a parameter takes any real value or only whole numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// Any real value in range.
    Real,
    /// A whole number in range.
    Integer,
}

/// One documented parameter.
#[derive(Clone, Copy)]
pub struct ParamDef {
    /// Name without the level prefix (`Length` for `0Length`..`3Length`, `Shape`).
    pub name: &'static str,
    /// True for `nX` parameters that exist once per level.
    pub per_level: bool,
    /// Lowest level at which a per-level parameter exists (`nBranches` starts at 1: `0Branches`
    /// is the number of trunks, a separate general parameter).
    pub first_level: usize,
    /// Real or whole-number values.
    pub kind: ParamKind,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// Unit, as shown to users.
    pub unit: &'static str,
    /// One line: what the parameter means.
    pub doc: &'static str,
    /// Reads the value (level ignored for general parameters).
    pub get: fn(&TreeParams, usize) -> f64,
    /// Writes the value, which must already be in range.
    pub set: fn(&mut TreeParams, usize, f64),
}

impl std::fmt::Debug for ParamDef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ParamDef")
            .field("name", &self.name)
            .finish()
    }
}

impl ParamDef {
    /// Levels this entry covers: `first_level..4` for per-level parameters, `0..1` otherwise.
    pub fn levels(&self) -> std::ops::Range<usize> {
        if self.per_level {
            self.first_level..LEVEL_SETS
        } else {
            0..1
        }
    }

    /// Full name at a level: `1DownAngle`, or the plain name of a general parameter.
    pub fn name_at(&self, level: usize) -> String {
        if self.per_level {
            format!("{level}{}", self.name)
        } else {
            self.name.to_string()
        }
    }

    /// Allowed range as text, `-180..180` or `1..9 (whole)`.
    pub fn range_text(&self) -> String {
        let whole = if self.kind == ParamKind::Integer {
            " (whole)"
        } else {
            ""
        };
        format!("{}..{}{}", self.min, self.max, whole)
    }

    /// Checks a value against the range and kind; `full_name` goes into the error.
    pub fn check(&self, full_name: &str, value: f64) -> Result<(), ParamsError> {
        let integral_ok = self.kind == ParamKind::Real || value.fract() == 0.0;
        if !value.is_finite() || value < self.min || value > self.max || !integral_ok {
            return Err(ParamsError::OutOfRange {
                name: full_name.to_string(),
                value,
                allowed: self.range_text(),
                source_name: None,
            });
        }
        Ok(())
    }
}

/// Finds a parameter by full name (`"Shape"`, `"2CurveV"`, `"0Branches"`) and returns it with the
/// level it addresses (0 for general parameters).
pub fn lookup(full_name: &str) -> Option<(&'static ParamDef, usize)> {
    if let Some(def) = PARAMS.iter().find(|d| !d.per_level && d.name == full_name) {
        return Some((def, 0));
    }
    let mut chars = full_name.chars();
    let level = chars.next()?.to_digit(10)? as usize;
    let rest = chars.as_str();
    PARAMS
        .iter()
        .find(|d| d.per_level && d.name == rest && (d.first_level..LEVEL_SETS).contains(&level))
        .map(|d| (d, level))
}

macro_rules! general {
    ($name:literal, $field:ident, $kind:ident, $min:expr, $max:expr, $unit:literal, $doc:literal) => {
        ParamDef {
            name: $name,
            per_level: false,
            first_level: 0,
            kind: ParamKind::$kind,
            min: $min,
            max: $max,
            unit: $unit,
            doc: $doc,
            get: |p, _| p.$field as f64,
            set: |p, _, v| p.$field = v as _,
        }
    };
}

macro_rules! per_level {
    ($name:literal, $first:expr, $field:ident, $kind:ident, $min:expr, $max:expr, $unit:literal, $doc:literal) => {
        ParamDef {
            name: $name,
            per_level: true,
            first_level: $first,
            kind: ParamKind::$kind,
            min: $min,
            max: $max,
            unit: $unit,
            doc: $doc,
            get: |p, n| p.level[n].$field as f64,
            set: |p, n, v| p.level[n].$field = v as _,
        }
    };
}

/// Every parameter, in the order of the paper's appendix (Arbaro's additions after their kin).
pub static PARAMS: &[ParamDef] = &[
    general!(
        "Shape",
        shape,
        Integer,
        0.0,
        8.0,
        "index",
        "crown shape for first-level branch lengths: 0 conical, 1 spherical, 2 hemispherical, 3 cylindrical, 4 tapered cylindrical, 5 flame, 6 inverse conical, 7 tend flame, 8 pruning envelope"
    ),
    general!(
        "BaseSize",
        base_size,
        Real,
        0.0,
        0.999,
        "fraction",
        "bare part of the trunk below the first branches"
    ),
    general!(
        "Scale",
        scale,
        Real,
        0.001,
        500.0,
        "m",
        "tree size: trunk length is 0Length * Scale"
    ),
    general!(
        "ScaleV",
        scale_v,
        Real,
        0.0,
        500.0,
        "m",
        "random variation of Scale (at most Scale)"
    ),
    general!(
        "ZScale",
        z_scale,
        Real,
        0.001,
        100.0,
        "factor",
        "vertical stretch of the whole tree"
    ),
    general!(
        "ZScaleV",
        z_scale_v,
        Real,
        0.0,
        100.0,
        "factor",
        "random variation of ZScale"
    ),
    general!(
        "Levels",
        levels,
        Integer,
        1.0,
        9.0,
        "count",
        "levels of recursion: 1 trunk only, 2 trunk and branches, ...; leaves sit on the last"
    ),
    general!(
        "Ratio",
        ratio,
        Real,
        0.000001,
        1.0,
        "fraction",
        "trunk base radius / trunk length"
    ),
    general!(
        "RatioPower",
        ratio_power,
        Real,
        -10.0,
        10.0,
        "exponent",
        "child radius = parent radius * (child length / parent length)^RatioPower"
    ),
    general!(
        "Lobes",
        lobes,
        Integer,
        0.0,
        64.0,
        "count",
        "sinusoidal lobes around the trunk (odd numbers look natural)"
    ),
    general!(
        "LobeDepth",
        lobe_depth,
        Real,
        0.0,
        10.0,
        "fraction",
        "lobe amplitude relative to the trunk radius"
    ),
    general!(
        "Flare",
        flare,
        Real,
        -1.0,
        10.0,
        "factor",
        "trunk widening at the ground: the radius grows up to (1 + Flare) in the lowest eighth"
    ),
    general!(
        "0Scale",
        trunk_scale,
        Real,
        0.000001,
        100.0,
        "factor",
        "extra scale of the trunk radius"
    ),
    general!(
        "0ScaleV",
        trunk_scale_v,
        Real,
        0.0,
        100.0,
        "factor",
        "random variation of 0Scale"
    ),
    general!(
        "0BaseSplits",
        base_splits,
        Integer,
        0.0,
        64.0,
        "count",
        "clones made at the end of the trunk's first segment (several leaders)"
    ),
    general!(
        "0Branches",
        trunks,
        Integer,
        1.0,
        1000.0,
        "count",
        "number of trunks from the ground (Arbaro), e.g. for shrubs and grasses"
    ),
    general!(
        "0BranchDist",
        trunk_spread,
        Real,
        0.0,
        1000.0,
        "m",
        "radius of the circle the trunks stand on (Arbaro)"
    ),
    per_level!(
        "Length",
        0,
        length,
        Real,
        0.0,
        1000.0,
        "fraction",
        "maximum length relative to the parent (trunk: relative to Scale)"
    ),
    per_level!(
        "LengthV",
        0,
        length_v,
        Real,
        0.0,
        1000.0,
        "fraction",
        "random variation of nLength"
    ),
    per_level!(
        "Taper",
        0,
        taper,
        Real,
        0.0,
        3.0,
        "index",
        "radius profile: 0 cylinder, 1 cone, 2 spherical end, 2..3 periodic beads (cacti, palm trunks)"
    ),
    per_level!(
        "SegSplits",
        0,
        seg_splits,
        Real,
        0.0,
        64.0,
        "per segment",
        "clones added per segment (1 = a fork at every segment)"
    ),
    per_level!(
        "SplitAngle",
        0,
        split_angle,
        Real,
        0.0,
        180.0,
        "deg",
        "angle of a clone away from its original"
    ),
    per_level!(
        "SplitAngleV",
        0,
        split_angle_v,
        Real,
        0.0,
        180.0,
        "deg",
        "random variation of nSplitAngle"
    ),
    per_level!(
        "CurveRes",
        0,
        curve_res,
        Integer,
        1.0,
        500.0,
        "count",
        "segments per stem"
    ),
    per_level!(
        "Curve",
        0,
        curve,
        Real,
        -3600.0,
        3600.0,
        "deg",
        "bend of the stem over its length about its x axis (positive bends down)"
    ),
    per_level!(
        "CurveBack",
        0,
        curve_back,
        Real,
        -3600.0,
        3600.0,
        "deg",
        "bend of the stem's second half, for S shapes (0 = plain curve)"
    ),
    per_level!(
        "CurveV",
        0,
        curve_v,
        Real,
        -89.9,
        3600.0,
        "deg",
        "random bend over the stem; negative: a helix with that declination"
    ),
    per_level!(
        "DownAngle",
        0,
        down_angle,
        Real,
        -180.0,
        180.0,
        "deg",
        "angle between a child and its parent's axis"
    ),
    per_level!(
        "DownAngleV",
        0,
        down_angle_v,
        Real,
        -180.0,
        180.0,
        "deg",
        "random variation of nDownAngle; negative: varies linearly along the parent instead"
    ),
    per_level!(
        "Rotate",
        0,
        rotate,
        Real,
        -360.0,
        360.0,
        "deg",
        "azimuth step between successive children; negative: alternate sides (180 + nRotate); fans: the fan angle"
    ),
    per_level!(
        "RotateV",
        0,
        rotate_v,
        Real,
        0.0,
        360.0,
        "deg",
        "random variation of nRotate"
    ),
    per_level!(
        "Branches",
        1,
        branches,
        Integer,
        -1000.0,
        100000.0,
        "count",
        "most children a parent stem gets; negative: a fan of that many at the parent's tip"
    ),
    per_level!(
        "BranchDist",
        1,
        branch_dist,
        Real,
        0.0,
        1.0,
        "fraction",
        "spacing inside a segment: 1 even, 0 all at the segment base (whorls, Arbaro)"
    ),
    general!(
        "Leaves",
        leaves,
        Integer,
        -1000.0,
        100000.0,
        "count",
        "leaves per leaf-bearing stem; negative: a fan of that many at the stem tip"
    ),
    general!(
        "LeafShape",
        leaf_shape,
        Integer,
        0.0,
        8.0,
        "index",
        "leaf outline: 0 oval, 1 triangle, 2 three-lobe oak, 3 three-lobe maple, 4 five-lobe maple, 5 three leaflets, 6 square, 7 palm leaflet, 8 sphere"
    ),
    general!(
        "LeafScale",
        leaf_scale,
        Real,
        0.000001,
        100.0,
        "m",
        "leaf length (divided by sqrt(LeafQuality))"
    ),
    general!(
        "LeafScaleX",
        leaf_scale_x,
        Real,
        0.000001,
        100.0,
        "fraction",
        "leaf width relative to its length"
    ),
    general!(
        "LeafBend",
        leaf_bend,
        Real,
        0.0,
        1.0,
        "fraction",
        "how far leaves turn up and outwards towards the light (the paper's bend)"
    ),
    general!(
        "LeafQuality",
        leaf_quality,
        Real,
        0.001,
        10.0,
        "factor",
        "the paper's quality: scales leaf count by q and leaf size by 1/sqrt(q)"
    ),
    general!(
        "LeafStemLen",
        leaf_stem_len,
        Real,
        -100.0,
        100.0,
        "leaf lengths",
        "petiole length between stem and leaf (Arbaro)"
    ),
    general!(
        "LeafDistrib",
        leaf_distrib,
        Integer,
        0.0,
        8.0,
        "index",
        "ShapeRatio index of leaf density along a stem (paper: 4, Arbaro)"
    ),
    general!(
        "AttractionUp",
        attraction_up,
        Real,
        -100.0,
        100.0,
        "factor",
        "upward curving of stems of level 2 and deeper (negative droops, as the weeping willow)"
    ),
    general!(
        "PruneRatio",
        prune_ratio,
        Real,
        0.0,
        1.0,
        "fraction",
        "strength of pruning to the envelope: 0 off, 1 full"
    ),
    general!(
        "PruneWidth",
        prune_width,
        Real,
        0.000001,
        100.0,
        "fraction",
        "envelope half-width relative to the tree scale"
    ),
    general!(
        "PruneWidthPeak",
        prune_width_peak,
        Real,
        0.0,
        1.0,
        "fraction",
        "height of the envelope's widest point above its base, as a fraction of its height"
    ),
    general!(
        "PrunePowerLow",
        prune_power_low,
        Real,
        0.0,
        100.0,
        "exponent",
        "envelope curvature below the peak (1 linear, <1 convex, >1 concave)"
    ),
    general!(
        "PrunePowerHigh",
        prune_power_high,
        Real,
        0.0,
        100.0,
        "exponent",
        "envelope curvature above the peak"
    ),
    general!(
        "Smooth",
        smooth,
        Real,
        0.0,
        1.0,
        "fraction",
        "mesh smoothness hint scaling ring resolution (Arbaro)"
    ),
];

#[cfg(test)]
#[path = "table_tests.rs"]
mod tests;
