//! Symmetric matrices stored by their envelope (profile), their LDLᵀ factorisation without
//! pivoting, solves, and the selected inverse (the entries of A⁻¹ inside the envelope).
//!
//! Row i stores the entries A[i][j] for `first[i] ≤ j ≤ i` (the lower triangle from the row's
//! first non-zero to the diagonal). Cholesky-type factorisations fill only inside the
//! envelope (Jennings 1966), so L is stored in place of A, the diagonal holding D. A band of
//! half-width b is the envelope `first[i] = max(0, i − b)`; the jump-lsq systems are a band
//! with Lagrange multipliers interleaved (see [`super`]), whose rows reach back a few
//! columns further, and closed curves use a folded order that keeps the envelope a band.
//!
//! No pivoting. The matrices factored here are symmetric quasi-definite in the sense that
//! every leading block [[H₁₁, C₁ᵀ], [C₁, 0]] is non-singular (H positive definite, the
//! constraint rows of the block independent): then the LDLᵀ factorisation exists with
//! positive pivots at the variables and negative ones at the multipliers (Sylvester's law of
//! inertia applied to the leading blocks), and each pivot is checked for that sign. LDLᵀ
//! without pivoting is invariant under symmetric diagonal scaling, so the units of the
//! multipliers do not matter.
//!
//! Costs for a matrix of size m whose rows reach back at most b columns: factorisation
//! O(m·b²), solve O(m·b), selected inverse O(m·b²), memory O(m·b).

use curve_repr::tridiagonal::Field;

/// Relative size below which a pivot counts as zero (against the row's scale).
const PIVOT_TOLERANCE: f64 = 1e-14;

/// The shape of an envelope: where each row starts and where its entries are stored.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Profile {
    first: Vec<usize>,
    start: Vec<usize>,
}

impl Profile {
    /// The profile whose row i starts at column `first[i]` (clamped to i).
    pub(super) fn new(mut first: Vec<usize>) -> Self {
        let mut start = Vec::with_capacity(first.len() + 1);
        let mut offset = 0;
        start.push(0);
        for (i, f) in first.iter_mut().enumerate() {
            *f = (*f).min(i);
            offset += i - *f + 1;
            start.push(offset);
        }
        Profile { first, start }
    }

    /// The matrix size m.
    pub(super) fn size(&self) -> usize {
        self.first.len()
    }

    /// Number of stored entries (lower triangle with the diagonal).
    pub(super) fn stored(&self) -> usize {
        self.start.last().copied().unwrap_or(0)
    }

    /// The first stored column of row i.
    #[cfg(test)]
    pub(super) fn first(&self, i: usize) -> usize {
        self.first[i]
    }

    /// The storage range of row i (columns `first(i)..=i`).
    fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.start[i]..self.start[i + 1]
    }

    /// The storage index of entry (i, j), j ≤ i, if it lies inside the envelope.
    pub(super) fn index(&self, i: usize, j: usize) -> Option<usize> {
        let f = *self.first.get(i)?;
        (f <= j && j <= i).then(|| self.start[i] + (j - f))
    }

    /// Row i's first stored column and the storage index of that entry.
    #[inline]
    pub(super) fn row(&self, i: usize) -> (usize, usize) {
        (self.first[i], self.start[i])
    }

    /// A zero matrix of this profile.
    pub(super) fn zeros(&self) -> Vec<f64> {
        vec![0.0; self.stored()]
    }

    /// out = A x for the symmetric matrix A with entries `values`. O(stored).
    pub(super) fn multiply<T: Field>(&self, values: &[f64], x: &[T], out: &mut [T]) {
        for o in out.iter_mut() {
            *o = *o * 0.0;
        }
        for i in 0..self.size() {
            let f = self.first[i];
            let row = &values[self.range(i)];
            let (lower, diag) = row.split_at(row.len() - 1);
            let mut acc = x[i] * diag[0];
            for (k, &a) in lower.iter().enumerate() {
                if a != 0.0 {
                    let j = f + k;
                    acc = acc + x[j] * a;
                    out[j] = out[j] + x[i] * a;
                }
            }
            out[i] = out[i] + acc;
        }
    }
}

/// Where a factorisation failed: the row whose pivot was zero, not finite or of the wrong
/// sign (a variable needs a positive pivot, a multiplier a negative one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PivotFailure {
    /// The row.
    pub row: usize,
    /// The pivot found.
    pub pivot: f64,
}

/// The factors A = L D Lᵀ on the envelope of A: L unit lower triangular (strict lower part
/// stored), D diagonal (stored on the diagonal).
#[derive(Clone, Debug)]
pub(crate) struct Ldlt<'p> {
    profile: &'p Profile,
    values: Vec<f64>,
    /// Where the storage goes back when the factors are dropped, for the next factorisation
    /// on the same profile (a trial λ reuses the last trial's pages instead of faulting in
    /// fresh ones: at 10^6 points they are 50 MB).
    pool: Option<&'p Pool>,
}

