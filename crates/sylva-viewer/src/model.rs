//! `sylva view tree.glb`: look at any model Sylva wrote (a fractal, whisk or lobe tree, a grown
//! street tree, a species) from every side. Drag turns and tilts, the wheel zooms.

use crate::window::{
    Screenshots, Turntable, ViewTexture, ensure_texture, render_timed, renderer_of, show_texture,
    window,
};
use anyhow::Result;
use eframe::{egui, egui_wgpu};
use std::path::{Path, PathBuf};
use std::time::Instant;
use sylva_render::glb_scene::{UploadedScene, read_glb_scene};
use sylva_render::{Renderer, View};

/// Opens the window (blocks until it is closed).
pub fn look_at(path: &Path, self_test: Option<PathBuf>) -> Result<()> {
    look_at_scene(
        read_glb_scene(path)?,
        &path.display().to_string(),
        self_test,
    )
}

/// Opens the window on a model already read (a tree Sylva just grew, as a GLB scene).
pub fn look_at_scene(
    model: sylva_render::glb_scene::GlbScene,
    name: &str,
    self_test: Option<PathBuf>,
) -> Result<()> {
    let title = format!("Sylva: {name}");
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(title)
            .with_inner_size([1100.0, 800.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    window("sylva-model", options, move |cc| {
        ModelViewer::new(cc, model, self_test)
    })
}

/// Scripted run for tests: a picture from the front, one turned a quarter, a report, close.
struct SelfTest {
    dir: PathBuf,
    step: u32,
    shots: Screenshots,
    started: Instant,
}

struct ModelViewer {
    renderer: Renderer,
    render_state: egui_wgpu::RenderState,
    /// The model's meshes, each once, with their copies.
    model: UploadedScene,
    show_leaves: bool,
    turntable: Turntable,
    texture: Option<ViewTexture>,
    needs_render: bool,
    frame_ms: f64,
    self_test: Option<SelfTest>,
}

impl ModelViewer {
    fn new(
        cc: &eframe::CreationContext<'_>,
        glb: sylva_render::glb_scene::GlbScene,
        self_test: Option<PathBuf>,
    ) -> Result<Self> {
        let (renderer, render_state) = renderer_of(cc)?;
        let model = UploadedScene::new(&renderer, glb);
        Ok(Self {
            renderer,
            render_state,
            model,
            show_leaves: true,
            turntable: Turntable::new(10.0),
            texture: None,
            needs_render: true,
            frame_ms: 0.0,
            self_test: self_test.map(|dir| SelfTest {
                shots: Screenshots::new(dir.clone(), "model-viewer"),
                dir,
                step: 0,
                started: Instant::now(),
            }),
        })
    }

    /// Frames the model's bounds whatever its size, turned and zoomed by the user.
    fn view(&self, aspect: f32) -> View {
        let (lo, hi) = self.model.bounds();
        let size = hi - lo;
        let across = size.x.max(size.y).max(0.5) * 1.2;
        let height = hi.z.max(1.9) + 0.3;
        let centre = 0.5 * (lo + hi).truncate();
        self.turntable.view(centre, across, height, aspect, 1.1)
    }

    fn draw(&mut self, size: [u32; 2]) {
        let size = [size[0].clamp(16, 4096), size[1].clamp(16, 4096)];
        if ensure_texture(&self.render_state, &mut self.texture, size) {
            self.needs_render = true;
        }
        let Some(texture) = &self.texture else {
            return;
        };
        if !self.needs_render {
            return;
        }
        let mut scene = self.model.scene();
        scene.show_leaves = self.show_leaves;
        let view = self.view(size[0] as f32 / size[1] as f32);
        let (_, ms) = render_timed(&self.renderer, &self.render_state, &scene, &view, texture);
        self.frame_ms = ms;
        self.needs_render = false;
    }

    fn self_test_step(&mut self, ctx: &egui::Context) {
        let settled = self.texture.is_some() && !self.needs_render;
        let (triangles, frame_ms) = (self.model.triangles(), self.frame_ms);
        let Some(test) = &mut self.self_test else {
            return;
        };
        test.step += test.shots.save_arrived();
        ctx.request_repaint();
        if test.started.elapsed().as_secs() > 120 {
            eprintln!("sylva: self-test timed out at step {}", test.step);
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            self.self_test = None;
            return;
        }
        if test.shots.waiting || !settled {
            return;
        }
        match test.step {
            0 => test.shots.take(ctx, 1),
            1 => {
                // A quarter turn, as a drag would make it.
                self.turntable.azimuth = 90.0;
                self.needs_render = true;
                test.step = 2;
            }
            2 => test.shots.take(ctx, 2),
            _ => {
                let report = serde_json::json!({
                    "triangles": triangles,
                    "frame_ms": frame_ms,
                    "azimuth": self.turntable.azimuth,
                    "adapter": self.renderer.adapter_name(),
                });
                let _ = std::fs::write(test.dir.join("model-viewer.json"), report.to_string());
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                self.self_test = None;
            }
        }
    }
}

impl eframe::App for ModelViewer {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        egui::Panel::top("model controls").show(ui, |ui| {
            ui.horizontal(|ui| {
                if ui.checkbox(&mut self.show_leaves, "leaves").changed() {
                    self.needs_render = true;
                }
                let (lo, hi) = self.model.bounds();
                ui.label(format!(
                    "{} triangles   |   {:.2} m tall, {:.2} x {:.2} m across   |   {:.0} ms a frame   |   drag: turn and tilt   wheel: zoom",
                    self.model.triangles(),
                    hi.z,
                    hi.x - lo.x,
                    hi.y - lo.y,
                    self.frame_ms
                ));
            });
        });
        egui::CentralPanel::default().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let ppp = ui.ctx().pixels_per_point();
            let response = ui.allocate_rect(rect, egui::Sense::drag());
            if self.turntable.handle(&response, ui) {
                self.needs_render = true;
            }
            self.draw([(rect.width() * ppp) as u32, (rect.height() * ppp) as u32]);
            show_texture(ui, rect, &self.texture);
        });
        let ctx = ui.ctx().clone();
        self.self_test_step(&ctx);
    }
}
