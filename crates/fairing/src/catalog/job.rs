//! What a method is given (a job) and what it gives back (a run), for curves and surfaces,
//! in either dimension: the one shape every method of the catalogue shares, so that the
//! command, config pipelines and bindings run any of them the same way.

use std::any::Any;
use std::collections::BTreeMap;

use curve_repr::{Curve, Vec2, Vec3, Vector};
use serde::{Deserialize, Serialize};

use super::Catalog;
use crate::{Constraints, FairingResult};

/// How a curve's points are read (one type for the catalogue, the measures and CAD output).
pub use curve_repr::CurveKind;

/// The points of a curve, planar or spatial.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CurvePoints {
    /// Points (x, y).
    Planar(Vec<Vec2>),
    /// Points (x, y, z).
    Spatial(Vec<Vec3>),
}

impl CurvePoints {
    /// Number of points.
    pub fn len(&self) -> usize {
        match self {
            CurvePoints::Planar(p) => p.len(),
            CurvePoints::Spatial(p) => p.len(),
        }
    }

    /// Whether there is no point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// 2 or 3.
    pub fn dimension(&self) -> usize {
        match self {
            CurvePoints::Planar(_) => 2,
            CurvePoints::Spatial(_) => 3,
        }
    }

    /// The points as vectors of dimension `D`, when they have it.
    pub fn as_dimension<const D: usize>(&self) -> Option<&[Vector<D>]> {
        let any: &dyn Any = match self {
            CurvePoints::Planar(p) => p,
            CurvePoints::Spatial(p) => p,
        };
        any.downcast_ref::<Vec<Vector<D>>>().map(Vec::as_slice)
    }

    /// Points of dimension `D` (2 or 3; `None` for another dimension).
    pub fn from_vectors<const D: usize>(points: Vec<Vector<D>>) -> Option<CurvePoints> {
        let mut any: Box<dyn Any> = Box::new(points);
        any = match any.downcast::<Vec<Vec2>>() {
            Ok(planar) => return Some(CurvePoints::Planar(*planar)),
            Err(other) => other,
        };
        any.downcast::<Vec<Vec3>>()
            .ok()
            .map(|spatial| CurvePoints::Spatial(*spatial))
    }

    /// The coordinates of point `index`, if it exists.
    pub fn coordinates(&self, index: usize) -> Option<Vec<f64>> {
        match self {
            CurvePoints::Planar(p) => p.get(index).map(|v| vec![v.x, v.y]),
            CurvePoints::Spatial(p) => p.get(index).map(|v| vec![v.x, v.y, v.z]),
        }
    }

    /// Points from coordinate rows that all have `dimension` (2 or 3) entries; `None` for
    /// another dimension or a row of the wrong length.
    pub fn from_rows(dimension: usize, rows: &[Vec<f64>]) -> Option<CurvePoints> {
        match dimension {
            2 => rows
                .iter()
                .map(|r| match r.as_slice() {
                    [x, y] => Some(Vec2::new(*x, *y)),
                    _ => None,
                })
                .collect::<Option<Vec<_>>>()
                .map(CurvePoints::Planar),
            3 => rows
                .iter()
                .map(|r| match r.as_slice() {
                    [x, y, z] => Some(Vec3::new(*x, *y, *z)),
                    _ => None,
                })
                .collect::<Option<Vec<_>>>()
                .map(CurvePoints::Spatial),
            _ => None,
        }
    }

    /// Index of the first point with a NaN or infinite coordinate.
    pub fn first_non_finite(&self) -> Option<usize> {
        match self {
            CurvePoints::Planar(p) => p.iter().position(|v| !v.iter().all(|c| c.is_finite())),
            CurvePoints::Spatial(p) => p.iter().position(|v| !v.iter().all(|c| c.is_finite())),
        }
    }

    /// The coordinates of every point as rows.
    pub fn rows(&self) -> Vec<Vec<f64>> {
        match self {
            CurvePoints::Planar(p) => p.iter().map(|v| vec![v.x, v.y]).collect(),
            CurvePoints::Spatial(p) => p.iter().map(|v| vec![v.x, v.y, v.z]).collect(),
        }
    }

    /// The distance of every point from the same point of `other` (as many as both have).
    pub fn distances(&self, other: &CurvePoints) -> Vec<f64> {
        match (self, other) {
            (CurvePoints::Planar(a), CurvePoints::Planar(b)) => {
                a.iter().zip(b).map(|(p, q)| (p - q).norm()).collect()
            }
            (CurvePoints::Spatial(a), CurvePoints::Spatial(b)) => {
                a.iter().zip(b).map(|(p, q)| (p - q).norm()).collect()
            }
            _ => Vec::new(),
        }
    }

