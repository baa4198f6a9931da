//! Sparse direct solves on faer 0.24: a sparse LU whose symbolic factorisation (with its
//! fill-reducing ordering) is computed once per sparsity pattern and whose numeric
//! factorisation is repeated per Newton iteration (DEPENDENCIES.md: symbolic 83 ms vs
//! numeric 31 ms at n = 100 000), the same LU taking (row, col, value) triplets with the
//! pattern cached by comparison, and a bordered LU for a sparse block with two dense
//! border rows and columns.
//!
//! Every type is generic over the error type `E` its caller propagates (any
//! `E: From<LinearError>`, [`LinearError`] itself by default), so that a caller keeps
//! its own error enum and `?` works without a wrapper at every call.

use std::marker::PhantomData;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::MatMut;
use thiserror::Error;
use crate::banded::{BandStructure, BorderedBand};
use crate::phases::{timed, Phase};

/// Why a sparse factorisation or solve failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LinearError {
    /// The pattern does not describe an n × n matrix (lengths differ, an index ≥ n, a
    /// border unknown repeated or outside).
    #[error("invalid sparse pattern for a {n} × {n} matrix: {detail}")]
    InvalidPattern { n: usize, detail: String },
    /// A value list or right-hand side of the wrong length.
    #[error("{what} has {got} entries, expected {expected}")]
    DimensionMismatch { what: &'static str, expected: usize, got: usize },
    /// A matrix entry is NaN or infinite (`index` is the first one, in pattern order).
    #[error("non-finite matrix entry at pattern position {index}")]
    NonFiniteMatrix { index: usize },
    /// `factorize` (or `set_pattern`) was not called before the solve.
    #[error("solve before factorisation")]
    NotFactorised,
    /// faer's symbolic or numeric LU failed (structurally or numerically singular).
    #[error("sparse LU failed: {detail}")]
    Singular { detail: String },
    /// The 2 × 2 Schur complement of a bordered system is singular:
    /// |det S| ≤ 10⁻¹⁴ max(|S₀₀ S₁₁|, |S₀₁ S₁₀|) or det S not finite.
    #[error("singular 2 × 2 Schur complement of the border unknowns: det {det:.3e}")]
    SingularSchur { det: f64 },
    /// The solve produced NaN or infinite values (a numerically singular matrix).
    #[error("the LU solve produced non-finite values (numerically singular matrix)")]
    NonFiniteSolution,
}

/// A caller whose error type is a plain message (kept for code written before the typed
/// errors; new code uses [`LinearError`] or its own enum).
impl From<LinearError> for String {
    fn from(e: LinearError) -> String {
        e.to_string()
    }
}

fn first_non_finite(v: &[f64]) -> Option<usize> {
    v.iter().position(|x| !x.is_finite())
}

fn check_pattern(n: usize, rows: &[usize], cols: &[usize]) -> Result<(), LinearError> {
    if rows.len() != cols.len() {
        return Err(LinearError::InvalidPattern {
            n,
            detail: format!("{} row indices but {} column indices", rows.len(), cols.len()),
        });
    }
    if let Some(&i) = rows.iter().chain(cols).find(|&&i| i >= n) {
        return Err(LinearError::InvalidPattern { n, detail: format!("index {i} outside") });
    }
    Ok(())
}

