//! Sylva's windows: the parameter editor, and viewers for a model file, a forest and street
//! trees growing. Each is an eframe/egui app whose 3-D view is drawn by `sylva-render`'s
//! [`Renderer`](sylva_render::Renderer) on eframe's own wgpu device, into a texture egui shows.
//!
//! A window needs a display and a graphics driver; a viewer cannot fall back to the CPU as
//! pictures do, so a window that cannot open, or a GPU that fails while it is open, is an
//! error saying what is missing. Every viewer has a scripted self-test (`self_test`: a folder)
//! that takes screenshots, writes a JSON report there and closes, so tests can run it under
//! Xvfb.

mod editor;
mod forest;
mod growth;
mod model;
mod panel;
mod window;
mod worker;

pub use editor::edit;
pub use forest::fly_through;
pub use growth::watch_growth;
pub use model::{look_at, look_at_scene};
