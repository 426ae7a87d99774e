//! The spline space, the forms that act on it, and the linear system of one solve.
//!
//! [`Space`]: the interpolating cubic splines on given knots with the representation's end
//! condition, parametrised freely by n unknowns γ (B-spline coefficients with the two end
//! conditions substituted, see [`super`]). Every quantity the method needs is a short linear
//! form in γ ([`Form`]): the value at a knot (3 coefficients), a derivative at an end, the
//! third-derivative jump at a knot (5), a penalty row Δ^d J (5 + d).
//!
//! [`System`]: the normal equations of one problem, the data and penalty Gram matrices A and B
//! on one envelope, with a Lagrange multiplier per equality constraint interleaved after the
//! last unknown it touches, so that K(λ) = A + λB stays banded.

use curve_repr::Vector;

use super::basis::{cubic_ders, Knots};
use super::envelope::{Ldlt, PivotFailure, Pool, Profile};
use super::qr::GivensQr;

/// The largest stiffness λ·max_j(B_jj/A_jj) at which K(λ) is factored directly; beyond it the
/// solve runs on the stacked least-squares problem by Givens QR ([`super::qr`]). At this
/// ratio the LDLᵀ still agrees with an orthogonal solve to about 1e-7 (`super::tests`).
pub(crate) const DIRECT_LIMIT: f64 = 1e9;

/// The weight of a constraint row in the QR path, relative to its unknowns' scale.
const CONSTRAINT_WEIGHT: f64 = 1e8;

/// The largest number of coefficients of a form (a penalty row of difference order 3 with an
/// end substitution has 9).
const MAX_FORM: usize = 12;

/// The condition at one end of an open interpolating spline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum End {
    /// Parabolic runout: s‴ = 0 on the end span (the end curvature is free).
    Runout,
    /// Natural: s″ = 0 at the end.
    Natural,
}

/// The end conditions of the interpolating spline, which is the representation the method
/// fairs (and the judge measures).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ends {
    /// An open curve: the conditions at its start and at its end.
    Open(End, End),
    /// Closed curve: a periodic spline.
    Periodic,
}

impl Ends {
    /// Parabolic runout at both ends (Han et al.'s spline function).
    pub(super) const RUNOUT: Ends = Ends::Open(End::Runout, End::Runout);
    /// Natural at both ends (the parametric kind's spline).
    pub(super) const NATURAL: Ends = Ends::Open(End::Natural, End::Natural);
}

/// A linear form Σ_r c_r γ_{(start + r) mod m} over the unknowns γ (indices wrap only for
/// closed curves).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Form {
    start: usize,
    len: usize,
    c: [f64; MAX_FORM],
}

impl Form {
    /// The form's (index, coefficient) pairs for m unknowns.
    pub(super) fn entries(&self, m: usize) -> impl Iterator<Item = (usize, f64)> + Clone + '_ {
        // start < m and len ≤ m, so one subtraction wraps an index (no division per entry).
        self.c[..self.len].iter().enumerate().map(move |(r, &c)| {
            let j = self.start + r;
            (if j >= m { j - m } else { j }, c)
        })
    }

    /// Σ c_r x_{index}: the form applied to `x` (γ values).
    pub(super) fn apply<const D: usize>(&self, x: &[Vector<D>]) -> Vector<D> {
        let m = x.len();
        let mut acc = Vector::<D>::zeros();
        for (j, c) in self.entries(m) {
            acc += x[j] * c;
        }
        acc
    }
}

/// The penalty's shape: Σ_rows (h̄^(a/2) h_med³ Δ^d J)² ([`Space::penalty_row`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Penalty {
    /// The difference order d (0 to 3).
    pub order: usize,
    /// The spacing exponent a.
    pub exponent: f64,
}

impl Penalty {
    /// The penalty of Δ^d J with the spacing exponent a.
    pub(super) fn differences(order: usize, exponent: f64) -> Self {
        Penalty { order, exponent }
    }
}

/// The interpolating cubic splines on given knots (module docs).
#[derive(Clone, Debug)]
pub(crate) struct Space {
    knots: Knots,
    ends: Ends,
    penalty: Penalty,
    /// Value at knot k: coefficients on β_k, β_{k+1}, β_{k+2}.
    value: Vec<[f64; 3]>,
    /// s‴ on span k: coefficients on β_k … β_{k+3}.
    third: Vec<[f64; 4]>,
    /// Open curves: β_1 = Σ_{r≠1} start_subst[r] β_r, and β_n = Σ_{r≠2} end_subst[r] β_{n−2+r}.
    start_subst: [f64; 4],
    end_subst: [f64; 4],
    /// Open curves: derivatives of β_0 … β_3 at t_0 and of β_{n−2} … β_{n+1} at t_{n−1}.
    ders_start: [[f64; 4]; 4],
    ders_end: [[f64; 4]; 4],
    /// The median knot spacing.
    h_median: f64,
}

/// Why a space could not be built.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum SpaceError {
    /// Too few points for the end conditions.
    TooFewPoints { needed: usize },
    /// An end condition could not be solved for its coefficient (degenerate knots).
    Degenerate,
}

/// x^e by binary powering, the same products in the same order as `f64::powi` (the
/// compiler's `__powidf2`), inlined: the penalty weight of every row takes one.
#[inline]
fn powi(mut x: f64, e: i32) -> f64 {
    let recip = e < 0;
    let mut b = e.unsigned_abs();
    let mut r = 1.0;
    loop {
        if b & 1 != 0 {
            r *= x;
        }
        b /= 2;
        if b == 0 {
            break;
        }
        x *= x;
    }
    if recip {
        1.0 / r
    } else {
        r
    }
}

fn binomial_signs(order: usize) -> [f64; 4] {
    match order {
        0 => [1.0, 0.0, 0.0, 0.0],
        1 => [-1.0, 1.0, 0.0, 0.0],
        2 => [1.0, -2.0, 1.0, 0.0],
        _ => [-1.0, 3.0, -3.0, 1.0],
    }
}

