//! Exact B-spline conversions (spline function, Hermite spline, Ferguson chain, bicubic
//! surface) and the least-squares rebuild, each against its defining condition: the
//! converted curve equals the original at many parameters to 1e-12 relative to its size, the
//! data points lie on it, and the fit's residual is orthogonal to the basis.

use curve_repr::bspline::{basis_functions, find_span};
use curve_repr::nurbs_curve::fit::{fit_knots, max_control_count, max_deviation};
use curve_repr::{
    BicubicSplineSurface, CubicPieces, Curve, EndCondition, Error, HermiteEnds, HermiteSettings,
    HermiteSpline, Interpolant, JoinRule, NurbsCurve, Parametrization, Side, SplineFunction, Surface, Vec2,
    Vec3, Vector,
};
use proptest::prelude::*;

/// A small deterministic generator (no dependency): xorshift64*.
struct Noise(u64);

impl Noise {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The larger of the bounding-box diagonal and the largest coordinate of some points.
fn size<const D: usize>(points: &[Vector<D>]) -> f64 {
    let mut low = Vector::<D>::from_element(f64::INFINITY);
    let mut high = Vector::<D>::from_element(f64::NEG_INFINITY);
    for p in points {
        low = low.inf(p);
        high = high.sup(p);
    }
    (high - low)
        .norm()
        .max(points.iter().map(|p| p.amax()).fold(0.0, f64::max))
}

/// Both curves agree at 1000 parameters spread over `domain` (and at its ends) to 1e-12 of
/// `scale`, values and first derivatives (the latter to 1e-9 of scale / domain length).
fn assert_same_curve<const D: usize>(
    original: &impl Curve<D>,
    converted: &NurbsCurve<D>,
    domain: (f64, f64),
    scale: f64,
) {
    assert_eq!(converted.domain(), domain);
    let length = domain.1 - domain.0;
    for k in 0..=1000 {
        let t = domain.0 + length * k as f64 / 1000.0;
        let t = if k == 1000 { domain.1 } else { t };
        let a = original.jet(t, Side::Right);
        let b = converted.jet(t, Side::Right);
        assert!(
            (a[0] - b[0]).norm() <= 1e-12 * scale,
            "t = {t}: {:?} vs {:?}",
            a[0],
            b[0]
        );
        assert!(
            (a[1] - b[1]).norm() <= 1e-9 * scale / length,
            "derivative at t = {t}"
        );
    }
}

fn function_case(n: usize, seed: u64, end: EndCondition) -> SplineFunction {
    let mut noise = Noise(seed);
    let mut x = vec![-3.0];
    for _ in 1..n {
        let last = *x.last().unwrap();
        x.push(last + 0.05 + noise.next());
    }
    let y: Vec<f64> = x.iter().map(|&v| (0.7 * v).sin() * 40.0 + noise.next()).collect();
    SplineFunction::new(&x, &y, end).unwrap()
}

#[test]
fn a_spline_function_is_a_c2_bspline_with_x_equal_to_t() {
    let ends = [
        EndCondition::ParabolicRunout,
        EndCondition::Natural,
        EndCondition::Clamped {
            start_slope: 2.0,
            end_slope: -1.0,
        },
    ];
    for (k, end) in ends.into_iter().enumerate() {
        for n in [2, 3, 4, 17, 200] {
            let spline = function_case(n, 7 + k as u64 + n as u64, end);
            let curve = spline.to_bspline().unwrap();
            // C2: one knot per break point, n + 2 control points.
            assert_eq!(curve.control_points().len(), n + 2, "n = {n}");
            assert_eq!(curve.knot_vector().distinct(), spline.x().to_vec());
            let points = spline.points();
            let scale = size(&points);
            assert_same_curve(&spline, &curve, spline.domain(), scale);
            for (p, &x) in points.iter().zip(spline.x()) {
                assert!((curve.point(x) - p).norm() <= 1e-12 * scale);
                // x(t) = t: the parameter is the abscissa.
                assert!((curve.point(x).x - x).abs() <= 1e-14 * scale);
            }
            // The ends are the data's ends exactly.
            assert_eq!(curve.control_points()[0], points[0]);
            assert_eq!(curve.control_points()[n + 1], points[n - 1]);
        }
    }
}

fn hermite_points<const D: usize>(n: usize, seed: u64) -> Vec<Vector<D>> {
    let mut noise = Noise(seed);
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.4;
            Vector::<D>::from_fn(|c, _| match c {
                0 => 10.0 * a.cos() + noise.next(),
                1 => 6.0 * a.sin() + noise.next(),
                _ => a + noise.next(),
            })
        })
        .collect()
}

