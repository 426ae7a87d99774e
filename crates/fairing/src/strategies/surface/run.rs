//! One run of [`SurfaceFairing`](super::SurfaceFairing): the grid's seams and poles, the
//! boundary fairing, the restraining regions, the steps in priority order, the judgement of
//! every step over the knots the output would have, and the result. See the module docs of
//! [`surface`](super) for what each part does and why.

use std::time::Instant;

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, GridTopology, Parametrization, Vec3};
use fairness::surface::thin_plate_energy;
use fairness::GaussLegendre;

use super::closed_form::{fixed_tangent_targets, limit_target, limit_targets};
use super::network::{prefetch, Network};
use super::queue::{LazyQueue, SweepQueue};
use super::{
    boundary, group_bad_points, singular, thin_plate, NodeMove, Objective, RefusalRule, Region,
    SurfaceFairingResult, SurfaceFairingSettings, SurfaceMode, SurfaceStep, SweepOrder,
};
use crate::strategies::Replacement;
use crate::{project_into_ball, Error, Result, TerminationReason};

/// The fractions of a refused step tried before the run ends (module docs, refusal rules).
const RETRIES: [f64; 3] = [0.5, 0.25, 0.125];

/// How many moves ahead the sorted sweep prefetches a move's first loads
/// ([`Network::prefetch`]); 1 and 2 measured alike at 400 × 400, about 10 % less time.
const PREFETCH_AHEAD: usize = 2;

/// How many grid lines on each side of a node whose z rose the max-z rule pins.
const PIN_REACH: usize = 2;

/// Relative slack of the refusal comparisons: a measure "rises" when it exceeds the accepted
/// value by more than this (the knot refresh alone moves the energy by ~1e-15 relative).
const SLACK: f64 = 1e-12;

/// The grid's layout: all nodes (with a closed direction's repeated line) and the distinct
/// nodes the network works on (without it).
#[derive(Clone, Debug)]
struct Layout {
    /// m + 1, n + 1 of the input.
    u_count: usize,
    v_count: usize,
    /// Distinct nodes along u and v.
    nu: usize,
    nv: usize,
    topology: GridTopology,
}

impl Layout {
    fn new(u_count: usize, v_count: usize, topology: GridTopology) -> Self {
        Self {
            u_count,
            v_count,
            nu: u_count - usize::from(topology.closed_u),
            nv: v_count - usize::from(topology.closed_v),
            topology,
        }
    }

    /// The distinct node of grid node (i, j) (a repeat names line 0).
    fn distinct(&self, i: usize, j: usize) -> (usize, usize) {
        (if i == self.nu { 0 } else { i }, if j == self.nv { 0 } else { j })
    }

    /// Flat index of a distinct node.
    fn index(&self, i: usize, j: usize) -> usize {
        i * self.nv + j
    }

    /// The distinct nodes' values, from the grid's layout.
    fn shrink<T: Copy>(&self, full: &[T]) -> Vec<T> {
        (0..self.nu)
            .flat_map(|i| (0..self.nv).map(move |j| full[i * self.v_count + j]))
            .collect()
    }

    /// [`shrink`](Self::shrink), borrowing the values themselves when no direction is closed.
    fn shrink_ref<'a, T: Copy>(&self, full: &'a [T]) -> std::borrow::Cow<'a, [T]> {
        if self.nu == self.u_count && self.nv == self.v_count {
            std::borrow::Cow::Borrowed(full)
        } else {
            std::borrow::Cow::Owned(self.shrink(full))
        }
    }

    /// The grid's layout, from the distinct nodes' values: the values themselves when no
    /// direction is closed, else a copy with the repeats (copied exactly).
    fn expand_ref<'a, T: Copy>(&self, distinct: &'a [T]) -> std::borrow::Cow<'a, [T]> {
        if self.nu == self.u_count && self.nv == self.v_count {
            std::borrow::Cow::Borrowed(distinct)
        } else {
            std::borrow::Cow::Owned(self.expand(distinct))
        }
    }

    /// [`expand`](Self::expand) of owned values: themselves when no direction is closed.
    fn expand_owned<T: Copy>(&self, distinct: Vec<T>) -> Vec<T> {
        if self.nu == self.u_count && self.nv == self.v_count {
            distinct
        } else {
            self.expand(&distinct)
        }
    }

    /// The grid's layout, from the distinct nodes' values (repeats copied exactly).
    fn expand<T: Copy>(&self, distinct: &[T]) -> Vec<T> {
        (0..self.u_count)
            .flat_map(|i| (0..self.v_count).map(move |j| (i, j)))
            .map(|(i, j)| {
                let (a, b) = self.distinct(i, j);
                distinct[self.index(a, b)]
            })
            .collect()
    }

    fn surface_settings(&self, parametrization: Parametrization) -> BicubicSurfaceSettings {
        BicubicSurfaceSettings::default()
            .with_parametrization(parametrization)
            .with_topology(&self.topology)
    }
}

/// What a step is judged on.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Measure {
    max_z: f64,
    energy: f64,
    thin_plate: Option<f64>,
}

impl Measure {
    /// The first rule `self` breaks against the accepted `before`, if any.
    fn worse_than(&self, before: &Measure) -> Option<RefusalRule> {
        let rises = |new: f64, old: f64| new > old + SLACK * old.abs();
        if rises(self.max_z, before.max_z) {
            return Some(RefusalRule::MaxZ);
        }
        if rises(self.energy, before.energy) {
            return Some(RefusalRule::Energy);
        }
        match (self.thin_plate, before.thin_plate) {
            (Some(new), Some(old)) if rises(new, old) => Some(RefusalRule::ThinPlateEnergy),
            _ => None,
        }
    }

    fn step(&self, moves: usize) -> SurfaceStep {
        SurfaceStep {
            energy: self.energy,
            max_z: self.max_z,
            moves,
        }
    }
}

