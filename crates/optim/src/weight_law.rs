//! Weight laws: maps from a few optimiser parameters to one positive weight per control point.
//!
//! Nowacki et al. (1996, §3, the unnumbered equation after "cubic Bézier curve relationship")
//! constrain the weights w_i of the control points P̄_0..P̄_n of a NURBS curve to a cubic
//! Bernstein law of four free parameters:
//!
//! w_i = k_0 B_0(i/n) + k_1 B_1(i/n) + k_2 B_2(i/n) + k_3 B_3(i/n),
//! B_j(u) = C(3, j) u^j (1 − u)^{3−j}.
//!
//! # Positivity
//!
//! A NURBS weight must be positive: a zero weight puts a pole on the curve, a negative one
//! makes the denominator change sign. Nelder–Mead is unconstrained, so every law here is
//! positive **by construction**: its parameters live on a logarithmic scale and pass through
//! [`positive_weight`], `x ↦ exp(clamp(x, −MAX_LOG_WEIGHT, MAX_LOG_WEIGHT))`. The exponential
//! makes every real parameter admissible and treats a weight's doubling and halving alike; the
//! clamp ([`MAX_LOG_WEIGHT`] = 7, weights within [9.1e−4, 1097]) keeps huge or very negative
//! parameters from making the rational curve numerically singular. Beyond the clamp the law is
//! flat, so the criterion is flat too and the simplex retreats.
//!
//! # Scale
//!
//! Multiplying every weight by the same factor leaves a NURBS curve unchanged (numerator and
//! denominator scale alike). A law that can scale all its weights has a direction along which
//! the criterion is constant: harmless for Nelder–Mead (it only costs iterations), but worth
//! knowing when reading the parameters. [`CubicBernstein`] keeps the paper's four parameters,
//! with this one redundant direction; [`PerPoint`] removes it by holding w_0 = 1.
//!
//! # Your own law
//!
//! Implement [`WeightLaw`]; nothing in the library needs to change. A one-parameter law that
//! tilts the weights exponentially from one end to the other:
//!
//! ```
//! use optim::weight_law::{check_parameters, positive_weight, WeightLaw};
//!
//! /// ln w_i = b (i/n − 1/2): one parameter, the slope b.
//! struct Tilt;
//!
//! impl WeightLaw for Tilt {
//!     fn name(&self) -> &str {
//!         "tilt"
//!     }
//!     fn parameter_count(&self, _control_points: usize) -> usize {
//!         1
//!     }
//!     fn parameter_names(&self, _control_points: usize) -> Vec<String> {
//!         vec!["slope".to_string()]
//!     }
//!     fn weights(&self, params: &[f64], control_points: usize) -> optim::Result<Vec<f64>> {
//!         check_parameters(1, params)?;
//!         let slope = params[0];
//!         let n = control_points.saturating_sub(1).max(1) as f64;
//!         Ok((0..control_points)
//!             .map(|i| positive_weight(slope * (i as f64 / n - 0.5)))
//!             .collect())
//!     }
//!     fn identity_params(&self, _control_points: usize) -> Vec<f64> {
//!         vec![0.0]
//!     }
//! }
//!
//! let weights = Tilt.weights(&[2.0], 3)?;
//! assert!((weights[0] * weights[2] - 1.0).abs() < 1e-12 && weights[1] == 1.0);
//! assert_eq!(Tilt.weights(&Tilt.identity_params(5), 5)?, vec![1.0; 5]);
//! # Ok::<(), optim::Error>(())
//! ```

use crate::error::{Error, Result};

/// The largest |ln w| a law produces: weights stay within [e^−20, e^20] ≈ [2.1e−9, 4.9e8].
///
/// Far from f64's range (so no weight overflows, underflows or makes a rational evaluation
/// lose all precision), far beyond any weight ratio a fair curve needs.
pub const MAX_LOG_WEIGHT: f64 = 7.0;

/// `exp(clamp(log_weight, −MAX_LOG_WEIGHT, MAX_LOG_WEIGHT))`: a positive, finite weight for
/// every finite input. NaN maps to NaN, so check parameters first ([`check_parameters`]).
pub fn positive_weight(log_weight: f64) -> f64 {
    log_weight.clamp(-MAX_LOG_WEIGHT, MAX_LOG_WEIGHT).exp()
}

