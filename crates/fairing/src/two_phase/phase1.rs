//! Phase 1 of Han's function-segment fairing (Han et al. §4.1, "Coarse fairing – eliminating
//! unnecessary curvature vibrations"): find short wrong-sign runs of the second differences
//! e_i of the x–c polyline and move one or two y values so that the targeted e vanishes.
//!
//! Indices count from 0 (Han's point k is our k − 1); e_i exists at the interior points
//! 1 … n − 2 and only those points move (Han §3.3 displaces y_2 … y_{n−1}). Every
//! displacement comes from the linear model ẽ_i = e_i + Σ_j γ_j ẽ_i^j (Han Eq. 18), which is
//! exact because c is linear in y: with λ = 1 the targeted e is zero up to rounding.
//!
//! The cases (Han's 1-based conditions translated to 0-based point indices):
//!
//! | case | condition | moves | target |
//! |---|---|---|---|
//! | [`CaseKind::Small`] (Case 1) | e_i e_{i+1} < 0 | γ_i = σ, γ_{i+1} = −σ | ẽ_i ẽ_{i+1} = 0, the root of smaller \|σ\| |
//! | [`CaseKind::Medium`] (Case 2) | e_{i−1} e_i < 0, e_i e_{i+1} < 0, 2 ≤ i ≤ n − 3 | γ_i = σ | ẽ_i = 0 |
//! | [`CaseKind::MediumEnd`] (Case 2, end) | i = 1: e_1 e_2 < 0, e_1 e_3 < 0 (mirror at n − 2) | γ_i = σ | ẽ_i = 0 |
//! | [`CaseKind::Large`] (Case 3) | e_i e_{i+1} > 0 and e_i differs in sign from e_{i−2}, e_{i−1}, e_{i+2}, e_{i+3}, all existing | γ_i = σ, γ_{i+1} = τ | ẽ_i = ẽ_{i+1} = 0 |
//! | [`CaseKind::LargeEnd`] (Case 3, end) | e_1 e_2 > 0, e_1 e_3 < 0, e_1 e_4 < 0 (mirror at n − 3, n − 2) | γ_1, γ_2 | ẽ_1 = ẽ_2 = 0 |
//!
//! Choices where the paper is ambiguous (each tested):
//! - The large end case prints "e_2e_4 > 0 and e_2e_5 > 0"; its own words ("different sign
//!   with e_4 and e_5") and the figure need < 0 (papers/README.md typo list).
//! - The medium end case prints "e_2 e_3 < 0 and e_3 e_4 < 0, then we make e_2 zero". With
//!   e_3 e_4 < 0 the isolated value is e_3, which the interior Case 2 already handles at
//!   i = 3; we read it as the analogue of the corrected large end case: e_2 differs in sign
//!   from e_3 and e_4 (1-based), and e_2 is zeroed.
//! - Han's Case 3 loop 3 … n − 3 (1-based) reaches e_1 and e_n, which do not exist; we
//!   require all six e values and leave the runs touching an end to the end case.
//! - Han runs three separate loops (Cases 1, 2, 3). Case 1's condition holds at every
//!   vibration, so it would pre-empt Cases 2–3; we sweep once and at each i try the most
//!   specific pattern first (large, then medium, then small).
//! - λ scales every case (the paper prints it for Case 1 only).
//!
//! Guards (not in the paper, see [`TwoPhaseSettings`]): a case whose |γ| exceeds
//! [`MAX_MOVE_FACTOR`](super::MAX_MOVE_FACTOR) × the smaller spacing next to the moved point is skipped; a move that
//! would increase the inflection or vibration count within [`GUARD_WINDOW`] points is refused
//! (judged before it is made, on c as the windowed update would leave it; counted by sign,
//! without docs/CONTRACT.md's drop level, so that a move is never credited for pushing a sign change
//! below it; recounted only where a sign changed); and a pass that increased either global
//! count is undone whole (O(n) once per pass). So a pass never increases Infl_num or Vib_num
//! (docs/CONTRACT.md counts) unless the guard is [`CountGuard::Off`]. On a noisy sine `Local`
//! (the default) ends with fewer sign changes than `Pass`, which stops at the first undone
//! pass, and more than `Off` (the paper's rule, not monotone pass by pass).

use curve_repr::SplineFunction;
#[cfg(doc)]
use fairness::sign::sign_changes;
use fairness::sign::{opposite_signs, same_signs};
use fairness::xc::e_sensitivity;

use super::{CountGuard, Rules, TwoPhaseSettings, END_RUN_MAX_DEVIANCE, GUARD_WINDOW};
use crate::state::strategy_error;
use crate::Result;

