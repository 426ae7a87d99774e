//! The surface baseline: a tensor-product cubic smoothing spline, coordinate by coordinate,
//! over the grid's parameters — the surface analogue of the curve baseline
//! ([`SmoothingSpline`], csaps's convention), and what csaps's `NdGridCubicSmoothingSpline`
//! computes on a grid.
//!
//! The grid P_ij (i = 0..m along u, j = 0..n along v) gets the averaged knots of its bicubic
//! surface (chord length by default, [`BicubicSplineSurface`]'s `u_knots`/`v_knots`). Along
//! one direction the smoothing spline's values at the sites are linear in the data,
//! f = A(p) y (module docs of [`smoothing_spline`](super::smoothing_spline): Reinsch's
//! equations, `(p R + (1 − p) QᵀΣQ) u = Qᵀ y`, `f = y − (1 − p) Σ Q u`). The tensor-product
//! smoothing spline's values at the grid are
//!
//! F = A_u(p_u) · P · A_v(p_v)ᵀ,
//!
//! each row smoothed along v, then each column of the result along u (the two passes
//! commute). This is csaps's `NdGridCubicSmoothingSpline` evaluated at its own grid (checked
//! against a fixture it wrote, `data/reference/surface_smoothing_csaps.json`).
//!
//! **Beyond csaps** (which has neither):
//! - *Closed directions* ([`Closure`], detected as for [`SurfaceFairing`](super::SurfaceFairing)):
//!   along a closed direction the lines are periodic smoothing splines (the same equations
//!   with Q and R cyclic: the spline is C2 across the seam, solved densely once per
//!   direction, O(N³) for N distinct sites, then O(N²) per line), and the repeated line is
//!   written from the first, so the seam stays closed exactly.
//! - *Held nodes*: fixed nodes and the nodes of a pole (a boundary line collapsed to a point)
//!   get weight +∞ (σ = 0) in both passes, so they keep their positions bit for bit; a pole
//!   stays one point.
//!
//! **The smoothing.** With `p` given, both directions use it. With `p` auto, each direction
//! gets csaps's trace rule `p = 1 / (1 + tr(R)/tr(QᵀΣQ))` (as csaps's `NdGrid…` with
//! `smooth=None` does). With a target displacement S_d = Σ_ij |F_ij − P_ij| (`displacement`),
//! both directions' ratios (1 − p)/p are scaled by one factor 10^s from their trace-rule
//! values and s is found by bisection (S_d grows with s) to a relative 1e-9: the baseline at
//! the same S_d as a fairing, which is how the papers' methods are compared against it.
//!
//! Cost: O(m·n) per evaluation on open directions, about 100 evaluations to match a
//! displacement; closed directions add the dense periodic solve.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, GridTopology, Parametrization, Vec3, Vector};
use nalgebra::DMatrix;

use super::smoothing_spline::{SmoothingSettings, SmoothingSpline};
use super::surface::Closure;
use crate::state::strategy_error;
use crate::{Error, Result};

/// The strategy's name, as `fair methods` lists it (a surface method).
pub const NAME: &str = "smoothing-spline";

/// Settings of [`SurfaceSmoothing`]: the parameters of the catalogue's surface
/// `smoothing-spline`. Default: csaps's trace rule per direction, closures detected,
/// chord-length knots.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct SurfaceSmoothingSettings {
    /// Smoothing parameter in [0, 1] for both directions (0: least-squares lines, 1: interpolation) or auto.
    ///
    /// `auto` (None): csaps's trace rule in each direction, or the value matching
    /// `displacement` when that is given.
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0, "maximum" = 1))]
    pub p: Option<f64>,
    /// Target S_d = Σ|ΔP_ij| to match by choosing the smoothing, or auto (no target).
    ///
    /// Needs `p` auto. A target beyond what the smoothest fit reaches gives that fit (the
    /// run's termination says `displacement-unreachable`).
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0))]
    pub displacement: Option<f64>,
    /// Closed directions: auto (where the last grid line repeats the first), open, u, v, both.
    pub closed: Closure,
    /// Knots, averaged over the grid lines: chord-length or uniform.
    pub parametrization: Parametrization,
    /// Nodes that must not move, (i, j). Not a parameter of the catalogue (`--fixed`).
    #[serde(skip)]
    pub fixed: Vec<(usize, usize)>,
}

impl Default for SurfaceSmoothingSettings {
    fn default() -> Self {
        Self {
            p: None,
            displacement: None,
            closed: Closure::Auto,
            parametrization: Parametrization::ChordLength,
            fixed: Vec::new(),
        }
    }
}

