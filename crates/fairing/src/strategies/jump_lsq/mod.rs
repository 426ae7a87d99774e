//! `jump-lsq`: least squares on the points with a penalty on the roughness of the third-
//! derivative jumps of their own interpolating spline.
//!
//! # The method
//!
//! For points P⁰ (function kind: y over fixed x; parametric: every coordinate over knots t),
//! find P minimising
//!
//! ```text
//! Σ_i |P_i − P⁰_i|²  +  λ · Σ_r ( h̄_r^(a/2) · h_med³ · (Δ^d J)_r )²
//! ```
//!
//! where J_i = s‴(t_i+) − s‴(t_i−) is the jump of the third derivative of the interpolating
//! cubic spline s through P at knot i (Zhang–Cheng Eq. 17's z_i as a signed vector, and
//! 6 e_i in Han et al.'s notation), Δ^d the d-th difference along the knots (d = 1, 2 or
//! 3, by default the one of least GCV score, see the settings), h̄_r the mean length of
//! the d + 2 spans that row r's jumps separate, relative to the median spacing h_med, and a
//! the spacing exponent (default 8). The factor h_med³ gives J the
//! units of the points, so λ is dimensionless and scale-free: multiplying all coordinates
//! (and knots) by a constant leaves the best λ unchanged.
//!
//! The spline is the representation the fairness measures use: for the function kind the
//! parabolic-runout spline of Han et al. (s‴ = 0 on the first and last spans), for the
//! parametric kind the natural spline (s″ = 0 at both ends) over chord-length knots (or the
//! runout spline there, `curve-ends`), for a closed curve the periodic spline over closed
//! chord-length knots.
//!
//! # The banded formulation (derivation)
//!
//! J depends on every point: s is found from P through the spline's tridiagonal system, so in
//! the points the penalty is J = G M⁻¹ Q P with M tridiagonal, and the normal equations
//! (I + λ Qᵀ M⁻ᵀ GᵀΩG M⁻¹ Q) P = P⁰ are dense. Reinsch (1967) keeps such problems banded by
//! taking the second derivatives (moments) as extra unknowns with the spline equations as
//! constraints; for his penalty ∫s″² the multipliers can be eliminated because the penalty's
//! matrix and the constraint's matrix coincide. For the jump penalty they do not, and the
//! constrained system in (P, moments, multipliers) is indefinite with 3n unknowns.
//!
//! Instead we eliminate the other way, to a definite banded system with n unknowns. The
//! interpolating spline is a bijection between the points and the space S of C² cubic
//! splines on the knots with the kind's end condition (interpolation is unique), so s itself
//! can be the unknown, with P_i = s(t_i). The problem becomes penalised least squares over S:
//!
//! ```text
//! minimise Σ_i |s(t_i) − P⁰_i|² + λ Σ_r ω_r |(Δ^d J(s))_r|²,   ω_r = h̄_r^a h_med⁶.
//! ```
//!
//! In a B-spline basis of S, s = Σ_j β_j N_j, every quantity is local: s(t_i) involves three
//! coefficients, s‴ is constant on a span and combines the four B-splines of that span, so
//! J_i involves five and (Δ^d J)_r involves 5 + d. With N the collocation matrix
//! (N_ij = N_j(t_i)) and G the matrix of the rows Δ^d J, the normal equations
//!
//! ```text
//! (Nᵀ W N + λ Gᵀ Ω G) γ = Nᵀ W P⁰,    P = N γ,
//! ```
//!
//! are symmetric positive definite and banded with half-bandwidth 4 + d (W the data weights,
//! 1 for a free point). The B-spline coefficients are exactly a null-space basis of Reinsch's
//! spline-equation constraints, which is why the reduced system is both banded and definite.
//! Each coordinate has the same matrix, so one factorisation serves all of them.
//!
//! End conditions. On open knots the clamped basis has n + 2 B-splines β_0 … β_{n+1}; the
//! two end conditions (runout: s‴ = 0 on the first/last span; natural: s″ = 0 at t_0 and
//! t_{n−1}) are local linear equations, solved for β_1 and β_n and substituted, leaving n
//! unknowns γ and the band intact. On closed knots the n periodic B-splines make the matrix
//! cyclically banded; ordering the unknowns 0, n−1, 1, n−2, … folds it into a band of twice
//! the width (no fill at the corners).
//!
//! Constraints are equality constraints C γ = d on the output's spline: fixed points
//! (s(t_i) = P_i, bit for bit at the output), G1/G2 end clamps (s′ and s″ at the ends equal to
//! those of the spline through the ORIGINAL points on its own knots), and the points pinned by
//! the tolerance band. They enter with Lagrange multipliers, each placed right after the last
//! unknown it touches:
//!
//! ```text
//! [ H  Cᵀ ] [γ]   [Nᵀ W P⁰]
//! [ C  0  ] [μ] = [   d   ],   H = Nᵀ W N + λ Gᵀ Ω G.
//! ```
//!
//! Every leading block of this order is [[H₁₁, C₁ᵀ], [C₁, 0]] with H₁₁ positive definite and
//! C₁ of full row rank (distinct constraint rows), so LDLᵀ without pivoting exists, with
//! positive pivots at the unknowns and negative ones at the multipliers; the envelope
//! (profile) of the interleaved matrix is a band plus a few columns, and the factorisation
//! fills only inside it (the `envelope` module). A constrained point keeps its data row: the
//! constraint makes that term constant, so the solution does not change, and H stays
//! positive definite for every λ ≥ 0 (N is square and invertible), λ = 0 included; its
//! residual is left out of the discrepancy and of GCV.
//!
//! The solver is our own envelope LDLᵀ rather than faer's sparse Cholesky or LU: the matrix
//! is a narrow band known in advance, so no ordering or symbolic analysis is needed, the
//! inner loops are contiguous dot products (~m·b² flops), the same profile is refactored at
//! every trial λ, the indefinite KKT form needs no pivoting, and the selected inverse for
//! GCV's trace (Takahashi's recurrence, which faer does not offer) runs on the same storage.
//!
//! # The ends of an open curve
//!
//! On an open curve the jumps J_1 and J_{n−2} next to the ends appear in few rows Δ^d J, and
//! Δ^d J = 0 leaves jumps that vary as a polynomial of degree d − 1 along the knots (for
//! the natural spline and d = 1, a spline with equal non-zero jumps: the penalty's null space
//! has one dimension more than the cubic smoothing spline's straight lines). Extra rows on
//! the end jumps themselves were measured as two-phase's pre-pass
//! (`docs/experiments/two_phase_judge.md`, end treatment): they left the judge's count where it
//! was or lowered it and did not bring the misses' rows nearer their clean curves at csaps's
//! S_d, so the penalty is that of Δ^d J alone.
//!
//! # Choosing λ, the noise estimate, the precision limit
//!
//! See the `lambda` and `noise` modules. By default (`rule = auto`) λ is chosen by GML where
//! its fit stays within 1.2 σ̂ of the data and by GCV elsewhere, σ̂ the noise estimated from
//! the points' third differences; `rule = gcv` chooses by generalised cross-validation,
//! `rule = gml` by generalised maximum likelihood, `rule = discrepancy` by the discrepancy
//! principle (the RMS displacement of the free points equals σ̂, Morozov's). `lambda` or
//! `target-sd` override the rule: `target-sd` = k·σ̂ is the discrepancy principle with the
//! factor k.
//!
//! The penalty's own shape can be chosen the same way: `function-ends = auto` fits a
//! function's four pairs of end conditions (the `ends` module), `difference-order = auto`
//! (the default) the orders d = 1, 2, 3 of a function or a curve ([`JumpLsqSettings::difference_order`]),
//! each under the GCV rule, and keeps the fit of least GCV score V: the candidates are
//! n-dimensional models fitted to the same data, which V compares as it compares values of
//! λ. The order is chosen first (with the ends chosen for each order), then λ by the
//! settings' rule.
//!
//! # Dense data: the reduced basis
//!
//! Beyond 10^4 points, where λ is chosen by a rule (neither `lambda` nor `target-sd` given), the
//! fit is made on bin means of consecutive points instead, with one knot per bin (a P-spline, Eilers
//! & Marx 1996), and the output is that spline evaluated at every input point's parameter
//! (the `reduced` module). With one knot per point the rule's λ stops at the precision limit on
//! dense noisy data (from 10^3 points of the speed peer's noisy sine on); on the bins it does not,
//! and the fit keeps the clean curve's inflections (`docs/experiments/speed.md`). Fixed points and
//! clamped ends are bins of their own and kept bit for bit, the tolerance band and radii are held
//! point by point (pins at the ball's surface); G1/G2 end clamps are refused there. The report's
//! `knots` gives the bins (`None`: one knot per point).
//!
//! # Parametric curves
//!
//! With the knots fixed J is linear in P and each solve is one linear system. The chord-length
//! knots of the result differ from those of the input, so the parametric kind re-solves
//! `refits` times, each time on the chord-length knots of the previous result (the data term
//! always measures the distance to the stage's input points). The reported penalty is computed
//! on the output's own knots ([`jump_penalty`]).
//!
//! # Costs
//!
//! O(n) time and memory per solve (on the reduced basis O(m) per solve on m bins, plus O(n)
//! for the bins, the read-back and the penalties): assembly O(n·(4 + d)²), factorisation
//! O(n·(5 + d)²) (four times that for closed curves), a discrepancy search one QR solve when λ stops at the
//! precision limit (dense noisy data; the normal equations are then never assembled), else
//! 3–9 solves, GCV about 60 solves with selected inverses; the parametric kind repeats the
//! search for each of its `refits`, GCV's within two decades of the previous round's λ (about
//! 20 solves; the `lambda` module).

