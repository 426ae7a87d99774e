//! Global interpolation by a NUBS (The NURBS Book A9.1) and by a NURBS with given weights.
//!
//! With parameters ū_k and averaged knots (Eq. 9.8, or Eq. 9.22 with end derivatives) the
//! conditions C(ū_k) = D_k of a NURBS with weights w_i read
//! Σ_i N_{i,p}(ū_k) w_i P_i = D_k Σ_i N_{i,p}(ū_k) w_i,
//! linear in the homogeneous points Q_i = w_i P_i with the *weight-independent* collocation
//! matrix N_{i,p}(ū_k). A given end derivative C'(ū) = T (with C(ū) = D) follows from
//! A = W C, A' = W' C + W C':
//! Σ_i N'_{i,p}(ū) Q_i = W'(ū) D + W(ū) T  (W = Σ N_i w_i),
//! again with a weight-independent row (The NURBS Book Eq. 9.11–9.12 for unit weights).
//! So [`Interpolation`] factors the banded collocation matrix once (faer's sparse LU) and each
//! new weight vector costs one O(n) right-hand side and one O(n) solve: what the weight
//! optimisation of Nowacki et al. (FAIRSHAPE 1996, §3) needs for every trial.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Lu;
use faer::sparse::{SparseColMat, Triplet};

use super::{check_weights, NurbsCurve};
use crate::bspline::{basis_derivatives, KnotVector};
use crate::curve::MAX_ORDER;
use crate::{Curve, Error, Interpolant, Parametrization, Result, Side, Vector};

/// Settings of [`Interpolation`]: the degree (default 3, cubic) and optional end tangents.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InterpolationSettings<const D: usize> {
    degree: usize,
    end_tangents: Option<(Vector<D>, Vector<D>)>,
}

impl<const D: usize> Default for InterpolationSettings<D> {
    fn default() -> Self {
        Self {
            degree: 3,
            end_tangents: None,
        }
    }
}

impl<const D: usize> InterpolationSettings<D> {
    /// Sets the degree p ≥ 1.
    pub fn with_degree(mut self, degree: usize) -> Self {
        self.degree = degree;
        self
    }

    /// Prescribes the end derivatives C'(0) = `start`, C'(1) = `end`, with respect to the
    /// normalised parameter u ∈ [0, 1] (so a unit tangent direction is usually scaled by the
    /// total parameter length before normalisation, e.g. the polygon length for chord-length
    /// parameters). Adds two control points (The NURBS Book §9.2.2).
    pub fn with_end_tangents(mut self, start: Vector<D>, end: Vector<D>) -> Self {
        self.end_tangents = Some((start, end));
        self
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The end tangents, if any.
    pub fn end_tangents(&self) -> Option<(Vector<D>, Vector<D>)> {
        self.end_tangents
    }
}

/// What a row of the collocation system imposes.
#[derive(Clone, Copy, Debug)]
enum Condition {
    /// C(ū_k) = D_k.
    Point(usize),
    /// C'(ū_k) = start tangent (false) or end tangent (true), with C(ū_k) = D_k.
    Tangent(usize, bool),
}

/// One row: the condition, the first column and the p + 1 basis values (or derivatives).
#[derive(Clone, Debug)]
struct Row {
    condition: Condition,
    first: usize,
    values: Vec<f64>,
    /// Basis values at the same parameter (for W(ū) in a tangent row's right-hand side).
    point_values: Vec<f64>,
}

/// A factored global interpolation problem: data points, their parameters in [0, 1], the
/// averaged knot vector, and the LU factors of the collocation matrix, ready to be solved for
/// any weights ([`Interpolation::solve`]) or moved points ([`Interpolation::solve_points`]).
///
/// Building costs O(n p²) for the matrix and one sparse LU of a banded matrix (O(n p²));
/// every solve then costs O(n p).
#[derive(Clone, Debug)]
pub struct Interpolation<const D: usize> {
    knots: KnotVector,
    params: Vec<f64>,
    points: Vec<Vector<D>>,
    end_tangents: Option<(Vector<D>, Vector<D>)>,
    rows: Vec<Row>,
    lu: Lu<usize, f64>,
}

fn check_params(params: &[f64]) -> Result<()> {
    crate::vector::check_finite_values("parameter", params)?;
    for (index, w) in params.windows(2).enumerate() {
        if w[1] <= w[0] {
            return Err(Error::NotIncreasing {
                what: "parameters",
                index: index + 1,
                previous: w[0],
                value: w[1],
            });
        }
    }
    Ok(())
}

impl<const D: usize> Interpolation<D> {
    /// Interpolation of `points` at parameters from `parametrization`, normalised to [0, 1].
    /// Fails like [`Interpolation::new`] and on repeated consecutive points.
    pub fn with_parametrization(
        points: &[Vector<D>],
        parametrization: Parametrization,
        settings: InterpolationSettings<D>,
    ) -> Result<Self> {
        let params = parametrization.normalized_parameters(points)?;
        Self::new(points, &params, settings)
    }