impl SurfaceSmoothingSettings {
    /// Checks the ranges: p in [0, 1], the displacement finite and not negative, not both
    /// given.
    pub fn validate(&self) -> Result<()> {
        if let Some(p) = self.p {
            if !(0.0..=1.0).contains(&p) {
                return Err(Error::BadParameter {
                    name: "p",
                    value: p.to_string(),
                    reason: "must lie in [0, 1] (or be auto)",
                });
            }
        }
        if let Some(d) = self.displacement {
            if !(d.is_finite() && d >= 0.0) {
                return Err(Error::BadParameter {
                    name: "displacement",
                    value: d.to_string(),
                    reason: "must be a finite non-negative number (or auto)",
                });
            }
            if self.p.is_some() {
                return Err(Error::BadParameter {
                    name: "displacement",
                    value: d.to_string(),
                    reason: "chooses p itself: give p = auto with it",
                });
            }
        }
        Ok(())
    }

    /// Sets p for both directions.
    pub fn with_p(mut self, p: f64) -> Self {
        self.p = Some(p);
        self
    }
    /// Sets the displacement S_d to match.
    pub fn with_displacement(mut self, displacement: f64) -> Self {
        self.displacement = Some(displacement);
        self
    }
    /// Sets the closed directions.
    pub fn with_closed(mut self, closed: Closure) -> Self {
        self.closed = closed;
        self
    }
    /// Sets the knot rule.
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }
    /// Sets the fixed nodes.
    pub fn with_fixed(mut self, fixed: impl IntoIterator<Item = (usize, usize)>) -> Self {
        self.fixed = fixed.into_iter().collect();
        self
    }
}

/// What [`SurfaceSmoothing::run`] returns.
#[derive(Clone, Debug)]
pub struct SurfaceSmoothingResult {
    /// The smoothed grid's bicubic surface (its knots averaged from the smoothed points,
    /// periodic along the closed directions).
    pub surface: BicubicSplineSurface,
    /// The smoothing parameters used along u and v.
    pub p: (f64, f64),
    /// S_d = Σ|ΔP_ij| over every grid node (both copies of a seam node).
    pub displacement: f64,
    /// Whether a target displacement was asked for and not reached (the smoothest fit
    /// tried is returned).
    pub unreachable: bool,
    /// The closures and poles used.
    pub topology: GridTopology,
    /// Nodes whose final position differs from the input, i-major.
    pub moved: Vec<(usize, usize)>,
    /// Time of the smoothing itself.
    pub elapsed: std::time::Duration,
}

/// The tensor-product smoothing spline of a grid; see the [module docs](self).
#[derive(Clone, Debug, Default)]
pub struct SurfaceSmoothing {
    settings: SurfaceSmoothingSettings,
}

/// One direction's smoother: the sites, closure, held nodes per line and p.
struct Direction {
    /// Sites t_0..t_{N} (the last is the period's end on a closed direction).
    knots: Vec<f64>,
    closed: bool,
}

impl Direction {
    /// Distinct sites along the direction.
    fn distinct(&self) -> usize {
        if self.closed {
            self.knots.len() - 1
        } else {
            self.knots.len()
        }
    }

    /// csaps's trace rule for unit weights (the periodic analogue on a closed direction).
    fn trace_p(&self) -> f64 {
        let h = steps(&self.knots);
        let (tr_r, tr_q) = if self.closed {
            let n = h.len();
            let mut tr_r = 0.0;
            let mut tr_q = 0.0;
            for i in 0..n {
                let (a, b) = (h[(i + n - 1) % n], h[i]);
                tr_r += (a + b) / 3.0;
                tr_q += 1.0 / (a * a) + (1.0 / a + 1.0 / b).powi(2) + 1.0 / (b * b);
            }
            (tr_r, tr_q)
        } else {
            let mut tr_r = 0.0;
            let mut tr_q = 0.0;
            for i in 1..h.len() {
                let (a, b) = (h[i - 1], h[i]);
                tr_r += (a + b) / 3.0;
                tr_q += 1.0 / (a * a) + (1.0 / a + 1.0 / b).powi(2) + 1.0 / (b * b);
            }
            (tr_r, tr_q)
        };
        if tr_q > 0.0 {
            1.0 / (1.0 + tr_r / tr_q)
        } else {
            1.0
        }
    }