impl Space {
    /// The fewest points an open curve needs (the two end substitutions must not meet).
    pub(super) const MIN_OPEN: usize = 4;
    /// The fewest points a closed curve needs.
    pub(super) const MIN_CLOSED: usize = 4;

    /// Builds the space on `knots` (strictly increasing; closed knots for `Ends::Periodic`).
    /// O(n).
    pub(super) fn new(knots: Knots, ends: Ends, penalty: Penalty) -> Result<Self, SpaceError> {
        let n = knots.len();
        let closed = ends == Ends::Periodic;
        let needed = if closed { Self::MIN_CLOSED } else { Self::MIN_OPEN };
        if n < needed {
            return Err(SpaceError::TooFewPoints { needed });
        }
        let spans = knots.spans();
        let mut value = Vec::with_capacity(n);
        let mut third = Vec::with_capacity(spans);
        let mut ders_end = [[0.0; 4]; 4];
        let mut ders_start = [[0.0; 4]; 4];
        for k in 0..spans {
            let window = knots.window(k);
            let ders = cubic_ders(&window, window[2]);
            value.push([ders[0][0], ders[0][1], ders[0][2]]);
            third.push(ders[3]);
            if k == 0 {
                ders_start = ders;
            }
            if !closed && k + 1 == spans {
                ders_end = cubic_ders(&window, window[3]);
                value.push([ders_end[0][1], ders_end[0][2], ders_end[0][3]]);
            }
        }
        let mut spacing: Vec<f64> = (0..spans).map(|k| knots.spacing(k)).collect();
        let mid = spacing.len() / 2;
        let (_, &mut h_median, _) = spacing.select_nth_unstable_by(mid, f64::total_cmp);
        let (mut start_subst, mut end_subst) = ([0.0; 4], [0.0; 4]);
        if let Ends::Open(start, end) = ends {
            // The open ends' condition rows: s‴ on the end span (runout) or s″ at the end
            // (natural), each on its own end's four coefficients.
            let start_form = match start {
                End::Runout => third[0],
                End::Natural => ders_start[2],
            };
            let end_form = match end {
                End::Runout => third[spans - 1],
                End::Natural => ders_end[2],
            };
            let pivot = start_form[1];
            let last = end_form[2];
            if !(pivot.is_finite() && pivot != 0.0 && last.is_finite() && last != 0.0) {
                return Err(SpaceError::Degenerate);
            }
            for r in 0..4 {
                if r != 1 {
                    start_subst[r] = -start_form[r] / pivot;
                }
                if r != 2 {
                    end_subst[r] = -end_form[r] / last;
                }
            }
        }
        if !(h_median.is_finite() && h_median > 0.0) {
            return Err(SpaceError::Degenerate);
        }
        Ok(Space {
            knots,
            ends,
            penalty,
            value,
            third,
            start_subst,
            end_subst,
            ders_start,
            ders_end,
            h_median,
        })
    }

    /// The number of points n (= the number of unknowns γ).
    pub(super) fn len(&self) -> usize {
        self.knots.len()
    }

    /// Whether the curve is closed.
    pub(super) fn is_closed(&self) -> bool {
        self.ends == Ends::Periodic
    }

    /// The knots.
    pub(super) fn knots(&self) -> &Knots {
        &self.knots
    }

    /// The β-form `coefficients` starting at β index `start` reduced to a form over γ: for
    /// open curves β_1 and β_n are replaced by their end conditions and the rest renumbered
    /// (β_0 → γ_0, β_j → γ_{j−1} for 2 ≤ j ≤ n − 1, β_{n+1} → γ_{n−1}); for closed curves the
    /// indices are taken modulo n and coefficients on the same unknown added.
    #[inline]
    fn reduce(&self, start: isize, coefficients: &[f64]) -> Form {
        // Open, away from the ends (nearly every form): β_j is γ_{j−1}.
        let hi = start + coefficients.len() as isize - 1;
        if !self.is_closed() && start > 1 && hi < self.len() as isize {
            let mut c = [0.0; MAX_FORM];
            c[..coefficients.len()].copy_from_slice(coefficients);
            return Form {
                start: (start - 1) as usize,
                len: coefficients.len(),
                c,
            };
        }
        self.reduce_near_ends(start, coefficients)
    }

    /// [`reduce`](Self::reduce) for closed curves and forms that touch an open curve's end
    /// substitutions.
    fn reduce_near_ends(&self, start: isize, coefficients: &[f64]) -> Form {
        let n = self.len();
        let mut form = Form {
            start: 0,
            len: 0,
            c: [0.0; MAX_FORM],
        };
        if self.is_closed() {
            let len = coefficients.len().min(n);
            form.start = start.rem_euclid(n as isize) as usize;
            form.len = len;
            for (r, &c) in coefficients.iter().enumerate() {
                form.c[r % len] += c;
            }
            return form;
        }
        let (mut lo, mut hi) = (start, start + coefficients.len() as isize - 1);
        let nb = n as isize;
        // Near an end: a buffer over β_lo … β_hi.
        let touches_start = lo <= 1 && 1 <= hi;
        let touches_end = lo <= nb && nb <= hi;
        if touches_start {
            lo = lo.min(0);
            hi = hi.max(3);
        }
        if touches_end {
            lo = lo.min(nb - 2);
            hi = hi.max(nb + 1);
        }
        let mut buffer = [0.0; MAX_FORM + 4];
        for (r, &c) in coefficients.iter().enumerate() {
            buffer[(start - lo) as usize + r] += c;
        }
        if touches_start {
            let c1 = std::mem::take(&mut buffer[(1 - lo) as usize]);
            for (r, s) in self.start_subst.iter().enumerate() {
                buffer[(r as isize - lo) as usize] += c1 * s;
            }
        }
        if touches_end {
            let cn = std::mem::take(&mut buffer[(nb - lo) as usize]);
            for (r, s) in self.end_subst.iter().enumerate() {
                buffer[(nb - 2 + r as isize - lo) as usize] += cn * s;
            }
        }
        // β_lo's unknown: γ_0 at or before β_1, γ_{j−1} inside, γ_{n−1} from β_n on.
        form.start = if lo <= 1 {
            0
        } else if lo < nb {
            (lo - 1) as usize
        } else {
            n - 1
        };
        for j in lo..=hi {
            if j == 1 || j == nb {
                continue;
            }
            form.c[form.len] = buffer[(j - lo) as usize];
            form.len += 1;
        }
        form
    }

