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
//!   changes by at most `tolerance` × its value in one step (2.6). The order of work
//!   ([`SweepOrder`]) is by default the paper's: z_ij at the step's start, sorted once per
//!   step (O(m·n log(m·n)), against the step's own O(m·n) moves of O(window) each). The
//!   other order, `order = queue`, takes the point of largest *current* z_ij off an indexed
//!   heap whose keys are raised in place as moves raise them (exactly the nodes a move
//!   changes are looked at; a pop is what a full rescan of the current z would choose). It
//!   was measured against the sort on the surface table's nets and lost: equal or worse
//!   largest z_ij at the end (twisted strip 0.0353 against 0.0231, noisy 100 × 100 grid 35.1
//!   against 27.9; equal on the teapot, hull and panel), and about three times the CPU per
//!   step (the heap's pops and re-keys miss the cache where the sort reads an array); on the
//!   noisy 200 × 200 grid it reaches a lower z (27.7 against 35.1, where the sort's run is
//!   stopped by the max-z rule) but takes 116 steps to converge against 16. The default,
//!   `order = tiles` (`tiles`), is the paper's sort inside 64 × 64 tiles of the grid, the
//!   tiles taken by their largest z: a move changes only its own windows, so far-apart moves
//!   do not see each other's order, and a tile's moves stay in the processor's cache where
//!   the global order scatters them over a grid that outgrew it. On a net of at most 64
//!   nodes each way it is the paper's order bit for bit (every net of the surface table but
//!   the grids); on the noisy 400 × 400 grid it ends lower than the sort on every measure
//!   (largest z 29.70 against 30.02, energy 97.02 against 97.06, RMS to the clean surface
//!   1.235e-3 against 1.236e-3, both 125 steps) in 0.59× the time, on the 200 × 200 grid
//!   at a lower energy (74.8 against 84.6) and RMS (2.12e-3 against 2.20e-3) with a largest
//!   z 1.5 % higher (35.6 against 35.1). `order = sort` is the paper's order on any net.
//!   Kjellander, which moves one point per step, takes its worst point off a lazy queue.
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
//!   in O(1) each, and a radix sort of each 64 × 64 tile's, O(m·n), `radix`, `tiles`; the comparison sort it replaced,
//!   O(m·n log(m·n)), was the only super-linear term, 7 % of the instructions of four steps
//!   at 400 × 400) and the judgement: chord-length knots from the moved points, the
//!   network rebuilt over them (one spline solve per grid line, the unit responses of the
//!   two knot vectors, O((m + n) · window)), its energy and largest z, in the storage of the
//!   step before (a fresh grid-sized array is fresh pages, a fault per 4 KB). The
//!   knot refresh cannot be local: a move of P_ij changes only the averaged knot steps next
//!   to i and j, but every u-line shares the u knots, so the responses, tangents and jumps
//!   of all n + 1 u-lines change near i (O(n · window) a move, against O(window) for the
//!   move itself); one full refresh per step is the cheaper schedule. The max-z and energy
//!   rules judge the whole surface over the refreshed knots, which a local measure cannot
//!   replace either.
//! - *Per grid line, not per point (so a small grid pays more per point):* the unit
//!   responses, O((m + n) · window) per step (they were O(m² + n²), quadratic on a long
//!   strip: a 10 × 20 000 strip's two steps took 10.1 s, now 0.86 s), and once per run the
//!   boundary fairing of step 2.1, the curve method on the four boundary curves to its own
//!   convergence (O(perimeter) per curve step, some 540 steps at 50 × 50). In the
//!   `surface_step` bench (4 steps, the whole run) at 50 × 50 the boundary fairing was 28 %
//!   of the instructions (callgrind) and the unit responses 13 %; at 400 × 400, 3.3 % and
//!   3.6 %. Per point moved that was 3 200 and 1 500 instructions at 50 × 50 against 260 and
//!   280 at 400 × 400, while the rest cost 6 600 against 7 400: these two terms were the
//!   whole difference in instructions between the sizes. Both now run on the spline's
//!   windowed update without allocating (its storage kept by the spline, one chord slope per
//!   row), and the curve method refreshes only the rows the update re-solved, computes each
//!   segment's C‴ once and pushes a z onto its heap only when it changed (same results bit
//!   for bit): at 50 × 50 the boundary fairing is 20 % of the instructions (1 840 per point
//!   moved) and the unit responses 12 % (1 140), the rest 6 350: 373 M instructions for
//!   four such runs against 451 M. Since then the unit responses no longer move the line
//!   back (the spline's trial move, `HermiteSpline::unit_move_tangents`, builds a unit
//!   move's window rows from the knots), the windowed solves build their rows in one loop
//!   that carries the knot step and chord slope, the window's decay bounds are measured
//!   once per knot vector, and an open net's input surface is built once (same results bit
//!   for bit): per point moved as above (callgrind, 4 steps), 8 560 instructions at
//!   50 × 50 (the boundary fairing 1 620, the unit responses 900, the rest 6 030) against
//!   9 370, 7 210 at 200 × 200 against 7 750, 7 100 at 400 × 400 against 7 510. The small
//!   end still executed 1.19× the instructions per point of 200 × 200 (1.21× before): the
//!   cuts in the rows and the surface build are cuts at every size.
//!
//!   The next round measured with `examples/surface_cost.rs` (the bench's `tiles` run: 4
//!   steps and the boundary fairing, on its noisy net), callgrind collecting inside
//!   `SurfaceFairing::run` only, instructions / (4 · N²). Before: 8 450 / 7 610 / 7 030 per
//!   point moved at 50² / 100² / 200² (the boundary fairing 1 610 / 770 / 290, the unit
//!   responses 905 / 560 / 307); after: 7 300 / 6 970 / 6 680 (the boundary fairing
//!   1 000 / 480 / 181, the unit responses 696 / 428 / 234), so 50 × 50 executes 1.09× the
//!   instructions per point of 200 × 200 (1.20× before); at 400² 6 620 after, ~6 860
//!   before (cachegrind's count of the whole program less the net's construction), and the
//!   D1 misses of the whole 400² program 81.5 M against 82.1 M. A boundary curve step (544 of them
//!   at 50 × 50, 1 698 at 400 × 400) cost ~29 500 instructions, now ~18 400. It was no
//!   O(n) work: the update window (~30 knots each side of the move, to the 1e-17 of
//!   `hermite::update`) covers most of a 50-point boundary, and the cost was per row. The
//!   worst point now comes off a tournament tree replayed over the refreshed rows (the lazy
//!   heap took a push per changed z, every z of the window, and skipped stale entries at
//!   every pop), each segment's chord slope serves its energy and its C‴, the spline keeps
//!   the rows of its tangent system between moves (a move of P_j changes rows j − 1..j + 1
//!   only; the window's other rows are copied, not rebuilt), and a step allocates nothing.
//!   The unit responses read the re-solved rows directly (no copy of the whole line) and
//!   take the rows' weights once per knot vector; every grid line's tangents are solved in
//!   one spline's storage (`HermiteSpline::refit`: a dozen allocations and a check of the
//!   knots fewer per line). The same results bit for bit (the faired nets at 50², 100²,
//!   200², 400² compared as bits, and the curve method alone on curves of 50–3 000 points:
//!   one point, pairs, interactive). What the small end still pays: the boundary fairing's
//!   ~18 400 instructions per curve step are the refresh of the window's segment energies,
//!   C‴ and z (~9 200, ~2 000 of it the tree) and the windowed solve (~7 200), arithmetic
//!   per row that the same bits need; a unit response ~11 600 per node, ~5 300 of it the
//!   solve of the unit move. Tried without a gain: refreshing only the rows whose tangents
//!   changed bit for bit (few fewer, and the comparison cost more), a tree keyed by the
//!   bits of z, one array for all of a line's responses (slower moves at every size).
//!   Criterion after that round (`surface_step/{tiles,tiles_steps}`, one round on a quiet
//!   machine, 2026-12-03, medians in M points moved/s at 50² / 100² / 200² / 400²): `tiles`
//!   0.77 / 0.93 / 0.91 / 0.66 (before it, the same morning: 0.51 / 0.71 / 0.74 / 0.66),
//!   `tiles_steps` 0.97 / 0.95 / 0.90 / 0.65. The small end is now 1.21× the time per point of the
//!   fastest size (1.45× before); the large end 1.42×: 400 × 400 executes the fewest instructions
//!   per point of all four and is the slowest, its step's whole-grid passes (the knot
//!   refresh and rebuilt network, the order, the energy and largest z) and its moves
//!   running from L3 and memory. Tried, not adopted: tiles of 32 × 32 nodes (three rounds:
//!   400² 0.70–0.74 against 0.66, but 100² 0.73–0.85 with the same code, the machine's
//!   noise as large as the effect; it would change the result on nets of 33–64 nodes a side,
//!   which now get the paper's order).
//!
//!   The round after it cut the step's whole-grid passes, which at 400² stream from memory
//!   (the same results bit for bit: `surface_cost SIZE dump` with and without `steps` at
//!   50²–400², its `curve` mode, and its `net` mode on both teapot nets and the PX121 hull,
//!   whose runs pin lines and retry steps). Each tile's candidates are sorted on their own
//!   while in cache and the sweep takes the tiles' runs in order (the whole grid's radix
//!   sort and regrouping were ~10 passes over 16 bytes a node); z for the order and the
//!   largest z come from the rebuild's exact z bounds (one contiguous array; the largest
//!   kept until a move, so the step's cap and the measure are O(1)); a rebuild takes each
//!   line's energy terms and jumps right after its solve (three passes fewer; the energy's
//!   running sum in its old order) and stores no tangents that the run never reads (limit
//!   replacement); the accepted state's jump norms are built only when the max-z rule
//!   pins; the judged and accepted points change hands by exchanging storage, not by
//!   copies. Cachegrind (`--cache-sim=yes`, D1 48 KB 12-way, LL 2 MB 16-way: this
//!   machine's L1 and L2; callgrind inside `SurfaceFairing::run`, per point moved, 4 · N²),
//!   at 50² / 100² / 200² / 400²: instructions 7 309 / 6 962 / 6 674 / 6 617 before,
//!   7 123 / 6 695 / 6 390 / 6 388 after; D1 misses 71.8 / 94.1 / 110.4 / 127.1 before,
//!   61.7 / 82.5 / 102.8 / 114.8 after; LL misses 0.0 / 7.2 / 21.3 / 35.3 before,
//!   0.0 / 4.3 / 11.4 / 18.7 after. Of the 400² LL misses left (12.0 M), the four
//!   rebuilds are ~3.5 M, the moves 1.6 M, and the rest is once per run: the data's
//!   precision 1.65 M (it sorts every coordinate), the input's and the result's bicubic
//!   surfaces ~1 M each, the first network ~1.3 M. Tried, not kept: the precision's sorts
//!   by the radix sort (231 M instructions at 400² against 202 M: the coordinates' keys
//!   share few digits, so all eight passes run).
//! - *What grows with the size:* memory traffic, not work. The moves come in the order of
//!   z, scattered over the grid; once its data outgrow the processor's caches the cache lines
//!   a move touches (~50: its point and its two windows of jumps and z bounds) are misses.
//!   The network keeps the windows contiguous where it can (`network`'s "memory layout") and
//!   the sweep prefetches the move two ahead (prefetching the move's whole windows as well
//!   measured slower: 1.29–1.39 against 1.49–1.54 M points/s of CPU time at 400 × 400). No
//!   order of the same moves avoids the rest: each move's result depends on every earlier
//!   move whose windows cross its own, so the paper's order can be followed but not
//!   regrouped by place without changing the result. The default `tiles` order changes it
//!   (the paper's order inside 64 × 64 tiles, `tiles`) and keeps a tile's moves in cache. How much this costs depends on the machine: the earlier notes
//!   measured the time per point at 400 × 400 at 1.32× that at 100 × 100; on the machine of
//!   the numbers below (2 MB of L2 per core, 32 MB of L3) it was within 5 % of it, and is
//!   1.11–1.13× now that the work per move is smaller.
//! - *Measured* (2 shared cores, AMD EPYC with 2 MB L2 per core and 32 MB L3, load 2–3
//!   from other work; the build before this change run alternately with it): `cargo bench
//!   -p fairing --bench fairing -- surface_step/sort`, three rounds each, criterion's
//!   medians 1.08–1.22 / 1.33–1.48 / 1.58–1.69 / 1.17–1.47 M points/s at 50² / 100² /
//!   200² / 400² before, 1.45–1.52 / 1.64–1.85 / 1.77–1.92 / 1.52–1.69 after (slowest to
//!   fastest size 1.39–1.46× before, 1.20–1.26× after; 1.23× on the medians of the three
//!   rounds, 1.48 against 1.83); on the process's CPU time over the same 4-step runs in a
//!   loop (medians of five rounds) before 1.18 / 1.46 / 1.56 / 1.42, after 1.47 / 1.71 /
//!   1.73 / 1.52 (1.18× from 50² to 200²); the same points, energies and counts bit for
//!   bit. Nearly flat, the small end still the slowest by the per-line and per-run costs
//!   above. The `sort_steps` entry (the four steps without the boundary fairing, a
//!   different run) shows the steps alone: 2.33 / 2.28 / 2.18 / 1.57 M points/s (medians of
//!   three rounds), the largest grid paying its cache misses. After the cuts of the
//!   per-line costs named above (the same points bit for bit), on the same machine at load
//!   2–5, five rounds alternating with the build before: 0.65–0.89 / 0.88–1.08 /
//!   0.63–0.92 / 0.53–0.80 M points/s (before 0.48–0.83 / 0.59–0.87 / 0.57–0.97 /
//!   0.45–0.65): slowest to fastest size 1.20–1.85× per round, 1.29× on the rounds'
//!   medians (1.45× before), the slowest now 400 × 400 in four rounds of five. So the time
//!   per point is not within 1.2× reliably: under load the large grid's cache misses (the
//!   caches shared with other processes), not the small grid's per-line costs, set the
//!   spread.
//! - *Where the large grid's time goes* (cachegrind, 4 MiB L2 simulated as the last level,
//!   `sort_steps`): the instructions per point are flat (6 440 / 6 410 / 6 360 / 6 380 at
//!   50² / 100² / 200² / 400² with the radix sort, 6 490–6 550 before), the L2 data misses
//!   per point are not (~0 / 2 / 13 / 56), half of them in the moves' updates of the
//!   windows of the jumps (48 B per node in two arrays of 3.8 MB at 400 × 400, against
//!   4 MiB of L2). On a quiet machine of that L2 size 400 × 400 is the slowest size by
//!   1.38–1.70× per point.
//!   What was tried without a gain: prefetching a move's whole windows one or two moves
//!   ahead, and transparent huge pages for the per-node arrays (`madvise`; glibc's
//!   `glibc.malloc.hugetlb=1` tunable, which covers them fully, looked ~10 % faster at
//!   400 × 400 in CPU time, not separable from the load of 7–10 it was measured at).

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
pub enum Refusal {
    /// The largest z_ij over the output's knots would rise.
    MaxZ,
    /// The network strain energy over the output's knots would rise.
    Energy,
    /// The thin-plate energy (the thin-plate objective's own) would rise.
    ThinPlateEnergy,
}

impl Refusal {
    /// `max-z`, `energy` or `thin-plate-energy`.
    pub fn name(self) -> &'static str {
        match self {
            Refusal::MaxZ => "max-z",
            Refusal::Energy => "energy",
            Refusal::ThinPlateEnergy => "thin-plate-energy",
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
    pub radius_scale: f64,
    /// Cap on the restraining radii, in quantisation steps of digitised data when it has one (0: no cap).
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
    pub refusal: Option<Refusal>,
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
