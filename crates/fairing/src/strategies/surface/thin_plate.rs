//! The thin-plate variants of Zhang–Cheng §4.5 (Eq. 27–29): move one point, an adjacent pair
//! or a 2×2 block to the minimiser of
//!
//! E = Σ_patches ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|² du dv
//!
//! over the patches having a moved point as a corner (Eq. 27: the four around P_ij; Eq. 28:
//! the six around a pair; Eq. 29: the nine around a block), the tangents and twists held, as
//! Eq. 18 holds the tangents. A moved corner P_a enters its patches through the value basis
//! B_a(u, v) = f(s) g(t) (f, g the Hermite value functions φ0 = 1 − 3s² + 2s³ or
//! ψ0 = 3s² − 2s³), so with L = (∂_uu, √2 ∂_uv, ∂_vv),
//!
//! E(P + Σ_a B_a Δ_a) = E + 2 Σ_a g_a·Δ_a + Σ_ab H_ab Δ_a·Δ_b,
//! H_ab = Σ ∫∫ L B_a · L B_b, g_a = Σ ∫∫ L B_a · L S (per coordinate),
//!
//! and the minimiser solves H Δ = −g. Each integrand is a polynomial of degree ≤ 6 in s and
//! in t, so the 4 × 4 Gauss–Legendre rule is exact. O(1) per group (at most 9 patches × 16
//! points).

use curve_repr::{BicubicSplineSurface, Surface, Vec3};

use super::closed_form::solve;
use crate::Result;

/// 4-point Gauss–Legendre nodes and weights on [0, 1].
const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_87, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// The Hermite value function of the corner at offset `far` (0: φ0, 1: ψ0) and its first and
/// second derivatives at s.
pub(crate) fn value_basis(far: bool, s: f64) -> [f64; 3] {
    let near = [
        1.0 - 3.0 * s * s + 2.0 * s * s * s,
        -6.0 * s + 6.0 * s * s,
        -6.0 + 12.0 * s,
    ];
    if far {
        [1.0 - near[0], -near[1], -near[2]]
    } else {
        near
    }
}

/// The grid positions of node (i, j): itself, and its stored repeats across the seams of a
/// closed surface.
fn copies(surface: &BicubicSplineSurface, i: usize, j: usize) -> Vec<(usize, usize)> {
    let (u_count, v_count) = surface.shape();
    let along = |k: usize, count: usize, closed: bool| {
        if closed && k == 0 {
            vec![0, count - 1]
        } else {
            vec![k]
        }
    };
    let mut all = Vec::new();
    for a in along(i, u_count, surface.closed_u()) {
        for b in along(j, v_count, surface.closed_v()) {
            all.push((a, b));
        }
    }
    all
}

/// The thin-plate minimiser (Eq. 27 / 28 / 29) for a group of interior nodes of `surface`
/// (a closed direction's seam nodes named by index 0; their patches on both sides of the seam
/// are summed): `Ok(None)` for an empty or oversized group, a node outside the interior, or a
/// singular system; errors only on a surface that cannot be evaluated.
pub(crate) fn thin_plate_targets(
    surface: &BicubicSplineSurface,
    group: &[(usize, usize)],
) -> Result<Option<Vec<Vec3>>> {
    let (u_count, v_count) = surface.shape();
    if group.is_empty()
        || group.len() > 4
        || group
            .iter()
            .any(|&(i, j)| surface.interior_node(i, j) != Some((i, j)))
    {
        return Ok(None);
    }
    let group_copies: Vec<Vec<(usize, usize)>> = group.iter().map(|&(i, j)| copies(surface, i, j)).collect();
    let mut patches: Vec<(usize, usize)> = group_copies
        .iter()
        .flatten()
        .flat_map(|&(i, j)| {
            [
                (i as isize - 1, j as isize - 1),
                (i as isize - 1, j as isize),
                (i as isize, j as isize - 1),
                (i as isize, j as isize),
            ]
        })
        .filter(|&(l, k)| l >= 0 && k >= 0 && (l as usize) + 1 < u_count && (k as usize) + 1 < v_count)
        .map(|(l, k)| (l as usize, k as usize))
        .collect();
    patches.sort_unstable();
    patches.dedup();
    let (uk, vk) = (surface.u_knots(), surface.v_knots());
    let mut hessian = [[0.0; 4]; 4];
    let mut gradient = [Vec3::zeros(); 4];
    for (l, k) in patches {
        let (hu, hv) = (uk[l + 1] - uk[l], vk[k + 1] - vk[k]);
        let corners: Vec<(usize, bool, bool)> = group_copies
            .iter()
            .enumerate()
            .flat_map(|(a, copies)| copies.iter().map(move |&node| (a, node)))
            .filter(|&(_, (i, j))| (i == l || i == l + 1) && (j == k || j == k + 1))
            .map(|(a, (i, j))| (a, i == l + 1, j == k + 1))
            .collect();
        for &(s, ws) in &GAUSS {
            for &(t, wt) in &GAUSS {
                let (u, v) = (uk[l] + s * hu, vk[k] + t * hv);
                let second = |du, dv| {
                    surface
                        .partial(u, v, du, dv)
                        .filter(|p| p.iter().all(|c| c.is_finite()))
                        .ok_or(crate::Error::NonFiniteMove {
                            index: l * v_count + k,
                        })
                };
                let (suu, suv, svv) = (second(2, 0)?, second(1, 1)?, second(0, 2)?);
                let weight = ws * wt * hu * hv;
                let operators: Vec<(usize, [f64; 3])> = corners
                    .iter()
                    .map(|&(a, far_u, far_v)| {
                        let (f, g) = (value_basis(far_u, s), value_basis(far_v, t));
                        (
                            a,
                            [
                                f[2] * g[0] / (hu * hu),
                                f[1] * g[1] / (hu * hv),
                                f[0] * g[2] / (hv * hv),
                            ],
                        )
                    })
                    .collect();
                for &(a, la) in &operators {
                    gradient[a] += (suu * la[0] + suv * (2.0 * la[1]) + svv * la[2]) * weight;
                    for &(b, lb) in &operators {
                        hessian[a][b] += weight * (la[0] * lb[0] + 2.0 * la[1] * lb[1] + la[2] * lb[2]);
                    }
                }
            }
        }
    }
    let rhs = gradient.map(|g| -g);
    Ok(solve(&hessian, &rhs, group.len()).map(|deltas| {
        group
            .iter()
            .zip(deltas)
            .map(|(&(i, j), d)| surface.point(i, j).unwrap_or_default() + d)
            .collect()
    }))
}
