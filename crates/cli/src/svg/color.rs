//! Colours: a categorical palette for series and a sequential map for values.

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Color {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
}

impl Color {
    /// A colour from its channels.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Color {
        Color { r, g, b }
    }

    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }

    /// The `index`-th colour of a ten-colour categorical palette (cycling).
    pub fn palette(index: usize) -> Color {
        const PALETTE: [Color; 10] = [
            Color::rgb(31, 119, 180),
            Color::rgb(214, 39, 40),
            Color::rgb(44, 160, 44),
            Color::rgb(255, 127, 14),
            Color::rgb(148, 103, 189),
            Color::rgb(140, 86, 75),
            Color::rgb(227, 119, 194),
            Color::rgb(127, 127, 127),
            Color::rgb(188, 189, 34),
            Color::rgb(23, 190, 207),
        ];
        PALETTE[index % PALETTE.len()]
    }

    /// A sequential (viridis-like) colour for `t` in [0, 1]; values outside are clamped, NaN is grey.
    pub fn sequential(t: f64) -> Color {
        const STOPS: [Color; 5] = [
            Color::rgb(68, 1, 84),
            Color::rgb(59, 82, 139),
            Color::rgb(33, 145, 140),
            Color::rgb(94, 201, 98),
            Color::rgb(253, 231, 37),
        ];
        if !t.is_finite() {
            return Color::rgb(160, 160, 160);
        }
        let scaled = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
        let k = (scaled.floor() as usize).min(STOPS.len() - 2);
        let f = scaled - k as f64;
        let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
        let (a, b) = (STOPS[k], STOPS[k + 1]);
        Color::rgb(mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequential_ends_and_clamping() {
        assert_eq!(Color::sequential(0.0), Color::rgb(68, 1, 84));
        assert_eq!(Color::sequential(1.0), Color::rgb(253, 231, 37));
        assert_eq!(Color::sequential(-3.0), Color::sequential(0.0));
        assert_eq!(Color::sequential(7.0), Color::sequential(1.0));
        assert_eq!(Color::sequential(f64::NAN).hex(), "#a0a0a0");
    }
}
