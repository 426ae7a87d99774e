//! Consecutive points averaged in bins, so that the noise pre-pass of a function segment or
//! an arbitrary curve with more points than its limit ([`MAX_PREPASS_POINTS`] for a function,
//! [`MAX_CURVE_PREPASS_POINTS`]) is fitted where double precision can fit it ([`super::denoise_by`], [`super::denoise_curve_by`]).
//!
//! **Why.** Both pre-pass smoothers solve a banded system with one knot per point. The cubic
//! smoothing spline's is M = R + λ QᵀΣQ (`smoothing_spline`'s module docs): on a Fourier mode
//! of frequency ω its eigenvalue is about h + λ ω⁴ h², from h (the smooth modes the fit keeps)
//! to 16 λ/h² (the noise at the Nyquist frequency), so at the λ that GCV asks for on a smooth
//! curve the condition number grows as (b/h)⁴, b the smoothing bandwidth and h the spacing.
//! On 10^6 evenly spaced points of y = sin(x/2) over [0, 20] with σ = 0.01 (b ≈ 0.2,
//! h = 2·10⁻⁵) it is of order 10^17, beyond 1/ε: the LDLᵀ solve's backward error swamps the
//! smooth modes, GCV's score jumps by 10⁻³ of itself between neighbouring λ, and two-phase
//! ended with 124–471 inflections (two draws) where the clean curve has 3. jump-lsq's system
//! is as ill-conditioned: its λ stops at its precision limit there, as it does from a few
//! thousand such points on, and the pre-pass then falls back to the cubic.
//!
//! **The remedy** is the binned smoother of large-sample smoothing (Wand & Jones, *Kernel
//! Smoothing*, 1995, on binned estimators; Eilers & Marx's P-splines, 1996, likewise fit n
//! points on far fewer knots): each run of m consecutive points is replaced by its mean
//! (x̄, ȳ), the pre-pass is fitted to the means, and its fit is read back at every x_i from
//! the natural quintic spline through it (`quintic`: C⁴, so that the points of a bin do not
//! all lie on one cubic, whose zero third-derivative jumps the output's e_i would turn into
//! round-off vibrations; a curve's from the cubic spline through it, at a parameter
//! interpolated between the bins' centres, `denoise_curve_binned`, so that the points keep
//! their order). Where m h ≪ b this changes the fit little (a mean
//! differs from the curve's value at x̄ by about f″ (m h)²/24), while the condition number
//! falls by m⁴, and the means carry σ/√m of noise. Points the pre-pass must keep (the ends,
//! fixed points) are bins of their own, so they are still interpolated and are returned bit
//! for bit.
//!
//! **How many bins** (`denoise_binned`): [`FIRST_BINS`] first, then four times as many while
//! the fit keeps more than one degree of freedom (tr A, GCV's trace) per [`BINS_PER_DOF`]
//! bins, up to [`MAX_BINS`] (one bin per point at most): a fit with k degrees of freedom resolves about k/2
//! waves, and 20 bins per degree of freedom leave about 40 bins per wave. Under a rule
//! without a trace (GML, the discrepancy rule) the finest bins are taken at once.
//!
//! On noisy sines of 3·10^5–10^6 points the bins keep the clean curve's inflections where
//! one knot per point does not, end nearer the clean curve and take a fraction of the time;
//! an arbitrary curve gains from 3·10^4 points on and not below 2.5·10^4, hence its later
//! limit. At these densities the vibration count is round-off's (the clean curve's own
//! e_i are below the rounding of the fourth differences), and bins raise it (the read-back
//! spline's third derivative jumps at the bins' centres), so it is not compared. The
//! function pre-pass's time is the fits on the bins, nearly flat in n. The measurements
//! behind these choices are in `docs/experiments/code-notes.md`.
//!
//! Bins are equal in size to within one point in each run between kept points (a run of L
//! points makes ⌈L/m⌉ bins), so the smoothers' unit weights stand (the means' variances
//! differ by at most a factor (m+1)/m). The partition itself (the crate's private `bins`
//! module) is shared with jump-lsq's reduced basis, which fits its own spline on bin means beyond 10^4 points (the
//! pre-pass calls jump-lsq with one knot per point, on its own bins). Building them is O(n),
//! reading back O(n + n_bins) for a function (one sorted sweep of the quintic) and
//! O(n log n_bins) for a curve.

/// The most points a function's pre-pass fits with one knot per point (module doc): beyond,
/// bins read back through the quintic spline came nearer the clean curve at every size
/// measured from 2 500 points on, with the clean curve's inflections and about its vibrations.
/// Up to this many points (every function row of the judge) nothing changes.
pub const MAX_PREPASS_POINTS: usize = 2_000;

/// The most points an arbitrary curve's pre-pass fits with one knot per point (module doc):
/// from 3·10^4 noisy points of an arc or a clothoid on, one knot per point left two-phase 1–7
/// inflections where bins leave 0–2, in a quarter of the time; at 2·10^4 bins are no better.
pub const MAX_CURVE_PREPASS_POINTS: usize = 25_000;

/// The most bins a binned pre-pass fits (or the pre-pass's limit of points, if larger), and
/// never more than the points: 10^5 knots still fit well in double precision (a function's
/// pre-pass on 10^5 points of the noisy sine ended two-phase with the clean curve's 3
/// inflections, RMS 2.5e-4 to it at σ = 0.01).
pub const MAX_BINS: usize = 100_000;

/// The bins a binned pre-pass starts with.
pub const FIRST_BINS: usize = 2_000;

/// The bins a binned pre-pass's fit needs per degree of freedom (tr A) to be kept.
pub const BINS_PER_DOF: usize = 20;

pub(crate) use crate::bins::Bins;