mod basis;
mod ends;
mod envelope;
mod lambda;
mod noise;
mod qr;
mod reduced;
mod system;
#[cfg(test)]
mod tests;

pub(crate) use noise::{coordinate_noise, noise as curve_noise};

use curve_repr::{Parametrization, Vector};
use serde::{Deserialize, Serialize};

use crate::strategies::smoothing_spline::CurveDomain;
use crate::{
    project_into_ball, Constraints, EndClamp, Error, FairingState, FairingStrategy, Result, StepOutcome,
};
use basis::Knots;
use lambda::{Choice, Evaluation};
use system::{Constraint, End, Ends, Penalty, Space, SpaceError, System};

/// The strategy's name, as `fair methods` lists it.
pub const NAME: &str = "jump-lsq";

/// How λ is chosen when neither `lambda` nor `target-sd` is given.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum LambdaRule {
    /// The discrepancy principle: RMS displacement = σ̂ (Morozov's; `target-sd` aims at any
    /// other).
    Discrepancy,
    /// Generalised cross-validation.
    Gcv,
    /// Generalised maximum likelihood (Wahba 1985), the restricted likelihood (REML) of the
    /// smoother's Bayesian model: minimise ln(RSS + λ(P − P_min)) + [ln det K(λ) −
    /// (q − m′) ln λ]/(n_f − m′) (the `lambda` module derives it).
    Gml,
    /// The default: the shared automatic rule ([`crate::smoothing::choose`]). GML where the
    /// data fit its model, else GCV: the GML fit is kept when its λ is not limited and its
    /// RMS displacement of the free points is at most [`AUTO_NOISE_FACTOR`] times the noise
    /// estimate σ̂ ([`JumpLsqReport::sigma_hat`]); otherwise the GCV fit is made and kept unless it moves the points by less than
    /// [`crate::smoothing::CROSS_VALIDATION_FLOOR`] σ̂ (GCV's minimum at interpolation), when
    /// GML's is kept after all. The report's `solves` counts both searches and its `rule`
    /// names the rule whose fit was kept (`gml` or `gcv`). Chosen over the discrepancy
    /// principle on the tuning set of `examples/default_judge.py`
    /// (`docs/experiments/default-smoothing.md`).
    ///
    #[default]
    /// GCV's score is flat over decades of λ on a few hundred noisy points, and its minimum
    /// then falls anywhere in them: on 200 points of a noisy sine (`two_phase_judge`'s `sine`,
    /// σ = 0.01) GCV took λ = 6.9·10^4 on seed 4, where 10^7–10^8 comes nearer the clean curve
    /// by a third, and GML took 4.9·10^7. GML assumes a smooth curve plus white noise. Where
    /// the data are that, its fit moves them by about σ: GML's RMS displacement over σ̂ was
    /// 0.78–1.17 on 32 draws of 200 noisy points of sin(x/2) (σ̂, a median of third
    /// differences, varies from draw to draw), so the factor 1.2 kept GML on all 32 (1 kept it
    /// on 26). Where the model fails it smooths far beyond the noise: tabulated airfoil
    /// ordinates, whose "noise" is rounding and shape, 1.26–25 σ̂ (the SC(2)-0714 upper
    /// surface 25 σ̂, where its 2 inflections lose to csaps), a hull waterline 90 σ̂; GCV's fit
    /// is kept there. At 1.5 the UA(2)-180 upper surface (1.31 σ̂) would take GML's fit at 3.3
    /// times GCV's S_d. One GML search, and one GCV search where GML's fit is refused; O(n)
    /// each.
    Auto,
}

/// How far GML's fit may move the free points under [`LambdaRule::Auto`], RMS, in units of
/// the data's noise estimate σ̂ (the rule's doc says why 1.2).
pub const AUTO_NOISE_FACTOR: f64 = crate::smoothing::LIKELIHOOD_NOISE_FACTOR;

/// The discrepancy rule's target RMS displacement in units of the noise estimate σ̂: 1,
/// Morozov's principle. Not a setting: `target-sd` aims at any other displacement. The issue's
/// dense prototype used 1.5; measured with the judge (README), 1.5 met the goal on as many
/// curves but moved every curve farther from its clean twin than the noisy input was.
const DISCREPANCY_NOISE_FACTOR: f64 = 1.0;

/// GCV's factor γ on the trace for the method itself: Craven and Wahba's GCV.
fn unit_gcv_gamma() -> f64 {
    1.0
}

impl LambdaRule {
    /// `discrepancy`, `gcv`, `gml` or `auto`.
    pub fn name(self) -> &'static str {
        match self {
            LambdaRule::Discrepancy => "discrepancy",
            LambdaRule::Gcv => "gcv",
            LambdaRule::Gml => "gml",
            LambdaRule::Auto => "auto",
        }
    }
}

/// The end conditions of an open parametric curve's spline (`curve-ends`). A function y(x)
/// always takes the parabolic runout, a closed curve the periodic spline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum CurveEnds {
    /// s″ = 0 at both ends: the natural spline (csaps's convention).
    #[default]
    Natural,
    /// s‴ = 0 on the first and last span (parabolic runout): the end curvature is free.
    Runout,
}

/// The end conditions of a function's spline y(x) (`function-ends`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum FunctionEnds {
    /// s‴ = 0 on the first and last span (parabolic runout, the representation's own spline
    /// function, Han et al.): the end curvature is free.
    #[default]
    Runout,
    /// s″ = 0 at both ends: the natural spline (csaps's convention).
    Natural,
    /// Each end natural or runout, chosen from the data by generalised cross-validation: of
    /// the four pairs (runout–runout, natural–runout, runout–natural, natural–natural), the one
    /// whose fit has the lowest GCV score min_λ V(λ) (V of the `gcv` rule),
    /// ties to the earlier. The end condition is a model choice like λ, and V compares the
    /// four spaces on the same data (each is n-dimensional): four GCV searches instead of
    /// one, each O(n). Where the pairs' minima lie within GCV's noise (noise large against
    /// the end's curvature) the choice is the draw's; at a strongly curved end (an
    /// airfoil's leading edge) natural is not chosen. Beyond 2000 points, and with an end
    /// clamp beyond G0 (whose targets come from the representation's spline), it is
    /// `runout`: on dense data a natural end at an inflection let noise turn the fit's
    /// curvature near the end (the `ends` module says what was measured).
    Auto,
}

