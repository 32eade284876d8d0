//! Growth charts drawn with plotters: five panels (height, crown height, crown diameter, DBH,
//! leaf area against age), the equations as a curve and the grown tree as points. Text in the
//! captions' bundled font, so no system fonts are needed.

use crate::{FrameStats, Picture, RenderError};
use plotters::prelude::*;
use sylva::growth::Measured;
use sylva::growth::Targets;
use sylva::growth::survey::report::{AgeRecord, CHARTED};
use sylva::street::accounts::items::{Benefit, Cost, Item};
use sylva::street::{Basis, YearAccount};

/// What plotters may fail with, boxed.
type Drawn<T> = Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// Makes the bundled font plotters' "sans-serif", once.
fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The captions' font, compiled in and known to parse.
        let _ = plotters::style::register_font(
            "sans-serif",
            plotters::style::FontStyle::Normal,
            crate::caption::FONT,
        );
    });
}

/// The chart of one species' history as a picture.
pub fn growth_chart(m: &Measured, history: &[AgeRecord]) -> Result<Picture, RenderError> {
    draw_growth(m, history).map_err(|e| RenderError::Chart(e.to_string()))
}

fn draw_growth(m: &Measured, history: &[AgeRecord]) -> Drawn<Picture> {
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
    Ok(rgb_picture(&buffer, w, h))
}

/// Linsen et al.'s (2005) yearly bars, every item of the account's table
/// (`sylva::street::accounts::items`): i-Tree Streets' benefit categories stacked above zero,
/// the costs below with a winter heating penalty and BVOC emissions, and the net as a line;
/// read from the account of `basis` (the typical position or this site).
pub fn benefit_chart(
    m: &Measured,
    accounts: &[YearAccount],
    missing: &[String],
    basis: Basis,
) -> Result<Picture, RenderError> {
    draw_benefits(m, accounts, missing, basis).map_err(|e| RenderError::Chart(e.to_string()))
}

fn draw_benefits(
    m: &Measured,
    accounts: &[YearAccount],
    missing: &[String],
    basis: Basis,
) -> Drawn<Picture> {
    register_font();
    let (w, h) = (1500u32, 900u32);
    let mut buffer = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        // What was not counted, wrapped to the chart's width, at most eight lines.
        let mut lines: Vec<String> = Vec::new();
        for note in missing {
            let mut line = String::from("not counted:");
            for word in note.split(' ') {
                if line.len() + word.len() > 150 {
                    lines.push(std::mem::take(&mut line));
                    line.push_str("    ");
                }
                line.push(' ');
                line.push_str(word);
            }
            lines.push(line);
        }
        lines.truncate(8);
        let (plot, notes) = root.split_vertically(h - 30 - 22 * lines.len() as u32);
        let bars = bars(basis);
        let ups = |a: &YearAccount| bars.iter().map(|b| b.up(a)).collect::<Vec<f64>>();
        let downs = |a: &YearAccount| bars.iter().map(|b| b.down(a)).collect::<Vec<f64>>();
        let top = accounts
            .iter()
            .map(|a| ups(a).iter().sum::<f64>())
            .fold(1.0f64, f64::max)
            * 1.1;
        // The axis holds every bar and the net line, however far below the costs take it.
        let bottom = accounts
            .iter()
            .map(|a| downs(a).iter().sum::<f64>().max(-a.net(basis)))
            .fold(0.0f64, f64::max)
            * 1.1;
        let a0 = accounts.first().map_or(0.0, |a| a.age) - 0.5;
        let a1 = accounts.last().map_or(1.0, |a| a.age) + 0.5;
        let mut chart = ChartBuilder::on(&plot)
            .caption(
                format!(
                    "{} in {}, {}: a living tree's benefits (up), costs (down), $ a year; \
                     {:.0}% of those planted alive at {}",
                    m.label(),
                    m.region.code,
                    basis.name(),
                    100.0 * accounts.last().map_or(1.0, |a| a.cohort.alive_at_end),
                    accounts.last().map_or(0.0, |a| a.age)
                ),
                ("sans-serif", 22),
            )
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(a0..a1, -bottom.max(top * 0.05)..top)?;
        chart
            .configure_mesh()
            .x_desc("age (years)")
            .y_desc("$ per year")
            .label_style(("sans-serif", 16))
            .draw()?;
        for (k, bar) in bars.iter().enumerate() {
            if accounts.iter().all(|a| ups(a)[k] == 0.0) {
                continue;
            }
            let [r, g, b] = bar.item.rgb();
            let colour = RGBColor(r, g, b);
            let rects = accounts.iter().map(|a| {
                let v = ups(a);
                let below: f64 = v[..k].iter().sum();
                Rectangle::new(
                    [(a.age - 0.35, below), (a.age + 0.35, below + v[k])],
                    colour.filled(),
                )
            });
            chart
                .draw_series(rects)?
                .label(bar.item.label)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 14, y + 6)], colour.filled())
                });
        }
        for (k, bar) in bars.iter().enumerate() {
            if accounts.iter().all(|a| downs(a)[k] == 0.0) {
                continue;
            }
            let [r, g, b] = bar.item.rgb();
            let colour = RGBColor(r, g, b);
            // A benefit drawn below the line (a heating penalty, BVOCs) is named as such.
            let label = match bar.benefit {
                Some(_) => format!("{} (below zero)", bar.item.label),
                None => bar.item.label.to_string(),
            };
            let rects = accounts.iter().map(|a| {
                let v = downs(a);
                let above: f64 = v[..k].iter().sum();
                Rectangle::new(
                    [(a.age - 0.35, -above), (a.age + 0.35, -above - v[k])],
                    colour.filled(),
                )
            });
            chart
                .draw_series(rects)?
                .label(label)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 14, y + 6)], colour.filled())
                });
        }
        chart
            .draw_series(LineSeries::new(
                accounts.iter().map(|a| (a.age, a.net(basis))),
                BLACK.stroke_width(3),
            ))?
            .label("net")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 14, y)], BLACK.stroke_width(3)));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 16))
            .draw()?;
        for (i, line) in lines.iter().enumerate() {
            notes.draw_text(
                line,
                &("sans-serif", 17).into_font().color(&RGBColor(90, 90, 90)),
                (70, 6 + 22 * i as i32),
            )?;
        }
        root.present()?;
    }
    Ok(rgb_picture(&buffer, w, h))
}

