//! argmin adapters for fairing: Nelder–Mead minimisation, weight laws for rational curves, and
//! the generic weight problem that Nowacki et al.'s NURBS weight fairing is an instance of.
//!
//! Nowacki, Liu & Lü, "Experiences in curve fairing" (FAIRSHAPE 1996), §3: an interpolating
//! cubic NUBS is rewritten as a NURBS with unit weights; its weights are then constrained to a
//! cubic Bernstein law of four parameters k0..k3 and chosen by the Nelder–Mead simplex method to
//! minimise a fairness criterion (E1, E2, E3, Ek, ...).
//!
//! - [`nelder_mead`]: [`minimize`] an [`Objective`] over `Vec<f64>` parameters.
//! - [`weight_law`]: [`WeightLaw`]s mapping parameters to positive weights
//!   ([`CubicBernstein`], [`PerPoint`], or your own).
//! - [`problem`]: [`WeightProblem`], a law plus a criterion of the weights, solved by Nelder–Mead.
//! - [`cancel`]: a [`Cancel`] token and the [`checkpoint`] the searches here (and the fairing
//!   strategies above) call, so that a caller can stop a long run.
//!
//! The crate hides argmin's types and `anyhow` errors behind its own [`Error`].

pub mod cancel;
pub mod dual;
pub mod error;
pub mod gradient;
pub mod lbfgs;
pub mod nelder_mead;
pub mod nurbs_weights;
pub mod problem;
pub mod weight_law;

pub use cancel::{checkpoint, Cancel, Cancelled};
pub use dual::Dual;
pub use error::{Error, Result};
pub use gradient::{InterpolantCriterion, SmoothCriterion};
pub use lbfgs::{minimize_lbfgs, GradientObjective, LbfgsMinimum, LbfgsSettings};
pub use nelder_mead::{
    minimize, InitialSimplex, Minimum, NelderMeadSettings, Objective, Observer, Progress, Termination,
};
pub use nurbs_weights::{
    CriterionName, LawName, NurbsWeightFairing, NurbsWeightResult, NurbsWeightSettings, SolverName,
};
pub use problem::{WeightCriterion, WeightProblem, WeightSolution};
pub use weight_law::{CubicBernstein, LawDescription, PerPoint, WeightLaw};
