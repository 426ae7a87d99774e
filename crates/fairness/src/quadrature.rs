//! Numerical integration: Gauss–Legendre rules and adaptive Gauss–Kronrod (G7K15).
//!
//! - [`GaussLegendre`]: an n-point rule (1 ≤ n ≤ [`GaussLegendre::MAX_POINTS`]), exact for
//!   polynomials of degree 2n − 1, with nodes found by Newton's method on the Legendre
//!   polynomial P_n and weights 2 / ((1 − x²) P_n′(x)²). Used piece by piece where the
//!   integrand is a polynomial of known degree (energies of polynomial splines, the
//!   thin-plate energy per knot cell).
//! - [`Adaptive`]: adaptive G7K15 (the 15-point Kronrod extension of the 7-point Gauss rule,
//!   QUADPACK's `qk15`): every piece between break points is integrated once, then the
//!   intervals that miss their share of the tolerance are bisected, level by level over the
//!   whole curve, until the summed estimate |K15 − G7| is at most max(absolute, relative ·
//!   |integral|) (QUADPACK QAG's test) or a pool of bisections linear in the number of pieces
//!   is spent. Default relative tolerance 10⁻¹⁰.
//!
//! Both return an [`Estimate`]: the value, its error, the tolerance and whether it was met,
//! in O(pieces) time and memory whatever the integrand. [`Adaptive::integrate_pieces`] turns an
//! unmet tolerance into [`Error::NoConvergence`] (for callers that need the digits, such as an
//! optimiser); [`Adaptive::estimate_pieces`] never fails for that reason, so that a report can
//! give the estimate with its error. A NaN or infinite integrand value is [`Error::NonFinite`]:
//! never a NaN result.
//!
//! Integration nodes are interior to each piece (neither rule uses end points), so an
//! integrand built from one-sided derivatives never lands on a break.

use crate::{Error, Result};

mod segments;

pub use segments::{
    estimate_many, estimate_many_nodes, estimate_many_nodes_parallel, estimate_many_parallel, NodeIntegrands,
    Segment, SinhMap, KRONROD_POINTS, SINH_CORE, SINH_PANEL, SINH_TAIL,
};

/// An n-point Gauss–Legendre rule on [−1, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// The largest number of points [`GaussLegendre::new`] accepts.
    pub const MAX_POINTS: usize = 64;

    /// The `points`-point rule, exact for polynomials of degree `2·points − 1`. O(points²).
    ///
    /// Fails with [`Error::InvalidSetting`] unless 1 ≤ points ≤ [`MAX_POINTS`](Self::MAX_POINTS).
    pub fn new(points: usize) -> Result<Self> {
        if points == 0 || points > Self::MAX_POINTS {
            return Err(Error::InvalidSetting {
                what: "Gauss–Legendre points",
                reason: "must be between 1 and 64",
            });
        }
        let n = points;
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        let nf = n as f64;
        for i in 0..n.div_ceil(2) {
            // Tricomi's initial guess for the i-th largest root, then Newton.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (p, dp) = legendre(n, x);
                derivative = dp;
                let step = p / dp;
                x -= step;
                if step.abs() <= 1e-16 * x.abs().max(1.0) {
                    break;
                }
            }
            let (_, dp) = legendre(n, x);
            if dp.is_finite() {
                derivative = dp;
            }
            let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
            nodes[i] = x;
            weights[i] = w;
            nodes[n - 1 - i] = -x;
            weights[n - 1 - i] = w;
        }
        if n % 2 == 1 {
            nodes[n / 2] = 0.0;
        }
        Ok(GaussLegendre { nodes, weights })
    }

    /// The smallest rule exact for polynomials of degree `degree` (⌈(degree + 1)/2⌉ points).
    pub fn exact_for_degree(degree: usize) -> Result<Self> {
        Self::new(degree / 2 + 1)
    }

    /// Number of points.
    pub fn points(&self) -> usize {
        self.nodes.len()
    }

    /// Nodes on [−1, 1], decreasing.
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Weights, matching [`nodes`](Self::nodes); they sum to 2.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The rule mapped to [a, b] applied to `f`. O(points).
    pub fn integrate<F: FnMut(f64) -> f64>(&self, mut f: F, a: f64, b: f64) -> f64 {
        let half = 0.5 * (b - a);
        let mid = 0.5 * (a + b);
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(|(x, w)| w * f(mid + half * x))
            .sum::<f64>()
            * half
    }

    /// The sum of the rule over every piece between consecutive `breaks`, checked: fails with
    /// [`Error::NonFinite`] at the first node where `f` is not finite. O(points · pieces).
    pub fn integrate_pieces<F: FnMut(f64) -> f64>(
        &self,
        what: &'static str,
        mut f: F,
        breaks: &[f64],
    ) -> Result<f64> {
        Ok(self.estimate_indexed(what, |_, t| f(t), breaks)?.value)
    }

    /// [`integrate_pieces`](Self::integrate_pieces) with its accuracy, for a rule that is exact
    /// on every piece (a polynomial integrand of degree ≤ 2·points − 1): the error is the
    /// round-off alone, estimated as 16ε Σ|w_k f(t_k) h/2| (a few units in the last place per
    /// term for the integrand and the product; the sum itself is compensated), and `met` is
    /// true. `f` is also told the index of the piece (the window `breaks[i]..breaks[i + 1]`).
    /// O(points · pieces).
    pub fn estimate_indexed<F: FnMut(usize, f64) -> f64>(
        &self,
        what: &'static str,
        mut f: F,
        breaks: &[f64],
    ) -> Result<Estimate> {
        check_breaks(breaks)?;
        let mut total = CompensatedSum::default();
        for (piece, window) in breaks.windows(2).enumerate() {
            let (a, b) = (window[0], window[1]);
            let half = 0.5 * (b - a);
            let mid = 0.5 * (a + b);
            for (x, w) in self.nodes.iter().zip(&self.weights) {
                let t = mid + half * x;
                let value = f(piece, t);
                if !value.is_finite() {
                    return Err(Error::NonFinite { what, parameter: t });
                }
                total.add(w * value * half);
            }
        }
        let value = finite_result(what, total.total(), breaks)?;
        Ok(Estimate {
            value,
            error: 4.0 * total.round_off(),
            tolerance: 0.0,
            met: true,
            bisections: 0,
            limit: None,
        })
    }
}

