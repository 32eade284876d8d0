//! A skeleton stored for range: its stem segments and leaves packed into records, grouped into
//! the paper's four lists and, within a list, into runs of items drawn alike, each run
//! rank-major.

use super::order::{LEAF_MASS, STEM_MASS, rank_major};
use super::packed::{Quantiser, light_class};
use super::{LodTree, Run};
use crate::mesh::{MeshOptions, ring_frame};
use crate::skeleton::{LeafShape, Skeleton};

/// What makes stem segments draw alike: their list, ring vertices, lobes and lobe depth.
#[derive(Clone, Copy, PartialEq)]
struct Ring {
    list: usize,
    sides: u32,
    lobes: u32,
    depth: f32,
}

/// Stores `skeleton` for range rendering, its rings as `options` meshes them.
pub(super) fn build(skeleton: &Skeleton, options: &MeshOptions) -> LodTree {
    let stems = || {
        (skeleton.meshed_stems().iter())
            .map(|s| &skeleton.sections[s.sections.start as usize..s.sections.end as usize])
            .filter(|sections| sections.len() >= 2)
    };
    let q = Quantiser::around(
        stems()
            .flatten()
            .map(|c| c.position)
            .chain(skeleton.leaves.iter().map(|l| l.position)),
        stems().flatten().map(|c| c.radius).fold(0.0, f32::max),
        skeleton.leaves.iter().map(|l| l.length).fold(0.0, f32::max),
        skeleton.leaves.iter().map(|l| l.width).fold(0.0, f32::max),
    );
    let mut tree = LodTree {
        quantiser: q,
        young_bark_darkening: 1.0 - options.young_bark,
        ..Default::default()
    };
    // Runs in the order their first item was made, items in creation order within a run.
    let mut runs: Vec<(Ring, Vec<super::packed::Segment>)> = Vec::new();
    let mut sums = [(0.0f64, 0.0f64, 0usize); 3];
    for stem in skeleton.meshed_stems() {
        let sections = &skeleton.sections[stem.sections.start as usize..stem.sections.end as usize];
        if sections.len() < 2 {
            continue;
        }
        let lobed = stem.lobes > 0 && stem.lobe_depth != 0.0;
        let key = Ring {
            list: (stem.level as usize).min(2),
            sides: options.ring_vertices(stem) as u32,
            lobes: if lobed { stem.lobes } else { 0 },
            depth: if lobed { stem.lobe_depth } else { 0.0 },
        };
        let at = match runs.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                runs.push((key, Vec::new()));
                runs.len() - 1
            }
        };
        let ring = |j: usize| {
            let c = &sections[j];
            q.ring(c.position, c.radius, ring_frame(sections, j))
        };
        let sum = &mut sums[key.list];
        // Each ring is packed once and ends one segment and starts the next.
        let mut a = ring(0);
        for j in 0..sections.len() - 1 {
            let (near, far) = (&sections[j], &sections[j + 1]);
            sum.0 += (near.radius + far.radius) as f64;
            sum.1 += near.position.distance(far.position) as f64;
            sum.2 += 1;
            let b = ring(j + 1);
            runs[at].1.push(super::packed::Segment { a, b });
            a = b;
        }
    }
    tree.segments.reserve_exact(sums.iter().map(|s| s.2).sum());
    for (list_index, &(dsum, lsum, n)) in sums.iter().enumerate() {
        let list = &mut tree.lists[list_index];
        list.mass = STEM_MASS;
        list.items = n;
        list.diameter = (dsum / n.max(1) as f64) as f32;
        list.length = (lsum / n.max(1) as f64) as f32;
        for (key, items) in runs.iter().filter(|(k, _)| k.list == list_index) {
            let start = tree.segments.len() as u32;
            tree.segments.extend(
                rank_major(items.len(), STEM_MASS)
                    .iter()
                    .map(|&i| items[i as usize]),
            );
            list.runs.push(Run {
                items: start..tree.segments.len() as u32,
                sides: key.sides,
                lobes: key.lobes,
                lobe_depth: key.depth,
                shape: LeafShape::Oval,
            });
        }
    }
    let leaves = &mut tree.lists[3];
    leaves.mass = LEAF_MASS;
    leaves.items = skeleton.leaves.len();
    leaves.length =
        skeleton.leaves.iter().map(|l| l.length).sum::<f32>() / skeleton.leaves.len().max(1) as f32;
    tree.leaves.reserve_exact(skeleton.leaves.len());
    let mut shapes: Vec<LeafShape> = Vec::new();
    for l in &skeleton.leaves {
        if !shapes.contains(&l.shape) {
            shapes.push(l.shape);
        }
    }
    for shape in shapes {
        // Packed in the order they were made, then put in rank-major order: reading the
        // skeleton's leaves in that order instead cost a cache miss per leaf.
        let items: Vec<super::packed::Leaf> = skeleton
            .leaves
            .iter()
            .filter(|l| l.shape == shape)
            .map(|l| {
                q.leaf(
                    l.position,
                    l.orientation,
                    l.length,
                    l.width,
                    light_class(l.light),
                )
            })
            .collect();
        let start = tree.leaves.len() as u32;
        tree.leaves.extend(
            rank_major(items.len(), LEAF_MASS)
                .iter()
                .map(|&i| items[i as usize]),
        );
        leaves.runs.push(Run {
            items: start..tree.leaves.len() as u32,
            sides: 0,
            lobes: 0,
            lobe_depth: 0.0,
            shape,
        });
    }
    tree
}
