//! The fairness summary of the `fair` command's report: its `before` and `after` blocks.
//!
//! docs/CONTRACT.md defines each field per kind (function, parametric, surface).
//! [`FairnessSummary::of_parametric_curve`] fills the parametric kind from any curve; the
//! function kind (Han's x–c polyline of the parabolic-runout spline function) and the
//! surface kind are filled by their representations' code.

use curve_repr::{Curve, Vector};

use crate::curvature::{curvature_at_breaks, CurvatureForm};
use crate::energy::{Energies, EnergyAccuracy};
use crate::jumps::{curvature_vibrations, third_derivative_jumps};
use crate::sign::sign_changes;
use crate::Result;

/// One `before` or `after` block of the report.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FairnessSummary {
    /// Number of inflections (null where undefined: 3D curves, surfaces).
    pub inflections: Option<usize>,
    /// Number of curvature vibrations (null for surfaces).
    pub vibrations: Option<usize>,
    /// The strain energy E_s.
    pub e_s: f64,
    /// The largest third-derivative jump (z_i, or z_ij for surfaces).
    pub max_z: f64,
    /// The five integral criteria (best estimates; see `energy_accuracy`).
    pub energies: Energies,
    /// How accurately each energy is known; `None` where the energies were not measured (a
    /// surface) or could not be (an integrand that is not finite, as at a vanishing tangent),
    /// in which case `energies` holds zeros and means nothing.
    pub energy_accuracy: Option<EnergyAccuracy>,
}

impl FairnessSummary {
    /// The parametric-kind summary of docs/CONTRACT.md, measured on `curve` (there, the natural cubic
    /// spline through the points with chord-length parameters, whose breaks are the knots t_i):
    ///
    /// - κ_i at the breaks (signed in 2D, unsigned in 3D);
    /// - `inflections` = #{i : κ_i κ_{i+1} < 0} for planar curves, `None` in 3D;
    /// - `vibrations` = sign changes of e_i built from (t_i, κ_i) ([`curvature_vibrations`]);
    /// - `e_s` = E2 = ∫ |C″(t)|² dt; `max_z` = max_i |C‴(t_i+) − C‴(t_i−)| (0 with no
    ///   interior break);
    /// - `energies` by [`Energies::of`] (failing when a tolerance is not met; `fair`'s report
    ///   measures them with [`Energies::measure_polynomial`] and keeps their accuracy instead).
    ///
    /// O(n).
    pub fn of_parametric_curve<const D: usize, C>(curve: &C) -> Result<Self>
    where
        C: Curve<D> + ?Sized,
        Vector<D>: CurvatureForm,
    {
        Self::of_parametric_curve_with_energies(curve, Energies::of(curve)?)
    }

    /// [`of_parametric_curve`](Self::of_parametric_curve) with the energies already computed
    /// (e.g. by [`Energies::of_polynomial`], exact and faster for polynomial pieces);
    /// `e_s` is their `e2`. O(n).
    pub fn of_parametric_curve_with_energies<const D: usize, C>(curve: &C, energies: Energies) -> Result<Self>
    where
        C: Curve<D> + ?Sized,
        Vector<D>: CurvatureForm,
    {
        let (inflections, vibrations) = parametric_counts(curve)?;
        let vibrations = Some(vibrations);
        let max_z = third_derivative_jumps(curve)?.into_iter().fold(0.0, f64::max);
        Ok(FairnessSummary {
            inflections,
            vibrations,
            e_s: energies.e2,
            max_z,
            energies,
            energy_accuracy: None,
        })
    }
}

