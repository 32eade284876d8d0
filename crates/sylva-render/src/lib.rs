//! Renders Sylva trees: a sun with a shadow map (the tree's shadow on the ground and inside its
//! crown), a sky term, two-sided translucent leaves, 4x multisampling, a ground with a metre
//! grid and a 1.8 m person for scale.
//!
//! Three backends draw the same picture from the same [`Scene`]: wgpu on Vulkan, Metal or
//! DX12 (a GPU, or Mesa's lavapipe); wgpu on OpenGL (Mesa's llvmpipe on a machine with no
//! Vulkan driver); and a CPU rasteriser in this crate when no driver answers. Any GPU failure,
//! at start-up or mid-frame, becomes a [`RenderError`] and the renderer carries on on the CPU.
//! `SYLVA_RENDERER=vulkan|gl|cpu` picks a backend instead of the first that works.
//!
//! ```no_run
//! let params = sylva::species::builtin("quaking_aspen").unwrap();
//! let skeleton = sylva::generate(&params, &Default::default()).unwrap();
//! let mesh = sylva::mesh::mesh_tree(&skeleton, &Default::default());
//! let renderer = sylva_render::Renderer::new_headless().unwrap();
//! let tree = renderer.upload(&mesh);
//! let scene = sylva_render::Scene::new(&tree, params.bark_color, params.leaf_color);
//! let picture = renderer.render(&scene, &sylva_render::View::named(sylva_render::ViewKind::Front), 640, 480).unwrap();
//! assert_eq!(picture.rgba.len(), 640 * 480 * 4);
//! ```
#![deny(missing_docs)]

pub mod bench;
mod camera;
pub mod caption;
pub mod chart;
pub mod coverage;
mod cpu;
mod forest;
mod frame;
pub mod glb_scene;
mod gpu;
mod impostor;
mod lod_chain;
mod props;
mod scene;
pub mod site;
pub mod street;
mod tree;

pub use camera::{Camera, ViewKind};
pub use forest::ForestOnGpu;
pub use frame::SKY_SRGB;
pub use lod_chain::{LodChain, bake_impostor, lod_chain};
pub use props::{PERSON_HEIGHT, PropMesh, Vertex, ground, person};
pub use scene::{DEFAULT_PRIMITIVE_BUDGET, FrameStats, Placement, Scene, Stand, View};
pub use tree::RenderTree;

use gpu::{Api, GpuRenderer};
use impostor::Atlas;
use std::sync::{Arc, Mutex, OnceLock};
use sylva::mesh::TreeMesh;
use tree::TreeData;

/// Rendering failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No graphics adapter of the kind asked for.
    #[error(
        "no graphics adapter found ({0}); on a machine without a GPU install Mesa's drivers \
         (Debian: mesa-vulkan-drivers for Vulkan, libegl1 and libgl1-mesa-dri for OpenGL), or \
         set SYLVA_RENDERER=cpu"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device, or lacks what the shaders need.
    #[error("cannot open the graphics device: {0}")]
    Device(String),
    /// The device failed: a validation error, out of memory, or lost.
    #[error("the graphics device failed while {what}: {message}")]
    Gpu {
        /// What the renderer was doing.
        what: &'static str,
        /// What the driver said.
        message: String,
    },
    /// A picture size the renderer cannot make.
    #[error("picture size {width}x{height} is not allowed: each side must be 16..={max}")]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// Largest side.
        max: u32,
    },
    /// A tree to draw could not be made.
    #[error("making the tree to draw: {0}")]
    Tree(String),
    /// A chart could not be drawn.
    #[error("drawing a chart: {0}")]
    Chart(String),
    /// Something only a GPU can do (drawing into a window's texture).
    #[error("{0} needs a GPU device")]
    NeedsGpu(&'static str),
    /// `SYLVA_RENDERER` names no backend.
    #[error("SYLVA_RENDERER={0}: expected auto, vulkan, gl or cpu")]
    Choice(String),
    /// A picture that cannot be encoded (its pixels do not fill its size).
    #[error("cannot encode the picture as PNG: {0}")]
    Encode(String),
    /// A model that cannot be written.
    #[error(transparent)]
    Export(#[from] sylva::ExportError),
}

impl RenderError {
    /// Why, without the advice: for an adapter not found, only the backends wgpu tried (its
    /// message also lists every backend it was not asked for or was built without).
    fn reason(&self) -> String {
        match self {
            RenderError::NoAdapter(wgpu) => {
                let tried: Vec<&str> = wgpu
                    .split([';', ',', '(', ')'])
                    .map(str::trim)
                    .filter(|part| {
                        !part.is_empty()
                            && !part.ends_with("not requested")
                            && !part.ends_with("not compiled in")
                            && !part.starts_with("No suitable graphics adapter")
                    })
                    .collect();
                if tried.is_empty() {
                    "no adapter".into()
                } else {
                    tried.join(", ")
                }
            }
            other => other.to_string(),
        }
    }
}

/// Colour format of headless pictures.
pub const PICTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Largest side of a picture drawn on the CPU.
const CPU_MAX_SIDE: u32 = 8192;

/// A rendered picture: RGBA, 8 bits per channel (sRGB), rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// 4 bytes per pixel.
    pub rgba: Vec<u8>,
    /// What was drawn.
    pub stats: FrameStats,
}

