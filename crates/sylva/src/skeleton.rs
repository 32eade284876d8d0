//! The Skeleton: what every tree model produces and every output consumes.
//!
//! Stems are polylines of cross-sections (centre, orientation, radius); leaves are frames with a
//! size and a shape. Nothing here refers to model parameters, so a mesher, an exporter or a
//! measurement works the same for every model.
//!
//! Coordinates: metres, Z up, the base of the (first) trunk at the origin. A cross-section's
//! orientation maps the stem's local axes to the world: local z is the growth direction, x and y
//! span the section plane (for a branch growing sideways, y points up).

use glam::{Quat, Vec3};
use std::ops::Range;

/// Index of a stem in [`Skeleton::stems`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct StemId(pub u32);

/// One ring along a stem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossSection {
    /// Centre of the section, metres.
    pub position: Vec3,
    /// Frame of the stem segment that starts here (local z along the stem).
    pub orientation: Quat,
    /// Radius before lobing, metres (taper and flare included).
    pub radius: f32,
    /// Unit position along the stem, 0 at its base, 1 at its tip (clones continue their
    /// original's scale, so a clone starts above 0).
    pub z: f32,
}

/// A trunk, branch or clone.
#[derive(Clone, Debug, PartialEq)]
pub struct Stem {
    /// Recursion level: 0 trunk, 1 main branches, ...
    pub level: u8,
    /// The stem this one grows from (`None` for trunks).
    pub parent: Option<StemId>,
    /// For a clone (a split of a stem), the stem it split from.
    pub clone_of: Option<StemId>,
    /// Distance from the parent's base to where this stem attaches, metres.
    pub offset: f32,
    /// Length of the stem from its base (a clone: of the stem it split from), metres.
    pub length: f32,
    /// Range of this stem's cross-sections in [`Skeleton::sections`].
    pub sections: Range<u32>,
    /// Number of sinusoidal lobes around the stem (0: round).
    pub lobes: u32,
    /// Lobe amplitude relative to the radius.
    pub lobe_depth: f32,
}

/// Leaf outline, scaled per leaf (unit length along local z, unit width along local x).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LeafShape {
    /// Elliptic leaf (index 0), the paper's most used shape.
    Oval,
    /// Deltoid leaf (1), as poplars and birches.
    Triangle,
    /// Three-lobed oak leaf (2).
    Oak,
    /// Three-lobed maple leaf (3).
    Maple3,
    /// Five-lobed maple leaf (4).
    Maple5,
    /// Three leaflets on one petiole (5).
    ThreeLeaflets,
    /// Square (6), Arbaro's `square`.
    Square,
    /// Long narrow leaflet (7), for palms, grasses and bamboo; Arbaro's `palm`.
    Palm,
    /// Small closed sphere (8), for berries and grain; Arbaro's `sphere`.
    Sphere,
    /// Palmately five-lobed blade of few corners: planes and maples grown from the database.
    Lobed5,
    /// Heart-shaped blade, two rounded lobes at the base: lindens, redbuds, catalpas.
    Cordate,
    /// A fan, widest at its notched tip: the ginkgo.
    Fan,
    /// Deeply cut lobes ending in points: the red-oak group (pin, red, willow-leaved kin).
    PointedLobes,
    /// A compound leaf of this many leaflets in pairs along a rachis (an odd count ends in a
    /// terminal leaflet): ashes, pistache, goldenrain tree. 2 to 25.
    Pinnate(u8),
    /// A twice-compound leaf: this many pinnae along the rachis, each a feather of small
    /// leaflets: honeylocust, jacaranda, silk tree. 2 to 20.
    Bipinnate(u8),
    /// A compound leaf of this many leaflets spread from the petiole's tip like fingers:
    /// buckeyes and horsechestnuts. 3 to 11.
    Palmate(u8),
    /// A bundle (fascicle) of this many needles from one sheath: pines. 1 to 5.
    Needles(u8),
    /// A twig set with single needles in two ranks: spruces, firs, Douglas fir, redwood.
    NeedleSpray,
    /// A flat spray of branchlets clad in scale leaves: junipers, arborvitae, incense cedar.
    ScaleSpray,
}

/// Leaflet, pinna and needle counts a [`LeafShape`] may carry (inclusive); outside them the
/// nearest is used.
pub const PINNATE_LEAFLETS: (u8, u8) = (2, 25);
/// See [`PINNATE_LEAFLETS`].
pub const BIPINNATE_PINNAE: (u8, u8) = (2, 20);
/// See [`PINNATE_LEAFLETS`].
pub const PALMATE_LEAFLETS: (u8, u8) = (3, 11);
/// See [`PINNATE_LEAFLETS`].
pub const BUNDLE_NEEDLES: (u8, u8) = (1, 5);