/// docs/CONTRACT.md's parametric-kind counts of `curve` (the `inflections` and `vibrations` of
/// [`FairnessSummary::of_parametric_curve`]): sign changes of the signed curvature κ at the
/// breaks (`None` in 3D, where κ has no sign) and of e_i built from (t_i, κ_i)
/// ([`curvature_vibrations`]). For code that needs the counts without the energies (a
/// fairing's guard). O(n).
pub fn parametric_counts<const D: usize, C>(curve: &C) -> Result<(Option<usize>, usize)>
where
    C: Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    let kappa = curvature_at_breaks(curve)?;
    let breaks = curve.breaks();
    let inflections = <Vector<D> as CurvatureForm>::SIGNED.then(|| sign_changes(&kappa));
    let vibrations = sign_changes(&curvature_vibrations(&breaks, &kappa)?);
    Ok((inflections, vibrations))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sign::binormal_flips;
    use crate::test_curves::PiecewiseCubic;
    use curve_repr::{Parametrization, Side};

    /// The natural cubic spline through `points` over chord-length parameters, written here
    /// from the textbook moment equations (test-only, independent of curve-repr's splines):
    /// h_{i−1}M_{i−1} + 2(h_{i−1} + h_i)M_i + h_iM_{i+1} = 6(Δ_i − Δ_{i−1}), M_0 = M_n = 0.
    fn natural_spline<const D: usize>(points: &[Vector<D>]) -> PiecewiseCubic<D> {
        let t = Parametrization::ChordLength.parameters(points).unwrap();
        let n = points.len();
        let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let slope: Vec<Vector<D>> = (0..n - 1).map(|i| (points[i + 1] - points[i]) / h[i]).collect();
        let lower: Vec<f64> = (1..n - 1).map(|i| h[i - 1]).collect();
        let diag: Vec<f64> = (1..n - 1).map(|i| 2.0 * (h[i - 1] + h[i])).collect();
        let upper: Vec<f64> = (1..n - 1).map(|i| h[i]).collect();
        let rhs: Vec<Vector<D>> = (1..n - 1).map(|i| (slope[i] - slope[i - 1]) * 6.0).collect();
        let inner = curve_repr::tridiagonal::solve(&lower, &diag, &upper, &rhs).unwrap();
        let mut m = vec![Vector::<D>::zeros()];
        m.extend(inner);
        m.push(Vector::<D>::zeros());
        let pieces = (0..n - 1)
            .map(|i| {
                let b = slope[i] - (m[i] * 2.0 + m[i + 1]) * (h[i] / 6.0);
                [points[i], b, m[i] * 0.5, (m[i + 1] - m[i]) / (6.0 * h[i])]
            })
            .collect();
        PiecewiseCubic { breaks: t, pieces }
    }

    fn floats(v: &serde_json::Value) -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    }

    fn check<const D: usize>(set: &serde_json::Value) -> FairnessSummary
    where
        Vector<D>: CurvatureForm,
    {
        let points: Vec<Vector<D>> = set["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| Vector::<D>::from_iterator(floats(p)))
            .collect();
        let curve = natural_spline(&points);
        let close = |a: f64, b: f64, scale: f64| (a - b).abs() <= 1e-9 * scale.max(1e-300);
        for (got, want) in curve.breaks.iter().zip(floats(&set["t"])) {
            assert!(close(*got, want, want.abs().max(1.0)));
        }
        let kappa = floats(&set["kappa"]);
        let scale = kappa.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (got, want) in curvature_at_breaks(&curve).unwrap().iter().zip(&kappa) {
            assert!(close(*got, *want, scale), "κ {got} {want}");
        }
        let z = floats(&set["z"]);
        let scale = z.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (got, want) in third_derivative_jumps(&curve).unwrap().iter().zip(&z) {
            assert!(close(*got, *want, scale), "z {got} {want}");
        }
        let summary = FairnessSummary::of_parametric_curve(&curve).unwrap();
        let e2 = set["E_2"].as_f64().unwrap();
        assert!(close(summary.e_s, e2, e2), "E2 {} {e2}", summary.e_s);
        assert_eq!(summary.e_s, summary.energies.e2);
        assert!(close(summary.max_z, scale, scale));
        assert_eq!(summary.vibrations.map(|v| v as u64), set["vibrations"].as_u64());
        summary
    }

    /// Against `parametric_metrics.json` (SciPy's natural chord-length spline): κ_i, z_i, E_2,
    /// inflections and vibrations.
    #[test]
    fn parametric_summary_matches_oracle() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/reference/parametric_metrics.json"
        );
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        for set in json["datasets"].as_array().unwrap() {
            match set["dim"].as_u64() {
                Some(2) => {
                    let summary = check::<2>(set);
                    assert_eq!(summary.inflections.map(|v| v as u64), set["inflections"].as_u64());
                }
                Some(3) => {
                    let summary = check::<3>(set);
                    assert_eq!(summary.inflections, None);
                    // The oracle's 3D inflections: binormal flips at the knots.
                    let points: Vec<curve_repr::Vec3> = set["points"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|p| curve_repr::Vec3::from_iterator(floats(p)))
                        .collect();
                    let curve = natural_spline(&points);
                    let binormals: Vec<_> = curve
                        .breaks
                        .iter()
                        .map(|t| {
                            let jet = curve.jet(*t, Side::Right);
                            jet[1].cross(&jet[2])
                        })
                        .collect();
                    assert_eq!(
                        binormal_flips(&binormals) as u64,
                        set["inflections"].as_u64().unwrap()
                    );
                }
                other => panic!("unexpected dim {other:?}"),
            }
        }
    }

    #[test]
    fn summary_serialises_with_null_fields() {
        let summary = FairnessSummary {
            inflections: None,
            vibrations: Some(3),
            ..Default::default()
        };
        let json = serde_json::to_value(summary).unwrap();
        assert!(json["inflections"].is_null());
        assert_eq!(json["vibrations"], 3);
        assert_eq!(json["energies"]["ek_prime"], 0.0);
    }
}
