//! The parameter table: every name round-trips through lookup, and ranges hold.

use super::*;

#[test]
fn every_name_round_trips_through_lookup() {
    let mut seen = std::collections::HashSet::new();
    for def in PARAMS {
        for level in def.levels() {
            let name = def.name_at(level);
            let (found, found_level) = lookup(&name).expect(&name);
            assert_eq!(found.name, def.name);
            assert_eq!(found_level, level);
            assert!(seen.insert(name.clone()), "duplicate name {name}");
        }
    }
    assert!(lookup("0BranchDist").unwrap().0.name == "0BranchDist");
    assert!(lookup("4Length").is_none());
    assert!(lookup("").is_none());
}

#[test]
fn defaults_lie_inside_their_ranges() {
    let p = TreeParams::default();
    for def in PARAMS {
        for level in def.levels() {
            let v = (def.get)(&p, level);
            def.check(&def.name_at(level), v).unwrap();
        }
    }
}
