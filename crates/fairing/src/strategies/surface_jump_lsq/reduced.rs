//! A reduced basis along a long direction: each of its lines a cubic spline on a subset of
//! the sites (a P-spline), so that the direction's problem is of a fixed size and the cost of
//! the method is linear in the nodes.
//!
//! # What
//!
//! Along a direction of m sites t_0 < … < t_{m−1} (and the period's end t_m on a closed one)
//! the exact method's line is the natural (periodic) cubic spline through its m values. The
//! reduced line is the natural (periodic) cubic spline s through M values c at the knots
//! τ = a subset of the sites (both ends among them on an open direction), spread by count;
//! its values at the sites are x = N c, and its penalty the same scaled third-derivative
//! jumps (module `operator`) across its own knots, cᵀ K' c with K' = D'ᵀD', D' the jump
//! operator of τ. So the penalty's null space is still the lines (open; s″ = 0 at both ends)
//! or the constants (closed), and with τ = all the sites N = I and the reduced problem is the
//! exact one.
//!
//! With moments M = G c (G = A⁻¹B, the spline's tridiagonal moment system on τ) the value at
//! a site t in the span [τ_k, τ_{k+1}] of length h is
//!
//! ```text
//! s(t) = a c_k + b c_{k+1} + (a³ − a) h²/6 M_k + (b³ − b) h²/6 M_{k+1},
//! a = (τ_{k+1} − t)/h, b = (t − τ_k)/h,
//! ```
//!
//! so N = E_c + E_M G with E_c, E_M of two entries a row: N c and Nᵀy cost O(m + M) per
//! line (G applied by its tridiagonal system, not as the dense matrix). The direction's data
//! term is cᵀ NᵀN c − 2 cᵀ Nᵀ y, and its part of the normal equations the generalised
//! eigenproblem (K', NᵀN): with NᵀN = L Lᵀ (Cholesky; N has full
//! column rank, its rows at the knots being unit rows) and L⁻¹ K' L⁻ᵀ = U diag(μ) Uᵀ, the
//! columns of T = N L⁻ᵀ U are orthonormal, span the reduced space, and diagonalise the
//! penalty, so module `spectral`'s entrywise solve, GCV's RSS and trace as spectral sums and
//! the λ → ∞ limits hold unchanged with T in place of the exact eigenbasis; the RSS gains the
//! (λ-independent) part of the data outside the reduced space.
//!
//! # Held ends
//!
//! On an open direction whose first or last line is held (a boundary under `g0`, a pole) the
//! spline's value at that end knot is the held value: those coefficients leave the unknowns,
//! the sites' data lose N's held columns times them (a shift of the data) and the penalty
//! couples the free coefficients to them through K'[free, held] (a coupling in coefficient
//! space, [`Basis::t_left`] with `data = false`). With τ = all the sites this is again the
//! exact method's held lines.
//!
//! # Both directions
//!
//! With both directions reduced the block is X = N_u C N_vᵀ over the two bases'
//! coefficients, whose border rows and columns belong to the held ends. A held edge's data
//! along the other direction is not a spline of that basis, so the border is its projection
//! onto the free splines (the Galerkin form of the problem): the edge's data h less the other
//! direction's end splines through the corners, h' = h − P⁰_corners N_vEᵀ, projected; the
//! corners' product N_uE P⁰_corners N_vEᵀ once. The data are shifted by that border and the
//! solution gets it back. Next to a held edge the fit thus follows the edge's data as far as
//! the basis can (the edge's nodes themselves are held bit for bit): adding back the edge's
//! noise outside the basis would leave it unsmoothed on the lines beside the edge, and the
//! refusal rule turned such fits down. The other direction's penalty meets the border through
//! h''s projection, in that direction's eigenbasis ν_b times the transformed shift (μ_a for
//! held columns). Tested against the normal equations solved densely (held rows; every edge
//! held), 13–14 knots a direction.
//!
//! # Cost
//!
//! Building: O(m) for E and EᵀE, O(M³) for G, NᵀN = [I; G]ᵀ EᵀE [I; G], the Cholesky factor,
//! L⁻¹K'L⁻ᵀ and its eigendecomposition; memory O(m + M²). Each transform of an m × n block
//! O(m·n + M²·n), the M²·n the dense eigenbasis W. Linear in the nodes for a fixed M.

