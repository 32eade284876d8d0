//! One frame, planned without a GPU: the lighting, the copies of each tree that are in view,
//! what each copy draws at its range, and the props. The GPU records this plan into passes;
//! the CPU rasteriser draws the same plan, so both backends show the same picture.

use crate::camera::Camera;
use crate::impostor::{Atlas, Cell};
use crate::props::{PropMesh, ground, person};
use crate::scene::{FrameStats, Placement, Scene};
use crate::tree::RenderTree;
use glam::Vec3;
use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use sylva::lod::Choice;
use sylva::lod::sway::Sway;

/// Side of the square shadow map, texels.
pub(crate) const SHADOW_SIZE: u32 = 2048;
/// Background (sRGB): a pale sky.
pub const SKY_SRGB: [f32; 3] = [0.80, 0.87, 0.94];
const GROUND_SRGB: [f32; 3] = [0.55, 0.52, 0.45];
const PERSON_SRGB: [f32; 3] = [0.35, 0.38, 0.45];

/// What the shaders read for the whole frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Globals {
    pub view_proj: [[f32; 4]; 4],
    pub light_view_proj: [[f32; 4]; 4],
    pub sun_dir: [f32; 4],
    pub sun_color: [f32; 4],
    pub sky_color: [f32; 4],
    pub ground_bounce: [f32; 4],
    /// x: shadow map texel size, y: depth bias.
    pub shadow: [f32; 4],
    /// xyz: the eye; w: pixels per metre at 1 m from it.
    pub eye: [f32; 4],
}

/// A surface's linear colour and kind (x: 0 opaque, 1 leaf, 2 ground with its grid).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct Material {
    pub color: [f32; 4],
    pub kind: [f32; 4],
}

pub(crate) const KIND_OPAQUE: f32 = 0.0;
pub(crate) const KIND_LEAF: f32 = 1.0;
pub(crate) const KIND_GROUND: f32 = 2.0;

/// A copy of a tree as the vertex shader reads it: offset and scale, cos and sin of the turn.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct InstanceData {
    pub place: [f32; 4],
    pub turn: [f32; 2],
    /// Lines and points: how many items each drawn one stands for (items not meshed / items
    /// drawn flat), so that together they cover what the whole list would.
    pub stands_for: [f32; 2],
    /// Trees stored for range: the copy's sway (`sylva::lod::sway::Sway`: turn about x and y,
    /// trunk length).
    pub sway: [f32; 4],
}

impl From<&Placement> for InstanceData {
    fn from(p: &Placement) -> Self {
        let (s, c) = p.turn.sin_cos();
        Self {
            place: [p.position.x, p.position.y, p.position.z, p.scale],
            turn: [c, s],
            stands_for: [1.0, 0.0],
            sway: [0.0; 4],
        }
    }
}

impl InstanceData {
    /// Where a point of the tree lands.
    pub fn place(&self, p: Vec3) -> Vec3 {
        Vec3::from_slice(&self.place[..3]) + self.place[3] * self.turn(p)
    }

    /// A direction turned with the copy.
    pub fn turn(&self, v: Vec3) -> Vec3 {
        let [c, s] = self.turn;
        Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Primitive {
    Triangles,
    Lines,
    Points,
}

/// Which vertices (and indices) a draw reads.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Part<'a> {
    /// A tree's whole bark or leaf mesh.
    Mesh {
        tree: &'a RenderTree,
        leaves: bool,
    },
    /// One run of a tree stored for range: its segments drawn as tubes and its leaves as
    /// cards or, with `flat`, as lines along their axes and as points. The draw's range counts
    /// records. Leaf cards are drawn with the outline `card`.
    Run {
        tree: &'a RenderTree,
        list: usize,
        run: usize,
        flat: bool,
        card: sylva::LeafShape,
        /// Whether the copy is dissolving into its impostor (its instance's `sway[3]` is the
        /// impostor's share of pixels).
        fading: bool,
    },
    /// The impostor of a copy of a tree: one quad showing `cell` of the atlas.
    Impostor {
        cell: Cell,
    },
    Ground,
    Person,
}

/// One draw call: a range of indexed triangles, or of line/point vertices, for a range of
/// instances (tree copies; the props use instance 0, which stands at the origin).
#[derive(Clone, Debug)]
pub(crate) struct Draw<'a> {
    pub primitive: Primitive,
    pub part: Part<'a>,
    pub range: std::ops::Range<u32>,
    /// What the shadow pass draws of the same vertices; empty for what casts no shadow.
    pub shadow: std::ops::Range<u32>,
    pub instances: std::ops::Range<u32>,
    /// Index into [`Frame::materials`].
    pub material: usize,
}

