//! The noisy function segment of the `fair` command's slowest test (`tests/cli/columns_cli.rs`)
//! and of the Sapidis–Farin bench, written once: both include this file (`#[path]`).

/// n points of y = sin(x/2) + σ·N(0, 1), x in random steps of (0.5 + u)·4π/n, u uniform in
/// (0, 1) from a 64-bit LCG seeded with `seed`, the normal by Box–Muller (two uniforms per
/// point after the step's). O(n).
pub(crate) fn noisy_segment(n: usize, sigma: f64, seed: u64) -> Vec<[f64; 2]> {
    let mut state = seed;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    let mut x = 0.0;
    (0..n)
        .map(|_| {
            x += (0.5 + uniform()) * 4.0 * std::f64::consts::PI / n as f64;
            let gauss = (-2.0 * uniform().ln()).sqrt() * (2.0 * std::f64::consts::PI * uniform()).cos();
            [x, (x / 2.0).sin() + sigma * gauss]
        })
        .collect()
}