/// Settings of `jump-lsq` (module docs). The defaults are those the issue asks for and the
/// measurements in the README's table confirmed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct JumpLsqSettings {
    /// Penalty weight λ: `auto` (chosen by the rule) or a number ≥ 0 (dimensionless).
    ///
    /// 0 returns the input; large values leave jumps that vary linearly along the knots.
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0))]
    pub lambda: Option<f64>,
    /// RMS displacement to aim at: `auto` (the rule's) or a length ≥ 0.
    ///
    /// Given, it overrides the rule (the discrepancy principle with this target; k σ̂ for the
    /// principle with a factor k on the report's noise estimate `sigma`).
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0))]
    pub target_sd: Option<f64>,
    /// How λ is chosen when not given: auto (the default: gml where its RMS displacement is within 1.2 σ̂, else gcv unless it moves less than 0.5 σ̂), discrepancy (RMS displacement = σ̂), gcv or gml (generalised maximum likelihood, REML).
    pub rule: LambdaRule,
    /// GCV's factor γ ≥ 1 on the trace in V(λ) = (RSS/n) / (1 − γ tr A(λ)/n)²: 1, Craven and
    /// Wahba's GCV, for the method; not a setting. γ > 1 charges each degree of freedom more
    /// (the modified GCV of Cummins, Filloon and Nychka 2001, γ = 1.4 in Kim and Gu 2004) and
    /// so smooths more; two-phase's curve pre-pass sets 1.4
    /// ([`TwoPhaseSettings::curve_prepass`](crate::two_phase::TwoPhaseSettings::curve_prepass)).
    /// As a public setting it earned no place on the judge's sets
    /// (`docs/experiments/default-smoothing.md`).
    #[serde(skip, default = "unit_gcv_gamma")]
    pub(crate) gcv_gamma: f64,
    /// Spacing exponent a ∈ [0, 16]: the weight of a row is h̄^a, h̄ its mean spacing over the median; or auto (8 or 0, whichever fits with the lowest GCV score; up to 2000 unevenly spaced points).
    ///
    /// Default 8: Δ^d J then measures the jumps in the units of the local spacing, so a
    /// densely sampled stretch (an airfoil's nose) is smoothed less per unit length than a
    /// sparse one, as if its density said where the detail is. 0 weighs every row alike,
    /// whatever its spacing. On evenly spaced points the two are the same fit.
    ///
    /// `auto` treats a as a model choice like d and the ends: for at most [`ORDER_AUTO_MAX`]
    /// points whose spacings differ (by more than 1e-6 of the largest), the fits with a = 8
    /// and a = 0 (each with its own d where `difference-order` is `auto` too) are compared by
    /// their GCV score under the `gcv` rule, the lowest kept (ties to 8), and the fit is then
    /// made with it under the settings' own rule; on evenly spaced points, and beyond, 8
    /// without a search. Twice the fits of the order's search where both are `auto`.
    /// Measured as two-phase's function pre-pass (`function-exponent`,
    /// `docs/experiments/two_phase_judge.md`): where the sampling density follows the detail GCV keeps
    /// 8, on all 40 noisy draws of the judge's NACA upper surface (cosine spacing; with a = 0
    /// two-phase ends 25 % farther from the clean curve) and on 36 with other spacings; on
    /// noisy sines sampled with spacings in a ratio of 2 it took 0 on 21 of 24 draws, which
    /// came about 10 % nearer their clean curve. On R140 upper it took 0 by a 4 % lower score
    /// and ended farther from the database's smoothed twin, so 8 stays the default. The
    /// report's `exponent` says which was used.
    #[serde(with = "crate::catalog::value::auto")]
    #[schemars(with = "crate::catalog::value::AutoNumber")]
    #[schemars(extend("minimum" = 0, "maximum" = 16))]
    pub exponent: Option<f64>,
    /// Difference order d of the jumps penalised (0 to 3), or auto (1, 2 or 3, whichever fits with the lowest GCV score; up to 2000 points).
    ///
    /// Default `auto`. A fixed d: 1 (jumps that vary alike are fair; the default before), 2 or
    /// 3. Chosen on the default judge's tuning set (`examples/default_judge.py`, 170 noisy
    /// curves with clean twins; `docs/experiments/default-smoothing.md`): with `auto` the
    /// default beat csaps and OpenCASCADE at equal displacement on 82 cases, with d = 1 on
    /// 72, with d = 2 on 72; the test set's result is reported there.
    ///
    /// `auto` treats d as a model choice like λ and the ends: for at most [`ORDER_AUTO_MAX`]
    /// points, the fits of d = 1, 2 and 3 under the `gcv` rule (with γ = 1, these ends,
    /// `function-ends = auto` choosing its pair for each d, and a curve's refits: the score of
    /// the last round) are compared by their GCV score min_λ V(λ), the lowest kept (ties to
    /// the lower d); the fit itself is then made with that d under the settings' own rule.
    /// Three GCV fits more, each O(n) per round (two where the settings' rule is GCV: the
    /// chosen order's scored fit is the run's own). A higher d leaves the jumps free to vary as a
    /// polynomial of higher degree along the knots, which suits a smooth analytic curve (a
    /// sine, an arc) and not an airfoil's nose: measured on 40 noisy draws of the judge's sine
    /// and 20 of its NACA upper surface (`docs/experiments/two_phase_judge.md`), GCV kept d = 3 on 32
    /// sines, 2 on 3, 1 on 5, and d = 1 on every airfoil and on 8 of the 9 real function
    /// rows; with `rule = auto` the sines' fits came nearer their clean curve (geometric mean
    /// of the RMS over csaps's at the same S_d 0.771 → 0.694). Beyond 2000 points d = 1. The
    /// report's `difference_order` says which was used.
    #[serde(with = "crate::catalog::value::auto_count")]
    #[schemars(with = "crate::catalog::value::AutoCount")]
    #[schemars(extend("maximum" = 3))]
    pub difference_order: Option<usize>,
    /// Parametric kind: re-solves on the chord-length knots of the previous result.
    #[schemars(range(max = 100))]
    pub refits: usize,
    /// The points form a closed curve (the last joins the first): a periodic spline.
    pub closed: bool,
    /// Open parametric curves: the spline's end conditions, natural (s'' = 0 at the ends) or runout (s''' = 0 on the end spans, the end curvature free).
    ///
    /// Default `natural` (csaps's convention). `runout` is what a function y(x) always has;
    /// natural ends pull the fit's curvature to zero at each end, a bias wherever the curve is
    /// curved there (an arc, a loop's node). Two-phase's curve pre-pass sets its own
    /// ([`TwoPhaseSettings::curve_prepass`](crate::two_phase::TwoPhaseSettings::curve_prepass):
    /// runout, measured there). No effect on functions or closed curves.
    pub curve_ends: CurveEnds,
    /// Functions y(x): the spline's end conditions, runout (s''' = 0 on the end spans), natural (s'' = 0 at the ends) or auto (each end chosen from the data by GCV).
    ///
    /// Default `runout`, the representation's own spline function (Han et al.). `auto` lets
    /// GCV choose each end; on the judge's data it took natural where the curve has no
    /// curvature at its end (a sine starting at an inflection) and runout at an airfoil's
    /// leading edge, and where the pairs score alike the choice is the draw's. Measured as
    /// two-phase's function pre-pass, which sets its own
    /// ([`TwoPhaseSettings::function_prepass`](crate::two_phase::TwoPhaseSettings::function_prepass):
    /// `auto`; `docs/experiments/two_phase_judge.md`). The output is the faired ordinates; the
    /// representation through them stays the runout spline. No effect on parametric curves.
    pub function_ends: FunctionEnds,
}

impl Default for JumpLsqSettings {
    fn default() -> Self {
        Self {
            lambda: None,
            target_sd: None,
            rule: LambdaRule::Auto,
            gcv_gamma: unit_gcv_gamma(),
            curve_ends: CurveEnds::Natural,
            function_ends: FunctionEnds::Runout,
            exponent: Some(EXPONENT_DEFAULT),
            difference_order: None,
            refits: 3,
            closed: false,
        }
    }
}

