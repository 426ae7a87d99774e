//! Okada's numerical batten (Y. Okada, *A numerical experiment on the fairing of free-form
//! curves*, Joho Shori 10(3), 1969; §2): the curve is a chain of Ferguson cubic segments, each
//! on its own parameter t ∈ [0, 1], treated as an elastic batten whose strain energy is
//! lowered alternately over the tangents (Eq. 12) and over the point positions (Eq. 13).
//!
//! Notation (0-based, n points P_0..P_{n−1}): segment i runs from P_i to P_{i+1}, with chord
//! C_i = |P_{i+1} − P_i| (Eq. 8), start tangent X_i and end tangent Y_i = k_{i+1} X_{i+1},
//! k_i = C_{i−1}/C_i (Eq. 9; the last segment's Y_{n−2} is its own end tangent, there is no
//! C_{n−1}). The energy of segment i is (1/C_i³) ∫_0^1 |P̈_i(t)|² dt (Eq. 5's terms), i.e.
//! ∫|d²P/ds²|² ds with s = C_i t: the chord-length strain energy.
//!
//! With M_i = X_i / C_i (the derivative in chord length), Eq. 12 is the C2 condition of the
//! chord-length cubic spline, h_i M_{i−1} + 2(h_{i−1} + h_i) M_i + h_{i−1} M_{i+1} =
//! 3(h_i d_{i−1} + h_{i−1} d_i) (tested), and Eq. 13's row is Zhang–Cheng's Eq. 8 with
//! chord-length knots: the batten is a chord-length strain-energy fairing whose knots are
//! re-measured every iteration and whose end tangents come from circles.
//!
//! One iteration (Okada §2.2, Steps 2–6), the `step` of [`Batten`]:
//! 1. end tangents X_0 and Y_{n−2} from the circle through the three end points
//!    ([`end_tangent`]); prescribed tangent directions split the tangent solve (Step 3);
//! 2. the interior tangents from Eq. 12 ([`okada_tangents`]), k held at the current chords;
//! 3. the signs of the curvatures of the curve's projections on the coordinate planes
//!    ([`curvature_signs`]; one plane in 2D, xy, yz, zx in 3D) (Step 4);
//! 4. the positions from Eq. 13 with those tangents held (Step 5): by default one
//!    Gauss–Seidel sweep of its rows ([`eq13_sweep`]), or the whole system solved
//!    ([`eq13_positions`]; see [`PositionUpdate`]); fixed points and the two ends stay, and
//!    each point is kept in its adjustable range (the constraints' restraining radius or
//!    tolerance);
//! 5. stop when the curvature signs at every point equal the previous iteration's (Step 6,
//!    never before the second iteration).
//!
//! Okada's auxiliary information (1), "the coordinates of points to be adjusted" (a per-
//! component mask), is not offered: every coordinate of a movable point is adjusted, as in
//! his Table 1 experiment.
//!
//! Cost per iteration O(n) (two tridiagonal solves), plus O(n · sweeps) when a range binds.

use curve_repr::{tridiagonal, Vector};

use crate::state::strategy_error;
use crate::{project_into_ball, Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome};

/// How Step 5 applies Eq. (13) to the positions in one iteration. Okada says only that the
/// positions are adjusted "using the Eq. (13)" and that Eq. (12) and (13) are easy to solve
/// because their matrices are diagonally dominant.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum PositionUpdate {
    /// Solve Eq. (13) as a system over every movable point at once (one tridiagonal solve):
    /// each iteration goes to the minimiser of V with the tangents held.
    Solve,
    /// One Gauss–Seidel sweep of Eq. (13), first point to last: each point goes to its own
    /// row's solution with its neighbours as they are at that moment (Kjellander-like). The
    /// default: on Okada's Table 1 it stops after 5 iterations (published: 6) and lands
    /// nearest the published result of the three (examples/okada_table1.rs).
    #[default]
    GaussSeidel,
    /// One Jacobi sweep: every point to its row's solution with the neighbours of the
    /// previous iteration.
    Jacobi,
}