/// P_n(x) and P_n′(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let mut p0 = 1.0;
    let mut p1 = x;
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let nf = n as f64;
    let dp = nf * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

fn check_breaks(breaks: &[f64]) -> Result<()> {
    if let Some(index) = breaks.iter().position(|b| !b.is_finite()) {
        return Err(Error::NonFiniteInput {
            what: "break point",
            index,
        });
    }
    if let Some(index) = breaks.windows(2).position(|w| w[1] < w[0]) {
        return Err(curve_repr::Error::NotIncreasing {
            what: "break points",
            index: index + 1,
            previous: breaks[index],
            value: breaks[index + 1],
        }
        .into());
    }
    Ok(())
}

fn finite_result(what: &'static str, value: f64, breaks: &[f64]) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite {
            what,
            parameter: breaks.first().copied().unwrap_or(0.0),
        })
    }
}

/// Kronrod nodes of the 15-point rule on [0, 1] (symmetric); the odd ones (1, 3, 5) and the
/// centre (7) are the 7-point Gauss nodes. QUADPACK's `qk15` values.
// QUADPACK's tables are kept digit for digit as published, beyond f64's precision.
#[allow(clippy::excessive_precision)]
pub(crate) const KRONROD_NODES: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
/// Kronrod weights matching [`KRONROD_NODES`].
// QUADPACK's tables are kept digit for digit as published, beyond f64's precision.
#[allow(clippy::excessive_precision)]
pub(crate) const KRONROD_WEIGHTS: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
/// Gauss weights of the 7-point rule, for Kronrod nodes 1, 3, 5 and the centre 7.
// QUADPACK's tables are kept digit for digit as published, beyond f64's precision.
#[allow(clippy::excessive_precision)]
pub(crate) const GAUSS7_WEIGHTS: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// The bisection budget every initial piece brings to the shared pool, whatever
/// [`Adaptive::max_subdivisions`] says: on average at most this many bisections per piece, so
/// that the work of [`Adaptive::estimate_pieces`] stays within (2 + 2·8) G7K15 evaluations
/// per piece however rough the integrand (pass 1 twice, see there, and two per bisection),
/// and the estimate comes back with its error instead.
pub const SUBDIVISIONS_PER_PIECE: usize = 8;