use faer::linalg::solvers::Solve;
use nalgebra::DMatrix;

use crate::state::strategy_error;
use crate::Result;

use super::operator::{gram, jump_matrix};
use super::spectral::{refine_bottom, symmetric_eigen};
use super::NAME;

/// The site indices of the reduced knots: `count` of the `sites` spread by count, the first
/// and (open) the last among them. Strictly increasing when `count ≤ sites`.
pub(crate) fn knot_sites(sites: usize, count: usize, closed: bool) -> Vec<usize> {
    let count = count.min(sites);
    if closed {
        (0..count)
            .map(|k| (k * sites + count / 2) / count)
            .map(|i| i.min(sites - 1))
            .collect()
    } else {
        (0..count)
            .map(|k| ((k * (sites - 1)) as f64 / (count - 1) as f64).round() as usize)
            .collect()
    }
}

/// One direction's reduced basis (module docs).
pub(crate) struct Reduced {
    /// The sites of the block (free sites of the direction), count.
    sites: usize,
    /// Per block site: the span k, the weights (a, b) on c_k, c_{k+1} and (α, β) on the
    /// moments M_k, M_{k+1}, k + 1 taken modulo the knot count on a closed direction.
    rows: Vec<(usize, usize, [f64; 4])>,
    /// The moments of the full coefficient vector, M = G c, as products with G and Gᵀ.
    moments: Box<MomentMap>,
    /// The free coefficients (knot indices), in order.
    free: Vec<usize>,
    /// The held coefficients (knot indices): the held ends, first then last.
    held: Vec<usize>,
    /// L⁻ᵀ U (free × free): T = N[:, free] W.
    w: DMatrix<f64>,
    /// K'[free, held], the penalty's coupling of the free coefficients to the held ones.
    k_held: DMatrix<f64>,
    /// The knot count M (coefficients, free and held).
    knots: usize,
}

