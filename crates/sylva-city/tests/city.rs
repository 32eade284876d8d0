//! A demo city through `sylva city`'s library: every form and layout gives the same trees,
//! every row is accounted for, and the tiles pass the structural checks.

use std::collections::HashMap;
use std::path::Path;
use sylva_city::demo::{DemoCity, DemoLayout, demo_city};
use sylva_city::inventory::{self, Layout};
use sylva_city::tiles::check::check_tileset;
use sylva_city::trees::plan::{CityOptions, Kind, Plan, plan};
use sylva_city::{Quiet, tile_city};

/// A tree as each form gives it: place, species, DBH, age, height and condition.
type Seen = (
    glam::DVec3,
    String,
    f32,
    f32,
    f32,
    Option<inventory::Condition>,
);

fn planned(path: &Path, layout: &Layout) -> Plan {
    let inv = inventory::load(path, None, layout).unwrap();
    plan(&inv, &CityOptions::default()).unwrap()
}

fn city(n: usize) -> DemoCity {
    demo_city("PacfNW", n, 3, 2026).unwrap()
}

#[test]
fn every_form_and_layout_gives_the_same_trees() {
    let c = city(1000);
    let dir = tempfile::tempdir().unwrap();
    let files = [
        ("census.csv", DemoLayout::Census, None),
        ("gis.csv", DemoLayout::Gis, Some(c.epsg)),
        ("census.geojson", DemoLayout::Census, None),
        ("gis.gpkg", DemoLayout::Gis, None),
    ];
    let mut plans = Vec::new();
    for (name, layout, crs) in files {
        let path = dir.path().join(name);
        c.write(&path, layout).unwrap();
        let l = Layout {
            crs,
            ..Default::default()
        };
        plans.push((
            name,
            planned(&path, &l),
            inventory::load(&path, None, &l).unwrap(),
        ));
    }
    let (_, first, first_inv) = &plans[0];
    // Every row counted, by what became of it.
    let s = &first.summary;
    let skipped: usize = s.skipped.values().sum();
    assert_eq!(s.rows, 1000);
    assert_eq!(
        s.trees + s.stumps + skipped + s.rejected.len(),
        1000,
        "{s:?}"
    );
    assert!(
        s.rejected.len() >= 5,
        "the demo's broken rows: {:?}",
        s.rejected
    );
    assert!(
        s.skipped.keys().any(|k| k.contains("dead")),
        "{:?}",
        s.skipped
    );
    assert!(
        s.skipped.keys().any(|k| k.contains("sites")),
        "{:?}",
        s.skipped
    );
    let ids = |inv: &inventory::Inventory, p: &Plan| -> HashMap<String, Seen> {
        p.epochs[0]
            .trees
            .iter()
            .map(|t| {
                let code = match &t.kind {
                    // The age class is left out: DBH rounded to inches or to cm can put an age
                    // on either side of a class boundary; the ages are compared below.
                    Kind::Tree(k) => format!("{} {}", k.code, k.region),
                    Kind::Stump => "stump".into(),
                };
                (
                    inv.trees[t.row].id.clone(),
                    (
                        t.at,
                        code,
                        t.dbh,
                        t.age,
                        t.height,
                        inv.trees[t.row].observed.condition,
                    ),
                )
            })
            .collect()
    };
    let reference = ids(first_inv, first);
    assert!(reference.len() > 950, "{}", reference.len());
    for (name, p, inv) in &plans[1..] {
        assert_eq!(p.summary.rejected.len(), s.rejected.len(), "{name}");
        assert_eq!(p.summary.skipped, s.skipped, "{name}");
        assert_eq!(p.summary.trees, s.trees, "{name}");
        let other = ids(inv, p);
        assert_eq!(other.len(), reference.len(), "{name}");
        for (id, (at, code, dbh, age, height, condition)) in &reference {
            let (at2, code2, dbh2, age2, height2, condition2) = &other[id];
            // The census's Good, Fair, Poor and the GIS export's finer classes read alike.
            assert_eq!(condition, condition2, "{name} {id}");
            assert!(
                condition.is_some(),
                "{name} {id}: the demo's living trees have one"
            );
            // Positions through UTM and back agree within centimetres of the census's
            // degrees (8 decimals: a millimetre); GeoPackage and GeoJSON hold the same.
            assert!(at.distance(*at2) < 0.05, "{name} {id}: {at} vs {at2}");
            assert_eq!(code, code2, "{name} {id}");
            // DBH written as inches with 2 decimals, or cm with 1.
            assert!((dbh - dbh2).abs() < 0.1, "{name} {id}: {dbh} vs {dbh2}");
            // Ages from DBHs that differ by that rounding: old trees add little DBH a year.
            assert!((age - age2).abs() < 0.5, "{name} {id}: {age} vs {age2}");
            assert!(
                (height / height2 - 1.0).abs() < 0.01,
                "{name} {id}: {height} vs {height2}"
            );
        }
    }
}

