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
//! The four pairs are fitted to the whole function: four GCV searches of O(n) each, the
//! winner's search the fit's own under the GCV rule. Beyond [`AUTO_MAX`] points the runout
//! pair is kept without a search: on dense data the pairs' minima lie within GCV's noise,
//! and a natural end where the curve has an inflection holds the fit's curvature at zero
//! there, so that noise turns its sign near the end (2·10^4 noisy points of sin(x/2) over
//! [0, 4π], the dense test of two-phase's tests: 7 inflections where the clean curve has 1 or 2,
//! with each end chosen on its own window of 1000 points). Four searches there would also
//! make two-phase 2.4× slower at 10^5 points and 3.7× at 10^6.

use curve_repr::Vector;

use super::basis::Knots;
use super::lambda::{self, Choice};
use super::system::{Constraint, End, Ends, Penalty, Space, System};

/// The most points for which the ends are chosen; beyond, the runout pair.
pub(crate) const AUTO_MAX: usize = 2000;

/// What [`choose`] chose.
pub(crate) struct EndChoice<const D: usize> {
    /// The conditions at the start and at the end.
    pub ends: Ends,
    /// The winner's GCV search (none beyond [`AUTO_MAX`] points).
    pub choice: Option<Choice<D>>,
    /// Solves made by all searches.
    pub solves: usize,
}

/// The pair of end conditions of least GCV for the function `data` (its smoothed coordinates,
/// x masked out) on `knots` (its x), the `frozen` points kept at their data; `penalty` and
/// GCV's trace factor `gamma` as the fit's own, `coordinates` the smoothed ones. Beyond
/// [`AUTO_MAX`] points the runout pair, unsearched. `None` when no pair could be fitted (the
/// fit's own solve then reports why). O(n).
pub(crate) fn choose<const D: usize>(
    knots: &Knots,
    data: &[Vector<D>],
    frozen: &[bool],
    penalty: Penalty,
    coordinates: usize,
    gamma: f64,
) -> Option<EndChoice<D>> {
    if data.len() > AUTO_MAX {
        return Some(EndChoice {
            ends: Ends::RUNOUT,
            choice: None,
            solves: 0,
        });
    }
    let ones = vec![1.0; data.len()];
    let mut solves = 0;
    let mut best: Option<(f64, Ends, Choice<D>)> = None;
    for pair in [
        Ends::RUNOUT,
        Ends::Open(End::Natural, End::Runout),
        Ends::Open(End::Runout, End::Natural),
        Ends::NATURAL,
    ] {
        let Ok(space) = Space::new(knots.clone(), pair, penalty) else {
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
        let Ok(mut choice) = lambda::gcv(&system, coordinates, gamma, lambda_max, None) else {
            continue;
        };
        // Counted here; the fit that reuses the winner's search adds none.
        solves += choice.evaluations;
        choice.evaluations = 0;
        let score = choice.gcv.unwrap_or(f64::INFINITY);
        if best.as_ref().is_none_or(|b| score < b.0) {
            best = Some((score, pair, choice));
        }
    }
    best.map(|(_, ends, choice)| EndChoice {
        ends,
        choice: Some(choice),
        solves,
    })
}