/// One series of the bars: a benefit category or a cost item of the account's table
/// (`sylva::street::accounts::items`), every one of them in the table's order.
struct Bar {
    item: &'static Item,
    benefit: Option<Benefit>,
    cost: Option<Cost>,
    basis: Basis,
}

impl Bar {
    /// What it adds above zero in a year: a benefit's positive dollars.
    fn up(&self, a: &YearAccount) -> f64 {
        (self.benefit)
            .and_then(|b| a.money(self.basis).get(b))
            .map_or(0.0, |v| v.max(0.0))
    }

    /// What it takes below zero: a negative benefit (a heating penalty, BVOCs) or a cost.
    fn down(&self, a: &YearAccount) -> f64 {
        match (self.benefit, self.cost) {
            (Some(b), _) => -a.money(self.basis).get(b).unwrap_or(0.0).min(0.0),
            (_, Some(c)) => a.costs.map_or(0.0, |y| y[c]),
            _ => 0.0,
        }
    }
}

/// Every item of the account's table as a series, benefits first.
fn bars(basis: Basis) -> Vec<Bar> {
    let benefits = Benefit::ALL.map(|b| Bar {
        item: b.item(),
        benefit: Some(b),
        cost: None,
        basis,
    });
    let costs = Cost::ALL.map(|c| Bar {
        item: c.item(),
        benefit: None,
        cost: Some(c),
        basis,
    });
    benefits.into_iter().chain(costs).collect()
}

/// plotters' RGB buffer as a picture.
fn rgb_picture(buffer: &[u8], width: u32, height: u32) -> Picture {
    Picture {
        width,
        height,
        rgba: buffer
            .chunks(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
        stats: FrameStats::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::street::accounts::items;

    /// The bars are every item of the account's one table, once each, in its order: a new
    /// item is drawn without touching the chart.
    #[test]
    fn the_bars_draw_every_item_of_the_table() {
        let drawn: Vec<&str> = bars(Basis::Site).iter().map(|b| b.item.key).collect();
        let table: Vec<&str> = items::all().map(|i| i.key).collect();
        assert_eq!(drawn, table);
    }
}