#[test]
fn units_circumference_and_broken_rows_are_read_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("trees.csv");
    std::fs::write(
        &path,
        "id,species,circumference_cm,lat,lon,status\n\
         a,Platanus x acerifolia,94.25,37.64,-120.99,Alive\n\
         b,PLAC,not a number,37.64,-120.99,Alive\n\
         c,PLAC,50,95.0,-120.99,Alive\n\
         d,PLAC,50,0,0,Alive\n\
         e,,,37.64,-120.99,Stump\n\
         f,\"Acer rubrum,37.64\n",
    )
    .unwrap();
    let inv = inventory::load(&path, None, &Layout::default()).unwrap();
    // 94.25 cm around is 30 cm across.
    assert_eq!(inv.trees.len(), 2, "{inv:?}");
    assert!((inv.trees[0].dbh.unwrap() - 30.0).abs() < 0.01);
    let lines: Vec<usize> = inv.rejected.iter().map(|r| r.line).collect();
    assert_eq!(lines, [3, 4, 5, 7], "{:?}", inv.rejected);
    assert!(
        inv.rejected[0].reason.contains("circumference_cm")
            && inv.rejected[0].reason.contains("not a number")
    );
    assert!(inv.rejected[1].reason.contains("latitude"));
    // Inches by default; cm when asked.
    let path = dir.path().join("inches.csv");
    std::fs::write(&path, "id,species,dbh,lat,lon\na,PLAC,10,37.64,-120.99\n").unwrap();
    let inv = inventory::load(&path, None, &Layout::default()).unwrap();
    assert!((inv.trees[0].dbh.unwrap() - 25.4).abs() < 1e-9);
    let cm = Layout {
        dbh_unit: Some(sylva_city::LengthUnit::Cm),
        ..Default::default()
    };
    let inv = inventory::load(&path, None, &cm).unwrap();
    assert!((inv.trees[0].dbh.unwrap() - 10.0).abs() < 1e-9);
    // Projected columns without a system: the flag to give is named.
    let path = dir.path().join("xy.csv");
    std::fs::write(&path, "id,species,dbh,x,y\na,PLAC,10,500000,4100000\n").unwrap();
    let e = inventory::load(&path, None, &Layout::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("--crs"), "{e}");
    let e = inventory::load(&dir.path().join("trees.shp"), None, &Layout::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains(".shp") && e.contains(".gpkg"), "{e}");
}

/// Where the structural test below leaves its tiles when it is set: CI's glTF validator and
/// its CesiumJS test check those very tiles, so CI grows the 1,000-tree city once, not twice
/// (some 70 s on two cores). The folder must be absent or empty.
const KEEP_TILES: &str = "SYLVA_TEST_CITY_TILES";

