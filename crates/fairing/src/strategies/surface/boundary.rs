//! Step 2.1 of Zhang–Cheng's automatic surface algorithm (§4.4): the four boundary curves are
//! faired first with the curve method (§3.3 automatic algorithm, [`StrainEnergy`]).

use curve_repr::Vec3;

use super::NodeMove;
use crate::strategies::{StrainEnergy, StrainEnergySettings};
use crate::{Constraints, Pipeline, Result};

/// The nodes (i, j) of the boundary curves of an (m+1) × (n+1) grid, each in order: u-lines
/// j = 0 and j = n (i = 0..m) when the grid is open in v, then v-lines i = 0 and i = m
/// (j = 0..n) when it is open in u. A boundary curve that runs along a closed direction is a
/// closed curve, which the curve method does not fair: it is left out, and so is a seam (a
/// closed direction has no boundary there).
pub(crate) fn boundary_curves(
    u_count: usize,
    v_count: usize,
    closed: (bool, bool),
) -> Vec<Vec<(usize, usize)>> {
    let along_u = |j: usize| (0..u_count).map(|i| (i, j)).collect::<Vec<_>>();
    let along_v = |i: usize| (0..v_count).map(|j| (i, j)).collect::<Vec<_>>();
    if closed.0 || closed.1 {
        // Closed in u: the boundary lines j = 0, n run along u and are closed curves, the
        // rows i = 0, m are the seam; likewise in v.
        return Vec::new();
    }
    vec![along_u(0), along_u(v_count - 1), along_v(0), along_v(u_count - 1)]
}

/// Fairs every boundary curve of the flat grid `points` (index i·v_count + j) in place with
/// the automatic curve algorithm (chord-length knots, restraining circles, relative energy
/// tolerance `tolerance`); `is_fixed` nodes and the corners (the curves' end points, which the
/// curve method never moves) stay put, and no point moves farther than `max_distance`.
/// A boundary curve with two equal consecutive points (a degenerate edge, a pole) is left
/// as it is. Returns the moves made and the steps taken. O(perimeter) per step.
pub(crate) fn fair_boundary(
    points: &mut [Vec3],
    u_count: usize,
    v_count: usize,
    closed: (bool, bool),
    tolerance: f64,
    max_distance: Option<f64>,
    is_fixed: impl Fn(usize, usize) -> bool,
) -> Result<(Vec<NodeMove>, usize)> {
    let mut moves = Vec::new();
    let mut steps = 0;
    for curve in boundary_curves(u_count, v_count, closed) {
        let line: Vec<Vec3> = curve.iter().map(|&(i, j)| points[i * v_count + j]).collect();
        // A boundary collapsed to a point in places (a pole, as the teapot's bottom row) has
        // no chord-length curve through it: it is left as it is.
        if line.windows(2).any(|w| w[0] == w[1]) {
            continue;
        }
        let fixed = curve
            .iter()
            .enumerate()
            .filter(|(_, &(i, j))| is_fixed(i, j))
            .map(|(k, _)| k);
        let mut constraints = Constraints::default().with_fixed(fixed);
        if let Some(distance) = max_distance {
            constraints = constraints.with_tolerance(distance);
        }
        let strategy = StrainEnergy::<3>::new(StrainEnergySettings::default().with_tolerance(tolerance));
        let result = Pipeline::new(strategy)
            .with_constraints(constraints)
            .with_trace(false)
            .run(line)?;
        steps += result.iterations;
        for (&(i, j), &p) in curve.iter().zip(&result.points) {
            let slot = &mut points[i * v_count + j];
            if *slot != p {
                *slot = p;
                moves.push(((i, j), p));
            }
        }
    }
    Ok((moves, steps))
}
