//! Random streams. The user's seed is hashed (SplitMix64) so that neighbouring seeds give
//! unrelated trees, and every stem draws from its own stream keyed by its place in the tree, so
//! that changing a deep level never reshuffles the trunk and generation order does not matter.

use rand::Rng;
use rand_pcg::Pcg32;

/// SplitMix64's finaliser: a bijective 64-bit mix with good avalanche.
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Key of a random stream: the tree's hashed seed refined by a path of small numbers
/// (kind, child index, clone index...). Keys are cheap to copy and combine.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct StreamKey(pub u64);

impl StreamKey {
    /// Root key of a tree with the user's `seed`.
    pub fn from_seed(seed: u64) -> Self {
        Self(mix64(seed ^ 0x5EED_5EED_5EED_5EED))
    }

    /// A child key: the same parent and `index` always give the same key.
    pub fn child(self, index: u64) -> Self {
        Self(mix64(
            self.0 ^ mix64(index.wrapping_add(0xA076_1D64_78BD_642F)),
        ))
    }

    /// The random stream for this key.
    pub fn stream(self) -> Random {
        Random(Pcg32::new(self.0, mix64(self.0) | 1))
    }
}

/// A random stream with the draws the model needs.
#[derive(Clone, Debug)]
pub struct Random(Pcg32);

impl Random {
    /// Uniform in [0, 1).
    #[inline]
    pub fn unit(&mut self) -> f64 {
        // 53 random bits from two draws.
        let hi = (self.0.next_u32() >> 5) as u64;
        let lo = (self.0.next_u32() >> 6) as u64;
        ((hi << 26) | lo) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// The paper's v(x): uniform in [-x, x).
    #[inline]
    pub fn var(&mut self, x: f64) -> f64 {
        (2.0 * self.unit() - 1.0) * x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbouring_seeds_are_uncorrelated() {
        // First draws of seeds 0..2000: their lag-1 correlation must be near zero.
        let xs: Vec<f64> = (0..2000)
            .map(|s| StreamKey::from_seed(s).stream().unit())
            .collect();
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        let var: f64 = xs.iter().map(|x| (x - mean).powi(2)).sum();
        let cov: f64 = xs.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum();
        assert!((mean - 0.5).abs() < 0.03, "mean {mean}");
        assert!((cov / var).abs() < 0.06, "lag-1 correlation {}", cov / var);
    }

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let k = StreamKey::from_seed(42);
        let a: Vec<f64> = (0..5)
            .map({
                let mut r = k.child(3).stream();
                move |_| r.unit()
            })
            .collect();
        let b: Vec<f64> = (0..5)
            .map({
                let mut r = k.child(3).stream();
                move |_| r.unit()
            })
            .collect();
        let c: Vec<f64> = (0..5)
            .map({
                let mut r = k.child(4).stream();
                move |_| r.unit()
            })
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        let mut r = k.stream();
        for _ in 0..1000 {
            let v = r.var(2.0);
            assert!((-2.0..2.0).contains(&v));
        }
    }
}
