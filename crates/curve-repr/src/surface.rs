//! The [`Surface`] trait.

use crate::{Side, Vec3};

/// The highest partial derivative order, in each of u and v, that a [`Surface`] reports.
pub const MAX_PARTIAL_ORDER: usize = 3;

/// A parametric surface S(u, v) in 3D.
pub trait Surface {
    /// The parameter rectangle `((u_start, u_end), (v_start, v_end))`.
    fn domain(&self) -> ((f64, f64), (f64, f64));

    /// The partial derivative ∂^(du+dv) S / ∂u^du ∂v^dv at (u, v), with one-sided limits at
    /// knot lines taken from `side_u` and `side_v`.
    ///
    /// Returns `None` when `du` or `dv` exceeds [`MAX_PARTIAL_ORDER`].
    fn partial_from(&self, u: f64, v: f64, du: usize, dv: usize, side_u: Side, side_v: Side) -> Option<Vec3>;

    /// The partial derivative ∂^(du+dv) S / ∂u^du ∂v^dv at (u, v), from the right at knot lines.
    fn partial(&self, u: f64, v: f64, du: usize, dv: usize) -> Option<Vec3> {
        self.partial_from(u, v, du, dv, Side::Right, Side::Right)
    }

    /// The point S(u, v).
    fn eval(&self, u: f64, v: f64) -> Vec3 {
        self.partial(u, v, 0, 0).unwrap_or_else(Vec3::zeros)
    }

    /// The unit normal S_u × S_v / |S_u × S_v|, or `None` where the surface is degenerate.
    fn normal(&self, u: f64, v: f64) -> Option<Vec3> {
        let su = self.partial(u, v, 1, 0)?;
        let sv = self.partial(u, v, 0, 1)?;
        let n = su.cross(&sv);
        let len = n.norm();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }
}
