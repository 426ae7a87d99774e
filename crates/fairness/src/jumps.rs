//! Local indicators at the knots of a curve: derivative jumps and curvature vibrations.
//!
//! - Zhang–Cheng Eq. (17): z_i = |C‴(t_i+) − C‴(t_i−)|, the third-derivative jump at an
//!   interior break; z_i = 0 exactly when the point is where Eq. (11) would put it.
//! - Zhang–Cheng Eq. (16) (after Sapidis–Farin, Poliakoff): |dκ/ds(t_i+) − dκ/ds(t_i−)|, the
//!   jump of the curvature slope.
//! - Han §3.2's e_i built from (s_i, κ_i) in place of (x_i, c_i): docs/CONTRACT.md's curvature
//!   vibrations of the parametric kind, e_i = (κ_{i+1} − κ_i)/(s_{i+1} − s_i)
//!   − (κ_i − κ_{i−1})/(s_i − s_{i−1}) for the interior points, and the number of sign
//!   changes of e.

use std::marker::PhantomData;

use curve_repr::{Curve, Side, Vector};

use crate::curvature::{curvature_at_breaks, CurvatureForm};
use crate::sign::sign_changes;
use crate::{Error, LocalIndicator, Result};

fn interior_breaks<const D: usize, C: Curve<D> + ?Sized>(curve: &C) -> Result<Vec<f64>> {
    let breaks = curve.breaks();
    if breaks.len() < 2 {
        return Err(Error::TooFewPoints {
            what: "a curve's break points",
            needed: 2,
            got: breaks.len(),
        });
    }
    Ok(breaks[1..breaks.len() - 1].to_vec())
}

fn checked(what: &'static str, value: f64, parameter: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite { what, parameter })
    }
}

/// z_i = |C‴(t_i+) − C‴(t_i−)| at every interior break t_1 … t_{n−2} (Zhang–Cheng Eq. 17).
/// Length `breaks().len() − 2`. O(n).
pub fn third_derivative_jumps<const D: usize, C>(curve: &C) -> Result<Vec<f64>>
where
    C: Curve<D> + ?Sized,
{
    interior_breaks(curve)?
        .into_iter()
        .map(|t| {
            let right = curve.jet(t, Side::Right)[3];
            let left = curve.jet(t, Side::Left)[3];
            checked("third-derivative jump", (right - left).norm(), t)
        })
        .collect()
}

/// |dκ/ds(t_i+) − dκ/ds(t_i−)| at every interior break (Zhang–Cheng Eq. 16, Sapidis–Farin).
/// Length `breaks().len() − 2`. O(n). Fails where the tangent vanishes.
pub fn curvature_slope_jumps<const D: usize, C>(curve: &C) -> Result<Vec<f64>>
where
    C: Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    interior_breaks(curve)?
        .into_iter()
        .map(|t| {
            let right = crate::curvature::curvature_slope_at(curve, t, Side::Right)?;
            let left = crate::curvature::curvature_slope_at(curve, t, Side::Left)?;
            checked("curvature-slope jump", (right - left).abs(), t)
        })
        .collect()
}

/// Han's e built from (s, κ): e_i = (κ_{i+1} − κ_i)/(s_{i+1} − s_i) − (κ_i − κ_{i−1})/(s_i − s_{i−1})
/// for i = 1 … n − 2 (0-based; length n − 2, empty when n < 3). O(n).
///
/// With s the chord-length parameters and κ the curvature at the knots this is docs/CONTRACT.md's
/// parametric-kind vibration sequence (and `parametric_metrics.json`'s f_i); with (x, c) it
/// is Han's own e. Fails on lengths that differ, non-finite values, or s not strictly
/// increasing.
pub fn curvature_vibrations(s: &[f64], kappa: &[f64]) -> Result<Vec<f64>> {
    if s.len() != kappa.len() {
        return Err(Error::LengthMismatch {
            what: "curvatures (one per parameter)",
            expected: s.len(),
            got: kappa.len(),
        });
    }
    for (what, values) in [("parameter", s), ("curvature", kappa)] {
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFiniteInput { what, index });
        }
    }
    if let Some(index) = s.windows(2).position(|w| w[1] <= w[0]) {
        return Err(curve_repr::Error::NotIncreasing {
            what: "parameters",
            index: index + 1,
            previous: s[index],
            value: s[index + 1],
        }
        .into());
    }
    let slopes: Vec<f64> = s
        .windows(2)
        .zip(kappa.windows(2))
        .map(|(s, k)| (k[1] - k[0]) / (s[1] - s[0]))
        .collect();
    let e: Vec<f64> = slopes.windows(2).map(|w| w[1] - w[0]).collect();
    match e.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(Error::NonFinite {
            what: "curvature vibration",
            parameter: s[index + 1],
        }),
        None => Ok(e),
    }
}