#[test]
fn a_demo_city_tiles_and_passes_the_structural_checks() {
    let c = city(1000);
    let dir = tempfile::tempdir().unwrap();
    // A GeoPackage, every status in it: the form a city's GIS team exports, through the whole
    // pipeline (the other forms give the same trees: the test above).
    let inventory = dir.path().join("city.gpkg");
    c.write(&inventory, DemoLayout::Gis).unwrap();
    let out = std::env::var_os(KEEP_TILES).map_or_else(|| dir.path().join("tiles"), Into::into);
    let options = CityOptions {
        variants: 1,
        stumps: true,
        cache: Some((dir.path().join("cache"), 512)),
        report: true,
        dxf: true,
        ..Default::default()
    };
    let run = tile_city(&inventory, None, &Layout::default(), &options, &out, &Quiet).unwrap();
    assert_eq!(run.from_cache, 0, "an empty cache");
    // A second run takes every grown tree from the cache, and writes the same bytes.
    let again = dir.path().join("again");
    let second = tile_city(
        &inventory,
        None,
        &Layout::default(),
        &options,
        &again,
        &Quiet,
    )
    .unwrap();
    assert!(
        second.growths > 0 && second.from_cache == second.growths,
        "{} of {}",
        second.from_cache,
        second.growths
    );
    let files = |root: &std::path::Path| {
        let mut all = Vec::new();
        let mut stack = vec![root.to_path_buf()];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).unwrap().flatten() {
                if e.path().is_dir() {
                    stack.push(e.path());
                } else if e.file_name() != "summary.json" {
                    let rel = e.path().strip_prefix(root).unwrap().to_path_buf();
                    all.push((rel, std::fs::read(e.path()).unwrap()));
                }
            }
        }
        all.sort();
        all
    };
    assert!(
        files(&out) == files(&again),
        "the cached run's tiles differ"
    );
    let checked = check_tileset(&out).unwrap_or_else(|p| panic!("{}", p.join("\n")));
    let drawn = run.summary.trees + run.summary.stumps - run.epochs[0].3;
    assert_eq!(
        checked.root_instances,
        drawn.min(sylva_city::tiles::COARSE_TREES)
    );
    assert_eq!(checked.leaf_instances, drawn);
    // The trees the root leaves out of its meshes are its points: each tree is in it once
    // (a unit test holds a root that leaves trees out: `tiles::tests`).
    assert_eq!(checked.root_instances + checked.root_points, drawn);
    // The report counts every standing tree the tiles hold (the stumps aside), by species,
    // DBH class and genus, and its shares and importance values add up.
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let trees = report["trees"].as_u64().unwrap() as usize;
    assert_eq!(trees + run.summary.stumps, drawn);
    assert_eq!(
        report["epochs"][0]["trees"].as_u64().unwrap() as usize,
        trees
    );
    let species = report["species"].as_array().unwrap();
    let sum = |f: &dyn Fn(&serde_json::Value) -> f64| species.iter().map(f).sum::<f64>();
    assert_eq!(sum(&|s| s["trees"].as_f64().unwrap()) as usize, trees);
    assert!((sum(&|s| s["share"].as_f64().unwrap()) - 1.0).abs() < 1e-9);
    assert!((sum(&|s| s["importance"].as_f64().unwrap()) - 200.0).abs() < 1e-6);
    let counted = |s: &serde_json::Value, classes: &str| -> u64 {
        s[classes]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_u64().unwrap())
            .sum()
    };
    for s in species {
        assert_eq!(
            counted(s, "dbh_classes"),
            s["trees"].as_u64().unwrap(),
            "{s}"
        );
        let ages = counted(s, "age_classes");
        assert_eq!(ages, s["trees"].as_u64().unwrap(), "{s}");
        let mean = s["mean_age_years"].as_f64().unwrap();
        assert!(mean > 0.0 && mean < 150.0, "{s}");
        assert!(s["at_oldest_measured"].as_u64().unwrap() <= ages, "{s}");
    }
    let genera: u64 = report["genera"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g[1].as_u64().unwrap())
        .sum();
    assert_eq!(genera as usize, trees);
    // Every genus of the database has its family (APG IV), so none is unknown.
    let families = report["families"].as_array().unwrap();
    let in_families: u64 = families.iter().map(|f| f[1].as_u64().unwrap()).sum();
    assert_eq!(in_families as usize, trees);
    assert!(families.iter().all(|f| f[0] != "unknown"), "{families:?}");
    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    assert_eq!(csv.lines().count(), species.len() + 1);
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("Not computed") && html.contains("replacement value"));
    assert!(html.contains("relative age as i-Tree Streets shows it"));
    // The GeoPackage's CONDITION (i-Tree's finer classes) read for every living tree: each
    // species' condition adds up to its trees, and its RPI is its share in good condition
    // over the city's.
    let seen = &report["observed"];
    let all: Vec<u64> = (seen["good_fair_poor"].as_array().unwrap().iter())
        .map(|n| n.as_u64().unwrap())
        .collect();
    assert_eq!(all.iter().sum::<u64>() as usize, trees);
    assert_eq!(seen["not_recorded"], 0);
    let city_good = all[0] as f64 / trees as f64;
    for c in seen["condition"].as_array().unwrap() {
        let n: Vec<u64> = (c["good_fair_poor"].as_array().unwrap().iter())
            .map(|n| n.as_u64().unwrap())
            .collect();
        let of = species.iter().find(|s| s["code"] == c["code"]).unwrap();
        assert_eq!(n.iter().sum::<u64>(), of["trees"].as_u64().unwrap(), "{c}");
        let rpi = n[0] as f64 / n.iter().sum::<u64>() as f64 / city_good;
        assert!((c["rpi"].as_f64().unwrap() - rpi).abs() < 1e-12, "{c}");
    }
    // A GIS export records no problems; the census layout does (`inventory::observed`).
    assert!(seen["problems"].as_array().unwrap().is_empty());
    assert!(html.contains("relative performance index") && html.contains("Condition and"));
    assert!(
        csv.lines()
            .next()
            .unwrap()
            .ends_with("condition_not_recorded,rpi")
    );
    assert!(checked.tiles > 4, "{checked:?}");
    planting_plan_places_every_tree(&out.join("planting-plan.dxf"), &inventory, drawn);
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["rows"], 1000);
    // Every shared mesh a tile names is there.
    let glb = std::fs::read(out.join("content/0/0-0.glb")).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    for b in doc["buffers"].as_array().unwrap().iter().skip(1) {
        let uri = b["uri"].as_str().unwrap();
        let file = out.join("content/0").join(uri);
        assert_eq!(
            std::fs::metadata(&file).unwrap().len(),
            b["byteLength"].as_u64().unwrap()
        );
    }
    // The root, the coarsest level, draws each tree as its grown tree's impostor (16
    // triangles, its atlas unlit and alpha-masked), every one from the city's one picture
    // through one material; the leaf tiles keep the meshes.
    let meshes = doc["meshes"].as_array().unwrap();
    let materials = doc["materials"].as_array().unwrap();
    let textured = |m: &serde_json::Value| {
        let material = &materials[m["primitives"][0]["material"].as_u64().unwrap() as usize];
        !material["pbrMetallicRoughness"]["baseColorTexture"].is_null()
            && material["alphaMode"] == "MASK"
            && material["extensions"]["KHR_materials_unlit"].is_object()
    };
    let trees = meshes.iter().filter(|m| m["name"] != "stump").count();
    assert!(trees > 0);
    assert_eq!(meshes.iter().filter(|m| textured(m)).count(), trees);
    let images = doc["images"].as_array().unwrap();
    assert_eq!(images.len(), 1, "one picture: {images:?}");
    let uri = images[0]["uri"].as_str().unwrap();
    assert!(uri.ends_with("prototypes/impostors-0.png"), "{uri}");
    let atlas = std::fs::read(out.join("content/0").join(uri)).unwrap();
    assert!(atlas.starts_with(b"\x89PNG"));
    let texture = |m: &&serde_json::Value| !m["pbrMetallicRoughness"]["baseColorTexture"].is_null();
    assert_eq!(materials.iter().filter(texture).count(), 1);
    let depth = run.epochs[0].2.depth;
    let leaf = std::fs::read_dir(out.join(format!("content/{depth}")))
        .unwrap()
        .flatten()
        .next()
        .unwrap()
        .path();
    let glb = std::fs::read(leaf).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    assert!(doc["images"].is_null(), "a leaf tile draws meshes");
    // A folder holding other files is refused and left as it was.
    let other = dir.path().join("mine");
    std::fs::create_dir(&other).unwrap();
    std::fs::write(other.join("notes.txt"), "keep").unwrap();
    let e = tile_city(
        &inventory,
        None,
        &Layout::default(),
        &options,
        &other,
        &Quiet,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("-o") && e.contains("notes.txt"), "{e}");
    assert_eq!(
        std::fs::read_to_string(other.join("notes.txt")).unwrap(),
        "keep"
    );
}

