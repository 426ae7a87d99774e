//! The network of iso-parametric curves of a bicubic spline surface (Zhang–Cheng §4): the
//! cubic spline of every u-line j (P_{0,j}..P_{m,j} over u_0..u_m) and of every v-line i
//! (P_{i,0}..P_{i,n} over v_0..v_n), natural at open ends and periodic along a closed
//! direction, with their tangents M^u, M^v, third-derivative jumps and strain energy kept up
//! to date by local updates.
//!
//! These curves are exactly the knot lines of [`BicubicSplineSurface`](curve_repr::BicubicSplineSurface)
//! (its module docs: every u-line S(·, v_j) is the spline through row j), so z_ij (Eq. 26),
//! the objectives of Eq. 18, 22, 24 and the network strain energy are read here without the
//! twists, which only the thin-plate variant needs.
//!
//! **Distinct nodes.** A closed direction's repeated grid line is not stored: the network has
//! N distinct nodes along it, indices taken mod N (node N − 1's next node is node 0, over the
//! closing knot step). The caller maps the grid's layout to these nodes and back.
//!
//! Every u-line has the same knots, so the same linear map A_u takes its points to its
//! tangents (M^u_{·,j} = A_u P_{·,j}, Eq. 2). Moving P_ij by δ therefore adds δ·(A_u e_i)_k to
//! M^u_{k,j}: the response A_u e_i is measured once per i (a unit move on a zero
//! [`HermiteSpline`] over the knots, which re-solves only the window whose change exceeds
//! 1e-17 relative, see curve-repr's `hermite::update`) and a move is two short vector updates.
//!
//! The jumps J^u, J^v are linear in the points too, so they are kept the same way (the
//! response ∂J_k/∂P_i = K_{k,i}, one column of the stiffness, measured with the tangents'),
//! z_ij = |J^u_ij| + |J^v_ij| is read in O(1), and a move can be checked against a cap on
//! every z it changes ([`Network::exceeds`]) at little more than the move's own cost: each
//! node carries an upper bound of its z that a move raises by |K_{k,i}|·|δ| (no square root),
//! and only a node whose bound passes the cap has its z computed.
//!
//! **Energy.** With the knots fixed the strain energy of one line is E = Σ_k P_k · J_k, J the
//! third-derivative jumps (∫|C''|² integrated by parts twice: C'' vanishes at natural ends and
//! the boundary terms cancel round a closed line), and J = K P with K symmetric, so
//! E(P + δ e_i) = E + 2 J_i·δ + K_ii |δ|². A move of P_ij therefore changes the network energy
//! by 2(J^u_ij + J^v_ij)·δ + (K_u[i,i] + K_v[j,j]) |δ|², computed in O(1) from the jumps before
//! the move. A move costs O(window), a constant (~30 knots per side for uniform knots, at most
//! ~57); a rebuild ([`Network::new`]) sums the segments exactly in O(m·n).
//!
//! **Memory layout.** A move writes the jumps of a window of u-line j (a column of the grid)
//! and of v-line i (a row). The u-line data (tangents M^u, jumps J^u) are stored
//! column-major and the v-line data row-major, so both windows are contiguous runs (~17
//! cache lines each). In the automatic mode the moves come in the order of z, scattered over
//! the grid, and once the grid outgrows the cache every line a move touches is a miss: with
//! the u-line data row-major, as the points are, the u-window touched one line per node
//! (~45). The z bounds (one f64 per node, a third of the jumps' size) stay row-major, so
//! their u-window is strided.
//!
//! The moves' scattered order also makes the first load of each move (its point, jumps and
//! bound) a miss that stalls it; [`Network::prefetch`] lets the caller, which knows the
//! order, start those loads two moves ahead.
//!
//! A run rebuilds its network once per step ([`Network::rebuild`]): into the storage it
//! already has, so that a step touches no fresh pages (at 400 × 400 a step's arrays were
//! ~45 MB of new allocations), and in two passes, one per direction: each line's energy
//! terms and jumps are taken right after its solve, the z bounds and the largest z with the
//! v-lines. Until the next move the bounds are the exact z ([`Network::exact_zs`]).

use curve_repr::{HermiteEnds, HermiteSettings, HermiteSpline, Vec3, Vector};

use super::super::strain_energy::hermite_energy;
use crate::{Error, Result};

/// C''' on a Hermite segment: (6(M_0 + M_1) − 12(P_1 − P_0)/h)/h².
fn third(p0: Vec3, p1: Vec3, m0: Vec3, m1: Vec3, h: f64) -> Vec3 {
    ((m0 + m1) * 6.0 - (p1 - p0) * (12.0 / h)) / (h * h)
}

/// Adds the strain energy ∫|C''|² of every segment of one line (`line` its points,
/// `tangents` its tangents, `stiffness` its knots) to `energy`, segment by segment from
/// node 0 (the closing segment last round a closed line). O(line).
fn add_line_energy(stiffness: &Stiffness, line: &[Vec3], tangents: &[Vec3], energy: &mut f64) {
    for i in 0..line.len() {
        if let Some(n) = stiffness.next(i) {
            *energy += hermite_energy(line[i], line[n], tangents[i], tangents[n], stiffness.step(i));
        }
    }
}

/// Pushes the third-derivative jump C‴(t_k+) − C‴(t_k−) at every node k of one line onto
/// `out` (0 at an open end). O(line).
fn push_line_jumps(stiffness: &Stiffness, line: &[Vec3], tangents: &[Vec3], out: &mut Vec<Vec3>) {
    let third_from =
        |k: usize, n: usize| third(line[k], line[n], tangents[k], tangents[n], stiffness.step(k));
    out.extend((0..line.len()).map(|k| {
        if !stiffness.is_interior(k) {
            return Vec3::zeros();
        }
        let after = stiffness.next(k).map_or(Vec3::zeros(), |n| third_from(k, n));
        let before = stiffness.previous(k).map_or(Vec3::zeros(), |b| third_from(b, k));
        after - before
    }));
}

