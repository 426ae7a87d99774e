//! How far a fairing moved the points, and how far the data say it may move them unasked.
//!
//! A user who gives no `--tolerance` has not asked for any bound, but has not asked for a
//! doubled airfoil either. [`data_bound`] derives a bound from the data alone: a robust
//! estimate of the noise normal to the curve ([`noise_estimate`]) times a factor that grows
//! with the number of points (the largest of n noise values is about σ√(2 ln n)), and never
//! less than the data's decimal quantisation step ([`decimal_quantum`]). [`largest_move`]
//! says how far the farthest point went, where, and whether that exceeds the bound, so that a
//! report can say so:
//!
//! ```
//! use curve_repr::Vec2;
//! use fairing::displacement::{data_bound, largest_move};
//!
//! let data: Vec<Vec2> = (0..50).map(|k| Vec2::new(k as f64, 0.0)).collect();
//! let mut faired = data.clone();
//! faired[20].y += 3.0;
//! let bound = data_bound(&data);
//! let largest = largest_move(&data, &faired, bound.bound).unwrap();
//! assert_eq!((largest.index, largest.distance), (20, 3.0));
//! assert!(largest.exceeds);
//! ```

use curve_repr::Vector;

use crate::{Error, Result};

/// A robust estimate of the noise σ of planar or spatial data points, measured normal to the
/// curve they sample. O(n).
///
/// r_i is the offset of P_i from the chord P_{i−1}P_{i+1} (its part normal to the chord).
/// For a smooth curve r_i ≈ κ h_{i−1} h_i / 2 varies slowly; for independent noise of σ per
/// coordinate and even spacing r_i ≈ n·(−ε_{i−1}/2 + ε_i − ε_{i+1}/2), so the difference
/// r_{i+1} − r_i cancels the smooth part to first order and carries noise of variance 5σ² in
/// each normal direction (weights ½, −³⁄₂, ³⁄₂, −½). σ is the median of |r_{i+1} − r_i|
/// divided by √5 and by the median of the norm of a unit normal deviate with D − 1
/// components (0.6745 for D = 2, 1.1774 for D = 3): the median makes a few real bumps or
/// outliers count for nothing. Sparse data with fast-changing curvature (an airfoil's nose)
/// leave some curvature in the differences, which makes the estimate larger, never smaller.
///
/// Known limit: the chord's direction must follow the curve. Where the noise is much larger
/// than the spacing (10^5 points of y = sin(x/2) + N(0, 0.01²) with x steps of 1.3e-4), the
/// chords point along the noise and the offsets normal to them are small: the estimate there
/// was 3.0e-4 for σ = 0.01, and [`data_bound`] 30 times too tight (every method's report then
/// said `exceeds`). For a function y(x) use [`vertical_noise_estimate`] (what
/// [`NoiseModel::Vertical`] selects), which has no such limit.
///
/// Returns 0 for fewer than 4 points, for D < 2, or when the points are exactly on a smooth
/// enough curve (a straight line, equally spaced points on a circle). Non-finite or repeated
/// consecutive points give a meaningless value: check them first.
pub fn noise_estimate<const D: usize>(points: &[Vector<D>]) -> f64 {
    if D < 2 || points.len() < 4 {
        return 0.0;
    }
    let offsets: Vec<Vector<D>> = points
        .windows(3)
        .map(|w| {
            let (a, b, c) = (w[0], w[1], w[2]);
            let chord = c - a;
            let length2 = chord.norm_squared();
            let d = b - a;
            if length2 > 0.0 {
                d - chord * (d.dot(&chord) / length2)
            } else {
                d
            }
        })
        .collect();
    let mut differences: Vec<f64> = offsets.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let Some(median) = median(&mut differences) else {
        return 0.0;
    };
    // Median of |N(0, 1)| (one normal direction) and of a 2-component normal's norm.
    let median_norm = match D {
        2 => 0.674_489_750_196_081_7,
        3 => 1.177_410_022_515_474_7,
        _ => {
            let k = (D - 1) as f64;
            (k * (1.0 - 2.0 / (9.0 * k)).powi(3)).sqrt()
        }
    };
    median / (5f64.sqrt() * median_norm)
}

