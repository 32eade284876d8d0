//! The Weber–Penn model (Weber & Penn 1995, restated in `shared/spec/weber-penn.md`):
//! parameters in, [`Skeleton`] out.
//!
//! Each stem draws from its own random stream keyed by its place in the tree (trunk i, child j
//! of that, clone k of that...), so the tree does not depend on generation order, and changing a
//! parameter of a deep level leaves the stems above it untouched.

mod apart;
mod children;
pub mod equations;
pub mod made;
mod trace;

use crate::error::GenerateError;
use crate::mesh::{leaf_triangles, ring_vertices};
use crate::params::TreeParams;
use crate::rng::{Random, StreamKey};
use crate::skeleton::{Leaf, LeafShape, Skeleton, Stem, StemId};
use equations::{Envelope, inside_envelope, shape_ratio};
use glam::{DQuat, DVec3, Quat, Vec3};
use std::sync::atomic::{AtomicU64, Ordering};
use trace::{StemStart, Tracer};

const KEY_TRUNK: u64 = 1;
const KEY_CHILD: u64 = 2;
const KEY_CLONE: u64 = 3;
const KEY_LEAF: u64 = 4;
const KEY_WIND: u64 = 5;

/// One step of one-dimensional error diffusion (the paper's \[FLOY76\]): how many whole items
/// to make where `expected` are due, carrying the rounding error to the next step.
pub fn diffuse(expected: f64, error: &mut f64) -> usize {
    let k = (expected + *error + 0.5).floor().max(0.0);
    *error -= k - expected;
    k as usize
}

/// Degrees to radians.
fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// Wind at one instant (spec section 12): every stem bends about its x and y axes by
/// sinusoids with random per-stem phases, more where it is long and thin. The default is calm,
/// which changes nothing (the tree is bit-identical to one generated without wind).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wind {
    /// Steady wind speed in the paper's units: the sway amplitude is speed / 50 of a stem's
    /// cantilever deflection; 2 to 10 is a breeze, 20 a strong wind.
    pub speed: f64,
    /// Gust strength on top of the steady wind.
    pub gust: f64,
    /// Time, seconds.
    pub time: f64,
}

impl Wind {
    /// True when the wind moves anything.
    pub fn is_active(&self) -> bool {
        self.speed != 0.0 || self.gust != 0.0
    }
}

/// Options of one generation run (what the calling program decides, not the species).
#[derive(Clone, Debug, PartialEq)]
pub struct GenerateOptions {
    /// The user's seed; hashed before use.
    pub seed: u64,
    /// Show only stem levels below this (1 = trunk only); leaves appear only when no level is
    /// cut. The stems shown are exactly those of the full tree. `None` = all levels.
    pub max_levels: Option<u32>,
    /// The paper's quality factor from the calling program: multiplies `LeafQuality` (more,
    /// smaller leaves) and the mesh resolution estimate used by the budget.
    pub quality: f64,
    /// Whether to generate leaves.
    pub leaves: bool,
    /// Wind at one instant.
    pub wind: Wind,
    /// Stop with [`GenerateError::Budget`] when the tree's mesh would exceed this many triangles.
    pub max_triangles: u64,
}

impl Default for GenerateOptions {
    fn default() -> Self {
        Self {
            seed: 0,
            max_levels: None,
            quality: 1.0,
            leaves: true,
            wind: Wind::default(),
            max_triangles: 10_000_000,
        }
    }
}

/// Generates the tree of `params` (validated first) with `options`.
pub fn generate(params: &TreeParams, options: &GenerateOptions) -> Result<Skeleton, GenerateError> {
    let mut skeleton = Skeleton::default();
    generate_into(params, options, &mut skeleton)?;
    Ok(skeleton)
}

