//! The network of iso-parametric curves of a bicubic spline surface (Zhang–Cheng §4): the
//! natural cubic spline of every u-line j (P_{0,j}..P_{m,j} over u_0..u_m) and of every v-line i
//! (P_{i,0}..P_{i,n} over v_0..v_n), with their tangents M^u, M^v, third-derivative jumps and
//! strain energies kept up to date by local updates.
//!
//! These curves are exactly the knot lines of [`BicubicSplineSurface`] (its module docs: every
//! u-line S(·, v_j) is the natural spline through row j), so z_ij (Eq. 26), the objectives of
//! Eq. 18, 22, 24 and the network strain energy are read here without the twists, which only
//! the thin-plate variant needs. A move of P_ij re-solves u-line j and v-line i through
//! [`Interpolant::move_points`] (a window of knots independent of the grid size) and updates
//! the energy from the segments in that window: a move costs O(1) in the grid size.

use curve_repr::{HermiteSettings, HermiteSpline, Interpolant, Vec3, Vector};

use super::super::strain_energy::{jump, segment_energy, WINDOW};
use crate::Result;

/// K_{i,i} and K_{i,i+1} of the natural spline's jump map J = K P along one knot vector (the
/// tangents re-solved): J_i changes by K_{i,i'} per unit move of P_{i'}. Index 0 and the last
/// are unused (no jump at the ends).
#[derive(Clone, Debug, PartialEq)]
pub struct Stiffness {
    /// K_{i,i}, per knot.
    pub diagonal: Vec<f64>,
    /// K_{i,i+1} = K_{i+1,i} (K is symmetric), per knot.
    pub upper: Vec<f64>,
}

impl Stiffness {
    /// Measures K by moving one point at a time of the zero scalar spline over `knots` to 1
    /// and reading the jumps next to it (J is linear in P, so the response is exact up to
    /// rounding). O(len · window).
    pub fn new(knots: &[f64]) -> Result<Self> {
        let len = knots.len();
        let settings = HermiteSettings::<1>::new().with_parameters(knots.to_vec());
        let mut line = HermiteSpline::new(&vec![Vector::<1>::zeros(); len], &settings)?;
        let mut diagonal = vec![0.0; len];
        let mut upper = vec![0.0; len];
        for i in 1..len.saturating_sub(1) {
            line.move_points(&[(i, Vector::<1>::new(1.0))])?;
            diagonal[i] = jump(&line, i)[0];
            if i + 2 < len {
                upper[i] = jump(&line, i + 1)[0];
            }
            line.move_points(&[(i, Vector::<1>::zeros())])?;
        }
        Ok(Self { diagonal, upper })
    }

    /// K_{a,b} for |a − b| ≤ 1, else 0 (the far entries are not needed: the groups of
    /// Eq. 23 and 25 are adjacent).
    pub fn entry(&self, a: usize, b: usize) -> f64 {
        match a.abs_diff(b) {
            0 => self.diagonal.get(a).copied().unwrap_or(0.0),
            1 => self.upper.get(a.min(b)).copied().unwrap_or(0.0),
            _ => 0.0,
        }
    }
}

/// The iso-parametric spline network of a grid (see the module docs).
#[derive(Clone, Debug)]
pub struct Network {
    /// m + 1.
    u_count: usize,
    /// n + 1.
    v_count: usize,
    u_knots: Vec<f64>,
    v_knots: Vec<f64>,
    /// u-line j: the natural spline through P_{0,j}..P_{m,j}.
    u_lines: Vec<HermiteSpline<3>>,
    /// v-line i: the natural spline through P_{i,0}..P_{i,n}.
    v_lines: Vec<HermiteSpline<3>>,
    u_segment_energy: Vec<Vec<f64>>,
    v_segment_energy: Vec<Vec<f64>>,
    energy: f64,
    u_stiffness: Stiffness,
    v_stiffness: Stiffness,
}

impl Network {
    /// The network of the flat grid `points[i·v_count + j]` = P_ij over the given knots
    /// (one per grid line). O(m·n + (m + n) · window).
    pub fn new(points: &[Vec3], u_knots: &[f64], v_knots: &[f64]) -> Result<Self> {
        let (u_count, v_count) = (u_knots.len(), v_knots.len());
        if points.len() != u_count * v_count {
            return Err(curve_repr::Error::LengthMismatch {
                what: "grid points",
                expected: u_count * v_count,
                got: points.len(),
            }
            .into());
        }
        let u_settings = HermiteSettings::<3>::new().with_parameters(u_knots.to_vec());
        let v_settings = HermiteSettings::<3>::new().with_parameters(v_knots.to_vec());
        let mut u_lines = Vec::with_capacity(v_count);
        for j in 0..v_count {
            let line: Vec<Vec3> = points.iter().skip(j).step_by(v_count).copied().collect();
            u_lines.push(HermiteSpline::new(&line, &u_settings)?);
        }
        let mut v_lines = Vec::with_capacity(u_count);
        for line in points.chunks(v_count) {
            v_lines.push(HermiteSpline::new(line, &v_settings)?);
        }
        let u_segment_energy: Vec<Vec<f64>> = u_lines.iter().map(HermiteSpline::segment_energies).collect();
        let v_segment_energy: Vec<Vec<f64>> = v_lines.iter().map(HermiteSpline::segment_energies).collect();
        let energy = u_segment_energy.iter().chain(&v_segment_energy).flatten().sum();
        Ok(Self {
            u_count,
            v_count,
            u_knots: u_knots.to_vec(),
            v_knots: v_knots.to_vec(),
            u_lines,
            v_lines,
            u_segment_energy,
            v_segment_energy,
            energy,
            u_stiffness: Stiffness::new(u_knots)?,
            v_stiffness: Stiffness::new(v_knots)?,
        })
    }

