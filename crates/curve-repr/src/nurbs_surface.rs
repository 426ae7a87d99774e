//! Tensor-product NURBS surfaces (The NURBS Book A3.6 on homogeneous points, then A4.4).

use serde::ser::SerializeStruct;

use crate::bspline::{basis_derivatives, KnotVector};
use crate::nurbs_curve::binomial;
use crate::surface::MAX_PARTIAL_ORDER;
use crate::{Error, Result, Side, Surface, Vec3};

/// A NURBS surface S(u, v) = Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) w_ij P_ij / Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) w_ij
/// with clamped knot vectors in u and v.
///
/// `control_points[i][j]`: i runs along u, j along v. Weights are finite and positive.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    knots_u: KnotVector,
    knots_v: KnotVector,
    /// Row-major: index i·columns + j.
    control_points: Vec<Vec3>,
    weights: Vec<f64>,
    weighted: Vec<Vec3>,
    columns: usize,
}

/// Flattens a rectangular grid, or reports the first ragged row.
fn flatten<T: Copy>(grid: &[Vec<T>], columns: usize) -> Result<Vec<T>> {
    let mut out = Vec::with_capacity(grid.len() * columns);
    for (row, values) in grid.iter().enumerate() {
        if values.len() != columns {
            return Err(Error::RaggedGrid {
                row,
                expected: columns,
                got: values.len(),
            });
        }
        out.extend_from_slice(values);
    }
    Ok(out)
}

impl NurbsSurface {
    /// A surface of degrees (`degree_u`, `degree_v`) with full clamped knot vectors, a control
    /// net `control_points[i][j]` and `weights[i][j]` of the same shape.
    ///
    /// Fails with [`Error::RaggedGrid`] for a non-rectangular net or weight grid,
    /// [`Error::LengthMismatch`] when the weight grid has another number of rows,
    /// [`Error::BadKnots`] / [`Error::BadDegree`] / [`Error::TooFewPoints`] as
    /// [`KnotVector::new`] in each direction, [`Error::NonFinite`] and [`Error::BadWeight`]
    /// (index i·columns + j). O(size of the net).
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        control_points: Vec<Vec<Vec3>>,
        weights: Vec<Vec<f64>>,
    ) -> Result<Self> {
        let rows = control_points.len();
        let columns = control_points.first().map_or(0, Vec::len);
        let points = flatten(&control_points, columns)?;
        if weights.len() != rows {
            return Err(Error::LengthMismatch {
                what: "weight rows",
                expected: rows,
                got: weights.len(),
            });
        }
        let weights = flatten(&weights, columns)?;
        let knots_u = KnotVector::new(degree_u, knots_u, rows)?;
        let knots_v = KnotVector::new(degree_v, knots_v, columns)?;
        crate::vector::check_finite(&points)?;
        crate::nurbs_curve::check_weights(&weights)?;
        let weighted = points.iter().zip(&weights).map(|(p, &w)| p * w).collect();
        Ok(Self {
            knots_u,
            knots_v,
            control_points: points,
            weights,
            weighted,
            columns,
        })
    }

    /// The degrees (p, q).
    pub fn degrees(&self) -> (usize, usize) {
        (self.knots_u.degree(), self.knots_v.degree())
    }

    /// The knot vectors in u and v.
    pub fn knot_vectors(&self) -> (&KnotVector, &KnotVector) {
        (&self.knots_u, &self.knots_v)
    }

    /// The net size (rows along u, columns along v).
    pub fn net_size(&self) -> (usize, usize) {
        (self.knots_u.control_count(), self.columns)
    }

    /// Control point P_ij, if in range.
    pub fn control_point(&self, i: usize, j: usize) -> Option<Vec3> {
        (j < self.columns)
            .then(|| self.control_points.get(i * self.columns + j).copied())
            .flatten()
    }

    /// Weight w_ij, if in range.
    pub fn weight(&self, i: usize, j: usize) -> Option<f64> {
        (j < self.columns)
            .then(|| self.weights.get(i * self.columns + j).copied())
            .flatten()
    }

    /// All partial derivatives S^{(k,l)} for k ≤ `order_u`, l ≤ `order_v` at (u, v), with
    /// one-sided limits at knot lines from `side_u`, `side_v`; result\[k\]\[l\].
    ///
    /// Homogeneous partials A^{(k,l)}, w^{(k,l)} by The NURBS Book A3.6 on the weighted net,
    /// then Eq. 4.20 (A4.4):
    /// S^{(k,l)} = (A^{(k,l)} − Σ_{j=1}^{l} C(l,j) w^{(0,j)} S^{(k,l−j)}
    ///   − Σ_{i=1}^{k} C(k,i) [w^{(i,0)} S^{(k−i,l)} + Σ_{j=1}^{l} C(l,j) w^{(i,j)} S^{(k−i,l−j)}]) / w.
    /// O(p q (order_u + 1)(order_v + 1) + order⁴).
    pub fn derivatives(
        &self,
        u: f64,
        v: f64,
        order_u: usize,
        order_v: usize,
        side_u: Side,
        side_v: Side,
    ) -> Vec<Vec<Vec3>> {
        let (p, q) = self.degrees();
        let span_u = self.knots_u.span(u, side_u);
        let span_v = self.knots_v.span(v, side_v);
        let nu = basis_derivatives(self.knots_u.knots(), p, span_u, u, order_u);
        let nv = basis_derivatives(self.knots_v.knots(), q, span_v, v, order_v);
        let (first_u, first_v) = (span_u - p, span_v - q);
        let mut a = vec![vec![Vec3::zeros(); order_v + 1]; order_u + 1];
        let mut w = vec![vec![0.0; order_v + 1]; order_u + 1];
        for (k, row_u) in nu.iter().enumerate() {
            for (l, row_v) in nv.iter().enumerate() {
                let mut sum = Vec3::zeros();
                let mut weight = 0.0;
                for (r, &bu) in row_u.iter().enumerate() {
                    for (s, &bv) in row_v.iter().enumerate() {
                        let index = (first_u + r) * self.columns + first_v + s;
                        if let (Some(pw), Some(&wi)) = (self.weighted.get(index), self.weights.get(index)) {
                            sum += pw * (bu * bv);
                            weight += wi * bu * bv;
                        }
                    }
                }
                a[k][l] = sum;
                w[k][l] = weight;
            }
        }
        let mut out = vec![vec![Vec3::zeros(); order_v + 1]; order_u + 1];
        for k in 0..=order_u {
            for l in 0..=order_v {
                let mut value = a[k][l];
                for j in 1..=l {
                    value -= out[k][l - j] * (binomial(l, j) * w[0][j]);
                }
                for i in 1..=k {
                    value -= out[k - i][l] * (binomial(k, i) * w[i][0]);
                    let mut inner = Vec3::zeros();
                    for j in 1..=l {
                        inner += out[k - i][l - j] * (binomial(l, j) * w[i][j]);
                    }
                    value -= inner * binomial(k, i);
                }
                out[k][l] = value / w[0][0];
            }
        }
        out
    }
}

