//! The new positions of one, two or four bad points (Zhang–Cheng §4.1–4.3).
//!
//! Notation of Eq. 20 (corrected, papers/README.md): ū_i = 1/(u_{i+1} − u_i),
//! v̄_j = 1/(v_{j+1} − v_j),
//!
//! α_ij = ū_{i−1}² M^u_{i−1,j} − (ū_i² − ū_{i−1}²) M^u_ij − ū_i² M^u_{i+1,j},
//! β_ij = v̄_{j−1}² M^v_{i,j−1} − (v̄_j² − v̄_{j−1}²) M^v_ij − v̄_j² M^v_{i,j+1},
//! τ_ij = 2(ū_{i−1}³ + ū_i³ + v̄_{j−1}³ + v̄_j³).
//!
//! **Tangents held** ([`fixed_tangent_targets`]): the minimiser of the network-curve energy
//! around the group (Eq. 18, 22, 24) with M^u, M^v fixed. Its gradient in P_ab is
//! 2(J^u_ab + J^v_ab) (integrate ∫C''·δC'' by parts twice on each Hermite segment), and the
//! jumps are affine in the points with ∂J^u_ij/∂P_ij = 12(ū_{i−1}³ + ū_i³),
//! ∂J^u_ij/∂P_{i±1,j} = −12ū³ of the shared interval (likewise in v). Setting the gradient to
//! zero and dividing by 6 gives the paper's systems: Eq. 20 for one point
//! (τ_ij P̄_ij = 2(ū_{i−1}³P_{i−1,j} + ū_i³P_{i+1,j} + v̄_{j−1}³P_{i,j−1} + v̄_j³P_{i,j+1}) + α_ij + β_ij),
//! Eq. 23 for an adjacent pair (off-diagonal −2ū_i³ coupling the two), Eq. 25 for a 2×2 block
//! (−2ū_i³ along u, −2v̄_j³ along v). One routine builds all three: the coefficient of a
//! neighbour that is itself in the group moves to the left-hand side.
//!
//! **Limit** ([`limit_targets`]): the fixed point of repeating the above with the tangents
//! re-solved after every move, the system Eq. 21 (and its two- and four-point analogues):
//! J^u_ab + J^v_ab = 0 at every point of the group for the re-built surface. Along a u-line
//! J = K_u P with K_u the same for every line (same knots), so the group's displacements Δ
//! solve Σ_b (K_u[i_a, i_b]·[j_a = j_b] + K_v[j_a, j_b]·[i_a = i_b]) Δ_b = −(J^u_a + J^v_a):
//! one small system with the [`Stiffness`](super::network::Stiffness) entries, solved once.
//! For one point this is P̄ = P − (J^u + J^v)/(K_u[i,i] + K_v[j,j]), the exact minimiser of
//! the whole network energy over P_ij (whose Hessian is that scalar times the identity).
//!
//! Both are O(1) per group after the network is built. Along a closed direction the
//! neighbours and knot steps wrap round the seam (node 0's previous node is node N − 1, over
//! the closing step), so a seam node is replaced like any other.

use curve_repr::Vec3;

use super::network::{Network, Stiffness};

/// A group of bad points: one point, an adjacent pair, or a 2×2 block, as (i, j) nodes.
pub type Group = Vec<(usize, usize)>;

/// Whether every node of `group` is interior and the group is one, two or four nodes.
pub(crate) fn is_valid_group(network: &Network, group: &[(usize, usize)]) -> bool {
    !group.is_empty() && group.len() <= 4 && group.iter().all(|&(i, j)| network.is_interior(i, j))
}

/// (1/h before node k, 1/h after it) along a line, the steps wrapping round a closed line.
fn reciprocal_steps(stiffness: &Stiffness, k: usize) -> (f64, f64) {
    let before = stiffness.previous(k).map_or(f64::INFINITY, |p| stiffness.step(p));
    (1.0 / before, 1.0 / stiffness.step(k))
}

/// The neighbours of node k along a line: (previous, next), wrapping round a closed line.
fn neighbours(stiffness: &Stiffness, k: usize) -> (usize, usize) {
    (stiffness.previous(k).unwrap_or(k), stiffness.next(k).unwrap_or(k))
}

/// α_ij of Eq. 20.
pub(crate) fn alpha(network: &Network, i: usize, j: usize) -> Vec3 {
    let s = network.u_stiffness();
    let (a, b) = reciprocal_steps(s, i);
    let (before, after) = neighbours(s, i);
    network.u_tangent(before, j) * (a * a)
        - network.u_tangent(i, j) * (b * b - a * a)
        - network.u_tangent(after, j) * (b * b)
}

/// β_ij of Eq. 20 (M^v throughout, papers/README.md).
pub(crate) fn beta(network: &Network, i: usize, j: usize) -> Vec3 {
    let s = network.v_stiffness();
    let (a, b) = reciprocal_steps(s, j);
    let (before, after) = neighbours(s, j);
    network.v_tangent(i, before) * (a * a)
        - network.v_tangent(i, j) * (b * b - a * a)
        - network.v_tangent(i, after) * (b * b)
}

