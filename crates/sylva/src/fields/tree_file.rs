//! Fields' `.tree` files (appendix 8.3): the tree type, the random seed, the trunk branches and
//! the leaf lobes; the rest of the tree grows again from the rules when it is loaded.
//!
//! ```text
//! Cherry Tree
//! 100
//! #BRANCHES
//! 0 -1 1.110022 -1.582516 4.728205 1.14952 -0.8700994 4.896452 1
//! #LEAF LOBES
//! 2.307282 0.5082518 4.534246 1
//! ```
//!
//! A branch line is `id parent startX startY startZ endX endY endZ` (parent −1: none). The
//! appendix's own example carries a ninth number on every branch line (always 1) that its format
//! description leaves out; it is read, kept and written back. The paper's application ran on XNA,
//! so files are Y-up (its Kinect example has the trunk rising along Y); Sylva converts to Z-up
//! when it grows the tree and back when it saves.
//!
//! Round trips are byte-for-byte: lines read from a file are written back as they were unless
//! their values changed, and line endings (LF or CRLF) and the final newline are kept.

use super::lobe::Lobe;
use super::pipeline::{Placement, TrunkPiece};
use crate::error::ParamsError;
use glam::Vec3;

/// A branch line.
#[derive(Clone, Debug, PartialEq)]
pub struct FileBranch {
    /// Branch id.
    pub id: i64,
    /// Parent id, −1 for none.
    pub parent: i64,
    /// Start (file coordinates, Y up).
    pub start: [f32; 3],
    /// End.
    pub end: [f32; 3],
    /// The appendix example's ninth number, when present.
    pub extra: Option<i64>,
    /// The line as read, written back while the values above are unchanged.
    line: Option<String>,
}

/// A lobe line.
#[derive(Clone, Debug, PartialEq)]
pub struct FileLobe {
    /// Centre (file coordinates, Y up).
    pub centre: [f32; 3],
    /// Radius.
    pub radius: f32,
    line: Option<String>,
}

/// A `.tree` file's contents.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeFile {
    /// The species the tree grows with.
    pub tree_type: String,
    /// Seed of the random generator.
    pub seed: i64,
    /// Trunk branches.
    pub branches: Vec<FileBranch>,
    /// Leaf lobes.
    pub lobes: Vec<FileLobe>,
    seed_text: Option<String>,
    crlf: bool,
    final_newline: bool,
}

/// Most lines a `.tree` file may hold.
pub const MAX_LINES: usize = 1_000_000;

fn numbers<const N: usize>(fields: &[&str], what: &str) -> Result<[f32; N], String> {
    let mut out = [0.0f32; N];
    for (slot, f) in out.iter_mut().zip(fields) {
        *slot = f
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("{what}: `{f}` is not a finite number"))?;
    }
    Ok(out)
}

