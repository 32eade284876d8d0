//! Bytes counted where they live: a [`Held`] value adds its size to a [`Ledger`] when it is
//! made and takes it off when the last holder drops it, so the ledger reads what is alive,
//! wherever it is held: in the cache, or by a request still meshing a tree the cache has
//! since let go of.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Live bytes of every [`Held`] value made against it.
#[derive(Debug, Default)]
pub struct Ledger {
    live: AtomicUsize,
}

impl Ledger {
    /// Bytes alive now.
    pub fn bytes(&self) -> usize {
        self.live.load(Ordering::Relaxed)
    }
}

/// A value whose bytes the ledger counts while it lives.
#[derive(Debug)]
pub struct Held<T> {
    value: T,
    bytes: usize,
    ledger: Arc<Ledger>,
}

impl<T> Held<T> {
    /// Counts `bytes` for `value` until it is dropped.
    pub fn new(value: T, bytes: usize, ledger: &Arc<Ledger>) -> Held<T> {
        ledger.live.fetch_add(bytes, Ordering::Relaxed);
        Held {
            value,
            bytes,
            ledger: ledger.clone(),
        }
    }

    /// The bytes counted for it.
    pub fn bytes(&self) -> usize {
        self.bytes
    }
}

impl<T> std::ops::Deref for Held<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.value
    }
}

impl<T> Drop for Held<T> {
    fn drop(&mut self) {
        self.ledger.live.fetch_sub(self.bytes, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_is_counted_until_its_last_holder_drops_it() {
        let ledger = Arc::new(Ledger::default());
        let a = Arc::new(Held::new(vec![1u8; 10], 10, &ledger));
        let b = Held::new("x", 5, &ledger);
        assert_eq!(ledger.bytes(), 15);
        let copy = a.clone();
        drop(a);
        assert_eq!(ledger.bytes(), 15, "still held by the copy");
        assert_eq!(copy.len(), 10);
        drop(copy);
        drop(b);
        assert_eq!(ledger.bytes(), 0);
    }
}
