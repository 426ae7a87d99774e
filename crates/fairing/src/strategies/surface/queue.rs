//! The order of work: max-priority queues of grid nodes keyed by z_ij, with lazy keys.
//!
//! A key is the node's z when it was pushed; moves elsewhere change z afterwards. A pop
//! therefore re-reads the node's current z when it comes to the top and puts it back if it
//! has fallen below the next key, so nodes come off in the order of their current z as far
//! as their keys are fresh, and a caller that raises a node's z pushes it again (the stale
//! copy is skipped later). O(log K) per push and pop.
//!
//! - [`LazyQueue`] (Kjellander): the caller refreshes the keys of the nodes next to a move.
//! - [`SweepQueue`] (the automatic mode's `order = queue`): every node once per step, each
//!   time the one of largest *current* z; an indexed heap whose keys are raised in place for
//!   exactly the nodes a move raised, so a pop is always the node a full rescan would choose
//!   (ties: smaller index).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::network::Network;

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
pub(super) struct LazyQueue {
    heap: BinaryHeap<Entry>,
}

impl LazyQueue {
    /// The queue of `(z, node)` pairs. O(K).
    pub(super) fn new(entries: impl IntoIterator<Item = (f64, usize)>) -> Self {
        Self {
            heap: entries.into_iter().map(|(z, k)| Entry(z, k)).collect(),
        }
    }

    /// Adds a node with its current z. O(log K).
    pub(super) fn push(&mut self, z: f64, node: usize) {
        self.heap.push(Entry(z, node));
    }

    /// The node of largest current z among those `accept` lets through (others are dropped
    /// when they come to the top), re-reading z with `current` as described in the module
    /// docs; `None` when the queue runs empty.
    pub(super) fn pop(
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

/// The automatic mode's queue: every candidate node once, largest current z first.
///
/// An indexed binary heap (one entry per node, its position kept) with lazy keys.
/// Invariant: every node still to come has a key at least its current z. Then the root,
/// once its key is set to its current z and it stays the root, has the largest z of all
/// nodes to come (every other z is at most its key, at most the root's), which is what a
/// full rescan finds. A move of P_ij changes z only on the nodes of [`Network::affected`];
/// for those whose z bound passes their key the z is computed and, when it passes the key,
/// the key is raised in place (sift up). O(K) to build, O(log K) a pop, O(window) a move
/// plus O(log K) per raised node (usually O(1): a small rise climbs few levels).
#[derive(Debug)]
pub(super) struct SweepQueue {
    /// Nodes in heap order.
    heap: Vec<usize>,
    /// Each node's position in `heap` (`usize::MAX`: not in the queue).
    position: Vec<usize>,
    /// Each node's key.
    keys: Vec<f64>,
    buffer: Vec<usize>,
}

impl SweepQueue {
    /// The queue of `members` (flat indices into the network's nodes, each once) keyed by
    /// their current z. O(K).
    pub(super) fn new(network: &Network, members: impl IntoIterator<Item = usize>) -> Self {
        let total = network.points().len();
        let mut queue = Self {
            heap: members.into_iter().collect(),
            position: vec![usize::MAX; total],
            keys: vec![f64::NEG_INFINITY; total],
            buffer: Vec::new(),
        };
        for (p, &k) in queue.heap.iter().enumerate() {
            queue.position[k] = p;
            queue.keys[k] = network.z_at(k);
        }
        for p in (0..queue.heap.len() / 2).rev() {
            queue.sift_down(p);
        }
        queue
    }

    /// Whether node a comes before node b: larger key, ties to the smaller index.
    fn before(&self, a: usize, b: usize) -> bool {
        match self.keys[a].total_cmp(&self.keys[b]) {
            Ordering::Greater => true,
            Ordering::Less => false,
            Ordering::Equal => a < b,
        }
    }

    fn place(&mut self, p: usize, node: usize) {
        self.heap[p] = node;
        self.position[node] = p;
    }

    fn sift_up(&mut self, mut p: usize) {
        let node = self.heap[p];
        while p > 0 {
            let parent = (p - 1) / 2;
            if !self.before(node, self.heap[parent]) {
                break;
            }
            self.place(p, self.heap[parent]);
            p = parent;
        }
        self.place(p, node);
    }

    fn sift_down(&mut self, mut p: usize) {
        let node = self.heap[p];
        let len = self.heap.len();
        loop {
            let mut child = 2 * p + 1;
            if child >= len {
                break;
            }
            if child + 1 < len && self.before(self.heap[child + 1], self.heap[child]) {
                child += 1;
            }
            if !self.before(self.heap[child], node) {
                break;
            }
            self.place(p, self.heap[child]);
            p = child;
        }
        self.place(p, node);
    }

    /// The node to come with the largest current z (ties: smaller index), taken off the
    /// queue; `None` when every member has come.
    pub(super) fn pop(&mut self, network: &Network) -> Option<usize> {
        loop {
            let &top = self.heap.first()?;
            let z = network.z_at(top);
            if z < self.keys[top] {
                // Fell since keyed: key it exactly, and it stays on top only if still largest.
                self.keys[top] = z;
                self.sift_down(0);
                if self.heap[0] != top {
                    continue;
                }
            }
            let last = self.heap.pop()?;
            self.position[top] = usize::MAX;
            if last != top {
                self.place(0, last);
                self.sift_down(0);
            }
            return Some(top);
        }
    }

    /// After P_ij moved (or a move was tried and undone): raises the keys of the nodes still
    /// to come whose z the move raised above their key. O(window).
    pub(super) fn moved(&mut self, network: &mut Network, i: usize, j: usize) {
        let mut buffer = std::mem::take(&mut self.buffer);
        network.affected(i, j, &mut buffer);
        for &k in &buffer {
            let p = self.position[k];
            if p != usize::MAX && network.z_bound(k) > self.keys[k] {
                let z = network.tighten(k);
                if z > self.keys[k] {
                    self.keys[k] = z;
                    self.sift_up(p);
                }
            }
        }
        self.buffer = buffer;
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
