//! Construction of the bicubic spline surface (Zhang–Cheng §4, first paragraph): knots,
//! natural cubic splines along every u-line and v-line, twists, all in O(m·n).

use super::natural::NaturalSplineSystem;
use super::BicubicSplineSurface;
use crate::{Error, Parametrization, Result, Vec3};

/// How a [`BicubicSplineSurface`] is built: its knots, and which directions close up.
///
/// By default the knots are chord-length *averaged*, the definition the `fair` report uses
/// (docs/CONTRACT.md, "surface kind"): u_0 = 0 and u_{i+1} − u_i = (1/(n+1)) Σ_j |P_{i+1,j} − P_{i,j}|,
/// the mean over the n + 1 u-lines of their chord lengths; v_j likewise over the m + 1
/// v-lines. [`with_parametrization`](Self::with_parametrization) swaps the chord length for
/// another step rule (uniform steps of 1 give Kjellander's surfaces), averaged the same way;
/// [`with_u_knots`](Self::with_u_knots) and [`with_v_knots`](Self::with_v_knots) give the
/// knots outright.
///
/// By default both directions are open (natural splines along every grid line, the report's
/// surface). [`with_closed_u`](Self::with_closed_u) / [`with_closed_v`](Self::with_closed_v)
/// make a direction periodic: the grid's last line along it repeats its first (the layout
/// keeps the repeat; see [`GridTopology`](super::GridTopology)), every line across the seam is
/// a periodic cubic spline, and the averages above run over the distinct lines only (the
/// repeat is not counted twice).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BicubicSurfaceSettings {
    parametrization: Parametrization,
    u_knots: Option<Vec<f64>>,
    v_knots: Option<Vec<f64>>,
    closed_u: bool,
    closed_v: bool,
}

impl BicubicSurfaceSettings {
    /// The step rule averaged into knots where none are given (default: chord length).
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }

    /// Given knots u_0..u_m (finite, strictly increasing, one per grid line i).
    pub fn with_u_knots(mut self, knots: Vec<f64>) -> Self {
        self.u_knots = Some(knots);
        self
    }

    /// Given knots v_0..v_n (finite, strictly increasing, one per grid line j).
    pub fn with_v_knots(mut self, knots: Vec<f64>) -> Self {
        self.v_knots = Some(knots);
        self
    }

    /// Periodic along u: row i = m repeats row i = 0 (default false).
    pub fn with_closed_u(mut self, closed: bool) -> Self {
        self.closed_u = closed;
        self
    }

    /// Periodic along v: column j = n repeats column j = 0 (default false).
    pub fn with_closed_v(mut self, closed: bool) -> Self {
        self.closed_v = closed;
        self
    }

    /// Both closures from a detected or given [`GridTopology`](super::GridTopology).
    pub fn with_topology(self, topology: &super::GridTopology) -> Self {
        self.with_closed_u(topology.closed_u)
            .with_closed_v(topology.closed_v)
    }

    /// The step rule of averaged knots.
    pub fn parametrization(&self) -> Parametrization {
        self.parametrization
    }

    /// The given u knots, if any.
    pub fn u_knots(&self) -> Option<&[f64]> {
        self.u_knots.as_deref()
    }

    /// The given v knots, if any.
    pub fn v_knots(&self) -> Option<&[f64]> {
        self.v_knots.as_deref()
    }

    /// The knots (u_0..u_m, v_0..v_n) these settings give the flat grid
    /// `points[i·v_count + j]`: the given ones, or averaged as described above (a closed
    /// direction's repeated line left out of the means). The knots of
    /// [`BicubicSplineSurface::from_flat`] on the same grid, without building it. Fails as that
    /// does on bad knots or repeated grid lines. O(m·n).
    pub fn knots(&self, points: &[Vec3], u_count: usize, v_count: usize) -> Result<(Vec<f64>, Vec<f64>)> {
        if points.len() != u_count * v_count || u_count < 2 || v_count < 2 {
            return Err(Error::LengthMismatch {
                what: "grid points",
                expected: u_count.max(2) * v_count.max(2),
                got: points.len(),
            });
        }
        let closed = (self.closed_u, self.closed_v);
        if self.u_knots.is_none() && self.v_knots.is_none() {
            // Both averaged: their sums in one pass over the points (the same sums, each in
            // the order of its own pass), then each direction's knots as
            // [`averaged_knots`] makes them, u first.
            let (u_sums, v_sums) = chord_sums(points, (u_count, v_count), closed, self.parametrization);
            let u_knots = knots_from_sums(&u_sums, v_count - usize::from(closed.1), Direction::U)?;
            let v_knots = knots_from_sums(&v_sums, u_count - usize::from(closed.0), Direction::V)?;
            return Ok((u_knots, v_knots));
        }
        let u_knots = match self.u_knots() {
            Some(knots) => checked_knots("u knots", knots, u_count)?,
            None => averaged_knots(
                points,
                (u_count, v_count),
                closed,
                self.parametrization,
                Direction::U,
            )?,
        };
        let v_knots = match self.v_knots() {
            Some(knots) => checked_knots("v knots", knots, v_count)?,
            None => averaged_knots(
                points,
                (u_count, v_count),
                closed,
                self.parametrization,
                Direction::V,
            )?,
        };
        Ok((u_knots, v_knots))
    }

    /// Whether the surface is periodic along u.
    pub fn closed_u(&self) -> bool {
        self.closed_u
    }

    /// Whether the surface is periodic along v.
    pub fn closed_v(&self) -> bool {
        self.closed_v
    }
}

