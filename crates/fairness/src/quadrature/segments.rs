//! The adaptive G7K15 engine behind [`Adaptive`]: several integrands at once over the same
//! intervals, initial intervals chosen by the caller (each optionally integrated after a sinh
//! change of variable), run sequentially ([`estimate_many`]) or over rayon's threads
//! ([`estimate_many_parallel`]) with results that are bit for bit the same either way.
//!
//! Speed: the integrands are asked for the 15 nodes of a rule at once ([`NodeIntegrands`]),
//! so that a curve's integrand is one loop the compiler vectorises; a mapped interval's nodes
//! cost one exp (none for the core panels, whose centres repeat); pass 1 keeps no interval
//! unless its totals miss the tolerance. On a noisy 10⁶-point spline function that takes less
//! than half the CPU and a fraction of the memory of one integrand call per node with every
//! interval stored.
//!
//! Determinism: every interval's G7K15 result depends on that interval alone, intervals are
//! kept in an order fixed by the pieces (never by which thread finished first), pass 1 runs
//! over fixed chunks of [`CHUNK`] pieces whose partial sums are merged in chunk order, and the
//! refinement's sums run sequentially in interval order. The thread count changes nothing.

use rayon::prelude::*;

use super::{check_breaks, Adaptive, CompensatedSum, Estimate, SUBDIVISIONS_PER_PIECE};
use super::{GAUSS7_WEIGHTS, KRONROD_NODES, KRONROD_WEIGHTS};
use crate::{Error, Result};

/// Pieces per pass-1 chunk: fixed, so that the merge order, and hence every bit of the result,
/// does not depend on the number of threads.
const CHUNK: usize = 1024;

/// The initial intervals of a [`SinhMap`]ped segment in s: [k, k + 1]·`SINH_PANEL` in the
/// core |s| ≤ [`SINH_CORE`], then tails of at most [`SINH_TAIL`]. In s a Lorentzian peak of
/// width w (a pair of poles at centre ± iw) becomes a bump whose poles sit at ±iπ/2: on a
/// core interval of half-length ¼ the G7 rule converges like 12.6⁻¹⁴ ≈ 4·10⁻¹⁶ (6.4⁻¹⁴ ≈
/// 5·10⁻¹² at half-length ½, but (dκ/ds)²|C′| has poles of order 10 there and missed 10⁻⁸
/// shares on half of its panels). Beyond |s| = 3 the curvature integrands have fallen by
/// e⁻¹² (κ²|C′| decays like cosh⁻⁴ s, (dκ/ds)²|C′| faster): the tails need little relative
/// accuracy. Measured on a noisy 10⁶-point spline function (one peak in 90 % of its pieces):
/// 14 initial intervals per piece and no refinement at all, against 7 and 2.4·10⁶
/// bisections with panels of 1 and tails of 8 — 5 % more CPU, a third of the memory.
pub const SINH_PANEL: f64 = 0.5;

/// The half-width in s of the core of a mapped segment (see [`SINH_PANEL`]).
pub const SINH_CORE: f64 = 3.0;

/// The longest initial interval in s of a mapped segment's tails (see [`SINH_PANEL`]).
pub const SINH_TAIL: f64 = 3.0;

/// The initial cuts in s of a mapped segment over [s0, s1] (s0 < s1), pushed in increasing
/// order with s1 last: [`SINH_PANEL`] steps in the core, [`SINH_TAIL`] steps beyond it.
fn sinh_cuts(s0: f64, s1: f64, cuts: &mut Vec<f64>) {
    cuts.clear();
    let mut push = |s: f64| {
        if s > s0 && s < s1 {
            cuts.push(s);
        }
    };
    let core = (SINH_CORE / SINH_PANEL).round() as i32;
    let mut s = -SINH_CORE - SINH_TAIL;
    while s > s0 {
        s -= SINH_TAIL;
    }
    while s < -SINH_CORE {
        push(s);
        s += SINH_TAIL;
    }
    for k in -core..=core {
        push(k as f64 * SINH_PANEL);
    }
    let mut s = SINH_CORE + SINH_TAIL;
    while s < s1 {
        push(s);
        s += SINH_TAIL;
    }
    cuts.push(s1);
}

