//! What a picture shows and from where: stands of placed trees, the props, the sun, the camera.

use crate::RenderTree;
use crate::camera::Camera;
use crate::props::PERSON_HEIGHT;
use glam::Vec3;

/// Where the camera is: a named view or an orbit framing the whole scene, or an explicit eye
/// and target (fly-throughs, forests seen from a given range).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Degrees around the tree: 0 from the south, 90 from the east.
    pub azimuth: f32,
    /// Degrees above the horizon.
    pub elevation: f32,
    /// Vertical field of view, degrees.
    pub fov_y: f32,
    /// Zoom: 1 frames the tree; 2 is twice as close.
    pub zoom: f32,
    /// Pan of the look-at point, metres (viewer).
    pub pan: Vec3,
    /// Eye and target, metres: when set, the camera stands there instead of framing.
    pub look: Option<(Vec3, Vec3)>,
}

impl View {
    /// A named view with the default lens (30 degrees).
    pub fn named(kind: crate::ViewKind) -> Self {
        let (azimuth, elevation) = kind.angles();
        Self::orbit(azimuth, elevation)
    }

    /// An orbit view.
    pub fn orbit(azimuth: f32, elevation: f32) -> Self {
        Self {
            azimuth,
            elevation,
            fov_y: 30.0,
            zoom: 1.0,
            pan: Vec3::ZERO,
            look: None,
        }
    }

    /// A camera at `eye` looking at `target` with a `fov_y`-degree lens.
    pub fn look_at(eye: Vec3, target: Vec3, fov_y: f32) -> Self {
        let back = (eye - target).normalize_or(Vec3::Y);
        Self {
            azimuth: back.x.atan2(-back.y).to_degrees(),
            elevation: back.z.clamp(-1.0, 1.0).asin().to_degrees(),
            look: Some((eye, target)),
            ..Self::orbit(0.0, 0.0)
        }
        .with_fov(fov_y)
    }

    fn with_fov(mut self, fov_y: f32) -> Self {
        self.fov_y = fov_y;
        self
    }
}

/// Where one copy of a tree stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Position of the tree's base, metres (Z up).
    pub position: Vec3,
    /// Turn about the vertical, radians.
    pub turn: f32,
    /// Uniform scale.
    pub scale: f32,
}

impl Placement {
    /// The tree where it was made.
    pub const ORIGIN: Placement = Placement {
        position: Vec3::ZERO,
        turn: 0.0,
        scale: 1.0,
    };

    /// Where a point of the tree lands.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        let (s, c) = self.turn.sin_cos();
        self.position + self.scale * Vec3::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z)
    }
}

/// Copies of one tree, with its colours.
#[derive(Clone, Debug)]
pub struct Stand<'a> {
    /// The tree.
    pub tree: &'a RenderTree,
    /// Bark colour, sRGB 0..1.
    pub bark: [f32; 3],
    /// Leaf colour, sRGB 0..1.
    pub leaves: [f32; 3],
    /// Where its copies stand.
    pub placements: std::borrow::Cow<'a, [Placement]>,
}

impl<'a> Stand<'a> {
    /// This stand and, where the tree has flowers (uploaded apart by
    /// [`crate::Renderer::upload_flowers`]), a second at the same places that draws them in
    /// their colour as its leaves.
    pub fn with_flowers(
        self,
        flowers: Option<(&'a RenderTree, [f32; 3])>,
    ) -> impl Iterator<Item = Stand<'a>> {
        let second = flowers.map(|(tree, colour)| Stand {
            tree,
            leaves: colour,
            ..self.clone()
        });
        std::iter::once(self).chain(second)
    }

    /// Centre and radius of a sphere holding the copy at `p`.
    pub fn sphere(&self, p: &Placement) -> (Vec3, f32) {
        let t = self.tree;
        let centre = p.apply((t.lo + t.hi) / 2.0);
        (centre, (t.hi - t.lo).length() / 2.0 * p.scale)
    }
}

