//! Surface jump least squares (`jump-lsq` for surfaces, issue 46) on whole noisy nets of
//! 50², 200² and 1000² nodes, λ by GCV, default settings; criterion's throughput in nodes.
//! Issue 46's targets: 200² well under 1 s, 1000² in seconds. Group `surface_jump_join`: the
//! same nets with edge u0 held g1 to a neighbour net (50², 200²). Group `surface_jump_strip`:
//! long strips of 4000 × 20 and 50 000 × 20 nodes (a scanned strip; the long direction on
//! the reduced basis), which should cost in proportion to their nodes.

use criterion::{criterion_group, BenchmarkId, Criterion, Throughput};
use curve_repr::Vec3;
use fairing::strategies::{Continuity, Join, JoinEdge, SurfaceJumpLsq, SurfaceJumpLsqSettings};

/// Under `cargo test` (no `--bench` flag) only the smallest size runs.
fn sizes<T: Copy>(all: &[T]) -> Vec<T> {
    if std::env::args().any(|a| a == "--bench") {
        all.to_vec()
    } else {
        all[..1].to_vec()
    }
}

/// A smooth surface over a square with deterministic pseudo-random bumps on every point.
fn noisy_net(size: usize) -> Vec<Vec<Vec3>> {
    shifted_net(size, 0)
}

/// [`noisy_net`]'s surface with its rows shifted back by `back` lines: at `back` = size − 1
/// the net ends where [`noisy_net`] starts (its neighbour across u0).
fn shifted_net(size: usize, back: usize) -> Vec<Vec<Vec3>> {
    (0..size)
        .map(|i| {
            (0..size)
                .map(|j| {
                    let (x, y) = ((i as f64 - back as f64) / 10.0, j as f64 / 10.0);
                    let noise = 0.01 * ((i * 7919 + j * 104_729) as f64 * 12.9898).sin().fract();
                    Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + noise)
                })
                .collect()
        })
        .collect()
}

/// A strip of `length` × `width` nodes, z = sin 3u cos 2v over u ∈ [0, 4], v ∈ [0, 1]
/// (x = 10u, y = v), with ±0.002 hashed noise on z.
fn strip(length: usize, width: usize) -> Vec<Vec<Vec3>> {
    (0..length)
        .map(|i| {
            (0..width)
                .map(|j| {
                    let (u, v) = (
                        4.0 * i as f64 / (length - 1) as f64,
                        j as f64 / (width - 1) as f64,
                    );
                    let noise =
                        0.002 * (((i * 7919 + j * 104_729) as f64 * 12.9898).sin() * 43_758.545_3).fract();
                    Vec3::new(10.0 * u, v, (3.0 * u).sin() * (2.0 * v).cos() + noise)
                })
                .collect()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface_jump");
    group.sample_size(10);
    for size in sizes(&[50usize, 200, 1000]) {
        let net = noisy_net(size);
        group.throughput(Throughput::Elements((size * size) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(size), &net, |b, net| {
            b.iter(|| {
                SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
                    .run(net)
                    .unwrap()
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("surface_jump_strip");
    group.sample_size(10);
    for length in sizes(&[4000usize, 50_000]) {
        let net = strip(length, 20);
        group.throughput(Throughput::Elements((length * 20) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(length), &net, |b, net| {
            b.iter(|| {
                SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
                    .run(net)
                    .unwrap()
            })
        });
    }
    group.finish();
    let mut group = c.benchmark_group("surface_jump_join");
    group.sample_size(10);
    for size in sizes(&[50usize, 200]) {
        let net = noisy_net(size);
        let settings = SurfaceJumpLsqSettings::default().with_join(Join {
            edge: JoinEdge::U0,
            continuity: Continuity::G1,
            neighbour: shifted_net(size, size - 1),
            source: "neighbour".into(),
        });
        group.throughput(Throughput::Elements((size * size) as u64));
        group.bench_with_input(BenchmarkId::from_parameter(size), &net, |b, net| {
            b.iter(|| SurfaceJumpLsq::new(settings.clone()).run(net).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
