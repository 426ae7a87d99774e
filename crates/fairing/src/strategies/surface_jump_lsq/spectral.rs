//! The Kronecker-sum system of the free block and its exact solution in the eigenbases of
//! the two directions' jump operators.
//!
//! On a block of free rows R × free columns C the normal equations of the method (module
//! docs of [`super`]) are, coordinate by coordinate,
//!
//! ```text
//! X + λ_u K_u X + λ_v X K_v = Y − (λ_u B_u + λ_v B_v),
//! ```
//!
//! K_u = K[R, R] and K_v = K[C, C] the principal submatrices of the two Gram matrices, Y the
//! data of the block and B_u, B_v the coupling to the held rows and columns. With
//! K_u = U diag(μ) Uᵀ and K_v = V diag(ν) Vᵀ, X̂ = Uᵀ X V solves the system entry by entry:
//! X̂_ab = (Ŷ_ab − λ_u B̂u_ab − λ_v B̂v_ab) / (1 + λ_u μ_a + λ_v ν_b). The residual and the
//! trace of the smoother are sums over the same entries, so a GCV score costs O(|R|·|C|) per
//! pair (λ_u, λ_v) once Ŷ and B̂ are known. A long direction's eigenbasis is that of its
//! reduced basis (module `reduced`, [`Basis::Reduced`]), orthonormal at the sites as well, and
//! the RSS then includes the data outside it (`Energies::with_outside`). Cost: the two eigendecompositions O(|R|³ + |C|³) (faer's, 2-4× faster than nalgebra's at 200-2000 sites), a transform O(|R|·|C|·(|R| + |C|)).

use nalgebra::{DMatrix, DVector};

use curve_repr::Vec3;

use super::reduced::Reduced;

/// Eigenvalues at most this fraction of the largest are taken as 0 (the null space; see
/// [`clean`]).
const NULL_EIGENVALUE: f64 = 1e-25;

/// The eigenbases of the block's two operators.
pub(crate) struct Spectral {
    pub u: Basis,
    pub mu: Vec<f64>,
    pub v: Basis,
    pub nu: Vec<f64>,
}

/// One direction's orthonormal basis T (sites × entries) diagonalising its penalty: the
/// eigenvectors of K (exact), or T = N L⁻ᵀ U of a reduced basis (module `reduced`).
pub(crate) enum Basis {
    Exact(DMatrix<f64>),
    Reduced(Reduced),
}

impl Basis {
    /// Tᵀ y; `data`: y at the sites, else (a reduced basis's coupling) in its coefficients.
    fn t_left(&self, y: &DMatrix<f64>, data: bool) -> DMatrix<f64> {
        match self {
            Basis::Exact(u) => &u.transpose() * y,
            Basis::Reduced(r) => r.t_left(y, data),
        }
    }

    /// y T, `data` as for [`t_left`](Self::t_left).
    fn right(&self, y: &DMatrix<f64>, data: bool) -> DMatrix<f64> {
        match self {
            Basis::Exact(v) => y * v,
            Basis::Reduced(r) => r.right(y, data),
        }
    }

    /// T x̂.
    fn left(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        match self {
            Basis::Exact(u) => u * x,
            Basis::Reduced(r) => r.left(x),
        }
    }

    /// x̂ Tᵀ.
    fn t_right(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        match self {
            Basis::Exact(v) => x * &v.transpose(),
            Basis::Reduced(r) => r.t_right(x),
        }
    }

    /// Tᵀ c for a vector at the sites.
    pub(crate) fn t_vector(&self, c: &DVector<f64>) -> DVector<f64> {
        match self {
            Basis::Exact(u) => u.transpose() * c,
            Basis::Reduced(r) => r
                .t_left(&DMatrix::from_column_slice(c.len(), 1, c.as_slice()), true)
                .column(0)
                .into_owned(),
        }
    }
}

/// Three coordinate planes of a block, each |R| × |C|.
pub(crate) type Planes = [DMatrix<f64>; 3];

/// The penalty weights of the two directions, λ_u on the u-jumps and λ_v on the v-jumps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Weights {
    pub u: f64,
    pub v: f64,
}

impl Weights {
    /// One weight on both directions.
    pub(crate) fn both(lambda: f64) -> Self {
        Self { u: lambda, v: lambda }
    }

    /// Both weights times `factor`.
    pub(crate) fn scaled(self, factor: f64) -> Self {
        Self {
            u: self.u * factor,
            v: self.v * factor,
        }
    }
}

/// The coupling of the block to the held lines, split by direction: B_u = K_u[R, Rh] P⁰[Rh, C]
/// (held rows) and B_v = P⁰[R, Ch] K_v[Ch, C] (held columns).
pub(crate) struct Coupling {
    pub u: Planes,
    pub v: Planes,
}