/// Sparse LU of an n × n matrix with a fixed pattern (`rows[k]`, `cols[k]`): the
/// symbolic factorisation once in [`Self::set_pattern`], the numeric one per
/// [`Self::factorize`] with the values in pattern order. Duplicate (row, col) entries
/// are summed.
///
/// Made by [`Self::banded`], it first looks for a band with a small dense border in the
/// pattern ([`BandStructure::detect`]: a mesh's unknowns numbered node by node, a
/// closed loop's wrap-around and global unknowns in the border) and factorises it by
/// [`BorderedBand`], linear in n; faer's general sparse LU is used for any other pattern,
/// and from the first matrix of a pattern that the banded LU refuses (any zero or, under
/// a border, small pivot: faer's LU decides whether the matrix is singular).
#[derive(Debug)]
pub struct SparseLu<E = LinearError> {
    n: usize,
    /// Length of the pattern (entries, duplicates included).
    entries: usize,
    /// Look for a band in each new pattern.
    try_band: bool,
    /// The matrices are symmetric: the banded LU tries Cholesky first ([`BorderedBand::symmetric`]).
    symmetric: bool,
    /// The pattern, kept while the band is used (for a fallback to faer).
    indices: Option<(Vec<usize>, Vec<usize>)>,
    band: Option<BorderedBand>,
    pattern: Option<FaerSymbolic>,
    factors: Factors,
    /// Symbolic factorisations done (one per pattern).
    pub symbolic_factorisations: usize,
    /// Numeric factorisations done.
    pub numeric_factorisations: usize,
    /// Matrices the banded LU refused (each switched the pattern to faer's LU).
    pub band_refusals: usize,
    error: PhantomData<fn() -> E>,
}

/// Which factorisation the last [`SparseLu::factorize`] left.
#[derive(Debug)]
enum Factors {
    None,
    Faer(Box<Lu<usize, f64>>),
    Band,
}

impl<E> Default for SparseLu<E> {
    fn default() -> Self {
        Self {
            n: 0,
            entries: 0,
            try_band: false,
            symmetric: false,
            indices: None,
            band: None,
            pattern: None,
            factors: Factors::None,
            symbolic_factorisations: 0,
            numeric_factorisations: 0,
            band_refusals: 0,
            error: PhantomData,
        }
    }
}

/// faer's symbolic pattern, its value order and its symbolic LU.
type FaerSymbolic = (SymbolicSparseColMat<usize>, Argsort<usize>, SymbolicLu<usize>);

/// faer's symbolic LU of the n × n pattern.
fn faer_symbolic(n: usize, rows: &[usize], cols: &[usize]) -> Result<FaerSymbolic, LinearError> {
    let pairs: Vec<Pair<usize, usize>> = rows.iter().zip(cols).map(|(&r, &c)| Pair::new(r, c)).collect();
    let (sym, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).map_err(|e| LinearError::InvalidPattern { n, detail: format!("{e:?}") })?;
    let symbolic = SymbolicLu::try_new(sym.as_ref()).map_err(|e| LinearError::Singular { detail: format!("symbolic LU: {e:?}") })?;
    Ok((sym, argsort, symbolic))
}

impl<E: From<LinearError>> SparseLu<E> {
    /// An empty factorisation (set a pattern before factorising), faer's LU for every
    /// pattern.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty factorisation that uses the banded LU where the pattern is a band with a
    /// small border (see the type's docs).
    pub fn banded() -> Self {
        Self { try_band: true, ..Self::default() }
    }

    /// An empty factorisation for symmetric matrices (an energy's Hessian): where the
    /// banded LU is used ([`Self::set_pattern_with_border`], or a band found by
    /// [`Self::banded`]'s detection — not made by this), the band block is factorised by
    /// Cholesky when the values are symmetric and it is positive definite, else by the
    /// LU as always ([`BorderedBand::symmetric`]); the solution agrees with the LU's to
    /// round-off.
    pub fn symmetric() -> Self {
        Self { symmetric: true, ..Self::default() }
    }

    /// Factorisations by the band Cholesky, and matrices it refused to the LU (not
    /// symmetric, not positive definite, or a Schur complement judged singular; 0 when
    /// the banded LU is not in use, or not made by [`Self::symmetric`]).
    pub fn cholesky_counts(&self) -> (usize, usize) {
        self.band.as_ref().map_or((0, 0), |b| (b.cholesky_factorisations, b.cholesky_refusals))
    }

    /// Order n of the matrix of the current pattern (0 before the first).
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The band-and-border split in use, if the banded LU factorises this pattern.
    pub fn band_structure(&self) -> Option<&BandStructure> {
        self.band.as_ref().map(BorderedBand::structure)
    }

    fn has_pattern(&self) -> bool {
        self.pattern.is_some() || self.band.is_some()
    }

