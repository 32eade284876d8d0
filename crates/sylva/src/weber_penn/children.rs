//! Children of a traced stem (spec sections 4, 5 and 9): where along it they go (error
//! diffusion over the segments, bare base, `BranchDist`), how they turn around it (spiral or
//! alternating phyllotaxis, fans), and the leaves with their bend toward the light.

use super::*;

impl<'a> Generator<'a> {
    /// Unit positions along the stem where `count` items go, error-diffused over the segments
    /// (spec section 4), honouring the bare base, clone shares and `BranchDist`.
    pub(super) fn place(
        &self,
        t: &Traced,
        count: f64,
        branch_dist: f64,
        rng: &mut Random,
        out: &mut Vec<f64>,
    ) {
        out.clear();
        let n = self.p().level(t.start.level).curve_res.max(1) as usize;
        let nf = n as f64;
        let z_min = t.start.z_min.clamp(0.0, 1.0);
        if count <= 0.0 || z_min >= 1.0 {
            return;
        }
        let rate = count / (1.0 - z_min);
        let mut error = rng.var(0.5);
        for s in t.start.first_segment..n {
            let z0 = (s as f64 / nf).max(z_min);
            let z1 = (s + 1) as f64 / nf;
            if z1 <= z0 {
                continue;
            }
            let k = diffuse(rate * (z1 - z0) * t.shares[s], &mut error);
            let d = (z1 - z0) / k as f64;
            for i in 0..k {
                let along = (i as f64 + 0.5) * d + rng.var(d / 4.0);
                out.push((z0 + branch_dist * along).clamp(z0, z1));
            }
        }
    }

    pub(super) fn grow_child_stems(&mut self, t: &Traced) -> Result<(), GenerateError> {
        let p = self.p();
        let level = t.start.level;
        let child_level = level + 1;
        let cp = p.level(child_level).clone();
        let mut rng = t.rng.clone();
        let lmax = cp.length + rng.var(cp.length_v);
        let length = t.start.length;
        let mut zs = self.spare.numbers();
        let fan = cp.branches < 0;
        if fan {
            zs.resize(cp.branches.unsigned_abs() as usize, 1.0);
        } else {
            let b = cp.branches as f64;
            let count = match level {
                0 => b,
                1 => {
                    b * (0.2
                        + 0.8 * (length / t.start.parent_length) / t.start.parent_lmax.max(1e-9))
                }
                _ => b * (1.0 - 0.5 * t.start.offset / t.start.parent_length.max(1e-9)),
            };
            self.place(t, count, cp.branch_dist, &mut rng, &mut zs);
        }
        let mut around = Phyllotaxis::starting_at(t.start.rotate_start);
        let fan_count = zs.len();
        // Every child's start is worked out before any child grows: a child's subtree draws
        // from its own streams and reads only its own sections, so growing it earlier or later,
        // here or on another thread, changes nothing.
        let mut children = self.spare.starts();
        for (index, &z) in zs.iter().enumerate() {
            let (pos, q_seg, r_here) = self.skeleton.sample(t.id, z as f32);
            let offset = z * length;
            let orientation = if fan {
                let spread = fan_angle(index, fan_count, cp.rotate);
                q_seg.as_dquat()
                    * DQuat::from_rotation_y(deg(spread))
                    * DQuat::from_rotation_x(deg(cp.down_angle))
            } else {
                let azimuth = around.next(cp.rotate, cp.rotate_v, &mut rng);
                let down = if cp.down_angle_v >= 0.0 {
                    cp.down_angle + rng.var(cp.down_angle_v)
                } else {
                    let span = if level == 0 {
                        length * (1.0 - p.base_size)
                    } else {
                        length
                    };
                    let r = ((length - offset) / span.max(1e-9)).clamp(0.0, 1.0);
                    cp.down_angle
                        + cp.down_angle_v * (1.0 - 2.0 * shape_ratio(0, r, &self.envelope))
                };
                q_seg.as_dquat()
                    * DQuat::from_rotation_z(deg(azimuth))
                    * DQuat::from_rotation_x(deg(down))
            };
            let child_length = if level == 0 {
                let base = p.base_size * self.scale;
                let r = ((length - offset) / (length - base).max(1e-9)).clamp(0.0, 1.0);
                length * lmax * shape_ratio(p.shape, r, &self.envelope)
            } else {
                lmax * (length - 0.6 * offset)
            };
            if child_length <= 1e-6 {
                continue;
            }
            // A fan sits on the tip, where a tapered parent has no radius left: limit it by
            // the parent's radius where its last segment starts instead.
            let limit = if fan {
                let n = p.level(level).curve_res.max(1) as f32;
                self.skeleton.sample(t.id, 1.0 - 1.0 / n).2
            } else {
                r_here
            };
            let radius =
                (t.start.radius * (child_length / length).powf(p.ratio_power)).min(limit as f64);
            children.push(StemStart {
                level: child_level,
                parent: Some(t.id),
                clone_of: None,
                offset,
                length: child_length,
                radius,
                position: pos.as_dvec3(),
                orientation: orientation.normalize(),
                key: t.start.key.child(KEY_CHILD).child(index as u64),
                first_segment: 0,
                curve_correction: 0.0,
                split_error: 0.0,
                share: 1.0,
                parent_length: length,
                parent_lmax: lmax,
                z_min: (r_here as f64 / child_length).min(1.0),
                rotate_start: 0.0,
            });
        }
        self.spare.numbers.push(zs);
        self.grow_stems(children)
    }

