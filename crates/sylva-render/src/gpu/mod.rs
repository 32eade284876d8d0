//! The wgpu backend: a device (a GPU, lavapipe, or OpenGL through Mesa), its pipelines, and
//! frames recorded from a [`Frame`] plan. Every call that can fail on the device runs inside
//! error scopes, and uncaptured errors and device loss are recorded rather than panicking, so
//! that any failure reaches the caller as a [`RenderError`].

mod atlas;
mod buffers;
mod pipelines;
mod record;

use buffers::buffer;
use pipelines::{DEPTH, Pipelines, SAMPLES};
use record::{Props, Source, record};

use crate::RenderError;
use crate::frame::Frame;
use crate::props::PropMesh;
use crate::tree::{TreeBuffers, TreeData};
use std::sync::{Arc, Mutex};

/// A device with Sylva's pipelines.
pub(crate) struct GpuRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    target_format: wgpu::TextureFormat,
    pipelines: Pipelines,
    /// The adapter and its API, e.g. "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)".
    pub name: String,
    /// The first error no scope caught, or the device's loss.
    failure: Arc<Mutex<Option<String>>>,
    max_buffer: u64,
    /// The last impostor atlas uploaded, under its id.
    atlas: Mutex<Option<(u64, wgpu::BindGroup)>>,
    /// Held from writing a frame's globals to submitting its passes. The globals buffer and
    /// the shadow map are the pipelines' own, one each: a `write_buffer` lands at the next
    /// submit, whoever makes it, so two threads drawing at once would each draw with the
    /// other's camera and lights (`sylva sweep --picture` draws a species a thread).
    drawing: Mutex<()>,
}

/// Which wgpu backends to try.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Api {
    /// Vulkan, Metal or DX12.
    Native,
    /// OpenGL / GLES (Mesa's llvmpipe on a machine without a GPU).
    Gl,
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    let api = match info.backend {
        wgpu::Backend::Vulkan => "Vulkan",
        wgpu::Backend::Metal => "Metal",
        wgpu::Backend::Dx12 => "DX12",
        wgpu::Backend::Gl => "OpenGL",
        _ => "other",
    };
    format!("{} ({api})", info.name)
}

