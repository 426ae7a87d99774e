//! Boundaries that join: an edge of the faired net held to a neighbour's edge with G0, G1 or
//! G2 continuity, the neighbour untouched.
//!
//! # What a join holds
//!
//! The neighbour is a net (a CAD surface is sampled into one by the caller). Its edge that
//! meets the joined edge is found by the nodes: among its four edges, either way round, the
//! one with as many nodes as the joined edge and the smallest largest gap between
//! corresponding nodes. Then, with S the faired net's bicubic surface and N the neighbour's:
//!
//! - **g0**: the joined edge's nodes are set to the neighbour's edge nodes and held (a held
//!   grid line, as `--clamp-ends g0` holds the boundary). The faired net takes the neighbour's
//!   knots along the edge (mapped affinely onto its own range), so its edge curve — the
//!   natural cubic spline through the edge nodes over those knots — *is* the neighbour's
//!   edge curve, between the nodes as well as at them.
//! - **g1**: g0, and the derivative across the edge is the neighbour's continued,
//!   ∂S/∂u(u_0, v_j) = −β d^N_j at every edge node (u_0 the joined edge, d^N_j the neighbour's
//!   derivative into itself at the node, β = h^N / h^S the ratio of the knot steps next to
//!   the edge, so the two parametrisations meet C1). ∂S/∂u(u_0, v_j) = Σ_i a_i P_ij is a
//!   fixed linear functional a of each grid line across the edge (the end tangent of its
//!   natural spline), so these are linear equality constraints, one per line and
//!   coordinate. Along the edge both ∂S/∂u and ∂N/∂t are the natural splines through their
//!   node values over the same knots, so equality at the nodes is equality along the whole
//!   edge: the join is C1, and the tangent planes agree everywhere on it.
//! - **g2**: every open edge of these surfaces has zero second derivative across it (the
//!   natural end condition), S_uu = N_tt = 0, and S_uv = β N_tv, S_vv = N_vv follow from
//!   the C1 join along the shared edge curve: a C1 join of two such nets is already C2, so g2
//!   holds the same constraints as g1 and its report measures the curvature jump.
//!
//! # The solve
//!
//! The held edge lines leave the unknowns (the coupling goes to the right-hand side). The
//! g1 constraints on the block, c_kᵀ X[:, b] = τ_k,b for each free line b across the edge
//! (k over the g1 joins across that direction, at most two), enter by Lagrange
//! multipliers: X = X₀ − A⁻¹ Σ_k c_k μ_kᵀ, A the Kronecker-sum operator. In the eigenbases
//! (X̂ = UᵀXV, ĉ = Uᵀc, τ̂ = Vᵀτ, g_ab = 1/(1 + λ_u μ_a + λ_v ν_b)) the Schur complement is block
//! diagonal, one k × k block per eigenvector b:
//!
//! ```text
//! W_b[k, l] = Σ_a ĉ_k,a ĉ_l,a g_ab,   W_b μ̂_b = ĉᵀ X̂₀[:, b] − τ̂_b,   X̂_ab = X̂₀_ab − g_ab Σ_k ĉ_k,a μ̂_k,b
//! ```
//!
//! so the constrained solve costs O(m·n) on top of the unconstrained one, and GCV sees the
//! join: the smoother's trace loses Σ_b tr(W_b⁻¹ W′_b), W′_b[k, l] = Σ_a ĉ_k,a ĉ_l,a g_ab².
//! g1/g2 joins across both directions at once (a u edge and a v edge) would couple the
//! blocks; they are refused, as are g1/g2 joins with fixed nodes or a tolerance band
//! (the scattered-node solve does not carry these constraints). g0 joins combine with
//! everything but a node fixed on the joined edge.
//!
//! # Reduced bases
//!
//! On a long direction (module `reduced`) the same algebra holds with that direction's
//! reduced basis T (orthonormal at the sites) in place of the eigenbasis: ĉ = Tᵀc across
//! the edge, τ̂ = Tᵀτ along it. The joined edge is a held end, which shifts the block's data
//! by its line, projected onto the basis along the edge when that direction is reduced too
//! (module `reduced`, "Both directions"; the shift's part of cᵀX is taken from τ first).
//! Along a reduced direction τ̂ is τ's projection, so the spectral correction meets the
//! constraints in the reduced space only; the solution at the sites is then brought onto them
//! exactly by the least change per line, x_l −= C (CᵀC)⁻¹ (Cᵀx_l − τ_l) (`correct_at_sites`),
//! C's rows decaying away from the edge within a few lines. That change is the size of the
//! edge's and τ's parts outside the basis (at most 2.9·10⁻⁵ on unit nets whose noise was
//! 1.4·10⁻³ to 5.7·10⁻³, `docs/experiments/surface-joins.md`), and GCV does not see it. With
//! knots at every site it is nothing, and the fit is the exact path's (tested to round-off).
//!
//! # The report
//!
//! [`JoinReport`]: along the edge, at every node and at the middle of every span, the gap
//! |S − N|, the angle between the two tangent planes, and the jump of the normal curvature
//! across the edge (in the direction normal to the edge within the tangent plane), before
//! (the input's surface over its own knots) and after. Cost O(n) evaluations per edge.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, Parametrization, Side, Surface, Vec3};
use nalgebra::{DMatrix, DVector};

