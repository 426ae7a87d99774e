//! Consecutive points averaged in bins: the partition that two-phase's binned noise pre-pass
//! ([`crate::two_phase::bins`]'s module doc says why and how many) and jump-lsq's reduced
//! basis beyond its limit of points (`strategies::jump_lsq`'s `reduced` module) both fit
//! their means on. Building the bins and their means is O(n).

use std::ops::Range;

/// A partition of 0..n into runs of consecutive indices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Bins {
    /// Bin b is `bounds[b]..bounds[b + 1]`.
    bounds: Vec<usize>,
}

impl Bins {
    /// Bins of n points, about `size` points each, every point `keep` says alone: each run
    /// between kept points of L points makes ⌈L/size⌉ bins, equal in size to within one point.
    /// O(n).
    pub(crate) fn new(n: usize, size: usize, keep: &dyn Fn(usize) -> bool) -> Self {
        let size = size.max(1);
        let mut bounds = vec![0];
        let mut run_start = 0;
        let close_run = |bounds: &mut Vec<usize>, start: usize, end: usize| {
            let length = end - start;
            let count = length.div_ceil(size);
            for j in 1..=count {
                bounds.push(start + j * length / count);
            }
        };
        for i in 0..n {
            if keep(i) {
                close_run(&mut bounds, run_start, i);
                bounds.push(i + 1);
                run_start = i + 1;
            }
        }
        close_run(&mut bounds, run_start, n);
        Bins { bounds }
    }

    /// The number of bins.
    pub(crate) fn len(&self) -> usize {
        self.bounds.len() - 1
    }

    /// The indices of bin b.
    pub(crate) fn range(&self, b: usize) -> Range<usize> {
        self.bounds[b]..self.bounds[b + 1]
    }

    /// The mean of `values` over each bin. O(n).
    pub(crate) fn means(&self, values: &[f64]) -> Vec<f64> {
        (0..self.len())
            .map(|b| {
                let range = self.range(b);
                let count = range.len() as f64;
                values[range].iter().sum::<f64>() / count
            })
            .collect()
    }

    /// The mean index (start + end − 1)/2 of bin b: where its mean sits along the points.
    pub(crate) fn centre(&self, b: usize) -> f64 {
        let range = self.range(b);
        (range.start + range.end - 1) as f64 / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_cover_every_point_once_in_order_and_kept_points_are_alone() {
        let kept = [0usize, 7, 8, 30, 99];
        let keep = |i: usize| kept.contains(&i);
        let bins = Bins::new(100, 4, &keep);
        let mut next = 0;
        for b in 0..bins.len() {
            let range = bins.range(b);
            assert_eq!(range.start, next, "bin {b} starts where the last ended");
            assert!(!range.is_empty(), "bin {b} is empty");
            assert!(range.len() <= 4, "bin {b} has {} points", range.len());
            if range.clone().any(keep) {
                assert_eq!(range.len(), 1, "kept point shares bin {b}");
            }
            next = range.end;
        }
        assert_eq!(next, 100);
        // The run 9..30 (21 points) makes ⌈21/4⌉ = 6 bins of 3 or 4 points.
        let run: Vec<usize> = (0..bins.len())
            .map(|b| bins.range(b))
            .filter(|r| r.start >= 9 && r.end <= 30)
            .map(|r| r.len())
            .collect();
        assert_eq!(run.len(), 6);
        assert!(run.iter().all(|&l| l == 3 || l == 4), "{run:?}");
        let values: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let means = bins.means(&values);
        for (b, mean) in means.iter().enumerate() {
            let range = bins.range(b);
            assert_eq!(*mean, (range.start + range.end - 1) as f64 / 2.0);
        }
    }
}