impl LeafShape {
    /// All shapes in index order.
    pub const ALL: [LeafShape; 9] = [
        LeafShape::Oval,
        LeafShape::Triangle,
        LeafShape::Oak,
        LeafShape::Maple3,
        LeafShape::Maple5,
        LeafShape::ThreeLeaflets,
        LeafShape::Square,
        LeafShape::Palm,
        LeafShape::Sphere,
    ];

    /// Every shape with a template of its own: the indexed nine, then the outlines and the
    /// counts of the compound kinds.
    pub fn every() -> impl Iterator<Item = LeafShape> {
        let counts = |(lo, hi): (u8, u8)| lo..=hi;
        Self::ALL
            .into_iter()
            .chain([
                LeafShape::Lobed5,
                LeafShape::Cordate,
                LeafShape::Fan,
                LeafShape::PointedLobes,
            ])
            .chain(counts(PINNATE_LEAFLETS).map(LeafShape::Pinnate))
            .chain(counts(BIPINNATE_PINNAE).map(LeafShape::Bipinnate))
            .chain(counts(PALMATE_LEAFLETS).map(LeafShape::Palmate))
            .chain(counts(BUNDLE_NEEDLES).map(LeafShape::Needles))
            .chain([LeafShape::NeedleSpray, LeafShape::ScaleSpray])
    }

    /// This shape with its count brought within its bounds (see [`PINNATE_LEAFLETS`]).
    pub fn clamped(self) -> LeafShape {
        let within = |n: u8, (lo, hi): (u8, u8)| n.clamp(lo, hi);
        match self {
            LeafShape::Pinnate(n) => LeafShape::Pinnate(within(n, PINNATE_LEAFLETS)),
            LeafShape::Bipinnate(n) => LeafShape::Bipinnate(within(n, BIPINNATE_PINNAE)),
            LeafShape::Palmate(n) => LeafShape::Palmate(within(n, PALMATE_LEAFLETS)),
            LeafShape::Needles(n) => LeafShape::Needles(within(n, BUNDLE_NEEDLES)),
            other => other,
        }
    }

    /// Position of this shape (clamped) in [`LeafShape::every`]: where its template is kept.
    pub fn slot(self) -> usize {
        let fixed = Self::ALL.len() + 4;
        let span = |(lo, hi): (u8, u8)| usize::from(hi - lo) + 1;
        let (p, b, m) = (
            span(PINNATE_LEAFLETS),
            span(BIPINNATE_PINNAE),
            span(PALMATE_LEAFLETS),
        );
        match self.clamped() {
            LeafShape::Lobed5 => Self::ALL.len(),
            LeafShape::Cordate => Self::ALL.len() + 1,
            LeafShape::Fan => Self::ALL.len() + 2,
            LeafShape::PointedLobes => Self::ALL.len() + 3,
            LeafShape::Pinnate(n) => fixed + usize::from(n - PINNATE_LEAFLETS.0),
            LeafShape::Bipinnate(n) => fixed + p + usize::from(n - BIPINNATE_PINNAE.0),
            LeafShape::Palmate(n) => fixed + p + b + usize::from(n - PALMATE_LEAFLETS.0),
            LeafShape::Needles(n) => fixed + p + b + m + usize::from(n - BUNDLE_NEEDLES.0),
            LeafShape::NeedleSpray => fixed + p + b + m + span(BUNDLE_NEEDLES),
            LeafShape::ScaleSpray => fixed + p + b + m + span(BUNDLE_NEEDLES) + 1,
            indexed => Self::ALL.iter().position(|&s| s == indexed).unwrap_or(0),
        }
    }

    /// Shape for a `LeafShape` index; out-of-range indices give `None`.
    pub fn from_index(index: u32) -> Option<Self> {
        Self::ALL.get(index as usize).copied()
    }

