//! How data points get their curve parameters.

use crate::{Error, Result, Vector};

/// The rule that assigns a parameter t_i to each data point P_i.
///
/// With t_0 = 0 and t_{i+1} = t_i + d_i:
/// - `Uniform`: d_i = 1 (Kjellander's parameters);
/// - `ChordLength`: d_i = |P_{i+1} − P_i| (Poliakoff's, Zhang–Cheng's and the report's);
/// - `Centripetal`: d_i = |P_{i+1} − P_i|^½ (Lee's, cf. The NURBS Book Eq. 9.6 with e = ½).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Parametrization {
    /// Equal steps of 1.
    Uniform,
    /// Steps equal to the chord lengths.
    #[default]
    ChordLength,
    /// Steps equal to the square roots of the chord lengths.
    Centripetal,
}

impl Parametrization {
    /// The parameter step between two consecutive points.
    fn step<const D: usize>(self, a: &Vector<D>, b: &Vector<D>) -> f64 {
        match self {
            Parametrization::Uniform => 1.0,
            Parametrization::ChordLength => distance(a, b),
            Parametrization::Centripetal => distance(a, b).sqrt(),
        }
    }

    /// Parameters t_0 = 0, …, t_{n−1} of an open curve through `points`. O(n).
    ///
    /// Chord lengths are computed without under- or overflow of the squares ([`distance`]),
    /// so points 1e-300 apart get steps of 1e-300, not 0.
    ///
    /// Fails on non-finite coordinates and, for chord-length and centripetal parameters, on
    /// two consecutive points that coincide (a zero step); uniform parameters reject them too,
    /// since no interpolant through a repeated point is a regular curve.
    pub fn parameters<const D: usize>(self, points: &[Vector<D>]) -> Result<Vec<f64>> {
        crate::vector::check_finite(points)?;
        let mut t = Vec::with_capacity(points.len());
        if points.is_empty() {
            return Ok(t);
        }
        t.push(0.0);
        for (i, w) in points.windows(2).enumerate() {
            if w[0] == w[1] {
                return Err(Error::RepeatedPoint { index: i });
            }
            let step = self.step(&w[0], &w[1]);
            if !step.is_finite() {
                return Err(Error::DistanceOverflow { index: i });
            }
            let last = t[i];
            t.push(last + step);
        }
        Ok(t)
    }

    /// Parameters of a closed curve: n + 1 values, the last one that of the first point
    /// reached again after the closing segment P_{n−1} → P_0. O(n).
    pub fn closed_parameters<const D: usize>(self, points: &[Vector<D>]) -> Result<Vec<f64>> {
        let mut t = self.parameters(points)?;
        if let (Some(first), Some(last)) = (points.first(), points.last()) {
            if first == last {
                return Err(Error::ClosingRepeat {
                    last: points.len() - 1,
                });
            }
            let step = self.step(last, first);
            if !step.is_finite() {
                return Err(Error::DistanceOverflow {
                    index: points.len() - 1,
                });
            }
            let end = t[t.len() - 1] + step;
            t.push(end);
        }
        Ok(t)
    }

    /// Parameters scaled to [0, 1] (the convention of The NURBS Book and geomdl). O(n).
    pub fn normalized_parameters<const D: usize>(self, points: &[Vector<D>]) -> Result<Vec<f64>> {
        let mut t = self.parameters(points)?;
        if let Some(&total) = t.last() {
            if total > 0.0 {
                t.iter_mut().for_each(|v| *v /= total);
                if let Some(last) = t.last_mut() {
                    *last = 1.0;
                }
            }
        }
        Ok(t)
    }
}

/// |b − a| without under- or overflow of the squares: the difference is scaled by its largest
/// component first (nalgebra's `norm` squares it directly, so a difference of 1e-170 came out
/// 0). O(D).
pub fn distance<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> f64 {
    let d = b - a;
    let scale = d.amax();
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    scale * (d / scale).norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec2;

    #[test]
    fn chord_length_steps_are_distances() {
        let p = [Vec2::new(0.0, 0.0), Vec2::new(3.0, 4.0), Vec2::new(3.0, 5.0)];
        let t = Parametrization::ChordLength.parameters(&p).unwrap();
        assert_eq!(t, vec![0.0, 5.0, 6.0]);
        let c = Parametrization::Centripetal.parameters(&p).unwrap();
        assert!((c[1] - 5f64.sqrt()).abs() < 1e-15 && (c[2] - c[1] - 1.0).abs() < 1e-15);
        let n = Parametrization::ChordLength.normalized_parameters(&p).unwrap();
        assert_eq!(n[2], 1.0);
        assert!((n[1] - 5.0 / 6.0).abs() < 1e-15);
        let closed = Parametrization::ChordLength.closed_parameters(&p).unwrap();
        assert!((closed[3] - (6.0 + 34f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn extreme_scales_keep_their_steps_or_say_why_not() {
        // Squares of 1e-300 underflow; the scaled distance does not.
        let tiny = [
            Vec2::new(0.0, 0.0),
            Vec2::new(3e-300, 4e-300),
            Vec2::new(6e-300, 8e-300),
        ];
        let t = Parametrization::ChordLength.parameters(&tiny).unwrap();
        assert!(
            (t[1] / 5e-300 - 1.0).abs() < 1e-15 && (t[2] / 1e-299 - 1.0).abs() < 1e-15,
            "{t:?}"
        );
        assert!((distance(&Vec2::new(0.0, 0.0), &Vec2::new(3e200, 4e200)) / 5e200 - 1.0).abs() < 1e-15);
        // A difference past f64::MAX cannot be held: said so, not "coincide".
        let huge = [Vec2::new(0.0, -1e308), Vec2::new(0.0, 1e308)];
        assert_eq!(
            Parametrization::ChordLength.parameters(&huge),
            Err(Error::DistanceOverflow { index: 0 })
        );
        // A closed curve with its first point repeated at the end names the last point.
        let closed = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 0.0),
        ];
        let e = Parametrization::ChordLength
            .closed_parameters(&closed)
            .unwrap_err();
        assert_eq!(e, Error::ClosingRepeat { last: 3 });
        assert!(e.to_string().contains("index 3") && e.to_string().contains("repeats the first"));
    }

    #[test]
    fn repeated_and_non_finite_points_are_rejected() {
        let p = [Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0)];
        assert_eq!(
            Parametrization::Uniform.parameters(&p),
            Err(Error::RepeatedPoint { index: 0 })
        );
        let q = [Vec2::new(0.0, 0.0), Vec2::new(f64::NAN, 0.0)];
        assert_eq!(
            Parametrization::ChordLength.parameters(&q),
            Err(Error::NonFinite {
                what: "point",
                index: 1
            })
        );
    }
}
