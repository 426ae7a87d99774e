//! NURBS curves and surfaces against geomdl (cross-checked with OpenCASCADE), finite
//! differences, interpolation conditions and exact conics.

use curve_repr::{
    Curve, Error, Interpolant, Interpolation, InterpolationSettings, NurbsCurve, NurbsInterpolant,
    NurbsSurface, Parametrization, Side, Surface, Vec2, Vec3, Vector,
};
use proptest::prelude::*;
use serde_json::Value;

fn load(name: &str) -> Value {
    let path = format!("{}/../../data/reference/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn vectors<const D: usize>(v: &Value) -> Vec<Vector<D>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| Vector::<D>::from_iterator(floats(p)))
        .collect()
}

/// |a − b| ≤ tol · max(1, |b|), per vector.
fn close<const D: usize>(a: &Vector<D>, b: &Vector<D>, tol: f64) -> bool {
    (a - b).norm() <= tol * b.norm().max(1.0)
}

fn check_curve<const D: usize>(case: &Value) {
    let curve = NurbsCurve::<D>::new(
        case["degree"].as_u64().unwrap() as usize,
        floats(&case["knots"]),
        vectors::<D>(&case["control_points"]),
        floats(&case["weights"]),
    )
    .unwrap();
    let params = floats(&case["params"]);
    let (points, d1, d2) = (
        vectors::<D>(&case["points"]),
        vectors::<D>(&case["d1"]),
        vectors::<D>(&case["d2"]),
    );
    for (k, &u) in params.iter().enumerate() {
        for side in [Side::Left, Side::Right] {
            let jet = curve.jet(u, side);
            assert!(
                close(&jet[0], &points[k], 1e-9),
                "point at {u}: {:?} vs {:?}",
                jet[0],
                points[k]
            );
            assert!(
                close(&jet[1], &d1[k], 1e-9),
                "d1 at {u}: {:?} vs {:?}",
                jet[1],
                d1[k]
            );
            assert!(
                close(&jet[2], &d2[k], 1e-9),
                "d2 at {u}: {:?} vs {:?}",
                jet[2],
                d2[k]
            );
        }
    }
}

#[test]
fn curves_agree_with_geomdl() {
    let data = load("nurbs_geomdl.json");
    for case in data["curves"].as_array().unwrap() {
        match case["name"].as_str().unwrap() {
            "2d" => check_curve::<2>(case),
            "3d" => check_curve::<3>(case),
            other => panic!("unexpected case {other}"),
        }
    }
}

fn reference_surface(data: &Value) -> NurbsSurface {
    let s = &data["surface"];
    let net: Vec<Vec<Vec3>> = s["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(vectors::<3>)
        .collect();
    let weights: Vec<Vec<f64>> = s["weights"].as_array().unwrap().iter().map(floats).collect();
    NurbsSurface::new(
        s["degree_u"].as_u64().unwrap() as usize,
        s["degree_v"].as_u64().unwrap() as usize,
        floats(&s["knots_u"]),
        floats(&s["knots_v"]),
        net,
        weights,
    )
    .unwrap()
}

#[test]
fn surface_agrees_with_geomdl() {
    let data = load("nurbs_geomdl.json");
    let surface = reference_surface(&data);
    let s = &data["surface"];
    let uv = s["uv"].as_array().unwrap();
    for (field, du, dv) in [
        ("points", 0, 0),
        ("Su", 1, 0),
        ("Sv", 0, 1),
        ("Suu", 2, 0),
        ("Suv", 1, 1),
        ("Svv", 0, 2),
    ] {
        let expected = vectors::<3>(&s[field]);
        for (k, point) in uv.iter().enumerate() {
            let p = floats(point);
            let got = surface.partial(p[0], p[1], du, dv).unwrap();
            assert!(
                close(&got, &expected[k], 1e-9),
                "{field} at {p:?}: {got:?} vs {:?}",
                expected[k]
            );
        }
    }
}

/// Third derivatives (and every lower order) against central differences of the order below,
/// inside spans, for both reference curves and the surface: there is no oracle for order 3.
#[test]
fn third_derivatives_match_differences_of_second() {
    let data = load("nurbs_geomdl.json");
    let case = &data["curves"][1];
    let curve = NurbsCurve::<3>::new(
        3,
        floats(&case["knots"]),
        vectors::<3>(&case["control_points"]),
        floats(&case["weights"]),
    )
    .unwrap();
    let h = 1e-6;
    for i in 1..40 {
        let u = i as f64 / 40.0 + 0.003;
        let jet = curve.jet(u, Side::Right);
        let (plus, minus) = (curve.jet(u + h, Side::Right), curve.jet(u - h, Side::Right));
        for order in 0..3 {
            let fd = (plus[order] - minus[order]) / (2.0 * h);
            assert!(
                (fd - jet[order + 1]).norm() < 1e-5 * jet[order + 1].norm().max(1.0),
                "order {} at {u}",
                order + 1
            );
        }
        let d = curve.derivatives(u, 4, Side::Right);
        let fd4 = (curve.derivatives(u + h, 3, Side::Right)[3] - curve.derivatives(u - h, 3, Side::Right)[3])
            / (2.0 * h);
        assert!((fd4 - d[4]).norm() < 1e-5 * d[4].norm().max(1.0));
    }
    let surface = reference_surface(&data);
    for &(u, v) in &[(0.13, 0.27), (0.52, 0.61), (0.87, 0.09)] {
        for du in 0..3 {
            for dv in 0..3 {
                let up = surface.partial(u + h, v, du, dv).unwrap();
                let um = surface.partial(u - h, v, du, dv).unwrap();
                let exact = surface.partial(u, v, du + 1, dv).unwrap();
                assert!(
                    ((up - um) / (2.0 * h) - exact).norm() < 1e-5 * exact.norm().max(1.0),
                    "u {du} {dv}"
                );
                let vp = surface.partial(u, v + h, du, dv).unwrap();
                let vm = surface.partial(u, v - h, du, dv).unwrap();
                let exact = surface.partial(u, v, du, dv + 1).unwrap();
                assert!(
                    ((vp - vm) / (2.0 * h) - exact).norm() < 1e-5 * exact.norm().max(1.0),
                    "v {du} {dv}"
                );
            }
        }
    }
    assert!(surface.partial(0.5, 0.5, 4, 0).is_none());
}

/// At an interior simple knot of a cubic the third derivative jumps; each side must equal the
/// limit of its own span (one-sided differences), and the two sides must differ.
#[test]
fn one_sided_third_derivatives_at_knots() {
    let data = load("nurbs_geomdl.json");
    let case = &data["curves"][0];
    let curve = NurbsCurve::<2>::new(
        3,
        floats(&case["knots"]),
        vectors::<2>(&case["control_points"]),
        floats(&case["weights"]),
    )
    .unwrap();
    let breaks = curve.breaks();
    assert_eq!(breaks.first(), Some(&0.0));
    assert_eq!(breaks.last(), Some(&1.0));
    let h = 1e-7;
    for &knot in &breaks[1..breaks.len() - 1] {
        let left = curve.jet(knot, Side::Left);
        let right = curve.jet(knot, Side::Right);
        let from_left = curve.jet(knot - h, Side::Right)[3];
        let from_right = curve.jet(knot + h, Side::Right)[3];
        assert!((left[3] - from_left).norm() < 1e-4 * left[3].norm().max(1.0));
        assert!((right[3] - from_right).norm() < 1e-4 * right[3].norm().max(1.0));
        assert!((left[3] - right[3]).norm() > 1e-6 * left[3].norm());
        for order in 0..3 {
            assert!((left[order] - right[order]).norm() < 1e-9 * left[order].norm().max(1.0));
        }
    }
}

fn check_interpolation<const D: usize>(case: &Value) {
    let points = vectors::<D>(&case["points"]);
    let parametrization = match case["parametrization"].as_str().unwrap() {
        "chord_length" => Parametrization::ChordLength,
        "centripetal" => Parametrization::Centripetal,
        other => panic!("unknown parametrization {other}"),
    };
    let problem =
        Interpolation::with_parametrization(&points, parametrization, InterpolationSettings::default())
            .unwrap();
    for (a, b) in problem.params().iter().zip(floats(&case["params"])) {
        assert!((a - b).abs() <= 1e-12, "param {a} vs {b}");
    }
    for (a, b) in problem.knot_vector().knots().iter().zip(floats(&case["knots"])) {
        assert!((a - b).abs() <= 1e-12, "knot {a} vs {b}");
    }
    assert_eq!(problem.knot_vector().knots().len(), floats(&case["knots"]).len());
    let curve = problem.nubs().unwrap();
    for (a, b) in curve
        .control_points()
        .iter()
        .zip(vectors::<D>(&case["control_points"]))
    {
        assert!(close(a, &b, 1e-9), "control point {a:?} vs {b:?}");
    }
    assert_eq!(curve.control_points().len(), points.len());
}

#[test]
fn interpolation_agrees_with_geomdl() {
    let data = load("interpolate_curve_geomdl.json");
    for case in data["cases"].as_array().unwrap() {
        match case["name"].as_str().unwrap() {
            "2d_chord" => check_interpolation::<2>(case),
            "3d_centripetal" => check_interpolation::<3>(case),
            other => panic!("unexpected case {other}"),
        }
    }
}

fn wavy_points(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64 * 6.0;
            Vec2::new(t + 0.1 * (3.0 * t).sin(), t.sin() + 0.05 * (7.0 * t).cos())
        })
        .collect()
}