impl Surface for NurbsSurface {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (self.knots_u.domain(), self.knots_v.domain())
    }

    /// One-sided at knot lines: `Side::Left` uses the span ending at the knot.
    fn partial_from(&self, u: f64, v: f64, du: usize, dv: usize, side_u: Side, side_v: Side) -> Option<Vec3> {
        if du > MAX_PARTIAL_ORDER || dv > MAX_PARTIAL_ORDER {
            return None;
        }
        let d = self.derivatives(u, v, du, dv, side_u, side_v);
        d.get(du).and_then(|row| row.get(dv)).copied()
    }
}

impl serde::Serialize for NurbsSurface {
    /// `{"type": "nurbs-surface", "degree_u", "degree_v", "knots_u", "knots_v",
    /// "control_points": [[[x, y, z], …], …], "weights": [[…], …]}`.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        let columns = self.columns.max(1);
        let points: Vec<Vec<[f64; 3]>> = self
            .control_points
            .chunks(columns)
            .map(|row| row.iter().map(|p| [p.x, p.y, p.z]).collect())
            .collect();
        let weights: Vec<Vec<f64>> = self.weights.chunks(columns).map(<[f64]>::to_vec).collect();
        let (p, q) = self.degrees();
        let mut s = serializer.serialize_struct("NurbsSurface", 7)?;
        s.serialize_field("type", "nurbs-surface")?;
        s.serialize_field("degree_u", &p)?;
        s.serialize_field("degree_v", &q)?;
        s.serialize_field("knots_u", self.knots_u.knots())?;
        s.serialize_field("knots_v", self.knots_v.knots())?;
        s.serialize_field("control_points", &points)?;
        s.serialize_field("weights", &weights)?;
        s.end()
    }
}
