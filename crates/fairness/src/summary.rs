//! The report's `before`/`after` block of each kind, exactly as docs/CONTRACT.md "Definitions" says:
//! [`function`] (Han's x–c polyline of the parabolic-runout spline function), [`parametric`]
//! (the natural chord-length Hermite spline, 2D or 3D) and [`surface`] (the bicubic spline
//! surface of Zhang–Cheng §4 with chord-length averaged knots).
//!
//! Each returns a [`FairnessSummary`]; the `*_of` variants take a representation already
//! built (the `fair` command draws it too). Every function is O(n) time and memory (O(m·n)
//! for surfaces).
//!
//! What each number's accuracy is:
//! - `inflections`, `vibrations`: exact counts under docs/CONTRACT.md's sign rule (integers, from the
//!   values at the knots; no integration);
//! - `e_s`: closed form, exact up to round-off; `max_z`: exact differences at the knots;
//! - `energies`: E1–E3 exactly (Gauss–Legendre rules exact for the cubic pieces, round-off
//!   only), Ek and Ek′ adaptively to [`ENERGY_TOLERANCE`] relative within a budget linear in
//!   n; `energy_accuracy` carries each energy's error estimate and whether its tolerance was
//!   met. A tolerance that cannot be met (a noisy 10⁶-point curve has Ek′ dominated by
//!   sharp curvature peaks) leaves the estimate and its error in the summary: measuring never
//!   fails for it. Where an integrand is not finite (a tangent that vanishes at a node) the
//!   energies are left out (`energy_accuracy` is `None`) and the rest of the summary stands.

use curve_repr::{BicubicSplineSurface, EndCondition, HermiteSpline, SplineFunction, Vec3, Vector};

use crate::curvature::CurvatureForm;
use crate::energy::{Energies, EnergyAccuracy, MeasuredEnergies};
use crate::quadrature::Adaptive;
use crate::report::FairnessSummary;
use crate::xc::XcPolyline;
use crate::{Error, Result};

/// The relative tolerance of the adaptive energies (Ek, Ek′) in the summaries: 10⁻⁸ of each
/// total, far below any difference a fairing makes and within reach of the linear budget of
/// [`Adaptive::estimate_pieces`] for smooth and moderately noisy curves alike.
pub const ENERGY_TOLERANCE: f64 = 1e-8;

/// The quadrature settings of the summaries' adaptive energies: [`Adaptive::default`] with
/// [`ENERGY_TOLERANCE`].
pub fn energy_settings() -> Adaptive {
    Adaptive::default().with_relative_tolerance(ENERGY_TOLERANCE)
}

/// The energies of a curve of cubic pieces with their accuracy; `None` for the accuracy (and
/// zeros) where an integrand is not finite, so that the counts still stand. O(n).
fn cubic_energies<const D: usize, C>(curve: &C) -> (Energies, Option<EnergyAccuracy>)
where
    C: curve_repr::Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    match Energies::measure_polynomial(curve, 3, &energy_settings()) {
        Ok(MeasuredEnergies { values, accuracy }) => (values, Some(accuracy)),
        Err(_) => (Energies::default(), None),
    }
}

/// The function-kind summary of the spline function `spline` (docs/CONTRACT.md builds it with the
/// parabolic-runout end condition, see [`function`]):
///
/// - `inflections`, `vibrations`: Han's Infl_num and Vib_num of the x–c polyline
///   ([`XcPolyline`], sign-change rule of docs/CONTRACT.md);
/// - `e_s` = ∫ y″(x)² dx, exact ([`SplineFunction::second_derivative_energy`]);
/// - `max_z` = max_i |y‴(x_i+) − y‴(x_i−)| = 6 max |e_i|;
/// - `energies` of the graph (x, y(x)) over its parameter x (E1–E3 exact for cubic pieces,
///   Ek and Ek′ adaptive to [`ENERGY_TOLERANCE`]) with their accuracy (see the module doc).
pub fn function_of(spline: &SplineFunction) -> Result<FairnessSummary> {
    // The energies' quadrature on rayon's threads, the counts beside it.
    let (xc, (energies, energy_accuracy)) =
        rayon::join(|| XcPolyline::of_spline(spline), || cubic_energies(spline));
    let xc = xc?;
    let e_s = spline.second_derivative_energy();
    if !e_s.is_finite() {
        return Err(Error::NonFinite {
            what: "strain energy ∫ y″² dx",
            parameter: spline.x().first().copied().unwrap_or(0.0),
        });
    }
    Ok(FairnessSummary {
        inflections: Some(xc.inflections()),
        vibrations: Some(xc.vibrations()),
        e_s,
        max_z: xc.max_third_derivative_jump(),
        energies,
        energy_accuracy,
    })
}

