//! Parametric C2 cubic spline curves in Hermite form, in 2D and 3D.
//!
//! The curve of Zhang, Zhang & Cheng, *Fairing spline curves and surfaces by minimizing
//! energy* (CAD 33, 2001) §2, which is also Okada's (1969) chain of Ferguson segments: data
//! points P_i at knots t_i, tangents M_i = C'(t_i), and on [t_i, t_{i+1}] the cubic Hermite
//! interpolant of Eq. (1). The tangents come from C2 continuity, the tridiagonal Eq. (2),
//! closed by an end condition ([`HermiteEnds`]) and solved in O(n). Eq. (2) is also the
//! stationarity ∂E/∂M_i = 0 (Eq. 4) of the strain energy E = ∫|C''|² dt (Eq. 3), which
//! [`HermiteSpline::strain_energy`] gives in closed form; the fairing indicator of Eq. (17)
//! is built on [`HermiteSpline::third_derivative_jumps`].
//!
//! Moving data points ([`Interpolant::move_points`]) keeps the knots and updates the tangents
//! only in a window around the moves, whose size does not depend on n (see
//! [`HermiteSpline::rebuild`] for the full recomputation).

mod ends;
mod energy;
mod settings;
mod solve;
mod update;

pub use ends::HermiteEnds;
pub use settings::HermiteSettings;

use crate::curve::{Curve, Interpolant, Side};
use crate::{Error, Result, Vector};

/// A parametric C2 cubic spline in Hermite form through data points P_0..P_n.
///
/// Segment i, on [t_i, t_{i+1}] with h_i = t_{i+1} − t_i and s = (t − t_i)/h_i, is
/// (Zhang–Cheng Eq. 1)
///
/// C_i(t) = φ_0(s) P_i + φ_1(s) h_i M_i + ψ_1(s) h_i M_{i+1} + ψ_0(s) P_{i+1},
///
/// φ_0 = (s−1)²(2s+1), φ_1 = (s−1)² s, ψ_0 = s²(3−2s), ψ_1 = s²(s−1). A closed curve has one
/// more segment, P_n → P_0, on [t_n, t_{n+1}].
///
/// Evaluation costs O(log n) (a binary search for the segment); construction O(n).
#[derive(Debug, PartialEq)]
pub struct HermiteSpline<const D: usize> {
    points: Vec<Vector<D>>,
    /// The knots: one per point, plus the closing one for a closed curve.
    knots: Vec<f64>,
    tangents: Vec<Vector<D>>,
    ends: HermiteEnds<D>,
    /// Storage of the windowed updates, reused from one move to the next.
    workspace: update::Workspace<D>,
}

impl<const D: usize> Clone for HermiteSpline<D> {
    fn clone(&self) -> Self {
        Self {
            points: self.points.clone(),
            knots: self.knots.clone(),
            tangents: self.tangents.clone(),
            ends: self.ends,
            workspace: update::Workspace::default(),
        }
    }

    /// Reuses this spline's storage (and keeps its workspace): a reset to a saved spline
    /// allocates nothing when the sizes agree.
    fn clone_from(&mut self, source: &Self) {
        self.points.clone_from(&source.points);
        self.knots.clone_from(&source.knots);
        self.tangents.clone_from(&source.tangents);
        self.ends = source.ends;
        // The knots may differ: the decay bounds of the windowed update are measured again,
        // and the rows of the system built again.
        self.workspace.decays.clear();
        self.workspace.weights.clear();
        self.workspace.rows.clear();
    }
}

