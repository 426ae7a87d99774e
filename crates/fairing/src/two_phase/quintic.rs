//! The natural quintic interpolating spline: the read-back of a binned pre-pass
//! ([`super::bins`]).
//!
//! **Why a quintic.** A binned pre-pass fits n_b bin means and reads its fit back at all n
//! points. Read back from the cubic spline through the fitted means, the points of a bin
//! lie on one cubic, so the output's own interpolating cubic (knots at every point) has
//! third-derivative jumps of zero inside the bins, which the x–c polyline's e_i (and the
//! judge's vibration count) then see as round-off of either sign: on 10^4 noisy points of
//! y = sin(kx) over [0, 20] (σ = 0.01, 2 000 bins of 5, jump-lsq by GCV on the means),
//! 7 010–7 140 vibrations against the clean curve's 14–60. The quintic spline through the
//! same fitted means is C⁴: its fourth derivative is continuous, so the output's jumps are
//! h·s⁗ as a smooth curve's samples have, and the same read-back ends with the clean
//! curve's 14 / 24 / 60 vibrations (k = 0.5 / 2 / 8) at the same distance to it.
//!
//! **Representation** (on knots x_0 < … < x_N with values y_i). s″ =: g is a cubic spline,
//! written with its values G_i = s″(x_i) and second derivatives P_i = g″(x_i) = s⁗(x_i);
//! on [x_i, x_{i+1}], with h = x_{i+1} − x_i and t = (x − x_i)/h,
//!
//! ```text
//! s = y_i (1−t) + y_{i+1} t + h² [G_i ψ₁(1−t) + G_{i+1} ψ₁(t)] + h⁴ [P_i ψ₂(1−t) + P_{i+1} ψ₂(t)],
//! ψ₁(t) = (t³ − t)/6,   ψ₂(t) = t⁵/120 − t³/36 + 7t/360,
//! ```
//!
//! (ψ₁″ = t, ψ₂″ = ψ₁, both zero at t = 0 and 1), so that s interpolates and s″ = g is the
//! cubic with those end values and second derivatives. s is C⁴ when g is C² and s is C¹:
//!
//! ```text
//! (B_i)  h_{i−1} P_{i−1}/6 + (h_{i−1} + h_i) P_i/3 + h_i P_{i+1}/6
//!            = (G_{i+1} − G_i)/h_i − (G_i − G_{i−1})/h_{i−1}                     (g′ continuous)
//! (A_i)  h_{i−1} G_{i−1}/6 + (h_{i−1} + h_i) G_i/3 + h_i G_{i+1}/6
//!            − [7 h_{i−1}³ P_{i−1} + 8 (h_{i−1}³ + h_i³) P_i + 7 h_i³ P_{i+1}]/360
//!            = Δ_i − Δ_{i−1},   Δ_i = (y_{i+1} − y_i)/h_i                         (s′ continuous)
//! ```
//!
//! at the interior knots, and the natural end conditions s‴ = s⁗ = 0 (P_0 = P_N = 0,
//! g′(x_0) = (G_1 − G_0)/h_0 − h_0 P_1/6 = 0, g′(x_N) = (G_N − G_{N−1})/h_{N−1} +
//! h_{N−1} P_{N−1}/6 = 0): the natural interpolating spline of order 6 (de Boor, *A Practical
//! Guide to Splines*, 1978; SciPy's `make_interp_spline(k=5)` with those conditions). It
//! reproduces quadratics. The 2(N + 1) unknowns, interleaved (G_0, P_0, G_1, P_1, …), form a
//! band of three sub- and three super-diagonals, solved by Gaussian elimination with partial
//! pivoting on the band. O(N) to build, O(1) per value (O(log N) to find a piece; a sorted
//! sweep [`Quintic::values`] is O(N + n)).

use crate::state::strategy_error;
use crate::Result;

/// The natural quintic spline through (x_i, y_i) (module doc).
#[derive(Clone, Debug)]
pub(crate) struct Quintic {
    x: Vec<f64>,
    y: Vec<f64>,
    /// s″ at the knots.
    g: Vec<f64>,
    /// s⁗ at the knots.
    p: Vec<f64>,
}

/// ψ₁(t) = (t³ − t)/6 and its first three derivatives.
fn psi1(t: f64) -> [f64; 4] {
    [(t * t * t - t) / 6.0, (3.0 * t * t - 1.0) / 6.0, t, 1.0]
}

