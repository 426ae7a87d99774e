//! Oracle and property tests of the cubic spline function (Han et al. §3.1–3.3).

use curve_repr::spline_function::UPDATE_WINDOW;
use curve_repr::{Curve, EndCondition, Error, Interpolant, Side, SplineFunction, Vec2};
use proptest::prelude::*;
use serde_json::Value;

fn load(name: &str) -> Value {
    let path = format!("{}/../../data/reference/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn floats(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// |got − want| ≤ 1e-9 (|want| + 1e-3·max|want|) entry by entry.
fn assert_close(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= 1e-9 * (w.abs() + 1e-3 * scale),
            "{what}[{i}]: got {g}, want {w}"
        );
    }
}

const ENDS: [EndCondition; 3] = [
    EndCondition::ParabolicRunout,
    EndCondition::Natural,
    EndCondition::Clamped {
        start_slope: 0.0,
        end_slope: 0.0,
    },
];

#[test]
fn natural_and_clamped_splines_match_scipy() {
    let data = load("cubic_spline.json");
    for set in data["datasets"].as_array().unwrap() {
        let x = floats(&set["x"]);
        let y = floats(&set["y"]);
        let eval_x = floats(&set["eval_x"]);
        for kind in ["natural", "clamped"] {
            let expected = &set[kind];
            let end = if kind == "natural" {
                EndCondition::Natural
            } else {
                let slopes = floats(&expected["end_slopes"]);
                EndCondition::Clamped {
                    start_slope: slopes[0],
                    end_slope: slopes[1],
                }
            };
            let spline = SplineFunction::new(&x, &y, end).unwrap();
            let jets: Vec<[f64; 4]> = eval_x.iter().map(|&t| spline.jet_at(t, Side::Right)).collect();
            for (order, field) in ["value", "d1", "d2", "d3"].iter().enumerate() {
                let got: Vec<f64> = jets.iter().map(|j| j[order]).collect();
                assert_close(&format!("{kind} {field}"), &got, &floats(&expected[field]));
            }
            let second: Vec<f64> = spline.c().iter().map(|c| 6.0 * c).collect();
            assert_close(
                &format!("{kind} d2_at_knots"),
                &second,
                &floats(&expected["d2_at_knots"]),
            );
            let third: Vec<f64> = x[..x.len() - 1]
                .iter()
                .map(|&t| spline.third_derivative(t, Side::Right))
                .collect();
            assert_close(
                &format!("{kind} d3_per_interval"),
                &third,
                &floats(&expected["d3_per_interval"]),
            );
            // From the left at the last knot, the last interval too; at an interior knot the left limit is the previous interval's.
            let last = *x.last().unwrap();
            assert_eq!(spline.third_derivative(last, Side::Left), *third.last().unwrap());
            assert_eq!(spline.third_derivative(x[1], Side::Left), third[0]);
        }
    }
}

/// e_i = (c_{i+1} − c_i)/h_i − (c_i − c_{i−1})/h_{i−1} for the interior i (the reference's definition).
fn e_values(x: &[f64], c: &[f64]) -> Vec<f64> {
    (1..x.len() - 1)
        .map(|i| (c[i + 1] - c[i]) / (x[i + 1] - x[i]) - (c[i] - c[i - 1]) / (x[i] - x[i - 1]))
        .collect()
}

#[test]
fn runout_spline_matches_the_reference() {
    let data = load("runout_spline_function.json");
    for set in data["datasets"].as_array().unwrap() {
        let x = floats(&set["x"]);
        let y = floats(&set["y"]);
        let spline = SplineFunction::new(&x, &y, EndCondition::default()).unwrap();
        assert_close("c", spline.c(), &floats(&set["c"]));
        assert_close("e", &e_values(&x, spline.c()), &floats(&set["e"]));
        let energy = set["E_s"].as_f64().unwrap();
        assert_close("E_s", &[spline.second_derivative_energy()], &[energy]);
    }
}