/// d/dx [`positive_weight`]`(x)`: the weight inside the clamp, 0 beyond it (the law is flat).
pub fn positive_weight_derivative(log_weight: f64) -> f64 {
    if log_weight.abs() < MAX_LOG_WEIGHT {
        log_weight.exp()
    } else {
        0.0
    }
}

/// Checks that `weight_gradient` has one entry per control point.
fn check_gradient(control_points: usize, weight_gradient: &[f64]) -> Result<()> {
    if weight_gradient.len() == control_points {
        Ok(())
    } else {
        Err(Error::LengthMismatch {
            what: "weight gradient",
            expected: control_points,
            got: weight_gradient.len(),
        })
    }
}

/// Checks that `params` has `expected` entries, all finite.
pub fn check_parameters(expected: usize, params: &[f64]) -> Result<()> {
    if params.len() != expected {
        return Err(Error::LengthMismatch {
            what: "weight-law parameters",
            expected,
            got: params.len(),
        });
    }
    match params.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(Error::NonFinite {
            what: "weight-law parameter",
            index,
        }),
        None => Ok(()),
    }
}

/// A law's name and parameter names, for reports.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct LawDescription {
    /// The law's name.
    pub name: String,
    /// One name per parameter, in order.
    pub parameters: Vec<String>,
}

/// A map from optimiser parameters to one positive weight per control point.
///
/// Contract (the tests run it on every law here): for every finite parameter vector of length
/// [`parameter_count`](WeightLaw::parameter_count), [`weights`](WeightLaw::weights) returns
/// `control_points` finite weights > 0; [`identity_params`](WeightLaw::identity_params) gives
/// unit weights; wrong lengths or non-finite parameters are errors, never panics.
pub trait WeightLaw {
    /// The law's name, e.g. `"cubic-bernstein"`.
    fn name(&self) -> &str;

    /// How many parameters the law has for a curve of `control_points` control points.
    fn parameter_count(&self, control_points: usize) -> usize;

    /// One name per parameter. Defaults to `p0, p1, ...`.
    fn parameter_names(&self, control_points: usize) -> Vec<String> {
        (0..self.parameter_count(control_points))
            .map(|i| format!("p{i}"))
            .collect()
    }

    /// The weights of the `control_points` control points (all finite and > 0).
    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>>;

    /// Parameters that give unit weights (the NURBS curve equal to the NUBS one): the
    /// optimisation's start.
    fn identity_params(&self, control_points: usize) -> Vec<f64>;

    /// The chain rule through the law: the gradient with respect to the parameters of a
    /// function of the weights whose gradient with respect to the weights is `weight_gradient`
    /// (Jᵀ g, J = ∂w/∂params), for gradient-based solvers. `None` when the law has no
    /// derivative (the default: a user's law works with Nelder–Mead without one).
    fn pull_back(
        &self,
        params: &[f64],
        control_points: usize,
        weight_gradient: &[f64],
    ) -> Option<Result<Vec<f64>>> {
        let _ = (params, control_points, weight_gradient);
        None
    }

    /// Name and parameter names together, for a report.
    fn describe(&self, control_points: usize) -> LawDescription {
        LawDescription {
            name: self.name().to_string(),
            parameters: self.parameter_names(control_points),
        }
    }
}

impl<L: WeightLaw + ?Sized> WeightLaw for &L {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn parameter_count(&self, control_points: usize) -> usize {
        (**self).parameter_count(control_points)
    }
    fn parameter_names(&self, control_points: usize) -> Vec<String> {
        (**self).parameter_names(control_points)
    }
    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>> {
        (**self).weights(params, control_points)
    }
    fn identity_params(&self, control_points: usize) -> Vec<f64> {
        (**self).identity_params(control_points)
    }
    fn pull_back(
        &self,
        params: &[f64],
        control_points: usize,
        weight_gradient: &[f64],
    ) -> Option<Result<Vec<f64>>> {
        (**self).pull_back(params, control_points, weight_gradient)
    }
}

