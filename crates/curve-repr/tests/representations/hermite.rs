//! The parametric cubic Hermite spline against its defining conditions and the oracles.

use curve_repr::{
    Curve, HermiteEnds, HermiteSettings, HermiteSpline, Interpolant, Parametrization, Side, Vec2, Vec3,
    Vector,
};
use proptest::prelude::*;
use serde_json::Value;

fn reference(name: &str) -> Value {
    let path = format!("{}/../../data/reference/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap()
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

fn close(got: f64, expected: f64, tolerance: f64, what: &str) {
    let error = (got - expected).abs();
    assert!(
        error <= tolerance * expected.abs().max(1e-300) || error <= 1e-15,
        "{what}: got {got}, expected {expected}"
    );
}

/// Curvature at a knot from the jet: signed (x'y'' − y'x'')/|C'|³ in 2D, |C'×C''|/|C'|³ in 3D.
fn curvature<const D: usize>(spline: &HermiteSpline<D>, t: f64) -> f64 {
    let jet = spline.jet(t, Side::Right);
    let (d1, d2) = (jet[1], jet[2]);
    let speed = d1.norm();
    let cross = if D == 2 {
        d1[0] * d2[1] - d1[1] * d2[0]
    } else {
        Vec3::new(d1[0], d1[1], d1[2])
            .cross(&Vec3::new(d2[0], d2[1], d2[2]))
            .norm()
    };
    cross / (speed * speed * speed)
}

fn check_metrics<const D: usize>(dataset: &Value) {
    let points: Vec<Vector<D>> = dataset["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| Vector::<D>::from_iterator(numbers(p)))
        .collect();
    let spline = HermiteSpline::natural(&points).unwrap();
    let t = numbers(&dataset["t"]);
    assert_eq!(spline.parameters().len(), t.len());
    for (got, expected) in spline.parameters().iter().zip(&t) {
        close(*got, *expected, 1e-12, "t");
    }
    let z = numbers(&dataset["z"]);
    let jumps = spline.third_derivative_jumps();
    assert_eq!(jumps.len(), z.len());
    for (jump, expected) in jumps.iter().zip(&z) {
        close(jump.norm(), *expected, 1e-9, "z");
    }
    let kappa = numbers(&dataset["kappa"]);
    let largest = kappa.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    for (i, expected) in kappa.iter().enumerate() {
        let got = curvature(&spline, t[i]);
        if i == 0 || i + 1 == kappa.len() {
            // Zero up to round-off at the free ends.
            assert!(got.abs() < 1e-9 * largest && expected.abs() < 1e-9 * largest);
        } else {
            close(got, *expected, 1e-9, "kappa");
        }
    }
    close(
        spline.strain_energy(),
        dataset["E_2"].as_f64().unwrap(),
        1e-9,
        "E_2",
    );
}

#[test]
fn natural_chord_length_spline_matches_parametric_metrics() {
    let data = reference("parametric_metrics.json");
    let mut seen = [false; 2];
    for dataset in data["datasets"].as_array().unwrap() {
        match dataset["dim"].as_u64().unwrap() {
            2 => {
                check_metrics::<2>(dataset);
                seen[0] = true;
            }
            3 => {
                check_metrics::<3>(dataset);
                seen[1] = true;
            }
            other => panic!("unexpected dimension {other}"),
        }
    }
    assert_eq!(seen, [true, true]);
}

/// A spline function y(x) is the parametric spline through (x_i, y_i) with t = x: x(t) = t
/// exactly (the natural or slope-1 clamped spline of linear data is linear), y(t) = y(x).
#[test]
fn graph_of_a_function_matches_scipy_cubic_spline() {
    let data = reference("cubic_spline.json");
    for dataset in data["datasets"].as_array().unwrap() {
        let x = numbers(&dataset["x"]);
        let y = numbers(&dataset["y"]);
        let points: Vec<Vec2> = x.iter().zip(&y).map(|(&a, &b)| Vec2::new(a, b)).collect();
        let eval_x = numbers(&dataset["eval_x"]);
        let slopes = numbers(&dataset["clamped"]["end_slopes"]);
        for (case, ends) in [
            ("natural", HermiteEnds::Natural),
            (
                "clamped",
                HermiteEnds::Clamped {
                    start: Vec2::new(1.0, slopes[0]),
                    end: Vec2::new(1.0, slopes[1]),
                },
            ),
        ] {
            let settings = HermiteSettings::default()
                .with_parameters(x.clone())
                .with_ends(ends);
            let spline = HermiteSpline::new(&points, &settings).unwrap();
            let expected = &dataset[case];
            let columns = ["value", "d1", "d2", "d3"].map(|k| numbers(&expected[k]));
            let scales = columns
                .clone()
                .map(|c| c.iter().fold(0.0f64, |m, v| m.max(v.abs())));
            for (k, &t) in eval_x.iter().enumerate() {
                let jet = spline.jet(t, Side::Right);
                for order in 0..4 {
                    let error = (jet[order][1] - columns[order][k]).abs();
                    assert!(
                        error <= 1e-9 * scales[order],
                        "{case} order {order} at {t}: {} vs {}",
                        jet[order][1],
                        columns[order][k]
                    );
                }
                assert!((jet[0][0] - t).abs() <= 1e-12 * t.abs().max(1.0));
                assert!((jet[1][0] - 1.0).abs() <= 1e-12);
            }
        }
    }
}

/// Largest norm among the values.
fn largest<const D: usize>(values: impl IntoIterator<Item = Vector<D>>) -> f64 {
    values.into_iter().fold(0.0, |m, v| m.max(v.norm()))
}

fn near<const D: usize>(a: Vector<D>, b: Vector<D>, scale: f64, what: &str) -> Result<(), TestCaseError> {
    prop_assert!(
        (a - b).norm() <= 1e-9 * scale,
        "{what}: {a:?} vs {b:?} (scale {scale})"
    );
    Ok(())
}

/// Interpolation, C2 continuity, the end condition, the closed-form energy, and the windowed
/// update against a full rebuild.
fn check_spline<const D: usize>(
    points: &[Vector<D>],
    ends: HermiteEnds<D>,
    parametrization: Parametrization,
    moves: &[(usize, Vector<D>)],
) -> Result<(), TestCaseError> {
    let settings = HermiteSettings::default()
        .with_parametrization(parametrization)
        .with_ends(ends);
    let spline = HermiteSpline::new(points, &settings).unwrap();
    let knots = spline.knots().to_vec();
    let segments = spline.segment_count();
    prop_assert_eq!(segments + 1, knots.len());
    let left: Vec<[Vector<D>; 4]> = knots.iter().map(|&t| spline.jet(t, Side::Left)).collect();
    let right: Vec<[Vector<D>; 4]> = knots.iter().map(|&t| spline.jet(t, Side::Right)).collect();
    let scale = |order: usize| {
        largest(left.iter().chain(&right).map(|j| j[order])).max(largest(points.iter().copied()) * 1e-3)
    };
    let scales = [scale(0), scale(1), scale(2), scale(3)];
    // Through every point; the closing knot of a closed curve returns to P_0.
    for (i, p) in points.iter().enumerate() {
        near(right[i][0], *p, scales[0], "interpolation (right)")?;
        near(left[i][0], *p, scales[0], "interpolation (left)")?;
        near(right[i][1], spline.tangents()[i], scales[1], "tangent")?;
    }
    // C2 at interior knots.
    for i in 1..segments {
        for order in 0..3 {
            near(left[i][order], right[i][order], scales[order], "C2")?;
        }
    }
    let (first, last) = (0, segments);
    match ends {
        HermiteEnds::Natural => {
            near(right[first][2], Vector::zeros(), scales[2], "natural start")?;
            near(left[last][2], Vector::zeros(), scales[2], "natural end")?;
        }
        HermiteEnds::Clamped { start, end } => {
            near(right[first][1], start, scales[1], "clamped start")?;
            near(left[last][1], end, scales[1], "clamped end")?;
        }
        HermiteEnds::ParabolicRunout => {
            near(right[first][2], left[first + 1][2], scales[2], "runout start")?;
            near(right[last - 1][2], left[last][2], scales[2], "runout end")?;
        }
        HermiteEnds::Closed => {
            for order in 0..3 {
                near(left[last][order], right[first][order], scales[order], "closed")?;
            }
        }
    }
    // Strain energy: 3-point Gauss–Legendre per segment (exact for the quadratic |C''|²).
    let nodes = [-(0.6f64.sqrt()), 0.0, 0.6f64.sqrt()];
    let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
    let mut quadrature = 0.0;
    for w in knots.windows(2) {
        let (a, b) = (w[0], w[1]);
        for (x, weight) in nodes.iter().zip(weights) {
            let t = 0.5 * (a + b) + 0.5 * (b - a) * x;
            quadrature += weight * 0.5 * (b - a) * spline.jet(t, Side::Right)[2].norm_squared();
        }
    }
    let energy = spline.strain_energy();
    prop_assert!(
        (energy - quadrature).abs() <= 1e-10 * quadrature.max(1e-300),
        "energy {} vs quadrature {}",
        energy,
        quadrature
    );
    // Windowed move against a rebuild from scratch over the same knots.
    let mut moved = spline.clone();
    moved.move_points(moves).unwrap();
    let mut moved_points = points.to_vec();
    for &(i, p) in moves {
        moved_points[i] = p;
    }
    prop_assert_eq!(moved.points(), &moved_points[..]);
    prop_assert_eq!(moved.knots(), &knots[..]);
    let settings = HermiteSettings::default()
        .with_parameters(knots.clone())
        .with_ends(ends);
    let rebuilt = HermiteSpline::new(&moved_points, &settings).unwrap();
    let tangent_scale = largest(rebuilt.tangents().iter().copied());
    for (i, (a, b)) in moved.tangents().iter().zip(rebuilt.tangents()).enumerate() {
        prop_assert!(
            (a - b).norm() <= 1e-12 * tangent_scale,
            "tangent {}: windowed {:?}, rebuilt {:?}",
            i,
            a,
            b
        );
    }
    let mut refreshed = moved.clone();
    refreshed.rebuild().unwrap();
    prop_assert_eq!(refreshed.tangents(), rebuilt.tangents());
    Ok(())
}

/// Random walks with steps of length 0.05 to 1 (so chords differ by up to 20 times).
fn walk<const D: usize>(min: usize, max: usize) -> impl Strategy<Value = Vec<Vector<D>>> {
    let step = (prop::array::uniform::<_, D>(-1.0f64..1.0), 0.05f64..1.0)
        .prop_filter("direction", |(d, _)| d.iter().map(|c| c * c).sum::<f64>() > 0.01)
        .prop_map(|(d, length)| {
            let v = Vector::<D>::from_iterator(d);
            v * (length / v.norm())
        });
    prop::collection::vec(step, min..max).prop_map(|steps| {
        let mut p = Vector::<D>::zeros();
        steps
            .into_iter()
            .map(|s| {
                p += s;
                p
            })
            .collect()
    })
}

/// One random case: points, moves (index, offset), clamped end tangents, parametrisation.
type Case<const D: usize> = (Vec<Vector<D>>, Vec<(usize, Vector<D>)>, [Vector<D>; 2], usize);

fn case<const D: usize>() -> impl Strategy<Value = Case<D>> {
    walk::<D>(3, 260).prop_flat_map(|points| {
        let n = points.len();
        let moves = prop::collection::vec((0..n, prop::array::uniform::<_, D>(-1.0f64..1.0)), 1..4).prop_map(
            move |m| {
                m.into_iter()
                    .map(|(i, d)| (i, Vector::<D>::from_iterator(d)))
                    .collect::<Vec<_>>()
            },
        );
        let tangents = prop::array::uniform::<_, 2>(prop::array::uniform::<_, D>(-3.0f64..3.0))
            .prop_map(|[a, b]| [Vector::<D>::from_iterator(a), Vector::<D>::from_iterator(b)]);
        (Just(points), moves, tangents, 0usize..3)
    })
}

fn run<const D: usize>(
    (points, offsets, [start, end], parametrization): Case<D>,
) -> Result<(), TestCaseError> {
    let parametrization = [
        Parametrization::Uniform,
        Parametrization::ChordLength,
        Parametrization::Centripetal,
    ][parametrization];
    let moves: Vec<(usize, Vector<D>)> = offsets.iter().map(|&(i, d)| (i, points[i] + d)).collect();
    for ends in [
        HermiteEnds::Natural,
        HermiteEnds::Clamped { start, end },
        HermiteEnds::ParabolicRunout,
        HermiteEnds::Closed,
    ] {
        if ends == HermiteEnds::Closed && points.first() == points.last() {
            continue;
        }
        check_spline(&points, ends, parametrization, &moves)?;
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn planar_splines_meet_their_defining_conditions(input in case::<2>()) {
        run(input)?;
    }

    #[test]
    fn spatial_splines_meet_their_defining_conditions(input in case::<3>()) {
        run(input)?;
    }
}

/// The worst case for the window: chords alternating between 1 and 1e-3, where the decay per
/// knot approaches its bound ½; the windowed update still equals a rebuild.
#[test]
fn windowed_update_survives_wildly_non_uniform_knots() {
    let points: Vec<Vec3> = (0..3000)
        .scan(Vec3::zeros(), |p, i| {
            let length = if i % 2 == 0 { 1.0 } else { 1e-3 };
            let angle = i as f64 * 0.37;
            *p += Vec3::new(angle.cos(), angle.sin(), 0.3) * length;
            Some(*p)
        })
        .collect();
    for ends in [HermiteEnds::Natural, HermiteEnds::Closed] {
        let settings = HermiteSettings::default().with_ends(ends);
        let mut spline = HermiteSpline::new(&points, &settings).unwrap();
        let moves = [
            (1500, Vec3::new(0.0, 0.0, 5.0)),
            (1530, Vec3::new(1.0, 0.0, 0.0)),
            (2999, Vec3::zeros()),
        ];
        let moves: Vec<(usize, Vec3)> = moves.iter().map(|&(i, d)| (i, points[i] + d)).collect();
        spline.move_points(&moves).unwrap();
        let mut rebuilt = spline.clone();
        rebuilt.rebuild().unwrap();
        let scale = largest(rebuilt.tangents().iter().copied());
        let worst = spline
            .tangents()
            .iter()
            .zip(rebuilt.tangents())
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        assert!(worst <= 1e-12 * scale, "{ends:?}: {worst} vs scale {scale}");
        // The move is local: a tangent far away did not change at all.
        let fresh = HermiteSpline::new(&points, &settings).unwrap();
        assert_eq!(spline.tangents()[700], fresh.tangents()[700]);
    }
}

#[test]
fn closed_curve_jumps_cover_every_knot_and_a_circle_is_nearly_fair() {
    let n = 24;
    let circle: Vec<Vec2> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            Vec2::new(a.cos(), a.sin())
        })
        .collect();
    let settings = HermiteSettings::default().with_ends(HermiteEnds::Closed);
    let spline = HermiteSpline::new(&circle, &settings).unwrap();
    let jumps = spline.third_derivative_jumps();
    assert_eq!(jumps.len(), n);
    // By symmetry every knot carries the same jump magnitude.
    let first = jumps[0].norm();
    assert!(jumps.iter().all(|j| (j.norm() - first).abs() <= 1e-9 * first));
    // The closed interpolant's knot curvature converges to 1 at second order in the spacing:
    // doubling the points divides the error by about 4.
    let error = |points: usize| {
        let circle: Vec<Vec2> = (0..points)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / points as f64;
                Vec2::new(a.cos(), a.sin())
            })
            .collect();
        let spline = HermiteSpline::new(&circle, &settings).unwrap();
        spline
            .knots()
            .iter()
            .map(|&t| (curvature(&spline, t) - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (error(n), error(2 * n));
    assert!(
        coarse < 1e-2 && (3.5..4.5).contains(&(coarse / fine)),
        "{coarse} {fine}"
    );
    let open = HermiteSpline::natural(&circle).unwrap();
    assert_eq!(open.third_derivative_jumps().len(), n - 2);
}
