//! [`Dual`]: a forward-mode dual number that implements `num_traits::Float`, so that code
//! written over `T: Float` (the rational curve evaluation of
//! [`curve_repr::nurbs_curve::generic`], the fixed-rule energies of `fairness::fixed_rule`)
//! differentiates itself.
//!
//! A dual number a + b ε with ε² = 0 carries a value and one directional derivative: for a
//! smooth f, f(a + b ε) = f(a) + f′(a) b ε. The calculus (every derivative rule: products,
//! quotients, sqrt, powers, exp, trigonometry …) is the crate `num-dual`'s (`Dual64`); this
//! type only adds the `num_traits::Float` interface that `num-dual` does not implement (it has
//! its own `DualNum` trait). Comparisons, rounding and classification look at the value
//! (the real part): piecewise-constant functions have derivative zero, `max`/`min` pick the
//! branch the value picks.
//!
//! ```
//! use num_traits::Float;
//! use optim::Dual;
//!
//! // d/dx (x² sin x) at x = 2
//! let x = Dual::variable(2.0);
//! let f = x.powi(2) * x.sin();
//! assert_eq!(f.value(), 4.0 * 2f64.sin());
//! assert!((f.derivative() - (4.0 * 2f64.sin() + 4.0 * 2f64.cos())).abs() < 1e-14);
//! ```

use std::cmp::Ordering;
use std::num::FpCategory;
use std::ops::{Add, Div, Mul, Neg, Rem, Sub};

use num_dual::{Dual64, DualNum};
use num_traits::{Float, Num, NumCast, One, ToPrimitive, Zero};

/// A forward-mode dual number value + derivative·ε (ε² = 0) over f64, implementing
/// `num_traits::Float`; the arithmetic and elementary functions are `num_dual::Dual64`'s.
#[derive(Clone, Copy, Debug)]
pub struct Dual(pub Dual64);

impl Dual {
    /// value + derivative·ε.
    pub fn new(value: f64, derivative: f64) -> Self {
        Dual(Dual64::new(value, derivative))
    }

    /// A constant (derivative 0).
    pub fn constant(value: f64) -> Self {
        Dual::new(value, 0.0)
    }

    /// The independent variable (derivative 1).
    pub fn variable(value: f64) -> Self {
        Dual::new(value, 1.0)
    }

    /// The value (real part).
    pub fn value(self) -> f64 {
        self.0.re
    }

    /// The derivative (ε part).
    pub fn derivative(self) -> f64 {
        self.0.eps
    }

    /// A function of the value only: derivative zero.
    fn flat(value: f64) -> Self {
        Dual::constant(value)
    }
}

impl PartialEq for Dual {
    fn eq(&self, other: &Self) -> bool {
        self.0.re == other.0.re
    }
}

impl PartialOrd for Dual {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        self.0.re.partial_cmp(&other.0.re)
    }
}

macro_rules! binary {
    ($($trait:ident $method:ident),*) => {$(
        impl $trait for Dual {
            type Output = Dual;
            #[inline]
            fn $method(self, rhs: Dual) -> Dual {
                Dual($trait::$method(self.0, rhs.0))
            }
        }
    )*};
}
binary!(Add add, Sub sub, Mul mul, Div div, Rem rem);

impl Neg for Dual {
    type Output = Dual;
    #[inline]
    fn neg(self) -> Dual {
        Dual(-self.0)
    }
}

impl Zero for Dual {
    fn zero() -> Self {
        Dual::constant(0.0)
    }
    fn is_zero(&self) -> bool {
        self.0.re == 0.0 && self.0.eps == 0.0
    }
}

impl One for Dual {
    fn one() -> Self {
        Dual::constant(1.0)
    }
}

impl Num for Dual {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(text: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(text, radix).map(Dual::constant)
    }
}