/// Settings of [`Batten`]: the parameters of the catalogue's `batten`.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct BattenSettings {
    /// Adjustable range: no point moves farther than this from its data point.
    ///
    /// Okada's adjustable ranges, one for every point; `inf` (the default, as in Okada's
    /// Table 1) leaves the points unrestricted. The strategy keeps every point within it
    /// (and within the constraints' band and radii, whichever is smaller).
    #[serde(with = "crate::catalog::value::unbounded")]
    #[schemars(with = "crate::catalog::value::BoundNumber")]
    #[schemars(extend("minimum" = 0))]
    pub range: f64,
    /// Prescribed tangent directions, `INDEX:DX,DY[,DZ]` separated by ';'.
    ///
    /// Okada Step 1 (4): (point index, direction components). The direction's length is
    /// ignored; its magnitude is found as in Step 2 (2). Default none. Written as text
    /// (`5:1,0.4;8:0,1`) or as a list of `[index, [dx, dy]]` pairs in a config file. The
    /// components are checked against the points' dimension when the strategy starts.
    #[serde(with = "tangent_directions")]
    #[schemars(with = "tangent_directions::Schema")]
    pub tangent_directions: Vec<(usize, Vec<f64>)>,
    /// Eq. 13 per iteration: gauss-seidel (one sweep), solve (whole system), jacobi.
    ///
    /// Default [`PositionUpdate::GaussSeidel`].
    #[serde(rename = "update")]
    pub position_update: PositionUpdate,
    /// Batten iterations at most (each: Eq. 12 tangents, Eq. 13 positions).
    ///
    /// The pipeline's step limit when the catalogue runs the strategy. Default 1000.
    pub max_iterations: usize,
    /// update=solve: projected Gauss-Seidel sweeps at most when a range binds.
    ///
    /// Default 10 000.
    pub max_sweeps: usize,
}

impl Default for BattenSettings {
    fn default() -> Self {
        Self {
            range: f64::INFINITY,
            tangent_directions: Vec::new(),
            position_update: PositionUpdate::GaussSeidel,
            max_iterations: 1000,
            max_sweeps: 10_000,
        }
    }
}

/// Serde for the prescribed tangent directions: the text form `INDEX:DX,DY[,DZ];…` or a list
/// of `[index, [dx, dy(, dz)]]`; a direction that is zero, not finite, of the wrong dimension
/// or given twice for one point is refused.
pub mod tangent_directions {
    use std::borrow::Cow;

    use serde::de::Error as _;
    use serde::{Deserialize, Deserializer, Serializer};

    /// The JSON Schema of the field: the text form or a list of pairs.
    pub struct Schema;

    impl schemars::JsonSchema for Schema {
        fn schema_name() -> Cow<'static, str> {
            "TangentDirections".into()
        }
        fn inline_schema() -> bool {
            true
        }
        fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
            schemars::json_schema!({
                "anyOf": [
                    { "type": "string" },
                    { "type": "array", "items": { "type": "array" } }
                ]
            })
        }
    }

    /// Writes the text form.
    pub fn serialize<S: Serializer>(value: &[(usize, Vec<f64>)], serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&text(value))
    }

    /// The text form `INDEX:DX,DY[,DZ];…`.
    pub fn text(value: &[(usize, Vec<f64>)]) -> String {
        value
            .iter()
            .map(|(i, d)| {
                let d: Vec<String> = d.iter().map(|c| c.to_string()).collect();
                format!("{i}:{}", d.join(","))
            })
            .collect::<Vec<_>>()
            .join(";")
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Given {
        Text(String),
        List(Vec<(usize, Vec<f64>)>),
    }

    /// Reads the text form or a list of pairs.
    pub fn deserialize<'de, De: Deserializer<'de>>(
        deserializer: De,
    ) -> Result<Vec<(usize, Vec<f64>)>, De::Error> {
        let pairs = match Given::deserialize(deserializer)? {
            Given::List(pairs) => pairs,
            Given::Text(text) => parse(&text).map_err(De::Error::custom)?,
        };
        let mut out: Vec<(usize, Vec<f64>)> = Vec::with_capacity(pairs.len());
        for (index, values) in pairs {
            if values.is_empty() || !values.iter().all(|v| v.is_finite()) || values.iter().all(|v| *v == 0.0)
            {
                return Err(De::Error::custom(format!(
                    "the direction at point {index} is zero or not finite"
                )));
            }
            if out.iter().any(|(k, _)| *k == index) {
                return Err(De::Error::custom(format!(
                    "point {index} is given a direction twice"
                )));
            }
            out.push((index, values));
        }
        Ok(out)
    }

    /// Parses `INDEX:DX,DY[,DZ];…` (items separated by `;`, blanks ignored).
    fn parse(text: &str) -> Result<Vec<(usize, Vec<f64>)>, String> {
        let mut out = Vec::new();
        for item in text.split(';').map(str::trim).filter(|s| !s.is_empty()) {
            let (index, direction) = item
                .split_once(':')
                .ok_or_else(|| format!("`{item}` is not INDEX:DX,DY[,DZ]"))?;
            let index: usize = index
                .trim()
                .parse()
                .map_err(|_| format!("`{index}` is not a point index"))?;
            let values: Vec<f64> = direction
                .split(',')
                .map(|v| v.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| format!("`{direction}` is not a list of numbers"))?;
            out.push((index, values));
        }
        Ok(out)
    }
}