/// Settings of the adaptive G7K15 integrator.
///
/// Defaults: relative tolerance 10⁻¹⁰, absolute tolerance 0, at most 40 bisections of any
/// initial piece, and a pool of max(100 000, [`SUBDIVISIONS_PER_PIECE`] · pieces) bisections
/// for the whole integral (so that the budget grows with the curve, linearly).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Adaptive {
    /// Relative tolerance on the integral.
    pub relative_tolerance: f64,
    /// Absolute tolerance on the integral (the target is the larger of the two).
    pub absolute_tolerance: f64,
    /// How many times one initial piece may be halved.
    pub max_depth: u32,
    /// How many bisections may be made in all (at least [`SUBDIVISIONS_PER_PIECE`] per
    /// initial piece).
    pub max_subdivisions: usize,
}

impl Default for Adaptive {
    fn default() -> Self {
        Adaptive {
            relative_tolerance: 1e-10,
            absolute_tolerance: 0.0,
            max_depth: 40,
            max_subdivisions: 100_000,
        }
    }
}

/// An integral with its accuracy: what [`Adaptive::estimate_pieces`] and
/// [`GaussLegendre::estimate_indexed`] return, whether or not the tolerance was met.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// The best estimate of the integral.
    pub value: f64,
    /// An estimate of its absolute error: for the adaptive rule Σ |K15 − G7| over the final
    /// intervals (the error of the 7-point Gauss rule, a conservative bound on the Kronrod
    /// value's error once an interval is resolved), for an exact Gauss–Legendre rule the
    /// round-off of the sum; plus the summation's own round-off.
    pub error: f64,
    /// The absolute tolerance asked, max(absolute, relative · |value|) (0 for an exact rule).
    pub tolerance: f64,
    /// Whether `error ≤ tolerance` (always true for an exact rule).
    pub met: bool,
    /// Bisections made.
    pub bisections: usize,
    /// What stopped the refinement before the tolerance was met, if anything did.
    pub limit: Option<&'static str>,
}

impl Estimate {
    /// The value when the tolerance was met, else [`Error::NoConvergence`] with the estimate,
    /// its error and the reason. `what` names the integral.
    pub fn into_result(self, what: &'static str) -> Result<f64> {
        if self.met {
            Ok(self.value)
        } else {
            Err(Error::NoConvergence {
                what,
                estimate: self.value,
                error_estimate: self.error,
                tolerance: self.tolerance,
                reason: self
                    .limit
                    .unwrap_or("tolerance not met after refining every piece to its share"),
            })
        }
    }
}

/// Neumaier's compensated sum: the round-off of adding n terms stays a few ε of the largest
/// partial sum instead of growing with n, so that an error estimate over 10⁶ pieces is not
/// drowned by the summation itself. O(1) per term.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CompensatedSum {
    sum: f64,
    compensation: f64,
    magnitude: f64,
}

impl CompensatedSum {
    pub(crate) fn add(&mut self, value: f64) {
        let sum = self.sum + value;
        if self.sum.abs() >= value.abs() {
            self.compensation += (self.sum - sum) + value;
        } else {
            self.compensation += (value - sum) + self.sum;
        }
        self.sum = sum;
        self.magnitude += value.abs();
    }

    pub(crate) fn total(&self) -> f64 {
        self.sum + self.compensation
    }

    /// A bound on the round-off of [`total`](Self::total): 4ε Σ|terms| (Neumaier's bound is
    /// 2ε|total| + O(nε²) Σ|terms|; the factor covers the second term up to n ~ 10¹⁴).
    /// Adds another sum's terms (as if they had been added one by one, up to round-off).
    pub(crate) fn merge(&mut self, other: &CompensatedSum) {
        let magnitude = self.magnitude + other.magnitude;
        self.add(other.sum);
        self.add(other.compensation);
        self.magnitude = magnitude;
    }

    pub(crate) fn round_off(&self) -> f64 {
        4.0 * f64::EPSILON * self.magnitude
    }
}

impl Adaptive {
    /// Sets the relative tolerance.
    pub fn with_relative_tolerance(mut self, tolerance: f64) -> Self {
        self.relative_tolerance = tolerance;
        self
    }

    /// Sets the absolute tolerance.
    pub fn with_absolute_tolerance(mut self, tolerance: f64) -> Self {
        self.absolute_tolerance = tolerance;
        self
    }

    /// Sets the maximum number of halvings of one initial piece.
    pub fn with_max_depth(mut self, depth: u32) -> Self {
        self.max_depth = depth;
        self
    }

