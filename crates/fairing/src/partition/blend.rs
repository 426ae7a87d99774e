//! Blending of overlapping segments (Han et al. §4.2.4).
//!
//! The paper blends "the overlapped part ... by its two adjacent faired segments" without a
//! formula. Choice made here: linear weights that ramp over the overlap. If segments s and
//! s + 1 share m points, the j-th of them (j = 0..m−1, along the curve) takes weight
//! (j + 1)/(m + 1) from segment s + 1 and (m − j)/(m + 1) from segment s: the weights sum to
//! one, never reach 0 or 1 inside the overlap, and a point shared by one junction point only
//! (m = 1) takes the mean. Segments are blended as DISPLACEMENTS added to the current points,
//! so an unchanged segmentation reproduces its input bit for bit.

use curve_repr::Vec2;

use super::Segment;
use crate::{Error, Result};

impl Segment {
    /// The blending weight of the segment's `j`-th point (see the module docs); 1 outside the
    /// overlaps, 0 for `j` beyond the segment.
    pub fn blend_weight(&self, j: usize) -> f64 {
        let len = self.indices.len();
        if j >= len {
            return 0.0;
        }
        let mut weight = 1.0;
        if j < self.overlap_before {
            weight *= (j + 1) as f64 / (self.overlap_before + 1) as f64;
        }
        let after_start = len.saturating_sub(self.overlap_after);
        if j >= after_start {
            let k = j - after_start;
            weight *= (self.overlap_after - k) as f64 / (self.overlap_after + 1) as f64;
        }
        weight
    }
}

/// Blends per-segment displacements into one displacement per point.
///
/// `displacements[s][j]` is the move segment `s` proposes for its `j`-th point. The result at
/// point i is Σ_s w_s d_s / Σ_s w_s over the segments holding i (weights of
/// [`Segment::blend_weight`]); a point no segment holds gets zero. O(total segment length).
///
/// Errors: a displacement list whose length differs from its segment's, an index ≥ `n`.
pub fn blend(n: usize, segments: &[Segment], displacements: &[Vec<Vec2>]) -> Result<Vec<Vec2>> {
    if segments.len() != displacements.len() {
        return Err(curve_repr::Error::LengthMismatch {
            what: "segment displacements",
            expected: segments.len(),
            got: displacements.len(),
        }
        .into());
    }
    let mut sum = vec![Vec2::zeros(); n];
    let mut weight = vec![0.0; n];
    for (segment, moves) in segments.iter().zip(displacements) {
        if moves.len() != segment.indices.len() {
            return Err(curve_repr::Error::LengthMismatch {
                what: "displacements of a segment",
                expected: segment.indices.len(),
                got: moves.len(),
            }
            .into());
        }
        for (j, (&i, d)) in segment.indices.iter().zip(moves).enumerate() {
            let (Some(s), Some(w)) = (sum.get_mut(i), weight.get_mut(i)) else {
                return Err(Error::Partition {
                    reason: format!("segment index {i} out of range for {n} points"),
                });
            };
            let wj = segment.blend_weight(j);
            *s += d * wj;
            *w += wj;
        }
    }
    Ok(sum
        .into_iter()
        .zip(weight)
        .map(|(s, w)| if w > 0.0 { s / w } else { Vec2::zeros() })
        .collect())
}