fn max_residual<const D: usize>(curve: &NurbsCurve<D>, points: &[Vector<D>], params: &[f64]) -> f64 {
    points
        .iter()
        .zip(params)
        .map(|(p, &u)| (curve.point(u) - p).norm())
        .fold(0.0, f64::max)
}

/// Dense reference: the collocation matrix assembled independently from `NurbsCurve` evaluation
/// (the curve through unit control vectors), solved by nalgebra's LU.
#[test]
fn nubs_interpolation_matches_a_dense_solve() {
    let points = wavy_points(17);
    let problem = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let n = points.len();
    let mut matrix = nalgebra::DMatrix::<f64>::zeros(n, n);
    for i in 0..n {
        let mut unit = vec![Vec2::zeros(); n];
        unit[i] = Vec2::new(1.0, 0.0);
        let basis = NurbsCurve::non_rational(3, problem.knot_vector().knots().to_vec(), unit).unwrap();
        for (k, &u) in problem.params().iter().enumerate() {
            matrix[(k, i)] = basis.point(u).x;
        }
    }
    let rhs = nalgebra::DMatrix::<f64>::from_fn(n, 2, |k, c| points[k][c]);
    let dense = matrix.lu().solve(&rhs).unwrap();
    let curve = problem.nubs().unwrap();
    for i in 0..n {
        for c in 0..2 {
            assert!((curve.control_points()[i][c] - dense[(i, c)]).abs() < 1e-12 * 10.0);
        }
    }
}

