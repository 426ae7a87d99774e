//! Zhang–Cheng fairing of bicubic spline surfaces (Zhang, Zhang & Cheng, *Fairing spline
//! curves and surfaces by minimizing energy*, CAD 33 (2001) §4), with Kjellander's one-point
//! method as the baseline preset.
//!
//! The surface is the [`BicubicSplineSurface`] through a grid P_ij (i = 0..m along u,
//! j = 0..n along v). A bad point is moved to the minimiser of the strain energy of the
//! iso-parametric curves through it (`closed_form`: one point Eq. 18–20 and its limit Eq. 21,
//! an adjacent pair Eq. 22–23, a 2×2 block Eq. 24–25), or of the thin-plate energy of the
//! patches around it (`thin_plate`, Eq. 27–29) as an option.
//!
//! - **Automatic** (§4.4, algorithm 2): the boundary curves are faired first with the curve
//!   method (`boundary`); each interior point gets a restraining sphere of radius
//!   `radius_scale` · |P̄_ij − P_ij| (P̄ from Eq. 21 on the surface after step 2.1); then every
//!   step fairs every interior point once, the largest z_ij (Eq. 26) first, each kept in its
//!   sphere; the surface is rebuilt (2.5) and the run stops when the network strain energy
//!   changes by at most `tolerance` × its value in one step (2.6). The order of work is a
//!   [`SweepOrder`]. `order = sort` is the paper's: z_ij at the step's start, sorted once per
//!   step (O(m·n log(m·n)), against the step's own O(m·n) moves of O(window) each).
//!   `order = queue` takes the point of largest *current* z_ij off an indexed heap whose keys
//!   are raised in place as moves raise them (exactly the nodes a move changes are looked at;
//!   a pop is what a full rescan of the current z would choose); on the surface table's nets
//!   it ends with an equal or larger largest z_ij than the sort, at about three times the
//!   CPU per step (the heap's pops and re-keys miss the cache where the sort reads an array).
//!   The default, `order = tiles`, is the paper's sort inside 64 × 64 tiles of the grid, the
//!   tiles taken by their largest z: a move changes only its own windows, so far-apart moves
//!   do not see each other's order, and a tile's moves stay in the processor's cache where
//!   the global order scatters them over a grid that outgrew it. On a net of at most 64
//!   nodes each way it is the paper's order bit for bit (every net of the surface table but
//!   the grids); on the large noisy grids it ends at the sort's measures or lower in less
//!   time. Kjellander, which moves one point per step, takes its worst point off a lazy queue.
//! - **Interactive** (§4.4, algorithm 1): the user's bad points are sorted by z_ij and grouped
//!   as step 1.3 says (the next two adjacent: a pair, Eq. 23; diagonal: the 2×2 block they
//!   span, Eq. 25; else one point, Eq. 20); one step fairs every group once; stop on the
//!   energy tolerance (1.5).
//! - **Kjellander** ([`SurfaceFairingSettings::kjellander`]): uniform knots, one point per
//!   step, the interior point of largest z_ij (or of the user's list), moved to its Eq. 21
//!   point (the surface form of Kjellander's curve rule, which zeroes the jump), kept in its
//!   sphere; a point its sphere holds (target outside, point already on the border) is passed
//!   over for the next worst. The worst point comes off a priority queue whose keys are
//!   refreshed around every move, so a step costs O(window · log K), not a rescan of the grid.
//!   The energy tolerance and the judgement below apply to a sweep: as many steps as there are
//!   candidate points. The paper does not print Kjellander's surface formula; with uniform
//!   knots on a square grid `K_u[i,i] = K_v[j,j]`, so this point is also the mean of the
//!   u-curve's and the v-curve's own Kjellander points.
//!
//! **Beyond the paper** (each is one setting away from the paper's behaviour):
//!
//! - *Closed nets and poles* ([`SurfaceFairingSettings::closed`], [`GridTopology`]): a net
//!   whose last column repeats its first (or last row its first) is periodic there: the
//!   network curves across the seam are periodic splines, the seam's nodes are interior nodes
//!   faired like any other (z_ij measured across the seam), and the seam stays closed exactly
//!   (the repeat is written from its first line). A boundary line collapsed to one point (a
//!   pole) is never moved, so it stays one point; the rows next to it are free. Boundary
//!   curves that are closed curves (the rows of a net closed in v) are not faired by step 2.1.
//! - *Knots the output will have* (`refresh_knots`): the paper keeps the knots while it fairs,
//!   but a user measures the result over the knots of the result. After every step (a sweep of
//!   Kjellander steps) the knots are recomputed from the points and the next step works on
//!   them, so the run's own measure is the output's.
//! - *Refusal rules* (`guard`): a step is judged over the knots the output would have if the
//!   run stopped there. If the largest z_ij (Eq. 26) or the network strain energy (and, with
//!   the thin-plate objective, the thin-plate energy) is higher than after the last accepted
//!   step, the step is retried at 1/2, 1/4 and 1/8 of its moves (a shorter step inside the
//!   same restraining spheres); if every retry is refused too, the run ends at the last
//!   accepted state and [`SurfaceFairingResult::refusal`] says which rule refused. The
//!   boundary fairing of step 2.1 is judged the same way (undone if it makes the surface
//!   worse). Within a step a move that would raise the network energy (possible for a pair or
//!   block cut by its spheres, or for the iterated and thin-plate replacements) is not made.
//!
//! Within a step, moves go to the iso-parametric spline network (`network::Network`): the
//! tangents of u-line j and v-line i of the moved point updated by the spline's measured
//! response to a unit move, in a window of knots, and the energy by an exact O(1) formula.
//! The thin-plate option reads the twists and updates the surface after every move
//! ([`BicubicSplineSurface::move_points`]: two unit responses, O(m + n), and the tangents and
//! twists in a window round the point).
//!
//! **Cost of a step** (automatic mode, network objective, m·n points):
//!
//! - *Independent of the grid's size, per move:* the target (Eq. 21 from the two jumps at
//!   the node, O(1)), the restraining sphere, the energy change (O(1)), the update of the
//!   jumps and z bounds along the node's u-line and v-line windows, and the check that no z
//!   in those windows passes the step's cap (`Network::exceeds`): O(window), the window
//!   (~45 nodes) set by the decay of the spline's response (0.27 per knot) and its 1e-13
//!   trim, not by m or n.
//! - *O(m·n) per step, that is O(1) per point moved:* the order (z of every candidate, read
//!   in O(1) each, and a radix sort of each 64 × 64 tile's, O(m·n), `radix`, `tiles`) and the
//!   judgement: chord-length knots from the moved points, the network rebuilt over them (one
//!   spline solve per grid line, the unit responses of the two knot vectors,
//!   O((m + n) · window)), its energy and largest z, in the storage of the step before (a
//!   fresh grid-sized array is fresh pages, a fault per 4 KB). The knot refresh cannot be
//!   local: a move of P_ij changes only the averaged knot steps next to i and j, but every
//!   u-line shares the u knots, so the responses, tangents and jumps of all n + 1 u-lines
//!   change near i (O(n · window) a move, against O(window) for the move itself); one full
//!   refresh per step is the cheaper schedule. The max-z and energy rules judge the whole
//!   surface over the refreshed knots, which a local measure cannot replace either.
//! - *Per grid line, not per point (so a small grid pays more per point):* the unit
//!   responses, O((m + n) · window) per step, and once per run the boundary fairing of step
//!   2.1, the curve method on the four boundary curves to its own convergence (O(perimeter)
//!   per curve step). Both run on the spline's windowed update without allocating.
//! - *What grows with the size:* memory traffic, not work. The moves come in the order of
//!   z, scattered over the grid; once its data outgrow the processor's caches the cache lines
//!   a move touches (~50: its point and its two windows of jumps and z bounds) are misses.
//!   The network keeps the windows contiguous where it can (`network`'s "memory layout") and
//!   the sweep prefetches the move two ahead. No order of the same moves avoids the rest:
//!   each move's result depends on every earlier move whose windows cross its own, so the
//!   paper's order can be followed but not regrouped by place without changing the result.
//!   The default `tiles` order changes it (the paper's order inside 64 × 64 tiles) and keeps
//!   a tile's moves in cache.
//!
//! So the work per point moved is flat in the grid's size and the time per point nearly so,
//! the small end paying its per-line costs and the large end its cache misses. The profiles
//! and benchmarks behind this, and what was tried and not kept, are in
//! `docs/experiments/code-notes.md`.

