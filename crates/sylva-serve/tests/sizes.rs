//! What each species' growth holds, against the cache's first guess of it
//! ([`BYTES_PER_AGE`]): run by hand (every other Modesto species grown through all its ages
//! takes two minutes), `cargo test -p sylva-serve --test sizes -- --ignored --nocapture`.

use sylva::growth::Database;
use sylva_serve::cache::BYTES_PER_AGE;
use sylva_serve::grown::{ages_of, grow_all};

#[test]
#[ignore]
fn what_each_species_takes() {
    let db = Database::builtin();
    let codes: Vec<String> = db
        .growable("InlVal")
        .iter()
        .map(|s| s.code.clone())
        .collect();
    let mut within = 0;
    let mut grown = 0;
    for code in codes.iter().step_by(2) {
        let m = db.find("InlVal", code).unwrap();
        let ages = ages_of(&m).len();
        let mut total = 0usize;
        grow_all(&m, 0, None, |e| {
            total += e.bytes();
            true
        });
        let per_age = total / ages;
        println!(
            "{code}: {ages} ages, {:.0} MB, {:.1} MB an age",
            total as f64 / 1e6,
            per_age as f64 / 1e6
        );
        // None far past the guess: a growth past it is stopped if it cannot make room.
        assert!(
            per_age <= BYTES_PER_AGE * 3 / 2,
            "{code}: {per_age} bytes an age"
        );
        within += usize::from(per_age <= BYTES_PER_AGE);
        grown += 1;
    }
    assert!(
        3 * within >= 2 * grown,
        "{within} of {grown} within the guess"
    );
}
