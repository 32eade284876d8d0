//! Generation and meshing throughput of the paper's four appendix species, in triangles per
//! second (criterion's "thrpt" in elements/s), plus the copy of the finished mesh as a baseline
//! measured in the same run.

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

criterion_group!(benches, appendix_species);
criterion_main!(benches);
