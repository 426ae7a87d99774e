//! Knot insertion (The NURBS Book A5.1) and removal (A5.8): the same curve on a refined or
//! coarsened knot vector (removal within a tolerance). The Sapidis–Farin fairing baseline
//! removes and reinserts knots.

use super::NurbsCurve;
use crate::{Error, Result, Side, Vector};

/// A homogeneous control point (w P, w).
type Homogeneous<const D: usize> = (Vector<D>, f64);

fn lerp<const D: usize>(a: Homogeneous<D>, b: Homogeneous<D>, alpha: f64) -> Homogeneous<D> {
    (
        a.0 * (1.0 - alpha) + b.0 * alpha,
        a.1 * (1.0 - alpha) + b.1 * alpha,
    )
}

impl<const D: usize> NurbsCurve<D> {
    /// The same curve with the knot `u` inserted `times` more times (The NURBS Book A5.1,
    /// on homogeneous points, so weights change and the rational curve does not).
    ///
    /// `u` must lie strictly inside the domain and its multiplicity after insertion must not
    /// exceed the degree ([`Error::OutOfRange`], [`Error::BadKnots`]). O(n + times·p).
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<Self> {
        let p = self.degree();
        let (a, b) = self.knots.domain();
        if !(u > a && u < b) {
            return Err(Error::OutOfRange {
                what: "knot to insert",
                value: u,
                reason: "must lie strictly inside the domain",
            });
        }
        let up = self.knots();
        let s = up.iter().filter(|&&k| k == u).count();
        if s + times > p {
            return Err(Error::BadKnots {
                reason: format!(
                    "inserting {u} {times} times gives multiplicity {} above the degree {p}",
                    s + times
                ),
            });
        }
        if times == 0 {
            return Ok(self.clone());
        }
        let k = self.knots.span(u, Side::Right);
        let np = self.control_points.len() - 1;
        let r = times;
        let pw: Vec<Homogeneous<D>> = self
            .weighted
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
            .collect();
        let mut uq = Vec::with_capacity(up.len() + r);
        uq.extend_from_slice(&up[..=k]);
        uq.extend(std::iter::repeat_n(u, r));
        uq.extend_from_slice(&up[k + 1..]);
        let mut qw: Vec<Homogeneous<D>> = vec![(Vector::<D>::zeros(), 0.0); np + 1 + r];
        qw[..=(k - p)].copy_from_slice(&pw[..=(k - p)]);
        qw[(k - s + r)..=(np + r)].copy_from_slice(&pw[(k - s)..=np]);
        let mut rw: Vec<Homogeneous<D>> = pw[(k - p)..=(k - s)].to_vec();
        let mut l = k - p;
        for j in 1..=r {
            l = k - p + j;
            for i in 0..=(p - j - s) {
                let alpha = (u - up[l + i]) / (up[i + k + 1] - up[l + i]);
                rw[i] = lerp(rw[i], rw[i + 1], alpha);
            }
            qw[l] = rw[0];
            qw[k + r - j - s] = rw[p - j - s];
        }
        if l + 1 < k - s {
            qw[(l + 1)..(k - s)].copy_from_slice(&rw[1..(k - s - l)]);
        }
        let weights: Vec<f64> = qw.iter().map(|q| q.1).collect();
        let points: Vec<Vector<D>> = qw.iter().map(|q| q.0 / q.1).collect();
        NurbsCurve::new(p, uq, points, weights)
    }