/// Like [`generate`], but reuses `skeleton`'s buffers (cleared first): regenerating into the
/// same skeleton, as an editor does on every change, allocates nothing once warm. On error the
/// skeleton is left empty.
pub fn generate_into(
    params: &TreeParams,
    options: &GenerateOptions,
    skeleton: &mut Skeleton,
) -> Result<(), GenerateError> {
    skeleton.stems.clear();
    skeleton.sections.clear();
    skeleton.leaves.clear();
    params.validate()?;
    if !(options.quality > 0.0 && options.quality <= 16.0) {
        return Err(crate::error::ParamsError::OutOfRange {
            name: "quality".into(),
            value: options.quality,
            allowed: "0..16 (exclusive of 0)".into(),
            source_name: None,
        }
        .into());
    }
    let root = StreamKey::from_seed(options.seed);
    let mut tree_rng = root.stream();
    let scale = params.scale + tree_rng.var(params.scale_v);
    let z_scale = params.z_scale + tree_rng.var(params.z_scale_v);
    let stem_levels = options
        .max_levels
        .map_or(params.levels, |m| m.clamp(1, params.levels)) as usize;
    let spent = AtomicU64::new(0);
    let mut g = Generator {
        tracer: Tracer {
            p: params,
            wind: options.wind,
        },
        options,
        scale,
        stem_levels,
        leaves_on: options.leaves && params.leaves != 0 && stem_levels == params.levels as usize,
        leaf_quality: params.leaf_quality * options.quality,
        leaf_shape: LeafShape::from_index(params.leaf_shape).unwrap_or(LeafShape::Oval),
        envelope: Envelope {
            peak: params.prune_width_peak,
            power_low: params.prune_power_low,
            power_high: params.prune_power_high,
        },
        skeleton: std::mem::take(skeleton),
        spent: &spent,
        profile: Vec::new(),
        shares: Vec::new(),
        spare: Spare::default(),
    };
    let grown = g.grow_trunks(root);
    *skeleton = std::mem::take(&mut g.skeleton);
    if let Err(e) = grown {
        skeleton.stems.clear();
        skeleton.sections.clear();
        skeleton.leaves.clear();
        return Err(e);
    }
    if (z_scale - 1.0).abs() > 1e-12 {
        stretch_vertically(skeleton, z_scale as f32);
    }
    Ok(())
}

/// Per-stem facts needed to grow its children after its axis is traced.
struct Traced {
    id: StemId,
    start: StemStart,
    shares: Vec<f64>,
    rng: Random,
}

struct Generator<'a> {
    tracer: Tracer<'a>,
    options: &'a GenerateOptions,
    scale: f64,
    stem_levels: usize,
    leaves_on: bool,
    leaf_quality: f64,
    leaf_shape: LeafShape,
    envelope: Envelope,
    skeleton: Skeleton,
    /// Triangles the tree's mesh would hold so far, shared by every thread growing a part of
    /// the tree (see `apart.rs`), so a runaway tree stops wherever it runs away.
    spent: &'a AtomicU64,
    profile: Vec<f64>,
    shares: Vec<f64>,
    spare: Spare,
}

/// Buffers lent to one stem at a time and handed back when it is done, so that growing a tree
/// allocates only until the recursion has been as deep once (there is one buffer per level in
/// use at a time), not per stem.
#[derive(Default)]
struct Spare {
    numbers: Vec<Vec<f64>>,
    starts: Vec<Vec<StemStart>>,
    family: Vec<Vec<Traced>>,
    /// Stems of one family waiting to be traced (one family is traced at a time).
    pending: Vec<(StemStart, Random)>,
}

impl Spare {
    fn numbers(&mut self) -> Vec<f64> {
        lend(&mut self.numbers)
    }

    fn starts(&mut self) -> Vec<StemStart> {
        lend(&mut self.starts)
    }
}

/// An empty buffer from `pool`, or a new one.
fn lend<T>(pool: &mut Vec<Vec<T>>) -> Vec<T> {
    let mut v = pool.pop().unwrap_or_default();
    v.clear();
    v
}

