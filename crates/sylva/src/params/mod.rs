//! Weber–Penn tree parameters: the typed struct, and the one table that names, documents and
//! bounds every parameter.
//!
//! Names follow the paper's appendix (`Shape`, `BaseSize`, `0Length`, `1DownAngle`, ...), with
//! Arbaro's additions (`0Branches`, `nBranchDist`, `LeafStemLen`, `LeafDistrib`, `Smooth`). Per-level
//! parameters are written `nX` for n = 0..3; deeper levels reuse level 3. Angles are in degrees,
//! lengths in metres or as fractions, as each entry of [`PARAMS`] says.

pub(crate) mod arbaro;
mod table;
mod toml_io;

pub use arbaro::{ARBARO_LEAF_SHAPES, from_arbaro_xml};
pub use table::{PARAMS, ParamDef, ParamKind, lookup};
pub use toml_io::{format_value, from_toml, to_toml};

use crate::error::ParamsError;

/// Default bark colour (sRGB): grey-brown.
pub const DEFAULT_BARK: [f32; 3] = [112.0 / 255.0, 94.0 / 255.0, 79.0 / 255.0];
/// Default leaf colour (sRGB): mid summer green.
pub const DEFAULT_LEAVES: [f32; 3] = [84.0 / 255.0, 128.0 / 255.0, 51.0 / 255.0];

/// Parses `#RRGGBB` into sRGB 0..1.
pub fn parse_color(text: &str) -> Option<[f32; 3]> {
    let hex = text.strip_prefix('#')?;
    if hex.len() != 6 || !hex.is_ascii() {
        return None;
    }
    let channel = |i: usize| {
        u8::from_str_radix(&hex[i..i + 2], 16)
            .ok()
            .map(|v| v as f32 / 255.0)
    };
    Some([channel(0)?, channel(2)?, channel(4)?])
}

/// Formats sRGB 0..1 as `#RRGGBB`.
pub fn format_color(c: [f32; 3]) -> String {
    let b = c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
    format!("#{:02x}{:02x}{:02x}", b[0], b[1], b[2])
}

/// Number of per-level parameter sets stored; levels deeper than 3 reuse level 3, as in the paper.
pub const LEVEL_SETS: usize = 4;

/// Per-level stem parameters (`nLength`, `nTaper`, ...). Index `n` of [`TreeParams::level`].
#[derive(Clone, Debug, PartialEq)]
pub struct LevelParams {
    /// `nLength`: maximum length of a child relative to its parent (trunk: relative to the tree scale).
    pub length: f64,
    /// `nLengthV`: random variation of `nLength`.
    pub length_v: f64,
    /// `nTaper`: radius profile. 0 cylinder, 1 cone, 2 spherical end, 2..3 periodic beads.
    pub taper: f64,
    /// `nSegSplits`: clones added per segment (error-diffused).
    pub seg_splits: f64,
    /// `nSplitAngle`: angle between a clone and its original, degrees.
    pub split_angle: f64,
    /// `nSplitAngleV`: random variation of the split angle, degrees.
    pub split_angle_v: f64,
    /// `nCurveRes`: segments per stem.
    pub curve_res: u32,
    /// `nCurve`: total bend of a stem about its x axis, degrees.
    pub curve: f64,
    /// `nCurveBack`: bend of the second half of an S-shaped stem, degrees (0 = simple curve).
    pub curve_back: f64,
    /// `nCurveV`: random bend per stem, degrees; negative makes a helix of that declination.
    pub curve_v: f64,
    /// `nDownAngle`: angle between a child and its parent's axis, degrees.
    pub down_angle: f64,
    /// `nDownAngleV`: its variation; negative spreads it linearly along the parent.
    pub down_angle_v: f64,
    /// `nRotate`: azimuth step between successive children, degrees; negative alternates sides.
    pub rotate: f64,
    /// `nRotateV`: variation of the azimuth step, degrees.
    pub rotate_v: f64,
    /// `nBranches`: most children a stem of the previous level gets; negative makes a tip fan.
    pub branches: i64,
    /// `nBranchDist`: spacing of children inside a segment: 1 even, 0 all at the segment base (whorls).
    pub branch_dist: f64,
}

