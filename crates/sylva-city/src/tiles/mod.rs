//! A city's trees at one epoch as an OGC 3D Tiles 1.1 tileset: an explicit quadtree of tiles
//! (`tileset.json`), each tile's content a GLB of instanced trees ([`content`]). Leaf tiles
//! draw their trees at the most detailed level; each parent draws every tree below it at a
//! coarser level (REPLACE refinement), and its geometric error is how far that level's
//! surfaces lie from the whole trees'.

pub(crate) mod atlas;
pub mod check;
pub mod content;
pub mod quadtree;

use crate::error::CityError;
use crate::trees::benefits::TreeYear;
use crate::trees::plan::{Kind, Planned, ProtoKey};
use crate::trees::prototypes::Prototype;
use content::TileTree;
use glam::{DMat4, DVec3};
use quadtree::Node;
use serde::{Deserialize, Serialize};
use serde_json::{Value, json};
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use sylva::export::SharedMesh;

/// Most trees in a leaf tile (Sylva's choice): some 2.5 million triangles at the most
/// detailed level's 10,000 a tree.
pub const LEAF_TREES: usize = 250;

/// Most trees a tile above the leaves draws (Sylva's choice): its tallest, so that a city's
/// coarse tiles stay some 400,000 triangles at the coarsest level's 400 a tree however many
/// trees lie below them. Without it the root of a 100,000-tree city drew every tree, 38 million
/// triangles, wherever its error put the camera. A tile that leaves trees out is in error by the
/// tallest of them (a missing tree is wrong by its whole height), so a viewer refines it near
/// the camera; below some 1,000 trees a tile draws them all.
pub const COARSE_TREES: usize = 1000;

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

/// What a tile's table says of a tree beyond its plan: the inventory's id for it, its
/// species as written, and its condition as recorded (`good`, `fair`, `poor`, or empty).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Labels {
    /// The inventory's id.
    pub id: String,
    /// The species as the inventory names it.
    pub written: String,
    /// The condition as recorded.
    pub condition: String,
}

/// One tile's work, whole: everything its content needs, so that any process can make it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TileTask {
    /// The folder of its tileset, relative to the run's output (`""` or `"year-10/"`).
    pub tileset: String,
    /// Depth, and x, y among the tiles of its depth.
    pub level: u32,
    pub x: u32,
    pub y: u32,
    /// Its square on the ground: west, south, east, north, m.
    pub square: [f64; 4],
    /// Levels below it: 0 for a leaf tile.
    pub height: u32,
    /// The trees it draws: every tree below it, or the tallest [`COARSE_TREES`] of them.
    pub trees: Vec<TileTree>,
    /// The tallest tree below it that it does not draw, m (0: it draws them all).
    pub omitted: f64,
    /// The trees below it that it does not draw: where each stands (the city's frame) and
    /// what it is (a species code, or `stump`). The tile holds them as points, so that a
    /// viewer far off shows every tree of a dense city as a dot and its streets with them.
    pub left_out: Vec<([f64; 3], String)>,
    /// The grown trees they are drawn as.
    pub prototypes: Vec<Prototype>,
    /// The stump's mesh.
    pub stump: SharedMesh,
    /// Where the prototypes' files lie, relative to the tileset's folder.
    pub prototypes_uri: String,
}

