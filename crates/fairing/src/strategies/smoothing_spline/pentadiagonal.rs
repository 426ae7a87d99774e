//! Symmetric positive definite pentadiagonal systems: LDLᵀ factorisation, solve, and the band
//! of the inverse (Hutchinson & de Hoog 1985), all O(m).
//!
//! The matrix is given by its three upper bands: `diag[i] = A[i][i]`, `first[i] = A[i][i+1]`
//! (length m − 1), `second[i] = A[i][i+2]` (length m − 2). No pivoting: the Reinsch matrix
//! p·R + (1 − p)·QᵀΣQ is positive definite whenever the smoothing problem is well posed; a
//! pivot that is not positive (relative to the diagonal) is reported, never divided by.

use curve_repr::tridiagonal::Field;

/// Relative size below which a pivot d_i (against A[i][i]) counts as zero.
const PIVOT_TOLERANCE: f64 = 1e-13;

/// The factors A = L D Lᵀ of a symmetric pentadiagonal matrix: D = diag(d), L unit lower
/// triangular with L[i+1][i] = `l1[i]`, L[i+2][i] = `l2[i]`.
#[derive(Clone, Debug)]
pub(crate) struct Ldlt {
    d: Vec<f64>,
    l1: Vec<f64>,
    l2: Vec<f64>,
}

/// The band |i − j| ≤ 2 of a symmetric matrix: `diag[i] = Z[i][i]`, `first[i] = Z[i][i+1]`,
/// `second[i] = Z[i][i+2]`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Band {
    pub diag: Vec<f64>,
    pub first: Vec<f64>,
    pub second: Vec<f64>,
}

impl Band {
    /// A zero band of size m.
    pub(super) fn zeros(m: usize) -> Self {
        Band {
            diag: vec![0.0; m],
            first: vec![0.0; m.saturating_sub(1)],
            second: vec![0.0; m.saturating_sub(2)],
        }
    }

    /// Σ_ij Z_ij B_ji for two symmetric pentadiagonal matrices given by their bands: the trace
    /// of Z·B, which only sees Z inside B's band. O(m).
    pub(super) fn trace_product(&self, other: &Band) -> f64 {
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        dot(&self.diag, &other.diag)
            + 2.0 * dot(&self.first, &other.first)
            + 2.0 * dot(&self.second, &other.second)
    }
}

impl Ldlt {
    /// Factors the matrix `band`. Returns `None` when a pivot is not positive (the matrix is
    /// not positive definite, numerically) or not finite. O(m).
    ///
    /// d_i = a_i − l1_{i−1}² d_{i−1} − l2_{i−2}² d_{i−2},
    /// l1_i = (b_i − l1_{i−1} l2_{i−1} d_{i−1}) / d_i, l2_i = c_i / d_i
    /// (the entries (i,i), (i+1,i), (i+2,i) of L D Lᵀ equated to A's).
    pub(super) fn factor(band: &Band) -> Option<Self> {
        let m = band.diag.len();
        let mut d = vec![0.0; m];
        let mut l1 = vec![0.0; m.saturating_sub(1)];
        let mut l2 = vec![0.0; m.saturating_sub(2)];
        for i in 0..m {
            let mut pivot = band.diag[i];
            if i >= 1 {
                pivot -= l1[i - 1] * l1[i - 1] * d[i - 1];
            }
            if i >= 2 {
                pivot -= l2[i - 2] * l2[i - 2] * d[i - 2];
            }
            if !(pivot.is_finite() && pivot > PIVOT_TOLERANCE * band.diag[i].abs()) {
                return None;
            }
            d[i] = pivot;
            if i + 1 < m {
                let mut b = band.first[i];
                if i >= 1 {
                    b -= l1[i - 1] * l2[i - 1] * d[i - 1];
                }
                l1[i] = b / pivot;
            }
            if i + 2 < m {
                l2[i] = band.second[i] / pivot;
            }
        }
        Some(Ldlt { d, l1, l2 })
    }

    /// ln det A = Σ ln d_i (det L = 1). O(m).
    pub(super) fn log_det(&self) -> f64 {
        self.d.iter().map(|d| d.ln()).sum()
    }

    /// Solves A x = `rhs` in place (forward, diagonal, backward substitution). O(m).
    pub(super) fn solve_in_place<T: Field>(&self, rhs: &mut [T]) {
        let m = self.d.len().min(rhs.len());
        for i in 1..m {
            let mut v = rhs[i] - rhs[i - 1] * self.l1[i - 1];
            if i >= 2 {
                v = v - rhs[i - 2] * self.l2[i - 2];
            }
            rhs[i] = v;
        }
        for (x, &d) in rhs.iter_mut().zip(&self.d) {
            *x = *x * (1.0 / d);
        }
        for i in (0..m).rev() {
            let mut v = rhs[i];
            if i + 1 < m {
                v = v - rhs[i + 1] * self.l1[i];
            }
            if i + 2 < m {
                v = v - rhs[i + 2] * self.l2[i];
            }
            rhs[i] = v;
        }
    }