// The building blocks index the grid directly (their callers validate it first), so they
// stay inside the crate; `SurfaceFairing` is the checked entry point.
pub(crate) mod boundary;
pub(crate) mod closed_form;
pub(crate) mod network;
pub mod precision;
mod queue;
mod radix;
mod run;
pub(crate) mod thin_plate;
mod tiles;

#[cfg(test)]
mod tests;

use std::collections::BTreeSet;
use std::time::Duration;

use curve_repr::{BicubicSplineSurface, GridTopology, NurbsSurface, Parametrization, Vec3};

use crate::strategies::Replacement;
use crate::{Error, Result, TerminationReason};

pub use closed_form::Group;

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

/// Which directions of a net are closed (periodic, the last grid line repeating the first).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Closure {
    /// Closed where the last grid line repeats the first ([`GridTopology::detect`]).
    #[default]
    Auto,
    /// Open in both directions (the paper's surfaces).
    Open,
    /// Closed in u (row m repeats row 0).
    U,
    /// Closed in v (column n repeats column 0).
    V,
    /// Closed in both.
    Both,
}

impl Closure {
    /// The topology of the flat grid under this choice (poles detected on open ends).
    pub fn topology(self, points: &[Vec3], u_count: usize, v_count: usize) -> GridTopology {
        let (u, v) = match self {
            Closure::Auto => return GridTopology::detect(points, u_count, v_count),
            Closure::Open => (false, false),
            Closure::U => (true, false),
            Closure::V => (false, true),
            Closure::Both => (true, true),
        };
        GridTopology::with_closure(points, u_count, v_count, u, v)
    }
}

