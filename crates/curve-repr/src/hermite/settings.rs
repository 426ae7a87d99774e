//! Construction settings of a [`HermiteSpline`](super::HermiteSpline).

use super::HermiteEnds;
use crate::{Parametrization, Vector};

/// How to build a [`HermiteSpline`](super::HermiteSpline): parameters and end condition.
///
/// The default is the curve of Zhang–Cheng §2 and of the `fair` report: chord-length
/// parameters and natural (free) ends.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HermiteSettings<const D: usize> {
    /// The rule that assigns parameters, used unless [`parameters`](Self::parameters) is set.
    pub parametrization: Parametrization,
    /// Explicit parameters t_i, strictly increasing: one per point for an open curve, one
    /// more than the points for a closed one (the last is that of P_0 reached again).
    /// Fairing keeps the knots fixed while it moves points; Okada and Kjellander need
    /// uniform ones.
    pub parameters: Option<Vec<f64>>,
    /// The end condition.
    pub ends: HermiteEnds<D>,
}

impl<const D: usize> HermiteSettings<D> {
    /// The default settings: chord length, natural ends.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the parametrization (and clears explicit parameters).
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self.parameters = None;
        self
    }

    /// Sets explicit parameters, which take precedence over the parametrization.
    pub fn with_parameters(mut self, parameters: Vec<f64>) -> Self {
        self.parameters = Some(parameters);
        self
    }

    /// Sets the end condition.
    pub fn with_ends(mut self, ends: HermiteEnds<D>) -> Self {
        self.ends = ends;
        self
    }

    /// Shorthand for `with_ends(HermiteEnds::Clamped { start, end })`.
    pub fn with_clamped_ends(self, start: Vector<D>, end: Vector<D>) -> Self {
        self.with_ends(HermiteEnds::Clamped { start, end })
    }
}
