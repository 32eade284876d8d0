//! The part of a tree's energy effect that does not depend on where it stands: i-Tree's
//! "climate effects", calibrated per region against i-Tree Streets' own figures.
//!
//! i-Tree Streets' energy figures (McPherson and Simpson 1999, PSW-GTR-171) add two things: the
//! shade a tree casts on the building, which depends on its distance and direction, and the
//! climate effects of its canopy (cooler air from evapotranspiration, slower wind, so less
//! infiltration in winter), which GTR-171 computes from the canopy cover the tree adds and so
//! does not depend on its position. Sylva computes the shade from the crown itself
//! (`street::energy::shade`). GTR-171's climate-effect coefficients were not reachable, so the climate
//! term is calibrated instead: per region, per square metre of the crown's projection, it is
//! what i-Tree's figures hold beyond Sylva's own shade, with each tree at i-Tree's typical
//! positions around a standard house (`street::accounts::calibrate`).
//!
//! - Cooling: a least-squares fit through the origin of (i-Tree's electricity − Sylva's shade)
//!   against the crown projection, over the region's species at 20, 30 and 40 cm DBH.
//! - Heating and the useful share of winter sun, fitted together. Sylva's shade model counts
//!   every kWh of winter sun a crown keeps off the walls (an evergreen's leaves, a deciduous
//!   tree's bare wood) as heat the furnace must replace. Only part of it is: on a sunny winter
//!   day a house's solar and internal gains can exceed its losses, and the excess is not useful
//!   (ISO 13790's gain utilisation). i-Tree's gas = heating x projection - share x Sylva's
//!   penalty: heating is fitted through the origin over the region's deciduous broadleaves
//!   (their bare wood's penalty counted at the share), the share over its evergreens (whose
//!   leaves' penalty is large) with that heating term, both at once; the share is held to 0..1.
//!   Where the region has no evergreen, the whole penalty counts.
//!
//! The fitted term absorbs whatever Sylva's shade model leaves out of i-Tree's: the roof, a
//! cooling season longer than June to August, older and less efficient buildings. It is a
//! calibration, not a measurement of wind or evapotranspiration, and docs/benefits.md says so.
//! The built-in coefficients are in `data/itree-streets/climate-effect.csv`, written by
//! `tools/fit-climate-effect.sh` (`sylva rank --calibrate --fit` for every region).

use std::sync::OnceLock;

/// A region's climate effect per square metre of crown projection.
#[derive(Clone, Debug, PartialEq)]
pub struct ClimateEffect {
    /// Region code.
    pub region: String,
    /// Electricity saved, kWh per m² of crown projection per year.
    pub cooling_kwh_per_m2: f64,
    /// Natural gas saved (negative: used), kBtu per m² of crown projection per year.
    pub heating_kbtu_per_m2: f64,
    /// The share of the winter sun an evergreen keeps out that the furnace must replace, 0..1;
    /// `None` where no evergreen could be fitted (then all of it counts).
    pub useful_winter_share: Option<f64>,
    /// Calibration points (species at a DBH) the cooling fit read, the deciduous broadleaf ones
    /// the heating fit read, and the evergreen ones the useful share's fit read.
    pub points: (usize, usize, usize),
}

impl ClimateEffect {
    /// The climate effect of a crown whose projection is `projection_m2`: kWh and kBtu saved.
    pub fn of(&self, projection_m2: f64) -> (f64, f64) {
        (
            self.cooling_kwh_per_m2 * projection_m2,
            self.heating_kbtu_per_m2 * projection_m2,
        )
    }

    /// The share of a winter shade penalty that is counted (1 where none was fitted).
    pub fn useful_share(&self) -> f64 {
        self.useful_winter_share.unwrap_or(1.0)
    }
}

/// One calibration point: a grown tree at typical position beside i-Tree's figures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Crown projection, m².
    pub projection_m2: f64,
    /// Sylva's shade: electricity saved, kWh, and natural gas saved (negative), kBtu.
    pub shade: (f64, f64),
    /// i-Tree's electricity, kWh, and natural gas, kBtu.
    pub itree: (f64, f64),
    /// Whether the species is a deciduous broadleaf (i-Tree type `BD*`).
    pub deciduous_broadleaf: bool,
    /// Whether it keeps its leaves in winter (i-Tree type `?E?`).
    pub evergreen: bool,
}

