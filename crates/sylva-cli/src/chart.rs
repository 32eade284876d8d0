//! Growth charts drawn with plotters: five panels (height, crown height, crown diameter, DBH,
//! leaf area against age), the equations as a curve and the grown tree as points. Text in the
//! captions' bundled font, so no system fonts are needed.

use anyhow::Result;
use plotters::prelude::*;
use sylva::growth::Measured;
use sylva::growth::Targets;
use sylva::growth::report::{AgeRecord, CHARTED};
use sylva_render::{FrameStats, Picture};

/// Makes the bundled font plotters' "sans-serif", once.
fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The captions' font, compiled in and known to parse.
        let _ = plotters::style::register_font(
            "sans-serif",
            plotters::style::FontStyle::Normal,
            sylva_render::caption::FONT,
        );
    });
}

/// The chart of one species' history as a picture.
pub fn growth_chart(m: &Measured, history: &[AgeRecord]) -> Result<Picture> {
    register_font();
    let (w, h) = (1500u32, 900u32);
    let mut buffer = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(
            &format!(
                "{} in {}: grown (points) against the equations (line)",
                m.label(),
                m.region.code
            ),
            ("sans-serif", 26),
        )?;
        let panels = root.split_evenly((2, 3));
        let a0 = history.first().map_or(0.0, |g| g.age);
        let a1 = history.last().map_or(1.0, |g| g.age).max(a0 + 1.0);
        for (panel, q) in panels.iter().zip(&CHARTED) {
            let top = history
                .iter()
                .map(|g| (q.model)(&g.model).max((q.measured)(&g.measured)))
                .fold(0.0f64, f64::max)
                * 1.1
                + 1e-6;
            let mut chart = ChartBuilder::on(panel)
                .caption(q.name, ("sans-serif", 22))
                .margin(12)
                .x_label_area_size(36)
                .y_label_area_size(56)
                .build_cartesian_2d(a0..a1, 0.0..top)?;
            chart
                .configure_mesh()
                .x_desc("age (years)")
                .label_style(("sans-serif", 15))
                .draw()?;
            let steps = 200;
            let curve = (0..=steps).map(|i| {
                let a = a0 + (a1 - a0) * i as f64 / steps as f64;
                (a, (q.measured)(&Targets::of(m, a)))
            });
            chart.draw_series(LineSeries::new(curve, BLUE.stroke_width(2)))?;
            chart.draw_series(
                history
                    .iter()
                    .map(|g| Circle::new((g.age, (q.model)(&g.model)), 4, RED.filled())),
            )?;
        }
        root.present()?;
    }
    Ok(Picture {
        width: w,
        height: h,
        rgba: buffer
            .chunks(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
        stats: FrameStats::default(),
    })
}
