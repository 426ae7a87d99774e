//! Every reader against mutated files: the files this crate writes, with bytes flipped, cut,
//! duplicated, nested 20 000 deep, numbers made huge. A reader may accept or refuse such a
//! file, but it must neither panic nor overflow its stack, and its message is one line of at
//! most 500 characters however much of the input is garbage.
//!
//! Deterministic (a seeded SplitMix64) and bounded by a case count, not by time, so a failure
//! reproduces; coverage-guided fuzzing is left out of CI.

use cad::{CadModel, Format, Units, WriteOptions};

use crate::common::{curves, surfaces};

/// SplitMix64 (Steele, Lea & Flood 2014): enough randomness for mutations, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// The longest message a reader may give.
const LONGEST_MESSAGE: usize = 500;

/// Mutations per valid file; with 3 formats × 2 files this is a few seconds in a debug build.
const CASES: usize = 300;

fn valid_files(format: Format) -> Vec<String> {
    let all = curves();
    let mut models = vec![CadModel {
        curves: all[..2].to_vec(),
        surfaces: vec![],
        units: Units::Millimetre,
        tolerance: 1e-6,
    }];
    if format != Format::Dxf {
        models.push(CadModel {
            curves: vec![all[4].clone()],
            surfaces: surfaces(),
            units: Units::Metre,
            tolerance: 1e-7,
        });
    }
    models
        .iter()
        .map(|m| cad::write(m, format, &WriteOptions::default()).unwrap())
        .collect()
}

/// One mutation of `text`, chosen by `rng`.
fn mutate(text: &str, rng: &mut Rng) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    let at = rng.below(bytes.len());
    match rng.below(9) {
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
        // Nest parentheses deeply (the STEP parser once recursed on these).
        4 => {
            let depth = 20_000;
            let nested: Vec<u8> = std::iter::repeat_n(b'(', depth)
                .chain(std::iter::repeat_n(b')', rng.below(2) * depth))
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

#[test]
fn mutated_files_are_read_or_refused_in_one_short_line() {
    for format in Format::ALL {
        for (f, text) in valid_files(format).iter().enumerate() {
            let mut rng = Rng(0x5eed ^ (f as u64) << 8 ^ format as u64);
            for case in 0..CASES {
                let bytes = mutate(text, &mut rng);
                let text = String::from_utf8_lossy(&bytes);
                let outcome = std::panic::catch_unwind(|| cad::read(&text, format));
                let Ok(result) = outcome else {
                    panic!("{format} file {f} case {case}: the reader panicked");
                };
                if let Err(e) = result {
                    let message = e.to_string();
                    assert!(
                        message.chars().count() <= LONGEST_MESSAGE && !message.contains(['\n', '\r']),
                        "{format} file {f} case {case}: a message of {} characters: {}",
                        message.chars().count(),
                        message.chars().take(200).collect::<String>()
                    );
                }
            }
        }
    }
}

#[test]
fn twenty_thousand_nested_parentheses_are_refused_naming_the_line() {
    let deep = format!(
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('',{}1.{});\nENDSEC;\nEND-ISO-10303-21;\n",
        "(".repeat(20_000),
        ")".repeat(20_000)
    );
    let message = cad::read(&deep, Format::Step).unwrap_err().to_string();
    assert!(message.starts_with("STEP line 5:"), "{message}");
    assert!(message.contains("nested"), "{message}");
}
