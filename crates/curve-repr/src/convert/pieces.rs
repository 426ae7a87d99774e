//! Piecewise cubics in Bézier form, and their exact B-spline form by blossoming.

use crate::vector::check_finite_values;
use crate::{Error, NurbsCurve, Result, Vector};

/// The default relative tolerance of the continuity checks of [`CubicPieces::to_bspline`]:
/// two pieces join C^r when the control points that C^r makes common differ by at most this
/// times the curve's size (see [`CubicPieces::size`]).
///
/// The C2 splines of this crate join C2 to rounding (about 1e-16 relative), far inside it; a
/// C1 Hermite chain misses C2 by a curvature jump, typically 1e-3 of the size or more.
pub const C2_TOLERANCE: f64 = 1e-12;

/// Which knot multiplicity each interior break point gets in [`CubicPieces::to_bspline`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JoinRule {
    /// Double knots at every break where the pieces join C1 (triple where only C0): every
    /// control point is a Bézier point of the pieces, the textbook conversion of a cubic
    /// Hermite spline.
    Double,
    /// A single knot where the pieces join C2, double where C1, triple where C0, each join
    /// checked with the relative `tolerance` (see [`C2_TOLERANCE`]): the fewest control
    /// points that represent the curve.
    Detect {
        /// Relative tolerance of the checks, finite and ≥ 0.
        tolerance: f64,
    },
}

impl Default for JoinRule {
    /// `Detect` with [`C2_TOLERANCE`].
    fn default() -> Self {
        JoinRule::Detect {
            tolerance: C2_TOLERANCE,
        }
    }
}

/// A piecewise cubic curve in Bézier form: break points t_0 < … < t_n and, for each piece
/// i on [t_i, t_{i+1}], its Bézier points b_0 … b_3, so that with s = (t − t_i)/(t_{i+1} − t_i)
/// the piece is Σ_k C(3, k) s^k (1 − s)^{3−k} b_k.
///
/// Every cubic representation of the crate converts into this form exactly (to one rounding
/// per Bézier point), and [`to_bspline`](Self::to_bspline) turns it into a B-spline without
/// approximation. Memory O(n).
#[derive(Clone, Debug, PartialEq)]
pub struct CubicPieces<const D: usize> {
    breaks: Vec<f64>,
    bezier: Vec<[Vector<D>; 4]>,
}

/// a (1 − s) + b s: exactly a at s = 0 and exactly b at s = 1.
fn lerp<const D: usize>(a: &Vector<D>, b: &Vector<D>, s: f64) -> Vector<D> {
    a * (1.0 - s) + b * s
}

/// The blossom (polar form) f(x_1, x_2, x_3) of the cubic with Bézier points `b` on
/// [start, end]: de Casteljau's algorithm with parameter s_k = (x_k − start)/(end − start) at
/// level k. Symmetric in its arguments, affine in each, and f(t, t, t) is the point at t;
/// f(start, start, start) = b_0, f(start, start, end) = b_1, … exactly. O(D).
pub(crate) fn blossom<const D: usize>(b: &[Vector<D>; 4], start: f64, end: f64, args: [f64; 3]) -> Vector<D> {
    let h = end - start;
    let s = args.map(|x| (x - start) / h);
    let level1 = [
        lerp(&b[0], &b[1], s[0]),
        lerp(&b[1], &b[2], s[0]),
        lerp(&b[2], &b[3], s[0]),
    ];
    let level2 = [
        lerp(&level1[0], &level1[1], s[1]),
        lerp(&level1[1], &level1[2], s[1]),
    ];
    lerp(&level2[0], &level2[1], s[2])
}

/// How far the blossom arguments lie outside [start, end], in units of its length: 0 when
/// all lie inside. The piece with the smallest value gives the best-conditioned control point.
pub(crate) fn extrapolation(start: f64, end: f64, args: [f64; 3]) -> f64 {
    let h = end - start;
    args.iter()
        .map(|&x| (start - x).max(x - end).max(0.0) / h)
        .fold(0.0, f64::max)
}

