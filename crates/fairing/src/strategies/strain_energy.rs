//! Zhang–Cheng strain-energy point replacement (Zhang, Zhang & Cheng, *Fairing spline curves
//! and surfaces by minimizing energy*, CAD 33 (2001) §2–3) on a natural parametric cubic
//! [`HermiteSpline`], with Kjellander (uniform knots) and Poliakoff (chord length) as presets.
//!
//! Notation: J_k = C'''(t_k+) − C'''(t_k−), the third-derivative jump at knot k; the
//! indicator is z_k = |J_k| (Eq. 17). With the tangents M held fixed, J_k is affine in the
//! points: ∂J_k/∂P_k = 12(1/h_{k−1}³ + 1/h_k³), ∂J_k/∂P_{k±1} = −12/h³ of the shared
//! segment. With the tangents re-solved (the C2 spline through the points, knots fixed),
//! J = K P with K symmetric, and Zhang–Cheng's energy is E = const · Σ P_k·J_k.
//!
//! Knots are fixed during fairing: the spline is built once with the chosen
//! [`Parametrization`] and updated by [`HermiteSpline::move_points_within`] (O(window)). The
//! indicator, the energy and the tree of the worst point are updated only over the rows whose
//! tangents that update re-solved (at most [`WINDOW`] knots on each side of a move), so a
//! step costs O(window + log n) independent of n and allocates nothing.

use curve_repr::{Curve, HermiteSettings, HermiteSpline, Parametrization, Vector};

use super::tournament::Tournament;
use crate::catalog::SharedIndicator;
use crate::state::strategy_error;
use crate::{project_into_ball, Error, FairingState, FairingStrategy, Refusal, Result, StepOutcome};
use fairness::LocalIndicator;

/// Knots on each side of a move within which tangents (and so jumps and segment energies) can
/// change: the Hermite update window is at most ~57 knots per side for any spacing
/// (see curve-repr's `hermite::update`), so 64 covers it. A step refreshes the window the
/// update reports, not this bound.
pub const WINDOW: usize = 64;

/// How bad points are chosen.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Mode {
    /// Zhang–Cheng §3.3 algorithm 2: the worst z_i first, each point kept inside its
    /// restraining circle/sphere of radius |P̄_i − P_i| (Eq. 11 point on the ORIGINAL curve).
    #[default]
    Automatic,
    /// Zhang–Cheng §3.3 algorithm 1: the user's bad points, worst z first; the two worst are
    /// replaced together (Eq. 13/15) when adjacent (step 1.3). Each listed point is used once
    /// with [`Replacement::Limit`]; with [`Replacement::Iterated`] the list is kept and the
    /// stage ends on the energy tolerance.
    Interactive(Vec<usize>),
}

/// Which replacement formula a step applies.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Replacement {
    /// The one-step limits: Eq. (11) for one point, Eq. (15) for two.
    #[default]
    Limit,
    /// One application of Eq. (8) for one point, Eq. (13) (cube weights) for two.
    Iterated,
}

/// Settings of [`StrainEnergy`]: the parameters of the catalogue's `strain-energy`,
/// `kjellander` and `poliakoff` (the presets pin `parametrization`).
///
/// `mode` and `parameters` are not parameters of the catalogue (`--points` chooses the mode;
/// explicit knots come from a program), so they are skipped by serde.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct StrainEnergySettings {
    /// How bad points are chosen. Default automatic.
    #[serde(skip)]
    pub mode: Mode,
    /// limit = Eq. 11/15 in one step; iterated = one application of Eq. 8/13 per step.
    ///
    /// Default limit.
    pub replacement: Replacement,
    /// Automatic mode: replace the two worst adjacent points together (Eq. 15).
    ///
    /// Beyond the paper's automatic algorithm, which moves one. Default false.
    pub pairs: bool,
    /// Fixed knots: chord-length, uniform or centripetal.
    ///
    /// Fixed during fairing. Default chord length.
    pub parametrization: Parametrization,
    /// Stop when one step changes the strain energy by at most this × E.
    ///
    /// |ΔE| ≤ tolerance · E, Zhang–Cheng step 2.5. Default 1e-6.
    #[serde(rename = "energy-tolerance")]
    #[schemars(range(min = 0))]
    pub tolerance: f64,
    /// Explicit knots (one per point), overriding `parametrization`: lets several stages
    /// keep the same knots. Default none.
    #[serde(skip)]
    pub parameters: Option<Vec<f64>>,
    /// Automatic mode: restraining radius = this × |Eq. 11 point − P_i| (1 = the paper).
    ///
    /// Point i stays within `radius_scale · |P̄_i − P_i|` of its original position (P̄_i from
    /// Eq. 11 on the original curve). 1 is Zhang–Cheng §3.3; larger lets points travel
    /// farther, `inf` removes the regions (then a point with P̄_i = P_i is still frozen).
    /// Default 1.
    #[serde(with = "crate::catalog::value::unbounded")]
    #[schemars(with = "crate::catalog::value::BoundNumber")]
    #[schemars(extend("minimum" = 0))]
    pub radius_scale: f64,
    /// Replacement steps at most.
    ///
    /// The pipeline's step limit when the catalogue runs the strategy. Default 100 000.
    pub max_iterations: usize,
    /// Where to act: the registered indicator whose largest value picks the next point.
    ///
    /// Default `third-derivative-jump`, the paper's z_i (Eq. 17), kept up to date in
    /// O(window) per step. Another name is resolved by the catalogue and handed to
    /// [`StrainEnergy::with_indicator`]; its values are recomputed over the whole curve after
    /// every step (O(n) per step).
    pub indicator: String,
}