    /// Sets the maximum total number of bisections.
    pub fn with_max_subdivisions(mut self, subdivisions: usize) -> Self {
        self.max_subdivisions = subdivisions;
        self
    }

    pub(crate) fn validate(&self) -> Result<()> {
        let ok = |v: f64| v.is_finite() && v >= 0.0;
        if !ok(self.relative_tolerance) || !ok(self.absolute_tolerance) {
            return Err(Error::InvalidSetting {
                what: "quadrature tolerance",
                reason: "tolerances must be finite and non-negative",
            });
        }
        if self.relative_tolerance == 0.0 && self.absolute_tolerance == 0.0 {
            return Err(Error::InvalidSetting {
                what: "quadrature tolerance",
                reason: "one of the relative and absolute tolerances must be positive",
            });
        }
        Ok(())
    }

    /// ∫ f over [a, b]. See [`integrate_pieces`](Self::integrate_pieces).
    pub fn integrate<F: FnMut(f64) -> f64>(&self, what: &'static str, f: F, a: f64, b: f64) -> Result<f64> {
        self.integrate_pieces(what, f, &[a, b])
    }

    /// ∫ f over [breaks₀, breaks_last] to max(absolute, relative · |integral|): the value of
    /// [`estimate_pieces`](Self::estimate_pieces) when it met the tolerance, else
    /// [`Error::NoConvergence`] carrying the estimate and its error.
    ///
    /// Fails with [`Error::NonFinite`] where `f` is not finite, [`Error::NoConvergence`] when
    /// the limits are hit before the tolerance is met, and [`Error::InvalidSetting`] on bad
    /// tolerances. `what` names the integral in errors.
    pub fn integrate_pieces<F: FnMut(f64) -> f64>(
        &self,
        what: &'static str,
        f: F,
        breaks: &[f64],
    ) -> Result<f64> {
        self.estimate_pieces(what, f, breaks)?.into_result(what)
    }

    /// ∫ f over [breaks₀, breaks_last] with its error, whether or not the tolerance can be met:
    /// the pieces between consecutive breaks (where f may be non-smooth) are the initial
    /// intervals.
    ///
    /// 1. G7K15 on every piece gives the estimate T and the tolerance τ = max(absolute,
    ///    relative · |T|).
    /// 2. While the summed error Σ|K15 − G7| exceeds τ (QUADPACK QAG's global test), every
    ///    interval whose error exceeds its share of τ — half by length, half by |value|:
    ///    τ (½ ℓ/L + ½ |v|/Σ|v|), so a flat interval whose integral is near zero still has a
    ///    positive share — is bisected, one level at a time over the whole curve, with τ
    ///    updated from the improving estimate after each level. Intervals that meet their
    ///    share are added up and forgotten.
    ///
    /// Refinement therefore happens only where the integrand needs it, and stops at the first
    /// limit: an interval `max_depth` halvings deep or too small to halve is kept as it is,
    /// and the pool of max(`max_subdivisions`, [`SUBDIVISIONS_PER_PIECE`] · pieces) bisections
    /// goes, within a level, to the intervals with the largest errors. The answer is then the
    /// estimate with its error and `met = false`: never a failure for lack of convergence.
    ///
    /// Cost: O(pieces) time and memory — one G7K15 per piece plus at most two per bisection
    /// from a pool linear in the pieces, and at most the intervals of one level in memory.
    /// Step 1 keeps no interval: when its totals already meet τ (the common case: a smooth
    /// integrand, or 10⁶ pieces whose errors are each far below their share) the answer needs
    /// no memory beyond the sums. Only when they miss is step 1 run a second time, keeping
    /// the intervals that may need bisecting — the same intervals, bit for bit — so that the
    /// worst case costs two G7K15 per piece before refinement.
    ///
    /// Fails only with [`Error::NonFinite`] where `f` is not finite (the integral does not
    /// exist or overflows), [`Error::InvalidSetting`] on bad tolerances, and on breaks that
    /// are not finite or not increasing. `what` names the integral in errors.
    pub fn estimate_pieces<F: FnMut(f64) -> f64>(
        &self,
        what: &'static str,
        mut f: F,
        breaks: &[f64],
    ) -> Result<Estimate> {
        self.estimate_indexed(what, |_, t| f(t), breaks)
    }