/// The response of one knot vector's splines (natural, or periodic when closed) to unit point
/// moves, and the stiffness J = K P read from it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Stiffness {
    /// Distinct nodes N.
    count: usize,
    /// Whether the line is closed (indices mod N).
    closed: bool,
    /// K_{k,k}, per node (0 at the two ends of an open line, where there is no jump).
    pub diagonal: Vec<f64>,
    /// K_{k,next(k)} = K_{next(k),k} (K is symmetric), per node; 0 where there is no next
    /// node or either node is an open end.
    pub side: Vec<f64>,
    /// For each node k: the first index lo and the values ∂M_l/∂P_k for l = lo, lo + 1, …
    /// (mod N when closed; zero outside).
    response: Vec<(usize, Vec<f64>)>,
    /// For each node k: the first index lo and the values ∂J_l/∂P_k = K_{l,k} (0 at open
    /// ends), as `response`.
    jump_response: Vec<(usize, Vec<f64>)>,
    /// The knot steps h_k from node k to node next(k) (N − 1 open, N closed).
    steps: Vec<f64>,
}

impl Stiffness {
    /// Measures the responses by moving one point at a time of the zero scalar spline over
    /// `knots` to 1 (the tangents are linear in the points, so the response is exact up to
    /// rounding), and K from the jumps next to it. `knots` has one entry per node, plus the
    /// closing one when `closed`. O(N · window): each unit move changes the tangents only in
    /// the spline's update window and leaves them exactly 0 elsewhere, so the jumps are read
    /// in that band only (see [`band_of`]); the values are bit for bit those of reading the
    /// whole line. The move is not made: the spline's
    /// [`unit_move_tangents`](HermiteSpline::unit_move_tangents) gives the re-solved rows
    /// and the line stays zero (moving it back, or copying the zero line, cost as much as
    /// the move again).
    pub(crate) fn new(knots: &[f64], closed: bool) -> Result<Self> {
        let count = knots.len() - usize::from(closed);
        let mut settings = HermiteSettings::<1>::new().with_parameters(knots.to_vec());
        if closed {
            settings = settings.with_ends(HermiteEnds::Closed);
        }
        let mut zero = HermiteSpline::new(&vec![Vector::<1>::zeros(); count], &settings)?;
        // The line's tangents after the unit move: zero but in the rows the move re-solves,
        // written there for each move and cleared after it.
        let mut moved = vec![Vector::<1>::zeros(); count];
        let steps: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let mut stiffness = Self {
            count,
            closed,
            diagonal: vec![0.0; count],
            side: vec![0.0; count],
            response: Vec::with_capacity(count),
            jump_response: Vec::with_capacity(count),
            steps,
        };
        let mut tangent_band = Vec::new();
        let mut jump_band = Vec::new();
        if !closed {
            for i in 0..count {
                let (solved_from, solved) = zero.unit_move_tangents(i)?;
                stiffness.open_node(i, solved_from, solved, &mut tangent_band, &mut jump_band);
            }
            return Ok(stiffness);
        }
        for i in 0..count {
            let (solved_from, solved) = zero.unit_move_tangents(i)?;
            let solved_rows = solved.len();
            for (d, &t) in solved.iter().enumerate() {
                moved[(solved_from + d) % count] = t;
            }
            let tangents = &moved;
            let tangent = |k: usize| tangents[k][0];
            let point = |k: usize| if k == i { 1.0 } else { 0.0 };
            // The third derivative on the segment from node k to its next node, if any.
            let third_from = |k: usize| {
                stiffness
                    .next(k)
                    .map(|n| third1(point(k), point(n), tangent(k), tangent(n), stiffness.steps[k]))
            };
            // The tangents' support, one node wider for the jumps (a jump reads the tangents
            // next to it); the whole line when that band would meet itself round a closed one.
            // Round a closed line the whole line is read in the order of `window`'s ring.
            let whole = if closed {
                let back = (count as isize - 1) / 2;
                (back, count as isize - 1 - back)
            } else {
                (i as isize, (count - 1 - i) as isize)
            };
            let (back, ahead) = band_of(tangents, i, closed).map_or(whole, |(b, a)| {
                if closed {
                    (b + 1, a + 1)
                } else {
                    ((b + 1).min(whole.0), (a + 1).min(whole.1))
                }
            });
            // The band's nodes in order, wrapping round a closed line.
            let first = (i as isize - back).rem_euclid(count as isize) as usize;
            let nodes = (0..=(back + ahead) as usize).map(|d| {
                let k = first + d;
                if k >= count {
                    k - count
                } else {
                    k
                }
            });
            tangent_band.clear();
            tangent_band.extend(nodes.clone().map(tangent));
            // The jump at a node is the third derivative after it minus the one before it:
            // each segment's once, the segment before a band node being the one after the
            // band node before it.
            jump_band.clear();
            let mut before = stiffness.previous(first).and_then(third_from);
            for k in nodes {
                let after = third_from(k);
                jump_band.push(if stiffness.is_interior(k) {
                    after.unwrap_or(0.0) - before.unwrap_or(0.0)
                } else {
                    0.0
                });
                before = after;
            }
            let response = band_window(&tangent_band, back, i, count);
            let jump_window = band_window(&jump_band, back, i, count);
            // i is band node `back`, its previous node (if any) band node `back` − 1.
            let own = back as usize;
            let diagonal = stiffness.is_interior(i).then(|| jump_band[own]);
            // K_{p,i} = ∂J_p/∂P_i, p the previous node.
            let side = stiffness
                .previous(i)
                .filter(|&p| stiffness.is_interior(p) && stiffness.is_interior(i))
                .map(|p| (p, jump_band[own - 1]));
            stiffness.response.push(response);
            stiffness.jump_response.push(jump_window);
            if let Some(value) = diagonal {
                stiffness.diagonal[i] = value;
            }
            if let Some((p, value)) = side {
                stiffness.side[p] = value;
            }
            // Back to the zero line's tangents.
            for d in 0..solved_rows {
                moved[(solved_from + d) % count] = Vector::<1>::zeros();
            }
        }
        Ok(stiffness)
    }

