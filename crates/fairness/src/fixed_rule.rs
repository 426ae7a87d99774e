//! Ek and E2 of a rational B-spline with a FIXED Gauss–Legendre rule per knot span, written
//! once over the scalar `T: num_traits::Float`, so that a dual number differentiates them
//! exactly with respect to the weights (or points) of the curve.
//!
//! The adaptive criteria ([`Ek`](crate::Ek), [`E2`](crate::E2)) refine where the integrand
//! needs it: the number and place of their nodes depend on the weights, so the value is only
//! piecewise smooth in the weights and a derivative of it means nothing. Here every nonempty
//! knot span [u_i, u_{i+1}] gets the same m-point Gauss–Legendre rule, the nodes depend only
//! on the knots, and the value is a smooth function of the weights and control points:
//!
//! - [`ek`]: Ek = ∫ κ² ds = ∫ |C′ × C″|² / |C′|⁵ dt (Nowacki et al. 1996, §2, the curvature
//!   criterion; |C′ × C″|² by the Lagrange identity |C′|²|C″|² − (C′·C″)² above 3D);
//! - [`e2`]: E2 = ∫ |C″|² dt (§2, the second-order parametric criterion).
//!
//! The size of the rule: a NURBS span's integrands are rational, not polynomial, so no finite
//! rule is exact. [`FixedRule::default`] takes [`FixedRule::DEFAULT_POINTS`] = 20 points per
//! span, the size at which the f64 value agrees with the adaptive criterion to its relative
//! tolerance 1e-10 on a ship waterline (Gunnerus wl_03) and an airfoil (NACA 2412 upper) with
//! unit and with strongly varying weights (the tests of `fair-optim` check it). Measured
//! relative errors of Ek with varying weights: 3e-8 (waterline) and 1e-8 (airfoil) at 12
//! points, 6e-10 and 9e-11 at 16, 1.5e-12 and 3e-13 at 20; E2 converges faster. Cost: spans · m evaluations of
//! [`RationalCurve::derivatives`] (order 2): O(spans · m · p²) operations on `T`.

use curve_repr::nurbs_curve::generic::lift;
use curve_repr::nurbs_curve::RationalCurve;
use curve_repr::Side;
use num_traits::Float;

use crate::quadrature::GaussLegendre;
use crate::Result;

/// An m-point Gauss–Legendre rule applied on every nonempty knot span.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedRule {
    rule: GaussLegendre,
}

impl FixedRule {
    /// Points per span of [`FixedRule::default`] (see the module docs for why 20).
    pub const DEFAULT_POINTS: usize = 20;

    /// `points` per span (1 ≤ points ≤ 64, else [`Error::InvalidSetting`](crate::Error)).
    pub fn new(points: usize) -> Result<Self> {
        Ok(FixedRule {
            rule: GaussLegendre::new(points)?,
        })
    }

    /// Points per span.
    pub fn points(&self) -> usize {
        self.rule.points()
    }

    /// Σ over spans and nodes of weight · f(C′(t), C″(t)) · half-length.
    fn integrate<T: Float, const D: usize>(
        &self,
        curve: &RationalCurve<T, D>,
        f: impl Fn(&[T; D], &[T; D]) -> T,
    ) -> T {
        let knots = curve.knot_vector().distinct();
        let mut total = T::zero();
        for span in knots.windows(2) {
            let (a, b) = (span[0], span[1]);
            let half = 0.5 * (b - a);
            let mid = 0.5 * (a + b);
            let mut sum = T::zero();
            for (x, w) in self.rule.nodes().iter().zip(self.rule.weights()) {
                let d = curve.derivatives(mid + half * x, 2, Side::Right);
                sum = sum + f(&d[1], &d[2]) * lift(*w);
            }
            total = total + sum * lift(half);
        }
        total
    }
}

impl Default for FixedRule {
    fn default() -> Self {
        FixedRule::new(Self::DEFAULT_POINTS).unwrap_or_else(|_| unreachable!("20 points is a valid rule"))
    }
}

