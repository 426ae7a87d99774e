//! The network of iso-parametric curves of a bicubic spline surface (Zhang–Cheng §4): the
//! natural cubic spline of every u-line j (P_{0,j}..P_{m,j} over u_0..u_m) and of every v-line i
//! (P_{i,0}..P_{i,n} over v_0..v_n), with their tangents M^u, M^v, third-derivative jumps and
//! strain energies kept up to date by local updates.
//!
//! These curves are exactly the knot lines of [`BicubicSplineSurface`](curve_repr::BicubicSplineSurface)
//! (its module docs: every u-line S(·, v_j) is the natural spline through row j), so z_ij
//! (Eq. 26), the objectives of Eq. 18, 22, 24 and the network strain energy are read here
//! without the twists, which only the thin-plate variant needs.
//!
//! Every u-line has the same knots, so the same linear map A_u takes its points to its
//! tangents (M^u_{·,j} = A_u P_{·,j}, Eq. 2 with free ends). Moving P_ij by δ therefore adds
//! δ·(A_u e_i)_k to M^u_{k,j}: the response A_u e_i is measured once per i (a unit move on a
//! zero [`HermiteSpline`] over the knots, which re-solves only the window whose change exceeds
//! 1e-17 relative, see curve-repr's `hermite::update`) and a move is then two short vector
//! updates, plus the segment energies in the response's window. A move costs O(window), a
//! constant (~30 knots per side for uniform knots, at most ~57).

use curve_repr::{HermiteSettings, HermiteSpline, Interpolant, Vec3, Vector};

use super::super::strain_energy::hermite_energy;
use crate::{Error, Result};

/// The response of one knot vector's natural splines to unit point moves, and the stiffness
/// J = K P read from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Stiffness {
    /// K_{i,i}, per knot (0 at the two ends, where there is no jump).
    pub diagonal: Vec<f64>,
    /// K_{i,i+1} = K_{i+1,i} (K is symmetric), per knot.
    pub upper: Vec<f64>,
    /// For each knot i: the first index lo and the values ∂M_k/∂P_i for k = lo, lo + 1, …
    /// (zero outside).
    response: Vec<(usize, Vec<f64>)>,
    /// The knot steps h_k = t_{k+1} − t_k.
    steps: Vec<f64>,
}

/// C''' on a Hermite segment: (6(M_0 + M_1) − 12(P_1 − P_0)/h)/h².
fn third(p0: Vec3, p1: Vec3, m0: Vec3, m1: Vec3, h: f64) -> Vec3 {
    ((m0 + m1) * 6.0 - (p1 - p0) * (12.0 / h)) / (h * h)
}

