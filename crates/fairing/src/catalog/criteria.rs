//! Criteria and local indicators by name: the entries of the catalogue that reports list
//! (`before.criteria`, `after.criteria`) and that methods choose (`--set criterion=…`,
//! `--set indicator=…`).
//!
//! Both are evaluated on curves behind the [`Curve`] trait object, so one entry applies to
//! every representation: the spline the report measures, a method's NURBS, a user's own
//! curve type. An entry holds an implementation per dimension it applies to.

use std::any::Any;
use std::collections::BTreeMap;
use std::sync::Arc;

use curve_repr::{Curve, EndCondition, HermiteSpline, Side, SplineFunction, Vector};
use fairness::curvature::{curvature_slope_at, CurvatureForm};
use fairness::{Criterion, Ek, EkPrime, Energies, EnergyName, LocalIndicator, MeasuredEnergies, E1, E2, E3};

use super::job::{AnyCurve, CurveKind, CurvePoints};
use crate::{Error, Result};

/// A criterion over any curve of dimension `D`, shareable between threads.
pub type SharedCriterion<const D: usize> = Arc<dyn Criterion<dyn Curve<D>> + Send + Sync>;

/// A local indicator over any curve of dimension `D` (one value per break of the curve),
/// shareable between threads and cloneable, as strategies hold it.
#[derive(Clone)]
pub struct SharedIndicator<const D: usize>(pub Arc<dyn LocalIndicator<dyn Curve<D>> + Send + Sync>);

impl<const D: usize> SharedIndicator<D> {
    /// Shares `indicator`.
    pub fn new(indicator: impl LocalIndicator<dyn Curve<D>> + Send + Sync + 'static) -> Self {
        SharedIndicator(Arc::new(indicator))
    }
}

impl<const D: usize> LocalIndicator<dyn Curve<D>> for SharedIndicator<D> {
    fn name(&self) -> &str {
        self.0.name()
    }
    fn values(&self, curve: &(dyn Curve<D> + 'static)) -> fairness::Result<Vec<f64>> {
        self.0.values(curve)
    }
}

impl<const D: usize> std::fmt::Debug for SharedIndicator<D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SharedIndicator({})", self.0.name())
    }
}

/// A [`SharedCriterion`] used as a criterion of a concrete representation `R` (a
/// `NurbsCurve<D>` in the weight search, say).
pub struct OnCurve<const D: usize>(pub SharedCriterion<D>);

impl<const D: usize, R: Curve<D> + 'static> Criterion<R> for OnCurve<D> {
    fn name(&self) -> &str {
        self.0.name()
    }
    fn evaluate(&self, curve: &R) -> fairness::Result<f64> {
        self.0.evaluate(curve as &dyn Curve<D>)
    }
}

/// One criterion of the catalogue: a name, a one-line summary and an implementation for
/// planar and/or spatial curves.
///
/// ```
/// use fairing::catalog::CriterionEntry;
/// use fairness::{E2, Criterion};
/// let entry = CriterionEntry::new("e2", "∫|C''|² dt").planar(E2::<2>::new()).spatial(E2::<3>::new());
/// assert!(entry.applies_to(2) && entry.applies_to(3));
/// ```
#[derive(Clone)]
pub struct CriterionEntry {
    name: String,
    summary: String,
    planar: Option<SharedCriterion<2>>,
    spatial: Option<SharedCriterion<3>>,
    energy: Option<EnergyName>,
}

impl CriterionEntry {
    /// An entry without implementations yet (add them with [`planar`](Self::planar) and
    /// [`spatial`](Self::spatial)).
    pub fn new(name: impl Into<String>, summary: impl Into<String>) -> Self {
        CriterionEntry {
            name: name.into(),
            summary: summary.into(),
            planar: None,
            spatial: None,
            energy: None,
        }
    }

