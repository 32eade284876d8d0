//! One species grown through every whole age its data cover, once, with what the page shows at
//! each age: the tree measured against the equations, its account on each built-in site, and
//! its skeleton (meshed or drawn only when asked for: a skeleton is a fraction of a mesh's
//! size, and meshing a grown tree takes milliseconds).

use std::sync::OnceLock;
use sylva::ExportError;
use sylva::Skeleton;
use sylva::export::{Materials, shelled_glb, to_glb};
use sylva::growth::survey::report::{AgeRecord, MESH};
use sylva::growth::{Dress, Measured, dressed_mesh};
use sylva::lod::{LodTree, leaf_shell};
use sylva::mesh::{MeshOptions, TreeMesh, leaf_template};
use sylva::skeleton::{Leaf, LeafShape};
use sylva::street::study::{Spread, StreetTree, StudyYear};
use sylva::street::{Assessor, Kind, Site, YearAccount, rank};

/// A planting site the page offers: its key in the API, what the page calls it, and the site.
pub struct NamedSite {
    /// The `site` parameter's value.
    pub key: &'static str,
    /// What the page says.
    pub label: &'static str,
    /// The site.
    pub site: Site,
}

/// The three sites of issue N, read from the repository's `sites/` files at build time.
pub fn sites() -> &'static [NamedSite] {
    static SITES: OnceLock<Vec<NamedSite>> = OnceLock::new();
    SITES.get_or_init(|| {
        let files: [(&str, &str, &str, &str); 3] = [
            (
                "narrow",
                "Narrow sidewalk under wires",
                "sites/narrow-under-wires.toml",
                include_str!("../../../sites/narrow-under-wires.toml"),
            ),
            (
                "boulevard",
                "Wide boulevard",
                "sites/boulevard.toml",
                include_str!("../../../sites/boulevard.toml"),
            ),
            (
                "facade",
                "Façade 3 m from the trunk",
                "sites/facade-3m.toml",
                include_str!("../../../sites/facade-3m.toml"),
            ),
        ];
        files
            .into_iter()
            .map(|(key, label, file, text)| NamedSite {
                key,
                label,
                // The files are the repository's own and a test parses them: a failure here
                // is a broken build, not bad input.
                site: Site::parse(text, file).expect("the built-in sites parse"),
            })
            .collect()
    })
}

/// The index of a site key, or `None`.
pub fn site_index(key: &str) -> Option<usize> {
    sites().iter().position(|s| s.key == key)
}

/// One age of a grown species.
pub struct AgeEntry {
    /// The tree measured, and the equations at that age.
    pub record: AgeRecord,
    /// The year's account on each of [`sites`], in order.
    pub accounts: Vec<YearAccount>,
    /// The tree.
    pub skeleton: Skeleton,
    /// The tree as the page draws it, stored for range (leaves as kites): a request meshes
    /// any detail level from it in a few milliseconds, packing having been done here, on the
    /// growth's low-priority threads.
    pub lod: LodTree,
    /// The GLB at [`OPENING`], the level a page opens on and a browser without a graphics
    /// card keeps, made here as well: when many ask at once, each answer is a copy (empty if
    /// it could not be made; a request then meshes it).
    pub opening: axum::body::Bytes,
}

impl AgeEntry {
    /// Bytes held on the heap and in the entry itself, counting what each list has room for
    /// (its capacity), not only what it uses: what the cache's memory bound counts.
    pub fn bytes(&self) -> usize {
        let s = &self.skeleton;
        std::mem::size_of::<Self>()
            + s.stems.capacity() * std::mem::size_of::<sylva::skeleton::Stem>()
            + s.sections.capacity() * std::mem::size_of::<sylva::skeleton::CrossSection>()
            + s.leaves.capacity() * std::mem::size_of::<sylva::skeleton::Leaf>()
            + self.lod.heap_bytes()
            + self.opening.len()
            + self.accounts.capacity() * std::mem::size_of::<YearAccount>()
            + self
                .accounts
                .iter()
                .map(|a| std::mem::size_of_val(a.conflicts.as_slice()))
                .sum::<usize>()
    }
}

/// The whole ages the page shows for a species: from the first its data cover (at least 1)
/// to the last.
pub fn ages_of(m: &Measured) -> Vec<u32> {
    let ages = m.whole_ages();
    ((*ages.start()).max(1)..=*ages.end()).collect()
}

