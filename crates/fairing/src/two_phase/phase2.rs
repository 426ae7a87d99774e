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
//! | [`CaseKind::WrongSignRun`] (option, not in the paper) | c_i … c_{i+k−1} of sign s, 3 ≤ k ≤ `max_run`, c_{i−1}, c_{i+k} of sign −s | the exact local y move of the absorption below (run and flanks) | every c̃ of the run = α, the flanks scaled by 1 − μ, c elsewhere unchanged |
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
//! [`PAIR_MIN_SINE`] (0.05, not in the paper). Otherwise we fix the ratio τ/σ: the
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
//! Such a run is *absorbed into its flanks* by a move designed in c rather than in y. A y move
//! on finitely many points changes c only locally when the change δc meets two moment
//! conditions, ∫ δy'' = 0 and ∫ x δy'' = 0 in their discrete form
//! ([`SplineFunction::local_y_change`], derived from the three-moment rows, Han Eq. 4); then
//! the y move is found by integrating twice, exactly. The move sets every c of the run to
//! α = s_flank · min(|c_{i−1}|, |c_{i+k}|)/`alpha_divisor` (the α rule's fifth of the smaller
//! neighbour) and scales each flank (points next to the run within the adjacent runs of the
//! other sign, up to `max_run` of them) by one factor 1 − μ_L, 1 − μ_R; the two factors solve
//! the 2 × 2 moment system ([`absorption_factors`]). It needs 0 < μ ≤ 1 − 1/`alpha_divisor`:
//! each flank keeps its sign and at least a fifth of itself, a lever rule (the run's ∫|y''|,
//! weighted by its distance to the other flank, must be smaller than each flank's: the
//! condition that says which of two alternating runs is the noise). The flanks are the
//! *shortest* that qualify, grown one point per side at a time: δy is the double integral of
//! δc, so wide flanks move y far (at n = 10^5 in the table below, flanks as wide as their runs
//! (up to `max_run`) ended at RMS 2.1e-2 and 2133 inflections for σ = 0.01, 2.8e-3 and 1615
//! for σ = 0.001; the shortest at 1.2e-2 / 1909 and 1.4e-3 / 1611). When the move is made,
//! c changes on the run and its flanks only, all of them end with the flanks' sign, and
//! Infl_num falls by exactly 2 (tested on a fresh spline). Runs within two points of an end
//! are left alone.
//!
//! With the option on, the fine pass's count guards look at inflections only (a move may add
//! vibrations if it adds no inflection; Phase 1 then works on them), and in a
//! [`full_pass`](super::full_pass) the coarse pass first runs without count guards; a full
//! pass that ends with more inflections than it began with is undone and redone with the
//! coarse moves guarded. On noise, Phase 1 turns short wrong-sign runs into runs the
//! absorption can take, adding inflections on the way that Phase 2 removes; guarding every
//! coarse move blocked that (with wide flanks: 9738 inflections left at 10^5, σ = 0.01,
//! against 2133 with the full-pass guard). So a full pass never increases Infl_num but may
//! increase Vib_num.
//!
//! On dense noisy sines (`examples/two_phase_runs.rs`) the option leaves about the clean
//! curve's inflection count where the paper's rules leave many times it, and fewer
//! vibrations. The price is distance: with the default size guard the points end about as far
//! from the clean curve as the noise.
//! It is meant for dense noisy data: on the sparse real curves of `examples/han_tables.rs` it
//! moves the points much farther than the paper's rules. Without the count guards it ends
//! several times farther from the truth with about as many inflections. The measured table
//! is in `docs/experiments/code-notes.md`.
//!
//! Detection: a run is recognised at its first point, values with |c| ≤ 1e-12 · max|c| count
//! as zero (docs/CONTRACT.md) and end a run without starting a case. The sweep visits i = 0 … n − 1
//! once and continues after a case's run. Guards as in Phase 1 ([`TwoPhaseSettings`]): size of
//! every move (including the neighbours' −λσ), local and pass count guards.

use curve_repr::{EndCondition, SplineFunction};

