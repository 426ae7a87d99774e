//! Penalised, robustly weighted least squares of a cubic B-spline function of one variable
//! (an edge line alone) or a tensor product of two (the hull), with the smoothing chosen by the
//! discrepancy principle: the smoothest spline whose robust RMS move equals tol/√3, the RMS of
//! an error spread evenly over ±tol (rounding). On Block Island no λ reaches it (its offsets
//! disagree by more than the rounding), and the smallest λ tried (10⁻⁸) is taken: the knot
//! grid, one span per station interval and per waterline, is then the smoother.

#![allow(clippy::needless_range_loop)] // index loops over fixed-size basis arrays read as the book writes them

use crate::spline::{Band, Knots};

/// One observation: the spline at `at` should equal `target`; `free` says how a move of the
/// offset's measured coordinates maps to the residual (see [`Fit::gain`]).
#[derive(Clone, Debug)]
pub(crate) struct Obs {
    /// (x, u): the spline's arguments (u unused in one variable).
    pub at: (f64, f64),
    pub target: f64,
    /// Which coordinates of the offset were measured: the value v, the argument u.
    pub free_v: bool,
    pub free_u: bool,
    /// Held: weighted heavily and never rejected (a knuckle's faired point shared by regions).
    pub held: bool,
    /// Length per unit of u at this offset (the measured coordinate is this times u): 1, or
    /// the knuckle's half-breadth where u is the fraction of the way out to it.
    pub u_scale: f64,
}

impl Obs {
    pub(crate) fn new(at: (f64, f64), target: f64, free_v: bool, free_u: bool) -> Self {
        Self {
            at,
            target,
            free_v,
            free_u,
            held: false,
            u_scale: 1.0,
        }
    }
}

/// Weight of a held observation relative to an offset.
const HELD: f64 = 1e4;

/// A spline of one (`ku` None) or two variables, v = S(x, u).
#[derive(Clone, Debug)]
pub(crate) struct Spline {
    pub kx: Knots,
    pub ku: Option<Knots>,
    /// Coefficients, index i·nu + j.
    pub c: Vec<f64>,
}

impl Spline {
    pub(crate) fn nu(&self) -> usize {
        self.ku.as_ref().map_or(1, Knots::count)
    }

    /// Coefficient indices and weights of S (d = 0), ∂S/∂x (1) or ∂S/∂u (2) at (x, u).
    pub(crate) fn row(&self, x: f64, u: f64, which: usize) -> Vec<(usize, f64)> {
        let sx = self.kx.span(x, false);
        let bx = self.kx.ders(sx, x, 1);
        let nu = self.nu();
        match &self.ku {
            None => (0..4)
                .map(|r| (sx - 3 + r, bx[usize::from(which == 1)][r]))
                .collect(),
            Some(ku) => {
                let su = ku.span(u, false);
                let bu = ku.ders(su, u, 1);
                let (dx, du) = match which {
                    1 => (1, 0),
                    2 => (0, 1),
                    _ => (0, 0),
                };
                let mut out = Vec::with_capacity(16);
                for r in 0..4 {
                    for q in 0..4 {
                        out.push(((sx - 3 + r) * nu + su - 3 + q, bx[dx][r] * bu[du][q]));
                    }
                }
                out
            }
        }
    }

    fn dot(&self, row: &[(usize, f64)]) -> f64 {
        row.iter().map(|&(i, w)| self.c[i] * w).sum()
    }

    /// (S, ∂S/∂x, ∂S/∂u) at (x, u).
    pub(crate) fn eval(&self, x: f64, u: f64) -> (f64, f64, f64) {
        let v = self.dot(&self.row(x, u, 0));
        let vx = self.dot(&self.row(x, u, 1));
        let vu = if self.ku.is_some() {
            self.dot(&self.row(x, u, 2))
        } else {
            0.0
        };
        (v, vx, vu)
    }

