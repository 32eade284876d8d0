//! Bark patterns drawn as vertex shades: the light and dark of a species' bark (the plane's
//! shed patches, a cherry's bands of lenticels, an ash's furrows) as a luminance factor on
//! each bark vertex, which GLB files carry as COLOR_0 and the renderer multiplies into the bark
//! colour, so a file and a picture show the same bark. A pattern is a function of where a
//! vertex lies on its stem's surface in metres (around and along) and of the stem's radius:
//! the same bark at any mesh resolution, though never finer than the ring's vertices.
//!
//! The scales below (plates a decimetre across, bands of lenticels every few centimetres) are
//! Sylva's drawing of the sources' words (see `growth/data/foliage.csv`), not measurements; the
//! darkest tone of each pattern is what makes it read at a street's distance.

use crate::rng::mix64;

/// The bark's pattern where it is distinctive.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BarkPattern {
    /// Smooth, or too fine to tell at a street tree's distance: no shades.
    #[default]
    Smooth,
    /// Ridges and furrows running up the trunk.
    Furrowed,
    /// Flat plates between dark cracks.
    Plates,
    /// Shed in patches, paler beneath (planes, crape myrtle).
    Patches,
    /// Long strips loose at their ends (silver maple).
    Strips,
    /// Scaly ridges.
    Scaly,
    /// Smooth and banded by horizontal lenticels (cherries, birches).
    Lenticels,
}

/// Stems up to this radius (m) wear the young shoots' bark, and stems from
/// [`MATURE_BARK_RADIUS`] the bark's own colour, blended between: the white birch's bark is
/// "golden-brown at first", white later (Vakkari 2009) and its twigs purplish-brown; the
/// sources give no size, so the change from 1 to 3 cm across is Sylva's reading.
const YOUNG_TWIG_RADIUS: f32 = 0.005;
const MATURE_BARK_RADIUS: f32 = 0.015;

/// The luminance factor of young bark on a stem of `radius` m, for a species whose young
/// shoots' bark is `young` times as bright as its bark (1: no difference).
pub fn young_bark_shade(radius: f32, young: f32) -> f32 {
    let mature =
        ((radius - YOUNG_TWIG_RADIUS) / (MATURE_BARK_RADIUS - YOUNG_TWIG_RADIUS)).clamp(0.0, 1.0);
    young + (1.0 - young) * mature
}

/// Stems thinner than this (radius, m) keep a young stem's smooth bark: furrows, plates and
/// scales form as the stem thickens, and on twigs they would be finer than the ring's vertices.
const YOUNG_BARK_RADIUS: f32 = 0.03;

impl BarkPattern {
    /// Luminance factor (0..1) of the bark at `around` and `along` metres on a stem of
    /// `radius` metres; `stem` decorrelates the stems' patterns.
    pub fn shade(self, around: f32, along: f32, radius: f32, stem: u32) -> f32 {
        let seed = u64::from(stem);
        let noise = |cell_around: f32, cell_along: f32| {
            value_noise(around / cell_around, along / cell_along, seed)
        };
        // Patterns of thick bark fade in between the young radius and twice it.
        let age = ((radius - YOUNG_BARK_RADIUS) / YOUNG_BARK_RADIUS).clamp(0.0, 1.0);
        let mature = |dark: f32| 1.0 - age * (1.0 - dark);
        match self {
            BarkPattern::Smooth => 1.0,
            // Shed patches: pale where the bark has flaked, two darker tones of old bark.
            BarkPattern::Patches => {
                let n = noise(0.09, 0.12);
                if n > 0.56 {
                    1.0
                } else if n > 0.4 {
                    0.78
                } else {
                    0.58
                }
            }
            // Long strips, loose at their ends: dark gaps between pale vertical strips.
            BarkPattern::Strips => mature(0.6 + 0.4 * smoothstep(0.35, 0.6, noise(0.05, 0.45))),
            // Furrows: dark grooves up the stem, wandering a little between ridges.
            BarkPattern::Furrowed => mature(0.5 + 0.5 * smoothstep(0.3, 0.55, noise(0.035, 0.3))),
            // Plates: pale blocks a decimetre across, dark where they crack apart.
            BarkPattern::Plates => {
                let n = noise(0.08, 0.11);
                mature(if n < 0.32 { 0.5 } else { 0.95 + 0.05 * n })
            }
            BarkPattern::Scaly => mature(0.7 + 0.3 * noise(0.04, 0.05)),
            // Horizontal dashes a few centimetres apart along the stem.
            BarkPattern::Lenticels => {
                let band = (along / 0.045).rem_euclid(1.0) < 0.3;
                if band && noise(0.04, 0.045) > 0.45 {
                    0.45
                } else {
                    1.0
                }
            }
        }
    }
}

