//! Honda's (1971) tree-like bodies as Nagel (1986) drew them: every mother branch A→B gives two
//! daughters B→C, each turned by θ from the mother's direction and R times as long.
//!
//! Honda's equations (Nagel p. 57, program line 5010), with U, V, W = B − A and L = |B − A|:
//!
//! ```text
//! X = XB + R (U cos θ − L V sin θ / √(U² + V²))
//! Y = YB + R (V cos θ + L U sin θ / √(U² + V²))
//! Z = ZB + R W cos θ
//! ```
//!
//! That is the mother's direction rotated by θ toward the horizontal perpendicular (−V, U), so a
//! daughter keeps the mother's vertical plane turned a quarter and is exactly R·L long. Z is up,
//! as in the thesis' plots. A vertical mother has no horizontal direction; its daughters turn
//! toward +X (Nagel tilted his trunk by one unit to dodge the division by zero).
//!
//! Generation follows the thesis: generation by generation, in constant memory. Nagel toggled
//! between two array rows that doubled each generation, which bounds the depth by the array. Here
//! each segment is recomputed from its ancestors along one root-to-tip path, cached level by level;
//! walking a generation in order changes on average two cached levels per segment, so a tree of
//! any depth streams with a fixed-size stack and no heap memory at all.

use crate::drawing::{LineSink, LineSource, Stroke, leaf_lines};
use crate::error::ParamsError;
use crate::rng::StreamKey;
use crate::skeleton::{CrossSection, Leaf, LeafShape, Skeleton, Stem, StemId};
use glam::{DVec3, Mat3, Quat, Vec3};

/// Deepest generation the streaming stack holds (2^40 segments is beyond any budget anyway).
pub const MAX_DEPTH: u32 = 40;

/// The user's controls of a fractal tree.
#[derive(Clone, Debug, PartialEq)]
pub struct FractalParams {
    /// Divergence of the first daughter from the mother's direction, degrees.
    pub theta1: f64,
    /// Divergence of the second daughter, degrees (same sign as θ1: both turn the same way).
    pub theta2: f64,
    /// Length ratio of the first daughter to its mother.
    pub r1: f64,
    /// Length ratio of the second daughter.
    pub r2: f64,
    /// Branching generations after the trunk: depth d gives 2^d tips.
    pub depth: u32,
    /// Daughters of each branch of the last generation (2 as elsewhere; Nagel suggests 10–15 to
    /// suggest needles). They fan from θ1 to θ2 with ratios from R1 to R2.
    pub tip_daughters: u32,
    /// Trunk length, metres.
    pub trunk_length: f64,
    /// Trunk radius, metres; branches follow the pipe model (area kept across each fork).
    pub trunk_radius: f64,
    /// Random variation of each ratio, as a fraction (0.1: ±10%), per branch.
    pub length_variation: f64,
    /// Random variation of each angle, ± degrees, per branch.
    pub angle_variation: f64,
    /// Seed of the variations.
    pub seed: u64,
    /// A leaf at the end of every tip (for meshes; drawings show its outline).
    pub leaves: bool,
    /// Most segments allowed; more is refused before anything is generated.
    pub max_segments: u64,
}

impl Default for FractalParams {
    /// The issue's example tree: θ1 −35°, θ2 10°, R1 0.73, R2 0.83, depth 12.
    fn default() -> Self {
        Self {
            theta1: -35.0,
            theta2: 10.0,
            r1: 0.73,
            r2: 0.83,
            depth: 12,
            tip_daughters: 2,
            trunk_length: 2.0,
            trunk_radius: 0.12,
            length_variation: 0.0,
            angle_variation: 0.0,
            seed: 0,
            leaves: false,
            max_segments: 1 << 22,
        }
    }
}

/// One streamed segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FractalSegment {
    /// 0 for the trunk, then one per branching.
    pub generation: u32,
    /// Position within its generation, left to right as Nagel's array stored it.
    pub index: u64,
    /// Where it starts (its mother's end), metres.
    pub start: Vec3,
    /// Where it ends.
    pub end: Vec3,
    /// Pipe-model radius at the start, metres.
    pub radius: f32,
    /// Radius at the end: the daughters' radius, so that stems taper without steps (a tip
    /// thins to 70% of its start).
    pub end_radius: f32,
}

/// Honda's equation: the end C of the daughter of mother A→B turned by `theta` (radians) with
/// length ratio `r`.
pub fn honda_daughter(a: DVec3, b: DVec3, theta: f64, r: f64) -> DVec3 {
    let m = b - a;
    let l = m.length();
    if l == 0.0 {
        return b;
    }
    let h = (m.x * m.x + m.y * m.y).sqrt();
    let side = if h > 1e-12 * l {
        DVec3::new(-m.y, m.x, 0.0) / h
    } else {
        DVec3::X
    };
    b + r * (m * theta.cos() + l * side * theta.sin())
}