#[test]
fn second_derivative_energy_is_the_integral() {
    // Simpson's rule is exact for the quadratic y''² on each interval.
    let x = [0.0, 0.4, 1.5, 1.7, 3.0];
    let y = [0.0, 1.0, -1.0, 0.5, 2.0];
    for end in ENDS {
        let spline = SplineFunction::new(&x, &y, end).unwrap();
        let simpson: f64 = x
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let f = |t: f64, side| spline.jet_at(t, side)[2].powi(2);
                (b - a) / 6.0 * (f(a, Side::Right) + 4.0 * f(0.5 * (a + b), Side::Right) + f(b, Side::Left))
            })
            .sum();
        let energy = spline.second_derivative_energy();
        assert!(
            (energy - simpson).abs() < 1e-12 * simpson,
            "{end:?}: {energy} vs {simpson}"
        );
    }
}

/// Non-uniform abscissae with gaps spanning two orders of magnitude.
fn uneven_x(n: usize) -> Vec<f64> {
    let mut x = vec![0.0];
    for i in 1..n {
        let gap = 0.05 + (i as f64 * 1.7).sin().abs() * 3.0 + if i % 5 == 0 { 4.0 } else { 0.0 };
        x.push(x[i - 1] + gap);
    }
    x
}

/// The defining condition of the sensitivities: column j is the spline through the unit vector e_j.
fn check_sensitivities_against_unit_splines(x: &[f64]) {
    let n = x.len();
    for end in ENDS {
        let y: Vec<f64> = (0..n).map(|i| (i as f64 * 0.9).cos()).collect();
        let spline = SplineFunction::new(x, &y, end).unwrap();
        for j in 0..n {
            let mut unit = vec![0.0; n];
            unit[j] = 1.0;
            let direct = SplineFunction::new(x, &unit, end).unwrap();
            let scale = direct.c().iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..n {
                let got = spline.sensitivity(i, j);
                let want = direct.c()[i];
                assert!(
                    (got - want).abs() <= 1e-12 * scale,
                    "{end:?} n={n} c~[{i}][{j}] = {got}, unit spline gives {want}"
                );
            }
            let column = spline.sensitivity_column(j, UPDATE_WINDOW).unwrap();
            for (k, value) in column.values.iter().enumerate() {
                let want = direct.c()[column.first + k];
                assert!(
                    (value - want).abs() <= 1e-12 * scale,
                    "{end:?} column {j} entry {k}"
                );
            }
        }
    }
}

#[test]
fn sensitivities_are_the_unit_splines_for_every_end_condition() {
    for n in [2, 3, 4, 5, 6, 9, 17] {
        check_sensitivities_against_unit_splines(&uneven_x(n));
    }
}

#[test]
fn sensitivities_follow_the_papers_sign_pattern_and_runout_ends() {
    // Han §3.3 property (1)-(2): c~_j^j < 0, c~_{j±1}^j > 0, then alternating, and for runout
    // c~_1 = c~_2, c~_{n−1} = c~_n.
    let x = uneven_x(12);
    let n = x.len();
    let spline = SplineFunction::new(&x, &vec![0.0; n], EndCondition::ParabolicRunout).unwrap();
    for j in 2..n - 2 {
        assert!(spline.sensitivity(j, j) < 0.0);
        for i in 1..n - 1 {
            let distance = i.abs_diff(j);
            if distance >= 1 {
                let expected_sign = if distance % 2 == 1 { 1.0 } else { -1.0 };
                assert!(
                    spline.sensitivity(i, j) * expected_sign > 0.0,
                    "sign of c~[{i}][{j}]"
                );
            }
        }
        assert_eq!(spline.sensitivity(0, j), spline.sensitivity(1, j));
        assert_eq!(spline.sensitivity(n - 1, j), spline.sensitivity(n - 2, j));
    }
}

#[test]
fn sensitivities_decay_at_least_like_a_power_of_two() {
    let x = uneven_x(80);
    let n = x.len();
    for end in ENDS {
        let spline = SplineFunction::new(&x, &vec![0.0; n], end).unwrap();
        for j in 0..n {
            let near = spline
                .sensitivity(j.wrapping_sub(1), j)
                .abs()
                .max(spline.sensitivity(j + 1, j).abs());
            for i in 0..n {
                let distance = i.abs_diff(j);
                if distance >= 2 {
                    let bound = 2.0 * near * 0.5f64.powi(distance as i32 - 1);
                    assert!(spline.sensitivity(i, j).abs() <= bound, "{end:?} [{i}][{j}]");
                }
            }
        }
    }
}