/// Checks that break points (or knots of a grid) are finite and strictly increasing.
pub(crate) fn check_breaks(what: &'static str, breaks: &[f64]) -> Result<()> {
    check_finite_values(what, breaks)?;
    match breaks.windows(2).position(|w| w[1] <= w[0]) {
        Some(index) => Err(Error::NotIncreasing {
            what,
            index: index + 1,
            previous: breaks[index],
            value: breaks[index + 1],
        }),
        None => Ok(()),
    }
}

/// The order r ∈ {0, 1, 2} of the join at b of the cubic `left` on [a, b] and `right` on
/// [b, c] (`breaks` = [a, b, c]), each condition to `allowed` (absolute): C0 when
/// f(b, b, b) = g(b, b, b), C1 when also f(x, b, b) = g(x, b, b) for x = a and c, C2 when also
/// f(a, b, c) = g(a, b, c). `Err(gap)` when the pieces do not meet. O(D).
pub(crate) fn join_order<const D: usize>(
    left: &[Vector<D>; 4],
    right: &[Vector<D>; 4],
    breaks: [f64; 3],
    allowed: f64,
) -> std::result::Result<usize, f64> {
    let [a, b, c] = breaks;
    let gap = |args: [f64; 3]| (blossom(left, a, b, args) - blossom(right, b, c, args)).norm();
    let c0 = gap([b, b, b]);
    if c0.is_nan() || c0 > allowed {
        return Err(c0);
    }
    if gap([a, b, b]).max(gap([b, b, c])) > allowed {
        return Ok(0);
    }
    if gap([a, b, c]) > allowed {
        return Ok(1);
    }
    Ok(2)
}

/// The clamped cubic knot vector of `breaks` with interior break i + 1 repeated
/// 3 − `continuity[i]` times, and for every knot the index of its break. O(n).
pub(crate) fn clamped_knots(breaks: &[f64], continuity: &[usize]) -> (Vec<f64>, Vec<usize>) {
    let n = breaks.len() - 1;
    let mut knots = vec![breaks[0]; 4];
    let mut knot_break = vec![0usize; 4];
    for (i, &order) in continuity.iter().enumerate() {
        for _ in 0..3usize.saturating_sub(order) {
            knots.push(breaks[i + 1]);
            knot_break.push(i + 1);
        }
    }
    knots.extend([breaks[n]; 4]);
    knot_break.extend([n; 4]);
    (knots, knot_break)
}

/// The piece whose blossom gives control point j: among the pieces inside its support
/// [u_j, u_{j+4}], the one whose interval the arguments leave least. O(1).
pub(crate) fn best_piece(breaks: &[f64], knot_break: &[usize], j: usize, args: [f64; 3]) -> usize {
    let n = breaks.len() - 1;
    let first = knot_break[j].min(n - 1);
    let last = knot_break[j + 4].clamp(first + 1, n);
    (first..last)
        .min_by(|&p, &q| {
            let e = |k: usize| extrapolation(breaks[k], breaks[k + 1], args);
            e(p).total_cmp(&e(q))
        })
        .unwrap_or(first)
}

