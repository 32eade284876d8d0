use super::*;
use crate::nagel::{FractalParams, WhiskParams, read_profile, whisk_tree};
use crate::skeleton::Skeleton;

fn whisk() -> Skeleton {
    let p = read_profile("p.csv", "0,2\n1.5,2.6\n2.6,4\n3,5.5\n2.2,7.2\n0,8\n", None).unwrap();
    whisk_tree(
        &p,
        &WhiskParams {
            ribs: 8,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn vector_files_round_trip_byte_for_byte() {
    let tree = crate::generate(
        &crate::species::builtin("quaking_aspen").unwrap(),
        &crate::GenerateOptions {
            seed: 2,
            ..Default::default()
        },
    )
    .unwrap();
    for source in [&tree, &whisk()] {
        let bytes = write_vec(source, Vec::new()).unwrap();
        let text = String::from_utf8(bytes.clone()).unwrap();
        let lines = read_vec(&text, "t.vec").unwrap();
        let again = write_vec(&lines, Vec::new()).unwrap();
        assert_eq!(bytes, again);
    }
    // Nagel's whisk file: each rib one `P` then an `L` per further profile point; the first rib
    // starts where the trunk ends, so the pen goes straight on.
    let text = String::from_utf8(write_vec(&whisk(), Vec::new()).unwrap()).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with('P')).count(), 8);
    assert_eq!(
        text.lines().filter(|l| l.starts_with('L')).count(),
        1 + 8 * 5
    );
    assert!(text.starts_with("P 0.0000,0.0000,0.0000\nL 0.0000,0.0000,2.0000\n"));
}

#[test]
fn malformed_vector_files_name_the_line() {
    let cases = [
        ("P 0,0,0\nL 1,1\n", "v.vec, line 2", "three coordinates"),
        ("L 0,0,0\n", "v.vec, line 1", "before any `P`"),
        (
            "P 0,0,0\n\nQ 1,2,3\n",
            "v.vec, line 3",
            "expected `P x,y,z`",
        ),
        ("P 0,0,0\nL 1,nan,3\n", "v.vec, line 2", "finite"),
    ];
    for (text, place, what) in cases {
        let e = read_vec(text, "v.vec").unwrap_err().to_string();
        assert!(e.contains(place) && e.contains(what), "{text:?}: {e}");
    }
    // Spaces instead of commas, lower case and comments are accepted.
    let lines = read_vec("# tree\np 0 0 0\nl 1 2 3\n", "v.vec").unwrap();
    assert_eq!(
        lines,
        vec![vec![glam::Vec3::ZERO, glam::Vec3::new(1.0, 2.0, 3.0)]]
    );
}

/// Dark pixels (any channel below 160) of an RGBA picture, as (x, y).
fn ink(rgba: &[u8], width: u32) -> Vec<(u32, u32)> {
    rgba.chunks(4)
        .enumerate()
        .filter(|(_, p)| p[..3].iter().any(|&c| c < 160))
        .map(|(i, _)| (i as u32 % width, i as u32 / width))
        .collect()
}

#[test]
fn views_put_the_tree_where_it_belongs() {
    let tree = whisk();
    let options = |view| DrawOptions {
        view,
        width: 400,
        height: 400,
        ..Default::default()
    };
    // Front: 6 m wide and 8 m tall, standing on the bottom margin, centred.
    let front = ink(&draw_rgba(&tree, &options(View::Front)), 400);
    let (x0, x1) = (
        front.iter().map(|p| p.0).min().unwrap(),
        front.iter().map(|p| p.0).max().unwrap(),
    );
    let (y0, y1) = (
        front.iter().map(|p| p.1).min().unwrap(),
        front.iter().map(|p| p.1).max().unwrap(),
    );
    let (w, h) = ((x1 - x0) as f32, (y1 - y0) as f32);
    assert!((w / h - 6.0 / 8.0).abs() < 0.03, "front {w}x{h}");
    // The ground is the bottom margin (376); the trunk's round cap reaches a little below.
    assert!((376..=384).contains(&y1), "stands at {y1}");
    assert!(((x0 + x1) as i32 - 400).abs() <= 2);
    // Plan: eight ribs make an eight-pointed star, as wide as it is deep; the centre is inked.
    let top = draw_rgba(&tree, &options(View::Top));
    let plan = ink(&top, 400);
    let (x0, x1) = (
        plan.iter().map(|p| p.0).min().unwrap(),
        plan.iter().map(|p| p.0).max().unwrap(),
    );
    let (y0, y1) = (
        plan.iter().map(|p| p.1).min().unwrap(),
        plan.iter().map(|p| p.1).max().unwrap(),
    );
    assert!(((x1 - x0) as i32 - (y1 - y0) as i32).abs() <= 2);
    let centre = ((x0 + x1) / 2, (y0 + y1) / 2);
    assert!(plan.contains(&centre));
    // Along each of the 8 rib directions the star is inked half-way out; between them it is not.
    let reach = (x1 - x0) as f32 / 2.0;
    for k in 0..16 {
        let a = std::f32::consts::TAU * k as f32 / 16.0;
        let at = (
            (centre.0 as f32 + 0.6 * reach * a.cos()).round() as u32,
            (centre.1 as f32 - 0.6 * reach * a.sin()).round() as u32,
        );
        let near = plan
            .iter()
            .any(|p| p.0.abs_diff(at.0) <= 1 && p.1.abs_diff(at.1) <= 1);
        assert_eq!(near, k % 2 == 0, "direction {k}");
    }
    // Perspective and overlay draw something inside the page.
    for view in [View::Perspective, View::Overlay, View::Side] {
        let px = ink(&draw_rgba(&tree, &options(view)), 400);
        assert!(px.len() > 500, "{view:?}");
    }
}

#[test]
fn overlay_is_front_and_side_together() {
    // One branch along +X and one along +Y: front sees the first sideways, side the second;
    // the overlay shows both, folded onto the same side.
    let fractal = FractalParams {
        depth: 1,
        theta1: 60.0,
        theta2: 60.0,
        ..Default::default()
    }
    .build()
    .unwrap();
    let s = fractal.skeleton();
    let opts = |view| DrawOptions {
        view,
        width: 300,
        height: 300,
        depth_cue: false,
        ..Default::default()
    };
    let count = |view| ink(&draw_rgba(&s, &opts(view)), 300).len();
    let (front, side, overlay) = (count(View::Front), count(View::Side), count(View::Overlay));
    assert!(front > 100 && side > 100);
    // θ1 = θ2: both daughters coincide (Nagel's figure 21), so every view draws one fork.
    assert!(overlay as f32 > 0.9 * front.min(side) as f32);
}

#[test]
fn svg_is_well_formed_and_scaled() {
    let svg = draw_svg(&whisk(), &DrawOptions::default());
    let mut reader = quick_xml::Reader::from_str(&svg);
    let (mut paths, mut depth) = (0, 0i32);
    loop {
        match reader.read_event().expect("well-formed SVG") {
            quick_xml::events::Event::Start(e) => {
                depth += 1;
                paths += (e.name().as_ref() == "path") as i32;
            }
            quick_xml::events::Event::Empty(e) => paths += (e.name().as_ref() == "path") as i32,
            quick_xml::events::Event::End(_) => depth -= 1,
            quick_xml::events::Event::Eof => break,
            _ => {}
        }
    }
    assert_eq!(depth, 0);
    assert!(paths >= 2, "{paths}");
    // An 8 m tree on a 1024 px page: the scale bar is a round 1-2-5 length.
    assert!(
        svg.contains(">2 m</text>") || svg.contains(">1 m</text>"),
        "{svg}"
    );
}
