//! Splitting an arbitrary planar curve into overlapping function segments (Han et al. §4.2).
//!
//! Han's explicit fairing works on a spline *function* y(x). An arbitrary curve is split into
//! segments whose edge directions turn by less than a limit (§4.2.1–4.2.2), each segment is
//! expressed in the frame of the angular bisector of its extreme directions, where it is a
//! function (§4.2.3, [`Frame`]), faired, moved back and blended over the overlaps (§4.2.4,
//! [`blend()`]). [`SegmentedFairing`] runs the whole loop as a [`FairingStrategy`](crate::FairingStrategy).
//!
//! **The turning angle.** Walk the points in order; edge j joins the walk's points j and
//! j + 1. α_0 = 0 and α_{j+1} = α_j + τ_j, where τ_j ∈ (−π, π] is the signed angle from edge j
//! to edge j + 1 (atan2 of their cross and dot products). So α_j is the direction of edge j
//! relative to the first edge, *unwrapped*: it is continuous along the curve and can exceed
//! ±π (a circle's α runs through 2π). The paper's range (−π/2, π/2) is that of the angles
//! measured in a segment's own frame. A segment's turning angle is max α − min α over its
//! edges; it is a function of its frame's x exactly when this is below π.
//!
//! **Partition** (§4.2.2, greedy as in the paper): a segment grows from its first point while
//! its turning angle stays strictly below [`PartitionSettings::limit`]. The next segment
//! starts `overlap` points before the end of the previous one, so that adjacent segments share
//! `overlap` points. Two refinements the paper does not need for its smooth examples: the
//! overlap is reduced (down to one shared point) when (a) the next segment could not grow past
//! the previous one (a corner sharper than the limit lies there), or (b) a point would fall in
//! three segments (segments shorter than the overlap); and a segment is shortened if rounding
//! leaves its x not strictly increasing in its frame.
//!
//! **Closed curves** (airfoils, frame sections; not in the paper): the walk starts at the
//! point of the largest turn (a natural break such as a trailing edge), goes once round, and
//! the last segment wraps over the first with the same overlap rule.
//!
//! Cost: O(n · overlap).

mod blend;
mod frame;
mod guard;
mod segmented;

pub use blend::blend;
pub use frame::Frame;
pub use guard::{curve_counts, CurveGuard, CURVE_GUARD_CHUNK, CURVE_GUARD_MARGIN};
pub use segmented::{SegmentFairer, SegmentedFairing};

use std::f64::consts::PI;

use curve_repr::Vec2;

use crate::{Error, Result};

/// Settings of [`partition`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartitionSettings {
    /// The turning-angle limit, in radians, in (0, π]: every segment turns by strictly less.
    /// Default π (Han §4.2.1). Smaller limits keep a segment's edges farther from vertical in
    /// its frame; 2π/3 behaved better in trials (papers/README.md).
    pub limit: f64,
    /// How many points adjacent segments share, at least 1. Default 5 (Han §4.2.2).
    pub overlap: usize,
}

impl Default for PartitionSettings {
    fn default() -> Self {
        Self {
            limit: Self::DEFAULT_LIMIT_DEGREES * PI / 180.0,
            overlap: 5,
        }
    }
}

impl PartitionSettings {
    /// The default turning-angle limit in degrees, 120 (2π/3 radians, the same bits): kept
    /// in degrees so that the catalogue's `turning-limit` default is 120 exactly, not the
    /// 119.99999999999999 that converting 2π/3 back gives.
    pub const DEFAULT_LIMIT_DEGREES: f64 = 120.0;

    /// The paper's partition (Han §4.2.1–4.2.2): turning limit π, overlap 5.
    pub fn paper() -> Self {
        Self {
            limit: PI,
            overlap: 5,
        }
    }

    /// Sets the turning-angle limit (radians).
    pub fn with_limit(mut self, limit: f64) -> Self {
        self.limit = limit;
        self
    }

    /// Sets the overlap (points shared by adjacent segments).
    pub fn with_overlap(mut self, overlap: usize) -> Self {
        self.overlap = overlap;
        self
    }

