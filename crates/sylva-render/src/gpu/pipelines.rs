//! The render pipelines, their layouts and the shadow map, built once per device.

use crate::frame::{Globals, InstanceData, SHADOW_SIZE};
use crate::props::Vertex;

/// Samples per pixel of every colour pass.
pub(crate) const SAMPLES: u32 = 4;
pub(crate) const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

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

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A stored tree's segments, read one per instance: two rings of (x, y, z, radius) as 16-bit
/// fractions and a packed frame (`sylva::lod::packed::Segment`).
const SEGMENT_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<sylva::lod::packed::Segment>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![8 => Uint16x4, 9 => Uint32, 10 => Uint16x4, 11 => Uint32],
};

/// Its leaf cards, one per instance (`sylva::lod::packed::Leaf`).
const CARD_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<sylva::lod::packed::Leaf>() as u64,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![8 => Uint16x4, 9 => Uint32],
};

/// A leaf outline's vertices: position and normal at unit size.
const TEMPLATE_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 24,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3],
};

/// Bytes between two draws' entries in the copy buffer (WebGPU's largest uniform offset
/// alignment).
pub(crate) const COPY_STRIDE: u64 = 256;

/// The pipelines of one kind of primitive: the colour pass and the shadow pass, and the
/// colour pass of a copy dissolving into its impostor.
pub(crate) struct Pair {
    pub colour: wgpu::RenderPipeline,
    pub shadow: wgpu::RenderPipeline,
    /// `colour` dropping the pixels the impostor takes: a pipeline of its own because a
    /// shader that may discard loses early depth testing on llvmpipe.
    pub fading: wgpu::RenderPipeline,
}

/// The shaders: shader.wgsl, the shadow filter and the impostors' (which use its functions;
/// WGSL's declarations may come in any order).
const SHADER: &str = concat!(
    include_str!("../shader.wgsl"),
    include_str!("../shadow.wgsl"),
    include_str!("../impostor.wgsl")
);

/// Most vertices around a stored stem's ring (`sylva::mesh::MeshOptions::ring_vertices`).
const MAX_SIDES: u32 = 256;

/// Every leaf outline's template on the device, where each lies in its buffers, and the
/// triangles of a tube's sides.
pub(crate) struct Templates {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    /// Per shape of `sylva::LeafShape::ALL`: first index, index count, base vertex.
    pub ranges: Vec<(u32, u32, i32)>,
    /// A tube's quads, side after side: vertex `2 i + end` is vertex i of the near (0) or
    /// far (1) ring, so the first `6 sides` indices draw any tube, and each vertex is shaded
    /// once rather than for every triangle that uses it.
    pub tube: wgpu::Buffer,
}