impl<const D: usize> CubicPieces<D> {
    /// Pieces from break points t_0 < … < t_n and n arrays of Bézier points.
    ///
    /// Fails with [`Error::TooFewPoints`] without a piece, [`Error::LengthMismatch`] unless
    /// there is one more break than pieces, [`Error::NonFinite`] on a non-finite break or
    /// Bézier point (index 4·piece + k) and [`Error::NotIncreasing`] when the breaks do not
    /// increase strictly. O(n).
    pub fn new(breaks: Vec<f64>, bezier: Vec<[Vector<D>; 4]>) -> Result<Self> {
        if bezier.is_empty() {
            return Err(Error::TooFewPoints {
                what: "a piecewise cubic (pieces)",
                needed: 1,
                got: 0,
            });
        }
        if breaks.len() != bezier.len() + 1 {
            return Err(Error::LengthMismatch {
                what: "break points (one more than the pieces)",
                expected: bezier.len() + 1,
                got: breaks.len(),
            });
        }
        check_breaks("break points", &breaks)?;
        let flat: Vec<Vector<D>> = bezier.iter().flatten().copied().collect();
        if let Some(index) = flat.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::NonFinite {
                what: "Bézier point",
                index,
            });
        }
        Ok(Self { breaks, bezier })
    }

    /// The cubic Hermite interpolant of points P_i with derivatives M_i = C'(t_i) at the
    /// breaks t_i (Zhang–Cheng Eq. 1, Okada's Ferguson segments on a global parameter): piece
    /// i has the Bézier points P_i, P_i + h_i M_i/3, P_{i+1} − h_i M_{i+1}/3, P_{i+1}, with
    /// h_i = t_{i+1} − t_i.
    ///
    /// An open curve has one point per break; a closed one (n pieces through n points) one
    /// fewer, its last piece ending at P_0 with M_0. The result joins C1 at every break by
    /// construction, C2 where the M_i solve the C2 conditions. Fails as [`new`](Self::new)
    /// and with [`Error::LengthMismatch`] on other counts. O(n).
    pub fn from_hermite(breaks: &[f64], points: &[Vector<D>], tangents: &[Vector<D>]) -> Result<Self> {
        let pieces = breaks.len().saturating_sub(1);
        if points.len() != breaks.len() && points.len() != pieces {
            return Err(Error::LengthMismatch {
                what: "points (one per break, or one fewer for a closed curve)",
                expected: breaks.len(),
                got: points.len(),
            });
        }
        if tangents.len() != points.len() {
            return Err(Error::LengthMismatch {
                what: "tangents (one per point)",
                expected: points.len(),
                got: tangents.len(),
            });
        }
        if pieces == 0 {
            return Err(Error::TooFewPoints {
                what: "a cubic Hermite curve",
                needed: 2,
                got: points.len(),
            });
        }
        check_breaks("break points", breaks)?;
        let bezier = (0..pieces)
            .map(|i| {
                let next = if i + 1 == points.len() { 0 } else { i + 1 };
                let third = (breaks[i + 1] - breaks[i]) / 3.0;
                let (p0, p1) = (points[i], points[next]);
                [p0, p0 + tangents[i] * third, p1 - tangents[next] * third, p1]
            })
            .collect();
        Self::new(breaks.to_vec(), bezier)
    }

    /// Pieces given in power form on their own unit parameter: segment i is
    /// R_0 + R_1 s + R_2 s² + R_3 s³, s ∈ [0, 1], placed on [t_i, t_{i+1}] (Okada's Ferguson
    /// coefficients with the chord-length breaks). Bézier points b_0 = R_0,
    /// b_1 = R_0 + R_1/3, b_2 = R_0 + (2R_1 + R_2)/3, b_3 = R_0 + R_1 + R_2 + R_3. Fails as
    /// [`new`](Self::new). O(n).
    pub fn from_unit_power(breaks: &[f64], segments: &[[Vector<D>; 4]]) -> Result<Self> {
        let bezier = segments
            .iter()
            .map(|[r0, r1, r2, r3]| [*r0, r0 + r1 / 3.0, r0 + (r1 * 2.0 + r2) / 3.0, r0 + r1 + r2 + r3])
            .collect();
        Self::new(breaks.to_vec(), bezier)
    }

    /// The break points t_0 < … < t_n.
    pub fn breaks(&self) -> &[f64] {
        &self.breaks
    }

    /// The Bézier points of each piece.
    pub fn bezier(&self) -> &[[Vector<D>; 4]] {
        &self.bezier
    }

    /// The number of pieces n.
    pub fn piece_count(&self) -> usize {
        self.bezier.len()
    }

    /// The piece used at `t`: the one with t_i ≤ t < t_{i+1}, the last at t_n, the end
    /// pieces outside the domain.
    fn piece_at(&self, t: f64) -> usize {
        self.breaks
            .partition_point(|&b| b <= t)
            .saturating_sub(1)
            .min(self.bezier.len() - 1)
    }

    /// The point at `t` by de Casteljau's algorithm on its piece. O(log n).
    pub fn point(&self, t: f64) -> Vector<D> {
        let i = self.piece_at(t);
        self.blossom(i, [t, t, t])
    }

    /// The blossom of piece `piece` at three parameters (see the module documentation).
    /// Callers keep `piece < piece_count()`.
    pub fn blossom(&self, piece: usize, args: [f64; 3]) -> Vector<D> {
        blossom(
            &self.bezier[piece],
            self.breaks[piece],
            self.breaks[piece + 1],
            args,
        )
    }

    /// The scale of the continuity checks: the larger of the diagonal of the Bézier points'
    /// bounding box and their largest coordinate magnitude (rounding grows with both). O(n).
    pub fn size(&self) -> f64 {
        let mut low = Vector::<D>::from_element(f64::INFINITY);
        let mut high = Vector::<D>::from_element(f64::NEG_INFINITY);
        let mut largest = 0.0_f64;
        for p in self.bezier.iter().flatten() {
            low = low.inf(p);
            high = high.sup(p);
            largest = largest.max(p.amax());
        }
        (high - low).norm().max(largest)
    }

    /// The continuity r ∈ {0, 1, 2} with which pieces `index − 1` and `index` join at the
    /// interior break t_index (1 ≤ index < n), each condition checked to
    /// `tolerance` · [`size`](Self::size).
    ///
    /// With f and g the two pieces and a < b < c the breaks around the join: C0 when
    /// f(b, b, b) = g(b, b, b); C1 when also f(x, b, b) = g(x, b, b) for x = a and x = c; C2
    /// when also f(a, b, c) = g(a, b, c). (Two cubics that agree to order r at b differ by a
    /// multiple of (t − b)^{r+1}, whose blossom vanishes when b is among 3 − r arguments; each
    /// difference is the displacement of a control point, so the tolerance is geometric.)
    /// Fails with [`Error::Discontinuous`] when the pieces do not meet, and
    /// [`Error::IndexOutOfRange`] for a break that is not interior. O(n) for the size.
    pub fn join_continuity(&self, index: usize, tolerance: f64) -> Result<usize> {
        self.join_within(index, tolerance * self.size())
    }

    /// [`join_continuity`](Self::join_continuity) with an absolute tolerance. O(D).
    fn join_within(&self, index: usize, allowed: f64) -> Result<usize> {
        if index == 0 || index >= self.bezier.len() {
            return Err(Error::IndexOutOfRange {
                what: "interior break points",
                index,
                len: self.breaks.len(),
            });
        }
        join_order(
            &self.bezier[index - 1],
            &self.bezier[index],
            [self.breaks[index - 1], self.breaks[index], self.breaks[index + 1]],
            allowed,
        )
        .map_err(|gap| Error::Discontinuous { index, gap })
    }

    /// The same curve as a cubic B-spline (unit weights): the breaks become knots (the ends
    /// clamped, repeated 4 times), interior ones repeated as `rule` says, and control point j
    /// is the blossom f(u_{j+1}, u_{j+2}, u_{j+3}) of a piece in its support, the one whose
    /// interval the three knots leave least (de Boor's dual functionals; exact in exact
    /// arithmetic whenever the joins have the continuity their multiplicity promises, which
    /// [`join_continuity`](Self::join_continuity) checks). The scale of the checks is computed
    /// once, so the whole conversion is O(n).
    ///
    /// The B-spline has n + 3 control points when every join is C2, 2n + 2 with double
    /// knots. Its end control points are b_0 of the first and b_3 of the last piece exactly.
    /// Fails with [`Error::OutOfRange`] on a negative or non-finite tolerance and
    /// [`Error::Discontinuous`] when pieces do not meet. O(n).
    pub fn to_bspline(&self, rule: JoinRule) -> Result<NurbsCurve<D>> {
        let tolerance = match rule {
            JoinRule::Double => C2_TOLERANCE,
            JoinRule::Detect { tolerance } => tolerance,
        };
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(Error::OutOfRange {
                what: "continuity tolerance",
                value: tolerance,
                reason: "must be finite and at least 0",
            });
        }
        let n = self.bezier.len();
        let allowed = tolerance * self.size();
        let continuity = (1..n)
            .map(|i| {
                let order = self.join_within(i, allowed)?;
                Ok(if rule == JoinRule::Double {
                    order.min(1)
                } else {
                    order
                })
            })
            .collect::<Result<Vec<usize>>>()?;
        let (knots, knot_break) = clamped_knots(&self.breaks, &continuity);
        let points = (0..knots.len() - 4)
            .map(|j| {
                let args = [knots[j + 1], knots[j + 2], knots[j + 3]];
                self.blossom(best_piece(&self.breaks, &knot_break, j, args), args)
            })
            .collect();
        NurbsCurve::non_rational(3, knots, points)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Curve, Vec2};

    /// A cubic with Bézier points b on [1, 3], written in power form to check the blossom.
    #[test]
    fn blossom_is_symmetric_multi_affine_and_the_point_on_its_diagonal() {
        let b = [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 3.0),
            Vec2::new(2.5, -1.0),
            Vec2::new(4.0, 0.5),
        ];
        let (start, end) = (1.0, 3.0);
        let bernstein = |t: f64| {
            let s = (t - start) / (end - start);
            b[0] * (1.0 - s).powi(3)
                + b[1] * (3.0 * s * (1.0 - s).powi(2))
                + b[2] * (3.0 * s * s * (1.0 - s))
                + b[3] * s.powi(3)
        };
        for t in [0.5, 1.0, 1.7, 3.0, 3.6] {
            assert!((blossom(&b, start, end, [t, t, t]) - bernstein(t)).norm() < 1e-13);
        }
        let f = |x: [f64; 3]| blossom(&b, start, end, x);
        let (x, y, z) = (0.3, 2.2, 3.9);
        assert!((f([x, y, z]) - f([z, x, y])).norm() < 1e-13);
        assert!((f([y, z, x]) - f([x, z, y])).norm() < 1e-13);
        // affine in the first argument
        let mid = f([0.5 * (x + 1.4), y, z]);
        assert!((mid - (f([x, y, z]) + f([1.4, y, z])) * 0.5).norm() < 1e-13);
        // the Bézier points are blossoms at the interval's ends, exactly
        assert_eq!(f([start, start, start]), b[0]);
        assert_eq!(f([start, start, end]), b[1]);
        assert_eq!(f([start, end, end]), b[2]);
        assert_eq!(f([end, end, end]), b[3]);
    }

    fn pieces_of(points: &[Vec2], tangents: &[Vec2], breaks: &[f64]) -> CubicPieces<2> {
        CubicPieces::from_hermite(breaks, points, tangents).unwrap()
    }

    /// A C1 Hermite chain (tangents chosen freely) becomes a double-knot B-spline whose
    /// control points are the Bézier points, and equals the chain everywhere.
    #[test]
    fn a_c1_chain_gets_double_knots_and_is_reproduced() {
        let points = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 2.0),
            Vec2::new(3.0, 1.5),
            Vec2::new(4.0, -1.0),
        ];
        let tangents = [
            Vec2::new(1.0, 1.0),
            Vec2::new(2.0, 0.3),
            Vec2::new(0.5, -1.0),
            Vec2::new(1.0, -2.0),
        ];
        let breaks = [0.0, 1.5, 2.0, 4.0];
        let pieces = pieces_of(&points, &tangents, &breaks);
        for i in 1..3 {
            assert_eq!(pieces.join_continuity(i, C2_TOLERANCE).unwrap(), 1);
        }
        let curve = pieces.to_bspline(JoinRule::default()).unwrap();
        assert_eq!(
            curve.knots(),
            &[0.0, 0.0, 0.0, 0.0, 1.5, 1.5, 2.0, 2.0, 4.0, 4.0, 4.0, 4.0]
        );
        let expected: Vec<Vec2> = pieces
            .bezier()
            .iter()
            .enumerate()
            .flat_map(|(i, b)| if i == 0 { b[..3].to_vec() } else { b[1..3].to_vec() })
            .chain([points[3]])
            .collect();
        assert_eq!(curve.control_points(), &expected[..]);
        for k in 0..=400 {
            let t = 4.0 * k as f64 / 400.0;
            assert!((curve.point(t) - pieces.point(t)).norm() < 1e-13, "t {t}");
        }
        for (p, t) in points.iter().zip(breaks) {
            assert!((curve.point(t) - p).norm() < 1e-14);
        }
    }

    /// Cubic polynomials joined as one cubic are C∞: single knots, and the B-spline is that
    /// cubic (the control points are its blossoms, wherever the knots are).
    #[test]
    fn one_polynomial_cut_into_pieces_gets_single_knots() {
        let f = |t: f64| Vec2::new(1.0 + t - 0.5 * t * t + 0.1 * t * t * t, 2.0 - t * t * t * 0.2);
        let df = |t: f64| Vec2::new(1.0 - t + 0.3 * t * t, -0.6 * t * t);
        let breaks = [-1.0, 0.25, 0.5, 2.0, 2.1, 3.0];
        let points: Vec<Vec2> = breaks.iter().map(|&t| f(t)).collect();
        let tangents: Vec<Vec2> = breaks.iter().map(|&t| df(t)).collect();
        let pieces = pieces_of(&points, &tangents, &breaks);
        let curve = pieces.to_bspline(JoinRule::default()).unwrap();
        assert_eq!(curve.control_points().len(), breaks.len() + 2);
        assert_eq!(curve.knot_vector().distinct(), breaks.to_vec());
        for k in 0..=300 {
            let t = -1.0 + 4.0 * k as f64 / 300.0;
            assert!((curve.point(t) - f(t)).norm() < 1e-13, "t {t}");
            let d = curve.jet(t, crate::Side::Right);
            assert!((d[1] - df(t)).norm() < 1e-12);
        }
        let double = pieces.to_bspline(JoinRule::Double).unwrap();
        assert_eq!(double.control_points().len(), 2 * breaks.len());
        for k in 0..=300 {
            let t = -1.0 + 4.0 * k as f64 / 300.0;
            assert!((double.point(t) - f(t)).norm() < 1e-13);
        }
    }

    #[test]
    fn pieces_that_do_not_meet_are_refused_and_corners_get_triple_knots() {
        let a = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(3.0, 0.0),
        ];
        let corner = [
            Vec2::new(3.0, 0.0),
            Vec2::new(3.0, 1.0),
            Vec2::new(3.0, 2.0),
            Vec2::new(3.0, 3.0),
        ];
        let pieces = CubicPieces::new(vec![0.0, 1.0, 2.0], vec![a, corner]).unwrap();
        assert_eq!(pieces.join_continuity(1, C2_TOLERANCE), Ok(0));
        let curve = pieces.to_bspline(JoinRule::default()).unwrap();
        assert_eq!(curve.knots()[4..7], [1.0, 1.0, 1.0]);
        assert_eq!(curve.point(1.0), Vec2::new(3.0, 0.0));
        let mut gap = corner;
        gap[0] = Vec2::new(3.0, 0.5);
        let pieces = CubicPieces::new(vec![0.0, 1.0, 2.0], vec![a, gap]).unwrap();
        assert!(matches!(
            pieces.to_bspline(JoinRule::default()),
            Err(Error::Discontinuous { index: 1, .. })
        ));
        assert!(matches!(
            pieces.to_bspline(JoinRule::Detect { tolerance: f64::NAN }),
            Err(Error::OutOfRange { .. })
        ));
    }

    #[test]
    fn bad_input_is_an_error() {
        let p = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)];
        assert!(matches!(
            CubicPieces::from_hermite(&[0.0, 1.0, 2.0, 3.0], &p, &p),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            CubicPieces::from_hermite(&[0.0, 0.0], &p, &p),
            Err(Error::NotIncreasing { index: 1, .. })
        ));
        assert!(matches!(
            CubicPieces::from_hermite(&[0.0, 1.0], &p, &p[..1]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            CubicPieces::<2>::new(vec![0.0], vec![]),
            Err(Error::TooFewPoints { .. })
        ));
        let nan = [Vec2::new(0.0, f64::NAN), Vec2::new(1.0, 0.0)];
        assert!(matches!(
            CubicPieces::from_hermite(&[0.0, 1.0], &nan, &p),
            Err(Error::NonFinite { index: 0, .. })
        ));
    }
}