/// A state of the points: their knots and network (the method's), the network over the
/// output's knots when those differ (`judged`), and the measure.
struct State {
    knots: (Vec<f64>, Vec<f64>),
    network: Network,
    judged: Option<Network>,
    measure: Measure,
}

/// What the judgement of a step decided.
enum Verdict {
    /// The step stands.
    Accepted,
    /// The step is undone and the grid lines next to the nodes it raised above the largest
    /// z are pinned: the step is to be made again without them.
    Pinned,
    /// The step (and its shorter retries) is undone; the rule that refused it.
    Refused(RefusalRule),
}

/// State of one run.
struct Run<'a> {
    settings: &'a SurfaceFairingSettings,
    layout: Layout,
    /// The input's distinct points: the centres of the restraining spheres.
    original: Vec<Vec3>,
    /// Distinct nodes that never move: the user's, and the poles.
    fixed: Vec<bool>,
    /// Distinct nodes pinned by the max-z rule (see [`Verdict::Pinned`]).
    pinned: Vec<bool>,
    /// Restraining radii per distinct node (automatic mode).
    radii: Option<Vec<f64>>,
    /// The cap on the radii from the data's quantisation (automatic mode), if any.
    radius_cap: Option<f64>,
    /// The run's knots when they are not refreshed.
    fixed_knots: Option<(Vec<f64>, Vec<f64>)>,
    /// The working state: the points as moved, their knots and network.
    state: State,
    /// The measure and distinct points of the last accepted state.
    accepted: Measure,
    accepted_points: Vec<Vec3>,
    /// The surface with twists, for the thin-plate objective.
    surface: Option<BicubicSplineSurface>,
    /// No move may raise a z_ij above this (the working network's largest z at the step's
    /// start), when the guard is on.
    cap: f64,
    refused_moves: usize,
    refused_steps: usize,
    /// Storage kept from step to step (fresh arrays of the grid's size are fresh pages):
    /// the points after a step, a shorter retry of it, and the sorted sweep's order: its
    /// nodes (flat indices) and the runs of them in the sweep's order (one per tile for
    /// `tiles`).
    after: Vec<Vec3>,
    shorter: Vec<Vec3>,
    order_nodes: Vec<usize>,
    order_runs: Vec<std::ops::Range<usize>>,
    /// The (z, flat index) pairs being sorted: the whole grid's (`sorted`) or one tile's
    /// (`tiles`), and the radix sort's second buffer.
    order: Vec<(f64, usize)>,
    order_tile: Vec<(f64, usize)>,
    order_scratch: Vec<(f64, usize)>,
}