/// Which Phase-1 pattern was found (Han §4.1 Phase 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CaseKind {
    /// Case 1, small curvature vibration: e_i e_{i+1} < 0.
    Small,
    /// Case 2, medium curvature vibration at an interior point.
    Medium,
    /// Case 2 at an end (point 1 or n − 2).
    MediumEnd,
    /// Case 3, large curvature vibration: a run of two e values of one sign.
    Large,
    /// Case 3 at an end (points 1, 2 or n − 3, n − 2).
    LargeEnd,
    /// Phase 2, Case 1, small curve vibration: c_i differs in sign from both neighbours
    /// ([`phase2`](super::phase2)).
    SmallCurve,
    /// Phase 2, Case 2, large curve vibration: a run c_i, c_{i+1} of one sign.
    LargeCurve,
    /// Phase 2, Case 2 at an end: c_0 = c_1 (runout) differ from c_2 and c_3 (mirror at
    /// n − 1); moves point 1 (or n − 2) only.
    LargeCurveEnd,
    /// Beyond the paper (option): a wrong-sign run of three or more c values.
    WrongSignRun,
    /// Beyond the paper (option): a wrong-sign run that touches an end of the segment and is
    /// not the paper's end case (longer than two points, or followed by fewer than two values
    /// of the other sign).
    EndRun,
}

/// A detected case: its kind and the point(s) it targets (`second` is `None` for one point).
/// Phase 1 moves exactly the targeted points; Phase 2 also moves the run's neighbours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Case {
    /// The pattern.
    pub kind: CaseKind,
    /// The first moved point (0-based).
    pub first: usize,
    /// The second moved point, first + 1, for the two-point cases; for the Phase-2 cases the
    /// last point of the wrong-sign run (`None` for a run of one).
    pub second: Option<usize>,
}

/// What one coarse pass did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassReport {
    /// The applied displacements (point, γ), in order; empty if the pass was undone.
    pub moves: Vec<(usize, f64)>,
    /// The cases applied, in order.
    pub cases: Vec<Case>,
    /// Cases found but skipped (degenerate system, move too large, not movable, local guard).
    pub skipped: usize,
    /// Of `skipped`: the moves refused (or, designed in c, undone) because they increased a
    /// local count.
    pub undone_by_count_guard: usize,
    /// Of `skipped`: the moves the data refused
    /// ([`END_RUN_MAX_DEVIANCE`]).
    pub refused_by_data: usize,
    /// The pass increased a global count and was undone whole.
    pub reverted: bool,
    /// Global (vibrations, inflections) after the pass (docs/CONTRACT.md counts, as [`counts`]), so
    /// that a caller need not count again.
    pub counts: (usize, usize),
}

/// e_i at interior point i from the spline's c (0 elsewhere). O(1).
pub fn e_at(spline: &SplineFunction, i: usize) -> f64 {
    let (x, c) = (spline.x(), spline.c());
    match (x.get(i.wrapping_sub(1)), x.get(i), x.get(i + 1)) {
        (Some(&x0), Some(&x1), Some(&x2)) if i >= 1 => {
            let (c0, c1, c2) = (c[i - 1], c[i], c[i + 1]);
            (c2 - c1) / (x2 - x1) - (c1 - c0) / (x1 - x0)
        }
        _ => 0.0,
    }
}

/// The reciprocal spacings 1/(x_{k+1} − x_k), computed once per pass so that the e values
/// of the sweep and the guards cost multiplications only. O(n).
pub(super) fn inverse_steps(x: &[f64]) -> Vec<f64> {
    x.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect()
}

/// e_k from c and the reciprocal spacings (the formula of [`e_at`], multiplied instead of
/// divided: equal to it up to rounding). Callers keep 1 ≤ k ≤ n − 2.
#[inline]
pub(super) fn e_fast(c: &[f64], inverse: &[f64], k: usize) -> f64 {
    (c[k + 1] - c[k]) * inverse[k] - (c[k] - c[k - 1]) * inverse[k - 1]
}

/// The Phase-1 case at point i, trying large, then medium, then small (module doc). A small
/// case at (i, i + 1) is not reported when a medium or large pattern starts at i + 1: the
/// sweep reaches it next and the specific rule handles it. O(1).
pub fn detect(spline: &SplineFunction, i: usize) -> Option<Case> {
    detect_by(spline.x().len(), i, &|k| e_at(spline, k))
}

/// [`detect`] on a segment of n points whose e values `e(k)` gives (k interior). O(1).
fn detect_by(n: usize, i: usize, e: &impl Fn(usize) -> f64) -> Option<Case> {
    if let Some(case) = detect_specific(n, i, e) {
        return Some(case);
    }
    if n < 4 || i < 1 || i + 2 > n - 1 {
        return None;
    }
    if opposite_signs(e(i), e(i + 1)) && detect_specific(n, i + 1, e).is_none() {
        return Some(Case {
            kind: CaseKind::Small,
            first: i,
            second: Some(i + 1),
        });
    }
    None
}

