//! The reference frame every catalogue method runs in: the data centred on its bounding box
//! (unless they already lie within [`NEAR`] extents of the origin) and scaled by a power of
//! two to unit size, the result mapped back.
//!
//! Why: a method's arithmetic has thresholds and starting steps in absolute numbers (a
//! quantum, a first step, a regularisation floor); run on the data as given, the same curve at
//! ×8 or shifted by 10^5 was faired differently, slowly or not at all. In the frame every
//! input has the same size, so the result at ×2^k and +offset is the result at ×1, scaled and
//! shifted, to round-off. The scale is an exact power of two, so a result under 2^k scaling is
//! the same bit for bit (the centre scales exactly too); a translation changes the rounding of
//! `p − c` only, at the order of ε·|offset|.
//!
//! What the caller gives in absolute units is mapped in: the tolerance band and restraining
//! radii are multiplied by the scale (exact). What comes back is mapped out: points and grid
//! nodes, and the method's curve or surface record (coordinates, parameters that are lengths,
//! derivatives). A coordinate the method did not change comes back as the input's own bits, so
//! fixed points, clamped ends and a function's x stay bit for bit. Settings and report fields
//! that are lengths are mapped too ([`LENGTH_SETTINGS`], [`LENGTH_EXTRAS`]); other report
//! fields with units (energies, penalties, a smoothing parameter) are the frame's numbers.
//!
//! Coordinates beyond ±[`LARGEST`] are refused before the method runs: squares of their
//! differences, which every method forms, overflow. O(n).

use curve_repr::{Curve, Side, Vector};
use serde_json::Value;

use super::job::{AnyCurve, CurvePoints, Grid, Represented};
use crate::{Constraints, Error, Result};

/// The largest coordinate accepted: its square, and the square of a difference of two such,
/// stays far below `f64::MAX` (≈ 1.8e308) with room for sums over many points.
pub const LARGEST: f64 = 1e150;

/// The settings of the built-in methods given in the points' units (batten's adjustable
/// range, jump-lsq's target RMS displacement, sapidis-farin's largest move as a distance, the
/// surface smoothing spline's displacement sum S_d): the frame scales them with the points.
const LENGTH_SETTINGS: [&str; 4] = ["range", "target-sd", "max-move", "displacement"];

/// The settings among [`LENGTH_SETTINGS`] that bound every point's move, as the tolerance
/// band does.
const MOVE_BOUNDS: [&str; 2] = ["range", "max-move"];

/// Report fields of the built-in methods (in `extras`, at any depth) that are lengths or
/// squared lengths, with their length power: mapped out of the frame. Other fields with units
/// (energies, penalties, a smoothing parameter) stay the frame's numbers.
const LENGTH_EXTRAS: [(&str, i32); 9] = [
    ("sigma", 1),
    ("target_sd", 1),
    ("rms_displacement", 1),
    ("move_bound", 1),
    ("quantum", 1),
    ("displacement_sum", 1),
    ("gcv", 2),
    ("gap", 1),
    ("curvature_jump", -1),
];

/// Data whose bounding-box centre is within this many extents (largest distance from it) of
/// the origin are not moved, only scaled.
pub(crate) const NEAR: f64 = 4.0;

/// A centre and a power-of-two scale: frame = (p − centre) · 2^−exponent.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Frame {
    centre: Vec<f64>,
    exponent: i32,
}

/// `x · 2^n` for any `n` a frame uses, in two exact halves so that 2^n itself never
/// overflows or underflows.
fn times_power_of_two(x: f64, n: i32) -> f64 {
    let half = n / 2;
    x * 2f64.powi(half) * 2f64.powi(n - half)
}

/// E with x = m · 2^E, m ∈ [0.5, 1), for finite x > 0 (subnormals included).
fn binary_exponent(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    if biased == 0 {
        binary_exponent(x * 2f64.powi(64)) - 64
    } else {
        biased - 1022
    }
}