impl BicubicSplineSurface {
    /// The bicubic spline surface through the grid `grid[i][j]` = P_ij (i = 0..m along u,
    /// j = 0..n along v) with chord-length averaged knots. See [`with_settings`](Self::with_settings).
    pub fn new(grid: &[Vec<Vec3>]) -> Result<Self> {
        Self::with_settings(grid, &BicubicSurfaceSettings::default())
    }

    /// The bicubic spline surface through the grid `grid[i][j]` = P_ij: the outer slice runs
    /// along u (i = 0..m), each inner vector along v (j = 0..n). O(m·n).
    ///
    /// Needs m, n ≥ 1 (two grid lines in each direction; with two, the surface is linear in
    /// that direction). Fails with [`Error::TooFewPoints`], [`Error::RaggedGrid`] (an inner
    /// vector whose length differs from the first one's), [`Error::NonFinite`] (a coordinate,
    /// reported with the flat index i·(n+1) + j, or a knot), [`Error::LengthMismatch`] and
    /// [`Error::NotIncreasing`] for given knots, and [`Error::RepeatedGridLine`] when two
    /// consecutive grid lines coincide on average (a zero averaged step). A closed direction
    /// needs at least four lines along it (three distinct and the repeat, else
    /// [`Error::TooFewPoints`]) and its last line within 1e-9 of the bounding-box diagonal of
    /// its first ([`Error::OpenSeam`] otherwise); the repeat is then set to the first line
    /// exactly.
    pub fn with_settings(grid: &[Vec<Vec3>], settings: &BicubicSurfaceSettings) -> Result<Self> {
        let u_count = grid.len();
        if u_count < 2 {
            return Err(Error::TooFewPoints {
                what: "a bicubic spline surface (grid lines along u)",
                needed: 2,
                got: u_count,
            });
        }
        let v_count = grid[0].len();
        for (row, line) in grid.iter().enumerate() {
            if line.len() != v_count {
                return Err(Error::RaggedGrid {
                    row,
                    expected: v_count,
                    got: line.len(),
                });
            }
        }
        let points: Vec<Vec3> = grid.iter().flatten().copied().collect();
        Self::from_flat(points, u_count, v_count, settings)
    }