    pub(super) fn grow_leaves(&mut self, t: &Traced) -> Result<(), GenerateError> {
        let p = self.p();
        let lp = p.level(p.levels as usize).clone();
        let mut rng = t.start.key.child(KEY_LEAF).stream();
        let quality = self.leaf_quality;
        let leaf_length = (p.leaf_scale / quality.sqrt()) as f32;
        let leaf_width = (p.leaf_scale * p.leaf_scale_x / quality.sqrt()) as f32;
        let stem_offset = (p.leaf_stem_len * leaf_length as f64) as f32;
        let mut zs = self.spare.numbers();
        let fan = p.leaves < 0;
        if fan {
            zs.resize(p.leaves.unsigned_abs() as usize, 1.0);
        } else {
            let r = if t.start.parent_length > 0.0 {
                t.start.offset / t.start.parent_length
            } else {
                1.0
            };
            let count = p.leaves as f64 * shape_ratio(p.leaf_distrib, r, &self.envelope) * quality;
            self.place(t, count, 1.0, &mut rng, &mut zs);
        }
        let per_leaf = leaf_triangles(self.leaf_shape) as u64;
        self.spend(per_leaf * zs.len() as u64, t.start.level + 1)?;
        let mut around = Phyllotaxis::starting_at(0.0);
        let fan_count = zs.len();
        for (index, &z) in zs.iter().enumerate() {
            // Leaves are the bulk of a tree: their frames are computed in f32 (glam's SIMD types).
            let (pos, q_seg, _) = self.skeleton.sample(t.id, z as f32);
            let q = if fan {
                q_seg * Quat::from_rotation_y(deg(fan_angle(index, fan_count, lp.rotate)) as f32)
            } else {
                let azimuth = around.next(lp.rotate, lp.rotate_v, &mut rng);
                let down = lp.down_angle + rng.var(lp.down_angle_v.abs());
                q_seg
                    * Quat::from_rotation_z(deg(azimuth) as f32)
                    * Quat::from_rotation_x(deg(down) as f32)
            };
            let base = pos + q * Vec3::new(0.0, 0.0, stem_offset);
            let q = bend_leaf(q.normalize(), base, p.leaf_bend as f32);
            self.skeleton.leaves.push(Leaf {
                light: 1.0,
                position: base,
                orientation: q,
                length: leaf_length,
                width: leaf_width,
                shape: self.leaf_shape,
                stem: t.id,
            });
        }
        self.spare.numbers.push(zs);
        Ok(())
    }
}

/// Where successive children go around their parent (spec section 5): a spiral of `nRotate`
/// steps, or, for a negative `nRotate`, alternating sides at 180 + nRotate degrees.
struct Phyllotaxis {
    phi: f64,
    side: f64,
}

impl Phyllotaxis {
    fn starting_at(phi: f64) -> Self {
        Self { phi, side: 1.0 }
    }

    /// Azimuth of the next child, degrees.
    fn next(&mut self, rotate: f64, rotate_v: f64, rng: &mut Random) -> f64 {
        if rotate >= 0.0 {
            self.phi += rotate + rng.var(rotate_v);
            self.phi
        } else {
            self.side = -self.side;
            self.side * (180.0 + rotate + rng.var(rotate_v))
        }
    }
}

/// Angle of item `index` of a fan of `count` spread evenly over `total` degrees.
fn fan_angle(index: usize, count: usize, total: f64) -> f64 {
    if count > 1 {
        -total / 2.0 + total * index as f64 / (count - 1) as f64
    } else {
        0.0
    }
}

/// Turns a leaf towards the light (spec section 9): first about the world vertical so that its
/// normal faces away from the trunk, then tilts the normal up, each by the fraction `bend`.
fn bend_leaf(q: Quat, position: Vec3, bend: f32) -> Quat {
    if bend == 0.0 {
        return q;
    }
    let n = q * Vec3::Y;
    // The turn is the signed angle from the normal's heading to the leaf's heading from the
    // trunk: atan2(cross, dot) of the two horizontal directions, already in (-pi, pi].
    let cross = n.x * position.y - n.y * position.x;
    let dot = n.x * position.x + n.y * position.y;
    let q = if cross != 0.0 || dot != 0.0 {
        Quat::from_rotation_z(bend * atan2(cross, dot)) * q
    } else {
        q
    };
    let n = q * Vec3::Y;
    let horizontal = (n.x * n.x + n.y * n.y).sqrt();
    if horizontal < 1e-9 {
        return q;
    }
    // Tilt about n x Z (horizontal) by bend * the normal's angle from the vertical.
    let axis = Vec3::new(n.y / horizontal, -n.x / horizontal, 0.0);
    (Quat::from_axis_angle(axis, bend * atan2(horizontal, n.z)) * q).normalize()
}

/// atan2 to within 2e-5 radians, several times faster than libm's: it runs twice for every
/// leaf, where libm's took a tenth of a forest's generation time. An odd minimax polynomial of
/// degree 11 for atan on [-1, 1], with the octant folded in.
pub(super) fn atan2(y: f32, x: f32) -> f32 {
    use std::f32::consts::{FRAC_PI_2, PI};
    let (ax, ay) = (x.abs(), y.abs());
    let (num, den) = if ay > ax { (ax, ay) } else { (ay, ax) };
    if den == 0.0 {
        // Both zero: callers never ask; any fixed answer will do.
        return 0.0;
    }
    let t = num / den;
    let t2 = t * t;
    let mut a = t
        * (0.999_977_26
            + t2 * (-0.332_623_47
                + t2 * (0.193_543_46
                    + t2 * (-0.116_432_87 + t2 * (0.052_653_32 - 0.011_721_2 * t2)))));
    if ay > ax {
        a = FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = PI - a;
    }
    a.copysign(y)
}