    /// Interpolation of `points` at the strictly increasing `params`, which are mapped
    /// affinely onto [0, 1] (the end tangents of `settings` are derivatives with respect to
    /// that normalised parameter).
    ///
    /// Fails with [`Error::TooFewPoints`] (fewer than 2 points, or fewer control points than
    /// p + 1), [`Error::LengthMismatch`], [`Error::NonFinite`], [`Error::NotIncreasing`],
    /// [`Error::BadDegree`] and [`Error::Singular`] if the factorisation fails.
    pub fn new(points: &[Vector<D>], params: &[f64], settings: InterpolationSettings<D>) -> Result<Self> {
        if params.len() != points.len() {
            return Err(Error::LengthMismatch {
                what: "parameters",
                expected: points.len(),
                got: params.len(),
            });
        }
        crate::vector::check_finite(points)?;
        check_params(params)?;
        if let Some((a, b)) = settings.end_tangents {
            crate::vector::check_finite(&[a, b]).map_err(|e| match e {
                Error::NonFinite { index, .. } => Error::NonFinite {
                    what: "end tangent",
                    index,
                },
                other => other,
            })?;
        }
        let (Some(&t0), Some(&t1)) = (params.first(), params.last()) else {
            return Err(Error::TooFewPoints {
                what: "interpolation",
                needed: 2,
                got: points.len(),
            });
        };
        if points.len() < 2 {
            return Err(Error::TooFewPoints {
                what: "interpolation",
                needed: 2,
                got: points.len(),
            });
        }
        let span_length = t1 - t0;
        let mut params: Vec<f64> = params.iter().map(|t| (t - t0) / span_length).collect();
        params[0] = 0.0;
        if let Some(last) = params.last_mut() {
            *last = 1.0;
        }
        check_params(&params)?;
        let with_tangents = settings.end_tangents.is_some();
        let degree = settings.degree;
        let knots = KnotVector::averaged(degree, &params, with_tangents)?;
        let last = points.len() - 1;
        let mut conditions = Vec::with_capacity(points.len() + 2);
        for k in 0..points.len() {
            conditions.push(Condition::Point(k));
            if with_tangents && k == 0 {
                conditions.push(Condition::Tangent(0, false));
            }
            if with_tangents && k + 1 == last {
                conditions.push(Condition::Tangent(last, true));
            }
        }
        let mut rows = Vec::with_capacity(conditions.len());
        let mut triplets = Vec::with_capacity(conditions.len() * (degree + 1));
        for (r, condition) in conditions.iter().enumerate() {
            let (k, order) = match *condition {
                Condition::Point(k) => (k, 0),
                Condition::Tangent(k, _) => (k, 1),
            };
            let u = params[k];
            let span = knots.span(u, Side::Right);
            let basis = basis_derivatives(knots.knots(), degree, span, u, order);
            let first = span - degree;
            let values = basis[order].clone();
            for (j, &v) in values.iter().enumerate() {
                if v != 0.0 {
                    triplets.push(Triplet::new(r, first + j, v));
                }
            }
            rows.push(Row {
                condition: *condition,
                first,
                values,
                point_values: basis[0].clone(),
            });
        }
        let n = rows.len();
        let singular = Error::Singular {
            what: "factoring the NURBS interpolation matrix",
        };
        let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
            .map_err(|_| singular.clone())?;
        let lu = matrix.sp_lu().map_err(|_| singular)?;
        Ok(Self {
            knots,
            params,
            points: points.to_vec(),
            end_tangents: settings.end_tangents,
            rows,
            lu,
        })
    }

    /// The knot vector (averaged, Eq. 9.8 or 9.22).
    pub fn knot_vector(&self) -> &KnotVector {
        &self.knots
    }

    /// The data parameters, normalised to [0, 1].
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// The data points.
    pub fn points(&self) -> &[Vector<D>] {
        &self.points
    }

