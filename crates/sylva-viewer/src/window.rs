//! What every viewer window shares: opening a window that closes with an error when the GPU
//! fails, the renderer on eframe's device, the texture the 3-D view is drawn into, a
//! turntable camera, and the self-tests' screenshots.

use anyhow::{Context, Result, anyhow, bail};
use eframe::{egui, egui_wgpu};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};
use std::sync::{Arc, OnceLock};
use std::time::Instant;
use sylva_render::{FrameStats, Picture, Renderer, Scene, View};

/// Writes RGBA pixels as a PNG file.
pub(crate) fn save_png(path: &Path, width: u32, height: u32, rgba: Vec<u8>) -> Result<()> {
    let picture = Picture {
        width,
        height,
        rgba,
        stats: FrameStats::default(),
    };
    sylva::export::write_atomically(path, &picture.to_png()?)?;
    Ok(())
}

/// A GPU failure while a window is open: the window closes and the command fails with it.
pub(crate) static GPU_FAILURE: OnceLock<String> = OnceLock::new();

/// A viewer that closes its window once the GPU has failed.
pub(crate) struct Guarded<A>(A);

impl<A: eframe::App> eframe::App for Guarded<A> {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if GPU_FAILURE.get().is_some() {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        self.0.ui(ui, frame);
    }
}

/// Opens a window running the app `make` builds, until it is closed. A window that cannot
/// open, or a GPU that fails while it is open, is an error saying what the viewer needs: a
/// viewer cannot fall back to the CPU as pictures do.
pub(crate) fn window<A: eframe::App + 'static>(
    name: &str,
    options: eframe::NativeOptions,
    make: impl FnOnce(&eframe::CreationContext<'_>) -> Result<A> + 'static,
) -> Result<()> {
    let opened = eframe::run_native(
        name,
        options,
        Box::new(move |cc| Ok(Box::new(Guarded(make(cc)?)))),
    );
    if let Some(failure) = GPU_FAILURE.get() {
        bail!("the viewer closed because the GPU failed: {failure}");
    }
    opened.map_err(|e| {
        anyhow!(
            "cannot open the viewer window: {e}. The viewer needs a display (X11 or Wayland; \
             Xvfb where there is none) and a graphics driver (a GPU, or Mesa's software ones: \
             Debian's mesa-vulkan-drivers or libgl1-mesa-dri); `sylva render` draws pictures \
             without either"
        )
    })
}

/// The 3-D view's texture, registered with egui.
pub(crate) struct ViewTexture {
    /// sRGB view the renderer draws into.
    pub(crate) view: eframe::wgpu::TextureView,
    pub(crate) drawn: eframe::wgpu::Texture,
    /// The same bytes as unorm, which egui shows.
    pub(crate) shown: eframe::wgpu::Texture,
    pub(crate) id: egui::TextureId,
    pub(crate) size: [u32; 2],
}

/// The renderer on eframe's wgpu device, and that device's state.
pub(crate) fn renderer_of(
    cc: &eframe::CreationContext<'_>,
) -> Result<(Renderer, egui_wgpu::RenderState)> {
    let render_state = cc
        .wgpu_render_state
        .clone()
        .context("the viewer needs the wgpu backend, which did not start")?;
    let renderer = Renderer::from_device(
        render_state.device.clone(),
        render_state.queue.clone(),
        sylva_render::PICTURE_FORMAT,
        &render_state.adapter.get_info(),
    )?;
    Ok((renderer, render_state))
}

