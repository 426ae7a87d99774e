//! Least-squares B-spline approximation with knots placed by the data: The NURBS Book §9.4.1
//! (Eq. 9.63–9.69; the unweighted, unconstrained case of its A9.6), the "Rebuild" of CAD
//! systems: few control points through many faired points.
//!
//! Given points Q_0 … Q_m at parameters ū_0 < … < ū_m, a degree p and n + 1 control points
//! (p + 1 ≤ n + 1 ≤ m + 1), the curve C(u) = Σ_{i=0}^{n} N_{i,p}(u) P_i
//!
//! - interpolates the end points, P_0 = Q_0 and P_n = Q_m;
//! - has the knots of Eq. 9.68–9.69: d = (m + 1)/(n − p + 1) and, for j = 1 … n − p,
//!   i = ⌊j d⌋, α = j d − i, u_{p+j} = (1 − α) ū_{i−1} + α ū_i, so that every knot span holds
//!   at least one ū_k and the normal equations are positive definite (Schoenberg–Whitney);
//!   this crate asks for d ≥ 2 (at least two points per knot span on average): as n
//!   approaches m the knots of Eq. 9.69 crowd next to the parameters, the collocation matrix
//!   tends to a bidiagonal one with pivots near (j + 1)/(m + 1), and the normal equations
//!   lose every digit (measured: the "interpolating" fit n = m of 120 points misses its
//!   points by 2% of the curve's size at degree 1 and is singular at degree 2). A rebuild that
//!   needs more control points than half the points is better served by the exact curve;
//! - minimises Σ_{k=1}^{m−1} |Q_k − C(ū_k)|² over P_1 … P_{n−1}: with
//!   R_k = Q_k − N_{0,p}(ū_k) Q_0 − N_{n,p}(ū_k) Q_m (Eq. 9.63), the normal equations
//!   (NᵀN) P = R (Eq. 9.66) with N_{ki} = N_{i,p}(ū_k) and R_i = Σ_k N_{i,p}(ū_k) R_k (Eq. 9.67).
//!
//! NᵀN is banded (half-bandwidth p) and is solved by a banded Cholesky factorisation:
//! O(m p² + n p²) time, O(n p) memory.

use crate::bspline::{basis_functions, KnotVector};
use crate::{Error, NurbsCurve, Result, Side, Vec2, Vector};

/// A least-squares fit found by [`NurbsCurve::least_squares_within`].
#[derive(Clone, Debug, PartialEq)]
pub struct ToleranceFit<const D: usize> {
    /// The fitted curve.
    pub curve: NurbsCurve<D>,
    /// max_k |Q_k − C(ū_k)|, an upper bound of the distance of each point from the curve.
    pub max_deviation: f64,
    /// Whether `max_deviation` ≤ the tolerance asked for. `false` only when even the
    /// interpolating fit (n = m) misses it, by rounding.
    pub tolerance_met: bool,
}

/// The knots of Eq. 9.68–9.69 for `control_count` = n + 1 control points of `degree` p over
/// the parameters ū_0 … ū_m: p + 1 copies of ū_0 and ū_m and, for j = 1 … n − p,
/// u_{p+j} = (1 − α) ū_{i−1} + α ū_i with d = (m + 1)/(n − p + 1), i = ⌊j d⌋, α = j d − i.
///
/// Fails with [`Error::BadDegree`] for degree 0, [`Error::TooFewPoints`] unless
/// n + 1 ≥ p + 1 and m + 1 ≥ max(n + 1, 2(n − p + 1), 2) (see [`max_control_count`]),
/// [`Error::NonFinite`] / [`Error::NotIncreasing`] on bad parameters. O(m + n).
pub fn fit_knots(params: &[f64], degree: usize, control_count: usize) -> Result<KnotVector> {
    check_sizes(params.len(), degree, control_count)?;
    crate::convert::check_increasing("parameters", params)?;
    let m = params.len() - 1;
    let (n, p) = (control_count - 1, degree);
    let d = (m + 1) as f64 / (n - p + 1) as f64;
    let mut knots = Vec::with_capacity(n + p + 2);
    knots.extend(std::iter::repeat_n(params[0], p + 1));
    for j in 1..=n - p {
        let jd = j as f64 * d;
        let i = (jd.floor() as usize).clamp(1, m);
        let alpha = jd - i as f64;
        knots.push((1.0 - alpha) * params[i - 1] + alpha * params[i]);
    }
    knots.extend(std::iter::repeat_n(params[m], p + 1));
    KnotVector::new(degree, knots, control_count)
}