impl TileTask {
    /// The task of `node`, one of the tiles of `trees` (whose years are `years`, whose labels
    /// `labels` gives by inventory row), in the tileset at `tileset`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        tileset: &str,
        node: &Node,
        trees: &[Planned],
        years: &[TreeYear],
        labels: &dyn Fn(usize) -> Labels,
        prototypes: &HashMap<ProtoKey, Prototype>,
        stump: &SharedMesh,
        prototypes_uri: &str,
    ) -> TileTask {
        let (drawn, omitted) = if node.children.is_empty() {
            (node.trees.clone(), 0.0)
        } else {
            tallest(&node.trees, |i| trees[i as usize].height, COARSE_TREES)
        };
        // `drawn` keeps the order of `node.trees`: the rest, in that order, by one walk.
        let mut kept = drawn.iter().peekable();
        let mut rest: Vec<u32> = node
            .trees
            .iter()
            .copied()
            .filter(|&i| {
                let is_drawn = kept.peek() == Some(&&i);
                if is_drawn {
                    kept.next();
                }
                !is_drawn
            })
            .collect();
        // In an order shuffled by each tree's inventory row, fixed for the city: any first
        // share of them is an even sample over the tile, so a viewer may draw fewer dots than
        // trees where the tile is small on the screen and still show every street.
        rest.sort_by_key(|&i| shuffled(trees[i as usize].row as u64));
        let left_out = rest
            .iter()
            .map(|&i| {
                let t = &trees[i as usize];
                let what = match &t.kind {
                    Kind::Tree(k) => k.code.clone(),
                    Kind::Stump => "stump".to_string(),
                };
                (t.at.to_array(), what)
            })
            .collect();
        let members: Vec<TileTree> = drawn
            .iter()
            .map(|&i| {
                let tree = trees[i as usize].clone();
                let Labels {
                    id,
                    written,
                    condition,
                } = labels(tree.row);
                TileTree {
                    year: years[i as usize],
                    id,
                    written,
                    condition,
                    tree,
                }
            })
            .collect();
        let lod = node.height().min(2) as usize;
        let used: BTreeSet<ProtoKey> = members
            .iter()
            .filter_map(|t| match &t.tree.kind {
                Kind::Tree(k) => Some(k.clone()),
                Kind::Stump => None,
            })
            // Each tree's own grown tree gives its box and error; coarse levels draw each
            // class's first variant (`content::tile_glb`).
            .flat_map(|k| {
                if lod > 0 {
                    vec![k.first_variant(), k]
                } else {
                    vec![k]
                }
            })
            .collect();
        TileTask {
            tileset: tileset.to_string(),
            level: node.level,
            x: node.x,
            y: node.y,
            square: node.square,
            height: node.height(),
            trees: members,
            omitted,
            left_out,
            prototypes: used.iter().map(|k| prototypes[k].clone()).collect(),
            stump: stump.clone(),
            prototypes_uri: prototypes_uri.to_string(),
        }
    }
}