impl Default for StrainEnergySettings {
    fn default() -> Self {
        Self {
            mode: Mode::Automatic,
            replacement: Replacement::Limit,
            pairs: false,
            parametrization: Parametrization::ChordLength,
            tolerance: 1e-6,
            parameters: None,
            radius_scale: 1.0,
            max_iterations: 100_000,
            indicator: Self::PAPER_INDICATOR.to_owned(),
        }
    }
}

impl StrainEnergySettings {
    /// The paper's indicator, z_i (Zhang–Cheng Eq. 17), by its catalogue name.
    pub const PAPER_INDICATOR: &'static str = "third-derivative-jump";

    /// Checks the ranges: tolerance and radius scale not negative (and not NaN).
    pub fn validate(&self) -> Result<()> {
        if self.tolerance.is_nan() || self.tolerance < 0.0 {
            return Err(Error::BadParameter {
                name: "energy-tolerance",
                value: self.tolerance.to_string(),
                reason: "must be a number ≥ 0",
            });
        }
        if self.radius_scale.is_nan() || self.radius_scale < 0.0 {
            return Err(Error::BadParameter {
                name: "radius-scale",
                value: self.radius_scale.to_string(),
                reason: "must be a number ≥ 0 (or inf)",
            });
        }
        Ok(())
    }

    /// Kjellander's method: uniform parameters, one point at a time (Eq. 8 ≡ Eq. 11 form).
    pub fn kjellander() -> Self {
        Self::default().with_parametrization(Parametrization::Uniform)
    }
    /// Poliakoff's method: chord-length parameters, one point at a time (the same as
    /// [`Default`]).
    pub fn poliakoff() -> Self {
        Self::default().with_parametrization(Parametrization::ChordLength)
    }
    /// Sets the mode.
    pub fn with_mode(mut self, mode: Mode) -> Self {
        self.mode = mode;
        self
    }
    /// Sets the replacement formula.
    pub fn with_replacement(mut self, replacement: Replacement) -> Self {
        self.replacement = replacement;
        self
    }
    /// Allows pairs in automatic mode.
    pub fn with_pairs(mut self, pairs: bool) -> Self {
        self.pairs = pairs;
        self
    }
    /// Sets the parametrisation.
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }
    /// Sets explicit knots (one per point).
    pub fn with_parameters(mut self, parameters: Vec<f64>) -> Self {
        self.parameters = Some(parameters);
        self
    }
    /// Sets the relative energy tolerance.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }
    /// Sets the scale of the automatic mode's restraining radii (1 = the paper).
    pub fn with_radius_scale(mut self, scale: f64) -> Self {
        self.radius_scale = scale;
        self
    }
}

/// Zhang–Cheng strain-energy fairing as a [`FairingStrategy`]. Open curves only.
#[derive(Clone, Debug)]
pub struct StrainEnergy<const D: usize> {
    settings: StrainEnergySettings,
    name: String,
    spline: Option<HermiteSpline<D>>,
    /// z_k for every point (0 at the ends).
    z: Vec<f64>,
    /// The unblocked point of largest z (automatic mode).
    worst: Tournament,
    /// Points that can no longer move (stuck on their region); skipped by the automatic mode.
    blocked: Vec<bool>,
    /// Restraining radii of the automatic mode.
    radii: Vec<f64>,
    segment_energy: Vec<f64>,
    energy: f64,
    pending: Vec<usize>,
    /// (K_kk, K_{k,k+1}) of the stage's knots (see [`stiffness_band`]).
    stiffness: (Vec<f64>, Vec<f64>),
    /// An indicator other than the paper's z_i, if one was given.
    indicator: Option<SharedIndicator<D>>,
}

impl<const D: usize> StrainEnergy<D> {
    /// A strategy with these settings.
    pub fn new(settings: StrainEnergySettings) -> Self {
        let name = match settings.parametrization {
            Parametrization::Uniform if settings.mode == Mode::Automatic => "kjellander",
            _ => "strain-energy",
        };
        Self {
            settings,
            name: name.to_owned(),
            spline: None,
            z: Vec::new(),
            worst: Tournament::default(),
            blocked: Vec::new(),
            radii: Vec::new(),
            segment_energy: Vec::new(),
            energy: 0.0,
            pending: Vec::new(),
            stiffness: (Vec::new(), Vec::new()),
            indicator: None,
        }
    }