/// Grows `m` from seed `seed` through [`ages_of`], handing each age to `done` as it is
/// reached, so that the first ages can be shown while the rest grow. Stops early when `done`
/// returns false (nobody wants the rest). With `pruned`, the pruning regime of that site
/// ([`sites`]) cuts the tree as its cycles fall due, and that site's accounts carry the cycles
/// (the other sites' accounts are of the same cut tree, and the page never shows them).
pub fn grow_all(
    m: &Measured,
    seed: u64,
    pruned: Option<usize>,
    mut done: impl FnMut(AgeEntry) -> bool,
) {
    let on: Vec<Site> = sites().iter().map(|s| s.site.clone()).collect();
    let mut tree = StreetTree::on_sites(m, seed, &on, pruned);
    // The page draws no bark pattern (its rings are too coarse to carry one), but a species
    // whose twigs are darker than its bark (the white birch's) shows them so.
    let web_mesh = MeshOptions {
        young_bark: m.dress(None).young_bark,
        ..WEB_MESH
    };
    for age in ages_of(m) {
        let StudyYear {
            record,
            accounts,
            skeleton,
            ..
        } = tree.grow_to(f64::from(age), Spread::Whole, |_, _, _, _| {});
        // The page draws crowns in leaf, which hide the short twigs: each age keeps its frame
        // and leaves, and the memory the twigs would take goes to more growths held (the
        // accounts above read the whole tree, twigs' wood included).
        let mut skeleton = skeleton;
        skeleton.drop_short_twigs();
        skeleton.leaves.shrink_to_fit();
        // The page's crown, its leaves as kites, lent the skeleton's wood for the build
        // rather than a copy of it.
        let kited = kites(&skeleton.leaves);
        let leaves = std::mem::replace(&mut skeleton.leaves, kited);
        let lod = LodTree::build(&skeleton, &web_mesh);
        skeleton.leaves = leaves;
        let mut entry = AgeEntry {
            record,
            accounts,
            skeleton,
            lod,
            opening: Default::default(),
        };
        if let Ok(mut glb) = web_glb(m, &entry, OPENING) {
            // Held as long as the age is: no room past its length.
            glb.shrink_to_fit();
            entry.opening = glb.into();
        }
        if !done(entry) {
            return;
        }
    }
}

/// The benefits and costs not computed for `m`, each with its reason (the same on every site
/// but for the façade's energy).
pub fn missing(m: &Measured, site: usize) -> Vec<String> {
    let site = sites().get(site).map(|s| s.site.clone());
    Assessor::new(m, site, None, None).missing().to_vec()
}

/// The first age each kind of conflict happens on site `site`, in order of age (the
/// library's [`rank::first_conflicts`], which lists them by kind).
pub fn first_conflicts<'a>(
    entries: impl IntoIterator<Item = &'a AgeEntry>,
    site: usize,
) -> Vec<(u32, Kind)> {
    let accounts: Vec<YearAccount> = (entries.into_iter())
        .map(|e| e.accounts[site].clone())
        .collect();
    let mut first: Vec<(u32, Kind)> = rank::first_conflicts(&accounts)
        .into_iter()
        .map(|(age, c)| (age as u32, c.kind))
        .collect();
    first.sort_by_key(|(age, _)| *age);
    first
}

/// How the page's trees are meshed: a browser draws several trees of tens of thousands of
/// leaves each while a slider moves, so the rings are coarser than `sylva grow`'s and every
/// leaf is a four-corner kite instead of an eight-corner oval. The kite is widened by 1.4 so
/// that its area (0.50 of its length × width) is the oval's (the octagon Sylva meshes covers
/// 0.70): the crown holds the same leaf area and looks as dense.
pub const WEB_MESH: MeshOptions = MeshOptions {
    quality: MESH.quality * 0.6,
    sides: None,
    bark: sylva::mesh::BarkPattern::Smooth,
    young_bark: 1.0,
    twig_copies: false,
};

/// How much wider a kite is than the oval it stands for (see [`WEB_MESH`]).
const KITE_WIDENING: f32 = 0.70 / 0.50;

/// Most detail levels the page may ask for: 0 is the whole tree, each next one draws about
/// half the triangles, and the last, [`SHELL`], draws the crown as a leaf shell.
pub const DETAIL_LEVELS: u32 = 5;

/// The coarsest level: the trunk and the largest limbs, and the crown as a leaf shell
/// ([`leaf_shell`]), which a browser drawing WebGL on its CPU fills about a third as fast as
/// the coarsest crown of leaves (see `sylva-serve/tests/web/e2e.mjs`).
pub const SHELL: u32 = DETAIL_LEVELS - 1;

