//! The growth model's own properties that need its insides.

use super::*;
use crate::growth::Database;

#[test]
fn a_street_tree_grows_the_same_on_one_thread_or_three() {
    // The light's shade, the leaves' allocation, the crown's two measures and the skeleton's
    // leaves are each worked out on every core; the tree must not depend on how many.
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        pool.install(|| {
            let measured = Database::builtin()
                .find("InlVal", "ACSA1")
                .expect("built in");
            let mut grower = Grower::new(measured, GrowthOptions::default());
            let first = grower.age();
            grower.advance_to(first + 6.0);
            (grower.skeleton(), grower.light.clone())
        })
    };
    let (one, one_light) = on(1);
    let (three, three_light) = on(3);
    assert!(
        one.leaves.len() > 1000 && one.stems.len() > 100,
        "a crown grew"
    );
    assert!(
        one_light.density.iter().any(|&d| d < 0.9),
        "the crown shades its cells"
    );
    assert!(one == three, "the skeletons differ");
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&one_light.density), bits(&three_light.density));
    assert_eq!(bits(&one_light.light), bits(&three_light.light));
}
