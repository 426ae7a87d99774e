//! Sign-change counting: inflections and vibrations.
//!
//! Every count follows docs/CONTRACT.md's definition, so that our numbers agree with any
//! independent implementation: the values with |v_i| ≤ 10⁻¹² · max_j |v_j| (over the same
//! sequence) are dropped first, then the sign changes #{k : w_k w_{k+1} < 0} are counted along
//! the remaining values w. So `a, 0, −a` is one change, round-off (a natural spline's end
//! curvature) makes none, and a value driven exactly to zero hides none.
//!
//! "w_k w_{k+1} < 0" is read as the mathematics means it, opposite signs
//! ([`opposite_signs`]), not as a floating-point product: the product of two values below
//! ~1e-162 in magnitude underflows to 0 and would hide the change (a curve measured in
//! units of 1e150 has c values of 1e-150).

use curve_repr::Vec3;

/// Relative size, against the largest magnitude in the sequence, at or below which a value
/// is dropped before sign changes are counted.
pub const DROP_RELATIVE: f64 = 1e-12;

/// The values kept by the drop rule, with their indices in `values`.
///
/// Non-finite values are dropped too (and do not enter the maximum): they carry no sign that
/// a count could trust. The indicators of this crate never produce them.
fn kept(values: &[f64]) -> impl Iterator<Item = (usize, f64)> + '_ {
    let max = values
        .iter()
        .filter(|v| v.is_finite())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let threshold = DROP_RELATIVE * max;
    values
        .iter()
        .copied()
        .enumerate()
        .filter(move |(_, v)| v.is_finite() && v.abs() > threshold)
}

/// Whether a and b are non-zero with opposite signs: a·b < 0 in exact arithmetic, without
/// the product (which underflows for tiny values and overflows for huge ones). NaN has no
/// sign here. O(1).
///
/// ```
/// use fairness::sign::opposite_signs;
/// assert!(opposite_signs(1e-200, -1e-200)); // 1e-200 · (−1e-200) underflows to −0
/// assert!(!opposite_signs(0.0, -1.0));
/// assert!(!opposite_signs(2.0, 3.0));
/// ```
#[inline]
pub fn opposite_signs(a: f64, b: f64) -> bool {
    // Non-short-circuit operators: branch-free, as noisy signs defeat the branch predictor.
    ((a < 0.0) & (b > 0.0)) | ((a > 0.0) & (b < 0.0))
}

/// Whether a and b are non-zero with the same sign: a·b > 0 in exact arithmetic (see
/// [`opposite_signs`]). O(1).
#[inline]
pub fn same_signs(a: f64, b: f64) -> bool {
    ((a > 0.0) & (b > 0.0)) | ((a < 0.0) & (b < 0.0))
}

/// The number of sign changes of `values` after the drop rule. O(n).
///
/// ```
/// use fairness::sign::sign_changes;
/// assert_eq!(sign_changes(&[1.0, 0.0, -1.0]), 1);
/// assert_eq!(sign_changes(&[0.0, 0.0]), 0);
/// assert_eq!(sign_changes(&[1e-20, 1.0, -1e-20, 2.0]), 0);
/// ```
pub fn sign_changes(values: &[f64]) -> usize {
    sign_change_positions(values).len()
}

/// Where the sign changes: pairs `(k, l)` of indices into `values`, `k < l`, of consecutive
/// kept values with opposite signs (indices between them hold dropped values). O(n).
pub fn sign_change_positions(values: &[f64]) -> Vec<(usize, usize)> {
    let mut changes = Vec::new();
    let mut previous: Option<(usize, f64)> = None;
    for (index, value) in kept(values) {
        if let Some((previous_index, previous_value)) = previous {
            if opposite_signs(previous_value, value) {
                changes.push((previous_index, index));
            }
        }
        previous = Some((index, value));
    }
    changes
}

