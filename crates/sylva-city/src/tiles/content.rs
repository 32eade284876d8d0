//! One tile's content: a GLB drawing each of its trees as an instance of its grown tree's mesh
//! at the tile's level of detail (`EXT_mesh_gpu_instancing`, the meshes read from the shared
//! prototype files), each tree a feature with a row of attributes (`EXT_instance_features`,
//! `EXT_structural_metadata`).

use crate::trees::benefits::TreeYear;
use crate::trees::cad::drawn_scale;
use crate::trees::plan::{Kind, Planned, ProtoKey};
use crate::trees::prototypes::Prototype;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use serde_json::json;
use std::collections::{BTreeMap, HashMap};
use sylva::export::{
    Column, Features, InstancedGroup, InstancedMesh, Materials, MeshSource, Metadata, PointSet,
    PropertyTable, SharedImpostor, SharedMesh, instanced_glb,
};

/// The name of a coarse tile's points: the trees below it that it leaves out of its meshes.
pub const LEFT_OUT: &str = "left-out";

/// The level of detail whose trees draw as their impostors: the coarsest, whose tiles are
/// seen from so far that a tree is a few to some tens of pixels tall. Nearer levels keep
/// their meshes.
pub const IMPOSTOR_LEVEL: usize = 2;

/// One tree of a tile: its plan, its year's figures, and what its row of attributes says
/// beyond them (the inventory's id and the species as the inventory writes it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TileTree {
    /// Where it stands and what it is.
    pub tree: Planned,
    /// Its benefits this year.
    pub year: TreeYear,
    /// The inventory's id of it.
    pub id: String,
    /// The species as the inventory names it.
    pub written: String,
    /// Its condition as the inventory recorded it (`good`, `fair`, `poor`; empty: not
    /// recorded).
    pub condition: String,
}

/// The schema of every tile's property tables: one class, a street tree.
pub fn schema() -> serde_json::Value {
    let text = json!({ "type": "STRING" });
    let number = |description: &str| json!({ "type": "SCALAR", "componentType": "FLOAT32", "description": description });
    // -1 where no model or price gives the figure.
    let benefit = |description: &str| {
        json!({ "type": "SCALAR", "componentType": "FLOAT32", "description": description,
                "noData": crate::trees::benefits::NO_DATA })
    };
    json!({
        "id": "sylva_city",
        "classes": { "tree": {
            "name": "Street tree",
            "description": "A tree of the inventory, grown by Sylva from the USDA Urban Tree Database's equations",
            "properties": {
                "id": { "type": "STRING", "description": "The inventory's id of the tree (or its line)" },
                "species_written": { "type": "STRING", "description": "The species as the inventory names it" },
                "species": { "type": "STRING", "description": "Urban Tree Database species code it is grown as" },
                "common_name": text,
                "scientific_name": text,
                "region": { "type": "STRING", "description": "Urban Tree Database climate region whose equations grow it" },
                "condition": { "type": "STRING", "description": "Its condition as the inventory recorded it, in i-Tree Streets' classes: good, fair or poor; empty where not recorded" },
                "dbh_cm": number("Trunk diameter at breast height, cm"),
                "age_years": number("Age, years since planting"),
                "height_m": number("Height, m"),
                "crown_diameter_m": number("Crown diameter, m"),
                "co2_stored_kg": benefit("CO2 held in the tree, kg (Jenkins et al. 2003 biomass by DBH)"),
                "co2_sequestered_kg_per_year": benefit("CO2 taken up this year, kg"),
                "rain_intercepted_m3_per_year": benefit("Rain held back this year, m3"),
                "benefits_usd_per_year": benefit("This year's CO2 uptake, rain interception, air quality and aesthetics of the grown crown at the region's built-in prices (its energy is not computed: no façades), US dollars"),
                "typical_energy_usd_per_year": benefit("At i-Tree Streets' typical position, at this DBH: cooling and heating saved (a winter penalty negative), US dollars"),
                "typical_carbon_usd_per_year": benefit("At typical position: CO2 sequestered and avoided, US dollars"),
                "typical_stormwater_usd_per_year": benefit("At typical position: rain held back, US dollars"),
                "typical_air_quality_usd_per_year": benefit("At typical position: pollutants taken up and not emitted, less BVOCs emitted, US dollars"),
                "typical_aesthetics_usd_per_year": benefit("At typical position: aesthetics and property value (i-Tree's yearly leaf-area gain at the region's price per m², McPherson 2007), US dollars"),
                "typical_benefits_usd_per_year": benefit("At typical position: every benefit, US dollars"),
            }
        }}
    })
}