/// Storage kept between factorisations ([`Ldlt::factor_in`]).
pub(crate) type Pool = std::cell::RefCell<Vec<f64>>;

impl Drop for Ldlt<'_> {
    fn drop(&mut self) {
        if let Some(pool) = self.pool {
            if let Ok(mut kept) = pool.try_borrow_mut() {
                if kept.capacity() < self.values.capacity() {
                    *kept = std::mem::take(&mut self.values);
                }
            }
        }
    }
}

impl<'p> Ldlt<'p> {
    /// Factors the symmetric matrix with entries `values` (consumed; L and D are written in
    /// their place). `negative[i]` says that row i is a multiplier, whose pivot must be
    /// negative; every other pivot must be positive. O(m·b²).
    ///
    /// Row-oriented (Crout) envelope LDLᵀ: for j from first(i) to i − 1,
    /// v_j = A_ij − Σ_l v_l L_jl (l from max(first(i), first(j)) to j − 1), then
    /// L_ij = v_j / d_j and d_i = A_ii − Σ_j v_j L_ij (v_j = L_ij d_j, the entries of L D).
    #[cfg(test)]
    pub(super) fn factor(
        profile: &'p Profile,
        values: Vec<f64>,
        negative: &[bool],
    ) -> Result<Self, PivotFailure> {
        Self::factor_in(profile, values, negative, None)
    }

    /// [`factor`](Self::factor), returning the storage to `pool` when the factors (or a
    /// failed attempt) are dropped.
    pub(super) fn factor_in(
        profile: &'p Profile,
        values: Vec<f64>,
        negative: &[bool],
        pool: Option<&'p Pool>,
    ) -> Result<Self, PivotFailure> {
        let mut ldlt = Ldlt {
            profile,
            values,
            pool,
        };
        ldlt.factor_values(negative)?;
        Ok(ldlt)
    }

    fn factor_values(&mut self, negative: &[bool]) -> Result<(), PivotFailure> {
        let profile = self.profile;
        let values = &mut self.values;
        let m = profile.size();
        for i in 0..m {
            let fi = profile.first[i];
            let (done, rest) = values.split_at_mut(profile.start[i]);
            let row = &mut rest[..profile.start[i + 1] - profile.start[i]];
            let (lower, diag) = row.split_at_mut(i - fi);
            // The row's scale for the pivot test: |A_ii| for a variable, Σ A_ij² / |A_jj| (the
            // diagonal estimate of c H⁻¹ cᵀ) for a multiplier.
            let is_negative = negative.get(i).copied().unwrap_or(false);
            let scale = if is_negative {
                lower
                    .iter()
                    .enumerate()
                    .map(|(k, a)| {
                        let j = fi + k;
                        let d = done[profile.start[j + 1] - 1].abs();
                        if d > 0.0 {
                            a * a / d
                        } else {
                            0.0
                        }
                    })
                    .sum::<f64>()
            } else {
                diag[0].abs()
            };
            for k in 0..lower.len() {
                let j = fi + k;
                let fj = profile.first[j];
                let lo = fi.max(fj);
                let row_j = &done[profile.start[j]..profile.start[j + 1]];
                let mut s = lower[k];
                let vi = &lower[lo - fi..k];
                let lj = &row_j[lo - fj..j - fj];
                for (a, b) in vi.iter().zip(lj) {
                    s -= a * b;
                }
                lower[k] = s;
            }
            let mut d = diag[0];
            for (k, v) in lower.iter_mut().enumerate() {
                let j = fi + k;
                let dj = done[profile.start[j + 1] - 1];
                let l = *v / dj;
                d -= *v * l;
                *v = l;
            }
            let ok =
                d.is_finite() && d != 0.0 && (d < 0.0) == is_negative && d.abs() > PIVOT_TOLERANCE * scale;
            if !ok {
                return Err(PivotFailure { row: i, pivot: d });
            }
            diag[0] = d;
        }
        Ok(())
    }

    /// Factors given directly: `values` holds L's strict lower part and D on the diagonal,
    /// on `profile`.
    pub(super) fn from_factors(profile: &'p Profile, values: Vec<f64>) -> Self {
        Ldlt {
            profile,
            values,
            pool: None,
        }
    }