/// All Weber–Penn parameters of one species. Build one from a species file ([`from_toml`],
/// [`from_arbaro_xml`]) or start from [`TreeParams::default`] (Arbaro's defaults), then call
/// [`TreeParams::validate`] before generating.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeParams {
    /// Species name, shown in summaries.
    pub name: String,
    /// Free-text description (what the species is, where its values come from).
    pub description: String,
    /// What loading changed and why (e.g. an Arbaro variation clamped); shown as warnings.
    pub notes: Vec<String>,
    /// Bark colour, sRGB 0..1 (species file: `bark_color = "#RRGGBB"`).
    pub bark_color: [f32; 3],
    /// Leaf colour, sRGB 0..1 (species file: `leaf_color = "#RRGGBB"`).
    pub leaf_color: [f32; 3],
    /// `Shape`: crown shape index 0..8 for the ShapeRatio function (8 = pruning envelope).
    pub shape: u32,
    /// `BaseSize`: fraction of the trunk without branches.
    pub base_size: f64,
    /// `Scale`: tree size in metres.
    pub scale: f64,
    /// `ScaleV`: random variation of `Scale`, metres.
    pub scale_v: f64,
    /// `ZScale`: vertical stretch of the whole tree.
    pub z_scale: f64,
    /// `ZScaleV`: random variation of `ZScale`.
    pub z_scale_v: f64,
    /// `Levels`: levels of recursion (stems of level 0..Levels-1; leaves on the last).
    pub levels: u32,
    /// `Ratio`: trunk radius as a fraction of trunk length.
    pub ratio: f64,
    /// `RatioPower`: how fast child radii fall with relative length.
    pub ratio_power: f64,
    /// `Lobes`: number of sinusoidal lobes around the trunk.
    pub lobes: u32,
    /// `LobeDepth`: lobe amplitude as a fraction of the radius.
    pub lobe_depth: f64,
    /// `Flare`: exponential widening at the trunk base (up to 1 + Flare times the radius).
    pub flare: f64,
    /// `0Scale`: extra trunk radius scale.
    pub trunk_scale: f64,
    /// `0ScaleV`: its random variation.
    pub trunk_scale_v: f64,
    /// `0BaseSplits`: clones made at the end of the trunk's first segment.
    pub base_splits: u32,
    /// `0Branches` (Arbaro): number of trunks rising from the ground.
    pub trunks: u32,
    /// `0BranchDist` (Arbaro): radius of the circle the trunks stand on, metres.
    pub trunk_spread: f64,
    /// `Leaves`: leaves per leaf-bearing stem; negative makes a fan at the stem tip.
    pub leaves: i64,
    /// `LeafShape`: leaf outline index (see [`crate::LeafShape`]).
    pub leaf_shape: u32,
    /// `LeafScale`: leaf length, metres.
    pub leaf_scale: f64,
    /// `LeafScaleX`: leaf width relative to its length.
    pub leaf_scale_x: f64,
    /// `LeafBend`: how far leaves turn to face up and out, 0..1 (the paper's "bend").
    pub leaf_bend: f64,
    /// `LeafQuality`: the paper's quality factor: more, smaller leaves at equal coverage.
    pub leaf_quality: f64,
    /// `LeafStemLen` (Arbaro): petiole length in leaf lengths.
    pub leaf_stem_len: f64,
    /// `LeafDistrib` (Arbaro): ShapeRatio index of leaf density along the stem (paper: 4).
    pub leaf_distrib: u32,
    /// `AttractionUp`: upward curving of stems of level 2 and deeper; negative droops.
    pub attraction_up: f64,
    /// `PruneRatio`: how strongly stems are shortened to fit the envelope, 0..1.
    pub prune_ratio: f64,
    /// `PruneWidth`: envelope half-width relative to the tree scale.
    pub prune_width: f64,
    /// `PruneWidthPeak`: height of the envelope's widest point, fraction of the crown height.
    pub prune_width_peak: f64,
    /// `PrunePowerLow`: curvature of the envelope below its peak.
    pub prune_power_low: f64,
    /// `PrunePowerHigh`: curvature of the envelope above its peak.
    pub prune_power_high: f64,
    /// `Smooth` (Arbaro): mesh smoothness hint 0..1, scaling ring resolution.
    pub smooth: f64,
    /// Per-level parameters, index = level (0 trunk .. 3).
    pub level: [LevelParams; LEVEL_SETS],
}

impl LevelParams {
    /// Arbaro's per-level defaults for level `n`.
    pub fn default_for(n: usize) -> Self {
        Self {
            length: if n == 0 { 1.0 } else { 0.5 },
            length_v: 0.0,
            taper: 1.0,
            seg_splits: 0.0,
            split_angle: 0.0,
            split_angle_v: 0.0,
            curve_res: if n < 2 { 3 } else { 1 },
            curve: 0.0,
            curve_back: 0.0,
            curve_v: 0.0,
            down_angle: if n == 0 { 0.0 } else { 30.0 },
            down_angle_v: 0.0,
            rotate: if n == 0 { 0.0 } else { 120.0 },
            rotate_v: 0.0,
            branches: match n {
                0 => 1,
                1 => 10,
                _ => 5,
            },
            branch_dist: if n == 0 { 0.0 } else { 1.0 },
        }
    }
}

