//! Billboard impostors: a few views of a tree baked into one texture atlas with alpha, shown
//! on vertical quads through the trunk, one per view, each facing the direction its view was
//! taken from. The farthest level of an engine's LOD chain: 16 triangles for a whole tree.
//!
//! The library lays out the atlas and the quads; baking the pictures needs a renderer, which
//! the library does not hold (`sylva generate --lod-chain` bakes them with `sylva-render`).

use crate::mesh::{Mesh, TreeMesh};
use glam::{Vec2, Vec3};

/// Height on screen, pixels, below which a tree stored for range starts to dissolve into its
/// impostor. Above it the tree draws at most [`super::tree_cap`] primitives (5,000 here);
/// below, a baked picture on one quad draws what those would, at 2 triangles.
pub const IMPOSTOR_PIXELS: f32 = 50.0;

/// Height on screen, pixels, at which the tree has wholly become its impostor. Between this
/// and [`IMPOSTOR_PIXELS`] both are drawn, each on a complementary share of the pixels (a
/// dissolve), so the switch happens over many frames and pixels rather than at once.
pub const IMPOSTOR_WHOLE_PIXELS: f32 = 40.0;

/// The share of a tree's pixels its impostor draws at `height_pixels` tall: 0 at
/// [`IMPOSTOR_PIXELS`] and above, 1 at [`IMPOSTOR_WHOLE_PIXELS`] and below.
pub fn impostor_share(height_pixels: f32) -> f32 {
    let share = (IMPOSTOR_PIXELS - height_pixels) / (IMPOSTOR_PIXELS - IMPOSTOR_WHOLE_PIXELS);
    if share.is_nan() {
        0.0
    } else {
        share.clamp(0.0, 1.0)
    }
}

/// The two baked views on either side of an eye in horizontal direction `towards_eye` (from
/// the tree), for `views` views taken as [`ImpostorFrame::direction`] takes them, and the
/// weight of the second: the picture turns smoothly from one view to the next as the eye
/// goes round.
pub fn view_blend(views: u32, towards_eye: Vec2) -> (u32, u32, f32) {
    let views = views.max(1);
    let turns = towards_eye.x.atan2(-towards_eye.y) / std::f32::consts::TAU;
    let t = turns.rem_euclid(1.0) * views as f32;
    let first = (t.floor() as u32).min(views - 1);
    (
        first,
        (first + 1) % views,
        (t - first as f32).clamp(0.0, 1.0),
    )
}

/// A baked impostor.
#[derive(Clone, Debug, PartialEq)]
pub struct Impostor {
    /// The atlas as a PNG file (RGBA, straight alpha), cells left to right, top to bottom.
    pub png: Vec<u8>,
    /// The layout and size of the views.
    pub frame: ImpostorFrame,
}

/// Where the views of an impostor are taken from and what they cover.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ImpostorFrame {
    /// Number of views, evenly spread around the tree.
    pub views: u32,
    /// Atlas columns; rows are `ceil(views / columns)`.
    pub columns: u32,
    /// Half the width of every view, metres: the farthest reach of the tree from its trunk axis.
    pub half_width: f32,
    /// Lowest point of the views, metres (Z up).
    pub bottom: f32,
    /// Highest point.
    pub top: f32,
}

impl ImpostorFrame {
    /// Eight views in a 4 x 2 atlas framing a tree's mesh about its trunk axis (x = y = 0).
    pub fn around(mesh: &TreeMesh) -> Self {
        let mut reach = 0.1f32;
        let (mut bottom, mut top) = (0.0f32, 0.1f32);
        for p in mesh.bark.positions.iter().chain(&mesh.leaves.positions) {
            reach = reach.max(p[0].hypot(p[1]));
            bottom = bottom.min(p[2]);
            top = top.max(p[2]);
        }
        Self {
            views: 8,
            columns: 4,
            half_width: reach * 1.02,
            bottom,
            top: top * 1.01,
        }
    }

    /// Atlas rows.
    pub fn rows(&self) -> u32 {
        self.views.div_ceil(self.columns.max(1))
    }

    /// Unit vector from the tree towards the eye of view `k`: azimuth 360 k / views degrees,
    /// level, view 0 from the south (-Y), as the renderer's azimuths.
    pub fn direction(&self, k: u32) -> Vec3 {
        let a = (360.0 * k as f32 / self.views as f32).to_radians();
        Vec3::new(a.sin(), -a.cos(), 0.0)
    }