/// A number that depends only on `n`, spread evenly over u64 (splitmix64's finaliser,
/// Steele, Lea & Flood 2014).
fn shuffled(n: u64) -> u64 {
    let mut z = n.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The tallest `most` of `trees` (ties by their place in it), in the order they came in, and
/// the height of the tallest left out (0 when none is).
pub fn tallest(trees: &[u32], height: impl Fn(u32) -> f32, most: usize) -> (Vec<u32>, f64) {
    if trees.len() <= most {
        return (trees.to_vec(), 0.0);
    }
    let mut order: Vec<usize> = (0..trees.len()).collect();
    let h = |k: usize| height(trees[k]);
    order.sort_by(|&a, &b| h(b).total_cmp(&h(a)).then(a.cmp(&b)));
    let omitted = order[most..]
        .iter()
        .map(|&k| h(k) as f64)
        .fold(0.0, f64::max);
    let mut kept = order[..most].to_vec();
    kept.sort_unstable();
    (kept.into_iter().map(|k| trees[k]).collect(), omitted)
}

/// Makes the content of `task`: what the tileset's JSON needs of the tile, and its GLB.
pub fn make_tile(task: &TileTask) -> Result<(Tile, Vec<u8>), CityError> {
    let prototypes: HashMap<&ProtoKey, &Prototype> =
        task.prototypes.iter().map(|p| (&p.key, p)).collect();
    let tile = tile_of(task, &prototypes);
    let prefix = format!("../../{}", task.prototypes_uri);
    let glb = content::tile_glb(
        &task.trees,
        tile.centre,
        tile.lod,
        &prototypes,
        &task.stump,
        &prefix,
        &task.left_out,
    )
    .map_err(|e| CityError::write(Path::new(&format!("{}{}", task.tileset, tile.uri)), e))?;
    Ok((
        Tile {
            content_bytes: glb.len() as u64,
            ..tile
        },
        glb,
    ))
}

/// The tileset's JSON: the tiles of the quadtree `root` (made by [`make_tile`], in any
/// order), placed in the city's frame whose ECEF transform is `frame`, over trees the
/// tallest of which is `tallest` m.
pub fn tileset_json(
    root: &Node,
    tiles: &[Tile],
    frame: [f64; 16],
    tallest: f32,
) -> Result<(Vec<u8>, TilesetReport), CityError> {
    let by_node: HashMap<(u32, u32, u32), &Tile> =
        tiles.iter().map(|t| ((t.level, t.x, t.y), t)).collect();
    let mut nodes = Vec::new();
    root.walk(&mut nodes);
    if let Some(n) = nodes
        .iter()
        .find(|n| !by_node.contains_key(&(n.level, n.x, n.y)))
    {
        return Err(CityError::Growth(format!(
            "tile {}/{}-{} was not made",
            n.level, n.x, n.y
        )));
    }
    let (mut root_json, _, _) = tile_json(root, &by_node, None);
    // The root carries the city's frame: local east-north-up metres to ECEF.
    let root_tile = by_node[&(0, 0, 0)];
    let m = DMat4::from_cols_array(&frame) * DMat4::from_translation(root_tile.centre);
    root_json["transform"] = json!(m.to_cols_array());
    root_json["refine"] = json!("REPLACE");
    let error = root_json["geometricError"]
        .as_f64()
        .unwrap_or(0.0)
        .max(tallest.max(1.0) as f64);
    let tileset = json!({
        "asset": {
            "version": "1.1",
            "generator": format!("Sylva {}", env!("CARGO_PKG_VERSION")),
        },
        "geometricError": error,
        "root": root_json,
    });
    let text = serde_json::to_vec_pretty(&tileset)
        .map_err(|e| CityError::write(Path::new("tileset.json"), e))?;
    let report = TilesetReport {
        tiles: nodes.len(),
        content_bytes: nodes
            .iter()
            .map(|n| by_node[&(n.level, n.x, n.y)].content_bytes)
            .sum(),
        depth: root.height(),
        trees: root.trees.len(),
    };
    Ok((text, report))
}

/// A tile's content and how it is placed: what the tileset's JSON says of it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tile {
    /// The folder of its tileset, relative to the run's output.
    pub tileset: String,
    /// Depth, and x, y among the tiles of its depth.
    pub level: u32,
    pub x: u32,
    pub y: u32,
    /// Its content's path, relative to its tileset's folder.
    pub uri: String,
    /// Its centre in the city's frame: the middle of its square, at the ground.
    pub centre: DVec3,
    /// Level of detail it draws its trees at.
    pub lod: usize,
    /// Geometric error, m, before it is made no smaller than its children's.
    pub error: f64,
    /// Its box in the city's frame: low and high corners.
    pub lo: DVec3,
    pub hi: DVec3,
    /// Bytes of its GLB.
    pub content_bytes: u64,
}

