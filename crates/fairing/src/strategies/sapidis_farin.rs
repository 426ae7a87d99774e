//! Sapidis–Farin fairing (Sapidis & Farin, *Automatic fairing algorithm for B-spline curves*,
//! CAD 22 (1990)), the baseline Han et al. §5 call SF: on the cubic B-spline through the data,
//! the interior knot with the largest curvature-slope jump |dκ/ds(u+) − dκ/ds(u−)| (Zhang–Cheng
//! Eq. 16) is removed and reinserted, and this is repeated.
//!
//! One step at a simple knot u = U_r: remove u once with The NURBS Book A5.8 accepting any
//! deviation (the two computations of the new control points, from the left and from the
//! right, are both kept, as A5.8 does), then insert u again (A5.1). Reinsertion gives back
//! P_{r−3} and P_{r−1} (up to round-off) and changes only P_{r−2}, to the blend of its left and
//! right computations with the insertion ratio α = (u − U_{r−2})/(U_{r+2} − U_{r−2}) (A5.1 on the
//! knot vector without u, whose index r + 1 holds U_{r+2}): that is
//! Sapidis–Farin's new control point. The curve between removal and reinsertion has no knot
//! at u, so the faired curve is C3 there: its third-derivative jump at u vanishes.
//!
//! The representation is the cubic non-rational B-spline (NURBS with unit weights) that
//! interpolates the data at chord-length parameters in [0, 1] with averaged knots (The NURBS
//! Book A9.1, [`Interpolation`]). Only P_{r−2} changes, and N_{r−2} is zero outside
//! (U_{r−2}, U_{r+2}), so the curve changes only there.
//!
//! Functions y(x) ([`CurveDomain::Function`]): the B-spline interpolates the points (x_i, y_i)
//! at the parameters u_i = (x_i − x_0)/(x_{n−1} − x_0). Its x-coordinate interpolates data
//! linear in u, which cubic interpolation reproduces, so x(u) is linear; a knot of a linear
//! function is removable exactly, so every step keeps x(u) linear (up to round-off) and the
//! curve stays the graph of a function parametrised by its abscissa. The faired data points
//! keep their x bit for bit (only y is taken from the curve).
//!
//! Data points: the method moves control points, not data points. Data point i keeps its
//! parameter t_i and is mapped to the faired curve, P̃_i = C̃(t_i); after a step only the data
//! points with t_i in (U_{r−2}, U_{r+2}) are updated (the others are left bit for bit).
//!
//! Constraints, honoured by choosing among knots (never by a partial step, which would not
//! make the knot C3):
//! - a fixed data point (or a clamped end) is never moved: a knot whose support interval
//!   (U_{r−2}, U_{r+2}) holds a frozen point's parameter is not a candidate;
//! - tolerance band and restraining radii: a knot whose step would carry a data point out of
//!   its ball (around its ORIGINAL position) is not a candidate;
//! - end clamps: P_0, P_1, P_{n−2}, P_{n−1} never change (r − 2 ≥ 2 and ≤ n − 3), so the end
//!   points and end tangents of the curve are kept (G0, G1); for G2 the first and last
//!   interior knots (which change P_2 and P_{n−3}) are excluded;
//! - closed curves are rejected.
//!
//! - the move bound ([`SapidisFarinSettings::max_move`], not in the paper): by default no data
//!   point may leave the ball of [`data_bound`](crate::displacement::data_bound) around its
//!   input position, so that a run the user did not bound cannot change the shape by more than
//!   the data's noise (the paper's unbounded run doubled an airfoil's thickness).
//!
//! At each step the candidate with the largest jump is faired; the strategy is done when the
//! largest jump over all interior knots is at most `jump_reduction` × the largest jump of the
//! initial curve, or when no knot is a candidate.
//!
//! Cost: O(n) at `init` (the interpolant, the jumps, and two tournament trees over the knots:
//! the candidates by jump, ties to the smaller index as a stable sort by decreasing jump
//! orders them, and all interior knots for the largest jump); then O(window + log n) per knot
//! tried. The step is done on a window of the curve (u_{r−W} … u_{r+W}, clamped at the cut)
//! and its control points written into the curve in place (only P_{r−2} changes beyond
//! round-off); the jumps are updated only at the five knots U_{r−2} … U_{r+2} and the trees
//! replayed above them. A refused knot leaves the candidates' tree until a step near it
//! clears its refusal, so a run tries at most n + (4p + 10)·steps knots, each O(window) and
//! O(log n) in the trees: O(n + (refusals + steps) · log n) in all, O(n log n) at worst when
//! nearly every knot is refused once (a full sort per step cost that at every step). Another
//! indicator ([`SapidisFarin::with_indicator`]) is recomputed over the whole curve after
//! every step and the trees rebuilt: O(n) a step. The same knots, curve and points bit for
//! bit as the whole-curve step after a full sort of the knots at every step (the unit tests'
//! reference).