fn check_hermite<const D: usize>(spline: &HermiteSpline<D>) {
    let curve = spline.to_bspline().unwrap();
    let breaks = spline.knots();
    // A C2 spline needs one knot per break: segments + 3 control points.
    assert_eq!(curve.control_points().len(), breaks.len() + 2);
    let scale = size(spline.points());
    assert_same_curve(spline, &curve, spline.domain(), scale);
    for (p, &t) in spline.points().iter().zip(breaks) {
        assert!((curve.point(t) - p).norm() <= 1e-12 * scale);
    }
    if spline.is_closed() {
        let end = *breaks.last().unwrap();
        assert!((curve.point(end) - spline.points()[0]).norm() <= 1e-12 * scale);
        // The seam is C2 as a curve: the derivatives at both ends agree.
        let (a, b) = (curve.jet(breaks[0], Side::Right), curve.jet(end, Side::Left));
        for order in 1..3 {
            assert!((a[order] - b[order]).norm() <= 1e-8 * a[order].norm().max(1.0));
        }
    }
}

#[test]
fn hermite_splines_of_every_end_and_parametrization_convert_exactly() {
    let ends2 = [
        HermiteEnds::Natural,
        HermiteEnds::ParabolicRunout,
        HermiteEnds::Closed,
        HermiteEnds::Clamped {
            start: Vec2::new(1.0, 2.0),
            end: Vec2::new(-3.0, 0.5),
        },
    ];
    let rules = [
        Parametrization::ChordLength,
        Parametrization::Uniform,
        Parametrization::Centripetal,
    ];
    for (k, ends) in ends2.into_iter().enumerate() {
        for (r, parametrization) in rules.into_iter().enumerate() {
            for n in [3, 5, 40] {
                let settings = HermiteSettings::default()
                    .with_ends(ends)
                    .with_parametrization(parametrization);
                let points = hermite_points::<2>(n, (k * 10 + r + n) as u64 + 1);
                check_hermite(&HermiteSpline::new(&points, &settings).unwrap());
            }
        }
    }
    for ends in [HermiteEnds::Natural, HermiteEnds::Closed] {
        let settings = HermiteSettings::default().with_ends(ends);
        let points = hermite_points::<3>(25, 99);
        check_hermite(&HermiteSpline::new(&points, &settings).unwrap());
    }
    // Two points: a line.
    let line = HermiteSpline::natural(&[Vec2::new(0.0, 0.0), Vec2::new(3.0, 4.0)]).unwrap();
    check_hermite(&line);
}