    /// The value s(t_k) at knot k.
    #[inline]
    pub(super) fn value_form(&self, k: usize) -> Form {
        self.reduce(k as isize, &self.value[k])
    }

    /// The value s(t_k) at knot k for unknowns `gamma`: [`value_form`](Self::value_form)
    /// applied, without building the form away from an open curve's ends. O(1).
    #[inline]
    pub(super) fn value_of<const D: usize>(&self, k: usize, gamma: &[Vector<D>]) -> Vector<D> {
        if !self.is_closed() && k > 1 && k + 2 < self.len() {
            let c = &self.value[k];
            return gamma[k - 1] * c[0] + gamma[k] * c[1] + gamma[k + 1] * c[2];
        }
        self.value_form(k).apply(gamma)
    }

    /// The value s(u) at a parameter u of span k (open: k < n − 1; closed: k < n, u taken
    /// within the span's own period) for unknowns `gamma`: the four B-splines of the span
    /// at u, reduced to γ as at a knot. Reads the spline between its knots (the reduced
    /// basis evaluates its fit on bins at every input point). O(1).
    pub(super) fn value_on_span<const D: usize>(&self, k: usize, u: f64, gamma: &[Vector<D>]) -> Vector<D> {
        let ders = cubic_ders(&self.knots.window(k), u);
        self.reduce(k as isize, &ders[0]).apply(gamma)
    }

    /// The derivative of `order` (1 or 2) at the start (`at_end` false) or end of an open
    /// curve.
    pub(super) fn end_derivative_form(&self, order: usize, at_end: bool) -> Form {
        if at_end {
            self.reduce(self.len() as isize - 2, &self.ders_end[order])
        } else {
            self.reduce(0, &self.ders_start[order])
        }
    }

    /// The span index of span k wrapped for closed curves (k may be −1 or n).
    fn third_of(&self, k: isize) -> [f64; 4] {
        let spans = self.third.len() as isize;
        self.third[k.rem_euclid(spans) as usize]
    }

    /// The jump J_i = s‴(t_i+) − s‴(t_i−) at knot i (interior for open curves).
    pub(super) fn jump_form(&self, i: usize) -> Form {
        let i = i as isize;
        let (right, left) = (self.third_of(i), self.third_of(i - 1));
        let mut c = [0.0; 5];
        for r in 0..4 {
            c[r] -= left[r];
            c[r + 1] += right[r];
        }
        self.reduce(i - 1, &c)
    }

    /// The knots i that carry a jump: 1 … n − 2 open, 0 … n − 1 closed.
    pub(super) fn jump_knots(&self) -> std::ops::Range<usize> {
        if self.is_closed() {
            0..self.len()
        } else {
            1..self.len() - 1
        }
    }

    /// The number of penalty rows Δ^d J: n − 2 − d open (none if negative), n closed.
    pub(super) fn penalty_rows(&self) -> usize {
        if self.is_closed() {
            self.len()
        } else {
            (self.len() - 2).saturating_sub(self.penalty.order)
        }
    }

    /// The dimension m of the penalty's null space: the splines of the space with every
    /// penalty row zero. Open curves: the rows' kernel in the n unknowns, n − rows, where the
    /// rows are independent (measured against a dense rank in `super::tests`), but never
    /// below the cubic's (jumps all zero): lines (2) for the natural spline, parabolas (3)
    /// for the runout spline (s‴ = 0 on the end spans and no jump: one parabola), lines (2)
    /// for mixed ends (one parabola with s″ = 0 at an end). With d ≥ 1
    /// this is d + 2 for both: jumps that are polynomials of degree < d in the
    /// knot index (d dimensions; the runout spline's last span asks Σ J_i = 0, one fewer)
    /// plus the cubic's (natural 2, runout 3). Closed curves: 1 (the constants: a periodic
    /// spline without jumps is one periodic cubic, and Δ^d J = 0 around the loop with
    /// Σ J_i = 0 leaves no jump).
    pub(super) fn penalty_nullity(&self) -> usize {
        let n = self.len();
        match self.ends {
            Ends::Periodic => 1,
            Ends::Open(End::Runout, End::Runout) => n.saturating_sub(self.penalty_rows()).max(3).min(n),
            Ends::Open(..) => n.saturating_sub(self.penalty_rows()).max(2).min(n),
        }
    }

    /// h̄^a h_med⁶ for a row whose spans have mean length `mean` (relative to the median).
    #[inline]
    fn row_weight(&self, mean: f64) -> f64 {
        let scale = powi(self.h_median, 3);
        let exponent = self.penalty.exponent;
        let power = if exponent.fract() == 0.0 && exponent.abs() <= 64.0 {
            powi(mean, exponent as i32)
        } else {
            mean.powf(exponent)
        };
        power * scale * scale
    }

