//! The measurements `sylva bench` prints: each runs a pipeline of this crate the way a user
//! does and returns its timings, with a baseline timed in the same call (copying what was
//! made), so figures compare across runs on shared, noisy machines. Nothing here prints.
//!
//! ```
//! let params = sylva::species::builtin("quaking_aspen").unwrap();
//! let t = sylva::bench::generate_times(&params, 1).unwrap();
//! assert!(t.triangles > 0 && t.warm_ms() > 0.0 && t.copy_ms > 0.0);
//! ```

use crate::growth::survey::report::MESH;
use crate::growth::{Database, Grower, GrowthError, GrowthOptions};
use crate::lod::{LodTree, Viewer};
use crate::mesh::{MeshOptions, TreeMesh, mesh_tree, mesh_tree_into};
use crate::{GenerateError, GenerateOptions, Skeleton, TreeParams};
use std::time::Instant;

/// The paper's four appendix species: the benchmark set.
pub const APPENDIX_SPECIES: [&str; 4] = [
    "quaking_aspen",
    "black_tupelo",
    "weeping_willow",
    "ca_black_oak",
];

/// Fastest of `runs` timings of `f`, milliseconds (the least disturbed by a shared machine).
pub fn fastest_ms<E>(runs: u32, mut f: impl FnMut() -> Result<(), E>) -> Result<f64, E> {
    let mut best = f64::MAX;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        f()?;
        best = best.min(t.elapsed().as_secs_f64());
    }
    Ok(best * 1e3)
}

/// [`fastest_ms`] of work that cannot fail.
pub fn fastest_of(runs: u32, mut f: impl FnMut()) -> f64 {
    let timed: Result<f64, std::convert::Infallible> = fastest_ms(runs, || {
        f();
        Ok(())
    });
    match timed {
        Ok(ms) => ms,
        Err(never) => match never {},
    }
}

/// Generating and meshing one tree, fastest of several runs, on every core of rayon's pool
/// (a tree's main branches grow apart, its bark and leaves are meshed at once) and on one.
#[derive(Clone, Copy, Debug)]
pub struct GenerateTimes {
    /// Triangles in the mesh.
    pub triangles: usize,
    /// Generate and mesh into fresh buffers, as a one-shot command-line run, ms.
    pub cold_ms: f64,
    /// Generate into warm buffers, as an editor regenerating on every change, ms.
    pub generate_ms: f64,
    /// Mesh into warm buffers, ms.
    pub mesh_ms: f64,
    /// Baseline: copy the finished mesh's buffers into warm buffers, ms.
    pub copy_ms: f64,
    /// Baseline: generate and mesh into warm buffers on one thread, ms (`None` where no
    /// one-thread pool could be made).
    pub one_thread_ms: Option<f64>,
}

impl GenerateTimes {
    /// Generate and mesh into warm buffers, ms.
    pub fn warm_ms(&self) -> f64 {
        self.generate_ms + self.mesh_ms
    }
}

/// Times generating and meshing `params` (default options, quality 1), fastest of `runs`.
pub fn generate_times(params: &TreeParams, runs: u32) -> Result<GenerateTimes, GenerateError> {
    let options = GenerateOptions::default();
    let mesh_options = MeshOptions::for_species(params, 1.0);
    let cold_ms = fastest_ms::<GenerateError>(runs, || {
        let skeleton = crate::generate(params, &options)?;
        std::hint::black_box(mesh_tree(&skeleton, &mesh_options));
        Ok(())
    })?;
    let mut skeleton = Skeleton::default();
    let mut mesh = TreeMesh::default();
    let generate_ms = fastest_ms(runs, || {
        crate::generate_into(params, &options, &mut skeleton)
    })?;
    let mesh_ms = fastest_of(runs, || mesh_tree_into(&skeleton, &mesh_options, &mut mesh));
    let mut copy = TreeMesh::default();
    let copy_ms = fastest_of(runs, || copy.clone_from(&mesh));
    let one_thread_ms = match rayon::ThreadPoolBuilder::new().num_threads(1).build() {
        Ok(pool) => Some(pool.install(|| {
            fastest_ms(runs, || {
                crate::generate_into(params, &options, &mut skeleton)?;
                mesh_tree_into(&skeleton, &mesh_options, &mut mesh);
                Ok::<(), GenerateError>(())
            })
        })?),
        Err(_) => None,
    };
    Ok(GenerateTimes {
        triangles: mesh.triangle_count(),
        cold_ms,
        generate_ms,
        mesh_ms,
        copy_ms,
        one_thread_ms,
    })
}

