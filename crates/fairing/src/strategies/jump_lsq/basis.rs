//! The cubic B-spline basis on the knots of the points: one span at a time, without
//! allocation.
//!
//! The spline space of [`super`] is spanned by cubic B-splines whose breakpoints are the
//! parameters t_0 < … < t_{n−1} of the points. Knot j of the extended knot sequence is
//! - open curves (clamped ends): u_j = t_{clamp(j, 0, n−1)} for j = −3 … n + 2, so that the
//!   n + 2 B-splines β_0 … β_{n+1} have supports [u_{j−3}, u_{j+1}];
//! - closed curves (periodic): u_j = t_{j mod n} + ⌊j/n⌋·T with T the period, n B-splines,
//!   indices modulo n.
//!
//! In both cases span k = [u_k, u_{k+1}] carries the four B-splines β_k … β_{k+3} (modulo n
//! when closed), and their values there depend on the six knots u_{k−2} … u_{k+3}.

/// Values and derivatives of orders 0 to 3 of the four cubic B-splines that do not vanish on
/// the span [w\[2\], w\[3\]] of the knot window `w` = (u_{k−2}, …, u_{k+3}), at `u`:
/// `ders[k][r]` = d^k N_r/du^k (The NURBS Book A2.3 with p = 3, on the window). The span must
/// have positive length; the other knot differences may vanish (clamped ends). O(1).
pub(crate) fn cubic_ders(w: &[f64; 6], u: f64) -> [[f64; 4]; 4] {
    const P: usize = 3;
    let mut ndu = [[0.0f64; 4]; 4];
    let mut left = [0.0f64; 4];
    let mut right = [0.0f64; 4];
    ndu[0][0] = 1.0;
    for j in 1..=P {
        left[j] = u - w[3 - j];
        right[j] = w[2 + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut ders = [[0.0f64; 4]; 4];
    for j in 0..=P {
        ders[0][j] = ndu[j][P];
    }
    let inverse = |x: f64| if x != 0.0 { 1.0 / x } else { 0.0 };
    for r in 0..=P {
        let mut a = [[0.0f64; 4]; 2];
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=P {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = P - k;
            if r >= k {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] * inverse(ndu[pk + 1][rk]);
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                k - 1
            } else {
                P - r
            };
            for j in j1..=j2 {
                let column = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * inverse(ndu[pk + 1][column]);
                d += a[s2][j] * ndu[column][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] * inverse(ndu[pk + 1][r]);
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = P as f64;
    for (k, row) in ders.iter_mut().enumerate().skip(1) {
        for v in row.iter_mut() {
            *v *= factor;
        }
        factor *= (P - k) as f64;
    }
    ders
}

/// The knots of the points, open (clamped) or closed (periodic).
#[derive(Clone, Debug)]
pub(crate) struct Knots {
    /// t_0 … t_{n−1}, strictly increasing.
    t: Vec<f64>,
    /// The period T (closed curves): t_n = T closes the last span.
    period: Option<f64>,
}

impl Knots {
    /// Open knots t (at least 2, strictly increasing: the caller checks).
    pub(super) fn open(t: Vec<f64>) -> Self {
        Knots { t, period: None }
    }

    /// Closed knots: `t` holds t_0 … t_n, t_n the period end (n + 1 values).
    pub(super) fn closed(mut t: Vec<f64>) -> Self {
        let end = t.pop();
        let period = end.zip(t.first()).map(|(e, s)| e - s);
        Knots { t, period }
    }

    /// The number of points n.
    pub(super) fn len(&self) -> usize {
        self.t.len()
    }

    /// The period T of closed knots (`None` when open).
    pub(super) fn period(&self) -> Option<f64> {
        self.period
    }

    /// Whether the knots are periodic.
    pub(super) fn is_closed(&self) -> bool {
        self.period.is_some()
    }

    /// The parameters t_i.
    pub(super) fn values(&self) -> &[f64] {
        &self.t
    }

    /// Knot u_j of the extended sequence (module docs).
    pub(super) fn knot(&self, j: isize) -> f64 {
        let n = self.t.len() as isize;
        match self.period {
            None => self.t[j.clamp(0, n - 1) as usize],
            Some(period) => {
                let wraps = j.div_euclid(n);
                self.t[j.rem_euclid(n) as usize] + wraps as f64 * period
            }
        }
    }

    /// The number of spans: n − 1 open, n closed.
    pub(super) fn spans(&self) -> usize {
        if self.is_closed() {
            self.t.len()
        } else {
            self.t.len() - 1
        }
    }

    /// The length of span k.
    pub(super) fn spacing(&self, k: usize) -> f64 {
        let k = k as isize;
        self.knot(k + 1) - self.knot(k)
    }

    /// The window u_{k−2} … u_{k+3} of span k.
    pub(super) fn window(&self, k: usize) -> [f64; 6] {
        let k = k as isize;
        std::array::from_fn(|r| self.knot(k - 2 + r as isize))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::bspline::basis::basis_derivatives;

    #[test]
    fn window_basis_matches_the_nurbs_book_on_the_full_knot_vector() {
        let t = [0.0, 0.3, 1.0, 1.1, 2.5, 2.6, 4.0];
        let knots = Knots::open(t.to_vec());
        // The full clamped vector: t_0 four times, the interior once, t_{n-1} four times.
        let mut full = vec![t[0]; 3];
        full.extend_from_slice(&t);
        full.extend([t[6]; 3]);
        for k in 0..knots.spans() {
            for u in [t[k], 0.5 * (t[k] + t[k + 1]), t[k + 1]] {
                let ours = cubic_ders(&knots.window(k), u);
                let theirs = basis_derivatives(&full, 3, k + 3, u, 3);
                for order in 0..4 {
                    for r in 0..4 {
                        let (a, b) = (ours[order][r], theirs[order][r]);
                        assert!(
                            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                            "span {k} u {u} order {order} r {r}: {a} vs {b}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn periodic_basis_is_a_partition_of_unity_with_continuous_derivatives() {
        let knots = Knots::closed(vec![0.0, 0.4, 1.0, 1.3, 2.2, 3.0]);
        assert_eq!(knots.len(), 5);
        assert_eq!(knots.spans(), 5);
        for k in 0..knots.spans() {
            let (a, b) = (knots.knot(k as isize), knots.knot(k as isize + 1));
            let ders = cubic_ders(&knots.window(k), 0.5 * (a + b));
            let sum: f64 = ders[0].iter().sum();
            assert!((sum - 1.0).abs() < 1e-14);
            // Values and first two derivatives of each B-spline agree across the knot at the
            // end of span k (C2): B-spline k + 1 + r on span k + 1 is index r on that span.
            let end = cubic_ders(&knots.window(k), b);
            let k1 = (k + 1) % knots.spans();
            let next = cubic_ders(&knots.window(k1), knots.knot(k1 as isize));
            for order in 0..3 {
                for r in 1..4 {
                    let (x, y) = (end[order][r], next[order][r - 1]);
                    assert!(
                        (x - y).abs() < 1e-10 * (1.0 + x.abs()),
                        "span {k} order {order} r {r}: {x} vs {y}"
                    );
                }
                // The B-spline that starts at the knot has a zero value and derivatives up to
                // the second there.
                assert!(next[order][3].abs() < 1e-12 * (1.0 + next[order][0].abs()));
            }
        }
    }
}
