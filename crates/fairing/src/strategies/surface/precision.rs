//! The data's own precision: the quantisation step of a digitised net.
//!
//! Offsets read off a drawing or an image are integer multiples of a step (the PX121 hull's
//! half-breadths are multiples of 1/1140 of the half-beam: one pixel). Moving such points by
//! many steps is reshaping the design, not fairing it, so the automatic mode caps its
//! restraining radii at a multiple of the step when it finds one
//! ([`SurfaceFairingSettings::quantum_scale`](super::SurfaceFairingSettings::quantum_scale)).
//!
//! A coordinate axis is *quantised* at q when every value of it is an integer multiple of q
//! (to 1e-3 q: digitised values are printed with a few decimals), and q is a *measurement* step, not the grid's sampling: q is at most a tenth
//! of the median change of that coordinate between grid neighbours and at least 1e-4 of its
//! range (a finer lattice is the number format's, e.g. values printed with three decimals;
//! the sampling coordinates of a table, stations 8.2 m apart, are multiples of their spacing
//! and are left out). The candidates are the smallest gap between distinct values divided by
//! 1 … 8; the largest that fits is the axis's step. The data's precision is the largest step
//! of its quantised axes. O(m·n log(m·n)) (a sort of each axis's values).

use curve_repr::Vec3;

/// The quantisation step of the flat grid `points[i·v_count + j]` (module docs), or `None`
/// when no coordinate is quantised.
pub fn quantum(points: &[Vec3], u_count: usize, v_count: usize) -> Option<f64> {
    if points.len() != u_count * v_count || points.len() < 4 {
        return None;
    }
    // One buffer for every axis' values (fresh arrays of the grid's size are fresh pages).
    let mut values = Vec::with_capacity(points.len());
    (0..3)
        .filter_map(|axis| axis_quantum(points, u_count, v_count, axis, &mut values))
        .fold(None, |best: Option<f64>, q| Some(best.map_or(q, |b| b.max(q))))
}

fn axis_quantum(
    points: &[Vec3],
    u_count: usize,
    v_count: usize,
    axis: usize,
    values: &mut Vec<f64>,
) -> Option<f64> {
    values.clear();
    values.extend(points.iter().map(|p| p[axis]));
    if values.iter().any(|v| !v.is_finite()) {
        return None;
    }
    values.sort_unstable_by(f64::total_cmp);
    let range = values[values.len() - 1] - values[0];
    if range <= 0.0 {
        return None;
    }
    let gap = values
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&d| d > 1e-12 * range)
        .fold(f64::INFINITY, f64::min);
    if !gap.is_finite() {
        return None;
    }
    // The first step that fits, kept if it is at least 1e-4 of the range and at most a
    // tenth of the median change between grid neighbours (read only then: on most axes no
    // step fits).
    let q = (1..=8).find_map(|k| fitted_step(values, gap / k as f64))?;
    (q >= 1e-4 * range && at_most_tenth_of_median(points, u_count, v_count, axis, q)).then_some(q)
}

/// Calls `f` with each change of coordinate `axis` between grid neighbours
/// (|P_{i+1,j} − P_ij| and |P_{i,j+1} − P_ij| along the axis).
fn for_each_neighbour_change(
    points: &[Vec3],
    u_count: usize,
    v_count: usize,
    axis: usize,
    mut f: impl FnMut(f64),
) {
    for i in 0..u_count {
        for j in 0..v_count {
            let here = points[i * v_count + j][axis];
            if i + 1 < u_count {
                f((points[(i + 1) * v_count + j][axis] - here).abs());
            }
            if j + 1 < v_count {
                f((points[i * v_count + j + 1][axis] - here).abs());
            }
        }
    }
}

/// Whether `q <= 0.1 · median` of the neighbour changes of `axis` (the median the change of
/// rank ⌊len/2⌋ in `f64::total_cmp`'s order), without storing or sorting them: the changes
/// are non-negative (+0 at least: no −0, no NaN), where `total_cmp` is the numeric order,
/// and `q <= 0.1 · s` can only turn from false to true as s grows (rounding is monotone),
/// so it holds at the change of rank r exactly when at most r changes fail it. O(m·n), one
/// pass over the points (was an array of 2·m·n changes and a selection in it).
fn at_most_tenth_of_median(points: &[Vec3], u_count: usize, v_count: usize, axis: usize, q: f64) -> bool {
    let (mut count, mut failing) = (0usize, 0usize);
    for_each_neighbour_change(points, u_count, v_count, axis, |s| {
        count += 1;
        let holds = q <= 0.1 * s;
        failing += usize::from(!holds);
    });
    failing <= count / 2
}