impl GpuRenderer {
    /// A device without a window on the best adapter of `api`.
    pub fn headless(api: Api) -> Result<Self, RenderError> {
        let backends = match api {
            Api::Native => wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12,
            Api::Gl => wgpu::Backends::GL,
        };
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .map_err(|e| RenderError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        let supported = adapter.limits();
        // Downlevel limits (what OpenGL ES 3 guarantees) with the adapter's own picture and
        // buffer sizes.
        let limits = wgpu::Limits {
            max_buffer_size: supported.max_buffer_size,
            ..wgpu::Limits::downlevel_defaults().using_resolution(supported)
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("sylva"),
            required_features: wgpu::Features::empty(),
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(format!("{}: {e}", describe(&info))))?;
        check_adapter(&adapter)?;
        Self::new(device, queue, crate::PICTURE_FORMAT, &info)
    }

    /// Sylva's pipelines on an existing device drawing into `target_format`.
    pub fn new(
        device: wgpu::Device,
        queue: wgpu::Queue,
        target_format: wgpu::TextureFormat,
        info: &wgpu::AdapterInfo,
    ) -> Result<Self, RenderError> {
        let failure = Arc::new(Mutex::new(None));
        let record = |failure: &Arc<Mutex<Option<String>>>| {
            let failure = failure.clone();
            move |message: String| {
                if let Ok(mut f) = failure.lock() {
                    f.get_or_insert(message);
                }
            }
        };
        let on_error = record(&failure);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| on_error(e.to_string())));
        let on_lost = record(&failure);
        device.set_device_lost_callback(move |reason, message| {
            on_lost(format!("the device was lost ({reason:?}): {message}"))
        });
        let max_buffer = device.limits().max_buffer_size;
        let name = describe(info);
        let sample_mask = info.backend != wgpu::Backend::Gl;
        let pipelines = scoped(&device, &failure, "building the pipelines", || {
            Pipelines::new(&device, target_format, sample_mask)
        })
        .map_err(|e| RenderError::Device(format!("{name}: {e}")))?;
        Ok(Self {
            device,
            queue,
            target_format,
            pipelines,
            name,
            failure,
            max_buffer,
            atlas: Mutex::new(None),
            drawing: Mutex::new(()),
        })
    }

    /// Pretends the device's largest buffer is `bytes` (tests of meshes cut to fit, and of
    /// uploads that cannot fit).
    #[cfg(test)]
    pub fn limit_buffers(&mut self, bytes: u64) {
        self.max_buffer = bytes;
    }

    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    pub fn max_texture(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Uploads a tree; an error when the device refuses its buffers.
    pub fn upload(&self, data: &TreeData) -> Result<TreeBuffers, RenderError> {
        scoped(&self.device, &self.failure, "uploading a tree", || {
            buffers::upload(&self.device, data, self.max_buffer)
        })?
        .ok_or_else(|| RenderError::Gpu {
            what: "uploading a tree",
            message: format!(
                "a mesh stored for range rendering is over the device's {} MB buffer limit",
                self.max_buffer >> 20
            ),
        })
    }

    /// The bind group of an impostor atlas, uploaded on first use.
    fn atlas_group(&self, atlas: &crate::impostor::Atlas) -> wgpu::BindGroup {
        let mut kept = self.atlas.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((id, group)) = kept.as_ref()
            && *id == atlas.id
        {
            return group.clone();
        }
        let group = atlas::upload(&self.device, &self.queue, &self.pipelines, atlas);
        *kept = Some((atlas.id, group.clone()));
        group
    }

    fn prop(&self, label: &str, mesh: &PropMesh) -> crate::tree::GpuPart {
        crate::tree::GpuPart {
            vertices: buffer(
                &self.device,
                label,
                bytemuck::cast_slice(&mesh.vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer(
                &self.device,
                label,
                bytemuck::cast_slice(&mesh.indices),
                wgpu::BufferUsages::INDEX,
            ),
            count: mesh.indices.len() as u32,
        }
    }

    /// Records the shadow and main passes of `frame` into `encoder`, drawing into `target`
    /// (a `SAMPLES`-sample view) resolved into `resolve`.
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &Frame,
        target: &wgpu::TextureView,
        resolve: &wgpu::TextureView,
        depth: &wgpu::TextureView,
    ) -> Result<(), RenderError> {
        let p = &self.pipelines;
        self.queue
            .write_buffer(&p.globals, 0, bytemuck::bytes_of(&frame.globals));
        let props = Props {
            ground: self.prop("ground", &frame.ground),
            person: self.prop("person", &frame.person),
        };
        let materials: Vec<wgpu::BindGroup> = frame
            .materials
            .iter()
            .map(|m| {
                let uniform = buffer(
                    &self.device,
                    "material",
                    bytemuck::bytes_of(m),
                    wgpu::BufferUsages::UNIFORM,
                );
                self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("material"),
                    layout: &p.material_layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    }],
                })
            })
            .collect();
        let instances = buffer(
            &self.device,
            "instances",
            bytemuck::cast_slice(&frame.instances),
            wgpu::BufferUsages::VERTEX,
        );
        let (copy_bytes, copy_offsets) = record::copies(frame);
        let copies = buffer(
            &self.device,
            "copies",
            &copy_bytes,
            wgpu::BufferUsages::UNIFORM,
        );
        let copy_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("copies"),
            layout: &p.copy_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &copies,
                    offset: 0,
                    size: std::num::NonZeroU64::new(std::mem::size_of::<record::CopyData>() as u64),
                }),
            }],
        });
        let atlas = frame.atlas.map(|a| self.atlas_group(a));
        // Resolve every draw's buffers first, so that a tree without GPU buffers is an error
        // before anything is recorded.
        let sources: Vec<Vec<Source>> = frame
            .draws
            .iter()
            .map(|d| props.sources(d))
            .collect::<Result<_, _>>()?;
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &p.shadow_view,
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
            pass.set_bind_group(0, &p.shadow_group, &[]);
            // Far trees' lines and points cast shadows too, or a forest's shade would thin out
            // with the camera's range.
            for ((d, s), &offset) in frame.draws.iter().zip(&sources).zip(&copy_offsets) {
                pass.set_pipeline(record::pipeline(p, d, true));
                let buffers = (&instances, &copy_group, offset, None);
                record(&mut pass, d, s, buffers, &p.templates, d.shadow.clone());
            }
        }
        let [r, g, b, a] = frame.clear.map(f64::from);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("main"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: Some(resolve),
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
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
        pass.set_bind_group(0, &p.globals_group, &[]);
        for ((d, s), &offset) in frame.draws.iter().zip(&sources).zip(&copy_offsets) {
            pass.set_pipeline(record::pipeline(p, d, false));
            pass.set_bind_group(1, &materials[d.material], &[]);
            let buffers = (&instances, &copy_group, offset, atlas.as_ref());
            record(&mut pass, d, s, buffers, &p.templates, d.range.clone());
        }
        Ok(())
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

    /// Draws `frame` into `resolve`, a single-sample view of this renderer's target format.
    pub fn render_into(
        &self,
        frame: &Frame,
        resolve: &wgpu::TextureView,
        width: u32,
        height: u32,
    ) -> Result<(), RenderError> {
        scoped(&self.device, &self.failure, "drawing a frame", || {
            let (colour, depth) = self.targets(width, height);
            let mut encoder = self.device.create_command_encoder(&Default::default());
            let _drawing = self.drawing.lock().unwrap_or_else(|e| e.into_inner());
            self.encode(&mut encoder, frame, &colour, resolve, &depth)?;
            self.queue.submit([encoder.finish()]);
            Ok(())
        })?
    }

    /// Draws `frame` into a new `width` x `height` picture and reads it back (RGBA, sRGB).
    pub fn render(&self, frame: &Frame, width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
        let row = (width * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let readback = scoped(&self.device, &self.failure, "drawing a picture", || {
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
            let (colour, depth) = self.targets(width, height);
            let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("readback"),
                size: (row * height) as u64,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            let mut encoder = self.device.create_command_encoder(&Default::default());
            let _drawing = self.drawing.lock().unwrap_or_else(|e| e.into_inner());
            self.encode(&mut encoder, frame, &colour, &resolve, &depth)?;
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
            Ok::<_, RenderError>(readback)
        })??;
        let readback_error = |e: String| RenderError::Gpu {
            what: "reading the picture back",
            message: e,
        };
        let slice = readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| readback_error(e.to_string()))?;
        rx.recv()
            .map_err(|e| readback_error(e.to_string()))?
            .map_err(|e| readback_error(e.to_string()))?;
        self.check("reading the picture back")?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| readback_error(e.to_string()))?;
        let mut rgba = Vec::with_capacity((width * height * 4) as usize);
        for y in 0..height {
            let start = (y * row) as usize;
            rgba.extend_from_slice(&data[start..start + (width * 4) as usize]);
        }
        drop(data);
        readback.unmap();
        // A picture is RGBA whatever the target (a window's may be BGRA).
        if matches!(
            self.target_format,
            wgpu::TextureFormat::Bgra8UnormSrgb | wgpu::TextureFormat::Bgra8Unorm
        ) {
            rgba.chunks_exact_mut(4).for_each(|p| p.swap(0, 2));
        }
        Ok(rgba)
    }

    /// An error if the device failed outside any scope (or was lost).
    fn check(&self, what: &'static str) -> Result<(), RenderError> {
        failed(&self.failure, what)
    }
}

