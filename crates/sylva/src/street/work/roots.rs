//! Roots against the pavement: the chance that a street tree damages the sidewalk and curb
//! beside it, from its trunk's size, its distance from the pavement and its species, fitted to
//! what New York's 2015 Street Tree Census recorded beside every living tree.
//!
//! **The data.** The census records, for each tree, its DBH, whether its bed lies along the
//! curb or offset from it, and whether a sidewalk flag beside it is damaged, cracked or lifted
//! (`data/street/nyc-2015-sidewalk.csv`, counts over all 652,172 living trees). Published
//! models of the same question (Francis, Parresol & Marin de Patino 1996, J. Arboric. 22(4):
//! logistic models in distance, DBH and species, for twelve tropical species) give data-based
//! forms but their coefficients were not reachable, so Sylva fits the census, as the issue
//! allows ("fit it where a study gives data").
//!
//! **The model.** A flag beside a tree is damaged for reasons of its own (age, soil, traffic:
//! Sydnor et al. 2000, J. Arboric. 26(1), found sidewalks failing as often without trees) or
//! because the tree's roots lifted it:
//!
//! ```text
//! P(damaged) = P0(place) + (1 - P0(place)) T,   logit T = a + b ln(DBH cm) + c w(d) + s
//! ```
//!
//! - `P0`, the background, is the share damaged beside trees under 3 in DBH, whose roots
//!   cannot have done it: 13.8% along the curb, 8.1% offset from it.
//! - `T` is the share the tree has damaged. `a`, `b`, `c` are fitted by maximum likelihood to
//!   the census's trees of 3 to 50 in, their background held.
//! - `w(d)` reads the distance from the trunk to the nearest pavement, `d`, against the
//!   census's two places, whose points it maps 2.5 ft and 12 ft from the curb (its data
//!   dictionary): 0 at 0.76 m or nearer, 1 at 3.66 m or farther, linear between. Randrup,
//!   McPherson & Costello (2001, Urban Ecosystems 5:209-225) put the risk on trees within
//!   2-3 m of the pavement; the census's offset trees stand beyond it. Nothing is extrapolated
//!   past the census's two places.
//! - `s`, the species' rooting habit, is fitted to some 27,000 trees of the census with their
//!   species (`data/street/nyc-2015-sidewalk-species.csv`), each species' shift on the logit
//!   with `a`, `b`, `c` held, relative to the sample as a whole (the extracts run a little
//!   higher than the census), and shrunk towards 0 by its standard error against the spread
//!   between species (DerSimonian-Laird), so a species with few trees, or only small ones, is
//!   read as the census's mean. A species the census lacks takes its genus's, else 0 (said in
//!   the report).
//!
//! **A year.** The census is a snapshot: `T` is the share of trees of a size whose roots have
//! damaged the pavement by then. A tree growing from `D0` to `D1` in a year damages it for the
//! first time with chance `(T(D1) - T(D0)) / (1 - T(D0))`; Sylva takes that as the yearly
//! chance of a repair, the repaired flag being lifted again at the same rate. Damage the city
//! had already repaired, or trees removed for it, are missing from the snapshot, so the chance
//! is a lower bound, and the report says so.

use crate::street::site::Site;
use std::collections::HashMap;
use std::sync::OnceLock;

/// Where the census maps a tree along the curb, from it, m (2.5 ft).
pub const ON_CURB_M: f64 = 2.5 * 0.3048;
/// Where the census maps a tree offset from the curb, from it, m (12 ft).
pub const OFFSET_M: f64 = 12.0 * 0.3048;
/// Trees under this DBH, in, are the background: their roots have done no damage.
const BACKGROUND_BELOW_IN: u32 = 3;
/// The largest DBH fitted, in: past it the census's classes hold few trees.
const FITTED_UP_TO_IN: u32 = 50;
/// Least trees of a species (3 in and over) for a shift of its own.
const LEAST_TREES: usize = 30;

/// How a species' rooting habit was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Habit {
    /// Its own trees in the census.
    Species,
    /// Its genus's trees in the census.
    Genus,
    /// Not in the census: the census's mean.
    Unknown,
}

/// A species' rooting habit: its shift on the logit of `T`, and where it comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rooting {
    /// The shift (0: the census's mean).
    pub shift: f64,
    /// How it was found.
    pub habit: Habit,
    /// Trees of 3 in and more it was fitted to.
    pub trees: usize,
}