impl FractalParams {
    /// Checks every control and the segment budget.
    pub fn build(&self) -> Result<Fractal, ParamsError> {
        let check = |name: &str, v: f64, lo: f64, hi: f64, allowed: &str| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(ParamsError::out_of_range(name, v, allowed))
            }
        };
        check("theta1", self.theta1, -180.0, 180.0, "-180..180 degrees")?;
        check("theta2", self.theta2, -180.0, 180.0, "-180..180 degrees")?;
        check("r1", self.r1, 0.0, 1.5, "0..1.5 (daughter/mother length)")?;
        check("r2", self.r2, 0.0, 1.5, "0..1.5 (daughter/mother length)")?;
        check(
            "trunk-length",
            self.trunk_length,
            1e-3,
            1e3,
            "0.001..1000 metres",
        )?;
        check(
            "trunk-radius",
            self.trunk_radius,
            0.0,
            100.0,
            "0..100 metres",
        )?;
        check("vary-length", self.length_variation, 0.0, 0.9, "0..0.9")?;
        check(
            "vary-angle",
            self.angle_variation,
            0.0,
            90.0,
            "0..90 degrees",
        )?;
        if self.depth > MAX_DEPTH {
            return Err(ParamsError::out_of_range(
                "depth",
                self.depth as f64,
                &format!("0..{MAX_DEPTH}"),
            ));
        }
        if !(2..=64).contains(&self.tip_daughters) {
            return Err(ParamsError::out_of_range(
                "tip-daughters",
                self.tip_daughters as f64,
                "2..64",
            ));
        }
        let fractal = Fractal {
            params: self.clone(),
        };
        let segments = fractal.segment_count();
        if segments > self.max_segments {
            return Err(ParamsError::Combination(format!(
                "depth {} gives {segments} segments, over the budget of {} (--max-segments); \
                 lower --depth or --tip-daughters, or raise the budget",
                self.depth, self.max_segments
            )));
        }
        Ok(fractal)
    }
}

/// A checked fractal tree, ready to stream or to build.
#[derive(Clone, Debug, PartialEq)]
pub struct Fractal {
    params: FractalParams,
}

impl Fractal {
    /// The controls.
    pub fn params(&self) -> &FractalParams {
        &self.params
    }

    fn fan(&self) -> bool {
        self.params.tip_daughters != 2 && self.params.depth > 0
    }

    /// Segments in generation `g`.
    pub fn generation_len(&self, g: u32) -> u64 {
        let d = self.params.depth;
        if g == d && self.fan() {
            (1u64 << (d - 1)) * self.params.tip_daughters as u64
        } else {
            1u64 << g
        }
    }

    /// Tips (segments of the last generation).
    pub fn tip_count(&self) -> u64 {
        self.generation_len(self.params.depth)
    }

    /// All segments, trunk included.
    pub fn segment_count(&self) -> u64 {
        (1u64 << self.params.depth) - 1 + self.tip_count()
    }

    /// Flat index of segment (g, i) in generation order, which is also its stem index.
    pub fn flat_index(&self, g: u32, i: u64) -> u64 {
        (1u64 << g) - 1 + i
    }

    /// Index of the level-`k` ancestor of segment (g, i), k ≤ g.
    fn ancestor(&self, g: u32, i: u64, k: u32) -> u64 {
        if k == g {
            i
        } else if g == self.params.depth && self.fan() {
            (i / self.params.tip_daughters as u64) >> (g - 1 - k)
        } else {
            i >> (g - k)
        }
    }

    /// Radius of a generation-`g` branch: the pipe model gives each branch an area in
    /// proportion to the tips it carries, tip_count / generation_len(g) of them.
    fn radius(&self, g: u32) -> f32 {
        (self.params.trunk_radius / (self.generation_len(g) as f64).sqrt()) as f32
    }

    /// Radius at the end of a generation-`g` branch.
    fn end_radius(&self, g: u32) -> f32 {
        if g < self.params.depth {
            self.radius(g + 1)
        } else {
            0.7 * self.radius(g)
        }
    }

    /// The leaf at the end of a tip segment, when leaves are asked for.
    fn tip_leaf(&self, s: &FractalSegment) -> Option<Leaf> {
        if !self.params.leaves || s.generation != self.params.depth || s.end == s.start {
            return None;
        }
        let axis = s.end - s.start;
        let length = axis.length();
        let dir = axis / length;
        // Blade along the tip, its upper side as near to the sky as the tip allows.
        let across = Vec3::Z.cross(dir).try_normalize().unwrap_or(Vec3::X);
        let normal = dir.cross(across);
        let size = 0.6 * length;
        Some(Leaf {
            position: s.end,
            orientation: Quat::from_mat3(&Mat3::from_cols(across, normal, dir)),
            length: size,
            width: 0.5 * size,
            shape: LeafShape::Oval,
            stem: StemId(self.flat_index(s.generation, s.index) as u32),
            light: 1.0,
        })
    }