#[test]
fn epochs_age_every_tree_and_plant_the_planned_ones() {
    let c = city(1000);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("city.csv");
    c.write(&path, DemoLayout::Census).unwrap();
    let inv = inventory::load(&path, None, &Layout::default()).unwrap();
    let options = CityOptions {
        years: vec![0, 10],
        ..Default::default()
    };
    let p = plan(&inv, &options).unwrap();
    let (now, later) = (&p.epochs[0], &p.epochs[1]);
    // The demo plans plantings one to nine years on: absent now, in the ground in ten years.
    assert!(now.not_yet_planted > 0, "{}", now.not_yet_planted);
    assert_eq!(later.not_yet_planted, 0);
    assert_eq!(later.trees.len(), now.trees.len() + now.not_yet_planted);
    let by_row: HashMap<usize, &sylva_city::trees::plan::Planned> =
        later.trees.iter().map(|t| (t.row, t)).collect();
    for t in &now.trees {
        let Kind::Tree(k) = &t.kind else { continue };
        let m = &p.measured[&(k.region.clone(), k.code.clone())];
        let l = by_row[&t.row];
        // Ten years older, unless the data end first; never smaller.
        let want = (t.age as f64 + 10.0).min(m.ages.1);
        assert!((l.age as f64 - want).abs() < 1e-3, "{} -> {}", t.age, l.age);
        assert!(
            l.dbh >= t.dbh && l.height >= t.height * 0.999,
            "{t:?} {l:?}"
        );
    }
}