/// A change of variable u = centre + width · sinh(s) (width > 0; u the piece's local
/// parameter): a peak of the integrand of half-width `width` at `centre`, and the slowly decaying flanks on either side, become a
/// smooth function of s over a range of about 2 ln(2ℓ/width) for an interval of length ℓ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SinhMap {
    /// Where the peak is.
    pub centre: f64,
    /// Its half-width (the distance of the integrand's poles from the real axis).
    pub width: f64,
}

impl SinhMap {
    /// u(s).
    pub fn t(&self, s: f64) -> f64 {
        self.centre + self.width * s.sinh()
    }

    /// s(u), the inverse of [`t`](Self::t).
    pub fn s(&self, t: f64) -> f64 {
        ((t - self.centre) / self.width).asinh()
    }
}

/// An initial interval [start, end] of one piece, in the piece's local parameter u = t − tᵢ
/// (0 at the piece's start tᵢ), integrated in u or, with `map`, in s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Where it starts.
    pub start: f64,
    /// Where it ends.
    pub end: f64,
    /// The change of variable, if any.
    pub map: Option<SinhMap>,
}

impl Segment {
    /// Segments covering [start, end] around the peaks `(centre, width)` (centres inside
    /// [start, end], any order): one per peak, each mapped around its own peak, meeting
    /// half-way between consecutive centres; one plain segment when there is no peak. The
    /// peaks are sorted in place.
    pub fn around_peaks(start: f64, end: f64, peaks: &mut [(f64, f64)], out: &mut Vec<Segment>) {
        peaks.sort_by(|a, b| a.0.total_cmp(&b.0));
        if peaks.is_empty() {
            out.push(Segment {
                start,
                end,
                map: None,
            });
            return;
        }
        let mut left = start;
        for (k, &(centre, width)) in peaks.iter().enumerate() {
            let right = match peaks.get(k + 1) {
                Some(next) => (0.5 * (centre + next.0)).clamp(left, end),
                None => end,
            };
            if right > left {
                out.push(Segment {
                    start: left,
                    end: right,
                    map: Some(SinhMap { centre, width }),
                });
            }
            left = right;
        }
    }
}

/// An interval of the adaptive rule with its G7K15 results, in its segment's variable.
#[derive(Clone, Copy, Debug)]
struct Interval<const K: usize> {
    piece: u32,
    depth: u32,
    start: f64,
    end: f64,
    map: Option<SinhMap>,
    /// Its length in t (for the share of the tolerance).
    span: f64,
    value: [f64; K],
    error: [f64; K],
}

/// The number of nodes of one G7K15 rule: the integrands are asked for all of them at once
/// ([`estimate_many_nodes`]), so that they can be computed in one loop the compiler
/// vectorises.
pub const KRONROD_POINTS: usize = 15;

/// The nodes of a G7K15 rule in the order the integrands receive them: the centre, then for
/// each Kronrod abscissa xⱼ (j = 0 … 6, outermost first) the pair centre − xⱼ·half,
/// centre + xⱼ·half.
fn node_offsets() -> [f64; KRONROD_POINTS] {
    let mut out = [0.0; KRONROD_POINTS];
    for j in 0..7 {
        out[1 + 2 * j] = -KRONROD_NODES[j];
        out[2 + 2 * j] = KRONROD_NODES[j];
    }
    out
}

/// e^(half·xⱼ) for the nodes of [`node_offsets`], and sinh(half), cached for the last `half`
/// asked, and e^mid for recent interval centres: the core panels of every mapped segment
/// have the same half-length and centres on the same grid (k + ½)·[`SINH_PANEL`], so that
/// they need no exp at all. A cached value is the exp of exactly that argument: caching
/// changes no bit of a result.
struct ExpTable {
    half: f64,
    factors: [f64; KRONROD_POINTS],
    sinh_half: f64,
    centres: [(f64, f64); CENTRE_SLOTS],
}

/// Slots of [`ExpTable`]'s centre cache, indexed by round(4·mid) mod 32: distinct for the core
/// panels' centres ±¼, ±¾, … ±2¾ (round(4·mid) = ±1, ±3, … ±11).
const CENTRE_SLOTS: usize = 32;

