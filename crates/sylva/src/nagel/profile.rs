//! Reading what the user drew: a canopy profile for a whisk tree, or branches for a stick tree.
//!
//! Nagel digitised these on a tablet; here they come as CSV (metres) or as an SVG polyline
//! (drawn in any editor). A profile is the canopy's right half in a vertical plane: radius from
//! the trunk's axis and height above the ground, from the canopy's base to its top.

use crate::error::ParamsError;
use crate::params::arbaro::line_at;
use quick_xml::events::Event;

/// A canopy outline: (radius, height) in metres, in drawing order.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// The points; radius ≥ 0, height ≥ 0.
    pub points: Vec<[f64; 2]>,
}

/// Largest number of points read from one file (a budget against runaway input).
pub const MAX_POINTS: usize = 100_000;

fn syntax(name: &str, line: usize, message: String) -> ParamsError {
    ParamsError::Syntax {
        source_name: format!("{name}, line {line}"),
        message,
    }
}

/// Numbers of a CSV line: commas, semicolons or spaces between values.
fn fields(line: &str) -> Vec<&str> {
    line.split(|c: char| c == ',' || c == ';' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .collect()
}

/// Rows of numbers of a CSV file with `columns` values each, with their line numbers. A first
/// row that is not numeric is a header; `#` starts a comment line.
fn csv_rows(
    text: &str,
    name: &str,
    columns: &[&str],
) -> Result<Vec<(usize, Vec<f64>)>, ParamsError> {
    let mut rows = Vec::new();
    let mut first = true;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells = fields(line);
        let numbers: Option<Vec<f64>> = cells.iter().map(|c| c.parse::<f64>().ok()).collect();
        let header = first && numbers.is_none();
        first = false;
        if header {
            continue;
        }
        let Some(numbers) = numbers else {
            return Err(syntax(
                name,
                i + 1,
                format!("expected numbers ({}), found `{line}`", columns.join(", ")),
            ));
        };
        if numbers.len() != columns.len() {
            return Err(syntax(
                name,
                i + 1,
                format!(
                    "expected {} values ({}), found {}",
                    columns.len(),
                    columns.join(", "),
                    numbers.len()
                ),
            ));
        }
        if let Some(bad) = numbers.iter().find(|v| !v.is_finite()) {
            return Err(syntax(name, i + 1, format!("{bad} is not a finite number")));
        }
        if rows.len() >= MAX_POINTS {
            return Err(syntax(
                name,
                i + 1,
                format!("more than {MAX_POINTS} points; simplify the outline"),
            ));
        }
        rows.push((i + 1, numbers));
    }
    Ok(rows)
}

/// Checks one point: radius and height not negative.
fn check_point(name: &str, line: usize, r: f64, h: f64) -> Result<(), ParamsError> {
    if r < 0.0 {
        return Err(syntax(
            name,
            line,
            format!(
                "radius {r} is negative; a profile is the canopy's right half, radius 0 at the trunk"
            ),
        ));
    }
    if h < 0.0 {
        return Err(syntax(
            name,
            line,
            format!("height {h} is below the ground; heights are 0 or more"),
        ));
    }
    Ok(())
}

/// Scales points so that the highest is `height` metres.
fn scale_to(points: &mut [[f64; 2]], height: Option<f64>) {
    let Some(height) = height else { return };
    let top = points.iter().map(|p| p[1]).fold(0.0, f64::max);
    if top > 0.0 {
        for p in points {
            p[0] *= height / top;
            p[1] *= height / top;
        }
    }
}

/// Reads a profile from a `.csv` (`radius,height` rows, metres) or `.svg` file's text (the first
/// `<polyline>` or `<polygon>`; its first point is on the trunk's axis, the ground is the bottom
/// of the viewBox). `height`, when given, scales the profile so its top is that high; an SVG
/// without it is scaled to 10 m.
pub fn read_profile(name: &str, text: &str, height: Option<f64>) -> Result<Profile, ParamsError> {
    let mut points = if name.to_ascii_lowercase().ends_with(".svg") {
        let points = svg_polyline(name, text)?;
        scale_to_default(points, height)
    } else {
        let rows = csv_rows(text, name, &["radius", "height"])?;
        for (line, v) in &rows {
            check_point(name, *line, v[0], v[1])?;
        }
        let mut points: Vec<[f64; 2]> = rows.iter().map(|(_, v)| [v[0], v[1]]).collect();
        scale_to(&mut points, height);
        points
    };
    if points.len() < 2 {
        return Err(ParamsError::Syntax {
            source_name: name.into(),
            message: format!("a profile needs at least 2 points, found {}", points.len()),
        });
    }
    // Nagel's digitiser dropped repeated points; a rib through the same point twice would make
    // a zero-length segment.
    points.dedup();
    Ok(Profile { points })
}

fn scale_to_default(mut points: Vec<[f64; 2]>, height: Option<f64>) -> Vec<[f64; 2]> {
    scale_to(&mut points, Some(height.unwrap_or(10.0)));
    points
}

