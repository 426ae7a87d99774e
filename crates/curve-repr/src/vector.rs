//! Point and vector types: nalgebra's statically sized column vectors of `f64`.

/// A point or vector in `D` dimensions.
pub type Vector<const D: usize> = nalgebra::SVector<f64, D>;
/// A planar point or vector.
pub type Vec2 = Vector<2>;
/// A spatial point or vector.
pub type Vec3 = Vector<3>;

/// Checks that every coordinate of every point is finite.
///
/// Returns the index of the first offending point as [`Error::NonFinite`](crate::Error::NonFinite).
pub fn check_finite<const D: usize>(points: &[Vector<D>]) -> crate::Result<()> {
    match points.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        Some(index) => Err(crate::Error::NonFinite { what: "point", index }),
        None => Ok(()),
    }
}

/// Checks that the values strictly increase; `what` names the sequence in the error
/// ([`Error::NotIncreasing`](crate::Error::NotIncreasing) at the first value not above its
/// predecessor). Check finiteness first ([`check_finite_values`]): a NaN compares false.
pub fn check_increasing_values(what: &'static str, values: &[f64]) -> crate::Result<()> {
    match values.windows(2).position(|w| w[1] - w[0] <= 0.0) {
        Some(index) => Err(crate::Error::NotIncreasing {
            what,
            index: index + 1,
            previous: values[index],
            value: values[index + 1],
        }),
        None => Ok(()),
    }
}

/// Checks that every value is finite; `what` names the sequence in the error.
pub fn check_finite_values(what: &'static str, values: &[f64]) -> crate::Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(crate::Error::NonFinite { what, index }),
        None => Ok(()),
    }
}