/// The number of curvature vibrations, #{i : e_i e_{i+1} < 0} over
/// [`curvature_vibrations`] with docs/CONTRACT.md's drop rule. O(n).
pub fn vibration_count(s: &[f64], kappa: &[f64]) -> Result<usize> {
    Ok(sign_changes(&curvature_vibrations(s, kappa)?))
}

/// [`LocalIndicator`] of [`third_derivative_jumps`]: one value per interior break.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ThirdDerivativeJump<const D: usize = 2>(PhantomData<[(); D]>);

impl<const D: usize> ThirdDerivativeJump<D> {
    /// The indicator.
    pub fn new() -> Self {
        ThirdDerivativeJump(PhantomData)
    }
}

impl<const D: usize, C: Curve<D> + ?Sized> LocalIndicator<C> for ThirdDerivativeJump<D> {
    fn name(&self) -> &str {
        "third-derivative-jump"
    }
    fn values(&self, curve: &C) -> Result<Vec<f64>> {
        third_derivative_jumps(curve)
    }
}

/// [`LocalIndicator`] of [`curvature_slope_jumps`]: one value per interior break.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CurvatureSlopeJump<const D: usize = 2>(PhantomData<[(); D]>);

impl<const D: usize> CurvatureSlopeJump<D> {
    /// The indicator.
    pub fn new() -> Self {
        CurvatureSlopeJump(PhantomData)
    }
}

impl<const D: usize, C: Curve<D> + ?Sized> LocalIndicator<C> for CurvatureSlopeJump<D>
where
    Vector<D>: CurvatureForm,
{
    fn name(&self) -> &str {
        "curvature-slope-jump"
    }
    fn values(&self, curve: &C) -> Result<Vec<f64>> {
        curvature_slope_jumps(curve)
    }
}

/// [`LocalIndicator`]: [`curvature_vibrations`] of the curve's own break parameters and its
/// curvature there (one value per interior break). For the natural chord-length spline of
/// docs/CONTRACT.md's parametric kind this is the report's vibration sequence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CurvatureVibration<const D: usize = 2>(PhantomData<[(); D]>);

impl<const D: usize> CurvatureVibration<D> {
    /// The indicator.
    pub fn new() -> Self {
        CurvatureVibration(PhantomData)
    }
}

