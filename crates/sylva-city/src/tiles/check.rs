//! Structural checks of a written tileset, since the official 3D Tiles validator cannot be
//! installed here (the Khronos glTF validator checks each GLB as glTF): every tile's bounding
//! box holds its children's and its own trees, geometric errors fall from parent to child,
//! content files exist and are GLB, the extensions each uses are declared, every instanced
//! node's attributes agree in count and type, and every property table is consistent with its
//! schema, its feature ids and its buffers.

use glam::{DMat4, DVec3};
use serde_json::Value;
use std::path::Path;

/// What a tileset holds, found while checking it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Checked {
    /// Tiles.
    pub tiles: usize,
    /// Instances in the leaf tiles (each tree once).
    pub leaf_instances: usize,
    /// Instances in the root tile (coarsest: every tree, or the tallest
    /// [`super::COARSE_TREES`]).
    pub root_instances: usize,
    /// The root's points: the trees it leaves out of its meshes.
    pub root_points: usize,
    /// Property table rows read.
    pub rows: usize,
}

/// Checks the tileset at `dir/tileset.json`; every problem found is listed.
pub fn check_tileset(dir: &Path) -> Result<Checked, Vec<String>> {
    let mut problems = Vec::new();
    let mut out = Checked::default();
    let text = match std::fs::read(dir.join("tileset.json")) {
        Ok(t) => t,
        Err(e) => return Err(vec![format!("tileset.json: {e}")]),
    };
    let tileset: Value = match serde_json::from_slice(&text) {
        Ok(v) => v,
        Err(e) => return Err(vec![format!("tileset.json: {e}")]),
    };
    if tileset["asset"]["version"] != "1.1" {
        problems.push("asset.version is not 1.1".into());
    }
    let root = &tileset["root"];
    if !matches!(root["refine"].as_str(), Some("REPLACE" | "ADD")) {
        problems.push("the root has no refine".into());
    }
    if tileset["geometricError"].as_f64() < root["geometricError"].as_f64() {
        problems.push("the tileset's geometric error is below its root's".into());
    }
    walk(dir, root, None, "root", &mut out, &mut problems);
    // The leaves draw every tree once; a coarse tile draws some of them (its tallest).
    if out.root_instances > out.leaf_instances || out.root_instances == 0 {
        problems.push(format!(
            "the leaves draw {} trees, the root {}",
            out.leaf_instances, out.root_instances
        ));
    }
    if problems.is_empty() {
        Ok(out)
    } else {
        Err(problems)
    }
}

/// A tile's box in its parent's frame: centre and half-axes.
type Bx = (DVec3, [DVec3; 3]);

fn box_of(tile: &Value) -> Option<Bx> {
    let b: Vec<f64> = tile["boundingVolume"]["box"]
        .as_array()?
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    (b.len() == 12).then(|| {
        let v = |i: usize| DVec3::new(b[i], b[i + 1], b[i + 2]);
        (v(0), [v(3), v(6), v(9)])
    })
}

/// Whether `p` lies in box `b` (within `slack` metres).
fn inside(b: &Bx, p: DVec3, slack: f64) -> bool {
    let d = p - b.0;
    b.1.iter().all(|axis| {
        let l2 = axis.length_squared();
        l2 > 0.0 && (d.dot(*axis) / l2.sqrt()).abs() <= l2.sqrt() + slack
    })
}

fn corners(b: &Bx) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(8);
    for i in 0..8 {
        let s = |k: usize| if i >> k & 1 == 1 { 1.0 } else { -1.0 };
        out.push(b.0 + b.1[0] * s(0) + b.1[1] * s(1) + b.1[2] * s(2));
    }
    out
}