use curve_repr::{Curve, Interpolation, InterpolationSettings, NurbsCurve, Parametrization, Side, Vector};
use fairness::curvature::{curvature_slope_at, CurvatureForm};

use super::tournament::Tournament;
use super::CurveDomain;
use crate::catalog::SharedIndicator;
use crate::state::strategy_error;
use crate::{Constraints, EndClamp, Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome};
use fairness::LocalIndicator;

/// The strategy's name, as `fair methods` lists it.
pub const NAME: &str = "sapidis-farin";

/// How far [`SapidisFarin`] may move a data point from where it was, besides the
/// constraints' tolerance band and radii ([`SapidisFarinSettings::max_move`]).
///
/// Written as `data`, `off` or a distance.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum MoveBound {
    /// A named rule.
    Rule(MoveRule),
    /// A distance, in the points' units (finite, ≥ 0).
    Distance(f64),
}

/// The named rules of a [`MoveBound`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum MoveRule {
    /// The bound the data imply: [`data_bound`](crate::displacement::data_bound) (about five
    /// noise estimates, at least the decimal step of the coordinates).
    Data,
    /// No bound beyond the constraints (the paper).
    Off,
}

impl Default for MoveBound {
    fn default() -> Self {
        MoveBound::Rule(MoveRule::Data)
    }
}

impl MoveBound {
    /// The distance this bound allows for `points` (+∞ for `off`). O(n) for `data`.
    pub fn distance<const D: usize>(&self, points: &[Vector<D>]) -> f64 {
        match *self {
            MoveBound::Rule(MoveRule::Data) => crate::displacement::data_bound(points).bound,
            MoveBound::Rule(MoveRule::Off) => f64::INFINITY,
            MoveBound::Distance(d) => d,
        }
    }
}

/// Settings of [`SapidisFarin`]: the parameters of the catalogue's `sapidis-farin`. Default: jump reduction 1e-3, max iterations 1000, moves
/// bounded by the data ([`MoveRule::Data`]).
///
/// `domain` follows the kind of curve (`--kind`) and is not a parameter of the catalogue.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct SapidisFarinSettings {
    /// Stop when the largest curvature-slope jump is this fraction of the initial one.
    ///
    /// A relative stop (the jump's unit is 1/length²), not a distance: the command's
    /// `--tolerance` bounds how far points move. Called `tolerance` before.
    #[schemars(range(min = 0))]
    pub jump_reduction: f64,
    /// Knots faired (removed and reinserted) at most.
    ///
    /// The strategy reports done after that many steps.
    pub max_iterations: usize,
    /// A function y(x) (parameters from x, x kept) or a parametric curve (chord length).
    #[serde(skip)]
    pub domain: CurveDomain,
    /// How far a data point may move from its input position without the user having asked
    /// (not in the paper): a knot whose step would carry a point farther is not faired, as
    /// for the tolerance band. Default `data`, the bound the data imply
    /// ([`data_bound`](crate::displacement::data_bound)); `off` is the paper, which on the
    /// UA(2)-180 upper surface ran 1000 steps and moved a point by 0.14 chord (y at
    /// x = 0.18 from 0.137 to 0.271, the section's thickness doubled).
    pub max_move: MoveBound,
    /// Where to act: the registered indicator whose largest value picks the next knot.
    ///
    /// Default `curvature-slope-jump`, the paper's |dκ/ds(u+) − dκ/ds(u−)|, updated at five
    /// knots per step. Another name is resolved by the catalogue and handed to
    /// [`SapidisFarin::with_indicator`]; its values (one per break of the B-spline) are
    /// recomputed over the whole curve after every step.
    pub indicator: String,
}