/// The fitted model.
#[derive(Clone, Debug)]
pub struct RootDamage {
    /// The background share damaged, along the curb and offset from it.
    pub background: [f64; 2],
    /// `a`, `b` (per ln cm of DBH) and `c` (offset from the curb).
    pub theta: [f64; 3],
    species: HashMap<String, Rooting>,
    genus: HashMap<String, Rooting>,
}

/// One cell of the census's counts.
#[derive(Clone, Debug)]
struct Cell {
    key: String,
    dbh_in: u32,
    offset: bool,
    trees: f64,
    damaged: f64,
}

fn cells(text: &str, keyed: bool) -> Vec<Cell> {
    (text.lines())
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let (key, rest) = if keyed {
                (f[0].to_string(), &f[1..])
            } else {
                (String::new(), &f[..])
            };
            // The built-in files are checked by a test; a bad row would be a broken build.
            Cell {
                key,
                dbh_in: rest[0].parse().expect("a DBH"),
                offset: rest[1] == "OffsetFromCurb",
                trees: rest[2].parse().expect("a count"),
                damaged: rest[3].parse().expect("a count"),
            }
        })
        .collect()
}

fn sigmoid(z: f64) -> f64 {
    1.0 / (1.0 + (-z).exp())
}

/// A census DBH class's middle, cm (0 in read as half an inch).
fn dbh_cm(inches: u32) -> f64 {
    (inches as f64).max(0.5) * 2.54
}

/// `w(d)`: a distance from the pavement against the census's two places, 0 to 1.
pub fn place(distance_m: f64) -> f64 {
    ((distance_m - ON_CURB_M) / (OFFSET_M - ON_CURB_M)).clamp(0.0, 1.0)
}

/// The distance from the trunk to the nearest pavement on `site`, m: the curb, or the
/// sidewalk's near edge where it lies on the building side of the trunk, and as much again as
/// the site's `[mitigation]` cuts the pavement back.
pub fn distance_to_pavement(site: &Site) -> f64 {
    let s = &site.street;
    let mut d = -s.curb;
    if s.sidewalk[0] > 0.0 {
        d = d.min(s.sidewalk[0]);
    } else if s.sidewalk[1] >= 0.0 {
        // The trunk stands in the sidewalk itself, in a tree well.
        d = 0.0;
    }
    let cut = (site.mitigation.as_ref())
        .and_then(|m| m.cutout_m)
        .unwrap_or(0.0);
    d.max(0.0) + cut
}

/// What is left of the roots' damage under a linear root barrier: the roots of 1.25 cm and
/// more a DeepRoot barrier left near the surface six years after planting, against trees
/// without one, 1.1 against 4.3 (Pittenger & Hodel 2009, "Six-year evaluation of circular root
/// barriers on two tree species", Arboric. Urban For. 35(1):41-46, Table 3). It counts roots,
/// not lifted pavement; roots grew under the barriers and back to the surface a short way
/// beyond them, so it is the barrier's best case.
pub const BARRIER_SHARE: f64 = 1.1 / 4.3;

/// What is left of the repairs where the flags beside the tree are rubber or modular pavers,
/// which are relaid rather than replaced: Santa Monica forecast 80% less sidewalk maintenance
/// over the 20-year cycle of the 3,500 ficus it laid them beside (American City & County,
/// 1 March 2009, reporting the city), the concrete beside them having been redone every six or
/// seven years (CalRecycle's case study, quoting its street maintenance supervisor). A city's
/// forecast, not a measurement.
pub const FLEXIBLE_SHARE: f64 = 0.2;

/// The share of the roots' damage, and of its repairs' cost, left by `site`'s mitigations
/// other than distance (which `distance_to_pavement` counts).
pub fn mitigated_share(site: &Site) -> f64 {
    let Some(m) = &site.mitigation else {
        return 1.0;
    };
    let barrier = if m.root_barrier_m.is_some() {
        BARRIER_SHARE
    } else {
        1.0
    };
    let flexible = if m.flexible_pavement_m2.is_some() {
        FLEXIBLE_SHARE
    } else {
        1.0
    };
    barrier * flexible
}

/// The two names a scientific name is looked up by: its species (genus and epithet, with a
/// hybrid's `x`) and its genus, lower case.
fn names(scientific: &str) -> (String, String) {
    let words: Vec<String> = (scientific.split_whitespace())
        .map(|w| {
            w.trim_matches(|c| c == '\'' || c == '"')
                .to_ascii_lowercase()
        })
        .collect();
    let genus = words.first().cloned().unwrap_or_default();
    let n = if words.get(1).is_some_and(|w| w == "x" || w == "×") {
        3
    } else {
        2
    };
    let species = (words.len() >= n).then(|| words[..n].join(" "));
    (species.unwrap_or_default(), genus)
}

