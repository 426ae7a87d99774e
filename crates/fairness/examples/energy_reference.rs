//! Ek and Ek′ of a noisy spline function against a much finer reference computation.
//!
//! `cargo run --release -p fairness --example energy_reference -- FILE.csv [generic]`
//!
//! FILE.csv has a header `x,y` and x increasing (the file `speed.py N FILE.csv` writes). The
//! curve is the report's: the spline function with the parabolic-runout end condition. The
//! example prints
//! - the report's measure ([`Energies::measure_polynomial`] at the summaries' tolerance) with
//!   its error estimates, and its CPU time;
//! - with `generic`, the generic path ([`Energies::measure`], every node searches its piece);
//! - a reference written independently of the library's quadrature: on every piece the graph's
//!   integrands y″²/q^{5/2} and (y‴q − 3y′y″²)²/q^{11/2} (q = 1 + y′²) in the variable
//!   s = asinh((x − x*)/w) around each zero x* of y′ (w = 1/|y″(x*)|, the width of the
//!   curvature peak there), on panels of at most `ds` in s with a `points`-point Gauss–Legendre
//!   rule; pieces with no narrow peak on 32 equal panels. It is run twice (ds 0.25 with 20
//!   points, ds 0.125 with 24 points): their difference says how many digits it has.

use std::time::Instant;

use curve_repr::{EndCondition, Side, SplineFunction};
use fairness::energy::Energies;
use fairness::quadrature::GaussLegendre;
use fairness::summary::energy_settings;

/// Neumaier's compensated sum.
#[derive(Default)]
struct Sum {
    sum: f64,
    compensation: f64,
}

impl Sum {
    fn add(&mut self, value: f64) {
        let sum = self.sum + value;
        if self.sum.abs() >= value.abs() {
            self.compensation += (self.sum - sum) + value;
        } else {
            self.compensation += (value - sum) + self.sum;
        }
        self.sum = sum;
    }
    fn total(&self) -> f64 {
        self.sum + self.compensation
    }
}

/// One cubic piece of the graph: y′(u) = a + bu + cu²/2 on [0, h].
struct Piece {
    a: f64,
    b: f64,
    c: f64,
    h: f64,
}

impl Piece {
    /// (Ek, Ek′) integrands at u.
    fn integrands(&self, u: f64) -> (f64, f64) {
        let d1 = self.a + u * (self.b + 0.5 * self.c * u);
        let d2 = self.b + self.c * u;
        let d3 = self.c;
        let q = 1.0 + d1 * d1;
        let root = q.sqrt();
        let q2 = q * q;
        let ek = d2 * d2 / (q2 * root);
        let m = d3 * q - 3.0 * d1 * d2 * d2;
        let ek_prime = m * m / (q2 * q2 * q * root);
        (ek, ek_prime)
    }

    /// The zeros of y′ inside [0, h] where the peak is narrow (w = 1/|y″| < h/4), with w.
    fn peaks(&self) -> Vec<(f64, f64)> {
        let mut roots = Vec::new();
        let (qa, qb, qc) = (0.5 * self.c, self.b, self.a);
        if qa != 0.0 {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 {
                let r = disc.sqrt();
                // The stable pair of roots.
                let t = -0.5 * (qb + qb.signum() * r);
                if t != 0.0 {
                    roots.push(t / qa);
                    roots.push(qc / t);
                } else {
                    roots.push(0.0);
                }
            }
        } else if qb != 0.0 {
            roots.push(-qc / qb);
        }
        let mut peaks: Vec<(f64, f64)> = roots
            .into_iter()
            .filter(|u| u.is_finite() && (0.0..=self.h).contains(u))
            .filter_map(|u| {
                let w = 1.0 / (self.b + self.c * u).abs();
                (w < self.h / 4.0).then_some((u, w))
            })
            .collect();
        peaks.sort_by(|x, y| x.0.total_cmp(&y.0));
        peaks
    }