    /// Indices of the points that differ from the same point of `other` (bit for bit).
    pub fn differences(&self, other: &CurvePoints) -> Vec<usize> {
        let (a, b) = (self.rows(), other.rows());
        a.iter()
            .zip(&b)
            .enumerate()
            .filter(|(_, (p, q))| p != q)
            .map(|(i, _)| i)
            .collect()
    }
}

/// A curve of either dimension behind the [`Curve`] trait: what criteria and indicators of
/// the catalogue are evaluated on.
pub enum AnyCurve {
    /// A planar curve.
    Planar(Box<dyn Curve<2> + Send + Sync>),
    /// A spatial curve.
    Spatial(Box<dyn Curve<3> + Send + Sync>),
}

impl AnyCurve {
    /// Boxes a curve of dimension `D` (2 or 3; `None` for another dimension).
    pub fn new<const D: usize, C: Curve<D> + Send + Sync + 'static>(curve: C) -> Option<AnyCurve> {
        let boxed: Box<dyn Curve<D> + Send + Sync> = Box::new(curve);
        let mut any: Box<dyn Any> = Box::new(boxed);
        any = match any.downcast::<Box<dyn Curve<2> + Send + Sync>>() {
            Ok(planar) => return Some(AnyCurve::Planar(*planar)),
            Err(other) => other,
        };
        any.downcast::<Box<dyn Curve<3> + Send + Sync>>()
            .ok()
            .map(|spatial| AnyCurve::Spatial(*spatial))
    }

    /// 2 or 3.
    pub fn dimension(&self) -> usize {
        match self {
            AnyCurve::Planar(_) => 2,
            AnyCurve::Spatial(_) => 3,
        }
    }

    /// The curve as a curve of dimension `D`, when it has it.
    pub fn as_dimension<const D: usize>(&self) -> Option<&(dyn Curve<D> + Send + Sync)> {
        let any: &dyn Any = match self {
            AnyCurve::Planar(c) => c,
            AnyCurve::Spatial(c) => c,
        };
        any.downcast_ref::<Box<dyn Curve<D> + Send + Sync>>()
            .map(|b| &**b)
    }
}

impl std::fmt::Debug for AnyCurve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "AnyCurve({}D)", self.dimension())
    }
}

/// The curves a method's result is represented by, when that is not the spline the report
/// measures (the curve through the points of `docs/CONTRACT.md`'s definitions): e.g. nurbs-weights
/// keeps the points and changes the weights of its NURBS. The report's energies and criteria
/// are then evaluated on these.
#[derive(Debug)]
pub struct Represented {
    /// The method's representation of the input.
    pub before: AnyCurve,
    /// Its representation of the result.
    pub after: AnyCurve,
}

/// Everything a curve method gets.
#[derive(Clone, Copy)]
pub struct CurveJob<'a> {
    /// The name of the catalogue entry that runs (a preset's own name), for messages.
    pub method: &'a str,
    /// The points.
    pub points: &'a CurvePoints,
    /// Function or parametric.
    pub kind: CurveKind,
    /// Fixed points, tolerance band, end clamp (and restraining radii, if a program sets
    /// them).
    pub constraints: &'a Constraints,
    /// The bad points (`--points`), for the methods that take them; empty otherwise.
    pub bad_points: &'a [usize],
    /// The catalogue, for criteria and indicators chosen by name.
    pub catalog: &'a Catalog,
}

impl std::fmt::Debug for CurveJob<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CurveJob")
            .field("method", &self.method)
            .field("points", &self.points.len())
            .field("kind", &self.kind)
            .field("constraints", self.constraints)
            .field("bad_points", &self.bad_points)
            .finish()
    }
}

/// What a curve method gives back: everything the report needs.
#[derive(Debug)]
pub struct CurveRun {
    /// The faired points: same count, order and dimension as the input (unchanged for
    /// methods that change weights).
    pub points: CurvePoints,
    /// Iterations (steps) made.
    pub iterations: usize,
    /// Indices of the points whose final position differs from the input.
    pub moved: Vec<usize>,
    /// Time of the fairing itself, in milliseconds (no parsing or writing).
    pub elapsed_ms: f64,
    /// Why the run stopped, in kebab-case (`strategy-done`, `max-iterations`, `converged`,
    /// `tolerance`, `no-candidate`, ...): present for every method, one spelling.
    pub termination: String,
    /// The faired curve as represented, for the report's `curve`; its fields depend on the
    /// representation (a `type` field names it).
    pub curve: serde_json::Value,
    /// Method-specific report fields (written at the report's top level).
    pub extras: BTreeMap<String, serde_json::Value>,
    /// The method's own curves, when they are not the measured spline (see [`Represented`]).
    pub represented: Option<Represented>,
}