/// The medium and large patterns at i (Cases 2–3, interior and ends). O(1).
fn detect_specific(n: usize, i: usize, e_raw: &impl Fn(usize) -> f64) -> Option<Case> {
    if n < 4 || i < 1 || i > n - 2 {
        return None;
    }
    let e = |k: isize| -> Option<f64> {
        if k >= 1 && (k as usize) <= n - 2 {
            Some(e_raw(k as usize))
        } else {
            None
        }
    };
    let ii = i as isize;
    let opp = |a: Option<f64>, b: Option<f64>| matches!((a, b), (Some(a), Some(b)) if opposite_signs(a, b));
    let same = |a: Option<f64>, b: Option<f64>| matches!((a, b), (Some(a), Some(b)) if same_signs(a, b));
    let ei = e(ii);
    let two = |kind| Case {
        kind,
        first: i,
        second: Some(i + 1),
    };
    let one = |kind| Case {
        kind,
        first: i,
        second: None,
    };
    // Case 3 (large), interior: all six values exist.
    if same(ei, e(ii + 1))
        && opp(ei, e(ii - 1))
        && opp(ei, e(ii - 2))
        && opp(ei, e(ii + 2))
        && opp(ei, e(ii + 3))
    {
        return Some(two(CaseKind::Large));
    }
    // Case 3, end: the run (1, 2) or (n − 3, n − 2), corrected sign.
    if i == 1 && same(ei, e(2)) && opp(ei, e(3)) && opp(ei, e(4)) {
        return Some(two(CaseKind::LargeEnd));
    }
    let last = (n - 2) as isize;
    if ii == last - 1 && same(ei, e(last)) && opp(ei, e(last - 2)) && opp(ei, e(last - 3)) {
        return Some(two(CaseKind::LargeEnd));
    }
    // Case 2 (medium), interior.
    if opp(ei, e(ii - 1)) && opp(ei, e(ii + 1)) {
        return Some(one(CaseKind::Medium));
    }
    // Case 2, end.
    if i == 1 && opp(ei, e(2)) && opp(ei, e(3)) {
        return Some(one(CaseKind::MediumEnd));
    }
    if ii == last && opp(ei, e(last - 1)) && opp(ei, e(last - 2)) {
        return Some(one(CaseKind::MediumEnd));
    }
    None
}

/// The displacements (point, γ) of Han's rule for `case`, scaled by `lambda`; `None` when the
/// rule is degenerate (a zero sensitivity, a singular 2×2 system). O(1).
///
/// - Small: ẽ_i = e_i + σ(ẽ_i^i − ẽ_i^{i+1}), ẽ_{i+1} = e_{i+1} + σ(ẽ_{i+1}^i − ẽ_{i+1}^{i+1})
///   (Eq. 18 with γ_i = σ, γ_{i+1} = −σ); σ is the root of smaller |σ| of ẽ_i ẽ_{i+1} = 0.
/// - Medium: σ = −e_i / ẽ_i^i.
/// - Large: [ẽ_i^i ẽ_i^{i+1}; ẽ_{i+1}^i ẽ_{i+1}^{i+1}] (σ, τ) = −(e_i, e_{i+1}) by Cramer's
///   rule, refused when |det| ≤ 1e-12 · (product of the row norms).
pub fn displacement(spline: &SplineFunction, case: Case, lambda: f64) -> Option<Vec<(usize, f64)>> {
    let s = |i: usize, j: usize| e_sensitivity(spline, i, j);
    let i = case.first;
    let ok = |v: f64| v.is_finite().then_some(v);
    match (case.kind, case.second) {
        (CaseKind::Medium | CaseKind::MediumEnd, _) => {
            let d = s(i, i);
            if d == 0.0 {
                return None;
            }
            Some(vec![(i, ok(-lambda * e_at(spline, i) / d)?)])
        }
        (CaseKind::Small, Some(k)) => {
            let roots = [
                (e_at(spline, i), s(i, i) - s(i, k)),
                (e_at(spline, k), s(k, i) - s(k, k)),
            ];
            let sigma = roots
                .iter()
                .filter(|(_, d)| *d != 0.0)
                .map(|(e, d)| -e / d)
                .filter(|v| v.is_finite())
                .min_by(|a, b| a.abs().total_cmp(&b.abs()))?;
            Some(vec![(i, lambda * sigma), (k, -lambda * sigma)])
        }
        (CaseKind::Large | CaseKind::LargeEnd, Some(k)) => {
            let (a, b, c, d) = (s(i, i), s(i, k), s(k, i), s(k, k));
            let det = a * d - b * c;
            let scale = a.hypot(b) * c.hypot(d);
            if !det.is_finite() || det.abs() <= 1e-12 * scale {
                return None;
            }
            let (ei, ek) = (e_at(spline, i), e_at(spline, k));
            let sigma = (-ei * d + ek * b) / det;
            let tau = (-ek * a + ei * c) / det;
            Some(vec![(i, ok(lambda * sigma)?), (k, ok(lambda * tau)?)])
        }
        _ => None,
    }
}