impl TreeFile {
    /// Reads a file's text; `name` goes into error messages, which give the line.
    pub fn parse(text: &str, name: &str) -> Result<Self, ParamsError> {
        let fail = |line: usize, message: String| ParamsError::Syntax {
            source_name: format!("{name}, line {line}"),
            message,
        };
        let crlf = text.contains("\r\n");
        let final_newline = text.ends_with('\n');
        let lines: Vec<&str> = text
            .lines()
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
            .collect();
        if lines.len() > MAX_LINES {
            return Err(fail(
                MAX_LINES + 1,
                format!("more than {MAX_LINES} lines; not a tree file Sylva will read"),
            ));
        }
        let expect = |i: usize, what: &str| -> Result<&str, ParamsError> {
            lines
                .get(i)
                .copied()
                .ok_or_else(|| fail(i + 1, format!("the file ends where {what} should be")))
        };
        let tree_type = expect(0, "the tree type")?.trim();
        if tree_type.is_empty() {
            return Err(fail(1, "expected the tree type (a species name)".into()));
        }
        let seed_text = expect(1, "the random seed")?;
        let seed = seed_text.trim().parse::<i64>().map_err(|_| {
            fail(
                2,
                format!("expected the random seed (a whole number), found `{seed_text}`"),
            )
        })?;
        if expect(2, "#BRANCHES")?.trim() != "#BRANCHES" {
            return Err(fail(
                3,
                format!("expected `#BRANCHES`, found `{}`", lines[2]),
            ));
        }
        let mut branches: Vec<FileBranch> = Vec::new();
        let mut lobes = Vec::new();
        let mut in_lobes = false;
        for (i, raw) in lines.iter().enumerate().skip(3) {
            let line_no = i + 1;
            let t = raw.trim();
            if t.is_empty() {
                if lines[i..].iter().all(|l| l.trim().is_empty()) {
                    break;
                }
                return Err(fail(line_no, "blank line inside the file".into()));
            }
            if t == "#LEAF LOBES" && !in_lobes {
                in_lobes = true;
                continue;
            }
            let fields: Vec<&str> = t.split_whitespace().collect();
            if in_lobes {
                if fields.len() != 4 {
                    return Err(fail(
                        line_no,
                        format!("a lobe is `x y z radius`, found {} values", fields.len()),
                    ));
                }
                let v: [f32; 4] = numbers(&fields, "lobe").map_err(|m| fail(line_no, m))?;
                if v[3] <= 0.0 {
                    return Err(fail(
                        line_no,
                        format!("lobe radius {} is not positive", v[3]),
                    ));
                }
                lobes.push(FileLobe {
                    centre: [v[0], v[1], v[2]],
                    radius: v[3],
                    line: Some(raw.to_string()),
                });
            } else {
                if fields.len() != 8 && fields.len() != 9 {
                    return Err(fail(
                        line_no,
                        format!(
                            "a branch is `id parent startX startY startZ endX endY endZ`, found {} values",
                            fields.len()
                        ),
                    ));
                }
                let int = |f: &str, what: &str| {
                    f.parse::<i64>()
                        .map_err(|_| fail(line_no, format!("{what} `{f}` is not a whole number")))
                };
                let id = int(fields[0], "branch id")?;
                let parent = int(fields[1], "parent id")?;
                if id < 0 {
                    return Err(fail(line_no, format!("branch id {id} is negative")));
                }
                if branches.iter().any(|b| b.id == id) {
                    return Err(fail(line_no, format!("branch id {id} is used twice")));
                }
                if parent != -1 && !branches.iter().any(|b| b.id == parent) {
                    return Err(fail(
                        line_no,
                        format!("parent {parent} is not an earlier branch's id (-1: no parent)"),
                    ));
                }
                let v: [f32; 6] = numbers(&fields[2..8], "branch").map_err(|m| fail(line_no, m))?;
                let extra = fields.get(8).map(|f| int(f, "ninth value")).transpose()?;
                branches.push(FileBranch {
                    id,
                    parent,
                    start: [v[0], v[1], v[2]],
                    end: [v[3], v[4], v[5]],
                    extra,
                    line: Some(raw.to_string()),
                });
            }
        }
        if !in_lobes {
            return Err(fail(lines.len() + 1, "no `#LEAF LOBES` section".into()));
        }
        Ok(Self {
            tree_type: lines[0].to_string(),
            seed,
            branches,
            lobes,
            seed_text: Some(seed_text.to_string()),
            crlf,
            final_newline,
        })
    }