/// Which offsets of the points measure their noise ([`noise_estimate_as`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum NoiseModel {
    /// Offsets normal to the curve ([`noise_estimate`]): parametric curves.
    #[default]
    Normal,
    /// Offsets of the last coordinate over the others ([`vertical_noise_estimate`]):
    /// functions y(x), whose methods move y only.
    Vertical,
}

/// The noise estimate of `points` read as `model` says. O(n).
pub fn noise_estimate_as<const D: usize>(points: &[Vector<D>], model: NoiseModel) -> f64 {
    match model {
        NoiseModel::Normal => noise_estimate(points),
        NoiseModel::Vertical => vertical_noise_estimate(points),
    }
}

/// A robust estimate of the noise σ in the last coordinate of points that sample a function
/// of the first (y(x) for planar points, x strictly increasing), measured vertically. O(n).
///
/// The third divided difference y[x_i, …, x_{i+3}] = Σ_j w_j y_{i+j}, w_j = 1/Π_{k≠j}(x_{i+j} −
/// x_{i+k}), is y‴(ξ)/6 for a smooth y, whatever the spacing; independent noise of σ in y gives
/// it the variance σ² Σ_j w_j². So z_i = y[x_i, …, x_{i+3}] / (Σ_j w_j²)^½ carries noise of
/// exactly σ, and a smooth part y‴ h³/√20 for even spacing h (2.8e-5 for y = sin(x/2) at
/// h = 0.1, 3e-13 at h = 1.3e-4): nothing in it depends on how the noise compares with the
/// spacing, unlike the normal offsets of [`noise_estimate`]. σ = 1.4826 · MAD(z) (the median
/// absolute deviation from the median, as jump-lsq's σ̂ reads the third differences; 1.4826
/// makes it σ for normal noise), so a few real bumps, outliers or a sharp nose count for
/// nothing.
///
/// Returns 0 for fewer than 4 points, for D < 2, or for points on a parabola (or a cubic at
/// even spacing). Points whose first
/// coordinate does not increase strictly give a meaningless value: check them first.
pub fn vertical_noise_estimate<const D: usize>(points: &[Vector<D>]) -> f64 {
    if D < 2 || points.len() < 4 {
        return 0.0;
    }
    let mut z: Vec<f64> = points
        .windows(4)
        .filter_map(|w| {
            let mut value = 0.0;
            let mut norm2 = 0.0;
            for j in 0..4 {
                let product: f64 = (0..4).filter(|&k| k != j).map(|k| w[j][0] - w[k][0]).product();
                if product == 0.0 || !product.is_finite() {
                    return None;
                }
                let weight = 1.0 / product;
                value += weight * w[j][D - 1];
                norm2 += weight * weight;
            }
            let z = value / norm2.sqrt();
            z.is_finite().then_some(z)
        })
        .collect();
    let Some(centre) = median(&mut z) else {
        return 0.0;
    };
    for v in z.iter_mut() {
        *v = (*v - centre).abs();
    }
    median(&mut z).map_or(0.0, |mad| MAD_TO_SIGMA * mad)
}

/// 1.4826 · MAD is σ for normally distributed values.
pub(crate) const MAD_TO_SIGMA: f64 = 1.482_602_218_505_602;

/// The median of `values` (reordered in place); the mean of the two middle values for an
/// even count. `None` when empty. O(n). (Also jump-lsq's σ̂.)
pub(crate) fn median(values: &mut [f64]) -> Option<f64> {
    let n = values.len();
    if n == 0 {
        return None;
    }
    let (_, &mut upper, _) = values.select_nth_unstable_by(n / 2, f64::total_cmp);
    if n % 2 == 1 {
        return Some(upper);
    }
    let lower = values[..n / 2].iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some(0.5 * (lower + upper))
}

