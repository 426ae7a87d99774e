//! The exact gradient of the fixed-rule criteria with respect to the NURBS weights: equal to
//! central differences of the same function, and the fixed rule's value equal to the adaptive
//! criterion's to its tolerance, on a ship waterline and an airfoil.

use curve_repr::{Interpolation, InterpolationSettings, Parametrization, Vec2};
use fairness::fixed_rule::FixedRule;
use fairness::{Criterion, Ek, E2};
use optim::gradient::{InterpolantCriterion, SmoothCriterion};

use crate::nurbs_weights::read_csv;

const CURVES: [&str; 2] = [
    "hull_gunnerus/waterlines/wl_03.csv",
    "airfoil_naca2412/naca2412_upper.csv",
];

fn interpolation(points: &[Vec2]) -> Interpolation<2> {
    Interpolation::with_parametrization(
        points,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap()
}

/// Unit weights and strongly varying ones (a factor e^{±0.6} between neighbours' extremes).
fn weight_sets(n: usize) -> Vec<Vec<f64>> {
    vec![
        vec![1.0; n],
        (0..n).map(|i| (0.6 * (0.9 * i as f64).sin()).exp()).collect(),
    ]
}

#[test]
fn gradient_equals_central_differences_of_the_same_function() {
    for file in CURVES {
        let points = read_csv(file);
        let interpolation = interpolation(&points);
        let n = interpolation.control_count();
        for criterion in [SmoothCriterion::Ek, SmoothCriterion::E2] {
            let smooth = InterpolantCriterion::new(&interpolation, criterion, FixedRule::default()).unwrap();
            for weights in weight_sets(n) {
                let (value, gradient) = smooth.value_and_gradient(&weights).unwrap();
                assert_eq!(value, smooth.value(&weights).unwrap());
                assert_eq!(gradient.len(), n);
                let scale = gradient.iter().fold(0.0f64, |m, g| m.max(g.abs()));
                assert!(scale > 0.0);
                for i in 0..n {
                    let h = 1e-5 * weights[i];
                    let mut plus = weights.clone();
                    let mut minus = weights.clone();
                    plus[i] += h;
                    minus[i] -= h;
                    let fd = (smooth.value(&plus).unwrap() - smooth.value(&minus).unwrap()) / (2.0 * h);
                    // relative to the gradient's largest component (some components are ~0)
                    assert!(
                        (gradient[i] - fd).abs() <= 1e-6 * scale,
                        "{file} {criterion:?} w{i}: dual {} vs central {fd} (scale {scale})",
                        gradient[i]
                    );
                }
            }
        }
    }
}

#[test]
fn fixed_rule_agrees_with_the_adaptive_criteria_to_their_tolerance() {
    let tolerance = fairness::Adaptive::default().relative_tolerance;
    for file in CURVES {
        let points = read_csv(file);
        let interpolation = interpolation(&points);
        let n = interpolation.control_count();
        let ek =
            InterpolantCriterion::new(&interpolation, SmoothCriterion::Ek, FixedRule::default()).unwrap();
        let e2 =
            InterpolantCriterion::new(&interpolation, SmoothCriterion::E2, FixedRule::default()).unwrap();
        for weights in weight_sets(n) {
            let curve = interpolation.solve(&weights).unwrap();
            let adaptive_ek = Ek::<2>::new().evaluate(&curve).unwrap();
            let adaptive_e2 = E2::<2>::new().evaluate(&curve).unwrap();
            let (fixed_ek, fixed_e2) = (ek.value(&weights).unwrap(), e2.value(&weights).unwrap());
            assert!(
                (fixed_ek - adaptive_ek).abs() <= tolerance * adaptive_ek,
                "{file}: Ek fixed {fixed_ek} adaptive {adaptive_ek}"
            );
            assert!(
                (fixed_e2 - adaptive_e2).abs() <= tolerance * adaptive_e2,
                "{file}: E2 fixed {fixed_e2} adaptive {adaptive_e2}"
            );
        }
    }
}