    /// An entry for a criterion of both dimensions, under the criterion's own
    /// [`name`](Criterion::name) (one name: the trait's is the catalogue's).
    ///
    /// ```
    /// use curve_repr::Curve;
    /// use fairing::catalog::CriterionEntry;
    ///
    /// /// The parameter span of the curve.
    /// struct Span;
    /// impl<const D: usize> fairness::Criterion<dyn Curve<D>> for Span {
    ///     fn name(&self) -> &str {
    ///         "span"
    ///     }
    ///     fn evaluate(&self, curve: &dyn Curve<D>) -> fairness::Result<f64> {
    ///         let (a, b) = curve.domain();
    ///         Ok(b - a)
    ///     }
    /// }
    ///
    /// let entry = CriterionEntry::of(Span, "the parameter span");
    /// assert_eq!(entry.name(), "span");
    /// assert!(entry.applies_to(2) && entry.applies_to(3));
    /// ```
    pub fn of<C>(criterion: C, summary: impl Into<String>) -> Self
    where
        C: Criterion<dyn Curve<2>> + Criterion<dyn Curve<3>> + Send + Sync + 'static,
    {
        let name = Criterion::<dyn Curve<2>>::name(&criterion).to_owned();
        let shared = Arc::new(criterion);
        CriterionEntry {
            planar: Some(shared.clone()),
            spatial: Some(shared),
            ..CriterionEntry::new(name, summary)
        }
    }

    /// The name of the first implementation that does not answer to the entry's name, if any
    /// (what [`Catalog::register_criterion`](super::Catalog::register_criterion) checks).
    pub(crate) fn other_name(&self) -> Option<String> {
        let planar = self.planar.as_ref().map(|c| c.name().to_owned());
        let spatial = self.spatial.as_ref().map(|c| c.name().to_owned());
        [planar, spatial].into_iter().flatten().find(|n| *n != self.name)
    }

    /// Says that the entry's value is the energy `name` of [`fairness::Energies`], so that a
    /// report that has measured a curve's energies takes the value from them instead of
    /// integrating again ([`evaluate_with`](Self::evaluate_with)). The built-in `e1` … `ek-prime`
    /// say it; an entry registered under their name by a user does not, and is evaluated.
    pub fn same_as_energy(mut self, name: EnergyName) -> Self {
        self.energy = Some(name);
        self
    }

    /// The energy the entry's value is, if it is one ([`same_as_energy`](Self::same_as_energy)).
    pub fn energy(&self) -> Option<EnergyName> {
        self.energy
    }

    /// Adds the implementation for planar curves.
    pub fn planar(mut self, criterion: impl Criterion<dyn Curve<2>> + Send + Sync + 'static) -> Self {
        self.planar = Some(Arc::new(criterion));
        self
    }

    /// Adds the implementation for spatial curves.
    pub fn spatial(mut self, criterion: impl Criterion<dyn Curve<3>> + Send + Sync + 'static) -> Self {
        self.spatial = Some(Arc::new(criterion));
        self
    }

    /// The name (`--set criterion=NAME`, the report's key).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// One line on what it measures.
    pub fn summary(&self) -> &str {
        &self.summary
    }

    /// Whether it has an implementation for curves of `dimension` (2 or 3).
    pub fn applies_to(&self, dimension: usize) -> bool {
        match dimension {
            2 => self.planar.is_some(),
            3 => self.spatial.is_some(),
            _ => false,
        }
    }

    /// The implementation for dimension `D`, if there is one.
    pub fn for_dimension<const D: usize>(&self) -> Option<SharedCriterion<D>> {
        let any: &dyn Any = match D {
            2 => &self.planar,
            3 => &self.spatial,
            _ => return None,
        };
        any.downcast_ref::<Option<SharedCriterion<D>>>()
            .and_then(Clone::clone)
    }

    /// The criterion's value on `curve`, or `None` when it does not apply to its dimension.
    pub fn evaluate(&self, curve: &AnyCurve) -> Option<Result<f64>> {
        match curve {
            AnyCurve::Planar(c) => self
                .planar
                .as_ref()
                .map(|k| Ok(k.evaluate(&**c as &dyn Curve<2>)?)),
            AnyCurve::Spatial(c) => self
                .spatial
                .as_ref()
                .map(|k| Ok(k.evaluate(&**c as &dyn Curve<3>)?)),
        }
    }
}