fn check_sizes(point_count: usize, degree: usize, control_count: usize) -> Result<()> {
    if degree == 0 {
        return Err(Error::BadDegree {
            degree,
            reason: "a least-squares fit needs degree at least 1",
        });
    }
    if control_count < degree + 1 {
        return Err(Error::TooFewPoints {
            what: "control points of a fit of this degree",
            needed: degree + 1,
            got: control_count,
        });
    }
    let needed = control_count.max(2 * (control_count - degree)).max(2);
    if point_count < needed {
        return Err(Error::TooFewPoints {
            what: "data points of a least-squares fit with this many control points (two per knot span, Eq. 9.68's d ≥ 2)",
            needed,
            got: point_count,
        });
    }
    Ok(())
}

/// The most control points a least-squares fit of `degree` through `point_count` points
/// takes: the largest n + 1 with n + 1 ≤ m + 1 and d = (m + 1)/(n − p + 1) ≥ 2 (see the
/// [module documentation](self)); at least p + 1. O(1).
pub fn max_control_count(point_count: usize, degree: usize) -> usize {
    (point_count / 2 + degree).min(point_count).max(degree + 1)
}

/// max_k |Q_k − C(ū_k)|. O(m p²).
pub fn max_deviation<const D: usize>(curve: &NurbsCurve<D>, points: &[Vector<D>], params: &[f64]) -> f64 {
    points
        .iter()
        .zip(params)
        .map(|(q, &u)| (q - curve.point(u)).norm())
        .fold(0.0, f64::max)
}

/// The symmetric positive definite band matrix NᵀN (half-bandwidth p) over unknowns
/// 1 … n − 1, and its right-hand side, accumulated point by point.
struct NormalEquations<const D: usize> {
    bandwidth: usize,
    /// band[i][d] = A[i][i + d], d = 0 … p.
    band: Vec<Vec<f64>>,
    rhs: Vec<Vector<D>>,
}

impl<const D: usize> NormalEquations<D> {
    fn new(unknowns: usize, bandwidth: usize) -> Self {
        Self {
            bandwidth,
            band: vec![vec![0.0; bandwidth + 1]; unknowns],
            rhs: vec![Vector::<D>::zeros(); unknowns],
        }
    }

    /// Banded Cholesky A = L Lᵀ, then the two triangular solves. O(N p²). Fails with
    /// [`Error::Singular`] when a pivot is not positive (A not positive definite).
    fn solve(self) -> Result<Vec<Vector<D>>> {
        let size = self.band.len();
        let p = self.bandwidth;
        // lower[i][k] = L[i][i − p + k], k = 0 … p (the diagonal at k = p).
        let mut lower = vec![vec![0.0; p + 1]; size];
        let at = |lower: &Vec<Vec<f64>>, i: usize, j: usize| -> f64 {
            if j + p < i || j > i {
                0.0
            } else {
                lower[i][j + p - i]
            }
        };
        for i in 0..size {
            let start = i.saturating_sub(p);
            for j in start..=i {
                let mut sum = if i - j <= p { self.band[j][i - j] } else { 0.0 };
                for k in start.max(j.saturating_sub(p))..j {
                    sum -= at(&lower, i, k) * at(&lower, j, k);
                }
                if i == j {
                    if !(sum > 0.0 && sum.is_finite()) {
                        return Err(Error::Singular {
                            what: "solving the least-squares normal equations",
                        });
                    }
                    lower[i][p] = sum.sqrt();
                } else {
                    lower[i][j + p - i] = sum / lower[j][p];
                }
            }
        }
        let mut y = self.rhs;
        for i in 0..size {
            let known =
                (i.saturating_sub(p)..i).fold(Vector::<D>::zeros(), |sum, k| sum + y[k] * at(&lower, i, k));
            y[i] = (y[i] - known) / lower[i][p];
        }
        for i in (0..size).rev() {
            let known = (i + 1..(i + p + 1).min(size))
                .fold(Vector::<D>::zeros(), |sum, k| sum + y[k] * at(&lower, k, i));
            y[i] = (y[i] - known) / lower[i][p];
        }
        Ok(y)
    }
}

