//! Zhang–Cheng fairing of bicubic spline surfaces (Zhang, Zhang & Cheng, *Fairing spline
//! curves and surfaces by minimizing energy*, CAD 33 (2001) §4), with Kjellander's one-point
//! method as the baseline preset.
//!
//! The surface is the [`BicubicSplineSurface`] through a grid P_ij (i = 0..m along u,
//! j = 0..n along v); the knots are fixed while fairing. A bad point is moved to the minimiser
//! of the strain energy of the iso-parametric curves through it (`closed_form`: one point
//! Eq. 18–20 and its limit Eq. 21, an adjacent pair Eq. 22–23, a 2×2 block Eq. 24–25), or of
//! the thin-plate energy of the patches around it (`thin_plate`, Eq. 27–29) as an option.
//!
//! - **Automatic** (§4.4, algorithm 2): the boundary curves are faired first with the curve
//!   method (`boundary`); each interior point gets a restraining sphere of radius
//!   |P̄_ij − P_ij| (P̄ from Eq. 21 on the surface after step 2.1); then every step computes
//!   z_ij (Eq. 26) at the interior points and fairs them all, from the largest z_ij down, each
//!   kept in its sphere; the surface is rebuilt (2.5) and the run stops when the network
//!   strain energy changes by at most `tolerance` × its value in one step (2.6).
//! - **Interactive** (§4.4, algorithm 1): the user's bad points are sorted by z_ij and grouped
//!   as step 1.3 says (the next two adjacent: a pair, Eq. 23; diagonal: the 2×2 block they
//!   span, Eq. 25; else one point, Eq. 20); one step fairs every group once; stop on the
//!   energy tolerance (1.5).
//! - **Kjellander** ([`SurfaceFairingSettings::kjellander`]): uniform knots, one point per
//!   step, the interior point of largest z_ij (or of the user's list), moved to its Eq. 21
//!   point (the surface form of Kjellander's curve rule, which zeroes the jump), kept in its
//!   sphere; a point its sphere holds (target outside, point already on the border) is passed
//!   over for the next worst. The energy tolerance applies to the change over as many steps
//!   as there are candidate points (a sweep's worth). The paper does not print Kjellander's
//!   surface formula; with uniform knots on a square grid `K_u[i,i] = K_v[j,j]`, so this point
//!   is also the mean of the u-curve's and the v-curve's own Kjellander points.
//!
//! Within a step, moves go to the iso-parametric spline network (`network::Network`) (the tangents of u-line j
//! and v-line i of the moved point updated by the natural spline's measured response to a
//! unit move, in a window of knots: O(1) in the grid size); at the end of the
//! step the surface is rebuilt through [`BicubicSplineSurface::move_points`] (the rows,
//! columns and twists the paper says change). The thin-plate option, which reads the twists,
//! rebuilds the surface after every move. An automatic step costs O(m·n·window).

// The building blocks index the grid directly (their callers validate it first), so they
// stay inside the crate; `SurfaceFairing` is the checked entry point.
pub(crate) mod boundary;
pub(crate) mod closed_form;
pub(crate) mod network;
pub(crate) mod thin_plate;

#[cfg(test)]
mod tests;

use std::collections::BTreeSet;
use std::time::{Duration, Instant};

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, NurbsSurface, Parametrization, Vec3};

use crate::strategies::Replacement;
use crate::{project_into_ball, Error, Result, TerminationReason};

pub use closed_form::Group;
use closed_form::{fixed_tangent_targets, limit_targets};
use network::Network;

/// A move of grid node (i, j) to a new position.
pub type NodeMove = ((usize, usize), Vec3);

/// How bad points are chosen.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum SurfaceMode {
    /// §4.4 algorithm 2: boundary curves first, then every interior point each step, largest
    /// z_ij first, in restraining spheres.
    #[default]
    Automatic,
    /// §4.4 algorithm 1: the user's bad points (i, j), grouped per step 1.3.
    Interactive(Vec<(usize, usize)>),
}

/// Which energy a move minimises.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Objective {
    /// The strain energy of the iso-parametric network curves through the moved points
    /// (Eq. 18, 22, 24). The paper's choice.
    #[default]
    Network,
    /// The thin-plate energy of the patches around the moved points (Eq. 27–29), tangents and
    /// twists held. Only with [`Replacement::Iterated`] (the paper gives no limit form).
    ThinPlate,
}

