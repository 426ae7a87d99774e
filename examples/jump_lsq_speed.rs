//! Time and peak memory of one jump-lsq fairing (λ chosen automatically) on a CSV of points,
//! e.g. the speed peer's data: `python speed.py 1000000 sine.csv` prints csaps's time on it.
//!
//! Run: `cargo run --release --example jump_lsq_speed -- FILE.csv [function|parametric] [RUNS]
//! [--no-pipeline]`. Prints the medians of RUNS (default 3) runs of `jump_lsq::fair` and of the
//! same through a `Pipeline` (moves recorded in the trace, as the command runs it): wall time,
//! CPU time of the thread (Linux; steadier on a loaded machine), the λ chosen, and the peak
//! heap bytes per point of each (counted by this example's global allocator, the input
//! excluded).

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use curve_repr::Vec2;
use fairing::strategies::jump_lsq::{fair, JumpLsq, JumpLsqSettings};
use fairing::strategies::CurveDomain;
use fairing::{Constraints, Pipeline};

/// The system allocator, counting the bytes in use and their peak.
struct Counting;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: `alloc` and `dealloc` forward every call unchanged to `System`, which upholds
// `GlobalAlloc`'s contract; the counters are atomics touched after the call and never read by
// the allocator. The workspace denies unsafe code; this measuring allocator is the one use.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = IN_USE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        IN_USE.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The CPU time this thread has run, in seconds (Linux: `/proc/thread-self/schedstat`), or
/// None where that is not available. On a loaded machine it is steadier than the wall time.
fn cpu_seconds() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanoseconds: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(nanoseconds * 1e-9)
}

/// Runs `f` `runs` times; returns the median wall seconds, the median CPU seconds (if known)
/// and the peak heap growth in bytes.
fn measure(runs: usize, mut f: impl FnMut()) -> (f64, Option<f64>, usize) {
    let mut times = Vec::new();
    let mut cpu = Vec::new();
    let mut peak = 0;
    for _ in 0..runs {
        let base = IN_USE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let cpu_start = cpu_seconds();
        let start = Instant::now();
        f();
        times.push(start.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu_start, cpu_seconds()) {
            cpu.push(b - a);
        }
        peak = peak.max(PEAK.load(Ordering::Relaxed) - base);
    }
    times.sort_by(f64::total_cmp);
    cpu.sort_by(f64::total_cmp);
    let cpu = (cpu.len() == runs).then(|| cpu[runs / 2]);
    (times[runs / 2], cpu, peak)
}

/// "0.123 s CPU" or nothing.
fn cpu_text(cpu: Option<f64>) -> String {
    cpu.map_or(String::new(), |c| format!(", {c:.3} s CPU"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .ok_or("usage: jump_lsq_speed FILE.csv [function|parametric]")?;
    let domain = match args.next().as_deref() {
        None | Some("function") => CurveDomain::Function,
        Some("parametric") => CurveDomain::Parametric,
        Some(other) => return Err(format!("unknown kind {other}").into()),
    };
    // Optional: the number of runs (default 3) and `--no-pipeline`.
    let mut runs = 3;
    let mut pipeline = true;
    for arg in args {
        if arg == "--no-pipeline" {
            pipeline = false;
        } else {
            runs = arg
                .parse::<usize>()
                .ok()
                .filter(|r| *r > 0)
                .ok_or(format!("bad argument {arg:?}: a number of runs or --no-pipeline"))?;
        }
    }
    let text = std::fs::read_to_string(&path)?;
    let mut points = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let mut f = line.split(',').map(|v| v.trim().parse::<f64>());
        match (f.next(), f.next()) {
            (Some(Ok(x)), Some(Ok(y))) => points.push(Vec2::new(x, y)),
            _ => return Err(format!("{path}: bad line {line:?}").into()),
        }
    }
    let n = points.len();
    let settings = JumpLsqSettings::default();
    let none = Constraints::default();
    let mut report = None;
    let (seconds, cpu, peak) = measure(runs, || {
        let faired = fair(&points, &points, &none, domain, false, &settings).expect("fair");
        report = Some(faired.report);
    });
    let report = report.ok_or("no run")?;
    println!(
        "jump-lsq fair:     {n} points, {seconds:.3} s{} (medians of {runs}), {:.3} µs/point, peak heap {:.0} bytes/point",
        cpu_text(cpu),
        seconds * 1e6 / n as f64,
        peak as f64 / n as f64
    );
    println!(
        "  λ = {:.4e} ({}{}), σ̂ = {:.4e}, RMS displacement {:.4e}, {} solves",
        report.lambda,
        report.rule,
        if report.lambda_limited {
            ", at the precision limit"
        } else {
            ""
        },
        report.sigma_hat,
        report.rms_displacement,
        report.solves
    );
    if pipeline {
        let (seconds, cpu, peak) = measure(runs, || {
            Pipeline::new(JumpLsq::<2>::new(settings.clone(), domain))
                .run(points.clone())
                .expect("pipeline");
        });
        println!(
            "through a Pipeline: {seconds:.3} s{} (medians of {runs}), peak heap {:.0} bytes/point (trace of every move included)",
            cpu_text(cpu),
            peak as f64 / n as f64
        );
    }
    Ok(())
}