impl<const D: usize> NurbsCurve<D> {
    /// The least-squares B-spline of `degree` with `control_count` = n + 1 control points
    /// through `points` Q_0 … Q_m at `params` ū_0 < … < ū_m (The NURBS Book §9.4.1, see the
    /// [module documentation](self)): end points interpolated, knots by Eq. 9.68–9.69, the
    /// interior control points from the normal equations (Eq. 9.63–9.67). Unit weights.
    ///
    /// Fails as [`fit_knots`], with [`Error::LengthMismatch`] when the points and parameters
    /// differ in number, [`Error::NonFinite`] on a non-finite point, and [`Error::Singular`]
    /// if the normal equations are not positive definite. O(m p² + n p²).
    pub fn least_squares(
        points: &[Vector<D>],
        params: &[f64],
        degree: usize,
        control_count: usize,
    ) -> Result<Self> {
        if points.len() != params.len() {
            return Err(Error::LengthMismatch {
                what: "parameters (one per point)",
                expected: points.len(),
                got: params.len(),
            });
        }
        crate::vector::check_finite(points)?;
        let knots = fit_knots(params, degree, control_count)?;
        let m = points.len() - 1;
        let (n, p) = (control_count - 1, degree);
        let (first, last) = (points[0], points[m]);
        let unknowns = n.saturating_sub(1);
        let mut equations = NormalEquations::<D>::new(unknowns, p);
        for (q, &u) in points.iter().zip(params).take(m).skip(1) {
            let span = knots.span(u, Side::Right);
            let basis = basis_functions(knots.knots(), p, span, u);
            let offset = span - p;
            // Eq. 9.63: R_k without the end points' share.
            let mut r = *q;
            for (a, &value) in basis.iter().enumerate() {
                match offset + a {
                    0 => r -= first * value,
                    i if i == n => r -= last * value,
                    _ => {}
                }
            }
            for (a, &na) in basis.iter().enumerate() {
                let i = offset + a;
                if i == 0 || i >= n {
                    continue;
                }
                equations.rhs[i - 1] += r * na;
                for (b, &nb) in basis.iter().enumerate().skip(a) {
                    let j = offset + b;
                    if j >= n {
                        continue;
                    }
                    equations.band[i - 1][j - i] += na * nb;
                }
            }
        }
        let interior = equations.solve()?;
        let mut control = Vec::with_capacity(n + 1);
        control.push(first);
        control.extend(interior);
        control.push(last);
        let weights = vec![1.0; control.len()];
        NurbsCurve::from_parts(knots, control, weights)
    }

    /// The least-squares fit of [`least_squares`](Self::least_squares) with the fewest
    /// control points found whose largest deviation max_k |Q_k − C(ū_k)| is at most
    /// `tolerance`: p + 1 control points first, then doubling, then bisection between the
    /// last count that missed and the first that met the tolerance (the deviation is not
    /// strictly monotone in the count, so the count found is the smallest the bisection
    /// meets, and always one that meets the tolerance). The fit with
    /// [`max_control_count`] control points is the last resort; if even it misses the
    /// tolerance it is returned with `tolerance_met = false`.
    ///
    /// Fails with [`Error::OutOfRange`] on a negative or non-finite tolerance, otherwise as
    /// [`least_squares`](Self::least_squares). O(log m) fits, each O(m p²).
    pub fn least_squares_within(
        points: &[Vector<D>],
        params: &[f64],
        degree: usize,
        tolerance: f64,
    ) -> Result<ToleranceFit<D>> {
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(Error::OutOfRange {
                what: "fit tolerance",
                value: tolerance,
                reason: "must be finite and at least 0",
            });
        }
        let fit = |count: usize| -> Result<(NurbsCurve<D>, f64)> {
            let curve = Self::least_squares(points, params, degree, count)?;
            let deviation = max_deviation(&curve, points, params);
            Ok((curve, deviation))
        };
        let most = max_control_count(points.len(), degree);
        let mut low = degree + 1;
        let mut best = fit(low)?;
        if best.1 <= tolerance {
            return Ok(ToleranceFit {
                curve: best.0,
                max_deviation: best.1,
                tolerance_met: true,
            });
        }
        // Doubling: `low` misses; find a count that meets the tolerance.
        let mut high = low;
        loop {
            if high == most {
                return Ok(ToleranceFit {
                    curve: best.0,
                    max_deviation: best.1,
                    tolerance_met: false,
                });
            }
            high = (high * 2).min(most);
            let candidate = fit(high)?;
            if candidate.1 <= tolerance {
                best = candidate;
                break;
            }
            low = high;
            best = candidate;
        }
        while high - low > 1 {
            let middle = low + (high - low) / 2;
            let candidate = fit(middle)?;
            if candidate.1 <= tolerance {
                high = middle;
                best = candidate;
            } else {
                low = middle;
            }
        }
        Ok(ToleranceFit {
            curve: best.0,
            max_deviation: best.1,
            tolerance_met: true,
        })
    }
}