/// Settings of [`SurfaceFairing`]: the parameters of the catalogue's `zhang-cheng` (and,
/// with other defaults, `kjellander`). Defaults: Zhang–Cheng automatic, limit replacement,
/// network objective, chord-length knots, boundary faired, tolerance 1e-6, 1000 steps.
///
/// `mode`, `fixed` and `max_distance` come from the command's `--points`, `--fixed` and
/// `--tolerance` and are not parameters of the catalogue (skipped by serde).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct SurfaceFairingSettings {
    /// Automatic or interactive.
    #[serde(skip)]
    pub mode: SurfaceMode,
    /// Limit (Eq. 21 and its pair/block analogues, solved once) or iterated (one application of Eq. 20/23/25).
    pub replacement: Replacement,
    /// Network (curve strain energy, Eq. 18-25) or thin-plate (Eq. 27-29; needs replacement=iterated).
    pub objective: Objective,
    /// Knots, averaged over the grid lines and fixed while fairing: chord-length or uniform.
    pub parametrization: Parametrization,
    /// On: fair the boundary curves first with the curve method (automatic mode, step 2.1); off: keep them.
    #[serde(rename = "boundary")]
    pub fair_boundary: bool,
    /// Kjellander: one point per step instead of all (automatic) or every group (interactive).
    pub one_point_per_step: bool,
    /// Stop when the network strain energy changes by at most this fraction in one step.
    #[serde(rename = "energy-tolerance")]
    pub tolerance: f64,
    /// Step limit.
    pub max_steps: usize,
    /// Nodes that must not move.
    #[serde(skip)]
    pub fixed: BTreeSet<(usize, usize)>,
    /// No point moves farther than this from where it started.
    #[serde(skip)]
    pub max_distance: Option<f64>,
}

impl Default for SurfaceFairingSettings {
    fn default() -> Self {
        Self {
            mode: SurfaceMode::Automatic,
            replacement: Replacement::Limit,
            objective: Objective::Network,
            parametrization: Parametrization::ChordLength,
            fair_boundary: true,
            one_point_per_step: false,
            tolerance: 1e-6,
            max_steps: 1000,
            fixed: BTreeSet::new(),
            max_distance: None,
        }
    }
}

impl SurfaceFairingSettings {
    /// Checks the ranges: tolerance and distance not negative, the thin-plate objective only
    /// with the iterated replacement.
    pub fn validate(&self) -> Result<()> {
        if self.tolerance.is_nan() || self.tolerance < 0.0 {
            return Err(Error::BadParameter {
                name: "energy-tolerance",
                value: self.tolerance.to_string(),
                reason: "must be a non-negative number",
            });
        }
        if let Some(d) = self.max_distance {
            if d.is_nan() || d < 0.0 {
                return Err(Error::BadParameter {
                    name: "max_distance",
                    value: d.to_string(),
                    reason: "must be a non-negative number",
                });
            }
        }
        if self.objective == Objective::ThinPlate && self.replacement == Replacement::Limit {
            return Err(Error::BadParameter {
                name: "objective",
                value: "thin-plate".into(),
                reason:
                    "the thin-plate objective (Eq. 27-29) has no limit form; use the iterated replacement",
            });
        }
        Ok(())
    }

    /// Zhang–Cheng (the default).
    pub fn zhang_cheng() -> Self {
        Self::default()
    }

    /// Kjellander's one-point method: uniform knots, one point per step moved to its Eq. 21
    /// point, boundary left alone, 100 000 steps.
    pub fn kjellander() -> Self {
        Self {
            parametrization: Parametrization::Uniform,
            fair_boundary: false,
            one_point_per_step: true,
            max_steps: 100_000,
            ..Self::default()
        }
    }