    /// The penalty: jumps of the third derivative across every interior knot line, along x and
    /// along u, each weighted by its knot spacing cubed (jump-lsq's measure on a tensor
    /// product: the jump of ∂³S/∂x³ across x = ξ is a spline in u whose coefficients are the
    /// rows below). Returned as the rows r of Σ r rᵀ.
    fn penalty_rows(&self) -> Vec<Vec<(usize, f64)>> {
        let nu = self.nu();
        let mut out = Vec::new();
        for jr in self.kx.jumps() {
            for j in 0..nu {
                out.push(jr.iter().map(|&(i, w)| (i * nu + j, w)).collect());
            }
        }
        if let Some(ku) = &self.ku {
            for jr in ku.jumps() {
                for i in 0..self.kx.count() {
                    out.push(jr.iter().map(|&(j, w)| (i * nu + j, w)).collect());
                }
            }
        }
        out
    }
}

/// The straight-section limit of a surface: v = a(x) + b(x)·s(u), straight in u at every x, with
/// s the u domain mapped onto [0, 1]. A spline is linear in u exactly when its coefficients are
/// a linear function of the u knots' Greville abscissae, c_ij = a_i + b_i s_j, so the fit's
/// unknowns become (a_i, b_i) and every row over c is mapped onto them. This is the limit
/// λ_u → ∞ of a u penalty whose null space is the straight lines (the curvature's), the
/// per-direction limit of the surface method `surface_jump_lsq`: the third-derivative jumps
/// along u vanish on it and drop out.
#[derive(Clone, Debug)]
struct Straight {
    nu: usize,
    /// s_j: the Greville abscissa of coefficient j in [0, 1].
    s: Vec<f64>,
    /// The u domain mapped onto [0, 1].
    range: (f64, f64),
}

impl Straight {
    fn new(ku: &Knots) -> Self {
        let t = &ku.t;
        let nu = ku.count();
        let g: Vec<f64> = (0..nu).map(|j| (t[j + 1] + t[j + 2] + t[j + 3]) / 3.0).collect();
        let (a, b) = (t[0], t[t.len() - 1]);
        Self {
            nu,
            s: g.iter().map(|x| (x - a) / (b - a)).collect(),
            range: (a, b),
        }
    }

    /// A row over the full coefficients as a row over (a_i, b_i) (index 2i, 2i + 1).
    fn map(&self, row: &[(usize, f64)]) -> Vec<(usize, f64)> {
        let mut out: Vec<(usize, f64)> = Vec::with_capacity(8);
        for &(k, w) in row {
            let (i, j) = (k / self.nu, k % self.nu);
            for (idx, v) in [(2 * i, w), (2 * i + 1, w * self.s[j])] {
                match out.iter_mut().find(|e| e.0 == idx) {
                    Some(e) => e.1 += v,
                    None => out.push((idx, v)),
                }
            }
        }
        out
    }

    /// The penalty at the straight limit: across each x knot line ξ the jump of ∂³v/∂x³ is
    /// a line in s, J_a + s·J_b, and its square is averaged over the girth the offsets cover
    /// near ξ (those within a span of it; the whole region where none are), exactly, by
    /// two-point Gauss, and scaled by the count of u coefficients to keep the full penalty's
    /// magnitude. Over the region's whole rectangle instead, a section line that narrows
    /// towards an end (a bottom below a chine that closes in at the bow, extrapolated across the
    /// full beam) would be penalised where there is no hull.
    fn penalty(&self, kx: &Knots, obs: &[Obs], pen: &mut Band) {
        let t = &kx.t;
        let (u0, u1) = (self.range.0, self.range.1);
        for (k, jr) in kx.jumps().into_iter().enumerate() {
            let s = 4 + k;
            let (lo, hi) = (t[s - 1], t[s + 1]);
            let (mut a, mut b) = (f64::MAX, f64::MIN);
            for o in obs.iter().filter(|o| o.at.0 >= lo && o.at.0 <= hi) {
                let v = (o.at.1 - u0) / (u1 - u0);
                a = a.min(v);
                b = b.max(v);
            }
            if a > b {
                (a, b) = (0.0, 1.0);
            }
            let (m, h) = (0.5 * (a + b), 0.5 * (b - a) / 3f64.sqrt());
            for g in [m - h, m + h] {
                let row: Vec<(usize, f64)> = jr
                    .iter()
                    .flat_map(|&(i, w)| [(2 * i, w), (2 * i + 1, w * g)])
                    .collect();
                pen.add_outer(&row, 0.5 * self.nu as f64);
            }
        }
    }