/// Spatial inflections: the number of flips of the binormal direction, #{i : b_i · b_{i+1} < 0}
/// with b = C′ × C″, after dropping the vectors with |b_i| ≤ 10⁻¹² · max_j |b_j|.
///
/// This is the `inflections` count of the 3D data set of `parametric_metrics.json` (the report
/// of the `fair` command leaves 3D inflections null). O(n).
pub fn binormal_flips(binormals: &[Vec3]) -> usize {
    // Each b as (|b|, b / |b|), scaled by its largest component first so that neither the
    // norm nor the dot product of tiny (or huge) binormals under- or overflows.
    let unit = |b: &Vec3| -> Option<(f64, Vec3)> {
        let scale = b.amax();
        if !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        let scaled = b / scale;
        let norm = scaled.norm();
        Some((scale * norm, scaled / norm))
    };
    let units: Vec<Option<(f64, Vec3)>> = binormals.iter().map(unit).collect();
    let max = units
        .iter()
        .flatten()
        .map(|(norm, _)| *norm)
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let threshold = DROP_RELATIVE * max;
    let mut count = 0;
    let mut previous: Option<Vec3> = None;
    for (norm, direction) in units.into_iter().flatten() {
        if !(norm.is_finite() && norm > threshold) {
            continue;
        }
        if let Some(p) = previous {
            if p.dot(&direction) < 0.0 {
                count += 1;
            }
        }
        previous = Some(direction);
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn zero_between_opposite_values_is_one_change() {
        assert_eq!(sign_changes(&[2.0, 0.0, -2.0]), 1);
        assert_eq!(sign_change_positions(&[2.0, 0.0, -2.0]), vec![(0, 2)]);
    }

    #[test]
    fn all_zeros_and_empty_have_none() {
        assert_eq!(sign_changes(&[0.0; 5]), 0);
        assert_eq!(sign_changes(&[]), 0);
        assert_eq!(sign_changes(&[-3.0]), 0);
    }

    #[test]
    fn round_off_is_dropped_but_small_real_values_are_not() {
        // End curvatures of a natural spline: round-off around zero.
        assert_eq!(sign_changes(&[3e-17, 1.0, 2.0, 1.5, -4e-17]), 0);
        // Exactly at the threshold: dropped (≤); just above: kept.
        assert_eq!(sign_changes(&[1.0, -1e-12, 1.0]), 0);
        assert_eq!(sign_changes(&[1.0, -2e-12, 1.0]), 2);
    }

    #[test]
    fn touching_zero_without_crossing_is_no_change() {
        assert_eq!(sign_changes(&[1.0, 0.0, 1.0, -1.0, 0.0, 0.0, -1.0]), 1);
        assert_eq!(sign_change_positions(&[1.0, 0.0, 1.0, -1.0]), vec![(2, 3)]);
    }

    #[test]
    fn non_finite_values_are_skipped() {
        assert_eq!(sign_changes(&[1.0, f64::NAN, -1.0]), 1);
        assert_eq!(sign_changes(&[1.0, f64::INFINITY, -1.0, 1.0]), 2);
    }

    #[test]
    fn binormal_flips_count_opposite_directions() {
        let up = Vec3::new(0.0, 0.0, 1.0);
        let tilted = Vec3::new(1.0, 0.0, 0.5);
        let down = -up;
        let tiny = Vec3::new(0.0, 0.0, -1e-14);
        assert_eq!(binormal_flips(&[up, tilted, tiny, down, down, up]), 2);
        assert_eq!(binormal_flips(&[Vec3::zeros(); 3]), 0);
    }

    #[test]
    fn counts_do_not_depend_on_the_scale() {
        // The products (and dot products) of these values under- or overflow; the signs do not.
        let pattern = [1.0, -2.0, 0.5, 3.0, -1.0, 0.0, -4.0, 2.0];
        let up = Vec3::new(0.0, 0.2, 1.0);
        let vectors = [up, up, -up, Vec3::new(1.0, 0.0, 0.1), -up, up];
        let expected = (sign_changes(&pattern), binormal_flips(&vectors));
        assert_eq!(expected, (4, 4));
        for scale in [1e-300, 1e-170, 1e-150, 1e150, 1e170, 1e300] {
            let values: Vec<f64> = pattern.iter().map(|v| v * scale).collect();
            let scaled: Vec<Vec3> = vectors.iter().map(|v| v * scale).collect();
            assert_eq!(
                (sign_changes(&values), binormal_flips(&scaled)),
                expected,
                "scale {scale}"
            );
        }
        assert!(opposite_signs(1e-200, -1e-200) && same_signs(-1e-200, -1e-300));
        assert!(!opposite_signs(f64::NAN, 1.0) && !same_signs(f64::NAN, 1.0));
    }

    proptest! {
        /// Without zeros, the count equals the direct count on the raw sequence.
        #[test]
        fn equals_direct_count_without_small_values(
            signs in proptest::collection::vec(any::<bool>(), 0..50),
            magnitudes in proptest::collection::vec(1.0..10.0_f64, 50),
        ) {
            let values: Vec<f64> = signs.iter().zip(&magnitudes)
                .map(|(s, m)| if *s { *m } else { -*m }).collect();
            let direct = values.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
            prop_assert_eq!(sign_changes(&values), direct);
        }
    }
}
