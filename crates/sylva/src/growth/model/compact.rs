//! Shed wood leaves the tree's tables. A branch that dies (shade, the rising crown base, a cut,
//! the segment budget) is only marked dead, and every loop over the tree's branches and
//! segments used to step over it: an old bigleaf maple held 4,574 live branches and 4,859 shed
//! (issue X). Once a year, after the buds of dead wood have gone, the dead branches and their
//! segments are dropped and the rest renumbered in the same order.
//!
//! Nothing the growth computes depends on where a live branch or segment lies in the tables,
//! only on their order, which is kept: the random streams and drawing choices that used an
//! index now use the branch's or segment's own number (`Branch::id`, `Segment::id`), given
//! when it was made. So a tree grows to the same bytes whether its dead wood is kept or
//! dropped (`compacting_changes_no_byte_of_the_grown_tree`).

use super::*;

impl Grower {
    /// The id of the branch made next (`Branch::id`).
    pub(super) fn next_branch_id(&mut self) -> u32 {
        self.made.0 += 1;
        self.made.0 - 1
    }

    /// The id of the segment made next (`Segment::id`).
    pub(super) fn next_segment_id(&mut self) -> u32 {
        self.made.1 += 1;
        self.made.1 - 1
    }

    /// Drops the dead branches and their segments, renumbering what lives on (in order) in
    /// the branches' parents, children and segments, the buds, the short twigs and the
    /// per-segment tables. Buds and short twigs must stand on live wood (`prune_buds` and
    /// `grow_short_shoots` have run).
    pub(super) fn compact(&mut self) {
        let dead = self.branches.iter().filter(|b| !b.alive).count();
        #[cfg(test)]
        if tests::KEEP_DEAD.with(|k| k.get()) {
            return;
        }
        if dead == 0 {
            return;
        }
        const GONE: u32 = u32::MAX;
        let mut branch_at = vec![GONE; self.branches.len()];
        let mut kept = 0u32;
        for (b, branch) in self.branches.iter().enumerate() {
            if branch.alive {
                branch_at[b] = kept;
                kept += 1;
            }
        }
        let mut segment_at = vec![GONE; self.segments.len()];
        let mut kept = 0u32;
        for (s, segment) in self.segments.iter().enumerate() {
            if self.branches[segment.branch as usize].alive {
                segment_at[s] = kept;
                kept += 1;
            }
        }
        let keep_segment = |s: usize| segment_at[s] != GONE;
        retain_live(&mut self.leaves_on, &segment_at);
        retain_live(&mut self.radii, &segment_at);
        retain_live(&mut self.segments, &segment_at);
        for segment in &mut self.segments {
            segment.branch = branch_at[segment.branch as usize];
        }
        self.branches.retain(|b| b.alive);
        for branch in &mut self.branches {
            branch.parent = branch
                .parent
                .map(|(p, s)| (branch_at[p as usize], segment_at[s as usize]));
            branch.children.retain(|&c| branch_at[c as usize] != GONE);
            for c in &mut branch.children {
                *c = branch_at[*c as usize];
            }
            for s in &mut branch.segments {
                *s = segment_at[*s as usize];
            }
        }
        for bud in &mut self.buds {
            bud.branch = branch_at[bud.branch as usize];
            bud.segment = segment_at[bud.segment as usize];
        }
        self.short_shoots
            .retain(|t| keep_segment(t.segment as usize));
        for t in &mut self.short_shoots {
            t.segment = segment_at[t.segment as usize];
        }
        self.dropped_branches += dead;
        debug_assert!(
            self.buds
                .iter()
                .all(|b| b.branch != GONE && b.segment != GONE)
        );
    }
}

/// Keeps the entries of a per-segment table whose segments live (`at`: each segment's new
/// place, `u32::MAX` where it goes); entries past the segments (none) would stay.
fn retain_live<T>(table: &mut Vec<T>, at: &[u32]) {
    let mut s = 0;
    table.retain(|_| {
        s += 1;
        at.get(s - 1).is_none_or(|&a| a != u32::MAX)
    });
}

#[cfg(test)]
mod tests {
    use super::super::tests::grown;
    use std::cell::Cell;

    thread_local! {
        /// Set by a test to grow a tree that keeps its dead wood, as before `compact`.
        pub(super) static KEEP_DEAD: Cell<bool> = const { Cell::new(false) };
    }

    #[test]
    fn compacting_changes_no_byte_of_the_grown_tree() {
        // A plane to 25 years sheds most of the branches it has made; grown keeping them and
        // dropping them, it is the same tree.
        KEEP_DEAD.with(|k| k.set(true));
        let kept = grown("InlVal", "PLAC", 25.0);
        KEEP_DEAD.with(|k| k.set(false));
        let dropped = grown("InlVal", "PLAC", 25.0);
        let dead = kept.branches.iter().filter(|b| !b.alive).count();
        assert!(dead > 1000, "{dead} dead branches kept");
        assert!(dropped.branches.iter().filter(|b| !b.alive).count() < dead / 10);
        assert_eq!(kept.branch_counts(), dropped.branch_counts());
        assert_eq!(kept.segment_count(), dropped.segment_count());
        assert_eq!(kept.skeleton(), dropped.skeleton());
        assert_eq!(kept.leaf_carried(), dropped.leaf_carried());
    }
}
