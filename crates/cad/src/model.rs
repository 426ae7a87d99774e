//! What a CAD file holds: exact B-spline curves and surfaces, with the faired data points
//! they pass through, units and a tolerance.
//!
//! Every representation of `curve-repr` becomes a [`CadCurve`] or [`CadSurface`] without
//! approximation (see `curve_repr::convert`): a spline function y(x) as a planar cubic with
//! x(t) = t, a Hermite spline on single knots, a C1 Ferguson chain on double knots, a NURBS
//! as it is, a bicubic spline surface on single knots. Geometry is held in 3D (a planar curve
//! has z = 0 and remembers that it is planar), as every CAD format stores it.

use curve_repr::{
    BicubicSplineSurface, CubicPieces, Curve, EndCondition, HermiteSpline, JoinRule, NurbsCurve,
    NurbsSurface, SplineFunction, Surface, Vec3, Vector,
};

use crate::{Error, Result, Units};

/// How the faired points were measured, which decides how a rebuild counts curvature (the
/// one kind of the whole library, from `curve-repr`).
pub use curve_repr::CurveKind;

/// An exact B-spline (or NURBS) curve for a CAD file, with the data points it passes through.
#[derive(Clone, Debug, PartialEq)]
pub struct CadCurve {
    /// A name for the file (IGES entity label, STEP item name, DXF layer); may be empty.
    pub name: String,
    /// The curve, in 3D; a planar curve has z = 0.
    pub curve: NurbsCurve<3>,
    /// 2 for a planar curve in the xy plane, 3 otherwise.
    pub dimension: usize,
    /// Function or parametric.
    pub kind: CurveKind,
    /// The faired points the curve passes through (empty for a curve read from a file).
    pub points: Vec<Vec3>,
    /// Their parameters on `curve`, one per point.
    pub parameters: Vec<f64>,
}

/// An exact B-spline (or NURBS) surface for a CAD file, with the grid it passes through.
#[derive(Clone, Debug, PartialEq)]
pub struct CadSurface {
    /// A name for the file; may be empty.
    pub name: String,
    /// The surface.
    pub surface: NurbsSurface,
    /// The grid points P_ij it passes through, flat with index i·(v count) + j (empty for a
    /// surface read from a file).
    pub points: Vec<Vec3>,
    /// The u parameters of the grid lines i.
    pub u_parameters: Vec<f64>,
    /// The v parameters of the grid lines j.
    pub v_parameters: Vec<f64>,
}

/// One faired shape: a curve or a surface.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A curve.
    Curve(CadCurve),
    /// A surface.
    Surface(CadSurface),
}

/// The contents of a CAD file: curves, surfaces, their unit and the model's tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct CadModel {
    /// The curves, in file order.
    pub curves: Vec<CadCurve>,
    /// The surfaces, in file order.
    pub surfaces: Vec<CadSurface>,
    /// The length unit of the coordinates.
    pub units: Units,
    /// The model's resolution: IGES's minimum user-intended resolution, STEP's distance
    /// uncertainty; DXF has none and reads back as 0.
    pub tolerance: f64,
}

/// A point of `D` ≤ 3 coordinates in 3D, the missing ones 0.
pub(crate) fn lift<const D: usize>(p: &Vector<D>) -> Vec3 {
    Vec3::from_fn(|i, _| if i < D { p[i] } else { 0.0 })
}

fn check_dimension<const D: usize>() -> Result<()> {
    if (2..=3).contains(&D) {
        Ok(())
    } else {
        Err(Error::Unsupported(format!(
            "a curve in {D} dimensions: CAD files hold curves in 2D or 3D"
        )))
    }
}

/// A NURBS curve of `D` ≤ 3 dimensions in 3D, knots and weights unchanged.
pub(crate) fn lift_curve<const D: usize>(curve: &NurbsCurve<D>) -> Result<NurbsCurve<3>> {
    Ok(NurbsCurve::new(
        curve.degree(),
        curve.knots().to_vec(),
        curve.control_points().iter().map(lift).collect(),
        curve.weights().to_vec(),
    )?)
}

/// The first two coordinates of a 3D curve (a planar curve's xy), knots and weights unchanged.
pub(crate) fn planar_curve(curve: &NurbsCurve<3>) -> Result<NurbsCurve<2>> {
    Ok(NurbsCurve::new(
        curve.degree(),
        curve.knots().to_vec(),
        curve
            .control_points()
            .iter()
            .map(|p| curve_repr::Vec2::new(p.x, p.y))
            .collect(),
        curve.weights().to_vec(),
    )?)
}

impl CadCurve {
    /// A curve with no data points (as read from a file): planar (`dimension` 2) when every
    /// control point has z = 0, parametric.
    pub fn new(curve: NurbsCurve<3>) -> Self {
        let dimension = if curve.control_points().iter().all(|p| p.z == 0.0) {
            2
        } else {
            3
        };
        Self {
            name: String::new(),
            curve,
            dimension,
            kind: CurveKind::Parametric,
            points: Vec::new(),
            parameters: Vec::new(),
        }
    }

