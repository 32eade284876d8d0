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
//! clearance = 3.0            # radial clearance the utility requires
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
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Wire {
    /// Height of the line, m.
    pub height: f64,
    /// y of the line, m.
    pub offset: f64,
    /// Radial clearance the utility requires, m: what line clearance cuts to.
    pub clearance: f64,
    /// Years between its line clearances (`[pruning]`'s `line_cycle` where not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycle: Option<i64>,
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
        site.check(file)?;
        Ok(site)
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
            all_finite("wire", &[w.height, w.offset, w.clearance])?;
            if w.height.is_nan() || w.height <= 0.0 {
                return bad("wire.height", w.height, "a height above the ground (> 0 m)");
            }
            if w.clearance.is_nan() || w.clearance < 0.0 {
                return bad("wire.clearance", w.clearance, "a distance >= 0 m");
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
        check_pruning(self, file)
    }
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
}
