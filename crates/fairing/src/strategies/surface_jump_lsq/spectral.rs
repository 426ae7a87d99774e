//! The Kronecker-sum system of the free block and its exact solution in the eigenbases of
//! the two directions' jump operators.
//!
//! On a block of free rows R × free columns C the normal equations of the method (module
//! docs of [`super`]) are, coordinate by coordinate,
//!
//! ```text
//! X + λ (K_u X + X K_v) = Y − λ B,
//! ```
//!
//! K_u = K[R, R] and K_v = K[C, C] the principal submatrices of the two Gram matrices, Y the
//! data of the block and B the coupling to the held lines. With K_u = U diag(μ) Uᵀ and
//! K_v = V diag(ν) Vᵀ, X̂ = Uᵀ X V solves the system entry by entry:
//! X̂_ab = (Ŷ_ab − λ B̂_ab) / (1 + λ (μ_a + ν_b)). The residual and the trace of the smoother
//! are sums over the same entries, so a GCV score costs O(|R|·|C|) per λ once Ŷ and B̂ are
//! known. Cost: the two eigendecompositions O(|R|³ + |C|³), a transform O(|R|·|C|·(|R| + |C|)).

use nalgebra::{DMatrix, SymmetricEigen};

use curve_repr::Vec3;

/// Eigenvalues at most this fraction of the largest are taken as 0 (the null space).
const NULL_EIGENVALUE: f64 = 1e-11;

/// The eigenbases of the block's two operators.
pub(crate) struct Spectral {
    pub u: DMatrix<f64>,
    pub mu: Vec<f64>,
    pub v: DMatrix<f64>,
    pub nu: Vec<f64>,
}

/// Three coordinate planes of a block, each |R| × |C|.
pub(crate) type Planes = [DMatrix<f64>; 3];

impl Spectral {
    pub(super) fn new(ku: DMatrix<f64>, kv: DMatrix<f64>) -> Self {
        let eu = SymmetricEigen::new(ku);
        let ev = SymmetricEigen::new(kv);
        // The operators are PSD; round-off leaves their null space (the lines of an open
        // direction) at eigenvalues of ~1e-16 of the largest, which a large λ would turn into
        // a shrinkage. Below NULL_EIGENVALUE of the largest an eigenvalue is taken as 0.
        let clean = |values: &nalgebra::DVector<f64>| {
            let top = values.iter().fold(0.0f64, |m, &x| m.max(x));
            values
                .iter()
                .map(|&x| if x <= NULL_EIGENVALUE * top { 0.0 } else { x })
                .collect()
        };
        Self {
            mu: clean(&eu.eigenvalues),
            u: eu.eigenvectors,
            nu: clean(&ev.eigenvalues),
            v: ev.eigenvectors,
        }
    }

    /// Uᵀ X V for each plane.
    pub(super) fn forward(&self, x: &Planes) -> Planes {
        let ut = self.u.transpose();
        x.clone().map(|p| &ut * p * &self.v)
    }

    /// U X̂ Vᵀ for each plane.
    pub(super) fn back(&self, x: &Planes) -> Planes {
        let vt = self.v.transpose();
        x.clone().map(|p| &self.u * p * &vt)
    }

    /// s_ab = μ_a + ν_b.
    pub(super) fn s(&self, a: usize, b: usize) -> f64 {
        self.mu[a] + self.nu[b]
    }

    /// X̂ at λ.
    pub(super) fn solve_hat(&self, y: &Planes, coupling: Option<&Planes>, lambda: f64) -> Planes {
        let mut out = y.clone();
        for (c, plane) in out.iter_mut().enumerate() {
            for b in 0..plane.ncols() {
                for a in 0..plane.nrows() {
                    let mut rhs = plane[(a, b)];
                    if let Some(cp) = coupling {
                        rhs -= lambda * cp[c][(a, b)];
                    }
                    plane[(a, b)] = rhs / (1.0 + lambda * self.s(a, b));
                }
            }
        }
        out
    }

    /// (RSS, trace of the smoother) at λ: RSS = Σ |X̂ − Ŷ|² over the three planes, the
    /// trace Σ_ab 1/(1 + λ s_ab) (per coordinate).
    pub(super) fn rss_trace(&self, y: &Planes, coupling: Option<&Planes>, lambda: f64) -> (f64, f64) {
        let (rows, cols) = y[0].shape();
        let mut rss = 0.0;
        let mut trace = 0.0;
        for b in 0..cols {
            for a in 0..rows {
                let g = 1.0 / (1.0 + lambda * self.s(a, b));
                trace += g;
                for c in 0..3 {
                    let yv = y[c][(a, b)];
                    let cv = coupling.map_or(0.0, |cp| cp[c][(a, b)]);
                    // X̂ − Ŷ = −λ (s Ŷ + B̂) / (1 + λ s)
                    let r = lambda * (self.s(a, b) * yv + cv) * g;
                    rss += r * r;
                }
            }
        }
        (rss, trace)
    }
}

/// Splits points of a block into three planes.
pub(crate) fn planes(rows: usize, cols: usize, at: impl Fn(usize, usize) -> Vec3) -> Planes {
    std::array::from_fn(|c| DMatrix::from_fn(rows, cols, |a, b| at(a, b)[c]))
}