    /// The spline function y(x) as the planar cubic (x(t), y(t)) with x(t) = t
    /// ([`SplineFunction::to_bspline`]), through its points at parameters x_i. O(n).
    pub fn from_spline_function(spline: &SplineFunction) -> Result<Self> {
        let curve = lift_curve(&spline.to_bspline()?)?;
        let points = spline
            .x()
            .iter()
            .zip(spline.y())
            .map(|(&x, &y)| Vec3::new(x, y, 0.0))
            .collect();
        Ok(Self {
            name: String::new(),
            curve,
            dimension: 2,
            kind: CurveKind::Function,
            points,
            parameters: spline.x().to_vec(),
        })
    }

    /// A Hermite spline in 2D or 3D on single knots ([`HermiteSpline::to_bspline`]), through
    /// its points at their parameters. O(n).
    pub fn from_hermite<const D: usize>(spline: &HermiteSpline<D>) -> Result<Self> {
        check_dimension::<D>()?;
        Self::from_nurbs(&spline.to_bspline()?, spline.points(), spline.parameters())
    }

    /// A piecewise cubic (e.g. Okada's C1 Ferguson chain, [`CubicPieces::from_unit_power`])
    /// with the fewest knots its continuity allows ([`JoinRule::default`]), through `points`
    /// at `parameters`. O(n).
    pub fn from_pieces<const D: usize>(
        pieces: &CubicPieces<D>,
        points: &[Vector<D>],
        parameters: &[f64],
    ) -> Result<Self> {
        check_dimension::<D>()?;
        Self::from_nurbs(&pieces.to_bspline(JoinRule::default())?, points, parameters)
    }

    /// A NURBS curve as it is (e.g. the weight-faired curve of Nowacki et al.), through
    /// `points` at `parameters` (both may be empty). Fails with
    /// [`curve_repr::Error::LengthMismatch`] when they differ in number. O(n).
    pub fn from_nurbs<const D: usize>(
        curve: &NurbsCurve<D>,
        points: &[Vector<D>],
        parameters: &[f64],
    ) -> Result<Self> {
        check_dimension::<D>()?;
        if points.len() != parameters.len() {
            return Err(curve_repr::Error::LengthMismatch {
                what: "parameters (one per data point)",
                expected: points.len(),
                got: parameters.len(),
            }
            .into());
        }
        Ok(Self {
            name: String::new(),
            curve: lift_curve(curve)?,
            dimension: D,
            kind: CurveKind::Parametric,
            points: points.iter().map(lift).collect(),
            parameters: parameters.to_vec(),
        })
    }

    /// The spline the `fair` report measures for a function, through (x_i, y_i): the spline
    /// function with the parabolic-runout end condition ([`from_spline_function`](Self::from_spline_function)).
    /// For a method whose own representation is that spline (or that has none of its own).
    pub fn measured_function(x: &[f64], y: &[f64]) -> Result<Self> {
        Self::from_spline_function(&SplineFunction::new(x, y, EndCondition::ParabolicRunout)?)
    }

    /// The spline the `fair` report measures for a parametric curve in 2D or 3D: the natural
    /// cubic spline over chord length ([`from_hermite`](Self::from_hermite)).
    pub fn measured_parametric<const D: usize>(points: &[Vector<D>]) -> Result<Self> {
        Self::from_hermite(&HermiteSpline::natural(points)?)
    }

    /// The same curve with a name.
    pub fn with_name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// The same curve measured as `kind` (a NURBS of a function's points, say).
    pub fn with_kind(mut self, kind: CurveKind) -> Self {
        self.kind = kind;
        self
    }

    /// Whether the curve is closed: its end point equals its start point (within 1e-12 of
    /// its size).
    pub fn is_closed(&self) -> bool {
        let (a, b) = self.curve.domain();
        let gap = (self.curve.point(a) - self.curve.point(b)).norm();
        gap <= 1e-12 * size(self.curve.control_points())
    }

    /// Whether every weight is the same (a polynomial B-spline; IGES PROP3 = 1).
    pub fn is_polynomial(&self) -> bool {
        let w = self.curve.weights();
        w.iter().all(|&v| v == w[0])
    }