impl ExpTable {
    fn new() -> Self {
        ExpTable {
            half: f64::NAN,
            factors: [1.0; KRONROD_POINTS],
            sinh_half: 0.0,
            centres: [(f64::NAN, f64::NAN); CENTRE_SLOTS],
        }
    }

    /// e^mid, from the cache when mid was asked last in its slot.
    fn exp(&mut self, mid: f64) -> f64 {
        let slot = ((4.0 * mid).round() as i64).rem_euclid(CENTRE_SLOTS as i64) as usize;
        let (key, value) = self.centres[slot];
        if key == mid {
            return value;
        }
        let value = mid.exp();
        self.centres[slot] = (mid, value);
        value
    }

    /// (the factors, sinh(half)).
    fn factors(&mut self, half: f64) -> (&[f64; KRONROD_POINTS], f64) {
        if half != self.half {
            let offsets = node_offsets();
            for (factor, x) in self.factors.iter_mut().zip(offsets) {
                *factor = (half * x).exp();
            }
            self.sinh_half = half.sinh();
            self.half = half;
        }
        (&self.factors, self.sinh_half)
    }
}

/// The K integrands on the [`KRONROD_POINTS`] nodes `u` (in the piece's local parameter) of
/// piece `piece`: `out[k][i]` = f_k(piece, `u[i]`). What [`estimate_many_nodes`] integrates.
pub trait NodeIntegrands<const K: usize> {
    /// Fills `out`.
    fn eval(&mut self, piece: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]);
}

impl<const K: usize, F: FnMut(usize, &[f64; KRONROD_POINTS], &mut [[f64; KRONROD_POINTS]; K])>
    NodeIntegrands<K> for F
{
    fn eval(&mut self, piece: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]) {
        self(piece, u, out)
    }
}

/// A pointwise integrand f(piece, u) → [f64; K] as a [`NodeIntegrands`].
struct Pointwise<F>(F);

impl<const K: usize, F: FnMut(usize, f64) -> [f64; K]> NodeIntegrands<K> for Pointwise<F> {
    fn eval(&mut self, piece: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]) {
        for (i, &u) in u.iter().enumerate() {
            let values = (self.0)(piece, u);
            for k in 0..K {
                out[k][i] = values[k];
            }
        }
    }
}