impl JumpLsqSettings {
    /// Refuses values out of range with [`Error::BadParameter`].
    pub fn validate(&self) -> Result<()> {
        let bad = |name, value: String, reason| Err(Error::BadParameter { name, value, reason });
        if let Some(l) = self.lambda {
            if !(l.is_finite() && l >= 0.0) {
                return bad("lambda", l.to_string(), "λ is a finite number ≥ 0 (or auto)");
            }
        }
        if let Some(t) = self.target_sd {
            if !(t.is_finite() && t >= 0.0) {
                return bad("target-sd", t.to_string(), "a finite length ≥ 0 (or auto)");
            }
        }
        // Not a setting of the method, but a two-phase `Prepass` passes its own.
        if !(self.gcv_gamma.is_finite() && self.gcv_gamma >= 1.0) {
            return bad("gcv-gamma", self.gcv_gamma.to_string(), "a finite number ≥ 1");
        }
        if let Some(exponent) = self
            .exponent
            .filter(|a| !(a.is_finite() && (0.0..=16.0).contains(a)))
        {
            return bad("exponent", exponent.to_string(), "a number in [0, 16] or auto");
        }
        if let Some(order) = self.difference_order.filter(|&d| d > 3) {
            return bad("difference-order", order.to_string(), "0, 1, 2, 3 or auto");
        }
        if self.refits > 100 {
            return bad("refits", self.refits.to_string(), "at most 100");
        }
        Ok(())
    }

    /// Sets λ.
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.lambda = Some(lambda);
        self
    }

    /// Sets the target RMS displacement.
    pub fn with_target_sd(mut self, target: f64) -> Self {
        self.target_sd = Some(target);
        self
    }

    /// Sets the rule.
    pub fn with_rule(mut self, rule: LambdaRule) -> Self {
        self.rule = rule;
        self
    }

    /// Sets GCV's factor γ on the trace (≥ 1; 1: Craven and Wahba's GCV), for two-phase's
    /// curve pre-pass: not a setting of the method.
    pub(crate) fn with_gcv_gamma(mut self, gamma: f64) -> Self {
        self.gcv_gamma = gamma;
        self
    }

    /// Sets the spacing exponent a.
    pub fn with_exponent(mut self, exponent: f64) -> Self {
        self.exponent = Some(exponent);
        self
    }

    /// Lets GCV choose the spacing exponent (`exponent = auto`).
    pub fn with_exponent_auto(mut self) -> Self {
        self.exponent = None;
        self
    }

    /// Sets the difference order d.
    pub fn with_difference_order(mut self, order: usize) -> Self {
        self.difference_order = Some(order);
        self
    }

    /// Lets GCV choose the difference order of a function among 1, 2 and 3
    /// (`difference-order = auto`).
    pub fn with_auto_difference_order(mut self) -> Self {
        self.difference_order = None;
        self
    }

    /// Sets the number of parametric refits.
    pub fn with_refits(mut self, refits: usize) -> Self {
        self.refits = refits;
        self
    }

    /// Marks the curve closed.
    pub fn with_closed(mut self, closed: bool) -> Self {
        self.closed = closed;
        self
    }

    /// Sets an open parametric curve's end conditions.
    pub fn with_curve_ends(mut self, ends: CurveEnds) -> Self {
        self.curve_ends = ends;
        self
    }

    /// Sets a function's end conditions.
    pub fn with_function_ends(mut self, ends: FunctionEnds) -> Self {
        self.function_ends = ends;
        self
    }
}

/// What one run chose and measured (the report's extras).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub struct JumpLsqReport {
    /// The λ used (of the last solve).
    pub lambda: f64,
    /// How it was chosen: `given`, `discrepancy`, `target-sd`, `gcv` or `gml` (under `auto`,
    /// the rule whose fit was kept).
    pub rule: String,
    /// The noise estimate σ̂ of the input points.
    pub sigma_hat: f64,
    /// The RMS displacement aimed at (discrepancy rules).
    pub target_sd: Option<f64>,
    /// The RMS displacement of the free points reached.
    pub rms_displacement: f64,
    /// GCV's value at λ (GCV rule).
    pub gcv: Option<f64>,
    /// tr A(λ), the fit's equivalent degrees of freedom (Σ over the counted points of
    /// ∂ŷ_k/∂y_k), where the rule computed it (GCV rule).
    pub trace: Option<f64>,
    /// The open spline's end conditions used, at the start and the end: `runout` or
    /// `natural` each (`auto` reports its choice); `periodic` for a closed curve.
    pub ends: [String; 2],
    /// λ stopped at the precision limit before the rule was satisfied.
    pub lambda_limited: bool,
    /// Solves made (all trial λ of all rounds).
    pub solves: usize,
    /// Parametric refits made.
    pub refits: usize,
    /// Points pinned to the edge of their tolerance band or restraining radius.
    pub pinned: usize,
    /// Points whose data weight was raised instead (when pins would contradict the other
    /// constraints, e.g. an end clamp on a curve with every point pinned).
    pub reweighted: usize,
    /// Rounds of the tolerance band's active set.
    pub band_rounds: usize,
    /// Points still outside their band after the last round (projected, then off the spline).
    pub clipped: usize,
    /// The difference order d of the penalty (`difference-order = auto` reports its choice).
    pub difference_order: usize,
    /// The spacing exponent a of the penalty (`exponent = auto` reports its choice).
    pub exponent: f64,
    /// The penalty Σ (h̄^(a/2) h_med³ Δ^d J)² of the input, on its own knots.
    pub penalty_before: f64,
    /// The same of the output, on its own knots.
    pub penalty_after: f64,
    /// The knots of the reduced basis where the fit was made on bin means (more points than
    /// the fit with one knot per point resolves in double precision: the `reduced` module),
    /// `None` with one knot per point. λ, `rule`, `gcv`, `trace`, `target-sd` and `solves`
    /// are then the fit's on those bins; σ̂, the displacement, the pins and the penalties are
    /// the points'.
    pub knots: Option<usize>,
}

/// The faired points and the report of one run of [`fair`].
#[derive(Clone, Debug)]
pub struct Faired<const D: usize> {
    /// The faired points (fixed and clamped points bit for bit).
    pub points: Vec<Vector<D>>,
    /// What was chosen and measured.
    pub report: JumpLsqReport,
    /// The knots of the last solve: the output's spline for the end clamps (the output's own
    /// chord-length knots differ slightly for the parametric kind). On the reduced basis
    /// (`report.knots` given) the bins' knots, fewer than the points.
    pub knots: Vec<f64>,
    /// The period of the last solve's knots for a closed curve (its closing knot is
    /// `knots[0] + period`), `None` for an open one.
    pub period: Option<f64>,
}

/// Rounds of the tolerance band's active set at most.
const MAX_BAND_ROUNDS: usize = 100;

fn space_error(error: SpaceError, n: usize, closed: bool) -> Error {
    match error {
        SpaceError::TooFewPoints { needed } => curve_repr::Error::TooFewPoints {
            what: if closed {
                "a closed jump-lsq curve"
            } else {
                "a jump-lsq curve"
            },
            needed,
            got: n,
        }
        .into(),
        SpaceError::Degenerate => Error::Strategy {
            strategy: NAME.into(),
            reason: "the knots are degenerate (an end condition cannot be solved)".into(),
        },
    }
}

fn pivot_error(failure: envelope::PivotFailure) -> Error {
    Error::Strategy {
        strategy: NAME.into(),
        reason: format!(
            "the system is singular at row {} (pivot {:e}): constraints that contradict each \
             other or leave no freedom (e.g. end clamps and fixed points on too few points)",
            failure.row, failure.pivot
        ),
    }
}

/// The coordinates the kind smooths: all for parametric, all but x (coordinate 0) for a
/// function.
fn smoothed<const D: usize>(domain: CurveDomain) -> [bool; D] {
    std::array::from_fn(|c| domain == CurveDomain::Parametric || c > 0)
}

fn masked<const D: usize>(points: &[Vector<D>], mask: [bool; D]) -> Vec<Vector<D>> {
    points
        .iter()
        .map(|p| Vector::<D>::from_fn(|c, _| if mask[c] { p[c] } else { 0.0 }))
        .collect()
}

/// The knots of `points` for the kind: x (strictly increasing) for a function, chord lengths
/// otherwise (closed: with the closing chord).
fn knots_of<const D: usize>(points: &[Vector<D>], domain: CurveDomain, closed: bool) -> Result<Knots> {
    match domain {
        CurveDomain::Function => {
            let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
            curve_repr::vector::check_finite_values("x", &x)?;
            curve_repr::vector::check_increasing_values("x of a function", &x)?;
            Ok(Knots::open(x))
        }
        CurveDomain::Parametric => {
            if closed {
                Ok(Knots::closed(
                    Parametrization::ChordLength.closed_parameters(points)?,
                ))
            } else {
                Ok(Knots::open(Parametrization::ChordLength.parameters(points)?))
            }
        }
    }
}

