//! `strain-energy`, and its presets `kjellander` (uniform knots) and `poliakoff` (chord
//! length): Zhang–Cheng strain-energy point replacement ([`StrainEnergy`]; Zhang, Zhang &
//! Cheng, CAD 2001, §2–3). Without bad points the automatic algorithm (§3.3 algorithm 2);
//! with them (`--points`) the interactive one (algorithm 1).

use curve_repr::{HermiteSettings, HermiteSpline, Vector};
use fairness::curvature::CurvatureForm;

use super::{hermite_json, indicator_for};
use crate::catalog::{run_strategy, CurveJob, CurveMethod, CurvePoints, CurveRun, Settings};
use crate::strategies::{Mode, StrainEnergy, StrainEnergySettings};
use crate::{Error, FairingStrategy, Refusal, Result};

impl Settings for StrainEnergySettings {
    fn validate(&self) -> Result<()> {
        StrainEnergySettings::validate(self)
    }
}

/// The `strain-energy` method (and its presets).
#[derive(Clone, Copy, Debug, Default)]
pub struct StrainEnergyMethod;

impl CurveMethod for StrainEnergyMethod {
    type Settings = StrainEnergySettings;

    fn takes_bad_points(&self) -> bool {
        true
    }

    /// Bad points must be interior points; the indicator must be registered for the
    /// points' dimension; end clamps above g0 are refused (the natural spline's end tangent
    /// follows the interior points).
    fn check(&self, settings: &StrainEnergySettings, job: &CurveJob) -> Result<()> {
        let n = job.points.len();
        if let Some(k) = job.bad_points.iter().find(|&&k| k == 0 || k + 1 >= n) {
            return Err(Error::Refused {
                method: job.method.to_owned(),
                what: Refusal::BadPoints,
                reason: format!(
                    "replaces interior points only (1 to {}); point {k} is an end point",
                    n.saturating_sub(2)
                ),
            });
        }
        match job.points {
            CurvePoints::Planar(_) => self.strategy::<2>(settings, job)?.supports(job.constraints),
            CurvePoints::Spatial(_) => self.strategy::<3>(settings, job)?.supports(job.constraints),
        }
    }

    fn run(&self, settings: &StrainEnergySettings, job: &CurveJob) -> Result<CurveRun> {
        match job.points {
            CurvePoints::Planar(p) => self.run_points(settings, job, p),
            CurvePoints::Spatial(p) => self.run_points(settings, job, p),
        }
    }
}

impl StrainEnergyMethod {
    fn settings(settings: &StrainEnergySettings, job: &CurveJob) -> StrainEnergySettings {
        let mut settings = settings.clone();
        if !job.bad_points.is_empty() {
            settings.mode = Mode::Interactive(job.bad_points.to_vec());
        }
        settings
    }

    fn strategy<const D: usize>(
        &self,
        settings: &StrainEnergySettings,
        job: &CurveJob,
    ) -> Result<StrainEnergy<D>>
    where
        Vector<D>: CurvatureForm,
    {
        let mut strategy = StrainEnergy::<D>::new(Self::settings(settings, job));
        if settings.indicator != StrainEnergySettings::PAPER_INDICATOR {
            strategy = strategy.with_indicator(indicator_for::<D>(job, &settings.indicator)?);
        }
        Ok(strategy)
    }

    fn run_points<const D: usize>(
        &self,
        settings: &StrainEnergySettings,
        job: &CurveJob,
        points: &[Vector<D>],
    ) -> Result<CurveRun>
    where
        Vector<D>: CurvatureForm,
    {
        let strategy = self.strategy::<D>(settings, job)?;
        let mut run = run_strategy(Box::new(strategy), points, job, settings.max_iterations)?;
        let mode = if job.bad_points.is_empty() {
            "automatic"
        } else {
            "interactive"
        };
        run.extras.insert("mode".into(), mode.into());
        let parametrization = serde_json::to_value(settings.parametrization).unwrap_or_default();
        run.extras
            .insert("parametrization".into(), parametrization.clone());
        // The strain energy ∫|C''|² of the natural spline at the ORIGINAL points' knots (the
        // knots are fixed while fairing), before and after: the quantity the method lowers.
        let knots = settings.parametrization.parameters(points).map_err(Error::from)?;
        let spline_at = |p: &[Vector<D>]| {
            HermiteSpline::new(p, &HermiteSettings::new().with_parameters(knots.clone())).map_err(Error::from)
        };
        let faired: &[Vector<D>] = run.points.as_dimension::<D>().unwrap_or(&[]);
        let (before, after) = (spline_at(points)?, spline_at(faired)?);
        run.extras
            .insert("strain_energy_before".into(), before.strain_energy().into());
        run.extras
            .insert("strain_energy_after".into(), after.strain_energy().into());
        run.curve = hermite_json(&after, parametrization.as_str().unwrap_or("chord-length"));
        Ok(run)
    }
}
