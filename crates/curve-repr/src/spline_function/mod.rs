//! The cubic spline function y(x) of Han et al. (§3.1–3.3, Eq. 1–18): a C2 piecewise cubic
//! through points (x_i, y_i) with x strictly increasing, stored as its knot values y_i and
//! c_i = y''(x_i)/6 (Han's convention), with the unit-spline sensitivities ∂c_i/∂y_j and a
//! windowed update after points move.
//!
//! - [`EndCondition`]: parabolic runout (Han's choice, the default), natural, clamped.
//! - `recurrence`: the three-moment equations (Eq. 4) solved by Han's forward and backward
//!   recurrences (Eq. 5–10), O(n).
//! - `sensitivity`: c̃_i^j (Eq. 12–17) for every end condition and every j, O(1) per entry.
//! - `update`: [`SplineFunction::set_y`], O(window) per moved point.
//!
//! Indices count from 0 in the API (Han counts from 1).

mod end_condition;
mod recurrence;
pub mod sensitivity;
pub mod update;

pub use end_condition::EndCondition;
pub use sensitivity::SensitivityColumn;
pub use update::{LocalChange, UPDATE_WINDOW};

use recurrence::{chord_slope, effective_end, step, Elimination};
use sensitivity::LogProducts;

use crate::vector::check_finite_values;
use crate::{Curve, Error, Interpolant, Result, Side, Vec2};

/// A cubic spline function y(x) through (x_i, y_i), i = 0..n, x strictly increasing
/// (Han et al. §3.1).
///
/// On [x_i, x_{i+1}], with h_i = x_{i+1} − x_i and m_i = (y_{i+1} − y_i)/h_i (Han Eq. 2),
///
/// y(x) = y_i + m_i(x − x_i) − (x − x_i)(x_{i+1} − x)/h_i · [c_i(2x_{i+1} − x − x_i) + c_{i+1}(x_{i+1} + x − 2x_i)].
///
/// Outside [x_0, x_{n−1}] the end pieces are extended. As a [`Curve<2>`] it is the graph
/// (x, y(x)) with parameter x; as an [`Interpolant<2>`] its points are (x_i, y_i) at
/// parameters x_i, and only y may move.
///
/// Building costs O(n) time and memory (about 16 numbers per point: x, y, c, the
/// elimination factors and pivots, the three central sensitivities of each column and the
/// prefix sums that make every sensitivity O(1)).
#[derive(Clone, Debug)]
pub struct SplineFunction {
    x: Vec<f64>,
    y: Vec<f64>,
    c: Vec<f64>,
    end: EndCondition,
    elimination: Elimination,
    forward_log: LogProducts,
    backward_log: LogProducts,
    /// (c̃_{j−1}^j, c̃_j^j, c̃_{j+1}^j) for every j: they depend on x and the end condition
    /// only, so they are computed once (O(n)) and every sensitivity look-up is O(1) without a
    /// division.
    central: Vec<[f64; 3]>,
}

