//! Nowacki et al.'s NURBS weight fairing on real curves: the optimised criterion never rises,
//! the data points stay interpolated, weights stay positive, and any criterion plugs in.

use curve_repr::{Interpolation, InterpolationSettings, NurbsCurve, Parametrization, Vec2};
use fairness::Criterion;
use optim::{CriterionName, CubicBernstein, NelderMeadSettings, NurbsWeightFairing, PerPoint};

pub(crate) fn read_csv(relative: &str) -> Vec<Vec2> {
    let path = format!("{}/../../data/{relative}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            Vec2::new(v[0], v[1])
        })
        .collect()
}

/// The diagonal of the points' bounding box: the curve's size for relative tolerances.
fn size(points: &[Vec2]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    (hi - lo).norm()
}

/// max_k |C(ū_k) − D_k|, computed here from the curve, not taken from the result.
fn residual(curve: &NurbsCurve<2>, params: &[f64], points: &[Vec2]) -> f64 {
    params
        .iter()
        .zip(points)
        .map(|(u, p)| (curve.point(*u) - p).norm())
        .fold(0.0, f64::max)
}

#[test]
fn equal_weights_give_the_nubs() {
    let points = read_csv("airfoil_naca2412/naca2412_upper.csv");
    let interpolation = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let nubs = interpolation.nubs().unwrap();
    assert!(nubs.weights().iter().all(|w| *w == 1.0));
    // A common factor of the weights cancels in the rational form: same curve.
    let n = interpolation.control_count();
    let scaled = interpolation.solve(&vec![3.7; n]).unwrap();
    for i in 0..=1000 {
        let u = i as f64 / 1000.0;
        let d = (scaled.point(u) - nubs.point(u)).norm();
        assert!(d < 1e-12 * size(&points), "u = {u}: {d}");
    }
    // And the NUBS interpolates.
    assert!(residual(&nubs, interpolation.params(), &points) < 1e-12 * size(&points));
}

fn check_all_criteria(relative: &str) {
    let points = read_csv(relative);
    let scale = size(&points);
    let mut strictly_lower = Vec::new();
    for name in CriterionName::ALL {
        let result = NurbsWeightFairing::new(CubicBernstein, name.criterion::<2>())
            .with_nelder_mead(NelderMeadSettings::default().with_max_iterations(300))
            .run(&points)
            .unwrap_or_else(|e| panic!("{relative} {name}: {e}"));
        assert!(
            result.criterion_after <= result.criterion_before,
            "{relative} {name}: {} > {}",
            result.criterion_after,
            result.criterion_before
        );
        // The result's before/after energies agree with the optimised values.
        let b = name.of(&result.before);
        let a = name.of(&result.after);
        assert!(
            (b - result.criterion_before).abs() <= 1e-8 * b.abs(),
            "{name}: {b} vs {}",
            result.criterion_before
        );
        assert!(
            (a - result.criterion_after).abs() <= 1e-8 * a.abs(),
            "{name}: {a} vs {}",
            result.criterion_after
        );
        if result.criterion_after < result.criterion_before * (1.0 - 1e-6) {
            strictly_lower.push(name);
        }
        assert!(result.weights.iter().all(|w| *w > 0.0 && w.is_finite()));
        assert_eq!(result.weights, result.curve.weights());
        let r = residual(&result.curve, &result.params, &points);
        assert!(r < 1e-9 * scale, "{relative} {name}: residual {r}");
        assert!((r - result.max_residual).abs() <= 1e-15 * scale);
        assert_eq!(result.law_params.len(), 4);
    }
    assert!(
        strictly_lower.contains(&CriterionName::E2) || strictly_lower.contains(&CriterionName::Ek),
        "{relative}: only {strictly_lower:?} decreased"
    );
}

#[test]
fn airfoil_upper_surface_criteria_decrease() {
    check_all_criteria("airfoil_naca2412/naca2412_upper.csv");
}

#[test]
fn block_island_waterline_criteria_decrease() {
    check_all_criteria("hull_block_island_boat/waterlines/wl_36in.csv");
}

#[test]
fn per_point_law_does_at_least_as_well_as_unit_weights() {
    let points = read_csv("hull_block_island_boat/waterlines/wl_36in.csv");
    let result = NurbsWeightFairing::new(PerPoint, CriterionName::E2.criterion::<2>())
        .with_nelder_mead(NelderMeadSettings::default().with_max_iterations(300))
        .run(&points)
        .unwrap();
    assert!(result.criterion_after <= result.criterion_before);
    assert_eq!(result.law_params.len(), result.weights.len() - 1);
    assert_eq!(result.weights[0], 1.0);
    assert!(residual(&result.curve, &result.params, &points) < 1e-9 * size(&points));
}

/// A user's criterion: squared second differences of 200 equally spaced samples (a discrete
/// bending measure written without the fairness crate's integrals).
struct SampledBending;

impl Criterion<NurbsCurve<2>> for SampledBending {
    fn name(&self) -> &str {
        "sampled-bending"
    }
    fn evaluate(&self, curve: &NurbsCurve<2>) -> fairness::Result<f64> {
        let samples: Vec<Vec2> = (0..=200).map(|i| curve.point(i as f64 / 200.0)).collect();
        Ok(samples
            .windows(3)
            .map(|w| (w[0] - 2.0 * w[1] + w[2]).norm_squared())
            .sum())
    }
}

#[test]
fn user_defined_criterion_plugs_in() {
    let points = read_csv("airfoil_naca2412/naca2412_upper.csv");
    let result = NurbsWeightFairing::new(CubicBernstein, SampledBending)
        .with_nelder_mead(NelderMeadSettings::default().with_max_iterations(300))
        .run(&points)
        .unwrap();
    assert_eq!(result.criterion, "sampled-bending");
    // The reported values are the user's criterion of the NUBS and of the faired curve.
    let nubs = Interpolation::with_parametrization(
        &points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap()
    .nubs()
    .unwrap();
    // The Bernstein law's unit weights are 1 only to rounding (Σ B_j(s) = 1 in floating point).
    let unit = SampledBending.evaluate(&nubs).unwrap();
    assert!(
        (result.criterion_before - unit).abs() <= 1e-12 * unit,
        "{} vs {unit}",
        result.criterion_before
    );
    assert_eq!(
        result.criterion_after,
        SampledBending.evaluate(&result.curve).unwrap()
    );
    assert!(result.criterion_after <= result.criterion_before);
    assert!(result.weights.iter().all(|w| *w > 0.0));
}

#[test]
fn criterion_names_parse() {
    for name in CriterionName::ALL {
        assert_eq!(name.as_str().parse::<CriterionName>().unwrap(), name);
        assert_eq!(name.criterion::<2>().name(), name.as_str());
    }
    assert!("e4".parse::<CriterionName>().is_err());
}

#[test]
fn repeated_point_is_an_error_not_a_panic() {
    let points = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(2.0, 0.0),
        Vec2::new(3.0, 1.0),
    ];
    assert!(
        NurbsWeightFairing::new(CubicBernstein, CriterionName::E2.criterion::<2>())
            .run(&points)
            .is_err()
    );
}
