//! A planting site: the street, the building and the fixtures around one tree, read from a
//! `site.toml` and checked before anything grows.
//!
//! Frame: metres; the trunk stands at x = 0, y = 0; x runs along the street; y runs across it,
//! negative towards the roadway, positive towards the buildings; z is up from the ground.
//!
//! ```toml
//! [street]
//! curb = -1.0                # y of the curb face; the roadway lies beyond it
//! sidewalk = [0.8, 3.2]      # y range of the sidewalk
//! roadway_clearance = 4.3    # height kept clear over the roadway
//! sidewalk_clearance = 2.4   # and over the sidewalk
//!
//! [facade]
//! setback = 6.0              # y of the wall
//! height = 8.0
//! width = 12.0               # centred on the tree
//! faces = 180.0              # compass direction the wall looks out to (180: south)
//! window_share = 0.25        # share of the wall that is glass
//!
//! [[awning]]                 # also [[sign]]: a box on the wall
//! bottom = 2.6
//! top = 3.0
//! reach = 1.5                # out from the wall
//! along = [-2.0, 2.0]        # x range
//!
//! [[wire]]
//! height = 8.5
//! offset = -0.6              # y of the line
//! voltage_kv = 12.0          # optional: GO 95's clearances for the keys below not given
//! clearance = 1.22           # radial clearance at the time of cutting (GO 95: 4 ft, 2.4-72 kV)
//! minimum = 0.46             # radial clearance kept at all times (GO 95: 18 in, 0.75-22.5 kV)
//! access = "street"          # or "backyard": the crew that reaches the tree (its price)
//! cycle = 4                  # years between line clearances (optional: see [pruning])
//!
//! [[light]]
//! x = 6.0
//! y = -0.7
//! height = 7.0
//! clearance = 1.0
//!
//! [sight_triangle]           # kept clear between two heights
//! corners = [[-12.0, -1.0], [-4.0, -1.0], [-12.0, 6.0]]
//! low = 0.9
//! high = 2.4
//!
//! [pruning]                  # optional: the default standard's cycles (`street::work::pruning`)
//! standard = "us-street"
//! ```

use crate::street::error::StreetError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The street around the tree.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Street {
    /// y of the curb face, m (negative: between the tree and the roadway).
    pub curb: f64,
    /// y range of the sidewalk, m.
    pub sidewalk: [f64; 2],
    /// Clear height over the roadway, m.
    pub roadway_clearance: f64,
    /// Clear height over the sidewalk, m.
    pub sidewalk_clearance: f64,
}

/// The building's street wall.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Facade {
    /// y of the wall, m.
    pub setback: f64,
    /// Wall height, m.
    pub height: f64,
    /// Wall width along the street, centred on the tree, m.
    pub width: f64,
    /// Compass direction the wall faces, degrees clockwise from north.
    pub faces: f64,
    /// Share of the wall that is windows, 0..1.
    pub window_share: f64,
}

/// An awning or a sign: a box on the wall.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct WallBox {
    /// Underside height, m.
    pub bottom: f64,
    /// Top height, m.
    pub top: f64,
    /// How far it reaches out from the wall, m.
    pub reach: f64,
    /// Its x range along the wall, m.
    pub along: [f64; 2],
}

/// An overhead line along the street.
///
/// Two radii around it: the **clearance** the utility's crew cuts the tree to at each visit
/// (and beyond it the regrowth the tree makes before the next, `street::accounts::pruner`),
/// and the **minimum** no leaf or wood may enter at any time. California's General Order 95
/// gives both by the line's voltage ([`go95`]); a site may give them itself.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Wire {
    /// Height of the line, m.
    pub height: f64,
    /// y of the line, m.
    pub offset: f64,
    /// Radial clearance at the time of cutting, m: what line clearance cuts to, before the
    /// crew's allowance for regrowth. GO 95's for `voltage_kv` where not given.
    #[serde(default = "unset")]
    pub clearance: f64,
    /// Radial clearance kept at all times, m. GO 95's for `voltage_kv` where not given.
    #[serde(default = "unset")]
    pub minimum: f64,
    /// The line's voltage, kV, where its clearances are GO 95's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voltage_kv: Option<f64>,
    /// How the utility's crew reaches the tree.
    #[serde(default)]
    pub access: Access,
    /// Years between its line clearances (`[pruning]`'s `line_cycle` where not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<i64>,
}

/// How a utility's crew reaches a tree: its crew and so its hourly rate.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Access {
    /// From the street, a two-person crew with an aerial lift.
    #[default]
    Street,
    /// Behind buildings, a three-person climbing crew.
    Backyard,
}