/// The spline's end conditions for `domain`: a closed curve's periodic; an open parametric
/// curve's `curve_ends`; a function's `function_ends`, where `auto` (chosen by the data in
/// `ends::choose`) stands for the representation's own runout.
fn ends_of(domain: CurveDomain, closed: bool, curve_ends: CurveEnds, function_ends: FunctionEnds) -> Ends {
    if closed {
        Ends::Periodic
    } else if domain == CurveDomain::Function {
        match function_ends {
            FunctionEnds::Natural => Ends::NATURAL,
            FunctionEnds::Runout | FunctionEnds::Auto => Ends::RUNOUT,
        }
    } else if curve_ends == CurveEnds::Runout {
        Ends::RUNOUT
    } else {
        Ends::NATURAL
    }
}

/// The report's names of `ends`' conditions (start, end).
fn ends_names(ends: Ends) -> [String; 2] {
    let name = |end: End| match end {
        End::Runout => "runout",
        End::Natural => "natural",
    };
    match ends {
        Ends::Open(start, end) => [name(start).into(), name(end).into()],
        Ends::Periodic => ["periodic".into(), "periodic".into()],
    }
}

/// The penalty of `settings`; an unresolved `auto` order or exponent (resolved at the head
/// of `fair_from`) stands for d = 1 and a = [`EXPONENT_DEFAULT`].
fn penalty_of(settings: &JumpLsqSettings) -> Penalty {
    Penalty {
        order: settings.difference_order.unwrap_or(1),
        exponent: settings.exponent.unwrap_or(EXPONENT_DEFAULT),
    }
}

/// The third-derivative jumps J_i of the interpolating spline through `points` on their own
/// knots (module docs: runout spline over x for a function, natural or periodic spline over
/// chord lengths otherwise), at the interior knots (all knots when closed). For a function
/// only the coordinates after x are meaningful (x's are 0). O(n).
pub fn jumps<const D: usize>(
    points: &[Vector<D>],
    domain: CurveDomain,
    closed: bool,
) -> Result<Vec<Vector<D>>> {
    let (space, gamma) = interpolant(
        points,
        domain,
        closed,
        ends_of(domain, closed, CurveEnds::Natural, FunctionEnds::Runout),
        Penalty::differences(0, 0.0),
    )?;
    Ok(space
        .jump_knots()
        .map(|i| space.jump_form(i).apply(&gamma))
        .collect())
}

/// The penalty Σ_r (h̄_r^(a/2) h_med³ (Δ^d J)_r)² of the spline through `points` on their own
/// knots, with the exponent a and order d of `settings` (where either is `auto`: a = 8,
/// d = 1). O(n).
pub fn jump_penalty<const D: usize>(
    points: &[Vector<D>],
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
) -> Result<f64> {
    let ends = ends_of(domain, closed, settings.curve_ends, settings.function_ends);
    let (space, gamma) = interpolant(points, domain, closed, ends, penalty_of(settings))?;
    Ok(space.penalty_of(&gamma))
}

fn interpolant<const D: usize>(
    points: &[Vector<D>],
    domain: CurveDomain,
    closed: bool,
    ends: Ends,
    penalty: Penalty,
) -> Result<(Space, Vec<Vector<D>>)> {
    check_kind::<D>(domain, closed)?;
    let knots = knots_of(points, domain, closed)?;
    let n = points.len();
    let space = Space::new(knots, ends, penalty).map_err(|e| space_error(e, n, closed))?;
    let data = masked(points, smoothed(domain));
    let gamma = space.interpolate(&data).map_err(pivot_error)?;
    Ok((space, gamma))
}

fn check_kind<const D: usize>(domain: CurveDomain, closed: bool) -> Result<()> {
    if domain == CurveDomain::Function && D < 2 {
        return Err(Error::refused(
            NAME,
            crate::Refusal::Dimension,
            "needs points with at least 2 coordinates for a function y(x)",
        ));
    }
    if domain == CurveDomain::Function && closed {
        return Err(Error::ConstraintUnsupported {
            strategy: NAME.into(),
            constraint: "a closed curve of the function kind (x must increase)".into(),
        });
    }
    Ok(())
}

/// Fairs `points` (the stage's input) with `settings`, honouring `constraints` against
/// `original` (the pipeline's input, from which the tolerance band, radii and end clamps are
/// measured). The library entry point of the method; [`JumpLsq`] is the same as a
/// [`FairingStrategy`]. O(n) per solve (module docs). Beyond 10^4 points with λ chosen by a
/// rule the fit is made on the reduced basis (module docs, "Dense data").
///
/// Errors: bad settings, too few points (4), x not increasing (function kind), repeated
/// consecutive points (parametric kind), a closed function or a closed curve with end clamps,
/// constraints that leave the system singular; on the reduced basis a G1 or G2 end clamp.
pub fn fair<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
) -> Result<Faired<D>> {
    fair_from(points, original, constraints, domain, closed, settings, None)
}

/// [`fair`] of a parametric curve on given knots instead of chord lengths: one solve round on
/// `knots` (strictly increasing; one per point, and for a closed curve one more, the closing
/// knot t_n = t_0 + period), no refits (they would return to chord lengths). For a parameter
/// correction (Hoschek's intrinsic parametrisation: the knots are the foot-point parameters
/// of the points on an earlier fit). The reported `penalty-before` is the input's on its own
/// chord-length knots, as [`fair`] reports it. O(n) per solve.
///
/// Errors: those of [`fair`], the function kind, knots of the wrong count, not finite or not
/// strictly increasing.
pub fn fair_on_knots<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    knots: &[f64],
    closed: bool,
    settings: &JumpLsqSettings,
) -> Result<Faired<D>> {
    let n = points.len();
    let expected = n + usize::from(closed);
    if knots.len() != expected {
        return Err(curve_repr::Error::LengthMismatch {
            what: "jump-lsq knots",
            expected,
            got: knots.len(),
        }
        .into());
    }
    curve_repr::vector::check_finite_values("jump-lsq knots", knots)?;
    curve_repr::vector::check_increasing_values("jump-lsq knots", knots)?;
    let given = if closed {
        Knots::closed(knots.to_vec())
    } else {
        Knots::open(knots.to_vec())
    };
    fair_from(
        points,
        original,
        constraints,
        CurveDomain::Parametric,
        closed,
        settings,
        Some(given),
    )
}

/// The most points whose difference order `auto` chooses; beyond, d = 1.
pub const ORDER_AUTO_MAX: usize = ends::AUTO_MAX;

/// The orders `difference-order = auto` compares, in order of preference on a tie.
const ORDER_CHOICES: [usize; 3] = [1, 2, 3];

/// The spacing exponent a by default (`exponent`).
pub const EXPONENT_DEFAULT: f64 = 8.0;

/// The exponents `exponent = auto` compares, in order of preference on a tie.
const EXPONENT_CHOICES: [f64; 2] = [EXPONENT_DEFAULT, 0.0];

/// Knots whose spacings differ by at most this fraction of the largest are evenly spaced:
/// there h̄ = 1 on every row up to round-off, and the exponent changes no fit.
const EVEN_SPACING: f64 = 1e-6;

/// Whether the knots of `points` (or `given`) are evenly spaced ([`EVEN_SPACING`]). O(n).
fn evenly_spaced<const D: usize>(
    points: &[Vector<D>],
    domain: CurveDomain,
    closed: bool,
    given: Option<&Knots>,
) -> Result<bool> {
    let own;
    let knots = match given {
        Some(knots) => knots,
        None => {
            own = knots_of(points, domain, closed)?;
            &own
        }
    };
    let (low, high) = (0..knots.spans())
        .map(|k| knots.spacing(k))
        .fold((f64::INFINITY, 0.0_f64), |(low, high), h| {
            (low.min(h), high.max(h))
        });
    Ok(high - low <= EVEN_SPACING * high)
}