/// docs/CONTRACT.md's function-kind summary of the points (x_i, y_i), x strictly increasing: the
/// spline function with the parabolic-runout end condition (c_1 = c_2, c_{n−1} = c_n), then
/// [`function_of`]. O(n).
pub fn function(x: &[f64], y: &[f64]) -> Result<FairnessSummary> {
    function_of(&SplineFunction::new(x, y, EndCondition::ParabolicRunout)?)
}

/// docs/CONTRACT.md's parametric-kind summary of a Hermite spline (there the natural spline with
/// chord-length parameters, see [`parametric`]): κ_i at the knots (signed in 2D, unsigned in
/// 3D), e from (t, κ), inflections (2D only, else `None`), vibrations, `e_s` = ∫ |C″|² dt
/// (exact, [`HermiteSpline::strain_energy`]), `max_z` = max_i |C‴(t_i+) − C‴(t_i−)|, and the
/// energies (E1–E3 exact for cubic pieces, Ek and Ek′ adaptive) with their accuracy. Builds on
/// [`FairnessSummary::of_parametric_curve_with_energies`]. O(n).
pub fn parametric_of<const D: usize>(spline: &HermiteSpline<D>) -> Result<FairnessSummary>
where
    Vector<D>: CurvatureForm,
{
    let (energies, energy_accuracy) = cubic_energies(spline);
    let mut summary = FairnessSummary::of_parametric_curve_with_energies(spline, energies)?;
    summary.energy_accuracy = energy_accuracy;
    let e_s = spline.strain_energy();
    if e_s.is_finite() {
        summary.e_s = e_s;
    }
    Ok(summary)
}

/// docs/CONTRACT.md's parametric-kind summary of the points: the natural cubic spline with
/// chord-length parameters ([`HermiteSpline::natural`]), then [`parametric_of`]. O(n).
/// Fails on repeated consecutive points (a zero chord) and non-finite coordinates.
pub fn parametric<const D: usize>(points: &[Vector<D>]) -> Result<FairnessSummary>
where
    Vector<D>: CurvatureForm,
{
    parametric_of(&HermiteSpline::natural(points)?)
}

/// docs/CONTRACT.md's surface-kind summary of a bicubic spline surface: `max_z` = max z_ij (Eq. 26)
/// over the interior nodes, `e_s` = the network strain energy; `inflections` and
/// `vibrations` are `None`, and `energies` (curve criteria, undefined for a surface) are
/// zero — the `fair` report writes them as null. O(m·n).
pub fn surface_of(surface: &BicubicSplineSurface) -> Result<FairnessSummary> {
    let max_z = surface.max_z();
    let e_s = surface.network_strain_energy();
    for (what, value) in [("surface max z_ij", max_z), ("network strain energy", e_s)] {
        if !value.is_finite() {
            return Err(Error::NonFinite { what, parameter: 0.0 });
        }
    }
    Ok(FairnessSummary {
        inflections: None,
        vibrations: None,
        e_s,
        max_z,
        energies: Energies::default(),
        energy_accuracy: None,
    })
}