impl Coupling {
    /// λ_u B_u + λ_v B_v at one entry of plane `c`.
    pub(crate) fn at(&self, c: usize, a: usize, b: usize, w: Weights) -> f64 {
        w.u * self.u[c][(a, b)] + w.v * self.v[c][(a, b)]
    }

    /// λ_u B_u + λ_v B_v.
    pub(crate) fn combined(&self, w: Weights) -> Planes {
        std::array::from_fn(|c| &self.u[c] * w.u + &self.v[c] * w.v)
    }
}

impl Spectral {
    /// The exact eigenbases of K_u and K_v.
    #[cfg(test)]
    pub(super) fn new(ku: DMatrix<f64>, kv: DMatrix<f64>) -> Self {
        let (mu, u) = symmetric_eigen(&ku);
        let (nu, v) = symmetric_eigen(&kv);
        Self::from_parts((Basis::Exact(u), mu), (Basis::Exact(v), nu))
    }

    /// The spectral form from each direction's basis and penalty eigenvalues (those below
    /// [`NULL_EIGENVALUE`] of the largest taken as 0).
    pub(super) fn from_parts(u: (Basis, Vec<f64>), v: (Basis, Vec<f64>)) -> Self {
        Self {
            mu: clean(&u.1),
            u: u.0,
            nu: clean(&v.1),
            v: v.0,
        }
    }

    /// Whether each reduced direction's basis resolves the fit at the weights `w`: its
    /// equivalent degrees of freedom along the direction alone, Σ_a 1/(1 + λ μ_a), are at most
    /// `share` of the basis's size. O(|R| + |C|).
    pub(super) fn resolves(&self, w: Weights, share: f64) -> bool {
        let within = |basis: &Basis, values: &[f64], lambda: f64| {
            !matches!(basis, Basis::Reduced(_))
                || values.iter().map(|&m| 1.0 / (1.0 + lambda * m)).sum::<f64>()
                    <= share * values.len() as f64
        };
        within(&self.u, &self.mu, w.u) && within(&self.v, &self.nu, w.v)
    }

    /// N_uE C N_vEᵀ at the block's sites for both directions reduced with held ends, `corners(c)`
    /// the held nodes where held rows and columns cross (held rows × held columns, coordinate
    /// c): the corners' part of the two directions' held-end shifts. Empty planes when a
    /// direction is exact.
    pub(super) fn corner_product(&self, corners: impl Fn(usize) -> DMatrix<f64>) -> Planes {
        std::array::from_fn(|c| match (&self.u, &self.v) {
            (Basis::Reduced(u), Basis::Reduced(v)) => {
                let along_u = u.held_parts(&corners(c)).0; // N_uE C: sites × held columns
                v.held_parts(&along_u.transpose()).0.transpose()
            }
            _ => DMatrix::zeros(0, 0),
        })
    }

    /// Each plane's columns projected onto the u basis, U Uᵀ X (X at the sites).
    pub(super) fn project_u(&self, x: &Planes) -> Planes {
        x.clone().map(|p| self.u.left(&self.u.t_left(&p, true)))
    }

    /// Each plane's rows projected onto the v basis, X V Vᵀ (X at the sites).
    pub(super) fn project_v(&self, x: &Planes) -> Planes {
        x.clone().map(|p| self.v.t_right(&self.v.right(&p, true)))
    }

    /// Whether either direction has a reduced basis.
    pub(super) fn is_reduced(&self) -> bool {
        matches!(self.u, Basis::Reduced(_)) || matches!(self.v, Basis::Reduced(_))
    }

    /// Uᵀ X V for each plane.
    pub(super) fn forward(&self, x: &Planes) -> Planes {
        self.forward_with(x, true, true)
    }

    /// Uᵀ X V for each plane, X at the sites in u (`u_data`) or in a reduced u-basis's
    /// coefficients (a coupling through its penalty), likewise in v.
    pub(super) fn forward_with(&self, x: &Planes, u_data: bool, v_data: bool) -> Planes {
        x.clone()
            .map(|p| self.v.right(&self.u.t_left(&p, u_data), v_data))
    }

    /// U X̂ Vᵀ for each plane.
    pub(super) fn back(&self, x: &Planes) -> Planes {
        x.clone().map(|p| self.v.t_right(&self.u.left(&p)))
    }

    /// s_ab = λ_u μ_a + λ_v ν_b, the entry's penalty eigenvalue.
    pub(super) fn s(&self, a: usize, b: usize, w: Weights) -> f64 {
        w.u * self.mu[a] + w.v * self.nu[b]
    }