impl BattenSettings {
    /// Checks the ranges: `range` ≥ 0 (or `inf`).
    pub fn validate(&self) -> Result<()> {
        if self.range.is_nan() || self.range < 0.0 {
            return Err(crate::Error::BadParameter {
                name: "range",
                value: self.range.to_string(),
                reason: "must be a number ≥ 0 (or inf)",
            });
        }
        Ok(())
    }

    /// Sets the adjustable range of every point.
    pub fn with_range(mut self, range: f64) -> Self {
        self.range = range;
        self
    }
    /// Prescribes the tangent direction at point `index`.
    pub fn with_tangent_direction<const D: usize>(mut self, index: usize, direction: Vector<D>) -> Self {
        self.tangent_directions
            .push((index, direction.iter().copied().collect()));
        self
    }
    /// Sets how Eq. (13) updates the positions.
    pub fn with_position_update(mut self, update: PositionUpdate) -> Self {
        self.position_update = update;
        self
    }
    /// Sets the sweep limit of the projected Gauss–Seidel solve.
    pub fn with_max_sweeps(mut self, sweeps: usize) -> Self {
        self.max_sweeps = sweeps;
        self
    }
}

/// The tangents of Okada's Ferguson chain: `x[i]` = X_i (i = 0..n−2, the start tangent of
/// segment i on its own parameter) and `end` = Y_{n−2}, the end tangent of the last segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Tangents<const D: usize> {
    /// Chord lengths C_i = |P_{i+1} − P_i| (Eq. 8) the tangents were computed with.
    pub chords: Vec<f64>,
    /// X_0..X_{n−2}.
    pub x: Vec<Vector<D>>,
    /// Y_{n−2}.
    pub end: Vector<D>,
}

impl<const D: usize> Tangents<D> {
    /// Y_i = k_{i+1} X_{i+1} = (C_i / C_{i+1}) X_{i+1}, the end tangent of segment i (Eq. 6–7);
    /// the last segment's is [`end`](Self::end). `None` past the last segment.
    pub fn y(&self, i: usize) -> Option<Vector<D>> {
        let last = self.x.len().checked_sub(1)?;
        match i.cmp(&last) {
            std::cmp::Ordering::Less => {
                Some(*self.x.get(i + 1)? * (*self.chords.get(i)? / *self.chords.get(i + 1)?))
            }
            std::cmp::Ordering::Equal => Some(self.end),
            std::cmp::Ordering::Greater => None,
        }
    }
}

/// Chord lengths C_i = |P_{i+1} − P_i| (Eq. 8). Errors: coinciding consecutive points.
pub fn chords<const D: usize>(points: &[Vector<D>]) -> Result<Vec<f64>> {
    points
        .windows(2)
        .enumerate()
        .map(|(index, w)| {
            // Scaled, so that chords of 1e-300 do not underflow to 0 (or 1e200 overflow).
            let c = curve_repr::parametrization::distance(&w[0], &w[1]);
            if c > 0.0 && c.is_finite() {
                Ok(c)
            } else if c > 0.0 {
                Err(curve_repr::Error::DistanceOverflow { index }.into())
            } else {
                Err(curve_repr::Error::RepeatedPoint { index }.into())
            }
        })
        .collect()
}

/// The Ferguson coefficients R_{i,0..3} of the segment P_0 → P_1 with end tangents X, Y
/// (Eq. 1, 6, 7): P(t) = R_0 + R_1 t + R_2 t² + R_3 t³.
pub fn ferguson<const D: usize>(p0: Vector<D>, p1: Vector<D>, x: Vector<D>, y: Vector<D>) -> [Vector<D>; 4] {
    [p0, x, (p1 - p0) * 3.0 - x * 2.0 - y, (p0 - p1) * 2.0 + x + y]
}

