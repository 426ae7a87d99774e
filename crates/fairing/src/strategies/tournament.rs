//! A tournament (winner) tree: the candidate of the largest value, on a tie the smallest
//! index, kept under changes of a few values in O(log n) each. Shared by the strain-energy
//! automatic mode (its worst point) and Sapidis–Farin (its knot of the largest jump).

use std::cmp::Ordering;

/// The candidate of the largest z, kept as a tournament (winner) tree over the points (first
/// written for the strain-energy automatic mode's worst point): every leaf is a point that
/// can still move (or none), every inner node the winner
/// of its two children, the larger z by [`f64::total_cmp`] and on a tie the smaller index,
/// so the root is the point a full scan of z would pick (the order a max-heap of (z, index)
/// gives; the lazy heap it replaces gave the same). A refresh that changed z over a run of
/// points replays the matches above them only: O(run + log n), where the heap took a push
/// per changed z and skipped the stale entries at every pop.
#[derive(Clone, Debug, Default)]
pub(crate) struct Tournament {
    /// Leaves: a power of two ≥ the number of points.
    leaves: usize,
    /// Node v's winner (a point index, or [`Tournament::NONE`]); the root is node 1, the
    /// leaf of point k node `leaves + k`.
    nodes: Vec<usize>,
}

impl Tournament {
    const NONE: usize = usize::MAX;

    /// A tree whose candidates are the points k with `!blocked[k]`. O(n).
    pub(crate) fn new(z: &[f64], blocked: &[bool]) -> Self {
        let leaves = z.len().next_power_of_two();
        let mut nodes = vec![Self::NONE; 2 * leaves];
        for (k, &b) in blocked.iter().enumerate().take(z.len()) {
            if !b {
                nodes[leaves + k] = k;
            }
        }
        let mut tree = Self { leaves, nodes };
        if !z.is_empty() {
            tree.replay(z, 0, z.len() - 1);
        }
        tree
    }

    /// The winner of two nodes' winners.
    fn winner(z: &[f64], a: usize, b: usize) -> usize {
        if a == Self::NONE {
            return b;
        }
        if b == Self::NONE {
            return a;
        }
        match z[a].total_cmp(&z[b]) {
            Ordering::Greater => a,
            Ordering::Less => b,
            Ordering::Equal => a.min(b),
        }
    }

    /// Replays the matches above the leaves of points `first..=last` (after their z or
    /// candidacy changed). O(last − first + log n).
    pub(crate) fn replay(&mut self, z: &[f64], first: usize, last: usize) {
        if self.leaves == 0 {
            return;
        }
        let last = last.min(self.leaves - 1);
        if last < first {
            return;
        }
        let (mut lo, mut hi) = ((self.leaves + first) / 2, (self.leaves + last) / 2);
        while lo >= 1 {
            for v in lo..=hi {
                self.nodes[v] = Self::winner(z, self.nodes[2 * v], self.nodes[2 * v + 1]);
            }
            (lo, hi) = (lo / 2, hi / 2);
        }
    }

    /// Makes point k a candidate or not without replaying the matches above it: the caller
    /// replays a range holding k before the next [`Tournament::best`]. O(1).
    pub(crate) fn mark(&mut self, k: usize, candidate: bool) {
        if let Some(leaf) = self.nodes.get_mut(self.leaves + k) {
            *leaf = if candidate { k } else { Self::NONE };
        }
    }

    /// Makes point k a candidate or not. O(log n).
    pub(crate) fn set_candidate(&mut self, z: &[f64], k: usize, candidate: bool) {
        if let Some(leaf) = self.nodes.get_mut(self.leaves + k) {
            *leaf = if candidate { k } else { Self::NONE };
            self.replay(z, k, k);
        }
    }

    /// The candidate of the largest z (the smallest index among equals), if any. O(1).
    pub(crate) fn best(&self) -> Option<usize> {
        self.nodes.get(1).copied().filter(|&k| k != Self::NONE)
    }
}