impl<'a> Generator<'a> {
    fn p(&self) -> &'a TreeParams {
        self.tracer.p
    }

    fn spend(&mut self, triangles: u64, level: usize) -> Result<(), GenerateError> {
        let reached = self.spent.fetch_add(triangles, Ordering::Relaxed) + triangles;
        if reached > self.options.max_triangles {
            return Err(GenerateError::Budget {
                what: "triangles",
                limit: self.options.max_triangles,
                reached,
                level,
            });
        }
        Ok(())
    }

    fn grow_trunks(&mut self, root: StreamKey) -> Result<(), GenerateError> {
        let p = self.p();
        let trunks = p.trunks.max(1);
        let l0 = &p.level[0];
        for i in 0..trunks {
            let key = root.child(KEY_TRUNK).child(i as u64);
            let mut rng = key.stream();
            let length = (l0.length + rng.var(l0.length_v)) * self.scale;
            let radius = length * p.ratio * (p.trunk_scale + rng.var(p.trunk_scale_v));
            let azimuth = 360.0 * i as f64 / trunks as f64 + l0.rotate + rng.var(l0.rotate_v);
            let lean = l0.down_angle + rng.var(l0.down_angle_v);
            let spread = if trunks > 1 {
                p.trunk_spread * (0.5 + 0.5 * rng.unit())
            } else {
                0.0
            };
            let a = deg(azimuth);
            let start = StemStart {
                level: 0,
                parent: None,
                clone_of: None,
                offset: 0.0,
                length,
                radius,
                position: DVec3::new(spread * a.cos(), spread * a.sin(), 0.0),
                orientation: DQuat::from_rotation_z(a + std::f64::consts::FRAC_PI_2)
                    * DQuat::from_rotation_x(deg(lean)),
                key,
                first_segment: 0,
                curve_correction: 0.0,
                split_error: 0.0,
                share: 1.0,
                parent_length: 0.0,
                parent_lmax: 0.0,
                z_min: p.base_size,
                rotate_start: 0.0,
            };
            self.grow_stem(start)?;
        }
        Ok(())
    }

    /// Prunes (levels >= 1), traces the stem and its clones, then grows their children.
    fn grow_stem(&mut self, mut start: StemStart) -> Result<(), GenerateError> {
        if start.length <= 1e-6 || start.radius <= 0.0 {
            return Ok(());
        }
        let mut rng = start.key.stream();
        start.split_error = rng.var(0.5);
        if start.level >= 1 && self.p().prune_ratio > 0.0 {
            match self.pruned_length(&start, &rng) {
                Some(length) if length > 1e-6 => {
                    let ratio = length / start.length;
                    start.radius *= ratio.powf(self.p().ratio_power).min(1.0);
                    start.length = length;
                }
                _ => return Ok(()),
            }
        }
        let mut family = self.trace_family(start, rng)?;
        for traced in family.drain(..) {
            self.grow_children(&traced)?;
            self.spare.numbers.push(traced.shares);
        }
        self.spare.family.push(family);
        Ok(())
    }

    /// Traces a stem and all clones it splits into, adding them to the skeleton.
    fn trace_family(
        &mut self,
        start: StemStart,
        rng: Random,
    ) -> Result<Vec<Traced>, GenerateError> {
        let mut pending = std::mem::take(&mut self.spare.pending);
        pending.clear();
        pending.push((start, rng));
        let mut family = lend(&mut self.spare.family);
        let mut clones = self.spare.starts();
        while let Some((st, mut rng)) = pending.pop() {
            let level = st.level;
            let id = StemId(self.skeleton.stems.len() as u32);
            let first = self.skeleton.sections.len() as u32;
            self.tracer.profile_samples(&st, &mut self.profile);
            self.shares.clear();
            clones.clear();
            self.tracer.trace(
                &st,
                &mut rng,
                &self.profile,
                &mut self.skeleton.sections,
                &mut clones,
                &mut self.shares,
            );
            let end = self.skeleton.sections.len() as u32;
            let rings = (end - first) as u64;
            let ring = ring_vertices(level, self.options.quality, 0) as u64;
            self.spend(rings.saturating_sub(1) * ring * 2, level)?;
            let (lobes, lobe_depth) = if level == 0 {
                (self.p().lobes, self.p().lobe_depth as f32)
            } else {
                (0, 0.0)
            };
            self.skeleton.stems.push(Stem {
                level: level as u8,
                parent: st.parent,
                clone_of: st.clone_of,
                offset: st.offset as f32,
                length: st.length as f32,
                sections: first..end,
                lobes,
                lobe_depth,
            });
            for mut c in clones.drain(..) {
                c.clone_of = Some(id);
                let crng = c.key.stream();
                pending.push((c, crng));
            }
            let mut shares = self.spare.numbers();
            shares.extend_from_slice(&self.shares);
            family.push(Traced {
                id,
                start: st,
                shares,
                rng,
            });
        }
        self.spare.starts.push(clones);
        self.spare.pending = pending;
        Ok(family)
    }

    /// The pruned length of a stem (spec section 10), or `None` when nothing of it fits.
    fn pruned_length(&mut self, start: &StemStart, rng: &Random) -> Option<f64> {
        let p = self.p();
        let original = start.length;
        let n = p.level(start.level).curve_res.max(1) as f64;
        let mut length = original;
        let mut sections = Vec::new();
        let mut clones = Vec::new();
        let mut shares = Vec::new();
        let mut profile = Vec::new();
        loop {
            let mut probe = start.clone();
            probe.length = length;
            let mut pending = vec![(probe, rng.clone())];
            let mut fail: Option<f64> = None;
            while let Some((st, mut r)) = pending.pop() {
                sections.clear();
                clones.clear();
                self.tracer.profile_samples(&st, &mut profile);
                self.tracer.trace(
                    &st,
                    &mut r,
                    &profile,
                    &mut sections,
                    &mut clones,
                    &mut shares,
                );
                let outside = sections.iter().skip(1).find(|c| {
                    let rho = (c.position.x as f64).hypot(c.position.y as f64);
                    !inside_envelope(
                        rho,
                        c.position.z as f64,
                        self.scale,
                        p.base_size,
                        p.prune_width,
                        &self.envelope,
                    )
                });
                if let Some(c) = outside {
                    // Segment index of the offending point: s = floor(z N).
                    let s = ((c.z as f64 * n).ceil() - 1.0).max(0.0);
                    fail = Some(fail.map_or(s, |f: f64| f.min(s)));
                    break;
                }
                pending.extend(clones.drain(..).map(|c| {
                    let r = c.key.stream();
                    (c, r)
                }));
            }
            let Some(s) = fail else { break };
            let seg = length / n;
            length = (s * seg).max(length / 2.0).min(length - original / 15.0);
            if length < 0.001 * self.scale {
                length = 0.0;
                break;
            }
        }
        Some(original - (original - length) * p.prune_ratio)
    }

    /// Children (stems or leaves) of a traced stem.
    fn grow_children(&mut self, t: &Traced) -> Result<(), GenerateError> {
        let level = t.start.level;
        if level + 1 < self.stem_levels {
            self.grow_child_stems(t)
        } else if self.leaves_on && level + 1 == self.stem_levels {
            self.grow_leaves(t)
        } else {
            Ok(())
        }
    }
}

/// Applies `ZScale`: stretches heights and turns frames to follow the stretched axes.
fn stretch_vertically(skeleton: &mut Skeleton, z: f32) {
    let stretch = |q: glam::Quat| {
        let axis = q * Vec3::Z;
        let stretched = Vec3::new(axis.x, axis.y, axis.z * z).normalize_or(axis);
        glam::Quat::from_rotation_arc(axis, stretched) * q
    };
    for c in &mut skeleton.sections {
        c.position.z *= z;
        c.orientation = stretch(c.orientation);
    }
    for leaf in &mut skeleton.leaves {
        leaf.position.z *= z;
    }
}

#[cfg(test)]
mod tests;
#[cfg(test)]
mod wind_tests;
