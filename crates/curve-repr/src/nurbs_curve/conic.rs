//! Exact circular arcs as rational quadratic NURBS (The NURBS Book A7.1).

use std::f64::consts::{FRAC_PI_2, PI};

use super::NurbsCurve;
use crate::{Error, Result, Vec2, Vec3, Vector};

/// Relative tolerance for the sweep and the orthonormality of the plane axes.
const TOLERANCE: f64 = 1e-12;

/// The arc of The NURBS Book A7.1 in the plane through `center` spanned by the orthonormal
/// `x_axis`, `y_axis`: C(θ) = O + r cos θ X + r sin θ Y for θ from `start` to `end`.
///
/// The sweep is split into ⌈sweep / 90°⌉ ≤ 4 equal pieces of angle Δθ; each is a rational
/// quadratic Bézier arc with end weights 1 and middle weight cos(Δθ/2), its middle control
/// point at O + (r / cos(Δθ/2)) (cos θ_m X + sin θ_m Y) (the intersection of the end
/// tangents, θ_m the mid angle). The pieces join at double knots i/narcs. O(1).
fn arc<const D: usize>(
    center: Vector<D>,
    x_axis: Vector<D>,
    y_axis: Vector<D>,
    radius: f64,
    start: f64,
    end: f64,
) -> Result<NurbsCurve<D>> {
    crate::vector::check_finite(&[center, x_axis, y_axis])?;
    crate::vector::check_finite_values("arc parameter", &[radius, start, end])?;
    if radius <= 0.0 {
        return Err(Error::OutOfRange {
            what: "arc radius",
            value: radius,
            reason: "must be positive",
        });
    }
    let sweep = end - start;
    if sweep <= 0.0 || sweep > 2.0 * PI * (1.0 + TOLERANCE) {
        return Err(Error::OutOfRange {
            what: "arc sweep end - start",
            value: sweep,
            reason: "must lie in (0, 2 pi]",
        });
    }
    let sweep = sweep.min(2.0 * PI);
    let narcs = ((sweep / FRAC_PI_2) * (1.0 - TOLERANCE)).ceil().clamp(1.0, 4.0) as usize;
    let delta = sweep / narcs as f64;
    let middle_weight = (delta / 2.0).cos();
    let at =
        |angle: f64, scale: f64| center + (x_axis * angle.cos() + y_axis * angle.sin()) * (radius * scale);
    let mut points = Vec::with_capacity(2 * narcs + 1);
    let mut weights = Vec::with_capacity(2 * narcs + 1);
    points.push(at(start, 1.0));
    weights.push(1.0);
    for i in 0..narcs {
        let a0 = start + delta * i as f64;
        points.push(at(a0 + delta / 2.0, 1.0 / middle_weight));
        weights.push(middle_weight);
        let a1 = if i + 1 == narcs { end } else { a0 + delta };
        points.push(at(a1, 1.0));
        weights.push(1.0);
    }
    let mut knots = vec![0.0; 3];
    for i in 1..narcs {
        let k = i as f64 / narcs as f64;
        knots.push(k);
        knots.push(k);
    }
    knots.extend([1.0; 3]);
    NurbsCurve::new(2, knots, points, weights)
}

impl NurbsCurve<2> {
    /// The exact circular arc of `radius` about `center` from angle `start` to `end` (radians,
    /// counter-clockwise, 0 < end − start ≤ 2π), as a rational quadratic NURBS with up to
    /// four pieces (The NURBS Book A7.1) on the parameter domain [0, 1].
    ///
    /// Fails with [`Error::NonFinite`], [`Error::OutOfRange`] for an empty, reversed or
    /// over-full sweep or a radius that is not positive.
    pub fn circular_arc(center: Vec2, radius: f64, start: f64, end: f64) -> Result<Self> {
        arc(center, Vec2::x(), Vec2::y(), radius, start, end)
    }
}

impl NurbsCurve<3> {
    /// The exact circular arc in the plane through `center` spanned by `x_axis` and `y_axis`
    /// (orthogonal, any non-zero lengths: they are normalised), from angle `start` to `end`
    /// measured from `x_axis` towards `y_axis`. Otherwise as [`NurbsCurve::circular_arc`].
    ///
    /// Fails also with [`Error::Singular`] when the axes are zero or not orthogonal.
    pub fn circular_arc_3d(
        center: Vec3,
        x_axis: Vec3,
        y_axis: Vec3,
        radius: f64,
        start: f64,
        end: f64,
    ) -> Result<Self> {
        let (lx, ly) = (x_axis.norm(), y_axis.norm());
        let singular = Error::Singular {
            what: "building an arc: plane axes must be non-zero and orthogonal",
        };
        if !(lx.is_finite() && ly.is_finite() && lx > 0.0 && ly > 0.0) {
            return Err(singular);
        }
        let (x, y) = (x_axis / lx, y_axis / ly);
        if x.dot(&y).abs() > 1e-9 {
            return Err(singular);
        }
        arc(center, x, y, radius, start, end)
    }
}
