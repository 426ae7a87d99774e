//! The noise level σ̂ of the points, estimated from the points themselves.
//!
//! For each coordinate, the third differences over the point index
//! Δ³v_i = v_{i+3} − 3v_{i+2} + 3v_{i+1} − v_i remove any quadratic trend; white noise of
//! standard deviation σ gives them the variance (1 + 9 + 9 + 1)σ² = 20σ². Their robust
//! scale, 1.4826 times the median absolute deviation from their median (MAD; 1.4826 makes it
//! σ for a normal distribution), ignores the few large differences where the curve itself
//! bends sharply. So σ̂_c = 1.4826 · MAD(Δ³v) / √20 per coordinate c, and the points' noise is
//! σ̂ = (Σ_c σ̂_c²)^½, the expected length of a point's noise vector (the recipe measured in
//! the issue that asked for this method). Closed curves difference across the closing gap.
//!
//! O(n) time (medians by selection), O(n) memory.

use curve_repr::Vector;

use crate::displacement::{median, MAD_TO_SIGMA};

/// σ̂ of one sequence of values (module docs). 0 for fewer than 4 values (no third
/// difference) unless closed with at least 4.
pub(crate) fn coordinate_noise(values: &[f64], closed: bool) -> f64 {
    let n = values.len();
    if n < 4 {
        return 0.0;
    }
    let at = |i: usize| values[i % n];
    let count = if closed { n } else { n - 3 };
    let mut diffs: Vec<f64> = (0..count)
        .map(|i| at(i + 3) - 3.0 * at(i + 2) + 3.0 * at(i + 1) - at(i))
        .collect();
    let Some(centre) = median(&mut diffs) else {
        return 0.0;
    };
    for d in diffs.iter_mut() {
        *d = (*d - centre).abs();
    }
    median(&mut diffs).map_or(0.0, |mad| MAD_TO_SIGMA * mad / 20f64.sqrt())
}

/// σ̂ of the points over the coordinates marked in `smoothed` (module docs).
pub(crate) fn noise<const D: usize>(points: &[Vector<D>], smoothed: [bool; D], closed: bool) -> f64 {
    let mut sum = 0.0;
    let mut column = Vec::with_capacity(points.len());
    for (c, _) in smoothed.iter().enumerate().filter(|(_, s)| **s) {
        column.clear();
        column.extend(points.iter().map(|p| p[c]));
        let s = coordinate_noise(&column, closed);
        sum += s * s;
    }
    sum.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&mut []), None);
    }

    #[test]
    fn recovers_the_noise_of_a_smooth_curve_and_ignores_a_cubic_trend() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let normal = Normal::new(0.0, 0.01).unwrap();
        let n = 20_000;
        let values: Vec<f64> = (0..n)
            .map(|i| {
                let x = i as f64 / n as f64;
                (6.0 * x).sin() + normal.sample(&mut rng)
            })
            .collect();
        let s = coordinate_noise(&values, false);
        assert!((s / 0.01 - 1.0).abs() < 0.03, "σ̂ = {s}");
        // A cubic has constant third differences: no noise.
        let cubic: Vec<f64> = (0..50).map(|i| (i as f64).powi(3) * 0.01 - i as f64).collect();
        assert!(coordinate_noise(&cubic, false) < 1e-12);
        // Two coordinates with noise 0.01 each: σ̂ ≈ 0.01·√2.
        let points: Vec<Vector<2>> = values
            .iter()
            .zip(values.iter().rev())
            .map(|(a, b)| Vector::<2>::new(*a, *b))
            .collect();
        let both = noise(&points, [true, true], false);
        assert!((both / (0.01 * 2f64.sqrt()) - 1.0).abs() < 0.03, "σ̂ = {both}");
        assert!((noise(&points, [false, true], false) / 0.01 - 1.0).abs() < 0.03);
        assert_eq!(coordinate_noise(&[1.0, 2.0, 4.0], false), 0.0);
    }
}