impl<const D: usize, C: Curve<D> + ?Sized> LocalIndicator<C> for CurvatureVibration<D>
where
    Vector<D>: CurvatureForm,
{
    fn name(&self) -> &str {
        "curvature-vibration"
    }
    fn values(&self, curve: &C) -> Result<Vec<f64>> {
        curvature_vibrations(&curve.breaks(), &curvature_at_breaks(curve)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curvature::curvature_at;
    use crate::test_curves::{CircleArc, PiecewiseCubic};
    use curve_repr::{Vec2, Vec3};

    fn wiggly_2d() -> (PiecewiseCubic<2>, Vec<Vec2>) {
        let breaks = vec![0.0, 1.0, 1.5, 2.7, 3.0, 4.2];
        let third = vec![
            Vec2::new(0.3, -1.0),
            Vec2::new(-0.7, 2.0),
            Vec2::new(-0.7, 2.0),
            Vec2::new(1.1, 0.5),
            Vec2::new(0.0, -0.4),
        ];
        let start = [Vec2::zeros(), Vec2::new(1.0, 0.2), Vec2::new(0.1, 0.3)];
        (
            PiecewiseCubic::c2_from_third_derivatives(breaks, start, &third),
            third,
        )
    }

    #[test]
    fn third_derivative_jumps_are_the_constructed_ones() {
        let (curve, third) = wiggly_2d();
        let z = ThirdDerivativeJump::new().values(&curve).unwrap();
        let expected: Vec<f64> = third.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
        assert_eq!(z.len(), 4);
        for (got, want) in z.iter().zip(&expected) {
            assert!((got - want).abs() <= 1e-13 * want.max(1.0), "{got} {want}");
        }
        // The third piece repeats the second's C‴: no jump there.
        assert_eq!(z[1], 0.0);
        let largest = expected.iter().cloned().fold(0.0, f64::max);
        assert!((ThirdDerivativeJump::new().max_value(&curve).unwrap() - largest).abs() < 1e-13);
        // The construction really is C2: value, C′ and C″ agree from both sides.
        for t in &curve.breaks[1..5] {
            let (l, r) = (curve.jet(*t, Side::Left), curve.jet(*t, Side::Right));
            for k in 0..3 {
                assert!((l[k] - r[k]).norm() < 1e-12);
            }
        }
    }

    #[test]
    fn third_derivative_jumps_in_3d_and_smooth_curves() {
        let breaks = vec![0.0, 2.0, 3.0];
        let third = [Vec3::new(1.0, 2.0, 2.0), Vec3::new(-1.0, 2.0, 2.0)];
        let curve = PiecewiseCubic::c2_from_third_derivatives(breaks, [Vec3::zeros(); 3], &third);
        assert_eq!(third_derivative_jumps(&curve).unwrap(), vec![2.0]);
        let arc = CircleArc {
            centre: Vec2::zeros(),
            radius: 1.0,
            angles: (0.0, 1.0),
        };
        assert!(third_derivative_jumps(&arc).unwrap().is_empty());
    }

    /// dκ/ds on each side of a break against second-order one-sided differences of κ along
    /// arc length (ds = |C′| dt), on the pieces to the right and to the left.
    #[test]
    fn curvature_slope_jumps_match_one_sided_differences() {
        let (curve, _) = wiggly_2d();
        let jumps = CurvatureSlopeJump::new().values(&curve).unwrap();
        let h = 1e-5;
        for (i, t) in curve.breaks[1..5].iter().enumerate() {
            let k = |s: f64, side| curvature_at(&curve, s, side).unwrap();
            let speed = curve.jet(*t, Side::Right)[1].norm();
            let right = (-3.0 * k(*t, Side::Right) + 4.0 * k(t + h, Side::Right)
                - k(t + 2.0 * h, Side::Right))
                / (2.0 * h)
                / speed;
            let left = (3.0 * k(*t, Side::Left) - 4.0 * k(t - h, Side::Left) + k(t - 2.0 * h, Side::Left))
                / (2.0 * h)
                / speed;
            let expected = (right - left).abs();
            assert!(
                (jumps[i] - expected).abs() < 1e-6 * expected.max(1.0),
                "{} {expected}",
                jumps[i]
            );
        }
        assert!(jumps[1].abs() < 1e-14);
    }

    #[test]
    fn vibrations_by_hand() {
        // slopes 1, 0, 2 ⇒ e = −1, 2: one sign change.
        let e = curvature_vibrations(&[0.0, 1.0, 3.0, 4.0], &[0.0, 1.0, 1.0, 3.0]).unwrap();
        assert_eq!(e, vec![-1.0, 2.0]);
        assert_eq!(
            vibration_count(&[0.0, 1.0, 3.0, 4.0], &[0.0, 1.0, 1.0, 3.0]).unwrap(),
            1
        );
        assert!(curvature_vibrations(&[0.0, 1.0], &[1.0, 2.0]).unwrap().is_empty());
        assert!(curvature_vibrations(&[], &[]).unwrap().is_empty());
    }

    #[test]
    fn vibration_input_errors() {
        assert!(matches!(
            curvature_vibrations(&[0.0, 1.0, 2.0], &[0.0, 1.0]),
            Err(Error::LengthMismatch { .. })
        ));
        assert!(matches!(
            curvature_vibrations(&[0.0, 1.0, 1.0], &[0.0, 1.0, 2.0]),
            Err(Error::Curve(curve_repr::Error::NotIncreasing { .. }))
        ));
        assert!(matches!(
            curvature_vibrations(&[0.0, 1.0, 2.0], &[0.0, f64::NAN, 2.0]),
            Err(Error::NonFiniteInput { .. })
        ));
        assert!(matches!(
            curvature_vibrations(&[0.0, 1e-310, 2.0], &[0.0, 1e300, 2.0]),
            Err(Error::NonFinite { .. })
        ));
    }

    /// Han's x–c polyline: e from (x, c), Infl_num and Vib_num of the oracle.
    #[test]
    fn han_e_matches_runout_oracle() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/reference/runout_spline_function.json"
        );
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let floats = |v: &serde_json::Value| -> Vec<f64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        for set in json["datasets"].as_array().unwrap() {
            let (x, c, e) = (floats(&set["x"]), floats(&set["c"]), floats(&set["e"]));
            let got = curvature_vibrations(&x, &c).unwrap();
            assert_eq!(got.len(), e.len());
            let scale = e.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (g, w) in got.iter().zip(&e) {
                assert!((g - w).abs() <= 1e-9 * scale, "{g} {w}");
            }
            assert_eq!(sign_changes(&c) as u64, set["Infl_num"].as_u64().unwrap());
            assert_eq!(
                vibration_count(&x, &c).unwrap() as u64,
                set["Vib_num"].as_u64().unwrap()
            );
        }
    }
}
