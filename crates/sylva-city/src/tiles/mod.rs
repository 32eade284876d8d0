//! A city's trees at one epoch as an OGC 3D Tiles 1.1 tileset: an explicit quadtree of tiles
//! (`tileset.json`), each tile's content a GLB of instanced trees ([`content`]). Leaf tiles
//! draw their trees at the most detailed level; each parent draws every tree below it at a
//! coarser level (REPLACE refinement), and its geometric error is how far that level's
//! surfaces lie from the whole trees'.

pub mod check;
pub mod content;
pub mod quadtree;

use crate::CityError;
use crate::benefits::TreeYear;
use crate::plan::{Kind, Planned, ProtoKey};
use crate::prototypes::Prototype;
use content::Labels;
use glam::{DMat4, DVec3};
use quadtree::Node;
use serde_json::{Value, json};
use std::collections::HashMap;
use std::path::Path;
use sylva::export::SharedMesh;

/// Most trees in a leaf tile (Sylva's choice): some 5 million triangles at 20,000 a tree.
pub const LEAF_TREES: usize = 250;

/// What a tileset came to.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TilesetReport {
    /// Tiles, and tiles with content.
    pub tiles: usize,
    /// Bytes of its tiles' GLB files.
    pub content_bytes: u64,
    /// Depth of its quadtree.
    pub depth: u32,
    /// Trees drawn.
    pub trees: usize,
}

/// Writes `trees` (in the frame whose ECEF transform is `frame`) as a tileset in `dir`:
/// `dir/tileset.json` and `dir/content/<level>/<x>-<y>.glb`, the prototypes' files read from
/// `prototypes_uri` (relative to `dir`). `done` is called with the tiles written so far.
#[allow(clippy::too_many_arguments)]
pub fn write(
    dir: &Path,
    trees: &[Planned],
    years: &[TreeYear],
    frame: [f64; 16],
    prototypes: &HashMap<ProtoKey, Prototype>,
    stump: &SharedMesh,
    prototypes_uri: &str,
    labels: &Labels<'_>,
    done: &(dyn Fn(usize) + Sync),
) -> Result<TilesetReport, CityError> {
    let write_err = |path: &Path, e: &dyn std::fmt::Display| CityError::write(path, e);
    let at: Vec<[f64; 2]> = trees.iter().map(|t| [t.at.x, t.at.y]).collect();
    let root = quadtree::build(&at, LEAF_TREES);
    let mut nodes = Vec::new();
    root.walk(&mut nodes);
    let written = std::sync::atomic::AtomicUsize::new(0);
    use rayon::prelude::*;
    // Every tile's content, written in parallel; its error and box come back for the JSON.
    let tiles: Vec<(Tile, u64)> = nodes
        .par_iter()
        .map(|node| {
            let tile = tile_of(node, trees, prototypes);
            let members: Vec<(&Planned, &TreeYear)> = node
                .trees
                .iter()
                .map(|&i| (&trees[i as usize], &years[i as usize]))
                .collect();
            let path = dir.join(&tile.uri);
            let prefix = format!("../../{prototypes_uri}");
            let glb = content::tile_glb(
                &members,
                tile.centre,
                tile.lod,
                prototypes,
                stump,
                &prefix,
                labels,
            )
            .map_err(|e| write_err(&path, &e))?;
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(|e| write_err(parent, &e))?;
            }
            sylva::export::write_atomically(&path, &glb).map_err(|e| write_err(&path, &e))?;
            done(written.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            Ok((tile, glb.len() as u64))
        })
        .collect::<Result<_, CityError>>()?;
    let content_bytes = tiles.iter().map(|t| t.1).sum();
    let by_node: HashMap<(u32, u32, u32), &Tile> = tiles
        .iter()
        .map(|(t, _)| ((t.level, t.x, t.y), t))
        .collect();
    let mut root_json = tile_json(&root, &by_node, None);
    // The root carries the city's frame: local east-north-up metres to ECEF.
    let root_tile = by_node[&(0, 0, 0)];
    let m = DMat4::from_cols_array(&frame) * DMat4::from_translation(root_tile.centre);
    root_json["transform"] = json!(m.to_cols_array());
    root_json["refine"] = json!("REPLACE");
    let tallest = trees.iter().map(|t| t.height).fold(1.0f32, f32::max);
    let error = root_json["geometricError"]
        .as_f64()
        .unwrap_or(0.0)
        .max(tallest as f64);
    let tileset = json!({
        "asset": {
            "version": "1.1",
            "generator": format!("Sylva {}", env!("CARGO_PKG_VERSION")),
        },
        "geometricError": error,
        "root": root_json,
    });
    let path = dir.join("tileset.json");
    let text = serde_json::to_vec_pretty(&tileset).map_err(|e| write_err(&path, &e))?;
    sylva::export::write_atomically(&path, &text).map_err(|e| write_err(&path, &e))?;
    Ok(TilesetReport {
        tiles: tiles.len(),
        content_bytes,
        depth: root.height(),
        trees: trees.len(),
    })
}