/// The level the page asks for first, the coarsest.
pub const OPENING: u32 = SHELL;

/// Items of each of the four lists of a [`LodTree`] (stems by level, then leaves) that each
/// detail level but the shell keeps, as Weber & Penn's degradation at range thins a tree: twigs
/// and leaves first, the trunk and limbs never. The leaves that remain grow to keep the crown's
/// leaf area ([`LodTree::engine_mesh`]).
const DETAIL: [[f64; 4]; SHELL as usize] = [
    [16.0, 16.0, 16.0, 4.0],
    [16.0, 16.0, 8.0, 2.0],
    [16.0, 8.0, 2.0, 1.0],
    [16.0, 4.0, 1.0, 0.5],
];

/// The stems the shell level draws: the trunk and the largest eighth of the limbs (the rest
/// lie inside the shell).
const SHELL_STEMS: [f64; 4] = [16.0, 2.0, 0.0, 0.0];

/// A grown tree as the page draws it at `detail` (0 to [`DETAIL_LEVELS`] - 1), in a GLB. A
/// browser without a GPU draws some hundred thousand triangles a second, so the page asks for
/// the level its own frame times allow.
pub fn web_glb(m: &Measured, entry: &AgeEntry, detail: u32) -> Result<Vec<u8>, ExportError> {
    let (bark, leaves) = m.colours();
    let materials = Materials::from_srgb(bark, leaves);
    if detail >= SHELL {
        let wood = entry.lod.mesh_at(SHELL_STEMS).bark;
        let shell = leaf_shell(&entry.skeleton.leaves);
        return Ok(shelled_glb(&wood, &shell, &m.label(), &materials)?.to_vec());
    }
    let mesh = entry.lod.engine_mesh(DETAIL[detail as usize]);
    to_glb(&mesh, &m.label(), &materials)
}

/// The leaves, each drawn as a kite of the same area: ovals widened by
/// [`KITE_WIDENING`], any other outline (a species' lobed, heart-shaped or compound leaf) by its
/// template's area over the kite's. Four corners a leaf whatever the species wears, so the page's
/// frame times hold for every species; the species still shows in its colours, and in its
/// leaves' size and number.
fn kites(leaves: &[Leaf]) -> Vec<Leaf> {
    let kite = leaf_template(LeafShape::Triangle).area();
    // A tree's leaves share one or two shapes: each widening is worked out once.
    let mut widening: Vec<(LeafShape, f32)> = Vec::new();
    let mut light = leaves.to_vec();
    for leaf in &mut light {
        let w = match widening.iter().find(|(s, _)| *s == leaf.shape) {
            Some(&(_, w)) => w,
            None => {
                let w = match leaf.shape {
                    LeafShape::Triangle => 1.0,
                    LeafShape::Oval => KITE_WIDENING,
                    other => leaf_template(other).area() / kite,
                };
                widening.push((leaf.shape, w));
                w
            }
        };
        if leaf.shape != LeafShape::Triangle {
            leaf.width *= w;
        }
        leaf.shape = LeafShape::Triangle;
    }
    light
}