    /// Set the n × n pattern (`rows[k]`, `cols[k]`) and compute its symbolic LU (or
    /// its band structure).
    ///
    /// # Errors
    /// [`LinearError::InvalidPattern`], or [`LinearError::Singular`] if the symbolic
    /// factorisation fails.
    pub fn set_pattern(&mut self, n: usize, rows: &[usize], cols: &[usize]) -> Result<(), E> {
        check_pattern(n, rows, cols)?;
        let band = self.try_band.then(|| timed(Phase::SymbolicFactorisation, || BandStructure::detect(n, rows, cols, &[]))).flatten();
        self.install(n, rows, cols, band)
    }

    /// [`Self::set_pattern`] with the band-and-border split given by its border instead
    /// of detected ([`BandStructure::with_border`]: the unknowns `border` the border,
    /// the others in their order the band, without [`BandStructure::detect`]'s caps):
    /// for a caller that knows its structure, e.g. a closed mesh numbered node by node
    /// with one node's unknowns as the border. The banded LU is used whether or not the
    /// factorisation was made by [`Self::banded`]; a matrix it refuses goes to faer's LU
    /// as there.
    ///
    /// # Errors
    /// As [`Self::set_pattern`]; [`LinearError::InvalidPattern`] for a border index
    /// outside or repeated.
    pub fn set_pattern_with_border(&mut self, n: usize, rows: &[usize], cols: &[usize], border: &[usize]) -> Result<(), E> {
        check_pattern(n, rows, cols)?;
        let structure = timed(Phase::SymbolicFactorisation, || BandStructure::with_border(n, rows, cols, border))
            .ok_or_else(|| LinearError::InvalidPattern { n, detail: format!("border of {} unknowns outside or repeated", border.len()) })?;
        self.install(n, rows, cols, Some(structure))
    }

    /// The pattern's band split if `band`, else faer's symbolic LU.
    fn install(&mut self, n: usize, rows: &[usize], cols: &[usize], band: Option<BandStructure>) -> Result<(), E> {
        self.factors = Factors::None;
        if let Some(structure) = band {
            self.band = Some(if self.symmetric { BorderedBand::symmetric(structure, rows, cols) } else { BorderedBand::new(structure, rows, cols) });
            self.indices = Some((rows.to_vec(), cols.to_vec()));
            self.pattern = None;
        } else {
            self.pattern = Some(timed(Phase::SymbolicFactorisation, || faer_symbolic(n, rows, cols))?);
            self.band = None;
            self.indices = None;
        }
        self.symbolic_factorisations += 1;
        self.n = n;
        self.entries = rows.len();
        Ok(())
    }

