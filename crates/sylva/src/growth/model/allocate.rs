//! Borchert-Honda allocation (Palubicki et al. 2009): the buds' exposure is summed from the
//! tips to the base, then the tree's vigour is handed back up, split at every branching point
//! between the axis going on and the lateral leaving it. Apical control lambda weights the
//! axis: above 0.5 a leader takes most and the tree stays excurrent; below it the laterals
//! win and the crown forks into codominant limbs.

use super::*;

/// Something on a branch that draws resource: a side branch or a waiting bud.
#[derive(Clone, Copy)]
struct Attachment {
    branch: u32,
    offset: f32,
    /// A branch index, or a site index (buds).
    index: u32,
    bud: bool,
}

impl Grower {
    /// Resource for every site: `terminals[i]` is the branch whose apex is site i, and the
    /// lateral buds are sites `terminals.len()..` in `self.buds`' order; `q` is each site's
    /// exposure. The base receives `vigour` times the tree's whole exposure.
    pub(super) fn allocate(&self, terminals: &[u32], q: &[f32], lambda: f32) -> Vec<f32> {
        let nb = self.branches.len();
        let mut q_sub = vec![0.0f32; nb];
        let mut apex_site = vec![u32::MAX; nb];
        for (i, &b) in terminals.iter().enumerate() {
            apex_site[b as usize] = i as u32;
            q_sub[b as usize] += q[i];
        }
        // Where each segment starts along its branch, m.
        let mut seg_offset = vec![0.0f32; self.segments.len()];
        for b in self.branches.iter().filter(|b| b.alive) {
            let mut run = 0.0;
            for &s in &b.segments {
                seg_offset[s as usize] = run;
                run += self.segments[s as usize].length;
            }
        }
        let mut attachments = Vec::with_capacity(nb + self.buds.len());
        for (c, b) in self.branches.iter().enumerate().skip(1) {
            if let (true, Some((p, _))) = (b.alive, b.parent) {
                attachments.push(Attachment {
                    branch: p,
                    offset: b.offset,
                    index: c as u32,
                    bud: false,
                });
            }
        }
        for (k, bud) in self.buds.iter().enumerate() {
            let site = terminals.len() + k;
            let seg = &self.segments[bud.segment as usize];
            q_sub[bud.branch as usize] += q[site];
            attachments.push(Attachment {
                branch: bud.branch,
                offset: seg_offset[bud.segment as usize] + seg.length * bud.at,
                index: site as u32,
                bud: true,
            });
        }
        // Basipetal: every branch's descendants come after it.
        for b in (1..nb).rev() {
            if let (true, Some((p, _))) = (self.branches[b].alive, self.branches[b].parent) {
                q_sub[p as usize] += q_sub[b];
            }
        }
        attachments.sort_by(|a, b| {
            a.branch
                .cmp(&b.branch)
                .then(a.offset.total_cmp(&b.offset))
                .then(a.index.cmp(&b.index))
        });
        // Acropetal: a branch's resource is split at each attachment from its base up.
        let mut v_in = vec![0.0f32; nb];
        v_in[0] = self.vigour as f32 * q_sub[0];
        let mut out = vec![0.0f32; q.len()];
        let mut k = 0;
        for b in 0..nb {
            let (mut v, mut q_main) = (v_in[b], q_sub[b]);
            while k < attachments.len() && attachments[k].branch as usize == b {
                let a = attachments[k];
                k += 1;
                let q_lateral = if a.bud {
                    q[a.index as usize]
                } else {
                    q_sub[a.index as usize]
                };
                q_main = (q_main - q_lateral).max(0.0);
                let weight = lambda * q_main + (1.0 - lambda) * q_lateral;
                let v_lateral = if weight > 0.0 {
                    v * (1.0 - lambda) * q_lateral / weight
                } else {
                    0.0
                };
                v -= v_lateral;
                if a.bud {
                    out[a.index as usize] = v_lateral;
                } else {
                    v_in[a.index as usize] = v_lateral;
                }
            }
            if apex_site[b] != u32::MAX {
                out[apex_site[b] as usize] = v;
            }
        }
        out
    }
}