/// A grown tree as `sylva grow` meshes it and dresses it without a season (for pictures).
pub fn full_mesh(skeleton: &Skeleton, m: &Measured) -> (TreeMesh, Dress) {
    dressed_mesh(skeleton, m, None, &MESH)
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::growth::Database;

    /// The skeleton with its leaves as kites.
    fn with_kites(s: &Skeleton) -> Skeleton {
        Skeleton {
            leaves: kites(&s.leaves),
            ..s.clone()
        }
    }

    #[test]
    fn the_built_in_sites_parse_and_have_what_the_page_draws() {
        let s = sites();
        assert_eq!(s.len(), 3);
        assert!(!s[0].site.wire.is_empty(), "narrow has a wire");
        assert!(s[2].site.facade.is_some(), "façade site has a façade");
        assert_eq!(site_index("boulevard"), Some(1));
        assert_eq!(site_index("nowhere"), None);
    }

    #[test]
    fn the_web_kite_keeps_the_leaf_area_and_cuts_the_vertices() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut got = Vec::new();
        grow_all(&plane, 0, None, |e| {
            got.push(e);
            got.len() < 6
        });
        assert_eq!(got.len(), 6, "stops when told");
        assert_eq!(got[0].record.age, 1.0);
        assert_eq!(got[5].record.age, 6.0);
        // Each age holds the opening level's GLB as a request would mesh it, and counts it.
        for e in &got {
            let glb = web_glb(&plane, e, OPENING).unwrap();
            assert_eq!(e.opening.as_ref(), glb.as_slice(), "age {}", e.record.age);
            assert!(e.bytes() > glb.len() + e.lod.heap_bytes());
        }
        let s = &got[5].skeleton;
        let (full, _) = full_mesh(s, &plane);
        let web = sylva::mesh::mesh_tree(&with_kites(s), &WEB_MESH);
        // Every leaf a kite of four corners.
        assert_eq!(web.leaves.vertex_count(), 4 * s.leaves.len());
        assert!(web.leaves.vertex_count() < full.leaves.vertex_count());
        let area = |mesh: &sylva::mesh::Mesh| -> f64 {
            mesh.indices
                .chunks(3)
                .map(|t| {
                    let p = |i: u32| glam::Vec3::from(mesh.positions[i as usize]);
                    let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
                    f64::from((b - a).cross(c - a).length()) / 2.0
                })
                .sum()
        };
        let (f, w) = (area(&full.leaves), area(&web.leaves));
        assert!(
            (w / f - 1.0).abs() < 0.05,
            "leaf area web {w:.2} vs full {f:.2} m²"
        );
        // Each coarser level draws fewer triangles and keeps the leaf area.
        let lod = LodTree::build(&with_kites(s), &WEB_MESH);
        let whole = lod.engine_mesh(DETAIL[0]);
        println!(
            "level 0: {} triangles (mesh_tree: {}), leaves {:.1} m²",
            whole.triangle_count(),
            web.triangle_count(),
            area(&whole.leaves)
        );
        assert_eq!(whole.leaves.triangle_count(), web.leaves.triangle_count());
        assert!((area(&whole.leaves) / w - 1.0).abs() < 1e-3);
        let mut before = whole.triangle_count();
        for (level, x) in DETAIL.iter().enumerate().skip(1) {
            let m = lod.engine_mesh(*x);
            let a = area(&m.leaves);
            println!(
                "level {level}: {} triangles, leaves {a:.1} m²",
                m.triangle_count()
            );
            assert!(m.triangle_count() < before, "level {level}");
            assert!(
                (a / f - 1.0).abs() < 0.1,
                "level {level}: leaf area {a:.2} vs {f:.2} m²"
            );
            before = m.triangle_count();
        }
        // The shell level: the trunk and largest limbs, and one closed surface for the crown,
        // under the coarsest leaves' triangles and bytes.
        let (shell, coarsest) = (
            web_glb(&plane, &got[5], SHELL).unwrap(),
            web_glb(&plane, &got[5], SHELL - 1).unwrap(),
        );
        let shell_triangles =
            lod.mesh_at(SHELL_STEMS).triangle_count() + leaf_shell(&s.leaves).triangle_count();
        println!(
            "shell: {shell_triangles} triangles, {} bytes (level {}: {} bytes)",
            shell.len(),
            SHELL - 1,
            coarsest.len()
        );
        assert!(shell_triangles < before && shell.len() < coarsest.len());
    }

    /// The page's coarsest trees keep the grown crown's size: the shell's width (the mean of its
    /// x and y extents, as the survey measures a crown) and top are the grown tree's, within the
    /// reach the shell leaves out (the outermost tenth of each direction's leaves) and the
    /// roughness it adds.
    #[test]
    fn a_leaf_shell_is_as_wide_and_tall_as_its_crown() {
        let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
        let mut got = Vec::new();
        grow_all(&plane, 0, None, |e| {
            if (e.record.age as u32).is_multiple_of(5) {
                got.push(e);
            }
            got.len() < 4
        });
        for e in &got {
            let shell = leaf_shell(&e.skeleton.leaves);
            let (lo, hi) = shell.bounds().unwrap();
            let width = f64::from((hi[0] - lo[0]) + (hi[1] - lo[1])) / 2.0;
            let model = e.record.model;
            println!(
                "age {}: shell {width:.2} m wide, top {:.2} m; crown {:.2} m, height {:.2} m",
                e.record.age, hi[2], model.crown_diameter, model.height
            );
            assert!(
                (width / model.crown_diameter - 1.0).abs() < 0.06,
                "age {}: shell {width:.2} m, crown {:.2} m",
                e.record.age,
                model.crown_diameter
            );
            assert!(
                (f64::from(hi[2]) / model.height - 1.0).abs() < 0.05,
                "age {}: shell top {:.2} m, tree {:.2} m",
                e.record.age,
                hi[2],
                model.height
            );
        }
    }
}