impl SplineFunction {
    /// Builds the spline function through (x_i, y_i) with the given end condition. O(n).
    ///
    /// Fails with [`Error::LengthMismatch`] if `y` and `x` differ in length,
    /// [`Error::TooFewPoints`] below 2 points (every end condition; runout on 2 points is the
    /// straight line, on 3 the parabola, see [`EndCondition::ParabolicRunout`]),
    /// [`Error::NonFinite`] on a non-finite x, y or end slope, [`Error::NotIncreasing`] if x
    /// does not increase strictly, and [`Error::Singular`] if the numbers overflow.
    pub fn new(x: &[f64], y: &[f64], end: EndCondition) -> Result<Self> {
        if y.len() != x.len() {
            return Err(Error::LengthMismatch {
                what: "y of a spline function",
                expected: x.len(),
                got: y.len(),
            });
        }
        let needed = end.min_points();
        if x.len() < needed {
            return Err(Error::TooFewPoints {
                what: "a cubic spline function",
                needed,
                got: x.len(),
            });
        }
        check_finite_values("x", x)?;
        check_finite_values("y", y)?;
        if let EndCondition::Clamped {
            start_slope,
            end_slope,
        } = end
        {
            check_finite_values("end slope", &[start_slope, end_slope])?;
        }
        if let Some(index) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
            return Err(Error::NotIncreasing {
                what: "x",
                index,
                previous: x[index - 1],
                value: x[index],
            });
        }
        if let Some(index) = (1..x.len()).find(|&i| !(x[i] - x[i - 1]).is_finite()) {
            return Err(Error::NonFinite {
                what: "x step",
                index: index - 1,
            });
        }
        let effective = effective_end(end, x.len());
        let elimination = Elimination::new(x, effective)?;
        let c = elimination.solve(x, y, effective)?;
        let forward_log = LogProducts::new(&elimination.forward_factor);
        let backward_log = LogProducts::new(&elimination.backward_factor);
        let mut spline = Self {
            x: x.to_vec(),
            y: y.to_vec(),
            c,
            end,
            elimination,
            forward_log,
            backward_log,
            central: Vec::new(),
        };
        spline.central = (0..x.len())
            .map(|j| spline.compute_central_sensitivities(j))
            .collect();
        Ok(spline)
    }

    /// Recomputes c from x and y with a full O(n) solve, clearing the rounding that many
    /// [`set_y`](SplineFunction::set_y) calls accumulate. Fails with [`Error::Singular`],
    /// leaving the spline unchanged, if the numbers overflow.
    pub fn rebuild(&mut self) -> Result<()> {
        self.c = self.elimination.solve(&self.x, &self.y, self.effective_end())?;
        Ok(())
    }

    /// The abscissae x_i.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The ordinates y_i.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// c_i = y''(x_i)/6 (Han's fairness indicator, the x–c plot of §3.2).
    pub fn c(&self) -> &[f64] {
        &self.c
    }

    /// The end condition the spline was built with.
    pub fn end_condition(&self) -> EndCondition {
        self.end
    }

    /// The end condition as imposed (runout on 2 points becomes natural).
    fn effective_end(&self) -> EndCondition {
        effective_end(self.end, self.x.len())
    }

    /// The interval [x_i, x_{i+1}] whose piece gives the value at `t` from `side`.
    fn interval(&self, t: f64, side: Side) -> usize {
        let count = match side {
            Side::Right => self.x.partition_point(|&xi| xi <= t),
            Side::Left => self.x.partition_point(|&xi| xi < t),
        };
        count.saturating_sub(1).min(self.x.len().saturating_sub(2))
    }

    /// y, y', y'', y''' at `t`, limits from `side` at a knot (y''' jumps there; the others are
    /// continuous). Han Eq. 2 for y; its derivatives, which give Eq. 3 at the ends of an
    /// interval. O(log n) (binary search for the interval).
    pub fn jet_at(&self, t: f64, side: Side) -> [f64; 4] {
        self.jet_in(self.interval(t, side), t)
    }

    /// [`jet_at`](Self::jet_at) on interval `i` ([x_i, x_{i+1}], clamped to the last one; `t`
    /// normally inside it): no search. NaN for an empty spline. O(1).
    pub fn jet_in(&self, i: usize, t: f64) -> [f64; 4] {
        let i = i.min(self.x.len().saturating_sub(2));
        let (Some(&x0), Some(&y0), Some(&c0), Some(&c1)) =
            (self.x.get(i), self.y.get(i), self.c.get(i), self.c.get(i + 1))
        else {
            return [f64::NAN; 4];
        };
        let h = step(&self.x, i);
        let m = chord_slope(&self.x, &self.y, i);
        let u = t - x0;
        // Eq. 2, with x_{i+1} − x = h − u, 2x_{i+1} − x − x_i = 2h − u, x_{i+1} + x − 2x_i = h + u.
        let value = y0 + m * u - u * (h - u) / h * (c0 * (2.0 * h - u) + c1 * (h + u));
        // Eq. 3: y'(x_i+) = m_i − h_i(2c_i + c_{i+1}); y'' = 6c linear; y''' = 6(c_{i+1} − c_i)/h_i.
        let slope = m - h * (2.0 * c0 + c1) + 6.0 * c0 * u + 3.0 * (c1 - c0) * u * u / h;
        let second = 6.0 * (c0 * (h - u) + c1 * u) / h;
        let third = 6.0 * (c1 - c0) / h;
        [value, slope, second, third]
    }

    /// y(t).
    pub fn value(&self, t: f64) -> f64 {
        self.jet_at(t, Side::Right)[0]
    }

    /// y'(t).
    pub fn first_derivative(&self, t: f64) -> f64 {
        self.jet_at(t, Side::Right)[1]
    }

    /// y''(t).
    pub fn second_derivative(&self, t: f64) -> f64 {
        self.jet_at(t, Side::Right)[2]
    }

    /// y'''(t), from `side` at a knot (the first and last knots use their only interval).
    pub fn third_derivative(&self, t: f64, side: Side) -> f64 {
        self.jet_at(t, side)[3]
    }

    /// E_s = ∫_{x_0}^{x_{n−1}} y''(x)² dx, exact: y'' is linear on each interval, and an
    /// interval of length h with end values a = 6c_i, b = 6c_{i+1} adds h(a² + ab + b²)/3
    /// (Han's E_s). O(n).
    pub fn second_derivative_energy(&self) -> f64 {
        self.c
            .windows(2)
            .zip(self.x.windows(2))
            .map(|(c, x)| 12.0 * (x[1] - x[0]) * (c[0] * c[0] + c[0] * c[1] + c[1] * c[1]))
            .sum()
    }
}

