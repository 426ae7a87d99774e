//! What a writer puts into a file's header besides the geometry: a file name, an author, a
//! time stamp and, for STEP, the application protocol.

/// The application protocol named in a STEP file's `FILE_SCHEMA`. The entities written are
/// the same in both (B-spline curves and surfaces, products, units, uncertainty).
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
pub enum StepSchema {
    /// AP214, automotive design (`AUTOMOTIVE_DESIGN`): read by every STEP importer.
    #[default]
    Ap214,
    /// AP242, managed model-based 3D engineering, its successor.
    Ap242,
}

/// A UTC time stamp, to the second.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timestamp {
    /// Year, e.g. 2026.
    pub year: i64,
    /// Month, 1–12.
    pub month: u32,
    /// Day of the month, 1–31.
    pub day: u32,
    /// Hour, 0–23.
    pub hour: u32,
    /// Minute, 0–59.
    pub minute: u32,
    /// Second, 0–59.
    pub second: u32,
}

impl Timestamp {
    /// The current time (UTC), from the system clock; the Unix epoch if the clock is earlier.
    pub fn now() -> Self {
        let seconds = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        Self::from_unix(seconds as i64)
    }

    /// The UTC date and time of a Unix time (seconds since 1970-01-01T00:00:00Z), by Howard
    /// Hinnant's days-to-civil algorithm. O(1).
    pub fn from_unix(seconds: i64) -> Self {
        let days = seconds.div_euclid(86_400);
        let rest = seconds.rem_euclid(86_400);
        let z = days + 719_468;
        let era = z.div_euclid(146_097);
        let doe = z - era * 146_097;
        let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
        let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
        let mp = (5 * doy + 2) / 153;
        let day = (doy - (153 * mp + 2) / 5 + 1) as u32;
        let month = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
        let year = yoe + era * 400 + i64::from(month <= 2);
        Self {
            year,
            month,
            day,
            hour: (rest / 3600) as u32,
            minute: (rest % 3600 / 60) as u32,
            second: (rest % 60) as u32,
        }
    }

    /// IGES's form, `YYYYMMDD.HHNNSS`.
    pub fn iges(&self) -> String {
        format!(
            "{:04}{:02}{:02}.{:02}{:02}{:02}",
            self.year, self.month, self.day, self.hour, self.minute, self.second
        )
    }

    /// ISO 8601, `YYYY-MM-DDTHH:MM:SS` (STEP's `FILE_NAME` time stamp).
    pub fn iso(&self) -> String {
        format!(
            "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}",
            self.year, self.month, self.day, self.hour, self.minute, self.second
        )
    }
}

/// Header fields of a written file.
#[derive(Clone, Debug, PartialEq)]
pub struct WriteOptions {
    /// The file's name as recorded inside it (IGES Global parameter 4, STEP `FILE_NAME`).
    pub file_name: String,
    /// The author (IGES Global parameter 21, STEP `FILE_NAME`); may be empty.
    pub author: String,
    /// When the file was written.
    pub timestamp: Timestamp,
    /// The STEP application protocol.
    pub step_schema: StepSchema,
}

impl Default for WriteOptions {
    /// No file name or author, the current time, AP214.
    fn default() -> Self {
        Self {
            file_name: String::new(),
            author: String::new(),
            timestamp: Timestamp::now(),
            step_schema: StepSchema::Ap214,
        }
    }
}

/// `text` with every character outside printable ASCII, the quote `'` and the backslash
/// (STEP's escape) replaced by `_`, at most `limit` characters: safe inside IGES Hollerith
/// strings, STEP strings and DXF.
pub(crate) fn ascii(text: &str, limit: usize) -> String {
    text.chars()
        .map(|c| {
            if (' '..='~').contains(&c) && c != '\'' && c != '\\' {
                c
            } else {
                '_'
            }
        })
        .take(limit)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unix_times_become_civil_dates() {
        let t = Timestamp::from_unix(0);
        assert_eq!(t.iso(), "1970-01-01T00:00:00");
        // 2000-02-29T12:34:56Z
        let t = Timestamp::from_unix(951_827_696);
        assert_eq!(t.iso(), "2000-02-29T12:34:56");
        assert_eq!(t.iges(), "20000229.123456");
        // 2026-12-31T23:59:59Z
        assert_eq!(Timestamp::from_unix(1_798_761_599).iso(), "2026-12-31T23:59:59");
        assert_eq!(Timestamp::from_unix(-1).iso(), "1969-12-31T23:59:59");
    }

    #[test]
    fn names_are_made_ascii() {
        assert_eq!(ascii("wl 03 – it's", 40), "wl 03 _ it_s");
        assert_eq!(ascii("a\\b", 40), "a_b");
        assert_eq!(ascii("abcdef", 3), "abc");
    }
}
