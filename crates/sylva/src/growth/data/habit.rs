//! Species habits: the few numbers that give a grown tree its architecture while the measured
//! equations fix its size (growth-architecture spec section 3). A habit is chosen by species
//! code where the table below names it, otherwise by the Urban Tree Database's tree type.
//!
//! The numbers are the spec's mid-range defaults per form:
//!
//! | form | apical control | branch angle | up-tropism | envelope |
//! |---|---|---|---|---|
//! | excurrent conifer | 0.59 | 80 (near horizontal, whorled) | 0.30 (laterals level) | cone |
//! | oval / upright | 0.55 | 50 | 0.15 | cone, then an egg (by 30 years) |
//! | round, decurrent | 0.49 | 45 | 0.10 | ellipsoid |
//! | vase | 0.46 | 28 | 0.20 | inverted cone |
//! | umbrella, spreading | 0.47 | 50 | 0.05 | flattened ellipsoid |
//! | columnar | 0.57 | 18 | 0.30 | cylinder |
//! | weeping | 0.50 | 52 | -0.15 (tips hang) | ellipsoid |
//! | palm | - | no branches | - | a rosette of fronds |
//!
//! Apical control (lambda, Borchert-Honda) is the share of resource a branching point sends
//! along its axis when both arms are equally lit: above 0.5 a leader dominates (excurrent),
//! below it the laterals win and the crown forks (decurrent). The branch angle is measured from
//! the parent axis, degrees.

/// A tree's form, as street-tree references describe it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TreeForm {
    /// One leader to the top, near-level whorled laterals: pines, firs, cedars.
    ExcurrentConifer,
    /// Upright, pyramidal when young and oval later, keeping a leader: sweetgum, magnolia.
    Oval,
    /// Broad and rounded, the trunk forking into ascending scaffolds: plane, ash, maples.
    Round,
    /// Many ascending limbs from a short trunk: zelkova, American elm, crape myrtle.
    Vase,
    /// Wide and flat-topped, limbs spreading: pistache, goldenrain tree, live oak.
    Umbrella,
    /// Narrow and upright: Italian cypress, Lombardy poplar.
    Columnar,
    /// Tips hanging: weeping willow, weeping cherry.
    Weeping,
    /// A single unbranched stem with a rosette of fronds.
    Palm,
}

/// The shape of the space a crown may fill.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Envelope {
    /// Widest at the base.
    Cone,
    /// Widest at mid-height.
    Ellipsoid,
    /// A vase: opening straight from a narrow base, widest three quarters of the way up.
    InvertedCone,
    /// An umbrella: widest above the middle, flat-topped.
    FlatEllipsoid,
    /// As wide at the top as at the base.
    Cylinder,
    /// Pyramidal when young and oval later (the spec's "cone -> ellipsoid" for sweetgum,
    /// Callery pear, magnolia, linden): a cone that fills out into an egg, widest a third of
    /// the way up, as the tree grows up (see [`Envelope::grown`]).
    ConeThenOval,
}

impl Envelope {
    /// How far a crown of `age` years has come from its young form to its grown one, 0..1:
    /// only [`Envelope::ConeThenOval`] changes. The sources say "pyramidal when young, oval
    /// later" (sweetgum: "oval when old") and give no age; Sylva keeps the cone through the
    /// first decade after planting and reaches the oval at 30 years. Kept a cone (as it was
    /// until issue R), a 30-year Callery pear or sweetgum held its measured leaf area in two
    /// thirds of the outline an oval of the same height and width shows, and its picture
    /// covered 86-89% of that outline where street crowns stop 60-85% of the sun.
    pub fn grown(self, age: f64) -> f32 {
        ((age as f32 - OVAL_FROM) / (OVAL_BY - OVAL_FROM)).clamp(0.0, 1.0)
    }