    /// Smooths one line (the distinct sites' values; `held[k]` = weight +∞) at p.
    fn smooth(&self, line: &[Vec3], held: &[bool], p: f64, periodic: Option<&Periodic>) -> Result<Vec<Vec3>> {
        if held.iter().all(|&h| h) || p == 1.0 {
            return Ok(line.to_vec());
        }
        if self.closed {
            return match periodic {
                Some(base) if !held.iter().any(|&h| h) => Ok(base.apply(line)),
                _ => Ok(Periodic::new(&self.knots, held, p)?.apply(line)),
            };
        }
        let weights: Vec<f64> = held
            .iter()
            .map(|&h| if h { f64::INFINITY } else { 1.0 })
            .collect();
        let y: Vec<Vector<3>> = line.to_vec();
        let settings = SmoothingSettings::default().with_p(p).with_weights(weights);
        let fit = SmoothingSpline::<3>::fit(&self.knots, &y, &settings)?;
        Ok(fit
            .values()
            .iter()
            .zip(line)
            .zip(held)
            .map(|((f, y), &h)| if h { *y } else { *f })
            .collect())
    }
}

fn steps(knots: &[f64]) -> Vec<f64> {
    knots.windows(2).map(|w| w[1] - w[0]).collect()
}

/// The influence matrix of a periodic smoothing spline, A = I − (1 − p) Σ Q M⁻¹ Qᵀ with
/// M = p R + (1 − p) QᵀΣQ, Q and R cyclic (module docs). Dense, O(N³) to build.
struct Periodic {
    influence: DMatrix<f64>,
}

impl Periodic {
    fn new(knots: &[f64], held: &[bool], p: f64) -> Result<Self> {
        let h = steps(knots);
        let n = h.len();
        let sigma: Vec<f64> = held.iter().map(|&x| if x { 0.0 } else { 1.0 }).collect();
        if p == 0.0 {
            // The minimiser of ∫ s''² alone among periodic splines is a constant: the mean of
            // the free values (held values kept).
            let free = sigma.iter().filter(|&&s| s > 0.0).count().max(1) as f64;
            let mut influence = DMatrix::zeros(n, n);
            for r in 0..n {
                if sigma[r] == 0.0 {
                    influence[(r, r)] = 1.0;
                } else {
                    for c in 0..n {
                        if sigma[c] > 0.0 {
                            influence[(r, c)] = 1.0 / free;
                        }
                    }
                }
            }
            return Ok(Self { influence });
        }
        let mut q = DMatrix::zeros(n, n);
        let mut r = DMatrix::zeros(n, n);
        for i in 0..n {
            let prev = (i + n - 1) % n;
            let next = (i + 1) % n;
            let (a, b) = (h[prev], h[i]);
            q[(prev, i)] += 1.0 / a;
            q[(i, i)] -= 1.0 / a + 1.0 / b;
            q[(next, i)] += 1.0 / b;
            r[(i, i)] += (a + b) / 3.0;
            r[(i, next)] += b / 6.0;
            r[(next, i)] += b / 6.0;
        }
        let sq = DMatrix::from_fn(n, n, |row, col| sigma[row] * q[(row, col)]);
        let m = &r * p + q.transpose() * &sq * (1.0 - p);
        let cholesky = m
            .cholesky()
            .ok_or_else(|| strategy_error(NAME, format!("singular periodic system at p = {p}")))?;
        let solved = cholesky.solve(&q.transpose());
        let influence = DMatrix::identity(n, n) - sq * solved * (1.0 - p);
        Ok(Self { influence })
    }

    fn apply(&self, line: &[Vec3]) -> Vec<Vec3> {
        let n = line.len();
        let mut out = vec![Vec3::zeros(); n];
        for (c, column) in out.iter_mut().enumerate().take(n) {
            let mut sum = Vec3::zeros();
            for (k, y) in line.iter().enumerate() {
                sum += y * self.influence[(c, k)];
            }
            *column = sum;
        }
        out
    }
}

impl SurfaceSmoothing {
    /// A run with these settings.
    pub fn new(settings: SurfaceSmoothingSettings) -> Self {
        Self { settings }
    }

    /// The settings.
    pub fn settings(&self) -> &SurfaceSmoothingSettings {
        &self.settings
    }