#[test]
fn long_range_sensitivities_neither_underflow_to_nan_nor_lose_accuracy() {
    let x = uneven_x(5000);
    let n = x.len();
    let y = vec![0.0; n];
    for end in ENDS {
        let spline = SplineFunction::new(&x, &y, end).unwrap();
        for j in [0, 1, 2, 2500, n - 3, n - 2, n - 1] {
            let column = spline.sensitivity_column(j, 40).unwrap();
            for (k, want) in column.values.iter().enumerate() {
                let got = spline.sensitivity(column.first + k, j);
                // 40 rounded multiplications against 40 rounded logarithms.
                assert!(
                    (got - want).abs() <= 1e-13 * want.abs() + 1e-300,
                    "{end:?} [{}][{j}]",
                    column.first + k
                );
            }
            for i in [0, 1, n / 3, n - 2, n - 1] {
                let value = spline.sensitivity(i, j);
                assert!(value.is_finite());
                if i.abs_diff(j) > 1200 {
                    assert_eq!(value, 0.0, "below the smallest double");
                }
            }
        }
    }
}

#[test]
fn runout_on_two_points_is_the_line_and_on_three_the_parabola() {
    let line = SplineFunction::new(&[1.0, 3.0], &[2.0, 6.0], EndCondition::ParabolicRunout).unwrap();
    assert_eq!(line.c(), &[0.0, 0.0]);
    assert!((line.value(2.0) - 4.0).abs() < 1e-15);
    assert_eq!(line.sensitivity(0, 1), 0.0);
    // y = 2x² − x + 1 through three uneven points: y'' = 4, so c = 2/3 everywhere.
    let x = [0.0, 0.3, 2.0];
    let y: Vec<f64> = x.iter().map(|t| 2.0 * t * t - t + 1.0).collect();
    let parabola = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    for c in parabola.c() {
        assert!((c - 2.0 / 3.0).abs() < 1e-14);
    }
    for t in [0.1, 1.0, 1.9] {
        assert!((parabola.value(t) - (2.0 * t * t - t + 1.0)).abs() < 1e-14);
        assert!(parabola.third_derivative(t, Side::Right).abs() < 1e-13);
    }
}

#[test]
fn bad_input_is_the_right_error() {
    let end = EndCondition::default();
    assert!(matches!(
        SplineFunction::new(&[0.0, 1.0, f64::NAN], &[0.0; 3], end),
        Err(Error::NonFinite { what: "x", index: 2 })
    ));
    assert!(matches!(
        SplineFunction::new(&[0.0, 1.0, 2.0], &[0.0, f64::INFINITY, 0.0], end),
        Err(Error::NonFinite { what: "y", index: 1 })
    ));
    let clamped = EndCondition::Clamped {
        start_slope: f64::NAN,
        end_slope: 0.0,
    };
    assert!(matches!(
        SplineFunction::new(&[0.0, 1.0, 2.0], &[0.0; 3], clamped),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        SplineFunction::new(&[0.0, 1.0, 1.0, 2.0], &[0.0; 4], end),
        Err(Error::NotIncreasing { index: 2, .. })
    ));
    assert!(matches!(
        SplineFunction::new(&[0.0, 2.0, 1.0], &[0.0; 3], EndCondition::Natural),
        Err(Error::NotIncreasing { index: 2, .. })
    ));
    assert!(matches!(
        SplineFunction::new(&[0.0, 1.0, 2.0], &[0.0; 2], end),
        Err(Error::LengthMismatch {
            expected: 3,
            got: 2,
            ..
        })
    ));
    for end in ENDS {
        assert!(matches!(
            SplineFunction::new(&[0.0], &[0.0], end),
            Err(Error::TooFewPoints {
                needed: 2,
                got: 1,
                ..
            })
        ));
        assert!(matches!(
            SplineFunction::new(&[], &[], end),
            Err(Error::TooFewPoints { .. })
        ));
    }
    // Overflowing steps and slopes are reported, not turned into NaN.
    assert!(SplineFunction::new(&[-1e308, 1e308, 1.5e308], &[0.0; 3], end).is_err());
    assert!(SplineFunction::new(&[0.0, 1e-300, 1.0], &[0.0, 1e300, 0.0], end).is_err());
}