/// One G7K15 evaluation of the K integrands on [a, b] of `map`'s variable (t itself without
/// one), each value times dt/ds: (Kronrod estimates, |K15 − G7|, the interval's length in t).
/// A non-finite value is [`Error::NonFinite`] at the first such node (centre first, then
/// outward pairs).
fn kronrod<const K: usize, F: NodeIntegrands<K>>(
    what: [&'static str; K],
    f: &mut F,
    exps: &mut ExpTable,
    (piece, origin): (usize, f64),
    map: Option<SinhMap>,
    a: f64,
    b: f64,
) -> Result<([f64; K], [f64; K], f64)> {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    let offsets = node_offsets();
    let mut t = [0.0; KRONROD_POINTS];
    let mut jacobian = [1.0; KRONROD_POINTS];
    let span = match map {
        None => {
            for (t, x) in t.iter_mut().zip(offsets) {
                *t = mid + half * x;
            }
            b - a
        }
        Some(m) => {
            // u = c + w sinh(s), du/ds = w cosh(s), with e^s = e^mid · e^(half·xⱼ); the length
            // in t is w (sinh b − sinh a) = 2w cosh(mid) sinh(half).
            let centre = exps.exp(mid);
            let (factors, sinh_half) = exps.factors(half);
            for i in 0..KRONROD_POINTS {
                let e = centre * factors[i];
                let inverse = 1.0 / e;
                t[i] = m.centre + m.width * 0.5 * (e - inverse);
                jacobian[i] = m.width * 0.5 * (e + inverse);
            }
            m.width * (centre + 1.0 / centre) * sinh_half
        }
    };
    let mut values = [[0.0; KRONROD_POINTS]; K];
    f.eval(piece, &t, &mut values);
    for i in 0..KRONROD_POINTS {
        for k in 0..K {
            let v = values[k][i] * jacobian[i];
            if !v.is_finite() {
                return Err(Error::NonFinite {
                    what: what[k],
                    parameter: origin + t[i],
                });
            }
            values[k][i] = v;
        }
    }
    let mut kronrod = [0.0; K];
    let mut error = [0.0; K];
    for k in 0..K {
        let v = &values[k];
        let mut sum_k = KRONROD_WEIGHTS[7] * v[0];
        let mut sum_g = GAUSS7_WEIGHTS[3] * v[0];
        for j in 0..7 {
            let pair = v[1 + 2 * j] + v[2 + 2 * j];
            sum_k += KRONROD_WEIGHTS[j] * pair;
            if j % 2 == 1 {
                sum_g += GAUSS7_WEIGHTS[j / 2] * pair;
            }
        }
        kronrod[k] = sum_k * half;
        error[k] = (kronrod[k] - sum_g * half).abs();
    }
    Ok((kronrod, error, span))
}

fn new_interval<const K: usize, F: NodeIntegrands<K>>(
    what: [&'static str; K],
    f: &mut F,
    exps: &mut ExpTable,
    (piece, origin): (usize, f64),
    map: Option<SinhMap>,
    (start, end): (f64, f64),
    depth: u32,
) -> Result<Interval<K>> {
    let (value, error, span) = kronrod(what, f, exps, (piece, origin), map, start, end)?;
    Ok(Interval {
        piece: piece as u32,
        depth,
        start,
        end,
        map,
        span,
        value,
        error,
    })
}

/// The two halves of an interval.
fn bisect<const K: usize, F: NodeIntegrands<K>>(
    what: [&'static str; K],
    f: &mut F,
    exps: &mut ExpTable,
    breaks: &[f64],
    interval: &Interval<K>,
) -> Result<[Interval<K>; 2]> {
    let mid = 0.5 * (interval.start + interval.end);
    let piece = (interval.piece as usize, breaks[interval.piece as usize]);
    let depth = interval.depth + 1;
    Ok([
        new_interval(what, f, exps, piece, interval.map, (interval.start, mid), depth)?,
        new_interval(what, f, exps, piece, interval.map, (mid, interval.end), depth)?,
    ])
}

/// The sums of pass 1 (one G7K15 per initial interval) over some pieces, and the intervals
/// that may need refining.
struct Pass1<const K: usize> {
    value: [CompensatedSum; K],
    error: [CompensatedSum; K],
    magnitude: [f64; K],
    length: f64,
    early_value: [CompensatedSum; K],
    early_error: [CompensatedSum; K],
    level: Vec<Interval<K>>,
    /// Whether the intervals that may need refining are kept in `level` (else only summed).
    keep: bool,
    /// Scratch: the cuts of the current segment.
    cuts: Vec<f64>,
    /// Scratch: the node factors of mapped intervals.
    exps: ExpTable,
}

impl<const K: usize> Pass1<K> {
    fn new(capacity: usize, keep: bool) -> Self {
        Pass1 {
            value: [CompensatedSum::default(); K],
            error: [CompensatedSum::default(); K],
            magnitude: [0.0; K],
            length: 0.0,
            early_value: [CompensatedSum::default(); K],
            early_error: [CompensatedSum::default(); K],
            level: Vec::with_capacity(if keep { capacity } else { 0 }),
            keep,
            cuts: Vec::new(),
            exps: ExpTable::new(),
        }
    }

    /// The initial intervals of piece `piece` = [start, end]: `segments` (local, clipped to
    /// [0, end − start]; the whole piece when empty), each mapped one cut in s as
    /// [`SINH_PANEL`] says.
    #[allow(clippy::too_many_arguments)]
    fn piece<F: NodeIntegrands<K>>(
        &mut self,
        settings: &[Adaptive; K],
        what: [&'static str; K],
        f: &mut F,
        piece: usize,
        (start, end): (f64, f64),
        segments: &[Segment],
    ) -> Result<()> {
        if end <= start {
            return Ok(());
        }
        let origin = start;
        let (start, end) = (0.0, end - start);
        let whole = [Segment {
            start,
            end,
            map: None,
        }];
        let segments = if segments.is_empty() { &whole[..] } else { segments };
        for segment in segments {
            let (a, b) = (segment.start.max(start), segment.end.min(end));
            if b <= a {
                continue;
            }
            let (s0, s1) = match segment.map {
                None => (a, b),
                Some(m) => (m.s(a), m.s(b)),
            };
            if s1 <= s0 {
                continue;
            }
            match segment.map {
                None => {
                    self.cuts.clear();
                    self.cuts.push(s1);
                }
                Some(_) => sinh_cuts(s0, s1, &mut self.cuts),
            }
            let mut left = s0;
            for index in 0..self.cuts.len() {
                let right = self.cuts[index];
                let interval = new_interval(
                    what,
                    f,
                    &mut self.exps,
                    (piece, origin),
                    segment.map,
                    (left, right),
                    0,
                )?;
                self.length += interval.span;
                let mut early = true;
                for (k, setting) in settings.iter().enumerate() {
                    self.value[k].add(interval.value[k]);
                    self.error[k].add(interval.error[k]);
                    self.magnitude[k] += interval.value[k].abs();
                    // Within half the relative tolerance of its own value, an interval meets
                    // the |value| half of its share already (for an integrand of one sign,
                    // whose Σ|v| is |T|).
                    early &= interval.error[k] <= 0.5 * setting.relative_tolerance * interval.value[k].abs();
                }
                if early {
                    for k in 0..K {
                        self.early_value[k].add(interval.value[k]);
                        self.early_error[k].add(interval.error[k]);
                    }
                } else if self.keep {
                    self.level.push(interval);
                }
                left = right;
            }
        }
        Ok(())
    }

    /// Whether the totals meet every tolerance already (then nothing is refined and the
    /// intervals need not have been kept).
    fn met(&self, settings: &[Adaptive; K]) -> bool {
        (0..K).all(|k| {
            let s = &settings[k];
            self.error[k].total()
                <= s.absolute_tolerance
                    .max(s.relative_tolerance * self.value[k].total().abs())
        })
    }

    /// Appends `other` (the next chunk of pieces).
    fn merge(&mut self, other: Pass1<K>) {
        for k in 0..K {
            self.value[k].merge(&other.value[k]);
            self.error[k].merge(&other.error[k]);
            self.magnitude[k] += other.magnitude[k];
            self.early_value[k].merge(&other.early_value[k]);
            self.early_error[k].merge(&other.early_error[k]);
        }
        self.length += other.length;
        self.level.extend(other.level);
    }
}

/// The refinement after pass 1: which intervals to halve, level by level, and the estimates.
struct Refinement<'a, const K: usize> {
    settings: &'a [Adaptive; K],
    what: [&'static str; K],
    magnitude: [f64; K],
    length: f64,
    done_value: [CompensatedSum; K],
    done_error: [CompensatedSum; K],
    level: Vec<Interval<K>>,
    budget: usize,
    max_depth: u32,
    bisections: usize,
    limit: [Option<&'static str>; K],
    parameter: f64,
}

impl<'a, const K: usize> Refinement<'a, K> {
    fn tolerance(&self, k: usize, total: f64) -> f64 {
        let s = &self.settings[k];
        s.absolute_tolerance.max(s.relative_tolerance * total.abs())
    }

    fn finish(&self, value: [CompensatedSum; K], error: [CompensatedSum; K]) -> Result<[Estimate; K]> {
        let mut out = [Estimate {
            value: 0.0,
            error: 0.0,
            tolerance: 0.0,
            met: true,
            bisections: self.bisections,
            limit: None,
        }; K];
        for k in 0..K {
            let total = value[k].total();
            let err = error[k].total() + value[k].round_off();
            if !total.is_finite() || !err.is_finite() {
                return Err(Error::NonFinite {
                    what: self.what[k],
                    parameter: self.parameter,
                });
            }
            let tolerance = self.tolerance(k, total);
            let met = err <= tolerance;
            out[k] = Estimate {
                value: total,
                error: err,
                tolerance,
                met,
                bisections: self.bisections,
                limit: if met { None } else { self.limit[k] },
            };
        }
        Ok(out)
    }

    /// The intervals to halve next (taken out of the level, which is left empty), or the
    /// estimates when refinement is over.
    fn next(&mut self) -> std::result::Result<Vec<Interval<K>>, Result<[Estimate; K]>> {
        let (mut total, mut total_error) = (self.done_value, self.done_error);
        for interval in &self.level {
            for k in 0..K {
                total[k].add(interval.value[k]);
                total_error[k].add(interval.error[k]);
            }
        }
        let mut tolerance = [0.0; K];
        let mut open = [false; K];
        for k in 0..K {
            tolerance[k] = self.tolerance(k, total[k].total());
            open[k] = total_error[k].total() > tolerance[k];
        }
        if self.level.is_empty() || !open.iter().any(|&o| o) {
            return Err(self.finish(total, total_error));
        }
        // The share of interval i in component k: τ_k (½ ℓ_i/L + ½ |v_ik|/Σ|v_k|); how far
        // over its share an interval is, the largest ratio over the components still open.
        let share = |interval: &Interval<K>, k: usize| {
            let t = tolerance[k];
            let (magnitude, length) = (self.magnitude[k], self.length);
            if magnitude > 0.0 && length > 0.0 {
                t * (0.5 * interval.span / length + 0.5 * interval.value[k].abs() / magnitude)
            } else if length > 0.0 {
                t * interval.span / length
            } else {
                t
            }
        };
        let excess = |interval: &Interval<K>| {
            (0..K)
                .filter(|&k| open[k])
                .map(|k| interval.error[k] / share(interval, k).max(f64::MIN_POSITIVE))
                .fold(0.0_f64, f64::max)
        };
        let mut level = std::mem::take(&mut self.level);
        let (max_depth, done_value, done_error, limit) = (
            self.max_depth,
            &mut self.done_value,
            &mut self.done_error,
            &mut self.limit,
        );
        let mut retire = |interval: &Interval<K>, reason: Option<&'static str>| {
            for k in 0..K {
                done_value[k].add(interval.value[k]);
                done_error[k].add(interval.error[k]);
                if open[k] {
                    limit[k] = limit[k].or(reason);
                }
            }
        };
        level.retain(|interval| {
            let mid = 0.5 * (interval.start + interval.end);
            let reason = if excess(interval) <= 1.0 {
                None
            } else if interval.depth >= max_depth {
                Some("maximum depth reached")
            } else if mid <= interval.start || mid >= interval.end {
                Some("interval too small to bisect")
            } else {
                return true;
            };
            retire(interval, reason);
            false
        });
        let available = self.budget - self.bisections;
        if level.len() > available {
            if available > 0 {
                // The selection's order depends on the data alone (never on threads).
                level.select_nth_unstable_by(available - 1, |a, b| excess(b).total_cmp(&excess(a)));
            }
            for interval in level.drain(available..) {
                retire(&interval, Some("maximum number of subdivisions reached"));
            }
        }
        if level.is_empty() {
            let (value, error) = (*done_value, *done_error);
            return Err(self.finish(value, error));
        }
        self.bisections += level.len();
        Ok(level)
    }
}

/// Pass 1 over chunk `chunk` of [`CHUNK`] pieces (its sums, and its intervals to refine when
/// `keep`): the unit both engines merge in chunk order.
fn pass1_chunk<const K: usize, F, S>(
    settings: &[Adaptive; K],
    what: [&'static str; K],
    f: &mut F,
    segments: &mut S,
    breaks: &[f64],
    chunk: usize,
    keep: bool,
) -> Result<Pass1<K>>
where
    F: NodeIntegrands<K>,
    S: FnMut(usize, &mut Vec<Segment>) -> Result<()>,
{
    let pieces = breaks.len().saturating_sub(1);
    let (first, last) = (chunk * CHUNK, ((chunk + 1) * CHUNK).min(pieces));
    let mut pass1 = Pass1::new(last - first, keep);
    let mut scratch = Vec::new();
    for piece in first..last {
        scratch.clear();
        segments(piece, &mut scratch)?;
        pass1.piece(
            settings,
            what,
            f,
            piece,
            (breaks[piece], breaks[piece + 1]),
            &scratch,
        )?;
    }
    Ok(pass1)
}

fn validated<const K: usize>(settings: &[Adaptive; K], breaks: &[f64]) -> Result<usize> {
    for s in settings {
        s.validate()?;
    }
    check_breaks(breaks)?;
    let pieces = breaks.len().saturating_sub(1);
    if u32::try_from(pieces).is_err() {
        return Err(Error::InvalidSetting {
            what: "breaks",
            reason: "at most 2³² − 1 pieces",
        });
    }
    Ok(pieces)
}

fn refinement<'a, const K: usize>(
    settings: &'a [Adaptive; K],
    what: [&'static str; K],
    pass1: Pass1<K>,
    pieces: usize,
    breaks: &[f64],
) -> Refinement<'a, K> {
    let budget = settings
        .iter()
        .map(|s| s.max_subdivisions)
        .max()
        .unwrap_or(0)
        .max(SUBDIVISIONS_PER_PIECE.saturating_mul(pieces));
    // When pass 1 already meets every tolerance, nothing is refined: its totals are the answer.
    let (done_value, done_error, level) = if pass1.met(settings) {
        (pass1.value, pass1.error, Vec::new())
    } else {
        (pass1.early_value, pass1.early_error, pass1.level)
    };
    Refinement {
        settings,
        what,
        magnitude: pass1.magnitude,
        length: pass1.length,
        done_value,
        done_error,
        level,
        budget,
        max_depth: settings.iter().map(|s| s.max_depth).max().unwrap_or(0),
        bisections: 0,
        limit: [None; K],
        parameter: breaks.first().copied().unwrap_or(0.0),
    }
}

/// K integrals ∫ f_k over [breaks₀, breaks_last] with their errors, sequentially: the engine
/// of [`Adaptive::estimate_split`] (see there for the algorithm), generalised to K integrands
/// that share their nodes and intervals (an interval is halved while any integrand still
/// open misses its share there) and to initial intervals given by `segments(i, out)` in the
/// piece's local parameter (none pushed: the whole piece; an error stops the integration),
/// each [`SinhMap`]ped one integrated in s on the intervals [`SINH_PANEL`] describes.
/// `settings[k]` gives component k's tolerances; the depth and the pool of
/// bisections are the largest of them, shared. `f(i, u)` is called with the local parameter
/// u = t − `breaks[i]` (kept apart from tᵢ so that a peak of width w at u* is resolved to
/// ε·u*/w, not ε·tᵢ/w). O(pieces + segments).
pub fn estimate_many<const K: usize, F, S>(
    settings: &[Adaptive; K],
    what: [&'static str; K],
    f: F,
    breaks: &[f64],
    segments: S,
) -> Result<[Estimate; K]>
where
    F: FnMut(usize, f64) -> [f64; K],
    S: FnMut(usize, &mut Vec<Segment>) -> Result<()>,
{
    estimate_many_nodes(settings, what, Pointwise(f), breaks, segments)
}

/// [`estimate_many`] with the integrands evaluated on the [`KRONROD_POINTS`] nodes of one
/// rule at once ([`NodeIntegrands`]): the same sums, node for node, so the same result as
/// [`estimate_many`] with the pointwise integrand that gives the same values.
pub fn estimate_many_nodes<const K: usize, F, S>(
    settings: &[Adaptive; K],
    what: [&'static str; K],
    mut f: F,
    breaks: &[f64],
    mut segments: S,
) -> Result<[Estimate; K]>
where
    F: NodeIntegrands<K>,
    S: FnMut(usize, &mut Vec<Segment>) -> Result<()>,
{
    let pieces = validated(settings, breaks)?;
    // The chunks of the parallel engine, one after the other: the same sums in the same order.
    let mut pass = |keep: bool| -> Result<Pass1<K>> {
        let mut pass1 = Pass1::new(0, keep);
        for chunk in 0..pieces.div_ceil(CHUNK) {
            pass1.merge(pass1_chunk(
                settings,
                what,
                &mut f,
                &mut segments,
                breaks,
                chunk,
                keep,
            )?);
        }
        Ok(pass1)
    };
    // Pass 1 sums without keeping its intervals; only when its totals miss a tolerance is it
    // run again keeping those that may need refining (the same intervals, bit for bit), so
    // that the common case needs no O(intervals) memory.
    let mut pass1 = pass(false)?;
    if !pass1.met(settings) {
        pass1 = pass(true)?;
    }
    let mut refinement = refinement(settings, what, pass1, pieces, breaks);
    let mut exps = ExpTable::new();
    loop {
        match refinement.next() {
            Err(done) => return done,
            Ok(halve) => {
                let mut next = Vec::with_capacity(2 * halve.len());
                for interval in &halve {
                    next.extend(bisect(what, &mut f, &mut exps, breaks, interval)?);
                }
                refinement.level = next;
            }
        }
    }
}

/// [`estimate_many`] over rayon's threads, for integrands and segments that can be shared
/// between them. The result is bit for bit that of [`estimate_many`] (see the module doc),
/// whatever the number of threads; where several nodes give a non-finite value, the error
/// names the first in the pieces' order. O(pieces + segments) work.
pub fn estimate_many_parallel<const K: usize, F, S>(
    settings: &[Adaptive; K],
    what: [&'static str; K],
    f: F,
    breaks: &[f64],
    segments: S,
) -> Result<[Estimate; K]>
where
    F: Fn(usize, f64) -> [f64; K] + Sync,
    S: Fn(usize, &mut Vec<Segment>) -> Result<()> + Sync,
{
    estimate_many_nodes_parallel(
        settings,
        what,
        |piece: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]| {
            Pointwise(&f).eval(piece, u, out)
        },
        breaks,
        segments,
    )
}

/// [`estimate_many_nodes`] over rayon's threads (see [`estimate_many_parallel`]): bit for
/// bit its result, whatever the number of threads.
pub fn estimate_many_nodes_parallel<const K: usize, F, S>(
    settings: &[Adaptive; K],
    what: [&'static str; K],
    f: F,
    breaks: &[f64],
    segments: S,
) -> Result<[Estimate; K]>
where
    F: Fn(usize, &[f64; KRONROD_POINTS], &mut [[f64; KRONROD_POINTS]; K]) + Sync,
    S: Fn(usize, &mut Vec<Segment>) -> Result<()> + Sync,
{
    let pieces = validated(settings, breaks)?;
    let pass = |keep: bool| -> Result<Pass1<K>> {
        let chunks: Vec<Result<Pass1<K>>> = (0..pieces.div_ceil(CHUNK))
            .into_par_iter()
            .map(|chunk| {
                let mut g =
                    |i: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]| f(i, u, out);
                let mut cut = |i: usize, out: &mut Vec<Segment>| segments(i, out);
                pass1_chunk(settings, what, &mut g, &mut cut, breaks, chunk, keep)
            })
            .collect();
        let mut pass1 = Pass1::new(0, keep);
        for chunk in chunks {
            pass1.merge(chunk?);
        }
        Ok(pass1)
    };
    // As in `estimate_many_nodes`: keep the intervals only when the totals miss.
    let mut pass1 = pass(false)?;
    if !pass1.met(settings) {
        pass1 = pass(true)?;
    }
    let mut refinement = refinement(settings, what, pass1, pieces, breaks);
    loop {
        match refinement.next() {
            Err(done) => return done,
            Ok(halve) => {
                let halves: Vec<Result<[Interval<K>; 2]>> = halve
                    .par_iter()
                    .with_min_len(256)
                    .map_init(ExpTable::new, |exps, interval| {
                        let mut g =
                            |i: usize, u: &[f64; KRONROD_POINTS], out: &mut [[f64; KRONROD_POINTS]; K]| {
                                f(i, u, out)
                            };
                        bisect(what, &mut g, exps, breaks, interval)
                    })
                    .collect();
                let mut next = Vec::with_capacity(2 * halves.len());
                for pair in halves {
                    next.extend(pair?);
                }
                refinement.level = next;
            }
        }
    }
}
