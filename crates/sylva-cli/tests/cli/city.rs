//! `sylva city`'s own flags (the pipeline's tests are sylva-city's).

use super::{sylva, text};

#[test]
fn bad_cache_flags_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let inventory = dir.path().join("city.csv");
    std::fs::write(&inventory, "id,species,dbh\n1,Platanus x acerifolia,30\n").unwrap();
    let out = dir.path().join("tiles");
    let (inv, o) = (inventory.to_str().unwrap(), out.to_str().unwrap());
    // A file where the cache's folder should be.
    let run = sylva(&["city", inv, "-o", o, "--cache", inv]);
    assert_eq!(run.status.code(), Some(1), "{}", text(&run.stderr));
    assert!(
        text(&run.stderr).contains("--cache"),
        "{}",
        text(&run.stderr)
    );
    // A cache and none at once, and a negative bound.
    for args in [
        vec!["city", inv, "-o", o, "--cache", o, "--no-cache"],
        vec!["city", inv, "-o", o, "--cache-mib", "-5"],
    ] {
        let run = sylva(&args);
        assert_eq!(
            run.status.code(),
            Some(2),
            "{args:?}: {}",
            text(&run.stderr)
        );
    }
    assert!(!out.exists(), "nothing written");
}