impl Default for SapidisFarinSettings {
    fn default() -> Self {
        Self {
            jump_reduction: 1e-3,
            max_iterations: 1000,
            domain: CurveDomain::Parametric,
            max_move: MoveBound::default(),
            indicator: Self::PAPER_INDICATOR.to_owned(),
        }
    }
}

impl SapidisFarinSettings {
    /// The paper's indicator, the curvature-slope jump, by its catalogue name.
    pub const PAPER_INDICATOR: &'static str = "curvature-slope-jump";

    /// The paper's settings: no move bound beyond the constraints; the others at their
    /// defaults.
    pub fn paper() -> Self {
        Self {
            max_move: MoveBound::Rule(MoveRule::Off),
            ..Self::default()
        }
    }

    /// Sets the relative jump reduction at which the strategy stops.
    pub fn with_jump_reduction(mut self, reduction: f64) -> Self {
        self.jump_reduction = reduction;
        self
    }

    /// Sets the domain (function or parametric curve).
    pub fn with_domain(mut self, domain: CurveDomain) -> Self {
        self.domain = domain;
        self
    }

    /// Sets the step limit.
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    /// Sets the move bound.
    pub fn with_max_move(mut self, bound: MoveBound) -> Self {
        self.max_move = bound;
        self
    }

    /// Checks the ranges: the jump reduction finite and ≥ 0, a distance bound finite and
    /// ≥ 0.
    pub fn validate(&self) -> Result<()> {
        if !(self.jump_reduction >= 0.0 && self.jump_reduction.is_finite()) {
            return Err(Error::BadParameter {
                name: "jump_reduction",
                value: self.jump_reduction.to_string(),
                reason: "must be a finite non-negative number",
            });
        }
        if let MoveBound::Distance(d) = self.max_move {
            if !(d >= 0.0 && d.is_finite()) {
                return Err(Error::BadParameter {
                    name: "max_move",
                    value: d.to_string(),
                    reason: "must be `data`, `off` or a finite distance ≥ 0",
                });
            }
        }
        Ok(())
    }
}

/// One faired knot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnotStep {
    /// The knot's value u.
    pub knot: f64,
    /// Its index r in the full knot vector.
    pub index: usize,
    /// Its curvature-slope jump before the step.
    pub jump_before: f64,
    /// The largest jump over all interior knots after the step.
    pub max_jump_after: f64,
}

/// Why the strategy stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SapidisFarinStop {
    /// The largest jump fell to `jump_reduction` of the initial one.
    JumpReduction,
    /// The step limit was reached.
    MaxIterations,
    /// No knot can be faired without breaking a constraint.
    NoCandidate,
}

/// A knot faired on a window of the curve: the faired window, the index of its first control
/// point in the curve, and the data points' new positions (index, position).
type FairedKnot<const D: usize> = (NurbsCurve<D>, usize, Vec<(usize, Vector<D>)>);

/// Sapidis–Farin knot removal and reinsertion as a [`FairingStrategy`] (module docs).
#[derive(Clone, Debug)]
pub struct SapidisFarin<const D: usize> {
    settings: SapidisFarinSettings,
    curve: Option<NurbsCurve<D>>,
    params: Vec<f64>,
    /// Jump at each interior knot index r (indexed by r; 0 elsewhere).
    jumps: Vec<f64>,
    initial_max: f64,
    history: Vec<KnotStep>,
    stop: Option<SapidisFarinStop>,
    /// The distance of [`SapidisFarinSettings::max_move`] for the input points.
    move_bound: f64,
    indicator: Option<SharedIndicator<D>>,
    /// Knots (by index) that the constraints or the move bound refused since their
    /// neighbourhood last changed: not tried again until a step near them.
    refused: Vec<bool>,
    /// Whether knot index r is a simple interior knot (the knot vector never changes).
    interior: Vec<bool>,
    /// Every interior knot by its jump: the largest jump ([`SapidisFarin::max_jump`]).
    all: Tournament,
    /// The interior knots not refused by their jump, ties to the smaller index: the order in
    /// which a stable sort of all knots by decreasing jump would try them.
    open: Tournament,
    /// Control points i with fl(fl(w_i P_i) / w_i) ≠ P_i (only where a step left a weight
    /// off 1 by round-off). A step on the whole curve (removal, then insertion, each
    /// rebuilding the curve from its homogeneous points) divides w_i P_i by w_i twice at
    /// every control point it does not change, which moves these points by round-off; the
    /// step done on a window repeats that here, so the curve stays bit for bit the one the
    /// whole-curve step gives. A point leaves the list once the division gives it back.
    drifting: Vec<usize>,
}

