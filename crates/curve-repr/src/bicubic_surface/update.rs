//! Local rebuild after moving data points (Zhang–Cheng §4.1–4.3).
//!
//! Moving P_ij changes the natural spline of u-line j and of v-line i only: M^u changes on
//! row j (all of it, by an amount that decays geometrically away from i) and M^v on column i.
//! The paper then recomputes "all the twist vectors". Here the twists are updated exactly by
//! linearity instead: T_{·,k} = A_u M^v_{·,k} (A_u: values at u_0..u_m ↦ natural-spline
//! tangents), and M^v changed only at u-index i, so
//!
//! T_{l,k} += w_l · (M^v_{i,k}(new) − M^v_{i,k}(old)),  w = A_u e_i,
//!
//! one scalar tridiagonal solve for w and one rank-one pass over the twists. Every twist does
//! change (w has no zero entries), so a twist update cannot be cheaper than O(m·n) without
//! truncating the geometric decay; it is the pass over memory, with no solves.

use super::build::{check_finite_result, scatter_u_line};
use super::BicubicSplineSurface;
use crate::{Error, Result, Vec3};

/// Above this many distinct moved grid lines i, recomputing every twist ((n+1) tridiagonal
/// solves along u) is cheaper than one rank-one pass per line.
const RANK_UPDATE_LIMIT: usize = 8;

impl BicubicSplineSurface {
    /// Moves data points `((i, j), new position)` and rebuilds the surface through them, keeping
    /// the knots (the paper keeps the knots while it fairs; so do later moves).
    ///
    /// Equal to a full rebuild with the same knots, up to round-off. Cost, with r distinct
    /// rows j and c distinct columns i among the moves: O(r·m + c·n) for the tangents M^u, M^v
    /// (only the u-lines j and v-lines i are solved again), and O(m·n) for the twists: one
    /// rank-one pass per moved column i when c ≤ 8 (no solves), else the paper's recomputation
    /// of every twist. The data needed by the indicator ([`z`](Self::z)) and the network
    /// energy ([`network_strain_energy`](Self::network_strain_energy)) are the points and
    /// tangents only.
    ///
    /// Fails, leaving the surface unchanged, with [`Error::IndexOutOfRange`] for a node outside
    /// the grid, [`Error::NonFinite`] for a non-finite position (index into `moves`) or a
    /// tangent or twist that overflows. A node moved twice takes its last position.
    pub fn move_points(&mut self, moves: &[((usize, usize), Vec3)]) -> Result<()> {
        for (index, &((i, j), position)) in moves.iter().enumerate() {
            if i >= self.u_count {
                return Err(Error::IndexOutOfRange {
                    what: "grid lines along u (index i)",
                    index: i,
                    len: self.u_count,
                });
            }
            if j >= self.v_count {
                return Err(Error::IndexOutOfRange {
                    what: "grid lines along v (index j)",
                    index: j,
                    len: self.v_count,
                });
            }
            if position.iter().any(|c| !c.is_finite()) {
                return Err(Error::NonFinite {
                    what: "moved point",
                    index,
                });
            }
        }
        if moves.is_empty() {
            return Ok(());
        }
        let moves = self.with_seam_copies(moves);
        let moves = &moves[..];
        let vc = self.v_count;
        let mut previous = Vec::with_capacity(moves.len());
        for &((i, j), position) in moves {
            let k = i * vc + j;
            previous.push((k, self.points[k]));
            self.points[k] = position;
        }
        match self.rebuild_lines(moves) {
            Ok(()) => Ok(()),
            Err(error) => {
                for &(k, old) in previous.iter().rev() {
                    self.points[k] = old;
                }
                Err(error)
            }
        }
    }

    /// The moves with every seam node's stored repeat added (after it, so that a node moved
    /// twice still takes its last position, repeat included).
    fn with_seam_copies(&self, moves: &[((usize, usize), Vec3)]) -> Vec<((usize, usize), Vec3)> {
        let (closed_u, closed_v) = (self.closed_u(), self.closed_v());
        if !closed_u && !closed_v {
            return moves.to_vec();
        }
        let (last_i, last_j) = (self.u_count - 1, self.v_count - 1);
        let copies = |k: usize, last: usize, closed: bool| -> Vec<usize> {
            if closed && (k == 0 || k == last) {
                vec![0, last]
            } else {
                vec![k]
            }
        };
        let mut all = Vec::with_capacity(moves.len());
        for &((i, j), position) in moves {
            for a in copies(i, last_i, closed_u) {
                for b in copies(j, last_j, closed_v) {
                    all.push(((a, b), position));
                }
            }
        }
        all
    }