impl Templates {
    fn new(device: &wgpu::Device) -> Self {
        let (mut vertices, mut indices, mut ranges) = (Vec::<f32>::new(), Vec::new(), Vec::new());
        for &shape in &sylva::LeafShape::ALL {
            let t = sylva::mesh::leaf_template(shape);
            ranges.push((
                indices.len() as u32,
                t.indices.len() as u32,
                (vertices.len() / 6) as i32,
            ));
            for (p, n) in t.positions.iter().zip(&t.normals) {
                vertices.extend_from_slice(&[p.x, p.y, p.z, n.x, n.y, n.z]);
            }
            indices.extend_from_slice(&t.indices);
        }
        let make = |label, bytes: &[u8], usage| super::buffers::buffer(device, label, bytes, usage);
        let tube: Vec<u32> = (0..MAX_SIDES)
            .flat_map(|i| {
                let (a, b) = (2 * i, 2 * i + 1);
                [a, a + 2, b + 2, a, b + 2, b]
            })
            .collect();
        Self {
            tube: make(
                "tube sides",
                bytemuck::cast_slice(&tube),
                wgpu::BufferUsages::INDEX,
            ),
            vertices: make(
                "leaf outlines",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: make(
                "leaf outlines",
                bytemuck::cast_slice(&indices),
                wgpu::BufferUsages::INDEX,
            ),
            ranges,
        }
    }
}

/// Pipelines, bind groups and the shadow map of one device.
pub(crate) struct Pipelines {
    pub templates: Templates,
    pub triangles: wgpu::RenderPipeline,
    /// Whole leaf meshes: `triangles` lit as leaves.
    pub leaf_triangles: wgpu::RenderPipeline,
    pub shadow_triangles: wgpu::RenderPipeline,
    /// Stored trees: segments as tubes and as lines, leaves as cards and as points.
    pub tubes: Pair,
    pub axes: Pair,
    pub cards: Pair,
    pub dots: Pair,
    /// Impostors: a quad per copy showing its views in the atlas (bind group 3).
    pub impostors: wgpu::RenderPipeline,
    pub atlas_layout: wgpu::BindGroupLayout,
    pub atlas_sampler: wgpu::Sampler,
    pub copy_layout: wgpu::BindGroupLayout,
    pub globals: wgpu::Buffer,
    pub globals_group: wgpu::BindGroup,
    pub shadow_group: wgpu::BindGroup,
    pub shadow_view: wgpu::TextureView,
    pub material_layout: wgpu::BindGroupLayout,
}

impl Pipelines {
    /// Builds everything for `target_format`. `sample_mask` says whether the fragment shader
    /// may write the sample mask: OpenGL cannot (naga writes `gl_SampleMask` with the wrong
    /// type, gfx-rs/wgpu#4335), so there far stems and leaves shade each sample on its own
    /// and drop the ones outside their share instead.
    pub fn new(
        device: &wgpu::Device,
        target_format: wgpu::TextureFormat,
        sample_mask: bool,
    ) -> Self {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sylva"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let globals_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("globals"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                // Far stems and leaves are lit per vertex, shadows included.
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
            ],
        });
        let material_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("material"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)],
        });
        // Stored trees: the copy and its records' scales, one entry per draw.
        let copy_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("copy"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                // The fragment stage reads the dissolve's share.
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        // The shadow pass writes the shadow map, so its bind group must not also bind it.
        let shadow_globals_layout =
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("shadow globals"),
                entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX)],
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
        let stored_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("stored tree"),
            bind_group_layouts: &[
                Some(&globals_layout),
                Some(&material_layout),
                Some(&copy_layout),
            ],
            immediate_size: 0,
        });
        let stored_shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("stored tree shadow"),
            bind_group_layouts: &[Some(&shadow_globals_layout), None, Some(&copy_layout)],
            immediate_size: 0,
        });
        let vertex_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32],
        };
        let colour = |label,
                      vs,
                      fs,
                      pipeline_layout: &wgpu::PipelineLayout,
                      buffers: &[Option<wgpu::VertexBufferLayout>],
                      topology| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    cull_mode: None,
                    ..Default::default()
                },
                depth_stencil: Some(depth_test(Default::default())),
                multisample: MSAA,
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(target_format.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let mesh = [Some(vertex_layout.clone()), Some(INSTANCE_LAYOUT)];
        let triangles = colour(
            "tree",
            "vs_main",
            "fs_main",
            &layout,
            &mesh,
            wgpu::PrimitiveTopology::TriangleList,
        );
        let leaf_triangles = colour(
            "leaves",
            "vs_main",
            "fs_leaf",
            &layout,
            &mesh,
            wgpu::PrimitiveTopology::TriangleList,
        );
        // A line or point covers as many of a pixel's samples as the stems or leaves it
        // stands for would.
        let (axis, dot, fs_flat) = if sample_mask {
            ("vs_axis", "vs_dot", ("fs_flat", "fs_flat_fading"))
        } else {
            (
                "vs_axis_per_sample",
                "vs_dot_per_sample",
                ("fs_flat_per_sample", "fs_flat_per_sample_fading"),
            )
        };
        // Shadows of meshes, and of the lines and points that stand in for far stems and leaves.
        let shadow = |entry,
                      pipeline_layout: &wgpu::PipelineLayout,
                      buffers: &[Option<wgpu::VertexBufferLayout>],
                      topology| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("shadow"),
                layout: Some(pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    buffers,
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
        let shadow_triangles = shadow(
            "vs_shadow",
            &shadow_layout,
            &mesh,
            wgpu::PrimitiveTopology::TriangleList,
        );
        let pair = |label,
                    vs,
                    (fs, fading): (&'static str, &'static str),
                    shadow_vs,
                    buffers: &[Option<wgpu::VertexBufferLayout>],
                    topology| Pair {
            colour: colour(label, vs, fs, &stored_layout, buffers, topology),
            shadow: shadow(shadow_vs, &stored_shadow_layout, buffers, topology),
            fading: colour(label, vs, fading, &stored_layout, buffers, topology),
        };
        let segments = [Some(SEGMENT_LAYOUT)];
        let cards = [Some(TEMPLATE_LAYOUT), Some(CARD_LAYOUT)];
        let dots = [Some(CARD_LAYOUT)];
        let tubes = pair(
            "tubes",
            "vs_tube",
            ("fs_main", "fs_main_fading"),
            "vs_shadow_tube",
            &segments,
            wgpu::PrimitiveTopology::TriangleList,
        );
        let axes = pair(
            "axes",
            axis,
            fs_flat,
            "vs_shadow_axis",
            &segments,
            wgpu::PrimitiveTopology::LineList,
        );
        let cards = pair(
            "cards",
            "vs_card",
            ("fs_leaf", "fs_leaf_fading"),
            "vs_shadow_card",
            &cards,
            wgpu::PrimitiveTopology::TriangleList,
        );
        let dots = pair(
            "dots",
            dot,
            fs_flat,
            "vs_shadow_dot",
            &dots,
            wgpu::PrimitiveTopology::PointList,
        );
        let atlas_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("impostor atlas"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let impostor_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("impostors"),
            bind_group_layouts: &[
                Some(&globals_layout),
                Some(&material_layout),
                Some(&copy_layout),
                Some(&atlas_layout),
            ],
            immediate_size: 0,
        });
        let impostors = colour(
            "impostors",
            "vs_impostor",
            "fs_impostor",
            &impostor_layout,
            &[],
            wgpu::PrimitiveTopology::TriangleList,
        );
        let atlas_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("impostor atlas"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
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
            templates: Templates::new(device),
            triangles,
            leaf_triangles,
            shadow_triangles,
            tubes,
            axes,
            cards,
            dots,
            impostors,
            atlas_layout,
            atlas_sampler,
            copy_layout,
            globals,
            globals_group,
            shadow_group,
            shadow_view,
            material_layout,
        }
    }
}