/// A clearance the file left for GO 95 to give.
fn unset() -> f64 {
    f64::NAN
}

/// California Public Utilities Commission, General Order 95: the radial clearances of bare
/// line conductors from vegetation, m, for a line of `kv` kilovolts: at the time of trimming
/// (Appendix E, "Guidelines to Rule 35", the normal case: 4 ft for 2.4 to 72 kV, 6 ft to
/// 110 kV, 10 ft to 300 kV, 15 ft above) and at all times (Rule 35, Table 1, Case 13: 18 in
/// for 750 V to 22.5 kV; the Table's other voltage columns were not read, so above 22.5 kV a
/// site gives its own `minimum`). `None` for a voltage GO 95 gives no figure for here.
pub fn go95(kv: f64) -> (Option<f64>, Option<f64>) {
    const FOOT: f64 = 0.3048;
    let trimming = match kv {
        kv if (2.4..72.0).contains(&kv) => Some(4.0 * FOOT),
        kv if (72.0..110.0).contains(&kv) => Some(6.0 * FOOT),
        kv if (110.0..300.0).contains(&kv) => Some(10.0 * FOOT),
        kv if kv >= 300.0 => Some(15.0 * FOOT),
        _ => None,
    };
    let always = (0.75..=22.5).contains(&kv).then_some(1.5 * FOOT);
    (trimming, always)
}

/// A street light's lamp.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Light {
    /// Position along the street, m.
    pub x: f64,
    /// Position across it, m.
    pub y: f64,
    /// Lamp height, m.
    pub height: f64,
    /// Clear radius around the lamp, m.
    pub clearance: f64,
}

/// A sight triangle at a corner or signal: nothing between `low` and `high` inside it.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SightTriangle {
    /// Its three corners, (x, y), m.
    pub corners: [[f64; 2]; 3],
    /// Bottom of the clear band, m.
    pub low: f64,
    /// Top of the clear band, m.
    pub high: f64,
}

/// A named set of cycles.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum Standard {
    /// US street practice, each cycle from a published source (docs/benefits.md; the figures
    /// are `street::work::pruning`'s):
    /// - lines every 4 years: utilities clear distribution lines every 3 to 5 years, to a
    ///   clearance that keeps regrowth out of the line until the next cycle (Shenandoah Valley
    ///   Electric Cooperative, clearance specifications; United Electric Cooperative, primary
    ///   distribution lines);
    /// - crown raising and building clearance every 5 years: Miller and Sylvester (1981,
    ///   Journal of Arboriculture 7:109-112) found a five-year rotation optimal for
    ///   Milwaukee's 40,000 street trees, the goal many cities since adopted (Arboriculture &
    ///   Urban Forestry 28(3):137, on Rochester, NY);
    /// - structural pruning every 3 years while the DBH is under 15.24 cm (6 in): the
    ///   young-tree training cycle a municipal inventory recommends (Davey Resource Group, tree
    ///   inventory analysis for Orono, MN).
    #[default]
    UsStreet,
    /// No pruning at all (`sylva rank --no-pruning`).
    None,
}

/// A site's `[pruning]` table as written.
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PruningSpec {
    /// The standard whose cycles the keys below override.
    #[serde(default)]
    pub standard: Standard,
    /// Years between line clearances.
    pub line_cycle: Option<i64>,
    /// Years between crown raisings over the roadway and sidewalk.
    pub raise_cycle: Option<i64>,
    /// Years between clearances from the façade, awnings, signs and lamps.
    pub building_cycle: Option<i64>,
    /// Years between structural prunings of a young tree.
    pub structural_cycle: Option<i64>,
    /// DBH under which a tree gets structural pruning, cm.
    pub structural_until: Option<f64>,
}

/// A whole site.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Site {
    /// The file the site was read from (errors name it).
    #[serde(skip)]
    pub file: String,
    /// The street.
    pub street: Street,
    /// The building wall, if there is one.
    pub facade: Option<Facade>,
    /// Awnings on the wall.
    #[serde(default)]
    pub awning: Vec<WallBox>,
    /// Signs on the wall.
    #[serde(default)]
    pub sign: Vec<WallBox>,
    /// Overhead lines.
    #[serde(default)]
    pub wire: Vec<Wire>,
    /// Street lights.
    #[serde(default)]
    pub light: Vec<Light>,
    /// A sight triangle.
    pub sight_triangle: Option<SightTriangle>,
    /// How the street prunes the tree (`street::work::pruning`); the default standard where absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pruning: Option<PruningSpec>,
    /// What the street does at planting to spare its pavement from the roots.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mitigation: Option<Mitigation>,
}

