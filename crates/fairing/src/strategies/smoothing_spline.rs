//! The cubic smoothing spline, the baseline the papers call MST (Han et al. §5 compare against
//! it), in csaps's convention (de Boor's `csaps`, the Python `csaps` package).
//!
//! Given parameters t_0 < … < t_{n−1}, data y_i (scalars for a function y(x), points for a
//! parametric curve, smoothed coordinate by coordinate) and weights w_i > 0, the spline f
//! minimises
//!
//! p · Σ w_i |y_i − f(t_i)|² + (1 − p) · ∫ |f''(t)|² dt,   p ∈ [0, 1],
//!
//! p = 0 giving the weighted least-squares straight line, p = 1 the natural interpolating
//! cubic spline. The minimiser is a natural cubic spline with knots t_i (Reinsch 1967); with
//! h_i = t_{i+1} − t_i, Q the n×(n−2) matrix of second divided differences
//! (`Q[i−1][i] = 1/h_{i−1}`, `Q[i][i] = −1/h_{i−1} − 1/h_i`, `Q[i+1][i] = 1/h_i`), R the
//! (n−2)×(n−2) tridiagonal matrix `R[i][i] = (h_{i−1} + h_i)/3`, `R[i][i+1] = h_i/6`, and
//! Σ = W⁻¹ = diag(1/w_i), the solution is (Reinsch's equations, as csaps solves them, scaled
//! by 1/6):
//!
//! (p R + (1 − p) QᵀΣQ) u = Qᵀ y,   γ = p u,   f = y − (1 − p) Σ Q u,
//!
//! with γ the second derivatives at the interior knots (0 at both ends) and f the spline's
//! values at the knots. The matrix is symmetric positive definite and pentadiagonal, so the
//! solve is a banded LDLᵀ in O(n).
//!
//! A weight w_i = +∞ (σ_i = 0) makes point i an interpolation constraint: f_i = y_i exactly,
//! bit for bit. This is how [`SmoothingSplineFairing`] honours fixed points and clamped ends.
//!
//! Choosing p when it is not given ([`SmoothingRule`]):
//! - `Trace`: csaps's default, p = 1 / (1 + tr(R) / tr(QᵀΣQ)), which makes
//!   p·tr(R) = (1 − p)·tr(QᵀΣQ) (csaps writes it with 6R and 6(1−p), the same rule).
//! - `Gcv`: generalised cross-validation (Craven & Wahba 1979), minimise
//!   GCV(p) = n · Σ w_i |y_i − f_i|² / tr(I − A(p))² over p, A(p) the influence matrix
//!   (f = A y). Since I − A = (1 − p) Σ Q M⁻¹ Qᵀ with M = pR + (1−p)QᵀΣQ, and
//!   Σ w_i |y_i − f_i|² = (1 − p)² Σ σ_i |(Qu)_i|², the factors (1 − p)² cancel:
//!   GCV(p) = n · Σ σ_i |(Qu)_i|² / tr(M⁻¹ QᵀΣQ)². QᵀΣQ is pentadiagonal, so the trace needs
//!   only the band |i − j| ≤ 2 of M⁻¹, which Hutchinson & de Hoog's recurrence gives in O(n).
//!   Each evaluation is O(n). The search runs over ρ = log10((1 − p)/p): a grid of step 1/4
//!   over ±8 decades around the trace rule's ρ (which carries the data's scale), followed
//!   outwards in the same steps (up to 24 decades more) while GCV falls if its least value
//!   is on the grid's edge (dense noisy data need far more smoothing than the trace rule
//!   says), then a golden-section refinement in the best grid cell to |Δρ| < 1e-7. For parametric data the
//!   residual sum runs over all coordinates (one p for the curve; the influence matrix is the
//!   same for every coordinate).
//! - `Gml`: generalised maximum likelihood (Wahba 1985, *A comparison of GCV and GML for
//!   choosing the smoothing parameter in the generalized spline smoothing problem*, Ann.
//!   Statist. 13, §2; Wahba 1990 §4.8; the restricted likelihood, REML, of the spline's
//!   Bayesian model), minimise V_ML(p) = yᵀW(I − A)y / det⁺(I − A)^(1/r) over p, r the rank of I − A
//!   and det⁺ the product of its non-zero eigenvalues. In the Reinsch form (Green & Silverman
//!   1994, *Nonparametric regression and generalized linear models*, ch. 2 for Q, R and
//!   Reinsch's algorithm, ch. 3 for weights and the smoothing parameter):
//!   * the quadratic form: the minimum of the functional divided by p,
//!     Σ w_i |y_i − f_i|² + λ γᵀRγ with λ = (1 − p)/p, is
//!     (1 − p)² uᵀBu + (1 − p) p uᵀRu = (1 − p) uᵀMu = (1 − p) (Qᵀy)ᵀ M⁻¹ (Qᵀy), B = QᵀΣQ,
//!     and equals yᵀW(I − A)y (W(y − f) = λ K f, K = QR⁻¹Qᵀ);
//!   * the determinant: I − A = (1 − p) Σ Q M⁻¹ Qᵀ has the non-zero eigenvalues of
//!     (1 − p) M⁻¹B (XY and YX share them), r = rank B of them. When every weight is
//!     finite B is positive definite, r = n − 2 and det⁺(I − A) = (1 − p)^(n−2) det B / det M.
//!     With k ≥ 1 interpolation constraints (σ_i = 0) B has the null space N of the
//!     columns u with Qu supported on the constrained points, of dimension
//!     k − min(k, 2) (Qu is orthogonal to the straight lines, which take any values at two
//!     distinct knots), so r = n − 2 − (k − min(k, 2)) = n_f − m′ (n_f free points, m′ the
//!     null space of the penalty the constraints leave free); on N, M = pR, and
//!     det⁺(M⁻¹B) = det⁺B · det(NᵀRN) p^(n−2−r) / det M. So, up to constants,
//!     ln det⁺(I − A) = r ln(1 − p) + (n − 2 − r) ln p − ln det M.
//!
//!   The factors (1 − p)^r cancel between the two, and the criterion minimised is
//!
//!   ln V_ML = ln[(Qᵀy)ᵀ M⁻¹ (Qᵀy)] + [ln det M − (n − 2 − r) ln p] / r + const,
//!
//!   from the LDLᵀ factor of M (ln det M = Σ ln d_i) and one solve: O(n) per evaluation, no
//!   trace (checked against the dense definition with and without interpolation
//!   constraints). The sum in the quadratic form runs over the coordinates (σ̂² pooled). The
//!   same search as GCV. V_ML has a finite limit at interpolation, which can be its infimum
//!   (50 points of a sine with little noise); where the curve is smoother than the prior's
//!   sample paths it undersmooths (Wahba 1985; on the smooth analytic families of
//!   `examples/default_judge.py` 9–10 of 10 cases kept more than twice the clean curve's
//!   inflections, `docs/experiments/default-smoothing.md`).
//! - `Auto` (the default): the shared rule's safeguard in GCV-first order,
//!   [`crate::smoothing::choose_cross_validation_first`]: GCV's fit, unless it moves the free
//!   points by less than [`crate::smoothing::CROSS_VALIDATION_FLOOR`] σ̂ or its p is at the
//!   search's limit (its minimum at interpolation), then GML's. σ̂ is the third differences'
//!   noise estimate of the smoothed coordinates ([`crate::smoothing::difference_noise`]). The
//!   fit's [`SmoothingSpline::rule`] names the criterion kept (`gml` or `gcv`). GCV alone chose
//!   interpolation (p = 1 − 2·10⁻¹⁶) on a noisy closed ellipse and on the R140 upper surface
//!   (issue 44). Jump-lsq's order ([`crate::smoothing::choose`], GML first) measured worse for
//!   this spline, whose GML undersmooths smooth curves: on the judge's tuning set
//!   (`docs/experiments/default-smoothing.md`) geometric-mean RMS to the clean curve over the
//!   input's 0.714 (GCV 0.844, GML first 0.756), 90 cases with more than twice the clean
//!   inflections (83, 122), 17 interpolations of 170 by GCV alone.

