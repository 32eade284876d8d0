//! The trees of a city split into a quadtree over the ground plane: a tile is split into four
//! until it holds at most a leaf's worth of trees.

/// Deepest a tile may lie (a city 40 km across: leaf tiles 0.6 m wide).
pub const MAX_DEPTH: u32 = 16;

/// The fewest levels above the leaf tiles: a tile's height picks its trees' level of detail
/// (leaves the finest, their parents the next, every tile above the coarsest), so a city of
/// one or a few leaf tiles gets parents over the same ground holding the same trees, and a
/// viewer far off draws its coarsest level. Without them a census sample of 144 trees over
/// 2.7 km was one tile at the finest level, 10,000 triangles a tree at any distance. (Issue X.)
pub const MIN_HEIGHT: u32 = 2;

/// One tile of the quadtree.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Depth (the root is 0), and x, y among the 2^depth tiles of its depth.
    pub level: u32,
    pub x: u32,
    pub y: u32,
    /// Its square on the ground: west, south, east, north, m.
    pub square: [f64; 4],
    /// Its trees (indices into the city's trees): every tree below it.
    pub trees: Vec<u32>,
    /// Its four children (or none: a leaf).
    pub children: Vec<Node>,
}

impl Node {
    /// Levels below it: 0 for a leaf.
    pub fn height(&self) -> u32 {
        self.children
            .iter()
            .map(|c| c.height() + 1)
            .max()
            .unwrap_or(0)
    }

    /// The tile at `level`, `x`, `y` at or below this one, found by descending through the
    /// one child on its way at each level.
    pub fn find(&self, level: u32, x: u32, y: u32) -> Option<&Node> {
        if level < self.level {
            return None;
        }
        let up = level - self.level;
        if (x >> up, y >> up) != (self.x, self.y) {
            return None;
        }
        if up == 0 {
            return Some(self);
        }
        let child = |c: &&Node| (x >> (up - 1), y >> (up - 1)) == (c.x, c.y);
        self.children.iter().find(child)?.find(level, x, y)
    }

    /// Every tile, parents before their children.
    pub fn walk<'a>(&'a self, out: &mut Vec<&'a Node>) {
        out.push(self);
        for c in &self.children {
            c.walk(out);
        }
    }
}

/// The quadtree of the points `at` (east, north) with at most `leaf` points in a leaf tile
/// (more only at [`MAX_DEPTH`], where points stand on one spot).
pub fn build(at: &[[f64; 2]], leaf: usize) -> Node {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in at {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    if at.is_empty() {
        (lo, hi) = ([0.0; 2], [0.0; 2]);
    }
    // A square around them all, a metre wider, so every point is strictly inside.
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]) + 1.0;
    let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
    let square = [
        cx - side / 2.0,
        cy - side / 2.0,
        cx + side / 2.0,
        cy + side / 2.0,
    ];
    let mut root = split(
        at,
        (0..at.len() as u32).collect(),
        square,
        0,
        0,
        0,
        leaf.max(1),
    );
    while root.height() < MIN_HEIGHT {
        root = over(root);
    }
    root
}

/// A parent over `node`'s ground with its trees, `node` and everything below it one level
/// deeper (at the same place: the parent's one child is its own lower left quarter's address).
fn over(mut node: Node) -> Node {
    fn deeper(n: &mut Node) {
        n.level += 1;
        n.children.iter_mut().for_each(deeper);
    }
    deeper(&mut node);
    Node {
        level: 0,
        x: 0,
        y: 0,
        square: node.square,
        trees: node.trees.clone(),
        children: vec![node],
    }
}

fn split(
    at: &[[f64; 2]],
    trees: Vec<u32>,
    square: [f64; 4],
    level: u32,
    x: u32,
    y: u32,
    leaf: usize,
) -> Node {
    let mut node = Node {
        level,
        x,
        y,
        square,
        trees,
        children: Vec::new(),
    };
    if node.trees.len() <= leaf || level >= MAX_DEPTH {
        return node;
    }
    let [w, s, e, n] = square;
    let (mx, my) = ((w + e) / 2.0, (s + n) / 2.0);
    let mut quarters: [Vec<u32>; 4] = Default::default();
    for &t in &node.trees {
        let p = at[t as usize];
        let q = usize::from(p[0] >= mx) + 2 * usize::from(p[1] >= my);
        quarters[q].push(t);
    }
    for (q, trees) in quarters.into_iter().enumerate() {
        if trees.is_empty() {
            continue;
        }
        let (right, top) = (q % 2 == 1, q / 2 == 1);
        let sq = [
            if right { mx } else { w },
            if top { my } else { s },
            if right { e } else { mx },
            if top { n } else { my },
        ];
        let (cx, cy) = (2 * x + u32::from(right), 2 * y + u32::from(top));
        node.children
            .push(split(at, trees, sq, level + 1, cx, cy, leaf));
    }
    node
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_point_lands_in_one_leaf_inside_its_square() {
        let at: Vec<[f64; 2]> = (0..1000)
            .map(|i| [(i % 37) as f64 * 13.0, (i / 37) as f64 * 7.0])
            .collect();
        let root = build(&at, 50);
        let mut all = Vec::new();
        root.walk(&mut all);
        let leaves: Vec<&&Node> = all.iter().filter(|n| n.children.is_empty()).collect();
        let mut seen = vec![0; at.len()];
        for leaf in &leaves {
            assert!(leaf.trees.len() <= 50);
            for &t in &leaf.trees {
                seen[t as usize] += 1;
                let p = at[t as usize];
                let [w, s, e, n] = leaf.square;
                assert!(p[0] >= w && p[0] < e && p[1] >= s && p[1] < n);
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
        // Parents hold every tree below them.
        for n in &all {
            let below: usize = n.children.iter().map(|c| c.trees.len()).sum();
            assert!(n.children.is_empty() || below == n.trees.len());
        }
        assert!(root.height() >= 2);
        // Every tile is found again by its level and place; a place with no tile is not.
        for n in &all {
            assert!(std::ptr::eq(root.find(n.level, n.x, n.y).unwrap(), *n));
        }
        let deepest = root.height();
        assert!(root.find(deepest + 1, 0, 0).is_none());
        assert!(root.find(1, 5, 5).is_none());
    }

    #[test]
    fn a_city_of_one_leaf_tile_has_coarser_parents_over_the_same_trees() {
        // 30 trees over 3 km: one leaf's worth.
        let at: Vec<[f64; 2]> = (0..30)
            .map(|i| [(i * 97 % 3000) as f64, (i * 61 % 2000) as f64])
            .collect();
        let root = build(&at, 50);
        assert_eq!(root.height(), MIN_HEIGHT);
        let mut all = Vec::new();
        root.walk(&mut all);
        assert_eq!(all.len(), MIN_HEIGHT as usize + 1);
        for (depth, n) in all.iter().enumerate() {
            assert_eq!((n.level, n.x, n.y), (depth as u32, 0, 0));
            assert_eq!(n.trees.len(), 30);
            assert_eq!(n.square, root.square);
            assert!(std::ptr::eq(root.find(n.level, 0, 0).unwrap(), *n));
        }
        // A city deep enough already is left as it was split.
        let many: Vec<[f64; 2]> = (0..1000)
            .map(|i| [(i % 37) as f64 * 13.0, (i / 37) as f64 * 7.0])
            .collect();
        assert_eq!(
            build(&many, 50),
            split(
                &many,
                (0..1000).collect(),
                build(&many, 50).square,
                0,
                0,
                0,
                50
            )
        );
    }
}
