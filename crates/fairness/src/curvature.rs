//! Curvature κ and its arc-length derivative dκ/ds from a curve's jet.
//!
//! Planar curves get the signed curvature (counter-clockwise positive), spatial curves the
//! unsigned one, as docs/CONTRACT.md's parametric report and `parametric_metrics.json` define:
//!
//! - 2D: κ = (x′y″ − y′x″) / |C′|³,
//!   dκ/dt = [(x′y‴ − y′x‴)|C′|² − 3(x′y″ − y′x″)(C′·C″)] / |C′|⁵;
//! - 3D: with b = C′ × C″ (so b′ = C′ × C‴), κ = |b| / |C′|³,
//!   dκ/dt = [(b·b′)|C′|² / |b| − 3|b|(C′·C″)] / |C′|⁵;
//!
//! and dκ/ds = (dκ/dt) / |C′| in both. Where b = 0 in 3D (a point of zero curvature) |b| has a
//! corner: its one-sided derivatives are ±|b′|; we take their mean, 0, for the first term
//! (the set of such parameters has measure zero in every integral of this crate).
//!
//! [`CurvatureForm`] picks the form from the point type, so that generic code over
//! `const D: usize` asks for `Vector<D>: CurvatureForm`.

use curve_repr::{Curve, Side, Vec2, Vec3, Vector};

use crate::{Error, Result};

/// The curvature formulas of one dimension (implemented for [`Vec2`] and [`Vec3`]).
pub trait CurvatureForm: Sized {
    /// Whether the curvature carries a sign (planar curves), so that inflections make sense.
    const SIGNED: bool;

    /// κ from the first and second derivatives; `None` where C′ = 0 or the result is not finite.
    fn curvature(d1: &Self, d2: &Self) -> Option<f64>;

    /// dκ/ds from the first three derivatives; `None` where C′ = 0 or the result is not finite.
    fn curvature_slope(d1: &Self, d2: &Self, d3: &Self) -> Option<f64>;

    /// κ²|C′| and (dκ/ds)²|C′| from C′, C″, C‴: the integrands of Ek and Ek′, sharing one
    /// square root and one division (`None` where the tangent vanishes or a value is not
    /// finite).
    fn curvature_integrands(d1: &Self, d2: &Self, d3: &Self) -> Option<[f64; 2]>;

    /// [`curvature_integrands`](Self::curvature_integrands) of the cubic piece
    /// C′(u) = a + bu + cu²/2 (`taylor` = [a, b, c]) at the N parameters `u`: `out[0][i]` =
    /// κ²|C′| and `out[1][i]` = (dκ/ds)²|C′| at `u[i]`, NaN or ±∞ where the tangent vanishes.
    /// One loop over the nodes that the compiler can vectorise: what the quadrature of Ek and
    /// Ek′ spends its time in. O(N).
    fn curvature_integrands_at<const N: usize>(taylor: &[Self; 3], u: &[f64; N], out: &mut [[f64; N]; 2])
    where
        Self: Clone + std::ops::Add<Output = Self> + std::ops::Mul<f64, Output = Self>,
    {
        let [a, b, c] = taylor;
        for (i, &u) in u.iter().enumerate() {
            let d1 = a.clone() + (b.clone() + c.clone() * (0.5 * u)) * u;
            let d2 = b.clone() + c.clone() * u;
            let [ek, ek_prime] = Self::curvature_integrands(&d1, &d2, c).unwrap_or([f64::NAN; 2]);
            out[0][i] = ek;
            out[1][i] = ek_prime;
        }
    }

    /// Where the curvature integrands of a cubic piece have their poles, near the piece: for
    /// C′(u) = a + bu + cu²/2 on [0, `length`] (`taylor` = [a, b, c]), pushes `(centre,
    /// width)` for each narrow peak — `centre` in [0, `length`], `width` below `length`/8 —
    /// around which the curvature energies integrate after a sinh change of variable.
    ///
    /// Planar: the zeros ρ of C′ₓ + iC′ᵧ (a quadratic; with their conjugates, the zeros of
    /// |C′|²), centre Re ρ clamped to the piece and width the distance from ρ to it. Spatial
    /// (|C′|² has no such factorisation): the minima u* of |C′|² on the piece, width
    /// √(2q(u*)/q″(u*)), the zeros of its local quadratic model q(u*) + ½q″(u*)(u − u*)².
    /// O(1).
    fn speed_poles(taylor: &[Self; 3], length: f64, push: &mut dyn FnMut(f64, f64));
}