/// (1/C³) ∫_0^1 |P̈(t)|² dt of one Ferguson segment, Eq. (5)'s term:
/// 4(R_2·R_2 + 3 R_2·R_3 + 3 R_3·R_3)/C³ (Okada drops the common factor 4). O(D).
pub fn segment_energy<const D: usize>(
    p0: Vector<D>,
    p1: Vector<D>,
    x: Vector<D>,
    y: Vector<D>,
    c: f64,
) -> f64 {
    let [_, _, r2, r3] = ferguson(p0, p1, x, y);
    4.0 * (r2.dot(&r2) + 3.0 * r2.dot(&r3) + 3.0 * r3.dot(&r3)) / c.powi(3)
}

/// The total energy Σ_i (1/C_i³)∫|P̈_i|² of the chain with the given tangents and the chords
/// stored in them (k held, as in Eq. 10–11). O(n).
pub fn energy<const D: usize>(points: &[Vector<D>], tangents: &Tangents<D>) -> f64 {
    (0..tangents.x.len())
        .filter_map(|i| {
            Some(segment_energy(
                *points.get(i)?,
                *points.get(i + 1)?,
                tangents.x[i],
                tangents.y(i)?,
                *tangents.chords.get(i)?,
            ))
        })
        .sum()
}

/// Unit tangent at `a` of the circle through `a`, `b`, `c`, pointing towards `b` (Okada
/// Step 2 (1)). Inverting about `a` maps the circle onto the line through
/// a + (b−a)/|b−a|² and a + (c−a)/|c−a|², which is parallel to the tangent at `a`; in 3D this
/// stays in the points' plane, and for collinear points it is the line's direction. `None`
/// when two of the points coincide.
pub fn circle_tangent<const D: usize>(a: Vector<D>, b: Vector<D>, c: Vector<D>) -> Option<Vector<D>> {
    let (ab, ac) = (b - a, c - a);
    let (nb, nc) = (ab.norm_squared(), ac.norm_squared());
    if nb <= 0.0 || nc <= 0.0 {
        return None;
    }
    let mut t = ac / nc - ab / nb;
    if t.dot(&ab) < 0.0 {
        t = -t;
    }
    let len = t.norm();
    (len > 0.0 && len.is_finite()).then(|| t / len)
}

/// The start tangent X of the first segment P_0 → P_1 (Okada Step 2): its direction `u0`
/// from the circle through P_0, P_1, P_2 (or prescribed), its magnitude from "two parametric
/// quadratics in the two curve segments, making the second derivative vectors equal at the
/// middle point" (Step 2 (2)).
///
/// Our reading (the paper gives no formula): quadratic Q_0 on P_0 → P_1 starts with
/// derivative a·u0, quadratic Q_1 on P_1 → P_2 ends with derivative b·u2 (u2 the circle's
/// tangent at P_2), and their second derivatives with respect to chord length are equal at
/// P_1: 2(P_1 − P_0 − a u0)/C_0² = 2(b u2 − (P_2 − P_1))/C_1². Two unknowns, solved in least
/// squares (exactly in the points' plane). On a circle with equal chords this gives
/// a = R tan θ (θ the angle P_0 and P_1 subtend at the centre), the arc's derivative C_0 to
/// first order; for (nearly) collinear points, where u0 ∥ u2, a = C_0, and also where the
/// rule gives a ≤ 0 or a > 3 C_0 (wide arcs). O(D).
pub fn end_tangent<const D: usize>(
    p0: Vector<D>,
    p1: Vector<D>,
    p2: Vector<D>,
    direction: Option<Vector<D>>,
) -> Option<Vector<D>> {
    let u0 = match direction {
        Some(d) if d.norm() > 0.0 && d.iter().all(|v| v.is_finite()) => d / d.norm(),
        Some(_) => return None,
        None => circle_tangent(p0, p1, p2)?,
    };
    let u2 = -circle_tangent(p2, p1, p0)?;
    let (c0, c1) = ((p1 - p0).norm(), (p2 - p1).norm());
    // α u0 + β u2 = r with α = a/C_0², β = b/C_1²; normal equations of the 2×2 Gram system.
    let r = (p1 - p0) / (c0 * c0) + (p2 - p1) / (c1 * c1);
    let g = u0.dot(&u2);
    let det = 1.0 - g * g;
    let alpha = if det > 1e-10 {
        (u0.dot(&r) - g * u2.dot(&r)) / det
    } else {
        1.0 / c0
    };
    let a = alpha * c0 * c0;
    // On a circle a = R tan θ: it turns negative or explodes when the arc P_0P_1 turns by
    // 90° or more. Where the rule gives no usable magnitude (a ≤ 0, a > 3 C_0, where a
    // Ferguson segment can loop, or non-finite) the chord C_0 is taken instead.
    let a = if a.is_finite() && a > 0.0 && a <= 3.0 * c0 {
        a
    } else {
        c0
    };
    Some(u0 * a)
}