/// Writing a mesh as OBJ and as GLB into memory (the disk is left out: it is the machine's,
/// not the writer's), fastest of several runs, each beside a baseline from the same run.
#[derive(Clone, Copy, Debug)]
pub struct WriterTimes {
    /// OBJ bytes, as [`crate::export::to_obj`] writes them.
    pub obj_bytes: usize,
    /// Formatting them, ms.
    pub obj_ms: f64,
    /// Baseline: the plain writer (`std::fmt`, absolute indices, a normal per vertex), bytes.
    pub plain_obj_bytes: usize,
    /// Baseline: the plain writer, ms.
    pub plain_obj_ms: f64,
    /// GLB bytes.
    pub glb_bytes: usize,
    /// Laying out and writing them, ms.
    pub glb_ms: f64,
    /// Baseline: copying that many bytes from one buffer to another, ms (the memory's
    /// bandwidth, the most a writer can approach).
    pub copy_ms: f64,
}

/// Times writing `mesh` as OBJ and GLB, fastest of `runs`.
pub fn writer_times(mesh: &TreeMesh, runs: u32) -> Result<WriterTimes, crate::ExportError> {
    use crate::export::{Materials, to_obj, tree_glb};
    let materials = Materials::default();
    let mut obj_bytes = 0;
    let obj_ms = fastest_of(runs, || {
        obj_bytes = to_obj(mesh, "tree", "tree.mtl", &materials).0.len();
    });
    let mut plain_obj_bytes = 0;
    let plain_obj_ms = fastest_of(runs, || plain_obj_bytes = plain_obj(mesh).len());
    let mut out = Vec::new();
    let glb_ms = fastest_ms(runs, || {
        out.clear();
        tree_glb(mesh, "tree", &materials)?
            .write_to(&mut out)
            .map_err(|e| crate::ExportError::Format(e.to_string()))
    })?;
    let mut copy = Vec::with_capacity(out.len());
    let copy_ms = fastest_of(runs, || {
        copy.clear();
        copy.extend_from_slice(&out);
    });
    Ok(WriterTimes {
        obj_bytes,
        obj_ms,
        plain_obj_bytes,
        plain_obj_ms,
        glb_bytes: out.len(),
        glb_ms,
        copy_ms,
    })
}

/// The reference OBJ writer the fast one is measured against: every number through
/// `std::fmt`, every vertex with its own UV and normal, faces by absolute index.
fn plain_obj(mesh: &TreeMesh) -> String {
    use std::fmt::Write;
    let mut obj = String::new();
    let mut base = 1;
    for part in [&mesh.bark, &mesh.leaves] {
        for ([x, y, z], [nx, ny, nz]) in part.positions.iter().zip(&part.normals) {
            let _ = writeln!(obj, "v {x} {z} {}\nvn {nx} {nz} {}", -y, -ny);
        }
        for [u, v] in &part.uvs {
            let _ = writeln!(obj, "vt {u} {v}");
        }
        for t in part.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize + base);
            let _ = writeln!(obj, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}");
        }
        base += part.vertex_count();
    }
    obj
}