fn finite(value: f64) -> Option<f64> {
    value.is_finite().then_some(value)
}

fn cross2(a: &Vec2, b: &Vec2) -> f64 {
    a.x * b.y - a.y * b.x
}

impl CurvatureForm for Vec2 {
    const SIGNED: bool = true;

    fn curvature(d1: &Vec2, d2: &Vec2) -> Option<f64> {
        let speed = d1.norm();
        if speed == 0.0 {
            return None;
        }
        finite(cross2(d1, d2) / (speed * speed * speed))
    }

    fn curvature_slope(d1: &Vec2, d2: &Vec2, d3: &Vec2) -> Option<f64> {
        let speed2 = d1.norm_squared();
        if speed2 == 0.0 {
            return None;
        }
        let numerator = cross2(d1, d3) * speed2 - 3.0 * cross2(d1, d2) * d1.dot(d2);
        // dκ/dt = numerator / |C′|⁵, then divide by |C′| for dκ/ds.
        finite(numerator / (speed2 * speed2 * speed2))
    }

    fn curvature_integrands(d1: &Vec2, d2: &Vec2, d3: &Vec2) -> Option<[f64; 2]> {
        // κ = N/|C′|³ and dκ/ds = M/q³ with q = |C′|², N = C′ × C″ and
        // M = (C′ × C‴) q − 3 N (C′ · C″) (see `curvature_slope`): κ²|C′| = N² r/q³ and
        // (dκ/ds)²|C′| = M² r/q⁶, r = √q.
        let q = d1.norm_squared();
        if q == 0.0 {
            return None;
        }
        let r = q.sqrt();
        let n = cross2(d1, d2);
        let m = cross2(d1, d3) * q - 3.0 * n * d1.dot(d2);
        let inverse = 1.0 / q;
        let cube = inverse * inverse * inverse;
        let ek = n * n * cube * r;
        let ek_prime = m * m * cube * cube * r;
        (ek.is_finite() && ek_prime.is_finite()).then_some([ek, ek_prime])
    }

    fn curvature_integrands_at<const N: usize>(taylor: &[Vec2; 3], u: &[f64; N], out: &mut [[f64; N]; 2]) {
        // `curvature_integrands` written per coordinate, with no early exit, so that the loop
        // vectorises; the arithmetic is the same, operation for operation.
        let [a, b, c] = taylor;
        let [ek_out, ek_prime_out] = out;
        for i in 0..N {
            let u = u[i];
            let half_u = 0.5 * u;
            let d1x = a.x + (b.x + c.x * half_u) * u;
            let d1y = a.y + (b.y + c.y * half_u) * u;
            let d2x = b.x + c.x * u;
            let d2y = b.y + c.y * u;
            let q = d1x * d1x + d1y * d1y;
            let r = q.sqrt();
            let n = d1x * d2y - d1y * d2x;
            let m = (d1x * c.y - d1y * c.x) * q - 3.0 * n * (d1x * d2x + d1y * d2y);
            let inverse = 1.0 / q;
            let cube = inverse * inverse * inverse;
            ek_out[i] = n * n * cube * r;
            ek_prime_out[i] = m * m * cube * cube * r;
        }
    }