/// Refuses a non-finite coordinate or one beyond ±[`LARGEST`], naming the point (from 0).
pub(crate) fn check_coordinates(rows: impl Iterator<Item = Vec<f64>>, what: &'static str) -> Result<()> {
    for (index, row) in rows.enumerate() {
        if let Some(&value) = row.iter().find(|x| !x.is_finite() || x.abs() > LARGEST) {
            return Err(Error::CoordinateRange { what, index, value });
        }
    }
    Ok(())
}

impl Frame {
    /// The frame of `rows` (coordinates of equal length): the centre of their bounding box
    /// and the power of two just above their largest distance from it along an axis; the
    /// identity scale when every point is the same.
    pub(crate) fn of(rows: &[Vec<f64>]) -> Frame {
        let dimension = rows.first().map_or(0, Vec::len);
        let centre: Vec<f64> = (0..dimension)
            .map(|d| {
                let (lo, hi) = rows
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
                        (lo.min(r[d]), hi.max(r[d]))
                    });
                // Halves first: no overflow, and exact under scaling by 2^k.
                lo / 2.0 + hi / 2.0
            })
            .collect();
        let extent = rows
            .iter()
            .flat_map(|r| r.iter().zip(&centre).map(|(x, c)| (x - c).abs()))
            .fold(0.0, f64::max);
        let exponent = if extent > 0.0 { binary_exponent(extent) } else { 0 };
        // Data within a few of their extents of the origin are scaled only: the offset costs
        // them at most three bits, and their results stay the method's own (scaled exactly).
        let near = centre.iter().all(|c| c.abs() <= NEAR * extent);
        let centre = if near { vec![0.0; dimension] } else { centre };
        Frame { centre, exponent }
    }

    /// Marks the thread as running in this frame (for the data's decimal step, see
    /// [`decimal_quantum`](crate::displacement::decimal_quantum)) until the mark is dropped.
    pub(crate) fn mark(&self) -> crate::displacement::FrameMark {
        let mut centre = [0.0; 3];
        for (c, &x) in centre.iter_mut().zip(&self.centre) {
            *c = x;
        }
        crate::displacement::FrameMark::new(centre, self.exponent)
    }

    /// A coordinate along axis `d` into the frame.
    fn inward(&self, d: usize, x: f64) -> f64 {
        times_power_of_two(x - self.centre[d], -self.exponent)
    }

    /// A coordinate along axis `d` out of the frame.
    fn outward(&self, d: usize, x: f64) -> f64 {
        times_power_of_two(x, self.exponent) + self.centre[d]
    }

    /// A length (a tolerance, a radius) into the frame.
    fn length_to_frame(&self, length: f64) -> f64 {
        times_power_of_two(length, -self.exponent)
    }

    /// A quantity of `length_power` lengths (1 a length, 0 a ratio, −1 a curvature) out of
    /// the frame.
    fn scaled_out(&self, x: f64, length_power: i32) -> f64 {
        times_power_of_two(x, self.exponent * length_power)
    }

    fn points_to_frame<const D: usize>(&self, points: &[Vector<D>]) -> Vec<Vector<D>> {
        points
            .iter()
            .map(|p| Vector::<D>::from_fn(|d, _| self.inward(d, p[d])))
            .collect()
    }

    /// The method's points out of the frame: a coordinate equal to the one the method was
    /// given comes back as the input's own.
    fn points_from_frame<const D: usize>(
        &self,
        original: &[Vector<D>],
        given: &[Vector<D>],
        faired: &[Vector<D>],
    ) -> Vec<Vector<D>> {
        faired
            .iter()
            .enumerate()
            .map(|(i, q)| {
                Vector::<D>::from_fn(|d, _| match (given.get(i), original.get(i)) {
                    (Some(g), Some(o)) if g[d].to_bits() == q[d].to_bits() => o[d],
                    _ => self.outward(d, q[d]),
                })
            })
            .collect()
    }

    pub(crate) fn curve_points_to_frame(&self, points: &CurvePoints) -> CurvePoints {
        match points {
            CurvePoints::Planar(p) => CurvePoints::Planar(self.points_to_frame(p)),
            CurvePoints::Spatial(p) => CurvePoints::Spatial(self.points_to_frame(p)),
        }
    }

    /// `faired` (in the frame) out of it, `given` being what the method was given and
    /// `original` the caller's points.
    pub(crate) fn curve_points_from_frame(
        &self,
        original: &CurvePoints,
        given: &CurvePoints,
        faired: &CurvePoints,
    ) -> CurvePoints {
        match (original, given, faired) {
            (CurvePoints::Planar(o), CurvePoints::Planar(g), CurvePoints::Planar(f)) => {
                CurvePoints::Planar(self.points_from_frame(o, g, f))
            }
            (CurvePoints::Spatial(o), CurvePoints::Spatial(g), CurvePoints::Spatial(f)) => {
                CurvePoints::Spatial(self.points_from_frame(o, g, f))
            }
            // A wrong dimension is the run check's to report.
            _ => faired.clone(),
        }
    }

    pub(crate) fn grid_to_frame(&self, grid: &Grid) -> Grid {
        Grid {
            points: self.points_to_frame(&grid.points),
            ..grid.clone()
        }
    }

    pub(crate) fn grid_from_frame(&self, original: &Grid, given: &Grid, faired: &Grid) -> Grid {
        Grid {
            points: self.points_from_frame(&original.points, &given.points, &faired.points),
            ..faired.clone()
        }
    }

    /// The constraints with their lengths (tolerance, restraining radii) in the frame.
    pub(crate) fn constraints_to_frame(&self, constraints: &Constraints) -> Constraints {
        let mut out = Constraints::default()
            .with_fixed(constraints.fixed().iter().copied())
            .with_end_clamp(constraints.end_clamp());
        if let Some(t) = constraints.tolerance() {
            out = out.with_tolerance(self.length_to_frame(t));
        }
        if let Some(r) = constraints.restraining_radii() {
            out = out.with_restraining_radii(r.iter().map(|&r| self.length_to_frame(r)).collect());
        }
        for join in constraints.joins() {
            let neighbour = join
                .neighbour
                .iter()
                .map(|row| self.points_to_frame(row))
                .collect();
            out = out.with_join(crate::strategies::Join {
                neighbour,
                ..join.clone()
            });
        }
        out
    }

    /// The method's settings with the lengths among them in the frame: a number under one of
    /// [`LENGTH_SETTINGS`], at any depth (a pre-pass's own settings too); `auto`, `inf` and
    /// named rules are left as they are.
    pub(crate) fn settings_to_frame(&self, settings: &Value) -> Value {
        match settings {
            Value::Object(map) => Value::Object(
                map.iter()
                    .map(|(key, value)| {
                        let value = match value.as_f64() {
                            Some(v) if LENGTH_SETTINGS.contains(&key.as_str()) => {
                                serde_json::json!(self.length_to_frame(v))
                            }
                            _ => self.settings_to_frame(value),
                        };
                        (key.clone(), value)
                    })
                    .collect(),
            ),
            other => other.clone(),
        }
    }

    /// A report field out of the frame: the numbers under [`LENGTH_EXTRAS`] scaled by their
    /// length power, at any depth.
    pub(crate) fn extra_from_frame(&self, key: &str, value: Value) -> Value {
        let power = LENGTH_EXTRAS.iter().find(|(k, _)| *k == key).map(|&(_, p)| p);
        match (power, value) {
            (Some(power), Value::Number(n)) => match n.as_f64() {
                Some(v) => serde_json::json!(self.scaled_out(v, power)),
                None => Value::Number(n),
            },
            (_, Value::Object(map)) => Value::Object(
                map.into_iter()
                    .map(|(k, v)| {
                        let v = self.extra_from_frame(&k, v);
                        (k, v)
                    })
                    .collect(),
            ),
            (_, Value::Array(items)) => {
                Value::Array(items.into_iter().map(|v| self.extra_from_frame(key, v)).collect())
            }
            (_, other) => other,
        }
    }

    /// Pulls every moved point back inside its allowed distance when mapping out of the frame
    /// rounded it just outside (the frame's band is the caller's, scaled exactly, so the excess
    /// is a few ulps of the coordinates). O(n).
    ///
    /// `settings` may bound every move too ([`MOVE_BOUNDS`]), in the caller's units.
    pub(crate) fn hold_band<const D: usize>(
        constraints: &Constraints,
        settings: &Value,
        original: &[Vector<D>],
        faired: &mut [Vector<D>],
    ) {
        let bound = MOVE_BOUNDS
            .iter()
            .filter_map(|name| settings.get(*name).and_then(Value::as_f64))
            .fold(f64::INFINITY, f64::min);
        for (index, (p, q)) in original.iter().zip(faired.iter_mut()).enumerate() {
            let allowed = constraints.allowed_distance(index).min(bound);
            if !allowed.is_finite() {
                continue;
            }
            let mut shrink = 1.0;
            for _ in 0..8 {
                let distance = (*q - p).norm();
                if distance <= allowed {
                    break;
                }
                shrink *= 1.0 - 4.0 * f64::EPSILON;
                *q = p + (*q - p) * (allowed / distance * shrink);
            }
            if (*q - p).norm() > allowed {
                *q = *p;
            }
        }
    }

    /// The method's own curves out of the frame. Their parameter is the method's (nurbs-weights
    /// uses parameters normalised to [0, 1], which the frame does not change).
    pub(crate) fn represented_from_frame(&self, represented: Represented) -> Represented {
        Represented {
            before: self.any_curve_from_frame(represented.before),
            after: self.any_curve_from_frame(represented.after),
        }
    }

    fn any_curve_from_frame(&self, curve: AnyCurve) -> AnyCurve {
        match curve {
            AnyCurve::Planar(inner) => AnyCurve::Planar(Box::new(Unframed {
                inner,
                frame: self.clone(),
            })),
            AnyCurve::Spatial(inner) => AnyCurve::Spatial(Box::new(Unframed {
                inner,
                frame: self.clone(),
            })),
        }
    }

    /// A method's `curve` or `surface` record out of the frame, by its `type`: coordinates
    /// shifted and scaled, parameters scaled by their length power (a chord length is a
    /// length, a uniform or normalised parameter none), a k-th derivative by its length power
    /// minus k times the parameter's. A record of a type not known here becomes null (the
    /// report then measures the spline through the points), rather than a record in the
    /// frame's numbers.
    pub(crate) fn record_from_frame(&self, record: Value) -> Value {
        let Value::Object(mut map) = record else {
            return record;
        };
        let parametrization = map
            .get("parametrization")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_owned();
        // The parameter's length power: the exponent of 2 it scales with, halved for the
        // centripetal rule (√length), where 2^(E/2) is exact only for even E.
        let parameter_power = match parametrization.as_str() {
            "x" | "chord-length" | "chord-length-averaged" => 1.0,
            "centripetal" => 0.5,
            _ => 0.0,
        };
        let by_x = parametrization == "x";
        let derivative = |order: f64| 1.0 - order * parameter_power;
        let kind = map.get("type").and_then(Value::as_str).unwrap_or("").to_owned();
        match kind.as_str() {
            "nurbs" => self.map_rows(&mut map, "control_points"),
            "hermite" => {
                self.map_parameters(&mut map, "knots", parameter_power, by_x);
                self.map_rows(&mut map, "points");
                self.scale_rows(&mut map, "tangents", derivative(1.0));
            }
            "natural-cubic-spline" => {
                self.map_parameters(&mut map, "knots", parameter_power, by_x);
                self.map_rows(&mut map, "values");
                self.scale_rows(&mut map, "second_derivatives", derivative(2.0));
            }
            "interpolating-cubic-spline" => {}
            "interpolating-cubic" => self.map_rows(&mut map, "points"),
            "spline-function" => {
                self.map_axis(&mut map, "x", 0);
                self.map_axis(&mut map, "y", 1);
                // c = y''/6: a length over a length squared.
                self.scale_numbers(&mut map, "c", -1.0);
            }
            "ferguson" => {
                // Power-basis coefficients over t ∈ [0, 1] per segment: the first a point, the
                // others derivatives with respect to a parameter without length.
                if let Some(Value::Array(segments)) = map.get_mut("segments") {
                    for segment in segments {
                        if let Value::Array(coefficients) = segment {
                            for (k, c) in coefficients.iter_mut().enumerate() {
                                *c = self.row_from_frame(c, 1.0, k == 0);
                            }
                        }
                    }
                }
            }
            "bicubic" => {
                let power = if parametrization.starts_with("chord-length") {
                    1.0
                } else {
                    0.0
                };
                self.map_parameters(&mut map, "u_knots", power, false);
                self.map_parameters(&mut map, "v_knots", power, false);
                self.map_rows(&mut map, "points");
            }
            _ => return Value::Null,
        }
        Value::Object(map)
    }

    /// A row of coordinates out of the frame: shifted when `shift`, scaled by 2^(E·power).
    fn row_from_frame(&self, row: &Value, power: f64, shift: bool) -> Value {
        let Value::Array(items) = row else {
            return row.clone();
        };
        Value::Array(
            items
                .iter()
                .enumerate()
                .map(|(d, x)| match x.as_f64() {
                    Some(v) if shift && d < self.centre.len() => self.outward(d, v).into(),
                    Some(v) => self.scaled_by_power(v, power).into(),
                    None => x.clone(),
                })
                .collect(),
        )
    }

    /// 2^(E·power) times `v`; a half power is exact for even E only.
    fn scaled_by_power(&self, v: f64, power: f64) -> f64 {
        if power.fract() == 0.0 {
            self.scaled_out(v, power as i32)
        } else {
            v * 2f64.powf(f64::from(self.exponent) * power)
        }
    }

    /// Rows of coordinates (points) out of the frame.
    fn map_rows(&self, map: &mut serde_json::Map<String, Value>, key: &str) {
        if let Some(Value::Array(rows)) = map.get_mut(key) {
            for row in rows {
                *row = self.row_from_frame(row, 1.0, true);
            }
        }
    }

    fn scale_rows(&self, map: &mut serde_json::Map<String, Value>, key: &str, power: f64) {
        if let Some(Value::Array(rows)) = map.get_mut(key) {
            for row in rows {
                *row = self.row_from_frame(row, power, false);
            }
        }
    }

    fn scale_numbers(&self, map: &mut serde_json::Map<String, Value>, key: &str, power: f64) {
        if let Some(Value::Array(items)) = map.get_mut(key) {
            for x in items {
                if let Some(v) = x.as_f64() {
                    *x = self.scaled_by_power(v, power).into();
                }
            }
        }
    }

    fn map_axis(&self, map: &mut serde_json::Map<String, Value>, key: &str, axis: usize) {
        if axis >= self.centre.len() {
            return;
        }
        if let Some(Value::Array(items)) = map.get_mut(key) {
            for x in items {
                if let Some(v) = x.as_f64() {
                    *x = self.outward(axis, v).into();
                }
            }
        }
    }

    /// Parameters out of the frame: x coordinates when `by_x`, else scaled by their power.
    fn map_parameters(&self, map: &mut serde_json::Map<String, Value>, key: &str, power: f64, by_x: bool) {
        if by_x {
            self.map_axis(map, key, 0);
        } else {
            self.scale_numbers(map, key, power);
        }
    }
}

