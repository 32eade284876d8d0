//! The last files sent, kept within a byte bound, oldest dropped first: a tree's GLB is
//! meshed once however often the page's slider comes back to its age.

use axum::body::Bytes;
use std::collections::VecDeque;
use std::sync::Mutex;

/// Files by name, most recent last.
pub struct Recent {
    bound: usize,
    held: Mutex<(VecDeque<(String, Bytes)>, usize)>,
}

impl Recent {
    /// Keeps at most `bound` bytes.
    pub fn new(bound: usize) -> Recent {
        Recent {
            bound,
            held: Mutex::new((VecDeque::new(), 0)),
        }
    }

    /// The file kept under `name`, if any (it becomes the most recent).
    pub fn get(&self, name: &str) -> Option<Bytes> {
        let mut held = self.held.lock().unwrap_or_else(|e| e.into_inner());
        let at = held.0.iter().position(|(n, _)| n == name)?;
        let item = held.0.remove(at)?;
        let bytes = item.1.clone();
        held.0.push_back(item);
        Some(bytes)
    }

    /// Keeps `bytes` under `name`, dropping the oldest files past the bound. A file larger
    /// than the bound is not kept.
    pub fn put(&self, name: String, bytes: Bytes) {
        if bytes.len() > self.bound {
            return;
        }
        let mut held = self.held.lock().unwrap_or_else(|e| e.into_inner());
        held.1 += bytes.len();
        held.0.push_back((name, bytes));
        while held.1 > self.bound {
            let Some((_, old)) = held.0.pop_front() else {
                break;
            };
            held.1 -= old.len();
        }
    }

    /// The most bytes it keeps.
    pub fn bound(&self) -> usize {
        self.bound
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.held.lock().unwrap_or_else(|e| e.into_inner()).1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_oldest_go_first_and_a_read_counts_as_use() {
        let r = Recent::new(10);
        r.put("a".into(), Bytes::from_static(b"1234"));
        r.put("b".into(), Bytes::from_static(b"1234"));
        assert!(r.get("a").is_some());
        r.put("c".into(), Bytes::from_static(b"1234"));
        assert!(r.get("b").is_none(), "b was the least recently used");
        assert_eq!(r.get("a").as_deref(), Some(&b"1234"[..]));
        assert_eq!(r.bytes(), 8);
        r.put("big".into(), Bytes::from_static(b"12345678901"));
        assert!(r.get("big").is_none(), "larger than the bound");
    }
}