/// The magnitude of a prescribed interior tangent at point i (Okada Step 3: "determine the
/// magnitude of X_i using (2) in Step 2"): quadratics on the two segments meeting at P_i,
/// with derivative m·u there (in chord length, so X_i = C_i m u and Y_{i−1} = C_{i−1} m u),
/// whose second derivatives are equal at P_i. The condition is a vector equation in one
/// unknown; its least-squares solution is m = u·(C_i d_{i−1} + C_{i−1} d_i)/(C_{i−1} + C_i),
/// d = chord / length: the parabolic (Bessel) tangent projected onto u. O(D).
fn prescribed_speed<const D: usize>(prev: Vector<D>, p: Vector<D>, next: Vector<D>, u: Vector<D>) -> f64 {
    let (c0, c1) = ((p - prev).norm(), (next - p).norm());
    let bessel = ((p - prev) / c0 * c1 + (next - p) / c1 * c0) / (c0 + c1);
    u.dot(&bessel)
}

/// Okada's tangents for the current points: X_0 and Y_{n−2} by [`end_tangent`], the
/// prescribed directions `directions` (index, direction) by the same rule, and every other
/// X_i (i = 1..n−2) from Eq. (12), k held at the current chords:
///
/// X_{i−1} + 2k_i(1 + k_i) X_i + k_i² k_{i+1} X_{i+1} = 3(C_{i−1} + k_i² C_i),
///
/// where C_i is the chord *vector* P_{i+1} − P_i on the right and k_{i+1}X_{i+1} = Y_i. It is
/// ∂V_i/∂X_i = 0 (Eq. 10), V_i the energy of the two segments at P_i (Eq. 5); rows at a
/// prescribed point become X_i = its known value, which splits the solve as Step 3 does.
/// One tridiagonal solve, O(n). Errors: fewer than three points, coinciding points.
pub fn okada_tangents<const D: usize>(
    points: &[Vector<D>],
    directions: &[(usize, Vector<D>)],
) -> Result<Tangents<D>> {
    let n = points.len();
    if n < 3 {
        return Err(strategy_error(
            "batten",
            format!("{n} points; the batten needs at least 3"),
        ));
    }
    let c = chords(points)?;
    let bad = || strategy_error("batten", "the end tangent's circle is degenerate");
    let direction = |i: usize| directions.iter().rev().find(|(j, _)| *j == i).map(|(_, d)| *d);
    let x0 = end_tangent(points[0], points[1], points[2], direction(0)).ok_or_else(bad)?;
    let back = end_tangent(
        points[n - 1],
        points[n - 2],
        points[n - 3],
        direction(n - 1).map(|d| -d),
    )
    .ok_or_else(bad)?;
    let end = -back;
    // Unknowns X_1..X_{n−2}: row r = i − 1.
    let m = n - 2;
    let (mut lower, mut diag, mut upper, mut rhs) = (
        vec![0.0; m],
        vec![0.0; m],
        vec![0.0; m],
        vec![Vector::<D>::zeros(); m],
    );
    for i in 1..=m {
        let r = i - 1;
        if let Some(u) = direction(i) {
            let len = u.norm();
            if !(len > 0.0 && len.is_finite()) {
                return Err(Error::BadValue {
                    name: "tangent-directions".into(),
                    message: format!("prescribed tangent at point {i} has no direction"),
                });
            }
            let u = u / len;
            let speed = prescribed_speed(points[i - 1], points[i], points[i + 1], u);
            diag[r] = 1.0;
            rhs[r] = u * (speed * c[i]);
            continue;
        }
        let k = c[i - 1] / c[i];
        let mut b = ((points[i] - points[i - 1]) + (points[i + 1] - points[i]) * (k * k)) * 3.0;
        if i == 1 {
            b -= x0;
        } else {
            lower[r] = 1.0;
        }
        diag[r] = 2.0 * k * (1.0 + k);
        if i == m {
            b -= end * (k * k);
        } else {
            upper[r] = k * k * (c[i] / c[i + 1]);
        }
        rhs[r] = b;
    }
    let inner = tridiagonal::solve(&lower, &diag, &upper, &rhs)?;
    let mut x = Vec::with_capacity(n - 1);
    x.push(x0);
    x.extend(inner);
    Ok(Tangents { chords: c, x, end })
}