impl<'a> Part<'a> {
    /// The run a [`Part::Run`] draws.
    pub fn run(&self) -> Option<(&'a sylva::lod::LodTree, &'a sylva::lod::Run)> {
        match *self {
            Part::Run {
                tree, list, run, ..
            } => {
                let lod = tree.data.lod.as_ref()?;
                Some((lod, lod.lists.get(list)?.runs.get(run)?))
            }
            _ => None,
        }
    }
}

impl Draw<'_> {
    /// Primitives this draw makes.
    fn primitives(&self) -> usize {
        let n = self.range.len() * self.instances.len();
        match (self.part, self.primitive) {
            (Part::Run { flat: true, .. }, _) => n,
            (Part::Impostor { .. }, _) => 2 * n,
            (Part::Run { list: 3, card, .. }, _) => n * sylva::mesh::leaf_triangles(card),
            (Part::Run { .. }, _) => n * self.part.run().map_or(0, |(_, r)| r.triangles_per_item()),
            (_, Primitive::Triangles) => n / 3,
            (_, Primitive::Lines) => n / 2,
            (_, Primitive::Points) => n,
        }
    }
}

/// Everything one picture draws.
#[derive(Debug)]
pub(crate) struct Frame<'a> {
    pub globals: Globals,
    pub instances: Vec<InstanceData>,
    /// Trees, then the person and the ground, in drawing order.
    pub draws: Vec<Draw<'a>>,
    pub materials: Vec<Material>,
    pub ground: PropMesh,
    pub person: PropMesh,
    /// Linear RGBA the picture starts from.
    pub clear: [f32; 4],
    /// The views the impostors show.
    pub atlas: Option<&'a Atlas>,
    pub stats: FrameStats,
}

pub(crate) fn linear(c: [f32; 3]) -> [f32; 4] {
    let [r, g, b] = c.map(sylva::colour::srgb_to_linear);
    [r, g, b, 1.0]
}

/// The six planes of a view-projection's frustum (WebGPU depth 0..1), as `n.p + d >= 0` inside.
fn frustum_planes(m: glam::Mat4) -> [glam::Vec4; 6] {
    let (r0, r1, r2, r3) = (m.row(0), m.row(1), m.row(2), m.row(3));
    [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| p / p.truncate().length())
}

fn sphere_visible(planes: &[glam::Vec4; 6], centre: Vec3, radius: f32) -> bool {
    planes
        .iter()
        .all(|p| p.truncate().dot(centre) + p.w >= -radius)
}

fn material(colour: [f32; 3], kind: f32) -> Material {
    Material {
        color: linear(colour),
        kind: [kind, 0.0, 0.0, 0.0],
    }
}

/// Whole meshes: one instanced draw per mesh for every visible copy.
fn whole_meshes<'a>(
    scene: &Scene<'a>,
    stand: usize,
    tree: &'a RenderTree,
    copies: std::ops::Range<u32>,
    draws: &mut Vec<Draw<'a>>,
) {
    let (bark, leaves) = (2 * stand, 2 * stand + 1);
    let mut whole = |leaves_part: bool, material| {
        let data = if leaves_part {
            &tree.data.leaves
        } else {
            &tree.data.bark
        };
        let all = 0..data.indices.len() as u32;
        draws.push(Draw {
            primitive: Primitive::Triangles,
            part: Part::Mesh {
                tree,
                leaves: leaves_part,
            },
            range: all.clone(),
            shadow: all,
            instances: copies.clone(),
            material,
        });
    };
    whole(false, bark);
    if scene.show_leaves {
        whole(true, leaves);
    }
}

