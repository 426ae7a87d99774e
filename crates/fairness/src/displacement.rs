//! Han's displacement norms between data points and faired points (Han §5):
//! S_d = Σ |P̃_i − P_i| (the 1-norm of the displacement lengths) and
//! M_d = max |P̃_i − P_i| (their ∞-norm).

use curve_repr::Vector;

use crate::{Error, Result};

/// S_d and M_d of one fairing.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Displacement {
    /// S_d = Σ |P̃_i − P_i|.
    pub s_d: f64,
    /// M_d = max |P̃_i − P_i| (0 for no points).
    pub m_d: f64,
}

impl Displacement {
    /// S_d and M_d between `original` and `faired`, point by point. O(n).
    ///
    /// Fails on lengths that differ or non-finite coordinates.
    pub fn between<const D: usize>(original: &[Vector<D>], faired: &[Vector<D>]) -> Result<Self> {
        if original.len() != faired.len() {
            return Err(Error::LengthMismatch {
                what: "faired points (one per original point)",
                expected: original.len(),
                got: faired.len(),
            });
        }
        curve_repr::vector::check_finite(original)?;
        curve_repr::vector::check_finite(faired)?;
        let mut result = Displacement::default();
        for (p, q) in original.iter().zip(faired) {
            let d = (q - p).norm();
            result.s_d += d;
            result.m_d = result.m_d.max(d);
        }
        if result.s_d.is_finite() {
            Ok(result)
        } else {
            Err(Error::NonFinite {
                what: "displacement sum",
                parameter: f64::NAN,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    #[test]
    fn sums_and_maximum_of_distances() {
        let a = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, 0.0)];
        let b = [Vec2::new(3.0, 4.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, -1.0)];
        let d = Displacement::between(&a, &b).unwrap();
        assert_eq!(d, Displacement { s_d: 6.0, m_d: 5.0 });
        let d = Displacement::between(&[Vec3::new(1.0, 2.0, 2.0)], &[Vec3::zeros()]).unwrap();
        assert_eq!(d, Displacement { s_d: 3.0, m_d: 3.0 });
        assert_eq!(
            Displacement::between::<2>(&[], &[]).unwrap(),
            Displacement::default()
        );
    }

    #[test]
    fn mismatched_or_non_finite_input_is_an_error() {
        let a = [Vec2::zeros(), Vec2::zeros()];
        assert!(matches!(
            Displacement::between(&a, &a[..1]),
            Err(Error::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ));
        let nan = [Vec2::zeros(), Vec2::new(f64::NAN, 0.0)];
        assert!(matches!(Displacement::between(&a, &nan), Err(Error::Curve(_))));
        let huge = [Vec2::new(f64::MAX, 0.0), Vec2::new(f64::MAX, 0.0)];
        let minus = [Vec2::new(-f64::MAX, 0.0), Vec2::new(-f64::MAX, 0.0)];
        assert!(Displacement::between(&huge, &minus).is_err());
    }
}