/// Checks `tile` and its children; `parent` is its parent's box and geometric error.
fn walk(
    dir: &Path,
    tile: &Value,
    parent: Option<(&Bx, f64)>,
    name: &str,
    out: &mut Checked,
    problems: &mut Vec<String>,
) {
    out.tiles += 1;
    let Some(bx) = box_of(tile) else {
        problems.push(format!("{name}: no box of 12 numbers"));
        return;
    };
    let error = tile["geometricError"].as_f64().unwrap_or(-1.0);
    if error < 0.0 {
        problems.push(format!("{name}: no geometric error"));
    }
    // The tile's own transform (the root's places the city on the Earth).
    let own = match tile["transform"].as_array() {
        Some(m) if parent.is_some() => {
            let m: Vec<f64> = m.iter().filter_map(Value::as_f64).collect();
            if m.len() != 16 {
                problems.push(format!("{name}: transform is not 16 numbers"));
                return;
            }
            DMat4::from_cols_array(&m.try_into().unwrap_or([0.0; 16]))
        }
        _ => DMat4::IDENTITY,
    };
    if let Some((pbox, perror)) = parent {
        if error > perror + 1e-9 {
            problems.push(format!(
                "{name}: geometric error {error} above its parent's {perror}"
            ));
        }
        // Its box, in the parent's frame, within the parent's box.
        if corners(&bx)
            .iter()
            .any(|&c| !inside(pbox, own.transform_point3(c), 1e-3))
        {
            problems.push(format!("{name}: its box leaves its parent's"));
        }
    }
    let children = tile["children"].as_array().map_or(&[][..], |c| &c[..]);
    if let Some(uri) = tile["content"]["uri"].as_str() {
        match content(&dir.join(uri), &bx) {
            Ok((instances, rows, points)) => {
                out.rows += rows;
                if parent.is_none() {
                    out.root_instances = instances;
                    out.root_points = points;
                }
                if children.is_empty() {
                    out.leaf_instances += instances;
                }
            }
            Err(e) => problems.extend(e.into_iter().map(|p| format!("{name} ({uri}): {p}"))),
        }
    } else if children.is_empty() {
        problems.push(format!("{name}: a leaf without content"));
    }
    for (k, c) in children.iter().enumerate() {
        walk(
            dir,
            c,
            Some((&bx, error)),
            &format!("{name}/{k}"),
            out,
            problems,
        );
    }
}

/// A GLB's JSON and binary chunks.
fn glb(path: &Path) -> Result<(Value, Vec<u8>), String> {
    let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    let u32_at = |i: usize| -> Option<u32> {
        Some(u32::from_le_bytes(bytes.get(i..i + 4)?.try_into().ok()?))
    };
    if bytes.get(..4) != Some(b"glTF") || u32_at(4) != Some(2) {
        return Err("not a GLB 2.0 file".into());
    }
    if u32_at(8) != Some(bytes.len() as u32) {
        return Err("the header's length is not the file's".into());
    }
    let json_len = u32_at(12).ok_or("no JSON chunk")? as usize;
    let json: Value =
        serde_json::from_slice(bytes.get(20..20 + json_len).ok_or("JSON chunk cut short")?)
            .map_err(|e| format!("JSON chunk: {e}"))?;
    let at = 20 + json_len;
    let bin = match u32_at(at) {
        Some(n) => bytes
            .get(at + 8..at + 8 + n as usize)
            .ok_or("BIN chunk cut short")?
            .to_vec(),
        None => Vec::new(),
    };
    Ok((json, bin))
}