/// The cost of an edit in the editor, ms: `1DownAngle` changed, the tree regenerated and
/// re-meshed into warm buffers, fastest of `runs`.
pub fn edit_ms(params: &TreeParams, runs: u32) -> Result<f64, GenerateError> {
    let mut params = params.clone();
    let options = GenerateOptions::default();
    let mesh_options = MeshOptions::for_species(&params, 1.0);
    let mut skeleton = Skeleton::default();
    let mut mesh = TreeMesh::default();
    crate::generate_into(&params, &options, &mut skeleton)?;
    mesh_tree_into(&skeleton, &mesh_options, &mut mesh);
    let mut angle = params.level[1].down_angle;
    fastest_ms(runs, || {
        angle = if angle > 60.0 { 55.0 } else { angle + 1.0 };
        params.level[1].down_angle = angle;
        crate::generate_into(&params, &options, &mut skeleton)?;
        mesh_tree_into(&skeleton, &mesh_options, &mut mesh);
        Ok(())
    })
}

/// Range degradation's own costs for one tree.
#[derive(Clone, Copy, Debug)]
pub struct LodTimes {
    /// Building the lists, ms.
    pub build_ms: f64,
    /// Choosing what to draw for one copy in one frame, ns (over 100,000 ranges).
    pub select_ns: f64,
    /// Bytes stored: the packed records and their run tables.
    pub stored_bytes: usize,
    /// Baseline from the same run: the bytes of the tree's full mesh in a GPU's usual layout
    /// (position, normal and texture coordinate per vertex, 32-bit indices).
    pub mesh_bytes: usize,
}

/// Times storing `skeleton` for range and choosing what to draw, for `viewer`.
pub fn lod_times(
    skeleton: &Skeleton,
    options: &MeshOptions,
    viewer: &Viewer,
) -> (LodTree, LodTimes) {
    let t = Instant::now();
    let lod = LodTree::build(skeleton, options);
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    // Ranges of a forest's worth of trees.
    let ranges: Vec<f32> = (0..100_000)
        .map(|i| 10.0 + (i as f32 * 7.31) % 3000.0)
        .collect();
    let mut best = f64::MAX;
    for _ in 0..5 {
        let t = Instant::now();
        let mut sink = 0u32;
        for &r in &ranges {
            let c = lod.counts(r, viewer);
            sink = sink.wrapping_add((c.triangles ^ c.points) as u32);
        }
        std::hint::black_box(sink);
        best = best.min(t.elapsed().as_secs_f64());
    }
    let mesh = crate::mesh::mesh_tree(skeleton, options);
    let mesh_bytes = mesh.vertex_count() * 32 + mesh.triangle_count() * 12;
    let times = LodTimes {
        build_ms,
        select_ns: best / ranges.len() as f64 * 1e9,
        stored_bytes: lod.heap_bytes(),
        mesh_bytes,
    };
    (lod, times)
}

/// One row of the growth benchmark: a street tree's step at a size.
#[derive(Clone, Copy, Debug)]
pub struct GrowthStepTimes {
    /// Branch segments when timed.
    pub segments: usize,
    /// Age, years.
    pub age: f64,
    /// Leaves on the skeleton.
    pub leaves: usize,
    /// Production rules (buds, elongation, shedding), mean ms per step.
    pub growth_ms: f64,
    /// Light in the crown, mean ms per step.
    pub light_ms: f64,
    /// The tree as a skeleton, ms (fastest).
    pub skeleton_ms: f64,
    /// Skeleton and mesh, ms (fastest).
    pub mesh_ms: f64,
    /// Baseline: copying the skeleton, ms (fastest).
    pub copy_ms: f64,
    /// The mesh alone with the species' bark pattern drawn (finer rings on thick stems, a
    /// shade per vertex), ms (fastest), to compare with the mesh alone without it,
    /// `plain_mesh_ms`.
    pub patterned_mesh_ms: f64,
    /// The mesh alone without the bark pattern, ms (fastest).
    pub plain_mesh_ms: f64,
}

impl GrowthStepTimes {
    /// A whole step: growth, light and mesh, ms.
    pub fn total_ms(&self) -> f64 {
        self.growth_ms + self.light_ms + self.mesh_ms
    }
}

/// Segment counts the growth benchmark times a step at.
pub const GROWTH_SIZES: [usize; 4] = [5_000, 10_000, 20_000, 30_000];
/// Steps averaged at each size: one year.
pub const GROWTH_STEPS: usize = crate::growth::STEPS_PER_YEAR as usize;

