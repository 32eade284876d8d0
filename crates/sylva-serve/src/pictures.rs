//! Pictures the page offers for download, drawn by Sylva's own renderer (the first backend
//! that starts: Vulkan, OpenGL or the CPU), which is started once, on the first picture.

use crate::cache::Entry;
use crate::grown::{ages_of, full_mesh};
use crate::params::ApiError;
use std::sync::Mutex;
use sylva::growth::Measured;
use sylva::growth::survey::report::age_label;
use sylva_render::caption::with_caption;
use sylva_render::street::comparison_picture;
use sylva_render::{Choice, Renderer};

/// The renderer, started when first needed; a renderer that failed to start says why on
/// every request rather than retrying a broken driver each time.
#[derive(Default)]
pub struct Pictures {
    renderer: Mutex<Option<Result<Renderer, String>>>,
}

impl Pictures {
    /// The species side by side at `age`, captioned with their heights, as PNG.
    pub fn compare(
        &self,
        species: &[Measured],
        entries: &[Entry],
        age: u32,
        size: (u32, u32),
    ) -> Result<Vec<u8>, ApiError> {
        let mut slot = self.renderer.lock().unwrap_or_else(|e| e.into_inner());
        let renderer = slot.get_or_insert_with(|| {
            let choice = Choice::from_env().map_err(|e| e.to_string())?;
            Renderer::headless(choice, |note| eprintln!("sylva serve: {note}"))
                .map_err(|e| e.to_string())
        });
        let r = renderer
            .as_ref()
            .map_err(|e| ApiError::internal(format!("no renderer: {e}")))?;
        let (meshes, dresses): (Vec<_>, Vec<_>) = entries
            .iter()
            .zip(species)
            .map(|(e, m)| full_mesh(&e.skeleton, m))
            .unzip();
        // One frame for every age of these species, as `sylva grow --compare` keeps it, so
        // that pictures of different ages compare.
        let mut extent = (2.0f64, 1.0f64);
        for m in species {
            for a in ages_of(m) {
                extent.0 = extent.0.max(m.height(f64::from(a)));
                extent.1 = extent.1.max(m.crown_diameter(f64::from(a)));
            }
        }
        let picture = comparison_picture(r, &meshes, &dresses, species, size, extent)
            .map_err(|e| ApiError::internal(format!("drawing the comparison: {e}")))?;
        let heights: Vec<String> = species
            .iter()
            .zip(entries)
            .map(|(m, e)| {
                format!(
                    "{} {:.1} m, net ${:.0}/yr",
                    m.species.common,
                    e.record.model.height,
                    e.accounts[0].net(sylva::street::Basis::Site)
                )
            })
            .collect();
        let lines = [format!(
            "age {}: {} (narrow site under wires)",
            age_label(f64::from(age)),
            heights.join(", ")
        )];
        let picture = with_caption(&picture, &lines, 18.0);
        picture
            .to_png()
            .map_err(|e| ApiError::internal(format!("encoding the picture: {e}")))
    }
}
