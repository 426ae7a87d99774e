//! Phase 2 of Han's function-segment fairing (Han et al. §4.1, "Fine fairing – reducing
//! unnecessary inflections"): find short runs of c values whose sign differs from both
//! neighbours (inflection pairs of the x–c polyline) and move y so that the run takes the
//! neighbours' sign.
//!
//! Indices count from 0 (Han's point k is our k − 1); only the interior points 1 … n − 2 move.
//! Every displacement comes from the linear model c̃_k = c_k + Σ_j γ_j c̃_k^j (Han Eq. 13),
//! exact because c is linear in y, with the sensitivities of
//! [`SplineFunction::sensitivity`] (derived separately next to the ends, where the printed
//! Eq. 14–15 are wrong; `papers/README.md`).
//!
//! | case | condition (s = sign of the run) | moves | target |
//! |---|---|---|---|
//! | [`CaseKind::SmallCurve`] (Case 1) | c_{i−1}, c_{i+1} have sign −s | γ_i = σ, γ_{i±1} = −λσ | c̃_i = α |
//! | [`CaseKind::LargeCurve`] (Case 2) | c_i, c_{i+1} of sign s; c_{i−2}, c_{i−1}, c_{i+2}, c_{i+3} of sign −s | γ_i = γ_{i+1} = σ, γ_{i−1} = γ_{i+2} = τ | c̃_i = c̃_{i+1} = α |
//! | [`CaseKind::LargeCurveEnd`] (Case 2, end) | c_0 = c_1 of sign s, c_2, c_3 of sign −s (mirror at n − 1) | γ_1 = σ | c̃_1 = α (c̃_0 = c̃_1 by the runout) |
//! | [`CaseKind::WrongSignRun`] (option, not in the paper) | c_i … c_{i+k−1} of sign s, 3 ≤ k ≤ `max_run`, c_{i−1}, c_{i+k} of sign −s, the run's ∫\|y''\| below each flank's | γ_j = σ w_j (smooth bump) | every c̃ of the run reaches α or beyond |
//!
//! **The α rule** (Han Case 1 Step 3, Case 2 Step 4): solve with α = 0; if neither neighbour
//! (c̃_{i−1}, c̃_{i+1}, resp. c̃_{i−1}, c̃_{i+2}) changed sign, solve again with
//! α = −s · min(|c̃_{i−1}|, |c̃_{i+1}|) / `alpha_divisor` (5 in the paper). Han prints
//! "α = min(c̃_{i−1}, c̃_{i+1})/5"; for negative neighbours the literal min is the one of
//! *larger* size, so we read it as the neighbour of smaller magnitude, keeping its sign (the
//! brief and the figure: one fifth of the smaller neighbour). Because c is linear in y, the
//! second solve from the moved state equals one solve from the original state with the final
//! α; that is how it is computed (the neighbours after the α = 0 move are predicted by Eq. 13).
//! The α rule applies to the end case too (the paper prints only α = 0 there): c̃_0 = c̃_1 = 0
//! would leave a straight end span whose sign the next rounding decides.
//!
//! **Case 2 is ill-posed as printed** (`papers/README.md`): for uniform spacing the rows of the
//! 2 × 2 system in (σ, τ) are equal by symmetry (both unknowns move c_i and c_{i+1} alike) and
//! the system has no solution unless c_i = c_{i+1}; for mildly non-uniform spacing (x_k =
//! k + 0.3 sin k) the sine of the angle between its rows is ≈ 0.01 and the solution moves
//! points by absurd amounts. We solve it exactly only when that sine is at least
//! `pair_min_sine` (default 0.05, not in the paper). Otherwise we fix the ratio τ/σ: the
//! pattern is the bump of the long-run rule below over the pair and its two neighbours,
//! γ_j = σ w_j for j = i − 1 … i + 2, which on uniform knots is the paper's ansatz with
//! τ = 2σ/3 (w = 0.64, 0.96, 0.96, 0.64), and σ is the smallest that brings *both* c̃_i and
//! c̃_{i+1} to α or beyond (the member that needs the larger move reaches α, the other passes
//! it; refused if the members respond with opposite signs). One unknown, one condition: always
//! well-posed. A fixed ratio is needed because the free (σ, τ) of the singular system are not
//! determined, and the minimum-norm choice moves the neighbours so much (τ acts on c_i more
//! than σ) that they change sign; the bump raises the neighbours' c with the pair's.
//!
//! **Runs of more than two points** (option `max_run` > 2; the paper leaves them, "they can be
//! avoided very well by our alternative two-phases fairing", which dense noisy data refutes).
//! Which of two alternating runs is the noise? The one with less ∫|y''|: a run is handled only
//! if Σ|c_j|(x_{j+1} − x_{j−1})/2 over it is below that of each flanking run (scanned as far as
//! the run is long; Han's Case 2 asks the analogue, c_{i+3}, of its right flank). The move is
//! the smooth bump γ_j = σ (1 − u_j²)², u_j = (x_j − m)/L, m the midpoint of the neighbours
//! x_{i−1}, x_{i+k} and L = √3 · (x_{i+k} − x_{i−1})/2, over the points with |u| < 1: its
//! second derivative is positive exactly between the neighbours (zero at them), so the run
//! shifts in c together, the neighbours stay nearly unchanged and the unavoidable
//! compensation (∫ w'' = 0 for a local move) spreads over the flanks instead of piling on two
//! knots. σ by the "worst member reaches α" rule and the same α rule. Runs touching an end are
//! left alone. With the option on, the fine pass's count guards look at inflections only (a
//! move may add vibrations if it adds no inflection; Phase 1 then works on them), so a full
//! pass never increases Infl_num but may increase Vib_num.
//!
//! Measured (`examples/two_phase_runs.rs`: y = sin(x/2) + N(0, 0.01²) at x = 0.1k, 50 full
//! passes), inflections / vibrations / RMS distance to the clean sine:
//!
//! | n | clean | noisy | paper (`max_run` 2) | `max_run` 64 | `max_run` 64, [`CountGuard::Off`](super::CountGuard::Off) |
//! |---|---|---|---|---|---|
//! | 10^4 | 159 / 166 | 7953 / 8290 / 9.9e-3 | 2219 / 3673 / 6.4e-3 | 1291 / 3426 / 1.4e-2 | 627 / 2906 / 5.3e-2 |
//! | 10^5 | 1591 / 1595 | 79536 / 83342 / 1.0e-2 | 23372 / 36833 / 6.6e-3 | 12946 / 34617 / 1.4e-2 | 6678 / 29804 / 5.7e-2 |
//!
//! The option removes 45 % of the inflections the paper's rules leave (70 % without guards)
//! but does **not** bring the count close to the clean curve's (8× it with the guards, 4×
//! without), and it moves the points farther from the clean curve than the noise itself. At
//! this noise the x–c polyline's noise is ten times its trend and every local move's
//! compensation flips another value; 200 passes change nothing (it stops at 70).
//!
//! Detection: a run is recognised at its first point, values with |c| ≤ 1e-12 · max|c| count
//! as zero (DESIGN.md) and end a run without starting a case. The sweep visits i = 0 … n − 1
//! once and continues after a case's run. Guards as in Phase 1 ([`TwoPhaseSettings`]): size of
//! every move (including the neighbours' −λσ), local and pass count guards.

