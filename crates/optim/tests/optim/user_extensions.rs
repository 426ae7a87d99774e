//! A user-defined weight law and a user-defined objective plug in without touching the library.

use optim::weight_law::{check_parameters, positive_weight};
use optim::{
    minimize, NelderMeadSettings, Objective, Result, Termination, WeightCriterion, WeightLaw, WeightProblem,
};

/// A user's law: log-weights quadratic in s = i/n, symmetric about the middle,
/// ln w_i = a (s − ½)² − a/4 (so that w_0 = w_n = 1): one parameter.
struct SymmetricBulge;

impl WeightLaw for SymmetricBulge {
    fn name(&self) -> &str {
        "symmetric-bulge"
    }
    fn parameter_count(&self, _control_points: usize) -> usize {
        1
    }
    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>> {
        check_parameters(1, params)?;
        let a = params[0];
        let n = control_points.saturating_sub(1).max(1) as f64;
        Ok((0..control_points)
            .map(|i| {
                let s = i as f64 / n;
                positive_weight(a * (s - 0.5).powi(2) - a / 4.0)
            })
            .collect())
    }
    fn identity_params(&self, _control_points: usize) -> Vec<f64> {
        vec![0.0]
    }
}

/// A user's criterion type (not a closure): distance of the middle weight from a target.
struct MiddleWeight {
    target: f64,
}

impl WeightCriterion for MiddleWeight {
    fn evaluate(&self, weights: &[f64]) -> Result<f64> {
        let middle = weights
            .get(weights.len() / 2)
            .ok_or_else(|| optim::Error::objective("no weights"))?;
        Ok((middle - self.target).powi(2))
    }
}

/// A user's objective type: a shifted sphere.
struct Sphere {
    centre: Vec<f64>,
}

impl Objective for Sphere {
    fn cost(&self, params: &[f64]) -> Result<f64> {
        Ok(params
            .iter()
            .zip(&self.centre)
            .map(|(x, c)| (x - c).powi(2))
            .sum())
    }
}

#[test]
fn user_objective_plugs_into_minimize() {
    let sphere = Sphere {
        centre: vec![3.0, -1.0, 0.25, 7.0],
    };
    let m = minimize(
        &sphere,
        &[0.0; 4],
        NelderMeadSettings::default()
            .with_step(1.0)
            .with_sd_tolerance(1e-14),
    )
    .unwrap();
    assert_eq!(m.termination, Termination::Converged);
    for (x, c) in m.params.iter().zip(&sphere.centre) {
        assert!((x - c).abs() < 1e-5, "{x} vs {c}");
    }
}

#[test]
fn user_law_and_user_criterion_plug_into_weight_problem() {
    // 9 control points: the middle one is i = 4, s = ½, ln w = −a/4, so w_mid = 0.5 at
    // a = 4 ln 2.
    let problem = WeightProblem::new(SymmetricBulge, 9, MiddleWeight { target: 0.5 });
    let solution = problem
        .solve(NelderMeadSettings::default().with_sd_tolerance(1e-16))
        .unwrap();
    assert_eq!(solution.law.name, "symmetric-bulge");
    assert_eq!(solution.law.parameters, vec!["p0"]);
    assert!(
        (solution.params[0] - 4.0 * 2f64.ln()).abs() < 1e-5,
        "{:?}",
        solution.params
    );
    assert!((solution.weights[4] - 0.5).abs() < 1e-6);
    assert_eq!(solution.before, 0.25); // (1 − 0.5)² at unit weights
    assert!(solution.after < 1e-10);
    // The law's own promise: end weights stay 1.
    assert!((solution.weights[0] - 1.0).abs() < 1e-12);
    assert!((solution.weights[8] - 1.0).abs() < 1e-12);
}

#[test]
fn laws_can_be_chosen_at_run_time() {
    let laws: Vec<Box<dyn WeightLaw>> = vec![Box::new(SymmetricBulge), Box::new(optim::CubicBernstein)];
    for law in laws {
        let problem = WeightProblem::new(law, 9, MiddleWeight { target: 0.5 });
        let solution = problem.solve(NelderMeadSettings::default()).unwrap();
        assert!(solution.after < solution.before);
    }
}
