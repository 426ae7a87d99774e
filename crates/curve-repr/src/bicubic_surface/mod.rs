//! The bicubic spline surface of Zhang–Cheng (2001) §4: bicubic Hermite patches through a grid
//! of points, with first partial derivatives from natural cubic splines along the grid lines
//! and twists from natural cubic splines of those derivatives.
//!
//! Data: P_ij at knots (u_i, v_j), i = 0..m along u, j = 0..n along v, m, n ≥ 1. The
//! construction ([`build`](BicubicSplineSurface::with_settings)):
//! 1. M^u_ij = S_u(u_i, v_j): the tangents of the natural cubic spline (Zhang–Cheng §2,
//!    Eq. 1–2 with free ends) through the u-line P_{0,j}..P_{m,j} over u_0..u_m, every j;
//! 2. M^v_ij = S_v(u_i, v_j): likewise along every v-line P_{i,0}..P_{i,n} over v_0..v_n;
//! 3. T_ij = S_uv(u_i, v_j): the tangents of the natural cubic spline through M^v_{0,j}..M^v_{m,j}
//!    over u_0..u_m, every j;
//! 4. the patch on [u_i, u_{i+1}] × [v_j, v_{j+1}] is the bicubic Hermite patch of its four
//!    corners' P, M^u, M^v and T (the tensor product of Eq. 1's Hermite basis).
//!
//! What this guarantees (each is tested in `tests/representations/bicubic_surface.rs`): writing A_u for the
//! linear map from values at u_0..u_m to natural-spline tangents, M^u = A_u P, M^v = P A_vᵀ and
//! T = A_u P A_vᵀ, which is also A_v applied along v to M^u: the twists are the same whichever
//! direction step 3 takes. The surface is therefore the tensor-product natural bicubic spline
//! interpolant: every u-line S(·, v_j) and v-line S(u_i, ·) is exactly the natural cubic spline
//! through its row or column of points, and S is C2 in u across every u-knot line and C2 in v
//! across every v-knot line, everywhere on those lines, not only at the nodes (∂^{a+b}S/∂u^a∂v^b
//! with a ≤ 2 is continuous across u = u_i). Only ∂³S/∂u³ (resp. ∂³S/∂v³) jumps there. It
//! reproduces exactly every surface x(u)·y(v)-separable into natural cubic splines over the
//! knots, in particular every bilinear one a + b u + c v + d u v; it keeps every planar grid in
//! its plane. It does not reproduce a quadric (a natural spline has zero second derivative at
//! its ends).
//!
//! **Closed nets** ([`BicubicSurfaceSettings::with_closed_v`], [`GridTopology`]): along a
//! closed direction every grid line is the *periodic* cubic spline through its points (the
//! last repeating the first), so the surface is C2 across the seam as across any interior
//! knot line, the seam's nodes are interior nodes with a z_ij like any other, and the repeated
//! line is stored (the layout of the input) but counted once by [`max_z`](BicubicSplineSurface::max_z),
//! [`third_derivative_jumps`](BicubicSplineSurface::third_derivative_jumps) and
//! [`network_strain_energy`](BicubicSplineSurface::network_strain_energy). Everything above holds with
//! "natural" read as "periodic" in that direction.

mod build;
mod natural;
mod topology;
mod update;

pub use build::BicubicSurfaceSettings;
pub use topology::{GridTopology, Poles, COINCIDENCE};

use natural::{segment_second_derivatives, segment_third_derivative, NaturalSplineSystem};

use crate::surface::MAX_PARTIAL_ORDER;
use crate::{Side, Surface, Vec3};