/// Vibrations and inflections among points lo..=hi (docs/CONTRACT.md counts on the slice), the e
/// values computed once into `scratch`. O(hi − lo).
fn local_counts(spline: &SplineFunction, lo: usize, hi: usize, scratch: &mut Vec<f64>) -> (usize, usize) {
    let n = spline.x().len();
    scratch.clear();
    // e_k as in `e_at`, over slices (the same operations, so the same values).
    let (first, last) = (lo.max(1), hi.min(n.saturating_sub(2)));
    if let (Some(x), Some(c)) = (
        spline.x().get(first.saturating_sub(1)..last + 2),
        spline.c().get(first.saturating_sub(1)..last + 2),
    ) {
        if first <= last {
            scratch.extend(
                x.windows(3)
                    .zip(c.windows(3))
                    .map(|(x, c)| (c[2] - c[1]) / (x[2] - x[1]) - (c[1] - c[0]) / (x[1] - x[0])),
            );
        }
    }
    let c = spline.c().get(lo..=hi).unwrap_or(&[]);
    (changes(scratch.iter().copied()), changes(c.iter().copied()))
}

/// The values the local count guard compares: e_k for the interior k of lo..=hi, then c_k for
/// k in lo..=hi (e by [`e_fast`]). `c[k − offset]` holds c_k (0 for the whole sequence), and
/// it covers lo − 1 ..= hi + 1 within the n points. Returns where the c values start.
/// O(hi − lo).
fn window_values(
    c: &[f64],
    offset: usize,
    n: usize,
    inverse: &[f64],
    lo: usize,
    hi: usize,
    out: &mut Vec<f64>,
) -> usize {
    out.clear();
    let (first, last) = (lo.max(1), hi.min(n.saturating_sub(2)));
    if first <= last {
        let c = &c[first - 1 - offset..=last + 1 - offset];
        // The operations of `e_fast`, so the same values, over windows (no index checks).
        out.extend(
            c.windows(3)
                .zip(inverse[first - 1..=last].windows(2))
                .map(|(c, h)| (c[2] - c[1]) * h[1] - (c[1] - c[0]) * h[0]),
        );
    }
    let split = out.len();
    out.extend_from_slice(&c[lo - offset..=hi - offset]);
    split
}

/// How much a move changed the sign-change count of a window: (count after) − (count before),
/// exact zeros skipped. Only the stretch between the first and the last entry whose sign
/// changed, widened to the nearest non-zero entry on each side, is recounted: outside it both
/// sequences have the same signs. O(len).
///
/// Unlike the docs/CONTRACT.md count it drops no small value (no 1e-12 · max level): a move that
/// drives a value towards zero is judged by its sign, so that the guard never rewards hiding
/// a sign change below the drop level. The pass guard ([`counts`]) is docs/CONTRACT.md's.
fn count_change(before: &[f64], after: &[f64]) -> isize {
    match (sign_mask(before), sign_mask(after)) {
        (Some(b), Some(a)) if before.len() == after.len() => {
            // No exact zero in either window (the usual case): with the sign bits of each
            // sequence in a word, the sign changes of a stretch are the set bits of s ^ (s >> 1)
            // within it, and only the stretch from the first to the last flipped sign (one
            // entry wider on each side) can differ.
            let flipped = a ^ b;
            if flipped == 0 {
                return 0;
            }
            let (first, last) = (flipped.trailing_zeros(), 63 - flipped.leading_zeros());
            let lo = first.saturating_sub(1);
            let hi = (last + 1).min(before.len() as u32 - 1);
            // Bits k with lo ≤ k < hi: the pairs (k, k + 1) inside lo..=hi.
            let pairs = (1u64 << hi) - (1u64 << lo);
            let count = |s: u64| ((s ^ (s >> 1)) & pairs).count_ones() as isize;
            count(a) - count(b)
        }
        _ => count_change_with_zeros(before, after),
    }
}

/// The sign bits of `values` (bit k set when values[k] < 0), if there are at most 64 values
/// and none is an exact zero (which has no sign). O(len).
fn sign_mask(values: &[f64]) -> Option<u64> {
    if values.len() > 64 {
        return None;
    }
    let (mut mask, mut signless) = (0u64, false);
    for (k, &v) in values.iter().enumerate() {
        // The sign bit is v < 0 for every v but ±0 and NaN, which `signless` catches.
        mask |= (v.to_bits() >> 63) << k;
        signless |= v == 0.0 || v.is_nan();
    }
    (!signless).then_some(mask)
}