fn tile_of(task: &TileTask, prototypes: &HashMap<&ProtoKey, &Prototype>) -> Tile {
    let lod = task.height.min(2) as usize;
    let [w, s, e, n] = task.square;
    let mut error = 0.0f64;
    let mut overhang = 0.0f64;
    let (mut zlo, mut zhi) = (f64::MAX, f64::MIN);
    for t in &task.trees {
        let t = &t.tree;
        let (top, reach, err) = match &t.kind {
            Kind::Tree(k) => {
                let p = prototypes[k];
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
        tileset: task.tileset.clone(),
        level: task.level,
        x: task.x,
        y: task.y,
        uri: format!("content/{}/{}-{}.glb", task.level, task.x, task.y),
        centre: DVec3::new((w + e) / 2.0, (s + n) / 2.0, 0.0),
        lod,
        error: if task.height == 0 {
            0.0
        } else {
            error.max(task.omitted)
        },
        lo: DVec3::new(w - overhang - margin, s - overhang - margin, zlo - margin),
        hi: DVec3::new(e + overhang + margin, n + overhang + margin, zhi + margin),
        content_bytes: 0,
    }
}

/// A tile's JSON with its children's, and its box (the least and most corners, in the city's
/// frame); `parent` is the parent's centre (its frame's origin). The box holds its children's
/// too: a coarse tile draws only some of the trees below it.
fn tile_json(
    node: &Node,
    tiles: &HashMap<(u32, u32, u32), &Tile>,
    parent: Option<DVec3>,
) -> (Value, DVec3, DVec3) {
    let tile = tiles[&(node.level, node.x, node.y)];
    let (mut lo, mut hi) = (tile.lo, tile.hi);
    let mut children = Vec::with_capacity(node.children.len());
    for c in &node.children {
        let (json, clo, chi) = tile_json(c, tiles, Some(tile.centre));
        lo = lo.min(clo);
        hi = hi.max(chi);
        children.push(json);
    }
    // A parent's error is never smaller than its children's.
    let below = children
        .iter()
        .map(|c| c["geometricError"].as_f64().unwrap_or(0.0))
        .fold(0.0, f64::max);
    let error = tile.error.max(below);
    // The box in the tile's own frame, whose origin is its centre.
    let (c, h) = ((lo + hi) / 2.0 - tile.centre, (hi - lo) / 2.0);
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
    (out, lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_coarse_tile_keeps_its_tallest_trees_in_order_and_is_in_error_by_the_rest() {
        let trees = [7, 3, 9, 1, 4];
        let heights = |i: u32| [0.0, 12.0, 0.0, 5.0, 20.0, 0.0, 0.0, 8.0, 0.0, 5.0][i as usize];
        // Tallest three: 4 (20 m), 1 (12 m), 7 (8 m), kept in the order they came in; the
        // tallest left out is 5 m tall (3 and 9, tied).
        assert_eq!(tallest(&trees, heights, 3), (vec![7, 1, 4], 5.0));
        // A tile of no more than `most` draws them all, in error by nothing.
        assert_eq!(tallest(&trees, heights, 5), (trees.to_vec(), 0.0));
    }

    #[test]
    fn a_coarse_tile_holds_the_trees_it_leaves_out_as_points_of_their_kind() {
        // 1,500 stumps on a 150 m square, each 1 cm taller than the one before.
        let n = COARSE_TREES + 500;
        let planned: Vec<Planned> = (0..n)
            .map(|i| Planned {
                row: i,
                at: DVec3::new((i % 40) as f64 * 3.7, (i / 40) as f64 * 3.9, 0.0),
                kind: Kind::Stump,
                turn: 0.0,
                scale: 1.0,
                age: 0.0,
                dbh: 30.0,
                height: 0.5 + 0.01 * i as f32,
                crown_diameter: 0.0,
            })
            .collect();
        let at: Vec<[f64; 2]> = planned.iter().map(|t| [t.at.x, t.at.y]).collect();
        let root = quadtree::build(&at, LEAF_TREES);
        assert!(!root.children.is_empty());
        let years = vec![TreeYear::default(); n];
        let labels = |row: usize| Labels {
            id: format!("T{row}"),
            written: "stump".to_string(),
            condition: String::new(),
        };
        let stump = crate::tasks::stump_file().0;
        let task = TileTask::new(
            "",
            &root,
            &planned,
            &years,
            &labels,
            &HashMap::new(),
            &stump,
            "prototypes/",
        );
        // It draws the tallest 1,000 and holds the other 500 as points, where they stand.
        assert_eq!(task.trees.len(), COARSE_TREES);
        assert_eq!(task.left_out.len(), 500);
        for (at, what) in &task.left_out {
            let i = planned.iter().position(|t| t.at.to_array() == *at).unwrap();
            assert!(i < 500, "tree {i} is among the tallest");
            assert_eq!(what, "stump");
        }
        let (tile, glb) = make_tile(&task).unwrap();
        let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        let doc: serde_json::Value = serde_json::from_slice(&glb[20..20 + len]).unwrap();
        let node = doc["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|n| n["name"] == content::LEFT_OUT)
            .unwrap();
        let mesh = &doc["meshes"][node["mesh"].as_u64().unwrap() as usize];
        assert_eq!(mesh["primitives"][0]["mode"], 0, "POINTS");
        assert_eq!(mesh["extras"]["classes"], serde_json::json!(["stump"]));
        let position = &doc["accessors"][mesh["primitives"][0]["attributes"]["POSITION"]
            .as_u64()
            .unwrap() as usize];
        assert_eq!(position["count"], 500);
        // The first left out stands where tree 0 does, from the tile's centre, Y up.
        let centre = tile.centre;
        let min = position["min"].as_array().unwrap();
        assert!((min[0].as_f64().unwrap() - (0.0 - centre.x)).abs() < 1e-3);
        assert!((min[2].as_f64().unwrap() + (planned[499].at.y - centre.y)).abs() < 1e-3);
    }
}