fn failed(failure: &Mutex<Option<String>>, what: &'static str) -> Result<(), RenderError> {
    match failure.lock().ok().and_then(|f| f.clone()) {
        Some(message) => Err(RenderError::Gpu { what, message }),
        None => Ok(()),
    }
}

/// Runs `f` with every kind of device error caught, and turns the first into a
/// [`RenderError`].
fn scoped<T>(
    device: &wgpu::Device,
    failure: &Mutex<Option<String>>,
    what: &'static str,
    f: impl FnOnce() -> T,
) -> Result<T, RenderError> {
    failed(failure, what)?;
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    // A driver that panics (wgpu's own `expect`s, a backend's internal error) fails the GPU
    // like any other error: the picture is then drawn on the CPU.
    let out = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    // Scopes pop in the reverse order of their pushing.
    let errors = [
        pollster::block_on(internal.pop()),
        pollster::block_on(validation.pop()),
        pollster::block_on(memory.pop()),
    ];
    if let Some(e) = errors.into_iter().flatten().next() {
        return Err(RenderError::Gpu {
            what,
            message: e.to_string(),
        });
    }
    let out = out.map_err(|panic| RenderError::Gpu {
        what,
        message: match panic.downcast_ref::<&str>() {
            Some(s) => format!("the driver panicked: {s}"),
            None => match panic.downcast_ref::<String>() {
                Some(s) => format!("the driver panicked: {s}"),
                None => "the driver panicked".into(),
            },
        },
    })?;
    failed(failure, what)?;
    Ok(out)
}