    /// The surface through a flat grid: `points[i·v_count + j]` = P_ij, with m + 1 = `u_count`
    /// and n + 1 = `v_count`. Fails as [`with_settings`](Self::with_settings) does, and with
    /// [`Error::LengthMismatch`] when `points.len() != u_count·v_count`. O(m·n).
    pub fn from_flat(
        points: Vec<Vec3>,
        u_count: usize,
        v_count: usize,
        settings: &BicubicSurfaceSettings,
    ) -> Result<Self> {
        for (what, count) in [
            ("a bicubic spline surface (grid lines along u)", u_count),
            ("a bicubic spline surface (grid lines along v)", v_count),
        ] {
            if count < 2 {
                return Err(Error::TooFewPoints {
                    what,
                    needed: 2,
                    got: count,
                });
            }
        }
        let expected = u_count.checked_mul(v_count).ok_or(Error::LengthMismatch {
            what: "grid points",
            expected: usize::MAX,
            got: points.len(),
        })?;
        if points.len() != expected {
            return Err(Error::LengthMismatch {
                what: "grid points",
                expected,
                got: points.len(),
            });
        }
        crate::vector::check_finite(&points).map_err(|error| match error {
            Error::NonFinite { index, .. } => Error::NonFinite {
                what: "grid point (flat index i·(n+1) + j)",
                index,
            },
            other => other,
        })?;
        let mut points = points;
        close_seams(&mut points, u_count, v_count, settings)?;
        let (u_knots, v_knots) = settings.knots(&points, u_count, v_count)?;
        let u_system = NaturalSplineSystem::with_periodic(&u_knots, settings.closed_u())?;
        let v_system = NaturalSplineSystem::with_periodic(&v_knots, settings.closed_v())?;
        let mut surface = Self {
            u_count,
            v_count,
            points,
            u_knots,
            v_knots,
            u_tangents: Vec::new(),
            v_tangents: Vec::new(),
            twists: Vec::new(),
            u_system,
            v_system,
        };
        let total = u_count * v_count;
        // Whether every value solved is finite, each line checked as it is solved (three
        // passes over arrays of the grid's size afterwards were each a miss per cache line
        // on a large grid); the checks below name the first value that is not, as before.
        let mut finite = true;
        let mut u_tangents = vec![Vec3::zeros(); total];
        for j in 0..v_count {
            let line = surface.solve_along_u(&surface.points, j)?;
            finite &= all_finite(&line);
            scatter_u_line(&mut u_tangents, v_count, j, &line);
        }
        let mut v_tangents = Vec::with_capacity(total);
        for i in 0..u_count {
            let line = surface.solve_along_v(&surface.points, i)?;
            finite &= all_finite(&line);
            v_tangents.extend(line);
        }
        let (twists, finite_twists) = surface.all_twists_checked(&v_tangents)?;
        if !(finite && finite_twists) {
            check_finite_result("u tangent", &u_tangents)?;
            check_finite_result("v tangent", &v_tangents)?;
            check_finite_result("twist", &twists)?;
        }
        surface.u_tangents = u_tangents;
        surface.v_tangents = v_tangents;
        surface.twists = twists;
        Ok(surface)
    }

    /// The tangents ∂/∂u at (u_i, v_j), i = 0..m, of the natural cubic spline along u through
    /// `values[i·(n+1) + j]` (Eq. 2 with free ends). O(m).
    pub(super) fn solve_along_u(&self, values: &[Vec3], j: usize) -> Result<Vec<Vec3>> {
        let line: Vec<Vec3> = values.iter().skip(j).step_by(self.v_count).copied().collect();
        self.u_system.tangents(&line)
    }

    /// The tangents ∂/∂v at (u_i, v_j), j = 0..n, of the natural cubic spline along v through
    /// `values[i·(n+1) + j]` (Eq. 2 with free ends). O(n).
    pub(super) fn solve_along_v(&self, values: &[Vec3], i: usize) -> Result<Vec<Vec3>> {
        let start = i * self.v_count;
        let line = values
            .get(start..start + self.v_count)
            .ok_or(Error::IndexOutOfRange {
                what: "grid lines along u",
                index: i,
                len: self.u_count,
            })?;
        self.v_system.tangents(line)
    }

