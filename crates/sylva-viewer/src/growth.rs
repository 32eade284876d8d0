//! `sylva grow SPECIES --compare A,B --view`: watch street trees grow side by side. A worker
//! thread grows every species year by year and hands over each age's skeleton; the window
//! shows any age grown so far (the slider), or plays the years in turn.

use crate::window::{
    Screenshots, Turntable, ViewTexture, ensure_texture, render_timed, renderer_of, show_texture,
    window,
};
use anyhow::Result;
use eframe::{egui, egui_wgpu};
use glam::Vec3;
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::Instant;
use sylva::Skeleton;
use sylva::growth::{
    Dimensions, Dress, Grower, GrowthOptions, Measured, Month, Targets, dressed_mesh, measure,
};
use sylva_render::{Placement, RenderTree, Renderer, Scene, Stand, View};

/// One species at one age, as the worker sends it.
struct Grown {
    species: usize,
    age: usize,
    skeleton: Skeleton,
    dimensions: Dimensions,
}

/// Opens the window (blocks until it is closed).
pub fn watch_growth(
    species: Vec<Measured>,
    ages: Vec<f64>,
    seed: u64,
    season: Option<Month>,
    self_test: Option<PathBuf>,
) -> Result<()> {
    let names: Vec<String> = species.iter().map(|m| m.species.common.clone()).collect();
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(format!("Sylva: {} growing", names.join(", ")))
            .with_inner_size([1280.0, 800.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    window("sylva-grow", options, move |cc| {
        GrowthViewer::new(cc, species, ages, seed, season, self_test)
    })
}

/// Grows every species through the ages in step, sending each as it is reached; stops when
/// the window has gone.
fn grow_in_background(species: Vec<Measured>, ages: Vec<f64>, seed: u64, send: Sender<Grown>) {
    std::thread::spawn(move || {
        let mut growers: Vec<Grower> = species
            .into_iter()
            .map(|m| {
                Grower::new(
                    m,
                    GrowthOptions {
                        seed,
                        ..Default::default()
                    },
                )
            })
            .collect();
        for (k, &age) in ages.iter().enumerate() {
            for (i, g) in growers.iter_mut().enumerate() {
                g.advance_to(age);
                let skeleton = g.skeleton();
                let dimensions = measure(&skeleton);
                let grown = Grown {
                    species: i,
                    age: k,
                    skeleton,
                    dimensions,
                };
                if send.send(grown).is_err() {
                    return;
                }
            }
        }
    });
}

/// Scripted run for tests: pictures at the first, middle and last age, then play from the
/// start for a while, a report, close.
struct SelfTest {
    dir: PathBuf,
    step: usize,
    shots: Screenshots,
    shown: Vec<serde_json::Value>,
    started: Instant,
    play_started: Option<Instant>,
}

struct GrowthViewer {
    renderer: Renderer,
    render_state: egui_wgpu::RenderState,
    species: Vec<Measured>,
    ages: Vec<f64>,
    /// Skeleton and measured dimensions by species, then by age index.
    grown: Vec<Vec<Option<(Skeleton, Dimensions)>>>,
    receive: Receiver<Grown>,
    /// The age index on screen, and the one the GPU trees are of.
    age: usize,
    uploaded: Option<usize>,
    /// Each species' tree on the GPU, its flowers where it flowers, and how it is dressed.
    trees: Vec<(RenderTree, Option<RenderTree>, Dress)>,
    /// The month the trees are dressed for; `None`: summer leaves, no flowers.
    month: Option<Month>,
    playing: bool,
    years_per_second: f32,
    /// Fraction of a year played since the last step.
    play_clock: f32,
    /// Orbit about the row of trees, degrees, and zoom.
    turntable: Turntable,
    /// Tallest and widest tree the data predict over the ages, m: a fixed frame, so that
    /// ages compare.
    tallest: f32,
    widest: f32,
    texture: Option<ViewTexture>,
    needs_render: bool,
    frame_ms: f64,
    self_test: Option<SelfTest>,
}

impl GrowthViewer {
    fn new(
        cc: &eframe::CreationContext<'_>,
        species: Vec<Measured>,
        ages: Vec<f64>,
        seed: u64,
        month: Option<Month>,
        self_test: Option<PathBuf>,
    ) -> Result<Self> {
        let (renderer, render_state) = renderer_of(cc)?;
        let (mut tallest, mut widest) = (1.8f32, 1.0f32);
        for m in &species {
            for &age in &ages {
                let t = Targets::of(m, age);
                tallest = tallest.max(t.height as f32);
                widest = widest.max(t.crown_diameter as f32);
            }
        }
        let (send, receive) = channel();
        grow_in_background(species.clone(), ages.clone(), seed, send);
        let grown = vec![vec![None; ages.len()]; species.len()];
        let self_test = self_test.map(|dir| SelfTest {
            shots: Screenshots::new(dir.clone(), "grow-viewer"),
            dir,
            step: 0,
            shown: Vec::new(),
            started: Instant::now(),
            play_started: None,
        });
        Ok(Self {
            renderer,
            render_state,
            species,
            ages,
            grown,
            receive,
            age: 0,
            uploaded: None,
            trees: Vec::new(),
            month,
            playing: false,
            years_per_second: 2.0,
            play_clock: 0.0,
            turntable: Turntable::new(8.0),
            tallest: tallest * 1.1,
            widest: widest * 1.15,
            texture: None,
            needs_render: true,
            frame_ms: 0.0,
            self_test,
        })
    }

    /// Ages grown for every species so far.
    fn ready(&self) -> usize {
        (0..self.ages.len())
            .take_while(|&k| self.grown.iter().all(|g| g[k].is_some()))
            .count()
    }

    fn receive(&mut self) {
        while let Ok(g) = self.receive.try_recv() {
            self.grown[g.species][g.age] = Some((g.skeleton, g.dimensions));
        }
    }

    /// Where tree `i` stands: in a row along x, a crown's width apart.
    fn position(&self, i: usize) -> Vec3 {
        let n = self.species.len() as f32;
        Vec3::new((i as f32 - (n - 1.0) / 2.0) * (self.widest + 1.0), 0.0, 0.0)
    }

    /// The fixed frame, turned and zoomed by the user.
    fn view(&self, aspect: f32) -> View {
        let across = (self.widest + 1.0) * self.species.len() as f32 + 2.0;
        let height = self.tallest + 0.5;
        self.turntable
            .view(glam::Vec2::ZERO, across, height, aspect, 1.05)
    }

    /// Meshes and uploads the shown age when it is ready and not yet on the GPU.
    fn upload(&mut self) {
        if self.uploaded == Some(self.age) || self.age >= self.ready() {
            return;
        }
        let options = sylva::growth::survey::report::MESH;
        self.trees = self
            .grown
            .iter()
            .zip(&self.species)
            .map(|(g, m)| {
                let (skeleton, _) = g[self.age].as_ref().expect("ready");
                let (mesh, dress) = dressed_mesh(skeleton, m, self.month, &options);
                let flowers = self.renderer.upload_flowers(&mesh);
                (self.renderer.upload(&mesh), flowers, dress)
            })
            .collect();
        self.uploaded = Some(self.age);
        self.needs_render = true;
    }

    fn scene(&self) -> Scene<'_> {
        let stands = self
            .trees
            .iter()
            .enumerate()
            .flat_map(|(i, (tree, flowers, dress))| {
                let stand = Stand {
                    tree,
                    bark: dress.bark,
                    leaves: dress.leaves,
                    placements: Cow::Owned(vec![Placement {
                        position: self.position(i),
                        ..Placement::ORIGIN
                    }]),
                };
                stand.with_flowers(flowers.as_ref().zip(dress.flowers))
            })
            .collect();
        let mut scene = Scene::forest(stands);
        scene.show_person = true;
        scene
    }

    fn draw(&mut self, size: [u32; 2]) {
        let size = [size[0].clamp(16, 4096), size[1].clamp(16, 4096)];
        if ensure_texture(&self.render_state, &mut self.texture, size) {
            self.needs_render = true;
        }
        if self.trees.is_empty() || !self.needs_render {
            return;
        }
        let Some(texture) = &self.texture else {
            return;
        };
        let view = self.view(size[0] as f32 / size[1] as f32);
        let (_, ms) = render_timed(
            &self.renderer,
            &self.render_state,
            &self.scene(),
            &view,
            texture,
        );
        self.frame_ms = ms;
        self.needs_render = false;
    }

    /// Play: whole steps of the age list at the chosen pace, waiting where the worker has
    /// not got to yet, stopping at the last age.
    fn play(&mut self, dt: f32) {
        if !self.playing {
            return;
        }
        let step = self.ages.get(1).map_or(1.0, |a| a - self.ages[0]) as f32;
        self.play_clock += dt * self.years_per_second / step.max(1e-3);
        if self.play_clock >= 1.0 {
            self.play_clock = 0.0;
            if self.age + 1 < self.ready() {
                self.age += 1;
            } else if self.age + 1 >= self.ages.len() {
                self.playing = false;
            }
        }
    }

    /// Each tree's name, age and height under it.
    fn labels(&self, ui: &egui::Ui, rect: egui::Rect) {
        let Some((texture, Some(age))) = self.texture.as_ref().map(|t| (t, self.uploaded)) else {
            return;
        };
        let [w, h] = texture.size;
        let scene = self.scene();
        let camera = scene.camera(&self.view(w as f32 / h as f32), w as f32 / h as f32);
        let ppp = ui.ctx().pixels_per_point();
        for (i, (m, g)) in self.species.iter().zip(&self.grown).enumerate() {
            let Some((x, y)) = camera.project(self.position(i), w, h) else {
                continue;
            };
            let height = g[age].as_ref().map_or(0.0, |(_, d)| d.height);
            ui.painter().text(
                rect.min + egui::vec2(x / ppp, y / ppp + 8.0),
                egui::Align2::CENTER_TOP,
                format!("{}\n{height:.1} m", m.species.common),
                egui::FontId::proportional(15.0),
                egui::Color32::from_gray(20),
            );
        }
    }

    fn controls(&mut self, ui: &mut egui::Ui) {
        let ready = self.ready();
        ui.horizontal(|ui| {
            let label = if self.playing { "pause" } else { "play" };
            if ui.button(label).clicked() {
                if !self.playing && self.age + 1 >= self.ages.len() {
                    self.age = 0;
                }
                self.playing = !self.playing;
            }
            let last = self.ages.len().saturating_sub(1);
            let mut age = self.age;
            let slider = egui::Slider::new(&mut age, 0..=last)
                .custom_formatter(|k, _| format!("{}", self.ages[k as usize]))
                .text("age (years)");
            if ui.add(slider).changed() {
                self.playing = false;
                self.age = age.min(ready.saturating_sub(1));
            }
            ui.add(
                egui::Slider::new(&mut self.years_per_second, 0.25..=10.0)
                    .logarithmic(true)
                    .text("years per second"),
            );
            // Growth is the same in every season: a new month only dresses the trees again.
            let name = |m: Option<Month>| m.map_or("no season (summer leaves)", Month::label);
            let before = self.month;
            egui::ComboBox::from_label("season")
                .selected_text(name(self.month))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.month, None, name(None));
                    for m in (1..=12).filter_map(Month::new) {
                        ui.selectable_value(&mut self.month, Some(m), m.name());
                    }
                });
            if self.month != before {
                self.uploaded = None;
            }
            if ready < self.ages.len() {
                ui.label(format!(
                    "growing: {} of {} ages ready",
                    ready,
                    self.ages.len()
                ));
            }
        });
        if let Some(age) = self.uploaded {
            let rows: Vec<String> = self
                .species
                .iter()
                .zip(&self.grown)
                .map(|(m, g)| {
                    let t = Targets::of(m, self.ages[age]);
                    let d = g[age].as_ref().map_or(Dimensions::default(), |(_, d)| *d);
                    format!(
                        "{}: height {:.1} m ({:.1} measured), crown {:.1} m ({:.1}), DBH {:.0} cm \
                         ({:.0})",
                        m.species.common,
                        d.height,
                        t.height,
                        d.crown_diameter,
                        t.crown_diameter,
                        d.dbh,
                        t.dbh
                    )
                })
                .collect();
            ui.label(format!(
                "age {}   |   {}   |   {:.0} ms a frame",
                self.ages[age],
                rows.join("   |   "),
                self.frame_ms
            ));
        }
        ui.label("drag: turn and tilt   wheel: zoom");
    }

    fn self_test_step(&mut self, ctx: &egui::Context) {
        let ready = self.ready();
        let (settled, last) = (
            self.uploaded == Some(self.age) && !self.needs_render,
            self.ages.len() - 1,
        );
        let frame_ms = self.frame_ms;
        let shown = self.age;
        let triangles: usize = self
            .trees
            .iter()
            .map(|(t, f, _)| t.triangles + f.as_ref().map_or(0, |f| f.triangles))
            .sum();
        let Some(test) = &mut self.self_test else {
            return;
        };
        test.step += test.shots.save_arrived() as usize;
        ctx.request_repaint();
        if test.started.elapsed().as_secs() > 240 {
            eprintln!("sylva: self-test timed out at step {}", test.step);
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            self.self_test = None;
            return;
        }
        // Pictures at the first, middle and last age once all are grown, then play.
        let targets = [0, last / 2, last];
        if test.step < 3 {
            if ready <= last || test.shots.waiting {
                return;
            }
            let want = targets[test.step];
            if shown != want {
                self.age = want;
                return;
            }
            if !settled {
                return;
            }
            test.shown.push(serde_json::json!({
                "age": self.ages[shown],
                "triangles": triangles,
                "frame_ms": frame_ms,
            }));
            test.shots.take(ctx, test.step as u32);
            return;
        }
        match test.play_started {
            None => {
                self.age = 0;
                self.years_per_second = 10.0;
                self.playing = true;
                test.play_started = Some(Instant::now());
            }
            Some(since) if self.playing && since.elapsed().as_secs() < 30 => {}
            Some(_) => {
                let report = serde_json::json!({
                    "species": self.species.iter().map(|m| m.species.code.clone()).collect::<Vec<_>>(),
                    "ages": self.ages,
                    "shown": test.shown,
                    "played_to": self.ages[self.age],
                    "season": self.month.map(Month::label),
                    "adapter": self.renderer.adapter_name(),
                });
                let _ = std::fs::write(test.dir.join("grow-viewer.json"), report.to_string());
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                self.self_test = None;
            }
        }
    }
}

impl eframe::App for GrowthViewer {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.receive();
        let dt = ui.input(|i| i.stable_dt.min(0.1));
        self.play(dt);
        self.upload();
        egui::Panel::top("growth controls").show(ui, |ui| self.controls(ui));
        egui::CentralPanel::default().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let ppp = ui.ctx().pixels_per_point();
            let response = ui.allocate_rect(rect, egui::Sense::drag());
            if self.turntable.handle(&response, ui) {
                self.needs_render = true;
            }
            self.draw([(rect.width() * ppp) as u32, (rect.height() * ppp) as u32]);
            show_texture(ui, rect, &self.texture);
            self.labels(ui, rect);
        });
        let ctx = ui.ctx().clone();
        if self.playing || self.ready() < self.ages.len() {
            ctx.request_repaint();
        }
        self.self_test_step(&ctx);
    }
}