impl Picture {
    /// The picture as PNG bytes (RGBA, 8 bits per channel).
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        let mut bytes = Vec::new();
        image::ImageEncoder::write_image(
            image::codecs::png::PngEncoder::new(&mut bytes),
            &self.rgba,
            self.width,
            self.height,
            image::ExtendedColorType::Rgba8,
        )
        .map_err(|e| RenderError::Encode(e.to_string()))?;
        Ok(bytes)
    }

    /// Mean absolute difference of two pictures of one size, over every pixel's R, G and B,
    /// in steps of 255: how far apart range degradation leaves a picture. `None` when their
    /// sizes differ.
    pub fn mean_difference(&self, other: &Picture) -> Option<f64> {
        if (self.width, self.height) != (other.width, other.height) || self.rgba.is_empty() {
            return None;
        }
        let sum: u64 = self
            .rgba
            .chunks_exact(4)
            .zip(other.rgba.chunks_exact(4))
            .map(|(a, b)| (0..3).map(|i| a[i].abs_diff(b[i]) as u64).sum::<u64>())
            .sum();
        Some(sum as f64 / (self.rgba.len() / 4 * 3) as f64)
    }

    /// The RGB of one pixel.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = ((y * self.width + x) * 4) as usize;
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2]]
    }
}

/// Which backend draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// wgpu on a GPU or a software Vulkan/OpenGL driver.
    Gpu,
    /// The built-in CPU rasteriser.
    Cpu,
}

/// Which backend `SYLVA_RENDERER` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Choice {
    /// Vulkan/Metal/DX12, else OpenGL, else the CPU (the default).
    Auto,
    /// Vulkan, Metal or DX12 only.
    Native,
    /// OpenGL only.
    Gl,
    /// The CPU rasteriser.
    Cpu,
}

impl Choice {
    /// Reads `SYLVA_RENDERER` (unset or empty: [`Choice::Auto`]).
    pub fn from_env() -> Result<Self, RenderError> {
        let value = std::env::var("SYLVA_RENDERER").unwrap_or_default();
        match value.trim().to_ascii_lowercase().as_str() {
            "" | "auto" => Ok(Self::Auto),
            "vulkan" | "metal" | "dx12" | "native" => Ok(Self::Native),
            "gl" | "opengl" | "gles" => Ok(Self::Gl),
            "cpu" => Ok(Self::Cpu),
            _ => Err(RenderError::Choice(value)),
        }
    }
}

type Notice = Box<dyn Fn(&str) + Send + Sync>;

/// Draws trees on the best backend there is; reusable across frames.
pub struct Renderer {
    gpu: Option<GpuRenderer>,
    /// Set once the GPU has failed: from then on every picture is drawn on the CPU.
    gpu_failed: OnceLock<String>,
    notice: Notice,
    /// The impostors of the last scene drawn, and what they were baked for.
    impostors: Mutex<Option<(impostor::Key, Arc<Atlas>)>>,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("adapter", &self.adapter_name())
            .finish()
    }
}

impl Renderer {
    /// A renderer without a window, on the backend `SYLVA_RENDERER` asks for (by default the
    /// first that works: Vulkan/Metal/DX12, OpenGL, the CPU).
    pub fn new_headless() -> Result<Self, RenderError> {
        Self::headless(Choice::from_env()?, |_| {})
    }