/// What a street does at planting to spare its pavement from the tree's roots
/// (`street::work::roots` for their effects; the run's cost table prices them).
///
/// ```toml
/// [mitigation]
/// root_barrier_m = 6.0        # a linear root barrier this long along the curb and sidewalk
/// cutout_m = 0.5              # the pavement cut back this far from the trunk ...
/// cutout_m2 = 1.5             # ... removing this much of it
/// flexible_pavement_m2 = 9.0  # the flags beside the tree laid in rubber or modular pavers
/// ```
#[derive(Clone, Debug, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Mitigation {
    /// Length of a linear root barrier installed at planting, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_barrier_m: Option<f64>,
    /// How much farther from the trunk the pavement is cut back (a larger bed or cut-out, or
    /// a sidewalk curving away), m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cutout_m: Option<f64>,
    /// The pavement removed for it, m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cutout_m2: Option<f64>,
    /// Sidewalk beside the tree laid in rubber or modular pavers instead of concrete, m².
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flexible_pavement_m2: Option<f64>,
}

/// Checks a site's `[pruning]` keys, its wires' cycles and the clearances pruning cuts to;
/// errors name `file`, the key and what is allowed.
fn check_pruning(site: &Site, file: &str) -> Result<(), StreetError> {
    let bad = |key: &str, value: f64, allowed: &str| Err(bad_value(file, key, value, allowed));
    let cycle = |key: &str, years: Option<i64>| match years {
        Some(y) if !(1..=MOST_YEARS).contains(&y) => bad(
            key,
            y as f64,
            &format!("a cycle of whole years, 1 to {MOST_YEARS}"),
        ),
        _ => Ok(()),
    };
    if let Some(p) = &site.pruning {
        cycle("pruning.line_cycle", p.line_cycle)?;
        cycle("pruning.raise_cycle", p.raise_cycle)?;
        cycle("pruning.building_cycle", p.building_cycle)?;
        cycle("pruning.structural_cycle", p.structural_cycle)?;
        if let Some(d) = p.structural_until
            && !(d > 0.0 && d <= 100.0)
        {
            return bad(
                "pruning.structural_until",
                d,
                "a DBH above 0 and at most 100 cm",
            );
        }
    }
    for w in &site.wire {
        cycle("wire.cycle", w.cycle)?;
    }
    // Cleared to its clearance, a wire or lamp whose clearance reaches the ground takes the
    // trunk.
    let fixtures = (site.wire.iter().map(|w| ("wire", w.clearance, w.height)))
        .chain(site.light.iter().map(|l| ("light", l.clearance, l.height)));
    for (kind, clearance, height) in fixtures {
        if clearance >= height {
            return bad(
                &format!("{kind}.clearance"),
                clearance,
                &format!("less than its height ({height} m): pruning clears the tree to it"),
            );
        }
    }
    Ok(())
}

/// The error for `key` of `file` holding `value` where `allowed` is what it may hold.
fn bad_value(file: &str, key: &str, value: f64, allowed: &str) -> StreetError {
    StreetError::Value {
        file: file.to_string(),
        key: key.to_string(),
        value,
        allowed: allowed.to_string(),
    }
}

/// The longest pruning cycle a site may give, years: a street tree left longer is not on a
/// cycle.
pub const MOST_YEARS: i64 = 20;

/// Lamps closer than this are one lamp written twice, m.
const LIGHTS_APART: f64 = 0.5;
/// Largest distance or height a site may give, m: a street, not a map.
const FAR: f64 = 1000.0;