    /// Radius of the envelope at relative height `p` in the crown (0 at the crown base, 1 at
    /// the top), as a share of its widest radius, on a crown `grown` (0..1, see
    /// [`Envelope::grown`]) of the way to its mature form.
    pub fn relative_radius(self, p: f32, grown: f32) -> f32 {
        let p = p.clamp(0.0, 1.0);
        // A superellipse widest at `mid`, its lower and upper parts of their own powers (2:
        // an ellipse's quarter; higher: fuller, flatter at the end).
        let around = |mid: f32, low: f32, high: f32| {
            let (q, power) = if p < mid {
                ((mid - p) / mid, low)
            } else {
                ((p - mid) / (1.0 - mid), high)
            };
            (1.0 - q.min(1.0).powf(power)).powf(1.0 / power)
        };
        match self {
            Envelope::Cone => (1.0 - p).powf(0.9),
            Envelope::Ellipsoid => around(0.45, 2.0, 2.0),
            // A vase: straight sides opening from a narrow base to three quarters of the
            // way up, then a low dome.
            Envelope::InvertedCone => {
                if p < VASE_SHOULDER {
                    0.3 + 0.7 * p / VASE_SHOULDER
                } else {
                    around(VASE_SHOULDER, 2.0, 2.0)
                }
            }
            // An umbrella: full low down, widest above the middle, its top flat.
            Envelope::FlatEllipsoid => around(0.55, 2.0, 3.0),
            Envelope::Cylinder => around(0.5, 6.0, 6.0),
            // Grown, an egg: rounded below its widest, a third of the way up, and tapering
            // to a blunt top above it (a power under 2 is more pointed than an ellipse), so the
            // crown keeps its leader (magnolia and linden "keep a leader"). In an ellipse
            // widest at mid-height, or an egg of power 1.5, the magnolia's long upper limbs rose
            // to the top as a third codominant stem at 30-40 years.
            Envelope::ConeThenOval => {
                let cone = Envelope::Cone.relative_radius(p, grown);
                let oval = around(OVAL_WIDEST, 2.0, OVAL_TOP_POWER);
                cone + (oval - cone) * grown.clamp(0.0, 1.0)
            }
        }
    }
}

/// Ages (years since planting) at which an oval crown starts to fill out from its young cone
/// and at which it is oval (see [`Envelope::grown`]): Sylva's reading of "young" and "later".
const OVAL_FROM: f32 = 10.0;
const OVAL_BY: f32 = 30.0;
/// A grown oval's widest level, a share of the crown's height, and the power of its upper
/// part's profile (see [`Envelope::relative_radius`]). Sylva's drawing of "oval".
const OVAL_WIDEST: f32 = 0.35;
const OVAL_TOP_POWER: f32 = 1.3;

/// Where a vase's straight sides end and its dome begins, a share of the crown's height.
const VASE_SHOULDER: f32 = 0.75;

/// The habit parameters of a form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Habit {
    /// The form these numbers give.
    pub form: TreeForm,
    /// Apical control lambda, 0..1 (0.5: axis and lateral share equally).
    pub apical_control: f32,
    /// Angle of a new lateral from its parent axis, degrees.
    pub branch_angle: f32,
    /// Weight of the pull upward on new shoots (negative: tips hang).
    pub tropism: f32,
    /// The space the crown fills.
    pub envelope: Envelope,
    /// Stems from the ground (crape myrtle and other multi-stem trees: more than 1).
    pub stems: u8,
    /// How far each year's shoot of a limb turns aside from the last, degrees, the other way
    /// each year: the zig-zag of a limb's annual growth.
    pub zigzag: f32,
}

impl TreeForm {
    /// The spec's default habit for the form.
    pub fn habit(self) -> Habit {
        let (apical_control, branch_angle, tropism, envelope) = match self {
            TreeForm::ExcurrentConifer => (0.59, 80.0, 0.30, Envelope::Cone),
            TreeForm::Oval => (0.55, 50.0, 0.15, Envelope::ConeThenOval),
            TreeForm::Round => (0.49, 45.0, 0.10, Envelope::Ellipsoid),
            TreeForm::Vase => (0.46, 28.0, 0.20, Envelope::InvertedCone),
            TreeForm::Umbrella => (0.47, 50.0, 0.05, Envelope::FlatEllipsoid),
            TreeForm::Columnar => (0.57, 18.0, 0.30, Envelope::Cylinder),
            TreeForm::Weeping => (0.50, 52.0, -0.15, Envelope::Ellipsoid),
            TreeForm::Palm => (1.0, 0.0, 0.0, Envelope::Cylinder),
        };
        Habit {
            form: self,
            apical_control,
            branch_angle,
            tropism,
            envelope,
            stems: 1,
            zigzag: self.zigzag(),
        }
    }

