//! `sylva view forest.toml`: fly through a planted forest, with range degradation on or off,
//! and see what each frame draws and how long it takes.

use crate::window::{ViewTexture, ensure_texture, render_timed, renderer_of, show_texture, window};
use anyhow::Result;
use eframe::{egui, egui_wgpu};
use glam::Vec3;
use std::path::PathBuf;
use sylva::forest::Forest;
use sylva::lod::LodTree;
use sylva_render::{ForestOnGpu, FrameStats, Renderer, View};

/// Opens a window flying through `forest`, titled by `name` (blocks until it is closed).
/// `self_test`: a scripted run for tests (frames with and without LOD, a report, close).
pub fn fly_through(forest: Forest<LodTree>, name: &str, self_test: Option<PathBuf>) -> Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(format!("Sylva: {name}"))
            .with_inner_size([1280.0, 800.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    window("sylva-forest", options, move |cc| {
        ForestViewer::new(cc, &forest, self_test)
    })
}

struct ForestViewer {
    renderer: Renderer,
    render_state: egui_wgpu::RenderState,
    forest: ForestOnGpu,
    /// Where the camera stands, metres (Z up), and where it looks (degrees).
    eye: Vec3,
    yaw: f32,
    pitch: f32,
    fov: f32,
    use_lod: bool,
    lod_quality: f32,
    show_leaves: bool,
    /// Wind speed (the paper's units); the trees sway on the GPU while it blows.
    wind: f64,
    started: std::time::Instant,
    stats: FrameStats,
    frame_ms: f64,
    texture: Option<ViewTexture>,
    needs_render: bool,
    /// Scripted run for tests: frames with and without LOD, then a report into the folder.
    self_test: Option<(PathBuf, u32, Vec<serde_json::Value>)>,
}

impl ForestViewer {
    fn new(
        cc: &eframe::CreationContext<'_>,
        forest: &Forest<LodTree>,
        self_test: Option<PathBuf>,
    ) -> Result<Self> {
        let (renderer, render_state) = renderer_of(cc)?;
        let forest = ForestOnGpu::upload(&renderer, forest);
        // Start at the forest's edge, at eye height, looking across it.
        let (lo, hi) = forest.scene().tree_bounds();
        let eye = Vec3::new((lo.x + hi.x) / 2.0, lo.y - (hi.y - lo.y) * 0.15, 1.7);
        Ok(Self {
            renderer,
            render_state,
            forest,
            eye,
            yaw: 0.0,
            pitch: 8.0,
            fov: 50.0,
            use_lod: true,
            lod_quality: 1.0,
            show_leaves: true,
            wind: 0.0,
            started: std::time::Instant::now(),
            stats: FrameStats::default(),
            frame_ms: 0.0,
            texture: None,
            needs_render: true,
            self_test: self_test.map(|d| (d, 0, Vec::new())),
        })
    }

    fn forward(&self) -> Vec3 {
        let (y, p) = (self.yaw.to_radians(), self.pitch.to_radians());
        Vec3::new(-y.sin() * p.cos(), y.cos() * p.cos(), p.sin())
    }

    fn view(&self) -> View {
        View::look_at(self.eye, self.eye + self.forward(), self.fov)
    }

    /// Look with the left button; WASD or the arrows move, Q/E down and up, the wheel moves
    /// along the view; Shift is five times faster.
    fn input(&mut self, response: &egui::Response, ui: &egui::Ui) {
        if response.dragged_by(egui::PointerButton::Primary) {
            let d = response.drag_delta();
            self.yaw -= d.x * 0.25;
            self.pitch = (self.pitch - d.y * 0.25).clamp(-85.0, 85.0);
            self.needs_render = true;
        }
        let (dt, keys, scroll, fast) = ui.input(|i| {
            let key = |k: egui::Key| if i.key_down(k) { 1.0f32 } else { 0.0 };
            (
                i.stable_dt.min(0.1),
                [
                    key(egui::Key::W) + key(egui::Key::ArrowUp)
                        - key(egui::Key::S)
                        - key(egui::Key::ArrowDown),
                    key(egui::Key::D) + key(egui::Key::ArrowRight)
                        - key(egui::Key::A)
                        - key(egui::Key::ArrowLeft),
                    key(egui::Key::E) - key(egui::Key::Q),
                ],
                if response.hovered() {
                    i.smooth_scroll_delta.y
                } else {
                    0.0
                },
                i.modifiers.shift,
            )
        });
        // Faster when high above the trees, as in any flight camera.
        let speed = (8.0 + self.eye.z.abs() * 0.8) * if fast { 5.0 } else { 1.0 };
        let flat = Vec3::new(
            -self.yaw.to_radians().sin(),
            self.yaw.to_radians().cos(),
            0.0,
        );
        let right = flat.cross(Vec3::Z);
        let step = (flat * keys[0] + right * keys[1] + Vec3::Z * keys[2]) * speed * dt
            + self.forward() * scroll * 0.05;
        if step != Vec3::ZERO {
            self.eye += step;
            self.eye.z = self.eye.z.max(0.3);
            self.needs_render = true;
        }
        if keys != [0.0; 3] {
            ui.ctx().request_repaint();
        }
    }

    fn draw(&mut self, size: [u32; 2]) {
        let size = [size[0].clamp(16, 4096), size[1].clamp(16, 4096)];
        if ensure_texture(&self.render_state, &mut self.texture, size) {
            self.needs_render = true;
        }
        let (Some(texture), true) = (&self.texture, self.needs_render) else {
            return;
        };
        let mut scene = self.forest.scene();
        scene.use_lod = self.use_lod;
        scene.lod_quality = self.lod_quality;
        scene.show_leaves = self.show_leaves;
        scene.wind = sylva::Wind {
            speed: self.wind,
            gust: self.wind / 2.0,
            time: self.started.elapsed().as_secs_f64(),
        };
        (self.stats, self.frame_ms) = render_timed(
            &self.renderer,
            &self.render_state,
            &scene,
            &self.view(),
            texture,
        );
        self.needs_render = false;
    }

    fn self_test_step(&mut self, ctx: &egui::Context) {
        let Some((dir, step, frames)) = &mut self.self_test else {
            return;
        };
        if self.needs_render {
            ctx.request_repaint();
            return;
        }
        frames.push(serde_json::json!({
            "lod": self.use_lod,
            "trees": self.stats.trees,
            "trees_drawn": self.stats.trees_drawn,
            "triangles": self.stats.triangles,
            "lines": self.stats.lines,
            "points": self.stats.points,
            "frame_ms": self.frame_ms,
        }));
        *step += 1;
        match *step {
            1 => self.use_lod = false,
            2 => {
                // Fly up and back over the forest, LOD on again.
                self.use_lod = true;
                self.eye += Vec3::new(0.0, -150.0, 120.0);
                self.pitch = -25.0;
            }
            _ => {
                let report = serde_json::json!({ "frames": frames });
                let _ = std::fs::write(dir.join("forest-viewer.json"), report.to_string());
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                // Done: frames drawn while the window closes are not part of the report.
                self.self_test = None;
                return;
            }
        }
        self.needs_render = true;
        ctx.request_repaint();
    }
}

impl eframe::App for ForestViewer {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        egui::Panel::top("forest controls").show(ui, |ui| {
            ui.horizontal(|ui| {
                let mut changed = ui
                    .checkbox(&mut self.use_lod, "range degradation (LOD)")
                    .changed();
                changed |= ui
                    .add(egui::Slider::new(&mut self.lod_quality, 0.25..=4.0).text("LOD quality"))
                    .changed();
                changed |= ui.checkbox(&mut self.show_leaves, "leaves").changed();
                changed |= ui
                    .add(egui::Slider::new(&mut self.fov, 15.0..=90.0).text("lens (degrees)"))
                    .changed();
                changed |= ui
                    .add(egui::Slider::new(&mut self.wind, 0.0..=20.0).text("wind"))
                    .changed();
                // While the wind blows, every frame is a new moment of the sway.
                if changed || self.wind > 0.0 {
                    self.needs_render = true;
                    ui.ctx().request_repaint();
                }
            });
            ui.label(format!(
                "{}   |   {}",
                self.stats.describe(self.frame_ms),
                self.renderer.adapter_name()
            ));
            ui.label(
                "drag: look   W A S D / arrows: move   Q E: down, up   wheel: forward   \
                 Shift: faster",
            );
        });
        egui::CentralPanel::default().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let ppp = ui.ctx().pixels_per_point();
            let response = ui.allocate_rect(rect, egui::Sense::drag());
            self.input(&response, ui);
            self.draw([(rect.width() * ppp) as u32, (rect.height() * ppp) as u32]);
            show_texture(ui, rect, &self.texture);
        });
        let ctx = ui.ctx().clone();
        self.self_test_step(&ctx);
    }
}
