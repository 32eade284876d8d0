//! `sylva render`: pictures of a tree with the wgpu renderer, one view, a turntable contact
//! sheet, or wind animation frames.

use crate::args::{RenderArgs, RenderView};
use crate::glb_scene::{GlbScene, read_glb_scene};
use crate::shared::{encode_png, parse_size};
use crate::shared::{load_params, mesh_options};
use anyhow::{Context, Result, bail};
use std::borrow::Cow;
use std::path::{Path, PathBuf};
use sylva::mesh::{TreeMesh, mesh_tree};
use sylva::{GenerateOptions, Wind};
use sylva_render::{Picture, RenderTree, Renderer, Scene, Stand, View, ViewKind};

/// `out.png` -> `out-0007.png`.
fn numbered(path: &Path, index: u32) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!("{stem}-{index:04}.png"))
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

/// The trees of a GLB's scene on the renderer: each distinct mesh once, its copies placed.
pub struct UploadedScene {
    trees: Vec<RenderTree>,
    glb: GlbScene,
}

impl UploadedScene {
    pub fn new(renderer: &Renderer, glb: GlbScene) -> Self {
        let trees = glb
            .models
            .iter()
            .map(|m| renderer.upload(&m.mesh))
            .collect();
        Self { trees, glb }
    }

    /// The scene with ground and person, as a single tree's picture shows them.
    pub fn scene(&self) -> Scene<'_> {
        let stands = self
            .trees
            .iter()
            .zip(&self.glb.models)
            .map(|(tree, m)| Stand {
                tree,
                bark: m.bark,
                leaves: m.leaves,
                placements: Cow::Borrowed(&m.placements),
            })
            .collect();
        Scene {
            show_person: true,
            ..Scene::forest(stands)
        }
    }

    /// Triangles drawn, every copy counted.
    pub fn triangles(&self) -> usize {
        self.glb.triangles_placed()
    }

    /// The scene's bounds (metres, Z up).
    pub fn bounds(&self) -> (glam::Vec3, glam::Vec3) {
        self.scene().tree_bounds()
    }
}

/// The tree a species makes at a moment of the wind.
fn species_mesh(params: &sylva::TreeParams, args: &RenderArgs, time: f64) -> Result<TreeMesh> {
    let options = GenerateOptions {
        wind: Wind {
            speed: args.wind,
            gust: args.gust,
            time,
        },
        ..args.tree.options()
    };
    let skeleton =
        sylva::generate(params, &options).with_context(|| format!("species {}", args.input))?;
    Ok(mesh_tree(
        &skeleton,
        &mesh_options(params, args.tree.quality),
    ))
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
    // A GLB as it is; a species regenerated for each moment of the wind.
    if is_glb {
        let uploaded = UploadedScene::new(&renderer, read_glb_scene(Path::new(&args.input))?);
        let scene = uploaded.scene();
        let picture = draw(&renderer, args, scene, (width, height))?;
        return write_picture(&args.output, &picture, uploaded.triangles(), &renderer);
    }
    let params = load_params(&args.input, &args.tree.set)?;
    for frame in 0..args.frames.unwrap_or(1) {
        let time = args.time + frame as f64 / args.fps;
        let mesh = species_mesh(&params, args, time)?;
        let tree = renderer.upload(&mesh);
        let scene = Scene::new(&tree, params.bark_color, params.leaf_color);
        let picture = draw(&renderer, args, scene, (width, height))?;
        let path = if args.frames.is_some() {
            numbered(&args.output, frame)
        } else {
            args.output.clone()
        };
        write_picture(&path, &picture, tree.triangles, &renderer)?;
    }
    Ok(())
}

/// One view of `scene`, or a turntable sheet of several, as the flags ask.
fn draw(
    renderer: &Renderer,
    args: &RenderArgs,
    mut scene: Scene,
    (width, height): (u32, u32),
) -> Result<Picture> {
    scene.show_leaves = !args.tree.no_leaves;
    scene.show_ground = !args.bare;
    scene.show_person = !args.bare;
    let mut base = view_of(args.view);
    base.fov_y = args.fov;
    Ok(match args.turntable {
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
    })
}

fn write_picture(
    path: &Path,
    picture: &Picture,
    triangles: usize,
    renderer: &Renderer,
) -> Result<()> {
    encode_png(path, picture.width, picture.height, &picture.rgba)?;
    println!(
        "wrote {} ({}x{}, {} triangles, {})",
        path.display(),
        picture.width,
        picture.height,
        triangles,
        renderer.adapter_name()
    );
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