impl Reduced {
    /// The reduced basis of a direction with sites `t` (all of them, plus the period's end on
    /// a closed direction), `count` knots, and its first / last line held (`held_ends`, open
    /// directions only). The block's sites are the direction's sites without the held ends.
    /// Returns the basis and the eigenvalues μ of L⁻¹K'L⁻ᵀ.
    pub(crate) fn new(
        t: &[f64],
        closed: bool,
        count: usize,
        held_ends: (bool, bool),
    ) -> Result<(Self, Vec<f64>)> {
        let m = if closed { t.len() - 1 } else { t.len() };
        let idx = knot_sites(m, count, closed);
        let big_m = idx.len();
        let mut tau: Vec<f64> = idx.iter().map(|&i| t[i]).collect();
        if closed {
            tau.push(t[m]);
        }
        let g = moments(&tau, closed)?;
        // Block sites: all but the held ends.
        let first = usize::from(held_ends.0 && !closed);
        let last = if held_ends.1 && !closed { m - 1 } else { m };
        let mut rows = Vec::with_capacity(last - first);
        let mut k = 0;
        for (i, &ti) in t.iter().enumerate().take(last).skip(first) {
            let spans = if closed { big_m } else { big_m - 1 };
            while k + 1 < spans && i >= idx[k + 1] {
                k += 1;
            }
            let (lo, hi) = (tau[k], tau[k + 1]);
            let h = hi - lo;
            let a = (hi - ti) / h;
            let b = (ti - lo) / h;
            let q = h * h / 6.0;
            rows.push((
                k,
                (k + 1) % big_m,
                [a, b, (a * a * a - a) * q, (b * b * b - b) * q],
            ));
        }
        let mut held = Vec::new();
        if !closed && held_ends.0 {
            held.push(0);
        }
        if !closed && held_ends.1 {
            held.push(big_m - 1);
        }
        let free: Vec<usize> = (0..big_m).filter(|k| !held.contains(k)).collect();
        // NᵀN = [I; G]ᵀ EᵀE [I; G] over the block's sites, EᵀE = [[P, Q], [Qᵀ, R]].
        let mut p = DMatrix::<f64>::zeros(big_m, big_m);
        let mut qm = DMatrix::<f64>::zeros(big_m, big_m);
        let mut r = DMatrix::<f64>::zeros(big_m, big_m);
        for &(k0, k1, [a, b, al, be]) in &rows {
            let (cv, mv) = ([(k0, a), (k1, b)], [(k0, al), (k1, be)]);
            for &(x, wx) in &cv {
                for &(y, wy) in &cv {
                    p[(x, y)] += wx * wy;
                }
                for &(y, wy) in &mv {
                    qm[(x, y)] += wx * wy;
                }
            }
            for &(x, wx) in &mv {
                for &(y, wy) in &mv {
                    r[(x, y)] += wx * wy;
                }
            }
        }
        // Q and R have a few entries a row (neighbouring knots): sparse products, O(M²).
        let qg = sparse_times(&qm, &g);
        let ntn_full = &p + &qg + qg.transpose() + g.transpose() * sparse_times(&r, &g);
        let sub = |a: &DMatrix<f64>, rs: &[usize], cs: &[usize]| {
            DMatrix::from_fn(rs.len(), cs.len(), |i, j| a[(rs[i], cs[j])])
        };
        let ntn = sub(&ntn_full, &free, &free);
        let d = jump_matrix(&tau, closed)?;
        let k_full = gram(&d);
        let k_free = sub(&k_full, &free, &free);
        let k_held = sub(&k_full, &free, &held);
        // faer's blocked Cholesky and triangular solves (nalgebra's are unblocked, several
        // times slower at M in the hundreds).
        let singular = || strategy_error(NAME, "the reduced basis's Gram matrix is singular");
        let f = free.len();
        let llt = to_faer(&ntn).llt(faer::Side::Lower).map_err(|_| singular())?;
        let l = llt.L();
        // L⁻¹ K' L⁻ᵀ = L⁻¹ (L⁻¹ K')ᵀ, K' symmetric.
        let mut lk = to_faer(&k_free);
        l.solve_lower_triangular_in_place(&mut lk);
        let mut kt = lk.transpose().to_owned();
        l.solve_lower_triangular_in_place(&mut kt);
        let kt = DMatrix::from_fn(f, f, |i, j| 0.5 * (kt[(i, j)] + kt[(j, i)]));
        let (mut mu, mut u) = symmetric_eigen(&kt);
        // L⁻¹K'L⁻ᵀ = (D' L⁻ᵀ)ᵀ (D' L⁻ᵀ) with D' the jumps over the free knots.
        let d_free = d.select_columns(&free);
        refine_bottom(&mut mu, &mut u, |v| {
            let mut x = to_faer(v);
            l.transpose().solve_upper_triangular_in_place(&mut x);
            &d_free * DMatrix::from_fn(x.nrows(), x.ncols(), |i, j| x[(i, j)])
        });
        let mut w = to_faer(&u);
        l.transpose().solve_upper_triangular_in_place(&mut w);
        let w = DMatrix::from_fn(f, f, |i, j| w[(i, j)]);
        Ok((
            Self {
                sites: rows.len(),
                rows,
                moments: Box::new(MomentMap::new(&tau, closed, g)),
                free,
                held,
                w,
                k_held,
                knots: big_m,
            },
            mu,
        ))
    }

    /// N z for full coefficient columns z (knots × k): the values at the block's sites.
    fn n_apply(&self, z: &DMatrix<f64>) -> DMatrix<f64> {
        let mz = self.moments.apply(z);
        let k = z.ncols();
        let mut out = DMatrix::<f64>::zeros(self.sites, k);
        for c in 0..k {
            for (s, &(k0, k1, [a, b, al, be])) in self.rows.iter().enumerate() {
                out[(s, c)] = a * z[(k0, c)] + b * z[(k1, c)] + al * mz[(k0, c)] + be * mz[(k1, c)];
            }
        }
        out
    }

