//! Clamped cubic B-spline bases (The NURBS Book A2.1 and A2.3), the jumps of the third
//! derivative at interior knots (the fairness measure of jump-lsq), and a banded Cholesky solver
//! for penalised least squares.

#![allow(clippy::needless_range_loop)] // index loops over fixed-size basis arrays read as the book writes them

/// A clamped cubic knot vector on [a, b] with uniform interior knots.
#[derive(Clone, Debug)]
pub(crate) struct Knots {
    pub t: Vec<f64>,
}

impl Knots {
    /// `spans` uniform spans on [a, b] (a < b), knots of multiplicity 4 at the ends.
    pub(crate) fn uniform(a: f64, b: f64, spans: usize) -> Self {
        let spans = spans.max(1);
        let mut t = vec![a; 4];
        for k in 1..spans {
            t.push(a + (b - a) * k as f64 / spans as f64);
        }
        t.extend([b; 4]);
        Self { t }
    }

    /// Number of basis functions.
    pub(crate) fn count(&self) -> usize {
        self.t.len() - 4
    }

    /// The span s (t\[s\] ≤ u < t\[s+1\], 3 ≤ s < count) whose polynomial is used at u; outside
    /// [a, b] the end span's polynomial (its extension). `left`: at a knot, the span below.
    pub(crate) fn span(&self, u: f64, left: bool) -> usize {
        let n = self.count();
        let (lo, hi) = (3, n - 1);
        if u <= self.t[lo + 1] && !(left && u == self.t[lo + 1] && lo < hi) {
            return lo;
        }
        if u >= self.t[hi] {
            return hi;
        }
        let mut s = lo;
        while s < hi && (self.t[s + 1] < u || (!left && self.t[s + 1] == u)) {
            s += 1;
        }
        s
    }