    /// As [`Renderer::new_headless`], calling `notice` with one line whenever the renderer
    /// falls back to the CPU (no driver answered, or the GPU failed).
    pub fn headless(
        choice: Choice,
        notice: impl Fn(&str) + Send + Sync + 'static,
    ) -> Result<Self, RenderError> {
        let notice: Notice = Box::new(notice);
        let gpu = match choice {
            Choice::Cpu => None,
            Choice::Native => Some(GpuRenderer::headless(Api::Native)?),
            Choice::Gl => Some(GpuRenderer::headless(Api::Gl)?),
            Choice::Auto => match GpuRenderer::headless(Api::Native) {
                Ok(g) => Some(g),
                Err(native) => match GpuRenderer::headless(Api::Gl) {
                    Ok(g) => Some(g),
                    Err(gl) => {
                        notice(&format!(
                            "no graphics driver answered (Vulkan: {}; OpenGL: {}); drawing with \
                             the CPU rasteriser. For the GPU renderers install Mesa's drivers \
                             (Debian: mesa-vulkan-drivers, or libegl1 and libgl1-mesa-dri)",
                            native.reason(),
                            gl.reason()
                        ));
                        None
                    }
                },
            },
        };
        Ok(Self {
            gpu,
            gpu_failed: OnceLock::new(),
            notice,
            impostors: Mutex::new(None),
        })
    }

    /// The CPU rasteriser alone.
    pub fn cpu() -> Self {
        Self {
            gpu: None,
            gpu_failed: OnceLock::new(),
            notice: Box::new(|_| {}),
            impostors: Mutex::new(None),
        }
    }