    /// The file's text.
    pub fn to_text(&self) -> String {
        let mut lines: Vec<String> = Vec::with_capacity(self.branches.len() + self.lobes.len() + 4);
        lines.push(self.tree_type.clone());
        lines.push(match &self.seed_text {
            Some(t) if t.trim().parse::<i64>() == Ok(self.seed) => t.clone(),
            _ => self.seed.to_string(),
        });
        lines.push("#BRANCHES".into());
        for b in &self.branches {
            let fresh = || {
                let mut l = format!(
                    "{} {} {} {} {} {} {} {}",
                    b.id,
                    b.parent,
                    b.start[0],
                    b.start[1],
                    b.start[2],
                    b.end[0],
                    b.end[1],
                    b.end[2]
                );
                if let Some(x) = b.extra {
                    l.push_str(&format!(" {x}"));
                }
                l
            };
            lines.push(match &b.line {
                Some(l)
                    if Self::parse_branch_values(l)
                        == Some((b.id, b.parent, b.start, b.end, b.extra)) =>
                {
                    l.clone()
                }
                _ => fresh(),
            });
        }
        lines.push("#LEAF LOBES".into());
        for l in &self.lobes {
            let same = l.line.as_deref().and_then(|t| {
                let f: Vec<&str> = t.split_whitespace().collect();
                numbers::<4>(&f, "").ok()
            }) == Some([l.centre[0], l.centre[1], l.centre[2], l.radius]);
            lines.push(match (&l.line, same) {
                (Some(t), true) => t.clone(),
                _ => format!(
                    "{} {} {} {}",
                    l.centre[0], l.centre[1], l.centre[2], l.radius
                ),
            });
        }
        let eol = if self.crlf { "\r\n" } else { "\n" };
        let mut text = lines.join(eol);
        if self.final_newline {
            text.push_str(eol);
        }
        text
    }

    #[allow(clippy::type_complexity)]
    fn parse_branch_values(line: &str) -> Option<(i64, i64, [f32; 3], [f32; 3], Option<i64>)> {
        let f: Vec<&str> = line.split_whitespace().collect();
        let v: [f32; 6] = numbers(f.get(2..8)?, "").ok()?;
        Some((
            f[0].parse().ok()?,
            f[1].parse().ok()?,
            [v[0], v[1], v[2]],
            [v[3], v[4], v[5]],
            match f.get(8) {
                Some(x) => Some(x.parse().ok()?),
                None => None,
            },
        ))
    }

    /// A file for a placement grown with `tree_type` and `seed` (Z-up metres in, Y-up out).
    pub fn from_placement(tree_type: &str, seed: i64, placement: &Placement) -> Self {
        // Adding 0 turns -0 into 0, so files never read `-0`.
        let y_up = |v: Vec3| [v.x + 0.0, v.z + 0.0, 0.0 - v.y];
        Self {
            tree_type: tree_type.to_string(),
            seed,
            branches: placement
                .trunks
                .iter()
                .enumerate()
                .map(|(i, t)| FileBranch {
                    id: i as i64,
                    parent: t.parent.map_or(-1, |p| p as i64),
                    start: y_up(t.start),
                    end: y_up(t.end),
                    extra: None,
                    line: None,
                })
                .collect(),
            lobes: placement
                .lobes
                .iter()
                .map(|l| FileLobe {
                    centre: y_up(l.centre),
                    radius: l.radius,
                    line: None,
                })
                .collect(),
            seed_text: None,
            crlf: false,
            final_newline: true,
        }
    }

    /// The trunks and lobes in Sylva's frame: Z up, and moved so that the first root branch
    /// starts at the origin (the paper's files are in the Kinect's room coordinates).
    pub fn placement(&self) -> Placement {
        let z_up = |v: [f32; 3]| Vec3::new(v[0], -v[2], v[1]);
        let origin = self
            .branches
            .iter()
            .find(|b| b.parent == -1)
            .map(|b| z_up(b.start))
            .unwrap_or(Vec3::ZERO);
        let index_of = |id: i64| self.branches.iter().position(|b| b.id == id);
        Placement {
            trunks: self
                .branches
                .iter()
                .map(|b| TrunkPiece {
                    parent: index_of(b.parent),
                    start: z_up(b.start) - origin,
                    end: z_up(b.end) - origin,
                })
                .collect(),
            lobes: self
                .lobes
                .iter()
                .map(|l| Lobe {
                    centre: z_up(l.centre) - origin,
                    radius: l.radius,
                })
                .collect(),
        }
    }
}