/// Runs the fairing (the settings checked by the caller).
pub(super) fn run(
    settings: &SurfaceFairingSettings,
    grid: &[Vec<Vec3>],
    start_time: Instant,
) -> Result<SurfaceFairingResult> {
    // The grid as given (ragged or non-finite grids fail here), then its seams and poles.
    let open = BicubicSplineSurface::with_settings(
        grid,
        &BicubicSurfaceSettings::default().with_parametrization(settings.parametrization),
    )?;
    let (u_count, v_count) = open.shape();
    if u_count < 3 || v_count < 3 {
        return Err(Error::BadParameter {
            name: "grid",
            value: format!("{u_count} × {v_count}"),
            reason: "surface fairing needs at least 3 × 3 points (an interior point)",
        });
    }
    let topology = settings.closed.topology(open.points(), u_count, v_count);
    let layout = Layout::new(u_count, v_count, topology);
    // The topology's settings differ from the open build's only in the closed directions:
    // without one, the surface over them is the open one, which is not built again.
    let input = if topology.closed_u || topology.closed_v {
        BicubicSplineSurface::from_flat(
            open.points().to_vec(),
            u_count,
            v_count,
            &layout.surface_settings(settings.parametrization),
        )?
    } else {
        open
    };
    if let Some(&(i, j)) = settings
        .fixed
        .iter()
        .find(|&&(i, j)| i >= u_count || j >= v_count)
    {
        return Err(Error::BadConstraint {
            reason: format!("fixed node ({i}, {j}) is outside the {u_count} × {v_count} grid"),
        });
    }
    let mode = match &settings.mode {
        SurfaceMode::Automatic => SurfaceMode::Automatic,
        SurfaceMode::Interactive(list) => {
            let mut nodes = Vec::with_capacity(list.len());
            for &(i, j) in list {
                match input.interior_node(i, j) {
                    Some(node) => nodes.push(node),
                    None => {
                        return Err(Error::BadConstraint {
                            reason: format!(
                            "bad point ({i}, {j}) is not an interior node of the {u_count} × {v_count} grid"
                        ),
                        })
                    }
                }
            }
            SurfaceMode::Interactive(nodes)
        }
    };
    let mut fixed = vec![false; layout.nu * layout.nv];
    for &(i, j) in &settings.fixed {
        let (a, b) = layout.distinct(i, j);
        fixed[layout.index(a, b)] = true;
    }
    for i in 0..layout.nu {
        for j in 0..layout.nv {
            if topology.poles.contains(i, j, u_count, v_count) {
                fixed[layout.index(i, j)] = true;
            }
        }
    }
    let fixed_knots = (!settings.refresh_knots).then(|| (input.u_knots().to_vec(), input.v_knots().to_vec()));
    // The input's knots are those of its points (the same settings and points, seams
    // closed): the first state takes them rather than averaging the grid again.
    let input_knots = (input.u_knots().to_vec(), input.v_knots().to_vec());
    // The input's points, taken out of its surface (no longer needed) rather than copied.
    let original_full = input.into_points();
    let original = layout.shrink(&original_full);
    let state = State::new(settings, &layout, &original, fixed_knots.as_ref(), &input_knots)?;
    let start = state.measure;
    let mut run = Run {
        settings,
        pinned: vec![false; layout.nu * layout.nv],
        layout,
        accepted_points: original.clone(),
        original,
        fixed,
        radii: None,
        radius_cap: None,
        fixed_knots,
        state,
        accepted: start,
        surface: None,
        cap: f64::INFINITY,
        refused_moves: 0,
        refused_steps: 0,
        after: Vec::new(),
        shorter: Vec::new(),
        order: Vec::new(),
        order_scratch: Vec::new(),
        order_runs: Vec::new(),
        order_nodes: Vec::new(),
        order_tile: Vec::new(),
    };
    let mut history = Vec::new();

    // Step 2.1: the boundary curves. They are judged with the first step (faired alone they
    // usually raise z next to them until the interior follows); if that step is refused in
    // full, the run starts again from the input without them.
    let quantum = super::precision::quantum(&original_full, u_count, v_count);
    if mode == SurfaceMode::Automatic && settings.quantum_scale > 0.0 {
        run.radius_cap = quantum.map(|q| q * settings.quantum_scale);
    }
    let mut boundary_steps = 0;
    let mut boundary_pending = false;
    if mode == SurfaceMode::Automatic && settings.fair_boundary {
        let band = match (settings.max_distance, run.radius_cap) {
            (Some(d), Some(c)) => Some(d.min(c)),
            (d, c) => d.or(c),
        };
        let mut points = original_full.clone();
        let (moves, steps) = boundary::fair_boundary(
            &mut points,
            u_count,
            v_count,
            (topology.closed_u, topology.closed_v),
            settings.tolerance,
            band,
            |i, j| settings.fixed.contains(&(i, j)),
        )?;
        if !moves.is_empty() {
            // (Boundary curves are faired only on an open grid, whose distinct nodes are
            // all of its nodes: no copy.)
            run.rebuild_state(&run.layout.shrink_ref(&points))?;
            boundary_steps = steps;
            boundary_pending = true;
        }
    }
    if mode == SurfaceMode::Automatic {
        run.radii = Some(run.restraining_radii()?);
    }

    let mut steps = 0;
    let mut termination = TerminationReason::MaxIterations;
    let mut refusal = None;
    // The rule that refused the last step not kept, whatever ended the run.
    let mut last_rule = None;
    while steps < settings.max_steps {
        optim::cancel::checkpoint()?;
        if settings.objective == Objective::ThinPlate {
            run.surface = Some(run.surface_of(run.state.network.points(), &run.state.knots)?);
        }
        run.cap = run.state.network.max_z();
        let (moved, made) = run.sweep(&mode, settings.max_steps - steps)?;
        steps += made;
        if moved == 0 && !boundary_pending {
            termination = TerminationReason::StrategyDone;
            break;
        }
        let previous = run.accepted;
        match run.judge()? {
            Verdict::Accepted => boundary_pending = false,
            Verdict::Pinned => {
                last_rule = Some(RefusalRule::MaxZ);
                continue;
            }
            Verdict::Refused(rule) if boundary_pending => {
                last_rule = Some(rule);
                // Back at the input: go on without the boundary fairing.
                boundary_pending = false;
                boundary_steps = 0;
                if mode == SurfaceMode::Automatic {
                    run.radii = Some(run.restraining_radii()?);
                }
                continue;
            }
            Verdict::Refused(rule) => {
                refusal = Some(rule);
                termination = TerminationReason::StrategyDone;
                break;
            }
        }
        history.push(run.accepted.step(moved));
        if moved == 0 {
            termination = TerminationReason::StrategyDone;
            break;
        }
        let (old, new) = (previous.energy, run.accepted.energy);
        if (old - new).abs() <= settings.tolerance * old.abs() {
            termination = TerminationReason::Converged;
            break;
        }
    }
    let mut boundary_kept = false;
    if boundary_pending {
        match run.judge()? {
            Verdict::Accepted => boundary_kept = true,
            verdict => {
                // Judged alone (no step was left): pinned lines do not help it; it is undone.
                if let Verdict::Refused(rule) = verdict {
                    last_rule = Some(rule);
                }
                run.rebuild_accepted()?;
                boundary_steps = 0;
            }
        }
    }
    if history.is_empty() && !boundary_kept && run.refused_steps > 0 {
        // Nothing was kept and the rules refused what was tried: the report says so, with
        // the rule, rather than that the strategy found nothing to do.
        termination = TerminationReason::Refused;
        refusal = refusal.or(last_rule);
    }

    // The result, in the grid's layout: the surface built on the network's own points,
    // taken out of it (not copied twice: once into the grid's layout, once for the surface).
    let mut final_points = Vec::new();
    run.state.network.swap_points(&mut final_points);
    let surface = surface_through_full(
        &run.layout,
        run.layout.expand_owned(final_points),
        &run.state.knots,
        settings.parametrization,
    )?;
    // The surface keeps its points as given (its seams' repeats are exact copies already).
    let final_full = surface.points();
    let moved = (0..u_count)
        .flat_map(|i| (0..v_count).map(move |j| (i, j)))
        .filter(|&(i, j)| final_full[i * v_count + j] != original_full[i * v_count + j])
        .collect();
    let radii = run.radii.as_ref().map(|r| run.layout.expand(r));
    let pinned_full = run.layout.expand(&run.pinned);
    let pinned = (0..u_count)
        .flat_map(|i| (0..v_count).map(move |j| (i, j)))
        .filter(|&(i, j)| pinned_full[i * v_count + j])
        .collect();
    Ok(SurfaceFairingResult {
        surface,
        original: original_full,
        steps,
        boundary_steps,
        start: start.step(0),
        history,
        moved,
        radii,
        termination,
        refusal,
        refused_steps: run.refused_steps,
        refused_moves: run.refused_moves,
        pinned,
        topology,
        quantum,
        elapsed: start_time.elapsed(),
    })
}

impl State {
    /// The network over the output's knots.
    fn measured(&self) -> &Network {
        self.judged.as_ref().unwrap_or(&self.network)
    }