    /// A renderer on an existing device (the viewer's), drawing into `target_format`.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        target_format: wgpu::TextureFormat,
        adapter: &wgpu::AdapterInfo,
    ) -> Result<Self, RenderError> {
        Ok(Self {
            gpu: Some(GpuRenderer::new(device, queue, target_format, adapter)?),
            gpu_failed: OnceLock::new(),
            notice: Box::new(|_| {}),
            impostors: Mutex::new(None),
        })
    }

    /// The GPU, while it works.
    fn gpu(&self) -> Option<&GpuRenderer> {
        self.gpu
            .as_ref()
            .filter(|_| self.gpu_failed.get().is_none())
    }

    /// Which backend draws the next picture.
    pub fn backend(&self) -> Backend {
        match self.gpu() {
            Some(_) => Backend::Gpu,
            None => Backend::Cpu,
        }
    }

    /// What draws: the adapter and its API (e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)"),
    /// or "CPU rasteriser".
    pub fn adapter_name(&self) -> String {
        match self.gpu() {
            Some(g) => g.name.clone(),
            None => "CPU rasteriser".into(),
        }
    }

    /// Why the GPU is no longer used, once it failed.
    pub fn gpu_failure(&self) -> Option<&str> {
        self.gpu_failed.get().map(String::as_str)
    }

    /// The device (for the viewer's own textures); `None` on the CPU.
    pub fn device(&self) -> Option<&wgpu::Device> {
        self.gpu().map(GpuRenderer::device)
    }

    fn fall_back(&self, error: &RenderError) {
        if self.gpu_failed.set(error.to_string()).is_ok() {
            (self.notice)(&format!("{error}; drawing with the CPU rasteriser instead"));
        }
    }

    fn store(&self, data: TreeData, triangles: usize) -> RenderTree {
        let mut tree = tree::prepare(data, triangles);
        if let Some(gpu) = self.gpu() {
            match gpu.upload(&tree.data) {
                Ok(buffers) => tree.gpu = Some(buffers),
                Err(e) => self.fall_back(&e),
            }
        }
        tree
    }

    /// Uploads a tree mesh (Z up, metres, as the mesher makes it).
    pub fn upload(&self, mesh: &TreeMesh) -> RenderTree {
        self.store(TreeData::from_mesh(mesh), mesh.triangle_count())
    }

    /// Uploads a tree's flowers, if it has any, as a tree of their own whose leaves they are:
    /// a scene draws it as a second stand at the tree's placements, in the flowers' colour.
    pub fn upload_flowers(&self, mesh: &TreeMesh) -> Option<RenderTree> {
        if mesh.flowers.indices.is_empty() {
            return None;
        }
        let data = TreeData {
            leaves: tree::mesh_data(&mesh.flowers),
            ..Default::default()
        };
        Some(self.store(data, mesh.flowers.triangle_count()))
    }

    /// Uploads a tree stored for range degradation: drawn whole up close, and as fewer
    /// meshes, lines and points as it recedes (when the scene's `use_lod` is on).
    /// The tree is kept as it is stored (under a megabyte for a Black Tupelo): the GPU
    /// rebuilds its triangles every frame.
    pub fn upload_lod(&self, lod: &sylva::lod::LodTree) -> RenderTree {
        let data = TreeData {
            lod: Some(lod.clone()),
            ..Default::default()
        };
        self.store(data, lod.triangle_count())
    }

    /// The impostors of `scene`, baked on first use and kept while the same trees are drawn
    /// under the same sun; `None` when it draws none.
    fn impostors(&self, scene: &Scene) -> Result<Option<Arc<Atlas>>, RenderError> {
        let Some(key) = impostor::Key::of(scene) else {
            return Ok(None);
        };
        let kept = |cache: &Option<(impostor::Key, Arc<Atlas>)>| {
            cache
                .as_ref()
                .filter(|(k, _)| *k == key)
                .map(|(_, a)| a.clone())
        };
        if let Some(atlas) = self.impostors.lock().ok().and_then(|c| kept(&c)) {
            return Ok(Some(atlas));
        }
        // Baked without holding the lock: the bake draws through this renderer.
        let max = self.gpu().map_or(CPU_MAX_SIDE, |g| g.max_texture());
        let atlas = Arc::new(impostor::bake(self, scene, max)?);
        if let Ok(mut cache) = self.impostors.lock() {
            *cache = Some((key, atlas.clone()));
        }
        Ok(Some(atlas))
    }

    /// Makes ready what drawing `scene` needs beyond its trees: the impostors of its trees
    /// stored for range, baked from 8 sides under its sun (a few small pictures; otherwise
    /// the first frame bakes them).
    pub fn prepare(&self, scene: &Scene) -> Result<(), RenderError> {
        self.impostors(scene).map(|_| ())
    }

    /// Draws `scene` into `resolve` (a single-sample view of this renderer's target format and
    /// `width` x `height`), e.g. the viewer's texture. Needs the GPU.
    pub fn render_into(
        &self,
        scene: &Scene,
        view: &View,
        resolve: &wgpu::TextureView,
        width: u32,
        height: u32,
    ) -> Result<FrameStats, RenderError> {
        let what = "drawing into a window";
        let gpu = match (&self.gpu, self.gpu_failed.get()) {
            (Some(g), None) => g,
            (Some(_), Some(reason)) => {
                return Err(RenderError::Gpu {
                    what,
                    message: reason.clone(),
                });
            }
            (None, _) => return Err(RenderError::NeedsGpu(what)),
        };
        let atlas = self.impostors(scene)?;
        let camera = scene.camera(view, width as f32 / height as f32);
        let frame = frame::plan(scene, &camera, (view.azimuth, height), atlas.as_deref());
        gpu.render_into(&frame, resolve, width, height)?;
        Ok(frame.stats)
    }

    /// `count` views of `scene` turned evenly about it from `base`, laid out on one sheet as
    /// square as it can be (a turntable's contact sheet).
    pub fn turntable(
        &self,
        scene: &Scene,
        base: &View,
        count: u32,
        (width, height): (u32, u32),
    ) -> Result<Picture, RenderError> {
        let views = (0..count)
            .map(|i| {
                let view = View {
                    azimuth: base.azimuth + 360.0 * i as f32 / count as f32,
                    ..*base
                };
                self.render(scene, &view, width, height)
            })
            .collect::<Result<Vec<Picture>, _>>()?;
        let columns = (views.len() as f64).sqrt().ceil() as u32;
        Ok(caption::tile(&views, columns, 0, 255))
    }

    /// Draws `scene` from `view` into a new picture of `width` x `height` pixels: on the GPU
    /// while it works, else on the CPU.
    pub fn render(
        &self,
        scene: &Scene,
        view: &View,
        width: u32,
        height: u32,
    ) -> Result<Picture, RenderError> {
        let max = self.gpu().map_or(CPU_MAX_SIDE, |g| g.max_texture());
        if !(16..=max).contains(&width) || !(16..=max).contains(&height) {
            return Err(RenderError::Size { width, height, max });
        }
        let atlas = self.impostors(scene)?;
        let camera = scene.camera(view, width as f32 / height as f32);
        let frame = frame::plan(scene, &camera, (view.azimuth, height), atlas.as_deref());
        if let Some(gpu) = self.gpu() {
            match gpu.render(&frame, width, height) {
                Ok(rgba) => {
                    return Ok(Picture {
                        width,
                        height,
                        rgba,
                        stats: frame.stats,
                    });
                }
                Err(e) => self.fall_back(&e),
            }
        }
        Ok(Picture {
            width,
            height,
            rgba: cpu::render(&frame, width, height),
            stats: frame.stats,
        })
    }
}

#[cfg(test)]
mod tests;