impl CriterionEntry {
    /// Whether the value on a curve whose energies are known (`energies_known`) needs the
    /// curve itself: false only for an entry that is one of the energies.
    pub fn needs_curve(&self, energies_known: bool) -> bool {
        !(energies_known && self.energy.is_some())
    }

    /// The criterion's value on the curve `curve` whose energies are `energies`: read from
    /// them when the entry is one of the energies ([`same_as_energy`](Self::same_as_energy)),
    /// else evaluated on `curve` (an error when it is not given). `None` when it does not
    /// apply to `dimension`. O(1) for an energy, the criterion's own cost otherwise.
    pub fn evaluate_with(
        &self,
        dimension: usize,
        energies: Option<&Energies>,
        curve: Option<&AnyCurve>,
    ) -> Option<Result<f64>> {
        if !self.applies_to(dimension) {
            return None;
        }
        match (self.energy, energies, curve) {
            (Some(name), Some(energies), _) => Some(Ok(energies.get(name))),
            (_, _, Some(curve)) => self.evaluate(curve),
            (_, _, None) => Some(Err(Error::Strategy {
                strategy: "measure".into(),
                reason: format!("criterion `{}` needs the curve, which was not given", self.name),
            })),
        }
    }
}

impl std::fmt::Debug for CriterionEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "CriterionEntry({})", self.name)
    }
}

/// One local indicator of the catalogue: a name, a one-line summary and an implementation for
/// planar and/or spatial curves, giving one value per break of the curve.
#[derive(Clone)]
pub struct IndicatorEntry {
    name: String,
    summary: String,
    planar: Option<SharedIndicator<2>>,
    spatial: Option<SharedIndicator<3>>,
}

impl IndicatorEntry {
    /// An entry without implementations yet.
    pub fn new(name: impl Into<String>, summary: impl Into<String>) -> Self {
        IndicatorEntry {
            name: name.into(),
            summary: summary.into(),
            planar: None,
            spatial: None,
        }
    }

    /// Adds the implementation for planar curves.
    pub fn planar(mut self, indicator: impl LocalIndicator<dyn Curve<2>> + Send + Sync + 'static) -> Self {
        self.planar = Some(SharedIndicator::new(indicator));
        self
    }

    /// Adds the implementation for spatial curves.
    pub fn spatial(mut self, indicator: impl LocalIndicator<dyn Curve<3>> + Send + Sync + 'static) -> Self {
        self.spatial = Some(SharedIndicator::new(indicator));
        self
    }

    /// The name (`--set indicator=NAME`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// One line on what it measures.
    pub fn summary(&self) -> &str {
        &self.summary
    }

    /// Whether it has an implementation for curves of `dimension`.
    pub fn applies_to(&self, dimension: usize) -> bool {
        match dimension {
            2 => self.planar.is_some(),
            3 => self.spatial.is_some(),
            _ => false,
        }
    }

    /// The implementation for dimension `D`, if there is one.
    pub fn for_dimension<const D: usize>(&self) -> Option<SharedIndicator<D>> {
        let any: &dyn Any = match D {
            2 => &self.planar,
            3 => &self.spatial,
            _ => return None,
        };
        any.downcast_ref::<Option<SharedIndicator<D>>>()
            .and_then(Clone::clone)
    }
}

impl std::fmt::Debug for IndicatorEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "IndicatorEntry({})", self.name)
    }
}

/// The third-derivative jump z_k = |C'''(t_k+) − C'''(t_k−)| at every break (Zhang–Cheng
/// Eq. 17), 0 at the two ends where no jump is defined. O(breaks).
#[derive(Clone, Copy, Debug, Default)]
pub struct ThirdDerivativeJump;

