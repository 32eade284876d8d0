use super::order::paper_loop;
use super::*;
use crate::{GenerateOptions, generate, species::builtin};

const PAPER: Viewer = Viewer {
    image_height: 1000.0,
    fov_y: 60.0,
    quality: 1.0,
};

fn lod(id: &str, quality: f64) -> LodTree {
    let p = builtin(id).unwrap();
    let sk = generate(
        &p,
        &GenerateOptions {
            seed: 1,
            quality,
            ..Default::default()
        },
    )
    .unwrap();
    LodTree::build_keeping_indices(
        &sk,
        &MeshOptions {
            quality,
            ..Default::default()
        },
    )
}

#[test]
fn calibrated_range_matches_the_paper() {
    assert_eq!(PAPER.calibrated_range(2000.0), 2000.0);
    let tele = Viewer {
        image_height: 500.0,
        fov_y: 15.0,
        quality: 1.0,
    };
    assert!((tele.calibrated_range(2000.0) - 1000.0).abs() < 1e-3);
}

#[test]
fn near_trees_draw_everything_as_meshes() {
    let t = lod("quaking_aspen", 1.0);
    let full = t.mesh.bark.indices.len() + t.mesh.leaves.indices.len();
    let draws = t.select(5.0, &PAPER);
    let drawn: u32 = draws.iter().map(|d| d.triangles.end).sum();
    assert_eq!(drawn as usize, full, "all triangles at 5 m");
    assert!(draws.iter().all(|d| d.points.is_empty()));
    // Lists hold exactly the mesh's triangles, reordered.
    for (i, list) in t.lists.iter().enumerate() {
        let source = if i == 3 {
            &t.mesh.leaves.indices
        } else {
            &t.mesh.bark.indices
        };
        assert_eq!(
            *list.index_prefix.last().unwrap() as usize,
            list.indices.len()
        );
        let mut a = list.indices.clone();
        a.sort_unstable();
        assert!(a.iter().all(|&v| (v as usize)
            < if i == 3 {
                t.mesh.leaves.vertex_count()
            } else {
                t.mesh.bark.vertex_count()
            }));
        let _ = source;
    }
    let total: usize = t.lists[..3].iter().map(|l| l.indices.len()).sum();
    assert_eq!(total, t.mesh.bark.indices.len());
}

#[test]
fn each_level_of_detail_is_the_papers_set_of_items() {
    let t = lod("black_tupelo", 0.5);
    for range in [20.0, 80.0, 300.0, 1000.0, 3000.0] {
        for (i, list) in t.lists.iter().enumerate() {
            let leaves = i == 3;
            let (x_mesh, _) = list.levels_of_detail(leaves, range, &PAPER);
            let d = list.select(leaves, range, &PAPER);
            // The meshed items (a prefix of the rank-major list) are the paper's loop's items.
            let meshed = list
                .index_prefix
                .iter()
                .position(|&p| p == d.triangles.end)
                .unwrap();
            let mut from_prefix: Vec<usize> = order::rank_major(list.items, list.mass)[..meshed]
                .iter()
                .map(|&v| v as usize)
                .collect();
            from_prefix.sort_unstable();
            let mut loop_items = paper_loop(list.items, list.mass, x_mesh);
            loop_items.sort_unstable();
            assert_eq!(from_prefix.len(), loop_items.len(), "list {i} at {range} m");
            assert_eq!(from_prefix, loop_items, "list {i} at {range} m");
        }
    }
}

#[test]
fn receding_changes_counts_one_item_per_mass_at_most() {
    let t = lod("quaking_aspen", 1.0);
    let mut previous: Option<[ListDraw; 4]> = None;
    let mut range = 10.0f32;
    while range < 3000.0 {
        let now = t.select(range, &PAPER);
        if let Some(prev) = &previous {
            for (i, (a, b)) in prev.iter().zip(&now).enumerate() {
                let list = &t.lists[i];
                let masses = list.items.div_ceil(list.mass) as i64;
                let items = |d: &ListDraw| {
                    list.index_prefix
                        .iter()
                        .position(|&p| p == d.triangles.end)
                        .unwrap() as i64
                };
                assert!(items(b) <= items(a), "meshes grow as the camera recedes");
                assert!(
                    items(a) - items(b) <= masses,
                    "list {i}: mesh count jumped at {range} m"
                );
                let per = if i == 3 { 1 } else { 2 };
                let drawn = |d: &ListDraw| (d.points.end / per) as i64;
                assert!(
                    drawn(a) - drawn(b) <= masses && drawn(b) <= drawn(a),
                    "list {i}: drawn count jumped at {range} m"
                );
            }
        }
        previous = Some(now);
        range *= 1.01;
    }
}