mod pentadiagonal;
#[cfg(test)]
mod tests;

use curve_repr::{Curve, Parametrization, Side, Vector};
use serde::{Deserialize, Serialize};

use crate::smoothing::{choose_cross_validation_first, difference_noise, Criterion, RuleFit};
use crate::state::strategy_error;
use crate::{Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome};
use pentadiagonal::{Band, Ldlt};

/// The strategy's name, as `fair methods` lists it.
pub const NAME: &str = "smoothing-spline";

/// How the smoothing parameter p was (or is to be) chosen. The names of jump-lsq's
/// [`LambdaRule`](crate::strategies::LambdaRule) where they mean the same.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum SmoothingRule {
    /// Given by the user.
    Given,
    /// csaps's trace rule p = 1 / (1 + tr(R)/tr(QᵀΣQ)).
    Trace,
    /// Minimum of generalised cross-validation (csaps's objective with GCV's p). Unlike the
    /// trace rule, which depends on the parameters t_i only, it looks at the data (noise
    /// level) too; its minimum can fall at interpolation.
    Gcv,
    /// Minimum of generalised maximum likelihood (Wahba 1985, REML).
    Gml,
    /// The default: the shared rule of the methods that smooth (jump-lsq's `auto`): GML's p
    /// where its fit moves the points by at most 1.2 σ̂ (the noise estimate from third
    /// differences), else GCV's unless that moves them by less than 0.5 σ̂. A fit's rule, and
    /// the report's, is then the criterion kept, `gml` or `gcv`.
    #[default]
    Auto,
}

impl SmoothingRule {
    /// `given`, `trace`, `gcv`, `gml` or `auto`.
    pub fn name(self) -> &'static str {
        match self {
            SmoothingRule::Given => "given",
            SmoothingRule::Trace => "trace",
            SmoothingRule::Gcv => "gcv",
            SmoothingRule::Gml => "gml",
            SmoothingRule::Auto => "auto",
        }
    }
}

/// Settings of a smoothing-spline fit: the parameters of the catalogue's `smoothing-spline`.
/// Default: p chosen by the shared automatic rule (GML, else GCV), unit weights.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct SmoothingSettings {
    /// Smoothing parameter in [0, 1] (csaps: 0 LSQ line, 1 interpolation) or auto.
    ///
    /// `None` (written `auto`) lets `rule` choose it.
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0, "maximum" = 1))]
    pub p: Option<f64>,
    /// How auto chooses p: auto (GCV unless it interpolates, then GML), gml
    /// (maximum likelihood), gcv (generalised cross-validation) or trace (csaps's rule).
    ///
    /// [`SmoothingRule::Given`] is treated as the default, auto, when `p` is `None`.
    pub rule: SmoothingRule,
    /// One weight per data point (finite positive, or +∞ for an interpolation constraint);
    /// `None` for unit weights. Not a parameter of the catalogue.
    #[serde(skip)]
    pub weights: Option<Vec<f64>>,
}

