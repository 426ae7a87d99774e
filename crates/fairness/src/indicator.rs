//! The two traits of the second axis: how unfairness is measured.
//!
//! - [`LocalIndicator`]: one value per data point or knot (the x–c polyline's e_i, the
//!   third-derivative jump z_i of Zhang–Cheng Eq. 17, Sapidis–Farin's curvature-slope jump).
//!   Fairing strategies use them to find the bad points.
//! - [`Criterion`]: one number, the smaller the fairer (the energies E1, E2, E3, Ek, Ek′ of
//!   Nowacki et al., the strain energy). Optimisers minimise them.
//!
//! Both are generic over the representation `R` they measure and object safe, so that a
//! strategy can hold `Box<dyn Criterion<NurbsCurve<2>>>` chosen at run time (e.g. by
//! `--set criterion=ek`), and `R` may be unsized (`dyn Curve<2>`).
//!
//! Adding a criterion takes a few lines, either as a type or from a closure:
//!
//! ```
//! use curve_repr::{Curve, Side};
//! use fairness::{Criterion, FnCriterion, Result};
//!
//! /// The squared distance between the curve's end points (a made-up criterion).
//! struct EndGap;
//!
//! impl<C: Curve<2> + ?Sized> Criterion<C> for EndGap {
//!     fn name(&self) -> &str {
//!         "end-gap"
//!     }
//!     fn evaluate(&self, curve: &C) -> Result<f64> {
//!         let (a, b) = curve.domain();
//!         Ok((curve.eval(b) - curve.eval(a)).norm_squared())
//!     }
//! }
//!
//! // The same from a closure, boxed for a run-time choice.
//! let start_height: Box<dyn Criterion<dyn Curve<2>>> =
//!     Box::new(FnCriterion::<dyn Curve<2>, _>::new("start-height", |c| {
//!         Ok(c.jet(c.domain().0, Side::Right)[0].y)
//!     }));
//! # let _ = start_height;
//! ```

use std::marker::PhantomData;

use crate::Result;

/// A value per data point or knot, measuring how unfair the representation is there.
///
/// Which points get a value (all data points, interior knots only) is documented by each
/// implementation; the values are finite or the call fails.
pub trait LocalIndicator<R: ?Sized> {
    /// A short kebab-case name (for reports and `--set` options).
    fn name(&self) -> &str;

    /// The values, in the order of the points they belong to.
    fn values(&self, representation: &R) -> Result<Vec<f64>>;

    /// The largest value, or 0 when there is none (the report's `max_z`).
    fn max_value(&self, representation: &R) -> Result<f64> {
        Ok(self.values(representation)?.into_iter().fold(0.0, f64::max))
    }
}

/// A single number measuring the unfairness of the representation: smaller is fairer.
///
/// The value is finite or the call fails, so that an optimiser never sees NaN.
pub trait Criterion<R: ?Sized> {
    /// A short kebab-case name (for reports and `--set criterion=...`).
    fn name(&self) -> &str;

    /// The criterion's value.
    fn evaluate(&self, representation: &R) -> Result<f64>;
}

impl<R: ?Sized, T: LocalIndicator<R> + ?Sized> LocalIndicator<R> for Box<T> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn values(&self, representation: &R) -> Result<Vec<f64>> {
        (**self).values(representation)
    }
}

impl<R: ?Sized, T: LocalIndicator<R> + ?Sized> LocalIndicator<R> for &T {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn values(&self, representation: &R) -> Result<Vec<f64>> {
        (**self).values(representation)
    }
}

impl<R: ?Sized, T: Criterion<R> + ?Sized> Criterion<R> for Box<T> {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn evaluate(&self, representation: &R) -> Result<f64> {
        (**self).evaluate(representation)
    }
}

impl<R: ?Sized, T: Criterion<R> + ?Sized> Criterion<R> for &T {
    fn name(&self) -> &str {
        (**self).name()
    }
    fn evaluate(&self, representation: &R) -> Result<f64> {
        (**self).evaluate(representation)
    }
}

/// A [`Criterion`] over `R` made of a name and a closure.
///
/// `R` is a type parameter (not inferred from the closure alone) so that the closure's
/// argument type comes from it: write `FnCriterion::<dyn Curve<2>, _>::new(...)` for a
/// criterion over any planar curve. The closure's result is checked: a non-finite value
/// becomes [`Error::NonFinite`](crate::Error::NonFinite).
pub struct FnCriterion<R: ?Sized, F> {
    name: String,
    function: F,
    representation: PhantomData<fn(&R)>,
}

impl<R: ?Sized, F: Fn(&R) -> Result<f64>> FnCriterion<R, F> {
    /// A criterion called `name` that evaluates `function`.
    pub fn new(name: impl Into<String>, function: F) -> Self {
        FnCriterion {
            name: name.into(),
            function,
            representation: PhantomData,
        }
    }
}

impl<R: ?Sized, F: Fn(&R) -> Result<f64>> Criterion<R> for FnCriterion<R, F> {
    fn name(&self) -> &str {
        &self.name
    }
    fn evaluate(&self, representation: &R) -> Result<f64> {
        let value = (self.function)(representation)?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(crate::Error::NonFinite {
                what: "criterion value",
                parameter: f64::NAN,
            })
        }
    }
}

impl<R: ?Sized, F> std::fmt::Debug for FnCriterion<R, F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FnCriterion").field("name", &self.name).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Len;
    impl Criterion<[f64]> for Len {
        fn name(&self) -> &str {
            "len"
        }
        fn evaluate(&self, r: &[f64]) -> Result<f64> {
            Ok(r.len() as f64)
        }
    }

    #[test]
    fn boxed_and_borrowed_criteria_forward() {
        let boxed: Vec<Box<dyn Criterion<[f64]>>> = vec![
            Box::new(Len),
            Box::new(FnCriterion::<[f64], _>::new("sum", |r| Ok(r.iter().sum()))),
        ];
        let data = [1.0, 2.0, 4.0];
        let values: Vec<f64> = boxed.iter().map(|c| c.evaluate(&data[..]).unwrap()).collect();
        assert_eq!(values, vec![3.0, 7.0]);
        assert_eq!(boxed[1].name(), "sum");
    }

    #[test]
    fn closure_returning_nan_is_an_error() {
        let c = FnCriterion::<[f64], _>::new("nan", |_| Ok(f64::NAN));
        assert!(matches!(c.evaluate(&[][..]), Err(crate::Error::NonFinite { .. })));
    }
}