    fn speed_poles(taylor: &[Vec2; 3], length: f64, push: &mut dyn FnMut(f64, f64)) {
        use nalgebra::Complex;
        let [a, b, c] = taylor;
        // z(u) = C′ₓ(u) + i C′ᵧ(u) = A + Bu + ½Cu².
        let (za, zb, zc) = (
            Complex::new(a.x, a.y),
            Complex::new(b.x, b.y),
            Complex::new(0.5 * c.x, 0.5 * c.y),
        );
        let mut roots = [Complex::new(f64::NAN, 0.0); 2];
        if zc.norm_sqr() > 0.0 {
            let disc = zb * zb - zc * za * 4.0;
            let mut root = disc.sqrt();
            if (zb.conj() * root).re < 0.0 {
                root = -root;
            }
            // The stable pair: q = −(B ± √D)/2 with the sign that avoids cancellation.
            let q = -(zb + root) * 0.5;
            if q.norm_sqr() > 0.0 {
                roots = [q / zc, za / q];
            } else {
                roots[0] = Complex::new(0.0, 0.0);
            }
        } else if zb.norm_sqr() > 0.0 {
            roots[0] = -za / zb;
        }
        for rho in roots {
            if !(rho.re.is_finite() && rho.im.is_finite()) {
                continue;
            }
            let centre = rho.re.clamp(0.0, length);
            let width = (rho.re - centre).hypot(rho.im).max(1e-14 * length);
            if width < length / 8.0 {
                push(centre, width);
            }
        }
    }
}

impl CurvatureForm for Vec3 {
    const SIGNED: bool = false;

    fn curvature(d1: &Vec3, d2: &Vec3) -> Option<f64> {
        let speed = d1.norm();
        if speed == 0.0 {
            return None;
        }
        finite(d1.cross(d2).norm() / (speed * speed * speed))
    }

    fn curvature_slope(d1: &Vec3, d2: &Vec3, d3: &Vec3) -> Option<f64> {
        let speed2 = d1.norm_squared();
        if speed2 == 0.0 {
            return None;
        }
        let b = d1.cross(d2);
        let b_prime = d1.cross(d3);
        let b_norm = b.norm();
        let first = if b_norm > 0.0 {
            b.dot(&b_prime) * speed2 / b_norm
        } else {
            0.0
        };
        let numerator = first - 3.0 * b_norm * d1.dot(d2);
        finite(numerator / (speed2 * speed2 * speed2))
    }

    fn curvature_integrands(d1: &Vec3, d2: &Vec3, d3: &Vec3) -> Option<[f64; 2]> {
        let speed = d1.norm();
        let k = Self::curvature(d1, d2)?;
        let slope = Self::curvature_slope(d1, d2, d3)?;
        Some([k * k * speed, slope * slope * speed])
    }

    fn curvature_integrands_at<const N: usize>(taylor: &[Vec3; 3], u: &[f64; N], out: &mut [[f64; N]; 2]) {
        // With q = |C′|², r = √q, b = C′ × C″, B = |b|², b′ = C′ × C‴ and p = C′ · C″:
        // κ²|C′| = B r / q³ and, from `curvature_slope`'s dκ/ds = ((b·b′) q/√B − 3√B p)/q³,
        // (dκ/ds)²|C′| = ((b·b′) q − 3 B p)² r / (B q⁶) — no square root of B, and 0 on a
        // straight stretch (B = 0), as there. Per coordinate with no early exit, so that the
        // loop vectorises.
        let [a, b, c] = taylor;
        let [ek_out, ek_prime_out] = out;
        for i in 0..N {
            let u = u[i];
            let half_u = 0.5 * u;
            let (d1x, d1y, d1z) = (
                a.x + (b.x + c.x * half_u) * u,
                a.y + (b.y + c.y * half_u) * u,
                a.z + (b.z + c.z * half_u) * u,
            );
            let (d2x, d2y, d2z) = (b.x + c.x * u, b.y + c.y * u, b.z + c.z * u);
            let q = d1x * d1x + d1y * d1y + d1z * d1z;
            let r = q.sqrt();
            let (bx, by, bz) = (
                d1y * d2z - d1z * d2y,
                d1z * d2x - d1x * d2z,
                d1x * d2y - d1y * d2x,
            );
            let (ex, ey, ez) = (
                d1y * c.z - d1z * c.y,
                d1z * c.x - d1x * c.z,
                d1x * c.y - d1y * c.x,
            );
            let big_b = bx * bx + by * by + bz * bz;
            let p = d1x * d2x + d1y * d2y + d1z * d2z;
            let m = (bx * ex + by * ey + bz * ez) * q - 3.0 * big_b * p;
            let inverse = 1.0 / q;
            let cube = inverse * inverse * inverse;
            ek_out[i] = big_b * cube * r;
            let slope = m * m * cube * cube * r / big_b;
            ek_prime_out[i] = if big_b > 0.0 { slope } else { 0.0 * cube };
        }
    }