    /// Smooths the grid `grid[i][j]` = P_ij (at least 3 × 3; module docs). O(m·n) per
    /// evaluation (about 100 to match a displacement) plus O(N³) per closed direction.
    ///
    /// Errors: a bad setting, a ragged or too small grid, a fixed node outside the grid, a
    /// closed direction whose last line does not repeat its first.
    pub fn run(&self, grid: &[Vec<Vec3>]) -> Result<SurfaceSmoothingResult> {
        let settings = &self.settings;
        settings.validate()?;
        let start = std::time::Instant::now();
        let rows = grid.len();
        let columns = grid.first().map_or(0, Vec::len);
        if rows < 3 || columns < 3 {
            return Err(strategy_error(
                NAME,
                format!("needs a grid of at least 3 × 3 points, got {rows} × {columns}"),
            ));
        }
        let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
        let topology = settings.closed.topology(&flat, rows, columns);
        let build = BicubicSurfaceSettings::default()
            .with_parametrization(settings.parametrization)
            .with_topology(&topology);
        let surface = BicubicSplineSurface::with_settings(grid, &build)?;
        let mut held = vec![false; rows * columns];
        for &(i, j) in &settings.fixed {
            if i >= rows || j >= columns {
                return Err(Error::BadConstraint {
                    reason: format!("fixed node ({i}, {j}) lies outside the {rows} × {columns} grid"),
                });
            }
            held[i * columns + j] = true;
        }
        for i in 0..rows {
            for j in 0..columns {
                if topology.poles.contains(i, j, rows, columns) {
                    held[i * columns + j] = true;
                }
            }
        }
        // A seam node is held when either copy is.
        if topology.closed_v {
            for i in 0..rows {
                let h = held[i * columns] || held[i * columns + columns - 1];
                held[i * columns] = h;
                held[i * columns + columns - 1] = h;
            }
        }
        if topology.closed_u {
            for j in 0..columns {
                let h = held[j] || held[(rows - 1) * columns + j];
                held[j] = h;
                held[(rows - 1) * columns + j] = h;
            }
        }
        let along_u = Direction {
            knots: surface.u_knots().to_vec(),
            closed: topology.closed_u,
        };
        let along_v = Direction {
            knots: surface.v_knots().to_vec(),
            closed: topology.closed_v,
        };
        let smoother = Smoother {
            flat: &flat,
            held: &held,
            rows,
            columns,
            along_u: &along_u,
            along_v: &along_v,
        };
        let (pu0, pv0) = (along_u.trace_p(), along_v.trace_p());
        let (p, points, unreachable) = match (settings.p, settings.displacement) {
            (Some(p), _) => ((p, p), smoother.smooth(p, p)?, false),
            (None, None) => ((pu0, pv0), smoother.smooth(pu0, pv0)?, false),
            (None, Some(target)) => smoother.match_displacement(pu0, pv0, target)?,
        };
        let displacement = displacement(&flat, &points);
        let moved = (0..rows * columns)
            .filter(|&k| points[k] != flat[k])
            .map(|k| (k / columns, k % columns))
            .collect();
        let surface = BicubicSplineSurface::from_flat(points, rows, columns, &build)?;
        Ok(SurfaceSmoothingResult {
            surface,
            p,
            displacement,
            unreachable,
            topology,
            moved,
            elapsed: start.elapsed(),
        })
    }
}

/// The tensor-product smoothing spline's values at an open grid with the given sites:
/// F = A_u(p_u) · P · A_v(p_v)ᵀ for `points[i·v_knots.len() + j]` = P_ij, coordinate by
/// coordinate (module docs); `p` = None takes csaps's trace rule per direction. Returns the
/// values and the (p_u, p_v) used. This is csaps's `NdGridCubicSmoothingSpline` evaluated at
/// its grid. O(m·n).
///
/// Errors: sites not strictly increasing or fewer than 3 per direction, a point count that
/// is not their product, p outside [0, 1].
pub fn smooth_grid(
    u_knots: &[f64],
    v_knots: &[f64],
    points: &[Vec3],
    p: Option<(f64, f64)>,
) -> Result<(Vec<Vec3>, (f64, f64))> {
    let (rows, columns) = (u_knots.len(), v_knots.len());
    if points.len() != rows * columns {
        return Err(strategy_error(
            NAME,
            format!("{} points for a {rows} × {columns} grid", points.len()),
        ));
    }
    let along_u = Direction {
        knots: u_knots.to_vec(),
        closed: false,
    };
    let along_v = Direction {
        knots: v_knots.to_vec(),
        closed: false,
    };
    let p = p.unwrap_or_else(|| (along_u.trace_p(), along_v.trace_p()));
    for value in [p.0, p.1] {
        if !(0.0..=1.0).contains(&value) {
            return Err(Error::BadParameter {
                name: "p",
                value: value.to_string(),
                reason: "must lie in [0, 1]",
            });
        }
    }
    let held = vec![false; points.len()];
    let smoother = Smoother {
        flat: points,
        held: &held,
        rows,
        columns,
        along_u: &along_u,
        along_v: &along_v,
    };
    Ok((smoother.smooth(p.0, p.1)?, p))
}

