//! Test-only curves and surfaces with closed-form derivatives.

use curve_repr::{Curve, Side, Surface, Vec2, Vec3, Vector};

/// C(t) = a₀ + a₁t + a₂t² + a₃t³ (a cubic Bézier segment in power form) on `domain`.
#[derive(Clone, Debug)]
pub(crate) struct PowerCubic<const D: usize> {
    pub coefficients: [Vector<D>; 4],
    pub domain: (f64, f64),
}

impl<const D: usize> PowerCubic<D> {
    /// The Bézier segment with control points `b` on [0, 1]:
    /// a₀ = B₀, a₁ = 3(B₁ − B₀), a₂ = 3(B₂ − 2B₁ + B₀), a₃ = B₃ − 3B₂ + 3B₁ − B₀.
    pub(crate) fn bezier(b: [Vector<D>; 4]) -> Self {
        PowerCubic {
            coefficients: [
                b[0],
                (b[1] - b[0]) * 3.0,
                (b[2] - b[1] * 2.0 + b[0]) * 3.0,
                b[3] - b[2] * 3.0 + b[1] * 3.0 - b[0],
            ],
            domain: (0.0, 1.0),
        }
    }
}

fn cubic_jet<const D: usize>(a: &[Vector<D>; 4], t: f64) -> [Vector<D>; 4] {
    [
        a[0] + (a[1] + (a[2] + a[3] * t) * t) * t,
        a[1] + (a[2] * 2.0 + a[3] * (3.0 * t)) * t,
        a[2] * 2.0 + a[3] * (6.0 * t),
        a[3] * 6.0,
    ]
}

impl<const D: usize> Curve<D> for PowerCubic<D> {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn jet(&self, t: f64, _side: Side) -> [Vector<D>; 4] {
        cubic_jet(&self.coefficients, t)
    }
    fn breaks(&self) -> Vec<f64> {
        vec![self.domain.0, self.domain.1]
    }
}

/// C(θ) = centre + r (cos θ, sin θ), θ in `angles`.
#[derive(Clone, Debug)]
pub(crate) struct CircleArc {
    pub centre: Vec2,
    pub radius: f64,
    pub angles: (f64, f64),
}

impl Curve<2> for CircleArc {
    fn domain(&self) -> (f64, f64) {
        self.angles
    }
    fn jet(&self, t: f64, _side: Side) -> [Vec2; 4] {
        let (s, c) = t.sin_cos();
        let r = self.radius;
        [
            self.centre + Vec2::new(r * c, r * s),
            Vec2::new(-r * s, r * c),
            Vec2::new(-r * c, -r * s),
            Vec2::new(r * s, -r * c),
        ]
    }
    fn breaks(&self) -> Vec<f64> {
        vec![self.angles.0, self.angles.1]
    }
}

/// The graph (x, a x²).
#[derive(Clone, Debug)]
pub(crate) struct Parabola {
    pub a: f64,
    pub domain: (f64, f64),
}

impl Curve<2> for Parabola {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn jet(&self, x: f64, _side: Side) -> [Vec2; 4] {
        [
            Vec2::new(x, self.a * x * x),
            Vec2::new(1.0, 2.0 * self.a * x),
            Vec2::new(0.0, 2.0 * self.a),
            Vec2::zeros(),
        ]
    }
    fn breaks(&self) -> Vec<f64> {
        vec![self.domain.0, self.domain.1]
    }
}

/// (r cos t, r sin t, p t): κ = r / (r² + p²), dκ/ds = 0.
#[derive(Clone, Debug)]
pub(crate) struct Helix {
    pub radius: f64,
    pub pitch: f64,
    pub domain: (f64, f64),
}

impl Curve<3> for Helix {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn jet(&self, t: f64, _side: Side) -> [Vec3; 4] {
        let (s, c) = t.sin_cos();
        let r = self.radius;
        [
            Vec3::new(r * c, r * s, self.pitch * t),
            Vec3::new(-r * s, r * c, self.pitch),
            Vec3::new(-r * c, -r * s, 0.0),
            Vec3::new(r * s, -r * c, 0.0),
        ]
    }
    fn breaks(&self) -> Vec<f64> {
        vec![self.domain.0, self.domain.1]
    }
}

/// The twisted cubic (t, t², t³) on [−1, 2].
#[derive(Clone, Debug)]
pub(crate) struct TwistedCubic;

impl Curve<3> for TwistedCubic {
    fn domain(&self) -> (f64, f64) {
        (-1.0, 2.0)
    }
    fn jet(&self, t: f64, _side: Side) -> [Vec3; 4] {
        [
            Vec3::new(t, t * t, t * t * t),
            Vec3::new(1.0, 2.0 * t, 3.0 * t * t),
            Vec3::new(0.0, 2.0, 6.0 * t),
            Vec3::new(0.0, 0.0, 6.0),
        ]
    }
    fn breaks(&self) -> Vec<f64> {
        vec![-1.0, 2.0]
    }
}