fn smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Value noise in 0..1: random values at the integer lattice, blended smoothly between.
fn value_noise(x: f32, y: f32, seed: u64) -> f32 {
    let (xf, yf) = (x.floor(), y.floor());
    let (i, j) = (xf as i64, yf as i64);
    let (tx, ty) = (x - xf, y - yf);
    let (sx, sy) = (tx * tx * (3.0 - 2.0 * tx), ty * ty * (3.0 - 2.0 * ty));
    let at = |a: i64, b: i64| {
        // One mix of the seed and the lattice point, each coordinate spread by an odd constant.
        let h = mix64(
            seed.wrapping_mul(0xD6E8_FEB8_6659_FD93)
                ^ (a as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
                ^ (b as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F),
        );
        (h >> 40) as f32 / (1u64 << 24) as f32
    };
    let top = at(i, j) + (at(i + 1, j) - at(i, j)) * sx;
    let bottom = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx;
    top + (bottom - top) * sy
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn young_bark_is_on_the_twigs_and_gone_by_three_centimetres() {
        assert_eq!(young_bark_shade(0.0, 0.1), 0.1);
        assert_eq!(young_bark_shade(YOUNG_TWIG_RADIUS, 0.1), 0.1);
        let mid = young_bark_shade((YOUNG_TWIG_RADIUS + MATURE_BARK_RADIUS) / 2.0, 0.1);
        assert!((mid - 0.55).abs() < 1e-5, "{mid}");
        assert_eq!(young_bark_shade(MATURE_BARK_RADIUS, 0.1), 1.0);
        assert_eq!(young_bark_shade(0.5, 0.1), 1.0);
        // No young bark of its own: no shade.
        assert_eq!(young_bark_shade(0.0, 1.0), 1.0);
    }

    /// Shades over a trunk's metre of bark, 2 cm apart.
    fn samples(p: BarkPattern, radius: f32) -> Vec<f32> {
        (0..50)
            .flat_map(|i| (0..50).map(move |j| (i as f32 * 0.02, j as f32 * 0.02)))
            .map(|(a, b)| p.shade(a, b, radius, 7))
            .collect()
    }

    #[test]
    fn patterns_darken_part_of_the_bark_and_smooth_bark_none() {
        assert!(samples(BarkPattern::Smooth, 0.3).iter().all(|&s| s == 1.0));
        for p in [
            BarkPattern::Patches,
            BarkPattern::Strips,
            BarkPattern::Furrowed,
            BarkPattern::Plates,
            BarkPattern::Scaly,
            BarkPattern::Lenticels,
        ] {
            let s = samples(p, 0.3);
            assert!(s.iter().all(|v| (0.0..=1.0).contains(v)), "{p:?}");
            let dark = s.iter().filter(|&&v| v < 0.8).count() as f32 / s.len() as f32;
            // Enough dark bark to read, and never the whole trunk.
            assert!((0.08..0.7).contains(&dark), "{p:?}: {dark}");
        }
    }

    #[test]
    fn twigs_keep_young_smooth_bark_where_the_pattern_comes_with_age() {
        for p in [
            BarkPattern::Furrowed,
            BarkPattern::Plates,
            BarkPattern::Scaly,
        ] {
            assert!(samples(p, 0.01).iter().all(|&s| s == 1.0), "{p:?}");
        }
    }

    #[test]
    fn noise_is_continuous_and_in_range() {
        let mut last = value_noise(0.0, 0.3, 1);
        for k in 1..1000 {
            let v = value_noise(k as f32 * 0.001, 0.3, 1);
            assert!((0.0..=1.0).contains(&v));
            assert!((v - last).abs() < 0.01);
            last = v;
        }
    }
}