impl NurbsCurve<2> {
    /// The least-squares fit of a function's graph (x_k, y_k), x strictly increasing: y is
    /// fitted over the parameter x by [`least_squares`](NurbsCurve::least_squares) (knots by
    /// Eq. 9.68–9.69 over the x_k), and the control abscissae are the Greville points
    /// ξ_j = (u_{j+1} + … + u_{j+p})/p, so that x(t) = t: the rebuilt curve is again a function
    /// over the same x. Fails as [`least_squares`](NurbsCurve::least_squares). O(m p²).
    pub fn least_squares_graph(x: &[f64], y: &[f64], degree: usize, control_count: usize) -> Result<Self> {
        if x.len() != y.len() {
            return Err(Error::LengthMismatch {
                what: "y (one per x)",
                expected: x.len(),
                got: y.len(),
            });
        }
        let values: Vec<Vector<1>> = y.iter().map(|&v| Vector::<1>::new(v)).collect();
        let fit = NurbsCurve::<1>::least_squares(&values, x, degree, control_count)?;
        graph_of(&fit)
    }
}

/// The planar curve (t, f(t)) of a scalar B-spline f: the same knots and ordinates, the
/// Greville control abscissae, so that x(t) = t. Fails only as [`NurbsCurve::non_rational`]
/// (never for a valid f). O(n p).
pub fn graph_of(f: &NurbsCurve<1>) -> Result<NurbsCurve<2>> {
    let p = f.degree();
    let knots = f.knots().to_vec();
    let points = f
        .control_points()
        .iter()
        .enumerate()
        .map(|(j, v)| Vec2::new(greville(&knots, p, j), v[0]))
        .collect();
    NurbsCurve::non_rational(p, knots, points)
}

/// The Greville abscissa (u_{j+1} + … + u_{j+p})/p, summed as differences from u_{j+1} so
/// that p equal knots give that knot exactly.
pub(crate) fn greville(knots: &[f64], degree: usize, j: usize) -> f64 {
    let base = knots[j + 1];
    let sum: f64 = knots[j + 2..j + 1 + degree].iter().map(|&k| k - base).sum();
    base + sum / degree as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn banded_cholesky_solves_a_known_system() {
        // A = [[4, 1, 0], [1, 5, 2], [0, 2, 6]], half-bandwidth 1.
        let mut eq = NormalEquations::<1>::new(3, 1);
        eq.band = vec![vec![4.0, 1.0], vec![5.0, 2.0], vec![6.0, 0.0]];
        let x = [1.0, -2.0, 0.5];
        eq.rhs = vec![
            Vector::<1>::new(4.0 * x[0] + x[1]),
            Vector::<1>::new(x[0] + 5.0 * x[1] + 2.0 * x[2]),
            Vector::<1>::new(2.0 * x[1] + 6.0 * x[2]),
        ];
        let solution = eq.solve().unwrap();
        for (s, e) in solution.iter().zip(x) {
            assert!((s[0] - e).abs() < 1e-14);
        }
        let mut singular = NormalEquations::<1>::new(2, 1);
        singular.band = vec![vec![1.0, 1.0], vec![1.0, 0.0]];
        assert!(matches!(singular.solve(), Err(Error::Singular { .. })));
    }

    #[test]
    fn greville_of_equal_knots_is_the_knot() {
        let knots = [0.1, 0.1, 0.1, 0.1, 0.7, 0.9, 0.9, 0.9, 0.9];
        assert_eq!(greville(&knots, 3, 0), 0.1);
        assert_eq!(greville(&knots, 3, 4), 0.9);
        assert!((greville(&knots, 3, 2) - (0.1 + 0.7 + 0.9) / 3.0).abs() < 1e-16);
    }
}
