//! Renders Sylva trees with wgpu: a sun with a shadow map (the tree's shadow on the ground and
//! inside its crown), a sky term, two-sided translucent leaves, 4x multisampling, a ground with
//! a metre grid and a 1.8 m person for scale.
//!
//! Headless rendering works on machines without a GPU through Mesa (lavapipe Vulkan, or the GL
//! software fallback). The viewer shares the same [`Renderer`] on its own device.
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

mod camera;
mod props;
mod scene;

pub use camera::{Camera, ViewKind};
pub use props::{PERSON_HEIGHT, PropMesh, Vertex, ground, person};
pub use scene::{FrameStats, Placement, Scene, Stand, View};

// WebGPU's clip space (y up, depth 0..1) is glam's `directx` convention.
use glam::Vec3;
use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use sylva::mesh::{Mesh, TreeMesh};
use wgpu::util::DeviceExt;

/// Rendering failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No graphics adapter, not even a software one.
    #[error(
        "no graphics adapter found ({0}); on a machine without a GPU install Mesa's software drivers \
         (Debian: mesa-vulkan-drivers, or libgl1-mesa-dri for the GL fallback)"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("cannot open the graphics device: {0}")]
    Device(String),
    /// Reading the picture back failed.
    #[error("cannot read the rendered picture back: {0}")]
    Readback(String),
    /// A picture size the device cannot make.
    #[error("picture size {width}x{height} is not allowed: each side must be 16..={max}")]
    Size {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// Device limit.
        max: u32,
    },
}

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
    /// The RGB of one pixel.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = ((y * self.width + x) * 4) as usize;
        [self.rgba[i], self.rgba[i + 1], self.rgba[i + 2]]
    }
}

/// A tree on the GPU: bark and leaves, with their bounds.
#[derive(Debug)]
pub struct GpuTree {
    bark: GpuMesh,
    leaves: GpuMesh,
    /// Rank-major lists for drawing at range (trees uploaded with [`Renderer::upload_lod`]).
    lod: Option<GpuLod>,
    /// Lowest corner of the tree's bounds (metres, Z up).
    pub lo: Vec3,
    /// Highest corner.
    pub hi: Vec3,
    /// Triangles uploaded (bark + leaves).
    pub triangles: usize,
}

/// The GPU side of a [`sylva::lod::LodTree`]: per list, rank-major triangle indices (into the
/// bark or leaf vertices) and line/point positions; the CPU keeps only what choosing needs.
#[derive(Debug)]
struct GpuLod {
    indices: [wgpu::Buffer; 4],
    points: [wgpu::Buffer; 4],
    /// The lists without their big buffers: enough to choose draw ranges.
    choice: [sylva::lod::LodList; 4],
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Primitive {
    Triangles,
    Lines,
    Points,
}

/// One draw call: a range of indexed triangles, or of line/point vertices, for a range of
/// instances (tree copies; the props use instance 0, which stands at the origin).
struct Draw<'a> {
    primitive: Primitive,
    vertices: &'a wgpu::Buffer,
    indices: Option<&'a wgpu::Buffer>,
    range: std::ops::Range<u32>,
    /// What the shadow pass draws of the same buffers.
    shadow: std::ops::Range<u32>,
    instances: std::ops::Range<u32>,
    material: &'a wgpu::BindGroup,
}

impl<'a> Draw<'a> {
    fn mesh(
        mesh: &'a GpuMesh,
        material: &'a wgpu::BindGroup,
        instances: std::ops::Range<u32>,
    ) -> Self {
        Self {
            primitive: Primitive::Triangles,
            vertices: &mesh.vertices,
            indices: Some(&mesh.indices),
            range: 0..mesh.count,
            shadow: 0..mesh.count,
            instances,
            material,
        }
    }

    fn record(&self, pass: &mut wgpu::RenderPass<'_>, instances: &wgpu::Buffer) {
        self.record_range(pass, instances, self.range.clone());
    }

    fn record_shadow(&self, pass: &mut wgpu::RenderPass<'_>, instances: &wgpu::Buffer) {
        self.record_range(pass, instances, self.shadow.clone());
    }