/// The positions of Eq. (13), the tangents X and the chords (so k) held:
///
/// −2P_{i−1} + 2(1 + k_i³) P_i − 2k_i³ P_{i+1} = X_{i−1} + k_i(1 − k_i²) X_i − k_i³ Y_i,
///
/// which is ∂V_i/∂P_i = 0 (Eq. 11). Points with `movable[i]` false (the ends, fixed points)
/// keep their position. `allowed[i]` is the radius of point i's adjustable range around
/// `centers[i]` (its data point); when the unconstrained solution (one tridiagonal solve)
/// leaves a range, the constrained minimiser of V over the ranges is found by projected
/// Gauss–Seidel from the projected solution (exact per point: V's Hessian in P_i is a multiple
/// of the identity), at most `max_sweeps` sweeps. O(n), or O(n · sweeps) when a range binds.
pub fn eq13_positions<const D: usize>(
    points: &[Vector<D>],
    tangents: &Tangents<D>,
    movable: &[bool],
    centers: &[Vector<D>],
    allowed: &[f64],
    max_sweeps: usize,
) -> Result<Vec<Vector<D>>> {
    let n = points.len();
    check_eq13_lengths(n, tangents, movable, centers, allowed)?;
    // Row of interior point i: coefficients (lo, di, up) and right-hand side.
    let row = |i: usize| {
        let (k3, b) = eq13_row(tangents, i);
        (-2.0, 2.0 * (1.0 + k3), -2.0 * k3, b)
    };
    let free = |i: usize| i > 0 && i + 1 < n && movable[i];
    let m = n.saturating_sub(2);
    let (mut lower, mut diag, mut upper, mut rhs) = (
        vec![0.0; m],
        vec![0.0; m],
        vec![0.0; m],
        vec![Vector::<D>::zeros(); m],
    );
    for i in 1..n.saturating_sub(1) {
        let r = i - 1;
        if !free(i) {
            diag[r] = 1.0;
            rhs[r] = points[i];
            continue;
        }
        let (lo, di, up, mut b) = row(i);
        diag[r] = di;
        if i == 1 {
            b -= points[0] * lo;
        } else {
            lower[r] = lo;
        }
        if i + 2 == n {
            b -= points[n - 1] * up;
        } else {
            upper[r] = up;
        }
        rhs[r] = b;
    }
    let inner = tridiagonal::solve(&lower, &diag, &upper, &rhs)?;
    let mut out = points.to_vec();
    let mut binds = false;
    for (i, p) in inner.into_iter().enumerate().map(|(r, p)| (r + 1, p)) {
        if free(i) {
            let q = project_into_ball(&centers[i], allowed[i], &p);
            binds |= q != p;
            out[i] = q;
        }
    }
    if binds {
        let scale = points.iter().map(|p| p.amax()).fold(0.0, f64::max).max(1.0);
        for _ in 0..max_sweeps {
            optim::cancel::checkpoint()?;
            let mut change: f64 = 0.0;
            for i in (1..n.saturating_sub(1)).filter(|&i| free(i)) {
                let (lo, di, up, b) = row(i);
                let p = (b - out[i - 1] * lo - out[i + 1] * up) / di;
                let q = project_into_ball(&centers[i], allowed[i], &p);
                change = change.max((q - out[i]).amax());
                out[i] = q;
            }
            if change <= 1e-14 * scale {
                break;
            }
        }
    }
    if out.iter().any(|p| p.iter().any(|v| !v.is_finite())) {
        return Err(strategy_error("batten", "Eq. 13 gave a non-finite position"));
    }
    Ok(out)
}

/// Eq. (13) at interior point i, −2P_{i−1} + 2(1 + k³)P_i − 2k³P_{i+1} = b with
/// k = C_{i−1}/C_i and b = X_{i−1} + k(1 − k²)X_i − k³Y_i: returns (k³, b). O(1).
fn eq13_row<const D: usize>(tangents: &Tangents<D>, i: usize) -> (f64, Vector<D>) {
    let k = tangents.chords[i - 1] / tangents.chords[i];
    let k3 = k * k * k;
    let y = tangents.y(i).unwrap_or_else(Vector::zeros);
    (
        k3,
        tangents.x[i - 1] + tangents.x[i] * (k * (1.0 - k * k)) - y * k3,
    )
}