    /// Removes the interior knot `u` up to `times` times while the curve moves by at most
    /// `tolerance` (The NURBS Book A5.8, its test on homogeneous control points: a removal
    /// is accepted when the two computations of the new control point agree within
    /// `tolerance` in (wP, w) space; divide a Cartesian tolerance d by (1 + max|P|)/min w as
    /// Eq. 5.30 does). Returns the curve and the number of removals made (0 if none).
    ///
    /// Fails with [`Error::OutOfRange`] when `u` is not an interior knot or the tolerance is
    /// not finite and non-negative. O(n + times·p).
    pub fn remove_knot(&self, u: f64, times: usize, tolerance: f64) -> Result<(Self, usize)> {
        let p = self.degree();
        let knots = self.knots();
        let (a, b) = self.knots.domain();
        let s = knots.iter().filter(|&&k| k == u).count();
        if !(u > a && u < b) || s == 0 {
            return Err(Error::OutOfRange {
                what: "knot to remove",
                value: u,
                reason: "must be an interior knot",
            });
        }
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(Error::OutOfRange {
                what: "knot removal tolerance",
                value: tolerance,
                reason: "must be finite and non-negative",
            });
        }
        let distance =
            |x: Homogeneous<D>, y: Homogeneous<D>| ((x.0 - y.0).norm_squared() + (x.1 - y.1).powi(2)).sqrt();
        let num = times.min(s);
        let r = self.knots.span(u, Side::Right) as isize;
        let (p_i, s_i) = (p as isize, s as isize);
        let order = p_i + 1;
        let mut pw: Vec<Homogeneous<D>> = self
            .weighted
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
            .collect();
        let uk = |i: isize| knots.get(i as usize).copied().unwrap_or(f64::NAN);
        let mut first = r - p_i;
        let mut last = r - s_i;
        let mut removed = 0isize;
        let zero = (Vector::<D>::zeros(), 0.0);
        let mut temp = vec![zero; 2 * p + 3];
        while removed < num as isize {
            let t = removed;
            let off = first - 1;
            temp[0] = pw[off as usize];
            temp[(last + 1 - off) as usize] = pw[(last + 1) as usize];
            let (mut i, mut j) = (first, last);
            let (mut ii, mut jj) = (1isize, last - off);
            while j - i > t {
                let alpha_i = (u - uk(i)) / (uk(i + order + t) - uk(i));
                let alpha_j = (u - uk(j - t)) / (uk(j + order) - uk(j - t));
                let prev = temp[(ii - 1) as usize];
                let pi = pw[i as usize];
                temp[ii as usize] = (
                    (pi.0 - prev.0 * (1.0 - alpha_i)) / alpha_i,
                    (pi.1 - prev.1 * (1.0 - alpha_i)) / alpha_i,
                );
                let next = temp[(jj + 1) as usize];
                let pj = pw[j as usize];
                temp[jj as usize] = (
                    (pj.0 - next.0 * alpha_j) / (1.0 - alpha_j),
                    (pj.1 - next.1 * alpha_j) / (1.0 - alpha_j),
                );
                i += 1;
                ii += 1;
                j -= 1;
                jj -= 1;
            }
            let accepted = if j - i < t {
                distance(temp[(ii - 1) as usize], temp[(jj + 1) as usize]) <= tolerance
            } else {
                let alpha_i = (u - uk(i)) / (uk(i + order + t) - uk(i));
                let blend = lerp(temp[(ii - 1) as usize], temp[(ii + t + 1) as usize], alpha_i);
                distance(pw[i as usize], blend) <= tolerance
            };
            if !accepted {
                break;
            }
            let (mut i, mut j) = (first, last);
            while j - i > t {
                pw[i as usize] = temp[(i - off) as usize];
                pw[j as usize] = temp[(j - off) as usize];
                i += 1;
                j -= 1;
            }
            first -= 1;
            last += 1;
            removed += 1;
        }
        let t = removed as usize;
        if t == 0 {
            return Ok((self.clone(), 0));
        }
        let mut new_knots = knots.to_vec();
        let r_u = r as usize;
        new_knots.drain(r_u + 1 - t..=r_u);
        // Shift the control points (A5.8's last loop).
        let fout = ((2 * r - s_i - p_i) / 2) as usize;
        let (mut i, mut j) = (fout, fout);
        for k in 1..t {
            if k % 2 == 1 {
                i += 1;
            } else {
                j -= 1;
            }
        }
        let n = pw.len() - 1;
        for k in (i + 1)..=n {
            pw[j] = pw[k];
            j += 1;
        }
        pw.truncate(n + 1 - t);
        let weights: Vec<f64> = pw.iter().map(|q| q.1).collect();
        let points: Vec<Vector<D>> = pw.iter().map(|q| q.0 / q.1).collect();
        Ok((NurbsCurve::new(p, new_knots, points, weights)?, t))
    }
}