    /// The band |i − j| ≤ 2 of A⁻¹ (Hutchinson & de Hoog 1985, *Smoothing noisy data with
    /// spline functions*, Numer. Math. 47). Z = A⁻¹ satisfies Lᵀ Z = D⁻¹ L⁻¹, whose right side
    /// is lower triangular with diagonal D⁻¹; read on and above the diagonal, from the last
    /// row up:
    /// Z[i][i+2] = −l1_i Z[i+1][i+2] − l2_i Z[i+2][i+2],
    /// Z[i][i+1] = −l1_i Z[i+1][i+1] − l2_i Z[i+1][i+2],
    /// Z[i][i]   = 1/d_i − l1_i Z[i][i+1] − l2_i Z[i][i+2].
    /// Every term lies inside the band, so the cost is O(m).
    pub(super) fn inverse_band(&self) -> Band {
        let m = self.d.len();
        let mut z = Band::zeros(m);
        for i in (0..m).rev() {
            let (mut s2, mut s1) = (0.0, 0.0);
            if i + 2 < m {
                s2 = -self.l1[i] * z.first[i + 1] - self.l2[i] * z.diag[i + 2];
                z.second[i] = s2;
            }
            if i + 1 < m {
                s1 = -self.l1[i] * z.diag[i + 1];
                if i + 2 < m {
                    s1 -= self.l2[i] * z.first[i + 1];
                }
                z.first[i] = s1;
            }
            let mut s0 = 1.0 / self.d[i];
            if i + 1 < m {
                s0 -= self.l1[i] * s1;
            }
            if i + 2 < m {
                s0 -= self.l2[i] * s2;
            }
            z.diag[i] = s0;
        }
        z
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    fn example(m: usize) -> Band {
        let mut band = Band::zeros(m);
        for i in 0..m {
            band.diag[i] = 6.0 + (i as f64 * 0.7).sin();
        }
        for i in 0..m.saturating_sub(1) {
            band.first[i] = -2.0 + 0.3 * (i as f64).cos();
        }
        for i in 0..m.saturating_sub(2) {
            band.second[i] = 0.5 + 0.1 * (i as f64 * 1.3).sin();
        }
        band
    }

    fn dense(band: &Band) -> DMatrix<f64> {
        let m = band.diag.len();
        DMatrix::from_fn(m, m, |i, j| match i.abs_diff(j) {
            0 => band.diag[i],
            1 => band.first[i.min(j)],
            2 => band.second[i.min(j)],
            _ => 0.0,
        })
    }

    #[test]
    fn solve_and_inverse_band_match_dense() {
        for m in [1, 2, 3, 4, 9, 30] {
            let band = example(m);
            let a = dense(&band);
            let ldlt = Ldlt::factor(&band).unwrap();
            let rhs: Vec<f64> = (0..m).map(|i| (i as f64 * 0.37).sin() + 1.0).collect();
            let mut x = rhs.clone();
            ldlt.solve_in_place(&mut x);
            let residual = &a * nalgebra::DVector::from_vec(x) - nalgebra::DVector::from_vec(rhs);
            assert!(residual.amax() < 1e-12, "m = {m}: {residual}");
            let inverse = a.clone().try_inverse().unwrap();
            let z = ldlt.inverse_band();
            for i in 0..m {
                assert!((z.diag[i] - inverse[(i, i)]).abs() < 1e-13);
                if i + 1 < m {
                    assert!((z.first[i] - inverse[(i, i + 1)]).abs() < 1e-13);
                }
                if i + 2 < m {
                    assert!((z.second[i] - inverse[(i, i + 2)]).abs() < 1e-13);
                }
            }
            let trace = z.trace_product(&band);
            assert!((trace - m as f64).abs() < 1e-11, "tr(A⁻¹A) = {trace}");
            let det = a.determinant();
            assert!((ldlt.log_det() - det.ln()).abs() < 1e-12 * (1.0 + det.ln().abs()));
        }
    }

    #[test]
    fn indefinite_matrix_is_refused() {
        let mut band = example(5);
        band.diag[2] = -1.0;
        assert!(Ldlt::factor(&band).is_none());
        band.diag[2] = f64::NAN;
        assert!(Ldlt::factor(&band).is_none());
    }
}
