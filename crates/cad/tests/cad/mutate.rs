//! Mutations of valid files for the readers' fuzz tests: the CAD readers' (`fuzz.rs` here) and
//! the command's (`tests/cli/fuzz_readers.rs` includes this file), one framework for both.
//!
//! Deterministic (a seeded SplitMix64), so a failure reproduces from its seed and case number.

/// SplitMix64 (Steele, Lea & Flood 2014): enough randomness for mutations, no dependency.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One mutation of `text`, chosen by `rng`.
pub(crate) fn mutate(text: &str, rng: &mut Rng) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    let at = rng.below(bytes.len());
    match rng.below(11) {
        // Flip a few bytes to anything.
        0 => {
            for _ in 0..1 + rng.below(8) {
                let i = rng.below(bytes.len());
                bytes[i] = rng.next() as u8;
            }
        }
        // Cut the file short.
        1 => bytes.truncate(at),
        // Duplicate a stretch (repeated instances, entities, groups).
        2 => {
            let len = rng.below(400).min(bytes.len() - at);
            let piece = bytes[at..at + len].to_vec();
            for _ in 0..1 + rng.below(3) {
                bytes.splice(at..at, piece.iter().copied());
            }
        }
        // Delete a stretch.
        3 => {
            let len = rng.below(200).min(bytes.len() - at);
            bytes.drain(at..at + len);
        }
        // Nest brackets deeply (the STEP parser once recursed on parentheses; JSON nests
        // arrays and objects).
        4 => {
            let depth = 20_000;
            let (open, close) = [(b'(', b')'), (b'[', b']'), (b'{', b'}')][rng.below(3)];
            let nested: Vec<u8> = std::iter::repeat_n(open, depth)
                .chain(std::iter::repeat_n(close, rng.below(2) * depth))
                .collect();
            bytes.splice(at..at, nested);
        }
        // Make a number huge or absurd where a digit is.
        5 => {
            if let Some(i) = (at..bytes.len()).find(|&i| bytes[i].is_ascii_digit()) {
                let huge: &[&[u8]] = &[
                    b"99999999999999999999999",
                    b"1E308",
                    b"1E999",
                    b"-0",
                    b"NaN",
                    b"9223372036854775807",
                    b"18446744073709551616",
                ];
                let pick = huge[rng.below(huge.len())];
                bytes.splice(i..i + 1, pick.iter().copied());
            }
        }
        // A very long line of one character, with no line break (CR-only files, garbage).
        6 => {
            let c = [b'\r', b'7', b'\'', b'#', b',', b'x'][rng.below(6)];
            bytes.splice(at..at, std::iter::repeat_n(c, 10_000 + rng.below(20_000)));
        }
        // Line ends changed to CR only.
        7 => bytes.iter_mut().filter(|b| **b == b'\n').for_each(|b| *b = b'\r'),
        // NUL bytes, and other control characters, here and there.
        8 => {
            for _ in 0..1 + rng.below(4) {
                let i = rng.below(bytes.len() + 1);
                bytes.insert(i, [0, 0, 0x1b, 0x0c, b'\t'][rng.below(5)]);
            }
        }
        // A header or key repeated: the first line duplicated.
        9 => {
            let end = bytes
                .iter()
                .position(|&b| b == b'\n')
                .map_or(bytes.len(), |i| i + 1);
            let first = bytes[..end].to_vec();
            bytes.splice(0..0, first);
        }
        // Swap two lines.
        _ => {
            let mut lines: Vec<Vec<u8>> = bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
            let (i, j) = (rng.below(lines.len()), rng.below(lines.len()));
            lines.swap(i, j);
            bytes = lines.join(&b'\n');
        }
    }
    bytes
}