impl Default for TreeParams {
    /// Arbaro's documented defaults (paper-only parameters: `ZScale` 1, `ZScaleV` 0).
    fn default() -> Self {
        Self {
            name: "default".into(),
            description: String::new(),
            notes: Vec::new(),
            bark_color: DEFAULT_BARK,
            leaf_color: DEFAULT_LEAVES,
            shape: 0,
            base_size: 0.25,
            scale: 10.0,
            scale_v: 0.0,
            z_scale: 1.0,
            z_scale_v: 0.0,
            levels: 3,
            ratio: 0.05,
            ratio_power: 1.0,
            lobes: 0,
            lobe_depth: 0.0,
            flare: 0.5,
            trunk_scale: 1.0,
            trunk_scale_v: 0.0,
            base_splits: 0,
            trunks: 1,
            trunk_spread: 0.0,
            leaves: 0,
            leaf_shape: 0,
            leaf_scale: 0.2,
            leaf_scale_x: 0.5,
            leaf_bend: 0.3,
            leaf_quality: 1.0,
            leaf_stem_len: 0.5,
            leaf_distrib: 4,
            attraction_up: 0.0,
            prune_ratio: 0.0,
            prune_width: 0.5,
            prune_width_peak: 0.5,
            prune_power_low: 0.5,
            prune_power_high: 0.5,
            smooth: 0.5,
            level: std::array::from_fn(LevelParams::default_for),
        }
    }
}

impl TreeParams {
    /// Parameters of stem level `n` (levels past 3 reuse level 3, as the paper says).
    pub fn level(&self, n: usize) -> &LevelParams {
        &self.level[n.min(LEVEL_SETS - 1)]
    }

    /// Sets a parameter by its paper name (`"1DownAngle"`, `"Shape"`), checking its range.
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), ParamsError> {
        let (def, level) = lookup(name).ok_or_else(|| ParamsError::Unknown {
            name: name.to_string(),
            source_name: None,
        })?;
        def.check(name, value)?;
        (def.set)(self, level, value);
        Ok(())
    }

    /// Reads a parameter by its paper name.
    pub fn get(&self, name: &str) -> Option<f64> {
        lookup(name).map(|(def, level)| (def.get)(self, level))
    }

    /// Checks every parameter against its documented range, and the combinations the model
    /// cannot build (a trunk of non-positive length, `ScaleV >= Scale`).
    pub fn validate(&self) -> Result<(), ParamsError> {
        for def in PARAMS {
            for level in def.levels() {
                let value = (def.get)(self, level);
                def.check(&def.name_at(level), value)?;
            }
        }
        let worst_scale = self.scale - self.scale_v;
        let worst_length = self.level[0].length - self.level[0].length_v;
        // ScaleV == Scale is the paper's own CA Black Oak; only a negative scale is impossible.
        if worst_scale < 0.0 {
            return Err(ParamsError::Combination(format!(
                "ScaleV ({}) must not exceed Scale ({}): the tree scale Scale ± ScaleV could be {} m",
                self.scale_v, self.scale, worst_scale
            )));
        }
        if worst_length < 0.0 {
            return Err(ParamsError::Combination(format!(
                "0LengthV ({}) must not exceed 0Length ({}): the trunk could get length {} m",
                self.level[0].length_v,
                self.level[0].length,
                worst_length * worst_scale
            )));
        }
        if self.z_scale - self.z_scale_v < 0.0 {
            return Err(ParamsError::Combination(format!(
                "ZScaleV ({}) must not exceed ZScale ({})",
                self.z_scale_v, self.z_scale
            )));
        }
        if self.trunk_scale - self.trunk_scale_v < 0.0 {
            return Err(ParamsError::Combination(format!(
                "0ScaleV ({}) must not exceed 0Scale ({}): the trunk radius could be negative",
                self.trunk_scale_v, self.trunk_scale
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid() {
        TreeParams::default().validate().unwrap();
    }

    #[test]
    fn set_and_get_by_paper_name() {
        let mut p = TreeParams::default();
        p.set("1DownAngle", 45.0).unwrap();
        assert_eq!(p.level[1].down_angle, 45.0);
        assert_eq!(p.get("1DownAngle"), Some(45.0));
        p.set("0Branches", 3.0).unwrap();
        assert_eq!(p.trunks, 3);
        assert!(p.set("1Branches", 1e9).is_err());
        assert!(p.set("Levels", 50.0).is_err());
        assert!(p.set("NoSuchThing", 1.0).is_err());
        assert!(
            p.set("Levels", 2.5).is_err(),
            "integer parameters reject fractions"
        );
    }

    #[test]
    fn negative_trunk_is_rejected() {
        let p = TreeParams {
            scale: 5.0,
            scale_v: 6.0,
            ..TreeParams::default()
        };
        let err = p.validate().unwrap_err().to_string();
        assert!(err.contains("ScaleV"), "{err}");
    }
}