    /// The state of distinct `points`: their knots (or the fixed ones), network and measure.
    /// `own_knots` are the knots the settings' parametrization gives `points` (the input
    /// surface's, for the input's points). O(m·n).
    fn new(
        settings: &SurfaceFairingSettings,
        layout: &Layout,
        points: &[Vec3],
        fixed_knots: Option<&(Vec<f64>, Vec<f64>)>,
        own_knots: &(Vec<f64>, Vec<f64>),
    ) -> Result<Self> {
        let (knots, judged_knots) =
            Self::knots_given(settings, layout, points, fixed_knots, Some(own_knots))?;
        let closed = (layout.topology.closed_u, layout.topology.closed_v);
        // The limit replacement of the network objective never reads the tangents
        // ([`finish`](Self::finish) stops their tracking): the first network is built
        // without them.
        let tangents =
            !(settings.objective == Objective::Network && settings.replacement == Replacement::Limit);
        let network = Network::with_tangents(points, &knots.0, &knots.1, closed, tangents)?;
        let judged = match &judged_knots {
            None => None,
            Some(k) => Some(Network::new(points, &k.0, &k.1, closed)?),
        };
        let mut state = Self {
            knots,
            network,
            judged,
            measure: Measure {
                max_z: 0.0,
                energy: 0.0,
                thin_plate: None,
            },
        };
        state.finish(settings, layout, judged_knots)?;
        Ok(state)
    }

    /// This state made the state of other distinct `points`, in its own storage: the same
    /// values as [`new`](Self::new) without fresh m·n arrays (a run rebuilds its state at
    /// every step). On an error the state is left unusable. O(m·n).
    fn rebuild(
        &mut self,
        settings: &SurfaceFairingSettings,
        layout: &Layout,
        points: &[Vec3],
        fixed_knots: Option<&(Vec<f64>, Vec<f64>)>,
    ) -> Result<()> {
        let (knots, judged_knots) = Self::knots_of(settings, layout, points, fixed_knots)?;
        let closed = (layout.topology.closed_u, layout.topology.closed_v);
        self.network.rebuild(points, &knots.0, &knots.1, closed)?;
        self.knots = knots;
        match (&judged_knots, &mut self.judged) {
            (None, judged) => *judged = None,
            (Some(k), Some(judged)) => judged.rebuild(points, &k.0, &k.1, closed)?,
            (Some(k), judged) => *judged = Some(Network::new(points, &k.0, &k.1, closed)?),
        }
        self.finish(settings, layout, judged_knots)
    }

    /// The knots of distinct `points` (or the fixed ones), and the output's knots when they
    /// differ (the judgement is over the knots a user measures the output with: chord-length
    /// averaged over the points as they are, the run's own when it works on those).
    #[allow(clippy::type_complexity)]
    fn knots_of(
        settings: &SurfaceFairingSettings,
        layout: &Layout,
        points: &[Vec3],
        fixed_knots: Option<&(Vec<f64>, Vec<f64>)>,
    ) -> Result<((Vec<f64>, Vec<f64>), Option<(Vec<f64>, Vec<f64>)>)> {
        Self::knots_given(settings, layout, points, fixed_knots, None)
    }

    /// [`knots_of`](Self::knots_of), the knots of the settings' parametrization taken from
    /// `own_knots` when given (they must be those of `points`).
    #[allow(clippy::type_complexity)]
    fn knots_given(
        settings: &SurfaceFairingSettings,
        layout: &Layout,
        points: &[Vec3],
        fixed_knots: Option<&(Vec<f64>, Vec<f64>)>,
        own_knots: Option<&(Vec<f64>, Vec<f64>)>,
    ) -> Result<((Vec<f64>, Vec<f64>), Option<(Vec<f64>, Vec<f64>)>)> {
        let grid = layout.expand_ref(points);
        let knots = match (fixed_knots, own_knots) {
            (Some(knots), _) | (None, Some(knots)) => knots.clone(),
            (None, None) => layout.surface_settings(settings.parametrization).knots(
                &grid,
                layout.u_count,
                layout.v_count,
            )?,
        };
        let own = fixed_knots.is_none() && settings.parametrization == Parametrization::ChordLength;
        let judged_knots = if own {
            None
        } else {
            Some(layout.surface_settings(Parametrization::ChordLength).knots(
                &grid,
                layout.u_count,
                layout.v_count,
            )?)
        };
        Ok((knots, judged_knots))
    }

    /// The network's tracking of tangents as the settings need it, and the measure.
    fn finish(
        &mut self,
        settings: &SurfaceFairingSettings,
        layout: &Layout,
        judged_knots: Option<(Vec<f64>, Vec<f64>)>,
    ) -> Result<()> {
        if settings.objective == Objective::Network && settings.replacement == Replacement::Limit {
            self.network.stop_tracking_tangents();
        }
        let judged_knots = judged_knots.as_ref().unwrap_or(&self.knots);
        let measured = self.judged.as_ref().unwrap_or(&self.network);
        let thin_plate = if settings.objective == Objective::ThinPlate {
            let surface = surface_through(
                layout,
                measured.points(),
                judged_knots,
                Parametrization::ChordLength,
            )?;
            let rule =
                GaussLegendre::new(4).map_err(|e| crate::state::strategy_error("surface", e.to_string()))?;
            Some(
                thin_plate_energy(&surface, &judged_knots.0, &judged_knots.1, &rule)
                    .map_err(|e| crate::state::strategy_error("surface", e.to_string()))?,
            )
        } else {
            None
        };
        self.measure = Measure {
            max_z: measured.max_z(),
            energy: measured.energy(),
            thin_plate,
        };
        Ok(())
    }
}

/// The bicubic surface through distinct points over given knots, periodic where the layout
/// is closed. O(m·n).
fn surface_through(
    layout: &Layout,
    points: &[Vec3],
    knots: &(Vec<f64>, Vec<f64>),
    parametrization: Parametrization,
) -> Result<BicubicSplineSurface> {
    surface_through_full(layout, layout.expand(points), knots, parametrization)
}