impl SmoothingSettings {
    /// Checks the ranges: p in [0, 1] when given.
    pub fn validate(&self) -> Result<()> {
        if let Some(p) = self.p {
            if !(0.0..=1.0).contains(&p) {
                return Err(Error::BadParameter {
                    name: "p",
                    value: p.to_string(),
                    reason: "must lie in [0, 1] (or be auto)",
                });
            }
        }
        Ok(())
    }

    /// Sets p (in [0, 1]).
    pub fn with_p(mut self, p: f64) -> Self {
        self.p = Some(p);
        self
    }

    /// Sets the rule used when p is not given.
    pub fn with_rule(mut self, rule: SmoothingRule) -> Self {
        self.rule = rule;
        self
    }

    /// Sets the weights.
    pub fn with_weights(mut self, weights: Vec<f64>) -> Self {
        self.weights = Some(weights);
        self
    }
}

/// A natural cubic spline in `D` dimensions given by its values and second derivatives at the
/// knots: the result of a smoothing fit. Implements [`Curve`] over its parameter t.
///
/// For a function y(x) use `D = 1` (see [`SmoothingSpline::fit_function`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothingSpline<const D: usize> {
    t: Vec<f64>,
    values: Vec<Vector<D>>,
    second: Vec<Vector<D>>,
    p: f64,
    rule: SmoothingRule,
    gcv: Option<f64>,
    sigma_hat: Option<f64>,
}

/// How p was chosen for a fit: the value, the rule (the criterion kept under `Auto`), GCV's
/// score when GCV chose it, σ̂ when the automatic rule used it.
#[derive(Clone, Copy, Debug)]
struct Choice {
    p: f64,
    rule: SmoothingRule,
    gcv: Option<f64>,
    sigma_hat: Option<f64>,
}

/// The minimum of a criterion over p ([`Reinsch::minimise`]).
#[derive(Clone, Copy, Debug)]
struct Minimum {
    p: f64,
    value: f64,
    /// p is at the search's or the arithmetic's limit, not at an interior minimum
    /// ([`Reinsch::minimise`] says when).
    limited: bool,
}

/// The matrices of one parameter sequence and weight set: R, B = QᵀΣQ and Q's columns.
#[derive(Clone, Debug)]
struct Reinsch {
    h: Vec<f64>,
    sigma: Vec<f64>,
    r: Band,
    b: Band,
}

impl Reinsch {
    /// Builds R and B = QᵀΣQ. O(n).
    fn new(t: &[f64], sigma: Vec<f64>) -> Self {
        let n = t.len();
        let m = n - 2;
        let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let mut r = Band::zeros(m);
        let mut b = Band::zeros(m);
        // Column j of Q (interior knot j + 1) has entries (q0, q1, q2) in rows j, j+1, j+2.
        let q = |j: usize| {
            let (a, c) = (1.0 / h[j], 1.0 / h[j + 1]);
            [a, -a - c, c]
        };
        for j in 0..m {
            r.diag[j] = (h[j] + h[j + 1]) / 3.0;
            let qj = q(j);
            b.diag[j] =
                sigma[j] * qj[0] * qj[0] + sigma[j + 1] * qj[1] * qj[1] + sigma[j + 2] * qj[2] * qj[2];
            if j + 1 < m {
                r.first[j] = h[j + 1] / 6.0;
                let qk = q(j + 1);
                b.first[j] = sigma[j + 1] * qj[1] * qk[0] + sigma[j + 2] * qj[2] * qk[1];
            }
            if j + 2 < m {
                let qk = q(j + 2);
                b.second[j] = sigma[j + 2] * qj[2] * qk[0];
            }
        }
        Reinsch { h, sigma, r, b }
    }

    /// csaps's trace rule.
    fn trace_p(&self) -> f64 {
        let tr_r: f64 = self.r.diag.iter().sum();
        let tr_b: f64 = self.b.diag.iter().sum();
        1.0 / (1.0 + tr_r / tr_b)
    }