/// Okada's Ferguson chain is C1 only (the tangent directions are free): double knots, and
/// the B-spline is the chain, segment by segment on its own unit parameter.
#[test]
fn a_c1_ferguson_chain_gets_double_knots() {
    let points = hermite_points::<3>(6, 5);
    let chords: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let mut breaks = vec![0.0];
    for c in &chords {
        breaks.push(breaks.last().unwrap() + c);
    }
    // Unit tangents scaled by the chord (Okada's X_i = C_i T_i), rotated a little so that the
    // curvature jumps at the joints.
    let directions: Vec<Vec3> = (0..points.len())
        .map(|i| {
            let previous = points[i.saturating_sub(1)];
            let next = points[(i + 1).min(points.len() - 1)];
            ((next - previous).normalize() + Vec3::new(0.0, 0.0, 0.1 * i as f64)).normalize()
        })
        .collect();
    let segments: Vec<[Vec3; 4]> = (0..chords.len())
        .map(|i| {
            let (p0, p1) = (points[i], points[i + 1]);
            let (x, y) = (directions[i] * chords[i], directions[i + 1] * chords[i]);
            [p0, x, (p1 - p0) * 3.0 - x * 2.0 - y, (p0 - p1) * 2.0 + x + y]
        })
        .collect();
    let pieces = CubicPieces::from_unit_power(&breaks, &segments).unwrap();
    let curve = pieces.to_bspline(JoinRule::default()).unwrap();
    assert_eq!(curve.control_points().len(), 2 * points.len());
    let scale = size(&points);
    for (i, segment) in segments.iter().enumerate() {
        for k in 0..=50 {
            let s = k as f64 / 50.0;
            let expected = segment[0] + (segment[1] + (segment[2] + segment[3] * s) * s) * s;
            let t = breaks[i] + s * chords[i];
            assert!((curve.point(t) - expected).norm() <= 1e-12 * scale);
        }
    }
    for (p, &t) in points.iter().zip(&breaks) {
        assert!((curve.point(t) - p).norm() <= 1e-12 * scale);
    }
    // Tangent continuity on the global parameter: C1, so the double knots are right.
    for &t in &breaks[1..breaks.len() - 1] {
        let (l, r) = (curve.jet(t, Side::Left), curve.jet(t, Side::Right));
        assert!((l[1] - r[1]).norm() <= 1e-12 * l[1].norm());
        assert!((l[2] - r[2]).norm() > 1e-6 * l[2].norm());
    }
}

fn grid(rows: usize, columns: usize, seed: u64) -> Vec<Vec<Vec3>> {
    let mut noise = Noise(seed);
    let mut u = 0.0;
    (0..rows)
        .map(|_| {
            u += 0.5 + noise.next();
            let mut v = 0.0;
            (0..columns)
                .map(|_| {
                    v += 0.5 + noise.next();
                    Vec3::new(u, v, (0.5 * u).sin() * (0.3 * v).cos() * 3.0 + 0.2 * noise.next())
                })
                .collect()
        })
        .collect()
}

#[test]
fn a_bicubic_spline_surface_is_a_c2_bspline_surface() {
    for (rows, columns) in [(2, 2), (2, 5), (4, 3), (9, 12)] {
        let net = grid(rows, columns, (rows * 31 + columns) as u64);
        let surface = BicubicSplineSurface::new(&net).unwrap();
        let bspline = surface.to_bspline().unwrap();
        assert_eq!(bspline.net_size(), (rows + 2, columns + 2));
        assert_eq!(bspline.knot_vectors().0.distinct(), surface.u_knots().to_vec());
        assert_eq!(bspline.knot_vectors().1.distinct(), surface.v_knots().to_vec());
        let scale = size(surface.points());
        let ((u0, u1), (v0, v1)) = surface.domain();
        assert_eq!(bspline.domain(), surface.domain());
        for a in 0..=40 {
            for b in 0..=40 {
                let u = u0 + (u1 - u0) * a as f64 / 40.0;
                let v = v0 + (v1 - v0) * b as f64 / 40.0;
                let (u, v) = (u.min(u1), v.min(v1));
                assert!((bspline.eval(u, v) - surface.eval(u, v)).norm() <= 1e-12 * scale);
                for (du, dv) in [(1, 0), (0, 1), (1, 1)] {
                    let d = surface.partial(u, v, du, dv).unwrap();
                    let e = bspline.partial(u, v, du, dv).unwrap();
                    assert!((d - e).norm() <= 1e-9 * scale.max(d.norm()));
                }
            }
        }
        for (i, row) in net.iter().enumerate() {
            for (j, p) in row.iter().enumerate() {
                let q = bspline.eval(surface.u_knots()[i], surface.v_knots()[j]);
                assert!((q - p).norm() <= 1e-12 * scale);
            }
        }
    }
}

