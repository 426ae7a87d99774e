//! Strain energy (Zhang–Cheng Eq. 3) and third-derivative jumps (the basis of Eq. 17).

use super::HermiteSpline;
use crate::Vector;

impl<const D: usize> HermiteSpline<D> {
    /// C'' at both ends of segment i, (C''_i(t_i+), C''_i(t_{i+1}−)): from Eq. (1),
    /// (6d − 4M_i − 2M_{i+1})/h and (−6d + 2M_i + 4M_{i+1})/h with d = (P_{i+1} − P_i)/h.
    fn second_derivative_ends(&self, segment: usize) -> (Vector<D>, Vector<D>) {
        let h = self.step(segment);
        let slope = self.chord_slope(segment);
        let (m0, m1) = (self.tangents[segment], self.tangents[self.next(segment)]);
        (
            (slope * 6.0 - m0 * 4.0 - m1 * 2.0) / h,
            (m0 * 2.0 + m1 * 4.0 - slope * 6.0) / h,
        )
    }

    /// The constant C''' on segment i: (6(M_i + M_{i+1}) − 12d)/h².
    fn third_derivative(&self, segment: usize) -> Vector<D> {
        let h = self.step(segment);
        let (m0, m1) = (self.tangents[segment], self.tangents[self.next(segment)]);
        ((m0 + m1) * 6.0 - self.chord_slope(segment) * 12.0) / (h * h)
    }

    /// ∫ |C''(t)|² dt over each segment, in closed form: C'' is linear on a segment, so one
    /// of length h with end values a, b gives h(|a|² + a·b + |b|²)/3. O(n).
    pub fn segment_energies(&self) -> Vec<f64> {
        (0..self.segment_count())
            .map(|i| {
                let (a, b) = self.second_derivative_ends(i);
                self.step(i) * (a.norm_squared() + a.dot(&b) + b.norm_squared()) / 3.0
            })
            .collect()
    }

    /// The strain energy E = ∫ |C''(t)|² dt over the whole curve (Zhang–Cheng Eq. 3; the
    /// `fair` report's `e_s` for the parametric kind), the sum of
    /// [`segment_energies`](Self::segment_energies). O(n).
    pub fn strain_energy(&self) -> f64 {
        self.segment_energies().iter().sum()
    }

    /// The third-derivative jumps C'''(t_i+) − C'''(t_i−) at the interior knots t_1..t_{n−1}
    /// of an open curve, or at every knot t_0..t_n of a closed one (the jump at t_0 is between
    /// the closing segment and the first). Zhang–Cheng's indicator (Eq. 17) is z_i = |jump|.
    /// O(n).
    pub fn third_derivative_jumps(&self) -> Vec<Vector<D>> {
        let segments = self.segment_count();
        if self.is_closed() {
            (0..segments)
                .map(|i| {
                    let previous = if i == 0 { segments - 1 } else { i - 1 };
                    self.third_derivative(i) - self.third_derivative(previous)
                })
                .collect()
        } else {
            (1..segments)
                .map(|i| self.third_derivative(i) - self.third_derivative(i - 1))
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Curve, HermiteEnds, HermiteSettings, Side, Vec2, Vec3};

    fn zigzag() -> Vec<Vec3> {
        (0..9)
            .map(|i| {
                let t = i as f64;
                Vec3::new(
                    t + 0.3 * (t * 1.7).sin(),
                    (t * 0.9).cos() * 2.0,
                    0.4 * t * t.sqrt(),
                )
            })
            .collect()
    }

    /// Eq. (4): the natural spline makes the strain energy stationary in every tangent
    /// (free ends included: it minimises E over all C1 Hermite curves through the points).
    #[test]
    fn natural_tangents_make_the_energy_stationary_eq_4() {
        let spline = HermiteSpline::natural(&zigzag()).unwrap();
        let base = spline.strain_energy();
        for i in 0..spline.points.len() {
            for axis in 0..3 {
                let delta = 1e-4;
                let energy = |sign: f64| {
                    let mut moved = spline.clone();
                    moved.tangents[i][axis] += sign * delta;
                    moved.strain_energy()
                };
                let (plus, minus) = (energy(1.0), energy(-1.0));
                let gradient = (plus - minus) / (2.0 * delta);
                let curvature = (plus - 2.0 * base + minus) / (delta * delta);
                // E is quadratic in M: a gradient that vanishes means E(M ± δ) − E(M) = O(δ²).
                assert!(
                    gradient.abs() < 1e-7 * curvature.abs().max(1.0),
                    "i {i} axis {axis}: {gradient}"
                );
                assert!(plus > base && minus > base);
            }
        }
    }

    /// The jumps are the differences of the one-sided third derivatives of `jet`, and the
    /// segment energies agree with a 3-point Gauss–Legendre rule (exact for |C''|², degree 2).
    #[test]
    fn jumps_and_energies_agree_with_the_jet() {
        for ends in [
            HermiteEnds::Natural,
            HermiteEnds::ParabolicRunout,
            HermiteEnds::Closed,
        ] {
            let settings = HermiteSettings::default().with_ends(ends);
            let spline = HermiteSpline::new(&zigzag(), &settings).unwrap();
            let jumps = spline.third_derivative_jumps();
            let knots = spline.knots();
            let offset = usize::from(!spline.is_closed());
            for (k, jump) in jumps.iter().enumerate() {
                let i = k + offset;
                let right = spline.jet(knots[i], Side::Right)[3];
                let left = if i == 0 {
                    spline.jet(knots[knots.len() - 1], Side::Left)[3]
                } else {
                    spline.jet(knots[i], Side::Left)[3]
                };
                assert!((right - left - jump).norm() <= 1e-12 * jump.norm().max(1.0));
            }
            let nodes = [-(0.6f64.sqrt()), 0.0, 0.6f64.sqrt()];
            let weights = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
            for (i, energy) in spline.segment_energies().iter().enumerate() {
                let (a, b) = (knots[i], knots[i + 1]);
                let quadrature: f64 = nodes
                    .iter()
                    .zip(weights)
                    .map(|(x, w)| {
                        let t = 0.5 * (a + b) + 0.5 * (b - a) * x;
                        w * 0.5 * (b - a) * spline.jet(t, Side::Right)[2].norm_squared()
                    })
                    .sum();
                assert!((energy - quadrature).abs() <= 1e-12 * energy.max(1e-300));
            }
        }
    }

    #[test]
    fn a_straight_line_has_no_energy_and_no_jumps() {
        let line: Vec<Vec2> = (0..6).map(|i| Vec2::new(i as f64, 2.0 * i as f64)).collect();
        let spline = HermiteSpline::natural(&line).unwrap();
        assert!(spline.strain_energy() < 1e-24);
        assert!(spline.third_derivative_jumps().iter().all(|j| j.norm() < 1e-12));
    }
}