    /// M = pR + (1 − p)B, factored.
    fn factor(&self, p: f64) -> Result<Ldlt> {
        let combine = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| p * x + (1.0 - p) * y).collect();
        let m = Band {
            diag: combine(&self.r.diag, &self.b.diag),
            first: combine(&self.r.first, &self.b.first),
            second: combine(&self.r.second, &self.b.second),
        };
        Ldlt::factor(&m).ok_or_else(|| {
            strategy_error(
                NAME,
                format!(
                    "the smoothing system is singular at p = {p} (at p = 0 with more than two \
                     interpolation constraints no straight line fits them all)"
                ),
            )
        })
    }

    /// Qᵀy: second divided differences. O(n).
    fn qt<const D: usize>(&self, y: &[Vector<D>]) -> Vec<Vector<D>> {
        (0..self.h.len() - 1)
            .map(|j| (y[j + 2] - y[j + 1]) / self.h[j + 1] - (y[j + 1] - y[j]) / self.h[j])
            .collect()
    }

    /// Q u (length n). O(n).
    fn q<const D: usize>(&self, u: &[Vector<D>]) -> Vec<Vector<D>> {
        let n = self.h.len() + 1;
        let mut out = vec![Vector::<D>::zeros(); n];
        for (j, uj) in u.iter().enumerate() {
            let (a, c) = (1.0 / self.h[j], 1.0 / self.h[j + 1]);
            out[j] += uj * a;
            out[j + 1] -= uj * (a + c);
            out[j + 2] += uj * c;
        }
        out
    }

    /// Solves at p: u and Qu. O(n).
    fn solve<const D: usize>(
        &self,
        p: f64,
        y: &[Vector<D>],
    ) -> Result<(Ldlt, Vec<Vector<D>>, Vec<Vector<D>>)> {
        let ldlt = self.factor(p)?;
        let mut u = self.qt(y);
        ldlt.solve_in_place(&mut u);
        let qu = self.q(&u);
        Ok((ldlt, u, qu))
    }

    /// GCV(p) = n Σ σ_i |(Qu)_i|² / tr(M⁻¹B)² (module docs). O(n).
    fn gcv<const D: usize>(&self, p: f64, y: &[Vector<D>]) -> Result<f64> {
        let (ldlt, _, qu) = self.solve(p, y)?;
        let rss: f64 = qu
            .iter()
            .zip(&self.sigma)
            .map(|(v, s)| s * v.norm_squared())
            .sum();
        let trace = ldlt.inverse_band().trace_product(&self.b);
        let n = (self.h.len() + 1) as f64;
        let value = n * rss / (trace * trace);
        if value.is_finite() {
            Ok(value)
        } else {
            Err(strategy_error(NAME, format!("GCV is not finite at p = {p}")))
        }
    }

    /// The rank r of I − A: n − 2 − (k − min(k, 2)) for k interpolation constraints
    /// (σ_i = 0; module docs, `Gml`).
    fn likelihood_rank(&self) -> usize {
        let m = self.h.len() - 1;
        let k = self.sigma.iter().filter(|s| **s == 0.0).count();
        m.saturating_sub(k - k.min(2))
    }

    /// ln V_ML(p) up to a constant: ln[(Qᵀy)ᵀM⁻¹(Qᵀy)] + [ln det M − (n − 2 − r) ln p]/r
    /// (module docs, `Gml`). O(n).
    fn gml<const D: usize>(&self, p: f64, y: &[Vector<D>]) -> Result<f64> {
        let r = self.likelihood_rank();
        let qty = self.qt(y);
        let ldlt = self.factor(p)?;
        let mut u = qty.clone();
        ldlt.solve_in_place(&mut u);
        let quadratic: f64 = qty.iter().zip(&u).map(|(a, b)| a.dot(b)).sum();
        let null = (self.h.len() - 1 - r) as f64;
        let value = if r == 0 {
            f64::NAN
        } else {
            quadratic.max(f64::MIN_POSITIVE).ln() + (ldlt.log_det() - null * p.ln()) / r as f64
        };
        if value.is_finite() {
            Ok(value)
        } else {
            Err(strategy_error(NAME, format!("GML is not finite at p = {p}")))
        }
    }

    /// The p minimising GCV (module docs: grid over ρ, then golden section). O(n) per
    /// evaluation, about 100 evaluations.
    fn gcv_p<const D: usize>(&self, y: &[Vector<D>]) -> Result<Minimum> {
        self.minimise("GCV", |p| self.gcv(p, y))
    }

    /// The p minimising GML (module docs), the same search as GCV's.
    fn gml_p<const D: usize>(&self, y: &[Vector<D>]) -> Result<Minimum> {
        self.minimise("GML", |p| self.gml(p, y))
    }

    /// Minimises `criterion(p)` over ρ = log10((1 − p)/p) (module docs: a grid of step 1/4
    /// over ±8 decades around the trace rule's ρ, followed outwards while the criterion falls
    /// at an edge, then a golden section in the best cell). A p where the criterion fails
    /// (a singular system, p rounded to 0 or 1) is skipped. The minimum is `limited` when the
    /// criterion cannot be evaluated one grid step beyond it, or still fell where it could
    /// no longer be evaluated or after the last step outwards, or when its value at p = 0 or
    /// p = 1 itself (the limits, where finite) is no higher than the minimum found: GML's
    /// infimum lay at interpolation (found at p = 1 − 2·10⁻¹⁶) on 50 points of a sine with
    /// noise 0.0127 (`default_judge.py`'s `sine_0.25x_1000`; the dense criterion falls
    /// monotonically as λ → 0 there).
    fn minimise(&self, name: &str, criterion: impl Fn(f64) -> Result<f64>) -> Result<Minimum> {
        let p_of = |rho: f64| 1.0 / (1.0 + 10f64.powf(rho));
        let trace = self.trace_p();
        let centre = ((1.0 - trace) / trace).log10();
        let centre = if centre.is_finite() { centre } else { 0.0 };
        const STEP: f64 = 0.25;
        const HALF_WIDTH: i32 = 32;
        const EXTRA_STEPS: i32 = 96;
        let eval = |rho: f64| {
            let p = p_of(rho);
            if p <= 0.0 || p >= 1.0 {
                return f64::INFINITY;
            }
            criterion(p).unwrap_or(f64::INFINITY)
        };
        let mut best = (f64::INFINITY, centre);
        for k in -HALF_WIDTH..=HALF_WIDTH {
            let rho = centre + f64::from(k) * STEP;
            // A numerically singular system at an extreme ρ is skipped, not fatal.
            let g = eval(rho);
            if g < best.0 {
                best = (g, rho);
            }
        }
        if !best.0.is_finite() {
            return Err(strategy_error(
                NAME,
                format!("{name} could not be evaluated at any p"),
            ));
        }
        // A minimum on the grid's edge is followed outwards while the criterion falls: on
        // dense noisy data (10^5 points of a sine, spacing 1.3e-4, σ = 0.01) GCV's lies 12
        // decades above the trace rule's ρ, where the edge left the fit 3× farther from the
        // truth and with ~600 inflections.
        let (mut exhausted, mut stopped) = (false, false);
        for direction in [-1.0, 1.0] {
            let edge = centre + direction * f64::from(HALF_WIDTH) * STEP;
            if best.1 != edge {
                continue;
            }
            for k in 1..=EXTRA_STEPS {
                let rho = edge + direction * f64::from(k) * STEP;
                let g = eval(rho);
                // (eval maps failures to +∞: the criterion still fell where the arithmetic
                // stopped, p rounded to 1 or the system singular.)
                if !g.is_finite() {
                    stopped = true;
                    break;
                }
                if g >= best.0 {
                    break;
                }
                best = (g, rho);
                exhausted |= k == EXTRA_STEPS;
            }
        }
        let limited =
            exhausted || stopped || !eval(best.1 - STEP).is_finite() || !eval(best.1 + STEP).is_finite();
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        let (mut a, mut b) = (best.1 - STEP, best.1 + STEP);
        let mut c = b - ratio * (b - a);
        let mut d = a + ratio * (b - a);
        let (mut fc, mut fd) = (eval(c), eval(d));
        while b - a > 1e-7 {
            if fc < fd {
                b = d;
                d = c;
                fd = fc;
                c = b - ratio * (b - a);
                fc = eval(c);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + ratio * (b - a);
                fd = eval(d);
            }
        }
        let (g, rho) = if fc < fd { (fc, c) } else { (fd, d) };
        // The refinement never returns worse than the grid's best.
        let (p, value) = if g <= best.0 {
            (p_of(rho), g)
        } else {
            (p_of(best.1), best.0)
        };
        // The criterion's limits at p = 0 and p = 1 themselves, where they exist: one no
        // higher than the minimum found means the infimum lies at that end, beyond what the
        // search over ρ can reach in floating point.
        let at_end = [0.0, 1.0].into_iter().any(|end| {
            criterion(end).is_ok_and(|v| v.is_finite() && v <= value + 1e-9 * (1.0 + value.abs()))
        });
        Ok(Minimum {
            p,
            value,
            limited: limited || at_end,
        })
    }
}