/// ψ₂(t) = t⁵/120 − t³/36 + 7t/360 and its first four derivatives.
fn psi2(t: f64) -> [f64; 5] {
    let t2 = t * t;
    [
        t2 * t2 * t / 120.0 - t2 * t / 36.0 + 7.0 * t / 360.0,
        t2 * t2 / 24.0 - t2 / 12.0 + 7.0 / 360.0,
        t2 * t / 6.0 - t / 6.0,
        t2 / 2.0 - 1.0 / 6.0,
        t,
    ]
}

impl Quintic {
    /// The natural quintic spline through `(x, y)`, x strictly increasing, at least 3 knots
    /// (two knots give the line through them). O(N).
    ///
    /// Errors: mismatched lengths, fewer than 2 knots, x not strictly increasing, non-finite
    /// values, or a singular system.
    pub(crate) fn new(x: &[f64], y: &[f64]) -> Result<Self> {
        let fail = |why: String| strategy_error("two-phase", format!("quintic read-back: {why}"));
        if x.len() != y.len() || x.len() < 2 {
            return Err(fail(format!(
                "{} knots for {} values (at least 2)",
                x.len(),
                y.len()
            )));
        }
        if let Some(i) = (0..x.len()).find(|&i| !(x[i].is_finite() && y[i].is_finite())) {
            return Err(fail(format!("a non-finite knot or value at {i}")));
        }
        // All finite by now, so `<=` also catches equal knots.
        if let Some(i) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
            return Err(fail(format!("knots not strictly increasing at {i}")));
        }
        let n = x.len() - 1;
        if n == 1 {
            return Ok(Quintic {
                x: x.to_vec(),
                y: y.to_vec(),
                g: vec![0.0; 2],
                p: vec![0.0; 2],
            });
        }
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let delta: Vec<f64> = (0..n).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let size = 2 * (n + 1);
        let mut band = Band::new(size, 3, 3);
        let mut rhs = vec![0.0; size];
        let (g, p) = (|i: usize| 2 * i, |i: usize| 2 * i + 1);
        // g′(x_0) = 0 and P_0 = 0.
        band.set(0, g(0), -1.0 / h[0]);
        band.set(0, g(1), 1.0 / h[0]);
        band.set(0, p(1), -h[0] / 6.0);
        band.set(1, p(0), 1.0);
        for i in 1..n {
            let (a, b) = (h[i - 1], h[i]);
            let row = 2 * i;
            band.set(row, g(i - 1), a / 6.0);
            band.set(row, g(i), (a + b) / 3.0);
            band.set(row, g(i + 1), b / 6.0);
            band.set(row, p(i - 1), -7.0 * a * a * a / 360.0);
            band.set(row, p(i), -8.0 * (a * a * a + b * b * b) / 360.0);
            band.set(row, p(i + 1), -7.0 * b * b * b / 360.0);
            rhs[row] = delta[i] - delta[i - 1];
            let row = 2 * i + 1;
            band.set(row, p(i - 1), a / 6.0);
            band.set(row, p(i), (a + b) / 3.0);
            band.set(row, p(i + 1), b / 6.0);
            band.set(row, g(i - 1), -1.0 / a);
            band.set(row, g(i), 1.0 / a + 1.0 / b);
            band.set(row, g(i + 1), -1.0 / b);
        }
        // g′(x_N) = 0 and P_N = 0.
        let last = h[n - 1];
        band.set(2 * n, g(n - 1), -1.0 / last);
        band.set(2 * n, g(n), 1.0 / last);
        band.set(2 * n, p(n - 1), last / 6.0);
        band.set(2 * n + 1, p(n), 1.0);
        let z = band
            .solve(rhs)
            .ok_or_else(|| fail("the interpolation system is singular".into()))?;
        if z.iter().any(|v| !v.is_finite()) {
            return Err(fail("the interpolation system gave a non-finite value".into()));
        }
        Ok(Quintic {
            x: x.to_vec(),
            y: y.to_vec(),
            g: (0..=n).map(|i| z[g(i)]).collect(),
            p: (0..=n).map(|i| z[p(i)]).collect(),
        })
    }

    /// s and its first four derivatives at `x` on piece `i` (extended beyond the end knots
    /// by the end pieces' quintics).
    fn on_piece(&self, i: usize, x: f64) -> [f64; 5] {
        let h = self.x[i + 1] - self.x[i];
        let t = (x - self.x[i]) / h;
        let (a1, b1) = (psi1(1.0 - t), psi1(t));
        let (a2, b2) = (psi2(1.0 - t), psi2(t));
        let (y0, y1, g0, g1, p0, p1) = (
            self.y[i],
            self.y[i + 1],
            self.g[i],
            self.g[i + 1],
            self.p[i],
            self.p[i + 1],
        );
        let h2 = h * h;
        let h4 = h2 * h2;
        let mut out = [0.0; 5];
        out[0] = y0 * (1.0 - t) + y1 * t + h2 * (g0 * a1[0] + g1 * b1[0]) + h4 * (p0 * a2[0] + p1 * b2[0]);
        // d/dx = (1/h) d/dt; a term in (1 − t) changes sign with each derivative.
        let mut scale = 1.0 / h;
        for k in 1..5 {
            let sign = if k % 2 == 1 { -1.0 } else { 1.0 };
            let psi1_part = if k < 4 {
                g0 * sign * a1[k] + g1 * b1[k]
            } else {
                0.0
            };
            let linear = if k == 1 { y1 - y0 } else { 0.0 };
            out[k] = (linear + h2 * psi1_part + h4 * (p0 * sign * a2[k] + p1 * b2[k])) * scale;
            scale /= h;
        }
        out
    }

    /// The piece holding `x` (the end pieces beyond the knots).
    #[cfg(test)]
    fn piece(&self, x: f64) -> usize {
        let n = self.x.len() - 1;
        self.x[1..n].partition_point(|&k| k <= x)
    }

    /// s(x). O(log N).
    #[cfg(test)]
    pub(crate) fn value(&self, x: f64) -> f64 {
        self.on_piece(self.piece(x), x)[0]
    }

    /// s and its first four derivatives at `x`, from the piece on the left of a knot
    /// (`left`) or on its right. O(log N).
    #[cfg(test)]
    pub(crate) fn derivatives(&self, x: f64, left: bool) -> [f64; 5] {
        let mut i = self.piece(x);
        if left && i > 0 && x <= self.x[i] {
            i -= 1;
        }
        self.on_piece(i, x)
    }

    /// s at each of `xs`, sorted increasingly: one sweep, O(N + n).
    pub(crate) fn values(&self, xs: &[f64]) -> Vec<f64> {
        let n = self.x.len() - 1;
        let mut i = 0;
        xs.iter()
            .map(|&x| {
                while i + 1 < n && self.x[i + 1] <= x {
                    i += 1;
                }
                self.on_piece(i, x)[0]
            })
            .collect()
    }
}