impl Site {
    /// Reads and checks a site file.
    pub fn load(path: &Path) -> Result<Site, StreetError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| StreetError::Io {
            path: file.clone(),
            message: e.to_string(),
        })?;
        Site::parse(&text, &file)
    }

    /// Parses and checks a site from TOML text; `file` names it in errors.
    pub fn parse(text: &str, file: &str) -> Result<Site, StreetError> {
        let site: Site = toml::from_str(text).map_err(|e| StreetError::Syntax {
            file: file.to_string(),
            message: e.message().to_string()
                + &e.span()
                    .map(|s| format!(" (line {})", text[..s.start].lines().count().max(1)))
                    .unwrap_or_default(),
        })?;
        let mut site = site;
        site.file = file.to_string();
        site.resolve_wires(file)?;
        site.check(file)?;
        Ok(site)
    }

    /// Fills each wire's clearances GO 95 gives for its voltage where the file left them out;
    /// an error names the key where neither is given.
    fn resolve_wires(&mut self, file: &str) -> Result<(), StreetError> {
        for w in &mut self.wire {
            let (trimming, always) = match w.voltage_kv {
                Some(kv) if !(kv.is_finite() && kv > 0.0 && kv <= 1000.0) => {
                    return Err(bad_value(
                        file,
                        "wire.voltage_kv",
                        kv,
                        "a line voltage above 0 and at most 1000 kV",
                    ));
                }
                Some(kv) => go95(kv),
                None => (None, None),
            };
            for (key, value, given) in [
                ("wire.clearance", &mut w.clearance, trimming),
                ("wire.minimum", &mut w.minimum, always),
            ] {
                if !value.is_nan() {
                    continue;
                }
                *value = given.ok_or_else(|| {
                    let why = match w.voltage_kv {
                        Some(kv) => format!(
                            "a distance in metres: GO 95 gives none read here for {kv} kV \
                             (voltage_kv gives the clearance at trimming for 2.4 kV and up, \
                             the minimum for 0.75 to 22.5 kV)"
                        ),
                        None => "a distance in metres, or voltage_kv for GO 95's".to_string(),
                    };
                    StreetError::Syntax {
                        file: file.to_string(),
                        message: format!("`{key}` is not given: expected {why}"),
                    }
                })?;
            }
        }
        Ok(())
    }

    fn check(&self, file: &str) -> Result<(), StreetError> {
        let bad = |key: &str, value: f64, allowed: &str| Err(bad_value(file, key, value, allowed));
        let all_finite = |key: &str, values: &[f64]| -> Result<(), StreetError> {
            for &v in values {
                if !v.is_finite() || v.abs() > FAR {
                    return bad(key, v, "a finite number of metres within 1000 m");
                }
            }
            Ok(())
        };
        let s = &self.street;
        all_finite("street", &[s.curb, s.sidewalk[0], s.sidewalk[1]])?;
        if s.curb >= 0.0 {
            return bad(
                "street.curb",
                s.curb,
                "below 0: the curb lies between the trunk (y = 0) and the roadway",
            );
        }
        if s.sidewalk[0] >= s.sidewalk[1] || s.sidewalk[0] < s.curb {
            return bad(
                "street.sidewalk",
                s.sidewalk[1],
                "[from, to] with curb <= from < to",
            );
        }
        for (key, v) in [
            ("street.roadway_clearance", s.roadway_clearance),
            ("street.sidewalk_clearance", s.sidewalk_clearance),
        ] {
            if !(0.0..=50.0).contains(&v) {
                return bad(key, v, "0 to 50 m");
            }
        }
        if let Some(f) = &self.facade {
            all_finite("facade", &[f.setback, f.height, f.width, f.faces])?;
            if f.setback <= 0.0 {
                return bad(
                    "facade.setback",
                    f.setback,
                    "above 0: the wall stands on the building side of the trunk",
                );
            }
            if f.height.is_nan() || f.height <= 0.0 {
                return bad("facade.height", f.height, "a positive height");
            }
            if f.width.is_nan() || f.width <= 0.0 {
                return bad("facade.width", f.width, "a positive width");
            }
            if !(0.0..360.0).contains(&f.faces) {
                return bad(
                    "facade.faces",
                    f.faces,
                    "a compass direction, 0 to 360 degrees",
                );
            }
            if !(0.0..=1.0).contains(&f.window_share) {
                return bad("facade.window_share", f.window_share, "a share, 0 to 1");
            }
        }
        for (kind, boxes) in [("awning", &self.awning), ("sign", &self.sign)] {
            for b in boxes {
                all_finite(kind, &[b.bottom, b.top, b.reach, b.along[0], b.along[1]])?;
                if self.facade.is_none() {
                    return bad(
                        kind,
                        b.bottom,
                        "an [[awning]] or [[sign]] needs a [facade] to hang on",
                    );
                }
                if b.bottom < 0.0 {
                    return bad(
                        &format!("{kind}.bottom"),
                        b.bottom,
                        "a height above the ground (>= 0 m)",
                    );
                }
                if b.top <= b.bottom {
                    return bad(&format!("{kind}.top"), b.top, "above its bottom");
                }
                if b.reach.is_nan() || b.reach <= 0.0 {
                    return bad(
                        &format!("{kind}.reach"),
                        b.reach,
                        "a positive distance from the wall",
                    );
                }
                if b.along[0] >= b.along[1] {
                    return bad(
                        &format!("{kind}.along"),
                        b.along[1],
                        "[from, to] with from < to",
                    );
                }
            }
        }
        for w in &self.wire {
            all_finite("wire", &[w.height, w.offset, w.clearance, w.minimum])?;
            if w.height.is_nan() || w.height <= 0.0 {
                return bad("wire.height", w.height, "a height above the ground (> 0 m)");
            }
            if w.clearance.is_nan() || w.clearance < 0.0 {
                return bad("wire.clearance", w.clearance, "a distance >= 0 m");
            }
            if w.minimum.is_nan() || w.minimum <= 0.0 {
                return bad("wire.minimum", w.minimum, "a distance above 0 m");
            }
            if w.minimum > w.clearance {
                return bad(
                    "wire.minimum",
                    w.minimum,
                    &format!(
                        "at most the clearance at cutting ({} m): crews cut to the clearance, \
                         and regrowth may close it only down to the minimum",
                        w.clearance
                    ),
                );
            }
        }
        for (i, l) in self.light.iter().enumerate() {
            all_finite("light", &[l.x, l.y, l.height, l.clearance])?;
            if l.height.is_nan() || l.height <= 0.0 {
                return bad(
                    "light.height",
                    l.height,
                    "a height above the ground (> 0 m)",
                );
            }
            if l.clearance.is_nan() || l.clearance < 0.0 {
                return bad("light.clearance", l.clearance, "a distance >= 0 m");
            }
            for m in &self.light[..i] {
                let d = ((l.x - m.x).powi(2) + (l.y - m.y).powi(2)).sqrt();
                if d < LIGHTS_APART {
                    return bad(
                        "light",
                        l.x,
                        &format!(
                            "lights at least {LIGHTS_APART} m apart (two stand at x = {}, y = {})",
                            m.x, m.y
                        ),
                    );
                }
            }
        }
        if let Some(t) = &self.sight_triangle {
            let flat: Vec<f64> = t.corners.iter().flatten().copied().collect();
            all_finite("sight_triangle.corners", &flat)?;
            all_finite("sight_triangle", &[t.low, t.high])?;
            if t.low < 0.0 {
                return bad(
                    "sight_triangle.low",
                    t.low,
                    "a height above the ground (>= 0 m)",
                );
            }
            if t.high <= t.low {
                return bad("sight_triangle.high", t.high, "above low");
            }
            let [a, b, c] = t.corners;
            let area = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs() / 2.0;
            if area < 1e-3 {
                return bad(
                    "sight_triangle.corners",
                    area,
                    "three corners that enclose an area",
                );
            }
        }
        if let Some(m) = &self.mitigation {
            for (key, v) in [
                ("mitigation.root_barrier_m", m.root_barrier_m),
                ("mitigation.cutout_m", m.cutout_m),
                ("mitigation.cutout_m2", m.cutout_m2),
                ("mitigation.flexible_pavement_m2", m.flexible_pavement_m2),
            ] {
                if let Some(v) = v
                    && !(v.is_finite() && v > 0.0 && v <= 100.0)
                {
                    return bad(key, v, "a positive length (m) or area (m²), at most 100");
                }
            }
            if m.cutout_m.is_some() != m.cutout_m2.is_some() {
                return bad(
                    "mitigation.cutout_m2",
                    m.cutout_m2.unwrap_or(f64::NAN),
                    "given with cutout_m: the pavement a cut-out removes, m², and how far it \
                     moves the pavement from the trunk, m",
                );
            }
        }
        check_pruning(self, file)
    }
}