/// σ̂ of the data over the coordinates from `first` on: the root of the sum of the
/// coordinates' squared third-difference estimates ([`difference_noise`], open: a closed
/// polygon's repeated point is one more value). O(n).
fn noise<const D: usize>(y: &[Vector<D>], first: usize) -> f64 {
    (first..D)
        .map(|c| {
            let values: Vec<f64> = y.iter().map(|v| v[c]).collect();
            difference_noise(&values, false).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}

/// Checks parameters, data and weights; returns σ = 1/w.
fn validate<const D: usize>(t: &[f64], y: &[Vector<D>], weights: Option<&[f64]>) -> Result<Vec<f64>> {
    let n = t.len();
    if y.len() != n {
        return Err(curve_repr::Error::LengthMismatch {
            what: "smoothing data",
            expected: n,
            got: y.len(),
        }
        .into());
    }
    if n < 3 {
        return Err(curve_repr::Error::TooFewPoints {
            what: "a smoothing spline",
            needed: 3,
            got: n,
        }
        .into());
    }
    curve_repr::vector::check_finite_values("smoothing parameters", t)?;
    curve_repr::vector::check_finite(y)?;
    if let Some(index) = t.windows(2).position(|w| w[1] - w[0] <= 0.0) {
        return Err(curve_repr::Error::NotIncreasing {
            what: "smoothing parameters",
            index: index + 1,
            previous: t[index],
            value: t[index + 1],
        }
        .into());
    }
    match weights {
        None => Ok(vec![1.0; n]),
        Some(w) => {
            if w.len() != n {
                return Err(curve_repr::Error::LengthMismatch {
                    what: "smoothing weights",
                    expected: n,
                    got: w.len(),
                }
                .into());
            }
            if let Some(index) = w.iter().position(|w| w.is_nan() || *w <= 0.0) {
                return Err(Error::BadParameter {
                    name: "weights",
                    value: format!("w[{index}] = {}", w[index]),
                    reason: "weights must be positive (+inf for an interpolation constraint)",
                });
            }
            Ok(w.iter().map(|w| 1.0 / w).collect())
        }
    }
}

impl<const D: usize> SmoothingSpline<D> {
    /// Fits the smoothing spline to data `y` at increasing parameters `t` (module docs). O(n)
    /// for a given p or the trace rule, O(n) times about 100 evaluations for GCV or GML, twice
    /// that at most for the automatic rule.
    ///
    /// Errors: fewer than 3 points, lengths that differ, non-finite values, `t` not strictly
    /// increasing, a weight not positive, p outside [0, 1], a singular system (p = 0 with more
    /// than two infinite weights).
    pub fn fit(t: &[f64], y: &[Vector<D>], settings: &SmoothingSettings) -> Result<Self> {
        Self::fit_coordinates(t, y, settings, 0)
    }

    /// [`fit`](Self::fit) whose automatic rule measures the noise σ̂ and the displacement on
    /// the coordinates from `first` on (1 for a function y(x) given with its abscissa as
    /// coordinate 0, which the fit reproduces and the noise estimate must not see).
    fn fit_coordinates(
        t: &[f64],
        y: &[Vector<D>],
        settings: &SmoothingSettings,
        first: usize,
    ) -> Result<Self> {
        let sigma = validate(t, y, settings.weights.as_deref())?;
        let reinsch = Reinsch::new(t, sigma);
        let choice = match settings.p {
            Some(p) => {
                if !(0.0..=1.0).contains(&p) {
                    return Err(Error::BadParameter {
                        name: "p",
                        value: p.to_string(),
                        reason: "the smoothing parameter lies in [0, 1]",
                    });
                }
                Choice {
                    p,
                    rule: SmoothingRule::Given,
                    gcv: None,
                    sigma_hat: None,
                }
            }
            None => {
                let by = |rule: SmoothingRule| -> Result<(Choice, bool)> {
                    Ok(match rule {
                        SmoothingRule::Trace => (
                            Choice {
                                p: reinsch.trace_p(),
                                rule,
                                gcv: None,
                                sigma_hat: None,
                            },
                            false,
                        ),
                        SmoothingRule::Gml => {
                            let m = reinsch.gml_p(y)?;
                            (
                                Choice {
                                    p: m.p,
                                    rule,
                                    gcv: None,
                                    sigma_hat: None,
                                },
                                m.limited,
                            )
                        }
                        _ => {
                            let m = reinsch.gcv_p(y)?;
                            (
                                Choice {
                                    p: m.p,
                                    rule: SmoothingRule::Gcv,
                                    gcv: Some(m.value),
                                    sigma_hat: None,
                                },
                                m.limited,
                            )
                        }
                    })
                };
                match settings.rule {
                    SmoothingRule::Auto | SmoothingRule::Given => {
                        let sigma_hat = noise(y, first);
                        let chosen =
                            choose_cross_validation_first(sigma_hat, |criterion| -> Result<RuleFit<Self>> {
                                let (choice, limited) = by(match criterion {
                                    Criterion::Likelihood => SmoothingRule::Gml,
                                    Criterion::CrossValidation => SmoothingRule::Gcv,
                                })?;
                                let fit = Self::solve_at(
                                    t,
                                    y,
                                    &reinsch,
                                    Choice {
                                        sigma_hat: Some(sigma_hat),
                                        ..choice
                                    },
                                )?;
                                Ok(RuleFit {
                                    rms_displacement: fit.rms_displacement(y, &reinsch.sigma, first),
                                    fit,
                                    limited,
                                })
                            })?;
                        return Ok(chosen.fit);
                    }
                    rule => by(rule)?.0,
                }
            }
        };
        Self::solve_at(t, y, &reinsch, choice)
    }

    /// √(Σ |y_i − f_i|² / n_f) over the n_f points with finite weight and the coordinates
    /// from `first` on: the automatic rule's measure of a fit, the same as σ̂'s.
    fn rms_displacement(&self, y: &[Vector<D>], sigma: &[f64], first: usize) -> f64 {
        let (mut sum, mut count) = (0.0, 0usize);
        for ((v, y), s) in self.values.iter().zip(y).zip(sigma) {
            if *s > 0.0 {
                count += 1;
                sum += (first..D).map(|c| (v[c] - y[c]).powi(2)).sum::<f64>();
            }
        }
        if count == 0 {
            0.0
        } else {
            (sum / count as f64).sqrt()
        }
    }

    fn solve_at(t: &[f64], y: &[Vector<D>], reinsch: &Reinsch, choice: Choice) -> Result<Self> {
        let p = choice.p;
        if !(p.is_finite() && (0.0..=1.0).contains(&p)) {
            return Err(strategy_error(
                NAME,
                format!("the {} rule gave p = {p}", choice.rule.name()),
            ));
        }
        let (_, u, qu) = reinsch.solve(p, y)?;
        let values: Vec<Vector<D>> = y
            .iter()
            .zip(&qu)
            .zip(&reinsch.sigma)
            .map(|((y, q), s)| if *s == 0.0 { *y } else { y - q * ((1.0 - p) * s) })
            .collect();
        let mut second = Vec::with_capacity(t.len());
        second.push(Vector::<D>::zeros());
        second.extend(u.iter().map(|u| u * p));
        second.push(Vector::<D>::zeros());
        if values
            .iter()
            .chain(&second)
            .any(|v| v.iter().any(|c| !c.is_finite()))
        {
            return Err(strategy_error(NAME, format!("the fit at p = {p} is not finite")));
        }
        Ok(SmoothingSpline {
            t: t.to_vec(),
            values,
            second,
            p,
            rule: choice.rule,
            gcv: choice.gcv,
            sigma_hat: choice.sigma_hat,
        })
    }

    fn choice(&self) -> Choice {
        Choice {
            p: self.p,
            rule: self.rule,
            gcv: self.gcv,
            sigma_hat: self.sigma_hat,
        }
    }

    /// The smoothing parameter used.
    pub fn p(&self) -> f64 {
        self.p
    }

    /// How p was chosen.
    pub fn rule(&self) -> SmoothingRule {
        self.rule
    }

    /// GCV(p) at the chosen p when the GCV rule chose it.
    pub fn gcv(&self) -> Option<f64> {
        self.gcv
    }

    /// The noise estimate σ̂ the automatic rule compared the fits' displacements with (module
    /// docs, `Auto`); `None` when p was given or chosen by one criterion alone.
    pub fn sigma_hat(&self) -> Option<f64> {
        self.sigma_hat
    }

    /// The knots t_i (the data parameters).
    pub fn knots(&self) -> &[f64] {
        &self.t
    }

    /// The spline's values f(t_i) at the knots.
    pub fn values(&self) -> &[Vector<D>] {
        &self.values
    }

    /// The second derivatives f''(t_i) at the knots (zero at both ends).
    pub fn second_derivatives(&self) -> &[Vector<D>] {
        &self.second
    }

    /// ∫ |f''|² dt: f'' is linear on each interval, so an interval of length h with end values
    /// a, b adds h (|a|² + a·b + |b|²)/3. O(n).
    pub fn bending_energy(&self) -> f64 {
        self.t
            .windows(2)
            .zip(self.second.windows(2))
            .map(|(t, g)| (t[1] - t[0]) * (g[0].norm_squared() + g[0].dot(&g[1]) + g[1].norm_squared()) / 3.0)
            .sum()
    }

    /// The index of the interval holding `t` (the one ending at a knot for `Side::Left`).
    fn interval(&self, t: f64, side: Side) -> usize {
        let last = self.t.len() - 2;
        let k = match side {
            Side::Right => self.t.partition_point(|&x| x <= t),
            Side::Left => self.t.partition_point(|&x| x < t),
        };
        k.saturating_sub(1).min(last)
    }
}

impl SmoothingSpline<1> {
    /// The smoothing spline of a function y(x): [`fit`](Self::fit) with scalar data.
    pub fn fit_function(x: &[f64], y: &[f64], settings: &SmoothingSettings) -> Result<Self> {
        let y: Vec<Vector<1>> = y.iter().map(|&v| Vector::<1>::new(v)).collect();
        Self::fit(x, &y, settings)
    }
}

/// The smoothing spline of a parametric curve: each coordinate over the chord-length
/// parameters of `points` (t_0 = 0, t_{i+1} − t_i = |P_{i+1} − P_i|). O(n) (see
/// [`SmoothingSpline::fit`]). Fails on two consecutive equal points.
pub fn fit_parametric<const D: usize>(
    points: &[Vector<D>],
    settings: &SmoothingSettings,
) -> Result<SmoothingSpline<D>> {
    let t = Parametrization::ChordLength.parameters(points)?;
    SmoothingSpline::fit(&t, points, settings)
}

impl<const D: usize> Curve<D> for SmoothingSpline<D> {
    fn domain(&self) -> (f64, f64) {
        (self.t[0], self.t[self.t.len() - 1])
    }

    /// On [t_i, t_{i+1}] with τ = (t − t_i)/h: s = (1−τ)f_i + τf_{i+1} + h²/6·[((1−τ)³ − (1−τ))γ_i
    /// + (τ³ − τ)γ_{i+1}], and its derivatives.
    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        let i = self.interval(t, side);
        let (t0, t1) = (self.t[i], self.t[i + 1]);
        let h = t1 - t0;
        let (f0, f1) = (self.values[i], self.values[i + 1]);
        let (g0, g1) = (self.second[i], self.second[i + 1]);
        let tau = (t - t0) / h;
        let s = 1.0 - tau;
        let value = f0 * s + f1 * tau + (g0 * (s * s * s - s) + g1 * (tau * tau * tau - tau)) * (h * h / 6.0);
        let first = (f1 - f0) / h + (g1 * (3.0 * tau * tau - 1.0) - g0 * (3.0 * s * s - 1.0)) * (h / 6.0);
        let second = g0 * s + g1 * tau;
        let third = (g1 - g0) / h;
        [value, first, second, third]
    }

    fn breaks(&self) -> Vec<f64> {
        self.t.clone()
    }
}

/// Whether a strategy fairs a function y(x) or a parametric curve (used by the smoothing
/// spline and Sapidis–Farin).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CurveDomain {
    /// Coordinate 0 is the abscissa x (strictly increasing, kept bit for bit); the other
    /// coordinates are smoothed as functions of x.
    Function,
    /// Every coordinate is smoothed over the chord-length parameters of the current points.
    #[default]
    Parametric,
}