impl Stiffness {
    /// Measures the responses by moving one point at a time of the zero scalar natural
    /// spline over `knots` to 1 (the tangents are linear in the points, so the response is
    /// exact up to rounding), and K_{i,i}, K_{i,i+1} from the jumps next to it.
    /// O(len · window).
    pub fn new(knots: &[f64]) -> Result<Self> {
        let len = knots.len();
        let settings = HermiteSettings::<1>::new().with_parameters(knots.to_vec());
        let mut line = HermiteSpline::new(&vec![Vector::<1>::zeros(); len], &settings)?;
        let steps: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let mut diagonal = vec![0.0; len];
        let mut upper = vec![0.0; len];
        let mut response = Vec::with_capacity(len);
        for i in 0..len {
            line.move_points(&[(i, Vector::<1>::new(1.0))])?;
            let tangents: Vec<f64> = line.tangents().iter().map(|t| t[0]).collect();
            let lo = tangents.iter().position(|&t| t != 0.0).unwrap_or(i);
            let hi = tangents.iter().rposition(|&t| t != 0.0).unwrap_or(i);
            response.push((lo, tangents[lo..=hi.max(lo)].to_vec()));
            let point = |k: usize| Vec3::new(if k == i { 1.0 } else { 0.0 }, 0.0, 0.0);
            let tangent = |k: usize| Vec3::new(tangents[k], 0.0, 0.0);
            let jump = |k: usize| {
                third(point(k), point(k + 1), tangent(k), tangent(k + 1), steps[k])
                    - third(point(k - 1), point(k), tangent(k - 1), tangent(k), steps[k - 1])
            };
            if i >= 1 && i + 1 < len {
                diagonal[i] = jump(i)[0];
            }
            if i >= 2 {
                // K_{i−1,i} = ∂J_{i−1}/∂P_i.
                upper[i - 1] = jump(i - 1)[0];
            }
            line.move_points(&[(i, Vector::<1>::zeros())])?;
        }
        Ok(Self {
            diagonal,
            upper,
            response,
            steps,
        })
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
    /// P_ij at i·(n+1) + j.
    points: Vec<Vec3>,
    /// M^u_ij at i·(n+1) + j.
    u_tangents: Vec<Vec3>,
    /// M^v_ij at i·(n+1) + j.
    v_tangents: Vec<Vec3>,
    /// Energy of u-line segment (i, j) (from u_i to u_{i+1}) at i·(n+1) + j.
    u_segment_energy: Vec<f64>,
    /// Energy of v-line segment (i, j) (from v_j to v_{j+1}) at i·(n+1) + j.
    v_segment_energy: Vec<f64>,
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
        let mut u_tangents = vec![Vec3::zeros(); points.len()];
        for j in 0..v_count {
            let line: Vec<Vec3> = points.iter().skip(j).step_by(v_count).copied().collect();
            let spline = HermiteSpline::new(&line, &u_settings)?;
            for (i, t) in spline.tangents().iter().enumerate() {
                u_tangents[i * v_count + j] = *t;
            }
        }
        let mut v_tangents = Vec::with_capacity(points.len());
        for line in points.chunks(v_count) {
            v_tangents.extend_from_slice(HermiteSpline::new(line, &v_settings)?.tangents());
        }
        let mut network = Self {
            u_count,
            v_count,
            u_knots: u_knots.to_vec(),
            v_knots: v_knots.to_vec(),
            points: points.to_vec(),
            u_tangents,
            v_tangents,
            u_segment_energy: vec![0.0; points.len()],
            v_segment_energy: vec![0.0; points.len()],
            energy: 0.0,
            u_stiffness: Stiffness::new(u_knots)?,
            v_stiffness: Stiffness::new(v_knots)?,
        };
        for i in 0..u_count {
            for j in 0..v_count {
                if i + 1 < u_count {
                    network.u_segment_energy[i * v_count + j] = network.u_segment(i, j);
                }
                if j + 1 < v_count {
                    network.v_segment_energy[i * v_count + j] = network.v_segment(i, j);
                }
            }
        }
        network.resum_energy();
        Ok(network)
    }

    fn u_segment(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (i * self.v_count + j, (i + 1) * self.v_count + j);
        hermite_energy(
            self.points[a],
            self.points[b],
            self.u_tangents[a],
            self.u_tangents[b],
            self.u_stiffness.steps[i],
        )
    }

    fn v_segment(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (i * self.v_count + j, i * self.v_count + j + 1);
        hermite_energy(
            self.points[a],
            self.points[b],
            self.v_tangents[a],
            self.v_tangents[b],
            self.v_stiffness.steps[j],
        )
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
        self.points[i * self.v_count + j]
    }