/// The penalty's model where `difference-order` or `exponent` is `auto`: for at most
/// [`ORDER_AUTO_MAX`] points, the pair (d, a) of [`ORDER_CHOICES`] × [`EXPONENT_CHOICES`]
/// (a given one standing alone; the exponent alone at [`EXPONENT_DEFAULT`] on evenly spaced
/// knots) whose fit under the `gcv` rule (with the settings' trace factor γ, ends, refits and
/// constraints, on `given` knots if given) has the lowest GCV score (of its last round),
/// ties to the earlier pair (a = 8 before 0, then the lower d). Beyond [`ORDER_AUTO_MAX`]
/// points, where one pair is left, and where none could be scored (the fit then reports
/// why): d = 1 and a = 8 for an `auto`. Returns d, a, the solves made and the chosen pair's
/// GCV fit (`None` where there was no search or no pair was scored), which is the run's own
/// fit where the settings' rule is GCV too. O(n) per pair and round.
fn choose_model<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
    given: Option<&Knots>,
) -> Result<(usize, f64, usize, Option<Faired<D>>)> {
    let searched = points.len() <= ORDER_AUTO_MAX;
    let orders: Vec<usize> = match settings.difference_order {
        Some(order) => vec![order],
        None if searched => ORDER_CHOICES.to_vec(),
        None => vec![1],
    };
    let exponents: Vec<f64> = match settings.exponent {
        Some(exponent) => vec![exponent],
        None if searched && !evenly_spaced(points, domain, closed, given)? => EXPONENT_CHOICES.to_vec(),
        None => vec![EXPONENT_DEFAULT],
    };
    if orders.len() * exponents.len() == 1 {
        return Ok((orders[0], exponents[0], 0, None));
    }
    let mut solves = 0;
    let mut best: Option<(f64, usize, f64, Faired<D>)> = None;
    for &exponent in &exponents {
        for &order in &orders {
            let mut scored = settings
                .clone()
                .with_difference_order(order)
                .with_exponent(exponent)
                .with_rule(LambdaRule::Gcv);
            scored.lambda = None;
            scored.target_sd = None;
            let Ok(fit) = fair_per_point(
                points,
                original,
                constraints,
                domain,
                closed,
                &scored,
                given.cloned(),
            ) else {
                continue;
            };
            solves += fit.report.solves;
            let Some(score) = fit.report.gcv.filter(|v| v.is_finite()) else {
                continue;
            };
            if best.as_ref().is_none_or(|(b, ..)| score < *b) {
                best = Some((score, order, exponent, fit));
            }
        }
    }
    Ok(match best {
        Some((_, order, exponent, fit)) => (order, exponent, solves, Some(fit)),
        None => (
            settings.difference_order.unwrap_or(1),
            settings.exponent.unwrap_or(EXPONENT_DEFAULT),
            solves,
            None,
        ),
    })
}

/// [`fair`], on `given` knots in one round when they are given ([`fair_on_knots`]); beyond
/// `reduced::REDUCED_ABOVE` points with λ chosen by a rule, on the reduced basis (the
/// `reduced` module).
fn fair_from<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
    given: Option<Knots>,
) -> Result<Faired<D>> {
    if reduced::applies(points.len(), settings, given.is_some()) {
        return reduced::fair(points, original, constraints, domain, closed, settings);
    }
    fair_per_point(points, original, constraints, domain, closed, settings, given)
}

/// The checks every entry point makes of its input: `original` as long as `points`, finite
/// coordinates, constraints that name existing points. O(n).
pub(super) fn check_input<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
) -> Result<()> {
    let n = points.len();
    if original.len() != n {
        return Err(curve_repr::Error::LengthMismatch {
            what: "original points",
            expected: n,
            got: original.len(),
        }
        .into());
    }
    curve_repr::vector::check_finite(points)?;
    constraints.validate(n)
}

/// [`fair`] with one knot per point at any size: two-phase's pre-pass, which bins large
/// inputs itself. O(n) per solve.
pub(crate) fn fair_one_knot_per_point<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
) -> Result<Faired<D>> {
    fair_per_point(points, original, constraints, domain, closed, settings, None)
}

