//! A small hand-written SVG plotting toolkit for fairing pictures.
//!
//! A [`Figure`] holds one or more [`Panel`]s in a grid; a panel has axes with nice ticks
//! ([`ticks`]), axis titles, a legend and any number of [`Series`]: polylines, point
//! markers, bars (for z_i), curvature combs (teeth and envelope) and colour maps (for z_ij).
//! Curve panels can keep x and y at the same scale ([`Panel::with_equal_aspect`]).
//! Non-finite data are skipped (a line is broken there), never written. Output is a `String`;
//! [`Figure::write`] saves it. Cost is linear in the number of data points.

pub mod color;
mod figure;
mod series;
pub mod ticks;

pub use color::Color;
pub use figure::{Figure, Panel};
pub use series::{Bars, ColorMap, Comb, Line, Markers, Series};

/// Escapes text for XML content and attribute values (`&`, `<`, `>`, `"`, `'`), and drops
/// the control characters XML 1.0 forbids.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 => {}
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests;
