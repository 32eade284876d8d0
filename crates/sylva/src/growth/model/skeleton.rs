//! The growing tree as a Skeleton, the form every output reads.

use super::*;

impl Grower {
    /// The tree now as a Skeleton: one stem per live branch, sections at the segment joints
    /// (the trunk also at breast height and every half metre), leaves spiralled along the
    /// young shoots.
    pub fn skeleton(&self) -> Skeleton {
        let mut sk = Skeleton::default();
        self.skeleton_into(&mut sk);
        sk
    }

    /// Like [`Grower::skeleton`], but reuses `sk`'s buffers (cleared first), so showing the
    /// tree after every step allocates nothing once the buffers have grown.
    pub fn skeleton_into(&self, sk: &mut Skeleton) {
        sk.stems.clear();
        sk.sections.clear();
        sk.leaves.clear();
        let mut stem_of = vec![u32::MAX; self.branches.len()];
        let mut segs: Vec<(u32, &Segment)> = Vec::new();
        let mut points: Vec<(Vec3, Vec3, f32)> = Vec::new();
        let (leaf_len, leaf_width) = self.drawn_leaf_size();
        let top = self.targets_now().height as f32;
        for (b, branch) in self.branches.iter().enumerate() {
            if !branch.alive {
                continue;
            }
            let parent = branch.parent.map(|(p, _)| StemId(stem_of[p as usize]));
            if parent.is_some_and(|p| p.0 == u32::MAX) {
                continue;
            }
            let first = sk.sections.len() as u32;
            segs.clear();
            segs.extend(
                branch
                    .segments
                    .iter()
                    .map(|&s| (s, &self.segments[s as usize]))
                    .filter(|(_, s)| s.length > 1e-4),
            );
            if segs.is_empty() {
                continue;
            }
            let total: f32 = segs.iter().map(|(_, s)| s.length).sum();
            points.clear();
            let mut run = 0.0f32;
            for &(_, s) in &segs {
                let pieces = if branch.order == 0 {
                    (s.length / 0.5).ceil().max(1.0) as usize
                } else {
                    1
                };
                for k in 0..pieces {
                    let f = k as f32 / pieces as f32;
                    let p = s.start + s.direction * s.length * f;
                    points.push((p, s.direction, run + s.length * f));
                }
                run += s.length;
            }
            let (last_id, last) = segs[segs.len() - 1];
            points.push((last.end(), last.direction, total));
            if branch.order == 0 {
                // A section exactly at breast height, so DBH reads the trunk there.
                if let Some(i) = points.iter().position(|p| p.0.z > BREAST_HEIGHT)
                    && i > 0
                    && (points[i - 1].0.z - BREAST_HEIGHT).abs() > 1e-3
                {
                    let (a, b) = (points[i - 1], points[i]);
                    let f = (BREAST_HEIGHT - a.0.z) / (b.0.z - a.0.z);
                    points.insert(i, (a.0.lerp(b.0, f), a.1, a.2 + (b.2 - a.2) * f));
                }
            }
            for (k, &(p, d, at)) in points.iter().enumerate() {
                // Side branches: one section per segment (its base radius, older and thicker
                // toward the base), then a thin tip.
                let radius = if branch.order == 0 {
                    self.trunk_radius(p.z)
                } else if k < segs.len() {
                    self.radius_of(segs[k].0)
                } else {
                    (self.radius_of(last_id) * 0.35).max(0.001)
                };
                sk.sections.push(CrossSection {
                    position: p,
                    orientation: frame(d),
                    radius: radius.max(0.0008),
                    z: if total > 0.0 { at / total } else { 0.0 },
                });
            }
            let id = sk.stems.len() as u32;
            stem_of[b] = id;
            let offset = branch.offset;
            sk.stems.push(Stem {
                level: branch.order,
                parent,
                clone_of: None,
                offset,
                length: total,
                sections: first..sk.sections.len() as u32,
                lobes: 0,
                lobe_depth: 0.0,
            });
            self.for_each_leaf(b, leaf_len, top, |position, orientation| {
                sk.leaves.push(Leaf {
                    light: self.light.light_at(position),
                    position,
                    orientation,
                    length: leaf_len,
                    width: leaf_width,
                    shape: self.leaf_shape,
                    stem: StemId(id),
                })
            });
        }
    }
}