use super::spectral::{Planes, Spectral, Weights};

use crate::{Error, Result};

/// The largest gap between a joined edge and its neighbour's, as a share of the net's
/// bounding-box diagonal, beyond which the join is refused: a guard against gross mistakes
/// only. Noisy edges of neighbouring patches are a few noise levels apart, and a join may
/// deliberately move an edge some way onto a neighbour (a test's neighbour is 12 % off); a
/// neighbour across another edge is most of the net's size away (67 % on a square).
const JOIN_GAP_MAX: f64 = 0.25;

/// An edge of a net: `u0` the first row (i = 0), `u1` the last row (i = m), `v0` the first
/// column (j = 0), `v1` the last (j = n).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JoinEdge {
    /// Row i = 0.
    U0,
    /// Row i = m.
    U1,
    /// Column j = 0.
    V0,
    /// Column j = n.
    V1,
}

impl JoinEdge {
    /// Every edge.
    pub const ALL: [JoinEdge; 4] = [JoinEdge::U0, JoinEdge::U1, JoinEdge::V0, JoinEdge::V1];

    /// The name: u0, u1, v0, v1.
    pub fn name(self) -> &'static str {
        match self {
            JoinEdge::U0 => "u0",
            JoinEdge::U1 => "u1",
            JoinEdge::V0 => "v0",
            JoinEdge::V1 => "v1",
        }
    }

    /// The edge by its name.
    pub fn parse(text: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|e| e.name() == text)
    }

    /// Whether the edge is a row (a u edge: the grid lines across it run along u).
    fn across_u(self) -> bool {
        matches!(self, JoinEdge::U0 | JoinEdge::U1)
    }

    /// Whether the edge is the last line of its direction.
    fn at_end(self) -> bool {
        matches!(self, JoinEdge::U1 | JoinEdge::V1)
    }

    /// Nodes along the edge of a rows × columns net.
    fn count(self, rows: usize, columns: usize) -> usize {
        if self.across_u() {
            columns
        } else {
            rows
        }
    }

    /// The node (i, j) at position k along the edge.
    fn node(self, k: usize, rows: usize, columns: usize) -> (usize, usize) {
        match self {
            JoinEdge::U0 => (0, k),
            JoinEdge::U1 => (rows - 1, k),
            JoinEdge::V0 => (k, 0),
            JoinEdge::V1 => (k, columns - 1),
        }
    }
}

/// The continuity a join holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Continuity {
    /// Positions.
    G0,
    /// Positions and the tangent plane (held as C1). The default.
    #[default]
    G1,
    /// Positions, tangent plane and curvature (a C1 join of natural bicubic nets is C2).
    G2,
}

impl Continuity {
    /// The name: g0, g1, g2.
    pub fn name(self) -> &'static str {
        match self {
            Continuity::G0 => "g0",
            Continuity::G1 => "g1",
            Continuity::G2 => "g2",
        }
    }

    /// The continuity by its name.
    pub fn parse(text: &str) -> Option<Self> {
        [Continuity::G0, Continuity::G1, Continuity::G2]
            .into_iter()
            .find(|c| c.name() == text)
    }
}

/// One edge of the faired net held to a neighbour.
#[derive(Clone, Debug, PartialEq)]
pub struct Join {
    /// The faired net's edge.
    pub edge: JoinEdge,
    /// What is held.
    pub continuity: Continuity,
    /// The neighbour's net, `neighbour[i][j]` (never changed).
    pub neighbour: Vec<Vec<Vec3>>,
    /// Where the neighbour came from (a file name), for the report and errors.
    pub source: String,
}