    /// Sets the mode.
    pub fn with_mode(mut self, mode: SurfaceMode) -> Self {
        self.mode = mode;
        self
    }
    /// Sets the replacement formula.
    pub fn with_replacement(mut self, replacement: Replacement) -> Self {
        self.replacement = replacement;
        self
    }
    /// Sets the objective.
    pub fn with_objective(mut self, objective: Objective) -> Self {
        self.objective = objective;
        self
    }
    /// Sets the knot rule.
    pub fn with_parametrization(mut self, parametrization: Parametrization) -> Self {
        self.parametrization = parametrization;
        self
    }
    /// Fair the boundary curves first (automatic mode) or not.
    pub fn with_fair_boundary(mut self, fair_boundary: bool) -> Self {
        self.fair_boundary = fair_boundary;
        self
    }
    /// One point per step (Kjellander) or not.
    pub fn with_one_point_per_step(mut self, one: bool) -> Self {
        self.one_point_per_step = one;
        self
    }
    /// Sets the relative energy tolerance.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }
    /// Sets the step limit.
    pub fn with_max_steps(mut self, max_steps: usize) -> Self {
        self.max_steps = max_steps;
        self
    }
    /// Sets the fixed nodes.
    pub fn with_fixed(mut self, fixed: impl IntoIterator<Item = (usize, usize)>) -> Self {
        self.fixed = fixed.into_iter().collect();
        self
    }
    /// Sets the largest distance a point may move.
    pub fn with_max_distance(mut self, distance: f64) -> Self {
        self.max_distance = Some(distance);
        self
    }
}

/// One step of a run, for plots and comparisons.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceStep {
    /// Network strain energy after the step (over the run's knots).
    pub energy: f64,
    /// max z_ij after the step.
    pub max_z: f64,
    /// Points moved in the step.
    pub moves: usize,
}

/// What [`SurfaceFairing::run`] returns.
#[derive(Clone, Debug)]
pub struct SurfaceFairingResult {
    /// The faired surface (the run's knots).
    pub surface: BicubicSplineSurface,
    /// The input points, flat (index i·(n+1) + j).
    pub original: Vec<Vec3>,
    /// Steps made (not counting the boundary curves' steps).
    pub steps: usize,
    /// Steps the boundary curve fairing made (automatic mode).
    pub boundary_steps: usize,
    /// Network energy and max z_ij before the first step (after the boundary fairing).
    pub start: SurfaceStep,
    /// One entry per step.
    pub history: Vec<SurfaceStep>,
    /// The nodes whose final position differs from the input, i-major.
    pub moved: Vec<(usize, usize)>,
    /// Restraining radii (automatic mode), flat; 0 on the boundary and at fixed nodes.
    pub radii: Option<Vec<f64>>,
    /// Why the run stopped.
    pub termination: TerminationReason,
    /// Time of the fairing itself.
    pub elapsed: Duration,
}

/// Zhang–Cheng (or Kjellander) surface fairing; see the [module docs](self).
#[derive(Clone, Debug, Default)]
pub struct SurfaceFairing {
    settings: SurfaceFairingSettings,
}

impl SurfaceFairing {
    /// Fairs a B-spline or NURBS surface through the bicubic spline surface interpolating its
    /// control points (Zhang–Cheng §4.5): the control net is faired as a grid, and the result
    /// is the surface of the same degrees, knots and weights on the faired net. Fails as
    /// [`run`](Self::run) does on the net. O(as `run`).
    pub fn run_control_net(&self, surface: &NurbsSurface) -> Result<(NurbsSurface, SurfaceFairingResult)> {
        let (rows, columns) = surface.net_size();
        let net: Vec<Vec<Vec3>> = (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| surface.control_point(i, j).unwrap_or_default())
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| surface.weight(i, j).unwrap_or(1.0))
                    .collect()
            })
            .collect();
        let result = self.run(&net)?;
        let (degree_u, degree_v) = surface.degrees();
        let (knots_u, knots_v) = surface.knot_vectors();
        let faired = NurbsSurface::new(
            degree_u,
            degree_v,
            knots_u.knots().to_vec(),
            knots_v.knots().to_vec(),
            result.surface.grid(),
            weights,
        )?;
        Ok((faired, result))
    }
}

/// State of one run.
struct Run<'a> {
    settings: &'a SurfaceFairingSettings,
    network: Network,
    surface: BicubicSplineSurface,
    original: Vec<Vec3>,
    radii: Option<Vec<f64>>,
}

