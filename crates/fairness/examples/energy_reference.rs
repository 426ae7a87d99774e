//! Ek and Ek′ of a noisy spline function against a much finer reference computation.
//!
//! `cargo run --release -p fairness --example energy_reference -- FILE.csv [generic|report-only]`
//!
//! FILE.csv has a header `x,y` and x increasing (the file `speed.py N FILE.csv` writes). The
//! curve is the report's: the spline function with the parabolic-runout end condition. The
//! example prints
//! - the report's measure ([`Energies::measure_polynomial`] at the summaries' tolerance) with
//!   its error estimates, and its CPU time;
//! - with `generic`, the generic path ([`Energies::measure`], every node searches its piece);
//! - a reference written independently of the library's quadrature: on every piece the graph's
//!   integrands y″²/q^{5/2} and (y‴q − 3y′y″²)²/q^{11/2} (q = 1 + y′²) in the variable
//!   s = asinh((x − x*)/w) around each pole x* + iw of the integrands (the roots of
//!   y′(x) = ±i, from the quadratic formula in complex arithmetic), on panels of at most `ds` in s with a `points`-point Gauss–Legendre
//!   rule; pieces with no narrow peak on 32 equal panels. It is run twice (ds 0.25 with 20
//!   points, ds 0.0625 with 24 points): their difference says how many digits it has.

use std::time::Instant;

use curve_repr::{EndCondition, Side, SplineFunction};
use fairness::energy::{Energies, MeasuredEnergies};
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

    /// The poles of the integrands near [0, h]: the zeros of q = 1 + y′² = (y′ − i)(y′ + i),
    /// the roots of y′(u) = ±i (conjugate pairs, so the roots of y′ = i give them all), as
    /// (centre: the real part clamped to the piece, width: the distance to it), where the
    /// width is below h/4.
    fn peaks(&self) -> Vec<(f64, f64)> {
        // (c/2) u² + b u + (a − i) = 0, in complex arithmetic written out.
        let (qa, qb) = (0.5 * self.c, self.b);
        let (cr, ci) = (self.a, -1.0);
        let mut roots: Vec<(f64, f64)> = Vec::new();
        if qa != 0.0 {
            // discriminant b² − 4 qa (a − i) = (b² − 4 qa a) + i (4 qa)
            let (dr, di) = (qb * qb - 4.0 * qa * cr, -4.0 * qa * ci);
            let modulus = dr.hypot(di);
            let (mut sr, mut si) = (((modulus + dr) / 2.0).sqrt(), ((modulus - dr) / 2.0).sqrt());
            if di < 0.0 {
                si = -si;
            }
            if qb * sr < 0.0 {
                sr = -sr;
                si = -si;
            }
            // t = −(b + √D)/2; roots t/qa and (a − i)/t.
            let (tr, ti) = (-0.5 * (qb + sr), -0.5 * si);
            roots.push((tr / qa, ti / qa));
            let norm = tr * tr + ti * ti;
            if norm > 0.0 {
                roots.push(((cr * tr + ci * ti) / norm, (ci * tr - cr * ti) / norm));
            }
        } else if qb != 0.0 {
            roots.push((-cr / qb, -ci / qb));
        }
        let mut peaks: Vec<(f64, f64)> = roots
            .into_iter()
            .filter_map(|(re, im)| {
                let centre = re.clamp(0.0, self.h);
                let width = (re - centre).hypot(im);
                (width.is_finite() && width < self.h / 4.0).then_some((centre, width))
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

/// One line: Ek and Ek′ as the library measured them, with their errors, and the time since
/// `start`.
fn print_measured(label: &str, start: Instant, measured: &MeasuredEnergies) {
    let (v, a) = (measured.values, measured.accuracy);
    println!(
        "{label} ({:.2} s): Ek {:.12e} ± {:.3e} (met {}), Ek' {:.12e} ± {:.3e} (met {})",
        start.elapsed().as_secs_f64(),
        v.ek,
        a.errors.ek,
        a.within_tolerance.ek,
        v.ek_prime,
        a.errors.ek_prime,
        a.within_tolerance.ek_prime
    );
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
    print_measured("report path", start, &measured);
    let (v, a) = (measured.values, measured.accuracy);
    if args.iter().any(|a| a == "report-only") {
        return;
    }
    if args.iter().any(|a| a == "generic") {
        let start = Instant::now();
        let measured = Energies::measure(&spline, &energy_settings()).unwrap();
        print_measured("generic path", start, &measured);
    }
    let start = Instant::now();
    let (ek, ek_prime) = reference(&spline, 20, 0.25);
    println!(
        "reference ds 0.25, 20 points ({:.2} s): Ek {ek:.15e}, Ek' {ek_prime:.15e}",
        start.elapsed().as_secs_f64()
    );
    let (ek2, ek_prime2) = reference(&spline, 24, 0.0625);
    println!("reference ds 0.0625, 24 points: Ek {ek2:.15e}, Ek' {ek_prime2:.15e}");
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