/// The jet of the graph (x, y(x)) at x = `t` from y's jet.
fn graph_jet(t: f64, [value, slope, second, third]: [f64; 4]) -> [Vec2; 4] {
    [
        Vec2::new(t, value),
        Vec2::new(1.0, slope),
        Vec2::new(0.0, second),
        Vec2::new(0.0, third),
    ]
}

impl Curve<2> for SplineFunction {
    fn domain(&self) -> (f64, f64) {
        (
            self.x.first().copied().unwrap_or(0.0),
            self.x.last().copied().unwrap_or(0.0),
        )
    }

    /// (x, y), (1, y'), (0, y''), (0, y''') at parameter x = `t`.
    fn jet(&self, t: f64, side: Side) -> [Vec2; 4] {
        graph_jet(t, self.jet_at(t, side))
    }

    fn jet_on_piece(&self, piece: usize, t: f64) -> [Vec2; 4] {
        graph_jet(t, self.jet_in(piece, t))
    }

    /// The x_i.
    fn breaks(&self) -> Vec<f64> {
        self.x.clone()
    }
}

impl Interpolant<2> for SplineFunction {
    fn point_count(&self) -> usize {
        self.x.len()
    }

    /// (x_i, y_i); an index out of range (against the trait's contract) gives a NaN point
    /// rather than a panic.
    fn point(&self, index: usize) -> Vec2 {
        match (self.x.get(index), self.y.get(index)) {
            (Some(&x), Some(&y)) => Vec2::new(x, y),
            _ => Vec2::new(f64::NAN, f64::NAN),
        }
    }

    /// x_i (NaN for an index out of range, see [`point`](Interpolant::point)).
    fn parameter(&self, index: usize) -> f64 {
        self.x.get(index).copied().unwrap_or(f64::NAN)
    }

    /// Moves y through [`set_y`](SplineFunction::set_y) (O(window) per point). A move must
    /// keep x_i exactly, else [`Error::InvalidMove`]; the spline is then left unchanged.
    fn move_points(&mut self, moves: &[(usize, Vec2)]) -> Result<()> {
        let n = self.x.len();
        let mut y_moves = Vec::with_capacity(moves.len());
        for &(index, point) in moves {
            let Some(&x) = self.x.get(index) else {
                return Err(Error::IndexOutOfRange {
                    what: "data points",
                    index,
                    len: n,
                });
            };
            if !point.x.is_finite() || !point.y.is_finite() {
                return Err(Error::NonFinite { what: "point", index });
            }
            if point.x != x {
                return Err(Error::InvalidMove {
                    index,
                    reason: "a spline function's point may move in y only (x must stay x_i)",
                });
            }
            y_moves.push((index, point.y));
        }
        self.set_y(&y_moves)
    }
}