/// A copy's own sway phases, radians, from where it stands: neighbours do not sway in step.
fn phases(p: &Placement) -> [f32; 2] {
    let mut h = 0x9e37_79b9_7f4a_7c15u64;
    for v in [p.position.x, p.position.y, p.position.z] {
        h = (h ^ v.to_bits() as u64).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        h ^= h >> 31;
    }
    let unit = |bits: u64| (bits & 0xffff) as f32 / 65536.0 * std::f32::consts::TAU;
    [unit(h), unit(h >> 16)]
}

/// Which passes a set of draws is for, and the share of the copy's pixels its impostor
/// takes.
#[derive(Clone, Copy, PartialEq)]
struct Passes {
    colour: bool,
    shadow: bool,
    fade: f32,
}

/// Shadows are soft (the filter spans several texels of a map that covers the whole scene), so
/// a tree's shadow draws this share of what its picture does.
const SHADOW_SHARE: usize = 4;

/// The draws of one copy of a tree stored for range in `passes`: per list and run, the meshed
/// records and the lines or points after them.
fn stored_draws<'a>(
    scene: &Scene<'a>,
    (stand, tree): (usize, &'a RenderTree),
    choice: &Choice,
    (p, sway): (&Placement, &Sway),
    passes: Passes,
    instances: &mut Vec<InstanceData>,
    draws: &mut Vec<Draw<'a>>,
) {
    let only = |pass: bool, r: std::ops::Range<u32>| if pass { r } else { r.start..r.start };
    let Some(lod) = tree.data.lod.as_ref() else {
        return;
    };
    for (list, items) in lod.lists.iter().enumerate() {
        let is_leaves = list == 3;
        if is_leaves && !scene.show_leaves {
            continue;
        }
        let (x_mesh, x_drawn) = choice.x[list];
        // One instance entry per list: its lines or points stand for its items that are
        // neither meshed nor drawn, and its meshed leaves' area grows as the choice says.
        let index = instances.len() as u32;
        let (mut unmeshed, mut flat) = (0, 0);
        let material = 2 * stand + usize::from(is_leaves);
        for (k, run) in items.runs.iter().enumerate() {
            let pick = run.draw(items.mass, x_mesh, x_drawn);
            unmeshed += run.len() - pick.meshed.len();
            flat += pick.flat.len();
            let part = |flat| Part::Run {
                tree,
                list,
                run: k,
                flat,
                card: choice.card(run).0,
                fading: passes.fade > 0.0,
            };
            draws.push(Draw {
                primitive: Primitive::Triangles,
                part: part(false),
                shadow: only(passes.shadow, pick.meshed.clone()),
                range: only(passes.colour, pick.meshed),
                instances: index..index + 1,
                material,
            });
            draws.push(Draw {
                primitive: if is_leaves {
                    Primitive::Points
                } else {
                    Primitive::Lines
                },
                part: part(true),
                // A leaf that is not drawn is stood for by a meshed one grown to keep the
                // crown's leaf area, in the shadow map as in the picture.
                shadow: only(passes.shadow, pick.flat.clone()),
                range: only(passes.colour, pick.flat),
                instances: index..index + 1,
                material,
            });
        }
        instances.push(InstanceData {
            stands_for: [unmeshed as f32 / flat.max(1) as f32, choice.leaf_grow],
            sway: [sway.turn[0], sway.turn[1], sway.length, passes.fade],
            ..p.into()
        });
    }
}

/// The impostor of one copy of a stored tree, drawing `fade` of its pixels.
fn impostor_draw<'a>(
    (stand, cell): (usize, Cell),
    (p, sway): (&Placement, &Sway),
    fade: f32,
    instances: &mut Vec<InstanceData>,
    draws: &mut Vec<Draw<'a>>,
) {
    let index = instances.len() as u32;
    instances.push(InstanceData {
        sway: [sway.turn[0], sway.turn[1], sway.length, fade],
        ..p.into()
    });
    draws.push(Draw {
        primitive: Primitive::Triangles,
        part: Part::Impostor { cell },
        range: 0..1,
        shadow: 0..0,
        instances: index..index + 1,
        material: 2 * stand + 1,
    });
}

