//! `function-ends` = `auto`: each end condition of a function's spline chosen from the data
//! by generalised cross-validation.
//!
//! The end condition is a model choice like λ: the runout spline (s‴ = 0 on the end span)
//! leaves the end curvature free, the natural spline (s″ = 0 at the end) holds it at zero,
//! which is exact where the data's curve has no curvature at its end and a bias where it has.
//! Each pair of conditions spans its own n-dimensional space of interpolating splines, and
//! GCV's score V(λ) = (RSS/n) / (1 − γ tr A(λ)/n)² compares fits on the same data, so the pair
//! whose GCV search ends lowest is kept (ties to the earlier, runout first).
//!
//! Up to 2 · [`END_WINDOW`] points the four pairs are fitted to the whole function (four
//! GCV searches of O(n) each; the winner's search is the fit's own under the GCV rule).
//! Beyond, a condition changes the fit only near its own end, so each end is chosen on its
//! end window of [`END_WINDOW`] points alone (the window's cut side runout), between runout
//! and natural at that end: O(1) work besides the fit's own search, which a run of 10^6
//! points would otherwise pay four times over.

use curve_repr::Vector;

use super::basis::Knots;
use super::lambda::{self, Choice};
use super::system::{Constraint, End, Ends, Penalty, Space, System};

/// Points per end window: a function of more than twice as many points chooses each end's
/// condition on its own end window.
pub(crate) const END_WINDOW: usize = 1000;

/// What [`choose`] chose.
pub(crate) struct EndChoice<const D: usize> {
    /// The conditions at the start and at the end.
    pub ends: Ends,
    /// The winner's GCV search on the whole function (not with end windows).
    pub choice: Option<Choice<D>>,
    /// Solves made by all searches.
    pub solves: usize,
}

/// The pair of end conditions of least GCV for the function `data` (its smoothed coordinates,
/// x masked out) on `knots` (its x), the `frozen` points kept at their data; `penalty` and
/// GCV's trace factor `gamma` as the fit's own, `coordinates` the smoothed ones. `None` when
/// no pair could be fitted (the fit's own solve then reports why). O(n) up to
/// 2 · [`END_WINDOW`] points, O([`END_WINDOW`]) beyond.
pub(crate) fn choose<const D: usize>(
    knots: &Knots,
    data: &[Vector<D>],
    frozen: &[bool],
    penalty: Penalty,
    coordinates: usize,
    gamma: f64,
) -> Option<EndChoice<D>> {
    let n = data.len();
    let mut solves = 0;
    if n <= 2 * END_WINDOW {
        let pairs = [
            Ends::RUNOUT,
            Ends::Open(End::Natural, End::Runout),
            Ends::Open(End::Runout, End::Natural),
            Ends::NATURAL,
        ];
        let (ends, choice) = least_gcv(
            knots.values(),
            data,
            frozen,
            &pairs,
            penalty,
            coordinates,
            gamma,
            &mut solves,
        )?;
        return Some(EndChoice {
            ends,
            choice: Some(choice),
            solves,
        });
    }
    let t = knots.values();
    let w = END_WINDOW;
    let start = least_gcv(
        &t[..w],
        &data[..w],
        &frozen[..w],
        &[Ends::RUNOUT, Ends::Open(End::Natural, End::Runout)],
        penalty,
        coordinates,
        gamma,
        &mut solves,
    )?
    .0;
    let end = least_gcv(
        &t[n - w..],
        &data[n - w..],
        &frozen[n - w..],
        &[Ends::RUNOUT, Ends::Open(End::Runout, End::Natural)],
        penalty,
        coordinates,
        gamma,
        &mut solves,
    )?
    .0;
    let (Ends::Open(start, _), Ends::Open(_, end)) = (start, end) else {
        return None;
    };
    Some(EndChoice {
        ends: Ends::Open(start, end),
        choice: None,
        solves,
    })
}

/// Of `pairs`, the one whose GCV search on `data` over the knots `t` ends lowest, with its
/// search (its `evaluations` zeroed: they are counted in `solves`). O(n) per pair.
#[allow(clippy::too_many_arguments)]
fn least_gcv<const D: usize>(
    t: &[f64],
    data: &[Vector<D>],
    frozen: &[bool],
    pairs: &[Ends],
    penalty: Penalty,
    coordinates: usize,
    gamma: f64,
    solves: &mut usize,
) -> Option<(Ends, Choice<D>)> {
    let ones = vec![1.0; data.len()];
    let mut best: Option<(f64, Ends, Choice<D>)> = None;
    for &pair in pairs {
        let Ok(space) = Space::new(Knots::open(t.to_vec()), pair, penalty) else {
            continue;
        };
        if space.penalty_rows() == 0 {
            return None;
        }
        let base: Vec<Constraint<D>> = (0..data.len())
            .filter(|&i| frozen[i])
            .map(|i| Constraint {
                form: space.value_form(i),
                target: data[i],
                point: Some(i),
            })
            .collect();
        let system = System::new(&space, data, &ones, &base);
        let lambda_max = lambda::STIFFNESS_LIMIT / system.stiffness().max(f64::MIN_POSITIVE);
        let Ok(mut choice) = lambda::gcv(&system, coordinates, gamma, lambda_max) else {
            continue;
        };
        *solves += choice.evaluations;
        choice.evaluations = 0;
        let score = choice.gcv.unwrap_or(f64::INFINITY);
        if best.as_ref().is_none_or(|b| score < b.0) {
            best = Some((score, pair, choice));
        }
    }
    best.map(|(_, pair, choice)| (pair, choice))
}