    /// X̂ at the weights `w`.
    pub(super) fn solve_hat(&self, y: &Planes, coupling: Option<&Coupling>, w: Weights) -> Planes {
        let mut out = y.clone();
        for (c, plane) in out.iter_mut().enumerate() {
            for b in 0..plane.ncols() {
                for a in 0..plane.nrows() {
                    let mut rhs = plane[(a, b)];
                    if let Some(cp) = coupling {
                        rhs -= cp.at(c, a, b, w);
                    }
                    plane[(a, b)] = rhs / (1.0 + self.s(a, b, w));
                }
            }
        }
        out
    }

    /// The trace of the smoother at the weights `w`, Σ_ab 1/(1 + λ_u μ_a + λ_v ν_b) (per
    /// coordinate).
    pub(super) fn trace(&self, w: Weights) -> f64 {
        let mut trace = 0.0;
        for &nu in &self.nu {
            for &mu in &self.mu {
                trace += 1.0 / (1.0 + w.u * mu + w.v * nu);
            }
        }
        trace
    }

    /// (RSS, trace of the smoother) at the weights `w`: RSS = Σ |X̂ − Ŷ|² over the three
    /// planes, from the data's [`Energies`]; the trace as [`trace`](Self::trace). O(|R|·|C|).
    pub(super) fn rss_trace(&self, e: &Energies, w: Weights) -> (f64, f64) {
        let (rows, cols) = e.yy.shape();
        let mut rss = 0.0;
        let mut trace = 0.0;
        for b in 0..cols {
            for a in 0..rows {
                let s = w.u * self.mu[a] + w.v * self.nu[b];
                let g = 1.0 / (1.0 + s);
                trace += g;
                // X̂ − Ŷ = −(s Ŷ + λ_u B̂u + λ_v B̂v) / (1 + s), squared and summed over the
                // coordinates.
                let mut r2 = s * s * e.yy[(a, b)];
                if let Some([yu, yv, uu, uv, vv]) = &e.cross {
                    r2 += 2.0 * s * (w.u * yu[(a, b)] + w.v * yv[(a, b)])
                        + w.u * w.u * uu[(a, b)]
                        + 2.0 * w.u * w.v * uv[(a, b)]
                        + w.v * w.v * vv[(a, b)];
                }
                rss += g * g * r2;
            }
        }
        (rss + e.outside, trace)
    }
}

/// The transformed data's energies per spectral entry, summed over the three coordinates:
/// Σ_c Ŷ², and with a coupling Σ_c Ŷ B̂u, Σ_c Ŷ B̂v, Σ_c B̂u², Σ_c B̂u B̂v, Σ_c B̂v². The RSS at
/// any weights is then one term per entry ([`Spectral::rss_trace`]).
pub(crate) struct Energies {
    yy: DMatrix<f64>,
    cross: Option<[DMatrix<f64>; 5]>,
    /// Σ_c |Y − U Ŷ Vᵀ|²: the data outside a reduced basis's space (0 for exact bases).
    outside: f64,
}

impl Energies {
    pub(crate) fn new(y: &Planes, coupling: Option<&Coupling>) -> Self {
        let (rows, cols) = y[0].shape();
        let sum = |f: &dyn Fn(usize, usize, usize) -> f64| {
            DMatrix::from_fn(rows, cols, |a, b| (0..3).map(|c| f(c, a, b)).sum())
        };
        Self {
            yy: sum(&|c, a, b| y[c][(a, b)] * y[c][(a, b)]),
            cross: coupling.map(|k| {
                [
                    sum(&|c, a, b| y[c][(a, b)] * k.u[c][(a, b)]),
                    sum(&|c, a, b| y[c][(a, b)] * k.v[c][(a, b)]),
                    sum(&|c, a, b| k.u[c][(a, b)] * k.u[c][(a, b)]),
                    sum(&|c, a, b| k.u[c][(a, b)] * k.v[c][(a, b)]),
                    sum(&|c, a, b| k.v[c][(a, b)] * k.v[c][(a, b)]),
                ]
            }),
            outside: 0.0,
        }
    }

    /// With the data's part outside a reduced basis's space, Σ_c |Y − U Ŷ Vᵀ|² (every fit's
    /// RSS includes it).
    pub(crate) fn with_outside(mut self, outside: f64) -> Self {
        self.outside = outside;
        self
    }
}

/// The eigenvalues and orthonormal eigenvectors (columns) of a symmetric matrix, by faer's
/// self-adjoint eigendecomposition (its lower triangle read): O(m³), several times faster
/// than nalgebra's `SymmetricEigen` at m in the hundreds to thousands.
pub(crate) fn symmetric_eigen(k: &DMatrix<f64>) -> (Vec<f64>, DMatrix<f64>) {
    let m = k.nrows();
    let a = faer::Mat::<f64>::from_fn(m, m, |i, j| k[(i, j)]);
    match a.self_adjoint_eigen(faer::Side::Lower) {
        Ok(evd) => {
            let (s, u) = (evd.S().column_vector(), evd.U());
            (
                (0..m).map(|i| s[i]).collect(),
                DMatrix::from_fn(m, m, |i, j| u[(i, j)]),
            )
        }
        // faer's iteration did not converge (not seen on these operators): nalgebra's.
        Err(_) => {
            let e = nalgebra::SymmetricEigen::new(k.clone());
            (e.eigenvalues.iter().copied().collect(), e.eigenvectors)
        }
    }
}