    /// The end tangents, if prescribed.
    pub fn end_tangents(&self) -> Option<(Vector<D>, Vector<D>)> {
        self.end_tangents
    }

    /// Number of control points (and of weights a solve needs): n + 1, or n + 3 with end
    /// tangents.
    pub fn control_count(&self) -> usize {
        self.knots.control_count()
    }

    /// The interpolating NUBS (all weights 1), The NURBS Book A9.1. O(n p).
    pub fn nubs(&self) -> Result<NurbsCurve<D>> {
        self.solve(&vec![1.0; self.control_count()])
    }

    /// The NURBS with the given `weights` through every data point (and with the end
    /// tangents). O(n p): one right-hand side, one solve with the stored factors.
    ///
    /// Fails with [`Error::LengthMismatch`] or [`Error::BadWeight`], and with
    /// [`Error::Singular`] if the solution is not finite.
    pub fn solve(&self, weights: &[f64]) -> Result<NurbsCurve<D>> {
        self.solve_points(&self.points, weights)
    }

    /// The homogeneous control points Q_i = w_i P_i of the interpolant with `weights`
    /// (The NURBS Book A9.1 on the homogeneous points, see the module docs): the solution of
    /// the weight-independent collocation system, **linear in the weights**, so that for any
    /// real vector δ (signs unrestricted, no positivity check) Q(w + εδ) = Q(w) + ε Q(δ).
    /// That is what differentiating a criterion of the interpolant with respect to the
    /// weights needs: one O(n p) solve per direction. Fails with [`Error::LengthMismatch`],
    /// [`Error::NonFinite`] on non-finite weights, [`Error::Singular`] on a non-finite result.
    pub fn homogeneous_points(&self, weights: &[f64]) -> Result<Vec<Vector<D>>> {
        let n = self.control_count();
        if weights.len() != n {
            return Err(Error::LengthMismatch {
                what: "weights",
                expected: n,
                got: weights.len(),
            });
        }
        crate::vector::check_finite_values("weight", weights)?;
        let rhs = self.homogeneous(&self.points, weights)?;
        let q: Vec<Vector<D>> = (0..n).map(|i| Vector::<D>::from_fn(|c, _| rhs[(i, c)])).collect();
        if q.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::Singular {
                what: "solving the NURBS interpolation system",
            });
        }
        Ok(q)
    }

    /// Q = w_i P_i for `points` and `weights` (lengths checked by the callers): assemble the
    /// right-hand side, solve with the stored factors, refine once. O(n p).
    fn homogeneous(&self, points: &[Vector<D>], weights: &[f64]) -> Result<faer::Mat<f64>> {
        let n = self.control_count();
        let weight_at = |row: &Row, values: &[f64]| -> f64 {
            values
                .iter()
                .enumerate()
                .map(|(j, v)| v * weights.get(row.first + j).copied().unwrap_or(0.0))
                .sum()
        };
        let mut rhs = faer::Mat::<f64>::zeros(n, D);
        for (r, row) in self.rows.iter().enumerate() {
            let value = match row.condition {
                Condition::Point(k) => points.get(k).map(|p| p * weight_at(row, &row.values)),
                Condition::Tangent(k, at_end) => {
                    let tangent = self.end_tangents.map(|(a, b)| if at_end { b } else { a });
                    match (points.get(k), tangent) {
                        (Some(p), Some(t)) => {
                            Some(p * weight_at(row, &row.values) + t * weight_at(row, &row.point_values))
                        }
                        _ => None,
                    }
                }
            }
            .ok_or(Error::Singular {
                what: "assembling the NURBS interpolation right-hand side",
            })?;
            for c in 0..D {
                rhs[(r, c)] = value[c];
            }
        }
        let original = rhs.clone();
        self.lu.solve_in_place(rhs.as_mut());
        // One step of iterative refinement: the rows mix point conditions (entries O(1)) and
        // derivative conditions (entries O(p/Δu)), and with strongly varying weights the
        // first solve leaves a residual well above round-off in the derivative rows.
        let mut residual = original;
        for (r, row) in self.rows.iter().enumerate() {
            for (j, value) in row.values.iter().enumerate() {
                for c in 0..D {
                    residual[(r, c)] -= value * rhs[(row.first + j, c)];
                }
            }
        }
        self.lu.solve_in_place(residual.as_mut());
        rhs += &residual;
        Ok(rhs)
    }

    /// Like [`Interpolation::solve`] for other data points at the same parameters (a fairing
    /// move). Fails also on a wrong count or non-finite points.
    pub fn solve_points(&self, points: &[Vector<D>], weights: &[f64]) -> Result<NurbsCurve<D>> {
        let n = self.control_count();
        if weights.len() != n {
            return Err(Error::LengthMismatch {
                what: "weights",
                expected: n,
                got: weights.len(),
            });
        }
        if points.len() != self.points.len() {
            return Err(Error::LengthMismatch {
                what: "data points",
                expected: self.points.len(),
                got: points.len(),
            });
        }
        crate::vector::check_finite(points)?;
        check_weights(weights)?;
        let rhs = self.homogeneous(points, weights)?;
        let control_points: Vec<Vector<D>> = (0..n)
            .map(|i| Vector::<D>::from_fn(|c, _| rhs[(i, c)] / weights[i]))
            .collect();
        if control_points.iter().any(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(Error::Singular {
                what: "solving the NURBS interpolation system",
            });
        }
        NurbsCurve::from_parts(self.knots.clone(), control_points, weights.to_vec())
    }
}