    /// Nᵀ y for site columns y (block sites × k): full coefficient rows (knots × k).
    fn nt_apply(&self, y: &DMatrix<f64>) -> DMatrix<f64> {
        let k = y.ncols();
        let mut ec = DMatrix::<f64>::zeros(self.knots, k);
        let mut em = DMatrix::<f64>::zeros(self.knots, k);
        for c in 0..k {
            for (s, &(k0, k1, [a, b, al, be])) in self.rows.iter().enumerate() {
                let v = y[(s, c)];
                ec[(k0, c)] += a * v;
                ec[(k1, c)] += b * v;
                em[(k0, c)] += al * v;
                em[(k1, c)] += be * v;
            }
        }
        ec + self.moments.apply_transpose(&em)
    }

    /// Tᵀ y (free coefficients × k): y at the block's sites (`data`), or y already in the
    /// free coefficients' space (a coupling through K', not through N). The products are the
    /// exact basis's (`Uᵀ y`), so that with knots at every site (N = I, W = U) the results are
    /// the exact path's bit for bit.
    pub(crate) fn t_left(&self, y: &DMatrix<f64>, data: bool) -> DMatrix<f64> {
        let wt = self.w.transpose();
        if data {
            let full = self.nt_apply(y);
            let f = DMatrix::from_fn(self.free.len(), y.ncols(), |i, c| full[(self.free[i], c)]);
            &wt * f
        } else {
            &wt * y
        }
    }

    /// y T (k × free coefficients) for y at the block's sites along its columns (`data`), or in
    /// the free coefficients' space; the exact basis's product (`y V`) last.
    pub(crate) fn right(&self, y: &DMatrix<f64>, data: bool) -> DMatrix<f64> {
        if data {
            let full = self.nt_apply(&y.transpose());
            let f = DMatrix::from_fn(y.nrows(), self.free.len(), |r, i| full[(self.free[i], r)]);
            f * &self.w
        } else {
            y * &self.w
        }
    }

    /// x̂ Tᵀ (k × block sites) for spectral columns x̂ (k × free coefficients).
    pub(crate) fn t_right(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        let f = x * &self.w.transpose();
        let mut full = DMatrix::<f64>::zeros(self.knots, x.nrows());
        for (i, &k) in self.free.iter().enumerate() {
            full.row_mut(k).tr_copy_from(&f.column(i));
        }
        self.n_apply(&full).transpose()
    }

    /// T x̂ (block sites × k) for spectral rows x̂ (free coefficients × k).
    pub(crate) fn left(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        let f = &self.w * x;
        let mut full = DMatrix::<f64>::zeros(self.knots, x.ncols());
        for (i, &k) in self.free.iter().enumerate() {
            full.row_mut(k).copy_from(&f.row(i));
        }
        self.n_apply(&full)
    }

    /// The held ends' part of the lines: (N[:, held] c_held at the block's sites, K'[free,
    /// held] c_held), `ends` the held coefficients' rows (held × k, in the order first, last).
    pub(crate) fn held_parts(&self, ends: &DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
        let mut full = DMatrix::<f64>::zeros(self.knots, ends.ncols());
        for (i, &k) in self.held.iter().enumerate() {
            full.row_mut(k).copy_from(&ends.row(i));
        }
        (self.n_apply(&full), &self.k_held * ends)
    }
}