use super::phase1::{guarded_pass, Case, CaseKind, PassReport, Proposal};
use super::{Rules, TwoPhaseSettings, PAIR_MIN_SINE};
use crate::Result;

/// The level below which a c value counts as zero: 1e-12 · max |c| (docs/CONTRACT.md). O(n).
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

/// [`detect_fine`] at the zero level `zero`.
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
    // A run starts at i only after a value of the other sign (or at the left end): checked
    // before the scan, so that a long run is not rescanned from each of its points.
    if i > 0 && sg(i - 1) != -s {
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
    // Beyond the paper (long-run option): a wrong-sign run at an end that the paper's end
    // case does not take, of up to `max_run` points and no longer than the run of the other
    // sign next to it (of two alternating runs, the shorter is taken for the noise).
    let end_run = max_run > 2 && len <= max_run && len + 3 <= n;
    let run_of = |mut k: usize, step: isize| {
        let mut length = 0;
        while length < len && sg(k) == -s {
            length += 1;
            match k.checked_add_signed(step) {
                Some(next) if next < n => k = next,
                _ => break,
            }
        }
        length
    };
    if i == 0 {
        // Left end: c_0 = c_1 (runout) differ from c_2 and c_3.
        if len == 2 && sg(2) == -s && sg(3) == -s {
            return Some(case(CaseKind::LargeCurveEnd, 1));
        }
        return (end_run && last + 1 < n && run_of(last + 1, 1) >= len).then(|| case(CaseKind::EndRun, last));
    }
    if sg(i - 1) != -s {
        return None;
    }
    if last + 1 == n {
        // Right end: c_{n−2} = c_{n−1} differ from c_{n−3} and c_{n−4}.
        if len == 2 && sg(n - 4) == -s {
            return Some(case(CaseKind::LargeCurveEnd, last));
        }
        return (end_run && run_of(i - 1, -1) >= len).then(|| case(CaseKind::EndRun, last));
    }
    if sg(last + 1) != -s {
        return None;
    }
    match len {
        1 => Some(case(CaseKind::SmallCurve, i)),
        2 if i >= 2 && sg(i - 2) == -s && sg(i + 3) == -s => Some(case(CaseKind::LargeCurve, last)),
        2 => None,
        _ if len <= max_run => Some(case(CaseKind::WrongSignRun, last)),
        _ => None,
    }
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
        _ => return None,
    };
    Some(p)
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
    fine_with(spline, case, settings, zero_level(spline)).map(|p| p.moves)
}

fn fine_with(
    spline: &SplineFunction,
    case: Case,
    settings: &TwoPhaseSettings,
    zero: f64,
) -> Option<Proposal> {
    if case.kind == CaseKind::WrongSignRun {
        return absorb(spline, case, settings, zero);
    }
    if case.kind == CaseKind::EndRun {
        return absorb_at_end(spline, case, settings, zero);
    }
    let plan = plan(spline, case, settings.fine_lambda)?;
    let first = solve(spline, &plan, 0.0, PAIR_MIN_SINE)?;
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
            return Some(first.into());
        }
        smallest = smallest.min(predicted.abs());
    }
    let alpha = plan.goal * smallest / settings.alpha_divisor;
    solve(spline, &plan, alpha, PAIR_MIN_SINE).map(Proposal::from)
}