/// The restraining region of a point in the automatic mode (Zhang–Cheng §4.4 step 2.2).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Region {
    /// The paper's sphere: radius |P̄_ij − P_ij|, P̄ from Eq. 21 on the starting surface.
    Sphere,
    /// The paper's radius, but never below the median of all of them: a noisy point that
    /// happens to sit where its neighbours put it is not frozen at its start (the default).
    #[default]
    MedianFloor,
}

/// The order in which the automatic mode's step visits the points (every movable interior
/// point once per step either way, Zhang–Cheng §4.4 steps 2.3–2.4). See the module docs for
/// the measurement that chose the default.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum SweepOrder {
    /// The paper's: z_ij at the step's start, sorted once per step, largest first.
    Sort,
    /// Largest *current* z_ij first, off an indexed priority queue whose keys are raised in
    /// place when a move raises them.
    Queue,
    /// The paper's order inside square tiles of 64 × 64 nodes, the tiles by their largest
    /// z_ij (the default): the moves of a tile stay in the processor's cache. The paper's
    /// order bit for bit on a net of at most 64 nodes each way.
    #[default]
    Tiles,
}

/// The rule that refused a step (see the module docs, "refusal rules").
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum RefusalRule {
    /// The largest z_ij over the output's knots would rise.
    MaxZ,
    /// The network strain energy over the output's knots would rise.
    Energy,
    /// The thin-plate energy (the thin-plate objective's own) would rise.
    ThinPlateEnergy,
}

impl RefusalRule {
    /// `max-z`, `energy` or `thin-plate-energy`.
    pub fn name(self) -> &'static str {
        match self {
            RefusalRule::MaxZ => "max-z",
            RefusalRule::Energy => "energy",
            RefusalRule::ThinPlateEnergy => "thin-plate-energy",
        }
    }
}