impl<const D: usize> HermiteSpline<D> {
    /// Builds the spline through `points` as `settings` say. O(n).
    ///
    /// Fails with [`Error::TooFewPoints`] below [`HermiteEnds::min_points`],
    /// [`Error::NonFinite`] on a non-finite point, parameter or clamped tangent,
    /// [`Error::RepeatedPoint`] on consecutive equal points with computed parameters (also
    /// P_n = P_0 for a closed curve), [`Error::LengthMismatch`] on explicit parameters of the
    /// wrong count and [`Error::NotIncreasing`] on parameters that do not increase strictly.
    pub fn new(points: &[Vector<D>], settings: &HermiteSettings<D>) -> Result<Self> {
        let ends = settings.ends;
        crate::vector::check_finite(points)?;
        if points.len() < ends.min_points() {
            return Err(Error::TooFewPoints {
                what: ends.name(),
                needed: ends.min_points(),
                got: points.len(),
            });
        }
        if let HermiteEnds::Clamped { start, end } = ends {
            for (index, tangent) in [start, end].iter().enumerate() {
                if tangent.iter().any(|c| !c.is_finite()) {
                    return Err(Error::NonFinite {
                        what: "clamped end tangent",
                        index,
                    });
                }
            }
        }
        let knots = match &settings.parameters {
            Some(t) => {
                let expected = points.len() + usize::from(ends.is_closed());
                if t.len() != expected {
                    return Err(Error::LengthMismatch {
                        what: "parameters",
                        expected,
                        got: t.len(),
                    });
                }
                t.clone()
            }
            None if ends.is_closed() => settings.parametrization.closed_parameters(points)?,
            None => settings.parametrization.parameters(points)?,
        };
        check_knots(&knots)?;
        let mut spline = HermiteSpline {
            points: points.to_vec(),
            knots,
            tangents: Vec::new(),
            ends,
            workspace: update::Workspace::default(),
        };
        spline.tangents = solve::tangents(&spline)?;
        Ok(spline)
    }

    /// The spline [`new`](Self::new) builds through `points` (as many as this spline's) with
    /// this spline's knots and ends, in this spline's storage: the same tangents bit for bit
    /// (the same rows and elimination), without allocating once the storage has grown, so
    /// that many lines over one knot vector (a surface's network) are solved one after
    /// another. O(n).
    ///
    /// Errors: those of `new` on the points (a non-finite point; a singular system or an
    /// overflowing tangent), and [`Error::LengthMismatch`] for another number of points. On
    /// an error the spline's points and tangents are unspecified.
    pub fn refit(&mut self, points: &[Vector<D>]) -> Result<()> {
        crate::vector::check_finite(points)?;
        if points.len() != self.points.len() {
            return Err(Error::LengthMismatch {
                what: "points",
                expected: self.points.len(),
                got: points.len(),
            });
        }
        self.points.copy_from_slice(points);
        self.workspace.rows.clear();
        if self.is_closed() {
            self.tangents = solve::tangents(self)?;
            Ok(())
        } else {
            solve::open_tangents_in_place(self)
        }
    }

    /// The natural spline over chord-length parameters (Zhang–Cheng §2; the `fair` report's
    /// parametric curve). O(n).
    pub fn natural(points: &[Vector<D>]) -> Result<Self> {
        Self::new(points, &HermiteSettings::default())
    }

    /// The data points P_0..P_n.
    pub fn points(&self) -> &[Vector<D>] {
        &self.points
    }

    /// The data parameters t_0..t_n, one per point.
    pub fn parameters(&self) -> &[f64] {
        let count = self.points.len().min(self.knots.len());
        self.knots.get(..count).unwrap_or(&[])
    }

    /// All knots: the data parameters and, for a closed curve, the closing t_{n+1} at which
    /// the curve returns to P_0.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The tangents M_i = C'(t_i), one per point.
    pub fn tangents(&self) -> &[Vector<D>] {
        &self.tangents
    }

    /// The end condition.
    pub fn ends(&self) -> &HermiteEnds<D> {
        &self.ends
    }

    /// Whether the curve is closed.
    pub fn is_closed(&self) -> bool {
        self.ends.is_closed()
    }

    /// Number of cubic segments: n for an open curve through n + 1 points, n + 1 closed.
    pub fn segment_count(&self) -> usize {
        self.knots.len().saturating_sub(1)
    }

    /// Recomputes every tangent from the points (the full O(n) solve of Eq. 2), e.g. to
    /// check or refresh the windowed updates of [`Interpolant::move_points`].
    pub fn rebuild(&mut self) -> Result<()> {
        self.tangents = solve::tangents(self)?;
        Ok(())
    }

    /// [`Interpolant::move_points`], also telling which tangents it re-solved: `Some((first,
    /// last))`, the rows first..=last (for a closed curve they may wrap past the last point,
    /// then first > last; every row after a full solve), `None` for no moves. Tangents
    /// outside those rows are unchanged bit for bit, so a caller that keeps values derived
    /// from the tangents (jumps, segment energies) needs to refresh them only there and
    /// next to the moved points, which lie inside.
    pub fn move_points_within(&mut self, moves: &[(usize, Vector<D>)]) -> Result<Option<(usize, usize)>> {
        update::move_points(self, moves)
    }