/// Σ |a_k − b_k|.
fn displacement(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (p - q).norm()).sum()
}

/// p from a ratio λ = (1 − p)/p.
fn p_of(ratio: f64) -> f64 {
    1.0 / (1.0 + ratio)
}

struct Smoother<'a> {
    flat: &'a [Vec3],
    held: &'a [bool],
    rows: usize,
    columns: usize,
    along_u: &'a Direction,
    along_v: &'a Direction,
}

impl Smoother<'_> {
    /// F = A_u P A_v ᵀ at (p_u, p_v), seams written from their first line.
    fn smooth(&self, pu: f64, pv: f64) -> Result<Vec<Vec3>> {
        let (rows, columns) = (self.rows, self.columns);
        let mut out = self.flat.to_vec();
        // Rows along v.
        let nv = self.along_v.distinct();
        let base_v = if self.along_v.closed && pv < 1.0 {
            Some(Periodic::new(&self.along_v.knots, &vec![false; nv], pv)?)
        } else {
            None
        };
        for i in 0..rows {
            let line = &out[i * columns..i * columns + nv];
            let held = &self.held[i * columns..i * columns + nv];
            let smoothed = self.along_v.smooth(line, held, pv, base_v.as_ref())?;
            out[i * columns..i * columns + nv].copy_from_slice(&smoothed);
            if self.along_v.closed {
                out[i * columns + columns - 1] = out[i * columns];
            }
        }
        // Columns along u.
        let nu = self.along_u.distinct();
        let base_u = if self.along_u.closed && pu < 1.0 {
            Some(Periodic::new(&self.along_u.knots, &vec![false; nu], pu)?)
        } else {
            None
        };
        let mut line = Vec::with_capacity(nu);
        let mut held = Vec::with_capacity(nu);
        for j in 0..columns {
            line.clear();
            held.clear();
            line.extend((0..nu).map(|i| out[i * columns + j]));
            held.extend((0..nu).map(|i| self.held[i * columns + j]));
            let smoothed = self.along_u.smooth(&line, &held, pu, base_u.as_ref())?;
            for (i, p) in smoothed.into_iter().enumerate() {
                out[i * columns + j] = p;
            }
            if self.along_u.closed {
                out[(rows - 1) * columns + j] = out[j];
            }
        }
        // Held nodes bit for bit (the passes keep them; this states it).
        for (k, p) in out.iter_mut().enumerate() {
            if self.held[k] {
                *p = self.flat[k];
            }
        }
        if out.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(strategy_error(
                NAME,
                format!("the fit at p = ({pu}, {pv}) is not finite"),
            ));
        }
        Ok(out)
    }

    /// Bisection on s, λ_u = 10^s λ_u0, λ_v = 10^s λ_v0, for S_d = target.
    fn match_displacement(&self, pu0: f64, pv0: f64, target: f64) -> Result<((f64, f64), Vec<Vec3>, bool)> {
        let ratio = |p: f64| ((1.0 - p) / p).max(1e-300);
        let (lu, lv) = (ratio(pu0), ratio(pv0));
        let at = |s: f64| -> Result<((f64, f64), Vec<Vec3>)> {
            let scale = 10f64.powf(s);
            let p = (p_of(lu * scale), p_of(lv * scale));
            Ok((p, self.smooth(p.0, p.1)?))
        };
        if target == 0.0 {
            return Ok(((1.0, 1.0), self.flat.to_vec(), false));
        }
        let (mut low, mut high) = (-16.0f64, 16.0f64);
        let (p_high, top) = at(high)?;
        if displacement(self.flat, &top) <= target {
            return Ok((p_high, top, true));
        }
        let mut best = (p_high, top);
        for _ in 0..100 {
            let mid = 0.5 * (low + high);
            let (p, points) = at(mid)?;
            let d = displacement(self.flat, &points);
            let done = (d - target).abs() <= 1e-9 * target || high - low < 1e-12;
            if d > target {
                high = mid;
            } else {
                low = mid;
            }
            best = (p, points);
            if done {
                break;
            }
        }
        Ok((best.0, best.1, false))
    }
}