    /// Chooses the bad points by `indicator` instead of the paper's z_i: its values (one per
    /// break of the spline, i.e. per data point; a list of n − 2 is read as the interior
    /// points') are recomputed over the whole spline after every step, O(n) per step, and
    /// the point of the largest value moves next. The replacement itself (Eq. 8–15) and the
    /// restraining regions are unchanged.
    pub fn with_indicator(mut self, indicator: SharedIndicator<D>) -> Self {
        self.indicator = Some(indicator);
        self
    }

    /// The spline through the current points (after [`FairingStrategy::init`]).
    pub fn spline(&self) -> Option<&HermiteSpline<D>> {
        self.spline.as_ref()
    }

    /// The strain energy ∫|C''|² dt kept up to date by local updates.
    pub fn energy(&self) -> f64 {
        self.energy
    }

    /// The indicator at every point (0 at the ends): z_k = |J_k| (Eq. 17), kept up to date
    /// locally, or the values of the indicator given by [`with_indicator`](Self::with_indicator).
    pub fn indicator(&self) -> &[f64] {
        &self.z
    }

    fn spline_ref(&self) -> Result<&HermiteSpline<D>> {
        self.spline
            .as_ref()
            .ok_or_else(|| strategy_error(&self.name, "step before init"))
    }

    /// Recomputes what depends on the points and tangents of rows `first..=last` (those a
    /// move changed): the segment energies of segments first − 1..=last and z at knots
    /// first − 1..=last + 1, and updates the energy and the tree of the worst point.
    /// Everything else is unchanged bit for bit, so recomputing it would give the same
    /// values: the energy's running sum gets the same nonzero terms in the same order. No
    /// allocation with the paper's indicator.
    fn refresh(&mut self, first: usize, last: usize) -> Result<()> {
        let Some(spline) = self.spline.as_ref() else {
            return Err(strategy_error(&self.name, "step before init"));
        };
        let n = spline.points().len();
        let segs = n.saturating_sub(1);
        let lo = first.saturating_sub(1);
        // Another indicator's values first: a bad one is an error before anything changes.
        let values = match &self.indicator {
            Some(indicator) => {
                let values = indicator.values(spline as &dyn Curve<D>)?;
                let offset = match values.len() {
                    len if len == n => 0,
                    len if len + 2 == n => 1,
                    len => {
                        return Err(strategy_error(
                            &self.name,
                            format!(
                                "indicator `{}` gave {len} values for {n} points",
                                indicator.name()
                            ),
                        ))
                    }
                };
                if let Some(k) = (1..n.saturating_sub(1)).find(|&k| !values[k - offset].is_finite()) {
                    return Err(strategy_error(
                        &self.name,
                        format!(
                            "indicator `{}` is {} at point {k}",
                            indicator.name(),
                            values[k - offset]
                        ),
                    ));
                }
                Some((values, offset))
            }
            None => None,
        };
        let energy_last = last.min(segs.saturating_sub(1));
        let (from, to) = (lo.max(1), (last + 1).min(n.saturating_sub(2)));
        if values.is_some() || from > to {
            for s in lo..=energy_last {
                let e = segment_energy(spline, s);
                if let Some(slot) = self.segment_energy.get_mut(s) {
                    self.energy += e - *slot;
                    *slot = e;
                }
            }
        }
        match values {
            Some((values, offset)) => {
                for k in 1..n.saturating_sub(1) {
                    if let Some(z) = self.z.get_mut(k) {
                        *z = values[k - offset];
                    }
                }
                if n >= 3 {
                    self.worst.replay(&self.z, 1, n - 2);
                }
            }
            None if from <= to => {
                // One pass over the segments from − 1..=to (those of the energies, lo..=
                // energy_last, among them): each segment's chord slope, its C‴ and, in the
                // energies' range, its energy, each once; z_k = |C‴_k − C‴_{k−1}|. The same
                // operations as `segment_energy` and `third`, so the same bits, and the
                // energy's running sum takes its terms in the same order.
                let (p, t, m) = (spline.points(), spline.knots(), spline.tangents());
                let mut before: Option<Vector<D>> = None;
                for s in from - 1..=to {
                    let h = t[s + 1] - t[s];
                    let d = (p[s + 1] - p[s]) / h;
                    if (lo..=energy_last).contains(&s) {
                        let e = hermite_energy_of_slope(d, m[s], m[s + 1], h);
                        if let Some(slot) = self.segment_energy.get_mut(s) {
                            self.energy += e - *slot;
                            *slot = e;
                        }
                    }
                    let after = third_of_slope(d, m[s], m[s + 1], h);
                    if let Some(before) = before {
                        self.z[s] = (after - before).norm();
                    }
                    before = Some(after);
                }
                self.worst.replay(&self.z, from, to);
            }
            None => {}
        }
        Ok(())
    }

