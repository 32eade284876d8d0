//! Generation and meshing throughput of the paper's four appendix species, in triangles per
//! second (criterion's "thrpt" in elements/s), plus the copy of the finished mesh as a baseline
//! measured in the same run; the OBJ and GLB writers in bytes per second, beside a copy of as
//! many bytes; and a growth step of a street tree.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use sylva::mesh::{MeshOptions, TreeMesh, mesh_tree_into};
use sylva::{GenerateOptions, Skeleton, generate_into, species::builtin};

fn appendix_species(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate+mesh");
    group.sample_size(20);
    for id in [
        "quaking_aspen",
        "black_tupelo",
        "weeping_willow",
        "ca_black_oak",
    ] {
        let params = builtin(id).unwrap();
        let options = GenerateOptions::default();
        let mesh_options = MeshOptions {
            quality: 0.5 + params.smooth,
            ..Default::default()
        };
        let mut skeleton = Skeleton::default();
        let mut mesh = TreeMesh::default();
        generate_into(&params, &options, &mut skeleton).unwrap();
        mesh_tree_into(&skeleton, &mesh_options, &mut mesh);
        group.throughput(Throughput::Elements(mesh.triangle_count() as u64));
        group.bench_function(id, |b| {
            b.iter(|| {
                generate_into(&params, &options, &mut skeleton).unwrap();
                mesh_tree_into(&skeleton, &mesh_options, &mut mesh);
                black_box(mesh.triangle_count())
            })
        });
        let mut copy = TreeMesh::default();
        group.bench_function(format!("{id}/baseline-copy"), |b| {
            b.iter(|| {
                copy.clone_from(&mesh);
                black_box(copy.triangle_count())
            })
        });
    }
    group.finish();
}

fn writers(c: &mut Criterion) {
    use sylva::export::{Materials, to_obj, tree_glb};
    let params = builtin("black_tupelo").unwrap();
    let skeleton = sylva::generate(&params, &GenerateOptions::default()).unwrap();
    let mesh = sylva::mesh::mesh_tree(&skeleton, &MeshOptions::for_species(&params, 1.0));
    let materials = Materials::default();
    let mut group = c.benchmark_group("write");
    group.sample_size(20);
    let obj_bytes = to_obj(&mesh, "t", "t.mtl", &materials).0.len();
    group.throughput(Throughput::Bytes(obj_bytes as u64));
    group.bench_function("obj", |b| {
        b.iter(|| black_box(to_obj(&mesh, "t", "t.mtl", &materials).0.len()))
    });
    let mut out = Vec::new();
    tree_glb(&mesh, "t", &materials)
        .unwrap()
        .write_to(&mut out)
        .unwrap();
    group.throughput(Throughput::Bytes(out.len() as u64));
    group.bench_function("glb", |b| {
        b.iter(|| {
            out.clear();
            let glb = tree_glb(&mesh, "t", &materials).unwrap();
            glb.write_to(&mut out).unwrap();
            black_box(out.len())
        })
    });
    let mut copy = Vec::with_capacity(out.len());
    group.bench_function("glb/baseline-copy", |b| {
        b.iter(|| {
            copy.clear();
            copy.extend_from_slice(&out);
            black_box(copy.len())
        })
    });
    group.finish();
}

/// A step of a silver maple grown past 10,000 segments (it keeps growing while measured, a
/// few per cent over the samples), beside copying its skeleton.
fn growth_step(c: &mut Criterion) {
    use sylva::growth::{Database, Grower, GrowthOptions};
    let measured = Database::builtin().find("InlVal", "ACSA1").unwrap();
    let options = GrowthOptions::default();
    let mut grower = Grower::new(measured, options);
    while grower.segment_count() < 10_000 {
        grower.step_once(grower.step_length());
    }
    let dt = grower.step_length();
    let mut group = c.benchmark_group("growth");
    group.sample_size(10);
    group.bench_function("step-10k-segments", |b| b.iter(|| grower.step_once(dt)));
    let skeleton = grower.skeleton();
    let mut copy = Skeleton::default();
    group.bench_function("step-10k-segments/baseline-copy-skeleton", |b| {
        b.iter(|| {
            copy.clone_from(&skeleton);
            black_box(copy.stems.len())
        })
    });
    group.finish();
}

criterion_group!(benches, appendix_species, writers, growth_step);
criterion_main!(benches);