/// The repository's narrow street under wires (`sites/narrow-under-wires.toml`), for the
/// street's tests.
#[cfg(test)]
pub(crate) fn narrow_for_tests() -> Site {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../sites/narrow-under-wires.toml"
    ))
    .expect("the narrow site");
    Site::parse(&text, "narrow-under-wires.toml").expect("a good site")
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
[street]
curb = -1.0
sidewalk = [0.8, 3.2]
roadway_clearance = 4.3
sidewalk_clearance = 2.4
[facade]
setback = 6.0
height = 8.0
width = 12.0
faces = 180.0
window_share = 0.25
[[awning]]
bottom = 2.6
top = 3.0
reach = 1.5
along = [-2.0, 2.0]
[[wire]]
height = 8.5
offset = -0.6
clearance = 3.0
minimum = 0.46
[[light]]
x = 6.0
y = -0.7
height = 7.0
clearance = 1.0
[sight_triangle]
corners = [[-12.0, -1.0], [-4.0, -1.0], [-12.0, 6.0]]
low = 0.9
high = 2.4
"#;

    fn error(text: &str) -> String {
        Site::parse(text, "site.toml").unwrap_err().to_string()
    }

    #[test]
    fn the_documented_site_reads() {
        let site = Site::parse(GOOD, "site.toml").unwrap();
        assert_eq!(site.wire.len(), 1);
        assert_eq!(site.facade.unwrap().setback, 6.0);
        assert!(site.sight_triangle.is_some());
    }

    #[test]
    fn bad_sites_name_the_file_the_key_and_what_is_allowed() {
        let e = error(&GOOD.replace("height = 8.5", "height = -2.0"));
        assert!(
            e.contains("site.toml") && e.contains("wire.height") && e.contains("above the ground"),
            "{e}"
        );
        let e = error(&GOOD.replace("bottom = 2.6", "bottom = -1.0"));
        assert!(e.contains("awning.bottom"), "{e}");
        let e = error(&GOOD.replace("height = 8.0", "height = -8.0"));
        assert!(e.contains("facade.height"), "{e}");
        let e = error(&format!(
            "{GOOD}\n[[light]]\nx = 6.2\ny = -0.7\nheight = 7.0\nclearance = 1.0\n"
        ));
        assert!(e.contains("light") && e.contains("apart"), "{e}");
        let e = error(&GOOD.replace("reach = 1.5", "reach = 1.5\ncolour = 3"));
        assert!(e.contains("site.toml") && e.contains("colour"), "{e}");
        let e = error(&GOOD.replace("curb = -1.0", "curb = 1.0"));
        assert!(e.contains("street.curb"), "{e}");
        let e = error("[street]\ncurb = -1.0\n");
        assert!(e.contains("site.toml") && e.contains("sidewalk"), "{e}");
        let e = error(&GOOD.replace(
            "[[-12.0, -1.0], [-4.0, -1.0], [-12.0, 6.0]]",
            "[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]",
        ));
        assert!(e.contains("sight_triangle.corners"), "{e}");
    }

    #[test]
    fn a_wires_clearances_are_its_own_or_go95s_by_voltage() {
        let by_voltage = GOOD.replace("clearance = 3.0\nminimum = 0.46\n", "voltage_kv = 12.0\n");
        let w = &Site::parse(&by_voltage, "site.toml").unwrap().wire[0];
        // GO 95: 4 ft at trimming for 2.4-72 kV, 18 in at all times for 0.75-22.5 kV.
        assert!((w.clearance - 1.2192).abs() < 1e-9 && (w.minimum - 0.4572).abs() < 1e-9);
        assert_eq!(w.access, Access::Street);
        // A file's own figure stands over GO 95's.
        let own = by_voltage.replace(
            "voltage_kv = 12.0\n",
            "voltage_kv = 12.0\nclearance = 3.0\n",
        );
        assert_eq!(
            Site::parse(&own, "site.toml").unwrap().wire[0].clearance,
            3.0
        );
        assert_eq!(go95(115.0), (Some(10.0 * 0.3048), None));
        // Neither given: the key is named with what it may be.
        let e = error(&GOOD.replace("minimum = 0.46\n", ""));
        assert!(
            e.contains("site.toml") && e.contains("wire.minimum") && e.contains("voltage_kv"),
            "{e}"
        );
        // GO 95 has no minimum read here for 69 kV.
        let e = error(&by_voltage.replace("voltage_kv = 12.0", "voltage_kv = 69.0"));
        assert!(e.contains("wire.minimum") && e.contains("69 kV"), "{e}");
        // The minimum kept at all times may not exceed the clearance cut to.
        let e = error(&GOOD.replace("minimum = 0.46", "minimum = 3.5"));
        assert!(
            e.contains("wire.minimum") && e.contains("at most the clearance"),
            "{e}"
        );
        let e = error(&GOOD.replace("minimum = 0.46", "minimum = 0.0"));
        assert!(e.contains("wire.minimum"), "{e}");
        let e = error(&by_voltage.replace("voltage_kv = 12.0", "voltage_kv = -3.0"));
        assert!(e.contains("wire.voltage_kv"), "{e}");
        let e = error(&GOOD.replace("minimum = 0.46", "minimum = 0.46\naccess = \"roof\""));
        assert!(e.contains("roof") && e.contains("backyard"), "{e}");
    }
}