#[test]
fn moves_must_keep_x_and_failures_change_nothing() {
    let x = uneven_x(10);
    let y: Vec<f64> = x.iter().map(|t| t.sin()).collect();
    let mut spline = SplineFunction::new(&x, &y, EndCondition::default()).unwrap();
    let before = spline.c().to_vec();
    let moved_x = Vec2::new(x[3] + 1e-9, 1.0);
    assert!(matches!(
        spline.move_points(&[(3, moved_x)]),
        Err(Error::InvalidMove { index: 3, .. })
    ));
    let good = Vec2::new(x[2], 5.0);
    assert!(matches!(
        spline.move_points(&[(2, good), (10, good)]),
        Err(Error::IndexOutOfRange { index: 10, .. })
    ));
    assert!(matches!(
        spline.set_y(&[(1, 2.0), (4, f64::NAN)]),
        Err(Error::NonFinite { index: 4, .. })
    ));
    assert!(matches!(
        spline.set_y(&[(1, 2.0), (4, 1e308), (5, -1e308)]),
        Err(Error::InvalidMove { .. })
    ));
    assert_eq!(spline.c(), &before[..]);
    assert_eq!(spline.y(), &y[..]);
    spline.move_points(&[(2, good)]).unwrap();
    assert_eq!(spline.point(2), good);
    let mut moved = y.clone();
    moved[2] = 5.0;
    let rebuilt = SplineFunction::new(&x, &moved, EndCondition::default()).unwrap();
    for (a, b) in spline.c().iter().zip(rebuilt.c()) {
        assert!((a - b).abs() < 1e-13 * (1.0 + b.abs()));
    }
}

#[test]
fn the_graph_is_a_curve_through_its_points() {
    let x = uneven_x(7);
    let y: Vec<f64> = x.iter().map(|t| (0.3 * t).sin()).collect();
    let spline = SplineFunction::new(&x, &y, EndCondition::Natural).unwrap();
    assert_eq!(spline.breaks(), x);
    assert_eq!(spline.domain(), (x[0], x[6]));
    assert_eq!(spline.parameters(), x);
    assert_eq!(spline.point_count(), 7);
    let t = 0.5 * (x[2] + x[3]);
    let jet = spline.jet(t, Side::Right);
    let h = 1e-6;
    assert_eq!(jet[0], Vec2::new(t, spline.value(t)));
    assert_eq!(jet[1].x, 1.0);
    assert_eq!((jet[2].x, jet[3].x), (0.0, 0.0));
    // Derivatives against central differences of the level below.
    let (above, below) = (spline.jet(t + h, Side::Right), spline.jet(t - h, Side::Right));
    for (order, derivative) in jet.iter().enumerate().skip(1) {
        let difference = (above[order - 1].y - below[order - 1].y) / (2.0 * h);
        assert!(
            (difference - derivative.y).abs() < 1e-6 * (1.0 + derivative.y.abs()),
            "order {order}"
        );
    }
}

fn increasing_x(max_gaps: usize) -> impl Strategy<Value = Vec<f64>> {
    (
        prop::collection::vec(1e-3f64..10.0, 1..max_gaps),
        -100.0f64..100.0,
    )
        .prop_map(|(gaps, start)| {
            let mut x = vec![start];
            for gap in gaps {
                let next = x[x.len() - 1] + gap;
                x.push(next);
            }
            x
        })
}

fn spline_input(max_gaps: usize) -> impl Strategy<Value = (Vec<f64>, Vec<f64>, EndCondition)> {
    increasing_x(max_gaps).prop_flat_map(|x| {
        let n = x.len();
        (
            Just(x),
            prop::collection::vec(-50.0f64..50.0, n),
            prop_oneof![
                Just(EndCondition::ParabolicRunout),
                Just(EndCondition::Natural),
                (-5.0f64..5.0, -5.0f64..5.0).prop_map(|(start_slope, end_slope)| EndCondition::Clamped {
                    start_slope,
                    end_slope
                }),
            ],
        )
    })
}

