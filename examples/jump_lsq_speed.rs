//! Time and peak memory of one jump-lsq fairing (λ chosen automatically) on a CSV of points,
//! e.g. the speed peer's data: `python speed.py 1000000 sine.csv` prints csaps's time on it.
//!
//! Run: `cargo run --release --example jump_lsq_speed -- FILE.csv [function|parametric]`
//! Prints the median of three runs of `jump_lsq::fair` and of the same through a `Pipeline`
//! (moves recorded in the trace, as the command runs it), the λ chosen, and the peak heap
//! bytes per point of each (counted by this example's global allocator, the input excluded).

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

/// Runs `f` three times; returns the median seconds and the peak heap growth in bytes.
fn measure(mut f: impl FnMut()) -> (f64, usize) {
    let mut times = Vec::new();
    let mut peak = 0;
    for _ in 0..3 {
        let base = IN_USE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let start = Instant::now();
        f();
        times.push(start.elapsed().as_secs_f64());
        peak = peak.max(PEAK.load(Ordering::Relaxed) - base);
    }
    times.sort_by(f64::total_cmp);
    (times[1], peak)
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
    let (seconds, peak) = measure(|| {
        let faired = fair(&points, &points, &none, domain, false, &settings).expect("fair");
        report = Some(faired.report);
    });
    let report = report.ok_or("no run")?;
    println!(
        "jump-lsq fair:     {n} points, {seconds:.3} s (median of 3), peak heap {:.0} bytes/point",
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
    let (seconds, peak) = measure(|| {
        Pipeline::new(JumpLsq::<2>::new(settings.clone(), domain))
            .run(points.clone())
            .expect("pipeline");
    });
    println!(
        "through a Pipeline: {seconds:.3} s (median of 3), peak heap {:.0} bytes/point (trace of every move included)",
        peak as f64 / n as f64
    );
    Ok(())
}