/// docs/CONTRACT.md's surface-kind summary of the grid `grid[i][j]` = P_ij: the bicubic spline
/// surface with chord-length averaged knots ([`BicubicSplineSurface::new`]), then
/// [`surface_of`]. O(m·n).
pub fn surface(grid: &[Vec<Vec3>]) -> Result<FairnessSummary> {
    surface_of(&BicubicSplineSurface::new(grid)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    fn floats(v: &serde_json::Value) -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    }

    fn json(name: &str) -> serde_json::Value {
        let path = format!("{}/../../data/reference/{name}", env!("CARGO_MANIFEST_DIR"));
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * b.abs().max(1e-300)
    }

    /// Counts, E_s and max_z against `runout_spline_function.json`.
    #[test]
    fn function_summary_matches_runout_oracle() {
        for set in json("runout_spline_function.json")["datasets"]
            .as_array()
            .unwrap()
        {
            let (x, y) = (floats(&set["x"]), floats(&set["y"]));
            let summary = function(&x, &y).unwrap();
            assert_eq!(summary.inflections.map(|v| v as u64), set["Infl_num"].as_u64());
            assert_eq!(summary.vibrations.map(|v| v as u64), set["Vib_num"].as_u64());
            let e_s = set["E_s"].as_f64().unwrap();
            assert!(close(summary.e_s, e_s), "{} {e_s}", summary.e_s);
            let max_e = floats(&set["e"]).iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            assert!(close(summary.max_z, 6.0 * max_e));
            // The graph (x, y(x)) over x: E2 = ∫ y″² dx as well (C″ = (0, y″)).
            assert!(close(summary.energies.e2, e_s));
            let e = summary.energies;
            for v in [e.e1, e.e2, e.e3, e.ek, e.ek_prime] {
                assert!(v.is_finite() && v >= 0.0);
            }
        }
    }

    /// Counts and E_2 against `parametric_metrics.json` (SciPy's natural chord-length spline).
    #[test]
    fn parametric_summary_matches_oracle() {
        for set in json("parametric_metrics.json")["datasets"].as_array().unwrap() {
            let rows: Vec<Vec<f64>> = set["points"].as_array().unwrap().iter().map(floats).collect();
            let e2 = set["E_2"].as_f64().unwrap();
            let z = floats(&set["z"]).iter().fold(0.0_f64, |m, v| m.max(*v));
            let summary = match set["dim"].as_u64() {
                Some(2) => {
                    let p: Vec<Vec2> = rows.iter().map(|r| Vec2::new(r[0], r[1])).collect();
                    let s = parametric(&p).unwrap();
                    assert_eq!(s.inflections.map(|v| v as u64), set["inflections"].as_u64());
                    s
                }
                _ => {
                    let p: Vec<Vec3> = rows.iter().map(|r| Vec3::new(r[0], r[1], r[2])).collect();
                    let s = parametric(&p).unwrap();
                    assert_eq!(s.inflections, None);
                    s
                }
            };
            assert_eq!(summary.vibrations.map(|v| v as u64), set["vibrations"].as_u64());
            assert!(close(summary.e_s, e2), "{} {e2}", summary.e_s);
            // The exact Gauss–Legendre E2 agrees with the closed-form strain energy.
            assert!(close(summary.energies.e2, e2), "{} {e2}", summary.energies.e2);
            assert!(close(summary.max_z, z), "{} {z}", summary.max_z);
        }
    }

    /// A plane z = ax + by + c is reproduced exactly: no jumps, no bending.
    #[test]
    fn surface_summary_of_a_plane_is_zero() {
        let grid: Vec<Vec<Vec3>> = (0..5)
            .map(|i| {
                (0..4)
                    .map(|j| {
                        let (x, y) = (i as f64 * 1.5, j as f64 * 0.7);
                        Vec3::new(x, y, 0.3 * x - 0.2 * y + 1.0)
                    })
                    .collect()
            })
            .collect();
        let s = surface(&grid).unwrap();
        assert!(s.max_z.abs() < 1e-9 && s.e_s.abs() < 1e-9, "{s:?}");
        assert_eq!((s.inflections, s.vibrations), (None, None));
        // A bump in the middle makes both positive.
        let mut bumped = grid.clone();
        bumped[2][2].z += 0.5;
        let s = surface(&bumped).unwrap();
        assert!(s.max_z > 0.0 && s.e_s > 0.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert!(function(&[0.0, 1.0, 1.0], &[0.0, 1.0, 2.0]).is_err());
        let repeated = [Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)];
        assert!(parametric(&repeated).is_err());
    }
}