    /// Checks the ranges: limit in (0, π], overlap ≥ 1.
    pub fn validate(&self) -> Result<()> {
        if self.limit.is_nan() || self.limit <= 0.0 || self.limit > PI {
            return Err(Error::BadParameter {
                name: "limit",
                value: self.limit.to_string(),
                reason: "the turning-angle limit must lie in (0, π]",
            });
        }
        if self.overlap == 0 {
            return Err(Error::BadParameter {
                name: "overlap",
                value: "0".into(),
                reason: "adjacent segments must share at least one point",
            });
        }
        Ok(())
    }
}

/// One function segment of a partition.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The indices of its points, in curve order (for a closed curve they wrap past n − 1 to 0).
    pub indices: Vec<usize>,
    /// How many of its first points it shares with the previous segment (0 for the first
    /// segment of an open curve).
    pub overlap_before: usize,
    /// How many of its last points it shares with the next segment (0 for the last segment of
    /// an open curve).
    pub overlap_after: usize,
    /// Its turning angle, max α − min α over its edges (radians).
    pub turning: f64,
    /// The frame in which it is a function: x strictly increases along `indices`.
    pub frame: Frame,
}

impl Segment {
    /// The segment's points in its frame: (x, y) with x strictly increasing. O(len).
    pub fn local_points(&self, points: &[Vec2]) -> Vec<Vec2> {
        self.indices
            .iter()
            .filter_map(|&i| points.get(i))
            .map(|p| self.frame.to_local(p))
            .collect()
    }
}

/// The walk along the points: position → index, and the unwrapped edge directions α.
struct Walk<'a> {
    points: &'a [Vec2],
    /// α_j of edge j (from position j to j + 1).
    alpha: Vec<f64>,
    /// Direction of edge 0 in the original frame.
    phi0: f64,
    /// Index of the point at position 0.
    start: usize,
}

impl Walk<'_> {
    fn index(&self, position: usize) -> usize {
        (self.start + position) % self.points.len()
    }

    fn point(&self, position: usize) -> Vec2 {
        self.points
            .get(self.index(position))
            .copied()
            .unwrap_or_else(Vec2::zeros)
    }

    fn edge(&self, j: usize) -> Vec2 {
        self.point(j + 1) - self.point(j)
    }

    /// Min and max of α over edges `a..b` (positions a..=b).
    fn range(&self, a: usize, b: usize) -> (f64, f64) {
        self.alpha
            .get(a..b)
            .unwrap_or(&[])
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// The frame of positions a..=b and whether x increases strictly in it.
    fn frame(&self, a: usize, b: usize) -> (Frame, f64, bool) {
        let (lo, hi) = self.range(a, b);
        let frame = Frame::new(self.point(a), self.phi0 + 0.5 * (lo + hi));
        let mut previous = f64::NEG_INFINITY;
        let increasing = (a..=b).all(|p| {
            let x = frame.to_local(&self.point(p)).x;
            let ok = x > previous;
            previous = x;
            ok
        });
        (frame, hi - lo, increasing)
    }

    /// The longest segment from position `a` (at most to `last`) whose turning stays below
    /// `limit` and which is a function in its frame. Always at least positions a..=a+1.
    fn extend(&self, a: usize, last: usize, limit: f64) -> usize {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut b = a;
        while b < last {
            let v = self.alpha.get(b).copied().unwrap_or(0.0);
            let (nlo, nhi) = (lo.min(v), hi.max(v));
            if b > a && nhi - nlo >= limit {
                break;
            }
            lo = nlo;
            hi = nhi;
            b += 1;
        }
        while b > a + 1 && !self.frame(a, b).2 {
            b -= 1;
        }
        b
    }
}