    /// The twists S_uv at every node: along each u-line j, the tangents of the natural cubic
    /// spline through the v tangents M^v_{0,j}..M^v_{m,j} (Zhang–Cheng §4: "computed from
    /// natural cubic spline curves in u direction that interpolate the partial derivative of
    /// S(u,v) with respect to v"). O(m·n).
    pub(super) fn all_twists(&self, v_tangents: &[Vec3]) -> Result<Vec<Vec3>> {
        Ok(self.all_twists_checked(v_tangents)?.0)
    }

    /// [`all_twists`](Self::all_twists), and whether every twist is finite. O(m·n).
    fn all_twists_checked(&self, v_tangents: &[Vec3]) -> Result<(Vec<Vec3>, bool)> {
        let mut twists = vec![Vec3::zeros(); self.u_count * self.v_count];
        let mut finite = true;
        for j in 0..self.v_count {
            let line = self.solve_along_u(v_tangents, j)?;
            finite &= all_finite(&line);
            scatter_u_line(&mut twists, self.v_count, j, &line);
        }
        Ok((twists, finite))
    }
}

/// Writes `line[i]` into `grid[i·v_count + j]`.
pub(super) fn scatter_u_line(grid: &mut [Vec3], v_count: usize, j: usize, line: &[Vec3]) {
    for (slot, value) in grid.iter_mut().skip(j).step_by(v_count).zip(line) {
        *slot = *value;
    }
}

/// Whether every coordinate of `values` is finite.
fn all_finite(values: &[Vec3]) -> bool {
    values.iter().all(|p| p.iter().all(|c| c.is_finite()))
}