/// The planting plan (`--dxf`) holds an INSERT for every tree and stump drawn, each at its
/// row's own coordinates (the GeoPackage's UTM metres), on its species' layer, its crown
/// some centimetres to 25 m from its trunk once scaled (a plan symbol's width against the
/// grown tree's is `sylva::drawing::cad`'s test).
fn planting_plan_places_every_tree(path: &Path, inventory: &Path, drawn: usize) {
    use dxf::entities::EntityType;
    let drawing = dxf::Drawing::load_file(path).unwrap();
    assert_eq!(
        drawing.header.default_drawing_units,
        dxf::enums::Units::Meters
    );
    let inv = inventory::load(inventory, None, &Layout::default()).unwrap();
    let places: Vec<(f64, f64)> = (inv.trees.iter())
        .filter_map(|t| match t.position {
            inventory::Position::Projected(x, y) => Some((x, y)),
            _ => None,
        })
        .collect();
    let blocks: HashMap<String, f64> = (drawing.blocks())
        .map(|b| {
            let reach = (b.entities.iter())
                .filter_map(|e| match &e.specific {
                    EntityType::LwPolyline(p) => {
                        p.vertices.iter().map(|v| v.x.hypot(v.y)).reduce(f64::max)
                    }
                    EntityType::Circle(c) => Some(c.radius),
                    _ => None,
                })
                .fold(0.0, f64::max);
            (b.name.clone(), reach)
        })
        .collect();
    let mut inserts = 0;
    for e in drawing.entities() {
        let EntityType::Insert(i) = &e.specific else {
            continue;
        };
        inserts += 1;
        let at = (i.location.x, i.location.y);
        assert!(
            places
                .iter()
                .any(|p| (p.0 - at.0).abs() < 1e-3 && (p.1 - at.1).abs() < 1e-3),
            "{} at {at:?} is no row's place",
            i.name
        );
        if i.name == "STUMP" {
            assert_eq!(e.common.layer, "STUMPS");
            continue;
        }
        // PSME-PacfNW-30-0 on `TREE-PSME Pseudotsuga menziesii`.
        let code = i.name.split('-').next().unwrap();
        assert!(
            e.common.layer.starts_with(&format!("TREE-{code} ")),
            "{} on {}",
            i.name,
            e.common.layer
        );
        let reach = blocks[&i.name] * i.x_scale_factor;
        assert!(
            reach > 0.05 && reach < 25.0,
            "{}: crown reach {reach} m",
            i.name
        );
    }
    assert_eq!(inserts, drawn);
}