impl RootDamage {
    /// The model fitted to the built-in census counts, once.
    pub fn builtin() -> &'static RootDamage {
        static MODEL: OnceLock<RootDamage> = OnceLock::new();
        MODEL.get_or_init(|| {
            RootDamage::fit(
                include_str!("../../../data/street/nyc-2015-sidewalk.csv"),
                include_str!("../../../data/street/nyc-2015-sidewalk-species.csv"),
            )
        })
    }

    /// Fits the model to census counts by DBH and place (`population`) and by species
    /// (`by_species`), in the built-in files' formats.
    fn fit(population: &str, by_species: &str) -> RootDamage {
        let all = cells(population, false);
        let mut background = [0.0; 2];
        for (i, offset) in [false, true].into_iter().enumerate() {
            let (n, k) = (all.iter())
                .filter(|c| c.offset == offset && c.dbh_in < BACKGROUND_BELOW_IN)
                .fold((0.0, 0.0), |(n, k), c| (n + c.trees, k + c.damaged));
            background[i] = k / n.max(1.0);
        }
        let fitted: Vec<&Cell> = (all.iter())
            .filter(|c| (BACKGROUND_BELOW_IN..=FITTED_UP_TO_IN).contains(&c.dbh_in))
            .collect();
        let mut model = RootDamage {
            background,
            theta: [-5.0, 1.2, -1.0],
            species: HashMap::new(),
            genus: HashMap::new(),
        };
        model.theta = model.fit_theta(&fitted);
        let sample = cells(by_species, true);
        let sample: Vec<&Cell> = (sample.iter())
            .filter(|c| (BACKGROUND_BELOW_IN..=FITTED_UP_TO_IN).contains(&c.dbh_in))
            .collect();
        // The sample as a whole sits a little off the census: species read against it.
        let pool = model.fit_shift(&sample).0;
        let group = |key: &dyn Fn(&str) -> String| {
            let mut groups: HashMap<String, Vec<&Cell>> = HashMap::new();
            for &c in &sample {
                groups.entry(key(&c.key)).or_default().push(c);
            }
            model.shrunk(groups, pool)
        };
        let species = group(&|k: &str| names(k).0);
        let genus = group(&|k: &str| names(k).1);
        RootDamage {
            species,
            genus,
            ..model
        }
    }

    /// The modelled share damaged in a cell, and its derivative by the logit of `T`.
    fn cell_p(&self, c: &Cell, eta: f64) -> (f64, f64) {
        let p0 = self.background[usize::from(c.offset)];
        let t = sigmoid(eta);
        (p0 + (1.0 - p0) * t, (1.0 - p0) * t * (1.0 - t))
    }

    fn eta(&self, theta: &[f64; 3], dbh_cm: f64, w: f64) -> f64 {
        theta[0] + theta[1] * dbh_cm.ln() + theta[2] * w
    }

    /// `a`, `b`, `c` by Fisher scoring.
    fn fit_theta(&self, cells: &[&Cell]) -> [f64; 3] {
        let mut theta = self.theta;
        for _ in 0..50 {
            let mut g = [0.0; 3];
            let mut h = [[0.0; 3]; 3];
            for c in cells {
                let x = [1.0, dbh_cm(c.dbh_in).ln(), f64::from(u8::from(c.offset))];
                let eta: f64 = (0..3).map(|i| theta[i] * x[i]).sum();
                let (p, dp) = self.cell_p(c, eta);
                let score = (c.damaged / p - (c.trees - c.damaged) / (1.0 - p)) * dp;
                let info = c.trees * dp * dp / (p * (1.0 - p));
                for i in 0..3 {
                    g[i] += score * x[i];
                    for j in 0..3 {
                        h[i][j] += info * x[i] * x[j];
                    }
                }
            }
            let step = solve3(h, g);
            for i in 0..3 {
                theta[i] += step[i];
            }
            if step.iter().all(|s| s.abs() < 1e-10) {
                break;
            }
        }
        theta
    }

    /// One shift on the logit of `T` for `cells` with `theta` held, and its standard error.
    fn fit_shift(&self, cells: &[&Cell]) -> (f64, f64) {
        let mut s = 0.0;
        let mut info = 0.0;
        for _ in 0..50 {
            let (mut g, mut h) = (0.0, 0.0);
            for c in cells {
                let eta = self.eta(&self.theta, dbh_cm(c.dbh_in), f64::from(u8::from(c.offset)));
                let (p, dp) = self.cell_p(c, eta + s);
                g += (c.damaged / p - (c.trees - c.damaged) / (1.0 - p)) * dp;
                h += c.trees * dp * dp / (p * (1.0 - p));
            }
            info = h;
            let step = if h > 0.0 {
                (g / h).clamp(-1.0, 1.0)
            } else {
                0.0
            };
            s = (s + step).clamp(-5.0, 5.0);
            if step.abs() < 1e-10 {
                break;
            }
        }
        (s, 1.0 / info.max(1e-12).sqrt())
    }

    /// Each group's shift against `pool`, shrunk towards 0 by its standard error against the
    /// spread between groups (DerSimonian & Laird's moment estimate of it).
    fn shrunk(&self, groups: HashMap<String, Vec<&Cell>>, pool: f64) -> HashMap<String, Rooting> {
        let fitted: Vec<(String, f64, f64, usize)> = (groups.into_iter())
            .filter(|(k, _)| !k.is_empty())
            .filter_map(|(k, cells)| {
                let trees = cells.iter().map(|c| c.trees).sum::<f64>() as usize;
                (trees >= LEAST_TREES).then(|| {
                    let (s, se) = self.fit_shift(&cells);
                    (k, s - pool, se, trees)
                })
            })
            .collect();
        let w: Vec<f64> = fitted.iter().map(|f| 1.0 / (f.2 * f.2)).collect();
        let sw: f64 = w.iter().sum();
        let mean = (fitted.iter().zip(&w)).map(|(f, w)| w * f.1).sum::<f64>() / sw;
        let q: f64 = (fitted.iter().zip(&w))
            .map(|(f, w)| w * (f.1 - mean).powi(2))
            .sum();
        let k = fitted.len() as f64;
        let spread = ((q - (k - 1.0)) / (sw - w.iter().map(|w| w * w).sum::<f64>() / sw)).max(0.0);
        (fitted.into_iter())
            .map(|(key, s, se, trees)| {
                let shift = s * spread / (spread + se * se);
                let habit = if key.contains(' ') {
                    Habit::Species
                } else {
                    Habit::Genus
                };
                (
                    key,
                    Rooting {
                        shift,
                        habit,
                        trees,
                    },
                )
            })
            .collect()
    }

    /// The rooting habit of a species by its scientific name: its own, its genus's, or the
    /// census's mean.
    pub fn rooting(&self, scientific: &str) -> Rooting {
        let (species, genus) = names(scientific);
        (self.species.get(&species).copied())
            .or_else(|| self.genus.get(&genus).copied())
            .unwrap_or(Rooting {
                shift: 0.0,
                habit: Habit::Unknown,
                trees: 0,
            })
    }

    /// The share of trees of `dbh_cm` at `distance_m` from the pavement whose roots have
    /// damaged it, `T`.
    pub fn tree_share(&self, dbh_cm: f64, distance_m: f64, rooting: &Rooting) -> f64 {
        if dbh_cm <= 0.0 {
            return 0.0;
        }
        sigmoid(self.eta(&self.theta, dbh_cm, place(distance_m)) + rooting.shift)
    }

    /// The share of such trees beside a damaged flag, whatever damaged it, as the census
    /// counts it.
    pub fn prevalence(&self, dbh_cm: f64, distance_m: f64, rooting: &Rooting) -> f64 {
        let w = place(distance_m);
        let p0 = self.background[0] + (self.background[1] - self.background[0]) * w;
        p0 + (1.0 - p0) * self.tree_share(dbh_cm, distance_m, rooting)
    }

    /// The chance that a tree growing from `from_cm` to `to_cm` of DBH damages the pavement in
    /// that time: the rise in `T` over what it had not yet damaged.
    pub fn chance(&self, from_cm: f64, to_cm: f64, distance_m: f64, rooting: &Rooting) -> f64 {
        let t0 = self.tree_share(from_cm, distance_m, rooting);
        let t1 = self.tree_share(to_cm.max(from_cm), distance_m, rooting);
        ((t1 - t0) / (1.0 - t0).max(1e-9)).clamp(0.0, 1.0)
    }
}