impl<L: WeightLaw + ?Sized> WeightLaw for Box<L> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn parameter_count(&self, control_points: usize) -> usize {
        (**self).parameter_count(control_points)
    }
    fn parameter_names(&self, control_points: usize) -> Vec<String> {
        (**self).parameter_names(control_points)
    }
    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>> {
        (**self).weights(params, control_points)
    }
    fn identity_params(&self, control_points: usize) -> Vec<f64> {
        (**self).identity_params(control_points)
    }
    fn pull_back(
        &self,
        params: &[f64],
        control_points: usize,
        weight_gradient: &[f64],
    ) -> Option<Result<Vec<f64>>> {
        (**self).pull_back(params, control_points, weight_gradient)
    }
}

/// The paper's law: w_i = Σ_j k_j B_j(i/n), cubic Bernstein basis, n + 1 control points
/// (Nowacki et al. 1996, §3).
///
/// Parameters κ_0..κ_3 with k_j = `positive_weight(κ_j)` = e^{κ_j} (clamped). Since the
/// Bernstein basis is non-negative and sums to one, every w_i lies in [min k_j, max k_j]: the
/// weights are positive because the k_j are, and the law itself is exactly the paper's cubic
/// (only its coefficients are restricted to k_j > 0, which is what makes positivity hold for
/// every parameter vector). κ = 0 gives k = 1 and unit weights. The abscissa is the normalised
/// control-point index s_i = i/n, as printed (s_0 = 0 when there is a single control point).
///
/// Cost O(n) per evaluation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CubicBernstein;

impl CubicBernstein {
    /// The paper's coefficients k_j = e^{κ_j} (clamped) for the parameters κ.
    pub fn coefficients(&self, params: &[f64]) -> Result<[f64; 4]> {
        check_parameters(4, params)?;
        let mut k = [1.0; 4];
        for (k, kappa) in k.iter_mut().zip(params) {
            *k = positive_weight(*kappa);
        }
        Ok(k)
    }
}

impl WeightLaw for CubicBernstein {
    fn name(&self) -> &str {
        "cubic-bernstein"
    }

    fn parameter_count(&self, _control_points: usize) -> usize {
        4
    }

