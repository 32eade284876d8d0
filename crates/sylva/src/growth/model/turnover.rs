//! Turnover: branches that die. Deep shade kills a side branch, and near the segment budget
//! the darkest make room, so the crown keeps renewing itself at its lit surface.

use super::*;

impl Grower {
    /// Deep shade for years on end kills a side branch: the interior thins out.
    pub(super) fn shade_deaths(&mut self) {
        for b in 1..self.branches.len() {
            if !self.branches[b].alive || self.branches[b].order < 2 {
                continue;
            }
            let dark = self.light.light_at(self.apex_segment(b).end()) < 0.05;
            let br = &mut self.branches[b];
            br.shaded_years = if dark { br.shaded_years + 1 } else { 0 };
            if br.shaded_years >= 3 {
                self.kill(b);
            }
        }
    }

    /// Near the segment budget, the darkest side branches die, so the crown keeps renewing
    /// itself at its lit surface instead of freezing when the budget is spent: the interior
    /// turnover of a real crown, hastened.
    pub(super) fn make_room(&mut self) {
        let max = self.options.max_segments;
        let live = self.segment_count();
        if live * 20 < max * 17 {
            return;
        }
        let goal = max * 4 / 5;
        let mut dark: Vec<(f32, usize)> = self
            .branches
            .iter()
            .enumerate()
            .filter(|(_, b)| b.alive && b.order >= 2)
            .map(|(i, _)| (self.light.light_at(self.apex_segment(i).end()), i))
            .collect();
        dark.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut left = live;
        for (_, b) in dark {
            if left <= goal {
                break;
            }
            if self.branches[b].alive {
                left -= self.kill(b);
            }
        }
    }

    /// Marks a branch and everything on it dead.
    /// Returns how many live segments died.
    pub(super) fn kill(&mut self, b: usize) -> usize {
        let mut stack = vec![b];
        let mut segments = 0;
        while let Some(b) = stack.pop() {
            if !self.branches[b].alive {
                continue;
            }
            self.branches[b].alive = false;
            segments += self.branches[b].segments.len();
            stack.extend(self.branches[b].children.iter().map(|&c| c as usize));
        }
        segments
    }
}