/// [`count_change`] for windows with exact zeros or more than 64 values: the same count, by a
/// scan. O(len).
fn count_change_with_zeros(before: &[f64], after: &[f64]) -> isize {
    // Same sign unless the product is ≤ 0 (an underflowing product only costs a recount).
    let flipped = |(b, a): (&f64, &f64)| a * b <= 0.0 && a != b;
    let Some(first) = before.iter().zip(after).position(flipped) else {
        return 0;
    };
    let last = before.iter().zip(after).rposition(flipped).unwrap_or(first);
    let lo = before[..first].iter().rposition(|&v| v != 0.0).unwrap_or(first);
    let hi = before[last + 1..]
        .iter()
        .position(|&v| v != 0.0)
        .map_or(last, |k| last + 1 + k);
    let count = |values: &[f64]| {
        let mut previous = 0.0f64;
        let mut changes = 0isize;
        for &v in values {
            // Branch-free, by sign (a product of tiny values could underflow): an exact zero
            // has no sign and keeps the previous one.
            changes += isize::from(v != 0.0 && previous != 0.0 && (v < 0.0) != (previous < 0.0));
            previous = if v != 0.0 { v } else { previous };
        }
        changes
    };
    count(&after[lo..=hi]) - count(&before[lo..=hi])
}

/// Entries kept on each side of a moved point by the windowed updates inside a pass
/// ([`SplineFunction::set_y_within`]): the neglected part is below 2 · 2^−20 ≈ 2e-6 of the
/// move's effect for the most uneven knots and 0.27^20 ≈ 3e-12 on uniform ones. Inside a pass
/// c is read only to detect cases and by the local guard (whose window is [`GUARD_WINDOW`] + 2 =
/// 18 points, inside this one; a larger window would read values that the
/// truncated updates left stale). The truncation can change a decision inside a pass (which
/// case is found, whether the guard undoes it), never a promise: every pass ends with an
/// exact rebuild and the exact global count guard.
const PASS_UPDATE_WINDOW: usize = 20;

/// [`sign_changes`] without allocating (the same drop rule: values with |v| ≤ 1e-12 · max|v|
/// over the sequence are skipped). One sweep that skips exact zeros and tracks the extreme
/// magnitudes; a second, with the drop level, only when some non-zero |v| is at or below it.
/// O(len).
fn changes(values: impl Iterator<Item = f64> + Clone) -> usize {
    let (mut largest, mut smallest) = (0.0f64, f64::INFINITY);
    let mut previous = 0.0f64;
    let mut count = 0;
    for v in values.clone() {
        let a = v.abs();
        largest = largest.max(a);
        // Branch-free: noisy signs defeat the branch predictor. An exact zero has no sign; by
        // sign, not by product (which underflows for tiny values).
        count += usize::from(opposite_signs(previous, v));
        smallest = smallest.min(if v != 0.0 { a } else { f64::INFINITY });
        previous = if v != 0.0 { v } else { previous };
    }
    let level = 1e-12 * largest;
    if smallest > level {
        return count;
    }
    let mut previous = 0.0f64;
    let mut count = 0;
    for v in values.filter(|v| v.abs() > level) {
        if opposite_signs(previous, v) {
            count += 1;
        }
        previous = v;
    }
    count
}

/// Global (vibrations, inflections) of the spline's x–c polyline (docs/CONTRACT.md counts). O(n).
pub fn counts(spline: &SplineFunction) -> (usize, usize) {
    let n = spline.x().len();
    local_counts(spline, 0, n.saturating_sub(1), &mut Vec::new())
}

/// One coarse pass of Phase 1 over the whole segment (module doc): sweeps i = 1 … n − 2,
/// applies each detected case whose points are all `movable` and interior, with the guards of
/// [`TwoPhaseSettings`]. O(n · guard window).
///
/// Errors: bad settings; a failing spline update (the spline is then restored).
pub fn coarse_pass(
    spline: &mut SplineFunction,
    settings: &TwoPhaseSettings,
    movable: &dyn Fn(usize) -> bool,
) -> Result<PassReport> {
    coarse_pass_from(spline, &Rules::direct(settings), movable, None)
}

/// [`coarse_pass`] given the spline's [`counts`] if the caller knows them (the last pass's
/// [`PassReport::counts`]). O(n · guard window).
pub(super) fn coarse_pass_from(
    spline: &mut SplineFunction,
    settings: &Rules,
    movable: &dyn Fn(usize) -> bool,
    known: Option<(usize, usize)>,
) -> Result<PassReport> {
    settings.validate()?;
    let lambda = settings.coarse_lambda;
    let find = |spline: &SplineFunction, inverse: &[f64], i: usize| {
        let c = spline.c();
        let case = detect_by(c.len(), i, &|k| e_fast(c, inverse, k))?;
        Some((case, displacement(spline, case, lambda).map(Proposal::from)))
    };
    guarded_pass(spline, settings, movable, 1, false, known, &find)
}

