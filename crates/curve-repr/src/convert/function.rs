//! [`SplineFunction`] → planar B-spline with x(t) = t.

use super::{CubicPieces, JoinRule};
use crate::nurbs_curve::fit::greville;
use crate::{NurbsCurve, Result, SplineFunction, Vec2};

impl SplineFunction {
    /// The graph (x, y(x)) as Bézier pieces over the break points x_i. On [x_i, x_{i+1}] with
    /// h = x_{i+1} − x_i, m = (y_{i+1} − y_i)/h and the end slopes of Han's Eq. 3,
    /// y'(x_i+) = m − h(2c_i + c_{i+1}) and y'(x_{i+1}−) = m + h(c_i + 2c_{i+1}), the Bézier
    /// ordinates are y_i, y_i + h y'(x_i+)/3, y_{i+1} − h y'(x_{i+1}−)/3, y_{i+1}, and the
    /// abscissae x_i, x_i + h/3, x_{i+1} − h/3, x_{i+1}. O(n).
    pub fn cubic_pieces(&self) -> Result<CubicPieces<2>> {
        let (x, y, c) = (self.x(), self.y(), self.c());
        let bezier = (0..x.len().saturating_sub(1))
            .map(|i| {
                let h = x[i + 1] - x[i];
                let m = (y[i + 1] - y[i]) / h;
                let start_slope = m - h * (2.0 * c[i] + c[i + 1]);
                let end_slope = m + h * (c[i] + 2.0 * c[i + 1]);
                let third = h / 3.0;
                [
                    Vec2::new(x[i], y[i]),
                    Vec2::new(x[i] + third, y[i] + third * start_slope),
                    Vec2::new(x[i + 1] - third, y[i + 1] - third * end_slope),
                    Vec2::new(x[i + 1], y[i + 1]),
                ]
            })
            .collect();
        CubicPieces::new(x.to_vec(), bezier)
    }

    /// The spline function as a planar cubic B-spline (x(t), y(t)) with x(t) = t: knots at
    /// the x_i (single, since the spline is C2; each join checked as
    /// [`CubicPieces::to_bspline`] does with [`JoinRule::default`]), the control ordinates the
    /// blossoms of y, the control abscissae the Greville points
    /// ξ_j = (u_{j+1} + u_{j+2} + u_{j+3})/3 (the blossom of t itself), so that x(t) = t
    /// exactly in exact arithmetic and the curve's parameter is the abscissa. n + 2 control
    /// points for n points. O(n).
    pub fn to_bspline(&self) -> Result<NurbsCurve<2>> {
        let curve = self.cubic_pieces()?.to_bspline(JoinRule::default())?;
        let knots = curve.knots().to_vec();
        let points = curve
            .control_points()
            .iter()
            .enumerate()
            .map(|(j, p)| Vec2::new(greville(&knots, 3, j), p.y))
            .collect();
        NurbsCurve::non_rational(3, knots, points)
    }
}
