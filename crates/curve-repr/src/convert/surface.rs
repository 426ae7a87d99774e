//! [`BicubicSplineSurface`] → B-spline surface.

use super::pieces::{best_piece, blossom, clamped_knots, join_order};
use super::C2_TOLERANCE;
use crate::{BicubicSplineSurface, Error, NurbsSurface, Result, Vec3};

/// The Bézier net of one bicubic patch, `net[a][b]` with a along u and b along v.
type Net = [[Vec3; 4]; 4];

impl BicubicSplineSurface {
    /// The Bézier net of patch (i, j) on [u_i, u_{i+1}] × [v_j, v_{j+1}], `net[a][b]` with a
    /// along u, or `None` outside the grid of patches.
    ///
    /// The tensor product of Eq. 1's Hermite-to-Bézier step: at a corner with data P, M^u,
    /// M^v, T and signs σ_u = +1 at u_i, −1 at u_{i+1} (σ_v likewise), the corner point is P,
    /// its neighbours along u and v are P + σ_u h_u M^u/3 and P + σ_v h_v M^v/3, and the inner
    /// point is P + σ_u h_u M^u/3 + σ_v h_v M^v/3 + σ_u σ_v h_u h_v T/9. O(1).
    pub fn bezier_patch(&self, i: usize, j: usize) -> Option<Net> {
        let (uk, vk) = (self.u_knots(), self.v_knots());
        let (hu, hv) = (uk.get(i + 1)? - uk[i], vk.get(j + 1)? - vk[j]);
        let mut net = [[Vec3::zeros(); 4]; 4];
        for (di, su) in [(0usize, 1.0), (1, -1.0)] {
            for (dj, sv) in [(0usize, 1.0), (1, -1.0)] {
                let (ii, jj) = (i + di, j + dj);
                let p = self.point(ii, jj)?;
                let du = self.u_tangent(ii, jj)? * (su * hu / 3.0);
                let dv = self.v_tangent(ii, jj)? * (sv * hv / 3.0);
                let twist = self.twist(ii, jj)? * (su * sv * hu * hv / 9.0);
                let (a0, b0) = (3 * di, 3 * dj);
                let (a1, b1) = (if di == 0 { 1 } else { 2 }, if dj == 0 { 1 } else { 2 });
                net[a0][b0] = p;
                net[a1][b0] = p + du;
                net[a0][b1] = p + dv;
                net[a1][b1] = p + du + dv + twist;
            }
        }
        Some(net)
    }

    /// The surface as a bicubic B-spline surface (unit weights) on the same parameters:
    /// knots at the u_i and v_j, each interior knot line single where the patches on both
    /// sides join C2 across it (all of them, by the construction of Zhang–Cheng §4), double
    /// or triple where they are found to join only C1 or C0, the joins checked per patch
    /// and Bézier row with [`C2_TOLERANCE`] as [`CubicPieces::join_continuity`](super::CubicPieces::join_continuity)
    /// does. Control point (r, s) is the tensor blossom of a patch in its support. An
    /// (m + 1) × (n + 1) grid gives (m + 3) × (n + 3) control points. Fails with
    /// [`Error::Discontinuous`] (index of the knot line) if patches do not meet. O(m·n).
    pub fn to_bspline(&self) -> Result<NurbsSurface> {
        let (u_count, v_count) = self.shape();
        let (pu, pv) = (u_count - 1, v_count - 1);
        let nets: Vec<Net> = (0..pu)
            .flat_map(|i| (0..pv).map(move |j| (i, j)))
            .map(|(i, j)| self.bezier_patch(i, j).ok_or(Error::Singular { what: "patch" }))
            .collect::<Result<_>>()?;
        let net = |i: usize, j: usize| &nets[i * pv + j];
        let size = scale(&nets);
        let allowed = C2_TOLERANCE * size;
        let (uk, vk) = (self.u_knots(), self.v_knots());
        // Continuity across u = u_b: every v-patch, every Bézier column b of the nets.
        let mut u_continuity = Vec::with_capacity(pu.saturating_sub(1));
        for b in 1..pu {
            let mut order = 2;
            for j in 0..pv {
                for column in 0..4 {
                    let left = net(b - 1, j).map(|row| row[column]);
                    let right = net(b, j).map(|row| row[column]);
                    let o = join_order(&left, &right, [uk[b - 1], uk[b], uk[b + 1]], allowed)
                        .map_err(|gap| Error::Discontinuous { index: b, gap })?;
                    order = order.min(o);
                }
            }
            u_continuity.push(order);
        }
        let mut v_continuity = Vec::with_capacity(pv.saturating_sub(1));
        for b in 1..pv {
            let mut order = 2;
            for i in 0..pu {
                for row in 0..4 {
                    let left = net(i, b - 1)[row];
                    let right = net(i, b)[row];
                    let o = join_order(&left, &right, [vk[b - 1], vk[b], vk[b + 1]], allowed)
                        .map_err(|gap| Error::Discontinuous { index: b, gap })?;
                    order = order.min(o);
                }
            }
            v_continuity.push(order);
        }
        let (knots_u, break_u) = clamped_knots(uk, &u_continuity);
        let (knots_v, break_v) = clamped_knots(vk, &v_continuity);
        let rows = knots_u.len() - 4;
        let columns = knots_v.len() - 4;
        let mut control = Vec::with_capacity(rows);
        for r in 0..rows {
            let args_u = [knots_u[r + 1], knots_u[r + 2], knots_u[r + 3]];
            let i = best_piece(uk, &break_u, r, args_u);
            let row: Vec<Vec3> = (0..columns)
                .map(|s| {
                    let args_v = [knots_v[s + 1], knots_v[s + 2], knots_v[s + 3]];
                    let j = best_piece(vk, &break_v, s, args_v);
                    let patch = net(i, j);
                    let along_u: [Vec3; 4] = std::array::from_fn(|b| {
                        let column = patch.map(|line| line[b]);
                        blossom(&column, uk[i], uk[i + 1], args_u)
                    });
                    blossom(&along_u, vk[j], vk[j + 1], args_v)
                })
                .collect();
            control.push(row);
        }
        let weights = vec![vec![1.0; columns]; rows];
        NurbsSurface::new(3, 3, knots_u, knots_v, control, weights)
    }
}

/// The larger of the Bézier points' bounding-box diagonal and their largest coordinate.
fn scale(nets: &[Net]) -> f64 {
    let mut low = Vec3::from_element(f64::INFINITY);
    let mut high = Vec3::from_element(f64::NEG_INFINITY);
    let mut largest = 0.0_f64;
    for p in nets.iter().flatten().flatten() {
        low = low.inf(p);
        high = high.sup(p);
        largest = largest.max(p.amax());
    }
    (high - low).norm().max(largest)
}