    /// Numeric LU of the matrix with `values` in pattern order.
    ///
    /// # Errors
    /// [`LinearError::NotFactorised`] without a pattern, [`LinearError::NonFiniteMatrix`],
    /// [`LinearError::DimensionMismatch`], or [`LinearError::Singular`] (faer's LU; a
    /// matrix the banded LU refuses — see [`crate::banded`] — is handed to faer's, from
    /// then on for this pattern).
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), E> {
        if !self.has_pattern() {
            return Err(LinearError::NotFactorised.into());
        }
        if let Some(index) = first_non_finite(values) {
            return Err(LinearError::NonFiniteMatrix { index }.into());
        }
        if values.len() != self.entries {
            return Err(LinearError::DimensionMismatch { what: "value list", expected: self.entries, got: values.len() }.into());
        }
        self.factors = Factors::None;
        if let Some(band) = self.band.as_mut() {
            match timed(Phase::NumericFactorisation, || band.factorize(values, &[])) {
                Ok(()) => {
                    self.numeric_factorisations += 1;
                    self.factors = Factors::Band;
                    return Ok(());
                }
                // every refusal goes to faer's LU of the whole matrix, which gives the
                // verdict: the band block alone may be singular or ill conditioned under
                // a border (the whole matrix regular), a pivot judged against its column
                // may be small only because its row is badly scaled, the Schur
                // complement's test may be met by cancellation
                Err(_) => {
                    self.band_refusals += 1;
                    let (rows, cols) = self.indices.take().unwrap_or_default();
                    self.pattern = Some(timed(Phase::SymbolicFactorisation, || faer_symbolic(self.n, &rows, &cols))?);
                    self.band = None;
                    self.symbolic_factorisations += 1;
                }
            }
        }
        let (sym, argsort, symbolic) = self.pattern.as_ref().ok_or(LinearError::NotFactorised)?;
        let n = self.n;
        let lu = timed(Phase::NumericFactorisation, || -> Result<_, LinearError> {
            let mat = SparseColMat::new_from_argsort(sym.clone(), argsort, values)
                .map_err(|e| LinearError::InvalidPattern { n, detail: format!("{e:?}") })?;
            Lu::try_new_with_symbolic(symbolic.clone(), mat.as_ref()).map_err(|e| LinearError::Singular { detail: format!("{e:?}") })
        })?;
        self.numeric_factorisations += 1;
        self.factors = Factors::Faer(Box::new(lu));
        Ok(())
    }

    /// Overwrite `b` with A⁻¹ b.
    ///
    /// # Errors
    /// [`LinearError::NotFactorised`], [`LinearError::DimensionMismatch`], or
    /// [`LinearError::NonFiniteSolution`] (a numerically singular matrix).
    pub fn solve_in_place(&self, b: &mut [f64]) -> Result<(), E> {
        if matches!(self.factors, Factors::None) {
            return Err(LinearError::NotFactorised.into());
        }
        if b.len() != self.n {
            return Err(LinearError::DimensionMismatch { what: "right-hand side", expected: self.n, got: b.len() }.into());
        }
        match (&self.factors, &self.band) {
            (Factors::Band, Some(band)) => timed(Phase::LinearSolves, || band.solve_in_place(b)),
            (Factors::Faer(lu), _) => timed(Phase::LinearSolves, || lu.solve_in_place(MatMut::from_column_major_slice_mut(b, self.n, 1))),
            _ => return Err(LinearError::NotFactorised.into()),
        }
        if first_non_finite(b).is_some() {
            return Err(LinearError::NonFiniteSolution.into());
        }
        Ok(())
    }
}

/// The [`SparseLu`] of a matrix given as (row, col, value) triplets at every
/// factorisation: the symbolic LU is recomputed only when the pattern (the row and
/// column index lists, in order) changes — once per mesh in a Newton solve.
#[derive(Debug)]
pub struct TripletLu<E = LinearError> {
    rows: Vec<usize>,
    cols: Vec<usize>,
    lu: SparseLu<E>,
}

impl<E> Default for TripletLu<E> {
    fn default() -> Self {
        Self { rows: Vec::new(), cols: Vec::new(), lu: SparseLu::default() }
    }
}

impl<E: From<LinearError>> TripletLu<E> {
    /// An empty factorisation (call [`Self::factorize`] before solving).
    pub fn new() -> Self {
        Self::default()
    }

    /// Factorise the n × n matrix with entries `vals[e]` at (`rows[e]`, `cols[e]`).
    ///
    /// # Errors
    /// [`LinearError::InvalidPattern`] (lengths, indices), [`LinearError::NonFiniteMatrix`],
    /// [`LinearError::Singular`].
    pub fn factorize(&mut self, n: usize, rows: &[usize], cols: &[usize], vals: &[f64]) -> Result<(), E> {
        check_pattern(n, rows, cols)?;
        if vals.len() != rows.len() {
            return Err(LinearError::DimensionMismatch { what: "value list", expected: rows.len(), got: vals.len() }.into());
        }
        if let Some(index) = first_non_finite(vals) {
            return Err(LinearError::NonFiniteMatrix { index }.into());
        }
        let same = self.lu.has_pattern() && self.lu.n == n && self.rows == rows && self.cols == cols;
        if !same {
            self.lu.set_pattern(n, rows, cols)?;
            self.rows = rows.to_vec();
            self.cols = cols.to_vec();
        }
        self.lu.factorize(vals)
    }