/// A bicubic spline surface interpolating a grid of points (Zhang–Cheng 2001, §4).
///
/// Grid values are stored flat with index i·(n+1) + j for node (u_i, v_j); every accessor that
/// returns a slice uses this layout. See the [module documentation](self) for the construction
/// and what it guarantees.
#[derive(Clone, Debug, PartialEq)]
pub struct BicubicSplineSurface {
    /// m + 1.
    u_count: usize,
    /// n + 1.
    v_count: usize,
    points: Vec<Vec3>,
    u_knots: Vec<f64>,
    v_knots: Vec<f64>,
    /// M^u_ij = S_u(u_i, v_j).
    u_tangents: Vec<Vec3>,
    /// M^v_ij = S_v(u_i, v_j).
    v_tangents: Vec<Vec3>,
    /// T_ij = S_uv(u_i, v_j).
    twists: Vec<Vec3>,
    u_system: NaturalSplineSystem,
    v_system: NaturalSplineSystem,
}

/// The third-derivative jumps of a [`BicubicSplineSurface`] at one interior node (u_i, v_j):
/// the two terms of the surface indicator z_ij of Zhang–Cheng Eq. 26 (as corrected in
/// papers/README.md).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeJump {
    /// Index along u: 1 ≤ i ≤ m − 1, or 0 ≤ i ≤ m − 1 when the surface is closed in u.
    pub i: usize,
    /// Index along v: 1 ≤ j ≤ n − 1, or 0 ≤ j ≤ n − 1 when the surface is closed in v.
    pub j: usize,
    /// ∂³S/∂u³(u_i+, v_j) − ∂³S/∂u³(u_i−, v_j).
    pub u: Vec3,
    /// ∂³S/∂v³(u_i, v_j+) − ∂³S/∂v³(u_i, v_j−).
    pub v: Vec3,
}

impl NodeJump {
    /// z_ij = |u jump| + |v jump| (Eq. 26).
    pub fn z(&self) -> f64 {
        self.u.norm() + self.v.norm()
    }
}

impl BicubicSplineSurface {
    /// Index of node (i, j) in the flat layout, if it exists.
    fn index(&self, i: usize, j: usize) -> Option<usize> {
        (i < self.u_count && j < self.v_count).then(|| i * self.v_count + j)
    }

    /// (m + 1, n + 1): the number of grid lines along u and along v.
    pub fn shape(&self) -> (usize, usize) {
        (self.u_count, self.v_count)
    }

    /// Whether the surface is periodic along u (row m repeats row 0).
    pub fn closed_u(&self) -> bool {
        self.u_system.is_periodic()
    }

    /// Whether the surface is periodic along v (column n repeats column 0).
    pub fn closed_v(&self) -> bool {
        self.v_system.is_periodic()
    }

    /// The interior node that (i, j) names, or `None` if it is not interior: along an open
    /// direction 1 ≤ i ≤ m − 1; along a closed one every index, the repeated line m (or n)
    /// naming line 0.
    pub fn interior_node(&self, i: usize, j: usize) -> Option<(usize, usize)> {
        let along = |k: usize, count: usize, closed: bool| {
            if closed {
                (k < count).then_some(if k + 1 == count { 0 } else { k })
            } else {
                (k >= 1 && k + 1 < count).then_some(k)
            }
        };
        Some((
            along(i, self.u_count, self.closed_u())?,
            along(j, self.v_count, self.closed_v())?,
        ))
    }

    /// The interior nodes, each once (a closed direction's repeated line left out), i-major.
    pub fn interior_nodes(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let range = |count: usize, closed: bool| {
            if closed {
                0..count - 1
            } else {
                1..count.saturating_sub(1).max(1)
            }
        };
        let (us, vs) = (
            range(self.u_count, self.closed_u()),
            range(self.v_count, self.closed_v()),
        );
        us.flat_map(move |i| vs.clone().map(move |j| (i, j)))
    }

    /// The knots u_0 < … < u_m.
    pub fn u_knots(&self) -> &[f64] {
        &self.u_knots
    }

    /// The knots v_0 < … < v_n.
    pub fn v_knots(&self) -> &[f64] {
        &self.v_knots
    }