/// A piecewise cubic: on [t_i, t_{i+1}], C(t) = Σ_k a_{i,k} (t − t_i)^k.
#[derive(Clone, Debug)]
pub(crate) struct PiecewiseCubic<const D: usize> {
    pub breaks: Vec<f64>,
    pub pieces: Vec<[Vector<D>; 4]>,
}

impl<const D: usize> PiecewiseCubic<D> {
    /// The C2 piecewise cubic starting with value, C′, C″ = `start` at `breaks[0]` whose
    /// constant third derivative on piece i is `third[i]`: value, C′ and C″ carry over each
    /// break, so C‴ jumps by exactly `third[i] − third[i−1]` at `breaks[i]`.
    pub(crate) fn c2_from_third_derivatives(
        breaks: Vec<f64>,
        start: [Vector<D>; 3],
        third: &[Vector<D>],
    ) -> Self {
        let mut pieces = Vec::with_capacity(third.len());
        let [mut p, mut d1, mut d2] = start;
        for (i, d3) in third.iter().enumerate() {
            let a = [p, d1, d2 * 0.5, d3 / 6.0];
            let h = breaks[i + 1] - breaks[i];
            let jet = cubic_jet(&a, h);
            p = jet[0];
            d1 = jet[1];
            d2 = jet[2];
            pieces.push(a);
        }
        PiecewiseCubic { breaks, pieces }
    }

    fn piece(&self, t: f64, side: Side) -> usize {
        let last = self.pieces.len() - 1;
        // Index of the first break strictly greater than t (Right) or ≥ t (Left).
        let upper = match side {
            Side::Right => self.breaks.partition_point(|b| *b <= t),
            Side::Left => self.breaks.partition_point(|b| *b < t),
        };
        upper.saturating_sub(1).min(last)
    }
}

impl<const D: usize> Curve<D> for PiecewiseCubic<D> {
    fn domain(&self) -> (f64, f64) {
        (self.breaks[0], self.breaks[self.breaks.len() - 1])
    }
    fn jet(&self, t: f64, side: Side) -> [Vector<D>; 4] {
        let i = self.piece(t, side);
        cubic_jet(&self.pieces[i], t - self.breaks[i])
    }
    fn breaks(&self) -> Vec<f64> {
        self.breaks.clone()
    }
}

/// A scalar C2 piecewise cubic with one third-derivative jump:
/// f(u) = α u³/6 + (β − α)(u − k)₊³/6, so f‴ = α before k and β after.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Kinked {
    pub alpha: f64,
    pub beta: f64,
    pub knot: f64,
}

impl Kinked {
    /// f^(order)(u) from `side` (orders 0–3).
    pub(crate) fn derivative(&self, u: f64, order: usize, side: Side) -> f64 {
        let after = u > self.knot || (u == self.knot && side == Side::Right);
        let d = if after { u - self.knot } else { 0.0 };
        let jump = self.beta - self.alpha;
        match order {
            0 => self.alpha * u.powi(3) / 6.0 + jump * d.powi(3) / 6.0,
            1 => self.alpha * u * u / 2.0 + jump * d * d / 2.0,
            2 => self.alpha * u + jump * d,
            3 => {
                if after {
                    self.beta
                } else {
                    self.alpha
                }
            }
            _ => 0.0,
        }
    }
}

/// The height surface S(u, v) = (u, v, f(u) + g(v) + c u² v).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HeightSurface {
    pub f: Kinked,
    pub g: Kinked,
    pub c: f64,
    pub domain: ((f64, f64), (f64, f64)),
}

impl Surface for HeightSurface {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        self.domain
    }
    fn partial_from(&self, u: f64, v: f64, du: usize, dv: usize, su: Side, sv: Side) -> Option<Vec3> {
        if du > 3 || dv > 3 {
            return None;
        }
        let c = self.c;
        // c u² v: its partials.
        let cross = match (du, dv) {
            (0, 0) => c * u * u * v,
            (1, 0) => 2.0 * c * u * v,
            (0, 1) => c * u * u,
            (2, 0) => 2.0 * c * v,
            (1, 1) => 2.0 * c * u,
            (2, 1) => 2.0 * c,
            _ => 0.0,
        };
        let height = match (du, dv) {
            (0, 0) => self.f.derivative(u, 0, su) + self.g.derivative(v, 0, sv),
            (k, 0) => self.f.derivative(u, k, su),
            (0, k) => self.g.derivative(v, k, sv),
            _ => 0.0,
        } + cross;
        let x = match (du, dv) {
            (0, 0) => u,
            (1, 0) => 1.0,
            _ => 0.0,
        };
        let y = match (du, dv) {
            (0, 0) => v,
            (0, 1) => 1.0,
            _ => 0.0,
        };
        Some(Vec3::new(x, y, height))
    }
}