/// Refuses adapters that lack what the shaders need (shadow comparisons, 4x multisampling of
/// the picture and depth formats, per-sample shading on OpenGL).
fn check_adapter(adapter: &wgpu::Adapter) -> Result<(), RenderError> {
    let info = adapter.get_info();
    let caps = adapter.get_downlevel_capabilities();
    let mut need = vec![];
    if !caps
        .flags
        .contains(wgpu::DownlevelFlags::COMPARISON_SAMPLERS)
    {
        need.push("comparison samplers");
    }
    if info.backend == wgpu::Backend::Gl
        && !caps
            .flags
            .contains(wgpu::DownlevelFlags::MULTISAMPLED_SHADING)
    {
        need.push("per-sample shading");
    }
    for format in [crate::PICTURE_FORMAT, DEPTH] {
        if !adapter
            .get_texture_format_features(format)
            .flags
            .sample_count_supported(SAMPLES)
        {
            need.push("4x multisampling");
            break;
        }
    }
    if need.is_empty() {
        Ok(())
    } else {
        Err(RenderError::Device(format!(
            "{} lacks {}",
            describe(&info),
            need.join(", ")
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The machine's GPU backend, if it has one.
    fn gpu() -> Option<GpuRenderer> {
        let found = GpuRenderer::headless(Api::Native).or_else(|_| GpuRenderer::headless(Api::Gl));
        if let Err(e) = &found {
            eprintln!("no GPU here, nothing to test: {e}");
        }
        found.ok()
    }

    #[test]
    fn device_errors_become_render_errors() {
        let Some(g) = gpu() else { return };
        // A buffer over the device's limit is a validation error, which wgpu's default
        // handler would turn into a panic.
        let too_big = g.device.limits().max_buffer_size + 4;
        let result = scoped(&g.device, &g.failure, "testing", || {
            g.device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: too_big,
                usage: wgpu::BufferUsages::VERTEX,
                mapped_at_creation: false,
            })
        });
        match result {
            Err(RenderError::Gpu { what, message }) => {
                assert_eq!(what, "testing");
                assert!(!message.is_empty());
            }
            other => panic!("expected a GPU error, got {other:?}"),
        }
        // The device still works after a caught error.
        assert!(scoped(&g.device, &g.failure, "testing", || ()).is_ok());
    }
}