    fn parameter_names(&self, _control_points: usize) -> Vec<String> {
        ["ln k0", "ln k1", "ln k2", "ln k3"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>> {
        let [k0, k1, k2, k3] = self.coefficients(params)?;
        let n = control_points.saturating_sub(1).max(1) as f64;
        Ok((0..control_points)
            .map(|i| {
                let s = i as f64 / n;
                let t = 1.0 - s;
                k0 * t * t * t + 3.0 * k1 * s * t * t + 3.0 * k2 * s * s * t + k3 * s * s * s
            })
            .collect())
    }

    fn identity_params(&self, _control_points: usize) -> Vec<f64> {
        vec![0.0; 4]
    }

    /// ∂w_i/∂κ_j = B_j(s_i) e^{κ_j} inside the clamp, 0 beyond. O(n).
    fn pull_back(
        &self,
        params: &[f64],
        control_points: usize,
        weight_gradient: &[f64],
    ) -> Option<Result<Vec<f64>>> {
        Some((|| {
            check_parameters(4, params)?;
            check_gradient(control_points, weight_gradient)?;
            let n = control_points.saturating_sub(1).max(1) as f64;
            let mut out = vec![0.0; 4];
            for (i, g) in weight_gradient.iter().enumerate() {
                let s = i as f64 / n;
                let t = 1.0 - s;
                let basis = [t * t * t, 3.0 * s * t * t, 3.0 * s * s * t, s * s * s];
                for j in 0..4 {
                    out[j] += g * basis[j] * positive_weight_derivative(params[j]);
                }
            }
            Ok(out)
        })())
    }
}

/// One free weight per control point but the first: w_0 = 1, w_i = e^{p_{i−1}} (clamped) for
/// i = 1..n. `control_points − 1` parameters.
///
/// Weights matter only up to a common factor (scaling all of them leaves the NURBS curve
/// unchanged), so one weight can be fixed without losing any curve: fixing w_0 removes exactly
/// that redundant direction. Fixing both end weights, as is sometimes done, would also remove a
/// real degree of freedom (the ratio w_n/w_0 changes the curve), so only the first is held.
///
/// Cost O(n) per evaluation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PerPoint;

impl WeightLaw for PerPoint {
    fn name(&self) -> &str {
        "per-point"
    }

    fn parameter_count(&self, control_points: usize) -> usize {
        control_points.saturating_sub(1)
    }

    fn parameter_names(&self, control_points: usize) -> Vec<String> {
        (1..control_points).map(|i| format!("ln w{i}")).collect()
    }

    fn weights(&self, params: &[f64], control_points: usize) -> Result<Vec<f64>> {
        check_parameters(self.parameter_count(control_points), params)?;
        if control_points == 0 {
            return Ok(Vec::new());
        }
        let mut weights = Vec::with_capacity(control_points);
        weights.push(1.0);
        weights.extend(params.iter().map(|p| positive_weight(*p)));
        Ok(weights)
    }

    fn identity_params(&self, control_points: usize) -> Vec<f64> {
        vec![0.0; self.parameter_count(control_points)]
    }

    /// ∂w_i/∂p_{i−1} = e^{p_{i−1}} inside the clamp, 0 beyond; w_0 is fixed. O(n).
    fn pull_back(
        &self,
        params: &[f64],
        control_points: usize,
        weight_gradient: &[f64],
    ) -> Option<Result<Vec<f64>>> {
        Some((|| {
            check_parameters(self.parameter_count(control_points), params)?;
            check_gradient(control_points, weight_gradient)?;
            Ok(params
                .iter()
                .zip(weight_gradient.iter().skip(1))
                .map(|(p, g)| g * positive_weight_derivative(*p))
                .collect())
        })())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The paper's law by de Casteljau's algorithm (independent of the Bernstein sum above).
    fn de_casteljau(k: [f64; 4], s: f64) -> f64 {
        let mut b = k.to_vec();
        while b.len() > 1 {
            b = b.windows(2).map(|w| (1.0 - s) * w[0] + s * w[1]).collect();
        }
        b[0]
    }

    fn laws() -> Vec<Box<dyn WeightLaw>> {
        vec![Box::new(CubicBernstein), Box::new(PerPoint)]
    }

    #[test]
    fn pull_back_is_the_transposed_jacobian_by_differences() {
        let n = 9;
        let g: Vec<f64> = (0..n).map(|i| (i as f64 * 1.3).cos()).collect();
        let cases: Vec<(Box<dyn WeightLaw>, Vec<f64>)> = vec![
            (Box::new(CubicBernstein), vec![0.2, -0.4, 0.7, 0.1]),
            (Box::new(PerPoint), (1..n).map(|i| 0.1 * i as f64 - 0.3).collect()),
        ];
        for (law, params) in cases {
            let pulled = law.pull_back(&params, n, &g).unwrap().unwrap();
            for (j, value) in pulled.iter().enumerate() {
                let h = 1e-6;
                let (mut plus, mut minus) = (params.clone(), params.clone());
                plus[j] += h;
                minus[j] -= h;
                let (wp, wm) = (law.weights(&plus, n).unwrap(), law.weights(&minus, n).unwrap());
                let fd: f64 = (0..n).map(|i| g[i] * (wp[i] - wm[i]) / (2.0 * h)).sum();
                assert!((value - fd).abs() < 1e-8, "{} p{j}: {value} vs {fd}", law.name());
            }
            assert!(law.pull_back(&params, n, &g[1..]).unwrap().is_err());
        }
        // beyond the clamp the law is flat
        let flat = PerPoint
            .pull_back(&[8.0, 0.0], 3, &[1.0, 1.0, 1.0])
            .unwrap()
            .unwrap();
        assert_eq!(flat, vec![0.0, 1.0]);
    }

    #[test]
    fn identity_params_give_unit_weights() {
        for law in laws() {
            for n in [0, 1, 2, 4, 7, 30] {
                let params = law.identity_params(n);
                assert_eq!(params.len(), law.parameter_count(n), "{}", law.name());
                let weights = law.weights(&params, n).unwrap();
                assert_eq!(weights.len(), n);
                for w in weights {
                    assert!((w - 1.0).abs() < 1e-15, "{}: {w}", law.name());
                }
            }
        }
    }

    #[test]
    fn cubic_bernstein_is_the_papers_law() {
        let params = [0.3, -1.2, 0.8, 0.1];
        let k = params.map(f64::exp);
        let n_ctrl = 9;
        let weights = CubicBernstein.weights(&params, n_ctrl).unwrap();
        for (i, w) in weights.iter().enumerate() {
            let expected = de_casteljau(k, i as f64 / (n_ctrl - 1) as f64);
            assert!((w - expected).abs() < 1e-14 * expected, "{i}: {w} vs {expected}");
        }
        // End-point interpolation of a Bézier function: w_0 = k_0, w_n = k_3.
        assert!((weights[0] - k[0]).abs() < 1e-15);
        assert!((weights[n_ctrl - 1] - k[3]).abs() < 1e-15);
    }

    #[test]
    fn bad_parameters_are_errors() {
        for law in laws() {
            let n = 6;
            let count = law.parameter_count(n);
            assert!(matches!(
                law.weights(&vec![0.0; count + 1], n),
                Err(Error::LengthMismatch { .. })
            ));
            let mut params = vec![0.0; count];
            params[count - 1] = f64::NAN;
            assert!(matches!(law.weights(&params, n), Err(Error::NonFinite { .. })));
            params[count - 1] = f64::INFINITY;
            assert!(matches!(law.weights(&params, n), Err(Error::NonFinite { .. })));
        }
    }

    #[test]
    fn descriptions_name_every_parameter() {
        for law in laws() {
            let description = law.describe(5);
            assert_eq!(description.parameters.len(), law.parameter_count(5));
            assert_eq!(description.name, law.name());
        }
        assert_eq!(PerPoint.describe(3).parameters, vec!["ln w1", "ln w2"]);
    }

    #[test]
    fn per_point_holds_the_first_weight() {
        let weights = PerPoint.weights(&[1.0, -2.0], 3).unwrap();
        assert_eq!(weights[0], 1.0);
        assert!((weights[1] - 1f64.exp()).abs() < 1e-15);
        assert!((weights[2] - (-2f64).exp()).abs() < 1e-15);
    }

    fn any_param() -> impl Strategy<Value = f64> {
        prop_oneof![
            -50.0..50.0f64,
            -1e308..1e308f64,
            Just(f64::MAX),
            Just(f64::MIN),
            Just(-f64::MIN_POSITIVE),
        ]
    }

    proptest! {
        #[test]
        fn cubic_bernstein_weights_are_positive_and_bounded(
            params in proptest::collection::vec(any_param(), 4),
            n_ctrl in 0usize..40,
        ) {
            let weights = CubicBernstein.weights(&params, n_ctrl).unwrap();
            prop_assert_eq!(weights.len(), n_ctrl);
            let k = CubicBernstein.coefficients(&params).unwrap();
            let (lo, hi) = k.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), k| (lo.min(*k), hi.max(*k)));
            for w in weights {
                prop_assert!(w.is_finite() && w > 0.0, "{}", w);
                // Convex hull of the Bernstein coefficients, with round-off room.
                prop_assert!(w >= lo * (1.0 - 1e-12) && w <= hi * (1.0 + 1e-12), "{} not in [{}, {}]", w, lo, hi);
                prop_assert!(w >= (-MAX_LOG_WEIGHT).exp() * (1.0 - 1e-12));
                prop_assert!(w <= MAX_LOG_WEIGHT.exp() * (1.0 + 1e-12));
            }
        }

        #[test]
        fn per_point_weights_are_positive_and_bounded(
            params in proptest::collection::vec(any_param(), 0..40),
        ) {
            let n_ctrl = params.len() + 1;
            let weights = PerPoint.weights(&params, n_ctrl).unwrap();
            prop_assert_eq!(weights.len(), n_ctrl);
            for w in weights {
                prop_assert!(w.is_finite() && w > 0.0, "{}", w);
                prop_assert!(w >= (-MAX_LOG_WEIGHT).exp() && w <= MAX_LOG_WEIGHT.exp());
            }
        }
    }
}