/// A census-layout inventory with the NYC 2015 census's observation columns (Sylva's own test
/// rows, `tests/data/census-observed.csv`): condition by species with each species' RPI,
/// counted by hand, the problems by species, and the values Sylva could not place listed.
#[test]
fn a_census_inventorys_condition_and_problems_reach_the_report() {
    use sylva_city::report::observed::observations;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/census-observed.csv");
    let inv = inventory::load(&path, None, &Layout::default()).unwrap();
    assert_eq!(inv.trees.len(), 13);
    let p = plan(&inv, &CityOptions::default()).unwrap();
    let o = observations(&p);
    // Living trees: London plane 2 good, 1 fair, 1 poor; honeylocust 3 good, 1 fair; Callery
    // pear 1 good, 1 poor and one "Splendid", not recorded. The city: 6 good of 10 (60%).
    assert_eq!(o.good_fair_poor, [6, 2, 2]);
    assert_eq!(o.not_recorded, 1);
    let row = |code: &str| o.condition.iter().find(|c| c.code == code).unwrap();
    // By hand: plane 2/4 = 50%, over 60%: 0.833; honeylocust 3/4 = 75%: 1.25; pear 1/2: 0.833.
    assert_eq!(row("PLAC").good_fair_poor, [2, 1, 1]);
    assert!((row("PLAC").rpi.unwrap() - 0.5 / 0.6).abs() < 1e-12);
    let honeylocust = o
        .condition
        .iter()
        .find(|c| c.good_fair_poor == [3, 1, 0])
        .unwrap();
    assert!((honeylocust.rpi.unwrap() - 1.25).abs() < 1e-12);
    let pear = o.condition.iter().find(|c| c.not_recorded == 1).unwrap();
    assert!((pear.rpi.unwrap() - 0.5 / 0.6).abs() < 1e-12);
    // The values it could not place, each named with its column.
    assert_eq!(
        o.unread,
        vec![
            ("health".to_string(), "Splendid".to_string(), 1),
            ("sidewalk".to_string(), "maybe".to_string(), 1)
        ]
    );
    // The plane's sidewalk damage: 2 of its 4; lights in the branches: 1; wire on the trunk: 1.
    let plane: Vec<_> = o.problems.iter().filter(|r| r.code == "PLAC").collect();
    let sum = |f: &dyn Fn(&sylva_city::report::observed::ProblemRow) -> (usize, usize)| {
        plane.iter().fold((0, 0), |a, r| {
            let (n, w) = f(r);
            (a.0 + n, a.1 + w)
        })
    };
    assert_eq!(
        sum(&|r| (r.sidewalk_damage.recorded, r.sidewalk_damage.with)),
        (4, 2)
    );
    assert_eq!(
        sum(&|r| (r.branch_lights.recorded, r.branch_lights.with)),
        (4, 1)
    );
    assert_eq!(
        sum(&|r| (r.trunk_wire_or_lights.recorded, r.trunk_wire_or_lights.with)),
        (4, 1)
    );
}