/// Makes (or remakes, at a new size) the texture the 3-D view is drawn into and shown from;
/// true when it did.
pub(crate) fn ensure_texture(
    render_state: &egui_wgpu::RenderState,
    texture: &mut Option<ViewTexture>,
    size: [u32; 2],
) -> bool {
    if texture.as_ref().is_some_and(|t| t.size == size) {
        return false;
    }
    let device = &render_state.device;
    let make = |label, format, usage| {
        device.create_texture(&eframe::wgpu::TextureDescriptor {
            label: Some(label),
            size: eframe::wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: eframe::wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    use eframe::wgpu::TextureUsages as U;
    let drawn = make(
        "tree view",
        sylva_render::PICTURE_FORMAT,
        U::RENDER_ATTACHMENT | U::COPY_SRC,
    );
    // egui blends in gamma space: it must read the sRGB-encoded bytes as they are, so the
    // picture is copied into a plain unorm texture (a unorm view of the sRGB one would do,
    // but OpenGL devices cannot make one), or it comes out too dark.
    let shown = make(
        "tree view (shown)",
        eframe::wgpu::TextureFormat::Rgba8Unorm,
        U::TEXTURE_BINDING | U::COPY_DST,
    );
    let view = drawn.create_view(&Default::default());
    let egui_view = shown.create_view(&Default::default());
    let mut egui_renderer = render_state.renderer.write();
    let id = match &*texture {
        Some(old) => {
            egui_renderer.update_egui_texture_from_wgpu_texture(
                device,
                &egui_view,
                eframe::wgpu::FilterMode::Linear,
                old.id,
            );
            old.id
        }
        None => egui_renderer.register_native_texture(
            device,
            &egui_view,
            eframe::wgpu::FilterMode::Linear,
        ),
    };
    *texture = Some(ViewTexture {
        view,
        drawn,
        shown,
        id,
        size,
    });
    true
}

/// A camera turning about a fixed frame: drag turns and tilts, the wheel zooms. The growth and
/// model viewers use it; the editor adds panning, the forest viewer flies instead.
pub(crate) struct Turntable {
    /// Degrees about the vertical.
    pub(crate) azimuth: f32,
    /// Degrees above the horizon.
    pub(crate) elevation: f32,
    pub(crate) zoom: f32,
}

impl Turntable {
    pub(crate) fn new(elevation: f32) -> Self {
        Self {
            azimuth: 0.0,
            elevation,
            zoom: 1.0,
        }
    }

    /// Applies a drag or a wheel turn over `response`; true when the view changed.
    pub(crate) fn handle(&mut self, response: &egui::Response, ui: &egui::Ui) -> bool {
        let mut changed = false;
        if response.dragged_by(egui::PointerButton::Primary) {
            let d = response.drag_delta();
            self.azimuth -= d.x * 0.3;
            self.elevation = (self.elevation + d.y * 0.2).clamp(-5.0, 80.0);
            changed = true;
        }
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if response.hovered() && scroll != 0.0 {
            self.zoom = (self.zoom * (1.0 + scroll * 0.002)).clamp(0.3, 8.0);
            changed = true;
        }
        changed
    }

    /// A 30-degree camera that fits a frame `across` metres wide and `height` tall, standing
    /// on the ground below `centre`, with `margin` to spare, then turned and zoomed.
    pub(crate) fn view(
        &self,
        centre: glam::Vec2,
        across: f32,
        height: f32,
        aspect: f32,
        margin: f32,
    ) -> View {
        let fov = 30.0f32;
        let half = (fov / 2.0).to_radians().tan();
        let distance =
            (height / 2.0 / half).max(across / 2.0 / (half * aspect)) * margin / self.zoom;
        let target = centre.extend(height / 2.0);
        let turn = glam::Quat::from_rotation_z(self.azimuth.to_radians())
            * glam::Quat::from_rotation_x(-self.elevation.to_radians());
        View::look_at(
            target + turn * glam::Vec3::new(0.0, -distance, 0.0),
            target,
            fov,
        )
    }
}

/// Shows the 3-D view's texture over `rect`; false when there is none yet.
pub(crate) fn show_texture(ui: &egui::Ui, rect: egui::Rect, texture: &Option<ViewTexture>) -> bool {
    let Some(t) = texture else { return false };
    let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
    ui.painter().image(t.id, rect, uv, egui::Color32::WHITE);
    true
}

/// A self-test's screenshots: asked of the window, written as PNG into `dir` as they arrive.
pub(crate) struct Screenshots {
    pub(crate) dir: PathBuf,
    pub(crate) prefix: &'static str,
    pub(crate) receive: Receiver<(u32, Arc<egui::ColorImage>)>,
    pub(crate) send: std::sync::mpsc::Sender<(u32, Arc<egui::ColorImage>)>,
    /// A screenshot was asked for and has not come yet.
    pub(crate) waiting: bool,
}

impl Screenshots {
    pub(crate) fn new(dir: PathBuf, prefix: &'static str) -> Self {
        let (send, receive) = channel();
        Self {
            dir,
            prefix,
            receive,
            send,
            waiting: false,
        }
    }

    /// Asks the window for screenshot `n` (`prefix-n.png`).
    pub(crate) fn take(&mut self, ctx: &egui::Context, n: u32) {
        let send = self.send.clone();
        self.waiting = true;
        ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(
            egui::ScreenshotCallback::new(move |image| {
                let _ = send.send((n, image));
            }),
        ));
    }

    /// Writes the screenshots that have come (a failure is reported, and the test's report
    /// then lacks the picture); how many came.
    pub(crate) fn save_arrived(&mut self) -> u32 {
        let mut arrived = 0;
        while let Ok((n, image)) = self.receive.try_recv() {
            let path = self.dir.join(format!("{}-{n}.png", self.prefix));
            let rgba: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
            if let Err(e) = save_png(&path, image.size[0] as u32, image.size[1] as u32, rgba) {
                eprintln!("sylva: self-test: {e:#}");
            }
            self.waiting = false;
            arrived += 1;
        }
        arrived
    }
}

/// Draws `scene` into `texture` and waits for the GPU, so that the time (ms) is the frame's,
/// not just its recording.
pub(crate) fn render_timed(
    renderer: &Renderer,
    render_state: &egui_wgpu::RenderState,
    scene: &Scene,
    view: &View,
    texture: &ViewTexture,
) -> (sylva_render::FrameStats, f64) {
    let t = Instant::now();
    let [w, h] = texture.size;
    let stats = match renderer.render_into(scene, view, &texture.view, w, h) {
        Ok(stats) => stats,
        Err(e) => {
            let _ = GPU_FAILURE.set(e.to_string());
            Default::default()
        }
    };
    let mut encoder = render_state
        .device
        .create_command_encoder(&Default::default());
    encoder.copy_texture_to_texture(
        texture.drawn.as_image_copy(),
        texture.shown.as_image_copy(),
        texture.drawn.size(),
    );
    render_state.queue.submit([encoder.finish()]);
    if let Some(device) = renderer.device() {
        let _ = device.poll(eframe::wgpu::PollType::wait_indefinitely());
    }
    (stats, t.elapsed().as_secs_f64() * 1e3)
}