    /// Penalty row `row`, the row of Δ^d J over J_a … J_{a+d} (a = row + 1 open, a = row
    /// closed), as a form over γ and its weight h̄^a h_med⁶, h̄ the mean length of the d + 2
    /// spans it spans relative to the median spacing. The rows are in order of their first
    /// unknown, which keeps the QR's rotations within the band ([`System`]).
    #[inline]
    pub(super) fn penalty_row(&self, row: usize) -> (Form, f64) {
        let d = self.penalty.order;
        let a = if self.is_closed() {
            row as isize
        } else {
            row as isize + 1
        };
        let closed = self.is_closed();
        // One copy per order, so that the loops unroll and c stays in registers.
        let c = match d {
            0 => self.difference_of_jumps::<0>(a),
            1 => self.difference_of_jumps::<1>(a),
            2 => self.difference_of_jumps::<2>(a),
            _ => self.difference_of_jumps::<3>(a),
        };
        let width = if closed {
            self.knots.knot(a + d as isize + 1) - self.knots.knot(a - 1)
        } else {
            let t = self.knots.values();
            t[a as usize + d + 1] - t[a as usize - 1]
        };
        let mean = width / ((d + 2) as f64 * self.h_median);
        (self.reduce(a - 1, &c[..5 + d]), self.row_weight(mean))
    }

    /// The first and last unknown of [`value_form`](Self::value_form)`(k)`, without building
    /// it away from an open curve's ends (where it is γ_{k−1} … γ_{k+1}). O(1).
    #[inline]
    pub(super) fn value_extent(&self, k: usize) -> (usize, usize) {
        if !self.is_closed() && k > 1 && k + 2 < self.len() {
            return (k - 1, k + 1);
        }
        let form = self.value_form(k);
        (form.start, form.start + form.len - 1)
    }

    /// The first and last unknown of [`penalty_row`](Self::penalty_row)`(row)`, without
    /// building it away from an open curve's ends (γ_{row−1} … γ_{row+3+d} there). O(1).
    #[inline]
    pub(super) fn penalty_extent(&self, row: usize) -> (usize, usize) {
        let d = self.penalty.order;
        if !self.is_closed() && row > 1 && row + 4 + d < self.len() {
            return (row - 1, row + 3 + d);
        }
        let form = self.penalty_row(row).0;
        (form.start, form.start + form.len - 1)
    }

    /// The β-coefficients (from β_{a−1}) of Δ^ORDER J over the jumps J_a … J_{a+ORDER}.
    #[inline]
    fn difference_of_jumps<const ORDER: usize>(&self, a: isize) -> [f64; 9] {
        let signs = binomial_signs(ORDER);
        let mut c = [0.0; 9];
        if !self.is_closed() {
            // Open curves: 1 ≤ a and a + d ≤ n − 2, so the spans a − 1 … a + d need no
            // wrapping; they are read in place (copies of them through the stack stalled).
            let spans = &self.third[a as usize - 1..=a as usize + ORDER];
            for (q, &w) in signs.iter().enumerate().take(ORDER + 1) {
                let (left, right) = (&spans[q], &spans[q + 1]);
                for r in 0..4 {
                    c[q + 1 + r] += w * right[r];
                    c[q + r] -= w * left[r];
                }
            }
            return c;
        }
        for (q, &w) in signs.iter().enumerate().take(ORDER + 1) {
            let right = self.third_of(a + q as isize);
            let left = self.third_of(a + q as isize - 1);
            for r in 0..4 {
                c[q + 1 + r] += w * right[r];
                c[q + r] -= w * left[r];
            }
        }
        c
    }

    /// Σ_rows weight · |row · γ|²: the penalty of the spline with unknowns `gamma`. O(n).
    pub(super) fn penalty_of<const D: usize>(&self, gamma: &[Vector<D>]) -> f64 {
        (0..self.penalty_rows())
            .map(|r| {
                let (form, weight) = self.penalty_row(r);
                weight * form.apply(gamma).norm_squared()
            })
            .sum()
    }

    /// The unknowns of the interpolating spline through `values` (one per knot): the solve
    /// at λ = 0 without constraints. O(n).
    pub(super) fn interpolate<const D: usize>(
        &self,
        values: &[Vector<D>],
    ) -> Result<Vec<Vector<D>>, PivotFailure> {
        let weights = vec![1.0; self.len()];
        // Without the penalty's rows the envelope is the data rows' narrow band (half-width
        // 2 inside instead of 4 + d): a third of the storage and of the factorisation's work.
        let system = System::assemble(self, values, &weights, &[], false);
        let gamma = system.solve(0.0)?.gamma;
        Ok(gamma)
    }
}

/// An equality constraint: `form` · γ = `target`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Constraint<const D: usize> {
    pub form: Form,
    pub target: Vector<D>,
    /// The point whose value it fixes, for a value constraint: that point's data row then
    /// counts in neither the residual nor the influence trace.
    pub point: Option<usize>,
}

/// The normal equations of one problem on a [`Space`]: minimise
/// Σ_k w_k |value_k·γ − y_k|² + λ Σ_rows weight |row·γ|² subject to the constraints.
///
/// Every point keeps its data row (w_k > 0), constrained or not: a value constraint makes
/// that row's term constant, so the solution is the same, and H = NᵀWN + λB stays positive
/// definite for every λ ≥ 0 (N is square and invertible), which is what the LDLᵀ without
/// pivoting of the KKT matrix needs.
#[derive(Clone, Debug)]
pub(crate) struct System<'s, const D: usize> {
    space: &'s Space,
    data: &'s [Vector<D>],
    weights: &'s [f64],
    counted: Vec<bool>,
    constraints: Vec<Constraint<D>>,
    with_penalty: bool,
    stiffness: f64,
    /// The normal equations, assembled at the first direct solve: a search that goes straight
    /// to the Givens QR (dense data, λ at the precision limit) never needs them.
    kkt: std::cell::OnceCell<Kkt<D>>,
    /// The storage of the last factorisation, reused by the next trial λ.
    pool: Pool,
}

/// The KKT matrices of a [`System`] on their envelope: A = NᵀWN with the constraint rows, B
/// the penalty's Gram matrix, the right side, and where each unknown and multiplier sits.
#[derive(Clone, Debug)]
struct Kkt<const D: usize> {
    profile: Profile,
    var_pos: Vec<usize>,
    negative: Vec<bool>,
    a: Vec<f64>,
    b: Vec<f64>,
    rhs: Vec<Vector<D>>,
}

