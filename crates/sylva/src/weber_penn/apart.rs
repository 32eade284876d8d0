//! Growing a trunk's branches on several threads, with the very bytes one thread makes.
//!
//! Each main branch's subtree draws only from its own random streams (keyed by its place in
//! the tree) and reads only the sections it traces itself. So the subtrees can grow apart, each
//! into a skeleton of its own, and be joined in the order one thread would have made them:
//! stems, sections and leaves land at the same indices, with the same values.

use super::*;
use rayon::prelude::*;

/// Stems of this level are grown on separate threads: the trunk's main branches, a few dozen
/// subtrees of some thousands of stems each, enough to share out and few enough to join.
const APART_LEVEL: usize = 1;

impl Generator<'_> {
    /// Grows `children`, the stems starting on one traced parent, in order.
    pub(super) fn grow_stems(&mut self, children: Vec<StemStart>) -> Result<(), GenerateError> {
        let apart = children.len() > 1
            && children[0].level == APART_LEVEL
            && rayon::current_num_threads() > 1;
        if !apart {
            let mut children = children;
            for child in children.drain(..) {
                self.grow_stem(child)?;
            }
            self.spare.starts.push(children);
            return Ok(());
        }
        let grown = children
            .into_par_iter()
            .map(|child| {
                let mut part = self.fork();
                part.grow_stem(child)?;
                Ok(part.skeleton)
            })
            .collect::<Result<Vec<Skeleton>, GenerateError>>()?;
        for part in grown {
            self.skeleton.append_subtree(part, APART_LEVEL as u8);
        }
        Ok(())
    }

    /// A generator for one subtree: the same tree's settings and budget, an empty skeleton.
    fn fork(&self) -> Self {
        Generator {
            skeleton: Skeleton::default(),
            profile: Vec::new(),
            shares: Vec::new(),
            spare: Spare::default(),
            ..*self
        }
    }
}
