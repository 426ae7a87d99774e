//! Numbers in CAD files: the shortest decimal that reads back as the same `f64`.
//!
//! IGES and STEP want a decimal point in every real (`1.`, not `1`) and an upper-case `E`
//! exponent; DXF takes any decimal. [`real`] writes Rust's shortest round-trip digits
//! (positional for 1e-5 ≤ |v| < 1e15, scientific outside) in that form, so that every value
//! written reads back bit for bit with any correctly rounded reader (Rust's, glibc's
//! `strtod`, Python's `float`); [`parse_real`] reads them back, and also Fortran's `D`
//! exponent, which IGES allows.

/// The shortest decimal of `v` that reads back as `v`, always with a decimal point, with an
/// upper-case `E` exponent outside 1e-5 ≤ |v| < 1e15 (e.g. `0.25`, `-3.`, `1.5E-07`,
/// `1.E300`). Callers pass finite values. O(1).
///
/// ```
/// use cad::number::{parse_real, real};
/// assert_eq!(real(0.25), "0.25");
/// assert_eq!(real(-3.0), "-3.");
/// assert_eq!(real(1.5e-7), "1.5E-7");
/// assert_eq!(real(1e300), "1.E300");
/// assert_eq!(parse_real("1.5D-7"), Some(1.5e-7));
/// ```
pub fn real(v: f64) -> String {
    let magnitude = v.abs();
    if magnitude == 0.0 || (1e-5..1e15).contains(&magnitude) {
        let mut text = format!("{v}");
        if !text.contains('.') {
            text.push('.');
        }
        text
    } else {
        let text = format!("{v:e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let dot = if mantissa.contains('.') { "" } else { "." };
        format!("{mantissa}{dot}E{exponent}")
    }
}

/// Reads a real as IGES, STEP or DXF write it: optional sign, digits with an optional
/// decimal point, an optional exponent with `E`, `e`, `D` or `d`. `None` for anything else
/// (and for non-finite results). O(length).
pub fn parse_real(text: &str) -> Option<f64> {
    let text = text.trim();
    if text.is_empty() || text.contains(|c: char| c.is_ascii_alphabetic() && !"EeDd".contains(c)) {
        return None;
    }
    let normal: String = text
        .chars()
        .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
        .collect();
    normal.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_value_reads_back_bit_for_bit() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1.0 / 3.0,
            -2.0 / 3.0,
            1e-5,
            9.999999999999999e-6,
            1e15,
            999999999999999.9,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            -1.2345678901234567e-300,
            std::f64::consts::PI * 1e20,
        ];
        for v in values {
            let text = real(v);
            assert!(text.contains('.'), "{text}");
            assert!(!text.contains('e'), "{text}");
            assert!(text.len() <= 24, "{text}");
            assert_eq!(parse_real(&text).unwrap().to_bits(), v.to_bits(), "{v}: {text}");
        }
        let mut state = 0x1234_5678_9abc_def0_u64;
        for _ in 0..20000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = f64::from_bits(state);
            if v.is_finite() {
                assert_eq!(parse_real(&real(v)).unwrap().to_bits(), v.to_bits(), "{v:e}");
            }
        }
    }

    #[test]
    fn other_spellings_read() {
        assert_eq!(parse_real("1."), Some(1.0));
        assert_eq!(parse_real(".5"), Some(0.5));
        assert_eq!(parse_real("+2.5d3"), Some(2500.0));
        assert_eq!(parse_real(" 7 "), Some(7.0));
        assert_eq!(parse_real("1.E-07"), Some(1e-7));
        assert_eq!(parse_real("abc"), None);
        assert_eq!(parse_real("1e999"), None);
        assert_eq!(parse_real(""), None);
        assert_eq!(parse_real("nan"), None);
    }
}