/// Slope through the origin of `y` against `x`, or `None` with nothing to fit.
fn slope(points: impl Iterator<Item = (f64, f64)>) -> Option<f64> {
    let (mut xy, mut xx) = (0.0, 0.0);
    for (x, y) in points.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        xy += x * y;
        xx += x * x;
    }
    (xx > 0.0).then(|| xy / xx)
}

/// Fits a region's climate effect to its calibration points (see the module's comment);
/// `None` if no point has a crown, or none is a deciduous broadleaf.
pub fn fit(region: &str, points: &[Point]) -> Option<ClimateEffect> {
    let cooling = slope(
        points
            .iter()
            .map(|p| (p.projection_m2, p.itree.0 - p.shade.0)),
    )?;
    let deciduous = || points.iter().filter(|p| p.deciduous_broadleaf);
    let evergreen = || points.iter().filter(|p| p.evergreen && p.shade.1 < 0.0);
    // i-Tree's gas = heating x projection - share x penalty, the penalty being -shade.1 (a
    // deciduous tree's from its bare wood, an evergreen's from its leaves). Heating is read
    // from the deciduous trees with their penalty at the share: heating = h0 + share x k. The
    // share is read from the evergreens, whose penalty is large, with that heating term:
    // share = heating x m - q. Both hold at once where share = (h0 m - q) / (1 - k m).
    let sums = |it: &mut dyn Iterator<Item = &Point>, f: &dyn Fn(&Point) -> (f64, f64)| {
        it.map(f)
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y))
    };
    let (d_ay, d_aa) = sums(&mut deciduous(), &|p| {
        (
            p.projection_m2 * p.itree.1,
            p.projection_m2 * p.projection_m2,
        )
    });
    let (d_ab, _) = sums(&mut deciduous(), &|p| (-p.projection_m2 * p.shade.1, 0.0));
    if d_aa <= 0.0 {
        return None;
    }
    let (h0, k) = (d_ay / d_aa, d_ab / d_aa);
    let (e_ab, e_bb) = sums(&mut evergreen(), &|p| {
        (-p.shade.1 * p.projection_m2, p.shade.1 * p.shade.1)
    });
    let (e_by, _) = sums(&mut evergreen(), &|p| (-p.shade.1 * p.itree.1, 0.0));
    let useful = (e_bb > 0.0)
        .then(|| {
            let (m, q) = (e_ab / e_bb, e_by / e_bb);
            let share = (h0 * m - q) / (1.0 - k * m);
            share.is_finite().then_some(share)
        })
        .flatten()
        // Held to 0..1 (and never -0, which would print as "-0.0000").
        .map(|s| if s > 0.0 { s.min(1.0) } else { 0.0 });
    // With none fitted, the whole penalty counts.
    let heating = h0 + useful.unwrap_or(1.0) * k;
    Some(ClimateEffect {
        region: region.to_string(),
        cooling_kwh_per_m2: cooling,
        heating_kbtu_per_m2: heating,
        useful_winter_share: useful,
        points: (points.len(), deciduous().count(), evergreen().count()),
    })
}

const CSV: &str = include_str!("../../../data/itree-streets/climate-effect.csv");

/// Reads `climate-effect.csv`: comment lines (`#`), a header `region, cooling_kwh_per_m2,
/// heating_kbtu_per_m2, useful_winter_share, points, deciduous_points, evergreen_points`, then
/// one row per region (an empty useful share: not fitted).
pub fn parse(text: &str) -> Result<Vec<ClimateEffect>, String> {
    let mut rows = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.starts_with('#') && !l.trim().is_empty());
    let expected = "region,cooling_kwh_per_m2,heating_kbtu_per_m2,useful_winter_share,points,\
                    deciduous_points,evergreen_points";
    match rows.next() {
        Some((_, h)) if h == expected => {}
        other => {
            return Err(format!(
                "climate-effect.csv: header {:?}, expected {expected:?}",
                other.map(|o| o.1).unwrap_or_default()
            ));
        }
    }
    let mut out = Vec::new();
    for (n, line) in rows {
        let f: Vec<&str> = line.split(',').collect();
        let bad = |what: String| format!("climate-effect.csv line {}: {what}", n + 1);
        if f.len() != 7 {
            return Err(bad(format!("{} fields, 7 expected", f.len())));
        }
        let num = |i: usize| -> Result<f64, String> {
            f[i].parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    bad(format!(
                        "field {} is {:?}, not a finite number",
                        i + 1,
                        f[i]
                    ))
                })
        };
        let useful = match f[3] {
            "" => None,
            _ => Some(num(3)?)
                .filter(|u| (0.0..=1.0).contains(u))
                .map(Some)
                .ok_or_else(|| {
                    bad(format!(
                        "useful_winter_share is {}; a share is 0 to 1",
                        f[3]
                    ))
                })?,
        };
        out.push(ClimateEffect {
            region: f[0].to_string(),
            cooling_kwh_per_m2: num(1)?,
            heating_kbtu_per_m2: num(2)?,
            useful_winter_share: useful,
            points: (num(4)? as usize, num(5)? as usize, num(6)? as usize),
        });
    }
    Ok(out)
}