impl SurfaceFairing {
    /// A run with these settings.
    pub fn new(settings: SurfaceFairingSettings) -> Self {
        Self { settings }
    }

    /// The settings.
    pub fn settings(&self) -> &SurfaceFairingSettings {
        &self.settings
    }

    /// "zhang-cheng" or "kjellander".
    pub fn name(&self) -> &'static str {
        if self.settings.one_point_per_step {
            "kjellander"
        } else {
            "zhang-cheng"
        }
    }

    /// Fairs the grid `grid[i][j]` = P_ij (at least 3 × 3). O(steps · m·n·window).
    ///
    /// Errors: a grid the surface cannot be built through; a bad setting
    /// ([`Error::BadParameter`]); a fixed node outside the grid or a bad point that is not an
    /// interior node ([`Error::BadConstraint`]).
    pub fn run(&self, grid: &[Vec<Vec3>]) -> Result<SurfaceFairingResult> {
        let settings = &self.settings;
        settings.validate()?;
        let start_time = Instant::now();
        let surface = BicubicSplineSurface::with_settings(
            grid,
            &BicubicSurfaceSettings::default().with_parametrization(settings.parametrization),
        )?;
        let (u_count, v_count) = surface.shape();
        if u_count < 3 || v_count < 3 {
            return Err(Error::BadParameter {
                name: "grid",
                value: format!("{u_count} × {v_count}"),
                reason: "surface fairing needs at least 3 × 3 points (an interior point)",
            });
        }
        if let Some(&(i, j)) = settings
            .fixed
            .iter()
            .find(|&&(i, j)| i >= u_count || j >= v_count)
        {
            return Err(Error::BadConstraint {
                reason: format!("fixed node ({i}, {j}) is outside the {u_count} × {v_count} grid"),
            });
        }
        if let SurfaceMode::Interactive(list) = &settings.mode {
            if let Some(&(i, j)) = list
                .iter()
                .find(|&&(i, j)| i == 0 || j == 0 || i + 1 >= u_count || j + 1 >= v_count)
            {
                return Err(Error::BadConstraint {
                    reason: format!(
                        "bad point ({i}, {j}) is not an interior node of the {u_count} × {v_count} grid"
                    ),
                });
            }
        }
        let original = surface.points().to_vec();
        let mut points = original.clone();
        let mut surface = surface;
        let mut boundary_steps = 0;
        if settings.mode == SurfaceMode::Automatic && settings.fair_boundary {
            let (moves, steps) = boundary::fair_boundary(
                &mut points,
                u_count,
                v_count,
                settings.tolerance,
                settings.max_distance,
                |i, j| settings.fixed.contains(&(i, j)),
            )?;
            boundary_steps = steps;
            surface.move_points(&moves)?;
        }
        let network = Network::new(&points, surface.u_knots(), surface.v_knots())?;
        let mut run = Run {
            settings,
            network,
            surface,
            original,
            radii: None,
        };
        if settings.mode == SurfaceMode::Automatic {
            run.radii = Some(run.restraining_radii()?);
        }
        let start = run.record(0);
        let mut history = Vec::new();
        let mut termination = TerminationReason::MaxIterations;
        while history.len() < settings.max_steps {
            let before = run.network.energy();
            let (moves, counts) = run.step()?;
            if !moves.is_empty() && settings.objective != Objective::ThinPlate {
                run.surface.move_points(&moves)?;
            }
            run.network.resum_energy();
            history.push(run.record(moves.len()));
            let after = run.network.energy();
            if moves.is_empty() {
                termination = TerminationReason::StrategyDone;
                break;
            }
            // One point per step (Kjellander): the tolerance applies to the change over as
            // many steps as there are candidate points (a sweep's worth), else one small
            // point would stop the run.
            let (reference, enough) = if settings.one_point_per_step {
                let span = run.candidate_count().max(1);
                let k = history.len();
                let reference = if k > span {
                    history[k - 1 - span].energy
                } else {
                    start.energy
                };
                (reference, k >= span)
            } else {
                (before, true)
            };
            if counts && enough && (reference - after).abs() <= settings.tolerance * reference.abs() {
                termination = TerminationReason::Converged;
                break;
            }
        }
        let final_points = run.surface.points();
        let moved = (0..u_count)
            .flat_map(|i| (0..v_count).map(move |j| (i, j)))
            .filter(|&(i, j)| final_points[i * v_count + j] != run.original[i * v_count + j])
            .collect();
        Ok(SurfaceFairingResult {
            steps: history.len(),
            boundary_steps,
            start,
            history,
            moved,
            radii: run.radii,
            termination,
            elapsed: start_time.elapsed(),
            original: run.original,
            surface: run.surface,
        })
    }
}