/// Splits `points` into overlapping function segments (Han §4.2.1–4.2.3; see the module docs
/// for the definitions and the refinements). For `closed` curves the last point joins the
/// first (do not repeat the first point at the end).
///
/// Errors: bad settings; fewer than 2 points (3 for a closed curve); non-finite or repeated
/// consecutive points (a zero edge has no direction); a segment that is not a function in its
/// frame even at two points; a closed curve that does not turn enough to need two segments.
pub fn partition(points: &[Vec2], closed: bool, settings: &PartitionSettings) -> Result<Vec<Segment>> {
    settings.validate()?;
    let n = points.len();
    let needed = if closed { 3 } else { 2 };
    if n < needed {
        return Err(curve_repr::Error::TooFewPoints {
            what: "partition",
            needed,
            got: n,
        }
        .into());
    }
    curve_repr::vector::check_finite(points)?;
    let k = settings.overlap;
    // Closed: start at the largest turn; positions 0..=n+k (position n is position 0 again).
    let start = if closed { largest_turn(points) } else { 0 };
    let edges = if closed { n + k } else { n - 1 };
    let mut walk = Walk {
        points,
        alpha: Vec::with_capacity(edges),
        phi0: 0.0,
        start,
    };
    let mut previous: Option<Vec2> = None;
    let mut alpha = 0.0;
    for j in 0..edges {
        let e = walk.edge(j);
        if e.x == 0.0 && e.y == 0.0 {
            let index = walk.index(j);
            return Err(if index + 1 == n {
                curve_repr::Error::ClosingRepeat { last: index }
            } else {
                curve_repr::Error::RepeatedPoint { index }
            }
            .into());
        }
        match previous {
            None => walk.phi0 = e.y.atan2(e.x),
            Some(p) => alpha += (p.x * e.y - p.y * e.x).atan2(p.dot(&e)),
        }
        walk.alpha.push(alpha);
        previous = Some(e);
    }

    let last = if closed { n } else { n - 1 };
    let limit = settings.limit;
    // (start position, end position, overlap before) of each segment.
    let mut spans: Vec<(usize, usize, usize)> = Vec::new();
    let mut a = 0;
    let mut b = walk.extend(a, last, limit);
    spans.push((a, b, 0));
    let mut previous_end: Option<usize> = None;
    while b < last {
        let own = previous_end.map_or(b - a + 1, |pe| b - pe);
        let max_overlap = k.min(own).min(b - a).max(1);
        // Largest overlap that still lets the next segment grow past this one; overlap 1
        // (start at this segment's last point) always does, one edge turning by 0.
        let chosen = (2..=max_overlap)
            .rev()
            .map(|overlap| (b + 1 - overlap, overlap))
            .map(|(a2, overlap)| (a2, walk.extend(a2, last, limit), overlap))
            .find(|&(_, b2, _)| b2 > b)
            .unwrap_or_else(|| (b, walk.extend(b, last, limit), 1));
        previous_end = Some(b);
        (a, b) = (chosen.0, chosen.1);
        spans.push(chosen);
    }

    let mut wrap = 0;
    if closed {
        if spans.len() < 2 {
            return Err(Error::Partition {
                reason: "a closed curve that turns less than the limit".into(),
            });
        }
        let first_free = spans.get(1).map_or(0, |s| s.0);
        let (last_start, _, _) = spans.last().copied().unwrap_or((0, 0, 0));
        wrap = 1;
        for overlap in (2..=k.min(first_free)).rev() {
            let end = n + overlap - 1;
            let (_, turning, increasing) = walk.frame(last_start, end);
            if turning < limit && increasing {
                wrap = overlap;
                break;
            }
        }
        if let Some(span) = spans.last_mut() {
            span.1 = n + wrap - 1;
        }
    }

    let count = spans.len();
    let mut segments = Vec::with_capacity(count);
    for (s, &(a, b, overlap_before)) in spans.iter().enumerate() {
        let (frame, turning, increasing) = walk.frame(a, b);
        if !increasing {
            return Err(Error::Partition {
                reason: format!(
                    "points {} and {} are not a function in any frame",
                    walk.index(a),
                    walk.index(b)
                ),
            });
        }
        let overlap_after = match spans.get(s + 1) {
            Some(next) => next.2,
            None => wrap,
        };
        segments.push(Segment {
            indices: (a..=b).map(|p| walk.index(p)).collect(),
            overlap_before: if s == 0 { wrap } else { overlap_before },
            overlap_after,
            turning,
            frame,
        });
    }
    Ok(segments)
}

/// Index of the point of a closed polygon where the direction turns most. O(n).
fn largest_turn(points: &[Vec2]) -> usize {
    let n = points.len();
    let mut best = (0, f64::NEG_INFINITY);
    for i in 0..n {
        let (Some(p), Some(q), Some(r)) = (
            points.get((i + n - 1) % n),
            points.get(i),
            points.get((i + 1) % n),
        ) else {
            continue;
        };
        let (e, f) = (q - p, r - q);
        let turn = (e.x * f.y - e.y * f.x).atan2(e.dot(&f)).abs();
        if turn > best.1 {
            best = (i, turn);
        }
    }
    best.0
}