    /// Overwrite `b` with A⁻¹ b (see [`SparseLu::solve_in_place`]).
    ///
    /// # Errors
    /// As [`SparseLu::solve_in_place`].
    pub fn solve_in_place(&self, b: &mut [f64]) -> Result<(), E> {
        self.lu.solve_in_place(b)
    }

    /// Symbolic factorisations done (one per distinct pattern).
    pub fn symbolic_factorisations(&self) -> usize {
        self.lu.symbolic_factorisations
    }

    /// Numeric factorisations done.
    pub fn numeric_factorisations(&self) -> usize {
        self.lu.numeric_factorisations
    }
}

/// Where a pattern entry of the full matrix goes in the bordered system.
#[derive(Debug, Clone, Copy)]
enum Entry {
    /// Inner block A: position in the inner values.
    Inner(usize),
    /// Border column B: (inner row, border column).
    B(usize, usize),
    /// Border row C: (border row, inner column).
    C(usize, usize),
    /// Corner D: (border row, border column).
    D(usize, usize),
}

/// A sparse system [A B; C D] with two global unknowns as its border: A sparse (e.g.
/// banded), B, C the dense columns and rows of the two border unknowns, D 2 × 2. A
/// sparse LU of the whole matrix fills in like AᵀA through the dense rows (measured
/// for the steady drive, docs/fem-drive.md §12: 4 → 850 ms from 128 to 2048
/// elements); A's LU and the 2 × 2 Schur complement S = D − C A⁻¹ B keep the cost
/// linear. Solve: A u = r_A, A V = B, S y = r_D − C u, x_A = u − V y, x_D = y.
#[derive(Debug)]
pub struct BorderedLu<E = LinearError> {
    border: [usize; 2],
    global_of: Vec<usize>,
    entries: Vec<Entry>,
    inner_len: usize,
    inner_diagonal: Vec<usize>,
    lu: SparseLu<E>,
}

impl<E: From<LinearError>> BorderedLu<E> {
    /// The system of the n × n pattern (`rows[k]`, `cols[k]`) with the unknowns `border`
    /// as its border; the symbolic LU of A is computed here.
    ///
    /// # Errors
    /// [`LinearError::InvalidPattern`] (also for a border repeated or outside), or
    /// [`LinearError::Singular`] if A's symbolic factorisation fails.
    pub fn new(rows: &[usize], cols: &[usize], n: usize, border: [usize; 2]) -> Result<Self, E> {
        Self::with_lu(rows, cols, n, border, SparseLu::new())
    }

    /// As [`Self::new`], with A factorised by the banded LU where its pattern is a band
    /// with a small border ([`SparseLu::banded`]; the closing element of a loop couples
    /// its last node with its first).
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn banded(rows: &[usize], cols: &[usize], n: usize, border: [usize; 2]) -> Result<Self, E> {
        Self::with_lu(rows, cols, n, border, SparseLu::banded())
    }

    /// The inner block A is factorised by `lu`.
    fn with_lu(rows: &[usize], cols: &[usize], n: usize, border: [usize; 2], mut lu: SparseLu<E>) -> Result<Self, E> {
        check_pattern(n, rows, cols)?;
        if border[0] == border[1] || border.iter().any(|&b| b >= n) {
            return Err(LinearError::InvalidPattern { n, detail: format!("border unknowns {border:?}") }.into());
        }
        let mut inner_of = vec![usize::MAX; n];
        let mut global_of = Vec::with_capacity(n - 2);
        for (g, slot) in inner_of.iter_mut().enumerate() {
            if !border.contains(&g) {
                *slot = global_of.len();
                global_of.push(g);
            }
        }
        let bi = |g: usize| border.iter().position(|&b| b == g);
        let (mut ir, mut ic) = (Vec::new(), Vec::new());
        let entries: Vec<Entry> = rows
            .iter()
            .zip(cols)
            .map(|(&r, &c)| match (bi(r), bi(c)) {
                (None, None) => {
                    ir.push(inner_of[r]);
                    ic.push(inner_of[c]);
                    Entry::Inner(ir.len() - 1)
                }
                (None, Some(k)) => Entry::B(inner_of[r], k),
                (Some(k), None) => Entry::C(k, inner_of[c]),
                (Some(k), Some(l)) => Entry::D(k, l),
            })
            .collect();
        let mut inner_diagonal = vec![usize::MAX; global_of.len()];
        for (k, (&r, &c)) in ir.iter().zip(&ic).enumerate() {
            if r == c && inner_diagonal[r] == usize::MAX {
                inner_diagonal[r] = k;
            }
        }
        lu.set_pattern(global_of.len(), &ir, &ic)?;
        Ok(BorderedLu { border, global_of, entries, inner_len: ir.len(), inner_diagonal, lu })
    }