/// The decimal step the coordinates were written with: 10^−d for the smallest d ≤ 12 such
/// that every coordinate is a multiple of 10^−d (to 1e-3 of a step, so that a decimal read
/// into binary still counts) and no coordinate but 0 rounds to 0 at that step (a value
/// written with d decimals is 0 or at least 10^−d: without this, coordinates all below 1e-3
/// passed for whole numbers); 0 when there is none (data computed, not typed). O(n · 13).
///
/// Airfoil files with five or six decimals give 1e-5 or 1e-6; whole inches give 1.
///
/// Inside a catalogue method, which runs on points moved to a reference frame (centred, scaled
/// by 2^−E), the step is read from the caller's coordinates and returned in the frame's units,
/// since the frame's coordinates keep no decimal digits.
pub fn decimal_quantum<const D: usize>(points: &[Vector<D>]) -> f64 {
    if let Some((centre, exponent)) = FRAME.with(std::cell::Cell::get) {
        let caller: Vec<Vector<D>> = points
            .iter()
            .map(|p| Vector::<D>::from_fn(|d, _| p[d] * 2f64.powi(exponent) + centre[d.min(2)]))
            .collect();
        FRAME.with(|f| f.set(None));
        let quantum = decimal_quantum(&caller);
        FRAME.with(|f| f.set(Some((centre, exponent))));
        return quantum * 2f64.powi(-exponent);
    }
    let values: Vec<f64> = points.iter().flat_map(|p| p.iter().copied()).collect();
    if values.is_empty() || values.iter().any(|v| !v.is_finite()) {
        return 0.0;
    }
    for d in 0..=12 {
        let scale = 10f64.powi(d);
        let fits = values.iter().all(|&v| {
            let scaled = v * scale;
            // Beyond 2^50 a double has no room for the fraction this test reads.
            scaled.abs() < 1.1e15
                && (scaled - scaled.round()).abs() <= 1e-3
                && (scaled.round() != 0.0 || v == 0.0)
        });
        if fits {
            return 1.0 / scale;
        }
    }
    0.0
}

thread_local! {
    /// The reference frame a catalogue method runs in on this thread (centre, exponent E of
    /// the scale 2^E), for [`decimal_quantum`]; set by the catalogue around a run.
    static FRAME: std::cell::Cell<Option<([f64; 3], i32)>> = const { std::cell::Cell::new(None) };
}

/// Marks this thread as running in a reference frame until dropped.
pub(crate) struct FrameMark(Option<([f64; 3], i32)>);

impl FrameMark {
    pub(crate) fn new(centre: [f64; 3], exponent: i32) -> FrameMark {
        FrameMark(FRAME.with(|f| f.replace(Some((centre, exponent)))))
    }
}

impl Drop for FrameMark {
    fn drop(&mut self) {
        FRAME.with(|f| f.set(self.0));
    }
}

/// A bound on point moves derived from the data alone ([`data_bound`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DataBound {
    /// The noise estimate σ ([`noise_estimate`]).
    pub noise: f64,
    /// The decimal step of the coordinates ([`decimal_quantum`]), 0 if none.
    pub quantum: f64,
    /// The bound: max(factor · σ, quantum) with factor = [`NOISE_BOUND_OFFSET`] + √(2 ln n).
    pub bound: f64,
}

/// The offset of the noise factor of [`data_bound`]: the bound is
/// (NOISE_BOUND_OFFSET + √(2 ln n)) σ, about σ√(2 ln n) for the largest of n normal noise
/// values plus this margin (5.1 σ at n = 129, 6.8 σ at n = 10^5).
pub const NOISE_BOUND_OFFSET: f64 = 2.0;

/// The bound a point's move may reach without the user having asked for it: a noise-sized
/// move, max((2 + √(2 ln n)) σ, quantum) with σ = [`noise_estimate`] and quantum =
/// [`decimal_quantum`]. A fairing that moves a point farther than this changes the data by
/// more than its measurement error. O(n).
pub fn data_bound<const D: usize>(points: &[Vector<D>]) -> DataBound {
    data_bound_as(points, NoiseModel::Normal)
}

/// [`data_bound`] with the noise read as `model` says: [`NoiseModel::Vertical`] for a
/// function y(x). O(n).
pub fn data_bound_as<const D: usize>(points: &[Vector<D>], model: NoiseModel) -> DataBound {
    let noise = noise_estimate_as(points, model);
    let quantum = decimal_quantum(points);
    let n = points.len().max(1) as f64;
    let factor = NOISE_BOUND_OFFSET + (2.0 * n.ln()).sqrt();
    DataBound {
        noise,
        quantum,
        bound: (factor * noise).max(quantum),
    }
}

/// The farthest move of a fairing ([`largest_move`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LargestMove {
    /// The point that moved farthest (the first of equals), from 0.
    pub index: usize,
    /// How far it moved (M_d).
    pub distance: f64,
    /// The bound it was compared with.
    pub bound: f64,
    /// Whether `distance` > `bound`.
    pub exceeds: bool,
}