    /// The reduced coefficients of full ones that are straight in u (s_0 = 0, s_last = 1).
    fn unknowns(&self, c: &[f64]) -> Vec<f64> {
        let nx = c.len() / self.nu;
        let mut p = Vec::with_capacity(2 * nx);
        for i in 0..nx {
            let (a, b) = (c[i * self.nu], c[i * self.nu + self.nu - 1]);
            p.extend([a, b - a]);
        }
        p
    }

    /// The full coefficients of the reduced ones.
    fn expand(&self, p: &[f64]) -> Vec<f64> {
        let nx = p.len() / 2;
        let mut c = Vec::with_capacity(nx * self.nu);
        for i in 0..nx {
            c.extend(self.s.iter().map(|s| p[2 * i] + p[2 * i + 1] * s));
        }
        c
    }
}

/// The outcome of a fit.
#[derive(Clone, Debug)]
pub(crate) struct Fit {
    pub spline: Spline,
    /// Smoothing weight (dimensionless: penalty and data both in tolerance units).
    pub lambda: f64,
    /// Per observation: the robust weight (0 = rejected) and the move (residual over gain).
    pub weight: Vec<f64>,
    #[allow(dead_code)]
    pub moves: Vec<f64>,
    pub iterations: usize,
    /// The discrepancy target was reached (some λ moves the offsets by at most tol/√3 RMS).
    pub met: bool,
    /// Fitted at the straight-section limit ([`Straight`]).
    pub straight: bool,
    /// λ is GCV's, not the discrepancy's (see [`fit`]).
    pub by_gcv: bool,
    /// The robust scale of the moves in the final fit (the tolerance, or 1.4826 × their median
    /// absolute value where larger): a move beyond [`REJECT`] of them rejects an offset.
    pub scale: f64,
    /// Per offset of `how.probe`: its deleted move, the move it would have were it left out of
    /// the fit, m_k / (1 − h_kk) with h_kk its leverage (the hat matrix's diagonal entry): a
    /// wrong offset that a flexible fit bends to has a small move and a large deleted one.
    pub deleted_moves: Vec<(usize, f64)>,
}

/// Smallest gain: a residual is converted into a move of the offset's measured coordinates by
/// dividing by the gain |∇F| over those coordinates (F = S − v); where the surface is nearly
/// parallel to the measured direction the gain is small and the move ill-defined, so it is held
/// at this floor.
const MIN_GAIN: f64 = 0.1;
/// Huber's threshold, in robust scales (one rounding step on a table whose error is its rounding).
const HUBER: f64 = 2.0;
/// A move beyond this many robust scales (three rounding steps on a table whose error is its
/// rounding) rejects the offset (weight 0): a wrong offset does not bend the hull.
pub(crate) const REJECT: f64 = 6.0;
const OUTER: usize = 8;
/// Outer iterations fitted stiffer, the last of them deciding the first rejections.
const STIFF: usize = 2;
/// GCV's search above the discrepancy's λ stops after this many quarter decades without a
/// lower score (two decades).
const GCV_PATIENCE: usize = 8;

impl Fit {
    /// |∇F| over the measured coordinates of `o` on spline `s`.
    pub(crate) fn gain(s: &Spline, o: &Obs) -> f64 {
        let (_, _, vu) = s.eval(o.at.0, o.at.1);
        let mut g2 = 0.0;
        if o.free_v {
            g2 += 1.0;
        }
        if o.free_u {
            g2 += (vu / o.u_scale) * (vu / o.u_scale);
        }
        g2.sqrt().max(MIN_GAIN)
    }
}