/// Reads stick-tree branches: `branch,radius,height` rows (metres); rows with the same branch
/// number, in order, are one branch's polyline from its base on the trunk to its tip.
pub fn read_sticks(
    name: &str,
    text: &str,
    height: Option<f64>,
) -> Result<Vec<Vec<[f64; 2]>>, ParamsError> {
    let rows = csv_rows(text, name, &["branch", "radius", "height"])?;
    let mut branches: Vec<(f64, Vec<[f64; 2]>)> = Vec::new();
    for (line, v) in &rows {
        check_point(name, *line, v[1], v[2])?;
        match branches.last_mut() {
            Some((id, points)) if *id == v[0] => points.push([v[1], v[2]]),
            _ => {
                if branches.iter().any(|(id, _)| *id == v[0]) {
                    return Err(syntax(
                        name,
                        *line,
                        format!(
                            "branch {} continues after another branch; keep each branch's rows together",
                            v[0]
                        ),
                    ));
                }
                branches.push((v[0], vec![[v[1], v[2]]]));
            }
        }
    }
    if branches.is_empty() {
        return Err(ParamsError::Syntax {
            source_name: name.into(),
            message: "no branches: expected `branch,radius,height` rows".into(),
        });
    }
    for (id, points) in &branches {
        if points.len() < 2 {
            return Err(ParamsError::Syntax {
                source_name: name.into(),
                message: format!("branch {id} has one point; a branch needs two or more"),
            });
        }
    }
    let top = branches
        .iter()
        .flat_map(|(_, p)| p.iter().map(|q| q[1]))
        .fold(0.0, f64::max);
    let k = match height {
        Some(h) if top > 0.0 => h / top,
        _ => 1.0,
    };
    Ok(branches
        .into_iter()
        .map(|(_, p)| p.into_iter().map(|[r, h]| [r * k, h * k]).collect())
        .collect())
}

/// The first polyline or polygon of an SVG file as (radius, height) in drawing units: radius
/// from the first point's x, height up from the bottom of the viewBox (or the lowest point).
fn svg_polyline(name: &str, text: &str) -> Result<Vec<[f64; 2]>, ParamsError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut ground: Option<f64> = None;
    loop {
        let pos = reader.buffer_position();
        let event = reader.read_event().map_err(|e| {
            syntax(
                name,
                line_at(text, reader.error_position()),
                format!("not valid XML: {e}"),
            )
        })?;
        let line = line_at(text, pos);
        let (Event::Start(e) | Event::Empty(e)) = event else {
            if matches!(event, Event::Eof) {
                break;
            }
            continue;
        };
        let attr = |key: &str| -> Result<Option<String>, ParamsError> {
            for a in e.attributes() {
                let a = a.map_err(|err| syntax(name, line, format!("bad attribute: {err}")))?;
                if a.key.as_ref() == key {
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .map_err(|err| syntax(name, line, format!("bad attribute value: {err}")))?;
                    return Ok(Some(v.into_owned()));
                }
            }
            Ok(None)
        };
        match e.name().as_ref() {
            "svg" => {
                if let Some(vb) = attr("viewBox")? {
                    let v: Vec<f64> = fields(&vb).iter().filter_map(|s| s.parse().ok()).collect();
                    if v.len() != 4 {
                        return Err(syntax(
                            name,
                            line,
                            format!("viewBox `{vb}`: expected four numbers"),
                        ));
                    }
                    ground = Some(v[1] + v[3]);
                }
            }
            "polyline" | "polygon" => {
                let Some(list) = attr("points")? else {
                    return Err(syntax(
                        name,
                        line,
                        "the polyline has no `points` attribute".into(),
                    ));
                };
                let cells = fields(&list);
                let mut xy = Vec::with_capacity(cells.len() / 2);
                for c in &cells {
                    xy.push(
                        c.parse::<f64>()
                            .ok()
                            .filter(|v| v.is_finite())
                            .ok_or_else(|| {
                                syntax(name, line, format!("polyline point `{c}` is not a number"))
                            })?,
                    );
                }
                if xy.len() % 2 != 0 {
                    return Err(syntax(
                        name,
                        line,
                        format!(
                            "polyline has {} numbers; points come in x,y pairs",
                            xy.len()
                        ),
                    ));
                }
                if xy.len() / 2 > MAX_POINTS {
                    return Err(syntax(
                        name,
                        line,
                        format!("more than {MAX_POINTS} points; simplify the outline"),
                    ));
                }
                if xy.is_empty() {
                    return Err(syntax(name, line, "the polyline has no points".into()));
                }
                let axis = xy[0];
                let lowest = xy.chunks(2).map(|p| p[1]).fold(f64::MIN, f64::max);
                let ground = ground.unwrap_or(lowest).max(lowest);
                let mut points = Vec::with_capacity(xy.len() / 2);
                for (k, p) in xy.chunks(2).enumerate() {
                    let r = p[0] - axis;
                    if r < -1e-9 * (1.0 + axis.abs()) {
                        return Err(syntax(
                            name,
                            line,
                            format!(
                                "point {} ({}, {}) lies left of the trunk (the first point's x, {axis}); \
                                 a profile is the canopy's right half",
                                k + 1,
                                p[0],
                                p[1]
                            ),
                        ));
                    }
                    points.push([r.max(0.0), ground - p[1]]);
                }
                return Ok(points);
            }
            _ => {}
        }
    }
    Err(ParamsError::Syntax {
        source_name: name.into(),
        message: "no <polyline> or <polygon> element: draw the profile as one".into(),
    })
}