    /// M^u_ij = ∂S/∂u(u_i, v_j).
    pub fn u_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.u_tangents[i * self.v_count + j]
    }

    /// M^v_ij = ∂S/∂v(u_i, v_j).
    pub fn v_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.v_tangents[i * self.v_count + j]
    }

    /// ∂³S/∂u³(u_i+, v_j) − ∂³S/∂u³(u_i−, v_j) at an interior node.
    pub fn u_jump(&self, i: usize, j: usize) -> Vec3 {
        let (p, m, h) = (
            |k: usize| self.point(k, j),
            |k: usize| self.u_tangent(k, j),
            &self.u_stiffness.steps,
        );
        third(p(i), p(i + 1), m(i), m(i + 1), h[i]) - third(p(i - 1), p(i), m(i - 1), m(i), h[i - 1])
    }

    /// ∂³S/∂v³(u_i, v_j+) − ∂³S/∂v³(u_i, v_j−) at an interior node.
    pub fn v_jump(&self, i: usize, j: usize) -> Vec3 {
        let (p, m, h) = (
            |k: usize| self.point(i, k),
            |k: usize| self.v_tangent(i, k),
            &self.v_stiffness.steps,
        );
        third(p(j), p(j + 1), m(j), m(j + 1), h[j]) - third(p(j - 1), p(j), m(j - 1), m(j), h[j - 1])
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

    /// Moves points `((i, j), position)` one after another, updating the tangents of u-line j
    /// and v-line i by the measured responses and the energy from the segments in their
    /// windows. O(moves · window). Fails with [`Error::NonFiniteMove`] (flat index) on a
    /// position or an energy that is not finite, leaving that move undone, or
    /// [`Error::BadConstraint`] on a node outside the grid.
    pub fn move_points(&mut self, moves: &[((usize, usize), Vec3)]) -> Result<()> {
        for &((i, j), position) in moves {
            if i >= self.u_count || j >= self.v_count {
                return Err(Error::BadConstraint {
                    reason: format!(
                        "node ({i}, {j}) is outside the {} × {} grid",
                        self.u_count, self.v_count
                    ),
                });
            }
            let index = i * self.v_count + j;
            if position.iter().any(|c| !c.is_finite()) {
                return Err(Error::NonFiniteMove { index });
            }
            let old = self.points[index];
            let energy = self.energy;
            self.shift(i, j, position - old);
            if !self.energy.is_finite() {
                self.shift(i, j, old - position);
                self.points[index] = old;
                self.energy = energy;
                self.resum_energy();
                return Err(Error::NonFiniteMove { index });
            }
        }
        Ok(())
    }

    /// Adds `delta` to P_ij and its responses to the tangents; refreshes the energies.
    fn shift(&mut self, i: usize, j: usize, delta: Vec3) {
        let vc = self.v_count;
        self.points[i * vc + j] += delta;
        let (u_lo, u_values) = &self.u_stiffness.response[i];
        for (offset, &r) in u_values.iter().enumerate() {
            self.u_tangents[(u_lo + offset) * vc + j] += delta * r;
        }
        let (v_lo, v_values) = &self.v_stiffness.response[j];
        for (offset, &r) in v_values.iter().enumerate() {
            self.v_tangents[i * vc + v_lo + offset] += delta * r;
        }
        // Segments touching a changed tangent or the moved point.
        let (u_lo, u_hi) = (
            (*u_lo).min(i).saturating_sub(1),
            (u_lo + u_values.len()).max(i + 1).min(self.u_count - 1),
        );
        for k in u_lo..u_hi {
            let e = self.u_segment(k, j);
            let slot = &mut self.u_segment_energy[k * vc + j];
            self.energy += e - *slot;
            *slot = e;
        }
        let (v_lo, v_hi) = (
            (*v_lo).min(j).saturating_sub(1),
            (v_lo + v_values.len()).max(j + 1).min(self.v_count - 1),
        );
        for k in v_lo..v_hi {
            let e = self.v_segment(i, k);
            let slot = &mut self.v_segment_energy[i * vc + k];
            self.energy += e - *slot;
            *slot = e;
        }
    }

    /// Recomputes the energy as the sum of the stored segment energies (drops the rounding
    /// that the local updates gather). O(m·n).
    pub fn resum_energy(&mut self) {
        self.energy = self.u_segment_energy.iter().chain(&self.v_segment_energy).sum();
    }
}