impl<const D: usize> LocalIndicator<dyn Curve<D>> for ThirdDerivativeJump {
    fn name(&self) -> &str {
        "third-derivative-jump"
    }
    fn values(&self, curve: &(dyn Curve<D> + 'static)) -> fairness::Result<Vec<f64>> {
        let breaks = curve.breaks();
        let last = breaks.len().saturating_sub(1);
        Ok(breaks
            .iter()
            .enumerate()
            .map(|(k, &t)| {
                if k == 0 || k == last {
                    0.0
                } else {
                    (curve.jet(t, Side::Right)[3] - curve.jet(t, Side::Left)[3]).norm()
                }
            })
            .collect())
    }
}

/// Sapidis–Farin's curvature-slope jump |dκ/ds(t+) − dκ/ds(t−)| at every break (Zhang–Cheng
/// Eq. 16), 0 at the two ends. Fails where the curvature slope is undefined (a zero tangent).
/// O(breaks).
#[derive(Clone, Copy, Debug, Default)]
pub struct CurvatureSlopeJump;

impl<const D: usize> LocalIndicator<dyn Curve<D>> for CurvatureSlopeJump
where
    Vector<D>: CurvatureForm,
{
    fn name(&self) -> &str {
        "curvature-slope-jump"
    }
    fn values(&self, curve: &(dyn Curve<D> + 'static)) -> fairness::Result<Vec<f64>> {
        let breaks = curve.breaks();
        let last = breaks.len().saturating_sub(1);
        let mut values = Vec::with_capacity(breaks.len());
        for (k, &t) in breaks.iter().enumerate() {
            if k == 0 || k == last {
                values.push(0.0);
            } else {
                let right = curvature_slope_at(curve, t, Side::Right)?;
                let left = curvature_slope_at(curve, t, Side::Left)?;
                values.push((right - left).abs());
            }
        }
        Ok(values)
    }
}

/// The built-in criteria: Nowacki's E1, E2, E3, Ek, Ek′ in both dimensions, each the same as
/// its energy of [`fairness::Energies`] (a report reads them from its `energies`).
pub fn builtin_criteria() -> Vec<CriterionEntry> {
    vec![
        CriterionEntry::new("e1", "∫|C'|² dt over the curve's own parameter (Nowacki et al.)")
            .planar(E1::<2>::new())
            .spatial(E1::<3>::new())
            .same_as_energy(EnergyName::E1),
        CriterionEntry::new("e2", "∫|C''|² dt, the strain energy (Nowacki et al.)")
            .planar(E2::<2>::new())
            .spatial(E2::<3>::new())
            .same_as_energy(EnergyName::E2),
        CriterionEntry::new("e3", "∫|C'''|² dt (Nowacki et al.)")
            .planar(E3::<2>::new())
            .spatial(E3::<3>::new())
            .same_as_energy(EnergyName::E3),
        CriterionEntry::new("ek", "∫κ² ds over arc length (Nowacki et al.)")
            .planar(Ek::<2>::new())
            .spatial(Ek::<3>::new())
            .same_as_energy(EnergyName::Ek),
        CriterionEntry::new("ek-prime", "∫(dκ/ds)² ds over arc length (Nowacki et al.)")
            .planar(EkPrime::<2>::new())
            .spatial(EkPrime::<3>::new())
            .same_as_energy(EnergyName::EkPrime),
    ]
}

/// The built-in indicators: the third-derivative jump and the curvature-slope jump.
pub fn builtin_indicators() -> Vec<IndicatorEntry> {
    vec![
        IndicatorEntry::new(
            "third-derivative-jump",
            "z_i = |C'''(t_i+) - C'''(t_i-)| at each knot (Zhang & Cheng Eq. 17)",
        )
        .planar(ThirdDerivativeJump)
        .spatial(ThirdDerivativeJump),
        IndicatorEntry::new(
            "curvature-slope-jump",
            "|dκ/ds(t_i+) - dκ/ds(t_i-)| at each knot (Sapidis & Farin; Zhang & Cheng Eq. 16)",
        )
        .planar(CurvatureSlopeJump)
        .spatial(CurvatureSlopeJump),
    ]
}

/// The spline the report measures (`docs/CONTRACT.md`'s definitions): for a function the spline
/// function y(x) with parabolic runout ends, for a parametric curve the natural cubic spline
/// with chord-length parameters. O(n).
pub fn measured_curve(kind: CurveKind, points: &CurvePoints) -> Result<AnyCurve> {
    let none = || Error::Strategy {
        strategy: "measure".into(),
        reason: "points of an unsupported dimension".into(),
    };
    match (kind, points) {
        (CurveKind::Function, CurvePoints::Planar(p)) => {
            let x: Vec<f64> = p.iter().map(|v| v.x).collect();
            let y: Vec<f64> = p.iter().map(|v| v.y).collect();
            let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout)?;
            AnyCurve::new::<2, _>(spline).ok_or_else(none)
        }
        (CurveKind::Function, CurvePoints::Spatial(_)) => Err(Error::Refused {
            method: "measure".into(),
            what: crate::Refusal::Kind,
            reason: "measures a function y(x) of planar points only".into(),
        }),
        (CurveKind::Parametric, CurvePoints::Planar(p)) => {
            AnyCurve::new::<2, _>(HermiteSpline::natural(p)?).ok_or_else(none)
        }
        (CurveKind::Parametric, CurvePoints::Spatial(p)) => {
            AnyCurve::new::<3, _>(HermiteSpline::natural(p)?).ok_or_else(none)
        }
    }
}

/// Every criterion of `criteria` that applies to `curve`, by name, with its value or the
/// reason it could not be evaluated.
pub fn evaluate_all<'a>(
    criteria: impl IntoIterator<Item = &'a CriterionEntry>,
    curve: &AnyCurve,
) -> BTreeMap<String, Result<f64>> {
    criteria
        .into_iter()
        .filter_map(|entry| Some((entry.name.clone(), entry.evaluate(curve)?)))
        .collect()
}