/// The long-run option's move (module doc, "Runs of more than two points"): the wrong-sign
/// run `case.first ..= case.second` takes the constant α of the neighbours' sign, and its two
/// flanks (within the neighbouring runs of that sign, up to `max_run` points each, kept two
/// points from the ends) shrink by the factors 1 − μ_L and 1 − μ_R that make the change of c
/// local (the two moment conditions of [`SplineFunction::local_y_change`], a 2 × 2 system in
/// μ_L, μ_R). The flanks are the shortest that can take the run: grown one point per side at
/// a time (a side stops at the end of its run), the first extent with 0 < μ ≤
/// 1 − 1/`alpha_divisor` on both sides is taken, so that the flanks keep their sign and at
/// least |α|, and the y move, the double integral of δc, spreads no farther than it must;
/// `None` if no extent qualifies ([`absorption_factors`] solves one extent). The y move is
/// exact and local: c changes on the run and its flanks only, every value there ends with the
/// neighbours' sign, and Infl_num falls by exactly 2; the pass applies it exactly, with
/// [`SplineFunction::change_c_locally`]. O(run + flanks).
fn absorb(spline: &SplineFunction, case: Case, settings: &TwoPhaseSettings, zero: f64) -> Option<Proposal> {
    let (x, c) = (spline.x(), spline.c());
    let n = c.len();
    let (i, last) = (case.first, case.second?);
    let goal = -sign(*c.get(i)?, zero);
    let cap = settings.max_run.max(2);
    if i < 3 || last + 4 > n || sign(c[i - 1], zero) != goal || sign(c[last + 1], zero) != goal {
        return None;
    }
    // The widest flanks: the neighbouring runs of the goal's sign, capped.
    let mut lo_max = i - 1;
    while lo_max > 2 && i - lo_max < cap && sign(c[lo_max - 1], zero) == goal {
        lo_max -= 1;
    }
    let mut hi_max = last + 1;
    while hi_max + 4 <= n && hi_max - last < cap && sign(c[hi_max + 1], zero) == goal {
        hi_max += 1;
    }
    let alpha = f64::from(goal) * c[i - 1].abs().min(c[last + 1].abs()) / settings.alpha_divisor;
    let limit = 1.0 - 1.0 / settings.alpha_divisor;
    let origin = (x[i] + x[last]) / 2.0;
    let add = |sum: &mut (f64, f64), k: usize, value: f64| {
        let (w1, w2) = spline.moment_weights(k, origin);
        sum.0 += w1 * value;
        sum.1 += w2 * value;
    };
    let mut run = (0.0, 0.0);
    for (k, &value) in c.iter().enumerate().take(last + 1).skip(i) {
        add(&mut run, k, alpha - value);
    }
    let (mut left_sum, mut right_sum) = ((0.0, 0.0), (0.0, 0.0));
    let (mut lo, mut hi) = (i, last);
    let (left, right) = loop {
        let grow_left = lo > lo_max;
        if grow_left {
            lo -= 1;
            add(&mut left_sum, lo, c[lo]);
        }
        let grow_right = hi < hi_max;
        if grow_right {
            hi += 1;
            add(&mut right_sum, hi, c[hi]);
        }
        if !grow_left && !grow_right {
            return None;
        }
        if let Some((left, right)) = flank_factors(left_sum, right_sum, run) {
            if left > 0.0 && left <= limit && right > 0.0 && right <= limit {
                break (left, right);
            }
        }
    };
    let dc: Vec<f64> = (lo..=hi)
        .map(|k| {
            if k < i {
                -left * c[k]
            } else if k <= last {
                alpha - c[k]
            } else {
                -right * c[k]
            }
        })
        .collect();
    let dy = spline.local_y_change(lo, &dc).ok()?;
    Some(Proposal {
        moves: (lo..=hi).zip(dy).filter(|&(_, d)| d != 0.0).collect(),
        c_change: Some((lo, dc)),
    })
}