#[test]
fn unit_weights_give_the_nubs_and_end_tangents_are_honoured() {
    let points = wavy_points(12);
    let (t0, t1) = (Vec2::new(3.0, 1.0), Vec2::new(-2.0, 4.0));
    let settings = InterpolationSettings::default().with_end_tangents(t0, t1);
    let problem =
        Interpolation::with_parametrization(&points, Parametrization::ChordLength, settings).unwrap();
    assert_eq!(problem.control_count(), points.len() + 2);
    let nubs = problem.nubs().unwrap();
    let unit = problem.solve(&vec![1.0; problem.control_count()]).unwrap();
    assert_eq!(nubs, unit);
    assert!(max_residual(&nubs, &points, problem.params()) < 1e-12 * 10.0);
    // The NUBS with end derivatives (Eq. 9.11–9.12): P_1 = P_0 + u_{p+1}/p · D_0.
    let u4 = problem.knot_vector().knots()[4];
    assert!((nubs.control_points()[1] - (points[0] + t0 * (u4 / 3.0))).norm() < 1e-12);
    let weights: Vec<f64> = (0..problem.control_count())
        .map(|i| 0.5 + (i as f64 * 0.7).sin().abs())
        .collect();
    let rational = problem.solve(&weights).unwrap();
    assert!(max_residual(&rational, &points, problem.params()) < 1e-12 * 10.0);
    for curve in [&nubs, &rational] {
        assert!((curve.jet(0.0, Side::Right)[1] - t0).norm() < 1e-11 * t0.norm());
        assert!((curve.jet(1.0, Side::Left)[1] - t1).norm() < 1e-11 * t1.norm());
    }
    // Without tangents the end derivatives differ: the test above can fail.
    let free = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap()
    .nubs()
    .unwrap();
    assert!((free.jet(0.0, Side::Right)[1] - t0).norm() > 1e-3);
}