    /// Lower-case name (`oval`, `maple5`, ...).
    pub fn name(self) -> &'static str {
        match self {
            LeafShape::Oval => "oval",
            LeafShape::Triangle => "triangle",
            LeafShape::Oak => "oak",
            LeafShape::Maple3 => "maple3",
            LeafShape::Maple5 => "maple5",
            LeafShape::ThreeLeaflets => "three-leaflets",
            LeafShape::Square => "square",
            LeafShape::Palm => "palm",
            LeafShape::Sphere => "sphere",
            LeafShape::Lobed5 => "lobed5",
            LeafShape::Cordate => "cordate",
            LeafShape::Fan => "fan",
            LeafShape::PointedLobes => "pointed-lobes",
            LeafShape::Pinnate(_) => "pinnate",
            LeafShape::Bipinnate(_) => "bipinnate",
            LeafShape::Palmate(_) => "palmate",
            LeafShape::Needles(_) => "needles",
            LeafShape::NeedleSpray => "needle-spray",
            LeafShape::ScaleSpray => "scale-spray",
        }
    }
}

/// A leaf: its blade starts at `position` and extends along local z; local y is the blade normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leaf {
    /// Base of the blade (end of the petiole), metres.
    pub position: Vec3,
    /// Blade frame: z along the leaf, x across it, y its normal (the upper side).
    pub orientation: Quat,
    /// Blade length, metres.
    pub length: f32,
    /// Blade width, metres.
    pub width: f32,
    /// Outline.
    pub shape: LeafShape,
    /// The stem carrying the leaf.
    pub stem: StemId,
    /// Share of the sky's light reaching the leaf, 0..1 (1 in the open; the growth model's
    /// light grid sets less inside a crown). Meshes draw it in ten luminance classes.
    pub light: f32,
}

/// A whole tree as plain data.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Skeleton {
    /// Stems in creation order (a parent always before its children).
    pub stems: Vec<Stem>,
    /// All cross-sections, stem after stem.
    pub sections: Vec<CrossSection>,
    /// Leaves in creation order.
    pub leaves: Vec<Leaf>,
    /// How many of the last stems are short twigs (a grown tree's, `growth`): a crown in leaf
    /// hides each under its own leaves, so they are meshed only where the skeleton has no
    /// leaves (a bare crown), though they are always there to be measured and to cast shade.
    pub short_twigs: u32,
}

/// Counts and sizes of a skeleton.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SkeletonStats {
    /// Stems (clones included) per level, index = level.
    pub stems_per_level: Vec<usize>,
    /// Number of leaves.
    pub leaves: usize,
    /// Highest point of stems (centre plus radius) and leaves, metres above the trunk base.
    pub height: f32,
    /// Crown width: the largest horizontal extent (x or y) of everything but the trunks, metres.
    pub crown_width: f32,
}

impl Skeleton {
    /// The stems of the crown's frame: all but the short twigs (measures of a crown's form
    /// and size read these).
    pub fn frame_stems(&self) -> &[Stem] {
        let twigs = (self.short_twigs as usize).min(self.stems.len());
        &self.stems[..self.stems.len() - twigs]
    }

    /// Drops the short twigs (and their sections, which follow every other stem's): the
    /// crown's frame and leaves, for what draws only crowns in leaf.
    pub fn drop_short_twigs(&mut self) {
        let frame = self.frame_stems().len();
        let sections = (self.stems[..frame].iter())
            .map(|s| s.sections.end as usize)
            .max()
            .unwrap_or(0);
        self.stems.truncate(frame);
        self.sections.truncate(sections);
        // What is kept for long (the page's growths) must not hold the twigs' memory.
        self.stems.shrink_to_fit();
        self.sections.shrink_to_fit();
        self.short_twigs = 0;
    }

    /// The stems a mesh draws: all of them on a bare crown, all but the short twigs under a
    /// crown's leaves.
    pub fn meshed_stems(&self) -> &[Stem] {
        if self.leaves.is_empty() {
            &self.stems
        } else {
            self.frame_stems()
        }
    }

    /// Multiplies every length (positions, radii, stem lengths and offsets, leaf sizes) by
    /// `s`: the same tree at another size.
    pub fn scale(&mut self, s: f32) {
        if s == 1.0 {
            return;
        }
        for c in &mut self.sections {
            c.position *= s;
            c.radius *= s;
        }
        for stem in &mut self.stems {
            stem.length *= s;
            stem.offset *= s;
        }
        for leaf in &mut self.leaves {
            leaf.position *= s;
            leaf.length *= s;
            leaf.width *= s;
        }
    }