/// The step q near `guess` of which every value is an integer multiple to 1e-3 q (values
/// printed with a few decimals are multiples only to their last digit): the multiples n_i of
/// the guess, then q by least squares over v_i ≈ n_i q. `None` if some value is off. The
/// multiples are computed where they are read, twice, rather than stored (the same values:
/// an array of the grid's size per guess was a fresh page per 512 values).
fn fitted_step(values: &[f64], guess: f64) -> Option<f64> {
    let multiple = |v: f64| (v / guess).round();
    let (vn, nn) = values.iter().fold((0.0, 0.0), |(a, b), &v| {
        let n = multiple(v);
        (a + v * n, b + n * n)
    });
    if nn == 0.0 {
        return None;
    }
    let q = vn / nn;
    (q > 0.0 && values.iter().all(|&v| (v - multiple(v) * q).abs() <= 1e-3 * q)).then_some(q)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A table like PX121's: stations (x) and waterlines (z) on a coarse lattice, half-breadths
    /// (y) rounded to a pixel of 0.01.
    fn table(pixel: f64) -> (Vec<Vec3>, usize, usize) {
        let (rows, columns) = (6, 9);
        let points = (0..rows)
            .flat_map(|i| (0..columns).map(move |j| (i, j)))
            .map(|(i, j)| {
                let y = 3.0 * (1.0 - ((j as f64 - 4.0) / 5.0).powi(2)) * (0.5 + 0.1 * i as f64)
                    + 0.02 * ((7 * j + 3 * i) as f64).sin();
                let y = if pixel > 0.0 {
                    (y / pixel).round() * pixel
                } else {
                    y
                };
                Vec3::new(8.2 * j as f64, y, 1.6 * i as f64)
            })
            .collect();
        (points, rows, columns)
    }

    #[test]
    fn a_pixel_step_is_found_and_the_sampling_lattice_is_not() {
        let (points, rows, columns) = table(0.01);
        let q = quantum(&points, rows, columns).unwrap();
        assert!((q - 0.01).abs() < 1e-12, "{q}");
        // Printed with four decimals, as a table would be.
        let printed: Vec<Vec3> = points
            .iter()
            .map(|p| p.map(|c| (c * 1e4).round() / 1e4))
            .collect();
        let q = quantum(&printed, rows, columns).unwrap();
        assert!((q - 0.01).abs() < 1e-6, "{q}");
    }

    #[test]
    fn unrounded_and_finely_printed_data_have_no_step() {
        let (points, rows, columns) = table(0.0);
        assert_eq!(quantum(&points, rows, columns), None);
        // Printed with six decimals: a lattice of 1e-6, below 1e-4 of the range.
        let (points, rows, columns) = table(1e-6);
        assert_eq!(quantum(&points, rows, columns), None);
    }

    /// The median's test as it was: every change stored, the median selected.
    fn tenth_of_selected_median(
        points: &[Vec3],
        u_count: usize,
        v_count: usize,
        axis: usize,
        q: f64,
    ) -> bool {
        let mut steps = Vec::new();
        for_each_neighbour_change(points, u_count, v_count, axis, |s| steps.push(s));
        let middle = steps.len() / 2;
        let median = *steps.select_nth_unstable_by(middle, f64::total_cmp).1;
        q <= 0.1 * median
    }

    #[test]
    fn the_median_test_counts_as_the_selection_decides() {
        // Grids with many equal changes (a lattice), and steps q at, just below and just
        // above a tenth of every change present (where the comparison is decided by the
        // rounding of 0.1 · s), odd and even counts of changes.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut decided = [0usize; 2];
        for (rows, columns) in [(2, 2), (2, 3), (3, 5), (7, 4), (10, 10)] {
            for lattice in [0.0, 0.25, 3.0] {
                let points: Vec<Vec3> = (0..rows * columns)
                    .map(|_| {
                        let mut c = || {
                            let r = (random() >> 11) as f64 / (1u64 << 53) as f64 * 10.0;
                            if lattice > 0.0 {
                                (r / lattice).round() * lattice
                            } else {
                                r
                            }
                        };
                        Vec3::new(c(), c(), c())
                    })
                    .collect();
                for axis in 0..3 {
                    let mut changes = Vec::new();
                    for_each_neighbour_change(&points, rows, columns, axis, |s| changes.push(s));
                    for &s in &changes {
                        let tenth = 0.1 * s;
                        // The floats next to a tenth (non-negative: its bits ± 1).
                        let below = f64::from_bits(tenth.to_bits().saturating_sub(1));
                        let above = f64::from_bits(tenth.to_bits() + 1);
                        for q in [tenth, below, above, s, 0.0] {
                            let expected = tenth_of_selected_median(&points, rows, columns, axis, q);
                            assert_eq!(
                                at_most_tenth_of_median(&points, rows, columns, axis, q),
                                expected,
                                "{rows} × {columns}, lattice {lattice}, axis {axis}, q {q}"
                            );
                            decided[usize::from(expected)] += 1;
                        }
                    }
                }
            }
        }
        // Both answers occur.
        assert!(decided[0] > 100 && decided[1] > 100, "{decided:?}");
    }
}