/// A band matrix of `size` rows with `lower` sub- and `upper` super-diagonals, stored with
/// room for the fill of partial pivoting (`lower` more super-diagonals).
struct Band {
    size: usize,
    lower: usize,
    upper: usize,
    /// Row r holds columns r − lower … r + lower + upper.
    rows: Vec<Vec<f64>>,
}

impl Band {
    fn new(size: usize, lower: usize, upper: usize) -> Self {
        Band {
            size,
            lower,
            upper,
            rows: vec![vec![0.0; 2 * lower + upper + 1]; size],
        }
    }

    fn set(&mut self, row: usize, column: usize, value: f64) {
        debug_assert!(column + self.lower >= row && column <= row + self.upper);
        self.rows[row][column + self.lower - row] = value;
    }

    fn at(&self, row: usize, column: usize) -> f64 {
        self.rows[row][column + self.lower - row]
    }

    fn at_mut(&mut self, row: usize, column: usize) -> &mut f64 {
        &mut self.rows[row][column + self.lower - row]
    }

    /// Solves A z = rhs by Gaussian elimination with partial pivoting within the band
    /// (rows swapped keep their columns inside the widened band). `None` when a pivot is
    /// zero. O(size · lower · (lower + upper)).
    fn solve(mut self, mut rhs: Vec<f64>) -> Option<Vec<f64>> {
        let (size, lower) = (self.size, self.lower);
        let reach = lower + self.upper;
        for k in 0..size {
            let last_row = (k + lower).min(size - 1);
            let pivot_row =
                (k..=last_row).max_by(|&a, &b| self.at(a, k).abs().total_cmp(&self.at(b, k).abs()))?;
            if self.at(pivot_row, k) == 0.0 {
                return None;
            }
            let last_column = (k + reach).min(size - 1);
            if pivot_row != k {
                for c in k..=last_column {
                    let (a, b) = (self.at(k, c), self.at(pivot_row, c));
                    *self.at_mut(k, c) = b;
                    *self.at_mut(pivot_row, c) = a;
                }
                rhs.swap(k, pivot_row);
            }
            let pivot = self.at(k, k);
            for r in k + 1..=last_row {
                let factor = self.at(r, k) / pivot;
                if factor == 0.0 {
                    continue;
                }
                *self.at_mut(r, k) = 0.0;
                for c in k + 1..=last_column {
                    let v = self.at(k, c);
                    *self.at_mut(r, c) -= factor * v;
                }
                rhs[r] -= factor * rhs[k];
            }
        }
        let mut z = vec![0.0; size];
        for k in (0..size).rev() {
            let last_column = (k + reach).min(size - 1);
            let sum: f64 = (k + 1..=last_column).map(|c| self.at(k, c) * z[c]).sum();
            z[k] = (rhs[k] - sum) / self.at(k, k);
        }
        Some(z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uneven knots and values of a wiggly function.
    fn data() -> (Vec<f64>, Vec<f64>) {
        let x: Vec<f64> = (0..40)
            .map(|i| i as f64 * 0.3 + 0.1 * (i as f64 * 1.7).sin())
            .collect();
        let y = x
            .iter()
            .map(|&x| (0.7 * x).sin() + 0.2 * (2.3 * x).cos())
            .collect();
        (x, y)
    }

    #[test]
    fn it_interpolates_is_c4_at_every_knot_and_natural_at_the_ends() {
        let (x, y) = data();
        let s = Quintic::new(&x, &y).unwrap();
        let scale = s.g.iter().chain(&s.p).fold(1.0f64, |m, v| m.max(v.abs()));
        for (i, (&xi, &yi)) in x.iter().zip(&y).enumerate() {
            assert!(
                (s.value(xi) - yi).abs() < 1e-12,
                "knot {i}: {} against {yi}",
                s.value(xi)
            );
        }
        for (i, &xi) in x.iter().enumerate().take(x.len() - 1).skip(1) {
            let (l, r) = (s.derivatives(xi, true), s.derivatives(xi, false));
            for k in 0..5 {
                assert!(
                    (l[k] - r[k]).abs() < 1e-9 * scale,
                    "derivative {k} jumps at knot {i}: {} against {}",
                    l[k],
                    r[k]
                );
            }
        }
        for (xe, left) in [(x[0], false), (*x.last().unwrap(), true)] {
            let d = s.derivatives(xe, left);
            assert!(
                d[3].abs() < 1e-9 * scale && d[4].abs() < 1e-9 * scale,
                "end {xe}: {d:?}"
            );
        }
        // The derivatives are those of the values: a central difference of s‴ gives s⁗.
        let (xm, e) = (x[10] + 0.05, 1e-4);
        let d = s.derivatives(xm, false);
        let fd = (s.derivatives(xm + e, false)[3] - s.derivatives(xm - e, false)[3]) / (2.0 * e);
        assert!(
            (fd - d[4]).abs() < 1e-6 * scale,
            "s⁗ {} against the difference {fd}",
            d[4]
        );
        let fd = (s.value(xm + e) - s.value(xm - e)) / (2.0 * e);
        assert!(
            (fd - d[1]).abs() < 1e-6,
            "s′ {} against the difference {fd}",
            d[1]
        );
    }

    #[test]
    fn it_reproduces_quadratics_and_the_sweep_matches_the_values() {
        let (x, _) = data();
        let q = |x: f64| 0.3 - 1.2 * x + 0.05 * x * x;
        let y: Vec<f64> = x.iter().map(|&x| q(x)).collect();
        let s = Quintic::new(&x, &y).unwrap();
        let xs: Vec<f64> = (0..500).map(|k| -0.2 + k as f64 * 0.024).collect();
        let swept = s.values(&xs);
        for (&xv, &v) in xs.iter().zip(&swept) {
            assert!((v - q(xv)).abs() < 1e-10, "at {xv}: {v} against {}", q(xv));
            assert_eq!(v, s.value(xv), "the sweep and the lookup differ at {xv}");
        }
    }

    #[test]
    fn bad_knots_are_refused() {
        assert!(Quintic::new(&[0.0, 1.0, 1.0], &[0.0, 1.0, 2.0]).is_err());
        assert!(Quintic::new(&[0.0, 1.0], &[0.0]).is_err());
        assert!(Quintic::new(&[0.0, f64::NAN, 2.0], &[0.0, 1.0, 2.0]).is_err());
        let line = Quintic::new(&[0.0, 2.0], &[1.0, 3.0]).unwrap();
        assert_eq!(line.value(1.0), 2.0);
    }
}