/// A method's curve, computed in the frame, seen in the caller's coordinates (same parameter).
struct Unframed<const D: usize> {
    inner: Box<dyn Curve<D> + Send + Sync>,
    frame: Frame,
}

impl<const D: usize> Curve<D> for Unframed<D> {
    fn domain(&self) -> (f64, f64) {
        self.inner.domain()
    }

    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        let jet = self.inner.jet(t, side);
        let f = &self.frame;
        [
            Vector::<D>::from_fn(|d, _| f.outward(d, jet[0][d])),
            jet[1].map(|x| f.scaled_out(x, 1)),
            jet[2].map(|x| f.scaled_out(x, 1)),
            jet[3].map(|x| f.scaled_out(x, 1)),
        ]
    }

    fn breaks(&self) -> Vec<f64> {
        self.inner.breaks()
    }

    fn jet_on_piece(&self, piece: usize, t: f64) -> [Vector<D>; 4] {
        let jet = self.inner.jet_on_piece(piece, t);
        let f = &self.frame;
        [
            Vector::<D>::from_fn(|d, _| f.outward(d, jet[0][d])),
            jet[1].map(|x| f.scaled_out(x, 1)),
            jet[2].map(|x| f.scaled_out(x, 1)),
            jet[3].map(|x| f.scaled_out(x, 1)),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_scales_exactly_with_the_data() {
        let rows = vec![vec![13.0, -1.0], vec![15.5, 2.25], vec![14.0, 0.1]];
        let frame = Frame::of(&rows);
        assert_eq!(frame.centre, vec![14.25, 0.625]);
        let near = Frame::of(&[vec![3.0, -1.0], vec![5.5, 2.25]]);
        assert_eq!(near.centre, vec![0.0, 0.0]);
        // Largest distance from the centre 1.625 = 0.8125 · 2^1.
        assert_eq!(frame.exponent, 1);
        for k in [-60, -3, 7, 90] {
            let scaled: Vec<Vec<f64>> = rows
                .iter()
                .map(|r| r.iter().map(|x| times_power_of_two(*x, k)).collect())
                .collect();
            let other = Frame::of(&scaled);
            assert_eq!(other.exponent, 1 + k);
            for (a, b) in rows.iter().zip(&scaled) {
                for d in 0..2 {
                    assert_eq!(frame.inward(d, a[d]).to_bits(), other.inward(d, b[d]).to_bits());
                }
            }
        }
        assert_eq!(binary_exponent(f64::MIN_POSITIVE / 8.0), -1024);
        assert_eq!(binary_exponent(1.0), 1);
    }

    #[test]
    fn unchanged_coordinates_keep_their_bits() {
        let original = [Vector::<2>::new(0.1, 1e5 + 0.3), Vector::<2>::new(0.7, 1e5 - 0.2)];
        let frame = Frame::of(&original.iter().map(|p| vec![p.x, p.y]).collect::<Vec<_>>());
        let given = frame.points_to_frame(&original);
        let mut faired = given.clone();
        faired[1].y += 0.25;
        let back = frame.points_from_frame(&original, &given, &faired);
        assert_eq!(back[0], original[0]);
        assert_eq!(back[1].x.to_bits(), original[1].x.to_bits());
        assert!((back[1].y - original[1].y - 0.25 * 2f64.powi(frame.exponent)).abs() < 1e-9);
    }

    #[test]
    fn huge_coordinates_are_refused_naming_the_point() {
        let rows = vec![vec![0.0, 1.0], vec![2e150, 0.0]];
        let message = check_coordinates(rows.into_iter(), "point")
            .unwrap_err()
            .to_string();
        assert!(message.contains("point 1 has the coordinate 2e150"), "{message}");
    }
}