/// The tile's GLB: its trees (`trees`, each at `at - centre` in the city's frame) at level of
/// detail `lod`, the meshes read from `prefix` + each level's file name. Coarse levels draw
/// every tree as its class's first seed variant (variants differ in detail a coarse level does
/// not show), so a parent tile holds fewer meshes.
pub fn tile_glb(
    trees: &[TileTree],
    centre: DVec3,
    lod: usize,
    prototypes: &HashMap<&ProtoKey, &Prototype>,
    stump: &SharedMesh,
    prefix: &str,
    left_out: &[([f64; 3], String)],
) -> Result<Vec<u8>, sylva::ExportError> {
    // Trees by what they are drawn as, in a stable order; each keeps its row in the table.
    let mut groups: BTreeMap<Option<ProtoKey>, Vec<u32>> = BTreeMap::new();
    for (row, t) in trees.iter().enumerate() {
        let key = match &t.tree.kind {
            Kind::Tree(k) if lod > 0 => Some(k.first_variant()),
            Kind::Tree(k) => Some(k.clone()),
            Kind::Stump => None,
        };
        groups.entry(key).or_default().push(row as u32);
    }
    // What each group draws: its mesh at this level, or at the coarsest its impostor.
    enum Drawn {
        Mesh(SharedMesh),
        Impostor(SharedImpostor),
    }
    // Each file named from the tile's folder.
    let from_tile = |uri: &str| format!("{prefix}{uri}");
    let mesh = |m: &SharedMesh| {
        let mut m = m.clone();
        m.uri = from_tile(&m.uri);
        Drawn::Mesh(m)
    };
    let mut shared: Vec<(String, Drawn, Materials)> = Vec::with_capacity(groups.len());
    for key in groups.keys() {
        shared.push(match key {
            Some(k) => {
                let p = &prototypes[k];
                let drawn = match &p.impostor {
                    Some(imp) if lod == IMPOSTOR_LEVEL => Drawn::Impostor(SharedImpostor {
                        uri: from_tile(&imp.uri),
                        ..imp.clone()
                    }),
                    _ => mesh(&p.lods[lod]),
                };
                (format!("{}-L{lod}", k.file_stem()), drawn, p.materials)
            }
            None => ("stump".to_string(), mesh(stump), stump_materials()),
        });
    }
    let meshes: Vec<InstancedMesh<'_>> = shared
        .iter()
        .map(|(name, drawn, materials)| InstancedMesh {
            name,
            source: match drawn {
                Drawn::Mesh(mesh) => MeshSource::Shared(mesh),
                Drawn::Impostor(imp) => MeshSource::Impostor(imp),
            },
            materials: *materials,
        })
        .collect();
    // Each group's positions, turns and scales: each tree scaled to its height from the
    // height of the tree drawn for it.
    type Placement = (Vec<[f32; 3]>, Vec<f32>, Vec<f32>);
    let placed: Vec<Placement> = groups
        .iter()
        .map(|(key, rows)| {
            let drawn = key.as_ref().map(|k| prototypes[k].height);
            let of = |r: &u32| &trees[*r as usize].tree;
            (
                rows.iter()
                    .map(|r| (of(r).at - centre).as_vec3().to_array())
                    .collect(),
                rows.iter().map(|r| of(r).turn).collect(),
                rows.iter().map(|r| drawn_scale(of(r), drawn)).collect(),
            )
        })
        .collect();
    let groups: Vec<InstancedGroup<'_>> = placed
        .iter()
        .zip(groups.values())
        .enumerate()
        .map(|(k, ((positions, turns, scales), rows))| InstancedGroup {
            mesh: k,
            positions,
            turns,
            scales,
            features: Some(Features { table: 0, rows }),
        })
        .collect();
    let metadata = Metadata {
        schema: schema(),
        tables: vec![table(trees)],
    };
    // The trees it leaves out, as points of their species.
    let mut classes: Vec<String> = left_out.iter().map(|(_, c)| c.clone()).collect();
    classes.sort();
    classes.dedup();
    let class_of: Vec<u16> = left_out
        .iter()
        .map(|(_, c)| classes.binary_search(c).unwrap_or(0) as u16)
        .collect();
    let positions: Vec<[f32; 3]> = left_out
        .iter()
        .map(|(at, _)| (DVec3::from_array(*at) - centre).as_vec3().to_array())
        .collect();
    let points = PointSet {
        name: LEFT_OUT,
        positions: &positions,
        class_of: &class_of,
        classes: &classes,
    };
    instanced_glb(&meshes, &groups, Some(&metadata), Some(&points))
}

