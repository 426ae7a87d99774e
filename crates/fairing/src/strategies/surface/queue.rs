//! The order of work: a max-priority queue of grid nodes keyed by z_ij, with lazy keys.
//!
//! A key is the node's z when it was pushed; moves elsewhere change z afterwards. [`pop`]
//! (`LazyQueue::pop`) therefore re-reads the node's current z when it comes to the top and
//! puts it back if it has fallen below the next key, so nodes come off in the order of their
//! current z as far as their keys are fresh, and a caller that raises a node's z pushes it
//! again (the stale copy is skipped later). O(log K) per push and pop.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A heap entry: (z, node index), ordered by z then by the smaller index (reproducible ties).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Entry(f64, usize);

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Nodes by decreasing current z (module docs).
#[derive(Debug, Default)]
pub struct LazyQueue {
    heap: BinaryHeap<Entry>,
}

impl LazyQueue {
    /// The queue of `(z, node)` pairs. O(K).
    pub fn new(entries: impl IntoIterator<Item = (f64, usize)>) -> Self {
        Self {
            heap: entries.into_iter().map(|(z, k)| Entry(z, k)).collect(),
        }
    }

    /// Adds a node with its current z. O(log K).
    pub fn push(&mut self, z: f64, node: usize) {
        self.heap.push(Entry(z, node));
    }

    /// The node of largest current z among those `accept` lets through (others are dropped
    /// when they come to the top), re-reading z with `current` as described in the module
    /// docs; `None` when the queue runs empty.
    pub fn pop(
        &mut self,
        mut current: impl FnMut(usize) -> f64,
        mut accept: impl FnMut(usize) -> bool,
    ) -> Option<usize> {
        while let Some(Entry(key, node)) = self.heap.pop() {
            if !accept(node) {
                continue;
            }
            let now = current(node);
            if now < key {
                if let Some(next) = self.heap.peek() {
                    if now < next.0 {
                        self.heap.push(Entry(now, node));
                        continue;
                    }
                }
            }
            return Some(node);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_come_off_by_current_value_and_refused_ones_are_dropped() {
        let mut values = [5.0, 3.0, 4.0, 1.0];
        let mut queue = LazyQueue::new(values.iter().copied().zip(0..));
        // Node 0 fell to 2 after it was pushed: 2 (4.0) and 1 (3.0) come first.
        values[0] = 2.0;
        let mut order = Vec::new();
        while let Some(k) = queue.pop(|k| values[k], |k| k != 3) {
            order.push(k);
        }
        assert_eq!(order, vec![2, 1, 0]);
        assert_eq!(queue.pop(|k| values[k], |_| true), None);
        // Ties go to the smaller index.
        let mut queue = LazyQueue::new([(1.0, 4), (1.0, 2)]);
        assert_eq!(queue.pop(|_| 1.0, |_| true), Some(2));
    }
}