    /// All data points, flat: index i·(n+1) + j.
    pub fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// All data points, flat (as [`points`](Self::points)), taken out of the surface without
    /// a copy.
    pub fn into_points(self) -> Vec<Vec3> {
        self.points
    }

    /// The data points as a grid `grid[i][j]` = P_ij, the layout the constructor takes.
    pub fn grid(&self) -> Vec<Vec<Vec3>> {
        self.points.chunks(self.v_count).map(<[Vec3]>::to_vec).collect()
    }

    /// The data point P_ij, or `None` outside the grid.
    pub fn point(&self, i: usize, j: usize) -> Option<Vec3> {
        self.index(i, j).map(|k| self.points[k])
    }

    /// All M^u_ij = ∂S/∂u(u_i, v_j), flat.
    pub fn u_tangents(&self) -> &[Vec3] {
        &self.u_tangents
    }

    /// All M^v_ij = ∂S/∂v(u_i, v_j), flat.
    pub fn v_tangents(&self) -> &[Vec3] {
        &self.v_tangents
    }

    /// All twists T_ij = ∂²S/∂u∂v(u_i, v_j), flat.
    pub fn twists(&self) -> &[Vec3] {
        &self.twists
    }

    /// M^u_ij, or `None` outside the grid.
    pub fn u_tangent(&self, i: usize, j: usize) -> Option<Vec3> {
        self.index(i, j).map(|k| self.u_tangents[k])
    }

    /// M^v_ij, or `None` outside the grid.
    pub fn v_tangent(&self, i: usize, j: usize) -> Option<Vec3> {
        self.index(i, j).map(|k| self.v_tangents[k])
    }

    /// The twist T_ij, or `None` outside the grid.
    pub fn twist(&self, i: usize, j: usize) -> Option<Vec3> {
        self.index(i, j).map(|k| self.twists[k])
    }

    /// The third-derivative jumps at the interior node (u_i, v_j), or `None` unless it is
    /// interior (see [`interior_node`](Self::interior_node); across a seam the jump is between
    /// the last segment and the first). O(1): along v = v_j the surface is the Hermite spline
    /// of row j, whose third derivative on a segment is (12(P_k − P_{k+1})/h + 6(M_k + M_{k+1}))/h².
    pub fn third_derivative_jump(&self, i: usize, j: usize) -> Option<NodeJump> {
        let (i, j) = self.interior_node(i, j)?;
        let hu = self.u_system.steps();
        let hv = self.v_system.steps();
        let p = |a: usize, b: usize| self.points[a * self.v_count + b];
        let mu = |a: usize, b: usize| self.u_tangents[a * self.v_count + b];
        let mv = |a: usize, b: usize| self.v_tangents[a * self.v_count + b];
        // The segment before node 0 of a closed direction is the last one, ending on the
        // stored repeat of line 0.
        let iu = if i == 0 { self.u_count - 2 } else { i - 1 };
        let jv = if j == 0 { self.v_count - 2 } else { j - 1 };
        let u_before = segment_third_derivative(p(iu, j), mu(iu, j), mu(iu + 1, j), p(iu + 1, j), hu[iu]);
        let u_after = segment_third_derivative(p(i, j), mu(i, j), mu(i + 1, j), p(i + 1, j), hu[i]);
        let v_before = segment_third_derivative(p(i, jv), mv(i, jv), mv(i, jv + 1), p(i, jv + 1), hv[jv]);
        let v_after = segment_third_derivative(p(i, j), mv(i, j), mv(i, j + 1), p(i, j + 1), hv[j]);
        Some(NodeJump {
            i,
            j,
            u: u_after - u_before,
            v: v_after - v_before,
        })
    }

    /// The surface indicator z_ij of Zhang–Cheng Eq. 26 (corrected, papers/README.md) at an
    /// interior node (a seam's included), or `None` elsewhere. O(1).
    pub fn z(&self, i: usize, j: usize) -> Option<f64> {
        self.third_derivative_jump(i, j).map(|jump| jump.z())
    }

