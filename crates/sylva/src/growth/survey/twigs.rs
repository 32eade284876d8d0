//! How a crown branches, measured on the Skeleton: its twigs' lengths and its Horton-Strahler
//! orders. Issue W holds the grown trees to published shoot data with these, before and after
//! the model changes:
//! - a twig is the distal unbranched stretch of an axis, from its last lateral to its tip. In
//!   red maple and scarlet oak most twigs are 1-4 cm long, their number falling steeply through
//!   the 6-10 cm class, and old branches carry only twigs under 5 cm ("Tree branches as
//!   populations of twigs", abstract);
//! - Strahler orders count from the tips: a tip's link is order 1, and where two links of
//!   order i meet the link below is i + 1 (else the larger order goes on). The bifurcation
//!   ratio, streams of one order over streams of the next, was 3.19 in forest-grown and 7.05
//!   in open-grown sugar maple saplings (Steingraeber, Kascht & Franck 1979, Am. J. Bot.
//!   66:441-445).
//!
//! A Skeleton's stem is an axis and its children attach at their offsets along it, so the links
//! are the stretches of an axis between its laterals. Clones (splits) count as laterals.

use crate::skeleton::Skeleton;

/// Upper edges of the twig-length classes, cm: the published histograms' 1 cm classes up to
/// 4 cm, then 4-6, 6-10 (where the counts fall away) and longer.
pub const TWIG_CLASSES_CM: [f64; 8] = [1.0, 2.0, 3.0, 4.0, 6.0, 10.0, 20.0, 50.0];

/// A crown's branching, measured.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Branching {
    /// Twigs: every axis's stretch beyond its last lateral.
    pub twigs: usize,
    /// Twigs in each class of [`TWIG_CLASSES_CM`], and the last count for those longer.
    pub twig_classes: [usize; TWIG_CLASSES_CM.len() + 1],
    /// Median twig length, cm (`None` without twigs).
    pub median_twig_cm: Option<f64>,
    /// Streams (runs of links of one Strahler order) of order 1, 2, ...: the tree's number of
    /// orders is this list's length.
    pub streams: Vec<usize>,
    /// The bifurcation ratio of the whole tree: 10 to minus the slope of log10(streams)
    /// against order, fitted over every order (Horton's law); `None` with fewer than two.
    pub bifurcation_ratio: Option<f64>,
}

impl Branching {
    /// Share of the twigs shorter than `cm` (a class edge of [`TWIG_CLASSES_CM`]).
    pub fn share_under(&self, cm: f64) -> f64 {
        if self.twigs == 0 {
            return 0.0;
        }
        let n: usize = (TWIG_CLASSES_CM.iter().zip(&self.twig_classes))
            .take_while(|(edge, _)| **edge <= cm)
            .map(|(_, n)| n)
            .sum();
        n as f64 / self.twigs as f64
    }

    /// Share of the twigs `cm` long or longer (a class edge of [`TWIG_CLASSES_CM`]).
    pub fn share_from(&self, cm: f64) -> f64 {
        if self.twigs == 0 {
            return 0.0;
        }
        1.0 - self.share_under(cm)
    }
}