    /// The zig-zag of the form's limbs, degrees. Decurrent crowns are sympodial: each year's
    /// shoot grows on from a bud beside the last one's tip (the terminal bud dies or flowers),
    /// so their limbs zig-zag most (Barthélémy & Caraglio 2007, Annals of Botany 99:375,
    /// on monopodial and sympodial axes). An excurrent tree's axes grow on from their own
    /// terminal buds and run straighter; a conifer's are straight. The angles are Sylva's
    /// drawing choice, small enough that a limb's course still follows its crown.
    fn zigzag(self) -> f32 {
        match self {
            TreeForm::ExcurrentConifer | TreeForm::Palm => 0.0,
            TreeForm::Oval | TreeForm::Columnar => 7.0,
            TreeForm::Round | TreeForm::Vase | TreeForm::Umbrella | TreeForm::Weeping => 12.0,
        }
    }

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            TreeForm::ExcurrentConifer => "excurrent conifer",
            TreeForm::Oval => "oval",
            TreeForm::Round => "round",
            TreeForm::Vase => "vase",
            TreeForm::Umbrella => "umbrella",
            TreeForm::Columnar => "columnar",
            TreeForm::Weeping => "weeping",
            TreeForm::Palm => "palm",
        }
    }
}

/// Species with a form of their own: the Modesto seven, the twenty species planted in the most
/// of the database's regions, and a few whose form no tree type would guess. Codes as the
/// database writes them; a cultivar's suffix (`PYCA_B`) falls back to its species (`PYCA`).
const SPECIES: [(&str, TreeForm, &str); 31] = [
    // Modesto (region InlVal), the seeds' data.
    (
        "PLAC",
        TreeForm::Round,
        "London plane: pyramidal young, then broad and rounded, massive ascending scaffolds",
    ),
    // The spec's habit table puts maples with the round, broad decurrent trees (scaffolds
    // 35-55 degrees), and its vases (20-35 degrees from vertical) are zelkova, elm and crape
    // myrtle. The silver maple's upright-spreading oval comes from its measured crown, taller
    // than wide.
    (
        "ACSA1",
        TreeForm::Round,
        "silver maple: fast, upright-spreading, vase to oval, long limbs",
    ),
    ("FRVE_G", TreeForm::Round, "Modesto ash: rounded, dense"),
    (
        "KOPA",
        TreeForm::Umbrella,
        "goldenrain tree: small, rounded to irregular, spreading",
    ),
    (
        "MAGR",
        TreeForm::Oval,
        "southern magnolia: dense evergreen, pyramidal to oval, keeps a leader",
    ),
    (
        "PICH",
        TreeForm::Umbrella,
        "Chinese pistache: vase-like young, a broad umbrella when mature",
    ),
    (
        "CESI4",
        TreeForm::Round,
        "Chinese hackberry: broad, rounded, spreading",
    ),
    // The most widely planted (by regions listing them).
    (
        "LIST",
        TreeForm::Oval,
        "sweetgum: pyramidal with a leader, oval when old",
    ),
    (
        "GLTR",
        TreeForm::Umbrella,
        "honeylocust: open, spreading, flat-topped",
    ),
    ("PYCA", TreeForm::Oval, "Callery pear: upright, oval"),
    (
        "QURU",
        TreeForm::Round,
        "northern red oak: rounded, spreading",
    ),
    ("ACRU", TreeForm::Oval, "red maple: upright oval"),
    (
        "ACSA2",
        TreeForm::Oval,
        "sugar maple: upright oval to rounded",
    ),
    ("MA2", TreeForm::Round, "apple: small, rounded, spreading"),
    ("ACPL", TreeForm::Round, "Norway maple: dense, rounded"),
    (
        "CICA",
        TreeForm::Round,
        "camphor tree: broad, rounded evergreen",
    ),
    (
        "FRPE",
        TreeForm::Round,
        "green ash: upright-spreading, rounded",
    ),
    (
        "GIBI",
        TreeForm::Oval,
        "ginkgo: sparse, pyramidal and irregular young, spreading old",
    ),
    ("ULPU", TreeForm::Round, "Siberian elm: rounded, open"),
    ("ULAM", TreeForm::Vase, "American elm: the classic vase"),
    ("PRCE", TreeForm::Round, "cherry plum: small, rounded"),
    (
        "TICO",
        TreeForm::Oval,
        "littleleaf linden: pyramidal to oval, keeps a leader",
    ),
    ("LAIN", TreeForm::Vase, "crape myrtle: several stems, vase"),
    // Others whose form their tree type would not give.
    (
        "ZESE",
        TreeForm::Vase,
        "zelkova: vase, many ascending limbs from a short trunk",
    ),
    (
        "ULPA",
        TreeForm::Umbrella,
        "Chinese elm: broad, spreading, arching",
    ),
    (
        "QUVI",
        TreeForm::Umbrella,
        "southern live oak: broad, wide-spreading, low limbs",
    ),
    (
        "QUAG",
        TreeForm::Umbrella,
        "coast live oak: broad, wide-spreading, low limbs",
    ),
    (
        "CHLI",
        TreeForm::Vase,
        "desert willow: several stems, open vase",
    ),
    ("WARO", TreeForm::Palm, "Mexican fan palm"),
    ("SAPA", TreeForm::Palm, "cabbage palmetto"),
    ("PHCA", TreeForm::Palm, "Canary Island date palm"),
];