/// The argument lengths Eq. (13)'s solvers need: n points, n − 1 chords and tangents.
fn check_eq13_lengths<const D: usize>(
    n: usize,
    tangents: &Tangents<D>,
    movable: &[bool],
    centers: &[Vector<D>],
    allowed: &[f64],
) -> Result<()> {
    if tangents.x.len() + 1 != n
        || tangents.chords.len() + 1 != n
        || movable.len() != n
        || centers.len() != n
        || allowed.len() != n
    {
        return Err(strategy_error("batten", "Eq. 13: inconsistent lengths"));
    }
    Ok(())
}

/// One sweep of Eq. (13) row by row ([`PositionUpdate::GaussSeidel`] or
/// [`PositionUpdate::Jacobi`]): point i goes to the solution of its own row, projected into
/// its range (`allowed[i]` around `centers[i]`), with the neighbours as updated so far
/// (Gauss–Seidel) or as given (Jacobi). Tangents and chords held. O(n).
pub fn eq13_sweep<const D: usize>(
    points: &[Vector<D>],
    tangents: &Tangents<D>,
    movable: &[bool],
    centers: &[Vector<D>],
    allowed: &[f64],
    gauss_seidel: bool,
) -> Result<Vec<Vector<D>>> {
    let n = points.len();
    check_eq13_lengths(n, tangents, movable, centers, allowed)?;
    let mut out = points.to_vec();
    for i in 1..n.saturating_sub(1) {
        if !movable[i] {
            continue;
        }
        let (k3, b) = eq13_row(tangents, i);
        let prev = if gauss_seidel { out[i - 1] } else { points[i - 1] };
        let p = (b + prev * 2.0 + points[i + 1] * (2.0 * k3)) / (2.0 * (1.0 + k3));
        if p.iter().any(|v| !v.is_finite()) {
            return Err(strategy_error("batten", "Eq. 13 gave a non-finite position"));
        }
        out[i] = project_into_ball(&centers[i], allowed[i], &p);
    }
    Ok(out)
}

/// Signs (−1, 0, +1) of the curvature of the curve's projections on the coordinate planes at
/// every point (Okada Step 4): one plane (x, y) in 2D, then (x, y), (y, z), (z, x) in 3D, laid
/// out plane by plane (index plane·n + i). The curvature at point i is taken on segment i at
/// t = 0 (segment n−2 at t = 1 for the last point): (ẋẏ̈ − ẏẍ)/(ẋ² + ẏ²)^{3/2} in the plane;
/// values with |κ| ≤ 1e-12 · max |κ| over the plane count as 0 (docs/CONTRACT.md's sign rule). O(n).
pub fn curvature_signs<const D: usize>(points: &[Vector<D>], tangents: &Tangents<D>) -> Vec<i8> {
    let planes: &[(usize, usize)] = match D {
        2 => &[(0, 1)],
        3 => &[(0, 1), (1, 2), (2, 0)],
        _ => &[],
    };
    let n = points.len();
    let mut derivatives = Vec::with_capacity(n);
    for i in 0..n.saturating_sub(1) {
        let Some(y) = tangents.y(i) else { break };
        let [_, _, r2, r3] = ferguson(points[i], points[i + 1], tangents.x[i], y);
        derivatives.push((tangents.x[i], r2 * 2.0));
        if i + 2 == n {
            derivatives.push((y, r2 * 2.0 + r3 * 6.0));
        }
    }
    let mut signs = Vec::with_capacity(planes.len() * n);
    for &(a, b) in planes {
        let kappa: Vec<f64> = derivatives
            .iter()
            .map(|(d1, d2)| {
                let speed = (d1[a] * d1[a] + d1[b] * d1[b]).sqrt();
                if speed > 0.0 {
                    (d1[a] * d2[b] - d1[b] * d2[a]) / speed.powi(3)
                } else {
                    0.0
                }
            })
            .collect();
        let max = kappa.iter().fold(0.0f64, |m, k| m.max(k.abs()));
        signs.extend(kappa.iter().map(|&k| {
            if k.abs() <= 1e-12 * max || !k.is_finite() {
                0
            } else if k > 0.0 {
                1
            } else {
                -1
            }
        }));
    }
    signs
}