impl CurveRun {
    /// A run from a [`Pipeline`](crate::Pipeline)'s result: points, iterations, moved,
    /// elapsed time and termination; `curve` null, `extras` with the stages' reports when
    /// there are several.
    pub fn from_result<const D: usize>(result: FairingResult<D>) -> CurveRun {
        let mut extras = BTreeMap::new();
        if result.stages.len() > 1 {
            extras.insert(
                "stages".to_owned(),
                serde_json::to_value(&result.stages).unwrap_or_default(),
            );
        }
        CurveRun {
            points: CurvePoints::from_vectors(result.points).unwrap_or(CurvePoints::Planar(Vec::new())),
            iterations: result.iterations,
            moved: result.moved,
            elapsed_ms: result.elapsed.as_secs_f64() * 1e3,
            termination: result.termination.name().to_owned(),
            curve: serde_json::Value::Null,
            extras,
            represented: None,
        }
    }
}

/// A surface grid P_ij, i = 0..rows, j = 0..columns, stored row by row.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    /// Number of i values.
    pub rows: usize,
    /// Number of j values.
    pub columns: usize,
    /// The points, `points[i * columns + j]`.
    pub points: Vec<Vec3>,
}

impl Grid {
    /// The point P_ij, if inside the grid.
    pub fn get(&self, i: usize, j: usize) -> Option<&Vec3> {
        if i < self.rows && j < self.columns {
            self.points.get(i * self.columns + j)
        } else {
            None
        }
    }

    /// The grid as rows of points.
    pub fn to_rows(&self) -> Vec<Vec<Vec3>> {
        self.points
            .chunks(self.columns.max(1))
            .map(<[Vec3]>::to_vec)
            .collect()
    }

    /// The flat indices (row by row) of the boundary nodes: first and last row and column.
    pub fn boundary(&self) -> Vec<usize> {
        let (rows, columns) = (self.rows, self.columns.max(1));
        (0..self.points.len())
            .filter(|&k| {
                let (i, j) = (k / columns, k % columns);
                i == 0 || j == 0 || i + 1 == rows || j + 1 == columns
            })
            .collect()
    }
}

/// Everything a surface method gets. Point indices (fixed points in the constraints, bad
/// points) count the grid row by row from 0 (k = i · columns + j).
#[derive(Clone, Copy)]
pub struct SurfaceJob<'a> {
    /// The name of the catalogue entry that runs.
    pub method: &'a str,
    /// The grid.
    pub grid: &'a Grid,
    /// Fixed points, tolerance band, end clamp (`g0`: the boundary is fixed).
    pub constraints: &'a Constraints,
    /// The bad points (`--points`), for the methods that take them.
    pub bad_points: &'a [usize],
    /// The catalogue.
    pub catalog: &'a Catalog,
}

impl SurfaceJob<'_> {
    /// The grid nodes (i, j) a surface method must keep: the fixed points, and the whole
    /// boundary when the end clamp is `g0`. O(m + n + fixed).
    pub fn fixed_nodes<T: FromIterator<(usize, usize)>>(&self) -> T {
        let columns = self.grid.columns.max(1);
        let mut fixed: Vec<usize> = self.constraints.fixed().iter().copied().collect();
        if self.constraints.end_clamp() == crate::EndClamp::G0 {
            fixed.extend(self.grid.boundary());
        }
        fixed.into_iter().map(|k| (k / columns, k % columns)).collect()
    }
}

impl std::fmt::Debug for SurfaceJob<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SurfaceJob")
            .field("method", &self.method)
            .field("rows", &self.grid.rows)
            .field("columns", &self.grid.columns)
            .field("constraints", self.constraints)
            .field("bad_points", &self.bad_points)
            .finish()
    }
}

/// What a surface method gives back.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceRun {
    /// The faired grid, same size.
    pub grid: Grid,
    /// Iterations (steps) made.
    pub iterations: usize,
    /// Indices (row by row) of the grid points that moved.
    pub moved: Vec<usize>,
    /// Time of the fairing itself, in milliseconds.
    pub elapsed_ms: f64,
    /// Why the run stopped, kebab-case.
    pub termination: String,
    /// The faired surface for the report's `curve`.
    pub surface: serde_json::Value,
    /// Method-specific report fields.
    pub extras: BTreeMap<String, serde_json::Value>,
}