    /// [`new`](Self::new)'s reading of the unit move of node i of an open line, whose
    /// re-solved tangents are `solved` from node `solved_from` on (every other tangent 0):
    /// the same band ([`band_of`]'s scan), the same values in the same order as the general
    /// path (which reads them from a copy of the whole line), so the same bits, read from
    /// the re-solved rows directly. O(window).
    fn open_node(
        &mut self,
        i: usize,
        solved_from: usize,
        solved: &[Vector<1>],
        tangent_band: &mut Vec<f64>,
        jump_band: &mut Vec<f64>,
    ) {
        let count = self.count;
        let tangent = |k: usize| {
            k.checked_sub(solved_from)
                .and_then(|d| solved.get(d))
                .map_or(0.0, |t| t[0])
        };
        let point = |k: usize| if k == i { 1.0 } else { 0.0 };
        // `band_of` on the open line: out from i to the last nonzero tangent before a run of
        // ZERO_RUN zeros or the end, then one node wider for the jumps, within the line.
        let reach = |most: usize, at: &dyn Fn(usize) -> f64| -> usize {
            let (mut last, mut zeros, mut d) = (0, 0, 1);
            while zeros < ZERO_RUN {
                if d > most {
                    break;
                }
                if at(d) == 0.0 {
                    zeros += 1;
                } else {
                    (last, zeros) = (d, 0);
                }
                d += 1;
            }
            last
        };
        let back = (reach(i, &|d| tangent(i - d)) + 1).min(i);
        let ahead = (reach(count - 1 - i, &|d| tangent(i + d)) + 1).min(count - 1 - i);
        let (first, last) = (i - back, i + ahead);
        // The band's tangents with the nodes next to it (those the jumps read), and the
        // band itself within them.
        let (outer_first, outer_last) = (first.saturating_sub(1), (last + 1).min(count - 1));
        tangent_band.clear();
        tangent_band.extend((outer_first..=outer_last).map(tangent));
        let outer = &tangent_band[..];
        let band = first - outer_first..=last - outer_first;
        // The jump at an interior node: the third derivative after it minus the one before
        // it, each segment's once; 0 at the ends.
        let steps = &self.steps;
        let third_from = |k: usize| {
            let r = k - outer_first;
            third1(point(k), point(k + 1), outer[r], outer[r + 1], steps[k])
        };
        jump_band.clear();
        let mut before = (first > 0).then(|| third_from(first - 1));
        for k in first..=last {
            let after = (k + 1 < count).then(|| third_from(k));
            jump_band.push(if k >= 1 && k + 1 < count {
                after.unwrap_or(0.0) - before.unwrap_or(0.0)
            } else {
                0.0
            });
            before = after;
        }
        let back = back as isize;
        let response = band_window(&outer[band], back, i, count);
        let jump_window = band_window(jump_band, back, i, count);
        // i is band node `back`, its previous node (if any) band node `back` − 1.
        let own = back as usize;
        let interior = |k: usize| k >= 1 && k + 1 < count;
        if interior(i) {
            self.diagonal[i] = jump_band[own];
            if interior(i - 1) {
                self.side[i - 1] = jump_band[own - 1];
            }
        }
        self.response.push(response);
        self.jump_response.push(jump_window);
    }

    /// The next node along the line (wrapping when closed).
    pub(crate) fn next(&self, k: usize) -> Option<usize> {
        if k + 1 < self.count {
            Some(k + 1)
        } else {
            self.closed.then_some(0)
        }
    }

    /// The previous node along the line (wrapping when closed).
    pub(crate) fn previous(&self, k: usize) -> Option<usize> {
        if k > 0 {
            Some(k - 1)
        } else {
            self.closed.then(|| self.count - 1)
        }
    }

    /// Whether node k has a jump (every node of a closed line; not an open line's ends).
    pub(crate) fn is_interior(&self, k: usize) -> bool {
        self.closed || (k >= 1 && k + 1 < self.count)
    }

    /// The knot step from node k to node next(k).
    pub(crate) fn step(&self, k: usize) -> f64 {
        self.steps[k]
    }