/// G (knots × knots): the moments s″(τ_k) of the natural (periodic) cubic spline with values
/// c at the knots τ are G c (the natural spline's end moments 0). O(M³) by a dense Cholesky
/// factorisation of the (cyclic) tridiagonal moment system.
fn moments(tau: &[f64], closed: bool) -> Result<DMatrix<f64>> {
    let h: Vec<f64> = tau.windows(2).map(|w| w[1] - w[0]).collect();
    let n = if closed { h.len() } else { h.len() + 1 };
    let (lo, hi) = if closed { (0, n) } else { (1, n - 1) };
    let size = hi - lo;
    let mut a = DMatrix::<f64>::zeros(size, size);
    let mut b = DMatrix::<f64>::zeros(size, n);
    for k in lo..hi {
        let (p, q) = if closed {
            ((k + n - 1) % n, (k + 1) % n)
        } else {
            (k - 1, k + 1)
        };
        let (hp, hk) = (h[p], h[k]);
        let r = k - lo;
        a[(r, r)] += 2.0 * (hp + hk);
        if closed || k > lo {
            a[(r, p - lo)] += hp;
        }
        if closed || k + 1 < hi {
            a[(r, q - lo)] += hk;
        }
        b[(r, q)] += 6.0 / hk;
        b[(r, k)] -= 6.0 / hk + 6.0 / hp;
        b[(r, p)] += 6.0 / hp;
    }
    let llt = to_faer(&a)
        .llt(faer::Side::Lower)
        .map_err(|_| strategy_error(NAME, "singular spline moment system"))?;
    let mut solved = to_faer(&b);
    llt.solve_in_place(&mut solved);
    let mut g = DMatrix::<f64>::zeros(n, n);
    for r in 0..size {
        for c in 0..n {
            g[(r + lo, c)] = solved[(r, c)];
        }
    }
    Ok(g)
}

/// Products with the moment map G = A⁻¹B of [`moments`] (A the spline's symmetric tridiagonal
/// moment system, cyclic on a closed direction; B its second differences): G z = A⁻¹(B z) and
/// Gᵀ e = Bᵀ(A⁻¹ e) by tridiagonal solves, O(M) a column instead of the dense G's O(M²) (two
/// thirds of the method's time on a 1000² net). Fewer than four knots keep the dense G.
enum MomentMap {
    Tridiagonal(Tridiagonal),
    Dense(DMatrix<f64>),
}

/// A's rows (the interior knots of an open direction, whose end moments are 0; every knot of a
/// closed one, its corners the period's wrap) and the knot spacings h, one per span.
struct Tridiagonal {
    h: Vec<f64>,
    closed: bool,
    lower: Vec<f64>,
    diag: Vec<f64>,
    upper: Vec<f64>,
}

impl MomentMap {
    /// The map of knots `tau` (the period's end last on a closed direction), or `g` itself.
    fn new(tau: &[f64], closed: bool, g: DMatrix<f64>) -> Self {
        let h: Vec<f64> = tau.windows(2).map(|w| w[1] - w[0]).collect();
        let knots = if closed { h.len() } else { h.len() + 1 };
        if knots < 4 {
            return MomentMap::Dense(g);
        }
        // row r of A is knot k = r + lo: h_{k−1}·M_{k−1} + 2(h_{k−1} + h_k)·M_k + h_k·M_{k+1}
        let (lo, hi) = if closed { (0, knots) } else { (1, knots - 1) };
        let prev = |k: usize| h[(k + h.len() - 1) % h.len()];
        let lower = (lo..hi).map(prev).collect();
        let diag = (lo..hi).map(|k| 2.0 * (prev(k) + h[k])).collect();
        let upper = (lo..hi).map(|k| h[k]).collect();
        let t = Tridiagonal {
            h,
            closed,
            lower,
            diag,
            upper,
        };
        // whether a solve succeeds depends on A alone (its pivots and, closed, the rank-one
        // correction), not on the right-hand side: one probe settles every later solve
        if t.try_solve(&vec![0.0; t.diag.len()]).is_err() {
            return MomentMap::Dense(g);
        }
        MomentMap::Tridiagonal(t)
    }

    /// G z for coefficient columns z (knots × k).
    fn apply(&self, z: &DMatrix<f64>) -> DMatrix<f64> {
        match self {
            MomentMap::Dense(g) => g * z,
            MomentMap::Tridiagonal(t) => {
                let mut out = DMatrix::<f64>::zeros(z.nrows(), z.ncols());
                for c in 0..z.ncols() {
                    let rhs: Vec<f64> = (0..t.diag.len())
                        .map(|r| t.b_row(r).iter().map(|&(j, w)| w * z[(j, c)]).sum())
                        .collect();
                    for (r, m) in t.solve(&rhs).into_iter().enumerate() {
                        out[(r + t.lo(), c)] = m;
                    }
                }
                out
            }
        }
    }