/// Checks a tile's GLB; its instances and table rows.
fn content(path: &Path, bx: &Bx) -> Result<(usize, usize, usize), Vec<String>> {
    let (doc, bin) = glb(path).map_err(|e| vec![e])?;
    let mut problems = Vec::new();
    let list = |k: &str| -> Vec<String> {
        doc[k]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|s| s.as_str().map(String::from))
                    .collect()
            })
            .unwrap_or_default()
    };
    let (used, required) = (list("extensionsUsed"), list("extensionsRequired"));
    for e in [
        "EXT_mesh_gpu_instancing",
        "EXT_instance_features",
        "EXT_structural_metadata",
    ] {
        if !used.iter().any(|u| u == e) {
            problems.push(format!("{e} is not in extensionsUsed"));
        }
    }
    if !required.iter().any(|u| u == "EXT_mesh_gpu_instancing") {
        problems.push("EXT_mesh_gpu_instancing is not required".into());
    }
    if let Some(r) = required.iter().find(|r| !used.contains(r)) {
        problems.push(format!("{r} is required but not used"));
    }
    // Every file of its own that it names (shared meshes, impostors' atlases) is there: a
    // buffer as long as it says, an image a PNG file.
    let beside = path.parent().unwrap_or(Path::new("."));
    for (k, b) in doc["buffers"].as_array().into_iter().flatten().enumerate() {
        let Some(uri) = b["uri"].as_str() else {
            continue;
        };
        let len = std::fs::metadata(beside.join(uri)).map(|m| m.len()).ok();
        if len != b["byteLength"].as_u64() {
            problems.push(format!(
                "buffer {k} ({uri}): {len:?} bytes, not its byteLength"
            ));
        }
    }
    for (k, i) in doc["images"].as_array().into_iter().flatten().enumerate() {
        let Some(uri) = i["uri"].as_str() else {
            continue;
        };
        let head = std::fs::read(beside.join(uri))
            .ok()
            .and_then(|b| b.get(..8).map(<[u8]>::to_vec));
        if head.as_deref() != Some(&b"\x89PNG\r\n\x1a\n"[..]) {
            problems.push(format!("image {k} ({uri}) is not a PNG file there"));
        }
    }
    let accessors = doc["accessors"].as_array().cloned().unwrap_or_default();
    let views = doc["bufferViews"].as_array().cloned().unwrap_or_default();
    let metadata = &doc["extensions"]["EXT_structural_metadata"];
    let tables = metadata["propertyTables"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    // The bytes of a view of the GLB's own buffer.
    let view_bytes = |i: &Value| -> Option<&[u8]> {
        let v = views.get(i.as_u64()? as usize)?;
        if v["buffer"].as_u64()? != 0 {
            return None;
        }
        let at = v["byteOffset"].as_u64().unwrap_or(0) as usize;
        bin.get(at..at + v["byteLength"].as_u64()? as usize)
    };
    let floats = |a: &Value| -> Option<Vec<f32>> {
        let b = view_bytes(&a["bufferView"])?;
        Some(
            b.chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap_or([0; 4])))
                .collect(),
        )
    };
    // Whether a point of the file (glTF's Y up turned back to Z up) lies outside the box.
    let outside = |p: &[f32]| !inside(bx, DVec3::new(p[0] as f64, -p[2] as f64, p[1] as f64), 0.01);
    let mut instances = 0;
    let mut points = 0;
    let mut used_tables = std::collections::BTreeSet::new();
    for (n, node) in doc["nodes"].as_array().into_iter().flatten().enumerate() {
        let ext = &node["extensions"];
        for name in ext.as_object().into_iter().flat_map(|o| o.keys()) {
            if !used.contains(name) {
                problems.push(format!("node {n} uses {name}, not declared"));
            }
        }
        // A coarse tile's points (the trees it leaves out) are drawn once each.
        let primitive =
            &doc["meshes"][node["mesh"].as_u64().unwrap_or(u64::MAX) as usize]["primitives"][0];
        if primitive["mode"] == 0 {
            let at = accessors.get(
                primitive["attributes"]["POSITION"]
                    .as_u64()
                    .unwrap_or(u64::MAX) as usize,
            );
            let Some(p) = at.and_then(&floats) else {
                problems.push(format!("node {n}: points without positions"));
                continue;
            };
            if p.chunks_exact(3).any(outside) {
                problems.push(format!("node {n}: a point stands outside the tile's box"));
            }
            points += p.len() / 3;
            continue;
        }
        let inst = &ext["EXT_mesh_gpu_instancing"]["attributes"];
        let get = |k: &str| accessors.get(inst[k].as_u64().unwrap_or(u64::MAX) as usize);
        let (Some(t), Some(r), Some(s)) = (get("TRANSLATION"), get("ROTATION"), get("SCALE"))
        else {
            problems.push(format!(
                "node {n} is not instanced with TRANSLATION, ROTATION and SCALE"
            ));
            continue;
        };
        let count = t["count"].as_u64().unwrap_or(0) as usize;
        for (a, ty) in [(t, "VEC3"), (r, "VEC4"), (s, "VEC3")] {
            if a["count"].as_u64() != Some(count as u64)
                || a["type"] != ty
                || a["componentType"] != 5126
            {
                problems.push(format!(
                    "node {n}: an instance attribute is not {count} float {ty}"
                ));
            }
        }
        // Every tree stands in the tile's box.
        if floats(t).is_some_and(|p| p.chunks_exact(3).any(outside)) {
            problems.push(format!("node {n}: a tree stands outside the tile's box"));
        }
        instances += count;
        let features = &ext["EXT_instance_features"]["featureIds"][0];
        if features["featureCount"].as_u64() != Some(count as u64) {
            problems.push(format!(
                "node {n}: featureCount is not its {count} instances"
            ));
        }
        let Some(k) = features["propertyTable"].as_u64().map(|k| k as usize) else {
            problems.push(format!("node {n}: no property table"));
            continue;
        };
        let Some(table) = tables.get(k) else {
            problems.push(format!("node {n}: property table {k} is not there"));
            continue;
        };
        used_tables.insert(k);
        let rows = table["count"].as_u64().unwrap_or(0) as f32;
        // Each instance's row: its _FEATURE_ID_<attribute>, a whole number under the rows.
        let id = format!(
            "_FEATURE_ID_{}",
            features["attribute"].as_u64().unwrap_or(0)
        );
        match get(&id)
            .filter(|a| a["count"].as_u64() == Some(count as u64))
            .and_then(floats)
        {
            Some(ids) if ids.len() == count => {
                if let Some(bad) = ids
                    .iter()
                    .find(|&&i| i < 0.0 || i.fract() != 0.0 || i >= rows)
                {
                    problems.push(format!("node {n}: feature id {bad} is no row of table {k}"));
                }
            }
            _ => problems.push(format!("node {n}: no {count} float {id}")),
        }
    }
    let mut rows = 0;
    for &k in &used_tables {
        let table = &tables[k];
        let count = table["count"].as_u64().unwrap_or(0) as usize;
        let class = &metadata["schema"]["classes"][table["class"].as_str().unwrap_or("")];
        for (name, p) in table["properties"].as_object().into_iter().flatten() {
            let def = &class["properties"][name];
            if def.is_null() {
                problems.push(format!("table {k}: property {name} is not in its class"));
                continue;
            }
            let values = view_bytes(&p["values"]);
            match def["type"].as_str() {
                Some("STRING") => match (values, view_bytes(&p["stringOffsets"])) {
                    (Some(v), Some(o)) if o.len() == (count + 1) * 4 => {
                        let off: Vec<u32> = o
                            .chunks_exact(4)
                            .map(|c| u32::from_le_bytes(c.try_into().unwrap_or([0; 4])))
                            .collect();
                        if off.windows(2).any(|w| w[1] < w[0]) || off[count] as usize > v.len() {
                            problems.push(format!(
                                "table {k}: {name}'s string offsets are out of order or range"
                            ));
                        }
                    }
                    _ => {
                        problems.push(format!("table {k}: {name} has no {count}+1 string offsets"))
                    }
                },
                Some("SCALAR") => {
                    let size = match def["componentType"].as_str() {
                        Some("FLOAT32" | "UINT32" | "INT32") => 4,
                        Some("UINT16" | "INT16") => 2,
                        _ => 0,
                    };
                    if values.map(<[u8]>::len) != Some(count * size) {
                        problems.push(format!(
                            "table {k}: {name} is not {count} values of {size} bytes"
                        ));
                    }
                }
                _ => problems.push(format!("table {k}: {name} has a type not checked here")),
            }
        }
        rows += count;
    }
    if rows != instances {
        problems.push(format!("{rows} table rows for {instances} trees"));
    }
    if problems.is_empty() {
        Ok((instances, rows, points))
    } else {
        Err(problems)
    }
}
