//! Nagel's move/draw vector file: one point per line, `P x,y,z` moves the pen, `L x,y,z` draws
//! a line to the point. The thesis wrote these for the Evans & Sutherland PS-300; any CAD
//! package or plotter script reads them with a few lines of code.
//!
//! Sylva writes metres, Z up, four decimals (0.1 mm). A segment that starts where the last one
//! ended continues the pen's line, so a stem is one `P` and then `L`s.

use super::{LineSink, LineSource, Stroke};
use crate::error::ParamsError;
use glam::Vec3;
use std::io::{self, Write};

/// A [`LineSink`] that writes a vector file as the segments arrive; it holds only the last point.
pub struct VecWriter<W: Write> {
    out: W,
    pen: Option<Vec3>,
    error: Option<io::Error>,
}

impl<W: Write> VecWriter<W> {
    /// Writes to `out` (wrap files in a `BufWriter`).
    pub fn new(out: W) -> Self {
        Self {
            out,
            pen: None,
            error: None,
        }
    }

    /// The writer back, or the first write error.
    pub fn finish(mut self) -> io::Result<W> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.flush()?;
        Ok(self.out)
    }

    fn point(&mut self, tag: char, p: Vec3) {
        if self.error.is_some() {
            return;
        }
        // Rounding first keeps "-0.0000" out of the file.
        let r = |v: f32| {
            let v = (v as f64 * 1e4).round() / 1e4;
            if v == 0.0 { 0.0 } else { v }
        };
        if let Err(e) = writeln!(self.out, "{tag} {:.4},{:.4},{:.4}", r(p.x), r(p.y), r(p.z)) {
            self.error = Some(e);
        }
    }
}

impl<W: Write> LineSink for VecWriter<W> {
    fn segment(&mut self, a: Vec3, b: Vec3, _stroke: Stroke) {
        if self.pen != Some(a) {
            self.point('P', a);
        }
        self.point('L', b);
        self.pen = Some(b);
    }
}

/// Writes all of `source` as a vector file.
pub fn write_vec<W: Write>(source: &(impl LineSource + ?Sized), out: W) -> io::Result<W> {
    let mut writer = VecWriter::new(out);
    source.lines(&mut writer);
    writer.finish()
}

/// Reads a vector file into polylines (each starts at a `P`). Blank lines and lines starting
/// with `#` are skipped; coordinates may be separated by commas or spaces. `name` is used in
/// error messages, which give the line number.
pub fn read_vec(text: &str, name: &str) -> Result<Vec<Vec<Vec3>>, ParamsError> {
    let mut lines: Vec<Vec<Vec3>> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let fail = |message: String| ParamsError::Syntax {
            source_name: format!("{name}, line {}", i + 1),
            message,
        };
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (tag, rest) = line.split_at(1);
        let tag = tag.to_ascii_uppercase();
        if tag != "P" && tag != "L" {
            return Err(fail(format!(
                "expected `P x,y,z` (move) or `L x,y,z` (draw), found `{line}`"
            )));
        }
        let values: Vec<&str> = rest
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .collect();
        if values.len() != 3 {
            return Err(fail(format!(
                "expected three coordinates after `{tag}`, found {}",
                values.len()
            )));
        }
        let mut p = [0.0f32; 3];
        for (slot, v) in p.iter_mut().zip(&values) {
            *slot = v
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| fail(format!("`{v}` is not a finite number")))?;
        }
        let p = Vec3::from(p);
        if tag == "P" {
            lines.push(vec![p]);
        } else {
            match lines.last_mut() {
                Some(line) => line.push(p),
                None => {
                    return Err(fail(
                        "`L` before any `P`: the pen must move to a point before it draws".into(),
                    ));
                }
            }
        }
    }
    Ok(lines)
}
