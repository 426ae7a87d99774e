//! Han's x–c polyline (Han et al. §3.2): the curvature plot of a spline function y(x)
//! approximated by the polyline through (x_i, c_i), c_i = y″(x_i)/6, and its second
//! differences e_i, which locate inflections (c_i c_{i+1} < 0) and curvature vibrations
//! (e_i e_{i+1} < 0).
//!
//! Counts follow docs/CONTRACT.md's sign-change rule ([`sign_changes`]). The sensitivity of e_i to a
//! move of y_j (Han Eq. 18) is built from [`SplineFunction::sensitivity`] in O(1).

use curve_repr::SplineFunction;

use crate::sign::{sign_change_positions, sign_changes};
use crate::{Error, Result};

/// The x–c polyline of a spline function: knots x_i, c_i = y″(x_i)/6 and, for the interior
/// points, e_i = (c_{i+1} − c_i)/(x_{i+1} − x_i) − (c_i − c_{i−1})/(x_i − x_{i−1})
/// (Han §3.2, the formula under "x–c plot").
///
/// Indices count from 0: `e[k]` belongs to point k + 1 (k = 0 … n − 3), so `e` has n − 2
/// entries (none below 3 points).
#[derive(Clone, Debug, PartialEq)]
pub struct XcPolyline {
    /// The knots x_0 … x_{n−1}.
    pub x: Vec<f64>,
    /// c_i = y″(x_i)/6.
    pub c: Vec<f64>,
    /// e at the interior points 1 … n − 2 (`e[k]` at point k + 1).
    pub e: Vec<f64>,
}

/// e_i from (x, c) for the interior points; fails on a non-finite value. O(n).
fn second_differences(x: &[f64], c: &[f64]) -> Result<Vec<f64>> {
    let e: Vec<f64> = (1..x.len().saturating_sub(1))
        .map(|i| (c[i + 1] - c[i]) / (x[i + 1] - x[i]) - (c[i] - c[i - 1]) / (x[i] - x[i - 1]))
        .collect();
    match e.iter().position(|v| !v.is_finite()) {
        Some(k) => Err(Error::NonFinite {
            what: "x–c second difference e_i",
            parameter: x[k + 1],
        }),
        None => Ok(e),
    }
}

impl XcPolyline {
    /// The polyline of `spline` (whatever its end condition; docs/CONTRACT.md's function kind uses
    /// the parabolic runout, see [`XcPolyline::of_points`]). O(n).
    pub fn of_spline(spline: &SplineFunction) -> Result<Self> {
        let x = spline.x().to_vec();
        let c = spline.c().to_vec();
        if let Some(index) = c.iter().position(|v| !v.is_finite()) {
            return Err(Error::NonFiniteInput {
                what: "spline coefficient c_i",
                index,
            });
        }
        let e = second_differences(&x, &c)?;
        Ok(XcPolyline { x, c, e })
    }

    /// The polyline of the spline function through (x_i, y_i) with the parabolic-runout end
    /// condition (Han's choice; docs/CONTRACT.md's function kind). O(n). Fails as
    /// [`SplineFunction::new`] does (x not increasing, lengths, non-finite values).
    pub fn of_points(x: &[f64], y: &[f64]) -> Result<Self> {
        let spline = SplineFunction::new(x, y, curve_repr::EndCondition::ParabolicRunout)?;
        Self::of_spline(&spline)
    }

    /// Han's Infl_num = #{i : c_i c_{i+1} < 0} with docs/CONTRACT.md's drop rule. O(n).
    pub fn inflections(&self) -> usize {
        sign_changes(&self.c)
    }

    /// Han's Vib_num = #{i : e_i e_{i+1} < 0} with docs/CONTRACT.md's drop rule. O(n).
    pub fn vibrations(&self) -> usize {
        sign_changes(&self.e)
    }

    /// Where the inflections are: pairs of point indices (k, l) of consecutive kept c values
    /// of opposite signs (l = k + 1 unless values between were dropped). O(n).
    pub fn inflection_positions(&self) -> Vec<(usize, usize)> {
        sign_change_positions(&self.c)
    }

    /// Where the vibrations are: pairs of point indices (k, l), k < l, of consecutive kept
    /// e values of opposite signs (point indices, not indices into `e`). O(n).
    pub fn vibration_positions(&self) -> Vec<(usize, usize)> {
        sign_change_positions(&self.e)
            .into_iter()
            .map(|(k, l)| (k + 1, l + 1))
            .collect()
    }

    /// The largest third-derivative jump max_i |y‴(x_i+) − y‴(x_i−)| = 6 max |e_i| (y‴ is
    /// 6(c_{i+1} − c_i)/h_i on [x_i, x_{i+1}]); 0 with no interior point. O(n).
    pub fn max_third_derivative_jump(&self) -> f64 {
        6.0 * self.e.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }
}