    /// Recomputes the tangents of the moved lines and the twists from `self.points` (already
    /// moved); commits nothing unless everything succeeds.
    fn rebuild_lines(&mut self, moves: &[((usize, usize), Vec3)]) -> Result<()> {
        let vc = self.v_count;
        let mut rows: Vec<usize> = moves.iter().map(|&((_, j), _)| j).collect();
        rows.sort_unstable();
        rows.dedup();
        let mut columns: Vec<usize> = moves.iter().map(|&((i, _), _)| i).collect();
        columns.sort_unstable();
        columns.dedup();

        let mut u_lines = Vec::with_capacity(rows.len());
        for &j in &rows {
            let line = self.solve_along_u(&self.points, j)?;
            check_finite_result("u tangent", &line)?;
            u_lines.push(line);
        }
        let mut v_lines = Vec::with_capacity(columns.len());
        for &i in &columns {
            let line = self.solve_along_v(&self.points, i)?;
            check_finite_result("v tangent", &line)?;
            v_lines.push(line);
        }

        let twists = if columns.len() <= RANK_UPDATE_LIMIT {
            // T += Σ_i (A_u e_i) (ΔM^v_{i,·})ᵀ.
            let mut updates = Vec::with_capacity(columns.len());
            for (&i, line) in columns.iter().zip(&v_lines) {
                let mut unit = vec![0.0; self.u_count];
                unit[i] = 1.0;
                let response = self.u_system.tangents(&unit)?;
                let old = &self.v_tangents[i * vc..(i + 1) * vc];
                let change: Vec<Vec3> = line.iter().zip(old).map(|(new, old)| new - old).collect();
                updates.push((response, change));
            }
            let mut twists = self.twists.clone();
            for (l, twist_line) in twists.chunks_mut(vc).enumerate() {
                for (response, change) in &updates {
                    let weight = response[l];
                    for (twist, delta) in twist_line.iter_mut().zip(change) {
                        *twist += delta * weight;
                    }
                }
            }
            twists
        } else {
            let mut v_tangents = self.v_tangents.clone();
            for (&i, line) in columns.iter().zip(&v_lines) {
                v_tangents[i * vc..(i + 1) * vc].copy_from_slice(line);
            }
            self.all_twists(&v_tangents)?
        };
        check_finite_result("twist", &twists)?;

        for (&j, line) in rows.iter().zip(&u_lines) {
            scatter_u_line(&mut self.u_tangents, vc, j, line);
        }
        for (&i, line) in columns.iter().zip(&v_lines) {
            self.v_tangents[i * vc..(i + 1) * vc].copy_from_slice(line);
        }
        self.twists = twists;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BicubicSurfaceSettings;

    fn grid(u_count: usize, v_count: usize) -> Vec<Vec<Vec3>> {
        (0..u_count)
            .map(|i| {
                (0..v_count)
                    .map(|j| {
                        let (x, y) = (i as f64 + 0.1 * (j as f64).sin(), j as f64 * 0.7);
                        Vec3::new(x, y, (0.9 * x).sin() * (0.4 * y + 0.3 * x).cos())
                    })
                    .collect()
            })
            .collect()
    }

    fn rebuilt(surface: &BicubicSplineSurface) -> BicubicSplineSurface {
        let settings = BicubicSurfaceSettings::default()
            .with_u_knots(surface.u_knots().to_vec())
            .with_v_knots(surface.v_knots().to_vec());
        BicubicSplineSurface::with_settings(&surface.grid(), &settings).unwrap()
    }

    fn max_difference(a: &[Vec3], b: &[Vec3]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y).norm()).fold(0.0, f64::max)
    }

    #[test]
    fn both_twist_paths_equal_a_full_rebuild() {
        for count in [1, 3, 12] {
            let mut surface = BicubicSplineSurface::new(&grid(11, 9)).unwrap();
            let moves: Vec<_> = (0..count)
                .map(|k| {
                    (
                        ((k * 7) % 11, (k * 5 + 2) % 9),
                        Vec3::new(0.3 * k as f64, -1.0, 2.0),
                    )
                })
                .collect();
            surface.move_points(&moves).unwrap();
            let full = rebuilt(&surface);
            assert!(max_difference(surface.u_tangents(), full.u_tangents()) < 1e-12);
            assert!(max_difference(surface.v_tangents(), full.v_tangents()) < 1e-12);
            assert!(
                max_difference(surface.twists(), full.twists()) < 1e-12,
                "{count} moves"
            );
        }
    }

    #[test]
    fn bad_moves_leave_the_surface_unchanged() {
        let original = BicubicSplineSurface::new(&grid(5, 4)).unwrap();
        let mut surface = original.clone();
        let good = ((1, 1), Vec3::new(0.0, 0.0, 1.0));
        assert!(matches!(
            surface.move_points(&[good, ((5, 0), Vec3::zeros())]),
            Err(Error::IndexOutOfRange { index: 5, .. })
        ));
        assert!(matches!(
            surface.move_points(&[good, ((0, 4), Vec3::zeros())]),
            Err(Error::IndexOutOfRange { index: 4, .. })
        ));
        assert!(matches!(
            surface.move_points(&[good, ((0, 0), Vec3::new(f64::NAN, 0.0, 0.0))]),
            Err(Error::NonFinite { index: 1, .. })
        ));
        // Finite but so large that the tangents overflow.
        assert!(matches!(
            surface.move_points(&[((2, 2), Vec3::new(f64::MAX, -f64::MAX, 0.0))]),
            Err(Error::NonFinite { .. })
        ));
        assert_eq!(surface, original);
    }
}