/// How [`fit`] fits: the plain fit is `How::default()`.
#[derive(Clone, Debug)]
pub(crate) struct How<'a> {
    /// Two variables only: the straight-section limit ([`Straight`]).
    pub straight: bool,
    /// ≥ 1: the discrepancy target of the final fits widened by this factor ([`parsimony_slack`]).
    pub slack: f64,
    /// The final fit's smoothing GCV's where that is smoother (see [`fit`]).
    pub gcv: bool,
    /// Offsets whose deleted (leave-one-out) moves the fit reports ([`Fit::deleted_moves`]).
    pub probe: &'a [usize],
}

impl Default for How<'_> {
    fn default() -> Self {
        Self {
            straight: false,
            slack: 1.0,
            gcv: false,
            probe: &[],
        }
    }
}

/// Fits `obs` by a spline on knots (kx, ku) with tolerance `tol` per offset (half the rounding
/// step by default). Observations with `hold` are fitted with a large weight and never
/// rejected. `how.straight` (two variables only): the straight-section limit ([`Straight`]).
/// `how.slack` (≥ 1) widens the discrepancy target of the final fits by that factor (1: the plain
/// target; see [`parsimony_slack`]). `how.gcv`: once the discrepancy has met its target and
/// settled the weights, the final fit's λ is raised to the minimiser of GCV,
/// V(λ) = n·RSS(λ) / (n − tr H(λ))² (Craven & Wahba 1979; n the offsets fitted, H the weighted
/// hat matrix over them), searched on quarter decades from the discrepancy's λ up (until two
/// decades bring no lower score): the discrepancy takes the tolerance as the offsets' error,
/// and where they are noisier (a noisy table's RMS error is only near its declared value) it
/// spends the freedom on wiggles along the lines (at the straight limit all of it is along x,
/// the waterlines); GCV reads the error from the offsets. Never below the discrepancy's λ, so a
/// table as accurate as declared keeps its fit. Each grid point costs one factorisation and
/// the selected inverse's band, O(N·bw²), N the unknowns.
/// Returns None when the system is singular (too few offsets).
pub(crate) fn fit(kx: Knots, ku: Option<Knots>, obs: &[Obs], tol: f64, how: &How) -> Option<Fit> {
    let (straight, slack, gcv) = (how.straight, how.slack, how.gcv);
    let reduce = if straight {
        ku.as_ref().map(Straight::new)
    } else {
        None
    };
    let nu = ku.as_ref().map_or(1, Knots::count);
    let full = kx.count() * nu;
    // the unknowns: the coefficients, or (a_i, b_i) at the straight limit
    let (n, nun) = match &reduce {
        Some(_) => (kx.count() * 2, 2),
        None => (full, nu),
    };
    // a jump row spans five consecutive x coefficients
    let bw = 4 * nun + 4;
    let mut s = Spline {
        kx,
        ku,
        c: vec![0.0; full],
    };
    let rows: Vec<Vec<(usize, f64)>> = obs.iter().map(|o| s.row(o.at.0, o.at.1, 0)).collect();
    let unknown_rows: Vec<Vec<(usize, f64)>> = match &reduce {
        Some(r) => rows.iter().map(|row| r.map(row)).collect(),
        None => rows.clone(),
    };
    let mut pen = Band::zeros(n, bw);
    match &reduce {
        Some(r) => r.penalty(&s.kx, obs, &mut pen),
        None => {
            for row in s.penalty_rows() {
                pen.add_outer(&row, 1.0);
            }
        }
    }
    let expand = |p: Vec<f64>| -> Vec<f64> {
        match &reduce {
            Some(r) => r.expand(&p),
            None => p,
        }
    };
    let mut gain = vec![1.0; obs.len()];
    let mut robust = vec![1.0; obs.len()];
    let mut lambda: f64 = 1.0;
    let mut met = false;
    let mut by_gcv = false;
    let mut scale = tol;
    let mut deleted_moves = Vec::new();
    let mut moves = vec![0.0; obs.len()];
    let mut it = 0;
    let target = tol / 3f64.sqrt();
    for outer in 0..OUTER {
        it = outer + 1;
        // this iteration's weights, which its system and its measure of the moves use
        let (gain_fit, robust_fit) = (gain.clone(), robust.clone());
        let mut ata = Band::zeros(n, bw);
        let mut atb = vec![0.0; n];
        for (k, (r, o)) in unknown_rows.iter().zip(obs).enumerate() {
            let w = robust[k] / (gain[k] * gain[k]) * if o.held { HELD } else { 1.0 };
            if w == 0.0 {
                continue;
            }
            ata.add_outer(r, w);
            for &(i, v) in r {
                atb[i] += w * v * o.target;
            }
        }
        // a tiny ridge keeps coefficients without data (outside the hull) determined; it pulls
        // toward the previous outer iteration's spline, not toward zero: a pull toward zero,
        // scaled with λ to keep the factorisation definite, shrank every value by up to 1e-2
        // of itself at λ = 10⁸ (a chine's heights 0.3–2 steps low, a Wigley hull's half-breadths
        // 0.3 step narrow); toward the previous iterate the shrinkage of the first fit fades
        // by that factor per iteration
        let prev: Vec<f64> = match &reduce {
            Some(r) => r.unknowns(&s.c),
            None => s.c.clone(),
        };
        let system = |lam: f64| -> (Band, Vec<f64>) {
            let mut m = ata.clone();
            m.add_scaled(&pen, lam);
            let ridge = 1e-10 * (1.0 + lam);
            for row in m.a.iter_mut() {
                row[0] += ridge;
            }
            let rhs: Vec<f64> = atb.iter().zip(&prev).map(|(b, p)| b + ridge * p).collect();
            (m, rhs)
        };
        let solve = |lam: f64| -> Option<Vec<f64>> {
            let (m, rhs) = system(lam);
            m.solve(&rhs).map(expand)
        };
        let rms_move = |c: &[f64]| -> f64 {
            let (mut num, mut den) = (0.0, 0.0);
            for (k, r) in rows.iter().enumerate() {
                if obs[k].held {
                    continue;
                }
                let v: f64 = r.iter().map(|&(i, w)| c[i] * w).sum();
                let m = (v - obs[k].target) / gain_fit[k];
                num += robust_fit[k] * m * m;
                den += robust_fit[k];
            }
            (num / den.max(1e-300)).sqrt()
        };
        // the discrepancy principle: the largest λ whose robust RMS move is at most the RMS of
        // an error spread evenly over ±tol (rounding to the nearest step): tol/√3
        // the first two fits are stiffer (four times the move): an offset in conflict with a
        // neighbour at the same point then stands out against the fair trend of all the others
        // instead of sharing the conflict with it
        let goal = if outer < STIFF {
            4.0 * target
        } else {
            slack * target
        };
        // after the first fit, λ is searched near the previous one (the weights change little)
        let (mut lo, mut hi) = if outer == 0 {
            (-8.0f64, 8.0f64)
        } else {
            ((lambda.log10() - 3.0).max(-8.0), (lambda.log10() + 3.0).min(8.0))
        };
        let mut best: Option<(f64, Vec<f64>)> = None;
        // the straight limit is taken only when some λ reaches the target, so where the window
        // near the previous λ does not, its fit searches the whole range below (a window's
        // edge, not the offsets, decided it otherwise: the hard-chine bottom missed the
        // target by 0.3 % at the window's edge, 10³ above the λ that meets it)
        let mut at_lo = solve(10f64.powf(lo));
        if reduce.is_some()
            && outer >= STIFF
            && lo > -8.0
            && at_lo.as_ref().is_some_and(|c| rms_move(c) > goal)
        {
            hi = lo;
            lo = -8.0;
            at_lo = solve(10f64.powf(lo));
        }
        if let Some(c) = at_lo {
            if rms_move(&c) > goal {
                best = Some((lo, c));
                hi = lo;
            }
        }
        if best.is_none() {
            for _ in 0..24 {
                let mid = 0.5 * (lo + hi);
                let c = solve(10f64.powf(mid))?;
                if rms_move(&c) <= goal {
                    lo = mid;
                    best = Some((mid, c));
                } else {
                    hi = mid;
                }
                if hi - lo < 0.05 {
                    break;
                }
            }
        }
        let (l, c) = match best {
            Some(b) => b,
            None => (lo, solve(10f64.powf(lo))?),
        };
        met = rms_move(&c) <= goal * (1.0 + 1e-9);
        lambda = 10f64.powf(l);
        s.c = c;
        // new gains and moves; the robust scale: the tolerance, or the moves' own spread
        // (1.4826 × their median absolute value) where that is larger (a table noisier than
        // its rounding), so that noise is not mistaken for wrong offsets
        for (k, (r, o)) in rows.iter().zip(obs).enumerate() {
            gain[k] = Fit::gain(&s, o);
            let v: f64 = r.iter().map(|&(i, w)| s.c[i] * w).sum();
            moves[k] = (v - o.target) / gain[k];
        }
        let mut abs: Vec<f64> = moves.iter().map(|m| m.abs()).collect();
        abs.sort_by(f64::total_cmp);
        scale = tol.max(1.4826 * abs[abs.len() / 2]);
        let mut changed = false;
        for k in 0..obs.len() {
            let a = moves[k].abs() / scale;
            let w = if obs[k].held {
                1.0
            } else if outer + 1 >= STIFF && a > REJECT {
                0.0
            } else if a > HUBER {
                HUBER / a
            } else {
                1.0
            };
            if (w - robust[k]).abs() > 1e-3 {
                changed = true;
            }
            robust[k] = w;
        }
        let last = (!changed && outer > STIFF) || outer + 1 == OUTER;
        if last {
            // the probed offsets' leverages in this fit's system (its weights): one
            // factorisation, a solve each (a held or rejected offset has none)
            if !how.probe.is_empty() {
                let (m, _) = system(lambda);
                let rows: Vec<(&[(usize, f64)], f64)> = how
                    .probe
                    .iter()
                    .map(|&k| {
                        let w = robust_fit[k] / (gain_fit[k] * gain_fit[k]);
                        (unknown_rows[k].as_slice(), if obs[k].held { 0.0 } else { w })
                    })
                    .collect();
                for (&k, h) in how.probe.iter().zip(m.leverages(&rows)?) {
                    deleted_moves.push((k, moves[k] / (1.0 - h).max(1e-12)));
                }
            }
        }
        // the final fit's λ GCV's where that is smoother (offsets noisier than the tolerance
        // declares; see the doc above), with the weights and rejections the discrepancy decided
        if last && gcv && met {
            let active: Vec<(&[(usize, f64)], f64)> = unknown_rows
                .iter()
                .enumerate()
                .filter(|&(k, _)| !obs[k].held && robust_fit[k] > 0.0)
                .map(|(k, r)| (r.as_slice(), robust_fit[k] / (gain_fit[k] * gain_fit[k])))
                .collect();
            let count = active.len() as f64;
            let mut hat = Band::zeros(n, bw);
            for (r, w) in &active {
                hat.add_outer(r, *w);
            }
            let score = |lg: f64| -> Option<(f64, Vec<f64>)> {
                let (m, rhs) = system(10f64.powf(lg));
                let (c, tr) = m.solve_with_trace(&rhs, &hat)?;
                let c = expand(c);
                let rms = rms_move(&c);
                (count - tr > 0.5).then(|| (count * rms * rms / ((count - tr) * (count - tr)), c))
            };
            let l0 = lambda.log10();
            let mut pick: Option<(f64, Vec<f64>)> = None;
            let mut best_score = score(l0).map_or(f64::INFINITY, |s| s.0);
            // quarter decades up to 10⁸, until the score has stayed above its best for two
            // decades (GCV's minimum above the discrepancy's λ, not a distant second one)
            let (mut lg, mut worse) = (l0 + 0.25, 0);
            while lg <= 8.0 && worse < GCV_PATIENCE {
                match score(lg) {
                    Some((v, c2)) if v < best_score => {
                        best_score = v;
                        pick = Some((lg, c2));
                        worse = 0;
                    }
                    _ => worse += 1,
                }
                lg += 0.25;
            }
            if let Some((lg, c2)) = pick {
                lambda = 10f64.powf(lg);
                by_gcv = true;
                s.c = c2;
                for (k, (r, o)) in rows.iter().zip(obs).enumerate() {
                    gain[k] = Fit::gain(&s, o);
                    let v: f64 = r.iter().map(|&(i, w)| s.c[i] * w).sum();
                    moves[k] = (v - o.target) / gain[k];
                }
            }
        }
        if last {
            break;
        }
    }
    Some(Fit {
        spline: s,
        lambda,
        weight: robust,
        moves,
        iterations: it,
        met,
        straight: reduce.is_some(),
        by_gcv,
        scale,
        deleted_moves,
    })
}