/// The defining condition of the least-squares fit (Eq. 9.63–9.67): the end points are
/// interpolated and the residual Q_k − C(ū_k) of the other points is orthogonal to every
/// interior basis function, Σ_k N_i(ū_k)(Q_k − C(ū_k)) = 0 for i = 1 … n − 1.
fn check_normal_equations<const D: usize>(points: &[Vector<D>], params: &[f64], degree: usize, count: usize) {
    let curve = NurbsCurve::least_squares(points, params, degree, count).unwrap();
    assert_eq!(curve.control_points().len(), count);
    assert_eq!(curve.degree(), degree);
    let m = points.len() - 1;
    assert_eq!(curve.point(params[0]), points[0]);
    assert!((curve.point(params[m]) - points[m]).norm() <= 1e-15 * size(points));
    let knots = curve.knots();
    let mut products = vec![Vector::<D>::zeros(); count];
    let mut scale = vec![0.0; count];
    for (q, &u) in points.iter().zip(params).take(m).skip(1) {
        let span = find_span(knots, degree, u, Side::Right);
        let basis = basis_functions(knots, degree, span, u);
        let residual = q - curve.point(u);
        for (a, &n) in basis.iter().enumerate() {
            products[span - degree + a] += residual * n;
            scale[span - degree + a] += n * q.norm();
        }
    }
    for i in 1..count - 1 {
        assert!(
            products[i].norm() <= 1e-11 * scale[i].max(1e-300),
            "basis {i}: {:?}",
            products[i]
        );
    }
    // Eq. 9.69 puts at least one parameter in every knot span (Schoenberg–Whitney).
    let distinct = curve.knot_vector().distinct();
    for w in distinct.windows(2) {
        assert!(params.iter().any(|&u| u >= w[0] && u <= w[1]), "span {w:?}");
    }
}

#[test]
fn least_squares_fits_satisfy_the_normal_equations() {
    let points = hermite_points::<2>(120, 3);
    let params = Parametrization::ChordLength.parameters(&points).unwrap();
    for degree in [1, 2, 3, 5] {
        for count in [degree + 1, degree + 2, 10, 37, max_control_count(120, degree)] {
            check_normal_equations(&points, &params, degree, count);
        }
    }
    let points3 = hermite_points::<3>(50, 11);
    let params3 = Parametrization::Centripetal.parameters(&points3).unwrap();
    check_normal_equations(&points3, &params3, 3, 12);
}

/// Eq. 9.69 needs about two points per knot span (d ≥ 2); closer to interpolation its
/// normal equations lose every digit, so the fit refuses.
#[test]
fn a_fit_refuses_fewer_than_two_points_per_span() {
    let points = hermite_points::<2>(30, 8);
    let params = Parametrization::ChordLength.parameters(&points).unwrap();
    assert_eq!(max_control_count(30, 3), 18);
    assert!(NurbsCurve::least_squares(&points, &params, 3, 18).is_ok());
    assert!(matches!(
        NurbsCurve::least_squares(&points, &params, 3, 19),
        Err(Error::TooFewPoints {
            needed: 32,
            got: 30,
            ..
        })
    ));
    assert_eq!(max_control_count(3, 3), 4);
    assert!(matches!(
        NurbsCurve::least_squares(&points[..3], &params[..3], 3, 4),
        Err(Error::TooFewPoints {
            needed: 4,
            got: 3,
            ..
        })
    ));
}

