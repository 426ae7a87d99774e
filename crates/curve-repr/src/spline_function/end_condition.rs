//! The end conditions of a cubic spline function (Han et al. §3.1, the three kinds of
//! "practical lofting").

use serde::{Deserialize, Serialize};

/// The two extra conditions that, with the n − 2 three-moment equations (Han Eq. 4), fix a
/// cubic spline function y(x) through n points.
///
/// With c_i = y''(x_i)/6 (Han's convention), and indices counted from 1 as in the paper:
///
/// | variant | first row | last row |
/// |---|---|---|
/// | [`ParabolicRunout`](EndCondition::ParabolicRunout) | c_1 − c_2 = 0 | c_n − c_{n−1} = 0 |
/// | [`Natural`](EndCondition::Natural) | c_1 = 0 | c_n = 0 |
/// | [`Clamped`](EndCondition::Clamped) | 2h_1c_1 + h_1c_2 = m_1 − y'_1 | h_{n−1}c_{n−1} + 2h_{n−1}c_n = y'_n − m_{n−1} |
///
/// where h_i = x_{i+1} − x_i and m_i = (y_{i+1} − y_i)/h_i; the clamped rows are Han Eq. 3
/// solved for the given end slopes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum EndCondition {
    /// c_1 = c_2 and c_{n−1} = c_n: the end intervals are parabolas (Han's choice, condition ③;
    /// "produces best results and requires no user interaction"). The default.
    ///
    /// Degenerate cases: with n = 3 the spline is the interpolating parabola (all c_i equal);
    /// with n = 2 the conditions leave one free parameter and the spline is taken to be the
    /// straight line (c_1 = c_2 = 0), the member of that family of least ∫y''² dx.
    #[default]
    ParabolicRunout,
    /// c_1 = c_n = 0: zero curvature at both ends (condition ②).
    Natural,
    /// Given end slopes y'(x_1) and y'(x_n) (condition ①).
    Clamped {
        /// y'(x_1).
        start_slope: f64,
        /// y'(x_n).
        end_slope: f64,
    },
}

impl EndCondition {
    /// The least number of points that defines a spline function with this end condition:
    /// 2 for every variant (see [`ParabolicRunout`](EndCondition::ParabolicRunout) for
    /// what 2 and 3 points give there).
    pub fn min_points(&self) -> usize {
        2
    }
}