    fn speed_poles(taylor: &[Vec3; 3], length: f64, push: &mut dyn FnMut(f64, f64)) {
        speed_minima(taylor, length, push)
    }
}

/// The minima u* of q(u) = |C′(u)|² on [0, `length`] for C′(u) = a + bu + cu²/2, with the
/// widths √(2q(u*)/q″(u*)) below `length`/8: the roots of the cubic C′·C″ = ½q′ where it
/// turns from negative to positive (bisection on its monotone stretches), or an end of the
/// piece. O(1).
fn speed_minima<const D: usize>(taylor: &[Vector<D>; 3], length: f64, push: &mut dyn FnMut(f64, f64)) {
    let [a, b, c] = taylor;
    if length.is_nan() || length <= 0.0 {
        return;
    }
    // p(u) = C′·C″ = a·b + (a·c + |b|²) u + 3/2 (b·c) u² + 1/2 |c|² u³.
    let k = [
        a.dot(b),
        a.dot(c) + b.norm_squared(),
        1.5 * b.dot(c),
        0.5 * c.norm_squared(),
    ];
    let p = |u: f64| k[0] + u * (k[1] + u * (k[2] + u * k[3]));
    // The stretches where p is monotone: split at the roots of p′ = B + 2Cu + 3Du².
    let mut cuts = [0.0, length, f64::NAN, f64::NAN];
    let (qa, qb, qc) = (3.0 * k[3], 2.0 * k[2], k[1]);
    if qa != 0.0 {
        let discriminant = qb * qb - 4.0 * qa * qc;
        if discriminant > 0.0 {
            let root = discriminant.sqrt();
            cuts[2] = (-qb - root) / (2.0 * qa);
            cuts[3] = (-qb + root) / (2.0 * qa);
        }
    } else if qb != 0.0 {
        cuts[2] = -qc / qb;
    }
    let cuts = {
        let mut kept = [0.0; 4];
        let mut n = 0;
        for u in cuts {
            if u.is_finite() && (0.0..=length).contains(&u) {
                kept[n] = u;
                n += 1;
            }
        }
        kept[..n].sort_by(f64::total_cmp);
        (kept, n)
    };
    let mut minima = [f64::NAN; 5];
    let mut count = 0;
    if p(0.0) > 0.0 {
        minima[count] = 0.0;
        count += 1;
    }
    if p(length) < 0.0 {
        minima[count] = length;
        count += 1;
    }
    for w in cuts.0[..cuts.1].windows(2) {
        let (mut low, mut high) = (w[0], w[1]);
        if !(p(low) < 0.0 && p(high) > 0.0) {
            continue;
        }
        // 40 halvings place u* within 1e-12 of the piece: far inside the narrowest width kept.
        for _ in 0..40 {
            let mid = 0.5 * (low + high);
            if mid <= low || mid >= high {
                break;
            }
            if p(mid) < 0.0 {
                low = mid;
            } else {
                high = mid;
            }
        }
        minima[count] = 0.5 * (low + high);
        count += 1;
    }
    for &centre in &minima[..count] {
        let speed = a + (b + c * (0.5 * centre)) * centre;
        let bend = b + c * centre;
        let q = speed.norm_squared();
        let curvature_of_q = 2.0 * (bend.norm_squared() + speed.dot(c));
        if curvature_of_q.is_nan() || curvature_of_q <= 0.0 {
            continue;
        }
        let width = (2.0 * q / curvature_of_q).sqrt().max(1e-14 * length);
        if width < length / 8.0 {
            push(centre, width);
        }
    }
}

