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
//! of its quantised axes. O(m·n log(m·n)).

use curve_repr::Vec3;

/// The quantisation step of the flat grid `points[i·v_count + j]` (module docs), or `None`
/// when no coordinate is quantised.
pub fn quantum(points: &[Vec3], u_count: usize, v_count: usize) -> Option<f64> {
    if points.len() != u_count * v_count || points.len() < 4 {
        return None;
    }
    (0..3)
        .filter_map(|axis| axis_quantum(points, u_count, v_count, axis))
        .fold(None, |best: Option<f64>, q| Some(best.map_or(q, |b| b.max(q))))
}

fn axis_quantum(points: &[Vec3], u_count: usize, v_count: usize, axis: usize) -> Option<f64> {
    let mut values: Vec<f64> = points.iter().map(|p| p[axis]).collect();
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
    // The median change of this coordinate between grid neighbours.
    let mut steps: Vec<f64> = Vec::with_capacity(2 * points.len());
    for i in 0..u_count {
        for j in 0..v_count {
            let here = points[i * v_count + j][axis];
            if i + 1 < u_count {
                steps.push((points[(i + 1) * v_count + j][axis] - here).abs());
            }
            if j + 1 < v_count {
                steps.push((points[i * v_count + j + 1][axis] - here).abs());
            }
        }
    }
    let middle = steps.len() / 2;
    let median = *steps.select_nth_unstable_by(middle, f64::total_cmp).1;
    (1..=8)
        .filter_map(|k| fitted_step(&values, gap / k as f64))
        .next()
        .filter(|&q| q <= 0.1 * median && q >= 1e-4 * range)
}

/// The step q near `guess` of which every value is an integer multiple to 1e-3 q (values
/// printed with a few decimals are multiples only to their last digit): the multiples n_i of
/// the guess, then q by least squares over v_i ≈ n_i q. `None` if some value is off.
fn fitted_step(values: &[f64], guess: f64) -> Option<f64> {
    let multiples: Vec<f64> = values.iter().map(|v| (v / guess).round()).collect();
    let (vn, nn) = values
        .iter()
        .zip(&multiples)
        .fold((0.0, 0.0), |(a, b), (v, n)| (a + v * n, b + n * n));
    if nn == 0.0 {
        return None;
    }
    let q = vn / nn;
    (q > 0.0
        && values
            .iter()
            .zip(&multiples)
            .all(|(v, n)| (v - n * q).abs() <= 1e-3 * q))
    .then_some(q)
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
}