/// [`surface_through`] of the points in the grid's layout (`full`, repeats included).
fn surface_through_full(
    layout: &Layout,
    full: Vec<Vec3>,
    knots: &(Vec<f64>, Vec<f64>),
    parametrization: Parametrization,
) -> Result<BicubicSplineSurface> {
    Ok(BicubicSplineSurface::from_flat(
        full,
        layout.u_count,
        layout.v_count,
        &layout
            .surface_settings(parametrization)
            .with_u_knots(knots.0.clone())
            .with_v_knots(knots.1.clone()),
    )?)
}

impl Run<'_> {
    fn surface_of(&self, points: &[Vec3], knots: &(Vec<f64>, Vec<f64>)) -> Result<BicubicSplineSurface> {
        surface_through(&self.layout, points, knots, self.settings.parametrization)
    }

    /// Whether distinct node (i, j) may move: interior (a seam counts), not fixed, not a pole.
    fn is_movable(&self, i: usize, j: usize) -> bool {
        let k = self.layout.index(i, j);
        self.state.network.is_interior(i, j) && !self.fixed[k] && !self.pinned[k]
    }

    /// The movable interior nodes, i-major.
    fn candidates(&self, mode: &SurfaceMode) -> Vec<(usize, usize)> {
        match mode {
            SurfaceMode::Automatic => (0..self.layout.nu)
                .flat_map(|i| (0..self.layout.nv).map(move |j| (i, j)))
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
        }
    }

    /// Step 2.2: `radius_scale` · |P̄_ij − P_ij| with P̄ from Eq. 21, on the surface after
    /// step 2.1; 0 where a point may not move.
    fn restraining_radii(&self) -> Result<Vec<f64>> {
        let network = &self.state.network;
        let mut radii = vec![0.0; self.layout.nu * self.layout.nv];
        let mut own = Vec::new();
        for i in 0..self.layout.nu {
            for j in 0..self.layout.nv {
                if self.is_movable(i, j) {
                    let target = limit_targets(network, &[(i, j)]).ok_or_else(|| singular("Eq. 21"))?;
                    let distance = (target[0] - network.point(i, j)).norm();
                    radii[self.layout.index(i, j)] = distance;
                    own.push(distance);
                }
            }
        }
        let floor = match self.settings.region {
            Region::Sphere => 0.0,
            Region::MedianFloor if own.is_empty() => 0.0,
            Region::MedianFloor => {
                let middle = own.len() / 2;
                *own.select_nth_unstable_by(middle, f64::total_cmp).1
            }
        };
        let scale = self.settings.radius_scale;
        let cap = self.radius_cap.unwrap_or(f64::INFINITY);
        for r in radii.iter_mut().filter(|r| **r > 0.0 || floor > 0.0) {
            let widened = if scale.is_infinite() {
                f64::INFINITY
            } else {
                scale * r.max(floor)
            };
            *r = widened.min(cap);
        }
        for i in 0..self.layout.nu {
            for j in 0..self.layout.nv {
                if !self.is_movable(i, j) {
                    radii[self.layout.index(i, j)] = 0.0;
                }
            }
        }
        Ok(radii)
    }

    /// The targets of a group under the settings.
    fn targets(&self, group: &[(usize, usize)]) -> Result<Vec<Vec3>> {
        let network = &self.state.network;
        let found = match (self.settings.objective, self.settings.replacement) {
            (Objective::Network, Replacement::Limit) => limit_targets(network, group),
            (Objective::Network, Replacement::Iterated) => fixed_tangent_targets(network, group),
            (Objective::ThinPlate, _) => match &self.surface {
                Some(surface) => thin_plate::thin_plate_targets(surface, group)?,
                None => None,
            },
        };
        found.ok_or_else(|| singular("group system"))
    }

    /// Moves a group towards its targets, each point kept in its restraining sphere
    /// (automatic mode) and in the distance limit; fixed nodes are never in a group. Returns
    /// whether anything moved. A move that would raise the network energy is undone (not for
    /// the thin-plate objective, whose energy the judgement checks).
    fn move_group(&mut self, group: &[(usize, usize)]) -> Result<bool> {
        if let [(i, j)] = *group {
            if self.surface.is_none() {
                return self.move_one(i, j);
            }
        }
        let targets = self.targets(group)?;
        let mut moves: Vec<NodeMove> = Vec::new();
        let mut undo: Vec<NodeMove> = Vec::new();
        for (&(i, j), &target) in group.iter().zip(&targets) {
            let k = self.layout.index(i, j);
            let origin = self.original[k];
            let current = self.state.network.point(i, j);
            let mut to = target;
            if let Some(radii) = &self.radii {
                to = project_into_ball(&origin, radii[k], &to);
            }
            if let Some(d) = self.settings.max_distance {
                to = project_into_ball(&origin, d, &to);
            }
            if to != current {
                moves.push(((i, j), to));
                undo.push(((i, j), current));
            }
        }
        if moves.is_empty() {
            return Ok(false);
        }
        // The move, or 1/2 or 1/4 of it, if it keeps the network energy from rising (the
        // network objective's own) and every z it changes at most the step's starting
        // maximum (the guard).
        let cap = self.settings.guard.then_some(self.cap);
        for fraction in [1.0, 0.5, 0.25] {
            let trial: Vec<NodeMove> = moves
                .iter()
                .zip(&undo)
                .map(|(&(node, to), &(_, from))| {
                    (
                        node,
                        if fraction == 1.0 {
                            to
                        } else {
                            from + (to - from) * fraction
                        },
                    )
                })
                .collect();
            let before = self.state.network.energy();
            self.state.network.move_points(&trial)?;
            let energy_rose = self.settings.objective == Objective::Network
                && self.state.network.energy() > before + 4.0 * f64::EPSILON * before.abs();
            let z_rose = match cap {
                Some(cap) if !energy_rose => {
                    let network = &mut self.state.network;
                    trial.iter().any(|&((i, j), _)| network.exceeds(i, j, cap))
                }
                _ => false,
            };
            if !energy_rose && !z_rose {
                if let Some(surface) = &mut self.surface {
                    surface.move_points(&trial)?;
                }
                return Ok(true);
            }
            self.state.network.move_points(&undo)?;
        }
        self.refused_moves += 1;
        Ok(false)
    }

    /// [`move_group`](Self::move_group) for one point of the network objective, without
    /// allocations: the hot loop of the automatic mode.
    fn move_one(&mut self, i: usize, j: usize) -> Result<bool> {
        let network = &self.state.network;
        let target = match self.settings.replacement {
            Replacement::Limit => limit_target(network, i, j),
            Replacement::Iterated => fixed_tangent_targets(network, &[(i, j)]).map(|t| t[0]),
        }
        .ok_or_else(|| singular("Eq. 20/21"))?;
        let k = self.layout.index(i, j);
        let origin = self.original[k];
        let current = network.point(i, j);
        let mut to = target;
        if let Some(radii) = &self.radii {
            to = project_into_ball(&origin, radii[k], &to);
        }
        if let Some(d) = self.settings.max_distance {
            to = project_into_ball(&origin, d, &to);
        }
        if to == current {
            return Ok(false);
        }
        let energy = network.energy();
        for fraction in [1.0, 0.5, 0.25] {
            let trial = if fraction == 1.0 {
                to
            } else {
                current + (to - current) * fraction
            };
            if self.state.network.energy_change(i, j, trial - current) > 4.0 * f64::EPSILON * energy.abs() {
                continue;
            }
            self.state.network.move_points(&[((i, j), trial)])?;
            if self.settings.guard && self.state.network.exceeds(i, j, self.cap) {
                self.state.network.move_points(&[((i, j), current)])?;
                continue;
            }
            return Ok(true);
        }
        self.refused_moves += 1;
        Ok(false)
    }

    /// One step: every candidate once by current z (automatic), every group once
    /// (interactive), or, one point per step, up to a sweep's worth of single moves. Returns
    /// (points moved, steps made); a Kjellander step is one move and never more than
    /// `budget` are made.
    fn sweep(&mut self, mode: &SurfaceMode, budget: usize) -> Result<(usize, usize)> {
        let nv = self.layout.nv;
        let node = |k: usize| (k / nv, k % nv);
        if self.settings.one_point_per_step {
            let candidates = self.candidates(mode);
            return self.kjellander_sweep(&candidates, budget);
        }
        let mut moved = 0;
        match mode {
            SurfaceMode::Automatic if self.settings.order == SweepOrder::Queue => {
                // Steps 2.3–2.4 by current z: every point once, the largest z of those still
                // to come first (ties by index), re-keyed as moves raise it.
                let candidates = self.candidates(mode);
                let layout = &self.layout;
                let mut queue = SweepQueue::new(
                    &self.state.network,
                    candidates.iter().map(|&(i, j)| layout.index(i, j)),
                );
                while let Some(k) = queue.pop(&self.state.network) {
                    let (i, j) = node(k);
                    if self.move_group(&[(i, j)])? {
                        moved += 1;
                    }
                    queue.moved(&mut self.state.network, i, j);
                }
            }
            SurfaceMode::Automatic => {
                // Step 2.3: every point once, by z at the step's start, largest first (ties
                // by index); for `tiles` inside each tile, the tiles by their largest z.
                // The candidates (the movable nodes) with their z, in the run's storage; z
                // from the exact bounds when the network is fresh (it is, at a step's
                // start: one contiguous array), else from the jumps (the same values).
                let mut order = std::mem::take(&mut self.order);
                let mut nodes = std::mem::take(&mut self.order_nodes);
                let mut runs = std::mem::take(&mut self.order_runs);
                let mut tile = std::mem::take(&mut self.order_tile);
                let mut scratch = std::mem::take(&mut self.order_scratch);
                let network = &self.state.network;
                let exact = network.exact_zs();
                let z = |k: usize| exact.map_or_else(|| network.z_at(k), |zs| zs[k]);
                let movable = |i: usize, j: usize| self.is_movable(i, j);
                if self.settings.order == SweepOrder::Tiles {
                    super::tiles::tiled_order(
                        self.layout.nu,
                        nv,
                        z,
                        movable,
                        &mut nodes,
                        &mut runs,
                        &mut tile,
                        &mut scratch,
                    );
                } else {
                    order.clear();
                    order.extend(
                        (0..self.layout.nu)
                            .flat_map(|i| (0..nv).map(move |j| (i, j)))
                            .filter(|&(i, j)| movable(i, j))
                            .map(|(i, j)| (z(self.layout.index(i, j)), self.layout.index(i, j))),
                    );
                    super::radix::sort_descending(&mut order, &mut scratch);
                    nodes.clear();
                    nodes.extend(order.iter().map(|&(_, k)| k));
                    runs.clear();
                    runs.push(0..nodes.len());
                }
                (self.order_tile, self.order_scratch) = (tile, scratch);
                let result = self.sorted_sweep(&nodes, &runs);
                self.order = order;
                self.order_nodes = nodes;
                self.order_runs = runs;
                moved = result?;
            }
            SurfaceMode::Interactive(_) => {
                let candidates = self.candidates(mode);
                // Steps 1.2–1.3: by z, largest first (ties by index), grouped.
                let network = &self.state.network;
                let mut order: Vec<((usize, usize), f64)> = candidates
                    .iter()
                    .map(|&(i, j)| ((i, j), network.z(i, j)))
                    .collect();
                order.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
                let sorted: Vec<(usize, usize)> = order.iter().map(|o| o.0).collect();
                for mut group in group_bad_points(&sorted) {
                    group.retain(|&(i, j)| i < self.layout.nu && j < nv && self.is_movable(i, j));
                    if !group.is_empty() && self.move_group(&group)? {
                        moved += group.len();
                    }
                }
            }
        }
        Ok((moved, 1))
    }

    /// The moves of a sorted step, one per node of `nodes` (flat indices) in turn, taking
    /// the runs of `nodes` in `runs`' order. Returns the points moved.
    fn sorted_sweep(&mut self, nodes: &[usize], runs: &[std::ops::Range<usize>]) -> Result<usize> {
        let nv = self.layout.nv;
        let node = |k: usize| (k / nv, k % nv);
        let mut moved = 0;
        let sequence = runs.iter().flat_map(|run| &nodes[run.clone()]);
        let mut ahead = sequence.clone().skip(PREFETCH_AHEAD);
        for &k in sequence {
            // The order is scattered over the grid: the first loads of the move two ahead are
            // started now (no effect on any value).
            if let Some(&next) = ahead.next() {
                let (a, b) = node(next);
                self.state.network.prefetch(a, b);
                prefetch(&self.original[next]);
                if let Some(radii) = &self.radii {
                    prefetch(&radii[next]);
                }
            }
            if self.move_group(&[node(k)])? {
                moved += 1;
            }
        }
        Ok(moved)
    }

    /// Kjellander: up to one sweep (as many steps as candidates) of single moves, each of the
    /// worst point that can move; a point its sphere holds is set aside until a move next to
    /// it changes its z.
    fn kjellander_sweep(&mut self, candidates: &[(usize, usize)], budget: usize) -> Result<(usize, usize)> {
        let nv = self.layout.nv;
        let network = &self.state.network;
        let mut queue = LazyQueue::new(
            candidates
                .iter()
                .map(|&(i, j)| (network.z(i, j), self.layout.index(i, j))),
        );
        let mut member = vec![false; self.layout.nu * nv];
        for &(i, j) in candidates {
            member[self.layout.index(i, j)] = true;
        }
        let mut held = vec![false; self.layout.nu * nv];
        let limit = candidates.len().min(budget);
        let mut steps = 0;
        while steps < limit {
            let network = &self.state.network;
            let Some(k) = queue.pop(|k| network.z(k / nv, k % nv), |k| !held[k]) else {
                break;
            };
            let (i, j) = (k / nv, k % nv);
            if !self.move_group(&[(i, j)])? {
                held[k] = true;
                continue;
            }
            steps += 1;
            // The z of the nodes along the moved point's row and column change, most within
            // a few knots: their keys are refreshed (and held ones released).
            let (u, v) = (self.state.network.u_stiffness(), self.state.network.v_stiffness());
            let mut near = vec![(i, j)];
            let (mut back, mut ahead) = (u.previous(i), u.next(i));
            let (mut left, mut right) = (v.previous(j), v.next(j));
            for _ in 0..3 {
                if let Some(p) = back {
                    near.push((p, j));
                    back = u.previous(p);
                }
                if let Some(p) = ahead {
                    near.push((p, j));
                    ahead = u.next(p);
                }
                if let Some(q) = left {
                    near.push((i, q));
                    left = v.previous(q);
                }
                if let Some(q) = right {
                    near.push((i, q));
                    right = v.next(q);
                }
            }
            for (a, b) in near {
                let index = self.layout.index(a, b);
                if member[index] {
                    held[index] = false;
                    queue.push(self.state.network.z(a, b), index);
                }
            }
        }
        Ok((steps, steps))
    }

    /// Judges the points moved since the last accepted state (the working state's), over the
    /// knots the output would have: accepted when no rule breaks against it. A rise of the largest z first pins the
    /// grid lines whose chord lengths set the knots at the nodes that rose (see [`pin`]) and
    /// asks for the step again; else the step is retried at 1/2, 1/4, 1/8 of the way from
    /// the accepted state; else the working state goes back to it and the rule is returned.
    ///
    /// [`pin`]: Self::pin
    fn judge(&mut self) -> Result<Verdict> {
        // The working state becomes the candidate in place: its points are taken out first
        // (their storage exchanged with `after`'s, no copy: the rebuild copies them back)
        // and it is rebuilt from the accepted points whenever the step is not accepted.
        let mut after = std::mem::take(&mut self.after);
        self.state.network.swap_points(&mut after);
        let result = self.judge_points(&mut after);
        self.after = after;
        result
    }

    /// [`judge`](Self::judge) of the points `after` the step (`after`'s storage may be
    /// exchanged for other points').
    fn judge_points(&mut self, after: &mut Vec<Vec3>) -> Result<Verdict> {
        self.rebuild_state(after)?;
        let mut rule = if self.settings.guard {
            self.state.measure.worse_than(&self.accepted)
        } else {
            None
        };
        if rule == Some(RefusalRule::MaxZ) && self.pin()? {
            self.refused_steps += 1;
            self.rebuild_accepted()?;
            return Ok(Verdict::Pinned);
        }
        let mut shorter = std::mem::take(&mut self.shorter);
        let mut retried = false;
        for fraction in RETRIES {
            if rule.is_none() {
                break;
            }
            retried = true;
            self.refused_steps += 1;
            shorter.clear();
            shorter.extend(self.accepted_points.iter().zip(after.iter()).map(|(p, q)| {
                if p == q {
                    *p
                } else {
                    p + (q - p) * fraction
                }
            }));
            self.rebuild_state(&shorter)?;
            rule = self.state.measure.worse_than(&self.accepted);
        }
        let verdict = match rule {
            None => {
                self.accepted = self.state.measure;
                // The accepted points are those the state was last rebuilt from (its
                // network's are a copy): their storage is exchanged, not copied.
                let built = if retried { &mut shorter } else { after };
                std::mem::swap(&mut self.accepted_points, built);
                Ok(Verdict::Accepted)
            }
            Some(rule) => {
                self.refused_steps += 1;
                self.rebuild_accepted()?;
                Ok(Verdict::Refused(rule))
            }
        };
        self.shorter = shorter;
        verdict
    }

    /// The working state rebuilt in place as the state of distinct `points`.
    fn rebuild_state(&mut self, points: &[Vec3]) -> Result<()> {
        self.state
            .rebuild(self.settings, &self.layout, points, self.fixed_knots.as_ref())
    }

    /// The working state rebuilt in place as the last accepted state.
    fn rebuild_accepted(&mut self) -> Result<()> {
        let accepted = std::mem::take(&mut self.accepted_points);
        let result = self.rebuild_state(&accepted);
        self.accepted_points = accepted;
        result
    }

    /// The max-z rule's remedy for the knots. Over the output's knots a node's z changes
    /// when its neighbours' chord lengths do, which the step (made over the step's knots)
    /// does not see: on a fold like the teapot's rim, where the knot steps are short, that
    /// effect wins. For every node whose z rose above the accepted maximum, the grid lines
    /// whose moves set its knots are pinned for the rest of the run: the lines along u
    /// within [`PIN_REACH`] of it when its u-jump grew (their chord lengths make its u knot
    /// steps), the lines along v when its v-jump grew. Returns whether anything new was
    /// pinned. O(m·n).
    fn pin(&mut self) -> Result<bool> {
        let accepted_parts = self.accepted_parts()?;
        let network = self.state.measured();
        let (nu, nv) = (self.layout.nu, self.layout.nv);
        let limit = self.accepted.max_z + SLACK * self.accepted.max_z.abs();
        let (closed_u, closed_v) = (self.layout.topology.closed_u, self.layout.topology.closed_v);
        let reach = |k: usize, count: usize, closed: bool| -> Vec<usize> {
            let k = k as isize;
            let r = PIN_REACH as isize;
            (k - r..=k + r)
                .filter_map(|l| {
                    if closed {
                        Some(l.rem_euclid(count as isize) as usize)
                    } else {
                        (l >= 0 && (l as usize) < count).then_some(l as usize)
                    }
                })
                .collect()
        };
        let mut rows = vec![false; nu];
        let mut columns = vec![false; nv];
        for i in 0..nu {
            for j in 0..nv {
                if !network.is_interior(i, j) || network.z(i, j) <= limit {
                    continue;
                }
                let (u_before, v_before) = accepted_parts[self.layout.index(i, j)];
                let (u_after, v_after) = (network.u_jump(i, j).norm(), network.v_jump(i, j).norm());
                if u_after > u_before {
                    for l in reach(i, nu, closed_u) {
                        rows[l] = true;
                    }
                }
                if v_after > v_before {
                    for l in reach(j, nv, closed_v) {
                        columns[l] = true;
                    }
                }
            }
        }
        let mut new = false;
        for (i, &row) in rows.iter().enumerate().take(nu) {
            for (j, &column) in columns.iter().enumerate().take(nv) {
                let k = self.layout.index(i, j);
                if (row || column) && !self.pinned[k] && !self.fixed[k] && network.is_interior(i, j) {
                    self.pinned[k] = true;
                    new = true;
                }
            }
        }
        Ok(new)
    }

    /// (|J^u|, |J^v|) at every distinct node of the last accepted state, over the output's
    /// knots: from the network of its points over those knots, built as the state built it
    /// (the same values). Only the max-z rule's [`pin`](Self::pin) reads them, so they are
    /// built when it does instead of kept at every acceptance (a whole-grid pass over both
    /// jump arrays, one of them column-major, at every step). O(m·n).
    fn accepted_parts(&self) -> Result<Vec<(f64, f64)>> {
        let points = &self.accepted_points;
        let (knots, judged_knots) =
            State::knots_of(self.settings, &self.layout, points, self.fixed_knots.as_ref())?;
        let (u, v) = judged_knots.as_ref().unwrap_or(&knots);
        let closed = (self.layout.topology.closed_u, self.layout.topology.closed_v);
        Ok(jump_parts(&Network::new(points, u, v, closed)?))
    }
}