/// The join's quality across one edge: largest values over the samples along it.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JoinMeasure {
    /// Largest |S − N| (the position gap).
    pub gap: f64,
    /// Largest angle between the two tangent planes, degrees.
    pub angle_degrees: f64,
    /// Largest |κ_S − κ_N| of the normal curvatures across the edge (1/length).
    pub curvature_jump: f64,
}

/// What a join did, for the report.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JoinReport {
    /// The faired net's edge.
    pub edge: JoinEdge,
    /// The continuity held.
    pub continuity: Continuity,
    /// The neighbour's source.
    pub neighbour: String,
    /// The neighbour's edge it meets.
    pub neighbour_edge: JoinEdge,
    /// Whether the neighbour's edge runs the other way.
    pub reversed: bool,
    /// Across the edge before fairing (the input over its own knots).
    pub before: JoinMeasure,
    /// Across the edge after.
    pub after: JoinMeasure,
}

/// A join made ready for the solve: the neighbour's surface and edge, oriented to ours.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    pub edge: JoinEdge,
    pub continuity: Continuity,
    pub source: String,
    surface: BicubicSplineSurface,
    nb_edge: JoinEdge,
    reversed: bool,
    /// The neighbour's edge nodes, in our order.
    pub edge_points: Vec<Vec3>,
    /// The neighbour's knots along the edge, in our order (increasing).
    pub along_knots: Vec<f64>,
    /// The neighbour's derivative into itself at each edge node (per unit of its parameter).
    inward: Vec<Vec3>,
    /// The neighbour's knot step next to the edge.
    step: f64,
}

fn refuse(reason: String) -> Error {
    Error::Refused {
        method: super::NAME.into(),
        what: crate::Refusal::Join,
        reason: format!("cannot hold the joins: {reason}"),
    }
}