    /// The end of segment (k, idx) from its mother A→B.
    fn daughter(&self, a: DVec3, b: DVec3, k: u32, idx: u64) -> DVec3 {
        let p = &self.params;
        let (theta, r) = if k == p.depth && self.fan() {
            let j = (idx % p.tip_daughters as u64) as f64 / (p.tip_daughters - 1) as f64;
            (
                p.theta1 + (p.theta2 - p.theta1) * j,
                p.r1 + (p.r2 - p.r1) * j,
            )
        } else if idx & 1 == 0 {
            (p.theta1, p.r1)
        } else {
            (p.theta2, p.r2)
        };
        let (mut theta, mut r) = (theta, r);
        if p.length_variation > 0.0 || p.angle_variation > 0.0 {
            // Keyed by the branch's place, so any traversal order draws the same tree.
            let mut random = StreamKey::from_seed(p.seed)
                .child(k as u64)
                .child(idx)
                .stream();
            r *= 1.0 + random.var(p.length_variation);
            theta += random.var(p.angle_variation);
        }
        honda_daughter(a, b, theta.to_radians(), r)
    }

    /// Streams every segment to `emit`, generation by generation, each generation left to
    /// right. Uses a fixed stack of `MAX_DEPTH` levels and allocates nothing.
    pub fn stream(&self, emit: &mut dyn FnMut(&FractalSegment)) {
        let d = self.params.depth;
        // (start, end) and index of the cached ancestor at each level.
        let mut seg = [(DVec3::ZERO, DVec3::ZERO); MAX_DEPTH as usize + 1];
        let mut cached = [u64::MAX; MAX_DEPTH as usize + 1];
        seg[0] = (DVec3::ZERO, DVec3::new(0.0, 0.0, self.params.trunk_length));
        cached[0] = 0;
        let emit_one =
            |emit: &mut dyn FnMut(&FractalSegment), g: u32, i: u64, s: (DVec3, DVec3)| {
                emit(&FractalSegment {
                    generation: g,
                    index: i,
                    start: s.0.as_vec3(),
                    end: s.1.as_vec3(),
                    radius: self.radius(g),
                    end_radius: self.end_radius(g),
                })
            };
        emit_one(emit, 0, 0, seg[0]);
        for g in 1..=d {
            for i in 0..self.generation_len(g) {
                // The deepest cached ancestor still on this segment's path; every level above
                // it is then on the path too.
                let mut k = g - 1;
                while k > 0 && cached[k as usize] != self.ancestor(g, i, k) {
                    k -= 1;
                }
                for level in k + 1..=g {
                    let idx = self.ancestor(g, i, level);
                    let (a, b) = seg[level as usize - 1];
                    seg[level as usize] = (b, self.daughter(a, b, level, idx));
                    cached[level as usize] = idx;
                }
                emit_one(emit, g, i, seg[g as usize]);
            }
        }
    }

    /// The whole tree in memory: one stem per segment, in generation order, each attached to
    /// its mother's tip; a leaf at every tip when asked.
    pub fn skeleton(&self) -> Skeleton {
        let n = self.segment_count() as usize;
        let mut skeleton = Skeleton {
            stems: Vec::with_capacity(n),
            sections: Vec::with_capacity(2 * n),
            leaves: Vec::new(),
            short_twigs: 0,
        };
        self.stream(&mut |s: &FractalSegment| {
            let axis = s.end - s.start;
            let length = axis.length();
            let parent = (s.generation > 0).then(|| {
                let g = s.generation - 1;
                let i = self.ancestor(s.generation, s.index, g);
                StemId(self.flat_index(g, i) as u32)
            });
            let orientation = match parent {
                _ if length > 0.0 => Quat::from_rotation_arc(Vec3::Z, axis / length),
                Some(p) => {
                    skeleton.sections[skeleton.stems[p.0 as usize].sections.start as usize]
                        .orientation
                }
                None => Quat::IDENTITY,
            };
            let first = skeleton.sections.len() as u32;
            for (position, radius, z) in [(s.start, s.radius, 0.0), (s.end, s.end_radius, 1.0)] {
                skeleton.sections.push(CrossSection {
                    position,
                    orientation,
                    radius,
                    z,
                });
            }
            skeleton.stems.push(Stem {
                level: s.generation.min(u8::MAX as u32) as u8,
                parent,
                clone_of: None,
                offset: parent.map_or(0.0, |p| skeleton.stems[p.0 as usize].length),
                length,
                sections: first..first + 2,
                lobes: 0,
                lobe_depth: 0.0,
            });
            skeleton.leaves.extend(self.tip_leaf(s));
        });
        skeleton
    }
}

impl LineSource for Fractal {
    /// The segments straight from the generator (no skeleton is built), then the tip leaves'
    /// outlines exactly as a skeleton draws them.
    fn lines(&self, sink: &mut dyn LineSink) {
        self.stream(&mut |s: &FractalSegment| {
            sink.segment(s.start, s.end, Stroke::wood(s.radius + s.end_radius));
        });
        if self.params.leaves {
            // A skeleton draws its leaves after all stems; a second pass keeps that order
            // without storing the tips.
            self.stream(&mut |s: &FractalSegment| {
                if let Some(leaf) = self.tip_leaf(s) {
                    leaf_lines(&leaf, sink);
                }
            });
        }
    }
}

#[cfg(test)]
mod tests;