    /// Moves the points of the internal spline (knots fixed) and refreshes what the move
    /// changed (the rows whose tangents the spline re-solved).
    fn apply(&mut self, moves: &[(usize, Vector<D>)]) -> Result<()> {
        let spline = self
            .spline
            .as_mut()
            .ok_or_else(|| strategy_error("strain-energy", "step before init"))?;
        match spline.move_points_within(moves)? {
            Some((first, last)) => self.refresh(first, last),
            None => Ok(()),
        }
    }

    /// The worst unblocked candidate (the largest z, the smallest index among equals), or
    /// none when its z is not positive and finite. O(1).
    fn pop_worst(&mut self) -> Option<usize> {
        let k = self.worst.best()?;
        let z = self.z[k];
        if !z.is_finite() || z <= 0.0 {
            return None;
        }
        Some(k)
    }

    /// Proposed replacement of the points `ks` (one, or two adjacent) per the settings, the
    /// first `ks.len()` entries.
    fn target(&mut self, ks: &[usize]) -> Result<[Vector<D>; 2]> {
        let spline = self.spline_ref()?;
        let zero = Vector::<D>::zeros();
        match (self.settings.replacement, ks) {
            (Replacement::Iterated, [k]) => Ok([eq8(spline, *k), zero]),
            (Replacement::Iterated, [k, _]) => {
                let (a, b) = eq13(spline, *k);
                Ok([a, b])
            }
            (Replacement::Limit, [k]) => {
                let p = self.limit_one(*k)?;
                Ok([p, zero])
            }
            (Replacement::Limit, [k, _]) => {
                let (a, b) = self.limit_two(*k)?;
                Ok([a, b])
            }
            _ => Err(strategy_error(&self.name, "bad point set")),
        }
    }

    /// Eq. (11): P̄_k = P_k − J_k/K_kk, the point on the spline through the other points
    /// (J_k is affine in P_k with the same scalar slope K_kk in every coordinate; K from
    /// [`stiffness_band`], computed once per stage since the knots are fixed). O(1).
    fn limit_one(&mut self, k: usize) -> Result<Vector<D>> {
        let s = self.spline_ref()?;
        let (p, j0) = (s.points()[k], jump(s, k));
        let kk = self.stiffness.0.get(k).copied().unwrap_or(f64::NAN);
        if !(kk.is_finite() && kk.abs() > 0.0) {
            return Err(strategy_error(&self.name, "singular Eq. 11 (K_kk = 0)"));
        }
        Ok(p - j0 / kk)
    }

    /// Eq. (15): the pair (P̄_k, P̄_{k+1}) making J_k = J_{k+1} = 0 with the tangents re-solved,
    /// i.e. the spline through the remaining points at t_k, t_{k+1} (Theorem 3): the 2×2 block
    /// of K (symmetric) solved for the jumps. O(1).
    fn limit_two(&mut self, k: usize) -> Result<(Vector<D>, Vector<D>)> {
        let s = self.spline_ref()?;
        let (p0, p1, j0, j1) = (s.points()[k], s.points()[k + 1], jump(s, k), jump(s, k + 1));
        let (diagonal, upper) = &self.stiffness;
        let entry = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(f64::NAN);
        let (a, b, d) = (entry(diagonal, k), entry(upper, k), entry(diagonal, k + 1));
        solve2(a, b, b, d, j0, j1)
            .map(|(d0, d1)| (p0 - d0, p1 - d1))
            .ok_or_else(|| strategy_error(&self.name, "singular Eq. 15 block"))
    }

    /// Moves `ks` towards `targets` (restraining region in automatic mode, then the state's
    /// constraints), updates the spline and returns (whether anything moved, whether a region
    /// or constraint cut the move short).
    fn commit(
        &mut self,
        state: &mut FairingState<D>,
        ks: &[usize],
        targets: &[Vector<D>],
    ) -> Result<(bool, bool)> {
        let mut moves = [(0, Vector::<D>::zeros()); 2];
        let mut count = 0;
        let mut limited = false;
        for (&k, t) in ks.iter().zip(targets) {
            if !t.iter().all(|x| x.is_finite()) {
                return Err(Error::NonFiniteMove { index: k });
            }
            let mut proposed = *t;
            if self.settings.mode == Mode::Automatic {
                if let (Some(o), Some(&r)) = (state.original().get(k), self.radii.get(k)) {
                    proposed = project_into_ball(o, r, &proposed);
                }
            }
            let before = state.points()[k];
            let to = state.move_point(k, proposed)?;
            limited |= to != *t;
            if to != before {
                moves[count] = (k, to);
                count += 1;
            }
        }
        if count == 0 {
            return Ok((false, limited));
        }
        self.apply(&moves[..count])?;
        Ok((true, limited))
    }
}