    /// K_{a,b} for a = b or neighbours, else 0 (the far entries are not needed: the groups of
    /// Eq. 23 and 25 are adjacent).
    pub(crate) fn entry(&self, a: usize, b: usize) -> f64 {
        if a == b {
            self.diagonal.get(a).copied().unwrap_or(0.0)
        } else if self.next(a) == Some(b) {
            self.side.get(a).copied().unwrap_or(0.0)
        } else if self.next(b) == Some(a) {
            self.side.get(b).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    }
}

/// Scalar C''' on a Hermite segment.
fn third1(p0: f64, p1: f64, m0: f64, m1: f64, h: f64) -> f64 {
    (6.0 * (m0 + m1) - 12.0 * (p1 - p0) / h) / (h * h)
}

/// Responses are kept where they exceed this fraction of their largest entry: the neglected
/// far tail (it decays by ~0.27 per knot) changes a tangent or a jump by less than 1e-13 of
/// the move's own effect, and the network is rebuilt exactly at every step.
pub(crate) const RESPONSE_TRIM: f64 = 1e-13;

/// How many exact zeros in a row end the support of a unit move's tangents: inside the
/// spline's update window the response decays by at most 1/2 per knot from 1 down to
/// ~1e-17, so it holds no run of exact zeros (a single one can occur, at the moved node of a
/// symmetric stretch), and outside it every tangent is exactly 0.
const ZERO_RUN: usize = 4;

/// The support of the tangents after a unit move of node i of a line of zeros: (nodes
/// before i, nodes after i) up to the last nonzero tangent each way, scanning out from i
/// until [`ZERO_RUN`] exact zeros in a row. `None` on a closed line whose support reaches
/// round to within a node of itself (the caller then reads the whole line). O(window).
fn band_of(tangents: &[Vector<1>], i: usize, closed: bool) -> Option<(isize, isize)> {
    let count = tangents.len() as isize;
    let at = |d: isize| tangents[(i as isize + d).rem_euclid(count) as usize][0];
    // Offsets −⌊(N−1)/2⌋ … ⌊N/2⌋ round i name every node of a closed line once; the band
    // with its extra node for the jumps must stay inside them.
    let (most_back, most_ahead) = if closed {
        ((count - 1) / 2 - 1, count / 2 - 1)
    } else {
        (i as isize, count - 1 - i as isize)
    };
    let reach = |sign: isize, most: isize| -> Option<isize> {
        let (mut last, mut zeros, mut d) = (0, 0, 1);
        while zeros < ZERO_RUN as isize {
            if d > most {
                return if closed { None } else { Some(last) };
            }
            if at(sign * d) == 0.0 {
                zeros += 1;
            } else {
                (last, zeros) = (d, 0);
            }
            d += 1;
        }
        Some(last)
    };
    Some((reach(-1, most_back)?, reach(1, most_ahead)?))
}

/// The significant part of a response around node i, for a line whose values are zero
/// outside a band: `(lo, values)` with values for lo, lo + 1, … (mod N when closed), from the
/// first to the last entry above [`RESPONSE_TRIM`] of the largest (i alone when none is).: `band` holds the values of
/// nodes i − back … (wrapping round a closed line of `count` nodes), a band that, round a
/// closed line, stays within the offsets −⌊(N−1)/2⌋ … ⌊N/2⌋ of i. The values outside the
/// band being 0, it is the window of the whole line (the test `stiffness_equals_whole_line`).
fn band_window(band: &[f64], back: isize, i: usize, count: usize) -> (usize, Vec<f64>) {
    let largest = band.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let significant = |v: &f64| v.abs() > RESPONSE_TRIM * largest;
    let own = back as usize;
    let first = band.iter().position(significant).unwrap_or(own);
    let last = band.iter().rposition(significant).unwrap_or(own).max(first);
    let lo = (i as isize - back + first as isize).rem_euclid(count as isize) as usize;
    (lo, band[first..=last].to_vec())
}

/// Columns of the points a rebuild copies out at a time for the u-lines: 16 lines of up to a
/// few hundred nodes (~150 KB at 400 nodes) stay in the second-level cache while they are
/// solved, and a row's 16 points are whole cache lines.
const COLUMN_BLOCK: usize = 16;

/// The iso-parametric spline network of a grid of distinct nodes (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct Network {
    /// Distinct nodes along u.
    u_count: usize,
    /// Distinct nodes along v.
    v_count: usize,
    /// P_ij at i·v_count + j.
    points: Vec<Vec3>,
    /// Scratch of a rebuild: [`COLUMN_BLOCK`] columns of the points, column-major (kept
    /// for the next rebuild's storage).
    columns: Vec<Vec3>,
    /// M^u_ij at j·u_count + i (column-major: a u-line is contiguous).
    u_tangents: Vec<Vec3>,
    /// M^v_ij at i·v_count + j.
    v_tangents: Vec<Vec3>,
    /// J^u_ij at j·u_count + i, column-major as `u_tangents` (0 where the node is an open
    /// end along u).
    u_jumps: Vec<Vec3>,
    /// J^v_ij at i·v_count + j (row-major: a v-line is contiguous; 0 where the node is an
    /// open end along v).
    v_jumps: Vec<Vec3>,
    /// An upper bound of z_ij at i·v_count + j (exact after a rebuild, raised by moves).
    z_bounds: Vec<f64>,
    /// The largest z over the interior nodes while no move was made since the last
    /// rebuild (the z bounds are then the exact z), taken as the bounds were filled; `None`
    /// after a move.
    fresh_max_z: Option<f64>,
    /// Whether moves update the tangents (only Eq. 20 and the energy sum read them; the
    /// jumps, z and the energy change do not).
    track_tangents: bool,
    energy: f64,
    u_stiffness: Stiffness,
    v_stiffness: Stiffness,
}

impl Network {
    /// The network of the flat grid of distinct nodes `points[i·v_count + j]` = P_ij over the
    /// given knots: one per node along an open direction, one per node and the closing one
    /// along a closed direction (`closed` = (u, v)). O(m·n + (m + n) · window).
    pub(crate) fn new(
        points: &[Vec3],
        u_knots: &[f64],
        v_knots: &[f64],
        closed: (bool, bool),
    ) -> Result<Self> {
        Self::with_tangents(points, u_knots, v_knots, closed, true)
    }

    /// [`new`](Self::new), keeping the tangents or not (as after
    /// [`stop_tracking_tangents`](Self::stop_tracking_tangents), without writing them once
    /// first: two arrays of the grid's size a run never reads). The same points, jumps,
    /// bounds and energy either way.
    pub(crate) fn with_tangents(
        points: &[Vec3],
        u_knots: &[f64],
        v_knots: &[f64],
        closed: (bool, bool),
        track_tangents: bool,
    ) -> Result<Self> {
        let mut network = Self {
            u_count: 0,
            v_count: 0,
            points: Vec::new(),
            columns: Vec::new(),
            u_tangents: Vec::new(),
            v_tangents: Vec::new(),
            u_jumps: Vec::new(),
            v_jumps: Vec::new(),
            z_bounds: Vec::new(),
            fresh_max_z: None,
            track_tangents,
            energy: 0.0,
            u_stiffness: Stiffness::new(u_knots, closed.0)?,
            v_stiffness: Stiffness::new(v_knots, closed.1)?,
        };
        network.fill(points, u_knots, v_knots)?;
        Ok(network)
    }

    /// The network of other points and knots in this one's storage (the same values as
    /// [`new`](Self::new), without a fresh allocation of its m·n arrays: a run rebuilds once
    /// per step, and fresh arrays of that size are fresh pages, each a fault on first
    /// touch). Tangents are kept or not as before it ([`stop_tracking_tangents`]). On an
    /// error the network is left unusable.
    ///
    /// [`stop_tracking_tangents`]: Self::stop_tracking_tangents
    /// O(m·n + (m + n) · window).
    pub(crate) fn rebuild(
        &mut self,
        points: &[Vec3],
        u_knots: &[f64],
        v_knots: &[f64],
        closed: (bool, bool),
    ) -> Result<()> {
        self.u_stiffness = Stiffness::new(u_knots, closed.0)?;
        self.v_stiffness = Stiffness::new(v_knots, closed.1)?;
        self.fill(points, u_knots, v_knots)
    }

