//! The `surface_step/tiles` bench's run (automatic Zhang–Cheng, 4 steps, the boundary
//! fairing included) on its noisy net, once, for instruction counts under valgrind and for
//! bit-for-bit comparisons of the faired net between builds.
//!
//! Run: `cargo build --release -p fairing --example surface_cost`, then e.g.
//! `valgrind --tool=callgrind target/release/examples/surface_cost 50` (`SIZE [steps|dump]`:
//! `steps` runs without the boundary fairing, as `tiles_steps`; `dump` prints every faired
//! point's coordinates as bits and the run's counts, to diff between builds). `curve N`
//! instead fairs a noisy N-point curve with the curve method alone (automatic, one point
//! and pairs, and interactive) and prints its points as bits, the same way. `net PATH`
//! fairs the net of a CSV file (`i,j,x,y,z` after a header, as `data/surface_utah_teapot/`)
//! with Zhang–Cheng and with Kjellander and prints the same, with the pinned nodes: the
//! teapot's nets take the refusal rules' paths (pins, retries) that the noisy net does not.

use curve_repr::Vec3;
use fairing::strategies::{Mode, StrainEnergy, StrainEnergySettings, SurfaceFairing, SurfaceFairingSettings};
use fairing::Pipeline;

#[path = "../benches/fairing/step_net.rs"]
mod step_net;
use step_net::{noise, noisy_net};

/// The curve method on a noisy wave of `count` points, three ways, every point as bits.
fn curves(count: usize) {
    let line: Vec<Vec3> = (0..count)
        .map(|k| {
            let x = k as f64 / 10.0;
            Vec3::new(x, (0.3 * x).sin() + 0.01 * noise(k, 7), 0.01 * noise(3, k))
        })
        .collect();
    let interactive = Mode::Interactive((1..count - 1).step_by(7).collect());
    for settings in [
        StrainEnergySettings::default(),
        StrainEnergySettings::default().with_pairs(true),
        StrainEnergySettings::default().with_mode(interactive),
    ] {
        let result = Pipeline::new(StrainEnergy::<3>::new(settings.with_tolerance(1e-9)))
            .with_trace(false)
            .run(line.clone())
            .expect("the curve fairs");
        println!(
            "iterations {} termination {:?}",
            result.iterations, result.termination
        );
        for p in &result.points {
            println!("{:x} {:x} {:x}", p.x.to_bits(), p.y.to_bits(), p.z.to_bits());
        }
    }
}

/// Zhang–Cheng and Kjellander on the net of the CSV file at `path`, every point as bits.
fn net_file(path: &str) {
    let text = std::fs::read_to_string(path).expect("the net's file reads");
    let cells: Vec<(usize, usize, Vec3)> = text
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().expect("a number"))
                .collect();
            (f[0] as usize, f[1] as usize, Vec3::new(f[2], f[3], f[4]))
        })
        .collect();
    let rows = cells.iter().map(|c| c.0).max().expect("a point") + 1;
    let columns = cells.iter().map(|c| c.1).max().expect("a point") + 1;
    let mut net = vec![vec![Vec3::zeros(); columns]; rows];
    for (i, j, p) in cells {
        net[i][j] = p;
    }
    for settings in [
        SurfaceFairingSettings::zhang_cheng(),
        SurfaceFairingSettings::kjellander(),
    ] {
        let result = SurfaceFairing::new(settings).run(&net).expect("the net fairs");
        println!(
            "steps {} moved {} refused {} {} pinned {} refusal {:?} termination {:?}",
            result.steps,
            result.moved.len(),
            result.refused_steps,
            result.refused_moves,
            result.pinned.len(),
            result.refusal,
            result.termination
        );
        for p in result.surface.points() {
            println!("{:x} {:x} {:x}", p.x.to_bits(), p.y.to_bits(), p.z.to_bits());
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(String::as_str) == Some("curve") {
        curves(args.get(2).and_then(|s| s.parse().ok()).unwrap_or(300));
        return;
    }
    if args.get(1).map(String::as_str) == Some("net") {
        net_file(args.get(2).expect("net PATH"));
        return;
    }
    let size: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(50);
    let boundary = !args.iter().any(|a| a == "steps");
    let dump = args.iter().any(|a| a == "dump");
    let net = noisy_net(size);
    let settings = SurfaceFairingSettings::zhang_cheng()
        .with_fair_boundary(boundary)
        .with_max_steps(4);
    let result = SurfaceFairing::new(settings)
        .run(&net)
        .expect("the bench's net fairs");
    if dump {
        println!(
            "steps {} boundary_steps {} moved {} refused {} {} termination {:?}",
            result.steps,
            result.boundary_steps,
            result.moved.len(),
            result.refused_steps,
            result.refused_moves,
            result.termination
        );
        for s in &result.history {
            println!(
                "step {:x} {:x} {}",
                s.energy.to_bits(),
                s.max_z.to_bits(),
                s.moves
            );
        }
        for p in result.surface.points() {
            println!("{:x} {:x} {:x}", p.x.to_bits(), p.y.to_bits(), p.z.to_bits());
        }
    } else {
        eprintln!(
            "{size} × {size}: {} steps, {} boundary steps, {} points moved",
            result.steps,
            result.boundary_steps,
            result.moved.len()
        );
    }
}
