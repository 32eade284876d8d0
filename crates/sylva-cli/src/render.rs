//! `sylva render`: pictures of a tree with the wgpu renderer, one view, a turntable contact
//! sheet, or wind animation frames.

use crate::args::{RenderArgs, RenderView};
use crate::commands::{load_params, mesh_options};
use anyhow::{Context, Result, bail};
use image::ImageEncoder;
use std::path::{Path, PathBuf};
use sylva::export::write_atomically;
use sylva::mesh::{Mesh, TreeMesh, mesh_tree};
use sylva::{GenerateOptions, Wind};
use sylva_render::{Picture, Renderer, Scene, View, ViewKind};

/// Parses `WxH`.
pub fn parse_size(text: &str) -> Result<(u32, u32)> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--size {text}: expected WIDTHxHEIGHT, e.g. 1280x720"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (16..=8192).contains(v))
            .with_context(|| {
                format!("--size {text}: each side must be a whole number of pixels, 16..8192")
            })
    };
    Ok((parse(w)?, parse(h)?))
}

pub fn encode_png(path: &Path, width: u32, height: u32, rgba: &[u8]) -> Result<()> {
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(rgba, width, height, image::ExtendedColorType::Rgba8)
        .context("encoding PNG")?;
    write_atomically(path, &bytes)?;
    Ok(())
}

/// `out.png` -> `out-0007.png`.
fn numbered(path: &Path, index: u32) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!("{stem}-{index:04}.png"))
}

/// A GLB read back: the mesh and the sRGB base colours of its bark and leaf materials.
pub struct GlbTree {
    pub mesh: TreeMesh,
    pub bark: [f32; 3],
    pub leaves: [f32; 3],
}

fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.0031308 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Reads a GLB written by `sylva generate` (or any glTF with triangle primitives) back into a
/// tree mesh: primitives whose material is named `leaves` are leaves, the rest bark; Y up in
/// the file becomes Z up.
pub fn read_glb(path: &Path) -> Result<GlbTree> {
    let mut colours = (sylva::params::DEFAULT_BARK, sylva::params::DEFAULT_LEAVES);
    let gltf = gltf::Gltf::open(path)
        .with_context(|| format!("{}: not a readable glTF file", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = gltf::import_buffers(&gltf.document, Some(base), gltf.blob.clone())
        .with_context(|| format!("{}: cannot load its buffers", path.display()))?;
    let mut mesh = TreeMesh::default();
    let z_up = |p: [f32; 3]| [p[0], -p[2], p[1]];
    for node in gltf.document.nodes() {
        let Some(gmesh) = node.mesh() else { continue };
        let transform = glam::Mat4::from_cols_array_2d(&node.transform().matrix());
        for prim in gmesh.primitives() {
            if prim.mode() != gltf::mesh::Mode::Triangles {
                continue;
            }
            let [r, g, b, _] = prim.material().pbr_metallic_roughness().base_color_factor();
            let srgb = [r, g, b].map(linear_to_srgb);
            let part: &mut Mesh = if prim.material().name() == Some("leaves") {
                colours.1 = srgb;
                &mut mesh.leaves
            } else {
                colours.0 = srgb;
                &mut mesh.bark
            };
            let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let base = part.positions.len() as u32;
            let positions: Vec<[f32; 3]> = positions
                .map(|p| z_up(transform.transform_point3(glam::Vec3::from(p)).to_array()))
                .collect();
            let normals: Vec<[f32; 3]> = match reader.read_normals() {
                Some(n) => n
                    .map(|n| {
                        z_up(
                            transform
                                .transform_vector3(glam::Vec3::from(n))
                                .normalize_or_zero()
                                .to_array(),
                        )
                    })
                    .collect(),
                None => vec![[0.0, 0.0, 1.0]; positions.len()],
            };
            let count = positions.len() as u32;
            // COLOR_0 (a grown tree's leaf light classes) becomes the shade; the other
            // primitives of a part with shades are fully lit.
            let shades: Option<Vec<f32>> = reader
                .read_colors(0)
                .map(|c| c.into_rgb_f32().map(|c| c[1].clamp(0.0, 1.0)).collect())
                .filter(|c: &Vec<f32>| c.len() == count as usize);
            match shades {
                Some(c) => {
                    part.shades.resize(base as usize, 1.0);
                    part.shades.extend(c);
                }
                None if !part.shades.is_empty() => {
                    part.shades.resize(base as usize + count as usize, 1.0);
                }
                None => {}
            }
            part.positions.extend(positions);
            part.normals.extend(normals);
            part.uvs
                .extend(std::iter::repeat_n([0.0, 0.0], count as usize));
            match reader.read_indices() {
                Some(idx) => part
                    .indices
                    .extend(idx.into_u32().filter(|&i| i < count).map(|i| i + base)),
                None => part.indices.extend(base..base + count),
            }
            // Indices that pointed outside the primitive were dropped: keep whole triangles only.
            part.indices.truncate(part.indices.len() / 3 * 3);
        }
    }
    if mesh.triangle_count() == 0 {
        bail!("{}: no triangles to render", path.display());
    }
    Ok(GlbTree {
        mesh,
        bark: colours.0,
        leaves: colours.1,
    })
}

fn view_of(v: RenderView) -> View {
    View::named(match v {
        RenderView::Front => ViewKind::Front,
        RenderView::Side => ViewKind::Side,
        RenderView::Top => ViewKind::Top,
        RenderView::Iso => ViewKind::Iso,
    })
}

/// Lays `pictures` out in a grid on one sheet, as square as it can be.
fn contact_sheet(pictures: &[Picture]) -> Picture {
    let columns = (pictures.len() as f64).sqrt().ceil() as u32;
    crate::caption::tile(pictures, columns, 0, 255)
}

/// Where the pictured tree comes from.
enum TreeSource {
    /// A finished model, drawn as it is.
    Glb(Box<GlbTree>),
    /// A species, generated (and re-formed by the wind) for each frame.
    Species(Box<sylva::TreeParams>),
}

impl TreeSource {
    fn colours(&self) -> ([f32; 3], [f32; 3]) {
        match self {
            TreeSource::Glb(g) => (g.bark, g.leaves),
            TreeSource::Species(p) => (p.bark_color, p.leaf_color),
        }
    }

    fn mesh_at(&self, args: &RenderArgs, time: f64) -> Result<TreeMesh> {
        match self {
            TreeSource::Glb(g) => Ok(g.mesh.clone()),
            TreeSource::Species(params) => {
                let options = GenerateOptions {
                    wind: Wind {
                        speed: args.wind,
                        gust: args.gust,
                        time,
                    },
                    ..args.tree.options()
                };
                let skeleton = sylva::generate(params, &options)?;
                Ok(mesh_tree(
                    &skeleton,
                    &mesh_options(params, args.tree.quality),
                ))
            }
        }
    }
}

/// The headless renderer `SYLVA_RENDERER` asks for (by default the first that works: Vulkan,
/// OpenGL, the CPU), saying on stderr when pictures are drawn on the CPU instead of a GPU.
pub fn headless() -> Result<Renderer> {
    let choice = sylva_render::Choice::from_env()?;
    Ok(Renderer::headless(choice, |note| {
        eprintln!("sylva: {note}")
    })?)
}

/// One picture of a tree mesh from a named view, with ground and person (the `--preview` of
/// `sylva generate`).
pub fn picture(
    mesh: &TreeMesh,
    bark: [f32; 3],
    leaves: [f32; 3],
    view: RenderView,
    width: u32,
    height: u32,
) -> Result<Picture> {
    let renderer = headless()?;
    let tree = renderer.upload(mesh);
    let scene = Scene::new(&tree, bark, leaves);
    Ok(renderer.render(&scene, &view_of(view), width, height)?)
}

pub fn render(args: &RenderArgs) -> Result<()> {
    let (width, height) = parse_size(&args.size)?;
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    {
        bail!(
            "output {}: pictures are written as PNG; use a .png file name",
            args.output.display()
        );
    }
    if args.turntable == Some(0) || args.frames == Some(0) {
        bail!("--turntable and --frames need at least 1");
    }
    if !(1.0..=170.0).contains(&args.fov) {
        bail!("--fov {}: expected 1..170 degrees", args.fov);
    }
    if !(args.fps > 0.0 && args.fps <= 1000.0) {
        bail!("--fps {}: expected 0..1000", args.fps);
    }
    let is_glb = Path::new(&args.input)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
    if is_glb && (args.frames.is_some() || args.wind != 0.0 || args.gust != 0.0) {
        bail!("wind needs the species, not a finished .glb: render the species instead");
    }
    let renderer = headless()?;
    if crate::forest::is_forest_file(Path::new(&args.input)) {
        return crate::render_forest::render_forest(
            args,
            &renderer,
            view_of(args.view),
            (width, height),
        );
    }
    // One tree per frame: a GLB as it is, a species regenerated for each moment of the wind.
    let frames = args.frames.unwrap_or(1);
    let source = if is_glb {
        TreeSource::Glb(Box::new(read_glb(Path::new(&args.input))?))
    } else {
        TreeSource::Species(Box::new(load_params(&args.input, &args.tree.set)?))
    };
    let colours = source.colours();
    for frame in 0..frames {
        let time = args.time + frame as f64 / args.fps;
        let mesh = source.mesh_at(args, time)?;
        let tree = renderer.upload(&mesh);
        let mut scene = Scene::new(&tree, colours.0, colours.1);
        scene.show_leaves = !args.tree.no_leaves;
        scene.show_ground = !args.bare;
        scene.show_person = !args.bare;
        let mut base = view_of(args.view);
        base.fov_y = args.fov;
        let picture = match args.turntable {
            Some(n) => {
                let views: Result<Vec<Picture>> = (0..n)
                    .map(|i| {
                        let view = View {
                            azimuth: base.azimuth + 360.0 * i as f32 / n as f32,
                            ..base
                        };
                        Ok(renderer.render(&scene, &view, width, height)?)
                    })
                    .collect();
                contact_sheet(&views?)
            }
            None => renderer.render(&scene, &base, width, height)?,
        };
        let path = if args.frames.is_some() {
            numbered(&args.output, frame)
        } else {
            args.output.clone()
        };
        encode_png(&path, picture.width, picture.height, &picture.rgba)?;
        println!(
            "wrote {} ({}x{}, {} triangles, {})",
            path.display(),
            picture.width,
            picture.height,
            tree.triangles,
            renderer.adapter_name()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_names() {
        assert_eq!(parse_size("1280x720").unwrap(), (1280, 720));
        assert!(parse_size("12x720").is_err());
        assert!(parse_size("wide").is_err());
        assert_eq!(
            numbered(Path::new("dir/sway.png"), 3),
            PathBuf::from("dir/sway-0003.png")
        );
    }
}
