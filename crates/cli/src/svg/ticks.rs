//! Nice axis ticks (steps of 1, 2 or 5 times a power of ten) and their labels.

/// Ticks inside `[min, max]` about `target` apart in count, at multiples of a nice step.
///
/// A degenerate or non-finite range gives no ticks. At most a few times `target` ticks.
pub fn nice_ticks(min: f64, max: f64, target: usize) -> Vec<f64> {
    let step = nice_step(min, max, target);
    if step <= 0.0 {
        return Vec::new();
    }
    let first = (min / step).ceil();
    let last = (max / step).floor();
    if !(first.is_finite() && last.is_finite()) || last < first || last - first > 1000.0 {
        return Vec::new();
    }
    let count = (last - first) as usize + 1;
    (0..count)
        .map(|k| {
            let t = (first + k as f64) * step;
            if t.abs() < step * 1e-9 {
                0.0
            } else {
                t
            }
        })
        .collect()
}

/// The nice step for about `target` intervals over `[min, max]`, or 0 for a degenerate range.
pub fn nice_step(min: f64, max: f64, target: usize) -> f64 {
    let span = max - min;
    if !(span.is_finite() && span > 0.0) || target == 0 {
        return 0.0;
    }
    let raw = span / target as f64;
    let magnitude = 10f64.powf(raw.log10().floor());
    let normalised = raw / magnitude;
    let nice = if normalised < 1.5 {
        1.0
    } else if normalised < 3.0 {
        2.0
    } else if normalised < 7.0 {
        5.0
    } else {
        10.0
    };
    nice * magnitude
}

/// Labels for ticks with the given step: enough decimals to tell them apart, or scientific
/// notation for very large or very small values.
pub fn labels(ticks: &[f64], step: f64) -> Vec<String> {
    let largest = ticks.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    let scientific = largest >= 1e6 || (step > 0.0 && step < 1e-4);
    let decimals = if step > 0.0 {
        (-step.log10().floor()).clamp(0.0, 12.0) as usize
    } else {
        0
    };
    ticks
        .iter()
        .map(|t| {
            if *t == 0.0 {
                "0".to_string()
            } else if scientific {
                let text = format!("{t:.2e}");
                // 1.50e3 -> 1.5e3, 2.00e-5 -> 2e-5
                match text.split_once('e') {
                    Some((mantissa, exponent)) => {
                        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
                        format!("{mantissa}e{exponent}")
                    }
                    None => text,
                }
            } else {
                format!("{t:.decimals$}")
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_one_two_five() {
        for (min, max) in [
            (0.0, 1.0),
            (-3.7, 12.2),
            (1e-6, 3e-6),
            (0.0, 12345.0),
            (-1.0, -0.99),
        ] {
            for target in [3, 5, 8] {
                let step = nice_step(min, max, target);
                let mantissa = step / 10f64.powf(step.log10().floor());
                assert!(
                    [1.0, 2.0, 5.0, 10.0].iter().any(|m| (mantissa - m).abs() < 1e-9),
                    "{min} {max} {step}"
                );
                let ticks = nice_ticks(min, max, target);
                assert!(ticks.len() >= 2 && ticks.len() <= 3 * target, "{ticks:?}");
                assert!(ticks.iter().all(|t| *t >= min - 1e-12 && *t <= max + 1e-12));
                for w in ticks.windows(2) {
                    assert!(((w[1] - w[0]) - step).abs() < step * 1e-9);
                }
            }
        }
    }

    #[test]
    fn degenerate_ranges_give_nothing() {
        assert!(nice_ticks(1.0, 1.0, 5).is_empty());
        assert!(nice_ticks(f64::NAN, 1.0, 5).is_empty());
        assert!(nice_ticks(0.0, f64::INFINITY, 5).is_empty());
    }

    #[test]
    fn labels_are_distinct_and_short() {
        let ticks = nice_ticks(0.0, 1.0, 5);
        let l = labels(&ticks, nice_step(0.0, 1.0, 5));
        assert_eq!(l, ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        let l = labels(&[1e6, 2e6], 1e6);
        assert_eq!(l, ["1e6", "2e6"]);
        let l = labels(&[-2e-5, 0.0, 2e-5], 2e-5);
        assert_eq!(l, ["-2e-5", "0", "2e-5"]);
    }
}