impl<const D: usize> FairingStrategy<D> for StrainEnergy<D> {
    fn name(&self) -> &str {
        &self.name
    }

    fn init(&mut self, state: &mut FairingState<D>) -> Result<()> {
        if state.is_closed() {
            return Err(Error::refused(
                &self.name,
                Refusal::Closed,
                "does not fair closed curves",
            ));
        }
        self.settings.validate()?;
        let settings = match &self.settings.parameters {
            Some(t) => HermiteSettings::new().with_parameters(t.clone()),
            None => HermiteSettings::new().with_parametrization(self.settings.parametrization),
        };
        let spline = HermiteSpline::new(state.points(), &settings)?;
        let n = state.len();
        self.z = vec![0.0; n];
        self.blocked = (0..n)
            .map(|k| k == 0 || k + 1 >= n || !state.is_movable(k))
            .collect();
        self.worst = Tournament::new(&self.z, &self.blocked);
        self.segment_energy = spline.segment_energies();
        self.energy = self.segment_energy.iter().sum();
        self.stiffness = stiffness_band(&spline)
            .ok_or_else(|| strategy_error(&self.name, "singular tangent system (Eq. 11)"))?;
        self.spline = Some(spline);
        self.refresh(0, n.saturating_sub(1))?;
        if self.settings.mode == Mode::Automatic {
            // §3.3 step 2.1: radii from the ORIGINAL curve's Eq. (11) points.
            // |P̄_k − P_k| = |J_k| / K_kk with K's diagonal computed in O(n) above.
            let (diagonal, jumps) = {
                let spline = self.spline_ref()?;
                let jumps: Vec<Vector<D>> = (1..n.saturating_sub(1)).map(|k| jump(spline, k)).collect();
                (self.stiffness.0.clone(), jumps)
            };
            let mut radii = vec![0.0; n];
            for (k, r) in radii.iter_mut().enumerate().take(n.saturating_sub(1)).skip(1) {
                let kk = diagonal.get(k).copied().unwrap_or(f64::NAN);
                if !(kk.is_finite() && kk > 0.0) {
                    return Err(strategy_error(&self.name, "singular Eq. 11 (K_kk = 0)"));
                }
                let distance = jumps[k - 1].norm() / kk;
                // 0 · ∞ would be NaN: a point already at its Eq. 11 position stays frozen.
                *r = if distance > 0.0 {
                    self.settings.radius_scale * distance
                } else {
                    0.0
                };
            }
            self.radii = radii;
        }
        if let Mode::Interactive(list) = &self.settings.mode {
            for &k in list {
                if k == 0 || k + 1 >= n {
                    return Err(Error::BadParameter {
                        name: "bad point",
                        value: k.to_string(),
                        reason: "must be an interior point of an open curve",
                    });
                }
            }
            self.pending = list.clone();
        }
        state.criterion = Some(self.energy);
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<D>) -> Result<StepOutcome> {
        if self.spline.as_ref().map(|s| s.points().len()) != Some(state.len()) {
            return Err(strategy_error(&self.name, "step before init"));
        }
        let before = self.energy;
        // The point or pair of this step, on the stack (a step allocates nothing).
        let (group, size): ([usize; 2], usize) = match self.settings.mode.clone() {
            Mode::Automatic => {
                let Some(k) = self.pop_worst() else {
                    return Ok(StepOutcome::done(Some(self.energy)));
                };
                let mut ks = ([k, 0], 1);
                if self.settings.pairs {
                    let zl = if self.blocked.get(k - 1) == Some(&false) {
                        self.z[k - 1]
                    } else {
                        -1.0
                    };
                    let zr = if self.blocked.get(k + 1) == Some(&false) {
                        self.z[k + 1]
                    } else {
                        -1.0
                    };
                    // step 1.3: pair with the neighbour when it is the second worst
                    let second = self.second_worst(k);
                    if second == Some(k + 1) && zr > 0.0 {
                        ks = ([k, k + 1], 2);
                    } else if second == Some(k - 1) && zl > 0.0 {
                        ks = ([k - 1, k], 2);
                    }
                }
                ks
            }
            Mode::Interactive(_) => {
                if self.pending.is_empty() {
                    return Ok(StepOutcome::done(Some(self.energy)));
                }
                let mut order = self.pending.clone();
                order.sort_by(|a, b| self.z[*b].total_cmp(&self.z[*a]).then(a.cmp(b)));
                let first = order[0];
                let ks = match order.get(1) {
                    Some(&s) if s.abs_diff(first) == 1 => ([first.min(s), first.max(s)], 2),
                    _ => ([first, 0], 1),
                };
                if self.settings.replacement == Replacement::Limit {
                    self.pending.retain(|k| !ks.0[..ks.1].contains(k));
                }
                ks
            }
        };
        let ks = &group[..size];
        let targets = self.target(ks)?;
        let targets = &targets[..size];
        let mut old = [Vector::<D>::zeros(); 2];
        for (o, &k) in old.iter_mut().zip(ks) {
            *o = state.points()[k];
        }
        let (mut moved, limited) = self.commit(state, ks, targets)?;
        // Guard for Theorem 1: a single point's energy is isotropic in P_k, so cutting its move
        // by a convex region never raises E; a pair's is not, so a cut pair move can. Undo it.
        if moved && self.energy > before {
            let mut back = [(0, Vector::<D>::zeros()); 2];
            for ((b, &k), &p) in back.iter_mut().zip(ks).zip(&old) {
                *b = (k, state.move_point(k, p)?);
            }
            self.apply(&back[..size])?;
            moved = false;
        }
        // Choice where §3.3 is silent: a point whose move its restraining region (or a
        // constraint) cut short has reached the edge of what it may do; it is retired from
        // the automatic search, and its step does not count for the stopping test (else the
        // first saturated worst point, moving by a sliver, would end the whole run).
        if self.settings.mode == Mode::Automatic && (limited || !moved) {
            for &k in ks {
                if let Some(b) = self.blocked.get_mut(k) {
                    *b = true;
                    self.worst.set_candidate(&self.z, k, false);
                }
            }
            return Ok(StepOutcome::running(Some(self.energy)));
        }
        let change = (before - self.energy).abs();
        let stop = match self.settings.mode {
            Mode::Automatic => change <= self.settings.tolerance * before.abs(),
            Mode::Interactive(_) => {
                self.pending.is_empty()
                    || (self.settings.replacement == Replacement::Iterated
                        && change <= self.settings.tolerance * before.abs())
            }
        };
        Ok(StepOutcome {
            done: stop,
            criterion: Some(self.energy),
        })
    }
}

