//! Local rebuild after moving data points (Zhang–Cheng §4.1–4.3).
//!
//! Moving P_ij changes the natural spline of u-line j and of v-line i only: M^u changes on
//! row j (all of it, by an amount that decays geometrically away from i) and M^v on column i.
//! Those two lines are solved again (O(m + n), the same solve as a full build, so the
//! tangents are a full rebuild's bit for bit). The paper then recomputes "all the twist
//! vectors"; here they are updated by linearity instead: T_{·,k} = A_u M^v_{·,k} (A_u: values
//! at u_0..u_m ↦ natural-spline tangents, the same for every u-line), and M^v changed only at
//! u-index i, so
//!
//! T_{l,k} += w_l · (M^v_{i,k}(new) − M^v_{i,k}(old)),  w = A_u e_i,
//!
//! one scalar tridiagonal solve for w and a rank-one update. Both factors decay by about 0.27
//! a knot away from (i, j); entries below [`RESPONSE_TRIM`] of their largest are left out, so
//! the twists change only in a window of w_u × w_v nodes round the moved point (w ≈ 45 for
//! even knots, whatever the grid's size): the local rebuild, equal to a full rebuild to ~1e-13
//! of the twists' size. A seam node's stored repeat is one more moved column (the periodic
//! solve does not read a repeated value, so its w is zero and the sum is the periodic line's).

use super::build::check_finite_result;
use super::BicubicSplineSurface;
use crate::{Error, Result, Vec3};

/// Factors of a twist update are kept where they exceed this fraction of their largest: the
/// far tail changes a twist by less than 1e-13 of the move's own effect.
const RESPONSE_TRIM: f64 = 1e-13;

/// Above this many distinct moved grid lines i, recomputing every twist ((n+1) tridiagonal
/// solves along u) is cheaper than one windowed rank-one update per line.
const RANK_UPDATE_LIMIT: usize = 8;

/// Which array an undo entry restores.
#[derive(Clone, Copy)]
enum Slot {
    UTangent,
    VTangent,
    Twist,
}

