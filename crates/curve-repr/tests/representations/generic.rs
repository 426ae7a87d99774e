//! The generic (`T: num_traits::Float`) rational evaluation: with `T = f64` it is the f64 API,
//! bit for bit the algorithm the crate used before it was made generic, and it agrees with the
//! geomdl oracle; the interpolant's homogeneous points are linear in the weights.

use curve_repr::bspline::basis_derivatives;
use curve_repr::{
    Curve, Interpolation, InterpolationSettings, NurbsCurve, Parametrization, Side, Vec2, Vector,
};
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

/// The f64 evaluation as written before the scalar was made generic (The NURBS Book A3.2 on
/// the weighted points, then Eq. 4.8 with nalgebra vectors), kept here as the reference.
fn reference_derivatives<const D: usize>(
    curve: &NurbsCurve<D>,
    u: f64,
    order: usize,
    side: Side,
) -> Vec<Vector<D>> {
    let p = curve.degree();
    let knots = curve.knot_vector();
    let span = knots.span(u, side);
    let basis = basis_derivatives(knots.knots(), p, span, u, order);
    let first = span - p;
    let weighted: Vec<Vector<D>> = curve
        .control_points()
        .iter()
        .zip(curve.weights())
        .map(|(p, &w)| p * w)
        .collect();
    let mut numerator = vec![Vector::<D>::zeros(); order + 1];
    let mut denominator = vec![0.0; order + 1];
    for (k, row) in basis.iter().enumerate() {
        for (j, &n) in row.iter().enumerate() {
            numerator[k] += weighted[first + j] * n;
            denominator[k] += curve.weights()[first + j] * n;
        }
    }
    let binomial = |n: usize, k: usize| (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64);
    let mut out: Vec<Vector<D>> = Vec::with_capacity(order + 1);
    for k in 0..=order {
        let mut v = numerator[k];
        for i in 1..=k {
            v -= out[k - i] * (binomial(k, i) * denominator[i]);
        }
        out.push(v / denominator[0]);
    }
    out
}

fn oracle_curve<const D: usize>(case: &Value) -> NurbsCurve<D> {
    NurbsCurve::<D>::new(
        case["degree"].as_u64().unwrap() as usize,
        floats(&case["knots"]),
        vectors::<D>(&case["control_points"]),
        floats(&case["weights"]),
    )
    .unwrap()
}

fn check_bitwise<const D: usize>(curve: &NurbsCurve<D>, params: &[f64]) {
    let generic = curve.to_generic::<f64>();
    for &u in params {
        for side in [Side::Left, Side::Right] {
            let reference = reference_derivatives(curve, u, 3, side);
            let api = curve.derivatives(u, 3, side);
            let lifted = generic.derivatives(u, 3, side);
            for k in 0..=3 {
                for c in 0..D {
                    // Same operations in the same order: equal to the last bit.
                    assert_eq!(api[k][c].to_bits(), reference[k][c].to_bits(), "u {u} order {k}");
                    assert_eq!(lifted[k][c].to_bits(), api[k][c].to_bits(), "u {u} order {k}");
                }
            }
        }
    }
}

#[test]
fn f64_api_is_the_generic_code_bit_for_bit_on_the_oracle_curves() {
    let data = load("nurbs_geomdl.json");
    for case in data["curves"].as_array().unwrap() {
        let mut params = floats(&case["params"]);
        params.extend((0..=97).map(|i| i as f64 / 97.0));
        match case["name"].as_str().unwrap() {
            "2d" => check_bitwise(&oracle_curve::<2>(case), &params),
            "3d" => check_bitwise(&oracle_curve::<3>(case), &params),
            other => panic!("unexpected case {other}"),
        }
        // and the oracle itself, through the generic path (same 1e-9 as `nurbs.rs`)
        if case["name"] == "2d" {
            let curve = oracle_curve::<2>(case).to_generic::<f64>();
            let d2 = vectors::<2>(&case["d2"]);
            for (k, &u) in floats(&case["params"]).iter().enumerate() {
                let c2 = Vec2::from(curve.derivatives(u, 2, Side::Right)[2]);
                assert!(
                    (c2 - d2[k]).norm() <= 1e-9 * d2[k].norm().max(1.0),
                    "{c2} vs {}",
                    d2[k]
                );
            }
        }
    }
}

#[test]
fn homogeneous_points_are_linear_in_the_weights() {
    let points: Vec<Vec2> = (0..15)
        .map(|i| {
            let t = i as f64 / 14.0;
            Vec2::new(t * 3.0, (4.0 * t).sin() + 0.01 * (i % 3) as f64)
        })
        .collect();
    let interpolation = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let n = interpolation.control_count();
    let w: Vec<f64> = (0..n).map(|i| 1.0 + 0.3 * ((i as f64) * 0.7).sin()).collect();
    let delta: Vec<f64> = (0..n)
        .map(|i| if i % 2 == 0 { -0.5 } else { 0.25 * i as f64 })
        .collect();
    let q = interpolation.homogeneous_points(&w).unwrap();
    let dq = interpolation.homogeneous_points(&delta).unwrap();
    let moved: Vec<f64> = w.iter().zip(&delta).map(|(a, b)| a + 0.1 * b).collect();
    let q_moved = interpolation.homogeneous_points(&moved).unwrap();
    for i in 0..n {
        let expected = q[i] + dq[i] * 0.1;
        assert!(
            (q_moved[i] - expected).norm() < 1e-12 * (1.0 + expected.norm()),
            "{i}"
        );
    }
    // Q / w are the interpolant's control points.
    let curve = interpolation.solve(&w).unwrap();
    for i in 0..n {
        let p = q[i] / w[i];
        assert!((p - curve.control_points()[i]).norm() < 1e-12 * (1.0 + p.norm()));
    }
    // and the curve through them still passes through every data point
    for (u, d) in interpolation.params().iter().zip(&points) {
        assert!((curve.point(*u) - d).norm() < 1e-10);
    }
    assert!(interpolation.homogeneous_points(&w[1..]).is_err());
    let mut bad = w.clone();
    bad[2] = f64::NAN;
    assert!(interpolation.homogeneous_points(&bad).is_err());
    let _ = curve.domain();
}
