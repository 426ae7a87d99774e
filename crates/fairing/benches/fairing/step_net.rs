//! The noisy net of the `surface_step` bench, shared with `examples/surface_cost.rs` (which
//! counts the same run's instructions and must fair the same net).

use curve_repr::Vec3;

/// A deterministic pseudo-random number in [−1, 1] (the surface table's).
pub(crate) fn noise(i: usize, j: usize) -> f64 {
    let x = ((i * 7919 + j * 104_729 + 3 * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
    2.0 * (x - x.floor()) - 1.0
}

/// A smooth wave with ±0.01 hashed noise on every point, `size` × `size` nodes.
pub(crate) fn noisy_net(size: usize) -> Vec<Vec<Vec3>> {
    (0..size)
        .map(|i| {
            (0..size)
                .map(|j| {
                    let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
                    Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + 0.01 * noise(i, j))
                })
                .collect()
        })
        .collect()
}