    /// Gᵀ e for moment columns e (knots × k).
    fn apply_transpose(&self, e: &DMatrix<f64>) -> DMatrix<f64> {
        match self {
            MomentMap::Dense(g) => g.transpose() * e,
            MomentMap::Tridiagonal(t) => {
                let mut out = DMatrix::<f64>::zeros(e.nrows(), e.ncols());
                for c in 0..e.ncols() {
                    let rhs: Vec<f64> = (0..t.diag.len()).map(|r| e[(r + t.lo(), c)]).collect();
                    for (r, x) in t.solve(&rhs).into_iter().enumerate() {
                        for (j, w) in t.b_row(r) {
                            out[(j, c)] += w * x;
                        }
                    }
                }
                out
            }
        }
    }
}

impl Tridiagonal {
    /// The first knot with a row: 1 on an open direction, 0 on a closed one.
    fn lo(&self) -> usize {
        usize::from(!self.closed)
    }

    /// Row r of B (knot k = r + lo): 6/h_{k−1} on knot k − 1, −(6/h_k + 6/h_{k−1}) on k, 6/h_k
    /// on k + 1, neighbours modulo the knot count on a closed direction.
    fn b_row(&self, r: usize) -> [(usize, f64); 3] {
        let n = self.h.len();
        let knots = if self.closed { n } else { n + 1 };
        let k = r + self.lo();
        let (hp, hk) = (self.h[(k + n - 1) % n], self.h[k]);
        [
            ((k + knots - 1) % knots, 6.0 / hp),
            (k, -(6.0 / hk + 6.0 / hp)),
            ((k + 1) % knots, 6.0 / hk),
        ]
    }

    /// A⁻¹ x for one column over A's rows.
    fn try_solve(&self, x: &[f64]) -> curve_repr::Result<Vec<f64>> {
        let (lower, diag, upper) = (&self.lower, &self.diag, &self.upper);
        if self.closed {
            curve_repr::tridiagonal::solve_cyclic(lower, diag, upper, x)
        } else {
            curve_repr::tridiagonal::solve(lower, diag, upper, x)
        }
    }

    /// [`Tridiagonal::try_solve`] of a map whose solve was probed when it was made
    /// ([`MomentMap::new`]), so that it cannot fail.
    fn solve(&self, x: &[f64]) -> Vec<f64> {
        self.try_solve(x)
            .expect("the moment system's solve was probed in MomentMap::new")
    }
}

/// A nalgebra matrix as faer's.
fn to_faer(a: &DMatrix<f64>) -> faer::Mat<f64> {
    faer::Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}

/// `a b` for a sparse `a` (a few entries a row): O(entries of a × columns of b).
fn sparse_times(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut out = DMatrix::<f64>::zeros(a.nrows(), b.ncols());
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            let v = a[(i, j)];
            if v != 0.0 {
                for c in 0..b.ncols() {
                    out[(i, c)] += v * b[(j, c)];
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use nalgebra::DMatrix;

    use super::{moments, MomentMap};

    /// The tridiagonal products are the dense G = A⁻¹B's (made by `moments` with a dense
    /// factorisation), on uneven knots, open and closed, for G and Gᵀ.
    #[test]
    fn moment_map_products_are_the_dense_moment_matrixs() {
        let tau: Vec<f64> = (0..12).map(|k| k as f64 + 0.3 * (k as f64 * 1.7).sin()).collect();
        for closed in [false, true] {
            let g = moments(&tau, closed).unwrap();
            let knots = g.nrows();
            let map = MomentMap::new(&tau, closed, g.clone());
            assert!(matches!(map, MomentMap::Tridiagonal(_)));
            let z = DMatrix::from_fn(knots, 3, |i, c| ((i * 7 + c * 3) as f64 * 0.37).cos());
            let scale = z.amax() * g.amax();
            let gap = (map.apply(&z) - &g * &z).amax();
            assert!(gap <= 1e-12 * scale, "closed {closed}: G z off by {gap:e}");
            let gap = (map.apply_transpose(&z) - g.transpose() * &z).amax();
            assert!(gap <= 1e-12 * scale, "closed {closed}: Gᵀ e off by {gap:e}");
        }
    }
}