impl Prepared {
    /// Finds the neighbour's edge meeting `join.edge` of `grid` (rows × columns).
    pub(crate) fn new(join: &Join, grid: &[Vec<Vec3>], parametrization: Parametrization) -> Result<Self> {
        let (rows, columns) = (grid.len(), grid[0].len());
        let nb = &join.neighbour;
        let (nr, nc) = (nb.len(), nb.first().map_or(0, Vec::len));
        let name = &join.source;
        if nr < 3 || nc < 3 || nb.iter().any(|r| r.len() != nc) {
            return Err(refuse(format!(
                "join {}: the neighbour {name} is not a rectangular net of at least 3 × 3 nodes",
                join.edge.name()
            )));
        }
        if nb.iter().flatten().any(|p| !p.iter().all(|c| c.is_finite())) {
            return Err(refuse(format!(
                "join {}: a node of the neighbour {name} is not finite",
                join.edge.name()
            )));
        }
        let count = join.edge.count(rows, columns);
        let ours: Vec<Vec3> = (0..count)
            .map(|k| {
                let (i, j) = join.edge.node(k, rows, columns);
                grid[i][j]
            })
            .collect();
        let mut best: Option<(f64, JoinEdge, bool)> = None;
        for e in JoinEdge::ALL {
            if e.count(nr, nc) != count {
                continue;
            }
            for reversed in [false, true] {
                let gap = (0..count)
                    .map(|k| {
                        let kk = if reversed { count - 1 - k } else { k };
                        let (i, j) = e.node(kk, nr, nc);
                        (nb[i][j] - ours[k]).norm()
                    })
                    .fold(0.0, f64::max);
                if best.is_none_or(|b| gap < b.0) {
                    best = Some((gap, e, reversed));
                }
            }
        }
        let Some((gap, nb_edge, reversed)) = best else {
            return Err(refuse(format!(
                "join {}: the edge has {count} nodes but no edge of the neighbour {name} does \
                 (it is {nr} × {nc}: its edges have {nc} and {nr} nodes)",
                join.edge.name()
            )));
        };
        // The joined edge is moved onto the neighbour's: a neighbour that does not meet it (the
        // neighbour across another edge, a wrong file) would drag the edge across the net.
        let (lo, hi) = grid.iter().flatten().fold(
            (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let size = (hi - lo).norm();
        if gap > JOIN_GAP_MAX * size {
            return Err(refuse(format!(
                "join {}: the nearest edge of the neighbour {name} ({}) lies up to {gap:.4e} from \
                 this edge, {:.0} % of the net's size {size:.4e}; a join moves the edge onto the \
                 neighbour's, so the two must meet (at most {:.0} % apart): is {name} the \
                 neighbour across another edge?",
                join.edge.name(),
                nb_edge.name(),
                100.0 * gap / size,
                100.0 * JOIN_GAP_MAX,
            )));
        }
        let build = BicubicSurfaceSettings::default().with_parametrization(parametrization);
        let surface = BicubicSplineSurface::with_settings(nb, &build)
            .map_err(|e| refuse(format!("join {}: the neighbour {name}: {e}", join.edge.name())))?;
        let order = |k: usize| if reversed { count - 1 - k } else { k };
        let edge_points = (0..count)
            .map(|k| {
                let (i, j) = nb_edge.node(order(k), nr, nc);
                nb[i][j]
            })
            .collect();
        let (along, across) = if nb_edge.across_u() {
            (surface.v_knots(), surface.u_knots())
        } else {
            (surface.u_knots(), surface.v_knots())
        };
        let along_knots = if reversed {
            let end = along[count - 1];
            (0..count).map(|k| end - along[count - 1 - k]).collect()
        } else {
            along.to_vec()
        };
        let sign = if nb_edge.at_end() { -1.0 } else { 1.0 };
        let inward = (0..count)
            .map(|k| {
                let (i, j) = nb_edge.node(order(k), nr, nc);
                let d = if nb_edge.across_u() {
                    surface.u_tangent(i, j)
                } else {
                    surface.v_tangent(i, j)
                };
                d.unwrap_or_else(Vec3::zeros) * sign
            })
            .collect();
        let last = across.len() - 1;
        let step = if nb_edge.at_end() {
            across[last] - across[last - 1]
        } else {
            across[1] - across[0]
        };
        Ok(Self {
            edge: join.edge,
            continuity: join.continuity,
            source: join.source.clone(),
            surface,
            nb_edge,
            reversed,
            edge_points,
            along_knots,
            inward,
            step,
        })
    }

    /// Whether the join holds a derivative across the edge (g1, g2).
    pub(crate) fn holds_tangent(&self) -> bool {
        self.continuity != Continuity::G0
    }

    /// Our knots along the edge: the neighbour's, mapped affinely onto `own`'s range.
    pub(crate) fn mapped_knots(&self, own: &[f64]) -> Vec<f64> {
        let (a, b) = (own[0], own[own.len() - 1]);
        let (s, t) = (self.along_knots[0], self.along_knots[self.along_knots.len() - 1]);
        let mut out: Vec<f64> = self
            .along_knots
            .iter()
            .map(|&x| a + (x - s) * (b - a) / (t - s))
            .collect();
        let n = out.len();
        out[0] = a;
        out[n - 1] = b;
        out
    }

    /// The constraint across the edge on each grid line across it: the functional c (over
    /// the line's nodes, from the edge inward in grid order) with c·P = ∂S/∂(across) at the
    /// edge, and its targets τ (one per line along the edge), for our knots `across`
    /// (increasing, grid order).
    pub(crate) fn constraint(&self, across: &[f64]) -> (DVector<f64>, Vec<Vec3>) {
        let c = end_derivative(across, self.edge.at_end());
        let last = across.len() - 1;
        let h_ours = if self.edge.at_end() {
            across[last] - across[last - 1]
        } else {
            across[1] - across[0]
        };
        // Our along-edge knots are the neighbour's scaled by `scale`; its derivative into
        // itself per unit of its across parameter is `inward`. The C1 continuation: our
        // derivative into the net is −β × the neighbour's, β = h^N/h^S (in the neighbour's
        // along units); our along parameter differs from its by an affine map, which does not
        // enter a derivative across.
        let beta = self.step / h_ours;
        let sign = if self.edge.at_end() { 1.0 } else { -1.0 };
        let targets = self.inward.iter().map(|d| d * (sign * beta)).collect();
        (c, targets)
    }

    /// The join's measure for our surface `s` against the neighbour.
    pub(crate) fn measure(&self, s: &BicubicSplineSurface) -> JoinMeasure {
        let count = self.edge_points.len();
        let ours_along = if self.edge.across_u() {
            s.v_knots()
        } else {
            s.u_knots()
        };
        let ours_across = if self.edge.across_u() {
            s.u_knots()
        } else {
            s.v_knots()
        };
        let nb_along = if self.nb_edge.across_u() {
            self.surface.v_knots()
        } else {
            self.surface.u_knots()
        };
        let nb_across = if self.nb_edge.across_u() {
            self.surface.u_knots()
        } else {
            self.surface.v_knots()
        };
        let edge_param = |knots: &[f64], at_end: bool| {
            if at_end {
                (knots[knots.len() - 1], Side::Left)
            } else {
                (knots[0], Side::Right)
            }
        };
        let (s_edge, s_side) = edge_param(ours_across, self.edge.at_end());
        let (n_edge, n_side) = edge_param(nb_across, self.nb_edge.at_end());
        let mut out = JoinMeasure::default();
        for k in 0..count {
            for f in [0.0, 0.5] {
                if f > 0.0 && k + 1 == count {
                    continue;
                }
                let t_s = ours_along[k] + f * (ours_along[(k + 1).min(count - 1)] - ours_along[k]);
                let t_n = if self.reversed {
                    let kk = count - 1 - k;
                    nb_along[kk] - f * (nb_along[kk] - nb_along[kk.saturating_sub(1)])
                } else {
                    nb_along[k] + f * (nb_along[(k + 1).min(count - 1)] - nb_along[k])
                };
                let a = local(s, self.edge.across_u(), s_edge, s_side, t_s);
                let b = local(&self.surface, self.nb_edge.across_u(), n_edge, n_side, t_n);
                let (Some(a), Some(b)) = (a, b) else { continue };
                out.gap = out.gap.max((a.point - b.point).norm());
                let n_b = if a.normal.dot(&b.normal) < 0.0 {
                    -b.normal
                } else {
                    b.normal
                };
                let angle = a.normal.cross(&n_b).norm().atan2(a.normal.dot(&n_b)).to_degrees();
                out.angle_degrees = out.angle_degrees.max(angle);
                let jump = (a.curvature(&a.normal) - b.curvature(&n_b)).abs();
                out.curvature_jump = out.curvature_jump.max(jump);
            }
        }
        out
    }

    /// The report's entry.
    pub(crate) fn report(&self, before: JoinMeasure, after: JoinMeasure) -> JoinReport {
        JoinReport {
            edge: self.edge,
            continuity: self.continuity,
            neighbour: self.source.clone(),
            neighbour_edge: self.nb_edge,
            reversed: self.reversed,
            before,
            after,
        }
    }
}

/// Derivatives of a surface at a point of an edge, named by the edge: `c` across, `e` along.
struct Local {
    point: Vec3,
    normal: Vec3,
    c: Vec3,
    e: Vec3,
    cc: Vec3,
    ce: Vec3,
    ee: Vec3,
}

impl Local {
    /// The normal curvature (against `normal`) in the direction across the edge within the
    /// tangent plane: d = c + γ e ⟂ e, κ = n·(S_cc + 2γ S_ce + γ² S_ee)/|d|².
    fn curvature(&self, normal: &Vec3) -> f64 {
        let gamma = -self.c.dot(&self.e) / self.e.dot(&self.e);
        let d = self.c + self.e * gamma;
        let second = self.cc + self.ce * (2.0 * gamma) + self.ee * (gamma * gamma);
        normal.dot(&second) / d.dot(&d)
    }
}

fn local(s: &BicubicSplineSurface, across_u: bool, edge: f64, side: Side, t: f64) -> Option<Local> {
    let last = if across_u { s.v_knots() } else { s.u_knots() };
    let t_side = if t >= last[last.len() - 1] {
        Side::Left
    } else {
        Side::Right
    };
    let p = |dc: usize, de: usize| {
        if across_u {
            s.partial_from(edge, t, dc, de, side, t_side)
        } else {
            s.partial_from(t, edge, de, dc, t_side, side)
        }
    };
    let c = p(1, 0)?;
    let e = p(0, 1)?;
    let n = c.cross(&e);
    let len = n.norm();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    Some(Local {
        point: p(0, 0)?,
        normal: n / len,
        c,
        e,
        cc: p(2, 0)?,
        ce: p(1, 1)?,
        ee: p(0, 2)?,
    })
}

/// The row a with a·y = s′(t_0) (or s′(t_m) when `at_end`) for the natural cubic spline
/// through the values y over `knots`. O(m): one tridiagonal solve for the moments.
pub(crate) fn end_derivative(knots: &[f64], at_end: bool) -> DVector<f64> {
    let h: Vec<f64> = knots.windows(2).map(|w| w[1] - w[0]).collect();
    let sites = knots.len();
    let mut a = DVector::<f64>::zeros(sites);
    let inner = sites.saturating_sub(2);
    let (end, next, h_end) = if at_end {
        (sites - 1, sites - 2, h[sites - 2])
    } else {
        (0, 1, h[0])
    };
    // s′(t_0) = (y_1 − y_0)/h_0 − h_0 M_1/6;  s′(t_m) = (y_m − y_{m−1})/h + h M_{m−1}/6.
    let sign = if at_end { 1.0 } else { -1.0 };
    a[end] += sign / h_end;
    a[next] -= sign / h_end;
    if inner == 0 {
        return a;
    }
    // M = T⁻¹ B y, T symmetric tridiagonal (interior moments), so the row of M at the moment
    // next to the end is zᵀ B with T z = e.
    let diag: Vec<f64> = (1..=inner).map(|k| 2.0 * (h[k - 1] + h[k])).collect();
    let off: Vec<f64> = (1..inner).map(|k| h[k]).collect();
    let mut e = vec![0.0; inner];
    e[if at_end { inner - 1 } else { 0 }] = 1.0;
    let z = thomas(&diag, &off, &e);
    let factor = sign * h_end / 6.0; // −h/6 at the start, +h/6 at the end
    for (r, &zr) in z.iter().enumerate() {
        let k = r + 1; // interior moment index
        a[k - 1] += factor * zr * 6.0 / h[k - 1];
        a[k] -= factor * zr * (6.0 / h[k] + 6.0 / h[k - 1]);
        a[k + 1] += factor * zr * 6.0 / h[k];
    }
    a
}

/// Solves the symmetric tridiagonal system (diagonal `d`, off-diagonal `o`) for `r`.
fn thomas(d: &[f64], o: &[f64], r: &[f64]) -> Vec<f64> {
    let n = d.len();
    let mut c = vec![0.0; n];
    let mut x = vec![0.0; n];
    for i in 0..n {
        let lower = if i > 0 { o[i - 1] } else { 0.0 };
        let denom = d[i] - if i > 0 { lower * c[i - 1] } else { 0.0 };
        c[i] = if i + 1 < n { o[i] / denom } else { 0.0 };
        x[i] = (r[i] - if i > 0 { lower * x[i - 1] } else { 0.0 }) / denom;
    }
    for i in (0..n.saturating_sub(1)).rev() {
        x[i] -= c[i] * x[i + 1];
    }
    x
}

/// Whether `edge` is a row (a u edge).
pub(crate) fn across_u(edge: JoinEdge) -> bool {
    edge.across_u()
}

/// Node (i, j) at position k along `edge` of a rows × columns net.
pub(crate) fn edge_node(edge: JoinEdge, k: usize, rows: usize, columns: usize) -> (usize, usize) {
    edge.node(k, rows, columns)
}

/// The g1/g2 constraints of the block in the eigenbases (module docs, "The solve"): all
/// across one direction. `lines_are_columns`: the constraints sit on the grid's columns (u
/// edges), one per free column; otherwise on its rows.
pub(crate) struct Joined {
    lines_are_columns: bool,
    /// ĉ_k (over the free rows for u edges, the free columns for v edges).
    c_hat: Vec<DVector<f64>>,
    /// τ̂_k per coordinate (over the other direction's free lines).
    t_hat: Vec<[DVector<f64>; 3]>,
    /// With a reduced basis, the constraints at the sites ([`Joined::correct_at_sites`]): c_k
    /// over the free lines across, τ_k per coordinate over the other direction's free lines,
    /// and (CᵀC)⁻¹.
    at_sites: Option<AtSites>,
}

/// The constraints at the sites, c_kᵀ X[:, l] = τ_k,l (module docs, "Reduced bases").
struct AtSites {
    c: Vec<DVector<f64>>,
    tau: Vec<[DVector<f64>; 3]>,
    ctc_inverse: DMatrix<f64>,
}

impl Joined {
    /// The constraints of the g1/g2 joins in `prepared` (None when there are none), for the
    /// block of `free_rows` × `free_cols` with held values `data(i, j)` elsewhere, over our
    /// knots `u_knots`, `v_knots`; `shift` the block's data shift by a reduced direction's held
    /// ends (added back to the solution, so taken from the targets in the spectral space). The
    /// caller has refused g1/g2 joins across both directions.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        prepared: &[Prepared],
        u_knots: &[f64],
        v_knots: &[f64],
        free_rows: &[usize],
        free_cols: &[usize],
        data: &dyn Fn(usize, usize) -> Vec3,
        spectral: &Spectral,
        shift: Option<&Planes>,
    ) -> Option<Self> {
        let held: Vec<&Prepared> = prepared.iter().filter(|p| p.holds_tangent()).collect();
        let first = held.first()?;
        let lines_are_columns = first.edge.across_u();
        let (across_knots, mine, other) = if lines_are_columns {
            (u_knots, free_rows, free_cols)
        } else {
            (v_knots, free_cols, free_rows)
        };
        let across_count = across_knots.len();
        let basis = if lines_are_columns {
            &spectral.u
        } else {
            &spectral.v
        };
        let other_basis = if lines_are_columns {
            &spectral.v
        } else {
            &spectral.u
        };
        let mut c_hat = Vec::new();
        let mut t_hat = Vec::new();
        let mut c_sites = Vec::new();
        let mut tau_sites = Vec::new();
        for p in held {
            let (c, targets) = p.constraint(across_knots);
            let c_free = DVector::from_iterator(mine.len(), mine.iter().map(|&q| c[q]));
            let held_lines: Vec<usize> = (0..across_count).filter(|q| !mine.contains(q)).collect();
            let tau: [DVector<f64>; 3] = std::array::from_fn(|coord| {
                DVector::from_iterator(
                    other.len(),
                    other.iter().map(|&line| {
                        let mut t = targets[line][coord];
                        for &q in &held_lines {
                            let node = if lines_are_columns {
                                data(q, line)
                            } else {
                                data(line, q)
                            };
                            t -= c[q] * node[coord];
                        }
                        t
                    }),
                )
            });
            // The shift's part of c_kᵀ X[:, l] is known: the spectral part must meet the rest.
            let shifted: [DVector<f64>; 3] = std::array::from_fn(|coord| {
                let mut t = tau[coord].clone();
                if let Some(shift) = shift {
                    let plane = &shift[coord];
                    for (l, entry) in t.iter_mut().enumerate() {
                        *entry -= c_free
                            .iter()
                            .enumerate()
                            .map(|(q, c)| {
                                c * if lines_are_columns {
                                    plane[(q, l)]
                                } else {
                                    plane[(l, q)]
                                }
                            })
                            .sum::<f64>();
                    }
                }
                t
            });
            c_hat.push(basis.t_vector(&c_free));
            t_hat.push(shifted.map(|t| other_basis.t_vector(&t)));
            c_sites.push(c_free);
            tau_sites.push(tau);
        }
        let at_sites = spectral.is_reduced().then(|| {
            let k = c_sites.len();
            let ctc = DMatrix::from_fn(k, k, |a, b| c_sites[a].dot(&c_sites[b]));
            AtSites {
                ctc_inverse: ctc.try_inverse().unwrap_or_else(|| DMatrix::zeros(k, k)),
                c: c_sites,
                tau: tau_sites,
            }
        });
        Some(Self {
            lines_are_columns,
            c_hat,
            t_hat,
            at_sites,
        })
    }

    /// With a reduced basis, the solution `x` at the sites (its shift added) brought onto the
    /// constraints exactly. The spectral correction meets them within the reduced space only:
    /// τ̂ = Tᵀτ is τ's projection along the edge, and the held edge's shift its projection, so
    /// the derivative across the edge misses the neighbour's by their parts outside that space
    /// (small where the basis resolves the edge).
    /// Each line takes the least change that meets them, x_l −= C (CᵀC)⁻¹ (Cᵀ x_l − τ_l),
    /// C = [c_k] (the end-derivative rows, which decay away from the edge within a few
    /// lines). Exact bases meet the constraints already (nothing is done). O(m·n).
    pub(crate) fn correct_at_sites(&self, x: &mut Planes) {
        let Some(sites) = &self.at_sites else {
            return;
        };
        let k = sites.c.len();
        let mut line = Vec::new();
        for (coord, plane) in x.iter_mut().enumerate() {
            let lines = if self.lines_are_columns {
                plane.ncols()
            } else {
                plane.nrows()
            };
            for l in 0..lines {
                line.clear();
                if self.lines_are_columns {
                    line.extend(plane.column(l).iter().copied());
                } else {
                    line.extend(plane.row(l).iter().copied());
                }
                let r = DVector::from_fn(k, |a, _| {
                    sites.c[a].iter().zip(&line).map(|(c, v)| c * v).sum::<f64>() - sites.tau[a][coord][l]
                });
                let mu = &sites.ctc_inverse * r;
                for (q, &v) in line.iter().enumerate() {
                    let corrected = v - (0..k).map(|a| sites.c[a][q] * mu[a]).sum::<f64>();
                    if self.lines_are_columns {
                        plane[(q, l)] = corrected;
                    } else {
                        plane[(l, q)] = corrected;
                    }
                }
            }
        }
    }

    /// g_ab at the entry (q along the constrained direction, l the line).
    fn g(&self, spectral: &Spectral, w: Weights, q: usize, l: usize) -> f64 {
        let s = if self.lines_are_columns {
            spectral.s(q, l, w)
        } else {
            spectral.s(l, q, w)
        };
        1.0 / (1.0 + s)
    }

    fn lines(&self, x: &Planes) -> (usize, usize) {
        let (r, c) = x[0].shape();
        if self.lines_are_columns {
            (c, r)
        } else {
            (r, c)
        }
    }

    /// Line l's g along it (into `g`, reused between lines) and its Schur blocks W_l and W′_l.
    fn blocks(
        &self,
        spectral: &Spectral,
        weights: Weights,
        l: usize,
        g: &mut Vec<f64>,
        along: usize,
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        g.clear();
        g.extend((0..along).map(|q| self.g(spectral, weights, q, l)));
        let k = self.c_hat.len();
        let mut w = DMatrix::zeros(k, k);
        let mut w2 = DMatrix::zeros(k, k);
        for (q, &gq) in g.iter().enumerate() {
            for a in 0..k {
                for b in 0..k {
                    let cc = self.c_hat[a][q] * self.c_hat[b][q];
                    w[(a, b)] += cc * gq;
                    w2[(a, b)] += cc * gq * gq;
                }
            }
        }
        (w, w2)
    }

    /// Corrects the unconstrained X̂₀ (at the weights `w`) to the constrained X̂. O(m·n).
    pub(crate) fn correct(&self, x: &mut Planes, spectral: &Spectral, w: Weights) {
        self.correct_with_trace_loss(x, spectral, w);
    }

    /// [`Joined::correct`], and what the constraints take from the smoother's trace at the
    /// weights `w`, Σ_l tr(W_l⁻¹ W′_l): each line's g and blocks made once for both (GCV
    /// needs both at every trial pair). O(m·n).
    pub(crate) fn correct_with_trace_loss(&self, x: &mut Planes, spectral: &Spectral, w: Weights) -> f64 {
        let (lines, along) = self.lines(x);
        let mut g = Vec::with_capacity(along);
        let mut row = Vec::with_capacity(along);
        let mut loss = 0.0;
        for l in 0..lines {
            let (block, block2) = self.blocks(spectral, w, l, &mut g, along);
            let Some(lu) = block.try_inverse() else {
                continue;
            };
            loss += (&lu * block2).trace();
            for (coord, plane) in x.iter_mut().enumerate() {
                // the line as a slice: a column of the (column-major) plane in place, or a row
                // copied out and back
                if self.lines_are_columns {
                    let rows = plane.nrows();
                    let column = &mut plane.as_mut_slice()[l * rows..(l + 1) * rows];
                    self.correct_line(column, &lu, &g, coord, l);
                } else {
                    row.clear();
                    row.extend(plane.row(l).iter().copied());
                    self.correct_line(&mut row, &lu, &g, coord, l);
                    for (q, &v) in row.iter().enumerate() {
                        plane[(l, q)] = v;
                    }
                }
            }
        }
        loss
    }

    /// One line's values (`line`, coordinate `coord`) corrected to meet the constraints:
    /// r = Ĉ x − τ̂, μ = W⁻¹ r, x_q −= g_q Σ_a ĉ_aq μ_a.
    fn correct_line(&self, line: &mut [f64], w_inverse: &DMatrix<f64>, g: &[f64], coord: usize, l: usize) {
        let k = self.c_hat.len();
        let r = DVector::from_fn(k, |a, _| {
            let c = self.c_hat[a].as_slice();
            c.iter().zip(line.iter()).map(|(c, v)| c * v).sum::<f64>() - self.t_hat[a][coord][l]
        });
        let mu = w_inverse * r;
        for (q, (entry, &gq)) in line.iter_mut().zip(g).enumerate() {
            let d: f64 = (0..k).map(|a| self.c_hat[a][q] * mu[a]).sum();
            *entry -= gq * d;
        }
    }
}