/// Grows a silver maple (Inland Valleys: of the Modesto seven, the one whose crown holds the
/// most segments, past 30,000 by age 57) past each of [`GROWTH_SIZES`] segments and times
/// [`GROWTH_STEPS`] steps there, meshing at `runs` tries. An error if the tree stops growing
/// before a size.
pub fn growth_steps(runs: u32) -> Result<Vec<GrowthStepTimes>, GrowthError> {
    let measured = Database::builtin().find("InlVal", "ACSA1")?;
    let (_, last_age) = measured.ages;
    let mut grower = Grower::new(measured, GrowthOptions::default());
    let mut skeleton = grower.skeleton();
    let mut mesh = TreeMesh::default();
    let mut rows = Vec::new();
    for size in GROWTH_SIZES {
        while grower.segment_count() < size {
            if grower.age() > last_age {
                return Err(GrowthError::Stalled {
                    label: grower.measured().label(),
                    segments: grower.segment_count(),
                    age: last_age,
                });
            }
            grower.step_once(grower.step_length());
        }
        let (mut growth, mut light) = (0.0, 0.0);
        for _ in 0..GROWTH_STEPS {
            grower.step_once(grower.step_length());
            growth += grower.times.growth;
            light += grower.times.light;
        }
        let skeleton_ms = fastest_of(runs, || grower.skeleton_into(&mut skeleton));
        let plain_mesh_ms = fastest_of(runs, || mesh_tree_into(&skeleton, &MESH, &mut mesh));
        let mesh_ms = skeleton_ms + plain_mesh_ms;
        let patterned = grower.measured().dress(None).mesh_options(&MESH);
        let patterned_mesh_ms =
            fastest_of(runs, || mesh_tree_into(&skeleton, &patterned, &mut mesh));
        let mut copy = Skeleton::default();
        let copy_ms = fastest_of(runs, || copy.clone_from(&skeleton));
        rows.push(GrowthStepTimes {
            segments: grower.segment_count(),
            age: grower.age(),
            leaves: skeleton.leaves.len(),
            growth_ms: growth * 1e3 / GROWTH_STEPS as f64,
            light_ms: light * 1e3 / GROWTH_STEPS as f64,
            skeleton_ms,
            mesh_ms,
            copy_ms,
            patterned_mesh_ms,
            plain_mesh_ms,
        });
    }
    Ok(rows)
}

/// The street a tree's benefits and conflicts are timed on: a 1.2 m strip, shops 3.1 m back
/// facing south with awnings and a sign, lines over the strip, a lamp (the repository's
/// `sites/narrow-under-wires.toml`, compiled in so the benchmark runs anywhere).
pub const BENCH_SITE: &str = "[street]\ncurb = -0.6\nsidewalk = [0.6, 2.1]\n\
roadway_clearance = 4.3\nsidewalk_clearance = 2.4\n[facade]\nsetback = 3.1\nheight = 7.0\n\
width = 12.0\nfaces = 180.0\nwindow_share = 0.4\n[[awning]]\nbottom = 2.6\ntop = 3.1\n\
reach = 1.2\nalong = [-3.0, 3.0]\n[[sign]]\nbottom = 3.4\ntop = 4.2\nreach = 0.9\n\
along = [2.0, 3.0]\n[[wire]]\nheight = 8.5\noffset = -0.3\nvoltage_kv = 12.0\n[[light]]\n\
x = 7.0\ny = -0.7\nheight = 6.0\nclearance = 1.0\n";

/// A street tree grown yearly and accounted each year: the growth's time beside the
/// account's (benefits, shade on the façade, conflicts).
#[derive(Clone, Copy, Debug)]
pub struct StreetTimes {
    /// Years grown.
    pub years: usize,
    /// Growing the tree year by year and measuring it, as `sylva grow` does, s.
    pub growth_s: f64,
    /// Every year's account, s.
    pub account_s: f64,
}