    /// ∫ over [0, h] of both integrands, on panels of at most `ds` in s around each peak.
    fn integrate(&self, rule: &GaussLegendre, ds: f64) -> (f64, f64) {
        let peaks = self.peaks();
        let (mut ek, mut ek_prime) = (Sum::default(), Sum::default());
        let mut add = |u: f64, weight: f64| {
            let (e, p) = self.integrands(u);
            ek.add(weight * e);
            ek_prime.add(weight * p);
        };
        if peaks.is_empty() {
            let panels = 32;
            for k in 0..panels {
                let (lo, hi) = (
                    self.h * k as f64 / panels as f64,
                    self.h * (k + 1) as f64 / panels as f64,
                );
                let (half, mid) = (0.5 * (hi - lo), 0.5 * (hi + lo));
                for (x, w) in rule.nodes().iter().zip(rule.weights()) {
                    add(mid + half * x, w * half);
                }
            }
        } else {
            for (k, &(centre, width)) in peaks.iter().enumerate() {
                let lo = if k == 0 {
                    0.0
                } else {
                    0.5 * (peaks[k - 1].0 + centre)
                };
                let hi = if k + 1 == peaks.len() {
                    self.h
                } else {
                    0.5 * (peaks[k + 1].0 + centre)
                };
                let (s0, s1) = (((lo - centre) / width).asinh(), ((hi - centre) / width).asinh());
                let panels = ((s1 - s0) / ds).ceil().max(1.0) as usize;
                for j in 0..panels {
                    let a = s0 + (s1 - s0) * j as f64 / panels as f64;
                    let b = s0 + (s1 - s0) * (j + 1) as f64 / panels as f64;
                    let (half, mid) = (0.5 * (b - a), 0.5 * (b + a));
                    for (x, w) in rule.nodes().iter().zip(rule.weights()) {
                        let s = mid + half * x;
                        add(centre + width * s.sinh(), w * half * width * s.cosh());
                    }
                }
            }
        }
        (ek.total(), ek_prime.total())
    }
}

fn reference(spline: &SplineFunction, points: usize, ds: f64) -> (f64, f64) {
    let rule = GaussLegendre::new(points).unwrap();
    let (mut ek, mut ek_prime) = (Sum::default(), Sum::default());
    for w in spline.x().windows(2) {
        let jet = spline.jet_at(w[0], Side::Right);
        let piece = Piece {
            a: jet[1],
            b: jet[2],
            c: jet[3],
            h: w[1] - w[0],
        };
        let (e, p) = piece.integrate(&rule, ds);
        ek.add(e);
        ek_prime.add(p);
    }
    (ek.total(), ek_prime.total())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).expect("usage: energy_reference FILE.csv [generic]");
    let text = std::fs::read_to_string(path).unwrap();
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for line in text.lines().skip(1) {
        let mut fields = line.split(',');
        x.push(fields.next().unwrap().trim().parse::<f64>().unwrap());
        y.push(fields.next().unwrap().trim().parse::<f64>().unwrap());
    }
    let spline = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap();
    println!("{} points", x.len());

    let start = Instant::now();
    let measured = Energies::measure_polynomial(&spline, 3, &energy_settings()).unwrap();
    let (v, a) = (measured.values, measured.accuracy);
    println!(
        "report path ({:.2} s): Ek {:.12e} ± {:.3e} (met {}), Ek' {:.12e} ± {:.3e} (met {})",
        start.elapsed().as_secs_f64(),
        v.ek,
        a.errors.ek,
        a.within_tolerance.ek,
        v.ek_prime,
        a.errors.ek_prime,
        a.within_tolerance.ek_prime
    );
    if args.iter().any(|a| a == "generic") {
        let start = Instant::now();
        let measured = Energies::measure(&spline, &energy_settings()).unwrap();
        let (v, a) = (measured.values, measured.accuracy);
        println!(
            "generic path ({:.2} s): Ek {:.12e} ± {:.3e} (met {}), Ek' {:.12e} ± {:.3e} (met {})",
            start.elapsed().as_secs_f64(),
            v.ek,
            a.errors.ek,
            a.within_tolerance.ek,
            v.ek_prime,
            a.errors.ek_prime,
            a.within_tolerance.ek_prime
        );
    }
    let start = Instant::now();
    let (ek, ek_prime) = reference(&spline, 20, 0.25);
    println!(
        "reference ds 0.25, 20 points ({:.2} s): Ek {ek:.15e}, Ek' {ek_prime:.15e}",
        start.elapsed().as_secs_f64()
    );
    let (ek2, ek_prime2) = reference(&spline, 24, 0.125);
    println!("reference ds 0.125, 24 points: Ek {ek2:.15e}, Ek' {ek_prime2:.15e}");
    println!(
        "reference self-difference: Ek {:.2e}, Ek' {:.2e} (relative)",
        ((ek - ek2) / ek2).abs(),
        ((ek_prime - ek_prime2) / ek_prime2).abs()
    );
    println!(
        "report against reference: Ek {:.3e} (error estimate {:.3e}), Ek' {:.3e} (error estimate {:.3e})",
        v.ek - ek2,
        a.errors.ek,
        v.ek_prime - ek_prime2,
        a.errors.ek_prime
    );
}