    /// [`estimate_pieces`](Self::estimate_pieces) with an integrand that is also told the
    /// index of the piece (the window `breaks[i]..breaks[i + 1]`) that `t` lies in, so that a
    /// piecewise integrand needs no search. O(pieces).
    pub fn estimate_indexed<F: FnMut(usize, f64) -> f64>(
        &self,
        what: &'static str,
        f: F,
        breaks: &[f64],
    ) -> Result<Estimate> {
        self.estimate_split(what, f, breaks, |_, _| {})
    }

    /// [`estimate_indexed`](Self::estimate_indexed) with the initial intervals of each piece
    /// split where the caller knows the integrand changes scale: `split(i, points)` pushes
    /// increasing parameters strictly inside piece `i` (those outside are ignored). A narrow
    /// peak that no node of a single G7K15 would see — and whose |K15 − G7| would then be
    /// small though both rules miss it — is caught this way (the curvature energies split at
    /// the dips of the speed, graded to the peak's width). O(pieces + split points).
    pub fn estimate_split<F, S>(
        &self,
        what: &'static str,
        mut f: F,
        breaks: &[f64],
        mut split: S,
    ) -> Result<Estimate>
    where
        F: FnMut(usize, f64) -> f64,
        S: FnMut(usize, &mut Vec<f64>),
    {
        let mut points: Vec<f64> = Vec::new();
        let [estimate] = estimate_many(
            &[*self],
            [what],
            |piece, u| [f(piece, breaks[piece] + u)],
            breaks,
            |piece, out: &mut Vec<Segment>| {
                let (start, end) = (breaks[piece], breaks[piece + 1]);
                points.clear();
                split(piece, &mut points);
                let mut left = start;
                for right in points
                    .iter()
                    .copied()
                    .filter(|&p| p > start && p < end)
                    .chain(std::iter::once(end))
                {
                    if right > left {
                        out.push(Segment {
                            start: left - start,
                            end: right - start,
                            map: None,
                        });
                        left = right;
                    }
                }
                Ok(())
            },
        )?;
        Ok(estimate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_is_exact_to_its_degree_and_not_beyond() {
        for n in 1..=12 {
            let rule = GaussLegendre::new(n).unwrap();
            assert!((rule.weights().iter().sum::<f64>() - 2.0).abs() < 1e-14);
            for degree in 0..=(2 * n - 1) {
                let exact = if degree % 2 == 0 {
                    2.0 / (degree as f64 + 1.0)
                } else {
                    0.0
                };
                let got = rule.integrate(|x| x.powi(degree as i32), -1.0, 1.0);
                assert!((got - exact).abs() < 1e-13, "n={n} degree={degree}: {got}");
            }
            let degree = 2 * n;
            let exact = 2.0 / (degree as f64 + 1.0);
            let got = rule.integrate(|x| x.powi(degree as i32), -1.0, 1.0);
            // The Gauss–Legendre remainder for f = x^(2n), whose 2n-th derivative is the
            // constant (2n)!: E = 2^(2n+1) (n!)^4 / ((2n + 1) ((2n)!)^2).
            let factorial = |k: usize| (1..=k).map(|i| i as f64).product::<f64>();
            let remainder = 2f64.powi(2 * n as i32 + 1) * factorial(n).powi(4)
                / ((2 * n + 1) as f64 * factorial(2 * n).powi(2));
            assert!(
                ((exact - got) - remainder).abs() < 1e-6 * remainder + 1e-15,
                "n={n}, degree {degree}: error {} against remainder {remainder}",
                exact - got
            );
        }
        assert!(GaussLegendre::new(0).is_err());
        assert!(GaussLegendre::new(65).is_err());
        assert_eq!(GaussLegendre::exact_for_degree(4).unwrap().points(), 3);
    }

    #[test]
    fn gauss_legendre_64_points_are_accurate() {
        let rule = GaussLegendre::new(64).unwrap();
        let got = rule.integrate(f64::exp, 0.0, 3.0);
        assert!((got - (3.0_f64.exp() - 1.0)).abs() < 1e-13);
    }

    #[test]
    fn adaptive_meets_its_tolerance_on_a_peaked_integrand() {
        // ∫_{-1}^{1} 1/(ε² + x²) dx = (2/ε) atan(1/ε).
        let eps: f64 = 1e-3;
        let exact = 2.0 / eps * (1.0 / eps).atan();
        let got = Adaptive::default()
            .integrate("peak", |x| 1.0 / (eps * eps + x * x), -1.0, 1.0)
            .unwrap();
        assert!(((got - exact) / exact).abs() < 1e-10, "{got} {exact}");
    }

    #[test]
    fn adaptive_over_many_pieces_refines_only_where_needed_and_meets_the_global_tolerance() {
        // A peak inside one of 10 000 pieces, and an integrand that is zero on the left half
        // (pieces whose own integral is 0 still get a positive share of the tolerance).
        let eps: f64 = 1e-3;
        let centre = 0.750_03;
        let f = |x: f64| {
            if x < 0.5 {
                0.0
            } else {
                1.0 / (eps * eps + (x - centre).powi(2))
            }
        };
        let exact = (((1.0 - centre) / eps).atan() - ((0.5 - centre) / eps).atan()) / eps;
        let breaks: Vec<f64> = (0..=10_000).map(|i| i as f64 / 10_000.0).collect();
        let mut evaluations = 0usize;
        let got = Adaptive::default()
            .integrate_pieces(
                "peak",
                |x| {
                    evaluations += 1;
                    f(x)
                },
                &breaks,
            )
            .unwrap();
        assert!(((got - exact) / exact).abs() < 1e-10, "{got} {exact}");
        // One G7K15 per piece plus a bounded amount of local refinement.
        assert!(evaluations < 2 * 15 * 10_000, "{evaluations} evaluations");
    }

    #[test]
    fn adaptive_handles_kinks_at_breaks_exactly_and_inside_pieces() {
        let f = |x: f64| (x - 0.3).abs();
        let exact = 0.5 * (0.3 * 0.3 + 0.7 * 0.7);
        let with_break = Adaptive::default()
            .integrate_pieces("kink", f, &[0.0, 0.3, 1.0])
            .unwrap();
        assert!((with_break - exact).abs() < 1e-15);
        let without = Adaptive::default().integrate("kink", f, 0.0, 1.0).unwrap();
        assert!((without - exact).abs() < 1e-10 * exact);
    }

    #[test]
    fn non_convergence_is_an_error_not_a_number() {
        // 1/√x: integrable, but the error near 0 shrinks slowly; depth 5 cannot reach 1e-10.
        let result =
            Adaptive::default()
                .with_max_depth(5)
                .integrate("singular", |x: f64| 1.0 / x.sqrt(), 0.0, 1.0);
        assert!(matches!(result, Err(Error::NoConvergence { .. })), "{result:?}");
        let result = Adaptive::default().with_max_subdivisions(3).integrate(
            "oscillating",
            |x: f64| (1.0 / x).sin(),
            1e-4,
            1.0,
        );
        assert!(matches!(result, Err(Error::NoConvergence { .. })), "{result:?}");
    }

    /// The estimate never fails for lack of convergence: it says so, and its error covers the
    /// truth. ∫₀¹ 1/√x dx = 2 with only five halvings allowed cannot reach 1e-10.
    #[test]
    fn an_unmet_tolerance_is_an_estimate_with_an_honest_error() {
        let settings = Adaptive::default().with_max_depth(5);
        let estimate = settings
            .estimate_pieces("singular", |x: f64| 1.0 / x.sqrt(), &[0.0, 1.0])
            .unwrap();
        assert!(!estimate.met);
        assert_eq!(estimate.limit, Some("maximum depth reached"));
        assert!(estimate.error > estimate.tolerance);
        assert!((estimate.value - 2.0).abs() <= estimate.error, "{estimate:?}");
        assert!(matches!(
            estimate.into_result("singular"),
            Err(Error::NoConvergence { .. })
        ));
    }

    /// A smooth integrand whose pass-1 totals meet the tolerance is integrated with exactly
    /// one G7K15 per piece: pass 1 is not run a second time to keep intervals.
    #[test]
    fn met_totals_cost_one_rule_per_piece() {
        let pieces = 1000;
        let breaks: Vec<f64> = (0..=pieces).map(|i| i as f64 / pieces as f64).collect();
        let mut evaluations = 0usize;
        let estimate = Adaptive::default()
            .estimate_indexed(
                "exp",
                |_, x| {
                    evaluations += 1;
                    x.exp()
                },
                &breaks,
            )
            .unwrap();
        assert!(estimate.met && estimate.bisections == 0, "{estimate:?}");
        assert_eq!(evaluations, 15 * pieces);
        assert!((estimate.value - (1f64.exp() - 1.0)).abs() <= 1e-14);
    }

    /// A sharp peak inside every one of 20 000 pieces (width 1/100 of a piece, like the
    /// curvature peaks of a noisy spline): the work stays within the linear pool — two G7K15
    /// per piece (pass 1 summing, then again keeping the intervals to refine, since these
    /// totals miss) plus two per bisection, at most SUBDIVISIONS_PER_PIECE bisections per
    /// piece — and the answer, met or not, is within its error of the closed form.
    #[test]
    fn rough_integrands_cost_linear_time_and_report_their_error() {
        let pieces = 20_000;
        let eps: f64 = 1e-2 / pieces as f64;
        let breaks: Vec<f64> = (0..=pieces).map(|i| i as f64 / pieces as f64).collect();
        let centre = |i: usize| (i as f64 + 0.3) / pieces as f64;
        let mut evaluations = 0usize;
        let estimate = Adaptive::default()
            .estimate_indexed(
                "peaks",
                |i, x| {
                    evaluations += 1;
                    eps / (eps * eps + (x - centre(i)).powi(2))
                },
                &breaks,
            )
            .unwrap();
        let exact: f64 = (0..pieces)
            .map(|i| ((breaks[i + 1] - centre(i)) / eps).atan() - ((breaks[i] - centre(i)) / eps).atan())
            .sum();
        let bound = 15 * (2 * pieces + 2 * SUBDIVISIONS_PER_PIECE * pieces);
        assert!(evaluations <= bound, "{evaluations} evaluations > {bound}");
        assert!(estimate.bisections <= SUBDIVISIONS_PER_PIECE * pieces);
        assert!(
            (estimate.value - exact).abs() <= estimate.error.max(1e-10 * exact),
            "{estimate:?} against {exact}"
        );
        // Met within 1e-6 relative with the same budget: refinement goes where it is needed.
        let loose = Adaptive::default()
            .with_relative_tolerance(1e-6)
            .estimate_indexed(
                "peaks",
                |i, x| eps / (eps * eps + (x - centre(i)).powi(2)),
                &breaks,
            )
            .unwrap();
        assert!(loose.met, "{loose:?}");
        assert!((loose.value - exact).abs() <= 1e-6 * exact);
    }

    #[test]
    fn an_exact_rule_reports_round_off_only() {
        let rule = GaussLegendre::new(3).unwrap();
        let breaks: Vec<f64> = (0..=1000).map(|i| i as f64 * 0.001).collect();
        // ∫₀¹ x⁵ dx = 1/6, exact for 3 points.
        let estimate = rule.estimate_indexed("x^5", |_, x| x.powi(5), &breaks).unwrap();
        assert!(estimate.met && estimate.limit.is_none());
        assert!((estimate.value - 1.0 / 6.0).abs() <= estimate.error.max(1e-16));
        assert!(estimate.error > 0.0 && estimate.error < 1e-13, "{estimate:?}");
    }

    #[test]
    fn nan_integrand_and_bad_input_are_errors() {
        let result = Adaptive::default().integrate("nan", |x: f64| (x - 0.5).ln(), 0.0, 1.0);
        assert!(matches!(result, Err(Error::NonFinite { .. })), "{result:?}");
        let rule = GaussLegendre::new(3).unwrap();
        assert!(rule.integrate_pieces("nan", |_| f64::NAN, &[0.0, 1.0]).is_err());
        assert!(rule.integrate_pieces("x", |x| x, &[0.0, f64::NAN]).is_err());
        assert!(rule.integrate_pieces("x", |x| x, &[1.0, 0.0]).is_err());
        let bad = Adaptive::default().with_relative_tolerance(0.0);
        assert!(matches!(
            bad.integrate("x", |x| x, 0.0, 1.0),
            Err(Error::InvalidSetting { .. })
        ));
    }

    #[test]
    fn empty_or_degenerate_ranges_integrate_to_zero() {
        assert_eq!(
            Adaptive::default().integrate_pieces("e", |x| x, &[]).unwrap(),
            0.0
        );
        assert_eq!(Adaptive::default().integrate("e", |x| x, 1.0, 1.0).unwrap(), 0.0);
    }

    /// ∫₀¹ w/(w² + (t − c)²) dt = atan((1 − c)/w) + atan(c/w), and ∫₀¹ w³/(w² + (t − c)²)² dt
    /// = ½[z/(1 + z²) + atan z] between z = −c/w and (1 − c)/w: a peak of width 10⁻⁶ (the
    /// shape of a noisy scan's curvature peak, 10⁶ times narrower than its piece). Mapped by
    /// u = c + w sinh(s), both integrals meet 10⁻⁹ with a few halvings, and their errors
    /// bound the closed forms' distance.
    #[test]
    fn sinh_segments_resolve_a_narrow_peak_to_its_closed_form() {
        let (w, c) = (1e-6_f64, 0.3);
        let exact_1 = ((1.0 - c) / w).atan() + (c / w).atan();
        let primitive = |z: f64| 0.5 * (z / (1.0 + z * z) + z.atan());
        let exact_2 = primitive((1.0 - c) / w) - primitive(-c / w);
        // The integrand's own rounding of u − c, ε·c/w ≈ 7e-11 relative, bounds the accuracy.
        let settings = Adaptive::default().with_relative_tolerance(1e-9);
        let evaluations = std::sync::atomic::AtomicUsize::new(0);
        let f = |_: usize, t: f64| {
            evaluations.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let d = w * w + (t - c) * (t - c);
            [w / d, w * w * w / (d * d)]
        };
        let segments = |_: usize, out: &mut Vec<Segment>| {
            Segment::around_peaks(0.0, 1.0, &mut [(c, w)], out);
            Ok(())
        };
        let [one, two] =
            estimate_many(&[settings; 2], ["peak", "squared peak"], f, &[0.0, 1.0], segments).unwrap();
        for (estimate, exact) in [(one, exact_1), (two, exact_2)] {
            assert!(estimate.met, "{estimate:?}");
            assert!(
                (estimate.value - exact).abs() <= estimate.error.max(1e-15 * exact),
                "{estimate:?} against {exact}"
            );
            assert!(
                (estimate.value - exact).abs() <= 1e-9 * exact,
                "{estimate:?} against {exact}"
            );
        }
        // s runs over asinh(0.7/w) + asinh(0.3/w) ≈ 27: 12 core intervals of ½ and 8 tail
        // intervals of at most 3, then a few halvings at most. In t, G7K15 without the map sees neither peak.
        let used = evaluations.load(std::sync::atomic::Ordering::Relaxed);
        assert!(used <= 15 * 16 * 3, "{used} evaluations");
        let unmapped = Adaptive::default()
            .with_max_depth(5)
            .estimate_pieces("peak", |t| f(0, t)[0], &[0.0, 1.0])
            .unwrap();
        assert!(!unmapped.met);
    }

    /// A peak of random width (10⁻¹…10⁻⁴) and place in each of 5 000 pieces: the parallel engine gives
    /// bit for bit the sequential engine's estimates under 1, 2 and 3 threads.
    #[test]
    fn parallel_estimates_do_not_depend_on_the_thread_count() {
        let pieces = 5_000;
        let mut state: u64 = 11;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let breaks: Vec<f64> = (0..=pieces).map(|i| i as f64).collect();
        let peaks: Vec<(f64, f64)> = (0..pieces)
            .map(|_| (uniform(), 10f64.powf(-1.0 - 3.0 * uniform())))
            .collect();
        // Local parameters: u in [0, 1] on every piece.
        let f = |i: usize, t: f64| {
            let (c, w) = peaks[i];
            let d = w * w + (t - c) * (t - c);
            [w / d, (t - c) * (t - c) * w / (d * d)]
        };
        let segments = |i: usize, out: &mut Vec<Segment>| {
            Segment::around_peaks(0.0, 1.0, &mut [peaks[i]], out);
            Ok(())
        };
        let settings = [Adaptive::default(); 2];
        let sequential = estimate_many(&settings, ["a", "b"], f, &breaks, segments).unwrap();
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let parallel = pool
                .install(|| estimate_many_parallel(&settings, ["a", "b"], f, &breaks, segments))
                .unwrap();
            for (p, s) in parallel.iter().zip(&sequential) {
                assert_eq!(p.value.to_bits(), s.value.to_bits(), "{threads} threads");
                assert_eq!(p.error.to_bits(), s.error.to_bits(), "{threads} threads");
                assert_eq!(p.bisections, s.bisections);
            }
        }
        let exact: f64 = peaks
            .iter()
            .map(|&(c, w)| ((1.0 - c) / w).atan() - (-c / w).atan())
            .sum();
        assert!(sequential[0].met);
        assert!((sequential[0].value - exact).abs() <= sequential[0].error.max(1e-12 * exact));
    }
}