impl<const D: usize> SapidisFarin<D>
where
    Vector<D>: CurvatureForm,
{
    /// A strategy with `settings`.
    pub fn new(settings: SapidisFarinSettings) -> Self {
        Self {
            settings,
            curve: None,
            params: Vec::new(),
            jumps: Vec::new(),
            initial_max: 0.0,
            history: Vec::new(),
            stop: None,
            move_bound: f64::INFINITY,
            indicator: None,
            refused: Vec::new(),
            interior: Vec::new(),
            all: Tournament::default(),
            open: Tournament::default(),
            drifting: Vec::new(),
        }
    }

    /// Chooses the knot by `indicator` instead of the paper's curvature-slope jump: its
    /// values, one per break (distinct knot) of the B-spline, are recomputed over the whole
    /// curve after every step (O(n) evaluations), and the simple interior knot of the largest
    /// value is faired next. The step itself (removal and reinsertion) is unchanged.
    pub fn with_indicator(mut self, indicator: SharedIndicator<D>) -> Self {
        self.indicator = Some(indicator);
        self
    }

    /// The indicator's value at every knot index r of `curve` (0 where it is not a simple
    /// interior knot): the paper's jump, or the given indicator's value at that break.
    fn knot_values(&self, curve: &NurbsCurve<D>) -> Result<Vec<f64>> {
        let knots = curve.knots();
        let mut values = vec![0.0; knots.len()];
        match &self.indicator {
            None => {
                for r in Self::interior(curve) {
                    values[r] = Self::jump_at(curve, knots[r])?;
                }
            }
            Some(indicator) => {
                let breaks = curve.breaks();
                let at_breaks = indicator.values(curve as &dyn Curve<D>)?;
                if at_breaks.len() != breaks.len() {
                    return Err(strategy_error(
                        NAME,
                        format!(
                            "indicator `{}` gave {} values for {} breaks",
                            indicator.name(),
                            at_breaks.len(),
                            breaks.len()
                        ),
                    ));
                }
                for r in Self::interior(curve) {
                    let b = breaks.partition_point(|&t| t < knots[r]);
                    let value = at_breaks.get(b).copied().unwrap_or(0.0);
                    if !value.is_finite() {
                        return Err(strategy_error(
                            NAME,
                            format!("indicator `{}` is {value} at knot {}", indicator.name(), knots[r]),
                        ));
                    }
                    values[r] = value.abs();
                }
            }
        }
        Ok(values)
    }

    /// The current B-spline (after `init`).
    pub fn curve(&self) -> Option<&NurbsCurve<D>> {
        self.curve.as_ref()
    }

    /// The data points' parameters t_i on the curve.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Every step made, in order.
    pub fn history(&self) -> &[KnotStep] {
        &self.history
    }

    /// Why the strategy stopped, once it has.
    pub fn stop(&self) -> Option<SapidisFarinStop> {
        self.stop
    }

    /// The distance no data point may move from its input position (the constraints aside):
    /// [`SapidisFarinSettings::max_move`] for the input points, after `init`.
    pub fn move_bound(&self) -> f64 {
        self.move_bound
    }

    /// The largest jump of the initial curve.
    pub fn initial_max_jump(&self) -> f64 {
        self.initial_max
    }

    /// The largest current jump over the interior knots. O(1).
    pub fn max_jump(&self) -> f64 {
        self.all.best().map_or(0.0, |r| self.jumps[r])
    }

    /// Builds the trees of [`SapidisFarin::all`] and [`SapidisFarin::open`] from the jumps,
    /// the interior knots and the refusals. O(n).
    fn build_trees(&mut self) {
        let blocked: Vec<bool> = self.interior.iter().map(|&interior| !interior).collect();
        self.all = Tournament::new(&self.jumps, &blocked);
        let blocked: Vec<bool> = self
            .interior
            .iter()
            .zip(&self.refused)
            .map(|(&interior, &refused)| !interior || refused)
            .collect();
        self.open = Tournament::new(&self.jumps, &blocked);
    }

    /// Whether dividing w P by w gives P back bit for bit (module docs of
    /// [`SapidisFarin::drifting`]).
    fn settled(point: &Vector<D>, weight: f64) -> bool {
        (point * weight) / weight == *point
    }

    /// |dκ/ds(u+) − dκ/ds(u−)| at knot u of `curve`.
    pub fn jump_at(curve: &NurbsCurve<D>, u: f64) -> Result<f64> {
        let slope = |side| {
            curvature_slope_at(curve, u, side)
                .map_err(|e| strategy_error(NAME, format!("curvature slope at knot {u}: {e}")))
        };
        let jump = (slope(Side::Right)? - slope(Side::Left)?).abs();
        if jump.is_finite() {
            Ok(jump)
        } else {
            Err(strategy_error(
                NAME,
                format!("curvature-slope jump at knot {u} is not finite"),
            ))
        }
    }

    /// Indices r of the simple interior knots.
    fn interior(curve: &NurbsCurve<D>) -> Vec<usize> {
        let knots = curve.knots();
        let p = curve.degree();
        (p + 1..knots.len().saturating_sub(p + 1))
            .filter(|&r| knots[r - 1] < knots[r] && knots[r] < knots[r + 1])
            .collect()
    }

    /// The faired curve at knot r: remove once (A5.8, any deviation accepted), reinsert.
    pub fn fair_knot(curve: &NurbsCurve<D>, r: usize) -> Result<NurbsCurve<D>> {
        let u = curve
            .knots()
            .get(r)
            .copied()
            .ok_or_else(|| strategy_error(NAME, format!("knot index {r} out of range")))?;
        let (removed, count) = curve.remove_knot(u, 1, f64::MAX)?;
        if count != 1 {
            return Err(strategy_error(NAME, format!("knot {u} could not be removed")));
        }
        Ok(removed.insert_knot(u, 1)?)
    }

    /// Whether knot r of the current curve may be faired under the state's constraints, and
    /// if so the step done on a window of the curve ([`SapidisFarin::window`]) and the data
    /// points' new positions. O(window + log n): a refused knot costs no copy of the curve.
    fn try_knot(&self, r: usize, state: &FairingState<D>) -> Result<Option<FairedKnot<D>>> {
        let Some(curve) = self.curve.as_ref() else {
            return Err(strategy_error(NAME, "step before init"));
        };
        let constraints = state.constraints();
        let knots = curve.knots();
        let first_interior = curve.degree() + 1;
        let last_interior = knots.len() - curve.degree() - 2;
        if constraints.end_clamp() == EndClamp::G2 && (r == first_interior || r == last_interior) {
            return Ok(None);
        }
        let (low, high) = (knots[r - 2], knots[r + 2]);
        let start = self.params.partition_point(|&t| t <= low);
        let end = self.params.partition_point(|&t| t < high);
        if (start..end).any(|i| !state.is_movable(i)) {
            return Ok(None);
        }
        // The step on a clamped window of the curve (O(p) knots each side; the same new
        // control points and the same points on [u_{r−2}, u_{r+2}]): with a move bound, most
        // of the largest jumps of noisy data are refused, and an accepted step is copied
        // into the curve in place ([`SapidisFarin::apply`]).
        let (window, r_local, offset) = Self::window(curve, r)?;
        let faired = Self::fair_knot(&window, r_local)?;
        let mut moves = Vec::with_capacity(end.saturating_sub(start));
        for i in start..end {
            let mut to = faired.point(self.params[i]);
            if self.settings.domain == CurveDomain::Function {
                to[0] = state.points()[i][0];
            }
            let distance = (to - state.original()[i]).norm();
            if distance.is_nan() || distance > constraints.allowed_distance(i).min(self.move_bound) {
                return Ok(None);
            }
            moves.push((i, to));
        }
        Ok(Some((faired, offset, moves)))
    }

    /// Writes a step done on a window (its control points from index `offset` of the curve
    /// on) into the curve, and repeats at the other control points what the step on the
    /// whole curve does to them ([`SapidisFarin::drifting`]), so that the curve is bit for
    /// bit [`SapidisFarin::fair_knot`] of the curve before. O(window + drifting points).
    fn apply(&mut self, faired: &NurbsCurve<D>, offset: usize) -> Result<()> {
        let Some(curve) = self.curve.as_mut() else {
            return Err(strategy_error(NAME, "step before init"));
        };
        let count = faired.control_points().len();
        let window = offset..offset + count;
        let mut drifting = Vec::with_capacity(self.drifting.len() + 4);
        for &i in &self.drifting {
            if window.contains(&i) {
                continue;
            }
            let (point, weight) = (curve.control_points()[i], curve.weights()[i]);
            // Removal: the point from its homogeneous form; insertion: the same again.
            let once = (point * weight) / weight;
            let twice = (once * weight) / weight;
            curve.set_control_point(i, twice, weight)?;
            if !Self::settled(&twice, weight) {
                drifting.push(i);
            }
        }
        for (j, (&point, &weight)) in faired.control_points().iter().zip(faired.weights()).enumerate() {
            curve.set_control_point(offset + j, point, weight)?;
            if !Self::settled(&point, weight) {
                drifting.push(offset + j);
            }
        }
        self.drifting = drifting;
        Ok(())
    }

    /// Knots on each side of r that [`SapidisFarin::window`] keeps: enough for the spans
    /// [u_{r−2}, u_{r+2}) (knots u_{r−2−p} … u_{r+2+p}) and for knot removal at u_r
    /// (A5.8: knots u_{r−p} … u_{r+p+1}, control points P_{r−p−1} … P_r), with margin.
    const WINDOW: usize = 12;

    /// The curve cut to the knots u_{r−W} … u_{r+W} (W = [`SapidisFarin::WINDOW`]), clamped
    /// at both cut ends, with the control points over them; r's index in it; and the index
    /// of its first control point in the curve. Where the cut would reach the curve's own
    /// clamped end, the window runs to that end instead (uncut on that side). Its B-spline
    /// basis equals the curve's on every span whose p + 1 knots on each side lie inside the
    /// cut, [u_{r−2}, u_{r+2}) among them, and knot removal and insertion at u_r do the same
    /// arithmetic on its control points as on the curve's. O(W).
    fn window(curve: &NurbsCurve<D>, r: usize) -> Result<(NurbsCurve<D>, usize, usize)> {
        let knots = curve.knots();
        let p = curve.degree();
        let w = Self::WINDOW.max(2 * p + 6);
        // Uncut on a side, the window starts at u_p (ends at u_{m−p}), whose p + 1 copies
        // are the curve's clamped end.
        let a = if r < w + p + 1 { p } else { r - w };
        let b = if r + w + p + 1 >= knots.len() {
            knots.len() - 1 - p
        } else {
            r + w
        };
        // Clamped: u_a repeated p + 1 times, u_{a+1} … u_{b−1}, u_b repeated p + 1 times.
        let mut cut = vec![knots[a]; p + 1];
        cut.extend_from_slice(&knots[a + 1..b]);
        cut.extend(std::iter::repeat_n(knots[b], p + 1));
        // Knot k of the cut (k ≥ p + 1) is knot k + a − p of the curve, and so are the
        // control points whose supports start there.
        let offset = a - p;
        let count = cut.len() - p - 1;
        let points = curve.control_points()[offset..offset + count].to_vec();
        let weights = curve.weights()[offset..offset + count].to_vec();
        Ok((NurbsCurve::new(p, cut, points, weights)?, r - offset, offset))
    }
}