    /// (m + 1, n + 1).
    pub fn shape(&self) -> (usize, usize) {
        (self.u_count, self.v_count)
    }

    /// The knots u_0..u_m.
    pub fn u_knots(&self) -> &[f64] {
        &self.u_knots
    }

    /// The knots v_0..v_n.
    pub fn v_knots(&self) -> &[f64] {
        &self.v_knots
    }

    /// P_ij (callers keep i, j inside the grid).
    pub fn point(&self, i: usize, j: usize) -> Vec3 {
        self.u_lines[j].points()[i]
    }

    /// M^u_ij = ∂S/∂u(u_i, v_j).
    pub fn u_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.u_lines[j].tangents()[i]
    }

    /// M^v_ij = ∂S/∂v(u_i, v_j).
    pub fn v_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.v_lines[i].tangents()[j]
    }

    /// All points, flat (index i·(n+1) + j). O(m·n).
    pub fn points(&self) -> Vec<Vec3> {
        self.v_lines.iter().flat_map(|line| line.points().iter().copied()).collect()
    }

    /// ∂³S/∂u³(u_i+, v_j) − ∂³S/∂u³(u_i−, v_j) at an interior node.
    pub fn u_jump(&self, i: usize, j: usize) -> Vec3 {
        jump(&self.u_lines[j], i)
    }

    /// ∂³S/∂v³(u_i, v_j+) − ∂³S/∂v³(u_i, v_j−) at an interior node.
    pub fn v_jump(&self, i: usize, j: usize) -> Vec3 {
        jump(&self.v_lines[i], j)
    }

    /// z_ij = |u jump| + |v jump| (Eq. 26, corrected in papers/README.md), interior nodes.
    pub fn z(&self, i: usize, j: usize) -> f64 {
        self.u_jump(i, j).norm() + self.v_jump(i, j).norm()
    }

    /// The network strain energy Σ_j ∫|S_uu(u, v_j)|² du + Σ_i ∫|S_vv(u_i, v)|² dv, kept up to
    /// date by [`move_points`](Self::move_points).
    pub fn energy(&self) -> f64 {
        self.energy
    }

    /// The stiffness of the u-lines (shared by every u-line: same knots).
    pub fn u_stiffness(&self) -> &Stiffness {
        &self.u_stiffness
    }

    /// The stiffness of the v-lines.
    pub fn v_stiffness(&self) -> &Stiffness {
        &self.v_stiffness
    }

    /// The u-line j.
    pub fn u_line(&self, j: usize) -> &HermiteSpline<3> {
        &self.u_lines[j]
    }

    /// The v-line i.
    pub fn v_line(&self, i: usize) -> &HermiteSpline<3> {
        &self.v_lines[i]
    }

    /// Moves points `((i, j), position)`, re-solving the u-lines j and v-lines i they lie on
    /// (windowed), and updates the energy. O(moves · window).
    pub fn move_points(&mut self, moves: &[((usize, usize), Vec3)]) -> Result<()> {
        let mut rows: Vec<usize> = moves.iter().map(|m| m.0 .1).collect();
        rows.sort_unstable();
        rows.dedup();
        let mut columns: Vec<usize> = moves.iter().map(|m| m.0 .0).collect();
        columns.sort_unstable();
        columns.dedup();
        for &j in &rows {
            let line_moves: Vec<(usize, Vec3)> = moves.iter().filter(|m| m.0 .1 == j).map(|m| (m.0 .0, m.1)).collect();
            self.u_lines[j].move_points(&line_moves)?;
            let (lo, hi) = window(&line_moves, self.u_count);
            for s in lo..hi {
                let e = segment_energy(&self.u_lines[j], s);
                self.energy += e - self.u_segment_energy[j][s];
                self.u_segment_energy[j][s] = e;
            }
        }
        for &i in &columns {
            let line_moves: Vec<(usize, Vec3)> = moves.iter().filter(|m| m.0 .0 == i).map(|m| (m.0 .1, m.1)).collect();
            self.v_lines[i].move_points(&line_moves)?;
            let (lo, hi) = window(&line_moves, self.v_count);
            for s in lo..hi {
                let e = segment_energy(&self.v_lines[i], s);
                self.energy += e - self.v_segment_energy[i][s];
                self.v_segment_energy[i][s] = e;
            }
        }
        Ok(())
    }

    /// Recomputes the energy from every segment (drops the rounding the local updates gather).
    /// O(m·n).
    pub fn resum_energy(&mut self) {
        self.energy = self.u_segment_energy.iter().chain(&self.v_segment_energy).flatten().sum();
    }
}

/// The segments [lo, hi) whose energy a move of these line indices can change.
fn window(moves: &[(usize, Vec3)], count: usize) -> (usize, usize) {
    let lo = moves.iter().map(|m| m.0).min().unwrap_or(0).saturating_sub(WINDOW);
    let hi = (moves.iter().map(|m| m.0).max().unwrap_or(0) + WINDOW).min(count.saturating_sub(1));
    (lo, hi)
}