/// The smoothing spline as a [`FairingStrategy`]: one step that moves every free point onto
/// the smoothing spline (its value at the point's parameter), then reports done.
///
/// Constraints:
/// - fixed points, clamped ends (G0) and points with a zero restraining radius or tolerance
///   get weight +∞, i.e. they are interpolation constraints of the fit: the spline passes through them exactly and they do not move.
///   G1/G2 clamps are rejected ([`Error::ConstraintUnsupported`]). Closed curves are rejected.
/// - the tolerance band and restraining radii (one ball per point, the smaller of the two):
///   p is chosen once, on the user's weights; then, up to [`SmoothingSplineFairing::MAX_REWEIGHTS`]
///   times, every point whose fitted position lies outside its ball has its weight multiplied
///   by 2·(distance/allowed)² and the spline is refitted at the same p. The points then lie
///   on a smoothing spline with larger weights at the points that had to stay close. Whatever
///   still lies outside after the last round (rare) is projected into its ball by
///   [`FairingState::move_point`]; [`SmoothingSplineFairing::clipped`] counts those points,
///   which are then off the spline.
#[derive(Clone, Debug, Default)]
pub struct SmoothingSplineFairing<const D: usize> {
    settings: SmoothingSettings,
    domain: CurveDomain,
    fit: Option<SmoothingSpline<D>>,
    reweights: usize,
    clipped: usize,
}