impl<const D: usize> FairingStrategy<D> for SapidisFarin<D>
where
    Vector<D>: CurvatureForm,
{
    fn name(&self) -> &str {
        NAME
    }

    /// Every end clamp is honoured (module docs); the default rejects G1 and G2.
    fn supports(&self, _constraints: &Constraints) -> Result<()> {
        Ok(())
    }

    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        if state.is_closed() {
            return Err(Error::ConstraintUnsupported {
                strategy: NAME.into(),
                constraint: "a closed curve (the B-spline is open and clamped)".into(),
            });
        }
        self.settings.validate()?;
        self.move_bound = self.settings.max_move.distance(state.original());
        let interpolation = match self.settings.domain {
            CurveDomain::Parametric => Interpolation::with_parametrization(
                state.points(),
                Parametrization::ChordLength,
                InterpolationSettings::default(),
            )?,
            CurveDomain::Function => {
                if D < 2 {
                    return Err(Error::refused(
                        NAME,
                        Refusal::Dimension,
                        "needs points with at least 2 coordinates for a function y(x)",
                    ));
                }
                let x: Vec<f64> = state.points().iter().map(|p| p[0]).collect();
                Interpolation::new(state.points(), &x, InterpolationSettings::default())?
            }
        };
        let curve = interpolation.nubs()?;
        self.params = interpolation.params().to_vec();
        self.interior = vec![false; curve.knots().len()];
        for r in Self::interior(&curve) {
            self.interior[r] = true;
        }
        self.jumps = self.knot_values(&curve)?;
        self.refused = vec![false; curve.knots().len()];
        self.build_trees();
        self.initial_max = self.max_jump();
        self.drifting = (0..curve.control_points().len())
            .filter(|&i| !Self::settled(&curve.control_points()[i], curve.weights()[i]))
            .collect();
        self.curve = Some(curve);
        self.history.clear();
        self.stop = None;
        state.criterion = Some(self.initial_max);
        Ok(())
    }

    /// One knot faired: the knot of the largest jump not refused comes off a tournament tree
    /// (ties to the smaller index, as a stable sort by decreasing jump orders them), refused
    /// knots leave the tree until a step near them, the step is done on a window and copied
    /// into the curve, and the jumps are updated at five knots. O(window + log n) per knot
    /// tried (O(n) with another indicator, which is recomputed over the whole curve).
    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        let Some(degree) = self.curve.as_ref().map(NurbsCurve::degree) else {
            return Err(strategy_error(NAME, "step before init"));
        };
        let max = self.max_jump();
        if max <= self.settings.jump_reduction * self.initial_max || self.initial_max == 0.0 {
            self.stop = Some(SapidisFarinStop::JumpReduction);
            return Ok(StepOutcome::done(Some(max)));
        }
        if self.history.len() >= self.settings.max_iterations {
            self.stop = Some(SapidisFarinStop::MaxIterations);
            return Ok(StepOutcome::done(Some(max)));
        }
        while let Some(r) = self.open.best() {
            if self.jumps[r] == 0.0 {
                break;
            }
            let Some((faired, offset, moves)) = self.try_knot(r, state)? else {
                // The refusal depends on the curve near r only (and on the data and bounds,
                // which do not change): it holds until a step near r.
                self.refused[r] = true;
                self.open.set_candidate(&self.jumps, r, false);
                continue;
            };
            // A step at r changes the curve on [u_{r−p−1}, u_{r+p+1}]: the knots whose
            // windows see that span may be tried again.
            let reach = 2 * degree + 4;
            let (from, to) = (r.saturating_sub(reach), (r + reach + 1).min(self.refused.len()));
            for k in from..to {
                if self.refused[k] {
                    self.refused[k] = false;
                    if self.interior[k] {
                        self.open.mark(k, true);
                    }
                }
            }
            let jump_before = self.jumps[r];
            self.apply(&faired, offset)?;
            let Some(curve) = self.curve.as_ref() else {
                return Err(strategy_error(NAME, "step before init"));
            };
            let knot = curve.knots()[r];
            if self.indicator.is_some() {
                self.jumps = self.knot_values(curve)?;
                self.build_trees();
            } else {
                for (k, &u) in curve.knots().iter().enumerate().take(r + 3).skip(r - 2) {
                    if self.interior[k] {
                        self.jumps[k] = Self::jump_at(curve, u)?;
                    }
                }
                let (first, last) = (from.min(r - 2), (to - 1).max(r + 2));
                self.all.replay(&self.jumps, first, last);
                self.open.replay(&self.jumps, first, last);
            }
            for (i, to) in moves {
                state.move_point(i, to)?;
            }
            let max_jump_after = self.max_jump();
            self.history.push(KnotStep {
                knot,
                index: r,
                jump_before,
                max_jump_after,
            });
            return Ok(StepOutcome::running(Some(max_jump_after)));
        }
        self.stop = Some(SapidisFarinStop::NoCandidate);
        Ok(StepOutcome::done(Some(max)))
    }
}

#[cfg(test)]
mod tests;