/// [`fair_from`] with one knot per point (the method of the module docs).
fn fair_per_point<const D: usize>(
    points: &[Vector<D>],
    original: &[Vector<D>],
    constraints: &Constraints,
    domain: CurveDomain,
    closed: bool,
    settings: &JumpLsqSettings,
    given: Option<Knots>,
) -> Result<Faired<D>> {
    settings.validate()?;
    if settings.difference_order.is_none() || settings.exponent.is_none() {
        // The order and exponent of least GCV score (`auto`), then the fit with them.
        let (order, exponent, solves, scored) = choose_model(
            points,
            original,
            constraints,
            domain,
            closed,
            settings,
            given.as_ref(),
        )?;
        // Under the GCV rule (λ not given) the run's fit is the chosen pair's scored fit:
        // kept, not made again. Its solves are among `solves`.
        let gcv_run =
            settings.rule == LambdaRule::Gcv && settings.lambda.is_none() && settings.target_sd.is_none();
        if let (true, Some(mut fit)) = (gcv_run, scored) {
            fit.report.solves = solves;
            return Ok(fit);
        }
        let fixed = settings
            .clone()
            .with_difference_order(order)
            .with_exponent(exponent);
        let mut fit = fair_per_point(points, original, constraints, domain, closed, &fixed, given)?;
        fit.report.solves += solves;
        return Ok(fit);
    }
    if settings.rule == LambdaRule::Auto && settings.lambda.is_none() && settings.target_sd.is_none() {
        // The shared automatic rule (`LambdaRule::Auto`, `crate::smoothing::choose`).
        use crate::smoothing::{choose, Criterion, RuleFit};
        check_kind::<D>(domain, closed)?;
        let sigma_hat = noise::noise(points, smoothed::<D>(domain), closed);
        let chosen = choose(sigma_hat, |criterion| -> Result<RuleFit<Faired<D>>> {
            let rule = match criterion {
                Criterion::Likelihood => LambdaRule::Gml,
                Criterion::CrossValidation => LambdaRule::Gcv,
            };
            let by = settings.clone().with_rule(rule);
            let fit = fair_per_point(points, original, constraints, domain, closed, &by, given.clone())?;
            Ok(RuleFit {
                rms_displacement: fit.report.rms_displacement,
                limited: fit.report.lambda_limited,
                fit,
            })
        })?;
        let mut fit = chosen.fit;
        fit.report.solves += chosen.discarded.iter().map(|f| f.report.solves).sum::<usize>();
        return Ok(fit);
    }
    check_kind::<D>(domain, closed)?;
    let n = points.len();
    check_input(points, original, constraints)?;
    let clamp = constraints.end_clamp();
    if closed && clamp != EndClamp::None {
        return Err(Error::ConstraintUnsupported {
            strategy: NAME.into(),
            constraint: format!("end clamp {} on a closed curve, which has no ends", clamp.name()),
        });
    }
    let mask = smoothed::<D>(domain);
    let mut ends = ends_of(domain, closed, settings.curve_ends, settings.function_ends);
    let penalty = penalty_of(settings);
    let data = masked(points, mask);
    let frozen: Vec<bool> = (0..n).map(|i| !constraints.is_movable(i, n)).collect();
    // End clamps beyond G0: derivatives of the spline through the ORIGINAL points. With the
    // runout ends the first and last spans are parabolas, which position, slope and
    // curvature at the end determine: G2 there holds points 1 and n − 2 at the original's
    // values and the end slopes (the same conditions, without a redundant row).
    let mut held: Vec<(usize, Vector<D>)> = Vec::new();
    let clamp_targets: Vec<(usize, bool, Vector<D>)> = match clamp.order() {
        Some(order) if order >= 1 => {
            let (space, gamma) = interpolant(original, domain, closed, ends, penalty)?;
            let runout_at = |at_end: bool| match ends {
                Ends::Open(start, end) => (if at_end { end } else { start }) == End::Runout,
                Ends::Periodic => false,
            };
            if order >= 2 {
                for (i, at_end) in [(1, false), (n - 2, true)] {
                    if !frozen[i] && runout_at(at_end) {
                        let mut p = original[i];
                        for (c, keep) in mask.iter().enumerate() {
                            if !keep {
                                p[c] = points[i][c];
                            }
                        }
                        held.push((i, p));
                    }
                }
            }
            // The natural spline's end curvature is 0 before and after: G2 is G1 there.
            [false, true]
                .map(|at_end| (1, at_end, space.end_derivative_form(1, at_end).apply(&gamma)))
                .to_vec()
        }
        _ => Vec::new(),
    };
    // The input's penalty on its own knots: those of round 0 (set there, from its system).
    let mut penalty_before = f64::NAN;
    let sigma_hat = noise::noise(points, mask, closed);
    let coordinates = mask.iter().filter(|m| **m).count();
    let exact = |i: usize| frozen[i] || held.iter().any(|(j, _)| *j == i);
    let free = (0..n).filter(|&i| !exact(i)).count();
    let (rule, target) = match (settings.lambda, settings.target_sd) {
        (Some(_), _) => ("given", None),
        (None, Some(t)) => ("target-sd", Some(t)),
        (None, None) => match settings.rule {
            LambdaRule::Discrepancy => ("discrepancy", Some(DISCREPANCY_NOISE_FACTOR * sigma_hat)),
            // `auto` is resolved into one of these at the head of `fair_from`.
            LambdaRule::Gcv | LambdaRule::Auto => ("gcv", None),
            LambdaRule::Gml => ("gml", None),
        },
    };
    let base_of = |space: &Space| {
        let mut base: Vec<Constraint<D>> = Vec::new();
        for (i, _) in frozen.iter().enumerate().filter(|(_, f)| **f) {
            base.push(Constraint {
                form: space.value_form(i),
                target: data[i],
                point: Some(i),
            });
        }
        for (i, p) in &held {
            base.push(Constraint {
                form: space.value_form(*i),
                target: masked(std::slice::from_ref(p), mask)[0],
                point: Some(*i),
            });
        }
        for &(order, at_end, target) in &clamp_targets {
            base.push(Constraint {
                form: space.end_derivative_form(order, at_end),
                target,
                point: None,
            });
        }
        base
    };
    // `auto` ends of a function (`ends::choose`). The winner's search on the whole function
    // is the round's own when the rule is GCV (same space, data and constraints), so it is
    // kept for round 0.
    let mut chosen: Option<Choice<D>> = None;
    let mut selection_solves = 0;
    if domain == CurveDomain::Function
        && !closed
        && settings.function_ends == FunctionEnds::Auto
        && clamp_targets.is_empty()
    {
        let knots = knots_of(points, domain, closed)?;
        if let Some(choice) = ends::choose(&knots, &data, &frozen, penalty, coordinates, settings.gcv_gamma) {
            ends = choice.ends;
            chosen = choice.choice;
            selection_solves = choice.solves;
        }
    }
    let rounds = if domain == CurveDomain::Parametric && given.is_none() {
        settings.refits + 1
    } else {
        1
    };
    let mut current: Vec<Vector<D>> = points.to_vec();
    let mut lambda_previous = 1.0;
    let mut report = JumpLsqReport {
        lambda: 0.0,
        rule: rule.into(),
        sigma_hat,
        target_sd: target,
        rms_displacement: 0.0,
        gcv: None,
        trace: None,
        ends: ends_names(ends),
        lambda_limited: false,
        solves: selection_solves,
        refits: rounds - 1,
        pinned: 0,
        reweighted: 0,
        band_rounds: 0,
        clipped: 0,
        difference_order: penalty.order,
        exponent: penalty.exponent,
        penalty_before: f64::NAN,
        penalty_after: 0.0,
        knots: None,
    };
    let mut last_knots = Vec::new();
    let mut last_period = None;
    let mut last_evaluation: Option<(Space, Evaluation<D>)> = None;
    for round in 0..rounds {
        optim::cancel::checkpoint()?;
        let knots = match &given {
            Some(knots) => knots.clone(),
            None => knots_of(&current, domain, closed)?,
        };
        let mut space = Space::new(knots, ends, penalty).map_err(|e| space_error(e, n, closed))?;
        last_knots = space.knots().values().to_vec();
        last_period = space.knots().period();
        let mut base = base_of(&space);
        let mut weights: Vec<f64> = vec![1.0; n];
        if round == 0 && given.is_some() {
            penalty_before = jump_penalty(points, domain, closed, settings)?;
        } else if round == 0 {
            // Round 0's knots are the input's own, so the interpolant of the input is the
            // solve at λ = 0 without constraints, on the data rows' narrow band (before the
            // penalised system is assembled, so that the two are never held together).
            let gamma = space.interpolate(&data).map_err(pivot_error)?;
            penalty_before = space.penalty_of(&gamma);
        }
        let system = System::new(&space, &data, &weights, &base);
        let lambda_max = lambda::STIFFNESS_LIMIT / system.stiffness().max(f64::MIN_POSITIVE);
        let reuse = settings.lambda.is_none() && target.is_none() && settings.rule == LambdaRule::Gcv;
        let cached = chosen.take().filter(|_| reuse && round == 0);
        let choice: Choice<D> = if let Some(choice) = cached {
            choice
        } else if space.penalty_rows() == 0 {
            let evaluation = lambda::evaluate(&system, 0.0, false, false).map_err(pivot_error)?;
            Choice {
                evaluation,
                limited: false,
                gcv: None,
                evaluations: 1,
            }
        } else if let Some(l) = settings.lambda {
            let evaluation = lambda::evaluate(&system, l, false, false).map_err(pivot_error)?;
            Choice {
                evaluation,
                limited: false,
                gcv: None,
                evaluations: 1,
            }
        } else if let Some(t) = target {
            lambda::discrepancy(&system, free as f64 * t * t, lambda_previous, lambda_max)
                .map_err(pivot_error)?
        } else if settings.rule == LambdaRule::Gml {
            lambda::gml(&system, lambda_max).map_err(pivot_error)?
        } else {
            let near = (round > 0).then(|| lambda_previous.log10());
            lambda::gcv(&system, coordinates, settings.gcv_gamma, lambda_max, near).map_err(pivot_error)?
        };
        if !system.holds(&choice.evaluation.gamma, &base) {
            return Err(crate::state::strategy_error(
                NAME,
                "the constraints contradict each other (fixed points, end clamps and the \
                 spline's end conditions cannot all hold)",
            ));
        }
        report.solves += choice.evaluations;
        report.lambda = choice.evaluation.lambda;
        report.lambda_limited = choice.limited;
        report.gcv = choice.gcv;
        report.trace = choice.evaluation.trace;
        lambda_previous = choice.evaluation.lambda.max(1e-12);
        let mut evaluation: Evaluation<D> = choice.evaluation;
        drop(system);
        // The tolerance band and radii, in the last round: pin every point that left its ball
        // to the ball's surface and re-solve at the same λ, until none is outside. Pins can
        // contradict the other constraints (an end slope on a curve whose every point is
        // pinned); then the pins are dropped and the data weights of the points that left
        // their balls are raised instead, by 2·(distance/allowed)² per round, which always
        // converges (at infinite weight a point stays at its input, inside its ball).
        let mut pins: Vec<(usize, Vector<D>)> = held.clone();
        if round + 1 == rounds {
            let mut reweighting = false;
            let mut raised = vec![false; n];
            loop {
                let candidate = assemble(points, &evaluation.values, &frozen, &pins, mask);
                let mut violators = Vec::new();
                for i in 0..n {
                    if exact(i) || pins.iter().any(|(j, _)| *j == i) {
                        continue;
                    }
                    let allowed = constraints.allowed_distance(i);
                    let distance = (candidate[i] - original[i]).norm();
                    if distance > allowed {
                        violators.push((
                            i,
                            distance,
                            allowed,
                            pin(&candidate[i], &original[i], allowed, mask),
                        ));
                    }
                }
                if violators.is_empty() || report.band_rounds >= MAX_BAND_ROUNDS {
                    break;
                }
                report.band_rounds += 1;
                if !reweighting {
                    pins.extend(violators.iter().map(|v| (v.0, v.3)));
                    let mut with_pins = base.clone();
                    for (i, target) in pins.iter().skip(held.len()) {
                        with_pins.push(Constraint {
                            form: space.value_form(*i),
                            target: masked(std::slice::from_ref(target), mask)[0],
                            point: Some(*i),
                        });
                    }
                    let system = System::new(&space, &data, &weights, &with_pins);
                    report.solves += 1;
                    match lambda::evaluate(&system, evaluation.lambda, false, false) {
                        Ok(e) if system.holds(&e.gamma, &with_pins) => {
                            evaluation = e;
                            continue;
                        }
                        _ => {
                            // Contradictory pins: reweight every point pinned so far instead.
                            reweighting = true;
                            // The end clamps' targets are derivatives on the knots of the
                            // original points; on a refit's knots they contradict even the
                            // original points, which infinite weights tend to. Reweight on
                            // the original's knots, where that limit satisfies them.
                            if round > 0 && !clamp_targets.is_empty() {
                                let knots = knots_of(original, domain, closed)?;
                                space = Space::new(knots, ends, penalty)
                                    .map_err(|e| space_error(e, n, closed))?;
                                last_knots = space.knots().values().to_vec();
                                last_period = space.knots().period();
                                base = base_of(&space);
                            }
                            for (i, _) in pins.drain(held.len()..) {
                                weights[i] *= 2.0;
                                raised[i] = true;
                            }
                        }
                    }
                } else {
                    for &(i, distance, allowed, _) in &violators {
                        // allowed > 0: a point with nothing allowed is frozen, never a violator.
                        weights[i] *= 2.0 * (distance / allowed).powi(2);
                        raised[i] = true;
                    }
                }
                let system = System::new(&space, &data, &weights, &base);
                evaluation =
                    lambda::evaluate(&system, evaluation.lambda, false, false).map_err(pivot_error)?;
                report.solves += 1;
            }
            report.reweighted = raised.iter().filter(|r| **r).count();
        }
        report.pinned = pins.len() - held.len();
        current = assemble(points, &evaluation.values, &frozen, &pins, mask);
        if round + 1 == rounds {
            last_evaluation = Some((space, evaluation));
        }
    }
    if report.lambda == 0.0 {
        // At λ = 0 the minimiser is the interpolant of the data itself: whatever the solve
        // moved by round-off keeps the input's bits (λ → 0 returns the input exactly).
        let scale = points.iter().map(|p| p.amax()).fold(f64::MIN_POSITIVE, f64::max);
        for i in 0..n {
            let inside = (points[i] - original[i]).norm() <= constraints.allowed_distance(i);
            if !exact(i) && inside && (current[i] - points[i]).amax() <= 1e-12 * scale {
                current[i] = points[i];
            }
        }
    }
    let moved: f64 = current
        .iter()
        .zip(points)
        .enumerate()
        .filter(|(i, _)| !exact(*i))
        .map(|(_, (a, b))| (a - b).norm_squared())
        .sum();
    report.rms_displacement = if free > 0 {
        (moved / free as f64).sqrt()
    } else {
        0.0
    };
    report.clipped = (0..n)
        .filter(|&i| (current[i] - original[i]).norm() > constraints.allowed_distance(i))
        .count();
    report.penalty_before = penalty_before;
    // The output's penalty on its own knots. For a function they are the last solve's (x
    // never moves), and where every output point is the spline's value (no fixed or pinned
    // point replaced it) the interpolant of the output is that spline itself: its penalty is
    // read from the solve's unknowns instead of a second assembly and factorisation.
    report.penalty_after = match last_evaluation {
        Some((space, evaluation))
            if domain == CurveDomain::Function
                && current
                    .iter()
                    .zip(&evaluation.values)
                    .all(|(p, v)| (0..D).all(|c| !mask[c] || p[c] == v[c])) =>
        {
            space.penalty_of(&evaluation.gamma)
        }
        _ => jump_penalty(&current, domain, closed, settings)?,
    };
    Ok(Faired {
        points: current,
        report,
        knots: last_knots,
        period: last_period,
    })
}