    /// The jumps at every interior node, each once, i-major. O(m·n).
    pub fn third_derivative_jumps(&self) -> Vec<NodeJump> {
        self.interior_nodes()
            .filter_map(|(i, j)| self.third_derivative_jump(i, j))
            .collect()
    }

    /// max z_ij over the interior nodes (0 when there are none): the report's `max_z`. O(m·n).
    pub fn max_z(&self) -> f64 {
        self.interior_nodes()
            .filter_map(|(i, j)| self.z(i, j))
            .fold(0.0, f64::max)
    }

    /// The strain energy of the network curves (the report's `e_s` for surfaces, the sum that
    /// Zhang–Cheng Eq. 18 takes locally):
    /// Σ_j ∫ |∂²S/∂u²(u, v_j)|² du + Σ_i ∫ |∂²S/∂v²(u_i, v)|² dv.
    ///
    /// Each network curve is a natural cubic spline whose second derivative is linear on each
    /// segment, so a segment of length h with end second derivatives a, b adds
    /// h(|a|² + a·b + |b|²)/3 exactly. The repeated line of a closed direction is not a second
    /// network curve and is left out. O(m·n).
    pub fn network_strain_energy(&self) -> f64 {
        let segment = |p0: Vec3, m0: Vec3, m1: Vec3, p1: Vec3, h: f64| {
            let (a, b) = segment_second_derivatives(p0, m0, m1, p1, h);
            h * (a.norm_squared() + a.dot(&b) + b.norm_squared()) / 3.0
        };
        let vc = self.v_count;
        let (u_lines, v_lines) = (
            self.u_count - usize::from(self.closed_u()),
            vc - usize::from(self.closed_v()),
        );
        let mut energy = 0.0;
        for (i, &h) in self.u_system.steps().iter().enumerate() {
            for j in 0..v_lines {
                let (k0, k1) = (i * vc + j, (i + 1) * vc + j);
                energy += segment(
                    self.points[k0],
                    self.u_tangents[k0],
                    self.u_tangents[k1],
                    self.points[k1],
                    h,
                );
            }
        }
        for i in 0..u_lines {
            for (j, &h) in self.v_system.steps().iter().enumerate() {
                let (k0, k1) = (i * vc + j, i * vc + j + 1);
                energy += segment(
                    self.points[k0],
                    self.v_tangents[k0],
                    self.v_tangents[k1],
                    self.points[k1],
                    h,
                );
            }
        }
        energy
    }
}

/// The patch index k with the parameter in [t_k, t_{k+1}], taking the piece on `side` at an
/// interior knot and the end pieces outside the knot range.
fn patch_index(knots: &[f64], t: f64, side: Side) -> usize {
    let below = match side {
        Side::Right => knots.partition_point(|&knot| knot <= t),
        Side::Left => knots.partition_point(|&knot| knot < t),
    };
    below.saturating_sub(1).min(knots.len().saturating_sub(2))
}

/// The `order`-th derivatives in s of the cubic Hermite basis of Zhang–Cheng Eq. 1, in the
/// order [φ0, φ1, ψ1, ψ0] (coefficients of P_i, h M_i, h M_{i+1}, P_{i+1}).
fn hermite_basis(s: f64, order: usize) -> [f64; 4] {
    let s2 = s * s;
    match order {
        0 => [
            1.0 - 3.0 * s2 + 2.0 * s2 * s,
            s - 2.0 * s2 + s2 * s,
            -s2 + s2 * s,
            3.0 * s2 - 2.0 * s2 * s,
        ],
        1 => [
            -6.0 * s + 6.0 * s2,
            1.0 - 4.0 * s + 3.0 * s2,
            -2.0 * s + 3.0 * s2,
            6.0 * s - 6.0 * s2,
        ],
        2 => [-6.0 + 12.0 * s, -4.0 + 6.0 * s, -2.0 + 6.0 * s, 6.0 - 12.0 * s],
        _ => [12.0, 6.0, 6.0, -12.0],
    }
}