    /// Points to fair again: the data points if the curve has them, else the curve at its
    /// distinct knots (for a curve converted exactly, these are the faired points to
    /// rounding), each knot span split into `per_span` equal steps. O(n · per_span).
    pub fn sample_points(&self, per_span: usize) -> (Vec<Vec3>, Vec<f64>) {
        if !self.points.is_empty() {
            return (self.points.clone(), self.parameters.clone());
        }
        let breaks = self.curve.knot_vector().distinct();
        let per_span = per_span.max(1);
        let mut parameters = Vec::with_capacity((breaks.len() - 1) * per_span + 1);
        for w in breaks.windows(2) {
            for k in 0..per_span {
                parameters.push(w[0] + (w[1] - w[0]) * k as f64 / per_span as f64);
            }
        }
        parameters.extend(breaks.last());
        let points = parameters.iter().map(|&t| self.curve.point(t)).collect();
        (points, parameters)
    }
}

impl CadSurface {
    /// A surface with no data points (as read from a file).
    pub fn new(surface: NurbsSurface) -> Self {
        Self {
            name: String::new(),
            surface,
            points: Vec::new(),
            u_parameters: Vec::new(),
            v_parameters: Vec::new(),
        }
    }

    /// The bicubic spline surface of Zhang–Cheng §4 as a bicubic B-spline surface on single
    /// knots ([`BicubicSplineSurface::to_bspline`]), through its grid. O(m·n).
    pub fn from_bicubic(surface: &BicubicSplineSurface) -> Result<Self> {
        Ok(Self {
            name: String::new(),
            surface: surface.to_bspline()?,
            points: surface.points().to_vec(),
            u_parameters: surface.u_knots().to_vec(),
            v_parameters: surface.v_knots().to_vec(),
        })
    }

    /// The surface the `fair` report measures for a grid `grid[i][j]`: the bicubic spline
    /// surface of Zhang–Cheng §4 with chord-length averaged knots ([`from_bicubic`](Self::from_bicubic)).
    pub fn measured(grid: &[Vec<Vec3>]) -> Result<Self> {
        Self::from_bicubic(&BicubicSplineSurface::new(grid)?)
    }

    /// The same surface with a name.
    pub fn with_name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// The surface's control points, row by row (i along u).
    pub fn control_rows(&self) -> Vec<Vec<Vec3>> {
        let (rows, columns) = self.surface.net_size();
        (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| self.surface.control_point(i, j).unwrap_or_else(Vec3::zeros))
                    .collect()
            })
            .collect()
    }

    /// The surface's weights, row by row.
    pub fn weight_rows(&self) -> Vec<Vec<f64>> {
        let (rows, columns) = self.surface.net_size();
        (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| self.surface.weight(i, j).unwrap_or(1.0))
                    .collect()
            })
            .collect()
    }

    /// Whether every weight is the same.
    pub fn is_polynomial(&self) -> bool {
        let rows = self.weight_rows();
        let first = rows.first().and_then(|r| r.first()).copied().unwrap_or(1.0);
        rows.iter().flatten().all(|&w| w == first)
    }

    /// The grid point P_ij at its parameters, on the surface.
    pub fn point_at(&self, u: f64, v: f64) -> Vec3 {
        self.surface.eval(u, v)
    }
}

/// The larger of the bounding-box diagonal and the largest coordinate magnitude (0 for no
/// points): the scale of this crate's relative tolerances.
pub fn size(points: &[Vec3]) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    let mut low = Vec3::from_element(f64::INFINITY);
    let mut high = Vec3::from_element(f64::NEG_INFINITY);
    for p in points {
        low = low.inf(p);
        high = high.sup(p);
    }
    (high - low)
        .norm()
        .max(points.iter().map(|p| p.amax()).fold(0.0, f64::max))
}

impl CadModel {
    /// A model of one shape, with a unit and a tolerance.
    pub fn of(shape: Shape, units: Units, tolerance: f64) -> Self {
        let mut model = Self {
            curves: Vec::new(),
            surfaces: Vec::new(),
            units,
            tolerance,
        };
        model.push(shape);
        model
    }

    /// Adds a shape.
    pub fn push(&mut self, shape: Shape) {
        match shape {
            Shape::Curve(c) => self.curves.push(c),
            Shape::Surface(s) => self.surfaces.push(s),
        }
    }

    /// The largest coordinate magnitude of every control point (IGES Global parameter 20).
    pub fn max_coordinate(&self) -> f64 {
        let curves = self.curves.iter().flat_map(|c| c.curve.control_points().iter());
        let surfaces = self
            .surfaces
            .iter()
            .flat_map(|s| s.control_rows().into_iter().flatten());
        curves
            .copied()
            .chain(surfaces)
            .map(|p| p.amax())
            .fold(0.0, f64::max)
    }

    /// The size ([`size`]) of every control point together.
    pub fn size(&self) -> f64 {
        let mut all: Vec<Vec3> = self
            .curves
            .iter()
            .flat_map(|c| c.curve.control_points().iter().copied())
            .collect();
        for s in &self.surfaces {
            all.extend(s.control_rows().into_iter().flatten());
        }
        size(&all)
    }

    /// Whether the model holds nothing.
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty() && self.surfaces.is_empty()
    }
}