use curve_repr::SplineFunction;

use super::phase1::{guarded_pass, Case, CaseKind, PassReport};
use super::TwoPhaseSettings;
use crate::Result;

/// The level below which a c value counts as zero: 1e-12 · max |c| (DESIGN.md). O(n).
pub fn zero_level(spline: &SplineFunction) -> f64 {
    1e-12 * spline.c().iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

fn sign(v: f64, zero: f64) -> i8 {
    if v > zero {
        1
    } else if v < -zero {
        -1
    } else {
        0
    }
}

/// The Phase-2 case whose wrong-sign run starts at point i (module doc), runs of up to
/// `max_run` points (2 is the paper). O(n) for the zero level; the pass uses an O(max_run)
/// version.
pub fn detect_fine(spline: &SplineFunction, i: usize, max_run: usize) -> Option<Case> {
    detect_with(spline, i, max_run, zero_level(spline))
}

fn detect_with(spline: &SplineFunction, i: usize, max_run: usize, zero: f64) -> Option<Case> {
    let c = spline.c();
    let n = c.len();
    if n < 5 {
        return None;
    }
    let sg = |k: usize| c.get(k).map_or(0, |&v| sign(v, zero));
    let s = sg(i);
    if s == 0 {
        return None;
    }
    let case = |kind, last: usize| Case {
        kind,
        first: i,
        second: (last > i).then_some(last),
    };
    // Extend the run, scanning one past the longest handled length.
    let longest = max_run.max(2);
    let mut last = i;
    while last + 1 < n && sg(last + 1) == s && last - i < longest {
        last += 1;
    }
    let len = last - i + 1;
    if i == 0 {
        // Left end: c_0 = c_1 (runout) differ from c_2 and c_3.
        return (len == 2 && sg(2) == -s && sg(3) == -s).then(|| case(CaseKind::LargeCurveEnd, 1));
    }
    if sg(i - 1) != -s {
        return None;
    }
    if last + 1 == n {
        // Right end: c_{n−2} = c_{n−1} differ from c_{n−3} and c_{n−4}.
        return (len == 2 && sg(n - 4) == -s).then(|| case(CaseKind::LargeCurveEnd, last));
    }
    if sg(last + 1) != -s {
        return None;
    }
    match len {
        1 => Some(case(CaseKind::SmallCurve, i)),
        2 if i >= 2 && sg(i - 2) == -s && sg(i + 3) == -s => Some(case(CaseKind::LargeCurve, last)),
        2 => None,
        _ if len <= max_run && run_is_smaller_than_flanks(spline, i, last, zero) => {
            Some(case(CaseKind::WrongSignRun, last))
        }
        _ => None,
    }
}

/// ∫|y''| over a run of c values, Σ |c_j| (x_{j+1} − x_{j−1})/2 (one-sided at the ends).
fn run_area(spline: &SplineFunction, first: usize, last: usize) -> f64 {
    let (x, c) = (spline.x(), spline.c());
    let n = x.len();
    (first..=last.min(n - 1))
        .map(|j| c[j].abs() * (x[(j + 1).min(n - 1)] - x[j.saturating_sub(1)]) / 2.0)
        .sum()
}

/// The long-run option's test that the run at first..=last is the noise, not the trend: its
/// area (∫|y''|) is below that of each flanking run (scanned up to `first − last + 1` points
/// further, so O(run)). Han's Case 2 asks the same of its right flank (c_{i+3}).
fn run_is_smaller_than_flanks(spline: &SplineFunction, first: usize, last: usize, zero: f64) -> bool {
    let c = spline.c();
    let n = c.len();
    let len = last - first + 1;
    let s = sign(c[first], zero);
    let mut lo = first - 1;
    while lo > 0 && first - lo <= len && sign(c[lo - 1], zero) == -s {
        lo -= 1;
    }
    let mut hi = last + 1;
    while hi + 1 < n && hi - last <= len && sign(c[hi + 1], zero) == -s {
        hi += 1;
    }
    let area = run_area(spline, first, last);
    area < run_area(spline, lo, first - 1) && area < run_area(spline, last + 1, hi)
}

/// A move pattern: (point, weight).
pub(super) type Pattern = Vec<(usize, f64)>;

/// Σ_j w_j c̃_k^j: the change of c_k per unit of the pattern (Han Eq. 13). O(|pattern|).
fn effect(spline: &SplineFunction, k: usize, pattern: &[(usize, f64)]) -> f64 {
    pattern.iter().map(|&(j, w)| w * spline.sensitivity(k, j)).sum()
}

/// The smallest-magnitude t with every target c_k + t g_k at α or beyond (on α's far side
/// from c_k): all g_k non-zero and of one sign, t = the (α − c_k)/g_k of largest size.
fn reach(spline: &SplineFunction, targets: &[usize], pattern: &[(usize, f64)], alpha: f64) -> Option<f64> {
    let c = spline.c();
    let mut best: Option<f64> = None;
    let mut orientation = 0.0;
    for &k in targets {
        let g = effect(spline, k, pattern);
        if g == 0.0 || !g.is_finite() || g * orientation < 0.0 {
            return None;
        }
        orientation = g;
        let t = (alpha - c.get(k)?) / g;
        if best.is_none_or(|b| t.abs() > b.abs()) {
            best = Some(t);
        }
    }
    best.filter(|t| t.is_finite())
}

fn scaled(pattern: &[(usize, f64)], t: f64) -> Vec<(usize, f64)> {
    pattern.iter().map(|&(j, w)| (j, t * w)).collect()
}

/// What a case moves and aims at.
struct Plan {
    /// One pattern, or two (σ, τ) for Case 2.
    patterns: Vec<Pattern>,
    /// Case 2's one-parameter pattern when its system is ill-conditioned.
    fallback: Pattern,
    targets: Vec<usize>,
    neighbours: Vec<usize>,
    /// The sign the run should take (the neighbours').
    goal: f64,
}

fn plan(spline: &SplineFunction, case: Case, lambda: f64) -> Option<Plan> {
    let (x, c) = (spline.x(), spline.c());
    let n = x.len();
    let i = case.first;
    let last = case.second.unwrap_or(i);
    let goal = -c.get(i)?.signum();
    let targets: Vec<usize> = (i..=last).collect();
    // The parabola through the points next to the neighbours, zero there (module doc).
    let bump = || -> Option<Pattern> {
        let (a, b) = (*x.get(i.checked_sub(2)?)?, *x.get(last + 2)?);
        let half = (b - a) / 2.0;
        Some(
            (i - 1..=last + 1)
                .map(|j| (j, (x[j] - a) * (b - x[j]) / (half * half)))
                .collect(),
        )
    };
    let p = match case.kind {
        CaseKind::SmallCurve if i >= 1 => Plan {
            patterns: vec![vec![(i, 1.0), (i - 1, -lambda), (i + 1, -lambda)]],
            fallback: Vec::new(),
            targets,
            neighbours: vec![i - 1, i + 1],
            goal,
        },
        CaseKind::LargeCurve if i >= 1 => Plan {
            patterns: vec![vec![(i, 1.0), (last, 1.0)], vec![(i - 1, 1.0), (last + 1, 1.0)]],
            fallback: bump()?,
            targets,
            neighbours: vec![i - 1, last + 1],
            goal,
        },
        CaseKind::LargeCurveEnd if i == 0 => Plan {
            patterns: vec![vec![(1, 1.0)]],
            fallback: Vec::new(),
            targets,
            neighbours: vec![2],
            goal,
        },
        CaseKind::LargeCurveEnd if last + 1 == n && i >= 1 => Plan {
            patterns: vec![vec![(n - 2, 1.0)]],
            fallback: Vec::new(),
            targets,
            neighbours: vec![i - 1],
            goal,
        },
        CaseKind::WrongSignRun => Plan {
            patterns: vec![smooth_bump(x, i, last)?],
            fallback: Vec::new(),
            targets,
            neighbours: vec![i - 1, last + 1],
            goal,
        },
        _ => return None,
    };
    Some(p)
}

/// The long-run pattern: w(u) = (1 − u²)² with u = (x − m)/L, m the midpoint of the run's
/// neighbours x_{i−1}, x_{last+1} and L = √3 · (x_{last+1} − x_{i−1})/2, so that w'' > 0
/// exactly between the neighbours (w'' = 0 at |u| = 1/√3): the run shifts in c together, the
/// neighbours are left nearly unchanged and the compensation (∫ w'' = 0) spreads smoothly over
/// the flanks. Points with |u| < 1 move; `None` if that reaches an end point.
fn smooth_bump(x: &[f64], first: usize, last: usize) -> Option<Pattern> {
    let (a, b) = (*x.get(first.checked_sub(1)?)?, *x.get(last + 1)?);
    let m = (a + b) / 2.0;
    let l = 3f64.sqrt() * (b - a) / 2.0;
    let lo = x.partition_point(|&v| v <= m - l);
    let hi = x.partition_point(|&v| v < m + l);
    if lo == 0 || hi >= x.len() {
        return None;
    }
    Some(
        (lo..hi)
            .map(|j| {
                let u = (x[j] - m) / l;
                (j, (1.0 - u * u) * (1.0 - u * u))
            })
            .collect(),
    )
}

/// The moves that bring the plan's targets to α (module doc: exact for one pattern and a
/// well-conditioned Case 2, the bump rule otherwise).
fn solve(spline: &SplineFunction, plan: &Plan, alpha: f64, min_sine: f64) -> Option<Vec<(usize, f64)>> {
    match plan.patterns.as_slice() {
        [p] => reach(spline, &plan.targets, p, alpha).map(|t| scaled(p, t)),
        [ps, pt] => {
            let (&ka, &kb) = (plan.targets.first()?, plan.targets.last()?);
            let c = spline.c();
            let row = |k: usize| (effect(spline, k, ps), effect(spline, k, pt));
            let ((a, b), (d, e)) = (row(ka), row(kb));
            let det = a * e - b * d;
            let norms = a.hypot(b) * d.hypot(e);
            if norms > 0.0 && det.abs() >= min_sine * norms {
                // Exact: both targets reach α (Han Case 2 Step 2).
                let (ra, rb) = (alpha - c.get(ka)?, alpha - c.get(kb)?);
                let sigma = (ra * e - b * rb) / det;
                let tau = (a * rb - d * ra) / det;
                let mut moves = scaled(ps, sigma);
                moves.extend(scaled(pt, tau));
                return moves.iter().all(|m| m.1.is_finite()).then_some(moves);
            }
            // Ill-posed: the one-parameter bump, both members to α or beyond.
            let p = &plan.fallback;
            reach(spline, &plan.targets, p, alpha).map(|t| scaled(p, t))
        }
        _ => None,
    }
}

/// The displacements (point, γ) of Han's Phase-2 rule for `case` with the α rule (module
/// doc); `None` when the rule is degenerate. O(|run|²) sensitivity look-ups.
pub fn fine_displacement(
    spline: &SplineFunction,
    case: Case,
    settings: &TwoPhaseSettings,
) -> Option<Vec<(usize, f64)>> {
    fine_with(spline, case, settings, zero_level(spline))
}

fn fine_with(
    spline: &SplineFunction,
    case: Case,
    settings: &TwoPhaseSettings,
    zero: f64,
) -> Option<Vec<(usize, f64)>> {
    let plan = plan(spline, case, settings.fine_lambda)?;
    let first = solve(spline, &plan, 0.0, settings.pair_min_sine)?;
    // Neighbours after the α = 0 move (Eq. 13); α rule if none changed sign.
    let c = spline.c();
    let mut smallest = f64::INFINITY;
    for &m in &plan.neighbours {
        let predicted = c.get(m)?
            + first
                .iter()
                .map(|&(j, g)| g * spline.sensitivity(m, j))
                .sum::<f64>();
        if f64::from(sign(predicted, zero)) != plan.goal {
            return Some(first);
        }
        smallest = smallest.min(predicted.abs());
    }
    let alpha = plan.goal * smallest / settings.alpha_divisor;
    solve(spline, &plan, alpha, settings.pair_min_sine)
}

/// One fine pass of Phase 2 over the whole segment (module doc), with the guards of
/// [`TwoPhaseSettings`]. O(n · guard_window) (O(n · max_run²) with long runs).
///
/// Errors: bad settings; a failing spline update.
pub fn fine_pass(
    spline: &mut SplineFunction,
    settings: &TwoPhaseSettings,
    movable: &dyn Fn(usize) -> bool,
) -> Result<PassReport> {
    settings.validate()?;
    let zero = zero_level(spline).max(settings.detection_floor * 1e12 * zero_level(spline));
    let find = |spline: &SplineFunction, i: usize| {
        let case = detect_with(spline, i, settings.max_run, zero)?;
        Some((case, fine_with(spline, case, settings, zero)))
    };
    guarded_pass(spline, settings, movable, 0, settings.max_run > 2, &find)
}