#[test]
fn a_100k_facet_tree_at_2_km_is_about_30_lines_and_1000_points() {
    // The quaking aspen at quality 0.6 is about 100,000 facets.
    let t = lod("quaking_aspen", 0.6);
    let facets = t.mesh.triangle_count();
    assert!((70_000..=140_000).contains(&facets), "{facets} facets");
    let c = t.counts(2000.0, &PAPER);
    assert!((15..=60).contains(&c.lines), "{c:?}");
    assert!((500..=2000).contains(&c.points), "{c:?}");
    assert!(c.triangles < 100, "{c:?}");
}

#[test]
fn counts_fall_with_range() {
    let t = lod("quaking_aspen", 0.6);
    let mut previous = usize::MAX;
    for range in [10.0, 30.0, 100.0, 300.0, 1000.0, 2000.0, 3000.0] {
        let c = t.counts(range, &PAPER);
        let total = c.triangles + c.lines + c.points;
        eprintln!("{range:>6} m: {c:?}");
        assert!(
            total <= previous,
            "{range} m: {total} primitives, more than nearer"
        );
        previous = total;
    }
}

#[test]
fn stored_trees_drop_the_duplicate_order_and_rebuild_whole_meshes() {
    let kept = lod("quaking_aspen", 0.5);
    let p = builtin("quaking_aspen").unwrap();
    let sk = generate(
        &p,
        &GenerateOptions {
            seed: 1,
            quality: 0.5,
            ..Default::default()
        },
    )
    .unwrap();
    let stored = LodTree::build(
        &sk,
        &MeshOptions {
            quality: 0.5,
            ..Default::default()
        },
    );
    assert!(stored.mesh.bark.indices.is_empty() && stored.mesh.leaves.indices.is_empty());
    assert_eq!(stored.lists, kept.lists);
    assert!(stored.heap_bytes() < kept.heap_bytes());
    let full = stored.full_mesh();
    assert_eq!(full.triangle_count(), kept.mesh.triangle_count());
    assert_eq!(stored.triangle_count(), kept.mesh.triangle_count());
    // Same triangles as the mesh, as sets of corner positions.
    let corners = |m: &crate::mesh::Mesh| {
        let mut t: Vec<[u32; 9]> = m
            .indices
            .chunks(3)
            .map(|c| {
                let mut k = [0u32; 9];
                for (j, &i) in c.iter().enumerate() {
                    for a in 0..3 {
                        k[j * 3 + a] = m.positions[i as usize][a].to_bits();
                    }
                }
                k
            })
            .collect();
        t.sort_unstable();
        t
    };
    assert_eq!(corners(&full.bark), corners(&kept.mesh.bark));
    assert_eq!(corners(&full.leaves), corners(&kept.mesh.leaves));
    // A reduced level keeps only the vertices its triangles use.
    let half = stored.mesh_at([16.0, 16.0, 8.0, 2.0]);
    assert!(half.leaves.triangle_count() * 2 <= full.leaves.triangle_count() + 8);
    assert!(half.leaves.vertex_count() < full.leaves.vertex_count());
    assert!(
        half.leaves
            .indices
            .iter()
            .all(|&i| (i as usize) < half.leaves.vertex_count())
    );
}

#[test]
fn engine_levels_keep_the_leaf_area_with_fewer_leaves() {
    let t = lod("black_tupelo", 0.5);
    let area = |m: &crate::mesh::Mesh| {
        m.indices
            .chunks(3)
            .map(|c| {
                let [a, b, d] =
                    [c[0], c[1], c[2]].map(|i| glam::Vec3::from(m.positions[i as usize]));
                (b - a).cross(d - a).length() as f64 / 2.0
            })
            .sum::<f64>()
    };
    let chain = t.engine_chain();
    assert_eq!(chain.len(), 3);
    let full = area(&chain[0].0.leaves);
    for (k, (mesh, coverage)) in chain.iter().enumerate() {
        let a = area(&mesh.leaves);
        // Prefix counts round, so the kept share is within one leaf per mass of the ideal.
        assert!(
            (a / full - 1.0).abs() < 0.05,
            "level {k}: leaf area {a} vs {full}"
        );
        if k > 0 {
            let (prev, prev_cov) = (&chain[k - 1].0, chain[k - 1].1);
            assert!(
                mesh.triangle_count() * 10 < prev.triangle_count() * 7,
                "level {k} not smaller"
            );
            assert!(*coverage < prev_cov);
        }
    }
    assert_eq!(chain[0].0.triangle_count(), t.mesh.triangle_count());
}