    /// The tangents that [`move_points_within`](Self::move_points_within) would give for a
    /// move of point `index` to `position`, without making it: `(first, tangents)`, the
    /// new tangents of the rows first, first + 1, … (wrapping round a closed curve) that
    /// the move re-solves, bit for bit those of the move; every other tangent would keep
    /// its value. The spline is left as it was (its storage for windowed solves holds the
    /// result). For measuring a line's response to unit moves without moving it back.
    /// O(window), O(n) when a closed curve's window covers it. Fails as
    /// `move_points_within` does on a bad index or position, or a failed solve.
    pub fn tangents_after_move(
        &mut self,
        index: usize,
        position: Vector<D>,
    ) -> Result<(usize, &[Vector<D>])> {
        let (first, rows) = update::tangents_after_move(self, index, position)?;
        Ok((first, &self.workspace.values[..rows]))
    }
}

impl HermiteSpline<1> {
    /// [`tangents_after_move`](Self::tangents_after_move) of point `index` to 1, for a
    /// scalar spline whose points are all 0: the response of the tangents to a unit move
    /// (the tangents are linear in the points), bit for bit what the move would give. On a
    /// natural open spline the window's rows are built from the knots directly (a unit
    /// move's right-hand side is 0 but at three rows), some five times cheaper than the
    /// general rows; other ends take the general path. The points must be 0 (else the
    /// result is not the move's). O(window).
    pub fn unit_move_tangents(&mut self, index: usize) -> Result<(usize, &[Vector<1>])> {
        let (first, rows) = update::unit_move_tangents(self, index)?;
        Ok((first, &self.workspace.values[..rows]))
    }
}

impl<const D: usize> HermiteSpline<D> {
    /// The index of the point at the end of segment `segment`.
    fn next(&self, segment: usize) -> usize {
        if segment + 1 >= self.points.len() {
            0
        } else {
            segment + 1
        }
    }

    /// h_i = t_{i+1} − t_i.
    fn step(&self, segment: usize) -> f64 {
        self.knots[segment + 1] - self.knots[segment]
    }

    /// Power-form coefficients of segment i around t_i, C = P + u M + u² c2 + u³ c3 with
    /// u = t − t_i: Eq. (1) expanded,
    /// c2 = (3d − 2M_i − M_{i+1})/h, c3 = (M_i + M_{i+1} − 2d)/h², d = (P_{i+1} − P_i)/h.
    fn coefficients(&self, segment: usize) -> [Vector<D>; 4] {
        let h = self.step(segment);
        let end = self.next(segment);
        let (p0, p1) = (self.points[segment], self.points[end]);
        let (m0, m1) = (self.tangents[segment], self.tangents[end]);
        let slope = (p1 - p0) / h;
        let c2 = (slope * 3.0 - m0 * 2.0 - m1) / h;
        let c3 = (m0 + m1 - slope * 2.0) / (h * h);
        [p0, m0, c2, c3]
    }

    /// The segment used at `t` from `side` (end segments extend beyond the domain).
    fn segment_at(&self, t: f64, side: Side) -> usize {
        let count = match side {
            Side::Left => self.knots.partition_point(|&k| k < t),
            Side::Right => self.knots.partition_point(|&k| k <= t),
        };
        count
            .saturating_sub(1)
            .min(self.segment_count().saturating_sub(1))
    }
}

/// Checks that knots are finite and strictly increasing.
fn check_knots(knots: &[f64]) -> Result<()> {
    crate::vector::check_finite_values("parameter", knots)?;
    for (i, w) in knots.windows(2).enumerate() {
        if w[1] <= w[0] {
            return Err(Error::NotIncreasing {
                what: "parameters",
                index: i + 1,
                previous: w[0],
                value: w[1],
            });
        }
    }
    Ok(())
}

impl<const D: usize> Curve<D> for HermiteSpline<D> {
    fn domain(&self) -> (f64, f64) {
        let start = self.knots.first().copied().unwrap_or(0.0);
        (start, self.knots.last().copied().unwrap_or(start))
    }