    /// Picture size of one cell for a cell `height` pixels tall.
    pub fn cell_size(&self, height: u32) -> (u32, u32) {
        let aspect = 2.0 * self.half_width / (self.top - self.bottom).max(1e-3);
        (((height as f32 * aspect).round() as u32).max(8), height)
    }

    /// The quads: one per view, through the trunk axis, facing its view's eye (seen from
    /// behind, a quad is culled and its opposite number shows instead).
    pub fn quads(&self) -> Mesh {
        self.quads_within([0.0, 0.0, 1.0, 1.0])
    }

    /// [`ImpostorFrame::quads`] of an atlas that lies at `rect` of a larger picture (left,
    /// top, width, height, as shares of the picture's): their texture points scaled into it.
    /// The whole picture's give the same texture points to the bit.
    pub fn quads_within(&self, rect: [f32; 4]) -> Mesh {
        let [left, top, width, height] = rect;
        let mut m = Mesh::default();
        let (cols, rows) = (self.columns.max(1) as f32, self.rows().max(1) as f32);
        for k in 0..self.views {
            let back = self.direction(k);
            let right = Vec3::Z.cross(back).normalize();
            let (col, row) = (
                (k % self.columns.max(1)) as f32,
                (k / self.columns.max(1)) as f32,
            );
            let (u0, u1) = (col / cols, (col + 1.0) / cols);
            let (v0, v1) = (row / rows, (row + 1.0) / rows);
            let base = m.positions.len() as u32;
            let w = right * self.half_width;
            let corners = [
                (-w + Vec3::Z * self.bottom, [u0, v1]),
                (w + Vec3::Z * self.bottom, [u1, v1]),
                (w + Vec3::Z * self.top, [u1, v0]),
                (-w + Vec3::Z * self.top, [u0, v0]),
            ];
            for (p, [u, v]) in corners {
                m.positions.push(p.to_array());
                m.normals.push(back.to_array());
                m.uvs.push([left + u * width, top + v * height]);
            }
            m.indices
                .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eight_views() -> ImpostorFrame {
        ImpostorFrame {
            views: 8,
            columns: 4,
            half_width: 3.0,
            bottom: 0.0,
            top: 10.0,
        }
    }

    #[test]
    fn an_impostor_takes_over_between_fifty_and_forty_pixels() {
        assert_eq!(impostor_share(400.0), 0.0);
        assert_eq!(impostor_share(50.0), 0.0);
        assert!((impostor_share(45.0) - 0.5).abs() < 1e-6);
        assert_eq!(impostor_share(40.0), 1.0);
        assert_eq!(impostor_share(3.0), 1.0);
        assert_eq!(impostor_share(f32::NAN), 0.0);
    }

    #[test]
    fn views_blend_towards_the_eye() {
        let f = eight_views();
        for k in 0..8 {
            // Straight from view k's eye: view k alone.
            let (a, _, w) = view_blend(8, f.direction(k).truncate());
            assert!(
                (a == k && w < 1e-4) || ((a + 1) % 8 == k && w > 1.0 - 1e-4),
                "{k}: {a} {w}"
            );
        }
        // Halfway between views 7 and 0, south of south-west.
        let half = (f.direction(7) + f.direction(0)).truncate();
        let (a, b, w) = view_blend(8, half);
        assert_eq!((a, b), (7, 0));
        assert!((w - 0.5).abs() < 1e-4);
    }

    #[test]
    fn quads_face_their_views_and_tile_the_atlas() {
        let f = eight_views();
        let q = f.quads();
        assert_eq!(q.triangle_count(), 16);
        for k in 0..8 {
            let tri = &q.indices[k * 6..k * 6 + 3];
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| Vec3::from(q.positions[i as usize]));
            // Counter-clockwise seen from the view's eye.
            assert!((b - a).cross(c - a).dot(f.direction(k as u32)) > 0.0);
            let us: Vec<f32> = (0..4).map(|j| q.uvs[k * 4 + j][0]).collect();
            let lo = us.iter().cloned().fold(f32::MAX, f32::min);
            assert!((lo - (k % 4) as f32 / 4.0).abs() < 1e-6);
        }
        assert_eq!(f.cell_size(200), (120, 200));
        assert_eq!(f.rows(), 2);
    }
}