/// A tile's content and how it is placed.
struct Tile {
    level: u32,
    x: u32,
    y: u32,
    uri: String,
    /// Its centre in the city's frame: the middle of its square, at the ground.
    centre: DVec3,
    /// Level of detail it draws its trees at.
    lod: usize,
    /// Geometric error, m, before it is made no smaller than its children's.
    error: f64,
    /// Its box in the city's frame: low and high corners.
    lo: DVec3,
    hi: DVec3,
}

fn tile_of(node: &Node, trees: &[Planned], prototypes: &HashMap<ProtoKey, Prototype>) -> Tile {
    let lod = node.height().min(2) as usize;
    let [w, s, e, n] = node.square;
    let mut error = 0.0f64;
    let mut overhang = 0.0f64;
    let (mut zlo, mut zhi) = (f64::MAX, f64::MIN);
    for &i in &node.trees {
        let t = &trees[i as usize];
        let (top, reach, err) = match &t.kind {
            Kind::Tree(k) => {
                let p = &prototypes[k];
                let reach = (p.crown_diameter * t.scale).max(t.crown_diameter) as f64 / 2.0;
                (
                    (p.height * t.scale) as f64,
                    reach,
                    (p.errors[lod] * t.scale) as f64,
                )
            }
            Kind::Stump => {
                let d = t.dbh as f64 / 100.0;
                (d * content::STUMP_HEIGHT as f64, d / 2.0, 0.0)
            }
        };
        error = error.max(err);
        overhang = overhang.max(reach);
        zlo = zlo.min(t.at.z);
        zhi = zhi.max(t.at.z + top);
    }
    if zlo > zhi {
        (zlo, zhi) = (0.0, 1.0);
    }
    // A margin for the trees' leaves beyond their measured crowns, and rounding.
    let margin = 0.5;
    Tile {
        level: node.level,
        x: node.x,
        y: node.y,
        uri: format!("content/{}/{}-{}.glb", node.level, node.x, node.y),
        centre: DVec3::new((w + e) / 2.0, (s + n) / 2.0, 0.0),
        lod,
        error: if node.children.is_empty() { 0.0 } else { error },
        lo: DVec3::new(w - overhang - margin, s - overhang - margin, zlo - margin),
        hi: DVec3::new(e + overhang + margin, n + overhang + margin, zhi + margin),
    }
}

/// A tile's JSON with its children's; `parent` is the parent's centre (its frame's origin).
fn tile_json(node: &Node, tiles: &HashMap<(u32, u32, u32), &Tile>, parent: Option<DVec3>) -> Value {
    let tile = tiles[&(node.level, node.x, node.y)];
    let children: Vec<Value> = node
        .children
        .iter()
        .map(|c| tile_json(c, tiles, Some(tile.centre)))
        .collect();
    // A parent's error is never smaller than its children's.
    let below = children
        .iter()
        .map(|c| c["geometricError"].as_f64().unwrap_or(0.0))
        .fold(0.0, f64::max);
    let error = tile.error.max(below);
    // The box in the tile's own frame, whose origin is its centre.
    let (c, h) = (
        (tile.lo + tile.hi) / 2.0 - tile.centre,
        (tile.hi - tile.lo) / 2.0,
    );
    let mut out = json!({
        "boundingVolume": { "box": [c.x, c.y, c.z, h.x, 0.0, 0.0, 0.0, h.y, 0.0, 0.0, 0.0, h.z] },
        "geometricError": error,
        "content": { "uri": tile.uri },
    });
    if let Some(p) = parent {
        let d = tile.centre - p;
        out["transform"] = json!(DMat4::from_translation(d).to_cols_array());
    }
    if !children.is_empty() {
        out["children"] = Value::Array(children);
    }
    out
}