/// The eigenpairs of a Gram operator K = DᵀD (`values`, `vectors` from K's eigendecomposition)
/// made accurate at the bottom of the spectrum, where K's own are not: K squares D's condition
/// number, so every eigenvalue below ~10⁻¹⁶ of the largest comes out as round-off. For the
/// jump penalty the spectrum falls like (k/m)⁸ over a direction of m sites, so on 60 sites the
/// 3rd and 4th modes (the smoothest after the lines) are already below it, and on 800 sites
/// the first 30 are (module docs, "The spectrum's bottom"). The
/// eigenvectors of the computed eigenvalues below [`CLUSTER`] of the largest span the true
/// invariant subspace to ~10⁻¹² (round-off over the distance to the eigenvalues outside it);
/// within it the singular value decomposition of D V_c
/// (`apply_d(V_c)` = D V_c) gives D's singular values, whose squares are K's eigenvalues to
/// full relative accuracy, and rotates V_c to their vectors. O(r·c²) for c such eigenvalues
/// and r rows of D.
pub(crate) fn refine_bottom(
    values: &mut [f64],
    vectors: &mut DMatrix<f64>,
    apply_d: impl Fn(&DMatrix<f64>) -> DMatrix<f64>,
) {
    let top = values.iter().fold(0.0f64, |m, &x| m.max(x));
    let cluster: Vec<usize> = (0..values.len())
        .filter(|&i| values[i] <= CLUSTER * top)
        .collect();
    if cluster.is_empty() || top <= 0.0 {
        return;
    }
    let vc = DMatrix::from_fn(vectors.nrows(), cluster.len(), |i, j| vectors[(i, cluster[j])]);
    let b = apply_d(&vc);
    let fb = faer::Mat::<f64>::from_fn(b.nrows(), b.ncols(), |i, j| b[(i, j)]);
    // The thin decomposition has all of V when D has at least as many rows as the cluster.
    let svd = if b.nrows() >= b.ncols() {
        fb.thin_svd()
    } else {
        fb.svd()
    };
    let Ok(svd) = svd else {
        // faer's iteration did not converge (not seen): K's values stand, its round-off
        // (below 10⁻¹¹ of the largest) taken as null as before the refinement.
        for k in cluster {
            if values[k] <= 1e-11 * top {
                values[k] = 0.0;
            }
        }
        return;
    };
    let (sv, q) = (svd.S().column_vector(), svd.V());
    let c = cluster.len();
    let q = DMatrix::from_fn(c, c, |i, j| q[(i, j)]);
    let rotated = &vc * q;
    for (j, &k) in cluster.iter().enumerate() {
        // D has fewer rows than the cluster has vectors only on tiny directions: the rest
        // of V's columns are D's null space there.
        values[k] = if j < sv.nrows() { sv[j] * sv[j] } else { 0.0 };
        vectors.set_column(k, &rotated.column(j));
    }
}

/// Eigenvalues of K below this fraction of the largest are re-derived by [`refine_bottom`]
/// (about a third of a direction's modes). At 10⁻⁸ the null space came out at up to 2·10⁻²⁵
/// of the largest on 60 sites, too near the smoothest mode of 800 sites (~10⁻²²); at 10⁻⁴ at
/// most 5·10⁻²⁹.
const CLUSTER: f64 = 1e-4;

/// The operators are PSD, and their null space (the lines of an open direction, the constants
/// of a closed one) comes out of [`refine_bottom`] at eigenvalues below 10⁻²⁸ of the largest,
/// which a large λ would turn into a shrinkage; the smoothest mode that is not null lies at
/// ~10⁻²² of it on 800 sites. Below [`NULL_EIGENVALUE`] of the largest an eigenvalue is taken
/// as 0.
fn clean(values: &[f64]) -> Vec<f64> {
    let top = values.iter().fold(0.0f64, |m, &x| m.max(x));
    values
        .iter()
        .map(|&x| if x <= NULL_EIGENVALUE * top { 0.0 } else { x })
        .collect()
}

/// Splits points of a block into three planes.
pub(crate) fn planes(rows: usize, cols: usize, at: impl Fn(usize, usize) -> Vec3) -> Planes {
    std::array::from_fn(|c| DMatrix::from_fn(rows, cols, |a, b| at(a, b)[c]))
}