/// The output points: frozen points as given, pinned points at their pins, the others at the
/// spline's values (x kept for a function).
fn assemble<const D: usize>(
    points: &[Vector<D>],
    values: &[Vector<D>],
    frozen: &[bool],
    pins: &[(usize, Vector<D>)],
    mask: [bool; D],
) -> Vec<Vector<D>> {
    let mut out: Vec<Vector<D>> = points
        .iter()
        .zip(values)
        .zip(frozen)
        .map(|((p, v), f)| {
            if *f {
                *p
            } else {
                Vector::<D>::from_fn(|c, _| if mask[c] { v[c] } else { p[c] })
            }
        })
        .collect();
    for (i, target) in pins {
        out[*i] = *target;
    }
    out
}

/// Where a point that left its ball (radius `allowed` around `original`) is pinned: the
/// nearest point of the ball to `candidate` among those that keep the unsmoothed coordinates
/// (x of a function) of `candidate`.
fn pin<const D: usize>(
    candidate: &Vector<D>,
    original: &Vector<D>,
    allowed: f64,
    mask: [bool; D],
) -> Vector<D> {
    // The offset in the coordinates that cannot move uses up part of the radius.
    let fixed: f64 = (0..D)
        .filter(|&c| !mask[c])
        .map(|c| (candidate[c] - original[c]).powi(2))
        .sum();
    let radius = (allowed * allowed - fixed).max(0.0).sqrt();
    let centre = Vector::<D>::from_fn(|c, _| if mask[c] { original[c] } else { candidate[c] });
    project_into_ball(&centre, radius, candidate)
}

/// `jump-lsq` as a [`FairingStrategy`]: one step that moves every free point to the faired
/// position ([`fair`]), then reports done with the penalty of the output as its criterion.
///
/// Constraints: fixed points, clamped ends and points with a zero allowed distance are
/// interpolated exactly; the tolerance band and restraining radii are held by pinning the
/// points that leave their ball to its surface and re-solving (an active set that only grows;
/// any point still outside after 100 rounds is projected by
/// [`FairingState::move_point`] and counted in the report's `clipped`); G1/G2 end clamps are
/// equality constraints on the end derivatives of the output's spline (for the parametric
/// kind on the knots of the last solve, [`Faired::knots`]). Closed curves use the periodic
/// spline (from the state or `settings.closed`).
#[derive(Clone, Debug)]
pub struct JumpLsq<const D: usize> {
    settings: JumpLsqSettings,
    domain: CurveDomain,
    report: Option<JumpLsqReport>,
}

impl<const D: usize> JumpLsq<D> {
    /// The strategy with `settings` for curves of kind `domain`.
    pub fn new(settings: JumpLsqSettings, domain: CurveDomain) -> Self {
        Self {
            settings,
            domain,
            report: None,
        }
    }

    /// The settings.
    pub fn settings(&self) -> &JumpLsqSettings {
        &self.settings
    }

    /// What the last step chose and measured.
    pub fn report(&self) -> Option<&JumpLsqReport> {
        self.report.as_ref()
    }
}

impl<const D: usize> FairingStrategy<D> for JumpLsq<D> {
    fn name(&self) -> &str {
        NAME
    }

    /// Every constraint is honoured, G1 and G2 end clamps included; a closed curve cannot
    /// take an end clamp.
    fn supports(&self, constraints: &Constraints) -> Result<()> {
        if self.settings.closed && constraints.end_clamp() != EndClamp::None {
            return Err(Error::ConstraintUnsupported {
                strategy: NAME.into(),
                constraint: format!(
                    "end clamp {} on a closed curve, which has no ends",
                    constraints.end_clamp().name()
                ),
            });
        }
        Ok(())
    }

    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        self.settings.validate()?;
        check_kind::<D>(self.domain, self.settings.closed || state.is_closed())
    }

    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let closed = self.settings.closed || state.is_closed();
        let faired = fair(
            state.points(),
            state.original(),
            state.constraints(),
            self.domain,
            closed,
            &self.settings,
        )?;
        for (i, p) in faired.points.iter().enumerate() {
            if *p != state.points()[i] {
                state.move_point(i, *p)?;
            }
        }
        let criterion = faired.report.penalty_after;
        self.report = Some(faired.report);
        Ok(StepOutcome::done(Some(criterion)))
    }
}