/// Every criterion of `criteria` that applies to curves of `dimension`, by name, on the curve
/// whose energies are `energies`: the entries that are energies read from them, the others
/// evaluated on the curve `curve()` builds, called once and only if one of them needs it.
/// O(1) per energy. Fails only when the curve is needed and cannot be built.
pub fn evaluate_all_with<'a, C: std::borrow::Borrow<AnyCurve>>(
    criteria: impl IntoIterator<Item = &'a CriterionEntry>,
    dimension: usize,
    energies: Option<&Energies>,
    curve: impl FnOnce() -> Result<C>,
) -> Result<BTreeMap<String, Result<f64>>> {
    let entries: Vec<&CriterionEntry> = criteria
        .into_iter()
        .filter(|entry| entry.applies_to(dimension))
        .collect();
    let built = if entries.iter().any(|entry| entry.needs_curve(energies.is_some())) {
        Some(curve()?)
    } else {
        None
    };
    Ok(entries
        .into_iter()
        .filter_map(|entry| {
            let value = entry.evaluate_with(dimension, energies, built.as_ref().map(|c| c.borrow()))?;
            Some((entry.name.clone(), value))
        })
        .collect())
}

/// The five energies of `curve` with their accuracy, every one adaptive with the built-in
/// criteria's own settings ([`fairness::Adaptive::default`], relative tolerance 1e-10), so
/// that a report's energies of a method's own representation (a NURBS, whose pieces are not
/// polynomials) are the values its criteria give — the ones a method optimised. Never fails
/// for an unmet tolerance, only where an integrand is not finite. O(pieces).
pub fn measure_energies(curve: &AnyCurve) -> Result<MeasuredEnergies> {
    let settings = fairness::Adaptive::default();
    Ok(match curve {
        AnyCurve::Planar(c) => fairness::Energies::measure::<2, dyn Curve<2> + Send + Sync>(&**c, &settings)?,
        AnyCurve::Spatial(c) => {
            fairness::Energies::measure::<3, dyn Curve<3> + Send + Sync>(&**c, &settings)?
        }
    })
}