impl<const D: usize> StrainEnergy<D> {
    /// The second worst unblocked point, looking only at the two neighbours of `k` and the
    /// worst candidate other than `k`: a neighbour is "second worst" when its z is at least
    /// that of every other candidate. O(log n).
    fn second_worst(&mut self, k: usize) -> Option<usize> {
        let candidate = self.blocked.get(k) == Some(&false);
        self.worst.set_candidate(&self.z, k, false);
        let second = self.worst.best().map(|j| (self.z[j], j));
        self.worst.set_candidate(&self.z, k, candidate);
        let (z2, j2) = second?;
        for nb in [k + 1, k - 1] {
            if self.blocked.get(nb) == Some(&false) && self.z.get(nb).copied().unwrap_or(-1.0) >= z2 {
                return Some(nb);
            }
        }
        Some(j2)
    }
}

/// The constant C''' on segment s: (6(M_s + M_{s+1}) − 12 d)/h², d = (P_{s+1} − P_s)/h.
fn third<const D: usize>(spline: &HermiteSpline<D>, s: usize) -> Vector<D> {
    let (p, t, m) = (spline.points(), spline.knots(), spline.tangents());
    let h = t[s + 1] - t[s];
    let d = (p[s + 1] - p[s]) / h;
    third_of_slope(d, m[s], m[s + 1], h)
}

/// [`third`] from the segment's chord slope d, end tangents and length h.
fn third_of_slope<const D: usize>(d: Vector<D>, m0: Vector<D>, m1: Vector<D>, h: f64) -> Vector<D> {
    ((m0 + m1) * 6.0 - d * 12.0) / (h * h)
}

/// J_k = C'''(t_k+) − C'''(t_k−) at interior point k.
pub fn jump<const D: usize>(spline: &HermiteSpline<D>, k: usize) -> Vector<D> {
    third(spline, k) - third(spline, k - 1)
}

/// ∫_seg |C''|² dt of segment s in closed form (as curve-repr's `segment_energies`).
pub fn segment_energy<const D: usize>(spline: &HermiteSpline<D>, s: usize) -> f64 {
    let (p, t, m) = (spline.points(), spline.knots(), spline.tangents());
    hermite_energy(p[s], p[s + 1], m[s], m[s + 1], t[s + 1] - t[s])
}

/// ∫_0^h |C''|² of the cubic Hermite segment (P0, M0) → (P1, M1) of length h (Eq. 7's terms).
pub fn hermite_energy<const D: usize>(
    p0: Vector<D>,
    p1: Vector<D>,
    m0: Vector<D>,
    m1: Vector<D>,
    h: f64,
) -> f64 {
    hermite_energy_of_slope((p1 - p0) / h, m0, m1, h)
}

