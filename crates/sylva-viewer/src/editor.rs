//! The parameter editor: every parameter is live (the tree is rebuilt in the background), the
//! camera orbits, the wind blows in real time, and species, models and pictures can be
//! loaded, saved and exported.

use crate::panel;
use crate::window::{
    Screenshots, ViewTexture, ensure_texture, render_timed, renderer_of, save_png, show_texture,
    window,
};
use crate::worker::Worker;
use anyhow::{Result, anyhow};
use eframe::{egui, egui_wgpu};
use std::path::PathBuf;
use std::time::Instant;
use sylva::export::{Materials, to_glb, write_atomically, write_obj};
use sylva::mesh::{MeshOptions, TreeMesh};
use sylva::{GenerateOptions, SkeletonStats, TreeParams, Wind};
use sylva_render::{RenderTree, Renderer, Scene, View};

/// Opens the editor on `params` (read from `source`, a species name or file) and blocks until
/// its window is closed. `self_test`: a scripted run for tests that writes screenshots and a
/// report into the folder and closes.
pub fn edit(params: TreeParams, source: String, self_test: Option<PathBuf>) -> Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(format!("Sylva: {}", params.name))
            .with_inner_size([1280.0, 800.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    window("sylva", options, move |cc| {
        Viewer::new(cc, params, source, self_test)
    })
}

/// Scripted run for tests: screenshot, change a parameter, screenshot, report, close.
struct SelfTest {
    dir: PathBuf,
    step: u32,
    shots: Screenshots,
    triangles: Vec<usize>,
    started: Instant,
    /// When the wind was switched on, and the generation count then.
    wind_start: Option<(Instant, u32)>,
}

struct Viewer {
    params: TreeParams,
    source: String,
    seed: u64,
    shown_levels: u32,
    show_leaves: bool,
    quality: f64,
    wind_on: bool,
    wind_speed: f64,
    wind_gust: f64,
    started: Instant,
    worker: Worker,
    renderer: Renderer,
    render_state: egui_wgpu::RenderState,
    tree: Option<RenderTree>,
    mesh: Option<TreeMesh>,
    stats: Option<SkeletonStats>,
    generate_ms: f64,
    mesh_ms: f64,
    frame_ms: f64,
    texture: Option<ViewTexture>,
    view: View,
    needs_render: bool,
    /// The camera is being dragged (draw drafts).
    moving: bool,
    generations: u32,
    status: String,
    file: String,
    export: String,
    self_test: Option<SelfTest>,
}

impl Viewer {
    fn new(
        cc: &eframe::CreationContext<'_>,
        params: TreeParams,
        source: String,
        self_test: Option<PathBuf>,
    ) -> Result<Self> {
        let (renderer, render_state) = renderer_of(cc)?;
        let ctx = cc.egui_ctx.clone();
        let worker = Worker::start(move || ctx.request_repaint());
        let self_test = self_test.map(|dir| SelfTest {
            shots: Screenshots::new(dir.clone(), "viewer"),
            dir,
            step: 0,
            triangles: Vec::new(),
            started: Instant::now(),
            wind_start: None,
        });
        let stem = std::path::Path::new(&source)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "tree".into());
        let mut viewer = Self {
            shown_levels: params.levels,
            params,
            file: format!("{stem}.toml"),
            export: format!("{stem}.glb"),
            source,
            seed: 0,
            show_leaves: true,
            quality: 1.0,
            wind_on: false,
            wind_speed: 6.0,
            wind_gust: 3.0,
            started: Instant::now(),
            worker,
            renderer,
            render_state,
            tree: None,
            mesh: None,
            stats: None,
            generate_ms: 0.0,
            mesh_ms: 0.0,
            frame_ms: 0.0,
            texture: None,
            view: View::orbit(-30.0, 12.0),
            needs_render: true,
            moving: false,
            generations: 0,
            status: String::new(),
            self_test,
        };
        viewer.regenerate();
        Ok(viewer)
    }

    fn wind(&self) -> Wind {
        if self.wind_on {
            Wind {
                speed: self.wind_speed,
                gust: self.wind_gust,
                time: self.started.elapsed().as_secs_f64(),
            }
        } else {
            Wind::default()
        }
    }

    /// Asks the worker for the tree as the controls now describe it.
    fn regenerate(&mut self) {
        if let Err(e) = self.params.validate() {
            self.status = e.to_string();
            return;
        }
        let options = GenerateOptions {
            seed: self.seed,
            max_levels: Some(self.shown_levels.clamp(1, self.params.levels)),
            quality: self.quality,
            leaves: self.show_leaves,
            wind: self.wind(),
            ..Default::default()
        };
        let mesh = MeshOptions::for_species(&self.params, self.quality);
        self.worker.request(self.params.clone(), options, mesh);
    }

    fn receive(&mut self) {
        match self.worker.poll() {
            Some(Ok(built)) => {
                self.tree = Some(self.renderer.upload(&built.mesh));
                self.generate_ms = built.generate_ms;
                self.mesh_ms = built.mesh_ms;
                self.stats = Some(built.stats);
                self.mesh = Some(built.mesh);
                self.needs_render = true;
                self.generations += 1;
                if !self.status.starts_with("saved") && !self.status.starts_with("wrote") {
                    self.status.clear();
                }
            }
            Some(Err(e)) => self.status = e,
            None => {}
        }
    }

    fn scene<'a>(&self, tree: &'a RenderTree) -> Scene<'a> {
        let mut scene = Scene::new(tree, self.params.bark_color, self.params.leaf_color);
        scene.show_leaves = self.show_leaves;
        scene
    }

    /// Draws the 3-D view into its texture (re-created when the panel changes size).
    fn draw_view(&mut self, size: [u32; 2]) {
        let Some(tree) = &self.tree else { return };
        let size = [size[0].clamp(16, 4096), size[1].clamp(16, 4096)];
        if ensure_texture(&self.render_state, &mut self.texture, size) {
            self.needs_render = true;
        }
        if self.needs_render
            && let Some(texture) = &self.texture
        {
            let scene = self.scene(tree);
            render_timed(
                &self.renderer,
                &self.render_state,
                &scene,
                &self.view,
                texture,
            );
            self.needs_render = false;
        }
    }

    fn save_species(&mut self) {
        let path = PathBuf::from(&self.file);
        self.status = match write_atomically(&path, sylva::params::to_toml(&self.params).as_bytes())
        {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => e.to_string(),
        };
    }

    fn load_species(&mut self) {
        match sylva::species::load(&self.file) {
            Ok(p) => {
                self.shown_levels = p.levels;
                self.params = p;
                self.source = self.file.clone();
                self.regenerate();
            }
            Err(e) => self.status = e.to_string(),
        }
    }

    fn export(&mut self) {
        let path = PathBuf::from(&self.export);
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let materials = Materials::from_srgb(self.params.bark_color, self.params.leaf_color);
        let result: Result<()> = match (ext.as_deref(), &self.mesh, &self.tree) {
            (Some("glb"), Some(mesh), _) => to_glb(mesh, &self.params.name, &materials)
                .and_then(|b| write_atomically(&path, &b))
                .map_err(Into::into),
            (Some("obj"), Some(mesh), _) => {
                write_obj(&path, mesh, &self.params.name, &materials).map_err(Into::into)
            }
            (Some("png"), _, Some(tree)) => self
                .renderer
                .render(&self.scene(tree), &self.view, 1600, 1200)
                .map_err(Into::into)
                .and_then(|p| save_png(&path, p.width, p.height, p.rgba)),
            (Some("glb" | "obj" | "png"), _, _) => Err(anyhow!("no tree yet")),
            _ => Err(anyhow!("export to a .glb, .obj or .png file")),
        };
        self.status = match result {
            Ok(()) => format!("wrote {}", path.display()),
            Err(e) => format!("{e:#}"),
        };
    }

    /// Orbit with the left button, pan with the right, zoom with the wheel.
    fn camera_input(&mut self, response: &egui::Response, ui: &egui::Ui) {
        if response.dragged_by(egui::PointerButton::Primary) {
            let d = response.drag_delta();
            self.view.azimuth -= d.x * 0.4;
            self.view.elevation = (self.view.elevation + d.y * 0.3).clamp(-5.0, 89.0);
            self.needs_render = true;
        }
        if response.dragged_by(egui::PointerButton::Secondary) {
            let d = response.drag_delta();
            let a = self.view.azimuth.to_radians();
            let scale = 0.02 / self.view.zoom;
            let right = glam::Vec3::new(a.cos(), a.sin(), 0.0);
            self.view.pan += -right * d.x * scale + glam::Vec3::Z * d.y * scale;
            self.needs_render = true;
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.view.zoom = (self.view.zoom * (1.0 + scroll * 0.002)).clamp(0.2, 20.0);
                self.needs_render = true;
            }
        }
    }

    fn stats_ui(&self, ui: &mut egui::Ui) {
        if let (Some(stats), Some(tree)) = (&self.stats, &self.tree) {
            let levels: Vec<String> = stats
                .stems_per_level
                .iter()
                .map(|n| n.to_string())
                .collect();
            ui.label(format!(
                "stems {}   leaves {}   triangles {}   height {:.1} m   crown {:.1} m",
                levels.join("/"),
                stats.leaves,
                tree.triangles,
                stats.height,
                stats.crown_width
            ));
            ui.label(format!(
                "generate {:.1} ms   mesh {:.1} ms   frame {:.1} ms   {}",
                self.generate_ms,
                self.mesh_ms,
                self.frame_ms,
                self.renderer.adapter_name()
            ));
        }
    }

    /// Drives the scripted self-test, one step per frame.
    fn self_test_step(&mut self, ctx: &egui::Context) {
        let Some(test) = &mut self.self_test else {
            return;
        };
        test.step += test.shots.save_arrived();
        if test.started.elapsed().as_secs() > 240 {
            eprintln!("sylva: self-test timed out at step {}", test.step);
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        // While the wind blows the worker is never idle: step 4 only watches the clock.
        let ready = test.step == 4
            || self.tree.is_some()
                && !self.worker.busy()
                && !self.needs_render
                && !test.shots.waiting;
        if !ready {
            ctx.request_repaint();
            return;
        }
        let triangles = self.tree.as_ref().map_or(0, |t| t.triangles);
        match test.step {
            0 => {
                test.triangles.push(triangles);
                test.shots.take(ctx, 1);
            }
            1 => {
                // The edit a user would make: branches steeper and more of them.
                self.params.level[1].down_angle = (self.params.level[1].down_angle - 30.0).max(5.0);
                self.params.level[1].branches += 20;
                test.step = 2;
                self.regenerate();
            }
            2 => {
                test.triangles.push(triangles);
                test.shots.take(ctx, 2);
            }
            3 => {
                // Wind on: the tree is re-formed continuously while it blows.
                self.wind_on = true;
                test.wind_start = Some((Instant::now(), self.generations));
                test.step = 4;
            }
            4 => {
                // Until the wind has re-formed the tree three times (a loaded machine may
                // need a while); 20 s without that counts as a failure in the report.
                let (since, at_start) = test.wind_start.expect("set in step 3");
                if self.generations >= at_start + 3 || since.elapsed().as_secs() > 20 {
                    self.wind_on = false;
                    test.step = 5;
                }
            }
            _ => {
                let wind_generations = test.wind_start.map_or(0, |(_, g)| self.generations - g);
                let report = serde_json::json!({
                    "species": self.params.name,
                    "generations": self.generations,
                    "wind_generations": wind_generations,
                    "triangles": test.triangles,
                    "adapter": self.renderer.adapter_name(),
                });
                let _ = std::fs::write(test.dir.join("viewer.json"), report.to_string());
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        ctx.request_repaint();
    }
}

impl eframe::App for Viewer {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        // Frame time as the user feels it: from one frame to the next.
        self.frame_ms = 0.9 * self.frame_ms + 0.1 * ctx.input(|i| i.unstable_dt as f64) * 1e3;
        self.receive();
        let mut changed = false;
        egui::Panel::left("parameters")
            .resizable(true)
            .show(ui, |ui| {
                ui.heading(&self.params.name);
                ui.horizontal(|ui| {
                    ui.label("seed");
                    changed |= ui.add(egui::DragValue::new(&mut self.seed)).changed();
                    if ui.button("new seed").clicked() {
                        self.seed =
                            sylva::rng::mix64(self.seed ^ self.started.elapsed().as_nanos() as u64)
                                % 100_000;
                        changed = true;
                    }
                });
                ui.horizontal(|ui| {
                    ui.label("levels shown");
                    for k in 1..=self.params.levels {
                        changed |= ui
                            .selectable_value(&mut self.shown_levels, k, k.to_string())
                            .changed();
                    }
                    changed |= ui.checkbox(&mut self.show_leaves, "leaves").changed();
                });
                ui.horizontal(|ui| {
                    ui.label("quality");
                    changed |= ui
                        .add(egui::Slider::new(&mut self.quality, 0.1..=2.0))
                        .changed();
                });
                ui.horizontal(|ui| {
                    changed |= ui.checkbox(&mut self.wind_on, "wind").changed();
                    changed |= ui
                        .add(egui::Slider::new(&mut self.wind_speed, 0.0..=30.0).text("speed"))
                        .changed();
                    changed |= ui
                        .add(egui::Slider::new(&mut self.wind_gust, 0.0..=30.0).text("gust"))
                        .changed();
                });
                ui.separator();
                ui.horizontal(|ui| {
                    ui.text_edit_singleline(&mut self.file);
                    if ui.button("load").clicked() {
                        self.load_species();
                    }
                    if ui.button("save").clicked() {
                        self.save_species();
                    }
                });
                ui.horizontal(|ui| {
                    ui.text_edit_singleline(&mut self.export);
                    if ui
                        .button("export")
                        .on_hover_text(".glb, .obj or .png")
                        .clicked()
                    {
                        self.export();
                    }
                });
                ui.separator();
                egui::ScrollArea::vertical().show(ui, |ui| {
                    changed |= panel::parameters(ui, &mut self.params);
                });
            });
        egui::Panel::bottom("stats").show(ui, |ui| {
            self.stats_ui(ui);
            if !self.status.is_empty() {
                ui.colored_label(egui::Color32::from_rgb(200, 80, 40), &self.status);
            }
        });
        egui::CentralPanel::default().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let ppp = ctx.pixels_per_point();
            let size = [(rect.width() * ppp) as u32, (rect.height() * ppp) as u32];
            let response = ui.allocate_rect(rect, egui::Sense::drag());
            self.camera_input(&response, ui);
            // While the camera moves, draw at half resolution (a quarter of the pixels) so that
            // orbiting stays smooth on a software driver; the full picture follows on release.
            let moving = response.dragged();
            if self.moving != moving {
                self.moving = moving;
                self.needs_render = true;
            }
            let draft = if moving {
                [size[0] / 2, size[1] / 2]
            } else {
                size
            };
            self.draw_view(draft);
            if !show_texture(ui, rect, &self.texture) {
                ui.centered_and_justified(|ui| ui.label("growing the tree..."));
            }
        });
        if changed {
            self.regenerate();
        }
        if self.wind_on {
            // Re-form the tree for the current moment as soon as the last one is done.
            if !self.worker.busy() {
                self.regenerate();
            }
            ctx.request_repaint();
        }
        self.self_test_step(&ctx);
    }
}