/// An interpolating NURBS curve that keeps its [`Interpolation`] and weights, so that moved
/// data points or new weights cost one O(n) solve ([`Interpolant`]).
#[derive(Clone, Debug)]
pub struct NurbsInterpolant<const D: usize> {
    interpolation: Interpolation<D>,
    weights: Vec<f64>,
    curve: NurbsCurve<D>,
}

impl<const D: usize> NurbsInterpolant<D> {
    /// The curve of `interpolation` with `weights`. Fails like [`Interpolation::solve`].
    pub fn new(interpolation: Interpolation<D>, weights: Vec<f64>) -> Result<Self> {
        let curve = interpolation.solve(&weights)?;
        Ok(Self {
            interpolation,
            weights,
            curve,
        })
    }

    /// The interpolating NUBS (unit weights).
    pub fn nubs(interpolation: Interpolation<D>) -> Result<Self> {
        let weights = vec![1.0; interpolation.control_count()];
        Self::new(interpolation, weights)
    }

    /// Replaces the weights and re-solves; unchanged on error. O(n).
    pub fn set_weights(&mut self, weights: Vec<f64>) -> Result<()> {
        self.curve = self.interpolation.solve(&weights)?;
        self.weights = weights;
        Ok(())
    }

    /// The current curve.
    pub fn curve(&self) -> &NurbsCurve<D> {
        &self.curve
    }

    /// The interpolation problem.
    pub fn interpolation(&self) -> &Interpolation<D> {
        &self.interpolation
    }
}

impl<const D: usize> Curve<D> for NurbsInterpolant<D> {
    fn domain(&self) -> (f64, f64) {
        self.curve.domain()
    }

    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        let d = self.curve.derivatives(t, MAX_ORDER, side);
        [d[0], d[1], d[2], d[3]]
    }

    fn breaks(&self) -> Vec<f64> {
        self.curve.breaks()
    }
}

impl<const D: usize> Interpolant<D> for NurbsInterpolant<D> {
    fn point_count(&self) -> usize {
        self.interpolation.points.len()
    }

    /// Data point `index`; NaN coordinates for an index out of range.
    fn point(&self, index: usize) -> Vector<D> {
        self.interpolation
            .points
            .get(index)
            .copied()
            .unwrap_or_else(|| Vector::repeat(f64::NAN))
    }

    /// The normalised parameter of point `index`; NaN for an index out of range.
    fn parameter(&self, index: usize) -> f64 {
        self.interpolation.params.get(index).copied().unwrap_or(f64::NAN)
    }

    /// One O(n) solve with the stored factors, whatever the number of moves.
    fn move_points(&mut self, moves: &[(usize, Vector<D>)]) -> Result<()> {
        let mut points = self.interpolation.points.clone();
        let len = points.len();
        for &(index, position) in moves {
            let slot = points.get_mut(index).ok_or(Error::IndexOutOfRange {
                what: "data points",
                index,
                len,
            })?;
            if position.iter().any(|c| !c.is_finite()) {
                return Err(Error::NonFinite { what: "point", index });
            }
            *slot = position;
        }
        let curve = self.interpolation.solve_points(&points, &self.weights)?;
        self.interpolation.points = points;
        self.curve = curve;
        Ok(())
    }
}
