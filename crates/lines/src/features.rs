//! Runs of offsets the hull cannot follow: features kept as read, unless the crossing lines
//! of the other views refute them.

use crate::lofting::{dist, Cells, Source};
use crate::table::{Kind, Table};

/// Consecutive offsets of one line that the hull rejects or moves beyond six tolerances (the
/// robust fit's rejection line), this many or more, are a feature the smooth surface cannot
/// follow (a skeg, the edge of a flat of bottom, a deck's end), not transcription errors (one
/// wrong offset, far from its neighbours' agreement): they are kept as read (source
/// [`Source::Held`]) and stay flagged. Two: the planted errors of the generator's tables are
/// isolated, and Gunnerus's skeg and PX121's flat-of-bottom edge, which their data notes call
/// real features, are runs of two to five. Six tolerances and not three steps: on a noisy table
/// faired at its noise, two neighbouring noisy offsets can each move three steps. A run that
/// the crossing lines of the other views refute ([`refuted`]) is not held: two wrong offsets
/// can be neighbours too (planted table 602).
const FEATURE_RUN: usize = 2;

/// Holds runs of [`FEATURE_RUN`] or more suspect hull offsets along a line (see there) unless
/// the crossing lines refute them: their value is the input's again and they are marked
/// rejected (flagged). A refuted run keeps the hull's value, which the robust fit reached
/// without it (its offsets are rejected, or moved beyond six tolerances and weighted down).
pub(crate) fn hold_feature_runs(t: &Table, state: &mut Cells, tol: f64) {
    let Cells {
        values,
        sources,
        rejected,
    } = state;
    let suspect = |i: usize, values: &[[f64; 3]]| {
        let c = &t.cells[i];
        sources[i] == Source::Hull
            && (rejected[i] || dist(&[c.x, c.y, c.z], &values[i]) > 6.0 * tol * (1.0 + 1e-9))
    };
    let mut hold = Vec::new();
    for li in 0..t.lines.len() {
        let cells = t.line_cells(li);
        let mut k = 0;
        while k < cells.len() {
            if !suspect(cells[k], values) {
                k += 1;
                continue;
            }
            let mut e = k;
            while e + 1 < cells.len() && suspect(cells[e + 1], values) {
                e += 1;
            }
            if e + 1 - k >= FEATURE_RUN && !refuted(t, &cells[k..=e], values, sources, rejected, tol) {
                hold.extend_from_slice(&cells[k..=e]);
            }
            k = e + 1;
        }
    }
    for i in hold {
        let c = &t.cells[i];
        values[i] = [c.x, c.y, c.z];
        sources[i] = Source::Held;
        rejected[i] = true;
    }
}

/// A crossing offset departs from the hull when the fit rejects it or moves it beyond this
/// many tolerances (half the rejection line of six).
const CORROBORATE: f64 = 3.0;

/// Whether a run of suspect offsets along a line is refuted as a feature by the crossing lines
/// of the other views: a feature of the hull (a skeg, the edge of a flat of bottom) is one in
/// every view, so the lines crossing the run's stations near it (the waterlines bracketing a
/// buttock offset's height, the buttocks bracketing a waterline offset's half-breadth, both for
/// an edge) depart from the smooth hull there too; a run of wrong offsets is in one view only
/// and the crossing lines agree with the hull. Refuted: the run's stations have such crossing
/// offsets and none of them departs (rejected, or moved beyond [`CORROBORATE`] tolerances).
/// A table whose other views do not cross the run (a waterline grid) cannot refute it.
fn refuted(
    t: &Table,
    run: &[usize],
    values: &[[f64; 3]],
    sources: &[Source],
    rejected: &[bool],
    tol: f64,
) -> bool {
    let mut crossing = 0;
    let mut worst: f64 = 0.0;
    for &i in run {
        let c = &t.cells[i];
        let families: &[(Kind, usize)] = match t.lines[c.line].kind {
            Kind::Waterline => &[(Kind::Buttock, 1)],
            Kind::Buttock => &[(Kind::Waterline, 2)],
            Kind::Edge => &[(Kind::Waterline, 2), (Kind::Buttock, 1)],
            _ => &[],
        };
        for &(kind, coord) in families {
            let at = c.get_index(coord);
            // the nearest crossing offset of the family below and above the cell on its station
            let mut below: Option<(f64, usize)> = None;
            let mut above: Option<(f64, usize)> = None;
            for (j, d) in t.cells.iter().enumerate() {
                if d.station_index != c.station_index
                    || !d.on_station
                    || t.lines[d.line].kind != kind
                    || sources[j] != Source::Hull
                    || !d.get_index(coord).is_finite()
                {
                    continue;
                }
                let v = d.get_index(coord);
                if v <= at && below.is_none_or(|(b, _)| v > b) {
                    below = Some((v, j));
                }
                if v >= at && above.is_none_or(|(a, _)| v < a) {
                    above = Some((v, j));
                }
            }
            for (_, j) in below.into_iter().chain(above) {
                crossing += 1;
                let d = &t.cells[j];
                let m = if rejected[j] {
                    f64::INFINITY
                } else {
                    dist(&[d.x, d.y, d.z], &values[j]) / tol
                };
                worst = worst.max(m);
            }
        }
    }
    crossing > 0 && worst <= CORROBORATE
}