/// The built-in climate effect of a region, if it was fitted.
pub fn climate_effect(region: &str) -> Option<&'static ClimateEffect> {
    static TABLE: OnceLock<Vec<ClimateEffect>> = OnceLock::new();
    TABLE
        .get_or_init(|| parse(CSV).expect("the built-in climate-effect table parses"))
        .iter()
        .find(|c| c.region == region)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(p: f64, shade: (f64, f64), itree: (f64, f64), bd: bool) -> Point {
        Point {
            projection_m2: p,
            shade,
            itree,
            deciduous_broadleaf: bd,
            evergreen: !bd,
        }
    }

    #[test]
    fn the_fit_recovers_a_known_climate_effect() {
        // i-Tree = shade + 1.5 kWh/m² and, for deciduous trees, 2 kBtu/m².
        // Gas: 2 kBtu/m² less 0.7 of each tree's winter shade penalty (a deciduous tree's from
        // its bare wood, an evergreen's from its leaves).
        let pts = [
            point(50.0, (20.0, -10.0), (95.0, 100.0 - 7.0), true),
            point(100.0, (40.0, -15.0), (190.0, 200.0 - 10.5), true),
            point(80.0, (30.0, -300.0), (150.0, 160.0 - 210.0), false),
        ];
        let c = fit("X", &pts).unwrap();
        assert!((c.cooling_kwh_per_m2 - 1.5).abs() < 1e-12, "{c:?}");
        assert!((c.heating_kbtu_per_m2 - 2.0).abs() < 1e-9, "{c:?}");
        assert!((c.useful_winter_share.unwrap() - 0.7).abs() < 1e-9, "{c:?}");
        assert_eq!(c.of(10.0).0, 15.0);
        // Without an evergreen the share is not fitted: the whole penalty counts.
        let c = fit("X", &pts[..2]).unwrap();
        assert_eq!(c.useful_winter_share, None);
        assert!((c.heating_kbtu_per_m2 - (50.0 * 103.0 + 100.0 * 204.5) / 12500.0).abs() < 1e-9);
        // A share past 1 is held to 1 and heating refitted with it.
        let mut far = pts;
        far[2].itree.1 = 160.0 - 600.0;
        let c = fit("X", &far).unwrap();
        assert_eq!(c.useful_winter_share, Some(1.0));
        // Without a deciduous broadleaf there is nothing to fit heating to.
        assert!(fit("X", &pts[2..]).is_none());
    }

    #[test]
    fn every_region_is_fitted_and_a_damaged_table_is_refused() {
        for c in &crate::street::energy::climate::CLIMATES {
            let e = climate_effect(c.region).unwrap_or_else(|| panic!("{}", c.region));
            assert!(e.points.0 >= 3 && e.points.1 >= 1, "{e:?}");
        }
        let head = "region,cooling_kwh_per_m2,heating_kbtu_per_m2,useful_winter_share,points,\
                    deciduous_points,evergreen_points";
        let e = parse(&format!("# c\n{head}\nX,1,NaN,0.5,3,1,1\n")).unwrap_err();
        assert!(e.contains("line 3") && e.contains("field 3"), "{e}");
        let e = parse(&format!("{head}\nX,1,1,1.5,3,1,1\n")).unwrap_err();
        assert!(e.contains("0 to 1"), "{e}");
        let ok = parse(&format!("{head}\nX,1,1,,3,1,0\n")).unwrap();
        assert_eq!(ok[0].useful_winter_share, None);
        let e = parse(&format!("{head}\nX,1\n")).unwrap_err();
        assert!(e.contains("2 fields"), "{e}");
        assert!(parse("a,b\n").unwrap_err().contains("header"));
    }
}