/// What to draw.
#[derive(Clone, Debug)]
pub struct Scene<'a> {
    /// The trees, each with its placements.
    pub stands: Vec<Stand<'a>>,
    /// Draw the leaves.
    pub show_leaves: bool,
    /// Draw the ground and its grid.
    pub show_ground: bool,
    /// Draw the 1.8 m person beside the scene.
    pub show_person: bool,
    /// Unit vector towards the sun.
    pub sun: Vec3,
    /// Degrade trees with range (Weber & Penn section 5) when they were uploaded with
    /// [`crate::Renderer::upload_lod`]: meshes become lines and points as they recede.
    pub use_lod: bool,
    /// The paper's quality factor for range degradation: 2 keeps detail twice as far.
    pub lod_quality: f32,
    /// With range degradation, the most primitives the frame's trees draw together, shared
    /// among them by the pixels each covers (`sylva::lod::share_out`); each tree also draws at
    /// most `sylva::lod::PER_SQUARE_PIXEL` per pixel of its box. `None`: no frame budget.
    pub primitive_budget: Option<usize>,
    /// With range degradation, trees stored for range under `sylva::lod::IMPOSTOR_PIXELS`
    /// tall dissolve into impostors: pictures of them from 8 sides, baked for this scene's
    /// trees and sun on first use, on one quad each.
    pub impostors: bool,
    /// Clear to transparent instead of the sky (for baking impostors): the picture's alpha is
    /// then the trees' coverage.
    pub transparent: bool,
    /// Wind at one moment for trees stored for range: each copy sways by
    /// `sylva::lod::sway`, on the GPU, with phases of its own. Calm by default.
    pub wind: sylva::Wind,
}

/// The frame budget of a scene: 2 million primitives, what a software rasteriser draws in
/// about 2-3 seconds on two cores, and a small share of a GPU's frame.
pub const DEFAULT_PRIMITIVE_BUDGET: usize = 2_000_000;

impl<'a> Scene<'a> {
    /// One tree at the origin, with ground, person, leaves and an afternoon sun from the
    /// south-west.
    pub fn new(tree: &'a RenderTree, bark: [f32; 3], leaves: [f32; 3]) -> Self {
        Self::flowering(tree, None, bark, leaves)
    }

    /// [`Scene::new`]'s tree and, where it has them, its flowers (see
    /// [`Stand::with_flowers`]).
    pub fn flowering(
        tree: &'a RenderTree,
        flowers: Option<(&'a RenderTree, [f32; 3])>,
        bark: [f32; 3],
        leaves: [f32; 3],
    ) -> Self {
        let stand = Stand {
            tree,
            bark,
            leaves,
            placements: std::borrow::Cow::Borrowed(std::slice::from_ref(&Placement::ORIGIN)),
        };
        Self {
            show_person: true,
            ..Self::forest(stand.with_flowers(flowers).collect())
        }
    }

    /// Many trees: the same defaults as [`Scene::new`], without the person.
    pub fn forest(stands: Vec<Stand<'a>>) -> Self {
        Self {
            stands,
            show_leaves: true,
            show_ground: true,
            show_person: false,
            sun: Vec3::new(-0.45, -0.6, 0.66).normalize(),
            use_lod: true,
            lod_quality: 1.0,
            primitive_budget: Some(DEFAULT_PRIMITIVE_BUDGET),
            impostors: true,
            transparent: false,
            wind: sylva::Wind::default(),
        }
    }

    /// The linear colour a transparent picture starts from: the first trees' leaves,
    /// darkened, with no alpha, so that edge pixels blend towards a leaf's colour rather
    /// than the sky's.
    pub(crate) fn transparent_clear(&self) -> [f32; 4] {
        match self.stands.first() {
            Some(s) => {
                let [r, g, b] = s.leaves.map(|c| sylva::colour::srgb_to_linear(c) * 0.5);
                [r, g, b, 0.0]
            }
            None => [0.0; 4],
        }
    }

    /// Bounds of every placed tree (metres, Z up); the unit cube for an empty scene.
    pub fn tree_bounds(&self) -> (Vec3, Vec3) {
        let mut lo = Vec3::splat(f32::MAX);
        let mut hi = Vec3::splat(f32::MIN);
        for stand in &self.stands {
            let t = stand.tree;
            for p in stand.placements.iter() {
                if p.turn == 0.0 {
                    lo = lo.min(p.apply(t.lo));
                    hi = hi.max(p.apply(t.hi));
                } else {
                    // Any turn keeps the tree inside the circle through its farthest corner.
                    let r = t.lo.truncate().abs().max(t.hi.truncate().abs()).length() * p.scale;
                    lo = lo.min(p.position + Vec3::new(-r, -r, t.lo.z * p.scale));
                    hi = hi.max(p.position + Vec3::new(r, r, t.hi.z * p.scale));
                }
            }
        }
        if lo.x <= hi.x {
            (lo, hi)
        } else {
            (Vec3::ZERO, Vec3::ONE)
        }
    }

    /// Where the person stands for a camera at `azimuth` (degrees): just outside the trees, to
    /// the camera's right and in their picture plane, so it is never hidden behind them.
    pub fn person_feet(&self, azimuth: f32) -> Vec3 {
        let (lo, hi) = self.tree_bounds();
        let a = azimuth.to_radians();
        let right = Vec3::new(a.cos(), a.sin(), 0.0);
        let centre = Vec3::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0, 0.0);
        let half_width =
            (((hi.x - lo.x).abs() * right.x.abs() + (hi.y - lo.y).abs() * right.y.abs()) / 2.0)
                .max(0.5);
        centre + right * (half_width + 0.6)
    }