/// `h x = g` for a symmetric 3x3 `h` (Cramer's rule; the information matrix of three
/// parameters is never singular on the census's thousands of trees).
fn solve3(h: [[f64; 3]; 3], g: [f64; 3]) -> [f64; 3] {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(h);
    if d.abs() < 1e-300 {
        return [0.0; 3];
    }
    let mut out = [0.0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        let mut m = h;
        for (row, gi) in m.iter_mut().zip(g) {
            row[i] = gi;
        }
        *o = det(m) / d;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The census's own shares, by DBH class and place, from the built-in counts.
    fn census(lo: u32, hi: u32, offset: bool) -> (f64, f64) {
        let all = cells(
            include_str!("../../../data/street/nyc-2015-sidewalk.csv"),
            false,
        );
        let (n, k) = (all.iter())
            .filter(|c| c.offset == offset && (lo..hi).contains(&c.dbh_in))
            .fold((0.0, 0.0), |(n, k), c| (n + c.trees, k + c.damaged));
        (k / n, n)
    }

    #[test]
    fn the_fit_follows_the_census_by_size_and_place() {
        let m = RootDamage::builtin();
        // The counts are the census's: 652,172 living trees, 28.7% beside a damaged flag.
        let all = cells(
            include_str!("../../../data/street/nyc-2015-sidewalk.csv"),
            false,
        );
        let n: f64 = all.iter().map(|c| c.trees).sum();
        let k: f64 = all.iter().map(|c| c.damaged).sum();
        assert!((n - 652_022.0).abs() < 1.0, "{n}");
        assert!((k / n - 0.287).abs() < 0.002, "{}", k / n);
        assert!((m.background[0] - 0.138).abs() < 0.001 && (m.background[1] - 0.081).abs() < 0.001);
        // Damage rises with the trunk and falls away from the curb.
        assert!(m.theta[1] > 1.0 && m.theta[2] < -1.0, "{:?}", m.theta);
        let mean = Rooting {
            shift: 0.0,
            habit: Habit::Unknown,
            trees: 0,
        };
        // The model's share beside each census class of 3 to 30 in, along the curb, within 5
        // points of the census's (its classes over 30 in, 4% of the trees, it overstates).
        for (lo, hi) in [
            (3, 6),
            (6, 9),
            (9, 12),
            (12, 15),
            (15, 18),
            (18, 24),
            (24, 30),
        ] {
            let (share, trees) = census(lo, hi, false);
            let mid = dbh_cm(lo) * 0.5 + dbh_cm(hi) * 0.5;
            let model = m.prevalence(mid, ON_CURB_M, &mean);
            assert!(
                (model - share).abs() < 0.05,
                "{lo}-{hi} in ({trees} trees): {model} against {share}"
            );
            let (share, _) = census(lo, hi, true);
            let model = m.prevalence(mid, OFFSET_M, &mean);
            assert!(
                (model - share).abs() < 0.05,
                "offset {lo}-{hi} in: {model} against {share}"
            );
        }
    }

    #[test]
    fn species_read_their_own_habit_or_their_genus() {
        let m = RootDamage::builtin();
        // Honeylocust lifts more than its size says (Sydnor's NUCFAC study found Gleditsia
        // exploiting cracks fastest); a London plane is near the census's mean.
        let locust = m.rooting("Gleditsia triacanthos");
        assert_eq!(locust.habit, Habit::Species);
        assert!(locust.shift > 0.3, "{locust:?}");
        let plane = m.rooting("Platanus x acerifolia");
        assert_eq!(plane.habit, Habit::Species);
        assert!(plane.shift.abs() < 0.2, "{plane:?}");
        // The Chinese hackberry is read by its genus; a palm by the mean.
        assert_eq!(m.rooting("Celtis sinensis").habit, Habit::Genus);
        assert_eq!(m.rooting("Washingtonia robusta").habit, Habit::Unknown);
        assert_eq!(
            names("Acer platanoides 'Crimson King'").0,
            "acer platanoides"
        );
        assert_eq!(names("Platanus x acerifolia").0, "platanus x acerifolia");
    }

    #[test]
    fn a_year_s_chance_follows_growth_and_place() {
        let m = RootDamage::builtin();
        let mean = m.rooting("Nothing known");
        let curb = m.chance(30.0, 31.0, 0.6, &mean);
        let away = m.chance(30.0, 31.0, 4.0, &mean);
        // A tree growing a centimetre a year at the curb: under 1% a year; set back, less.
        assert!(curb > 0.004 && curb < 0.01, "{curb}");
        assert!(away < 0.5 * curb, "{away}");
        // No growth, no new damage; a faster grower, more.
        assert_eq!(m.chance(30.0, 30.0, 0.6, &mean), 0.0);
        assert!(m.chance(30.0, 32.0, 0.6, &mean) > 1.9 * curb);
        // A site's distance: the narrow strip is the census's curb, the boulevard a quarter of
        // the way out.
        let narrow = crate::street::site::narrow_for_tests();
        assert!((distance_to_pavement(&narrow) - 0.6).abs() < 1e-9);
        assert_eq!(place(0.6), 0.0);
        assert!((place(1.5) - 0.255).abs() < 0.01);
    }
}