impl Run<'_> {
    fn record(&self, moves: usize) -> SurfaceStep {
        SurfaceStep {
            energy: self.network.energy(),
            max_z: self.surface.max_z(),
            moves,
        }
    }

    fn shape(&self) -> (usize, usize) {
        self.network.shape()
    }

    fn is_movable(&self, i: usize, j: usize) -> bool {
        let (u_count, v_count) = self.shape();
        i >= 1 && j >= 1 && i + 1 < u_count && j + 1 < v_count && !self.settings.fixed.contains(&(i, j))
    }

    /// How many points a step chooses from: the movable interior points (automatic) or the
    /// movable named points (interactive).
    fn candidate_count(&self) -> usize {
        let (u_count, v_count) = self.shape();
        match &self.settings.mode {
            SurfaceMode::Automatic => (1..u_count - 1)
                .flat_map(|i| (1..v_count - 1).map(move |j| (i, j)))
                .filter(|&(i, j)| self.is_movable(i, j))
                .count(),
            SurfaceMode::Interactive(list) => {
                let mut list: Vec<(usize, usize)> = list
                    .iter()
                    .copied()
                    .filter(|&(i, j)| self.is_movable(i, j))
                    .collect();
                list.sort_unstable();
                list.dedup();
                list.len()
            }
        }
    }

    /// Step 2.2: |P̄_ij − P_ij| with P̄ from Eq. 21, on the surface after step 2.1.
    fn restraining_radii(&self) -> Result<Vec<f64>> {
        let (u_count, v_count) = self.shape();
        let mut radii = vec![0.0; u_count * v_count];
        for i in 1..u_count - 1 {
            for j in 1..v_count - 1 {
                if self.is_movable(i, j) {
                    let target = limit_targets(&self.network, &[(i, j)]).ok_or_else(|| singular("Eq. 21"))?;
                    radii[i * v_count + j] = (target[0] - self.network.point(i, j)).norm();
                }
            }
        }
        Ok(radii)
    }

    /// The targets of a group under the settings.
    fn targets(&mut self, group: &[(usize, usize)]) -> Result<Vec<Vec3>> {
        let found = match (self.settings.objective, self.settings.replacement) {
            (Objective::Network, Replacement::Limit) => limit_targets(&self.network, group),
            (Objective::Network, Replacement::Iterated) => fixed_tangent_targets(&self.network, group),
            (Objective::ThinPlate, _) => thin_plate::thin_plate_targets(&self.surface, group)?,
        };
        found.ok_or_else(|| singular("group system"))
    }

    /// Moves a group towards its targets, each point kept in its restraining sphere
    /// (automatic mode) and in the distance limit; fixed nodes are never in a group. Returns
    /// the moves made and whether a region cut any of them short. A group move that would
    /// raise the network energy (possible only when a region cuts a pair or block) is undone.
    fn move_group(&mut self, group: &[(usize, usize)]) -> Result<(Vec<NodeMove>, bool)> {
        let targets = self.targets(group)?;
        let v_count = self.shape().1;
        let mut moves = Vec::new();
        let mut limited = false;
        let mut undo = Vec::new();
        for (&(i, j), &target) in group.iter().zip(&targets) {
            let k = i * v_count + j;
            let origin = self.original[k];
            let mut to = target;
            if let Some(radii) = &self.radii {
                to = project_into_ball(&origin, radii[k], &to);
            }
            if let Some(d) = self.settings.max_distance {
                to = project_into_ball(&origin, d, &to);
            }
            limited |= to != target;
            let current = self.network.point(i, j);
            if to != current {
                moves.push(((i, j), to));
                undo.push(((i, j), current));
            }
        }
        if moves.is_empty() {
            return Ok((moves, limited));
        }
        let before = self.network.energy();
        self.network.move_points(&moves)?;
        if group.len() > 1
            && self.settings.objective == Objective::Network
            && self.network.energy() > before * (1.0 + 4.0 * f64::EPSILON)
        {
            self.network.move_points(&undo)?;
            return Ok((Vec::new(), true));
        }
        if self.settings.objective == Objective::ThinPlate {
            self.surface.move_points(&moves)?;
        }
        Ok((moves, limited))
    }

    /// One step; returns the moves (last position of each node) and whether the step counts
    /// for the tolerance test.
    fn step(&mut self) -> Result<(Vec<NodeMove>, bool)> {
        let (u_count, v_count) = self.shape();
        let candidates: Vec<(usize, usize)> = match &self.settings.mode {
            SurfaceMode::Automatic => (1..u_count - 1)
                .flat_map(|i| (1..v_count - 1).map(move |j| (i, j)))
                .filter(|&(i, j)| self.is_movable(i, j))
                .collect(),
            SurfaceMode::Interactive(list) => {
                let mut list: Vec<(usize, usize)> = list
                    .iter()
                    .copied()
                    .filter(|&(i, j)| self.is_movable(i, j))
                    .collect();
                list.sort_unstable();
                list.dedup();
                list
            }
        };
        // Steps 1.2 / 2.3: sort by z_ij, largest first (ties by index, for reproducibility).
        let mut order: Vec<((usize, usize), f64)> = candidates
            .iter()
            .map(|&(i, j)| ((i, j), self.network.z(i, j)))
            .collect();
        order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let mut all_moves = Vec::new();
        if self.settings.one_point_per_step {
            // Kjellander: the worst point that can still move (one its sphere holds at the
            // border, with its target outside, is passed over in this step).
            for &(node, _) in &order {
                let (moves, _) = self.move_group(&[node])?;
                if !moves.is_empty() {
                    return Ok((moves, true));
                }
            }
            return Ok((all_moves, false));
        }
        let groups: Vec<Group> = match self.settings.mode {
            SurfaceMode::Automatic => order.iter().map(|&(node, _)| vec![node]).collect(),
            SurfaceMode::Interactive(_) => group_bad_points(&order.iter().map(|o| o.0).collect::<Vec<_>>()),
        };
        for mut group in groups {
            group.retain(|&(i, j)| self.is_movable(i, j));
            if group.is_empty() {
                continue;
            }
            let (moves, _) = self.move_group(&group)?;
            all_moves.extend(moves);
        }
        // Keep each node's last position only.
        let mut seen = vec![false; u_count * v_count];
        let mut last: Vec<NodeMove> = Vec::with_capacity(all_moves.len());
        for (node, p) in all_moves.into_iter().rev() {
            let slot = &mut seen[node.0 * v_count + node.1];
            if !*slot {
                *slot = true;
                last.push((node, p));
            }
        }
        Ok((last, true))
    }
}