/// The point that moved farthest from `original` to `faired`, how far, and whether that is
/// farther than `bound` (say [`DataBound::bound`] when the user gave no tolerance). O(n).
///
/// Errors: lists of different lengths or empty, a non-finite coordinate.
pub fn largest_move<const D: usize>(
    original: &[Vector<D>],
    faired: &[Vector<D>],
    bound: f64,
) -> Result<LargestMove> {
    if original.len() != faired.len() || original.is_empty() {
        return Err(curve_repr::Error::LengthMismatch {
            what: "faired points",
            expected: original.len(),
            got: faired.len(),
        }
        .into());
    }
    curve_repr::vector::check_finite(original)?;
    curve_repr::vector::check_finite(faired)?;
    if bound.is_nan() {
        return Err(Error::BadParameter {
            name: "bound",
            value: bound.to_string(),
            reason: "must be a number",
        });
    }
    let (index, distance) = original
        .iter()
        .zip(faired)
        .map(|(a, b)| (b - a).norm())
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |best, (i, d)| if d > best.1 { (i, d) } else { best },
        );
    Ok(LargestMove {
        index,
        distance,
        bound,
        exceeds: distance > bound,
    })
}

/// The largest move of a fairing against the bound the user did not ask to exceed
/// ([`unasked_move`]): what a report's `largest_move` says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnaskedMove {
    /// The farthest move and whether it exceeds [`UnaskedMove::bound`].
    pub largest: LargestMove,
    /// The bound derived from the data ([`data_bound`]).
    pub data: DataBound,
    /// The tolerance band the user gave, if any: moves up to it were asked for.
    pub tolerance: Option<f64>,
}

impl UnaskedMove {
    /// The bound compared with: the larger of the data's bound and the tolerance band.
    pub fn bound(&self) -> f64 {
        self.largest.bound
    }

    /// Whether the bound is the user's tolerance band (`tolerance`) or the data's (`data`).
    pub fn bound_from(&self) -> &'static str {
        match self.tolerance {
            Some(t) if t > self.data.bound => "tolerance",
            _ => "data",
        }
    }

    /// The report's `largest_move` object: `index` (from 0), `distance`, `bound`,
    /// `bound_from` (`data` or `tolerance`), `noise` (σ estimate), `quantum` (decimal step),
    /// `exceeds`.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "index": self.largest.index,
            "distance": self.largest.distance,
            "bound": self.largest.bound,
            "bound_from": self.bound_from(),
            "noise": self.data.noise,
            "quantum": self.data.quantum,
            "exceeds": self.largest.exceeds,
        })
    }
}

/// How far a fairing of `original` to `faired` moved its farthest point, compared with the
/// bound the user did not ask to exceed: the data's own ([`data_bound`]: a noise-sized move,
/// at least the decimal step), or the tolerance band when the user gave a wider one. A
/// method that moves a point farther has changed the data by more than its measurement
/// error without being asked; a report says so. O(n).
///
/// Errors: as [`largest_move`]; a NaN tolerance.
pub fn unasked_move<const D: usize>(
    original: &[Vector<D>],
    faired: &[Vector<D>],
    tolerance: Option<f64>,
) -> Result<UnaskedMove> {
    unasked_move_as(original, faired, tolerance, NoiseModel::Normal)
}

/// [`unasked_move`] with the data's noise read as `model` says ([`data_bound_as`]): a
/// function's report uses [`NoiseModel::Vertical`]. O(n).
///
/// Errors: as [`unasked_move`].
pub fn unasked_move_as<const D: usize>(
    original: &[Vector<D>],
    faired: &[Vector<D>],
    tolerance: Option<f64>,
    model: NoiseModel,
) -> Result<UnaskedMove> {
    let data = data_bound_as(original, model);
    let bound = match tolerance {
        Some(t) if t.is_nan() => {
            return Err(Error::BadParameter {
                name: "tolerance",
                value: t.to_string(),
                reason: "must be a number",
            })
        }
        Some(t) => data.bound.max(t),
        None => data.bound,
    };
    Ok(UnaskedMove {
        largest: largest_move(original, faired, bound)?,
        data,
        tolerance,
    })
}