/// A detector for [`guarded_pass`]: the case starting at point i (if any) and its moves
/// (`None` when the rule is degenerate).
/// The finder gets the reciprocal spacings of [`inverse_steps`] too.
pub(super) type Finder<'a> = dyn Fn(&SplineFunction, &[f64], usize) -> Option<(Case, Option<Proposal>)> + 'a;

/// What a finder proposes: the moves (point, γ), and for a move designed in c (the long-run
/// absorption) its exact change of c, (first point, δc), which the pass applies with
/// [`SplineFunction::change_c_locally`] instead of through truncated sensitivity columns.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Proposal {
    pub moves: Vec<(usize, f64)>,
    pub c_change: Option<(usize, Vec<f64>)>,
}

impl From<Vec<(usize, f64)>> for Proposal {
    fn from(moves: Vec<(usize, f64)>) -> Self {
        Proposal {
            moves,
            c_change: None,
        }
    }
}

/// Whether the data refuse a move ([`END_RUN_MAX_DEVIANCE`]): an end-run case whose moves
/// (point, γ) would raise the residual sum of squares against the data,
/// Σ (y_k + γ_k − d_k)² − Σ (y_k − d_k)² over the moved points, by more than
/// [`END_RUN_MAX_DEVIANCE`] · σ̂². Off when the data or σ̂ are unknown (arbitrary curves'
/// segments, a direct [`fair_function`](super::fair_function)). O(m log m), m the moves.
fn refused_by_data(settings: &Rules, y: &[f64], kind: CaseKind, moves: &[(usize, f64)]) -> bool {
    let limit = END_RUN_MAX_DEVIANCE;
    let data = &settings.run.data;
    let sigma = settings.run.noise;
    if kind != CaseKind::EndRun || limit <= 0.0 || data.len() != y.len() || !sigma.is_finite() || sigma <= 0.0
    {
        return false;
    }
    // Points may repeat in a move list: sum each point's moves first (sorted by point, so
    // that an end run of 10^4 points costs m log m, not m²).
    let mut sorted = moves.to_vec();
    sorted.sort_by_key(|m| m.0);
    let mut total: Vec<(usize, f64)> = Vec::with_capacity(sorted.len());
    for (k, g) in sorted {
        match total.last_mut() {
            Some(t) if t.0 == k => t.1 += g,
            _ => total.push((k, g)),
        }
    }
    let change: f64 = total
        .iter()
        .filter_map(|&(k, g)| Some((*y.get(k)? - *data.get(k)?, g)))
        .map(|(r, g)| g * (2.0 * r + g))
        .sum();
    change > limit * sigma * sigma
}