/// Fails with [`Error::NonFinite`] if a computed value overflowed (points so large or knots
/// so close that a tangent is not representable).
pub(super) fn check_finite_result(what: &'static str, values: &[Vec3]) -> Result<()> {
    match values.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        Some(index) => Err(Error::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// Checks that every closed direction's last line repeats its first (within 1e-9 of the
/// bounding-box diagonal) and makes the repeat exact. O(m·n).
fn close_seams(
    points: &mut [Vec3],
    u_count: usize,
    v_count: usize,
    settings: &BicubicSurfaceSettings,
) -> Result<()> {
    // The seams' tolerance, taken (over the points as given) at the first closed direction:
    // an open grid needs no pass over its points here.
    let mut tolerance = None;
    for (closed, direction, count) in [
        (settings.closed_u(), Direction::U, u_count),
        (settings.closed_v(), Direction::V, v_count),
    ] {
        if !closed {
            continue;
        }
        let name = direction.name();
        if count < 4 {
            return Err(Error::TooFewPoints {
                what: if direction == Direction::U {
                    "a surface closed in u (grid lines along u: three distinct and the repeat)"
                } else {
                    "a surface closed in v (grid lines along v: three distinct and the repeat)"
                },
                needed: 4,
                got: count,
            });
        }
        let pairs: Vec<(usize, usize)> = match direction {
            Direction::U => (0..v_count).map(|j| (j, (u_count - 1) * v_count + j)).collect(),
            Direction::V => (0..u_count)
                .map(|i| (i * v_count, i * v_count + v_count - 1))
                .collect(),
        };
        let (worst, distance) = pairs
            .iter()
            .enumerate()
            .map(|(index, &(first, last))| (index, (points[first] - points[last]).norm()))
            .fold(
                (0, 0.0),
                |best, candidate| if candidate.1 > best.1 { candidate } else { best },
            );
        let tolerance = *tolerance.get_or_insert_with(|| 1e-9 * super::topology::diagonal(points));
        if distance > tolerance {
            return Err(Error::OpenSeam {
                direction: name,
                index: worst,
                distance,
            });
        }
        for (first, last) in pairs {
            points[last] = points[first];
        }
    }
    Ok(())
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Direction {
    U,
    V,
}

impl Direction {
    fn name(self) -> &'static str {
        match self {
            Direction::U => "u",
            Direction::V => "v",
        }
    }
}

/// Given knots: one per grid line, finite, strictly increasing.
fn checked_knots(what: &'static str, knots: &[f64], count: usize) -> Result<Vec<f64>> {
    if knots.len() != count {
        return Err(Error::LengthMismatch {
            what,
            expected: count,
            got: knots.len(),
        });
    }
    crate::vector::check_finite_values(what, knots)?;
    check_increasing(what, knots)?;
    Ok(knots.to_vec())
}

fn check_increasing(what: &'static str, knots: &[f64]) -> Result<()> {
    match knots
        .windows(2)
        .position(|w| w[1] <= w[0] || w[1].is_nan() || w[0].is_nan())
    {
        Some(i) => Err(Error::NotIncreasing {
            what,
            index: i + 1,
            previous: knots[i],
            value: knots[i + 1],
        }),
        None => Ok(()),
    }
}

/// Averaged knots: t_0 = 0, t_{k+1} − t_k = the mean over the lines of the other direction of
/// the step between grid lines k and k + 1 (docs/CONTRACT.md "surface kind"); when the other
/// direction is closed its repeated line is left out of the mean. O(m·n).
fn averaged_knots(
    points: &[Vec3],
    (u_count, v_count): (usize, usize),
    (closed_u, closed_v): (bool, bool),
    parametrization: Parametrization,
    direction: Direction,
) -> Result<Vec<f64>> {
    let (count, across) = match direction {
        Direction::U => (u_count, v_count - usize::from(closed_v)),
        Direction::V => (v_count, u_count - usize::from(closed_u)),
    };
    let at = |k: usize, l: usize| match direction {
        Direction::U => points[k * v_count + l],
        Direction::V => points[l * v_count + k],
    };
    let step = step_rule(parametrization);
    let sums: Vec<f64> = (0..count - 1)
        .map(|k| (0..across).map(|l| step(at(k, l), at(k + 1, l))).sum())
        .collect();
    knots_from_sums(&sums, across, direction)
}

/// The step rule of a parametrization between two grid points.
fn step_rule(parametrization: Parametrization) -> impl Fn(Vec3, Vec3) -> f64 {
    move |a: Vec3, b: Vec3| match parametrization {
        Parametrization::Uniform => 1.0,
        Parametrization::ChordLength => (b - a).norm(),
        Parametrization::Centripetal => (b - a).norm().sqrt(),
    }
}

/// [`averaged_knots`]' sums of both directions in one row-major pass over the points: the
/// u sums (between rows k and k + 1, over the columns in order) as that function takes
/// them, each in one run, and the v sums (between columns k and k + 1, over the rows in
/// order) one term per row into each, so each sum adds the same terms in the same order
/// (the terms are never −0, so the start of the sum, +0 here and −0 in `Iterator::sum`, does
/// not change a bit). The strided pass of the v sums and a second pass over a grid larger
/// than the cache were each a miss per cache line of the points. O(m·n).
fn chord_sums(
    points: &[Vec3],
    (u_count, v_count): (usize, usize),
    (closed_u, closed_v): (bool, bool),
    parametrization: Parametrization,
) -> (Vec<f64>, Vec<f64>) {
    let step = step_rule(parametrization);
    let (across_u, across_v) = (v_count - usize::from(closed_v), u_count - usize::from(closed_u));
    let mut u_sums = Vec::with_capacity(u_count - 1);
    let mut v_sums = vec![0.0; v_count - 1];
    let mut rows = points.chunks_exact(v_count).enumerate().peekable();
    while let Some((i, row)) = rows.next() {
        if i < across_v {
            for (sum, pair) in v_sums.iter_mut().zip(row.windows(2)) {
                *sum += step(pair[0], pair[1]);
            }
        }
        if let Some(&(_, next)) = rows.peek() {
            let mut sum = 0.0;
            for (&a, &b) in row[..across_u].iter().zip(next) {
                sum += step(a, b);
            }
            u_sums.push(sum);
        }
    }
    (u_sums, v_sums)
}

/// Averaged knots from the sums of the steps between consecutive grid lines over `across`
/// lines of the other direction (module docs of [`averaged_knots`]). O(count).
fn knots_from_sums(sums: &[f64], across: usize, direction: Direction) -> Result<Vec<f64>> {
    let name = direction.name();
    let what = match direction {
        Direction::U => "u knot",
        Direction::V => "v knot",
    };
    let mut knots = Vec::with_capacity(sums.len() + 1);
    knots.push(0.0);
    for (k, &sum) in sums.iter().enumerate() {
        let mean = sum / across as f64;
        if mean == 0.0 {
            return Err(Error::RepeatedGridLine {
                direction: name,
                index: k,
            });
        }
        let next = knots[k] + mean;
        if !next.is_finite() {
            return Err(Error::NonFinite { what, index: k + 1 });
        }
        knots.push(next);
    }
    check_increasing(what, &knots)?;
    Ok(knots)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each direction's knots by its own pass, as [`BicubicSurfaceSettings::knots`] made them
    /// before both came from one pass.
    fn separate(
        points: &[Vec3],
        counts: (usize, usize),
        closed: (bool, bool),
        parametrization: Parametrization,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let u = averaged_knots(points, counts, closed, parametrization, Direction::U)?;
        let v = averaged_knots(points, counts, closed, parametrization, Direction::V)?;
        Ok((u, v))
    }

    fn bits(result: &Result<(Vec<f64>, Vec<f64>)>) -> std::result::Result<(Vec<u64>, Vec<u64>), Error> {
        match result {
            Ok((u, v)) => Ok((
                u.iter().map(|x| x.to_bits()).collect(),
                v.iter().map(|x| x.to_bits()).collect(),
            )),
            Err(e) => Err(e.clone()),
        }
    }

    #[test]
    fn one_pass_knots_equal_each_direction_s_own() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut errors = 0;
        for (u_count, v_count) in [(2, 2), (2, 5), (4, 4), (5, 3), (9, 17), (30, 11)] {
            for parametrization in [
                Parametrization::ChordLength,
                Parametrization::Centripetal,
                Parametrization::Uniform,
            ] {
                for closed in [(false, false), (true, false), (false, true), (true, true)] {
                    if (closed.0 && u_count < 4) || (closed.1 && v_count < 4) {
                        continue;
                    }
                    // Noisy grids, one with a repeated line (an error, the same error),
                    // one with a point so large that a knot overflows.
                    for case in 0..3 {
                        let mut points: Vec<Vec3> = (0..u_count * v_count)
                            .map(|k| {
                                let (i, j) = ((k / v_count) as f64, (k % v_count) as f64);
                                Vec3::new(i + 0.3 * random(), j + 0.3 * random(), random() * 1e-3)
                            })
                            .collect();
                        if case == 1 {
                            let (a, b) = points.split_at_mut(v_count);
                            b[..v_count].copy_from_slice(a);
                        }
                        if case == 2 {
                            points[v_count + 1] = Vec3::new(1e308, -1e308, 1e308);
                        }
                        let settings = BicubicSurfaceSettings::default()
                            .with_parametrization(parametrization)
                            .with_closed_u(closed.0)
                            .with_closed_v(closed.1);
                        let fused = settings.knots(&points, u_count, v_count);
                        let expected = separate(&points, (u_count, v_count), closed, parametrization);
                        errors += usize::from(expected.is_err());
                        assert_eq!(
                            bits(&fused),
                            bits(&expected),
                            "{u_count} × {v_count} {parametrization:?} {closed:?} case {case}"
                        );
                    }
                }
            }
        }
        // The error paths were taken too.
        assert!(errors > 20, "{errors}");
    }
}