/// κ at `t` from `side`; fails with [`Error::NonFinite`] where the tangent vanishes.
pub fn curvature_at<const D: usize, C>(curve: &C, t: f64, side: Side) -> Result<f64>
where
    C: Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    let jet = curve.jet(t, side);
    CurvatureForm::curvature(&jet[1], &jet[2]).ok_or(Error::NonFinite {
        what: "curvature",
        parameter: t,
    })
}

/// dκ/ds at `t` from `side`; fails with [`Error::NonFinite`] where the tangent vanishes.
pub fn curvature_slope_at<const D: usize, C>(curve: &C, t: f64, side: Side) -> Result<f64>
where
    C: Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    let jet = curve.jet(t, side);
    CurvatureForm::curvature_slope(&jet[1], &jet[2], &jet[3]).ok_or(Error::NonFinite {
        what: "curvature slope",
        parameter: t,
    })
}

/// κ at every break point (the knots), from the right (the last one from the only piece
/// there). κ is continuous at the knots of a C2 curve, so the side only matters for curves
/// that are not. O(n) plus the curve's evaluation cost.
pub fn curvature_at_breaks<const D: usize, C>(curve: &C) -> Result<Vec<f64>>
where
    C: Curve<D> + ?Sized,
    Vector<D>: CurvatureForm,
{
    curve
        .breaks()
        .into_iter()
        .map(|t| curvature_at(curve, t, Side::Right))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_curves::{Helix, Parabola, TwistedCubic};

    /// The vectorised node loop of a planar cubic piece gives the pointwise integrands bit
    /// for bit (the same operations), and a non-finite value where the tangent vanishes.
    #[test]
    fn planar_node_integrands_equal_the_pointwise_ones() {
        let taylor = [Vec2::new(0.3, -1.2), Vec2::new(2.5, 0.7), Vec2::new(-4.0, 9.0)];
        let u: [f64; 15] = std::array::from_fn(|i| -0.2 + 0.1 * i as f64);
        let mut out = [[0.0; 15]; 2];
        Vec2::curvature_integrands_at(&taylor, &u, &mut out);
        for (i, &u) in u.iter().enumerate() {
            let [a, b, c] = taylor;
            let d1 = a + (b + c * (0.5 * u)) * u;
            let d2 = b + c * u;
            let expected = Vec2::curvature_integrands(&d1, &d2, &c).unwrap();
            assert_eq!([out[0][i], out[1][i]], expected, "node {i}");
        }
        // C′(u) = (u, 0): the tangent vanishes at u = 0.
        let stop = [Vec2::zeros(), Vec2::new(1.0, 0.0), Vec2::new(0.0, 2.0)];
        let mut out = [[0.0; 1]; 2];
        Vec2::curvature_integrands_at(&stop, &[0.0], &mut out);
        assert!(!out[0][0].is_finite() || !out[1][0].is_finite());
    }

    /// The spatial node loop (its own algebra, with no square root of |C′ × C″|²) agrees with
    /// the pointwise κ²|C′| and (dκ/ds)²|C′| to round-off, gives 0 for (dκ/ds)² on a straight
    /// piece, and a non-finite value where the tangent vanishes.
    #[test]
    fn spatial_node_integrands_equal_the_pointwise_ones() {
        let taylor = [
            Vec3::new(0.3, -1.2, 0.5),
            Vec3::new(2.5, 0.7, -1.0),
            Vec3::new(-4.0, 9.0, 3.0),
        ];
        let u: [f64; 15] = std::array::from_fn(|i| -0.3 + 0.07 * i as f64);
        let mut out = [[0.0; 15]; 2];
        Vec3::curvature_integrands_at(&taylor, &u, &mut out);
        for (i, &u) in u.iter().enumerate() {
            let [a, b, c] = taylor;
            let expected =
                Vec3::curvature_integrands(&(a + (b + c * (0.5 * u)) * u), &(b + c * u), &c).unwrap();
            for k in 0..2 {
                let (got, want) = (out[k][i], expected[k]);
                assert!(
                    (got - want).abs() <= 1e-12 * want.abs(),
                    "node {i} integrand {k}: {got} vs {want}"
                );
            }
        }
        let straight = [Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.5, 1.0, 1.5), Vec3::zeros()];
        let mut out = [[f64::NAN; 2]; 2];
        Vec3::curvature_integrands_at(&straight, &[0.0, 0.5], &mut out);
        assert_eq!(out, [[0.0; 2]; 2]);
        let stop = [Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 1.0)];
        let mut out = [[0.0; 1]; 2];
        Vec3::curvature_integrands_at(&stop, &[0.0], &mut out);
        assert!(!out[0][0].is_finite() || !out[1][0].is_finite());
    }

    #[test]
    fn parabola_curvature_matches_closed_form() {
        for a in [0.5, -2.0, 3.0] {
            let p = Parabola {
                a,
                domain: (-2.0, 2.0),
            };
            for x in [-1.5, -0.3, 0.0, 0.7, 1.9] {
                let expected = 2.0 * a / (1.0 + 4.0 * a * a * x * x).powf(1.5);
                let k = curvature_at(&p, x, Side::Right).unwrap();
                assert!(
                    (k - expected).abs() <= 1e-14 * expected.abs().max(1.0),
                    "{k} {expected}"
                );
            }
        }
    }

    /// dκ/ds against a central difference of the closed-form κ(x) over the arc length
    /// ds = √(1 + 4a²x²) dx.
    #[test]
    fn parabola_curvature_slope_matches_finite_difference() {
        let a = 1.3;
        let p = Parabola {
            a,
            domain: (-2.0, 2.0),
        };
        let kappa = |x: f64| 2.0 * a / (1.0 + 4.0 * a * a * x * x).powf(1.5);
        let h = 1e-5;
        for x in [-1.2, -0.4, 0.0, 0.25, 1.1] {
            let dk_dx = (kappa(x + h) - kappa(x - h)) / (2.0 * h);
            let expected = dk_dx / (1.0 + 4.0 * a * a * x * x).sqrt();
            let slope = curvature_slope_at(&p, x, Side::Right).unwrap();
            assert!(
                (slope - expected).abs() <= 1e-8 * expected.abs().max(1.0),
                "{slope} {expected}"
            );
        }
    }

    #[test]
    fn helix_has_constant_curvature() {
        let helix = Helix {
            radius: 2.0,
            pitch: 0.5,
            domain: (0.0, 10.0),
        };
        let expected = 2.0 / (4.0 + 0.25);
        for t in [0.0, 1.0, 3.3, 9.9] {
            assert!((curvature_at(&helix, t, Side::Left).unwrap() - expected).abs() < 1e-15);
            assert!(curvature_slope_at(&helix, t, Side::Left).unwrap().abs() < 1e-15);
        }
    }

    /// The 3D form of dκ/ds against a central difference of κ along arc length.
    #[test]
    fn spatial_curvature_slope_matches_finite_difference() {
        let c = TwistedCubic;
        let h = 1e-5;
        for t in [-0.8, 0.1, 0.6, 1.4] {
            let k = |t: f64| curvature_at(&c, t, Side::Right).unwrap();
            let speed = c.jet(t, Side::Right)[1].norm();
            let expected = (k(t + h) - k(t - h)) / (2.0 * h) / speed;
            let slope = curvature_slope_at(&c, t, Side::Right).unwrap();
            assert!(
                (slope - expected).abs() <= 1e-8 * expected.abs().max(1.0),
                "{slope} {expected}"
            );
        }
    }

    #[test]
    fn vanishing_tangent_is_an_error() {
        // The cusp (t², t³): C′(0) = 0.
        let cusp = crate::test_curves::PowerCubic::<2> {
            coefficients: [
                Vec2::zeros(),
                Vec2::zeros(),
                Vec2::new(1.0, 0.0),
                Vec2::new(0.0, 1.0),
            ],
            domain: (-1.0, 1.0),
        };
        assert!(matches!(
            curvature_at(&cusp, 0.0, Side::Right),
            Err(Error::NonFinite { .. })
        ));
        assert!(curvature_slope_at(&cusp, 0.0, Side::Right).is_err());
    }
}