    fn record_range(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        instances: &wgpu::Buffer,
        range: std::ops::Range<u32>,
    ) {
        if range.is_empty() || self.instances.is_empty() {
            return;
        }
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_vertex_buffer(1, instances.slice(..));
        match self.indices {
            Some(indices) => {
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(range, 0, self.instances.clone());
            }
            None => pass.draw(range, self.instances.clone()),
        }
    }

    /// Primitives this draw makes.
    fn primitives(&self) -> usize {
        let n = self.range.len() * self.instances.len();
        match self.primitive {
            Primitive::Triangles => n / 3,
            Primitive::Lines => n / 2,
            Primitive::Points => n,
        }
    }
}

/// A copy of a tree as the vertex shader reads it: offset and scale, cos and sin of the turn.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct InstanceData {
    place: [f32; 4],
    turn: [f32; 2],
    /// Lines and points: how many items each drawn one stands for (items not meshed / items
    /// drawn flat), so that together they cover what the whole list would.
    stands_for: [f32; 2],
}

impl From<&Placement> for InstanceData {
    fn from(p: &Placement) -> Self {
        let (s, c) = p.turn.sin_cos();
        Self {
            place: [p.position.x, p.position.y, p.position.z, p.scale],
            turn: [c, s],
            stands_for: [1.0, 0.0],
        }
    }
}

/// A line or point vertex: position, the size of what it stands for (stem diameter or blade
/// area) and a unit direction for lighting (stem axis or blade normal).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FlatVertex {
    position: [f32; 3],
    size: f32,
    normal: [i8; 4],
}

const INSTANCE_ATTRIBUTES: [wgpu::VertexAttribute; 3] = [
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x4,
        offset: 0,
        shader_location: 4,
    },
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x2,
        offset: 16,
        shader_location: 5,
    },
    wgpu::VertexAttribute {
        format: wgpu::VertexFormat::Float32x2,
        offset: 24,
        shader_location: 6,
    },
];

const INSTANCE_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<InstanceData>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &INSTANCE_ATTRIBUTES,
};

/// The six planes of a view-projection's frustum (WebGPU depth 0..1), as `n.p + d >= 0` inside.
fn frustum_planes(m: glam::Mat4) -> [glam::Vec4; 6] {
    let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
    [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| p / p.truncate().length())
}

fn sphere_visible(planes: &[glam::Vec4; 6], centre: Vec3, radius: f32) -> bool {
    planes
        .iter()
        .all(|p| p.truncate().dot(centre) + p.w >= -radius)
}

#[derive(Debug)]
struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    light_view_proj: [[f32; 4]; 4],
    sun_dir: [f32; 4],
    sun_color: [f32; 4],
    sky_color: [f32; 4],
    ground_bounce: [f32; 4],
    shadow: [f32; 4],
    /// xyz: the eye; w: pixels per metre at 1 m from it.
    eye: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Material {
    color: [f32; 4],
    kind: [f32; 4],
}

const SAMPLES: u32 = 4;
const SHADOW_SIZE: u32 = 2048;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Colour format of headless pictures.
pub const PICTURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Background (sRGB): a pale sky.
pub const SKY_SRGB: [f32; 3] = [0.80, 0.87, 0.94];
const GROUND_SRGB: [f32; 3] = [0.55, 0.52, 0.45];
const PERSON_SRGB: [f32; 3] = [0.35, 0.38, 0.45];

/// Depth test and write shared by every pipeline (the shadow pass adds a slope bias).
fn depth_test(bias: wgpu::DepthBiasState) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias,
    }
}

/// Multisampling of every colour pass.
const MSAA: wgpu::MultisampleState = wgpu::MultisampleState {
    count: SAMPLES,
    mask: !0,
    alpha_to_coverage_enabled: false,
};