    /// Solves A x = `rhs` in place. O(m·b).
    pub(super) fn solve_in_place<T: Field>(&self, rhs: &mut [T]) {
        let p = self.profile;
        let m = p.size();
        // L z = b, row by row.
        for i in 0..m {
            let fi = p.first[i];
            let row = &self.values[p.range(i)];
            let mut acc = rhs[i];
            for (k, &l) in row[..i - fi].iter().enumerate() {
                acc = acc - rhs[fi + k] * l;
            }
            rhs[i] = acc;
        }
        for (i, value) in rhs.iter_mut().enumerate().take(m) {
            *value = *value * (1.0 / self.values[p.start[i + 1] - 1]);
        }
        // Lᵀ x = z, column by column from the last row up.
        for i in (0..m).rev() {
            let fi = p.first[i];
            let row = &self.values[p.range(i)];
            let xi = rhs[i];
            for (k, &l) in row[..i - fi].iter().enumerate() {
                if l != 0.0 {
                    rhs[fi + k] = rhs[fi + k] - xi * l;
                }
            }
        }
    }

    /// The entries of A⁻¹ inside the envelope (the selected inverse; Takahashi, Fagan & Chen
    /// 1973, as Hutchinson & de Hoog 1985 use it for smoothing splines). With Z = A⁻¹ and
    /// S_i = {k > i : L_ki stored}, from Lᵀ Z = D⁻¹ L⁻¹ read on and below the diagonal:
    ///
    /// Z_ki = −Σ_{l ∈ S_i} L_li Z_kl (k ∈ S_i),   Z_ii = 1/d_i − Σ_{k ∈ S_i} L_ki Z_ki,
    ///
    /// for i from the last row up. Every Z_kl needed has k, l ∈ S_i, and such a pair lies
    /// inside the envelope (first(max(k, l)) ≤ i < min(k, l)), so the recurrence never
    /// leaves it. O(m·b²) time, O(stored) memory.
    pub(super) fn selected_inverse(&self) -> Vec<f64> {
        let p = self.profile;
        let m = p.size();
        // Column structure S_i of the strict lower part, as lists of rows (CSC pattern).
        let mut count = vec![0usize; m + 1];
        for k in 0..m {
            for j in p.first[k]..k {
                count[j + 1] += 1;
            }
        }
        for j in 0..m {
            count[j + 1] += count[j];
        }
        let mut rows = vec![0usize; count[m]];
        let mut fill = count.clone();
        for k in 0..m {
            for j in p.first[k]..k {
                rows[fill[j]] = k;
                fill[j] += 1;
            }
        }
        let lower = |values: &[f64], k: usize, l: usize| -> f64 {
            let (a, b) = if k >= l { (k, l) } else { (l, k) };
            values[p.start[a] + (b - p.first[a])]
        };
        let mut z = p.zeros();
        let mut column: Vec<f64> = Vec::new();
        for i in (0..m).rev() {
            let structure = &rows[count[i]..count[i + 1]];
            column.clear();
            for &k in structure {
                let mut s = 0.0;
                for &l in structure {
                    s -= lower(&self.values, l, i) * lower(&z, k, l);
                }
                column.push(s);
            }
            let mut zii = 1.0 / self.values[p.start[i + 1] - 1];
            for (&k, &zki) in structure.iter().zip(&column) {
                zii -= lower(&self.values, k, i) * zki;
                z[p.start[k] + (i - p.first[k])] = zki;
            }
            z[p.start[i + 1] - 1] = zii;
        }
        z
    }

    /// ln |det A| = Σ_i ln |d_i| (L is unit lower triangular). O(m).
    pub(super) fn log_abs_det(&self) -> f64 {
        (0..self.profile.size())
            .map(|i| self.values[self.profile.start[i + 1] - 1].abs().ln())
            .sum()
    }