/// The form the database's tree type gives (`BDL`: broadleaf, deciduous, large; `C..`:
/// conifer; `P..`: palm): conifers excurrent, palms unbranched, large broadleaves round,
/// medium ones oval, small ones round.
pub fn form_of_type(tree_type: &str) -> TreeForm {
    let t = tree_type.as_bytes();
    match (t.first(), t.get(2)) {
        (Some(b'C'), _) => TreeForm::ExcurrentConifer,
        (Some(b'P'), _) => TreeForm::Palm,
        (_, Some(b'M')) => TreeForm::Oval,
        _ => TreeForm::Round,
    }
}

/// The habit of a species: its own row where the table has one, else its tree type's. Multi-
/// stem species grow three stems: the crape myrtle ("several stems", the growth-architecture
/// spec's habit notes) and the desert willow ("often multi-trunked, but can be trained to a
/// single-trunk tree": C. Vadheim's native-plant notes on Chilopsis linearis; a "multi-trunk
/// tree", the Contra Costa water-saving plant list); three is Sylva's count for "several".
pub fn habit_of(code: &str, tree_type: &str) -> Habit {
    let base = code.split('_').next().unwrap_or(code);
    let row = SPECIES
        .iter()
        .find(|(c, _, _)| *c == code)
        .or_else(|| SPECIES.iter().find(|(c, _, _)| *c == base));
    let mut habit = row.map_or_else(|| form_of_type(tree_type), |r| r.1).habit();
    if matches!(base, "LAIN" | "CHLI") {
        habit.stems = 3;
    }
    habit
}

