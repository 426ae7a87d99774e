//! The jump operator of one grid direction: the linear map from the values at the sites of a
//! grid line to the scaled third-derivative jumps of the cubic spline through them (natural
//! on an open direction, periodic on a closed one), and its Gram matrix K = DᵀD.
//!
//! With moments M_k = s″(t_k) the spline's third derivative on span k is
//! (M_{k+1} − M_k)/h_k, so the jump at interior knot i is
//!
//! ```text
//! J_i = (M_{i+1} − M_i)/h_i − (M_i − M_{i−1})/h_{i−1},
//! ```
//!
//! the moments solving h_{k−1} M_{k−1} + 2(h_{k−1} + h_k) M_k + h_k M_{k+1}
//! = 6[(y_{k+1} − y_k)/h_k − (y_k − y_{k−1})/h_{k−1}] (M_0 = M_m = 0 for the natural spline;
//! indices modulo the site count for the periodic one). J_i is Zhang–Cheng's z_i (Eq. 17)
//! as a signed value; the row of D at knot i is J_i scaled by h̄_i³, h̄_i = (h_{i−1} + h_i)/2,
//! which gives it the units of the points (a jump of s‴ is a value over a length cubed), so
//! that λ is scale-free. O(N²) to build for N sites (N tridiagonal or cyclic solves).

use nalgebra::{DMatrix, DVector};

use crate::state::strategy_error;
use crate::Result;

use super::NAME;

/// D (rows: the jumps; columns: the sites) for the sites `knots` (t_0 < … < t_m; on a closed
/// direction t_m is the period's end and the sites are t_0..t_{m−1}).
pub(crate) fn jump_matrix(knots: &[f64], closed: bool) -> Result<DMatrix<f64>> {
    let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    if h.iter().any(|&s| !(s > 0.0 && s.is_finite())) {
        return Err(strategy_error(
            NAME,
            "two consecutive grid lines coincide (a knot step is not positive)",
        ));
    }
    let spans = h.len();
    if closed {
        let n = spans; // distinct sites
        if n < 3 {
            return Err(strategy_error(
                NAME,
                "a closed direction needs at least 3 distinct grid lines",
            ));
        }
        // Periodic moments: A M = B y, A cyclic tridiagonal.
        let mut a = DMatrix::<f64>::zeros(n, n);
        let mut b = DMatrix::<f64>::zeros(n, n);
        for k in 0..n {
            let (p, q) = ((k + n - 1) % n, (k + 1) % n);
            let (hp, hk) = (h[p], h[k]);
            a[(k, p)] += hp;
            a[(k, k)] += 2.0 * (hp + hk);
            a[(k, q)] += hk;
            b[(k, q)] += 6.0 / hk;
            b[(k, k)] -= 6.0 / hk + 6.0 / hp;
            b[(k, p)] += 6.0 / hp;
        }
        let moments = a
            .cholesky()
            .ok_or_else(|| strategy_error(NAME, "singular periodic spline system"))?
            .solve(&b);
        let mut d = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            let (p, q) = ((i + n - 1) % n, (i + 1) % n);
            let scale = (0.5 * (h[p] + h[i])).powi(3);
            for c in 0..n {
                let right = (moments[(q, c)] - moments[(i, c)]) / h[i];
                let left = (moments[(i, c)] - moments[(p, c)]) / h[p];
                d[(i, c)] = scale * (right - left);
            }
        }
        return Ok(d);
    }
    let sites = spans + 1;
    if sites < 3 {
        return Err(strategy_error(NAME, "a direction needs at least 3 grid lines"));
    }
    let inner = sites - 2; // moments M_1..M_{m-1}
                           // Tridiagonal solve per column of B (Thomas), M_0 = M_m = 0.
    let diag: Vec<f64> = (1..=inner).map(|k| 2.0 * (h[k - 1] + h[k])).collect();
    let mut moments = DMatrix::<f64>::zeros(sites, sites);
    let mut rhs = DVector::<f64>::zeros(inner);
    let mut c_prime = vec![0.0; inner];
    let mut d_prime = vec![0.0; inner];
    for col in 0..sites {
        rhs.fill(0.0);
        for k in 1..=inner {
            let mut v = 0.0;
            if col == k + 1 {
                v += 6.0 / h[k];
            }
            if col == k {
                v -= 6.0 / h[k] + 6.0 / h[k - 1];
            }
            if col + 1 == k {
                v += 6.0 / h[k - 1];
            }
            rhs[k - 1] = v;
        }
        for r in 0..inner {
            let lower = if r > 0 { h[r] } else { 0.0 };
            let upper = if r + 1 < inner { h[r + 1] } else { 0.0 };
            let denom = diag[r] - lower * if r > 0 { c_prime[r - 1] } else { 0.0 };
            c_prime[r] = upper / denom;
            d_prime[r] = (rhs[r] - lower * if r > 0 { d_prime[r - 1] } else { 0.0 }) / denom;
        }
        for r in (0..inner).rev() {
            let next = if r + 1 < inner { moments[(r + 2, col)] } else { 0.0 };
            moments[(r + 1, col)] = d_prime[r] - c_prime[r] * next;
        }
    }
    let mut d = DMatrix::<f64>::zeros(inner, sites);
    for i in 1..=inner {
        let scale = (0.5 * (h[i - 1] + h[i])).powi(3);
        for c in 0..sites {
            let right = (moments[(i + 1, c)] - moments[(i, c)]) / h[i];
            let left = (moments[(i, c)] - moments[(i - 1, c)]) / h[i - 1];
            d[(i - 1, c)] = scale * (right - left);
        }
    }
    Ok(d)
}

/// K = DᵀD, symmetrised.
pub(crate) fn gram(d: &DMatrix<f64>) -> DMatrix<f64> {
    let k = d.transpose() * d;
    (&k + k.transpose()) * 0.5
}