    /// Points, tangents, jumps, bounds and energy over the knots of the stiffnesses. O(m·n).
    fn fill(&mut self, points: &[Vec3], u_knots: &[f64], v_knots: &[f64]) -> Result<()> {
        let (u_count, v_count) = (self.u_stiffness.count, self.v_stiffness.count);
        let closed = (self.u_stiffness.closed, self.v_stiffness.closed);
        if points.len() != u_count * v_count {
            return Err(curve_repr::Error::LengthMismatch {
                what: "grid points",
                expected: u_count * v_count,
                got: points.len(),
            }
            .into());
        }
        (self.u_count, self.v_count) = (u_count, v_count);
        let settings = |knots: &[f64], closed: bool| {
            let s = HermiteSettings::<3>::new().with_parameters(knots.to_vec());
            if closed {
                s.with_ends(HermiteEnds::Closed)
            } else {
                s
            }
        };
        let (u_settings, v_settings) = (settings(u_knots, closed.0), settings(v_knots, closed.1));
        let total = u_count * v_count;
        // One spline per direction, built through its first line and refitted through the
        // others in its own storage (the same tangents as a spline built through each: a
        // fresh spline per line was a dozen allocations and a check of the knots per line).
        // Each line's energy terms and jumps are taken right after its solve, while its
        // points and tangents are in cache (they were separate passes over the whole grid,
        // each from memory on a large one). The energy is one running sum in the order it
        // always had: the u-lines j by j, node by node, then the v-lines.
        let mut energy = 0.0;
        let (u_stiffness, v_stiffness) = (&self.u_stiffness, &self.v_stiffness);
        self.u_tangents.clear();
        self.u_jumps.clear();
        if self.track_tangents {
            self.u_tangents.reserve(total);
        }
        self.u_jumps.reserve(total);
        // Every bound is written below (first the u-jump's norm, then z): no clearing pass.
        self.z_bounds.resize(total, 0.0);
        // The u-lines read the points column-major: [`COLUMN_BLOCK`] columns at a time are
        // copied out of the rows into a small column-major block (in cache while its lines
        // are solved), so the points are read once, in runs (was one transpose of the whole
        // grid into an array of its size, written and read back from memory on a large one).
        let block = &mut self.columns;
        block.clear();
        block.resize(COLUMN_BLOCK.min(v_count) * u_count, Vec3::zeros());
        let mut spline: Option<HermiteSpline<3>> = None;
        for j0 in (0..v_count).step_by(COLUMN_BLOCK) {
            let width = COLUMN_BLOCK.min(v_count - j0);
            for (i, row) in points.chunks_exact(v_count).enumerate() {
                for (c, &p) in row[j0..j0 + width].iter().enumerate() {
                    block[c * u_count + i] = p;
                }
            }
            for line in block.chunks_exact(u_count).take(width) {
                let spline = match &mut spline {
                    Some(spline) => {
                        spline.refit(line)?;
                        spline
                    }
                    None => spline.insert(HermiteSpline::new(line, &u_settings)?),
                };
                let tangents = &spline.tangents()[..u_count];
                if self.track_tangents {
                    self.u_tangents.extend_from_slice(tangents);
                }
                add_line_energy(u_stiffness, line, tangents, &mut energy);
                push_line_jumps(u_stiffness, line, tangents, &mut self.u_jumps);
            }
            // The block's u-jump norms into the bounds, row-major in runs: the v-lines add
            // the v-jump norms (z as [`z`](Self::z) reads it, the same sum), reading one
            // row-major array instead of the column-major u-jumps.
            let jumps = &self.u_jumps[j0 * u_count..(j0 + width) * u_count];
            for (i, bounds) in self.z_bounds.chunks_exact_mut(v_count).enumerate() {
                for (c, bound) in bounds[j0..j0 + width].iter_mut().enumerate() {
                    *bound = jumps[c * u_count + i].norm();
                }
            }
        }
        // The v-lines, and row by row the points' copy and the z bounds, the largest z with
        // them.
        self.v_tangents.clear();
        self.v_jumps.clear();
        self.points.clear();
        if self.track_tangents {
            self.v_tangents.reserve(total);
        }
        self.v_jumps.reserve(total);
        self.points.reserve(total);
        let mut max = 0.0f64;
        let mut spline: Option<HermiteSpline<3>> = None;
        for (i, line) in points.chunks_exact(v_count).enumerate() {
            let spline = match &mut spline {
                Some(spline) => {
                    spline.refit(line)?;
                    spline
                }
                None => spline.insert(HermiteSpline::new(line, &v_settings)?),
            };
            let tangents = &spline.tangents()[..v_count];
            if self.track_tangents {
                self.v_tangents.extend_from_slice(tangents);
            }
            self.points.extend_from_slice(line);
            add_line_energy(v_stiffness, line, tangents, &mut energy);
            push_line_jumps(v_stiffness, line, tangents, &mut self.v_jumps);
            let row = &self.v_jumps[i * v_count..];
            let bounds = &mut self.z_bounds[i * v_count..(i + 1) * v_count];
            let interior_row = u_stiffness.is_interior(i);
            for (j, (v_jump, bound)) in row.iter().zip(bounds).enumerate() {
                let z = *bound + v_jump.norm();
                *bound = z;
                if interior_row && v_stiffness.is_interior(j) {
                    max = max.max(z);
                }
            }
        }
        self.energy = energy;
        // The bounds are the exact z until a move (the max does not depend on the order).
        self.fresh_max_z = Some(max);
        Ok(())
    }

    /// Row-major index of node (i, j): points, v-line data, z bounds and the flat indices of
    /// the API.
    fn index(&self, i: usize, j: usize) -> usize {
        i * self.v_count + j
    }

    /// Column-major index of node (i, j): u-line data.
    fn column_index(&self, i: usize, j: usize) -> usize {
        j * self.u_count + i
    }