    /// Appends a stem through `points` (consecutive ones distinct) with a radius per point,
    /// each section framed along the segment that starts there (the last like the one before),
    /// and returns its id. For models that think in polylines (Nagel's, Fields').
    pub fn push_polyline(
        &mut self,
        points: &[Vec3],
        radii: &[f32],
        level: u8,
        parent: Option<StemId>,
    ) -> StemId {
        debug_assert_eq!(points.len(), radii.len());
        let first = self.sections.len() as u32;
        let total: f32 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
        let mut along = 0.0;
        let mut orientation = Quat::IDENTITY;
        for (i, (&p, &radius)) in points.iter().zip(radii).enumerate() {
            if let Some(next) = points.get(i + 1)
                && let Some(dir) = (*next - p).try_normalize()
            {
                orientation = Quat::from_rotation_arc(Vec3::Z, dir);
            }
            if i > 0 {
                along += p.distance(points[i - 1]);
            }
            self.sections.push(CrossSection {
                position: p,
                orientation,
                radius,
                z: if total > 0.0 { along / total } else { 0.0 },
            });
        }
        self.stems.push(Stem {
            level,
            parent,
            clone_of: None,
            offset: 0.0,
            length: total,
            sections: first..self.sections.len() as u32,
            lobes: 0,
            lobe_depth: 0.0,
        });
        StemId(self.stems.len() as u32 - 1)
    }

    /// Appends `part`, a subtree grown into a skeleton of its own whose roots are at `root_level`
    /// and hang from stems already here: its stem ids (clones, parents below the roots, leaves'
    /// stems) and section ranges are moved past what this skeleton holds. The roots' parents
    /// already name stems of this skeleton and stay.
    pub(crate) fn append_subtree(&mut self, part: Skeleton, root_level: u8) {
        let stem_base = self.stems.len() as u32;
        let section_base = self.sections.len() as u32;
        let moved = |id: StemId| StemId(id.0 + stem_base);
        self.stems.extend(part.stems.into_iter().map(|mut s| {
            if s.level > root_level {
                s.parent = s.parent.map(moved);
            }
            s.clone_of = s.clone_of.map(moved);
            s.sections = s.sections.start + section_base..s.sections.end + section_base;
            s
        }));
        self.sections.extend_from_slice(&part.sections);
        self.leaves.extend(part.leaves.into_iter().map(|mut l| {
            l.stem = moved(l.stem);
            l
        }));
    }

    /// Cross-sections of a stem.
    pub fn sections_of(&self, id: StemId) -> &[CrossSection] {
        let r = &self.stems[id.0 as usize].sections;
        &self.sections[r.start as usize..r.end as usize]
    }

    /// Position, segment frame and radius at unit position `z` of a stem (clamped to the stem's
    /// sections). Positions and radii are interpolated; the frame is that of the segment holding `z`.
    pub fn sample(&self, id: StemId, z: f32) -> (Vec3, Quat, f32) {
        let s = self.sections_of(id);
        debug_assert!(!s.is_empty());
        let i = s.partition_point(|c| c.z <= z);
        if i == 0 {
            return (s[0].position, s[0].orientation, s[0].radius);
        }
        if i >= s.len() {
            let last = s[s.len() - 1];
            return (last.position, last.orientation, last.radius);
        }
        let (a, b) = (s[i - 1], s[i]);
        let t = if b.z > a.z {
            (z - a.z) / (b.z - a.z)
        } else {
            0.0
        };
        (
            a.position.lerp(b.position, t),
            a.orientation,
            a.radius + (b.radius - a.radius) * t,
        )
    }

    /// Counts and dimensions.
    pub fn stats(&self) -> SkeletonStats {
        let mut stats = SkeletonStats::default();
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        let mut height = 0.0f32;
        for stem in &self.stems {
            let level = stem.level as usize;
            if stats.stems_per_level.len() <= level {
                stats.stems_per_level.resize(level + 1, 0);
            }
            stats.stems_per_level[level] += 1;
            let crown = stem.level > 0;
            for c in &self.sections[stem.sections.start as usize..stem.sections.end as usize] {
                height = height.max(c.position.z + c.radius);
                if crown {
                    lo = lo.min(c.position - c.radius);
                    hi = hi.max(c.position + c.radius);
                }
            }
        }
        for leaf in &self.leaves {
            let tip = leaf.position + leaf.orientation * Vec3::new(0.0, 0.0, leaf.length);
            for p in [leaf.position, tip] {
                height = height.max(p.z);
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        stats.leaves = self.leaves.len();
        stats.height = height;
        stats.crown_width = if lo.x.is_finite() {
            (hi.x - lo.x).max(hi.y - lo.y)
        } else {
            0.0
        };
        stats
    }
}