/// Grows `code` of `region` yearly from its first whole age to `years` on [`BENCH_SITE`] and
/// times the growth and the accounts apart.
pub fn street_times(
    region: &str,
    code: &str,
    years: f64,
) -> Result<StreetTimes, crate::street::StreetError> {
    use crate::growth::survey::report::Cohort;
    use crate::street::{Assessor, Site};
    let measured = Database::builtin().find(region, code)?;
    let site = Site::parse(BENCH_SITE, "the benchmark's site")?;
    let mut assessor = Assessor::new(&measured, Some(site), None, None);
    let mut cohort = Cohort::new(vec![measured.clone()], 0);
    let (mut growth_s, mut account_s) = (0.0, 0.0);
    let ages = crate::street::rank::ages(&measured, years);
    for &age in &ages {
        let t = Instant::now();
        let skeleton = cohort.advance_to(age).remove(0);
        growth_s += t.elapsed().as_secs_f64();
        let dims = cohort.history[0]
            .last()
            .map(|r| r.model)
            .unwrap_or_default();
        let t = Instant::now();
        let account = assessor.year(age, &dims, &skeleton);
        account_s += t.elapsed().as_secs_f64();
        std::hint::black_box(account);
    }
    Ok(StreetTimes {
        years: ages.len(),
        growth_s,
        account_s,
    })
}

/// `sylva rank`'s run of one species on [`BENCH_SITE`], with the site's pruning regime (the
/// default us-street standard) and without it, s: the best of `runs` each, run alternately
/// so both see the same machine.
pub fn pruning_times(
    region: &str,
    code: &str,
    years: f64,
    runs: usize,
) -> Result<(f64, f64), crate::street::StreetError> {
    use crate::street::Site;
    use crate::street::rank::{Pruning, Study, run};
    let measured = Database::builtin().find(region, code)?;
    let site = Site::parse(BENCH_SITE, "the benchmark's site")?;
    let time = |pruning: Pruning| {
        let study = Study {
            site: Some(site.clone()),
            pruning,
            ..Study::new(years)
        };
        let t = Instant::now();
        std::hint::black_box(run(&measured, &study));
        t.elapsed().as_secs_f64()
    };
    let (mut pruned, mut grown) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..runs.max(1) {
        grown = grown.min(time(Pruning::Off));
        pruned = pruned.min(time(Pruning::Regime));
    }
    Ok((pruned, grown))
}

/// The species whose branching `sylva bench --twigs` measures: the Modesto seven (region
/// InlVal, the seeds' data) and three of NoEast, the red maple and red oak of the published
/// twig counts ("Tree branches as populations of twigs": red maple and scarlet oak) and the
/// sugar maple of the published bifurcation ratios (Steingraeber et al. 1979).
pub const TWIG_SPECIES: [(&str, &str); 10] = [
    ("InlVal", "PLAC"),
    ("InlVal", "ACSA1"),
    ("InlVal", "FRVE_G"),
    ("InlVal", "KOPA"),
    ("InlVal", "MAGR"),
    ("InlVal", "PICH"),
    ("InlVal", "CESI4"),
    ("NoEast", "ACRU"),
    ("NoEast", "QURU"),
    ("NoEast", "ACSA2"),
];

/// Grows `code` of `region` (seed 0, no site) and measures its branching at each of `ages`
/// (ages past the data's last are left out).
pub fn branching_at(
    region: &str,
    code: &str,
    ages: &[f64],
) -> Result<Vec<(f64, crate::growth::survey::twigs::Branching)>, GrowthError> {
    let measured = Database::builtin().find(region, code)?;
    let last = measured.ages.1;
    let mut grower = Grower::new(measured, GrowthOptions::default());
    let mut out = Vec::new();
    for &age in ages.iter().filter(|&&a| a <= last) {
        grower.advance_to(age);
        let skeleton = grower.skeleton();
        out.push((
            age,
            crate::growth::survey::twigs::measure_branching(&skeleton),
        ));
    }
    Ok(out)
}