    /// Whether node (i, j) has a z_ij (interior along both directions, a seam counting as
    /// interior).
    pub(crate) fn is_interior(&self, i: usize, j: usize) -> bool {
        i < self.u_count
            && j < self.v_count
            && self.u_stiffness.is_interior(i)
            && self.v_stiffness.is_interior(j)
    }

    /// All points, flat (distinct nodes).
    pub(crate) fn points(&self) -> &[Vec3] {
        &self.points
    }

    /// Exchanges the points' storage with `other`: a caller that rebuilds the network from
    /// its own points takes them out without a copy. The network is unusable until its
    /// next [`rebuild`](Self::rebuild). O(1).
    pub(crate) fn swap_points(&mut self, other: &mut Vec<Vec3>) {
        std::mem::swap(&mut self.points, other);
        self.fresh_max_z = None;
    }

    /// P_ij (callers keep i, j inside the grid).
    pub(crate) fn point(&self, i: usize, j: usize) -> Vec3 {
        self.points[self.index(i, j)]
    }

    /// M^u_ij = ∂S/∂u(u_i, v_j).
    pub(crate) fn u_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.u_tangents[self.column_index(i, j)]
    }

    /// M^v_ij = ∂S/∂v(u_i, v_j).
    pub(crate) fn v_tangent(&self, i: usize, j: usize) -> Vec3 {
        self.v_tangents[self.index(i, j)]
    }

    /// ∂³S/∂u³(u_i+, v_j) − ∂³S/∂u³(u_i−, v_j) (0 at an open end along u). O(1).
    pub(crate) fn u_jump(&self, i: usize, j: usize) -> Vec3 {
        self.u_jumps[self.column_index(i, j)]
    }

    /// ∂³S/∂v³(u_i, v_j+) − ∂³S/∂v³(u_i, v_j−) (0 at an open end along v). O(1).
    pub(crate) fn v_jump(&self, i: usize, j: usize) -> Vec3 {
        self.v_jumps[self.index(i, j)]
    }

    /// Stops keeping the tangents, in moves and in rebuilds: a network used with the limit
    /// replacement (Eq. 21) reads only jumps (the energy of a rebuild is summed from the
    /// solves' own tangents), and skipping the tangents halves a move's cost and spares a
    /// rebuild two grid-sized writes. [`u_tangent`](Self::u_tangent) and
    /// [`v_tangent`](Self::v_tangent) are stale after moves made without them and are not
    /// to be called after a rebuild without them (their arrays are empty then).
    pub(crate) fn stop_tracking_tangents(&mut self) {
        self.track_tangents = false;
    }

    /// (J^u, J^v) at every node, flat (i-major).
    pub(crate) fn u_jumps_and_v_jumps(&self) -> impl Iterator<Item = (Vec3, Vec3)> + '_ {
        (0..self.u_count * self.v_count).map(|k| (self.u_jumps[self.column_of(k)], self.v_jumps[k]))
    }

    /// z_ij = |u jump| + |v jump| (Eq. 26, corrected in papers/README.md), interior nodes.
    /// O(1).
    pub(crate) fn z(&self, i: usize, j: usize) -> f64 {
        self.u_jump(i, j).norm() + self.v_jump(i, j).norm()
    }

    /// max z_ij over the interior nodes (0 when there are none). O(1) while no move was
    /// made since the last rebuild (taken then), else O(m·n).
    pub(crate) fn max_z(&self) -> f64 {
        if let Some(max) = self.fresh_max_z {
            return max;
        }
        // In bands of rows, so that both the column-major u-jumps and the row-major v-jumps
        // are read in runs (the largest value does not depend on the order).
        const BAND: usize = 8;
        let mut max = 0.0f64;
        for first in (0..self.u_count).step_by(BAND) {
            let band = first..(first + BAND).min(self.u_count);
            for j in 0..self.v_count {
                for i in band.clone() {
                    if self.is_interior(i, j) {
                        max = max.max(self.z(i, j));
                    }
                }
            }
        }
        max
    }

    /// The network strain energy Σ_j ∫|S_uu(u, v_j)|² du + Σ_i ∫|S_vv(u_i, v)|² dv over the
    /// distinct lines, kept up to date by [`move_points`](Self::move_points).
    pub(crate) fn energy(&self) -> f64 {
        self.energy
    }

    /// The stiffness of the u-lines (shared by every u-line: same knots).
    pub(crate) fn u_stiffness(&self) -> &Stiffness {
        &self.u_stiffness
    }

    /// The stiffness of the v-lines.
    pub(crate) fn v_stiffness(&self) -> &Stiffness {
        &self.v_stiffness
    }

    /// Moves points `((i, j), position)` one after another, updating the tangents and jumps
    /// of u-line j and v-line i by the measured responses and the energy by the O(1) formula
    /// of the module docs. O(moves · window). Fails with [`Error::NonFiniteMove`] (flat index)
    /// on a position or an energy that is not finite, leaving that move undone, or
    /// [`Error::BadConstraint`] on a node outside the grid or not interior (the energy formula
    /// holds at interior nodes; boundary nodes move through a rebuilt network).
    pub(crate) fn move_points(&mut self, moves: &[((usize, usize), Vec3)]) -> Result<()> {
        for &((i, j), position) in moves {
            self.move_one(i, j, position)?;
        }
        Ok(())
    }

    /// Whether a node on u-line j or v-line i of (i, j), within the jump responses of a move
    /// of P_ij, has z above `cap` (its bound checked first; its z computed, and its bound
    /// tightened, only when the bound passes the cap). O(window).
    pub(crate) fn exceeds(&mut self, i: usize, j: usize, cap: f64) -> bool {
        let vc = self.v_count;
        let (u_lo, u_values) = &self.u_stiffness.jump_response[i];
        for (start, _, len) in runs(*u_lo, u_values.len(), self.u_count) {
            for l in start..start + len {
                let k = l * vc + j;
                if self.z_bounds[k] > cap && self.tighten(k) > cap {
                    return true;
                }
            }
        }
        let (v_lo, v_values) = &self.v_stiffness.jump_response[j];
        for (start, _, len) in runs(*v_lo, v_values.len(), self.v_count) {
            for k in i * vc + start..i * vc + start + len {
                if self.z_bounds[k] > cap && self.tighten(k) > cap {
                    return true;
                }
            }
        }
        false
    }

    /// The flat indices of the nodes whose z a move of P_ij changes: u-line j and v-line i
    /// within the jump responses (P_ij itself twice), into `out` (cleared first). O(window).
    pub(crate) fn affected(&self, i: usize, j: usize, out: &mut Vec<usize>) {
        out.clear();
        let vc = self.v_count;
        let (u_lo, u_values) = &self.u_stiffness.jump_response[i];
        for (start, _, len) in runs(*u_lo, u_values.len(), self.u_count) {
            out.extend((start..start + len).map(|l| l * vc + j));
        }
        let (v_lo, v_values) = &self.v_stiffness.jump_response[j];
        for (start, _, len) in runs(*v_lo, v_values.len(), self.v_count) {
            out.extend(i * vc + start..i * vc + start + len);
        }
    }

    /// z of the node at flat index k (i·v_count + j): |J^u| + |J^v| (Eq. 26). O(1).
    pub(crate) fn z_at(&self, k: usize) -> f64 {
        self.u_jumps[self.column_of(k)].norm() + self.v_jumps[k].norm()
    }

    /// The column-major index of the node at flat (row-major) index k.
    fn column_of(&self, k: usize) -> usize {
        (k % self.v_count) * self.u_count + k / self.v_count
    }

    /// An upper bound of the z of the node at flat index k, kept by every move (exact after a
    /// rebuild or [`tighten`](Self::tighten)). O(1).
    pub(crate) fn z_bound(&self, k: usize) -> f64 {
        self.z_bounds[k]
    }

    /// z_ij of every node (row-major, flat index i·v_count + j; the boundary nodes' values
    /// are not z) while no move was made since the last rebuild: the z bounds are then
    /// exact, computed as [`z`](Self::z) computes z, so a whole-grid reader can take them
    /// from one contiguous array instead of the two jump arrays (one of them column-major).
    /// `None` after a move. O(1).
    pub(crate) fn exact_zs(&self) -> Option<&[f64]> {
        self.fresh_max_z.map(|_| &self.z_bounds[..])
    }

    /// The z of the node at flat index k, its bound set to it. O(1).
    pub(crate) fn tighten(&mut self, k: usize) -> f64 {
        let z = self.z_at(k);
        self.z_bounds[k] = z;
        z
    }

    /// Asks the processor to start loading what a move of P_ij reads first (the point, its
    /// jumps, its z bound): a caller that knows its next moves issues this a few moves ahead,
    /// so that the loads overlap the moves in between instead of stalling the next one (module
    /// docs, "memory layout"). Changes no value. O(1).
    pub(crate) fn prefetch(&self, i: usize, j: usize) {
        let k = self.index(i, j);
        prefetch(&self.points[k]);
        prefetch(&self.u_jumps[self.column_index(i, j)]);
        prefetch(&self.v_jumps[k]);
        prefetch(&self.z_bounds[k]);
    }

    fn move_one(&mut self, i: usize, j: usize, position: Vec3) -> Result<()> {
        if !self.is_interior(i, j) {
            return Err(Error::BadConstraint {
                reason: format!(
                    "node ({i}, {j}) is not an interior node of the {} × {} network",
                    self.u_count, self.v_count
                ),
            });
        }
        let index = self.index(i, j);
        if position.iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFiniteMove { index });
        }
        let delta = position - self.points[index];
        let change = self.energy_change(i, j, delta);
        if !(self.energy + change).is_finite() {
            return Err(Error::NonFiniteMove { index });
        }
        self.shift(i, j, delta);
        self.energy += change;
        Ok(())
    }

    /// The exact change of the network energy if P_ij moves by `delta` (module docs). O(1).
    pub(crate) fn energy_change(&self, i: usize, j: usize, delta: Vec3) -> f64 {
        let gradient = self.u_jump(i, j) + self.v_jump(i, j);
        let curvature = self.u_stiffness.diagonal[i] + self.v_stiffness.diagonal[j];
        2.0 * gradient.dot(&delta) + curvature * delta.norm_squared()
    }

    /// Adds `delta` to P_ij and its responses to the tangents, the jumps and the z bounds.
    fn shift(&mut self, i: usize, j: usize, delta: Vec3) {
        let (uc, vc) = (self.u_count, self.v_count);
        let size = delta.norm();
        self.fresh_max_z = None;
        self.points[i * vc + j] += delta;
        if self.track_tangents {
            let (u_lo, u_values) = &self.u_stiffness.response[i];
            for (start, offset, len) in runs(*u_lo, u_values.len(), uc) {
                let column = j * uc + start;
                for (t, &r) in self.u_tangents[column..column + len]
                    .iter_mut()
                    .zip(&u_values[offset..offset + len])
                {
                    *t += delta * r;
                }
            }
            let (v_lo, v_values) = &self.v_stiffness.response[j];
            for (start, offset, len) in runs(*v_lo, v_values.len(), self.v_count) {
                let row = i * vc + start;
                for (t, &r) in self.v_tangents[row..row + len]
                    .iter_mut()
                    .zip(&v_values[offset..offset + len])
                {
                    *t += delta * r;
                }
            }
        }
        let (u_lo, u_values) = &self.u_stiffness.jump_response[i];
        for (start, offset, len) in runs(*u_lo, u_values.len(), uc) {
            // The jumps along the u-line are contiguous; the z bounds are strided (a small
            // array, module docs).
            let column = j * uc + start;
            for ((l, jump), &r) in (start..start + len)
                .zip(&mut self.u_jumps[column..column + len])
                .zip(&u_values[offset..offset + len])
            {
                *jump += delta * r;
                self.z_bounds[l * vc + j] += r.abs() * size;
            }
        }
        let (v_lo, v_values) = &self.v_stiffness.jump_response[j];
        for (start, offset, len) in runs(*v_lo, v_values.len(), self.v_count) {
            let row = i * vc + start;
            let values = &v_values[offset..offset + len];
            for ((jump, bound), &r) in self.v_jumps[row..row + len]
                .iter_mut()
                .zip(&mut self.z_bounds[row..row + len])
                .zip(values)
            {
                *jump += delta * r;
                *bound += r.abs() * size;
            }
        }
    }
}