/// ẽ_i^j = ∂e_i/∂y_j, the sensitivity of Han Eq. 18:
/// ẽ_i^j = (c̃_{i+1}^j − c̃_i^j)/(x_{i+1} − x_i) − (c̃_i^j − c̃_{i−1}^j)/(x_i − x_{i−1}),
/// with c̃^j from [`SplineFunction::sensitivity`]. `i` is a point index (interior: 1 … n − 2),
/// `j` any point index; 0 outside those ranges. O(1).
pub fn e_sensitivity(spline: &SplineFunction, i: usize, j: usize) -> f64 {
    let x = spline.x();
    let n = x.len();
    if i == 0 || i + 1 >= n || j >= n {
        return 0.0;
    }
    let s = |k: usize| spline.sensitivity(k, j);
    (s(i + 1) - s(i)) / (x[i + 1] - x[i]) - (s(i) - s(i - 1)) / (x[i] - x[i - 1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::EndCondition;

    fn floats(v: &serde_json::Value) -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    }

    fn oracle() -> serde_json::Value {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data/reference/runout_spline_function.json"
        );
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    /// e, Infl_num and Vib_num against `runout_spline_function.json` (SciPy).
    #[test]
    fn polyline_matches_runout_oracle() {
        for set in oracle()["datasets"].as_array().unwrap() {
            let (x, y) = (floats(&set["x"]), floats(&set["y"]));
            let xc = XcPolyline::of_points(&x, &y).unwrap();
            let want_e = floats(&set["e"]);
            assert_eq!(xc.e.len(), want_e.len());
            let scale = want_e.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for (got, want) in xc.e.iter().zip(&want_e) {
                assert!((got - want).abs() <= 1e-9 * scale, "e {got} {want}");
            }
            for (got, want) in xc.c.iter().zip(floats(&set["c"])) {
                assert!((got - want).abs() <= 1e-9 * scale.max(1.0), "c {got} {want}");
            }
            assert_eq!(xc.inflections() as u64, set["Infl_num"].as_u64().unwrap());
            assert_eq!(xc.vibrations() as u64, set["Vib_num"].as_u64().unwrap());
            assert_eq!(xc.vibration_positions().len(), xc.vibrations());
            assert_eq!(xc.inflection_positions().len(), xc.inflections());
        }
    }

    /// ẽ_i^j against central finite differences of e over rebuilt splines (y_j ± h): the
    /// defining condition of Eq. 18 (e is linear in y, so the difference is exact up to
    /// round-off).
    #[test]
    fn e_sensitivity_is_the_derivative_of_e() {
        for set in oracle()["datasets"].as_array().unwrap() {
            let (x, y) = (floats(&set["x"]), floats(&set["y"]));
            let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
            let n = x.len();
            let h = 1e-3;
            for j in 0..n {
                let moved = |d: f64| {
                    let mut y = y.clone();
                    y[j] += d;
                    XcPolyline::of_points(&x, &y).unwrap().e
                };
                let (plus, minus) = (moved(h), moved(-h));
                let scale = plus.iter().fold(1.0_f64, |m, v| m.max(v.abs())) / h;
                for i in 1..n - 1 {
                    let fd = (plus[i - 1] - minus[i - 1]) / (2.0 * h);
                    let got = e_sensitivity(&spline, i, j);
                    assert!((got - fd).abs() <= 1e-7 * scale, "i {i} j {j}: {got} {fd}");
                }
            }
            assert_eq!(e_sensitivity(&spline, 0, 1), 0.0);
            assert_eq!(e_sensitivity(&spline, n - 1, 1), 0.0);
            assert_eq!(e_sensitivity(&spline, 1, n), 0.0);
        }
    }

    #[test]
    fn max_jump_is_the_third_derivative_jump() {
        let set = &oracle()["datasets"][0];
        let (x, y) = (floats(&set["x"]), floats(&set["y"]));
        let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
        let xc = XcPolyline::of_spline(&spline).unwrap();
        let direct = (1..x.len() - 1)
            .map(|i| {
                (spline.third_derivative(x[i], curve_repr::Side::Right)
                    - spline.third_derivative(x[i], curve_repr::Side::Left))
                .abs()
            })
            .fold(0.0, f64::max);
        assert!((xc.max_third_derivative_jump() - direct).abs() <= 1e-9 * direct);
    }

    #[test]
    fn short_inputs_and_bad_x_do_not_panic() {
        let xc = XcPolyline::of_points(&[0.0, 1.0], &[0.0, 1.0]).unwrap();
        assert!(xc.e.is_empty());
        assert_eq!(xc.vibrations(), 0);
        assert_eq!(xc.max_third_derivative_jump(), 0.0);
        assert!(XcPolyline::of_points(&[0.0, 0.0, 1.0], &[0.0, 1.0, 2.0]).is_err());
    }
}
