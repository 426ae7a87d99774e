//! B-spline basis functions and their derivatives (The NURBS Book A2.1–A2.3).
//!
//! The functions take the raw knot slice of a validated [`KnotVector`](super::KnotVector) and
//! a span index from [`find_span`]; with those they never index out of range.

use crate::Side;

/// The knot span index (The NURBS Book A2.1), by binary search: O(log m).
///
/// `knots` is a clamped knot vector of `degree` p with n + 1 = m − p control points. With
/// `Side::Right` the result is the i in [p, n] with u_i ≤ u < u_{i+1} (at u = u_{n+1}, the
/// end of the domain, the last span n as in A2.1); with `Side::Left` the i with
/// u_i < u ≤ u_{i+1} (at u = u_p the first span p). Parameters outside the domain (and NaN)
/// give the first or last span.
pub fn find_span(knots: &[f64], degree: usize, u: f64, side: Side) -> usize {
    let n = knots.len().saturating_sub(degree + 2);
    let count = match side {
        Side::Right => knots.partition_point(|&k| k <= u),
        Side::Left => knots.partition_point(|&k| k < u),
    };
    count.saturating_sub(1).clamp(degree, n.max(degree))
}

/// The p + 1 non-vanishing basis functions N_{span−p,p}(u) … N_{span,p}(u)
/// (The NURBS Book A2.2, the Cox–de Boor recurrence in triangular form). O(p²).
pub fn basis_functions(knots: &[f64], degree: usize, span: usize, u: f64) -> Vec<f64> {
    let p = degree;
    let mut values = vec![0.0; p + 1];
    let mut left = vec![0.0; p + 1];
    let mut right = vec![0.0; p + 1];
    values[0] = 1.0;
    for j in 1..=p {
        left[j] = u - knot(knots, span + 1 - j);
        right[j] = knot(knots, span + j) - u;
        let mut saved = 0.0;
        for r in 0..j {
            let denominator = right[r + 1] + left[j - r];
            let temp = if denominator != 0.0 {
                values[r] / denominator
            } else {
                0.0
            };
            values[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        values[j] = saved;
    }
    values
}

/// A knot by index; out-of-range indices (impossible for a validated vector and a span from
/// [`find_span`]) read as NaN rather than panic.
#[inline]
fn knot(knots: &[f64], index: usize) -> f64 {
    knots.get(index).copied().unwrap_or(f64::NAN)
}

/// The non-vanishing basis functions and their derivatives up to `order`
/// (The NURBS Book A2.3). Row k holds N^{(k)}_{span−p+j,p}(u) for j = 0..=p; rows above the
/// degree are zero. O(p² + order·p²).
pub fn basis_derivatives(knots: &[f64], degree: usize, span: usize, u: f64, order: usize) -> Vec<Vec<f64>> {
    let p = degree;
    // ndu[j][r]: basis functions (upper triangle incl. diagonal) and knot differences (lower).
    let mut ndu = vec![vec![0.0; p + 1]; p + 1];
    let mut left = vec![0.0; p + 1];
    let mut right = vec![0.0; p + 1];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - knot(knots, span + 1 - j);
        right[j] = knot(knots, span + j) - u;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = if ndu[j][r] != 0.0 {
                ndu[r][j - 1] / ndu[j][r]
            } else {
                0.0
            };
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut ders = vec![vec![0.0; p + 1]; order + 1];
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let top = order.min(p);
    let mut a = [vec![0.0; p + 1], vec![0.0; p + 1]];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0].iter_mut().for_each(|v| *v = 0.0);
        a[0][0] = 1.0;
        for k in 1..=top {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                let rk = rk as usize;
                let inv = if ndu[pk + 1][rk] != 0.0 {
                    1.0 / ndu[pk + 1][rk]
                } else {
                    0.0
                };
                a[s2][0] = a[s1][0] * inv;
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let column = (rk + j as isize) as usize;
                let inv = if ndu[pk + 1][column] != 0.0 {
                    1.0 / ndu[pk + 1][column]
                } else {
                    0.0
                };
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * inv;
                d += a[s2][j] * ndu[column][pk];
            }
            if r <= pk {
                let inv = if ndu[pk + 1][r] != 0.0 {
                    1.0 / ndu[pk + 1][r]
                } else {
                    0.0
                };
                a[s2][k] = -a[s1][k - 1] * inv;
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().take(top + 1).skip(1) {
        row.iter_mut().for_each(|v| *v *= factor);
        factor *= (p - k) as f64;
    }
    ders
}

#[cfg(test)]
mod tests {
    use super::*;

    const KNOTS: [f64; 12] = [0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0];

    #[test]
    fn spans_pick_the_side() {
        // cubic, 8 control points (m = 11)
        let k = &KNOTS[..];
        assert_eq!(find_span(k, 3, 0.0, Side::Right), 3);
        assert_eq!(find_span(k, 3, 0.0, Side::Left), 3);
        assert_eq!(find_span(k, 3, 0.2, Side::Right), 4);
        assert_eq!(find_span(k, 3, 0.2, Side::Left), 3);
        assert_eq!(find_span(k, 3, 0.5, Side::Right), 6);
        assert_eq!(find_span(k, 3, 0.5, Side::Left), 4);
        assert_eq!(find_span(k, 3, 1.0, Side::Right), 7);
        assert_eq!(find_span(k, 3, 2.0, Side::Right), 7);
        assert_eq!(find_span(k, 3, f64::NAN, Side::Right), 3);
    }

    #[test]
    fn basis_is_a_partition_of_unity_and_derivatives_match_differences() {
        let k = &KNOTS[..];
        for &u in &[0.0, 0.1, 0.2, 0.37, 0.5, 0.66, 0.93, 1.0] {
            let span = find_span(k, 3, u, Side::Right);
            let n = basis_functions(k, 3, span, u);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(n.iter().all(|&v| v >= 0.0));
            let d = basis_derivatives(k, 3, span, u, 4);
            for j in 0..4 {
                assert!((d[0][j] - n[j]).abs() < 1e-15);
            }
            // derivatives of every order sum to zero (the sum is the constant 1)
            for row in &d[1..] {
                assert!(row.iter().sum::<f64>().abs() < 1e-9);
            }
            assert!(d[4].iter().all(|&v| v == 0.0));
            // central differences within the span
            let h = 1e-6;
            if u > 0.0 && u < 1.0 && ![0.2, 0.5].contains(&u) {
                let plus = basis_derivatives(k, 3, span, u + h, 3);
                let minus = basis_derivatives(k, 3, span, u - h, 3);
                for order in 0..3 {
                    for j in 0..4 {
                        let fd = (plus[order][j] - minus[order][j]) / (2.0 * h);
                        assert!((fd - d[order + 1][j]).abs() < 1e-4 * (1.0 + d[order + 1][j].abs()));
                    }
                }
            }
        }
    }
}