/// A hint to the processor to bring the cache line of `value` into its caches (x86-64's
/// `prefetcht0`; nothing elsewhere). It has no effect on any value.
// The workspace denies unsafe code; this cache hint is its one exception (SAFETY below).
#[allow(unsafe_code)]
pub(crate) fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads no memory architecturally and cannot fault, whatever the
    // address (here a live reference); SSE, which provides it, is part of every x86-64
    // target.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>(std::ptr::from_ref(value).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// A window of `len` entries from node `lo` along a line of `count` nodes (wrapping round a
/// closed line) as at most two runs of consecutive nodes: (first node, offset into the
/// window's values, length). The second run is empty unless the window wraps.
fn runs(lo: usize, len: usize, count: usize) -> [(usize, usize, usize); 2] {
    let first = len.min(count - lo);
    [(lo, 0, first), (0, first, len - first)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::Interpolant;

    /// The significant part of a response around node i: `(lo, values)` with values for lo,
    /// lo + 1, … (mod N when closed), from the first to the last entry above [`RESPONSE_TRIM`]
    /// of the largest.
    fn whole_window(values: &[f64], i: usize, closed: bool) -> (usize, Vec<f64>) {
        let count = values.len();
        let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let significant = |v: &f64| v.abs() > RESPONSE_TRIM * largest;
        if !closed {
            let lo = values.iter().position(significant).unwrap_or(i);
            let hi = values.iter().rposition(significant).unwrap_or(i);
            return (lo, values[lo..=hi.max(lo)].to_vec());
        }
        // Offsets −⌊(N−1)/2⌋ … ⌊N/2⌋ round i name every node once.
        let back = (count - 1) / 2;
        let ring: Vec<f64> = (0..count)
            .map(|d| values[(i + count - back + d) % count])
            .collect();
        let first = ring.iter().position(significant).unwrap_or(back);
        let last = ring.iter().rposition(significant).unwrap_or(back).max(first);
        ((i + count - back + first) % count, ring[first..=last].to_vec())
    }

    /// The responses as measured before the band: the whole line read after every unit
    /// move, and the move undone by a second windowed re-solve. O(N²).
    fn whole_line_stiffness(knots: &[f64], closed: bool) -> Stiffness {
        let count = knots.len() - usize::from(closed);
        let mut settings = HermiteSettings::<1>::new().with_parameters(knots.to_vec());
        if closed {
            settings = settings.with_ends(HermiteEnds::Closed);
        }
        let zero = HermiteSpline::new(&vec![Vector::<1>::zeros(); count], &settings).unwrap();
        let mut line = zero.clone();
        let steps: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
        let mut stiffness = Stiffness {
            count,
            closed,
            diagonal: vec![0.0; count],
            side: vec![0.0; count],
            response: Vec::new(),
            jump_response: Vec::new(),
            steps,
        };
        for i in 0..count {
            line.move_points(&[(i, Vector::<1>::new(1.0))]).unwrap();
            let tangents: Vec<f64> = line.tangents().iter().map(|t| t[0]).collect();
            stiffness.response.push(whole_window(&tangents, i, closed));
            let point = |k: usize| if k == i { 1.0 } else { 0.0 };
            let jump = |k: usize| -> f64 {
                let after = stiffness.next(k).map_or(0.0, |n| {
                    third1(point(k), point(n), tangents[k], tangents[n], stiffness.steps[k])
                });
                let before = stiffness.previous(k).map_or(0.0, |p| {
                    third1(point(p), point(k), tangents[p], tangents[k], stiffness.steps[p])
                });
                after - before
            };
            let jumps: Vec<f64> = (0..count)
                .map(|k| if stiffness.is_interior(k) { jump(k) } else { 0.0 })
                .collect();
            let jump_window = whole_window(&jumps, i, closed);
            let diagonal = stiffness.is_interior(i).then(|| jump(i));
            let side = stiffness
                .previous(i)
                .filter(|&p| stiffness.is_interior(p) && stiffness.is_interior(i))
                .map(|p| (p, jump(p)));
            stiffness.jump_response.push(jump_window);
            if let Some(value) = diagonal {
                stiffness.diagonal[i] = value;
            }
            if let Some((p, value)) = side {
                stiffness.side[p] = value;
            }
            line.move_points(&[(i, Vector::<1>::zeros())]).unwrap();
            // The premise of the band and of the copy reset: undone, the move leaves exact
            // zeros.
            assert_eq!(line, zero, "node {i} of {count}");
        }
        stiffness
    }

    /// Knots with steps from a deterministic sequence spanning `spread` (1: uniform).
    fn knots(count: usize, spread: f64) -> Vec<f64> {
        let mut t = vec![0.0];
        for k in 0..count - 1 {
            let x = ((k as f64 + 1.0) * 12.9898).sin() * 43_758.545_3;
            let unit = x - x.floor();
            t.push(t[k] + spread.powf(unit - 0.5));
        }
        t
    }

    #[test]
    fn stiffness_equals_whole_line() {
        // Short and long lines (the longest past the 512 nodes up to which the line was once
        // reset by a copy), with uniform, uneven
        // and wildly uneven steps (ratios up to 10^6: the widest update windows), open and
        // closed (a closed line of N nodes has N + 1 knots).
        for count in [3, 4, 5, 7, 12, 40, 121, 300, 602] {
            for spread in [1.0, 3.0, 1e6] {
                for closed in [false, true] {
                    let t = knots(count + usize::from(closed), spread);
                    let banded = Stiffness::new(&t, closed).unwrap();
                    let whole = whole_line_stiffness(&t, closed);
                    assert!(banded == whole, "{count} nodes, spread {spread}, closed {closed}");
                }
            }
        }
    }
}