/// The sweep shared by both phases: from `start`, at each i ask `find`; apply the moves if
/// every moved point is interior, `movable` and within the size guard, then the local count
/// guard; continue after the case's last point (`second`, else `first`), else at i + 1.
/// Ends with a rebuild (clears the rounding of the windowed updates) and the pass guard.
/// The guards refuse a move (pass) that increases either count, or with `inflections_first`
/// (the long-run option's fine pass) one that increases the inflections, whatever it does to
/// the vibrations (ranking ties by vibrations measured worse: 1835 against 1291 inflections
/// left on the 10^4-point segment of `examples/two_phase_runs.rs`).
/// O(n · guard window) plus the finder's cost.
pub(super) fn guarded_pass(
    spline: &mut SplineFunction,
    settings: &Rules,
    movable: &dyn Fn(usize) -> bool,
    start: usize,
    inflections_first: bool,
    known: Option<(usize, usize)>,
    find: &Finder<'_>,
) -> Result<PassReport> {
    // Whether changes of (vibrations, inflections) make a move or pass worse.
    let worse_by =
        |vibrations: isize, inflections: isize| inflections > 0 || (!inflections_first && vibrations > 0);
    let worse = |before: (usize, usize), after: (usize, usize)| {
        let change = |a: usize, b: usize| if b > a { 1 } else { 0 };
        worse_by(change(before.0, after.0), change(before.1, after.1))
    };
    let n = spline.x().len();
    let mut report = PassReport::default();
    if n < 4 {
        report.counts = known.unwrap_or_else(|| counts(spline));
        return Ok(report);
    }
    let before_global = known.unwrap_or_else(|| counts(spline));
    let original_y = spline.y().to_vec();
    let inverse = inverse_steps(spline.x());
    let (mut before, mut after) = (Vec::new(), Vec::new());
    let (mut new, mut trial) = (Vec::new(), Vec::new());
    let mut i = start;
    while i < n {
        let Some((case, proposal)) = find(spline, &inverse, i) else {
            i += 1;
            continue;
        };
        let next = case.second.unwrap_or(case.first).max(i) + 1;
        i = next;
        let Some(Proposal { moves, c_change }) = proposal else {
            report.skipped += 1;
            continue;
        };
        let x = spline.x();
        let allowed = !moves.is_empty()
            && moves.iter().all(|&(k, g)| {
                k >= 1
                    && k + 1 < n
                    && movable(k)
                    && g.is_finite()
                    && g.abs() <= settings.move_limit((x[k] - x[k - 1]).min(x[k + 1] - x[k]))
            });
        if !allowed {
            report.skipped += 1;
            continue;
        }
        if refused_by_data(settings, spline.y(), case.kind, &moves) {
            report.skipped += 1;
            report.refused_by_data += 1;
            continue;
        }
        let (Some(lo), Some(hi)) = (moves.iter().map(|m| m.0).min(), moves.iter().map(|m| m.0).max()) else {
            continue;
        };
        let lo = lo.saturating_sub(GUARD_WINDOW + 2);
        let hi = (hi + GUARD_WINDOW + 2).min(n - 1);
        let guard = settings.count_guard == CountGuard::Local;
        let split = if guard {
            window_values(spline.c(), 0, n, &inverse, lo, hi, &mut before)
        } else {
            0
        };
        // Whether the move, made, would increase a count within the window (recounted only
        // where some value changed sign).
        let worse_window = |before: &[f64], after: &[f64]| {
            let (e_before, c_before) = before.split_at(split);
            let (e_after, c_after) = after.split_at(split);
            worse_by(count_change(e_before, e_after), count_change(c_before, c_after))
        };
        if let Some((first, dc)) = &c_change {
            // A move designed in c: made exactly, judged, undone if worse.
            let Ok(change) = spline.change_c_locally(*first, dc) else {
                report.skipped += 1;
                continue;
            };
            if guard && {
                window_values(spline.c(), 0, n, &inverse, lo, hi, &mut after);
                worse_window(&before, &after)
            } {
                spline.undo_local_change(&change);
                report.skipped += 1;
                report.undone_by_count_guard += 1;
                continue;
            }
        } else {
            new.clear();
            new.extend(moves.iter().map(|&(k, g)| (k, spline.y()[k] + g)));
            if guard {
                // Judged before it is made: c over the window as the windowed update would
                // leave it (bit for bit, `add_column_to`), so a refused move costs no undo.
                let (base, top) = (lo.saturating_sub(1), (hi + 1).min(n - 1));
                trial.clear();
                trial.extend_from_slice(&spline.c()[base..=top]);
                let y = spline.y();
                for (m, &(k, value)) in new.iter().enumerate() {
                    let current = new[..m].iter().rev().find(|p| p.0 == k).map_or(y[k], |p| p.1);
                    let delta = value - current;
                    if delta != 0.0 {
                        spline.add_column_to(k, delta, PASS_UPDATE_WINDOW, base, &mut trial);
                    }
                }
                window_values(&trial, base, n, &inverse, lo, hi, &mut after);
                if worse_window(&before, &after) {
                    report.skipped += 1;
                    report.undone_by_count_guard += 1;
                    continue;
                }
            }
            spline.set_y_within(&new, PASS_UPDATE_WINDOW)?;
        }
        report.moves.extend(moves);
        report.cases.push(case);
    }
    // Clear the rounding of the windowed updates, then the global guard.
    spline.rebuild()?;
    let after_global = counts(spline);
    if settings.count_guard != CountGuard::Off && worse(before_global, after_global) {
        let restore: Vec<(usize, f64)> = report
            .moves
            .iter()
            .filter_map(|&(k, _)| original_y.get(k).map(|&y| (k, y)))
            .collect();
        spline
            .set_y(&restore)
            .map_err(|e| strategy_error("two-phase", format!("restoring a pass failed: {e}")))?;
        spline.rebuild()?;
        report.moves.clear();
        report.cases.clear();
        report.reverted = true;
        report.counts = counts(spline);
    } else {
        report.counts = after_global;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::{changes, count_change, count_change_with_zeros};
    use curve_repr::{EndCondition, SplineFunction};
    use fairness::sign::sign_changes;

    /// A steep leading edge sampled as airfoil files are (cosine spacing, a first step of
    /// 0.003 after the tip, five decimals): y = −0.09 √x (1 − x), exact to its digits.
    fn leading_edge() -> (Vec<f64>, Vec<f64>) {
        let round = |v: f64| (v * 1e5).round() / 1e5;
        let x: Vec<f64> = (0..28)
            .map(|k| round(0.5 * (1.0 - (std::f64::consts::PI * f64::from(k) / 27.0).cos())))
            .collect();
        let y = x.iter().map(|&t| round(-0.09 * t.sqrt() * (1.0 - t))).collect();
        (x, y)
    }

    /// The moves of five full passes on [`leading_edge`] with the move cap `cap`, B and σ̂
    /// set as the strategy sets them.
    fn leading_edge_moves(cap: super::super::MoveCap) -> (Vec<(usize, f64)>, f64) {
        use crate::displacement::{data_bound_as, NoiseModel};
        let (x, y) = leading_edge();
        let points: Vec<curve_repr::Vec2> = x
            .iter()
            .zip(&y)
            .map(|(&a, &b)| curve_repr::Vec2::new(a, b))
            .collect();
        let bound = data_bound_as(&points, NoiseModel::Vertical);
        let rules = super::super::Rules {
            settings: super::TwoPhaseSettings::default().with_move_cap(cap),
            run: super::super::RunData {
                noise: bound.noise,
                bound: bound.bound,
                data: std::sync::Arc::from(y.clone()),
            },
        };
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let mut moves = Vec::new();
        for _ in 0..5 {
            let (coarse, fine) = super::super::full_pass_from(&mut spline, &rules, &|_| true, None).unwrap();
            moves.extend(coarse.moves.into_iter().chain(fine.moves));
        }
        (moves, bound.bound)
    }

    /// `move-cap` ([`MoveCap`](super::super::MoveCap)): on the exact points of a steep leading
    /// edge the spacing bound (in x units, the paper's reading) lets Phase 1 move y near the
    /// tip by many data bounds B (the interpolating spline's c rings there); with the data cap
    /// every move stays within B.
    #[test]
    fn the_data_bound_caps_each_move_on_a_steep_leading_edge() {
        use super::super::MoveCap;
        let (uncapped, bound) = leading_edge_moves(MoveCap::Spacing);
        assert!(bound > 0.0);
        assert!(
            uncapped.iter().any(|m| m.1.abs() > 10.0 * bound),
            "{uncapped:?} against B = {bound}"
        );
        let (capped, _) = leading_edge_moves(MoveCap::Data);
        assert!(!capped.is_empty());
        assert!(
            capped.iter().all(|m| m.1.abs() <= bound),
            "{capped:?} against B = {bound}"
        );
        assert_eq!(super::TwoPhaseSettings::paper().move_cap, MoveCap::Spacing);
    }

    /// The guard's count change equals the difference of two plain by-sign counts (exact
    /// zeros skipped) on windows with and without zeros, tiny and huge values, up to and past
    /// the 64 values of the bit-mask path.
    #[test]
    fn count_change_is_the_difference_of_the_sign_counts() {
        let plain = |v: &[f64]| {
            let signs: Vec<bool> = v.iter().filter(|x| **x != 0.0).map(|x| *x < 0.0).collect();
            signs.windows(2).filter(|w| w[0] != w[1]).count() as isize
        };
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for trial in 0..4000 {
            let len = [2usize, 5, 37, 63, 64, 65, 90][trial % 7];
            let value = |r: u64| match r % 11 {
                0 => 0.0,
                1 => 1e-300,
                2 => -1e-300,
                3 => 1e300,
                _ => (r % 2001) as f64 / 1000.0 - 1.0,
            };
            let before: Vec<f64> = (0..len).map(|_| value(next())).collect();
            // After: a few entries changed, as a move changes a window.
            let mut after = before.clone();
            for _ in 0..(next() % 6) {
                let k = (next() % len as u64) as usize;
                after[k] = value(next());
            }
            let want = plain(&after) - plain(&before);
            assert_eq!(count_change(&before, &after), want, "{before:?} -> {after:?}");
            assert_eq!(count_change_with_zeros(&before, &after), want);
        }
    }

    #[test]
    fn changes_agree_with_the_design_count() {
        let cases: [&[f64]; 8] = [
            &[1.0, 1e-13, -1.0, 1e-14, 1.0],
            &[-2.0, -1e-12, 3.0],
            &[1.0, 0.0, -1.0],
            &[0.0, 0.0],
            &[1e-20, 1.0, -1e-20, 2.0],
            &[-1.0, 2.0, -3.0, 4.0, 0.0, 5.0, -1e-13, -6.0],
            &[],
            &[3.0, -2.0, 1e-11, -1.0, 2.0],
        ];
        for v in cases {
            assert_eq!(changes(v.iter().copied()), sign_changes(v), "{v:?}");
            // Scaled far down or up, where products of neighbours under- or overflow, the
            // counts are the same.
            for scale in [1e-300, 1e-170, 1e170, 1e300] {
                let scaled: Vec<f64> = v.iter().map(|x| x * scale).collect();
                assert_eq!(
                    changes(scaled.iter().copied()),
                    sign_changes(v),
                    "{v:?} × {scale}"
                );
                assert_eq!(sign_changes(&scaled), sign_changes(v), "{v:?} × {scale}");
            }
        }
    }
}