/// τ_ij of Eq. 20.
pub(crate) fn tau(network: &Network, i: usize, j: usize) -> f64 {
    let (a, b) = reciprocal_steps(network.u_stiffness(), i);
    let (c, d) = reciprocal_steps(network.v_stiffness(), j);
    2.0 * (a.powi(3) + b.powi(3) + c.powi(3) + d.powi(3))
}

/// Eq. 20 / 23 / 25: the minimiser of the group's network-curve energy (Eq. 18 / 22 / 24)
/// with the tangents held, for a valid group (see [`is_valid_group`]); `None` for an invalid
/// group or a singular system. O(1).
pub(crate) fn fixed_tangent_targets(network: &Network, group: &[(usize, usize)]) -> Option<Vec<Vec3>> {
    if !is_valid_group(network, group) {
        return None;
    }
    let size = group.len();
    let mut matrix = [[0.0; 4]; 4];
    let mut rhs = [Vec3::zeros(); 4];
    for (a, &(i, j)) in group.iter().enumerate() {
        matrix[a][a] = tau(network, i, j);
        rhs[a] = alpha(network, i, j) + beta(network, i, j);
        let (u_before, u_after) = reciprocal_steps(network.u_stiffness(), i);
        let (v_before, v_after) = reciprocal_steps(network.v_stiffness(), j);
        let (ui, uo) = neighbours(network.u_stiffness(), i);
        let (vi, vo) = neighbours(network.v_stiffness(), j);
        let neighbours = [
            ((ui, j), u_before),
            ((uo, j), u_after),
            ((i, vi), v_before),
            ((i, vo), v_after),
        ];
        for (node, reciprocal) in neighbours {
            let weight = 2.0 * reciprocal.powi(3);
            match group.iter().position(|&g| g == node) {
                Some(b) => matrix[a][b] -= weight,
                None => rhs[a] += network.point(node.0, node.1) * weight,
            }
        }
    }
    solve(&matrix, &rhs, size)
}

/// The limit system (Eq. 21 for one point, its analogue for two and four): the positions at
/// which J^u + J^v vanishes at every node of the group with the tangents re-solved. `None`
/// for an invalid group or a singular system. O(1).
pub(crate) fn limit_targets(network: &Network, group: &[(usize, usize)]) -> Option<Vec<Vec3>> {
    if !is_valid_group(network, group) {
        return None;
    }
    let size = group.len();
    let mut matrix = [[0.0; 4]; 4];
    let mut rhs = [Vec3::zeros(); 4];
    for (a, &(i, j)) in group.iter().enumerate() {
        rhs[a] = -(network.u_jump(i, j) + network.v_jump(i, j));
        for (b, &(k, l)) in group.iter().enumerate() {
            if j == l {
                matrix[a][b] += network.u_stiffness().entry(i, k);
            }
            if i == k {
                matrix[a][b] += network.v_stiffness().entry(j, l);
            }
        }
    }
    let deltas = solve(&matrix, &rhs, size)?;
    Some(
        group
            .iter()
            .zip(deltas)
            .map(|(&(i, j), d)| network.point(i, j) + d)
            .collect(),
    )
}

/// Eq. 21 for one point, P̄ = P − (J^u + J^v)/(K_u[i,i] + K_v[j,j]): [`limit_targets`] of the
/// group `[(i, j)]` without its general solve. `None` for a node that is not interior. O(1).
pub(crate) fn limit_target(network: &Network, i: usize, j: usize) -> Option<Vec3> {
    if !network.is_interior(i, j) {
        return None;
    }
    let stiffness = network.u_stiffness().diagonal[i] + network.v_stiffness().diagonal[j];
    let target = network.point(i, j) - (network.u_jump(i, j) + network.v_jump(i, j)) / stiffness;
    (stiffness > 0.0 && target.iter().all(|c| c.is_finite())).then_some(target)
}

/// Gaussian elimination with partial pivoting on the leading `size` × `size` block, vector
/// right-hand sides; `None` when a pivot vanishes or the result is not finite.
pub(crate) fn solve(matrix: &[[f64; 4]; 4], rhs: &[Vec3; 4], size: usize) -> Option<Vec<Vec3>> {
    let mut a = *matrix;
    let mut b = *rhs;
    let scale = a
        .iter()
        .take(size)
        .flat_map(|row| row.iter().take(size))
        .fold(0.0f64, |m, x| m.max(x.abs()));
    for column in 0..size {
        let pivot = (column..size).max_by(|&p, &q| a[p][column].abs().total_cmp(&a[q][column].abs()))?;
        let magnitude = a[pivot][column].abs();
        if magnitude.is_nan() || magnitude <= 1e-14 * scale {
            return None;
        }
        a.swap(column, pivot);
        b.swap(column, pivot);
        for row in column + 1..size {
            let factor = a[row][column] / a[column][column];
            let pivot_row = a[column];
            for (x, p) in a[row][column..size].iter_mut().zip(&pivot_row[column..size]) {
                *x -= factor * p;
            }
            let pivot_rhs = b[column];
            b[row] -= pivot_rhs * factor;
        }
    }
    let mut x = vec![Vec3::zeros(); size];
    for row in (0..size).rev() {
        let mut sum = b[row];
        for k in row + 1..size {
            sum -= x[k] * a[row][k];
        }
        x[row] = sum / a[row][row];
    }
    x.iter().all(|p| p.iter().all(|c| c.is_finite())).then_some(x)
}