/// The long-run option's move for a wrong-sign run at an end of the segment
/// ([`CaseKind::EndRun`]): the run (which holds the end point, whose y never moves) takes the
/// constant α of the other sign (a fifth of its one neighbour, `alpha_divisor`), and one
/// flank, the points after it within the next run of that sign, shrinks by 1 − μ so that the
/// change of c is local ([`end_y_change`]: at an end the slope is free, so one moment
/// condition remains and one factor meets it). The flank is the shortest that qualifies with
/// 0 < μ ≤ 1 − 1/`alpha_divisor`, grown one point at a time up to `max_run` points and kept
/// two points from the other end; `None` if none does. Only for the parabolic runout (whose
/// end row c_0 = c_1 the move keeps: both are set to α). O(run + flank).
fn absorb_at_end(
    spline: &SplineFunction,
    case: Case,
    settings: &TwoPhaseSettings,
    zero: f64,
) -> Option<Proposal> {
    if spline.end_condition() != EndCondition::ParabolicRunout {
        return None;
    }
    let (x, c) = (spline.x(), spline.c());
    let n = c.len();
    let (first, last) = (case.first, case.second?);
    // Positions count from the end the run touches (mirrored at the right end: the rows of
    // the three-moment system are symmetric under x → −x).
    let left = first == 0;
    if !left && last + 1 != n {
        return None;
    }
    let index = |p: usize| if left { p } else { n - 1 - p };
    let h = |p: usize| {
        if left {
            x[p + 1] - x[p]
        } else {
            x[n - 1 - p] - x[n - 2 - p]
        }
    };
    let value = |p: usize| c[index(p)];
    let run = last - first + 1;
    let goal = -sign(value(0), zero);
    if goal == 0 || sign(value(run), zero) != goal || sign(value(0), zero) != -goal {
        return None;
    }
    let alpha = f64::from(goal) * value(run).abs() / settings.alpha_divisor;
    let limit = 1.0 - 1.0 / settings.alpha_divisor;
    let cap = settings.max_run.max(2);
    // δy at the window's far end is −Σ_p w_p δc_p (the one moment condition of
    // [`end_y_change`], about the end point): w_p = h_{p−1}X_{p−1} + 2(h_{p−1} + h_p)X_p +
    // h_p X_{p+1}, X_p the distance of position p from the end. So the run's part is summed
    // once and the flank's grows by one term a point: O(flank), not O(flank²).
    let mut distance = vec![0.0; 1];
    let mut weight = |p: usize| {
        while distance.len() <= p + 1 {
            let q = distance.len() - 1;
            let next = distance[q] + h(q);
            distance.push(next);
        }
        let before = if p == 0 { 0.0 } else { h(p - 1) * distance[p - 1] };
        let around = if p == 0 { h(p) } else { h(p - 1) + h(p) };
        before + 2.0 * around * distance[p] + h(p) * distance[p + 1]
    };
    let a: f64 = (0..run).map(|p| (alpha - value(p)) * weight(p)).sum();
    let mut b = 0.0;
    let mut hi = run - 1;
    loop {
        if hi + 1 - run >= cap || hi + 4 > n || sign(value(hi + 1), zero) != goal {
            return None;
        }
        hi += 1;
        b += value(hi) * weight(hi);
        let mu = a / b;
        if !(mu.is_finite() && mu > 0.0 && mu <= limit) {
            continue;
        }
        let dc: Vec<f64> = (0..=hi)
            .map(|p| if p < run { alpha - value(p) } else { -mu * value(p) })
            .collect();
        let dy = end_y_change(&h, &dc);
        return Some(Proposal {
            moves: (1..=hi)
                .filter_map(|p| Some((index(p), *dy.get(p)?)))
                .filter(|&(_, d)| d != 0.0)
                .collect(),
            c_change: None,
        });
    }
}

/// The y change at an end of a spline function that changes c by `dc` on the end positions
/// 0 … len − 1 (`dc.len()` = len; position 0 is the end point, `h(p)` the spacing from
/// position p to p + 1), keeps δy_0 = 0 and leaves the slope beyond the window unchanged:
/// δy_0 … δy_len, of which δy_len must vanish for the change to be local.
///
/// The rows 1 … len of the three-moment system (Han Eq. 4) change by
/// r_k = h_{k−1}δc_{k−1} + 2(h_{k−1} + h_k)δc_k + h_k δc_{k+1} = δm_k − δm_{k−1}; at an end
/// the first slope change δm_0 is free, so it is chosen to make δm_len = δm_0 + Σ r_k = 0,
/// and δy_{k+1} = δy_k + h_k δm_k. The remaining condition δy_len = 0 is the one moment
/// condition of an end window (the interior windows of [`SplineFunction::local_y_change`]
/// have two). O(len).
pub fn end_y_change(h: &dyn Fn(usize) -> f64, dc: &[f64]) -> Vec<f64> {
    let len = dc.len();
    let at = |p: usize| dc.get(p).copied().unwrap_or(0.0);
    let mut partial = Vec::with_capacity(len);
    let mut sum = 0.0;
    for k in 1..=len {
        sum += h(k - 1) * at(k - 1) + 2.0 * (h(k - 1) + h(k)) * at(k) + h(k) * at(k + 1);
        partial.push(sum);
    }
    let start = -sum;
    let mut dy = Vec::with_capacity(len + 1);
    dy.push(0.0);
    let mut y = 0.0;
    for k in 0..len {
        let slope = start + if k == 0 { 0.0 } else { partial[k - 1] };
        y += h(k) * slope;
        dy.push(y);
    }
    dy
}

