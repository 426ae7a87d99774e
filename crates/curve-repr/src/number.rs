//! Numbers as people read them: [`Compact`].

use std::fmt;

/// Displays an f64 with the shortest digits that read back as the same value: positional for
/// 1e-5 ≤ |v| < 1e16 and 0 (Rust's `{}`, e.g. `0.25`), scientific outside (`1e-200`, where
/// `{}` would write 200 digits). Used in error messages and by the command's writers. O(1).
///
/// ```
/// use curve_repr::number::Compact;
/// assert_eq!(Compact(0.25).to_string(), "0.25");
/// assert_eq!(Compact(1e-200).to_string(), "1e-200");
/// assert_eq!(Compact(-4.5e300).to_string(), "-4.5e300");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compact(pub f64);

impl fmt::Display for Compact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let magnitude = v.abs();
        if magnitude == 0.0 || (1e-5..1e16).contains(&magnitude) || !v.is_finite() {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Compact;

    #[test]
    fn round_trips_in_a_readable_form() {
        let values = [
            0.0, -0.0, 1.0, -2.5, 0.1, 1e-5, 9.99e-6, 1e-200, -3.7e-301, 1e15, 1e16, 4.2e300, 5e-324,
        ];
        for v in values {
            let text = Compact(v).to_string();
            assert_eq!(text.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{v}: {text}");
            assert!(text.len() <= 24, "{v}: {text}");
        }
        assert_eq!(Compact(f64::INFINITY).to_string(), "inf");
    }
}
