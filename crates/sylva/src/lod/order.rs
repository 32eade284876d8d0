//! Rank-major order (Weber & Penn, section 5): the items of a list (cross-sections of stems, or
//! leaves) are grouped in masses of `M` consecutive items; a level of detail draws the first
//! `x` items of every mass, for a real `x` in `0..=M`. Stored rank-major (every mass's first
//! item, then every mass's second item, ...), that set is one contiguous prefix of the list,
//! so a level of detail is one draw range and nothing is rebuilt per frame.

/// Stem lists group 16 cross-sections per mass (the paper's figure).
pub const STEM_MASS: usize = 16;
/// The leaf list groups 4 leaves per mass.
pub const LEAF_MASS: usize = 4;

/// The masses `0..masses` in bit-reversed order (0, n/2, n/4, 3n/4, ...): any first few of
/// them are spread over the whole list rather than bunched at its start.
pub fn spread(masses: usize) -> Vec<usize> {
    let bits = masses.next_power_of_two().trailing_zeros();
    (0..masses.next_power_of_two())
        .map(|i| {
            if bits == 0 {
                0
            } else {
                i.reverse_bits() >> (usize::BITS - bits)
            }
        })
        .filter(|&m| m < masses)
        .collect()
}

/// Positions of `total` items in rank-major order: `order[p]` is the creation index of the item
/// stored at position `p`. Within a rank the masses come in [`spread`] order, so that a level
/// of detail below 1 (fewer items than masses, as a budget may ask for) draws items from the
/// whole tree, not the masses made first (the lowest branches).
pub fn rank_major(total: usize, mass: usize) -> Vec<u32> {
    let mass = mass.max(1);
    let masses = total.div_ceil(mass);
    let order_of_masses = spread(masses);
    let mut order = Vec::with_capacity(total);
    for rank in 0..mass {
        for &m in &order_of_masses {
            let item = m * mass + rank;
            if item < total {
                order.push(item as u32);
            }
        }
    }
    order
}

/// How many items of a rank-major list of `total` items (masses of `mass`) a level of detail
/// `x` (0..=mass) draws: the paper's "floor(x) of every mass, and one more in the first
/// floor(masses * frac(x)) masses", counted as a prefix length.
pub fn prefix_len(total: usize, mass: usize, x: f64) -> usize {
    let mass = mass.max(1);
    if total == 0 || x.is_nan() || x <= 0.0 {
        return 0;
    }
    if x >= mass as f64 {
        return total;
    }
    let masses = total.div_ceil(mass);
    let whole = x.floor() as usize;
    let extra = (masses as f64 * x.fract()).floor() as usize;
    // Masses holding an item of rank r: all of them, except the last (partial) mass for
    // ranks at or above its size.
    let last = total - (masses - 1) * mass;
    let holding = |rank: usize| if rank < last { masses } else { masses - 1 };
    let full: usize = (0..whole).map(holding).sum();
    full + extra.min(holding(whole))
}

/// The paper's own loop over masses for a level of detail `x`: the creation indices drawn.
/// Kept as the reference that [`prefix_len`] over [`rank_major`] must reproduce.
pub fn paper_loop(total: usize, mass: usize, x: f64) -> Vec<usize> {
    let mass = mass.max(1);
    let masses = total.div_ceil(mass);
    let x = x.clamp(0.0, mass as f64);
    let whole = x.floor() as usize;
    let change = (masses as f64 * x.fract()).floor() as usize;
    let mut drawn = Vec::new();
    for m in 0..masses {
        let start = m * mass;
        let end = start + whole + usize::from(m < change);
        drawn.extend((start..end.min(start + mass)).filter(|&i| i < total));
    }
    drawn
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rank_major_is_a_permutation() {
        for total in [0, 1, 5, 16, 17, 100, 1000] {
            let mut o = rank_major(total, 16);
            o.sort_unstable();
            assert_eq!(o, (0..total as u32).collect::<Vec<_>>());
        }
        // Masses 0, 1, 2 in spread order 0, 2, 1.
        assert_eq!(rank_major(10, 4), vec![0, 8, 4, 1, 9, 5, 2, 6, 3, 7]);
        assert_eq!(spread(8), vec![0, 4, 2, 6, 1, 5, 3, 7]);
        assert_eq!(spread(1), vec![0]);
    }

    #[test]
    fn every_level_of_detail_is_a_prefix_equal_to_the_papers_loop() {
        for total in [0, 1, 3, 4, 15, 16, 17, 33, 100, 257] {
            for mass in [4, 16] {
                let order = rank_major(total, mass);
                for step in 0..=(mass * 20) {
                    let x = step as f64 / 20.0;
                    let n = prefix_len(total, mass, x);
                    let mut prefix: Vec<usize> = order[..n].iter().map(|&i| i as usize).collect();
                    prefix.sort_unstable();
                    // The paper's loop takes the first masses of a partial rank; the spread
                    // order takes others, so compare how many items of each rank are drawn.
                    let ranks = |items: &[usize]| {
                        let mut n = vec![0; mass];
                        items.iter().for_each(|&i| n[i % mass] += 1);
                        n
                    };
                    let paper = paper_loop(total, mass, x);
                    assert_eq!(ranks(&prefix), ranks(&paper), "T {total}, M {mass}, x {x}");
                }
            }
        }
    }

    #[test]
    fn counts_are_monotone_and_change_one_item_per_mass_at_most() {
        let (total, mass) = (1000usize, 16usize);
        let masses = total.div_ceil(mass);
        let mut previous = 0;
        for step in 0..=1600 {
            let n = prefix_len(total, mass, step as f64 / 100.0);
            assert!(n >= previous);
            // A small step in x never adds more than one item per mass.
            assert!(
                n - previous <= masses,
                "jump of {} at step {step}",
                n - previous
            );
            previous = n;
        }
        assert_eq!(previous, total);
    }
}