/// The flank factors (μ_L, μ_R) of the long-run absorption (module doc): the change of c that
/// is −μ_L c on lo..i−1, α − c on the run i..=last and −μ_R c on last+1..=hi meets both
/// moment conditions of
/// [`SplineFunction::local_y_change`] (weights [`SplineFunction::moment_weights`] about the
/// run's middle). `None` if the 2 × 2 system is singular. O(hi − lo).
pub fn absorption_factors(
    spline: &SplineFunction,
    lo: usize,
    i: usize,
    last: usize,
    hi: usize,
    alpha: f64,
) -> Option<(f64, f64)> {
    let (x, c) = (spline.x(), spline.c());
    let origin = (x[i] + x[last]) / 2.0;
    let sums = |range: std::ops::RangeInclusive<usize>, value: &dyn Fn(usize) -> f64| {
        range.fold((0.0, 0.0), |(s1, s2), k| {
            let (w1, w2) = spline.moment_weights(k, origin);
            (s1 + w1 * value(k), s2 + w2 * value(k))
        })
    };
    flank_factors(
        sums(lo..=i - 1, &|k| c[k]),
        sums(last + 1..=hi, &|k| c[k]),
        sums(i..=last, &|k| alpha - c[k]),
    )
}

/// μ_L (l1, l2) + μ_R (f1, f2) = (r1, r2) from the moment sums of the left flank, the right
/// flank and the run's change; `None` if singular or not finite. O(1).
fn flank_factors(left: (f64, f64), right: (f64, f64), run: (f64, f64)) -> Option<(f64, f64)> {
    let ((l1, l2), (f1, f2), (r1, r2)) = (left, right, run);
    let det = l1 * f2 - f1 * l2;
    if !det.is_finite() || det.abs() <= 1e-12 * l1.hypot(l2) * f1.hypot(f2) {
        return None;
    }
    let mu_left = (r1 * f2 - f1 * r2) / det;
    let mu_right = (l1 * r2 - r1 * l2) / det;
    (mu_left.is_finite() && mu_right.is_finite()).then_some((mu_left, mu_right))
}

/// One fine pass of Phase 2 over the whole segment (module doc), with the guards of
/// [`TwoPhaseSettings`]. O(n · guard window) (O(n · max_run²) with long runs).
///
/// Errors: bad settings; a failing spline update.
pub fn fine_pass(
    spline: &mut SplineFunction,
    settings: &TwoPhaseSettings,
    movable: &dyn Fn(usize) -> bool,
) -> Result<PassReport> {
    fine_pass_from(spline, &Rules::direct(settings), movable, None)
}

/// [`fine_pass`] given the spline's [`counts`](super::counts) if the caller knows them.
pub(super) fn fine_pass_from(
    spline: &mut SplineFunction,
    settings: &Rules,
    movable: &dyn Fn(usize) -> bool,
    known: Option<(usize, usize)>,
) -> Result<PassReport> {
    settings.validate()?;
    let zero = zero_level(spline);
    let find = |spline: &SplineFunction, _: &[f64], i: usize| {
        let case = detect_with(spline, i, settings.max_run, zero)?;
        Some((case, fine_with(spline, case, settings, zero)))
    };
    guarded_pass(spline, settings, movable, 0, settings.max_run > 2, known, &find)
}
