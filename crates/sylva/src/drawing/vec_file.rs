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

    fn point(&mut self, tag: u8, p: Vec3) {
        if self.error.is_some() {
            return;
        }
        // One line assembled on the stack and written at once: `{:.4}` formatting of three
        // floats per line was the slowest part of streaming a large tree.
        let mut line = [0u8; 3 * 24 + 4];
        line[0] = tag;
        line[1] = b' ';
        let mut at = 2;
        for (k, v) in [p.x, p.y, p.z].into_iter().enumerate() {
            if k > 0 {
                line[at] = b',';
                at += 1;
            }
            at += fixed4(v, &mut line[at..]);
        }
        line[at] = b'\n';
        if let Err(e) = self.out.write_all(&line[..=at]) {
            self.error = Some(e);
        }
    }
}

/// Writes `v` rounded to four decimals (as `{:.4}` would print the rounded value, and never
/// `-0.0000`) into `out`; returns the length. `out` holds at least 24 bytes.
fn fixed4(v: f32, out: &mut [u8]) -> usize {
    let n = (v as f64 * 1e4).round();
    // Beyond ±9e14 (90 billion metres) fall back to the formatter; a tree never gets there.
    if !n.is_finite() || n.abs() >= 9e14 {
        let text = format!("{:.4}", v);
        let len = text.len().min(out.len());
        out[..len].copy_from_slice(&text.as_bytes()[..len]);
        return len;
    }
    let n = n as i64;
    let mut at = 0;
    if n < 0 {
        out[0] = b'-';
        at = 1;
    }
    let (whole, frac) = (n.unsigned_abs() / 10_000, n.unsigned_abs() % 10_000);
    let mut digits = [0u8; 20];
    let mut d = 0;
    let mut w = whole;
    loop {
        digits[d] = b'0' + (w % 10) as u8;
        d += 1;
        w /= 10;
        if w == 0 {
            break;
        }
    }
    for k in (0..d).rev() {
        out[at] = digits[k];
        at += 1;
    }
    out[at] = b'.';
    let f = frac as u32;
    for (k, div) in [1000, 100, 10, 1].into_iter().enumerate() {
        out[at + 1 + k] = b'0' + (f / div % 10) as u8;
    }
    at + 5
}

impl<W: Write> LineSink for VecWriter<W> {
    fn segment(&mut self, a: Vec3, b: Vec3, _stroke: Stroke) {
        if self.pen != Some(a) {
            self.point(b'P', a);
        }
        self.point(b'L', b);
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

#[cfg(test)]
mod tests {
    use super::fixed4;

    #[test]
    fn fixed_point_matches_the_formatter() {
        let mut random = crate::rng::StreamKey::from_seed(8).stream();
        let mut buf = [0u8; 24];
        let mut values: Vec<f32> = (0..20_000)
            .map(|i| (random.var(1.0) * 10f64.powi(i % 7 - 2)) as f32)
            .collect();
        values.extend([
            0.0, -0.0, 0.00004, -0.00004, -0.00005, 0.99995, -12.5, 1e6, 123.4567,
        ]);
        for v in values {
            let len = fixed4(v, &mut buf);
            let r = (v as f64 * 1e4).round() / 1e4;
            let expect = format!("{:.4}", if r == 0.0 { 0.0 } else { r });
            assert_eq!(std::str::from_utf8(&buf[..len]).unwrap(), expect, "{v}");
        }
    }
}