/// The discrepancy target's slack for a simpler model (the straight-section limit): the RMS
/// move of n offsets whose errors have the target's spread is itself uncertain, its square's
/// relative standard error √(2/n) (a χ² with n degrees of freedom), so a model that misses
/// the target by less than that cannot be told from one that meets it (the one-standard-error
/// rule, Breiman et al. 1984; Hastie, Tibshirani & Friedman, *The Elements of Statistical
/// Learning*, §7.10). Returned as the factor on the RMS: √(1 + √(2/n)), n the offsets not held.
pub(crate) fn parsimony_slack(obs: &[Obs]) -> f64 {
    let n = obs.iter().filter(|o| !o.held).count().max(1) as f64;
    (1.0 + (2.0 / n).sqrt()).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parsimony_slack_is_one_standard_error_of_the_squared_rms() {
        // the defining condition: for n errors of the target's spread, the squared RMS over
        // the target's square has standard deviation slack² − 1 (sampled here, 20 000 draws)
        let mut rng = crate::generate::Rng(0x9E37_79B9_7F4A_7C15);
        for n in [12usize, 72, 400] {
            let obs: Vec<Obs> = (0..n)
                .map(|k| Obs::new((k as f64, 0.0), 0.0, true, false))
                .collect();
            let slack = parsimony_slack(&obs);
            let draws: Vec<f64> = (0..20_000)
                .map(|_| (0..n).map(|_| rng.normal().powi(2)).sum::<f64>() / n as f64)
                .collect();
            let mean = draws.iter().sum::<f64>() / draws.len() as f64;
            let sd =
                (draws.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (draws.len() - 1) as f64).sqrt();
            let want = slack * slack - 1.0;
            assert!(
                (sd / want - 1.0).abs() < 0.03,
                "n {n}: sampled sd {sd}, slack² − 1 = {want}"
            );
        }
    }

    #[test]
    fn offsets_on_a_line_far_from_zero_are_fitted_without_shrinkage() {
        // exact offsets in the penalty's null space: the discrepancy principle takes the
        // largest λ, and the ridge that keeps the system definite must not pull the values
        // toward zero there
        let obs: Vec<Obs> = (0..16)
            .map(|k| {
                let x = 15.0 * k as f64;
                Obs::new((x, 0.0), 1000.0 + 2.0 * x, true, false)
            })
            .collect();
        let f = fit(
            Knots::uniform(0.0, 225.0, 15),
            None,
            &obs,
            0.0625,
            &How::default(),
        )
        .unwrap();
        assert!(f.lambda > 1e6, "{}", f.lambda);
        for o in &obs {
            let v = f.spline.eval(o.at.0, 0.0).0;
            // a millionth of the value (a pull toward zero at λ = 10⁸ left 10⁻²)
            assert!((v - o.target).abs() < 1e-3, "{} -> {v}", o.target);
        }
    }
}