impl Surface for BicubicSplineSurface {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        let first_last = |knots: &[f64]| {
            (
                knots.first().copied().unwrap_or(0.0),
                knots.last().copied().unwrap_or(0.0),
            )
        };
        (first_last(&self.u_knots), first_last(&self.v_knots))
    }

    /// Evaluates the bicubic Hermite patch containing (u, v) (the patch on `side_u`/`side_v` at
    /// a knot line; the end patches extended outside the domain). O(log m + log n).
    ///
    /// Returns `None` when `du` or `dv` exceeds 3, and when u or v is not finite.
    fn partial_from(&self, u: f64, v: f64, du: usize, dv: usize, side_u: Side, side_v: Side) -> Option<Vec3> {
        if du > MAX_PARTIAL_ORDER || dv > MAX_PARTIAL_ORDER || !u.is_finite() || !v.is_finite() {
            return None;
        }
        let i = patch_index(&self.u_knots, u, side_u);
        let j = patch_index(&self.v_knots, v, side_v);
        let hu = *self.u_system.steps().get(i)?;
        let hv = *self.v_system.steps().get(j)?;
        let basis_u = hermite_basis((u - self.u_knots[i]) / hu, du);
        let basis_v = hermite_basis((v - self.v_knots[j]) / hv, dv);
        // Basis slot a ∈ {0, 1, 2, 3} is (node offset, derivative?): P_i, h M_i, h M_{i+1}, P_{i+1}.
        const SLOTS: [(usize, bool); 4] = [(0, false), (0, true), (1, true), (1, false)];
        let mut sum = Vec3::zeros();
        for (a, &(di, u_derivative)) in SLOTS.iter().enumerate() {
            for (b, &(dj, v_derivative)) in SLOTS.iter().enumerate() {
                let k = (i + di) * self.v_count + j + dj;
                let coefficient = match (u_derivative, v_derivative) {
                    (false, false) => self.points[k],
                    (true, false) => self.u_tangents[k] * hu,
                    (false, true) => self.v_tangents[k] * hv,
                    (true, true) => self.twists[k] * (hu * hv),
                };
                sum += coefficient * (basis_u[a] * basis_v[b]);
            }
        }
        Some(sum / (hu.powi(du as i32) * hv.powi(dv as i32)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_basis_derivatives_match_finite_differences() {
        let step = 1e-6;
        for &s in &[0.0, 0.3, 0.77, 1.0] {
            for order in 0..3 {
                let above = hermite_basis(s + step, order);
                let below = hermite_basis(s - step, order);
                let derivative = hermite_basis(s, order + 1);
                for k in 0..4 {
                    let difference = (above[k] - below[k]) / (2.0 * step);
                    assert!(
                        (difference - derivative[k]).abs() < 1e-8,
                        "s {s} order {order} k {k}"
                    );
                }
            }
        }
        // Hermite conditions at s = 0 and s = 1.
        assert_eq!(hermite_basis(0.0, 0), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(hermite_basis(1.0, 0), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(hermite_basis(0.0, 1), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(hermite_basis(1.0, 1), [0.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn patch_index_takes_the_requested_side() {
        let knots = [0.0, 1.0, 2.5, 4.0];
        assert_eq!(patch_index(&knots, 1.0, Side::Right), 1);
        assert_eq!(patch_index(&knots, 1.0, Side::Left), 0);
        assert_eq!(patch_index(&knots, 0.0, Side::Left), 0);
        assert_eq!(patch_index(&knots, 4.0, Side::Right), 2);
        assert_eq!(patch_index(&knots, -3.0, Side::Right), 0);
        assert_eq!(patch_index(&knots, 9.0, Side::Left), 2);
        assert_eq!(patch_index(&knots, 2.0, Side::Left), 1);
    }
}