proptest! {
    #[test]
    fn interpolates_is_c2_and_meets_its_end_condition((x, y, end) in spline_input(60)) {
        let spline = SplineFunction::new(&x, &y, end).unwrap();
        let n = x.len();
        let y_scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let c_scale = spline.c().iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        for i in 0..n {
            let left = spline.jet_at(x[i], Side::Left);
            let right = spline.jet_at(x[i], Side::Right);
            prop_assert!((left[0] - y[i]).abs() <= 1e-12 * y_scale);
            prop_assert!((right[0] - y[i]).abs() <= 1e-12 * y_scale);
            if i > 0 && i + 1 < n {
                let slope_scale = left[1].abs().max(right[1].abs()).max(y_scale / (x[n - 1] - x[0]));
                prop_assert!((left[1] - right[1]).abs() <= 1e-9 * slope_scale, "y' jumps at {}", i);
                prop_assert!((left[2] - right[2]).abs() <= 1e-9 * 6.0 * c_scale, "y'' jumps at {}", i);
            }
            prop_assert!((right[2] - 6.0 * spline.c()[i]).abs() <= 1e-12 * 6.0 * c_scale);
        }
        let c = spline.c();
        match end {
            EndCondition::ParabolicRunout if n >= 3 => {
                prop_assert_eq!(c[0], c[1]);
                prop_assert!((c[n - 1] - c[n - 2]).abs() <= 1e-14 * c_scale);
            }
            EndCondition::ParabolicRunout | EndCondition::Natural => {
                prop_assert_eq!(c[0], 0.0);
                prop_assert_eq!(c[n - 1], 0.0);
            }
            EndCondition::Clamped { start_slope, end_slope } => {
                let tolerance = 1e-9 * (1.0 + start_slope.abs().max(end_slope.abs()) + y_scale / (x[n - 1] - x[0]));
                prop_assert!((spline.first_derivative(x[0]) - start_slope).abs() <= tolerance);
                prop_assert!((spline.first_derivative(x[n - 1]) - end_slope).abs() <= tolerance);
            }
        }
    }

    #[test]
    fn windowed_update_equals_a_full_rebuild(
        // Up to 400 points, so that the window of 64 truncates the columns.
        (x, y, end) in spline_input(400),
        moves in prop::collection::vec((any::<prop::sample::Index>(), -50.0f64..50.0), 1..=5),
    ) {
        let mut spline = SplineFunction::new(&x, &y, end).unwrap();
        let moves: Vec<(usize, f64)> = moves.iter().map(|(index, value)| (index.index(x.len()), *value)).collect();
        spline.set_y(&moves).unwrap();
        let mut moved = y.clone();
        for &(j, value) in &moves {
            moved[j] = value;
        }
        prop_assert_eq!(spline.y(), &moved[..]);
        let rebuilt = SplineFunction::new(&x, &moved, end).unwrap();
        let scale = rebuilt.c().iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        for (a, b) in spline.c().iter().zip(rebuilt.c()) {
            prop_assert!((a - b).abs() <= 1e-12 * scale, "{} vs {}", a, b);
        }
        spline.rebuild().unwrap();
        prop_assert_eq!(spline.c(), rebuilt.c());
    }
}

#[test]
fn many_windowed_updates_on_a_long_spline_stay_at_the_rebuild() {
    let x = uneven_x(3000);
    let n = x.len();
    let y: Vec<f64> = x.iter().map(|t| (0.05 * t).sin()).collect();
    for end in [
        EndCondition::ParabolicRunout,
        EndCondition::Natural,
        EndCondition::Clamped {
            start_slope: 0.2,
            end_slope: -0.4,
        },
    ] {
        let mut spline = SplineFunction::new(&x, &y, end).unwrap();
        let mut moved = y.clone();
        for k in 0..300usize {
            // Every index class: the ends, their neighbours, the interior.
            let j = match k % 6 {
                0 => 0,
                1 => 1,
                2 => n - 1,
                3 => n - 2,
                _ => (k * 7919) % n,
            };
            let value = moved[j] + ((k as f64) * 1.3).sin() * 0.1;
            moved[j] = value;
            spline.set_y(&[(j, value)]).unwrap();
        }
        let rebuilt = SplineFunction::new(&x, &moved, end).unwrap();
        let scale = rebuilt.c().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, (a, b)) in spline.c().iter().zip(rebuilt.c()).enumerate() {
            assert!((a - b).abs() <= 1e-12 * scale, "{end:?} c[{i}]: {a} vs {b}");
        }
    }
}