fn dot<T: Float, const D: usize>(a: &[T; D], b: &[T; D]) -> T {
    a.iter().zip(b).fold(T::zero(), |acc, (x, y)| acc + *x * *y)
}

/// |a × b|²: the 2D cross product squared, the 3D one's squared norm, the Lagrange identity
/// |a|²|b|² − (a·b)² otherwise.
fn cross_squared<T: Float, const D: usize>(a: &[T; D], b: &[T; D]) -> T {
    match D {
        2 => {
            let c = a[0] * b[1] - a[1] * b[0];
            c * c
        }
        3 => {
            let x = a[1] * b[2] - a[2] * b[1];
            let y = a[2] * b[0] - a[0] * b[2];
            let z = a[0] * b[1] - a[1] * b[0];
            x * x + y * y + z * z
        }
        _ => {
            let ab = dot(a, b);
            dot(a, a) * dot(b, b) - ab * ab
        }
    }
}

/// Ek = ∫ κ² ds = ∫ |C′ × C″|² / |C′|⁵ dt with `rule` on every knot span (module docs).
/// A point where C′ = 0 gives a non-finite value. O(spans · m · p²).
pub fn ek<T: Float, const D: usize>(curve: &RationalCurve<T, D>, rule: &FixedRule) -> T {
    rule.integrate(curve, |d1, d2| {
        let speed_squared = dot(d1, d1);
        cross_squared(d1, d2) / (speed_squared * speed_squared * speed_squared.sqrt())
    })
}

/// E2 = ∫ |C″|² dt with `rule` on every knot span (module docs). O(spans · m · p²).
pub fn e2<T: Float, const D: usize>(curve: &RationalCurve<T, D>, rule: &FixedRule) -> T {
    rule.integrate(curve, |_, d2| dot(d2, d2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{NurbsCurve, Vec2, Vec3};

    /// The quarter circle as a rational quadratic: κ = 1/r, so Ek = (1/r²)(π r / 2).
    #[test]
    fn quarter_circle_has_the_exact_curvature_energy() {
        let r = 2.5;
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let circle = NurbsCurve::<2>::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![Vec2::new(r, 0.0), Vec2::new(r, r), Vec2::new(0.0, r)],
            vec![1.0, s, 1.0],
        )
        .unwrap();
        let value = ek(&circle.to_generic::<f64>(), &FixedRule::default());
        let exact = std::f64::consts::FRAC_PI_2 / r;
        assert!((value - exact).abs() < 1e-12 * exact, "{value} vs {exact}");
        // the same circle lifted into the plane z = 1 in 3D
        let spatial = NurbsCurve::<3>::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Vec3::new(r, 0.0, 1.0),
                Vec3::new(r, r, 1.0),
                Vec3::new(0.0, r, 1.0),
            ],
            vec![1.0, s, 1.0],
        )
        .unwrap();
        let value = ek(&spatial.to_generic::<f64>(), &FixedRule::default());
        assert!((value - exact).abs() < 1e-12 * exact);
    }

    /// A cubic polynomial piece: |C″|² has degree 2, so 2 points are already exact.
    #[test]
    fn e2_of_a_polynomial_is_exact() {
        // C(t) = (t, t³) on [0, 1] as a Bézier cubic: C″ = (0, 6t), E2 = ∫ 36 t² = 12.
        let curve = NurbsCurve::<2>::non_rational(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![
                Vec2::new(0.0, 0.0),
                Vec2::new(1.0 / 3.0, 0.0),
                Vec2::new(2.0 / 3.0, 0.0),
                Vec2::new(1.0, 1.0),
            ],
        )
        .unwrap();
        for points in [2, 5, 12] {
            let value = e2(&curve.to_generic::<f64>(), &FixedRule::new(points).unwrap());
            assert!((value - 12.0).abs() < 1e-12, "{points}: {value}");
        }
        assert!(FixedRule::new(0).is_err());
    }
}
