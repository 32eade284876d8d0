//! The cache's bound, held at every step, against real growths.

use super::*;
use sylva::growth::Database;

fn key(code: &str, seed: u64) -> Key {
    Key {
        region: "InlVal".into(),
        code: code.into(),
        seed,
        pruned: None,
    }
}

/// Awaits `g` to its end, checking the cache's count against its bound at every step, and
/// then its thread letting go of it (it marks the growth ended a moment before, and until
/// then the cache cannot drop it: something holds it).
async fn watched(cache: &Cache, g: &Arc<Growth>) {
    while g.running() || Arc::strong_count(g) > 2 {
        assert!(
            cache.bytes() <= cache.bound(),
            "{} > {}",
            cache.bytes(),
            cache.bound()
        );
        tokio::time::sleep(std::time::Duration::from_millis(2)).await;
    }
    assert!(cache.bytes() <= cache.bound());
}

// The flowering cherry (PRCE): Modesto's smallest growth, 38 ages, some 90 MB.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_growth_serves_every_request_and_ages_come_as_grown() {
    let m = Database::builtin().find("InlVal", "PRCE").unwrap();
    let cache = Arc::new(Cache::new(usize::MAX, 2));
    let a = cache.get(key("PRCE", 0), &m).unwrap();
    let b = cache.get(key("PRCE", 0), &m).unwrap();
    assert!(Arc::ptr_eq(&a, &b), "the same growth is shared");
    let early = a.at(3).await.expect("age 3 is grown");
    assert_eq!(early.record.age, 3.0);
    assert!(a.at(999).await.is_none(), "an age outside the data");
    let all = b.all().await;
    assert_eq!(all.len(), a.ages.len());
    assert!(a.finished());
    // Every age counted once, by what it holds.
    let counted: usize = all.iter().map(|e| e.bytes()).sum();
    assert_eq!(cache.bytes(), counted);
    assert_eq!(a.bytes(), counted);
    assert_eq!(cache.len(), 1);
    assert_eq!(cache.growing(), 0);
    // What it took is expected of the next growth of its species.
    assert_eq!(cache.expected(&key("PRCE", 9), &m), counted + counted / 16);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_bound_holds_and_what_requests_hold_is_counted() {
    let m = Database::builtin().find("InlVal", "PRCE").unwrap();
    let bound = 120 << 20;
    let cache = Arc::new(Cache::new(bound, 1));
    // A first growth is expected to take the most per age, here more than the bound: it
    // is tried at the bound.
    assert!(cache.expected(&key("PRCE", 1), &m) > bound);
    let first = cache.get(key("PRCE", 1), &m).unwrap();
    assert_eq!(
        cache.get(key("PRCE", 2), &m).err(),
        Some(Refused::Busy { growing: 1 }),
        "one growth at once"
    );
    watched(&cache, &first).await;
    let size = first.bytes();
    assert!(
        size > bound / 2,
        "each growth takes more than half the bound"
    );
    // A request still meshing age 30 of the first growth holds it.
    let kept = first.at(30).await.unwrap();
    drop(first);
    // The second growth makes room by dropping the first (no request holds it), but the
    // age the request holds stays counted until the request ends.
    let second = cache.get(key("PRCE", 2), &m).unwrap();
    assert_eq!(cache.len(), 1, "the finished growth made room");
    assert_eq!(cache.holding().in_use, kept.bytes());
    watched(&cache, &second).await;
    assert_eq!(cache.bytes(), second.bytes() + kept.bytes());
    drop(kept);
    assert_eq!(cache.bytes(), second.bytes());
    assert_eq!(cache.holding().in_use, 0);
    // While a request holds the second growth, a third cannot fit: refused, not let
    // through.
    match cache.get(key("PRCE", 3), &m) {
        Err(Refused::Full { committed, .. }) => assert_eq!(committed, second.bytes()),
        other => panic!("expected Full, got {:?}", other.map(|_| ())),
    }
    assert_eq!(cache.refusals.full.load(Ordering::Relaxed), 1);
    drop(second);
    assert!(
        cache.get(key("PRCE", 3), &m).is_ok(),
        "room once it is let go"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_species_larger_than_the_bound_is_stopped_then_refused() {
    let m = Database::builtin().find("InlVal", "PRCE").unwrap();
    let bound = 30 << 20;
    let cache = Arc::new(Cache::new(bound, 2));
    let g = cache.get(key("PRCE", 1), &m).unwrap();
    watched(&cache, &g).await;
    assert!(g.stopped() && !g.finished());
    let reached = g.all().await.len();
    assert!(reached > 5 && reached < g.ages.len(), "{reached} ages");
    assert_eq!(cache.len(), 0, "a stopped growth is let go of");
    assert_eq!(cache.refusals.stopped.load(Ordering::Relaxed), 1);
    match cache.get(key("PRCE", 1), &m) {
        Err(Refused::TooLarge { expected }) => assert!(expected > bound),
        other => panic!("expected TooLarge, got {:?}", other.map(|_| ())),
    }
    drop(g);
    assert_eq!(cache.bytes(), 0);
}