/// How the system at one λ was factored.
#[derive(Clone, Debug)]
pub(crate) enum Factor<'p, const D: usize> {
    /// LDLᵀ of the KKT matrix K(λ), and the solution vector in its order (unknowns and
    /// multipliers).
    Kkt { ldlt: Ldlt<'p>, x: Vec<Vector<D>> },
    /// Givens QR of the stacked least-squares problem (unknowns in the order of
    /// [`System::order_of`]).
    Qr(GivensQr<D>),
}

/// The solution at one λ.
#[derive(Clone, Debug)]
pub(crate) struct Solution<'p, const D: usize> {
    /// The factorisation.
    pub factor: Factor<'p, D>,
    /// The unknowns γ.
    pub gamma: Vec<Vector<D>>,
}

impl<'s, const D: usize> System<'s, D> {
    /// The position of unknown j in the order before the multipliers are inserted: the
    /// identity for open curves; for closed curves the folded order 0, n−1, 1, n−2, … that
    /// keeps cyclic neighbours within a band.
    fn order_of(closed: bool, m: usize, j: usize) -> usize {
        if !closed || j < m.div_ceil(2) {
            if closed {
                2 * j
            } else {
                j
            }
        } else {
            2 * (m - 1 - j) + 1
        }
    }

    /// Assembles the system: data `data[k]` with weight `weights[k]` > 0 at knot k, the
    /// penalty of `space`, and `constraints`. O(n).
    pub(super) fn new(
        space: &'s Space,
        data: &'s [Vector<D>],
        weights: &'s [f64],
        constraints: &[Constraint<D>],
    ) -> Self {
        Self::assemble(space, data, weights, constraints, true)
    }

    /// [`new`](Self::new), with the penalty (B) or without it (B = 0, for solves at λ = 0
    /// only, on the narrower envelope of the data and constraint rows).
    fn assemble(
        space: &'s Space,
        data: &'s [Vector<D>],
        weights: &'s [f64],
        constraints: &[Constraint<D>],
        with_penalty: bool,
    ) -> Self {
        let m = space.len();
        // The stiffness from the diagonals of A and B alone (the same sums, in the same order,
        // as the assembled matrices' diagonals).
        let mut stiffness: f64 = 0.0;
        if with_penalty {
            let mut diagonal_a = vec![0.0; m];
            let mut diagonal_b = vec![0.0; m];
            for (k, &w) in weights.iter().enumerate().take(m) {
                if w > 0.0 {
                    for (j, c) in space.value_form(k).entries(m) {
                        diagonal_a[j] += w * c * c;
                    }
                }
            }
            for r in 0..space.penalty_rows() {
                let (form, weight) = space.penalty_row(r);
                for (j, c) in form.entries(m) {
                    diagonal_b[j] += weight * c * c;
                }
            }
            for (a, b) in diagonal_a.iter().zip(&diagonal_b) {
                if *a > 0.0 {
                    stiffness = stiffness.max(b / a);
                }
            }
        }
        let mut counted = vec![true; m];
        for c in constraints {
            if let Some(k) = c.point {
                counted[k] = false;
            }
        }
        System {
            space,
            data,
            weights,
            counted,
            constraints: constraints.to_vec(),
            with_penalty,
            stiffness,
            kkt: std::cell::OnceCell::new(),
            pool: Pool::default(),
        }
    }

    /// The KKT matrices, assembled on first use. O(n).
    fn kkt(&self) -> &Kkt<D> {
        self.kkt.get_or_init(|| {
            Kkt::assemble(
                self.space,
                self.data,
                self.weights,
                &self.constraints,
                self.with_penalty,
            )
        })
    }
}

impl<const D: usize> Kkt<D> {
    /// Assembles the KKT matrices (module docs of [`System`]). O(n).
    fn assemble(
        space: &Space,
        data: &[Vector<D>],
        weights: &[f64],
        constraints: &[Constraint<D>],
        with_penalty: bool,
    ) -> Self {
        let penalty_rows = if with_penalty { space.penalty_rows() } else { 0 };
        let m = space.len();
        let closed = space.is_closed();
        let order = |j: usize| System::<D>::order_of(closed, m, j);
        let mut var_at = vec![0usize; m];
        for j in 0..m {
            var_at[order(j)] = j;
        }
        // Each multiplier goes right after the last (in order) unknown of its form: the
        // constraints as (anchor, index), sorted (stable: the given order on a shared anchor).
        let mut anchored: Vec<(usize, usize)> = constraints
            .iter()
            .enumerate()
            .map(|(c, constraint)| {
                let anchor = constraint
                    .form
                    .entries(m)
                    .map(|(j, _)| order(j))
                    .max()
                    .unwrap_or(0);
                (anchor, c)
            })
            .collect();
        anchored.sort_by_key(|&(anchor, _)| anchor);
        let total = m + constraints.len();
        let mut var_pos = vec![0usize; m];
        let mut con_pos = vec![0usize; constraints.len()];
        let mut negative = vec![false; total];
        let mut p = 0;
        let mut next = anchored.iter().peekable();
        for (o, &j) in var_at.iter().enumerate() {
            var_pos[j] = p;
            p += 1;
            while let Some(&(_, c)) = next.next_if(|(anchor, _)| *anchor == o) {
                con_pos[c] = p;
                negative[p] = true;
                p += 1;
            }
        }
        drop(var_at);
        let mut first: Vec<usize> = (0..total).collect();
        let widen = |form: &Form, first: &mut Vec<usize>| {
            let lowest = form.entries(m).map(|(j, _)| var_pos[j]).min().unwrap_or(0);
            for (j, _) in form.entries(m) {
                let q = var_pos[j];
                first[q] = first[q].min(lowest);
            }
        };
        for (k, _) in weights.iter().enumerate().take(m).filter(|(_, w)| **w > 0.0) {
            widen(&space.value_form(k), &mut first);
        }
        for r in 0..penalty_rows {
            widen(&space.penalty_row(r).0, &mut first);
        }
        for (c, constraint) in constraints.iter().enumerate() {
            let lowest = constraint
                .form
                .entries(m)
                .map(|(j, _)| var_pos[j])
                .min()
                .unwrap_or(0);
            first[con_pos[c]] = first[con_pos[c]].min(lowest);
        }
        let profile = Profile::new(first);
        let mut a = profile.zeros();
        // Without the penalty B is empty (K(λ) = A).
        let mut b = if with_penalty { profile.zeros() } else { Vec::new() };
        // weight · formᵀ form added to the lower triangle (the form's positions gathered once,
        // each row's storage offset looked up once).
        let outer = |values: &mut [f64], form: &Form, weight: f64| {
            let len = form.len;
            let mut pos = [0usize; MAX_FORM];
            for (p, (j, _)) in pos.iter_mut().zip(form.entries(m)) {
                *p = var_pos[j];
            }
            for (&pj, &cj) in pos[..len].iter().zip(&form.c[..len]) {
                let (first, start) = profile.row(pj);
                let wc = weight * cj;
                for (&pl, &cl) in pos[..len].iter().zip(&form.c[..len]) {
                    if pl <= pj && pl >= first {
                        values[start + (pl - first)] += wc * cl;
                    }
                }
            }
        };
        let mut rhs = vec![Vector::<D>::zeros(); total];
        for k in 0..m {
            if weights[k] > 0.0 {
                let form = space.value_form(k);
                outer(&mut a, &form, weights[k]);
                for (j, c) in form.entries(m) {
                    rhs[var_pos[j]] += data[k] * (weights[k] * c);
                }
            }
        }
        for r in 0..penalty_rows {
            let (form, weight) = space.penalty_row(r);
            outer(&mut b, &form, weight);
        }
        for (c, constraint) in constraints.iter().enumerate() {
            let row = con_pos[c];
            for (j, coefficient) in constraint.form.entries(m) {
                if let Some(index) = profile.index(row, var_pos[j]) {
                    a[index] += coefficient;
                }
            }
            rhs[row] = constraint.target;
        }
        Kkt {
            profile,
            var_pos,
            negative,
            a,
            b,
            rhs,
        }
    }
}