#[test]
fn interpolant_moves_points_and_keeps_parameters() {
    let points = wavy_points(20);
    let problem = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let weights: Vec<f64> = (0..20).map(|i| 1.0 + 0.3 * (i as f64).cos()).collect();
    let mut curve = NurbsInterpolant::new(problem, weights).unwrap();
    let moved = Vec2::new(3.0, 0.5);
    curve.move_points(&[(7, moved)]).unwrap();
    assert!((curve.eval(curve.parameter(7)) - moved).norm() < 1e-12);
    assert!((curve.eval(curve.parameter(3)) - points[3]).norm() < 1e-12);
    assert!(matches!(
        curve.move_points(&[(20, moved)]),
        Err(Error::IndexOutOfRange { .. })
    ));
    assert!(matches!(
        curve.set_weights(vec![1.0; 3]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!((curve.eval(curve.parameter(7)) - moved).norm() < 1e-12);
}

#[test]
fn knot_insertion_keeps_the_curve() {
    let data = load("nurbs_geomdl.json");
    let case = &data["curves"][0];
    let curve = NurbsCurve::<2>::new(
        3,
        floats(&case["knots"]),
        vectors::<2>(&case["control_points"]),
        floats(&case["weights"]),
    )
    .unwrap();
    let interior_knot = curve.knots()[4];
    for (u, times) in [(0.31, 1), (0.31, 3), (interior_knot, 2), (0.77, 2)] {
        let refined = curve.insert_knot(u, times).unwrap();
        assert_eq!(
            refined.control_points().len(),
            curve.control_points().len() + times
        );
        for i in 0..=50 {
            let t = i as f64 / 50.0;
            assert!(
                (refined.point(t) - curve.point(t)).norm() < 1e-12 * 10.0,
                "u {u} times {times} at {t}"
            );
        }
    }
    assert!(matches!(
        curve.insert_knot(interior_knot, 3),
        Err(Error::BadKnots { .. })
    ));
    // Removal undoes insertion (A5.8): the inserted knots are removable to round-off and the
    // original control net comes back.
    for (u, times) in [(0.31, 2), (interior_knot, 2), (0.77, 3)] {
        let refined = curve.insert_knot(u, times).unwrap();
        let (restored, removed) = refined.remove_knot(u, times, 1e-10).unwrap();
        assert_eq!(removed, times);
        assert_eq!(restored.knots(), curve.knots());
        for (a, b) in restored.control_points().iter().zip(curve.control_points()) {
            assert!((a - b).norm() < 1e-10, "{a:?} vs {b:?}");
        }
        for (a, b) in restored.weights().iter().zip(curve.weights()) {
            assert!((a - b).abs() < 1e-10);
        }
    }
    // An original knot of a generic curve is essential: nothing is removed.
    let (same, removed) = curve.remove_knot(interior_knot, 1, 1e-10).unwrap();
    assert_eq!(removed, 0);
    assert_eq!(&same, &curve);
    assert!(curve.remove_knot(0.31, 1, 1e-3).is_err());
    assert!(curve.remove_knot(interior_knot, 1, f64::NAN).is_err());
    assert!(curve.insert_knot(0.0, 1).is_err());
    assert!(curve.insert_knot(f64::NAN, 1).is_err());
}

#[test]
fn bad_inputs_are_errors() {
    let p = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(2.0, 0.0),
        Vec2::new(3.0, 1.0),
    ];
    let w = vec![1.0; 4];
    let good = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    assert!(NurbsCurve::new(3, good.clone(), p.clone(), w.clone()).is_ok());
    let bad_knots = [
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, f64::NAN],
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.5],
        vec![1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
    ];
    for knots in bad_knots {
        assert!(matches!(
            NurbsCurve::new(3, knots, p.clone(), w.clone()),
            Err(Error::BadKnots { .. })
        ));
    }
    // interior multiplicity above the degree
    let p5 = vec![Vec2::zeros(); 5];
    assert!(matches!(
        NurbsCurve::new(1, vec![0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0], p5, vec![1.0; 5]),
        Err(Error::BadKnots { .. })
    ));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let mut weights = w.clone();
        weights[2] = bad;
        assert!(matches!(
            NurbsCurve::new(3, good.clone(), p.clone(), weights),
            Err(Error::BadWeight { index: 2, .. })
        ));
    }
    assert!(matches!(
        NurbsCurve::new(3, good.clone(), p.clone(), vec![1.0; 3]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        NurbsCurve::new(0, vec![0.0, 1.0, 2.0, 3.0], p.clone(), w.clone()),
        Err(Error::BadDegree { .. })
    ));
    assert!(matches!(
        NurbsCurve::new(4, good.clone(), p.clone(), w.clone()),
        Err(Error::TooFewPoints { .. })
    ));
    let mut nan_points = p.clone();
    nan_points[1].x = f64::NAN;
    assert!(matches!(
        NurbsCurve::new(3, good, nan_points, w),
        Err(Error::NonFinite { .. })
    ));

    // interpolation
    let settings = InterpolationSettings::default();
    assert!(matches!(
        Interpolation::new(&p, &[0.0, 1.0, 2.0], settings),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        Interpolation::new(&p, &[0.0, 1.0, 1.0, 2.0], settings),
        Err(Error::NotIncreasing { .. })
    ));
    assert!(matches!(
        Interpolation::new(&p, &[0.0, 1.0, f64::NAN, 2.0], settings),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        Interpolation::new(&p[..2], &[0.0, 1.0], settings),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(matches!(
        Interpolation::new(&p[..1], &[0.0], settings),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(matches!(
        Interpolation::<2>::new(&[], &[], settings),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(Interpolation::new(&p[..2], &[0.0, 1.0], settings.with_degree(1)).is_ok());
    assert!(Interpolation::new(
        &p[..2],
        &[0.0, 1.0],
        settings.with_end_tangents(Vec2::x(), Vec2::y())
    )
    .is_ok());
    assert!(matches!(
        Interpolation::new(
            &p,
            &[0.0, 1.0, 2.0, 3.0],
            settings.with_end_tangents(Vec2::x(), Vec2::new(f64::NAN, 0.0))
        ),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        Interpolation::new(&p, &[0.0, 1.0, 2.0, 3.0], settings.with_degree(0)),
        Err(Error::BadDegree { .. })
    ));
    let problem = Interpolation::new(&p, &[0.0, 1.0, 2.0, 3.0], settings).unwrap();
    assert!(matches!(
        problem.solve(&[1.0, 1.0, -1.0, 1.0]),
        Err(Error::BadWeight { index: 2, .. })
    ));
    assert!(matches!(
        problem.solve(&[1.0, 1.0, 1.0]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        problem.solve(&[1.0, f64::NAN, 1.0, 1.0]),
        Err(Error::BadWeight { index: 1, .. })
    ));

    // arcs
    assert!(NurbsCurve::circular_arc(Vec2::zeros(), 0.0, 0.0, 1.0).is_err());
    assert!(NurbsCurve::circular_arc(Vec2::zeros(), -1.0, 0.0, 1.0).is_err());
    assert!(NurbsCurve::circular_arc(Vec2::zeros(), 1.0, 1.0, 1.0).is_err());
    assert!(NurbsCurve::circular_arc(Vec2::zeros(), 1.0, 0.0, 7.0).is_err());
    assert!(NurbsCurve::circular_arc(Vec2::zeros(), f64::NAN, 0.0, 1.0).is_err());
    assert!(NurbsCurve::circular_arc_3d(Vec3::zeros(), Vec3::x(), Vec3::x(), 1.0, 0.0, 1.0).is_err());

    // surfaces
    let row = vec![Vec3::zeros(); 4];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let net = vec![row.clone(), row.clone(), row.clone(), row.clone()];
    let weights = vec![vec![1.0; 4]; 4];
    assert!(NurbsSurface::new(3, 3, knots.clone(), knots.clone(), net.clone(), weights.clone()).is_ok());
    let mut ragged = net.clone();
    ragged[2].pop();
    assert!(matches!(
        NurbsSurface::new(3, 3, knots.clone(), knots.clone(), ragged, weights.clone()),
        Err(Error::RaggedGrid { row: 2, .. })
    ));
    let mut ragged_weights = weights.clone();
    ragged_weights[1].push(1.0);
    assert!(matches!(
        NurbsSurface::new(3, 3, knots.clone(), knots.clone(), net.clone(), ragged_weights),
        Err(Error::RaggedGrid { row: 1, .. })
    ));
    let mut bad_weights = weights.clone();
    bad_weights[3][3] = 0.0;
    assert!(matches!(
        NurbsSurface::new(3, 3, knots.clone(), knots.clone(), net.clone(), bad_weights),
        Err(Error::BadWeight { index: 15, .. })
    ));
    assert!(matches!(
        NurbsSurface::new(3, 3, knots.clone(), vec![0.0, 1.0], net.clone(), weights.clone()),
        Err(Error::BadKnots { .. })
    ));
    assert!(NurbsSurface::new(3, 3, knots.clone(), knots, vec![], vec![]).is_err());
}

#[test]
fn serialization_has_the_report_fields() {
    let arc = NurbsCurve::circular_arc(Vec2::zeros(), 2.0, 0.0, std::f64::consts::PI).unwrap();
    let json = serde_json::to_value(&arc).unwrap();
    assert_eq!(json["type"], "nurbs");
    assert_eq!(json["degree"], 2);
    assert_eq!(json["knots"].as_array().unwrap().len(), 8);
    assert_eq!(json["control_points"][1].as_array().unwrap().len(), 2);
    assert_eq!(json["weights"].as_array().unwrap().len(), 5);
}

#[test]
fn full_circle_is_closed_and_uses_four_arcs() {
    let circle =
        NurbsCurve::circular_arc(Vec2::new(1.0, -2.0), 3.0, 0.5, 0.5 + 2.0 * std::f64::consts::PI).unwrap();
    assert_eq!(circle.control_points().len(), 9);
    assert!((circle.point(0.0) - circle.point(1.0)).norm() < 1e-12);
    let arc = NurbsCurve::circular_arc_3d(
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        2.0,
        0.0,
        1.0,
    )
    .unwrap();
    for i in 0..=20 {
        let p = arc.point(i as f64 / 20.0) - Vec3::new(1.0, 2.0, 3.0);
        assert!((p.norm() - 2.0).abs() < 1e-12);
        assert!(p.dot(&Vec3::new(1.0, -1.0, 0.0)).abs() < 1e-12);
    }
}

proptest! {
    #[test]
    fn arcs_have_constant_radius_and_curvature(
        radius in 0.01f64..100.0,
        start in -10.0f64..10.0,
        sweep in 0.01f64..(2.0 * std::f64::consts::PI),
        cx in -5.0f64..5.0,
        cy in -5.0f64..5.0,
    ) {
        // The centre scales with the radius: a far centre makes C'' a difference of large
        // numbers (conditioning, not the construction), which a fixed tolerance cannot judge.
        let center = Vec2::new(cx, cy) * radius;
        let arc = NurbsCurve::circular_arc(center, radius, start, start + sweep).unwrap();
        for i in 0..=40 {
            let u = i as f64 / 40.0;
            for side in [Side::Left, Side::Right] {
                let jet = arc.jet(u, side);
                prop_assert!(((jet[0] - center).norm() - radius).abs() < 1e-12 * (radius + center.norm()));
                let speed = jet[1].norm();
                let curvature = (jet[1].x * jet[2].y - jet[1].y * jet[2].x).abs() / speed.powi(3);
                prop_assert!((curvature * radius - 1.0).abs() < 1e-9, "curvature {} radius {}", curvature, radius);
            }
        }
        let end = arc.point(1.0) - center;
        prop_assert!((end - Vec2::new((start + sweep).cos(), (start + sweep).sin()) * radius).norm() < 1e-12 * (radius + center.norm()));
    }

    #[test]
    fn weighted_interpolation_passes_through_every_point(
        weights in proptest::collection::vec(0.05f64..20.0, 15),
        tangents in any::<bool>(),
    ) {
        let points: Vec<Vec3> = (0..13)
            .map(|i| {
                let t = i as f64 * 0.5;
                Vec3::new(10.0 * t.cos(), 10.0 * t.sin(), t * t)
            })
            .collect();
        let size = points.iter().map(|p| p.norm()).fold(0.0, f64::max);
        let (t0, t1) = (Vec3::new(0.0, 20.0, 1.0), Vec3::new(-5.0, 3.0, 40.0));
        let settings = if tangents {
            InterpolationSettings::default().with_end_tangents(t0, t1)
        } else {
            InterpolationSettings::default()
        };
        let problem = Interpolation::with_parametrization(&points, Parametrization::Centripetal, settings).unwrap();
        let w = &weights[..problem.control_count()];
        let curve = problem.solve(w).unwrap();
        prop_assert!(max_residual(&curve, &points, problem.params()) < 1e-12 * size);
        prop_assert_eq!(curve.weights(), w);
        if tangents {
            // The rational derivative (A' - W'C)/W divides by the end weight after a
            // cancellation between weighted control points, so round-off grows with the
            // weight ratio; the bound is machine precision times that ratio.
            let ratio = w.iter().cloned().fold(0.0, f64::max) / w.iter().cloned().fold(f64::INFINITY, f64::min);
            for (u, t) in [(0.0, t0), (1.0, t1)] {
                let error = (curve.jet(u, Side::Right)[1] - t).norm();
                prop_assert!(error < 1e-12 * ratio * t.norm(), "end tangent error {} at u = {}", error, u);
            }
        }
    }

    #[test]
    fn arbitrary_knots_and_weights_never_panic(
        knots in proptest::collection::vec(-2.0f64..2.0, 0..12),
        weights in proptest::collection::vec(-1.0f64..2.0, 0..7),
        degree in 0usize..5,
        u in -3.0f64..3.0,
    ) {
        let points = vec![Vec2::new(1.0, 2.0); weights.len()];
        if let Ok(curve) = NurbsCurve::new(degree, knots, points, weights) {
            let jet = curve.jet(u, Side::Left);
            prop_assert!(jet.iter().all(|v| v.iter().all(|c| c.is_finite())));
        }
    }
}

/// `set_control_point` is the in-place form of building the curve again: after it the curve
/// equals (field for field, so bit for bit) the one `NurbsCurve::new` builds from the changed
/// control points and weights, and a bad index, point or weight is an error that leaves the
/// curve as it was.
#[test]
fn set_control_point_equals_a_rebuild_and_refuses_bad_input() {
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 1.0, 1.0, 1.0, 1.0];
    let mut points: Vec<Vec2> = (0..6)
        .map(|i| Vec2::new(i as f64, ((i * i) % 5) as f64 * 0.37))
        .collect();
    let mut weights = vec![1.0, 0.7, 1.3, 1.0, 2.1, 1.0];
    let mut curve = NurbsCurve::new(3, knots.clone(), points.clone(), weights.clone()).unwrap();
    let before = curve.point(0.42);
    curve.set_control_point(2, Vec2::new(2.25, -0.8), 0.45).unwrap();
    points[2] = Vec2::new(2.25, -0.8);
    weights[2] = 0.45;
    let rebuilt = NurbsCurve::new(3, knots, points, weights).unwrap();
    assert_eq!(curve, rebuilt);
    for k in 0..=20 {
        let u = k as f64 / 20.0;
        assert_eq!(curve.point(u), rebuilt.point(u), "u = {u}");
    }
    // The change is real: the point at 0.42 (inside the moved control point's support) moved.
    assert_ne!(curve.point(0.42), before);

    let kept = curve.clone();
    assert!(matches!(
        curve.set_control_point(6, Vec2::new(0.0, 0.0), 1.0),
        Err(Error::IndexOutOfRange { index: 6, len: 6, .. })
    ));
    assert!(matches!(
        curve.set_control_point(1, Vec2::new(f64::NAN, 0.0), 1.0),
        Err(Error::NonFinite { index: 1, .. })
    ));
    for bad in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        assert!(matches!(
            curve.set_control_point(1, Vec2::new(0.5, 0.5), bad),
            Err(Error::BadWeight { index: 1, .. })
        ));
    }
    assert_eq!(curve, kept);
}
