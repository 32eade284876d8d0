use super::order::paper_loop;
use super::*;
use crate::mesh::MeshOptions;
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
    LodTree::build(
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

fn meshed_and_flat(t: &LodTree, range: f32) -> Vec<Vec<RunDraw>> {
    t.lists
        .iter()
        .enumerate()
        .map(|(i, l)| l.select(i == 3, range, &PAPER).map(|(_, d)| d).collect())
        .collect()
}

#[test]
fn near_trees_draw_everything_as_meshes() {
    let t = lod("quaking_aspen", 1.0);
    for (list, draws) in t.lists.iter().zip(meshed_and_flat(&t, 5.0)) {
        for (run, d) in list.runs.iter().zip(draws) {
            assert_eq!(d.meshed, run.items.clone(), "all items meshed at 5 m");
            assert!(d.flat.is_empty());
        }
    }
    // Every segment and leaf is in exactly one run.
    let segments: usize = t.lists[..3].iter().map(|l| l.items).sum();
    assert_eq!(segments, t.segments.len());
    assert_eq!(t.lists[3].items, t.leaves.len());
    for list in &t.lists {
        assert_eq!(list.runs.iter().map(Run::len).sum::<usize>(), list.items);
    }
}

#[test]
fn each_level_of_detail_is_the_papers_set_of_items() {
    let t = lod("black_tupelo", 0.5);
    for range in [20.0, 80.0, 300.0, 1000.0, 3000.0] {
        for (i, list) in t.lists.iter().enumerate() {
            let (x_mesh, _) = list.levels_of_detail(i == 3, range, &PAPER);
            for (run, d) in list.select(i == 3, range, &PAPER) {
                // The meshed records (a prefix of the rank-major run) are the paper's loop's
                // items of the run.
                let meshed = d.meshed.len();
                let mut from_prefix: Vec<usize> = order::rank_major(run.len(), list.mass)[..meshed]
                    .iter()
                    .map(|&v| v as usize)
                    .collect();
                from_prefix.sort_unstable();
                // As many items of every rank as the paper's loop (its partial rank takes
                // the first masses; the stored order spreads them over the tree).
                let ranks = |items: &[usize]| {
                    let mut n = vec![0; list.mass];
                    items.iter().for_each(|&k| n[k % list.mass] += 1);
                    n
                };
                let loop_items = paper_loop(run.len(), list.mass, x_mesh);
                assert_eq!(
                    ranks(&from_prefix),
                    ranks(&loop_items),
                    "list {i} at {range} m"
                );
            }
        }
    }
}

#[test]
fn receding_changes_counts_one_item_per_mass_at_most() {
    let t = lod("quaking_aspen", 1.0);
    let mut previous: Option<Vec<Vec<RunDraw>>> = None;
    let mut range = 10.0f32;
    while range < 3000.0 {
        let now = meshed_and_flat(&t, range);
        if let Some(prev) = &previous {
            for (i, list) in t.lists.iter().enumerate() {
                for (k, run) in list.runs.iter().enumerate() {
                    let (a, b) = (&prev[i][k], &now[i][k]);
                    let masses = run.len().div_ceil(list.mass);
                    assert!(
                        b.meshed.len() <= a.meshed.len(),
                        "meshes grow as it recedes"
                    );
                    assert!(
                        a.meshed.len() - b.meshed.len() <= masses,
                        "list {i}: mesh count jumped at {range} m"
                    );
                    let drawn = |d: &RunDraw| d.flat.end as usize;
                    assert!(
                        drawn(b) <= drawn(a) && drawn(a) - drawn(b) <= masses,
                        "list {i}: drawn count jumped at {range} m"
                    );
                }
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
    let facets = t.triangle_count();
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

fn area(m: &crate::mesh::Mesh) -> f64 {
    m.indices
        .chunks(3)
        .map(|c| {
            let [a, b, d] = [c[0], c[1], c[2]].map(|i| glam::Vec3::from(m.positions[i as usize]));
            (b - a).cross(d - a).length() as f64 / 2.0
        })
        .sum()
}

#[test]
fn a_black_tupelo_is_stored_in_under_a_megabyte_and_rebuilds_its_mesh() {
    let p = builtin("black_tupelo").unwrap();
    let sk = generate(&p, &GenerateOptions::default()).unwrap();
    let options = MeshOptions::for_species(&p, 1.0);
    let t = LodTree::build(&sk, &options);
    assert!(t.heap_bytes() <= 1_000_000, "{} bytes", t.heap_bytes());
    let mesh = crate::mesh::mesh_tree(&sk, &options);
    let full = t.full_mesh();
    // Same leaves: as many triangles, the same area (the tupelo's leaves are all one size, so
    // their 6-bit sizes are exact), and the same box to a millimetre.
    assert_eq!(full.leaves.triangle_count(), mesh.leaves.triangle_count());
    let (a, b) = (area(&full.leaves), area(&mesh.leaves));
    assert!((a / b - 1.0).abs() < 1e-3, "leaf area {a} vs {b}");
    let (lo, hi) = full.leaves.bounds().unwrap();
    let (mlo, mhi) = mesh.leaves.bounds().unwrap();
    for k in 0..3 {
        assert!((lo[k] - mlo[k]).abs() < 1e-3 && (hi[k] - mhi[k]).abs() < 1e-3);
    }
    // Same bark, less the flat caps on open stem ends (the mesher's only triangles that have
    // no segment): area within 1%, and no triangle more than the mesher's segments hold.
    let (a, b) = (area(&full.bark), area(&mesh.bark));
    assert!((a / b - 1.0).abs() < 0.01, "bark area {a} vs {b}");
    assert!(full.bark.triangle_count() <= mesh.bark.triangle_count());
    assert!(full.bark.triangle_count() * 100 >= mesh.bark.triangle_count() * 95);
    // Every drawn item is counted: the stored triangles are the quads of every segment.
    let quads: usize = t.lists[..3]
        .iter()
        .flat_map(|l| &l.runs)
        .map(|r| r.len() * 2 * r.sides as usize)
        .sum::<usize>()
        + full.leaves.triangle_count();
    assert_eq!(t.triangle_count(), quads);
}

#[test]
fn records_hold_the_skeleton_to_their_steps() {
    let p = builtin("quaking_aspen").unwrap();
    let mut sk = generate(&p, &GenerateOptions::default()).unwrap();
    // Leaves of several sizes and lights, as a grown crown has.
    for (i, l) in sk.leaves.iter_mut().enumerate() {
        l.length *= 0.5 + (i % 7) as f32 / 12.0;
        l.light = (i % 10) as f32 / 9.0;
    }
    let t = LodTree::build(&sk, &MeshOptions::default());
    let q = &t.quantiser;
    let step = q.size.max_element() / 65535.0;
    let run = &t.lists[3].runs[0];
    assert_eq!(run.len(), sk.leaves.len(), "one outline, one run");
    let longest = sk.leaves.iter().map(|l| l.length).fold(0.0, f32::max);
    for (p, &i) in order::rank_major(run.len(), order::LEAF_MASS)
        .iter()
        .enumerate()
    {
        let (leaf, card) = (&sk.leaves[i as usize], expand::Card::of(q, &t.leaves[p]));
        assert!(leaf.position.distance(card.base) <= step, "leaf {i}");
        let turn = leaf.orientation.angle_between(card.frame).to_degrees();
        assert!(turn < 0.3, "leaf {i}: frame off by {turn} degrees");
        assert!((leaf.length - card.length).abs() <= longest / 126.0 + 1e-6);
        assert_eq!(card.shade, crate::mesh::luminance(leaf.light));
    }
}

#[test]
fn reduced_levels_keep_fewer_items() {
    let t = lod("quaking_aspen", 0.5);
    let full = t.full_mesh();
    let half = t.mesh_at([16.0, 16.0, 8.0, 2.0]);
    assert!(half.leaves.triangle_count() * 2 <= full.leaves.triangle_count() + 8);
    assert!(half.bark.triangle_count() < full.bark.triangle_count());
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
    assert_eq!(chain[0].0.triangle_count(), t.full_mesh().triangle_count());
}

#[test]
fn an_empty_or_leafless_tree_is_stored_and_drawn_as_nothing() {
    let empty = LodTree::build(&crate::Skeleton::default(), &MeshOptions::default());
    assert_eq!(empty.triangle_count(), 0);
    assert_eq!(empty.counts(10.0, &PAPER), LodCounts::default());
    assert_eq!(empty.full_mesh().triangle_count(), 0);
    let (lo, hi) = empty.quantiser.bounds();
    assert!(lo.is_finite() && hi.is_finite());
    // A leafless tree: stems only, and a budget cut leaves no leaf to grow.
    let p = builtin("quaking_aspen").unwrap();
    let mut sk = generate(&p, &GenerateOptions::default()).unwrap();
    sk.leaves.clear();
    let t = LodTree::build(&sk, &MeshOptions::default());
    assert!(t.leaves.is_empty() && t.lists[3].runs.is_empty());
    let c = t.within(t.full_choice(), 1000);
    assert!(t.primitives(&c) <= 1000);
    assert_eq!(c.leaf_grow, 1.0);
}

#[test]
fn engine_meshes_carry_each_stem_vertexs_radius_to_the_glb() {
    let t = lod("quaking_aspen", 1.0);
    let mesh = t.engine_mesh([16.0, 16.0, 8.0, 2.0]);
    assert_eq!(mesh.bark.radii.len(), mesh.bark.vertex_count());
    assert!(mesh.leaves.radii.is_empty());
    let trunk = mesh.bark.radii.iter().cloned().fold(0.0f32, f32::max);
    let twig = mesh.bark.radii.iter().cloned().fold(f32::MAX, f32::min);
    assert!(trunk > 0.05 && twig < 0.01, "radii {twig} .. {trunk} m");
    // The first ring: its vertices at its radius from their mean (the seam vertex repeats
    // the first, so the mean of the others is the centre; lobes move them a little).
    let sides = t.lists[0].runs[0].sides as usize;
    let ring: Vec<glam::Vec3> = mesh.bark.positions[..sides]
        .iter()
        .map(|p| glam::Vec3::from(*p))
        .collect();
    let centre = ring.iter().sum::<glam::Vec3>() / sides as f32;
    for p in &ring {
        let r = (*p - centre).length();
        assert!(
            (r / mesh.bark.radii[0] - 1.0).abs() < 0.3,
            "{r} vs {}",
            mesh.bark.radii[0]
        );
    }
    let glb = crate::export::to_glb(
        &mesh,
        "aspen",
        &crate::export::Materials::from_srgb([0.4; 3], [0.2, 0.5, 0.2]),
    )
    .unwrap();
    // Every bark primitive (a large bark is cut into primitives of 16-bit indices) carries
    // its vertices' radii.
    let gltf = gltf::Gltf::from_slice(&glb).unwrap();
    let mut carried = 0;
    for bark in gltf.meshes().next().unwrap().primitives() {
        if bark.material().name() != Some("bark") {
            continue;
        }
        let radius = bark
            .attributes()
            .find(|(s, _)| matches!(s, gltf::Semantic::Extras(name) if name == "RADIUS"))
            .expect("the bark carries _RADIUS");
        assert_eq!(
            radius.1.count(),
            bark.get(&gltf::Semantic::Positions).unwrap().count()
        );
        carried += radius.1.count();
    }
    assert_eq!(carried, mesh.bark.vertex_count());
}