/// The rows of a tile's trees, in their order.
fn table(trees: &[TileTree]) -> PropertyTable {
    let text = |f: &dyn Fn(&TileTree) -> String| Column::Text(trees.iter().map(f).collect());
    let number =
        |f: &dyn Fn(&Planned) -> f32| Column::Float32(trees.iter().map(|t| f(&t.tree)).collect());
    let year =
        |f: &dyn Fn(&TreeYear) -> f32| Column::Float32(trees.iter().map(|t| f(&t.year)).collect());
    let key = |t: &TileTree| match &t.tree.kind {
        Kind::Tree(k) => (k.code.clone(), k.region.clone()),
        Kind::Stump => ("stump".into(), String::new()),
    };
    let names = |t: &TileTree| {
        let (code, region) = key(t);
        species_names(&code, &region)
    };
    PropertyTable {
        class: "tree".into(),
        columns: vec![
            ("id".into(), text(&|t| t.id.clone())),
            ("species_written".into(), text(&|t| t.written.clone())),
            ("species".into(), text(&|t| key(t).0)),
            ("common_name".into(), text(&|t| names(t).0)),
            ("scientific_name".into(), text(&|t| names(t).1)),
            ("region".into(), text(&|t| key(t).1)),
            ("condition".into(), text(&|t| t.condition.clone())),
            ("dbh_cm".into(), number(&|t| t.dbh)),
            ("age_years".into(), number(&|t| t.age)),
            ("height_m".into(), number(&|t| t.height)),
            ("crown_diameter_m".into(), number(&|t| t.crown_diameter)),
            ("co2_stored_kg".into(), year(&|y| y.co2_stored_kg)),
            (
                "co2_sequestered_kg_per_year".into(),
                year(&|y| y.co2_sequestered_kg),
            ),
            (
                "rain_intercepted_m3_per_year".into(),
                year(&|y| y.rain_intercepted_m3),
            ),
            ("benefits_usd_per_year".into(), year(&|y| y.benefits_usd)),
            (
                "typical_energy_usd_per_year".into(),
                year(&|y| y.typical_usd[0]),
            ),
            (
                "typical_carbon_usd_per_year".into(),
                year(&|y| y.typical_usd[1]),
            ),
            (
                "typical_stormwater_usd_per_year".into(),
                year(&|y| y.typical_usd[2]),
            ),
            (
                "typical_air_quality_usd_per_year".into(),
                year(&|y| y.typical_usd[3]),
            ),
            (
                "typical_aesthetics_usd_per_year".into(),
                year(&|y| y.typical_usd[4]),
            ),
            (
                "typical_benefits_usd_per_year".into(),
                year(&|y| y.typical_benefits_usd),
            ),
        ],
    }
}

/// Common and scientific names of species `code` in `region` (none for a stump).
fn species_names(code: &str, region: &str) -> (String, String) {
    sylva::growth::Database::builtin()
        .species()
        .iter()
        .find(|s| s.code == code && s.region == region)
        .map_or((String::new(), String::new()), |s| {
            (s.common.clone(), s.scientific.clone())
        })
}

/// A stump's bark: the grey-brown of weathered wood.
fn stump_materials() -> Materials {
    Materials::from_srgb([0.42, 0.36, 0.30], [0.42, 0.36, 0.30])
}

/// Height of a stump over its diameter (Sylva's choice: a stump cut a little above the root
/// flare).
pub const STUMP_HEIGHT: f32 = 0.8;

/// A stump one metre across (scaled by each stump's DBH in metres): a closed cylinder of 16
/// sides, `STUMP_HEIGHT` tall.
pub fn stump_mesh() -> sylva::mesh::TreeMesh {
    let mut m = sylva::mesh::Mesh::default();
    let sides = 16u32;
    for k in 0..=sides {
        let a = k as f32 / sides as f32 * std::f32::consts::TAU;
        let (s, c) = a.sin_cos();
        for (z, v) in [(0.0, 0.0), (STUMP_HEIGHT, 1.0)] {
            m.positions.push([0.5 * c, 0.5 * s, z]);
            m.normals.push([c, s, 0.0]);
            m.uvs.push([k as f32 / sides as f32, v]);
        }
    }
    for k in 0..sides {
        let (a, b) = (2 * k, 2 * k + 2);
        m.indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
    }
    // The cut face.
    let centre = m.positions.len() as u32;
    m.positions.push([0.0, 0.0, STUMP_HEIGHT]);
    m.normals.push([0.0, 0.0, 1.0]);
    m.uvs.push([0.5, 0.5]);
    for k in 0..sides {
        let a = k as f32 / sides as f32 * std::f32::consts::TAU;
        let (s, c) = a.sin_cos();
        m.positions.push([0.5 * c, 0.5 * s, STUMP_HEIGHT]);
        m.normals.push([0.0, 0.0, 1.0]);
        m.uvs.push([0.5 + 0.5 * c, 0.5 + 0.5 * s]);
    }
    for k in 0..sides {
        let (a, b) = (centre + 1 + k, centre + 1 + (k + 1) % sides);
        m.indices.extend_from_slice(&[centre, a, b]);
    }
    sylva::mesh::TreeMesh {
        bark: m,
        ..Default::default()
    }
}
