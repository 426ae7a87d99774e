//! Banded QR by Givens rotations: the accurate solve for large λ.
//!
//! The normal equations K = A + λB square the condition of the least-squares problem
//! min |[W^½ N; (λΩ)^½ G] γ − [W^½ y; 0]|: where λB outweighs A by a ratio s (the stiffness),
//! their solution loses about log10(s) digits in the smoothest components. Orthogonal
//! factorisation of the stacked matrix itself loses only about half as many: the rows are
//! rotated one at a time into an upper-triangular banded R (row-sequential Givens QR, as in
//! Björck 1996 §6.6), which never forms GᵀΩG. Equality constraints enter as rows of weight
//! 10⁸ relative to their unknowns' scale (the method of weighting, stable for Givens QR
//! whatever the weight: Powell & Reid 1969, Van Loan 1985), which leaves them satisfied to
//! about 1e-16 relative.
//!
//! R's row j spans columns j … last(j), last the running maximum of the rows' last columns
//! over their leading ones, so each rotation touches at most the band's width; the whole
//! factorisation is O(rows · b²), about ten times the cost of the LDLᵀ of K, which is why it
//! only serves λ beyond the normal equations' range ([`super::lambda`]).

use curve_repr::Vector;

use super::envelope::{Ldlt, PivotFailure, Profile};

/// The triangular factor R of a stacked least-squares problem and Qᵀb.
#[derive(Clone, Debug)]
pub(crate) struct GivensQr<const D: usize> {
    last: Vec<usize>,
    start: Vec<usize>,
    r: Vec<f64>,
    qtb: Vec<Vector<D>>,
    filled: Vec<bool>,
    buffer: Vec<f64>,
}

impl<const D: usize> GivensQr<D> {
    /// An empty factor for m unknowns whose rows reach at most `reach[j]` from leading
    /// column j (`reach[j] ≥ j`; the running maximum is taken here).
    pub(super) fn new(mut reach: Vec<usize>) -> Self {
        let m = reach.len();
        let mut start = Vec::with_capacity(m + 1);
        start.push(0);
        let mut running = 0;
        for (j, r) in reach.iter_mut().enumerate() {
            running = running.max(*r).max(j).min(m - 1);
            *r = running;
            start.push(start[j] + running - j + 1);
        }
        let stored = start[m];
        GivensQr {
            last: reach,
            start,
            r: vec![0.0; stored],
            qtb: vec![Vector::<D>::zeros(); m],
            filled: vec![false; m],
            buffer: Vec::new(),
        }
    }

    /// Rotates the row with coefficients `entries` (column, value) and right side `rhs` into
    /// R. O(b²).
    pub(super) fn add_row(&mut self, entries: impl Iterator<Item = (usize, f64)> + Clone, rhs: Vector<D>) {
        let Some(lead) = entries.clone().map(|(j, _)| j).min() else {
            return;
        };
        let end = entries.clone().map(|(j, _)| j).max().unwrap_or(lead);
        let width = self.last[end].max(end) - lead + 1;
        self.buffer.clear();
        self.buffer.resize(width, 0.0);
        for (j, c) in entries {
            self.buffer[j - lead] += c;
        }
        self.rotate_in(lead, width, rhs);
    }

    /// [`add_row`](Self::add_row) for a row whose coefficients are those of the columns
    /// `lead`, `lead + 1`, … in order. O(b²).
    pub(super) fn add_contiguous(&mut self, lead: usize, coefficients: &[f64], rhs: Vector<D>) {
        if coefficients.is_empty() {
            return;
        }
        let end = lead + coefficients.len() - 1;
        let width = self.last[end].max(end) - lead + 1;
        self.buffer.clear();
        self.buffer.extend_from_slice(coefficients);
        self.buffer.resize(width, 0.0);
        self.rotate_in(lead, width, rhs);
    }

    /// Rotates the row held in the buffer (columns `lead` … `lead + width − 1`) into R.
    fn rotate_in(&mut self, lead: usize, mut width: usize, mut rhs: Vector<D>) {
        let mut k = lead;
        while k - lead < width {
            let b = self.buffer[k - lead];
            if b == 0.0 {
                k += 1;
                continue;
            }
            let reach = self.last[k];
            if reach - lead + 1 > width {
                width = reach - lead + 1;
                self.buffer.resize(width, 0.0);
            }
            let row = &mut self.r[self.start[k]..self.start[k + 1]];
            if !self.filled[k] {
                row.copy_from_slice(&self.buffer[k - lead..=reach - lead]);
                self.qtb[k] = rhs;
                self.filled[k] = true;
                return;
            }
            let a = row[0];
            // The entries are far from over- and underflow (weights below 1e20).
            let h = (a * a + b * b).sqrt();
            let (cos, sin) = (a / h, b / h);
            for (x, y) in row.iter_mut().zip(&mut self.buffer[k - lead..=reach - lead]) {
                let (u, v) = (*x, *y);
                *x = cos * u + sin * v;
                *y = cos * v - sin * u;
            }
            self.buffer[k - lead] = 0.0;
            let q = self.qtb[k];
            self.qtb[k] = q * cos + rhs * sin;
            rhs = rhs * cos - q * sin;
            k += 1;
        }
    }

    /// The least-squares solution R⁻¹ Qᵀb. O(m·b). Fails on a zero or non-finite diagonal
    /// (a column no row reached).
    pub(super) fn solve(&self) -> Result<Vec<Vector<D>>, PivotFailure> {
        let mut x = self.qtb.clone();
        self.back_substitute(&mut x)?;
        Ok(x)
    }