    /// Basis functions and their first `d` ≤ 3 derivatives at u on span s (The NURBS Book
    /// A2.3): out\[k\]\[r\] is the k-th derivative of N_{s−3+r}.
    pub(crate) fn ders(&self, s: usize, u: f64, d: usize) -> [[f64; 4]; 4] {
        const P: usize = 3;
        let t = &self.t;
        let mut ndu = [[0.0; 4]; 4];
        let mut left = [0.0; 4];
        let mut right = [0.0; 4];
        ndu[0][0] = 1.0;
        for j in 1..=P {
            left[j] = u - t[s + 1 - j];
            right[j] = t[s + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                ndu[j][r] = right[r + 1] + left[j - r];
                let temp = ndu[r][j - 1] / ndu[j][r];
                ndu[r][j] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            ndu[j][j] = saved;
        }
        let mut out = [[0.0; 4]; 4];
        for j in 0..=P {
            out[0][j] = ndu[j][P];
        }
        let mut a = [[0.0; 4]; 2];
        for r in 0..=P {
            let (mut s1, mut s2) = (0usize, 1usize);
            a[0][0] = 1.0;
            for k in 1..=d.min(P) {
                let mut dd = 0.0;
                let rk = r as isize - k as isize;
                let pk = P - k;
                if r >= k {
                    a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                    dd = a[s2][0] * ndu[rk as usize][pk];
                }
                let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
                let j2 = if r as isize - 1 <= pk as isize {
                    k - 1
                } else {
                    P - r
                };
                for j in j1..=j2 {
                    let idx = (rk + j as isize) as usize;
                    a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                    dd += a[s2][j] * ndu[idx][pk];
                }
                if r <= pk {
                    a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                    dd += a[s2][k] * ndu[r][pk];
                }
                out[k][r] = dd;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        let mut f = P as f64;
        for k in 1..=d.min(P) {
            for v in out[k].iter_mut() {
                *v *= f;
            }
            f *= (P - k) as f64;
        }
        out
    }

    /// Per interior knot ξ: the coefficients of the jump S'''(ξ⁺) − S'''(ξ⁻) (a linear functional
    /// of the spline's coefficients, over at most 5 of them), times h³ with h the mean of the two
    /// adjacent spans, so that the jump is measured in the spline's value units.
    pub(crate) fn jumps(&self) -> Vec<Vec<(usize, f64)>> {
        let n = self.count();
        let mut out = Vec::new();
        for s in 4..n {
            let xi = self.t[s];
            let h = 0.5 * (self.t[s + 1] - self.t[s - 1]);
            let right = self.ders(s, xi, 3);
            let left = self.ders(s - 1, xi, 3);
            let mut row: Vec<(usize, f64)> = Vec::new();
            let mut add = |i: usize, v: f64| {
                if let Some(e) = row.iter_mut().find(|e| e.0 == i) {
                    e.1 += v;
                } else {
                    row.push((i, v));
                }
            };
            for r in 0..4 {
                add(s - 3 + r, right[3][r] * h * h * h);
                add(s - 4 + r, -left[3][r] * h * h * h);
            }
            out.push(row);
        }
        out
    }
}

/// Rows of the Cholesky factor accumulated side by side ([`Band::factor`]).
const CHOLESKY_ROWS: usize = 4;

/// A symmetric positive definite banded matrix (lower band of half-width `bw`), assembled then
/// factored by Cholesky in O(n·bw²).
#[derive(Clone, Debug)]
pub(crate) struct Band {
    pub n: usize,
    pub bw: usize,
    /// a\[i\]\[k\] = A(i, i − k), k ≤ bw.
    pub a: Vec<Vec<f64>>,
}

impl Band {
    pub(crate) fn zeros(n: usize, bw: usize) -> Self {
        Self {
            n,
            bw,
            a: vec![vec![0.0; bw + 1]; n],
        }
    }

    /// A += w · r rᵀ for a sparse row r.
    pub(crate) fn add_outer(&mut self, row: &[(usize, f64)], w: f64) {
        for &(i, vi) in row {
            for &(j, vj) in row {
                if j <= i && i - j <= self.bw {
                    self.a[i][i - j] += w * vi * vj;
                }
            }
        }
    }

    pub(crate) fn add_scaled(&mut self, other: &Band, s: f64) {
        for (r, o) in self.a.iter_mut().zip(&other.a) {
            for (v, w) in r.iter_mut().zip(o) {
                *v += s * w;
            }
        }
    }

    /// Solves A x = b by banded Cholesky; None when A is not positive definite.
    pub(crate) fn solve(&self, b: &[f64]) -> Option<Vec<f64>> {
        let l = self.factor()?;
        Some(self.solve_factored(&l, b))
    }

    /// Per sparse row r_k with weight w_k, its leverage w_k r_kᵀ A⁻¹ r_k (a diagonal entry of
    /// a weighted least-squares hat matrix; their sum over all the fit's rows is its trace), one
    /// factorisation for all; None when A is not positive definite.
    pub(crate) fn leverages(&self, rows: &[(&[(usize, f64)], f64)]) -> Option<Vec<f64>> {
        let l = self.factor()?;
        let mut e = vec![0.0; self.n];
        let mut out = Vec::with_capacity(rows.len());
        for &(r, w) in rows {
            e.iter_mut().for_each(|v| *v = 0.0);
            for &(i, v) in r {
                e[i] += v;
            }
            let x = self.solve_factored(&l, &e);
            out.push(w * r.iter().map(|&(i, v)| v * x[i]).sum::<f64>());
        }
        Some(out)
    }

    /// The solution of A x = `rhs` and tr(A⁻¹ B) for a symmetric B banded within A's band (a
    /// weighted hat matrix's trace, B = Σ w_k r_k r_kᵀ), from one factorisation; None when A is
    /// not positive definite. The trace comes from the entries of A⁻¹ within the band (the
    /// selected inverse, Takahashi, Fagan & Chen 1973): with A = L Lᵀ, Z = A⁻¹ satisfies
    /// Z_ij = (δ_ij / L_ii − Σ_{k>i} L_ki Z_kj) / L_ii for j ≥ i, the sum over k ≤ i + bw, which
    /// needs only entries within the band of rows already done. O(n·bw²), a factorisation's cost.
    pub(crate) fn solve_with_trace(&self, rhs: &[f64], b: &Band) -> Option<(Vec<f64>, f64)> {
        let l = self.factor()?;
        Some((self.solve_factored(&l, rhs), self.selected_trace(&l, b)))
    }

    fn selected_trace(&self, l: &[Vec<f64>], b: &Band) -> f64 {
        let (n, bw) = (self.n, self.bw);
        // z[i][d] = Z(i + d, i)
        let mut z = vec![vec![0.0; bw + 1]; n];
        for i in (0..n).rev() {
            let top = (i + bw).min(n - 1);
            for j in (i..=top).rev() {
                let mut s = 0.0;
                for k in i + 1..=top {
                    let (lo, hi) = if k < j { (k, j) } else { (j, k) };
                    s += l[k][k - i] * z[lo][hi - lo];
                }
                let d = if i == j { 1.0 / l[i][0] } else { 0.0 };
                z[i][j - i] = (d - s) / l[i][0];
            }
        }
        let mut tr = 0.0;
        for i in 0..n {
            tr += z[i][0] * b.a[i][0];
            for d in 1..=bw.min(n - 1 - i) {
                tr += 2.0 * z[i][d] * b.a[i + d][d];
            }
        }
        tr
    }

    fn solve_factored(&self, l: &[Vec<f64>], b: &[f64]) -> Vec<f64> {
        let (n, bw) = (self.n, self.bw);
        let mut y = b.to_vec();
        for i in 0..n {
            let mut s = y[i];
            for k in 1..=bw.min(i) {
                s -= l[i][k] * y[i - k];
            }
            y[i] = s / l[i][0];
        }
        for i in (0..n).rev() {
            let mut s = y[i];
            for k in 1..=bw.min(n - 1 - i) {
                s -= l[i + k][k] * y[i + k];
            }
            y[i] = s / l[i][0];
        }
        y
    }

    /// The Cholesky factor L (A = L Lᵀ) in the band layout; None when A is not positive
    /// definite. Row by row, each entry L(i, j) = (A(i, j) − Σ_m L(i, j − m) L(j, j − m)) / L(j, j)
    /// summed in increasing m. The sums of [`CHOLESKY_ROWS`] consecutive rows at the columns left
    /// of the first of them depend only on finished rows and on their own row, so they are
    /// accumulated side by side: independent addition chains that the processor overlaps,
    /// each summed in the same order as alone, so the factor is bit for bit the row-by-row one.
    fn factor(&self) -> Option<Vec<Vec<f64>>> {
        let (n, bw) = (self.n, self.bw);
        let mut l = self.a.clone();
        let scale = (0..n)
            .map(|i| self.a[i][0].abs())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        // the sums start where a float `Iterator::sum` starts
        let zero: f64 = std::iter::empty::<f64>().sum();
        const R: usize = CHOLESKY_ROWS;
        let mut i = 0;
        while i < n {
            let rows = R.min(n - i);
            let (done, rest) = l.split_at_mut(i);
            let blk = &mut rest[..rows];
            // the block's entries left of column i: row i + r has k = i + r − j
            for j in i - bw.min(i)..i {
                let k0 = i - j;
                let lj = &done[j];
                // rows whose band reaches column j (k ≤ bw), and their sums' lengths
                let active = rows.min(bw + 1 - k0);
                let len = |r: usize| j.min(bw - k0 - r);
                let mut acc = [zero; R];
                let common = len(active - 1);
                if active == R {
                    let v = &lj[1..=common];
                    let b: [&[f64]; R] = std::array::from_fn(|r| &blk[r][k0 + r + 1..k0 + r + 1 + common]);
                    for m in 0..common {
                        for r in 0..R {
                            acc[r] += b[r][m] * v[m];
                        }
                    }
                } else {
                    for m in 1..=common {
                        for r in 0..active {
                            acc[r] += blk[r][k0 + r + m] * lj[m];
                        }
                    }
                }
                for r in 0..active {
                    let k = k0 + r;
                    for m in common + 1..=len(r) {
                        acc[r] += blk[r][k + m] * lj[m];
                    }
                    blk[r][k] = (blk[r][k] - acc[r]) / lj[0];
                }
            }
            // the block's own triangle, row by row
            for r in 0..rows {
                let (prev, cur) = blk.split_at_mut(r);
                let li = &mut cur[0];
                for k in (0..=bw.min(i + r).min(r)).rev() {
                    let j = i + r - k;
                    let mmax = j.min(bw - k);
                    let s = if k == 0 {
                        li[0] - li[1..=mmax].iter().map(|v| v * v).sum::<f64>()
                    } else {
                        let lj = &prev[j - i];
                        li[k]
                            - li[k + 1..=k + mmax]
                                .iter()
                                .zip(&lj[1..=mmax])
                                .map(|(a, b)| a * b)
                                .sum::<f64>()
                    };
                    if k == 0 {
                        if s <= 1e-14 * scale {
                            return None;
                        }
                        li[0] = s.sqrt();
                    } else {
                        li[k] = s / prev[j - i][0];
                    }
                }
            }
            i += rows;
        }
        Some(l)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `count` rows of a banded design, row k the bw + 1 entries from (k·stride) mod (n − bw),
    /// valued `value(k, i)`: the tests' least-squares systems.
    fn banded_rows(
        n: usize,
        bw: usize,
        count: usize,
        stride: usize,
        value: impl Fn(usize, usize) -> f64,
    ) -> Vec<Vec<(usize, f64)>> {
        (0..count)
            .map(|k| {
                let i0 = (k * stride) % (n - bw);
                (i0..=i0 + bw).map(|i| (i, value(k, i))).collect()
            })
            .collect()
    }

    fn knots() -> Knots {
        Knots {
            t: vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.5, 3.0, 4.5, 4.5, 4.5, 4.5],
        }
    }

    #[test]
    fn bases_sum_to_one_and_derivatives_match_differences() {
        let k = knots();
        for &u in &[0.0, 0.3, 1.0, 1.7, 2.9, 3.6, 4.5] {
            let s = k.span(u, false);
            let d = k.ders(s, u, 3);
            assert!(
                (d[0].iter().sum::<f64>() - 1.0).abs() < 1e-12,
                "partition of unity at {u}"
            );
            assert!(d[1].iter().sum::<f64>().abs() < 1e-12);
            let h = 1e-6;
            let (dp, dm) = (k.ders(s, u + h, 0), k.ders(s, u - h, 0));
            for r in 0..4 {
                let fd = (dp[0][r] - dm[0][r]) / (2.0 * h);
                assert!((fd - d[1][r]).abs() < 1e-6, "N' at {u}, {r}: {fd} vs {}", d[1][r]);
            }
        }
    }

    #[test]
    fn the_jumps_vanish_on_a_cubic_and_not_on_a_kink_of_the_third_derivative() {
        let k = knots();
        // the coefficients of x³ on this knot vector, by least squares through 7 points
        let n = k.count();
        let xs: Vec<f64> = (0..=20).map(|i| 4.5 * i as f64 / 20.0).collect();
        let mut a = Band::zeros(n, 3);
        let mut b = vec![0.0; n];
        for &x in &xs {
            let s = k.span(x, false);
            let row: Vec<(usize, f64)> = (0..4).map(|r| (s - 3 + r, k.ders(s, x, 0)[0][r])).collect();
            a.add_outer(&row, 1.0);
            for &(i, v) in &row {
                b[i] += v * x * x * x;
            }
        }
        let c = a.solve(&b).unwrap();
        for row in k.jumps() {
            let j: f64 = row.iter().map(|&(i, w)| w * c[i]).sum();
            assert!(j.abs() < 1e-8, "a cubic has no third-derivative jump: {j}");
        }
        // one coefficient bumped: some jump is nonzero
        let mut c2 = c.clone();
        c2[3] += 1.0;
        assert!(k
            .jumps()
            .iter()
            .any(|row| row.iter().map(|&(i, w)| w * c2[i]).sum::<f64>().abs() > 1e-3));
    }

    /// The factor computed one entry at a time, row by row: the reference for [`Band::factor`].
    fn factor_row_by_row(a: &Band) -> Option<Vec<Vec<f64>>> {
        let (n, bw) = (a.n, a.bw);
        let mut l = a.a.clone();
        let scale = (0..n)
            .map(|i| a.a[i][0].abs())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        for i in 0..n {
            let (done, rest) = l.split_at_mut(i);
            let li = &mut rest[0];
            for k in (0..=bw.min(i)).rev() {
                let j = i - k;
                let mmax = j.min(bw - k);
                let s = if k == 0 {
                    li[0] - li[1..=mmax].iter().map(|v| v * v).sum::<f64>()
                } else {
                    let lj = &done[j];
                    li[k]
                        - li[k + 1..=k + mmax]
                            .iter()
                            .zip(&lj[1..=mmax])
                            .map(|(a, b)| a * b)
                            .sum::<f64>()
                };
                if k == 0 {
                    if s <= 1e-14 * scale {
                        return None;
                    }
                    li[0] = s.sqrt();
                } else {
                    li[k] = s / done[j][0];
                }
            }
        }
        Some(l)
    }

    #[test]
    fn the_blocked_factor_is_bit_for_bit_the_row_by_row_one() {
        // random SPD band matrices (sums of outer products of random sparse rows, zeros left in
        // the band) of every size around the block's, and one that is not definite
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for n in 1..40 {
            for bw in [0, 1, 2, 3, 4, 5, 7, 12, 45] {
                let mut a = Band::zeros(n, bw);
                for _ in 0..3 * n {
                    let i0 = ((rnd() + 0.5) * n as f64) as usize % n;
                    let mut row: Vec<(usize, f64)> = Vec::new();
                    for i in i0..n.min(i0 + bw + 1) {
                        // some entries left out: zeros inside the band
                        if rnd() > -0.3 {
                            row.push((i, rnd()));
                        }
                    }
                    a.add_outer(&row, 1.0);
                }
                for i in 0..n {
                    a.a[i][0] += 1e-3;
                }
                let (got, want) = (a.factor(), factor_row_by_row(&a));
                assert_eq!(got.is_some(), want.is_some());
                for (g, w) in got.unwrap().iter().zip(&want.unwrap()) {
                    for (x, y) in g.iter().zip(w) {
                        assert_eq!(x.to_bits(), y.to_bits(), "n {n} bw {bw}");
                    }
                }
            }
        }
        let mut a = Band::zeros(9, 4);
        for i in 0..9 {
            a.a[i][0] = if i == 6 { -1.0 } else { 2.0 };
        }
        assert!(a.factor().is_none() && factor_row_by_row(&a).is_none());
    }

    #[test]
    fn the_hat_matrix_trace_of_an_unpenalised_fit_is_its_unknown_count() {
        // A = Σ w_k r_k r_kᵀ: the hat matrix of least squares is a projection onto the n
        // unknowns' span, trace n; scaled, A = c·Σ w_k r_k r_kᵀ, the trace is n / c
        let (n, bw) = (7, 3);
        let rows = banded_rows(n, bw, 20, 3, |k, i| 1.0 + ((k * 7 + i * 5) % 11) as f64 / 4.0);
        let w: Vec<f64> = (0..rows.len()).map(|k| 0.5 + (k % 3) as f64).collect();
        let pairs: Vec<(&[(usize, f64)], f64)> =
            rows.iter().map(|r| r.as_slice()).zip(w.iter().copied()).collect();
        for c in [1.0, 2.5] {
            let mut a = Band::zeros(n, bw);
            for (r, wk) in &pairs {
                a.add_outer(r, c * wk);
            }
            let tr: f64 = a.leverages(&pairs).unwrap().iter().sum();
            assert!((tr - n as f64 / c).abs() < 1e-10, "c {c}: {tr}");
        }
    }

    #[test]
    fn a_deleted_residual_is_the_residual_over_one_minus_the_leverage() {
        // penalised weighted least squares, M = Σ w_k r_k r_kᵀ + λ P: leaving offset k out
        // (M − w_k r_k r_kᵀ, its term dropped from the right side) leaves a residual at it of
        // e_k / (1 − h_kk), h_kk = w_k r_kᵀ M⁻¹ r_k, the identity `Fit::deleted_moves` uses
        let (n, bw) = (8, 3);
        let rows = banded_rows(n, bw, 14, 5, |k, i| 0.5 + ((k * 3 + i * 7) % 9) as f64 / 5.0);
        let w: Vec<f64> = (0..rows.len()).map(|k| 1.0 + (k % 4) as f64 / 2.0).collect();
        let y: Vec<f64> = (0..rows.len()).map(|k| ((k * 13) % 7) as f64 - 3.0).collect();
        let system = |skip: Option<usize>| {
            let mut m = Band::zeros(n, bw);
            let mut b = vec![0.0; n];
            for (k, r) in rows.iter().enumerate().filter(|(k, _)| Some(*k) != skip) {
                m.add_outer(r, w[k]);
                for &(i, v) in r {
                    b[i] += w[k] * v * y[k];
                }
            }
            for i in 0..n.saturating_sub(2) {
                // second differences of the coefficients, λ = 0.7
                m.add_outer(&[(i, 1.0), (i + 1, -2.0), (i + 2, 1.0)], 0.7);
            }
            (m, b)
        };
        let value = |c: &[f64], r: &[(usize, f64)]| r.iter().map(|&(i, v)| v * c[i]).sum::<f64>();
        let (m, b) = system(None);
        let c = m.solve(&b).unwrap();
        for k in [0, 5, 13] {
            let e = y[k] - value(&c, &rows[k]);
            let h = m.leverages(&[(rows[k].as_slice(), w[k])]).unwrap()[0];
            let (m2, b2) = system(Some(k));
            let c2 = m2.solve(&b2).unwrap();
            let deleted = y[k] - value(&c2, &rows[k]);
            assert!(
                (deleted - e / (1.0 - h)).abs() < 1e-9 * (1.0 + deleted.abs()),
                "{k}: {deleted} {e} {h}"
            );
        }
    }

    #[test]
    fn the_selected_inverse_gives_the_trace_one_solve_per_row_gives() {
        // tr(A⁻¹ B), B = Σ w_k r_k r_kᵀ: from the inverse's band and from a solve per row
        let (n, bw) = (9, 3);
        let rows = banded_rows(n, bw, 17, 5, |k, i| 0.3 + ((k * 5 + i * 3) % 7) as f64 / 3.0);
        let pairs: Vec<(&[(usize, f64)], f64)> = rows
            .iter()
            .enumerate()
            .map(|(k, r)| (r.as_slice(), 0.5 + (k % 5) as f64 / 4.0))
            .collect();
        let mut b = Band::zeros(n, bw);
        for (r, w) in &pairs {
            b.add_outer(r, *w);
        }
        let mut a = b.clone();
        for i in 0..n.saturating_sub(2) {
            a.add_outer(&[(i, 1.0), (i + 1, -2.0), (i + 2, 1.0)], 1.3);
        }
        let by_rows: f64 = a.leverages(&pairs).unwrap().iter().sum();
        let selected = a.solve_with_trace(&vec![0.0; n], &b).unwrap().1;
        assert!(
            (by_rows - selected).abs() < 1e-10 * by_rows.abs(),
            "{by_rows} {selected}"
        );
        // and the projection: A = B gives the unknown count
        assert!((b.solve_with_trace(&vec![0.0; n], &b).unwrap().1 - n as f64).abs() < 1e-9);
    }

    #[test]
    fn the_banded_solver_solves() {
        // a tridiagonal SPD system with a known solution
        let n = 6;
        let mut a = Band::zeros(n, 2);
        for i in 0..n {
            a.a[i][0] = 4.0;
            if i >= 1 {
                a.a[i][1] = -1.0;
            }
            if i >= 2 {
                a.a[i][2] = 0.5;
            }
        }
        let x: Vec<f64> = (0..n).map(|i| i as f64 - 2.0).collect();
        let mut b = vec![0.0; n];
        for i in 0..n {
            for j in 0..n {
                let d = i.abs_diff(j);
                let v = if d <= 2 { a.a[i.max(j)][d] } else { 0.0 };
                b[i] += v * x[j];
            }
        }
        let got = a.solve(&b).unwrap();
        for (g, w) in got.iter().zip(&x) {
            assert!((g - w).abs() < 1e-12);
        }
    }
}
