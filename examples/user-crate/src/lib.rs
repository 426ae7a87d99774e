//! A user's methods outside the project's workspace: a strategy `laplacian` and a criterion
//! `turning-angle`, registered into the built-in catalogue.

use curve_repr::{Curve, Side};
use fairing::catalog::{Catalog, CriterionEntry, CurveJob, MethodInfo, StrategySettings};
use fairing::{FairingState, FairingStrategy, Result, StepOutcome};

fairing::settings! {
    /// Laplacian smoothing: every free interior point a fraction of the way to its
    /// neighbours' midpoint, a number of passes.
    pub struct Laplacian {
        /// How far towards the midpoint per pass.
        pub factor: f64 = 0.5,
        /// Passes over the points.
        pub max_passes: usize = 10,
    }
}

impl StrategySettings for Laplacian {
    fn strategy<const D: usize>(&self, _: &CurveJob) -> Result<Box<dyn FairingStrategy<D>>> {
        Ok(Box::new(self.clone()))
    }
}

impl<const D: usize> FairingStrategy<D> for Laplacian {
    fn name(&self) -> &str {
        "laplacian"
    }
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        for i in 1..state.len().saturating_sub(1) {
            let p = state.points();
            let target = p[i] + ((p[i - 1] + p[i + 1]) / 2.0 - p[i]) * self.factor;
            if state.is_movable(i) {
                state.move_point(i, target)?;
            }
        }
        self.max_passes = self.max_passes.saturating_sub(1);
        Ok(if self.max_passes == 0 {
            StepOutcome::done(None)
        } else {
            StepOutcome::running(None)
        })
    }
}

/// The total turning of the tangent at the curve's breaks, in radians.
pub struct TurningAngle;

impl<const D: usize> fairness::Criterion<dyn Curve<D>> for TurningAngle {
    fn name(&self) -> &str {
        "turning-angle"
    }
    fn evaluate(&self, curve: &dyn Curve<D>) -> fairness::Result<f64> {
        let tangents: Vec<_> = curve
            .breaks()
            .iter()
            .map(|&t| curve.jet(t, Side::Right)[1])
            .collect();
        Ok(tangents
            .windows(2)
            .map(|w| {
                (w[0].dot(&w[1]) / (w[0].norm() * w[1].norm()))
                    .clamp(-1.0, 1.0)
                    .acos()
            })
            .filter(|a| a.is_finite())
            .sum())
    }
}

/// The built-ins and the two methods above.
pub fn catalog() -> Catalog {
    let mut catalog = Catalog::builtin();
    catalog.register_strategy::<Laplacian>(MethodInfo::new("laplacian", "Laplacian smoothing"));
    catalog.register_criterion(CriterionEntry::of(TurningAngle, "total tangent turning at the breaks"));
    catalog
}