/// `set_y_within` truncates each column at `window` entries per side: the difference from a
/// rebuild is within the decay bound 2 · max(|c̃_{j−1}^j|, |c̃_{j+1}^j|) · 2^{−window} of the
/// move (plus rounding), and it is not zero for a short window (the truncation is real).
#[test]
fn a_short_update_window_stays_within_the_decay_bound() {
    let x = uneven_x(300);
    let y: Vec<f64> = x.iter().map(|t| (0.05 * t).sin()).collect();
    let j = 150;
    let delta = 0.7;
    for window in [4usize, 8, 32] {
        let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let before = spline.clone();
        spline.set_y_within(&[(j, y[j] + delta)], window).unwrap();
        let mut moved = y.clone();
        moved[j] += delta;
        let rebuilt = SplineFunction::new(&x, &moved, EndCondition::ParabolicRunout).unwrap();
        let central = before
            .sensitivity(j - 1, j)
            .abs()
            .max(before.sensitivity(j + 1, j).abs());
        let bound = delta * 2.0 * central * 0.5f64.powi(window as i32);
        let scale = rebuilt.c().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = spline
            .c()
            .iter()
            .zip(rebuilt.c())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        assert!(
            worst <= bound + 1e-12 * scale,
            "window {window}: {worst} > {bound}"
        );
        if window == 4 {
            assert!(worst > 1e-12 * scale, "window 4 should truncate visibly");
        }
    }
}

/// `add_column_to` judges a move without making it: on any range, c plus the columns it adds
/// equals what `set_y_within` with the same window leaves there, bit for bit, for one move and
/// for moves in sequence (including one index moved twice), at the ends and inside, and the
/// spline it reads is unchanged.
#[test]
fn a_move_judged_before_it_is_made_matches_the_windowed_update() {
    let x = uneven_x(120);
    let y: Vec<f64> = x.iter().map(|t| (0.3 * t).sin() + 0.01 * t).collect();
    for end in [EndCondition::ParabolicRunout, EndCondition::Natural] {
        let spline = SplineFunction::new(&x, &y, end).unwrap();
        let move_sets: [&[(usize, f64)]; 5] = [
            &[(60, 0.3)],
            &[(0, -0.2)],
            &[(119, 0.4), (118, -0.1)],
            &[(30, 0.25), (31, -0.25), (29, 0.1)],
            &[(70, 0.2), (71, 0.1), (70, -0.05)],
        ];
        for moves in move_sets {
            for (window, first, len) in [
                (20usize, 0usize, 120usize),
                (8, 25, 40),
                (3, 55, 9),
                (64, 100, 20),
            ] {
                let mut made = spline.clone();
                let new: Vec<(usize, f64)> = moves.iter().map(|&(k, g)| (k, y[k] + g)).collect();
                made.set_y_within(&new, window).unwrap();
                let mut out = spline.c()[first..first + len].to_vec();
                let mut current = y.clone();
                for &(k, value) in &new {
                    spline.add_column_to(k, value - current[k], window, first, &mut out);
                    current[k] = value;
                }
                for (i, (a, b)) in out.iter().zip(&made.c()[first..first + len]).enumerate() {
                    assert_eq!(
                        a.to_bits(),
                        b.to_bits(),
                        "{end:?} {moves:?} w {window}: c[{}]",
                        first + i
                    );
                }
                assert_eq!(spline.y(), &y[..]);
            }
        }
    }
}

/// Sets dc[0] and dc[1] (the entries at `first`, `first + 1`) so that the change of c `dc`
/// meets both moment conditions of `local_y_change` (weights about x_first), the others kept.
fn balance_moments(spline: &SplineFunction, first: usize, dc: &mut [f64]) {
    let origin = spline.x()[first];
    let (mut s1, mut s2) = (0.0, 0.0);
    for (k, d) in dc.iter().enumerate().skip(2) {
        let (w1, w2) = spline.moment_weights(first + k, origin);
        s1 += w1 * d;
        s2 += w2 * d;
    }
    let (a1, a2) = spline.moment_weights(first, origin);
    let (b1, b2) = spline.moment_weights(first + 1, origin);
    let det = a1 * b2 - b1 * a2;
    dc[0] = (-s1 * b2 + b1 * s2) / det;
    dc[1] = (-a1 * s2 + a2 * s1) / det;
}