fn linear(c: [f32; 3]) -> [f32; 4] {
    let l = |c: f32| {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    [l(c[0]), l(c[1]), l(c[2]), 1.0]
}

/// Draws trees. Holds the device, the pipelines and the shadow map; reusable across frames.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    target_format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    line_pipeline: wgpu::RenderPipeline,
    point_pipeline: wgpu::RenderPipeline,
    shadow_pipeline: wgpu::RenderPipeline,
    shadow_line_pipeline: wgpu::RenderPipeline,
    shadow_point_pipeline: wgpu::RenderPipeline,
    globals: wgpu::Buffer,
    globals_group: wgpu::BindGroup,
    shadow_group: wgpu::BindGroup,
    shadow_view: wgpu::TextureView,
    material_layout: wgpu::BindGroupLayout,
    /// Name of the adapter (e.g. "llvmpipe" on a machine without a GPU).
    pub adapter_name: String,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("adapter", &self.adapter_name)
            .finish()
    }
}

impl Renderer {
    /// A renderer without a window, on the best adapter found (a GPU, else Mesa's software
    /// rasterisers).
    pub fn new_headless() -> Result<Self, RenderError> {
        // Native APIs first; OpenGL (Mesa's llvmpipe on a machine without a GPU) only when
        // nothing else answers, since probing it prints EGL warnings.
        let find = |backends| {
            let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
                backends,
                ..wgpu::InstanceDescriptor::new_without_display_handle()
            });
            pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: None,
                apply_limit_buckets: false,
            }))
        };
        let adapter = find(wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12)
            .or_else(|_| find(wgpu::Backends::GL))
            .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let name = adapter.get_info().name;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("sylva"),
            required_features: wgpu::Features::empty(),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Self::from_device(device, queue, PICTURE_FORMAT, name))
    }

    /// A renderer on an existing device (the viewer's), drawing into `target_format`.
    pub fn from_device(
        device: wgpu::Device,
        queue: wgpu::Queue,
        target_format: wgpu::TextureFormat,
        adapter_name: String,
    ) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("shader.wgsl"));
        let globals_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("globals"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
            ],
        });
        let material_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("material"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        // The shadow pass writes the shadow map, so its bind group must not also bind it.
        let shadow_globals_layout =
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("shadow globals"),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            });
        let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow"),
            bind_group_layouts: &[Some(&shadow_globals_layout)],
            immediate_size: 0,
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("tree"),
            bind_group_layouts: &[Some(&globals_layout), Some(&material_layout)],
            immediate_size: 0,
        });
        let vertex_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32],
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("tree"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(vertex_layout.clone()), Some(INSTANCE_LAYOUT)],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(depth_test(Default::default())),
            multisample: MSAA,
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(target_format.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        let flat_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<FlatVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32, 2 => Snorm8x4],
        };
        let flat = |topology, label| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some("vs_flat"),
                    compilation_options: Default::default(),
                    buffers: &[Some(flat_layout.clone()), Some(INSTANCE_LAYOUT)],
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    ..Default::default()
                },
                depth_stencil: Some(depth_test(Default::default())),
                // A line or point covers as many of a pixel's samples as the stems or leaves it
                // stands for would (the fragment shader writes the sample mask).
                multisample: MSAA,
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some("fs_flat"),
                    compilation_options: Default::default(),
                    targets: &[Some(target_format.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let line_pipeline = flat(wgpu::PrimitiveTopology::LineList, "lines");
        let point_pipeline = flat(wgpu::PrimitiveTopology::PointList, "points");
        // Shadows of meshes, and of the lines and points that stand in for far stems and leaves.
        let shadow = |entry, layout: &wgpu::VertexBufferLayout, topology| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("shadow"),
                layout: Some(&shadow_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    buffers: &[Some(layout.clone()), Some(INSTANCE_LAYOUT)],
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    cull_mode: None,
                    ..Default::default()
                },
                // Slope bias is for triangles only (WebGPU refuses it for lines and points).
                depth_stencil: Some(depth_test(
                    if topology == wgpu::PrimitiveTopology::TriangleList {
                        wgpu::DepthBiasState {
                            constant: 2,
                            slope_scale: 2.0,
                            clamp: 0.0,
                        }
                    } else {
                        Default::default()
                    },
                )),
                multisample: Default::default(),
                fragment: None,
                multiview_mask: None,
                cache: None,
            })
        };
        let shadow_pipeline = shadow(
            "vs_shadow",
            &vertex_layout,
            wgpu::PrimitiveTopology::TriangleList,
        );
        let shadow_line_pipeline = shadow(
            "vs_shadow_flat",
            &flat_layout,
            wgpu::PrimitiveTopology::LineList,
        );
        let shadow_point_pipeline = shadow(
            "vs_shadow_flat",
            &flat_layout,
            wgpu::PrimitiveTopology::PointList,
        );
        let shadow_texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow map"),
            size: wgpu::Extent3d {
                width: SHADOW_SIZE,
                height: SHADOW_SIZE,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let shadow_view = shadow_texture.create_view(&Default::default());
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let globals_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("globals"),
            layout: &globals_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&shadow_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&shadow_sampler),
                },
            ],
        });
        let shadow_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow globals"),
            layout: &shadow_globals_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            }],
        });
        Self {
            device,
            queue,
            target_format,
            shadow_group,
            pipeline,
            line_pipeline,
            point_pipeline,
            shadow_pipeline,
            shadow_line_pipeline,
            shadow_point_pipeline,
            globals,
            globals_group,
            shadow_view,
            material_layout,
            adapter_name,
        }
    }

    /// The device (for the viewer's own textures).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    fn upload_vertices(&self, label: &str, vertices: &[Vertex], indices: &[u32]) -> GpuMesh {
        // wgpu rejects zero-sized buffers: keep one dummy element for empty meshes.
        let dummy_v = [Vertex {
            position: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            shade: 1.0,
        }];
        let v = if vertices.is_empty() {
            &dummy_v[..]
        } else {
            vertices
        };
        let i = if indices.is_empty() {
            &[0u32, 0, 0][..]
        } else {
            indices
        };
        GpuMesh {
            vertices: self
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytemuck::cast_slice(v),
                    usage: wgpu::BufferUsages::VERTEX,
                }),
            indices: self
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytemuck::cast_slice(i),
                    usage: wgpu::BufferUsages::INDEX,
                }),
            count: indices.len() as u32,
        }
    }

    fn upload_mesh(&self, label: &str, mesh: &Mesh) -> GpuMesh {
        let vertices: Vec<Vertex> = mesh
            .positions
            .iter()
            .zip(&mesh.normals)
            .enumerate()
            .map(|(i, (p, n))| Vertex {
                position: *p,
                normal: *n,
                shade: mesh.shades.get(i).copied().unwrap_or(1.0),
            })
            .collect();
        self.upload_vertices(label, &vertices, &mesh.indices)
    }

    /// Uploads a tree mesh (Z up, metres, as the mesher makes it).
    pub fn upload(&self, mesh: &TreeMesh) -> GpuTree {
        let (lo, hi) = [&mesh.bark, &mesh.leaves]
            .iter()
            .filter_map(|m| m.bounds())
            .fold(
                (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
                |(lo, hi), (a, b)| (lo.min(Vec3::from(a)), hi.max(Vec3::from(b))),
            );
        let (lo, hi) = if lo.x <= hi.x {
            (lo, hi)
        } else {
            (Vec3::ZERO, Vec3::ONE)
        };
        GpuTree {
            bark: self.upload_mesh("bark", &mesh.bark),
            leaves: self.upload_mesh("leaves", &mesh.leaves),
            lod: None,
            lo,
            hi,
            triangles: mesh.triangle_count(),
        }
    }

    /// Uploads a tree stored for range degradation: drawn whole up close, and as fewer
    /// meshes, lines and points as it recedes (when the scene's `use_lod` is on).
    pub fn upload_lod(&self, lod: &sylva::lod::LodTree) -> GpuTree {
        let mut tree = self.upload(&lod.mesh);
        tree.triangles = lod.triangle_count();
        let buffer = |label, contents: &[u8], usage| {
            // wgpu refuses empty buffers: keep 12 zero bytes for an empty list.
            let contents = if contents.is_empty() {
                &[0u8; 12][..]
            } else {
                contents
            };
            self.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage,
                })
        };
        tree.lod = Some(GpuLod {
            indices: std::array::from_fn(|i| {
                buffer(
                    "lod indices",
                    bytemuck::cast_slice(&lod.lists[i].indices),
                    wgpu::BufferUsages::INDEX,
                )
            }),
            points: std::array::from_fn(|i| {
                let l = &lod.lists[i];
                let snorm = |v: f32| (v.clamp(-1.0, 1.0) * 127.0).round() as i8;
                let flat: Vec<FlatVertex> = l
                    .points
                    .iter()
                    .zip(&l.sizes)
                    .zip(&l.normals)
                    .map(|((p, &size), n)| FlatVertex {
                        position: *p,
                        size,
                        normal: [snorm(n[0]), snorm(n[1]), snorm(n[2]), 0],
                    })
                    .collect();
                buffer(
                    "lod points",
                    bytemuck::cast_slice(&flat),
                    wgpu::BufferUsages::VERTEX,
                )
            }),
            choice: std::array::from_fn(|i| {
                let l = &lod.lists[i];
                sylva::lod::LodList {
                    mass: l.mass,
                    items: l.items,
                    indices: Vec::new(),
                    index_prefix: l.index_prefix.clone(),
                    points: Vec::new(),
                    sizes: Vec::new(),
                    normals: Vec::new(),
                    diameter: l.diameter,
                    length: l.length,
                }
            }),
        });
        tree
    }

    fn material(&self, colour: [f32; 3], kind: f32) -> wgpu::BindGroup {
        let buffer = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("material"),
                contents: bytemuck::bytes_of(&Material {
                    color: linear(colour),
                    kind: [kind, 0.0, 0.0, 0.0],
                }),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("material"),
            layout: &self.material_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        })
    }

    /// Records the shadow and main passes of `scene` into `encoder`, drawing into `target`
    /// (a `SAMPLES`-sample view) resolved into `resolve`.
    #[allow(clippy::too_many_arguments)]
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &Scene,
        camera: &Camera,
        target: &wgpu::TextureView,
        resolve: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        azimuth: f32,
        height: u32,
    ) -> FrameStats {
        let (lo, hi) = scene.bounds(azimuth);
        let centre = (lo + hi) / 2.0;
        let radius = ((hi - lo).length() / 2.0).max(0.5);
        // The sun's view: orthographic over a disc of ground around the trees, where their
        // shadows fall.
        let reach = radius * 2.2;
        let light_view = look_at_mat4(centre + scene.sun * radius * 4.0, centre, Vec3::Z);
        let light_proj = directx::orthographic(-reach, reach, -reach, reach, 0.1, radius * 8.0);
        let view_proj = camera.view_proj();
        let globals = Globals {
            view_proj: view_proj.to_cols_array_2d(),
            light_view_proj: (light_proj * light_view).to_cols_array_2d(),
            sun_dir: scene.sun.normalize().extend(0.0).to_array(),
            sun_color: [2.6, 2.45, 2.2, 0.0],
            sky_color: [0.42, 0.5, 0.62, 0.0],
            ground_bounce: [0.18, 0.17, 0.14, 0.0],
            shadow: [1.0 / SHADOW_SIZE as f32, 0.0015, 0.0, 0.0],
            eye: camera
                .eye
                .extend(height as f32 / (2.0 * (camera.fov_y / 2.0).tan()))
                .to_array(),
        };
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        let ground_mesh = ground(centre, radius * 3.0);
        let person_mesh = person(scene.person_feet(azimuth), azimuth);
        let ground_gpu =
            self.upload_vertices("ground", &ground_mesh.vertices, &ground_mesh.indices);
        let person_gpu =
            self.upload_vertices("person", &person_mesh.vertices, &person_mesh.indices);
        let materials: Vec<_> = scene
            .stands
            .iter()
            .map(|s| (self.material(s.bark, 0.0), self.material(s.leaves, 1.0)))
            .collect();
        let ground_mat = self.material(GROUND_SRGB, 2.0);
        let person_mat = self.material(PERSON_SRGB, 0.0);
        let planes = frustum_planes(view_proj);
        let viewer = sylva::lod::Viewer {
            image_height: height as f32,
            fov_y: camera.fov_y.to_degrees(),
            quality: scene.lod_quality,
        };
        // Instance 0 stands at the origin for the props; the trees' copies follow.
        let mut instances = vec![InstanceData::from(&Placement::ORIGIN)];
        let mut stats = FrameStats::default();
        let mut draws: Vec<Draw> = Vec::new();
        for (stand, (bark, leaves)) in scene.stands.iter().zip(&materials) {
            let tree = stand.tree;
            stats.trees += stand.placements.len();
            let first = instances.len() as u32;
            for p in stand.placements.iter() {
                let (c, r) = stand.sphere(p);
                if !sphere_visible(&planes, c, r) {
                    continue;
                }
                stats.trees_drawn += 1;
                let Some(lod) = tree.lod.as_ref().filter(|_| scene.use_lod) else {
                    instances.push(p.into());
                    continue;
                };
                // Each copy's range, and the picture it lands in, choose what of each list is
                // drawn (Weber & Penn section 5); a copy scaled up looks as the original nearer.
                let range = camera.eye.distance(c) / p.scale.max(1e-3);
                for (i, list) in lod.choice.iter().enumerate() {
                    let is_leaves = i == 3;
                    if is_leaves && !scene.show_leaves {
                        continue;
                    }
                    let pick = list.select(is_leaves, range, &viewer);
                    // One instance entry per list: its lines or points stand for its items
                    // that are neither meshed nor drawn.
                    let index = instances.len() as u32;
                    let per_item = if is_leaves { 1 } else { 2 };
                    let flat = (list.items * per_item) as f32 - pick.points.start as f32;
                    instances.push(InstanceData {
                        stands_for: [flat / pick.points.len().max(1) as f32, 0.0],
                        ..p.into()
                    });
                    let (mesh, material) = if is_leaves {
                        (&tree.leaves, leaves)
                    } else {
                        (&tree.bark, bark)
                    };
                    draws.push(Draw {
                        primitive: Primitive::Triangles,
                        vertices: &mesh.vertices,
                        indices: Some(&lod.indices[i]),
                        shadow: pick.triangles.clone(),
                        range: pick.triangles,
                        instances: index..index + 1,
                        material,
                    });
                    draws.push(Draw {
                        primitive: if is_leaves {
                            Primitive::Points
                        } else {
                            Primitive::Lines
                        },
                        vertices: &lod.points[i],
                        indices: None,
                        // Shadows of every leaf not meshed: points are cheap, and a crown
                        // shading itself with only the drawn few would look too bright.
                        shadow: if is_leaves {
                            pick.points.start..list.items as u32
                        } else {
                            pick.points.clone()
                        },
                        range: pick.points,
                        instances: index..index + 1,
                        material,
                    });
                }
            }
            let copies = first..instances.len() as u32;
            match (&tree.lod, scene.use_lod) {
                (Some(_), true) => {}
                (Some(lod), false) => {
                    // Every list whole: one instanced draw per list for every visible copy.
                    for (i, list) in lod.choice.iter().enumerate() {
                        if i == 3 && !scene.show_leaves {
                            continue;
                        }
                        let (mesh, material) = if i == 3 {
                            (&tree.leaves, leaves)
                        } else {
                            (&tree.bark, bark)
                        };
                        draws.push(Draw {
                            primitive: Primitive::Triangles,
                            vertices: &mesh.vertices,
                            indices: Some(&lod.indices[i]),
                            range: 0..list.index_prefix.last().copied().unwrap_or(0),
                            shadow: 0..list.index_prefix.last().copied().unwrap_or(0),
                            instances: copies.clone(),
                            material,
                        });
                    }
                }
                (None, _) => {
                    // Whole meshes: one instanced draw per mesh for every visible copy.
                    draws.push(Draw::mesh(&tree.bark, bark, copies.clone()));
                    if scene.show_leaves {
                        draws.push(Draw::mesh(&tree.leaves, leaves, copies));
                    }
                }
            }
        }
        draws.retain(|d| !(d.instances.is_empty() || d.range.is_empty() && d.shadow.is_empty()));
        for d in &draws {
            stats.draw_calls += 1;
            match d.primitive {
                Primitive::Triangles => stats.triangles += d.primitives(),
                Primitive::Lines => stats.lines += d.primitives(),
                Primitive::Points => stats.points += d.primitives(),
            }
        }
        let instance_buffer = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("instances"),
                contents: bytemuck::cast_slice(&instances),
                usage: wgpu::BufferUsages::VERTEX,
            });
        if scene.show_person {
            draws.push(Draw::mesh(&person_gpu, &person_mat, 0..1));
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.shadow_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.shadow_group, &[]);
            // Far trees' lines and points cast shadows too, or a forest's shade would thin
            // out with the camera's range.
            for d in &draws {
                pass.set_pipeline(match d.primitive {
                    Primitive::Triangles => &self.shadow_pipeline,
                    Primitive::Lines => &self.shadow_line_pipeline,
                    Primitive::Points => &self.shadow_point_pipeline,
                });
                d.record_shadow(&mut pass, &instance_buffer);
            }
        }
        if scene.show_ground {
            draws.push(Draw::mesh(&ground_gpu, &ground_mat, 0..1));
        }
        // Transparent pictures clear to the leaves' colour, so that edge pixels blend
        // towards it rather than towards the sky.
        let sky = match (scene.transparent, scene.stands.first()) {
            (true, Some(s)) => {
                let [r, g, b, _] = linear(s.leaves);
                [r * 0.5, g * 0.5, b * 0.5, 0.0]
            }
            (true, None) => [0.0; 4],
            (false, _) => linear(SKY_SRGB),
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("main"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: Some(resolve),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: sky[0] as f64,
                        g: sky[1] as f64,
                        b: sky[2] as f64,
                        a: sky[3] as f64,
                    }),
                    store: wgpu::StoreOp::Discard,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.globals_group, &[]);
        for d in &draws {
            pass.set_pipeline(match d.primitive {
                Primitive::Triangles => &self.pipeline,
                Primitive::Lines => &self.line_pipeline,
                Primitive::Points => &self.point_pipeline,
            });
            pass.set_bind_group(1, d.material, &[]);
            d.record(&mut pass, &instance_buffer);
        }
        stats
    }

    /// Creates the multisampled colour and depth targets for a `width` x `height` picture.
    fn targets(&self, width: u32, height: u32) -> (wgpu::TextureView, wgpu::TextureView) {
        let make = |format, label| {
            self.device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width,
                        height,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: SAMPLES,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        (
            make(self.target_format, "colour (msaa)"),
            make(DEPTH, "depth"),
        )
    }

    /// Draws `scene` into `resolve` (a single-sample view of this renderer's target format and
    /// `width` x `height`), e.g. the viewer's texture.
    pub fn render_into(
        &self,
        scene: &Scene,
        view: &View,
        resolve: &wgpu::TextureView,
        width: u32,
        height: u32,
    ) -> FrameStats {
        let camera = scene.camera(view, width as f32 / height as f32);
        let (colour, depth) = self.targets(width, height);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let stats = self.encode(
            &mut encoder,
            scene,
            &camera,
            &colour,
            resolve,
            &depth,
            view.azimuth,
            height,
        );
        self.queue.submit([encoder.finish()]);
        stats
    }

    /// Draws `scene` from `view` into a new picture of `width` x `height` pixels.
    pub fn render(
        &self,
        scene: &Scene,
        view: &View,
        width: u32,
        height: u32,
    ) -> Result<Picture, RenderError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if !(16..=max).contains(&width) || !(16..=max).contains(&height) {
            return Err(RenderError::Size { width, height, max });
        }
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("picture"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.target_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let resolve = texture.create_view(&Default::default());
        let camera = scene.camera(view, width as f32 / height as f32);
        let (colour, depth) = self.targets(width, height);
        let row = (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: (row * height) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let stats = self.encode(
            &mut encoder,
            scene,
            &camera,
            &colour,
            &resolve,
            &depth,
            view.azimuth,
            height,
        );
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(height),
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        let slice = readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        rx.recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mut rgba = Vec::with_capacity((width * height * 4) as usize);
        for y in 0..height {
            let start = (y * row) as usize;
            rgba.extend_from_slice(&data[start..start + (width * 4) as usize]);
        }
        drop(data);
        readback.unmap();
        Ok(Picture {
            width,
            height,
            rgba,
            stats,
        })
    }
}