/// Step 1.3 of the interactive algorithm: walking the bad points in descending z order, the
/// current and the next point form a pair when they are grid neighbours
/// (|i_k − i_{k+1}| + |j_k − j_{k+1}| = 1), the 2×2 block they span when they are diagonal
/// (|i_k − i_{k+1}| = |j_k − j_{k+1}| = 1), else the current point goes alone. O(K).
pub fn group_bad_points(sorted: &[(usize, usize)]) -> Vec<Group> {
    let mut groups = Vec::new();
    let mut k = 0;
    while k < sorted.len() {
        let (i, j) = sorted[k];
        match sorted.get(k + 1) {
            Some(&(a, b)) if i.abs_diff(a) + j.abs_diff(b) == 1 => {
                groups.push(vec![(i, j), (a, b)]);
                k += 2;
            }
            Some(&(a, b)) if i.abs_diff(a) == 1 && j.abs_diff(b) == 1 => {
                let (i0, j0) = (i.min(a), j.min(b));
                groups.push(vec![(i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1)]);
                k += 2;
            }
            _ => {
                groups.push(vec![(i, j)]);
                k += 1;
            }
        }
    }
    groups
}

fn singular(what: &str) -> Error {
    crate::state::strategy_error("surface", format!("singular {what}"))
}
