//! A panel of a picture in metres: a world rectangle fitted into part of a pixmap, and the few
//! shapes the site pictures draw (rectangles, outlines, circles, segments, polygons).

use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap, Rect, Stroke, Transform};

/// A solid or translucent colour, anti-aliased.
pub fn paint(r: u8, g: u8, b: u8, a: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(r, g, b, a);
    p.anti_alias = true;
    p
}

/// World coordinates (u right, v up, metres) mapped into a panel of a pixmap.
pub struct Canvas<'a> {
    pixmap: &'a mut Pixmap,
    u0: f64,
    v0: f64,
    /// Pixels per metre.
    pub scale: f64,
    left: f64,
    base: f64,
}

impl<'a> Canvas<'a> {
    /// Fits `u` and `v` (each `(low, high)`, metres) into the panel `(x, y, width, height)` of
    /// `pixmap`, centred across, with 2% margins at the sides, 3% at the top and 8% at the
    /// bottom (room for the ground below `v.0`).
    pub fn fit(
        pixmap: &'a mut Pixmap,
        panel: (f64, f64, f64, f64),
        u: (f64, f64),
        v: (f64, f64),
    ) -> Canvas<'a> {
        let (x, y, w, h) = panel;
        let (du, dv) = ((u.1 - u.0).max(1e-3), (v.1 - v.0).max(1e-3));
        let base = y + h * 0.92;
        let scale = (w * 0.96 / du).min(h * 0.89 / dv);
        Canvas {
            pixmap,
            u0: u.0,
            v0: v.0,
            scale,
            left: x + (w - du * scale) / 2.0,
            base,
        }
    }

    /// Pixel position of a world point.
    pub fn px(&self, u: f64, v: f64) -> (f32, f32) {
        (
            (self.left + (u - self.u0) * self.scale) as f32,
            (self.base - (v - self.v0) * self.scale) as f32,
        )
    }

    /// Metres as pixels.
    pub fn pixels(&self, metres: f64) -> f32 {
        (metres * self.scale) as f32
    }

    fn pixel_rect(&self, a: (f64, f64), b: (f64, f64)) -> Option<Rect> {
        let (xa, ta) = self.px(a.0.min(b.0), a.1.max(b.1));
        let (xb, tb) = self.px(a.0.max(b.0), a.1.min(b.1));
        Rect::from_ltrb(xa, ta, xb.max(xa + 1.0), tb.max(ta + 1.0))
    }

    /// Fills the rectangle between two corners.
    pub fn rect(&mut self, a: (f64, f64), b: (f64, f64), p: &Paint) {
        if let Some(r) = self.pixel_rect(a, b) {
            self.pixmap.fill_rect(r, p, Transform::identity(), None);
        }
    }

    /// Outlines the rectangle between two corners, 2 px wide.
    pub fn outline(&mut self, a: (f64, f64), b: (f64, f64), p: &Paint) {
        if let Some(r) = self.pixel_rect(a, b) {
            self.stroke(&PathBuilder::from_rect(r), 2.0, p);
        }
    }

    /// A circle of `radius` pixels, filled or 1.5 px outlined.
    pub fn circle(&mut self, c: (f64, f64), radius: f32, p: &Paint, fill: bool) {
        let (x, y) = self.px(c.0, c.1);
        if let Some(path) = PathBuilder::from_circle(x, y, radius.max(0.5)) {
            if fill {
                self.pixmap
                    .fill_path(&path, p, FillRule::Winding, Transform::identity(), None);
            } else {
                self.stroke(&path, 1.5, p);
            }
        }
    }

    /// A segment `width` pixels wide.
    pub fn segment(&mut self, a: (f64, f64), b: (f64, f64), width: f32, p: &Paint) {
        let mut path = PathBuilder::new();
        let (xa, ya) = self.px(a.0, a.1);
        let (xb, yb) = self.px(b.0, b.1);
        path.move_to(xa, ya);
        path.line_to(xb, yb);
        if let Some(path) = path.finish() {
            self.stroke(&path, width, p);
        }
    }

    /// A filled polygon, and its outline when `edge` is given.
    pub fn polygon(&mut self, points: &[(f64, f64)], p: &Paint, edge: Option<&Paint>) {
        let mut path = PathBuilder::new();
        for (i, &(u, v)) in points.iter().enumerate() {
            let (x, y) = self.px(u, v);
            if i == 0 {
                path.move_to(x, y);
            } else {
                path.line_to(x, y);
            }
        }
        path.close();
        if let Some(path) = path.finish() {
            self.pixmap
                .fill_path(&path, p, FillRule::Winding, Transform::identity(), None);
            if let Some(e) = edge {
                self.stroke(&path, 2.0, e);
            }
        }
    }

    fn stroke(&mut self, path: &Path, width: f32, p: &Paint) {
        let stroke = Stroke {
            width,
            ..Stroke::default()
        };
        self.pixmap
            .stroke_path(path, p, &stroke, Transform::identity(), None);
    }
}
