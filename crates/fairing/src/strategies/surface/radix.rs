//! The sorted sweep's order (Zhang–Cheng §4.4 step 2.3: every point once, by z_ij at the
//! step's start, largest first, ties by index) by a least-significant-digit radix sort.
//!
//! A comparison sort spends O(log n) comparisons per point, the one per-point cost of a step
//! that would grow with the grid; the radix sort spends at most eight passes of 8 bits, and skips a
//! pass whose digit every key shares (the sign and the top of the exponent, on any net whose
//! z are within a few binades of each other). The order is the same: no two entries are
//! equal (the indices differ), so every correct sort gives the same sequence.

/// Digits per pass.
const BITS: u32 = 8;
/// Buckets per pass.
const BUCKETS: usize = 1 << BITS;
/// Passes over a 64-bit key.
const PASSES: usize = 64 / BITS as usize;

/// The unsigned key whose ascending order is `f64::total_cmp`'s descending order: the sign
/// bit flipped on non-negative values and every bit on negative ones gives total_cmp's
/// order, and the complement reverses it.
fn descending_key(z: f64) -> u64 {
    let bits = z.to_bits();
    let ascending = if bits >> 63 == 1 { !bits } else { bits | 1 << 63 };
    !ascending
}

/// Sorts `(z, index)` pairs by z descending (`f64::total_cmp`), pairs of equal z kept in
/// their order in `items` (stable): given in ascending index, the order of
/// `sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)))`. `scratch` is storage
/// reused from call to call (it may end up holding the sorted pairs' old storage). O(n): one
/// read for the histograms of every pass, one scatter per pass not skipped.
pub(super) fn sort_descending(items: &mut Vec<(f64, usize)>, scratch: &mut Vec<(f64, usize)>) {
    let n = items.len();
    if n < 2 {
        return;
    }
    let mut counts = [[0usize; BUCKETS]; PASSES];
    for &(z, _) in items.iter() {
        let key = descending_key(z);
        for (pass, count) in counts.iter_mut().enumerate() {
            count[digit(key, pass)] += 1;
        }
    }
    scratch.clear();
    scratch.resize(n, (0.0, 0));
    for (pass, count) in counts.iter().enumerate() {
        // One digit for all: the pass would leave the order as it is.
        if count.contains(&n) {
            continue;
        }
        let mut next = [0usize; BUCKETS];
        let mut sum = 0;
        for (start, &c) in next.iter_mut().zip(count) {
            *start = sum;
            sum += c;
        }
        for &item in items.iter() {
            let d = digit(descending_key(item.0), pass);
            scratch[next[d]] = item;
            next[d] += 1;
        }
        std::mem::swap(items, scratch);
    }
}

/// Digit `pass` (from the least significant) of `key`.
fn digit(key: u64, pass: usize) -> usize {
    ((key >> (pass as u32 * BITS)) & (BUCKETS as u64 - 1)) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The comparison sort the radix sort replaces.
    fn compared(items: &[(f64, usize)]) -> Vec<(f64, usize)> {
        let mut sorted = items.to_vec();
        sorted.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        sorted
    }

    fn bits(items: &[(f64, usize)]) -> Vec<(u64, usize)> {
        items.iter().map(|&(z, k)| (z.to_bits(), k)).collect()
    }

    #[test]
    fn the_order_of_the_comparison_sort() {
        // Values with many ties, both zeros, infinities, subnormals, negatives and values
        // spread over many binades, in ascending index as the sweep gives them.
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            -5e-324,
            1.0,
            -1.0,
        ];
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut random = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut scratch = Vec::new();
        for n in [0, 1, 2, 3, 17, 256, 1000, 5000] {
            let items: Vec<(f64, usize)> = (0..n)
                .map(|k| {
                    let r = random();
                    let z = match r % 4 {
                        0 => special[(r >> 8) as usize % special.len()],
                        1 => ((r >> 8) % 7) as f64,
                        2 => f64::from_bits(r >> 2) * if r & 2 == 0 { 1.0 } else { -1.0 },
                        _ => (r >> 11) as f64 / (1u64 << 53) as f64,
                    };
                    (z, k)
                })
                .collect();
            let mut sorted = items.clone();
            sort_descending(&mut sorted, &mut scratch);
            assert_eq!(bits(&sorted), bits(&compared(&items)), "{n} items");
        }
        // Keys that share all but their lowest digit, and keys that share none.
        let close: Vec<(f64, usize)> = (0..300)
            .map(|k| (f64::from_bits(0x3ff0_0000_0000_0000 + (k * 7 % 256) as u64), k))
            .collect();
        let mut sorted = close.clone();
        sort_descending(&mut sorted, &mut scratch);
        assert_eq!(bits(&sorted), bits(&compared(&close)));
    }
}