    /// Size n of the whole system (A and its border).
    pub fn dim(&self) -> usize {
        self.global_of.len() + 2
    }

    /// Numeric factorisations of A done.
    pub fn factorisations(&self) -> usize {
        self.lu.numeric_factorisations
    }

    /// Overwrite `rhs` with J⁻¹ rhs for the matrix `values` (pattern order, duplicates
    /// summed), with `shift` added to the diagonal (Levenberg–Marquardt; empty: none;
    /// an inner unknown without a diagonal entry in the pattern gets no shift).
    ///
    /// # Errors
    /// [`LinearError::Singular`] / [`LinearError::NonFiniteMatrix`] for A,
    /// [`LinearError::SingularSchur`], [`LinearError::NonFiniteSolution`].
    pub fn solve(&mut self, values: &[f64], shift: &[f64], rhs: &mut [f64]) -> Result<(), E> {
        let m = self.global_of.len();
        let mut a = vec![0.0; self.inner_len];
        let mut b = [vec![0.0; m], vec![0.0; m]];
        let mut c = [vec![0.0; m], vec![0.0; m]];
        let mut d = [[0.0; 2]; 2];
        for (e, &v) in self.entries.iter().zip(values) {
            match *e {
                Entry::Inner(k) => a[k] += v,
                Entry::B(i, k) => b[k][i] += v,
                Entry::C(k, j) => c[k][j] += v,
                Entry::D(k, l) => d[k][l] += v,
            }
        }
        if !shift.is_empty() {
            for (i, &pos) in self.inner_diagonal.iter().enumerate() {
                if pos != usize::MAX {
                    a[pos] += shift[self.global_of[i]];
                }
            }
            for k in 0..2 {
                d[k][k] += shift[self.border[k]];
            }
        }
        self.lu.factorize(&a)?;
        let mut u: Vec<f64> = self.global_of.iter().map(|&g| rhs[g]).collect();
        self.lu.solve_in_place(&mut u)?;
        for col in b.iter_mut() {
            self.lu.solve_in_place(col)?;
        }
        let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
        let s = [
            [d[0][0] - dot(&c[0], &b[0]), d[0][1] - dot(&c[0], &b[1])],
            [d[1][0] - dot(&c[1], &b[0]), d[1][1] - dot(&c[1], &b[1])],
        ];
        let g = [rhs[self.border[0]] - dot(&c[0], &u), rhs[self.border[1]] - dot(&c[1], &u)];
        let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
        let scale = (s[0][0] * s[1][1]).abs().max((s[0][1] * s[1][0]).abs());
        if !(det.abs() > 1e-14 * scale && det.is_finite()) {
            return Err(LinearError::SingularSchur { det }.into());
        }
        let y = [(g[0] * s[1][1] - s[0][1] * g[1]) / det, (s[0][0] * g[1] - s[1][0] * g[0]) / det];
        for (i, &gl) in self.global_of.iter().enumerate() {
            rhs[gl] = u[i] - b[0][i] * y[0] - b[1][i] * y[1];
        }
        rhs[self.border[0]] = y[0];
        rhs[self.border[1]] = y[1];
        if first_non_finite(rhs).is_some() {
            return Err(LinearError::NonFiniteSolution.into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{dense_of, dense_solve, Lcg};

    /// A random 60 × 60 matrix with about 8 % off-diagonal fill (some entries given
    /// twice, to be summed) and a diagonal of size 2…3 — non-symmetric, not diagonally
    /// dominant in every row, well conditioned enough for a 1e-12 comparison.
    fn random_triplets(n: usize, rng: &mut Lcg) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
        let (mut r, mut c, mut v) = (vec![], vec![], vec![]);
        for i in 0..n {
            r.push(i);
            c.push(i);
            v.push(2.5 + 0.5 * rng.next());
            for j in 0..n {
                if j != i && rng.next() > 0.84 {
                    r.push(i);
                    c.push(j);
                    v.push(rng.next());
                }
            }
        }
        for k in 0..10 {
            r.push(r[7 * k]);
            c.push(c[7 * k]);
            v.push(0.1 * rng.next());
        }
        (r, c, v)
    }

    #[test]
    fn sparse_lu_matches_a_dense_solve_on_a_random_matrix() {
        let n = 60;
        let mut rng = Lcg(12345);
        let (r, c, v) = random_triplets(n, &mut rng);
        let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let expected = dense_solve(dense_of(n, &r, &c, &v), b.clone());
        let mut lu: SparseLu = SparseLu::new();
        lu.set_pattern(n, &r, &c).unwrap();
        lu.factorize(&v).unwrap();
        let mut x = b.clone();
        lu.solve_in_place(&mut x).unwrap();
        let scale = expected.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
        for i in 0..n {
            // both are backward stable; cond(A) is O(10) here, so 1e-12 is round-off
            assert!((x[i] - expected[i]).abs() < 1e-12 * scale, "{i}: {} vs {}", x[i], expected[i]);
        }
        // a second numeric factorisation reuses the symbolic one
        lu.factorize(&v).unwrap();
        assert_eq!((lu.symbolic_factorisations, lu.numeric_factorisations), (1, 2));
    }

    #[test]
    fn periodic_system_with_a_duplicate_entry() {
        let n = 50;
        let (mut r, mut c, mut v) = (vec![], vec![], vec![]);
        for i in 0..n {
            for (j, a) in [(i, 4.0), ((i + 1) % n, -1.0), ((i + n - 1) % n, -1.0)] {
                r.push(i);
                c.push(j);
                v.push(a);
            }
        }
        r.push(0);
        c.push(0);
        v.push(1.0);
        let mut lu: SparseLu = SparseLu::new();
        lu.set_pattern(n, &r, &c).unwrap();
        lu.factorize(&v).unwrap();
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let mut b = vec![0.0; n];
        for k in 0..r.len() {
            b[r[k]] += v[k] * x[c[k]];
        }
        lu.solve_in_place(&mut b).unwrap();
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-13);
        }
    }