#[test]
fn eq_9_69_knots_as_printed() {
    // m + 1 = 10 parameters 0..9, p = 2, n + 1 = 6: d = 10/4 = 2.5, j = 1..3:
    // jd = 2.5, 5, 7.5 → u = 0.5·ū1 + 0.5·ū2, ū4, 0.5·ū6 + 0.5·ū7.
    let params: Vec<f64> = (0..10).map(|k| k as f64).collect();
    let knots = fit_knots(&params, 2, 6).unwrap();
    assert_eq!(knots.knots(), &[0.0, 0.0, 0.0, 1.5, 4.0, 6.5, 9.0, 9.0, 9.0]);
    assert!(matches!(
        fit_knots(&params, 2, 8),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(matches!(
        fit_knots(&params, 2, 2),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(matches!(fit_knots(&params, 0, 2), Err(Error::BadDegree { .. })));
    assert!(matches!(
        fit_knots(&[0.0, 1.0, 1.0, 2.0], 1, 3),
        Err(Error::NotIncreasing { index: 2, .. })
    ));
}

#[test]
fn a_tolerance_fit_meets_its_tolerance_with_few_control_points() {
    // 2000 points on a smooth curve: a handful of control points suffice for 1e-4.
    let points: Vec<Vec2> = (0..2000)
        .map(|k| {
            let a = k as f64 / 1999.0 * 3.0;
            Vec2::new(10.0 * a.cos(), 4.0 * a.sin() + a)
        })
        .collect();
    let params = Parametrization::ChordLength.parameters(&points).unwrap();
    let fit = NurbsCurve::least_squares_within(&points, &params, 3, 1e-4).unwrap();
    assert!(fit.tolerance_met);
    assert!(fit.max_deviation <= 1e-4);
    assert_eq!(fit.max_deviation, max_deviation(&fit.curve, &points, &params));
    let count = fit.curve.control_points().len();
    assert!(count < 60, "{count} control points");
    // One fewer misses the tolerance (the bisection stops next to a miss).
    let fewer = NurbsCurve::least_squares(&points, &params, 3, count - 1).unwrap();
    assert!(max_deviation(&fewer, &points, &params) > 1e-4);
    // A tolerance out of reach: the fit with the most control points allowed, flagged.
    let few: Vec<Vec2> = points.iter().step_by(100).copied().collect();
    let few_params = Parametrization::ChordLength.parameters(&few).unwrap();
    let best = NurbsCurve::least_squares_within(&few, &few_params, 3, 0.0).unwrap();
    assert!(!best.tolerance_met);
    assert_eq!(best.curve.control_points().len(), max_control_count(few.len(), 3));
    assert!(best.max_deviation > 0.0);
    assert!(matches!(
        NurbsCurve::least_squares_within(&points, &params, 3, -1.0),
        Err(Error::OutOfRange { .. })
    ));
}

#[test]
fn a_graph_fit_stays_a_function_of_x() {
    let x: Vec<f64> = (0..300)
        .map(|k| k as f64 * 0.1 + (k as f64 * 0.37).sin() * 0.03)
        .collect();
    let y: Vec<f64> = x.iter().map(|&v| (0.3 * v).sin() * 5.0).collect();
    let curve = NurbsCurve::least_squares_graph(&x, &y, 3, 15).unwrap();
    for k in 0..=500 {
        let t = x[0] + (x[299] - x[0]) * k as f64 / 500.0;
        let p = curve.point(t);
        assert!((p.x - t).abs() <= 1e-12 * x[299]);
        assert!((curve.jet(t, Side::Right)[1].x - 1.0).abs() <= 1e-12);
    }
    let values: Vec<Vector<1>> = y.iter().map(|&v| Vector::<1>::new(v)).collect();
    let scalar = NurbsCurve::<1>::least_squares(&values, &x, 3, 15).unwrap();
    for &t in &x {
        assert!((curve.point(t).y - scalar.point(t)[0]).abs() <= 1e-12);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Any natural spline through random points converts exactly (2D, chord length).
    #[test]
    fn random_natural_splines_convert_exactly(
        raw in prop::collection::vec((-100.0..100.0f64, -100.0..100.0f64), 2..40)
    ) {
        let points: Vec<Vec2> = raw.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
        prop_assume!(points.windows(2).all(|w| (w[1] - w[0]).norm() > 1e-3));
        let spline = HermiteSpline::natural(&points).unwrap();
        let curve = spline.to_bspline().unwrap();
        let scale = size(&points);
        let (a, b) = spline.domain();
        for k in 0..=200 {
            let t = (a + (b - a) * k as f64 / 200.0).min(b);
            prop_assert!((curve.point(t) - spline.eval(t)).norm() <= 1e-12 * scale);
        }
        for (p, &t) in points.iter().zip(spline.parameters()) {
            prop_assert!((curve.point(t) - p).norm() <= 1e-12 * scale);
        }
    }
}
