//! The renderer on the CPU and, where there is one, the GPU: pictures measured.

use super::*;
use std::sync::{Arc, Mutex};

fn small_tree() -> (sylva::lod::LodTree, sylva::TreeParams) {
    let params = sylva::species::builtin("quaking_aspen").unwrap();
    let options = sylva::GenerateOptions {
        max_levels: Some(3),
        quality: 0.3,
        ..Default::default()
    };
    let skeleton = sylva::generate(&params, &options).unwrap();
    let lod = sylva::lod::LodTree::build(&skeleton, &Default::default());
    (lod, params)
}

#[test]
fn a_missing_adapter_is_told_by_what_was_tried() {
    let e = RenderError::NoAdapter(
        "No suitable graphics adapter found; noop not requested, vulkan drivers/libraries \
         could not be loaded, metal support not compiled in, gl not requested"
            .into(),
    );
    assert_eq!(e.reason(), "vulkan drivers/libraries could not be loaded");
}

#[test]
fn a_tree_the_gpu_cannot_hold_is_drawn_on_the_cpu() {
    let notes = Arc::new(Mutex::new(Vec::<String>::new()));
    let sink = notes.clone();
    let Ok(mut r) = Renderer::headless(Choice::Auto, move |n| {
        sink.lock().unwrap().push(n.to_string())
    }) else {
        return;
    };
    let Some(g) = r.gpu.as_mut() else {
        eprintln!("no GPU here, nothing to test");
        return;
    };
    // A range-degraded tree must fit whole in one buffer; pretend the device holds 1 kB.
    g.limit_buffers(1024);
    let (lod, params) = small_tree();
    let tree = r.upload_lod(&lod);
    assert_eq!(r.backend(), Backend::Cpu, "the renderer moved to the CPU");
    assert!(r.gpu_failure().unwrap().contains("buffer limit"));
    let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
    let picture = r
        .render(&scene, &View::named(ViewKind::Front), 64, 64)
        .unwrap();
    assert!(
        picture.rgba.chunks(4).any(|p| p[1] > p[0] + 10),
        "green leaves"
    );
    let notes = notes.lock().unwrap();
    assert_eq!(notes.len(), 1, "one notice: {notes:?}");
    assert!(notes[0].contains("CPU rasteriser"));
}

#[test]
fn meshes_over_the_buffer_limit_are_cut_and_drawn_whole() {
    let Ok(mut r) = Renderer::headless(Choice::Auto, |_| {}) else {
        return;
    };
    if r.gpu.is_none() {
        eprintln!("no GPU here, nothing to test");
        return;
    }
    let (_, params) = small_tree();
    let skeleton = sylva::generate(&params, &Default::default()).unwrap();
    let mesh = sylva::mesh::mesh_tree(&skeleton, &Default::default());
    let whole = r.upload(&mesh);
    let view = View::named(ViewKind::Front);
    let before = r
        .render(
            &Scene::new(&whole, params.bark_color, params.leaf_color),
            &view,
            96,
            96,
        )
        .unwrap();
    // 64 kB buffers: the bark and leaves go up in many parts.
    r.gpu.as_mut().unwrap().limit_buffers(64 << 10);
    let cut = r.upload(&mesh);
    assert!(cut.gpu.as_ref().unwrap().leaves.parts.len() > 1);
    let after = r
        .render(
            &Scene::new(&cut, params.bark_color, params.leaf_color),
            &view,
            96,
            96,
        )
        .unwrap();
    assert_eq!(r.backend(), Backend::Gpu);
    assert_eq!(before.rgba, after.rgba, "the same picture from the parts");
}

/// One renderer drawing from several threads at once (as `sylva sweep --picture` does,
/// one species a thread) draws each picture as it draws it alone: its camera, lights and
/// shadow map are the picture's own, never another thread's.
#[test]
fn pictures_drawn_at_once_from_several_threads_are_each_their_own() {
    let Ok(r) = Renderer::headless(Choice::Auto, |_| {}) else {
        return;
    };
    let (_, params) = small_tree();
    let skeleton = sylva::generate(&params, &Default::default()).unwrap();
    let tree = r.upload(&sylva::mesh::mesh_tree(&skeleton, &Default::default()));
    let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
    // Four views as unlike as can be: each thread's camera frames the tree differently.
    let views: Vec<View> = (0..4)
        .map(|k| View::orbit(k as f32 * 90.0, k as f32 * 20.0))
        .collect();
    let alone: Vec<Vec<u8>> = views
        .iter()
        .map(|v| r.render(&scene, v, 128, 128).unwrap().rgba)
        .collect();
    assert!(
        alone.windows(2).all(|w| w[0] != w[1]),
        "four unlike pictures"
    );
    for round in 0..6 {
        let together: Vec<Vec<u8>> = std::thread::scope(|s| {
            let drawing: Vec<_> = views
                .iter()
                .map(|v| s.spawn(|| r.render(&scene, v, 128, 128).unwrap().rgba))
                .collect();
            drawing.into_iter().map(|d| d.join().unwrap()).collect()
        });
        for (k, (a, b)) in alone.iter().zip(&together).enumerate() {
            assert!(
                a == b,
                "round {round}: view {k} drawn at once differs from alone"
            );
        }
    }
}