impl ToPrimitive for Dual {
    fn to_i64(&self) -> Option<i64> {
        self.0.re.to_i64()
    }
    fn to_u64(&self) -> Option<u64> {
        self.0.re.to_u64()
    }
    fn to_f64(&self) -> Option<f64> {
        Some(self.0.re)
    }
}

impl NumCast for Dual {
    fn from<N: ToPrimitive>(n: N) -> Option<Self> {
        n.to_f64().map(Dual::constant)
    }
}

macro_rules! unary {
    ($($method:ident),*) => {$(
        #[inline]
        fn $method(self) -> Self {
            Dual(DualNum::$method(&self.0))
        }
    )*};
}

impl Float for Dual {
    fn nan() -> Self {
        Dual::constant(f64::NAN)
    }
    fn infinity() -> Self {
        Dual::constant(f64::INFINITY)
    }
    fn neg_infinity() -> Self {
        Dual::constant(f64::NEG_INFINITY)
    }
    fn neg_zero() -> Self {
        Dual::constant(-0.0)
    }
    fn min_value() -> Self {
        Dual::constant(f64::MIN)
    }
    fn min_positive_value() -> Self {
        Dual::constant(f64::MIN_POSITIVE)
    }
    fn epsilon() -> Self {
        Dual::constant(f64::EPSILON)
    }
    fn max_value() -> Self {
        Dual::constant(f64::MAX)
    }
    /// NaN in the value or the derivative.
    fn is_nan(self) -> bool {
        self.0.re.is_nan() || self.0.eps.is_nan()
    }
    fn is_infinite(self) -> bool {
        self.0.re.is_infinite() || self.0.eps.is_infinite()
    }
    /// Value and derivative both finite.
    fn is_finite(self) -> bool {
        self.0.re.is_finite() && self.0.eps.is_finite()
    }
    fn is_normal(self) -> bool {
        self.0.re.is_normal()
    }
    fn classify(self) -> FpCategory {
        self.0.re.classify()
    }
    fn floor(self) -> Self {
        Dual::flat(self.0.re.floor())
    }
    fn ceil(self) -> Self {
        Dual::flat(self.0.re.ceil())
    }
    fn round(self) -> Self {
        Dual::flat(self.0.re.round())
    }
    fn trunc(self) -> Self {
        Dual::flat(self.0.re.trunc())
    }
    fn fract(self) -> Self {
        Dual::new(self.0.re.fract(), self.0.eps)
    }
    fn abs(self) -> Self {
        if self.0.re.is_sign_negative() {
            -self
        } else {
            self
        }
    }
    fn signum(self) -> Self {
        Dual::flat(self.0.re.signum())
    }
    fn is_sign_positive(self) -> bool {
        self.0.re.is_sign_positive()
    }
    fn is_sign_negative(self) -> bool {
        self.0.re.is_sign_negative()
    }
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    fn recip(self) -> Self {
        Dual(DualNum::recip(&self.0))
    }
    fn powi(self, n: i32) -> Self {
        Dual(DualNum::powi(&self.0, n))
    }
    /// x^y; with a varying exponent, exp(y ln x).
    fn powf(self, n: Self) -> Self {
        if n.0.eps == 0.0 {
            Dual(DualNum::powf(&self.0, n.0.re))
        } else {
            (n * self.ln()).exp()
        }
    }
    unary!(sqrt, exp, exp2, ln, log2, log10, cbrt, sin, cos, tan, asin, acos, atan, exp_m1, ln_1p);
    unary!(sinh, cosh, tanh, asinh, acosh, atanh);
    /// log_base(x) = ln x / ln base.
    fn log(self, base: Self) -> Self {
        self.ln() / base.ln()
    }
    /// The larger by value (NaN loses, as for f64).
    fn max(self, other: Self) -> Self {
        if self.0.re.is_nan() || other.0.re > self.0.re {
            other
        } else {
            self
        }
    }
    /// The smaller by value (NaN loses, as for f64).
    fn min(self, other: Self) -> Self {
        if self.0.re.is_nan() || other.0.re < self.0.re {
            other
        } else {
            self
        }
    }
    #[allow(deprecated)]
    fn abs_sub(self, other: Self) -> Self {
        if self.0.re <= other.0.re {
            Dual::zero()
        } else {
            self - other
        }
    }
    fn hypot(self, other: Self) -> Self {
        (self * self + other * other).sqrt()
    }
    fn atan2(self, other: Self) -> Self {
        Dual(DualNum::atan2(&self.0, other.0))
    }
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = DualNum::sin_cos(&self.0);
        (Dual(s), Dual(c))
    }
    fn integer_decode(self) -> (u64, i16, i8) {
        self.0.re.integer_decode()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central difference of f at x.
    fn central(f: impl Fn(f64) -> f64, x: f64) -> f64 {
        let h = 1e-6 * (1.0 + x.abs());
        (f(x + h) - f(x - h)) / (2.0 * h)
    }

    #[test]
    fn arithmetic_follows_the_defining_rules() {
        let (a, b) = (Dual::new(3.0, 0.5), Dual::new(-2.0, 4.0));
        // (a + a′ε)(b + b′ε) = ab + (a′b + ab′)ε, and so on; ε² = 0.
        let p = a * b;
        assert_eq!((p.value(), p.derivative()), (-6.0, 0.5 * -2.0 + 3.0 * 4.0));
        let q = a / b;
        assert_eq!(q.value(), -1.5);
        assert!((q.derivative() - (0.5 * -2.0 - 3.0 * 4.0) / 4.0).abs() < 1e-15);
        let s = a - b;
        assert_eq!((s.value(), s.derivative()), (5.0, -3.5));
        assert_eq!((-a).derivative(), -0.5);
        assert_eq!(<Dual as NumCast>::from(2.5f64).unwrap().derivative(), 0.0);
        // Order and equality look at the value only.
        assert_eq!(a.partial_cmp(&b), Some(Ordering::Greater));
        assert_eq!(a, Dual::new(3.0, 99.0));
    }

    #[test]
    fn elementary_functions_match_finite_differences() {
        type F = fn(Dual) -> Dual;
        type G = fn(f64) -> f64;
        let cases: [(F, G); 8] = [
            (|x| x.sqrt(), f64::sqrt),
            (|x| x.powi(5), |x| x.powi(5)),
            (|x| x.powf(Dual::constant(2.5)), |x| x.powf(2.5)),
            (|x| x.exp(), f64::exp),
            (|x| x.ln(), f64::ln),
            (|x| x.sin() * x.cos(), |x| x.sin() * x.cos()),
            (|x| x.atan2(Dual::constant(0.3)), |x| x.atan2(0.3)),
            (|x| x.hypot(Dual::constant(2.0)).recip(), |x| x.hypot(2.0).recip()),
        ];
        for (dual, real) in cases {
            for x in [0.3, 1.0, 2.7] {
                let d = dual(Dual::variable(x));
                assert_eq!(d.value().to_bits(), real(x).to_bits());
                let fd = central(real, x);
                assert!(
                    (d.derivative() - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                    "{x}: {} vs {fd}",
                    d.derivative()
                );
            }
        }
        // abs and max/min keep the branch's derivative; rounding has none.
        assert_eq!(Dual::new(-2.0, 3.0).abs().derivative(), -3.0);
        assert_eq!(Dual::new(1.0, 3.0).max(Dual::new(0.5, 7.0)).derivative(), 3.0);
        assert_eq!(Dual::new(1.0, 3.0).min(Dual::new(0.5, 7.0)).derivative(), 7.0);
        assert_eq!(Dual::new(1.7, 3.0).floor().derivative(), 0.0);
        assert!(Dual::new(1.0, f64::NAN).is_nan() && !Dual::new(1.0, f64::INFINITY).is_finite());
    }
}