/// Measures a skeleton's twigs and Strahler orders.
pub fn measure_branching(skeleton: &Skeleton) -> Branching {
    let n = skeleton.stems.len();
    // Each stem's laterals (their offsets along it and their indices).
    let mut laterals: Vec<Vec<(f32, usize)>> = vec![Vec::new(); n];
    for (i, s) in skeleton.stems.iter().enumerate() {
        let from = s.clone_of.or(s.parent);
        if let Some(p) = from.map(|p| p.0 as usize).filter(|&p| p < n && p != i) {
            laterals[p].push((s.offset, i));
        }
    }
    for l in &mut laterals {
        l.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    let mut lengths: Vec<f64> = (skeleton.stems.iter().zip(&laterals))
        .map(|(s, l)| {
            let last = l.last().map_or(0.0, |x| x.0);
            ((s.length - last).max(0.0) * 100.0) as f64
        })
        .collect();
    let mut twig_classes = [0usize; TWIG_CLASSES_CM.len() + 1];
    for &cm in &lengths {
        let class = TWIG_CLASSES_CM.iter().position(|&edge| cm < edge);
        twig_classes[class.unwrap_or(TWIG_CLASSES_CM.len())] += 1;
    }
    lengths.sort_by(f64::total_cmp);
    let median_twig_cm = (!lengths.is_empty()).then(|| lengths[lengths.len() / 2]);
    // Strahler orders: a stem's order at its base needs its laterals' first, and a lateral
    // always comes after its parent in a grown skeleton but not necessarily in any skeleton, so
    // orders are found depth first from each root, without recursion (a crown may be deep).
    let mut base_order = vec![0u32; n];
    let mut streams: Vec<usize> = Vec::new();
    let count = |order: u32, streams: &mut Vec<usize>| {
        let k = order as usize - 1;
        if streams.len() <= k {
            streams.resize(k + 1, 0);
        }
        streams[k] += 1;
    };
    let roots = (0..n).filter(|&i| {
        let s = &skeleton.stems[i];
        s.clone_of
            .or(s.parent)
            .is_none_or(|p| p.0 as usize >= n || p.0 as usize == i)
    });
    for root in roots {
        // (stem, whether its laterals are done)
        let mut stack = vec![(root, false)];
        while let Some((i, done)) = stack.pop() {
            if !done {
                stack.push((i, true));
                stack.extend(laterals[i].iter().map(|&(_, c)| (c, false)));
                continue;
            }
            // From the tip down: the tip's link is order 1, a new stream.
            let mut order = 1u32;
            count(1, &mut streams);
            for &(_, c) in laterals[i].iter().rev() {
                let o = base_order[c];
                let next = if o == order { order + 1 } else { order.max(o) };
                // Two equal orders begin a stream of the next order; a lateral of a higher
                // order carries its own stream on down this axis.
                if next > order && next != o {
                    count(next, &mut streams);
                }
                order = next;
            }
            base_order[i] = order;
        }
    }
    let bifurcation_ratio = horton_ratio(&streams);
    Branching {
        twigs: lengths.len(),
        twig_classes,
        median_twig_cm,
        streams,
        bifurcation_ratio,
    }
}

/// 10^-slope of log10(streams) against order, least squares over the orders that have streams.
fn horton_ratio(streams: &[usize]) -> Option<f64> {
    let points: Vec<(f64, f64)> = (streams.iter().enumerate())
        .filter(|(_, n)| **n > 0)
        .map(|(k, n)| ((k + 1) as f64, (*n as f64).log10()))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let m = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / m, sy / m);
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    Some(10f64.powf(-sxy / sxx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{Stem, StemId};

    fn stem(parent: Option<u32>, offset: f32, length: f32) -> Stem {
        Stem {
            level: 0,
            parent: parent.map(StemId),
            clone_of: None,
            offset,
            length,
            sections: 0..0,
            lobes: 0,
            lobe_depth: 0.0,
        }
    }

    /// A trunk of 4 m with two main branches (at 1 and 2 m), each with two 3 cm twigs (at 0.5
    /// and 0.7 m of its 1 m).
    fn small_tree() -> Skeleton {
        let mut s = Skeleton {
            stems: vec![
                stem(None, 0.0, 4.0),
                stem(Some(0), 1.0, 1.0),
                stem(Some(0), 2.0, 1.0),
            ],
            ..Skeleton::default()
        };
        for b in [1, 2] {
            s.stems.push(stem(Some(b), 0.5, 0.03));
            s.stems.push(stem(Some(b), 0.7, 0.03));
        }
        s
    }

    #[test]
    fn twigs_are_the_axes_beyond_their_last_lateral() {
        let b = measure_branching(&small_tree());
        // Four 3 cm twigs, two 30 cm branch ends, the trunk's 2 m beyond its upper branch.
        assert_eq!(b.twigs, 7);
        assert_eq!(b.twig_classes[3], 4, "{b:?}");
        assert_eq!(b.twig_classes[7], 2, "{b:?}");
        assert_eq!(b.twig_classes[8], 1, "{b:?}");
        assert!((b.share_under(4.0) - 4.0 / 7.0).abs() < 1e-12);
        assert!((b.share_from(10.0) - 3.0 / 7.0).abs() < 1e-12);
        assert!((b.median_twig_cm.unwrap() - 3.0).abs() < 1e-4);
    }

    #[test]
    fn strahler_orders_count_streams_from_the_tips() {
        // Each branch: its tip (1) meets a twig (1) at 0.7 m: order 2 below; the next twig
        // (1) joins order 2 and it stays 2. The trunk's tip (1) meets branch 2 (order 2): 2;
        // then branch 1 (order 2): 3. Streams of order 1: seven tips; of order 2: the two
        // branches' and none new on the trunk (branch 2's stream carries on); order 3: one.
        let b = measure_branching(&small_tree());
        assert_eq!(b.streams, vec![7, 2, 1], "{b:?}");
        // A binary tree of three orders: the trunk's tip meets a bare lateral at 3 m (order
        // 2), and a lateral at 1 m whose own tip meets a twig (order 2): order 3 below. Four
        // tips, two streams of order 2, one of order 3: a bifurcation ratio of exactly 2.
        let s = Skeleton {
            stems: vec![
                stem(None, 0.0, 4.0),
                stem(Some(0), 1.0, 1.0),
                stem(Some(0), 3.0, 0.5),
                stem(Some(1), 0.5, 0.2),
            ],
            ..Skeleton::default()
        };
        let b = measure_branching(&s);
        assert_eq!(b.streams, vec![4, 2, 1], "{b:?}");
        assert!((b.bifurcation_ratio.unwrap() - 2.0).abs() < 1e-9, "{b:?}");
    }

    #[test]
    fn an_empty_skeleton_has_no_twigs() {
        let b = measure_branching(&Skeleton::default());
        assert_eq!(
            (b.twigs, b.median_twig_cm, b.bifurcation_ratio),
            (0, None, None)
        );
        assert_eq!(b.share_under(4.0), 0.0);
    }
}