impl BicubicSplineSurface {
    /// Moves data points `((i, j), new position)` and rebuilds the surface through them, keeping
    /// the knots (the paper keeps the knots while it fairs; so do later moves).
    ///
    /// Equal to a full rebuild with the same knots: the tangents bit for bit, the twists to
    /// ~1e-13 of their size (module docs). Cost, with r distinct rows j and c distinct columns
    /// i among the moves (a seam node's repeat counts): O(r·m + c·n) for the tangents (only
    /// the u-lines j and v-lines i are solved again) and, when c ≤ 8, O(c·(m + w_u·w_v)) for
    /// the twists (a unit solve and a windowed rank-one update per column, w the decay
    /// window, independent of the grid's size), else the paper's recomputation of every twist,
    /// O(m·n). The data needed by the indicator ([`z`](Self::z)) and the network energy
    /// ([`network_strain_energy`](Self::network_strain_energy)) are the points and tangents
    /// only.
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
        let mut undo = Vec::new();
        match self.rebuild_lines(moves, &mut undo) {
            Ok(()) => Ok(()),
            Err(error) => {
                for &(slot, k, old) in undo.iter().rev() {
                    match slot {
                        Slot::UTangent => self.u_tangents[k] = old,
                        Slot::VTangent => self.v_tangents[k] = old,
                        Slot::Twist => self.twists[k] = old,
                    }
                }
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

    /// Re-solves the tangents of the moved lines and updates the twists from `self.points`
    /// (already moved), recording every overwritten value in `undo`; fails on a result that is
    /// not finite (the caller then restores `undo`).
    fn rebuild_lines(
        &mut self,
        moves: &[((usize, usize), Vec3)],
        undo: &mut Vec<(Slot, usize, Vec3)>,
    ) -> Result<()> {
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

        if columns.len() <= RANK_UPDATE_LIMIT {
            // T += Σ_i (A_u e_i) (ΔM^v_{i,·})ᵀ over the significant entries of both factors.
            for (&i, line) in columns.iter().zip(&v_lines) {
                let weights = significant(&self.u_system.tangents(&unit(self.u_count, i))?);
                let old = &self.v_tangents[i * vc..(i + 1) * vc];
                let change: Vec<Vec3> = line.iter().zip(old).map(|(new, old)| new - old).collect();
                let largest = change.iter().fold(0.0f64, |m, c| m.max(c.norm()));
                let change: Vec<(usize, Vec3)> = change
                    .into_iter()
                    .enumerate()
                    .filter(|(_, c)| c.norm() > RESPONSE_TRIM * largest)
                    .collect();
                for &(l, w) in &weights {
                    for &(k, delta) in &change {
                        let index = l * vc + k;
                        undo.push((Slot::Twist, index, self.twists[index]));
                        self.twists[index] += delta * w;
                        finite("twist", index, &self.twists[index])?;
                    }
                }
            }
        } else {
            let mut v_tangents = self.v_tangents.clone();
            for (&i, line) in columns.iter().zip(&v_lines) {
                v_tangents[i * vc..(i + 1) * vc].copy_from_slice(line);
            }
            let twists = self.all_twists(&v_tangents)?;
            check_finite_result("twist", &twists)?;
            for (index, (slot, new)) in self.twists.iter_mut().zip(twists).enumerate() {
                undo.push((Slot::Twist, index, *slot));
                *slot = new;
            }
        }
        for (&j, line) in rows.iter().zip(&u_lines) {
            for (l, &value) in line.iter().enumerate() {
                let index = l * vc + j;
                undo.push((Slot::UTangent, index, self.u_tangents[index]));
                self.u_tangents[index] = value;
            }
        }
        for (&i, line) in columns.iter().zip(&v_lines) {
            for (l, &value) in line.iter().enumerate() {
                let index = i * vc + l;
                undo.push((Slot::VTangent, index, self.v_tangents[index]));
                self.v_tangents[index] = value;
            }
        }
        Ok(())
    }
}

/// e_i of length `count`.
fn unit(count: usize, i: usize) -> Vec<f64> {
    let mut unit = vec![0.0; count];
    unit[i] = 1.0;
    unit
}

/// The entries of a unit response above [`RESPONSE_TRIM`] of its largest, as (index, value).
fn significant(response: &[f64]) -> Vec<(usize, f64)> {
    let largest = response.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    response
        .iter()
        .enumerate()
        .filter(|(_, r)| r.abs() > RESPONSE_TRIM * largest)
        .map(|(l, &r)| (l, r))
        .collect()
}

/// [`Error::NonFinite`] if a computed value overflowed.
fn finite(what: &'static str, index: usize, value: &Vec3) -> Result<()> {
    if value.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite { what, index })
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

    mod properties {
        use super::*;
        use proptest::prelude::*;

        /// A grid of random heights, closed along u and/or v (the last line repeating the
        /// first), and its surface.
        fn random_surface(
            rows: usize,
            columns: usize,
            heights: &[f64],
            closed: (bool, bool),
        ) -> BicubicSplineSurface {
            let grid: Vec<Vec<Vec3>> = (0..rows)
                .map(|i| {
                    (0..columns)
                        .map(|j| {
                            let a = if closed.0 && i == rows - 1 { 0 } else { i };
                            let b = if closed.1 && j == columns - 1 { 0 } else { j };
                            let h = heights[(a * 11 + b) % heights.len()];
                            Vec3::new(a as f64 * (1.0 + 0.05 * b as f64), b as f64 + 0.1 * h, h)
                        })
                        .collect()
                })
                .collect();
            let settings = BicubicSurfaceSettings::default()
                .with_closed_u(closed.0)
                .with_closed_v(closed.1);
            BicubicSplineSurface::with_settings(&grid, &settings).unwrap()
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(48))]

            /// The local rebuild (two unit responses and a windowed rank-one twist update per
            /// move) equals a full rebuild over the same knots to 1e-12 of the values' size
            /// after random moves, open or closed, seams included.
            #[test]
            fn local_moves_equal_a_full_rebuild(
                rows in 4usize..40,
                columns in 4usize..40,
                heights in proptest::collection::vec(-1.0f64..1.0, 64),
                moves in proptest::collection::vec((0usize..1000, 0usize..1000, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 1..16),
                closed_u in any::<bool>(),
                closed_v in any::<bool>(),
            ) {
                let mut surface = random_surface(rows, columns, &heights, (closed_u, closed_v));
                let moves: Vec<_> = moves
                    .iter()
                    .map(|&(a, b, x, y, z)| {
                        let (i, j) = (a % rows, b % columns);
                        ((i, j), surface.point(i, j).unwrap() + Vec3::new(x, y, z))
                    })
                    .collect();
                surface.move_points(&moves).unwrap();
                let settings = BicubicSurfaceSettings::default()
                    .with_u_knots(surface.u_knots().to_vec())
                    .with_v_knots(surface.v_knots().to_vec())
                    .with_closed_u(closed_u)
                    .with_closed_v(closed_v);
                let full = BicubicSplineSurface::with_settings(&surface.grid(), &settings).unwrap();
                let size = |values: &[Vec3]| values.iter().fold(1.0f64, |m, v| m.max(v.norm()));
                for (local, rebuilt) in [
                    (surface.u_tangents(), full.u_tangents()),
                    (surface.v_tangents(), full.v_tangents()),
                    (surface.twists(), full.twists()),
                ] {
                    let difference = max_difference(local, rebuilt);
                    prop_assert!(difference <= 1e-12 * size(rebuilt), "{} against {}", difference, size(rebuilt));
                }
            }
        }
    }
}