/// Okada's batten as a [`FairingStrategy`]: one step is one iteration of §2.2 (Steps 2–6);
/// done when the curvature signs repeat. Open curves; fixed points, restraining radii
/// (Okada's adjustable ranges) and the tolerance band through the constraints; the two end
/// points never move (Eq. 13 runs over the interior). G1/G2 end clamps are refused: the end
/// tangents follow the circle through the (moving) end points.
#[derive(Clone, Debug)]
pub struct Batten<const D: usize> {
    settings: BattenSettings,
    /// The prescribed tangent directions as vectors (from the settings, at `init`).
    directions: Vec<(usize, Vector<D>)>,
    previous: Option<Vec<i8>>,
    iteration: usize,
    tangents: Option<Tangents<D>>,
}

impl<const D: usize> Batten<D> {
    /// A strategy with these settings.
    pub fn new(settings: BattenSettings) -> Self {
        Self {
            settings,
            directions: Vec::new(),
            previous: None,
            iteration: 0,
            tangents: None,
        }
    }
    /// The prescribed tangent directions as vectors (after `init`).
    pub fn tangent_directions(&self) -> &[(usize, Vector<D>)] {
        &self.directions
    }
    /// The tangents of the last iteration (before its position update).
    pub fn tangents(&self) -> Option<&Tangents<D>> {
        self.tangents.as_ref()
    }
    /// The curvature signs of the last iteration (see [`curvature_signs`]).
    pub fn signs(&self) -> Option<&[i8]> {
        self.previous.as_deref()
    }
}

impl<const D: usize> FairingStrategy<D> for Batten<D> {
    fn name(&self) -> &str {
        "batten"
    }

    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        if state.is_closed() {
            return Err(Error::refused(
                "batten",
                Refusal::Closed,
                "does not fair closed curves",
            ));
        }
        self.settings.validate()?;
        let n = state.len();
        let mut directions = Vec::with_capacity(self.settings.tangent_directions.len());
        for (i, d) in &self.settings.tangent_directions {
            if *i >= n {
                return Err(Error::BadValue {
                    name: "tangent-directions".into(),
                    message: format!("point {i} is past the last point ({n} points)"),
                });
            }
            if d.len() != D {
                return Err(Error::BadValue {
                    name: "tangent-directions".into(),
                    message: format!(
                        "the direction at point {i} has {} components, the points {D}",
                        d.len()
                    ),
                });
            }
            let d = Vector::<D>::from_iterator(d.iter().copied());
            if !(d.norm() > 0.0 && d.iter().all(|v| v.is_finite())) {
                return Err(Error::BadValue {
                    name: "tangent-directions".into(),
                    message: format!("prescribed tangent at point {i} has no direction"),
                });
            }
            directions.push((*i, d));
        }
        self.directions = directions;
        self.previous = None;
        self.iteration = 0;
        let tangents = okada_tangents(state.points(), &self.directions)?;
        state.criterion = Some(energy(state.points(), &tangents));
        self.tangents = Some(tangents);
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let n = state.len();
        let tangents = okada_tangents(state.points(), &self.directions)?;
        let signs = curvature_signs(state.points(), &tangents);
        let movable: Vec<bool> = (0..n).map(|i| state.is_movable(i)).collect();
        // Okada's adjustable range and the constraints' balls around the same centre: the
        // smaller one holds.
        let allowed: Vec<f64> = (0..n)
            .map(|i| state.constraints().allowed_distance(i).min(self.settings.range))
            .collect();
        let target = match self.settings.position_update {
            PositionUpdate::Solve => eq13_positions(
                state.points(),
                &tangents,
                &movable,
                state.original(),
                &allowed,
                self.settings.max_sweeps,
            )?,
            update => eq13_sweep(
                state.points(),
                &tangents,
                &movable,
                state.original(),
                &allowed,
                update == PositionUpdate::GaussSeidel,
            )?,
        };
        for (i, p) in target.iter().enumerate() {
            if movable[i] && i > 0 && i + 1 < n {
                state.move_point(i, *p)?;
            }
        }
        let criterion = energy(state.points(), &tangents);
        self.iteration += 1;
        let done = self.iteration >= 2 && self.previous.as_ref() == Some(&signs);
        self.previous = Some(signs);
        self.tangents = Some(tangents);
        Ok(StepOutcome {
            done,
            criterion: Some(criterion),
        })
    }
}