/// (|J^u|, |J^v|) at every distinct node.
fn jump_parts(network: &Network) -> Vec<(f64, f64)> {
    network
        .u_jumps_and_v_jumps()
        .map(|(u, v)| (u.norm(), v.norm()))
        .collect()
}

#[cfg(test)]
mod rules {
    use super::*;

    fn measure(max_z: f64, energy: f64, thin_plate: Option<f64>) -> Measure {
        Measure {
            max_z,
            energy,
            thin_plate,
        }
    }

    #[test]
    fn each_rule_refuses_its_own_rise_and_nothing_else() {
        let before = measure(2.0, 5.0, Some(7.0));
        assert_eq!(measure(2.0, 5.0, Some(7.0)).worse_than(&before), None);
        assert_eq!(measure(1.0, 4.0, Some(6.0)).worse_than(&before), None);
        // Within the slack of a knot refresh: not a rise.
        assert_eq!(
            measure(2.0 * (1.0 + 1e-13), 5.0, Some(7.0)).worse_than(&before),
            None
        );
        assert_eq!(
            measure(2.1, 4.0, Some(6.0)).worse_than(&before),
            Some(RefusalRule::MaxZ)
        );
        assert_eq!(
            measure(1.0, 5.1, Some(6.0)).worse_than(&before),
            Some(RefusalRule::Energy)
        );
        assert_eq!(
            measure(1.0, 4.0, Some(7.1)).worse_than(&before),
            Some(RefusalRule::ThinPlateEnergy)
        );
        // The network objective has no thin-plate energy to judge.
        assert_eq!(measure(1.0, 4.0, None).worse_than(&measure(2.0, 5.0, None)), None);
        // Max z is judged first.
        assert_eq!(
            measure(2.1, 5.1, Some(7.1)).worse_than(&before),
            Some(RefusalRule::MaxZ)
        );
    }
}