/// What one visible copy of a stored tree draws, before the frame's budget is shared out.
#[derive(Clone, Copy)]
struct Chosen<'a> {
    range: f32,
    stand: usize,
    placement: &'a Placement,
    choice: Choice,
    /// Its impostor's cell and share of the copy's pixels, while it has one.
    impostor: Option<(Cell, f32)>,
}

/// Plans `scene` seen by `camera` (at `azimuth` degrees) in a picture `height` pixels tall.
pub(crate) fn plan<'a>(
    scene: &Scene<'a>,
    camera: &Camera,
    (azimuth, height): (f32, u32),
    atlas: Option<&'a Atlas>,
) -> Frame<'a> {
    let (lo, hi) = scene.bounds(azimuth);
    let centre = (lo + hi) / 2.0;
    let radius = ((hi - lo).length() / 2.0).max(0.5);
    // The sun's view: orthographic over a disc of ground around the trees, where their
    // shadows fall.
    let reach = radius * 2.2;
    let light_view = look_at_mat4(centre + scene.sun * radius * 4.0, centre, Vec3::Z);
    let light_proj = directx::orthographic(-reach, reach, -reach, reach, 0.1, radius * 8.0);
    let view_proj = camera.view_proj();
    let globals = Globals {
        view_proj: view_proj.to_cols_array_2d(),
        light_view_proj: (light_proj * light_view).to_cols_array_2d(),
        sun_dir: scene.sun.normalize().extend(0.0).to_array(),
        sun_color: [2.6, 2.45, 2.2, 0.0],
        sky_color: [0.42, 0.5, 0.62, 0.0],
        ground_bounce: [0.18, 0.17, 0.14, 0.0],
        shadow: [1.0 / SHADOW_SIZE as f32, 0.0015, 0.0, 0.0],
        eye: camera
            .eye
            .extend(height as f32 / (2.0 * (camera.fov_y / 2.0).tan()))
            .to_array(),
    };
    let mut materials: Vec<Material> = scene
        .stands
        .iter()
        .flat_map(|s| [material(s.bark, KIND_OPAQUE), material(s.leaves, KIND_LEAF)])
        .collect();
    let planes = frustum_planes(view_proj);
    let viewer = sylva::lod::Viewer {
        image_height: height as f32,
        fov_y: camera.fov_y.to_degrees(),
        quality: scene.lod_quality,
    };
    // Instance 0 stands at the origin for the props; the trees' copies follow.
    let mut instances = vec![InstanceData::from(&Placement::ORIGIN)];
    let mut stats = FrameStats::default();
    let mut draws: Vec<Draw> = Vec::new();
    // Trees stored for range: every visible copy's choice first, then the frame's budget
    // shared among them, then their draws.
    let mut chosen: Vec<Chosen> = Vec::new();
    let mut wishes: Vec<(usize, f32)> = Vec::new();
    for (s, stand) in scene.stands.iter().enumerate() {
        let tree = stand.tree;
        stats.trees += stand.placements.len();
        let first = instances.len() as u32;
        for p in stand.placements.iter() {
            let (c, r) = stand.sphere(p);
            if !sphere_visible(&planes, c, r) {
                continue;
            }
            stats.trees_drawn += 1;
            let Some(lod) = tree.data.lod.as_ref() else {
                instances.push(p.into());
                continue;
            };
            // Each copy's range, and the picture it lands in, choose what of each list is
            // drawn (Weber & Penn section 5); a copy scaled up looks as the original nearer.
            // Without range degradation everything is meshed.
            let range = camera.eye.distance(c) / p.scale.max(1e-3);
            let choice = if scene.use_lod {
                lod.paper_choice(range, &viewer)
            } else {
                lod.full_choice()
            };
            let pixels = 2.0 * r / p.scale.max(1e-3) * viewer.pixels_per_metre(range);
            let wish = lod.primitives(&choice).min(sylva::lod::tree_cap(pixels));
            wishes.push((wish, pixels));
            // Small enough, a copy dissolves into its impostor when there is one.
            let tall = (tree.hi.z - tree.lo.z) * viewer.pixels_per_metre(range);
            let impostor = atlas
                .and_then(|a| a.cells.get(s).copied().flatten())
                .filter(|_| scene.use_lod)
                .map(|cell| (cell, sylva::lod::impostor_share(tall)))
                .filter(|&(_, fade)| fade > 0.0);
            chosen.push(Chosen {
                range,
                stand: s,
                placement: p,
                choice,
                impostor,
            });
        }
        if tree.data.lod.is_none() {
            whole_meshes(scene, s, tree, first..instances.len() as u32, &mut draws);
        }
    }
    let allowances = match (scene.use_lod, scene.primitive_budget) {
        (true, Some(budget)) => sylva::lod::share_out(&wishes, budget),
        (true, None) => wishes.iter().map(|w| w.0).collect(),
        (false, _) => vec![usize::MAX; wishes.len()],
    };
    // Nearest first, so that the depth test turns away what they hide before it is shaded.
    let mut order: Vec<(f32, usize)> = chosen.iter().map(|c| c.range).zip(0..).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, k) in order {
        let Chosen {
            stand: s,
            placement: p,
            choice,
            impostor,
            ..
        } = chosen[k];
        let fade = impostor.map_or(0.0, |(_, fade)| fade);
        let allowance = allowances[k];
        let stand = &scene.stands[s];
        let Some(lod) = stand.tree.data.lod.as_ref() else {
            continue;
        };
        let colour = lod.within(choice, allowance);
        let shadow = if scene.use_lod {
            lod.within(choice, allowance / SHADOW_SHARE)
        } else {
            colour
        };
        let tree = (s, stand.tree);
        // Once per copy and frame: every draw of the copy, and its impostor, sway alike.
        let sway = lod.sway(&scene.wind, phases(p));
        let mut draw = |choice: &Choice, colour, shadow| {
            let passes = Passes {
                colour,
                shadow,
                fade,
            };
            let copy = (p, &sway);
            stored_draws(
                scene,
                tree,
                choice,
                copy,
                passes,
                &mut instances,
                &mut draws,
            );
        };
        // Wholly an impostor, the tree still casts its shadow.
        let drawn = fade < 1.0;
        if shadow == colour {
            draw(&colour, drawn, true);
        } else {
            if drawn {
                draw(&colour, true, false);
            }
            draw(&shadow, false, true);
        }
        if let Some((cell, fade)) = impostor {
            impostor_draw((s, cell), (p, &sway), fade, &mut instances, &mut draws);
        }
    }
    draws.retain(|d| !(d.instances.is_empty() || d.range.is_empty() && d.shadow.is_empty()));
    for d in &draws {
        stats.draw_calls += 1;
        if let Part::Impostor { .. } = d.part {
            stats.impostors += d.instances.len();
        }
        match d.primitive {
            Primitive::Triangles => stats.triangles += d.primitives(),
            Primitive::Lines => stats.lines += d.primitives(),
            Primitive::Points => stats.points += d.primitives(),
        }
    }
    let ground_mesh = ground(centre, radius * 3.0);
    let person_mesh = person(scene.person_feet(azimuth), azimuth);
    if scene.show_person {
        materials.push(material(PERSON_SRGB, KIND_OPAQUE));
        let all = 0..person_mesh.indices.len() as u32;
        draws.push(Draw {
            primitive: Primitive::Triangles,
            part: Part::Person,
            range: all.clone(),
            shadow: all,
            instances: 0..1,
            material: materials.len() - 1,
        });
    }
    if scene.show_ground {
        // The ground receives shadows but casts none.
        materials.push(material(GROUND_SRGB, KIND_GROUND));
        draws.push(Draw {
            primitive: Primitive::Triangles,
            part: Part::Ground,
            range: 0..ground_mesh.indices.len() as u32,
            shadow: 0..0,
            instances: 0..1,
            material: materials.len() - 1,
        });
    }
    // Transparent pictures clear to the leaves' colour, so that edge pixels blend towards it
    // rather than towards the sky.
    let clear = match scene.transparent {
        true => scene.transparent_clear(),
        false => linear(SKY_SRGB),
    };
    Frame {
        globals,
        instances,
        draws,
        materials,
        ground: ground_mesh,
        person: person_mesh,
        clear,
        atlas,
        stats,
    }
}