    /// Bounds of what a camera at `azimuth` must frame: the trees and, when shown, the person.
    pub fn bounds(&self, azimuth: f32) -> (Vec3, Vec3) {
        let (mut lo, mut hi) = self.tree_bounds();
        if self.show_person {
            let f = self.person_feet(azimuth);
            lo = lo.min(f - Vec3::new(0.3, 0.15, 0.0));
            hi = hi.max(f + Vec3::new(0.3, 0.15, PERSON_HEIGHT));
        }
        (lo.min(Vec3::new(lo.x, lo.y, 0.0)), hi)
    }

    /// The camera for `view` in a picture of this aspect ratio.
    pub fn camera(&self, view: &View, aspect: f32) -> Camera {
        if let Some((eye, target)) = view.look {
            let (lo, hi) = self.bounds(view.azimuth);
            let ground = (hi - lo).length() * 3.0;
            let far = (0..8)
                .map(|i| {
                    let corner =
                        Vec3::select(glam::BVec3::new(i & 1 == 0, i & 2 == 0, i & 4 == 0), lo, hi);
                    eye.distance(corner)
                })
                .fold(0.0f32, f32::max)
                .max(ground)
                * 1.1
                + 10.0;
            // An eye outside everything drawn (the ground reaches beyond the trees) needs no
            // near plane closer than their bounds, and a farther one keeps the depth buffer's
            // precision.
            let outside = eye - eye.clamp(lo, hi);
            let near = (!self.show_ground).then(|| outside.length() * 0.9);
            return Camera {
                eye,
                target,
                fov_y: view.fov_y.to_radians(),
                aspect,
                far: Some(far),
                near,
            };
        }
        let (lo, hi) = self.bounds(view.azimuth);
        let mut cam = Camera::framing(
            lo,
            hi,
            view.azimuth,
            view.elevation,
            view.fov_y,
            aspect,
            0.05,
        );
        let zoom = view.zoom.max(0.01);
        cam.eye = cam.target + (cam.eye - cam.target) / zoom + view.pan;
        cam.target += view.pan;
        cam
    }
}

/// What one frame drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Tree copies in view (after culling).
    pub trees_drawn: usize,
    /// Tree copies in the scene.
    pub trees: usize,
    /// Triangles of trees.
    pub triangles: usize,
    /// Lines (stems seen from afar).
    pub lines: usize,
    /// Points (leaves seen from afar).
    pub points: usize,
    /// Draw calls of trees.
    pub draw_calls: usize,
    /// Tree copies drawn wholly or partly as impostors (2 triangles each, counted in
    /// `triangles`).
    pub impostors: usize,
}

impl FrameStats {
    /// Triangles + lines + points.
    pub fn primitives(&self) -> usize {
        self.triangles + self.lines + self.points
    }
}