/// [`hermite_energy`] from the segment's chord slope d = (P1 − P0)/h.
fn hermite_energy_of_slope<const D: usize>(d: Vector<D>, m0: Vector<D>, m1: Vector<D>, h: f64) -> f64 {
    let a = (d * 6.0 - m0 * 4.0 - m1 * 2.0) / h;
    let b = (m0 * 2.0 + m1 * 4.0 - d * 6.0) / h;
    h * (a.norm_squared() + a.dot(&b) + b.norm_squared()) / 3.0
}

/// Eq. (8) with the corrected weights λ = h_k³/(h_{k−1}³ + h_k³), μ = h_{k−1}³/(h_{k−1}³ + h_k³):
/// P̄_k = λP_{k−1} + μP_{k+1} + ½h_{k−1}λ(M_{k−1} + M_k) − ½h_kμ(M_k + M_{k+1}),
/// the minimiser of Eq. (7) with tangents fixed (equivalently J_k = 0 with M fixed). O(1).
pub fn eq8<const D: usize>(spline: &HermiteSpline<D>, k: usize) -> Vector<D> {
    let (p, t, m) = (spline.points(), spline.knots(), spline.tangents());
    let (h0, h1) = (t[k] - t[k - 1], t[k + 1] - t[k]);
    let s = h0.powi(3) + h1.powi(3);
    let (l, mu) = (h1.powi(3) / s, h0.powi(3) / s);
    p[k - 1] * l + p[k + 1] * mu + (m[k - 1] + m[k]) * (0.5 * h0 * l) - (m[k] + m[k + 1]) * (0.5 * h1 * mu)
}

/// Eq. (13) with cube weights: the minimiser of Eq. (12) over (P̄_k, P̄_{k+1}) with the
/// tangents fixed, i.e. J_k = J_{k+1} = 0 with M fixed. Each J is affine with slopes
/// ∂J_k/∂P_k = 12(1/h_{k−1}³ + 1/h_k³), ∂J_k/∂P_{k+1} = −12/h_k³ (and symmetrically);
/// solving the 2×2 system gives Eq. (13) (λ = h_{k−1}³/Σ, μ = h_{k+1}³/Σ, Σ = h_{k−1}³ + h_k³ +
/// h_{k+1}³, as papers/README.md corrects). O(1).
pub fn eq13<const D: usize>(spline: &HermiteSpline<D>, k: usize) -> (Vector<D>, Vector<D>) {
    let (p, t) = (spline.points(), spline.knots());
    let (a, b, c) = (
        (t[k] - t[k - 1]).powi(-3),
        (t[k + 1] - t[k]).powi(-3),
        (t[k + 2] - t[k + 1]).powi(-3),
    );
    let (j0, j1) = (jump(spline, k), jump(spline, k + 1));
    let (k00, k01, k11) = (12.0 * (a + b), -12.0 * b, 12.0 * (b + c));
    match solve2(k00, k01, k01, k11, j0, j1) {
        Some((d0, d1)) => (p[k] - d0, p[k + 1] - d1),
        None => (p[k], p[k + 1]),
    }
}

/// Solves [[a, b], [c, d]] (x, y) = (u, v) for vector right-hand sides.
fn solve2<const D: usize>(
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    u: Vector<D>,
    v: Vector<D>,
) -> Option<(Vector<D>, Vector<D>)> {
    let det = a * d - b * c;
    if !(det.is_finite() && det.abs() > f64::MIN_POSITIVE) {
        return None;
    }
    Some(((u * d - v * b) / det, (v * a - u * c) / det))
}

/// The diagonal K_kk = ∂J_k/∂P_k of the natural spline's stiffness (J = K P, tangents
/// re-solved, knots fixed) at every point, in O(n); `None` if the tangent system is singular.
/// See [`stiffness_band`].
pub fn stiffness_diagonal<const D: usize>(spline: &HermiteSpline<D>) -> Option<Vec<f64>> {
    stiffness_band(spline).map(|(diagonal, _)| diagonal)
}