/// `local_y_change`: a δc that meets the two moment conditions is made by a y move on the same
/// points, checked by rebuilding the spline from y + δy (the defining condition: c changes by
/// δc there and nowhere else), for every end condition; a δc that violates them is refused.
#[test]
fn a_local_change_of_c_comes_from_a_local_y_move() {
    let x = uneven_x(30);
    let y: Vec<f64> = x.iter().map(|t| (0.7 * t).sin() + 0.1 * t * t).collect();
    for end in [
        EndCondition::ParabolicRunout,
        EndCondition::Natural,
        EndCondition::Clamped {
            start_slope: 0.3,
            end_slope: -1.0,
        },
    ] {
        let spline = SplineFunction::new(&x, &y, end).unwrap();
        for (first, len) in [(2usize, 4usize), (9, 7), (20, 8)] {
            // Free entries, then the first two solved so that both moments vanish.
            let mut dc: Vec<f64> = (0..len)
                .map(|k| ((k * 7 + first) % 5) as f64 * 0.1 - 0.2)
                .collect();
            balance_moments(&spline, first, &mut dc);
            let dy = spline.local_y_change(first, &dc).unwrap();
            assert_eq!(dy.len(), len);
            let mut moved = y.clone();
            for (k, d) in dy.iter().enumerate() {
                moved[first + k] += d;
            }
            let rebuilt = SplineFunction::new(&x, &moved, end).unwrap();
            for k in 0..x.len() {
                let want = if (first..first + len).contains(&k) {
                    dc[k - first]
                } else {
                    0.0
                };
                let got = rebuilt.c()[k] - spline.c()[k];
                assert!(
                    (got - want).abs() < 1e-10,
                    "{end:?} window {first}+{len} at {k}: {got} vs {want}"
                );
            }
            // Breaking one moment: refused.
            let mut bad = dc.clone();
            bad[len / 2] += 0.05;
            assert!(matches!(
                spline.local_y_change(first, &bad),
                Err(Error::InvalidMove { .. })
            ));
        }
        // Too close to an end, empty, non-finite.
        assert!(spline.local_y_change(1, &[0.0; 4]).is_err());
        assert!(spline.local_y_change(x.len() - 3, &[0.0; 2]).is_err());
        assert!(spline.local_y_change(x.len() - 4, &[0.0; 2]).is_ok());
        assert!(spline.local_y_change(5, &[]).is_err());
        assert!(matches!(
            spline.local_y_change(5, &[0.0, f64::NAN, 0.0]),
            Err(Error::NonFinite { .. })
        ));
    }
}

/// `change_c_locally` leaves the spline that a full build through the moved points gives, and
/// `undo_local_change` restores y bit for bit.
#[test]
fn a_local_change_of_c_is_applied_and_undone() {
    let x = uneven_x(24);
    let y: Vec<f64> = x.iter().map(|t| (0.9 * t).cos()).collect();
    let mut spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    let (first, len) = (6usize, 6usize);
    let mut dc = vec![0.0, 0.0, 0.3, -0.1, 0.2, 0.05];
    balance_moments(&spline, first, &mut dc);
    let c0 = spline.c().to_vec();
    let change = spline.change_c_locally(first, &dc).unwrap();
    assert_eq!(change.first(), first);
    assert_eq!(change.dy().len(), len);
    let rebuilt = SplineFunction::new(&x, spline.y(), EndCondition::ParabolicRunout).unwrap();
    for (k, (a, b)) in spline.c().iter().zip(rebuilt.c()).enumerate() {
        assert!((a - b).abs() < 1e-12, "c at {k}: {a} vs {b}");
    }
    spline.undo_local_change(&change);
    assert_eq!(spline.y(), &y[..]);
    for (a, b) in spline.c().iter().zip(&c0) {
        assert!((a - b).abs() < 1e-14);
    }
}