impl<'s, const D: usize> System<'s, D> {
    /// The largest ratio B_jj / A_jj over the unknowns with A_jj > 0: how much a given λ lets
    /// the penalty outweigh the data locally (λ times this is the stiffness that decides the
    /// solver, [`DIRECT_LIMIT`]).
    pub(super) fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// Solves at λ: LDLᵀ of K(λ) while λ·stiffness ≤ [`DIRECT_LIMIT`], Givens QR of the
    /// stacked problem beyond — and also when the LDLᵀ meets a dependent set of constraints
    /// (e.g. every point fixed and an end slope: consistent, but one row too many), which the
    /// weighted rows of the QR solve as a least-squares problem ([`holds`](Self::holds) then
    /// tells a consistent set from a contradictory one). O(n).
    pub(super) fn solve(&self, lambda: f64) -> Result<Solution<'_, D>, PivotFailure> {
        if lambda * self.stiffness <= DIRECT_LIMIT {
            let kkt = self.kkt();
            let mut values = self.pool.take();
            values.clear();
            if kkt.b.is_empty() {
                values.extend_from_slice(&kkt.a);
            } else {
                values.extend(kkt.a.iter().zip(&kkt.b).map(|(a, b)| a + lambda * b));
            }
            if let Ok(ldlt) = Ldlt::factor_in(&kkt.profile, values, &kkt.negative, Some(&self.pool)) {
                let mut x = kkt.rhs.clone();
                ldlt.solve_in_place(&mut x);
                let gamma = kkt.var_pos.iter().map(|&p| x[p]).collect();
                return Ok(Solution {
                    factor: Factor::Kkt { ldlt, x },
                    gamma,
                });
            }
        }
        // The kept storage of the direct solves is not needed by the QR: freed before the QR
        // allocates its own, so that the peak memory stays that of one factorisation.
        drop(self.pool.take());
        let qr = self.qr(lambda);
        let y = qr.solve()?;
        let m = self.space.len();
        let closed = self.space.is_closed();
        let gamma = (0..m).map(|j| y[Self::order_of(closed, m, j)]).collect();
        Ok(Solution {
            factor: Factor::Qr(qr),
            gamma,
        })
    }

    /// The Givens QR of the stacked problem at λ (data rows, penalty rows, constraint rows of
    /// weight [`CONSTRAINT_WEIGHT`] times √K_jj of their unknowns). O(n·b²).
    fn qr(&self, lambda: f64) -> GivensQr<D> {
        let space = self.space;
        let m = space.len();
        let closed = space.is_closed();
        let order = |j: usize| Self::order_of(closed, m, j);
        // Rows in the order of their leading column, so that each is deposited in R after at
        // most the band's width of rotations (data rows first would fill R and leave every
        // later row to be rotated down to the last column: O(n²)).
        #[derive(Clone, Copy)]
        enum Row {
            Data(usize),
            Penalty(usize),
            Constraint(usize),
        }
        // Each row as its leading column (high 32 bits) and a tag (kind in bits 30–31, index
        // below): 8 bytes a row, for up to 2^30 points.
        const PENALTY: u64 = 1 << 30;
        const CONSTRAINT: u64 = 2 << 30;
        let mut reach: Vec<usize> = (0..m).collect();
        let lead_end = |form: &Form| {
            let lead = form.entries(m).map(|(j, _)| order(j)).min().unwrap_or(0);
            let end = form.entries(m).map(|(j, _)| order(j)).max().unwrap_or(0);
            (lead, end)
        };
        // Open curves without constraints (the common case, and the large one): the data
        // rows' and the penalty rows' leading columns each increase with their index, so the
        // rows in order are a merge of the two streams (data first on a tie, as the sort
        // below orders them), without a list of 2n rows to sort.
        let merged = !closed && self.constraints.is_empty() && self.weights.iter().all(|w| *w > 0.0);
        let mut rows: Vec<u64> = Vec::new();
        if merged {
            let mut widen = |(lead, end): (usize, usize)| {
                reach[lead] = reach[lead].max(end);
            };
            for k in 0..m {
                widen(space.value_extent(k));
            }
            for r in 0..space.penalty_rows() {
                widen(space.penalty_extent(r));
            }
        } else {
            rows.reserve(2 * m + self.constraints.len());
            let mut add = |form: &Form, tag: u64| {
                let (lead, end) = lead_end(form);
                reach[lead] = reach[lead].max(end);
                rows.push(((lead as u64) << 32) | tag);
            };
            for k in 0..m {
                if self.weights[k] > 0.0 {
                    add(&space.value_form(k), k as u64);
                }
            }
            for r in 0..space.penalty_rows() {
                add(&space.penalty_row(r).0, PENALTY | r as u64);
            }
            for (c, constraint) in self.constraints.iter().enumerate() {
                add(&constraint.form, CONSTRAINT | c as u64);
            }
            rows.sort_unstable();
        }
        let mut qr = GivensQr::new(reach);
        if merged {
            // Each row's form built once: the next data row and the next penalty row are held,
            // and the one with the smaller leading column goes in (data first on a tie). Open
            // curves: the unknowns are in order and each form's columns are contiguous from
            // its start.
            let penalty_rows = space.penalty_rows();
            let mut scaled = [0.0; MAX_FORM];
            let (mut k, mut r) = (0usize, 0usize);
            let mut data_form = (m > 0).then(|| space.value_form(0));
            let mut penalty_form = (penalty_rows > 0).then(|| space.penalty_row(0));
            loop {
                let take_data = match (&data_form, &penalty_form) {
                    (Some(d), Some((p, _))) => d.start <= p.start,
                    (Some(_), None) => true,
                    (None, Some(_)) => false,
                    (None, None) => break,
                };
                if take_data {
                    let form = data_form.take().unwrap_or_else(|| space.value_form(k));
                    let root = self.weights[k].sqrt();
                    for (s, c) in scaled.iter_mut().zip(&form.c[..form.len]) {
                        *s = c * root;
                    }
                    qr.add_contiguous(form.start, &scaled[..form.len], self.data[k] * root);
                    k += 1;
                    data_form = (k < m).then(|| space.value_form(k));
                } else {
                    let (form, weight) = penalty_form.take().unwrap_or_else(|| space.penalty_row(r));
                    let root = (lambda * weight).sqrt();
                    for (s, c) in scaled.iter_mut().zip(&form.c[..form.len]) {
                        *s = c * root;
                    }
                    qr.add_contiguous(form.start, &scaled[..form.len], Vector::<D>::zeros());
                    r += 1;
                    penalty_form = (r < penalty_rows).then(|| space.penalty_row(r));
                }
            }
            return qr;
        }
        for packed in rows {
            let tag = packed & 0xFFFF_FFFF;
            let index = (tag & 0x3FFF_FFFF) as usize;
            let row = match tag >> 30 {
                0 => Row::Data(index),
                1 => Row::Penalty(index),
                _ => Row::Constraint(index),
            };
            match row {
                Row::Data(k) => {
                    let form = space.value_form(k);
                    let root = self.weights[k].sqrt();
                    qr.add_row(
                        form.entries(m).map(|(j, c)| (order(j), c * root)),
                        self.data[k] * root,
                    );
                }
                Row::Penalty(r) => {
                    let (form, weight) = space.penalty_row(r);
                    let root = (lambda * weight).sqrt();
                    qr.add_row(
                        form.entries(m).map(|(j, c)| (order(j), c * root)),
                        Vector::<D>::zeros(),
                    );
                }
                Row::Constraint(c) => {
                    let constraint = &self.constraints[c];
                    let form = &constraint.form;
                    let weight = self.constraint_weight(c, lambda);
                    qr.add_row(
                        form.entries(m).map(|(j, c)| (order(j), c * weight)),
                        constraint.target * weight,
                    );
                }
            }
        }
        qr
    }

    /// The weight of constraint row `c` in the QR path at λ: [`CONSTRAINT_WEIGHT`] times
    /// √K_jj(λ) of its largest unknown (at least 1), over the row's norm.
    fn constraint_weight(&self, c: usize, lambda: f64) -> f64 {
        let m = self.space.len();
        let diagonal = |j: usize| -> f64 {
            let kkt = self.kkt();
            kkt.profile
                .index(kkt.var_pos[j], kkt.var_pos[j])
                .map_or(0.0, |index| {
                    kkt.a[index] + lambda * kkt.b.get(index).unwrap_or(&0.0)
                })
        };
        let form = &self.constraints[c].form;
        let scale = form
            .entries(m)
            .map(|(j, _)| diagonal(j))
            .fold(0.0, f64::max)
            .sqrt();
        let norm = form.entries(m).map(|(_, c)| c * c).sum::<f64>().sqrt();
        CONSTRAINT_WEIGHT * scale.max(1.0) / norm
    }

    /// ln |det K(λ)| up to a constant independent of λ, for the likelihood rule
    /// ([`super::lambda::gml`]): with Z an orthonormal basis of the constraints' null space,
    /// |det K| = det(ZᵀHZ) · det(CCᵀ) (H = A + λB, C the constraint rows), so Σ ln |d_i| of
    /// the LDLᵀ is ln det(ZᵀHZ) plus a constant. In the QR path RᵀR = H + CᵀΩ²C with the
    /// constraint rows' weights Ω (which depend on λ), whose determinant is
    /// det(ΩCCᵀΩ) · det(ZᵀHZ) to leading order in the weights (1e8, relative error about
    /// 1e-16): the weights' 2 Σ ln ω_c are taken off to return the same quantity. O(n).
    pub(super) fn log_det(&self, solution: &Solution<'_, D>, lambda: f64) -> Result<f64, PivotFailure> {
        match &solution.factor {
            Factor::Kkt { ldlt, .. } => Ok(ldlt.log_abs_det()),
            Factor::Qr(qr) => {
                let weights: f64 = (0..self.constraints.len())
                    .map(|c| 2.0 * self.constraint_weight(c, lambda).ln())
                    .sum();
                Ok(qr.log_det_normal()? - weights)
            }
        }
    }

    /// The space.
    pub(super) fn space(&self) -> &Space {
        self.space
    }

    /// The equality constraints.
    pub(super) fn constraints(&self) -> &[Constraint<D>] {
        &self.constraints
    }

    /// Whether `gamma` satisfies `constraints` to 1e-9 of the data's scale (a solve of
    /// contradictory constraints leaves them unmet in the QR path, whose constraint rows are
    /// weighted). O(constraints).
    pub(super) fn holds(&self, gamma: &[Vector<D>], constraints: &[Constraint<D>]) -> bool {
        let scale = self
            .data
            .iter()
            .chain(constraints.iter().map(|c| &c.target))
            .map(|v| v.amax())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        constraints
            .iter()
            .all(|c| (c.form.apply(gamma) - c.target).amax() <= 1e-9 * scale)
    }

    /// The values of the spline at the knots for unknowns `gamma`. O(n).
    pub(super) fn values(&self, gamma: &[Vector<D>]) -> Vec<Vector<D>> {
        (0..self.space.len())
            .map(|k| self.space.value_of(k, gamma))
            .collect()
    }

    /// The spline's value at knot k for unknowns `gamma`. O(1).
    #[inline]
    pub(super) fn value_at(&self, k: usize, gamma: &[Vector<D>]) -> Vector<D> {
        self.space.value_of(k, gamma)
    }

    /// dγ/dλ at a solution: K z = [−Bγ; 0] (the constraints' targets do not depend on λ;
    /// in the QR path RᵀR z = −Bγ, the constraints held by their weights). O(n).
    pub(super) fn gamma_derivative(
        &self,
        solution: &Solution<'_, D>,
    ) -> Result<Vec<Vector<D>>, PivotFailure> {
        let m = self.space.len();
        match &solution.factor {
            Factor::Kkt { ldlt, x } => {
                let kkt = self.kkt();
                let mut z = vec![Vector::<D>::zeros(); kkt.profile.size()];
                if !kkt.b.is_empty() {
                    kkt.profile.multiply(&kkt.b, x, &mut z);
                }
                for v in z.iter_mut() {
                    *v = -*v;
                }
                ldlt.solve_in_place(&mut z);
                if kkt.var_pos.windows(2).all(|w| w[0] < w[1]) {
                    // Open curves: the unknowns' positions increase, so they are gathered to
                    // the front in place (no second vector of n points at the peak).
                    for (j, &p) in kkt.var_pos.iter().enumerate() {
                        z[j] = z[p];
                    }
                    z.truncate(m);
                    return Ok(z);
                }
                Ok(kkt.var_pos.iter().map(|&p| z[p]).collect())
            }
            Factor::Qr(qr) => {
                let closed = self.space.is_closed();
                let mut z = vec![Vector::<D>::zeros(); m];
                for r in 0..self.space.penalty_rows() {
                    let (form, weight) = self.space.penalty_row(r);
                    let v = form.apply(&solution.gamma) * weight;
                    for (j, c) in form.entries(m) {
                        z[Self::order_of(closed, m, j)] -= v * c;
                    }
                }
                qr.solve_normal(&mut z)?;
                if !closed {
                    return Ok(z);
                }
                Ok((0..m).map(|j| z[Self::order_of(closed, m, j)]).collect())
            }
        }
    }

    /// The points whose data count (no value constraint on them).
    pub(super) fn counted(&self) -> &[bool] {
        &self.counted
    }

    /// The data.
    pub(super) fn data(&self) -> &[Vector<D>] {
        self.data
    }

    /// The trace of the influence matrix ∂(value_k·γ)/∂y_k summed over the counted points:
    /// Σ_k w_k value_kᵀ Z value_k with Z the unknowns' block of K(λ)⁻¹, read from the selected
    /// inverse. (A value-constrained point would add 0: Z annihilates the constraints' rows.)
    /// O(n).
    pub(super) fn influence_trace(&self, solution: &Solution<'_, D>) -> Result<f64, PivotFailure> {
        let closed = self.space.is_closed();
        let m = self.space.len();
        let qr_profile;
        type Position<'a> = Box<dyn Fn(usize) -> usize + 'a>;
        let (z, profile, position): (Vec<f64>, &Profile, Position<'_>) = match &solution.factor {
            Factor::Kkt { ldlt, .. } => (
                ldlt.selected_inverse(),
                &self.kkt().profile,
                Box::new(|j| self.kkt().var_pos[j]),
            ),
            Factor::Qr(qr) => {
                qr_profile = qr.ldlt_profile();
                let ldlt = qr.ldlt(&qr_profile)?;
                (
                    ldlt.selected_inverse(),
                    &qr_profile,
                    Box::new(move |j| Self::order_of(closed, m, j)),
                )
            }
        };
        let m = self.space.len();
        let mut trace = 0.0;
        for k in 0..m {
            if self.weights[k] <= 0.0 || !self.counted[k] {
                continue;
            }
            let form = self.space.value_form(k);
            let mut sum = 0.0;
            for (j, cj) in form.entries(m) {
                for (l, cl) in form.entries(m) {
                    let (pj, pl) = (position(j), position(l));
                    let (hi, lo) = if pj >= pl { (pj, pl) } else { (pl, pj) };
                    if let Some(index) = profile.index(hi, lo) {
                        sum += cj * cl * z[index];
                    }
                }
            }
            trace += self.weights[k] * sum;
        }
        Ok(trace)
    }
}