impl<const D: usize> SmoothingSplineFairing<D> {
    /// Rounds of reweighting for the tolerance band at most.
    pub const MAX_REWEIGHTS: usize = 60;

    /// A strategy with `settings` (its `weights` are the user's, before constraints) on
    /// `domain`.
    pub fn new(settings: SmoothingSettings, domain: CurveDomain) -> Self {
        Self {
            settings,
            domain,
            fit: None,
            reweights: 0,
            clipped: 0,
        }
    }

    /// The last fit (its p and rule), after a step.
    pub fn fit(&self) -> Option<&SmoothingSpline<D>> {
        self.fit.as_ref()
    }

    /// Rounds of reweighting the tolerance band needed in the last step.
    pub fn reweights(&self) -> usize {
        self.reweights
    }

    /// Points the last step had to project into their ball (then off the spline).
    pub fn clipped(&self) -> usize {
        self.clipped
    }

    /// Parameters and data of the current points for the domain.
    fn data(&self, points: &[Vector<D>]) -> Result<(Vec<f64>, Vec<Vector<D>>)> {
        match self.domain {
            CurveDomain::Parametric => {
                Ok((Parametrization::ChordLength.parameters(points)?, points.to_vec()))
            }
            CurveDomain::Function => {
                if D < 2 {
                    return Err(Error::refused(
                        NAME,
                        Refusal::Dimension,
                        "needs points with at least 2 coordinates for a function y(x)",
                    ));
                }
                let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
                Ok((x, points.to_vec()))
            }
        }
    }
}