/// The diagonal K_kk and the first off-diagonal K_{k,k+1} of the natural spline's stiffness
/// (J = K P, tangents re-solved, knots fixed; K depends on the knots only), in O(n); `None`
/// if the tangent system is singular.
///
/// E(P, M) = Σ_s ∫|C''|² is a quadratic form whose Hessian is (a scalar matrix) ⊗ I_D; the
/// natural spline's tangents minimise it over M, so E(P) = Pᵀ K P with K the Schur complement
/// H_PP − H_PM H_MM⁻¹ H_MP, and this K is the one of J = K P (E = Σ P_k·J_k for a natural
/// spline, integrating ∫C''·C'' by parts twice). Each segment's 4×4 form in (P_s, P_{s+1},
/// M_s, M_{s+1}) is read off [`hermite_energy`] exactly (it has no linear part); H_MM is
/// tridiagonal, SPD, and only its inverse's band |i − j| ≤ 2 is needed, from forward and
/// backward pivots: (H⁻¹)_ii = 1/(f_i + g_i − a_i), (H⁻¹)_{r,i} = −b_{r−1}/g_r (H⁻¹)_{r−1,i}
/// for r > i (the band |i − j| ≤ 3 is needed for K_{k,k+1}).
#[allow(clippy::type_complexity)]
pub fn stiffness_band<const D: usize>(spline: &HermiteSpline<D>) -> Option<(Vec<f64>, Vec<f64>)> {
    let t = spline.knots();
    let n = t.len();
    if n < 2 {
        return None;
    }
    // Q[s] over (p0, p1, m0, m1), from the energy of unit vectors (D = 1).
    let unit = |i: usize| -> [Vector<1>; 4] {
        let mut e = [Vector::<1>::zeros(); 4];
        e[i][0] = 1.0;
        e
    };
    let q: Vec<[[f64; 4]; 4]> = (0..n - 1)
        .map(|s| {
            let h = t[s + 1] - t[s];
            let energy = |e: [Vector<1>; 4]| hermite_energy(e[0], e[1], e[2], e[3], h);
            let mut m = [[0.0; 4]; 4];
            for (a, row) in m.iter_mut().enumerate() {
                row[a] = energy(unit(a));
            }
            for a in 0..4 {
                for b in a + 1..4 {
                    let mut e = unit(a);
                    e[b][0] = 1.0;
                    let v = (energy(e) - m[a][a] - m[b][b]) / 2.0;
                    m[a][b] = v;
                    m[b][a] = v;
                }
            }
            m
        })
        .collect();
    let (p0, p1, m0, m1) = (0, 1, 2, 3);
    // H_MM: diagonal a_i, off-diagonal b_i = (i, i+1).
    let a: Vec<f64> = (0..n)
        .map(|i| {
            let left = if i > 0 { q[i - 1][m1][m1] } else { 0.0 };
            let right = if i + 1 < n { q[i][m0][m0] } else { 0.0 };
            left + right
        })
        .collect();
    let b: Vec<f64> = (0..n - 1).map(|i| q[i][m0][m1]).collect();
    let mut f = vec![0.0; n];
    let mut g = vec![0.0; n];
    f[0] = a[0];
    for i in 1..n {
        f[i] = a[i] - b[i - 1] * b[i - 1] / f[i - 1];
    }
    g[n - 1] = a[n - 1];
    for i in (0..n - 1).rev() {
        g[i] = a[i] - b[i] * b[i] / g[i + 1];
    }
    // Band of G = H_MM⁻¹: G(i, j) for |i − j| ≤ 2.
    let diag: Vec<f64> = (0..n).map(|i| 1.0 / (f[i] + g[i] - a[i])).collect();
    let sub1 = |i: usize| -b[i] / g[i + 1] * diag[i]; // G(i+1, i)
    let band = |i: usize, j: usize| -> f64 {
        let (lo, hi) = (i.min(j), i.max(j));
        match hi - lo {
            0 => diag[lo],
            1 => sub1(lo),
            2 => -b[lo + 1] / g[lo + 2] * sub1(lo),
            3 => b[lo + 2] / g[lo + 3] * b[lo + 1] / g[lo + 2] * sub1(lo),
            _ => 0.0,
        }
    };
    // The column Q_MP(·, k): rows k−1, k, k+1 (those that exist).
    let column = |k: usize| -> Vec<(usize, f64)> {
        let mut column = Vec::with_capacity(3);
        if k > 0 {
            column.push((k - 1, q[k - 1][m0][p1]));
        }
        let left = if k > 0 { q[k - 1][m1][p1] } else { 0.0 };
        let right = if k + 1 < n { q[k][m0][p0] } else { 0.0 };
        column.push((k, left + right));
        if k + 1 < n {
            column.push((k + 1, q[k][m1][p0]));
        }
        column
    };
    let cross = |u: &[(usize, f64)], v: &[(usize, f64)]| -> f64 {
        u.iter()
            .map(|&(i, a)| v.iter().map(|&(j, b)| a * band(i, j) * b).sum::<f64>())
            .sum()
    };
    let columns: Vec<Vec<(usize, f64)>> = (0..n).map(column).collect();
    let mut diagonal = vec![0.0; n];
    let mut upper = vec![0.0; n - 1];
    for k in 0..n {
        let mut qpp = 0.0;
        if k > 0 {
            qpp += q[k - 1][p1][p1];
        }
        if k + 1 < n {
            qpp += q[k][p0][p0];
            upper[k] = q[k][p0][p1] - cross(&columns[k], &columns[k + 1]);
        }
        diagonal[k] = qpp - cross(&columns[k], &columns[k]);
    }
    let finite = diagonal.iter().chain(&upper).all(|v| v.is_finite());
    finite.then_some((diagonal, upper))
}