/// Every species with a row of its own: code, form, and the form in words.
pub fn species_rows() -> impl Iterator<Item = (&'static str, TreeForm, &'static str)> {
    SPECIES.iter().copied()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::growth::data::database::Database;

    #[test]
    fn every_species_in_the_database_has_a_habit_and_the_named_ones_their_form() {
        let db = Database::builtin();
        for entry in db.species() {
            let h = habit_of(&entry.code, &entry.tree_type);
            assert!((0.0..=1.0).contains(&h.apical_control), "{}", entry.code);
            if entry.tree_type.starts_with('P') {
                assert_eq!(h.form, TreeForm::Palm, "{}", entry.code);
            }
            if entry.tree_type.starts_with('C') {
                assert!(
                    h.apical_control > 0.5,
                    "a conifer keeps its leader: {}",
                    entry.code
                );
            }
        }
        assert!(db.species().len() > 300, "{}", db.species().len());
        assert_eq!(habit_of("PLAC", "BDL").form, TreeForm::Round);
        assert!(
            habit_of("PLAC", "BDL").apical_control < 0.5,
            "a plane forks"
        );
        assert_eq!(habit_of("PYCA_B", "BDM").form, TreeForm::Oval);
        assert_eq!(habit_of("LAIN", "BDS").stems, 3);
        assert_eq!(habit_of("XXXX", "CEL").form, TreeForm::ExcurrentConifer);
        // Every row names a species the database has.
        for (code, _, words) in species_rows() {
            assert!(!words.is_empty());
            let known = db
                .species()
                .iter()
                .any(|e| e.code == code || e.code.split('_').next() == Some(code));
            assert!(known, "{code} is not in the database");
        }
    }

    #[test]
    fn an_oval_crown_is_a_cone_when_young_and_an_egg_by_thirty() {
        let oval = TreeForm::Oval.habit().envelope;
        assert_eq!(oval, Envelope::ConeThenOval);
        assert_eq!(oval.grown(5.0), 0.0);
        assert_eq!(oval.grown(10.0), 0.0);
        assert!((oval.grown(20.0) - 0.5).abs() < 1e-6);
        assert_eq!(oval.grown(30.0), 1.0);
        assert_eq!(oval.grown(60.0), 1.0);
        for k in 0..=20 {
            let p = k as f32 / 20.0;
            let r = |e: Envelope, g: f32| e.relative_radius(p, g);
            assert_eq!(r(oval, 0.0), r(Envelope::Cone, 0.0));
            // Half-way, between the young and the grown profile.
            let (lo, hi) = (r(oval, 0.0), r(oval, 1.0));
            let mid = r(oval, 0.5);
            assert!(
                mid >= lo.min(hi) - 1e-6 && mid <= lo.max(hi) + 1e-6,
                "{p}: {mid}"
            );
        }
        // Young it is widest at its base; grown, a third of the way up.
        let widest = |g: f32| {
            (0..=100)
                .map(|k| k as f32 / 100.0)
                .max_by(|a, b| {
                    oval.relative_radius(*a, g)
                        .total_cmp(&oval.relative_radius(*b, g))
                })
                .unwrap()
        };
        assert_eq!(widest(0.0), 0.0);
        assert!((widest(1.0) - OVAL_WIDEST).abs() < 0.011, "{}", widest(1.0));
        // Grown, it fills more of its box than a cone (about half) and less than an ellipse
        // (pi/4), its top more pointed.
        let fill = |g: f32| {
            (0..1000)
                .map(|k| oval.relative_radius((k as f32 + 0.5) / 1000.0, g))
                .sum::<f32>()
                / 1000.0
        };
        assert!((fill(0.0) - 1.0 / 1.9).abs() < 0.01, "{}", fill(0.0));
        assert!((0.66..0.78).contains(&fill(1.0)), "{}", fill(1.0));
        assert!(oval.relative_radius(0.9, 1.0) < Envelope::Ellipsoid.relative_radius(0.9, 1.0));
    }

    #[test]
    fn vases_open_straight_and_umbrellas_are_flat_topped() {
        let r = |e: Envelope, p: f32| e.relative_radius(p, 1.0);
        // A vase: narrow at the base, its sides straight to the shoulder, widest there.
        let vase = Envelope::InvertedCone;
        assert!((r(vase, 0.0) - 0.3).abs() < 1e-6);
        let mid = r(vase, VASE_SHOULDER / 2.0);
        assert!((mid - (r(vase, 0.0) + 1.0) / 2.0).abs() < 1e-5, "{mid}");
        assert!((r(vase, VASE_SHOULDER) - 1.0).abs() < 1e-6);
        // An umbrella is fuller than an ellipsoid near its top: a flat top.
        let (umbrella, round) = (Envelope::FlatEllipsoid, Envelope::Ellipsoid);
        assert!(r(umbrella, 0.9) > r(round, 0.9) + 0.15);
        // Every profile stays within 0..1 and meets the top.
        for e in [
            Envelope::Cone,
            round,
            vase,
            umbrella,
            Envelope::Cylinder,
            Envelope::ConeThenOval,
        ] {
            for k in 0..=20 {
                let v = r(e, k as f32 / 20.0);
                assert!((0.0..=1.0).contains(&v), "{e:?} {v}");
            }
            assert!(r(e, 1.0) < 1e-3, "{e:?}");
        }
    }
}
