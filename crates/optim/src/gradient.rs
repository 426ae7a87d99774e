//! A smooth criterion of the interpolating NURBS as a function of its weights, with its
//! exact gradient by forward-mode dual numbers.
//!
//! Nowacki et al.'s weight problem (FAIRSHAPE 1996, §3) measures the NURBS through the data
//! re-solved with the trial weights w. Its homogeneous control points Q(w) = w_i P_i solve a
//! weight-independent collocation system with a right-hand side linear in w
//! ([`Interpolation::homogeneous_points`]), so Q is linear in w and its derivative along the
//! i-th weight is Q(e_i), one O(n) solve computed once. Seeding w_i + ε and Q + ε Q(e_i) as
//! [`Dual`] numbers and running the generic evaluation ([`RationalCurve`]) through the
//! fixed-rule energy ([`fairness::fixed_rule`]) gives ∂E/∂w_i exactly (to round-off): one
//! dual evaluation per weight, O(n · spans · m · p²) for the whole gradient.

use curve_repr::nurbs_curve::RationalCurve;
use curve_repr::{Interpolation, Vector};
use fairness::fixed_rule::{self, FixedRule};
use num_traits::Float;

use crate::dual::Dual;
use crate::error::{Error, Result};

/// The criteria with a fixed-rule, differentiable form.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SmoothCriterion {
    /// Ek = ∫ κ² ds ([`fixed_rule::ek`]).
    Ek,
    /// E2 = ∫ |C″|² dt ([`fixed_rule::e2`]).
    E2,
}

impl SmoothCriterion {
    /// The smooth form of the criterion named `name` ("ek", "e2"), if it has one.
    pub fn from_name(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().as_str() {
            "ek" => Some(SmoothCriterion::Ek),
            "e2" => Some(SmoothCriterion::E2),
            _ => None,
        }
    }

    /// The criterion of `curve` with `rule` on every knot span.
    pub fn evaluate<T: Float, const D: usize>(self, curve: &RationalCurve<T, D>, rule: &FixedRule) -> T {
        match self {
            SmoothCriterion::Ek => fixed_rule::ek(curve, rule),
            SmoothCriterion::E2 => fixed_rule::e2(curve, rule),
        }
    }
}

/// A [`SmoothCriterion`] of the curve of an [`Interpolation`] as a function of its weights:
/// value ([`value`](Self::value)) and exact gradient ([`value_and_gradient`](Self::value_and_gradient)).
#[derive(Clone, Debug)]
pub struct InterpolantCriterion<'a, const D: usize> {
    interpolation: &'a Interpolation<D>,
    criterion: SmoothCriterion,
    rule: FixedRule,
    /// Q(e_i), the derivative of the homogeneous points along weight i.
    directions: Vec<Vec<Vector<D>>>,
}

impl<'a, const D: usize> InterpolantCriterion<'a, D> {
    /// `criterion` of the curves of `interpolation`, integrated with `rule`. Solves for the n
    /// directions Q(e_i) once: O(n² p) time, n² D numbers of memory.
    pub fn new(
        interpolation: &'a Interpolation<D>,
        criterion: SmoothCriterion,
        rule: FixedRule,
    ) -> Result<Self> {
        let n = interpolation.control_count();
        let directions = (0..n)
            .map(|i| {
                let mut e = vec![0.0; n];
                e[i] = 1.0;
                interpolation.homogeneous_points(&e)
            })
            .collect::<curve_repr::Result<Vec<_>>>()?;
        Ok(InterpolantCriterion {
            interpolation,
            criterion,
            rule,
            directions,
        })
    }

    /// The criterion.
    pub fn criterion(&self) -> SmoothCriterion {
        self.criterion
    }

    /// The curve with `weights` over f64: homogeneous points and weights. Fails on a weight
    /// that is not finite and positive or a failed solve.
    fn homogeneous(&self, weights: &[f64]) -> Result<Vec<Vector<D>>> {
        if let Some(index) = weights.iter().position(|w| !(*w > 0.0 && w.is_finite())) {
            return Err(Error::objective(format!("weight {index} is {}", weights[index])));
        }
        Ok(self.interpolation.homogeneous_points(weights)?)
    }

    /// The criterion of the interpolant with `weights`. O(spans · m · p²) after one O(n p) solve.
    pub fn value(&self, weights: &[f64]) -> Result<f64> {
        let q = self.homogeneous(weights)?;
        let curve = RationalCurve::<f64, D>::new(
            self.interpolation.knot_vector().clone(),
            q.iter().map(|v| (*v).into()).collect(),
            weights.to_vec(),
        )?;
        finite(self.criterion.evaluate(&curve, &self.rule))
    }

    /// The criterion and its gradient with respect to every weight: one [`Dual`] evaluation
    /// per weight. O(n · spans · m · p²).
    pub fn value_and_gradient(&self, weights: &[f64]) -> Result<(f64, Vec<f64>)> {
        let q = self.homogeneous(weights)?;
        let knots = self.interpolation.knot_vector();
        let value = self.value(weights)?;
        let mut gradient = Vec::with_capacity(weights.len());
        for (i, direction) in self.directions.iter().enumerate() {
            let weighted: Vec<[Dual; D]> = q
                .iter()
                .zip(direction)
                .map(|(v, d)| std::array::from_fn(|c| Dual::new(v[c], d[c])))
                .collect();
            let seeded: Vec<Dual> = weights
                .iter()
                .enumerate()
                .map(|(j, &w)| Dual::new(w, if i == j { 1.0 } else { 0.0 }))
                .collect();
            let curve = RationalCurve::new(knots.clone(), weighted, seeded)?;
            gradient.push(finite(self.criterion.evaluate(&curve, &self.rule).derivative())?);
        }
        Ok((value, gradient))
    }
}

fn finite(value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::objective(format!("the smooth criterion is {value}")))
    }
}