    /// The pivots d_i.
    #[cfg(test)]
    pub(super) fn pivots(&self) -> Vec<f64> {
        (0..self.profile.size())
            .map(|i| self.values[self.profile.start[i + 1] - 1])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// A symmetric matrix on a random-looking envelope: positive definite with `multipliers`
    /// zero-diagonal rows interleaved (a KKT matrix), or plain positive definite.
    fn example(
        m: usize,
        reach: usize,
        constraints: &[usize],
    ) -> (Profile, Vec<f64>, Vec<bool>, DMatrix<f64>) {
        example_with(m, reach, constraints, 0.1)
    }

    /// `example` with constraint c's coefficients shifted by `shift`·c (0: identical rows on
    /// the same anchor).
    fn example_with(
        m: usize,
        reach: usize,
        constraints: &[usize],
        shift: f64,
    ) -> (Profile, Vec<f64>, Vec<bool>, DMatrix<f64>) {
        let total = m + constraints.len();
        // Order: variables with each constraint placed after its last variable.
        let mut order = Vec::new(); // (is_constraint, index)
        for v in 0..m {
            order.push((false, v));
            for (c, &anchor) in constraints.iter().enumerate() {
                if anchor == v {
                    order.push((true, c));
                }
            }
        }
        let pos_var: Vec<usize> = (0..m)
            .map(|v| order.iter().position(|&o| o == (false, v)).unwrap())
            .collect();
        let pos_con: Vec<usize> = (0..constraints.len())
            .map(|c| order.iter().position(|&o| o == (true, c)).unwrap())
            .collect();
        let mut dense = DMatrix::<f64>::zeros(total, total);
        for a in 0..m {
            for b in a.saturating_sub(reach)..=a {
                let v = if a == b {
                    4.0 * reach as f64 + 1.0 + (a as f64 * 0.3).sin()
                } else {
                    -1.0 + 0.4 * ((a * 7 + b * 3) as f64).cos()
                };
                dense[(pos_var[a], pos_var[b])] = v;
                dense[(pos_var[b], pos_var[a])] = v;
            }
        }
        for (c, &anchor) in constraints.iter().enumerate() {
            for (k, v) in (anchor.saturating_sub(2)..=anchor).enumerate() {
                let value = 0.5 + k as f64 + shift * c as f64;
                dense[(pos_con[c], pos_var[v])] = value;
                dense[(pos_var[v], pos_con[c])] = value;
            }
        }
        let first: Vec<usize> = (0..total)
            .map(|i| (0..=i).find(|&j| dense[(i, j)] != 0.0).unwrap_or(i))
            .collect();
        let profile = Profile::new(first);
        let mut values = profile.zeros();
        for i in 0..total {
            for j in profile.first(i)..=i {
                values[profile.index(i, j).unwrap()] = dense[(i, j)];
            }
        }
        let negative = (0..total).map(|i| pos_con.contains(&i)).collect();
        (profile, values, negative, dense)
    }

    #[test]
    fn factor_solve_and_selected_inverse_match_dense() {
        for (m, reach, constraints) in [
            (1, 0, vec![]),
            (6, 2, vec![]),
            (30, 6, vec![]),
            (30, 6, vec![4, 5, 17, 29]),
            (12, 3, vec![2, 3, 4, 5, 6]),
        ] {
            let (profile, values, negative, dense) = example(m, reach, &constraints);
            let ldlt = Ldlt::factor(&profile, values, &negative).unwrap();
            let total = profile.size();
            for (i, d) in ldlt.pivots().iter().enumerate() {
                assert_eq!(*d < 0.0, negative[i], "pivot {i} = {d}");
            }
            let rhs: Vec<f64> = (0..total).map(|i| (i as f64 * 0.37).sin() + 1.0).collect();
            let mut x = rhs.clone();
            ldlt.solve_in_place(&mut x);
            let residual = &dense * DVector::from_vec(x) - DVector::from_vec(rhs);
            assert!(residual.amax() < 1e-11, "m = {m}: residual {}", residual.amax());
            let inverse = dense.clone().try_inverse().unwrap();
            let z = ldlt.selected_inverse();
            for i in 0..total {
                for j in profile.first(i)..=i {
                    let got = z[profile.index(i, j).unwrap()];
                    assert!(
                        (got - inverse[(i, j)]).abs() < 1e-11 * inverse.amax(),
                        "m = {m}: Z[{i}][{j}] = {got}, dense {}",
                        inverse[(i, j)]
                    );
                }
            }
            let mut product = vec![0.0; total];
            let ones = vec![1.0; total];
            profile.multiply(&ldlt_values_of(&dense, &profile), &ones, &mut product);
            let expected = &dense * DVector::from_element(total, 1.0);
            for i in 0..total {
                assert!((product[i] - expected[i]).abs() < 1e-12);
            }
        }
    }

    fn ldlt_values_of(dense: &DMatrix<f64>, profile: &Profile) -> Vec<f64> {
        let mut values = profile.zeros();
        for i in 0..profile.size() {
            for j in profile.first(i)..=i {
                values[profile.index(i, j).unwrap()] = dense[(i, j)];
            }
        }
        values
    }

    #[test]
    fn wrong_sign_or_zero_pivots_are_refused() {
        let (profile, mut values, negative, _) = example(6, 2, &[]);
        let i = profile.index(3, 3).unwrap();
        values[i] = -5.0;
        assert_eq!(Ldlt::factor(&profile, values, &negative).unwrap_err().row, 3);
        // Two identical constraints on the same variables: the second multiplier's pivot
        // vanishes (dependent rows).
        let (profile, values, negative, _) = example_with(8, 2, &[4, 4], 0.0);
        assert!(Ldlt::factor(&profile, values, &negative).is_err());
        let (profile, values, negative, _) = example_with(8, 2, &[4, 4], 0.1);
        assert!(Ldlt::factor(&profile, values, &negative).is_ok());
        let (profile, mut values, negative, _) = example(6, 2, &[]);
        values[0] = f64::NAN;
        assert!(Ldlt::factor(&profile, values, &negative).is_err());
    }
}