    #[test]
    fn failures_are_typed() {
        let mut lu: SparseLu = SparseLu::new();
        assert_eq!(lu.solve_in_place(&mut [1.0]), Err(LinearError::NotFactorised));
        assert!(matches!(lu.set_pattern(2, &[0, 2], &[0, 1]), Err(LinearError::InvalidPattern { n: 2, .. })));
        lu.set_pattern(2, &[0, 1, 0, 1], &[0, 0, 1, 1]).unwrap();
        assert_eq!(lu.factorize(&[1.0, f64::NAN, 0.0, 1.0]), Err(LinearError::NonFiniteMatrix { index: 1 }));
        // rank 1: [[1, 2], [2, 4]]
        let singular = lu.factorize(&[1.0, 2.0, 2.0, 4.0]).and_then(|()| lu.solve_in_place(&mut [1.0, 1.0]));
        assert!(matches!(singular, Err(LinearError::Singular { .. } | LinearError::NonFiniteSolution)), "{singular:?}");
        lu.factorize(&[1.0, 0.0, 0.0, 1.0]).unwrap();
        assert!(matches!(lu.solve_in_place(&mut [1.0]), Err(LinearError::DimensionMismatch { expected: 2, got: 1, .. })));
        // the message form for callers that still carry strings
        let msg: Result<(), String> = SparseLu::<String>::new().solve_in_place(&mut []);
        assert_eq!(msg, Err("solve before factorisation".to_string()));
    }

