//! [`HermiteSpline`] → B-spline.

use super::{CubicPieces, JoinRule};
use crate::{HermiteSpline, NurbsCurve, Result};

impl<const D: usize> HermiteSpline<D> {
    /// The spline as Bézier pieces (Zhang–Cheng Eq. 1: P_i, P_i + h_i M_i/3,
    /// P_{i+1} − h_i M_{i+1}/3, P_{i+1}), see [`CubicPieces::from_hermite`]. A closed spline
    /// has n + 1 pieces through its n + 1 points. O(n).
    pub fn cubic_pieces(&self) -> Result<CubicPieces<D>> {
        CubicPieces::from_hermite(self.knots(), self.points(), self.tangents())
    }

    /// The spline as a cubic B-spline over its own parameter: single knots at the t_i where
    /// the pieces join C2 (all of them, since the tangents solve Eq. 2; each join checked by
    /// [`CubicPieces::to_bspline`] with [`JoinRule::default`]), so n + 3 control points for
    /// n + 1 points. A closed spline becomes a clamped curve on [t_0, t_{n+1}] that starts and
    /// ends at P_0 (C2 across that seam as a curve, though a clamped knot vector does not
    /// show it). O(n).
    pub fn to_bspline(&self) -> Result<NurbsCurve<D>> {
        self.cubic_pieces()?.to_bspline(JoinRule::default())
    }
}
