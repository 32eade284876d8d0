//! Draws every leaf shape side by side, seen from above, into `leaf_shapes.png` (or the path
//! given as the first argument): a quick look at the outlines the mesher instances.

use glam::{Quat, Vec3};
use image::ImageEncoder;
use sylva::mesh::{MeshOptions, mesh_tree};
use sylva::preview::{PreviewOptions, View, render_preview};
use sylva::{Leaf, LeafShape, Skeleton, StemId};

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "leaf_shapes.png".into());
    let leaves = LeafShape::ALL
        .iter()
        .enumerate()
        .map(|(i, &shape)| Leaf {
            light: 1.0,
            position: Vec3::new(i as f32 * 1.3, 0.0, 0.0),
            // Blade along +Y, normal up: seen from above.
            orientation: Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2),
            length: 1.0,
            width: 1.0,
            shape,
            stem: StemId(0),
        })
        .collect();
    let skeleton = Skeleton {
        leaves,
        ..Default::default()
    };
    let mesh = mesh_tree(&skeleton, &MeshOptions::default());
    let options = PreviewOptions {
        width: 1200,
        height: 180,
        view: View::Top,
        ..Default::default()
    };
    let picture = render_preview(&mesh, &options);
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(
            &picture.rgb,
            picture.width,
            picture.height,
            image::ExtendedColorType::Rgb8,
        )
        .expect("PNG encoding");
    std::fs::write(&out, bytes).expect("write the picture");
    println!("wrote {out}");
}