/// A condition column of numbers (a score, not classes) is refused naming the file and the
/// column, before anything is planned.
#[test]
fn a_condition_column_of_numbers_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scored.csv");
    std::fs::write(
        &path,
        "tree_id,spc_latin,tree_dbh,latitude,longitude,condition\n\
         1,Platanus x acerifolia,14,40.7231,-73.8442,80\n\
         2,Platanus x acerifolia,12,40.7232,-73.8441,65\n",
    )
    .unwrap();
    let e = inventory::load(&path, None, &Layout::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("scored.csv") && e.contains("`condition`") && e.contains("--condition-col"),
        "{e}"
    );
    // A column named by a flag that the file does not have is refused, not read as empty.
    let named = Layout {
        observed: inventory::ObservedColumns {
            condition: Some("COND".into()),
            ..Default::default()
        },
        ..Default::default()
    };
    let e = inventory::load(&path, None, &named)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--condition-col COND: no such column"), "{e}");
}

/// Sylva's roots model beside the sidewalk damage a real census recorded: New York's 2015
/// Street Tree Census, a random sample of 3,000 of its trees (tests/data, its original
/// columns), planned as `sylva city` plans it (no growth needed). The sample's trees are
/// among the census's 652,172 the model's size and place were fitted to (0.5% of them), its
/// species' shifts fitted to other trees of the census.
#[test]
fn the_roots_model_matches_a_real_census_s_recorded_sidewalk_damage() {
    use sylva_city::report::pavement::pavement;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/nyc-2015-random-3000.csv");
    let inv = inventory::load(&path, None, &Layout::default()).unwrap();
    let p = plan(
        &inv,
        &CityOptions {
            region: Some("NoEast".into()),
            ..Default::default()
        },
    )
    .unwrap();
    let pv = pavement(&p).expect("the census records sidewalk damage");
    let show = |c: &sylva_city::report::pavement::Class| {
        format!(
            "{}: {} trees, recorded {:.3}, model {:.3} (se {:.3})",
            c.class, c.trees, c.observed, c.predicted, c.error
        )
    };
    // Every living tree's sidewalk recorded, 29% damaged; the model within 3 points.
    assert!(pv.all.trees > 2800, "{}", show(&pv.all));
    assert!((pv.all.observed - 0.29).abs() < 0.02, "{}", show(&pv.all));
    assert!(pv.all.difference().abs() < 0.03, "{}", show(&pv.all));
    // By place and by DBH class, every class within 10 points or its own sampling error.
    for c in pv.by_place.iter().chain(&pv.by_dbh) {
        assert!(
            c.difference().abs() <= 0.10 || c.sampling().is_some(),
            "{}",
            show(c)
        );
    }
    // Trees offset from the curb are recorded damaged at about half the rate of those along
    // it, and the model says so.
    let place = |name: &str| pv.by_place.iter().find(|c| c.class == name).unwrap();
    let (along, offset) = (place("along the curb"), place("offset from the curb"));
    assert!(offset.observed < 0.6 * along.observed && offset.predicted < 0.6 * along.predicted);
    // Damage rises with the trunk, recorded and modelled.
    let first = &pv.by_dbh[0];
    let big = pv
        .by_dbh
        .iter()
        .find(|c| c.class.starts_with("45.7"))
        .unwrap();
    assert!(big.observed > first.observed + 0.15 && big.predicted > first.predicted + 0.15);
    // The species with most trees: each within 10 points or its sampling error, and read by
    // its own rooting habit.
    assert!(pv.by_species.len() >= 10);
    for (c, habit) in &pv.by_species {
        assert!(
            c.difference().abs() <= 0.10 || c.sampling().is_some(),
            "{} ({habit})",
            show(c)
        );
    }
    assert!(pv.by_species.iter().filter(|(_, h)| h == "species").count() >= 8);
}