/// Settings of [`SurfaceFairing`]: the parameters of the catalogue's `zhang-cheng` (and,
/// with other defaults, `kjellander`). Defaults: Zhang–Cheng automatic, limit replacement,
/// network objective, chord-length knots, boundary faired, energy tolerance 1e-3, 1000 steps,
/// closures detected, restraining radii 1.5 × the paper's with the median as a floor and
/// capped at one quantisation step of digitised data, knots refreshed, steps judged.
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
    #[schemars(range(min = 0))]
    pub tolerance: f64,
    /// Step limit.
    pub max_steps: usize,
    /// Nodes that must not move.
    #[serde(skip)]
    pub fixed: BTreeSet<(usize, usize)>,
    /// No point moves farther than this from where it started.
    #[serde(skip)]
    pub max_distance: Option<f64>,
    /// Closed directions: auto (where the last grid line repeats the first), open, u, v, both.
    pub closed: Closure,
    /// Restraining region: sphere (the paper's radius |P̄ − P|) or median-floor (never below the median radius).
    pub region: Region,
    /// Scale of the automatic mode's restraining radii (1 = the paper's; inf = no regions).
    #[serde(with = "crate::catalog::value::unbounded")]
    #[schemars(with = "crate::catalog::value::BoundNumber")]
    #[schemars(extend("minimum" = 0))]
    pub radius_scale: f64,
    /// Cap on the restraining radii, in quantisation steps of digitised data when it has one (0: no cap).
    #[schemars(range(min = 0))]
    pub quantum_scale: f64,
    /// Refresh the knots from the points after every step (on, default), or keep the first (off, the paper).
    pub refresh_knots: bool,
    /// Refuse a step that raises the largest z_ij or the energy (on, default), or take every step (off, the paper).
    pub guard: bool,
    /// Automatic mode's order within a step: tiles (default: the paper's sort inside 64 × 64 tiles, the tiles by their largest z_ij; the paper's order on nets of at most 64 nodes each way), sort (the paper's: by z_ij at the step's start) or queue (largest current z_ij first).
    pub order: SweepOrder,
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
            tolerance: 1e-3,
            max_steps: 1000,
            fixed: BTreeSet::new(),
            max_distance: None,
            closed: Closure::Auto,
            region: Region::MedianFloor,
            radius_scale: 1.5,
            quantum_scale: 1.0,
            refresh_knots: true,
            guard: true,
            order: SweepOrder::Tiles,
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
        if self.quantum_scale.is_nan() || self.quantum_scale < 0.0 || self.quantum_scale.is_infinite() {
            return Err(Error::BadParameter {
                name: "quantum-scale",
                value: self.quantum_scale.to_string(),
                reason: "must be a finite non-negative number (0: no cap)",
            });
        }
        if self.radius_scale.is_nan() || self.radius_scale < 0.0 {
            return Err(Error::BadParameter {
                name: "radius-scale",
                value: self.radius_scale.to_string(),
                reason: "must be a non-negative number (inf: no restraining regions)",
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
    /// Sets the closed directions.
    pub fn with_closed(mut self, closed: Closure) -> Self {
        self.closed = closed;
        self
    }
    /// Sets the restraining region rule.
    pub fn with_region(mut self, region: Region) -> Self {
        self.region = region;
        self
    }
    /// Sets the cap on the restraining radii in quantisation steps (0: none).
    pub fn with_quantum_scale(mut self, scale: f64) -> Self {
        self.quantum_scale = scale;
        self
    }
    /// Sets the scale of the restraining radii.
    pub fn with_radius_scale(mut self, scale: f64) -> Self {
        self.radius_scale = scale;
        self
    }
    /// Refresh the knots after every step or not (the paper: not).
    pub fn with_refresh_knots(mut self, refresh: bool) -> Self {
        self.refresh_knots = refresh;
        self
    }
    /// Refuse steps that make the surface worse or not (the paper: not).
    pub fn with_guard(mut self, guard: bool) -> Self {
        self.guard = guard;
        self
    }
    /// Sets the automatic mode's order within a step.
    pub fn with_order(mut self, order: SweepOrder) -> Self {
        self.order = order;
        self
    }
    /// The paper's algorithm as printed: knots fixed for the run, no refusal rule, the
    /// paper's restraining spheres and per-step sort, closed nets treated as open (their seams
    /// and poles as boundaries). The energy tolerance is kept (the paper gives no value).
    pub fn as_printed(self) -> Self {
        self.with_refresh_knots(false)
            .with_order(SweepOrder::Sort)
            .with_guard(false)
            .with_region(Region::Sphere)
            .with_radius_scale(1.0)
            .with_quantum_scale(0.0)
            .with_closed(Closure::Open)
    }
}

/// One judged step of a run (a Kjellander sweep), for plots and comparisons.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceStep {
    /// Network strain energy after the step, over the knots the output would have if the run
    /// stopped there (the run's fixed knots when `refresh_knots` is off).
    pub energy: f64,
    /// max z_ij after the step, over the same knots.
    pub max_z: f64,
    /// Points moved in the step.
    pub moves: usize,
}

/// What [`SurfaceFairing::run`] returns.
#[derive(Clone, Debug)]
pub struct SurfaceFairingResult {
    /// The faired surface, over the knots of its points (the run's fixed knots when
    /// `refresh_knots` is off), periodic along the closed directions.
    pub surface: BicubicSplineSurface,
    /// The input points, flat (index i·(n+1) + j).
    pub original: Vec<Vec3>,
    /// Steps made (point moves for Kjellander; not counting the boundary curves' steps).
    pub steps: usize,
    /// Steps the boundary curve fairing made (automatic mode).
    pub boundary_steps: usize,
    /// Network energy and max z_ij of the input (over its own knots).
    pub start: SurfaceStep,
    /// One entry per accepted judged step (a sweep of Kjellander steps); the boundary
    /// fairing, when accepted, is the first entry.
    pub history: Vec<SurfaceStep>,
    /// The nodes whose final position differs from the input, i-major (both copies of a
    /// seam node).
    pub moved: Vec<(usize, usize)>,
    /// Restraining radii (automatic mode), flat; 0 on the boundary and at fixed nodes.
    pub radii: Option<Vec<f64>>,
    /// Why the run stopped (`StrategyDone` also when a refusal ended it, see `refusal`).
    pub termination: TerminationReason,
    /// The rule that refused the last step tried, when a refusal ended the run.
    pub refusal: Option<RefusalRule>,
    /// Steps (and retries) refused by the rules, and the boundary fairing if it was undone.
    pub refused_steps: usize,
    /// Moves not made (nor their half or quarter) because they would have raised the network
    /// energy or a z_ij above the step's largest.
    pub refused_moves: usize,
    /// Interior nodes the max-z rule pinned (kept where they were from then on), i-major,
    /// both copies of a seam node: the grid lines next to nodes whose z the knot refresh
    /// raised above the largest (module docs).
    pub pinned: Vec<(usize, usize)>,
    /// The closures and poles the run used.
    pub topology: GridTopology,
    /// The quantisation step found in the input ([`precision::quantum`]), if any: the
    /// automatic mode's radii are capped at `quantum_scale` of it, and M_d is best read
    /// against it.
    pub quantum: Option<f64>,
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

    /// Fairs the grid `grid[i][j]` = P_ij (at least 3 × 3). O(steps · m·n) plus O(window)
    /// per point move (module docs).
    ///
    /// Errors: a grid the surface cannot be built through (a closed direction whose last
    /// line does not repeat its first); a bad setting ([`Error::BadParameter`]); a fixed node
    /// outside the grid or a bad point that is not an interior node
    /// ([`Error::BadConstraint`]).
    pub fn run(&self, grid: &[Vec<Vec3>]) -> Result<SurfaceFairingResult> {
        let settings = &self.settings;
        settings.validate()?;
        let start_time = std::time::Instant::now();
        run::run(settings, grid, start_time)
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