    #[test]
    fn triplet_lu_recomputes_the_symbolic_lu_only_on_a_new_pattern() {
        let n = 30;
        let mut rng = Lcg(7);
        let (r, c, v) = random_triplets(n, &mut rng);
        let mut lu: TripletLu = TripletLu::new();
        let b: Vec<f64> = (0..n).map(|i| i as f64).collect();
        for scale in [1.0, 2.0] {
            let vs: Vec<f64> = v.iter().map(|x| scale * x).collect();
            lu.factorize(n, &r, &c, &vs).unwrap();
            let mut x = b.clone();
            lu.solve_in_place(&mut x).unwrap();
            let expected = dense_solve(dense_of(n, &r, &c, &vs), b.clone());
            for i in 0..n {
                assert!((x[i] - expected[i]).abs() < 1e-11 * (1.0 + expected[i].abs()));
            }
        }
        assert_eq!((lu.symbolic_factorisations(), lu.numeric_factorisations()), (1, 2));
        // one entry fewer: a new pattern
        lu.factorize(n, &r[..r.len() - 1], &c[..c.len() - 1], &v[..v.len() - 1]).unwrap();
        assert_eq!((lu.symbolic_factorisations(), lu.numeric_factorisations()), (2, 3));
        assert!(matches!(lu.factorize(n, &r, &c, &v[1..]), Err(LinearError::DimensionMismatch { .. })));
    }

    /// The bordered solve against the plain LU of the whole matrix on a periodic band
    /// with two dense border rows and columns (the shape of the drive's Newton systems),
    /// with and without a diagonal shift.
    #[test]
    fn bordered_solve_matches_the_plain_lu() {
        let n = 40;
        let border = [17, 31];
        let (mut r, mut c, mut v) = (vec![], vec![], vec![]);
        for i in 0..n {
            for (j, a) in [(i, 5.0 + 0.1 * i as f64), ((i + 1) % n, -1.0), ((i + n - 1) % n, -1.3)] {
                r.push(i);
                c.push(j);
                v.push(a);
            }
            for (k, &b) in border.iter().enumerate() {
                r.push(i);
                c.push(b);
                v.push(0.01 * (i + k) as f64);
                r.push(b);
                c.push(i);
                v.push(0.02 * (i as f64 - 3.0 * k as f64).sin());
            }
        }
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        // faer's LU of A, and the banded one (A's wrap-around in its own border)
        for banded in [false, true] {
            let mut bordered: BorderedLu = if banded { BorderedLu::banded(&r, &c, n, border) } else { BorderedLu::new(&r, &c, n, border) }.unwrap();
            assert_eq!(bordered.lu.band_structure().map(|s| s.border.len()), banded.then_some(1));
            for shift in [vec![], vec![0.5; n]] {
                // the plain LU of the same matrix, the shift added as diagonal triplets
                let (mut rp, mut cp, mut vp) = (r.clone(), c.clone(), v.clone());
                for (i, s) in shift.iter().enumerate() {
                    rp.push(i);
                    cp.push(i);
                    vp.push(*s);
                }
                let mut plain: TripletLu = TripletLu::new();
                plain.factorize(n, &rp, &cp, &vp).unwrap();
                let mut expected = rhs.clone();
                plain.solve_in_place(&mut expected).unwrap();
                let mut x = rhs.clone();
                bordered.solve(&v, &shift, &mut x).unwrap();
                for i in 0..n {
                    assert!((x[i] - expected[i]).abs() < 1e-12, "{i}: {} vs {}", x[i], expected[i]);
                }
            }
            assert_eq!(bordered.factorisations(), 2);
            // the second border row all zero: S has a zero row
            let vs: Vec<f64> = r.iter().zip(&v).map(|(&ri, &vi)| if ri == border[1] { 0.0 } else { vi }).collect();
            let mut x = rhs.clone();
            assert_eq!(bordered.solve(&vs, &[], &mut x), Err(LinearError::SingularSchur { det: 0.0 }));
        }
        assert!(matches!(BorderedLu::<LinearError>::new(&r, &c, n, [3, 3]), Err(LinearError::InvalidPattern { .. })));
    }
}