    /// One-sided limits at knots: `Side::Left` uses the segment ending at t, `Side::Right`
    /// the one starting there. A closed curve is not wrapped: outside its domain, and at
    /// t_0 and t_{n+1}, its first and last segments are used like those of an open one.
    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        self.jet_on_piece(self.segment_at(t, side), t)
    }

    fn jet_on_piece(&self, segment: usize, t: f64) -> [Vector<D>; 4] {
        let segment = segment.min(self.segment_count().saturating_sub(1));
        let [p, m, c2, c3] = self.coefficients(segment);
        let u = t - self.knots[segment];
        [
            p + (m + (c2 + c3 * u) * u) * u,
            m + (c2 * 2.0 + c3 * (3.0 * u)) * u,
            c2 * 2.0 + c3 * (6.0 * u),
            c3 * 6.0,
        ]
    }

    fn breaks(&self) -> Vec<f64> {
        self.knots.clone()
    }
}

impl<const D: usize> Interpolant<D> for HermiteSpline<D> {
    fn point_count(&self) -> usize {
        self.points.len()
    }

    /// Data point `index`; NaN coordinates for an index out of range (a broken contract).
    fn point(&self, index: usize) -> Vector<D> {
        self.points
            .get(index)
            .copied()
            .unwrap_or_else(|| Vector::from_element(f64::NAN))
    }

    /// The parameter of point `index`; NaN for an index out of range (a broken contract).
    fn parameter(&self, index: usize) -> f64 {
        self.parameters().get(index).copied().unwrap_or(f64::NAN)
    }

    fn points(&self) -> Vec<Vector<D>> {
        self.points.clone()
    }

    fn parameters(&self) -> Vec<f64> {
        HermiteSpline::parameters(self).to_vec()
    }

    /// Moves points and updates the tangents in a window around each move (see
    /// [`HermiteSpline::rebuild`] and the `update` module): O(moves · window) rather than O(n).
    fn move_points(&mut self, moves: &[(usize, Vector<D>)]) -> Result<()> {
        update::move_points(self, moves).map(|_| ())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Parametrization, Vec2, Vec3};