    /// ln det(RᵀR) = 2 Σ_j ln |R_jj|. O(m). Fails as [`solve`](Self::solve) does.
    pub(super) fn log_det_normal(&self) -> Result<f64, PivotFailure> {
        self.check()?;
        Ok((0..self.last.len())
            .map(|j| 2.0 * self.r[self.start[j]].abs().ln())
            .sum())
    }

    fn check(&self) -> Result<(), PivotFailure> {
        for (j, f) in self.filled.iter().enumerate() {
            let d = self.r[self.start[j]];
            if !*f || d == 0.0 || !d.is_finite() {
                return Err(PivotFailure { row: j, pivot: d });
            }
        }
        Ok(())
    }

    fn back_substitute(&self, x: &mut [Vector<D>]) -> Result<(), PivotFailure> {
        self.check()?;
        for j in (0..x.len()).rev() {
            let row = &self.r[self.start[j]..self.start[j + 1]];
            let mut acc = x[j];
            for (offset, &c) in row.iter().enumerate().skip(1) {
                acc -= x[j + offset] * c;
            }
            x[j] = acc / row[0];
        }
        Ok(())
    }

    /// Solves RᵀR z = `rhs` in place (the normal equations through the factor). O(m·b).
    pub(super) fn solve_normal(&self, rhs: &mut [Vector<D>]) -> Result<(), PivotFailure> {
        self.check()?;
        // Rᵀ w = rhs: forward, column j of R scattered after w_j is known.
        for j in 0..rhs.len() {
            let row = &self.r[self.start[j]..self.start[j + 1]];
            let w = rhs[j] / row[0];
            rhs[j] = w;
            for (offset, &c) in row.iter().enumerate().skip(1) {
                rhs[j + offset] -= w * c;
            }
        }
        self.back_substitute(rhs)
    }

    /// RᵀR as an LDLᵀ factorisation on an envelope (L = Rᵀ scaled by its diagonal, D the
    /// squared diagonal), for the selected inverse.
    pub(super) fn ldlt_profile(&self) -> Profile {
        let m = self.last.len();
        let mut first = vec![0usize; m];
        let mut j = 0;
        for (i, f) in first.iter_mut().enumerate() {
            while self.last[j] < i {
                j += 1;
            }
            *f = j;
        }
        Profile::new(first)
    }

    /// The LDLᵀ factors of RᵀR on `profile` (from [`ldlt_profile`](Self::ldlt_profile)).
    pub(super) fn ldlt<'p>(&self, profile: &'p Profile) -> Result<Ldlt<'p>, PivotFailure> {
        self.check()?;
        let m = self.last.len();
        let mut values = profile.zeros();
        for j in 0..m {
            let row = &self.r[self.start[j]..self.start[j + 1]];
            let d = row[0];
            if let Some(index) = profile.index(j, j) {
                values[index] = d * d;
            }
            for (offset, &c) in row.iter().enumerate().skip(1) {
                if let Some(index) = profile.index(j + offset, j) {
                    values[index] = c / d;
                }
            }
        }
        Ok(Ldlt::from_factors(profile, values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    #[test]
    fn least_squares_solution_and_normal_solve_match_dense() {
        let m = 12;
        // Rows: a banded design with reach 3, plus a few longer rows.
        let mut rows: Vec<Vec<(usize, f64)>> = Vec::new();
        for i in 0..m {
            rows.push(
                (i..(i + 3).min(m))
                    .map(|j| (j, 1.0 + 0.3 * ((i * 5 + j) as f64).sin()))
                    .collect(),
            );
        }
        for i in 0..m - 4 {
            rows.push(
                (i..i + 5)
                    .map(|j| (j, 1e3 * ((i + 2 * j) as f64).cos()))
                    .collect(),
            );
        }
        let rhs: Vec<f64> = (0..rows.len()).map(|r| (r as f64 * 0.7).sin()).collect();
        let mut reach = vec![0usize; m];
        for row in &rows {
            let lead = row.iter().map(|e| e.0).min().unwrap();
            let end = row.iter().map(|e| e.0).max().unwrap();
            reach[lead] = reach[lead].max(end);
        }
        let mut qr = GivensQr::<1>::new(reach);
        for (row, b) in rows.iter().zip(&rhs) {
            qr.add_row(row.iter().copied(), Vector::<1>::new(*b));
        }
        let x = qr.solve().unwrap();
        let a = DMatrix::from_fn(rows.len(), m, |r, j| {
            rows[r].iter().find(|e| e.0 == j).map_or(0.0, |e| e.1)
        });
        let b = DVector::from_vec(rhs);
        let normal = a.transpose() * &a;
        let expected = normal.clone().lu().solve(&(a.transpose() * &b)).unwrap();
        for j in 0..m {
            assert!((x[j][0] - expected[j]).abs() < 1e-9 * expected.amax(), "x_{j}");
        }
        let mut z: Vec<Vector<1>> = (0..m).map(|j| Vector::<1>::new(j as f64 - 3.0)).collect();
        qr.solve_normal(&mut z).unwrap();
        let expected = normal
            .clone()
            .lu()
            .solve(&DVector::from_fn(m, |j, _| j as f64 - 3.0))
            .unwrap();
        for j in 0..m {
            assert!((z[j][0] - expected[j]).abs() < 1e-9 * expected.amax(), "z_{j}");
        }
        let profile = qr.ldlt_profile();
        let ldlt = qr.ldlt(&profile).unwrap();
        let inverse = normal.try_inverse().unwrap();
        let selected = ldlt.selected_inverse();
        for i in 0..m {
            for j in 0..=i {
                if let Some(index) = profile.index(i, j) {
                    assert!((selected[index] - inverse[(i, j)]).abs() < 1e-9 * inverse.amax());
                }
            }
        }
    }
}