impl<const D: usize> FairingStrategy<D> for SmoothingSplineFairing<D> {
    fn name(&self) -> &str {
        NAME
    }

    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        if state.is_closed() {
            return Err(Error::ConstraintUnsupported {
                strategy: NAME.into(),
                constraint: "a closed curve (the smoothing spline is open, natural ends)".into(),
            });
        }
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let n = state.len();
        let (t, y) = self.data(state.points())?;
        let constraints = state.constraints().clone();
        let mut weights = self.settings.weights.clone().unwrap_or_else(|| vec![1.0; n]);
        let user = SmoothingSettings {
            weights: Some(weights.clone()),
            ..self.settings.clone()
        };
        // p from the user's weights; fixed points as interpolation constraints.
        validate(&t, &y, Some(&weights))?;
        let smoothed = match self.domain {
            CurveDomain::Function => 1,
            CurveDomain::Parametric => 0,
        };
        let choice = SmoothingSpline::fit_coordinates(&t, &y, &user, smoothed)?.choice();
        // Fixed points, clamped ends and zero radii: interpolation constraints.
        let frozen = |i: usize| !constraints.is_movable(i, n);
        for (i, w) in weights.iter_mut().enumerate() {
            if frozen(i) {
                *w = f64::INFINITY;
            }
        }
        let original = state.original().to_vec();
        let target = |fit: &SmoothingSpline<D>, i: usize| -> Vector<D> {
            let mut v = fit.values[i];
            if self.domain == CurveDomain::Function {
                v[0] = y[i][0];
            }
            v
        };
        let mut fit;
        self.reweights = 0;
        loop {
            optim::cancel::checkpoint()?;
            let sigma: Vec<f64> = weights.iter().map(|w| 1.0 / w).collect();
            fit = SmoothingSpline::solve_at(&t, &y, &Reinsch::new(&t, sigma), choice)?;
            let mut violated = false;
            for (i, w) in weights.iter_mut().enumerate() {
                let allowed = constraints.allowed_distance(i);
                let distance = (target(&fit, i) - original[i]).norm();
                if distance > allowed && w.is_finite() {
                    violated = true;
                    *w = if allowed > 0.0 {
                        *w * 2.0 * (distance / allowed).powi(2)
                    } else {
                        f64::INFINITY
                    };
                }
            }
            if !violated || self.reweights >= Self::MAX_REWEIGHTS {
                break;
            }
            self.reweights += 1;
        }
        self.clipped = 0;
        for i in 0..n {
            let proposed = target(&fit, i);
            if proposed == state.points()[i] {
                continue;
            }
            let went = state.move_point(i, proposed)?;
            if state.is_movable(i) && went != proposed {
                self.clipped += 1;
            }
        }
        let criterion = fit.bending_energy();
        self.fit = Some(fit);
        Ok(StepOutcome::done(Some(criterion)))
    }
}