    fn sample() -> Vec<Vec2> {
        vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.5),
            Vec2::new(2.5, 0.2),
            Vec2::new(3.0, 1.5),
            Vec2::new(4.2, 1.0),
        ]
    }

    /// Eq. (1) with the Hermite basis written out, against the power form used by `jet`.
    #[test]
    fn power_form_is_the_hermite_basis_of_eq_1() {
        let spline = HermiteSpline::natural(&sample()).unwrap();
        for i in 0..spline.segment_count() {
            let h = spline.step(i);
            let (p0, p1) = (spline.points[i], spline.points[i + 1]);
            let (m0, m1) = (spline.tangents[i], spline.tangents[i + 1]);
            for s in [0.0, 0.2, 0.5, 0.9, 1.0] {
                let phi0 = (s - 1.0) * (s - 1.0) * (2.0 * s + 1.0);
                let phi1 = (s - 1.0) * (s - 1.0) * s;
                let psi0 = s * s * (3.0 - 2.0 * s);
                let psi1 = s * s * (s - 1.0);
                let expected = p0 * phi0 + m0 * (h * phi1) + m1 * (h * psi1) + p1 * psi0;
                let got = spline.jet(spline.knots[i] + s * h, Side::Left)[0];
                assert!((got - expected).norm() < 1e-12, "segment {i}, s {s}");
            }
        }
    }

    /// Eq. (2) as printed (a_i, 2, b_i and c_i P_i on the right) holds at interior knots.
    #[test]
    fn tangents_satisfy_eq_2_as_printed() {
        let spline = HermiteSpline::natural(&sample()).unwrap();
        let (p, m) = (&spline.points, &spline.tangents);
        for i in 1..p.len() - 1 {
            let (h0, h1) = (spline.step(i - 1), spline.step(i));
            let a = h1 / (h0 + h1);
            let b = h0 / (h0 + h1);
            let c = 3.0 * (a / h0 - b / h1);
            let lhs = m[i - 1] * a + m[i] * 2.0 + m[i + 1] * b;
            let rhs = p[i - 1] * (-3.0 * a / h0) + p[i] * c + p[i + 1] * (3.0 * b / h1);
            assert!((lhs - rhs).norm() < 1e-12);
        }
    }

    #[test]
    fn one_sided_limits_pick_the_segment_ending_or_starting_at_a_knot() {
        let spline = HermiteSpline::natural(&sample()).unwrap();
        let t = spline.knots[2];
        assert_eq!(spline.segment_at(t, Side::Left), 1);
        assert_eq!(spline.segment_at(t, Side::Right), 2);
        assert_eq!(spline.segment_at(spline.knots[0], Side::Left), 0);
        assert_eq!(spline.segment_at(spline.knots[4], Side::Right), 3);
        assert_eq!(spline.segment_at(1e9, Side::Right), 3);
        assert_eq!(spline.segment_at(-1e9, Side::Left), 0);
    }

    #[test]
    fn bad_input_is_an_error() {
        let two = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)];
        assert!(HermiteSpline::natural(&two).is_ok());
        assert!(matches!(
            HermiteSpline::natural(&two[..1]),
            Err(Error::TooFewPoints {
                needed: 2,
                got: 1,
                ..
            })
        ));
        for ends in [HermiteEnds::ParabolicRunout, HermiteEnds::Closed] {
            let settings = HermiteSettings::default().with_ends(ends);
            assert!(matches!(
                HermiteSpline::new(&two, &settings),
                Err(Error::TooFewPoints {
                    needed: 3,
                    got: 2,
                    ..
                })
            ));
        }
        let repeated = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        ];
        assert_eq!(
            HermiteSpline::natural(&repeated),
            Err(Error::RepeatedPoint { index: 1 })
        );
        let settings = HermiteSettings::default().with_parametrization(Parametrization::Centripetal);
        assert_eq!(
            HermiteSpline::new(&repeated, &settings),
            Err(Error::RepeatedPoint { index: 1 })
        );
        // Explicit parameters allow a repeated point: the spline is well defined.
        let settings = HermiteSettings::default().with_parameters(vec![0.0, 1.0, 2.0]);
        assert!(HermiteSpline::new(&repeated, &settings).is_ok());
        let settings = HermiteSettings::default().with_parameters(vec![0.0, 1.0, 1.0]);
        assert!(matches!(
            HermiteSpline::new(&repeated, &settings),
            Err(Error::NotIncreasing { index: 2, .. })
        ));
        let settings = HermiteSettings::default().with_parameters(vec![0.0, f64::NAN, 1.0]);
        assert!(matches!(
            HermiteSpline::new(&repeated, &settings),
            Err(Error::NonFinite { index: 1, .. })
        ));
        let settings = HermiteSettings::default().with_parameters(vec![0.0, 1.0]);
        assert!(matches!(
            HermiteSpline::new(&repeated, &settings),
            Err(Error::LengthMismatch {
                expected: 3,
                got: 2,
                ..
            })
        ));
        let closed = HermiteSettings::default()
            .with_ends(HermiteEnds::Closed)
            .with_parameters(vec![0.0, 1.0, 2.0]);
        assert!(matches!(
            HermiteSpline::new(&repeated, &closed),
            Err(Error::LengthMismatch {
                expected: 4,
                got: 3,
                ..
            })
        ));
        let nan = [Vec2::new(0.0, 0.0), Vec2::new(f64::NAN, 1.0)];
        assert!(matches!(
            HermiteSpline::natural(&nan),
            Err(Error::NonFinite { index: 1, .. })
        ));
        let clamped =
            HermiteSettings::default().with_clamped_ends(Vec2::zeros(), Vec2::new(f64::INFINITY, 0.0));
        assert!(matches!(
            HermiteSpline::new(&two, &clamped),
            Err(Error::NonFinite { index: 1, .. })
        ));
        // A closed curve whose last point repeats the first has a zero closing chord.
        let loop_points = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 0.0),
        ];
        let settings = HermiteSettings::default().with_ends(HermiteEnds::Closed);
        assert!(matches!(
            HermiteSpline::new(&loop_points, &settings),
            Err(Error::ClosingRepeat { last: 3 })
        ));
        // Huge coordinates overflow the chord lengths: an error, not a NaN curve.
        let huge = [
            Vec2::new(-1e308, 0.0),
            Vec2::new(1e308, 0.0),
            Vec2::new(1e308, 1e308),
        ];
        assert!(HermiteSpline::natural(&huge).is_err());
    }
}
