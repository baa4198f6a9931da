//! Sparse LU of the global tangent on faer 0.24: the symbolic factorisation (with its
//! fill-reducing ordering) once per sparsity pattern, the numeric one per Newton
//! iteration (DEPENDENCIES.md).

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::MatMut;

/// A sparse LU with cached symbolic factorisation. Duplicate triplets are summed.
#[derive(Debug, Default)]
pub struct SparseLu {
    n: usize,
    pattern: Option<(SymbolicSparseColMat<usize>, Argsort<usize>, SymbolicLu<usize>)>,
    lu: Option<Lu<usize, f64>>,
    /// Symbolic factorisations done (1 per pattern).
    pub symbolic_factorisations: usize,
    /// Numeric factorisations done.
    pub numeric_factorisations: usize,
}

impl SparseLu {
    /// An empty factorisation.
    pub fn new() -> Self {
        Self::default()
    }

    /// Set the n × n pattern (`rows[k]`, `cols[k]`) and compute its symbolic LU.
    ///
    /// # Errors
    /// A description if the pattern is invalid or the symbolic factorisation fails.
    pub fn set_pattern(&mut self, n: usize, rows: &[usize], cols: &[usize]) -> Result<(), String> {
        if rows.len() != cols.len() || rows.iter().chain(cols).any(|&i| i >= n) {
            return Err(format!("invalid sparse pattern for an {n} × {n} matrix"));
        }
        let pairs: Vec<Pair<usize, usize>> = rows.iter().zip(cols).map(|(&r, &c)| Pair::new(r, c)).collect();
        let (sym, argsort) =
            SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).map_err(|e| format!("sparse pattern: {e:?}"))?;
        let symbolic = SymbolicLu::try_new(sym.as_ref()).map_err(|e| format!("symbolic LU: {e:?}"))?;
        self.symbolic_factorisations += 1;
        self.n = n;
        self.pattern = Some((sym, argsort, symbolic));
        self.lu = None;
        Ok(())
    }

    /// Numeric LU of the matrix with `values` in pattern order.
    ///
    /// # Errors
    /// A description if no pattern is set, a value is not finite, or the matrix is
    /// numerically singular.
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), String> {
        let (sym, argsort, symbolic) = self.pattern.as_ref().ok_or("no sparse pattern set")?;
        if !values.iter().all(|v| v.is_finite()) {
            return Err("non-finite tangent entries".into());
        }
        let mat = SparseColMat::new_from_argsort(sym.clone(), argsort, values).map_err(|e| format!("sparse matrix: {e:?}"))?;
        self.lu = None;
        let lu = Lu::try_new_with_symbolic(symbolic.clone(), mat.as_ref()).map_err(|e| format!("sparse LU: {e:?}"))?;
        self.numeric_factorisations += 1;
        self.lu = Some(lu);
        Ok(())
    }

    /// Overwrite `b` with A⁻¹ b.
    ///
    /// # Errors
    /// A description if there is no factorisation, `b` has the wrong length, or the
    /// result is not finite (a numerically singular matrix).
    pub fn solve_in_place(&self, b: &mut [f64]) -> Result<(), String> {
        let lu = self.lu.as_ref().ok_or("solve before factorisation")?;
        if b.len() != self.n {
            return Err(format!("right-hand side has {} entries, matrix is {}", b.len(), self.n));
        }
        lu.solve_in_place(MatMut::from_column_major_slice_mut(b, self.n, 1));
        if b.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err("the LU solve produced non-finite values (numerically singular tangent)".into())
        }
    }
}

/// Where a pattern entry of the full Jacobian goes in the bordered system.
#[derive(Debug, Clone, Copy)]
enum Entry {
    /// Inner block A (z, τ): position in the inner values.
    Inner(usize),
    /// Border column B: (inner row, border column).
    B(usize, usize),
    /// Border row C: (border row, inner column).
    C(usize, usize),
    /// Corner D: (border row, border column).
    D(usize, usize),
}

/// A sparse system [A B; C D] with two global unknowns as its border: A banded (the
/// loop), B, C the dense columns and rows of the two unknowns. A sparse LU of the whole
/// matrix fills in like AᵀA through the dense rows (measured for the steady drive,
/// docs/fem-drive.md §12: 4 → 850 ms from 128 to 2048 elements); A's LU and the 2 × 2
/// Schur complement S = D − C A⁻¹ B keep the cost linear. The drive's two solvers use it
/// with (c, ω₂) and (a, φ) as the border.
#[derive(Debug)]
pub struct BorderedLu {
    border: [usize; 2],
    global_of: Vec<usize>,
    entries: Vec<Entry>,
    inner_len: usize,
    inner_diagonal: Vec<usize>,
    lu: SparseLu,
}

impl BorderedLu {
    /// The system of the n × n pattern (`rows[k]`, `cols[k]`) with the unknowns `border`
    /// as its border; the symbolic LU of A is computed here.
    ///
    /// # Errors
    /// A description if the pattern is invalid.
    pub fn new(rows: &[usize], cols: &[usize], n: usize, border: [usize; 2]) -> Result<BorderedLu, String> {
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
        let mut lu = SparseLu::new();
        lu.set_pattern(global_of.len(), &ir, &ic)?;
        Ok(BorderedLu { border, global_of, entries, inner_len: ir.len(), inner_diagonal, lu })
    }

    /// Overwrite `rhs` with J⁻¹ rhs for the matrix `values` (pattern order, duplicates
    /// summed), with `shift` added to the diagonal (Levenberg–Marquardt; empty: none).
    ///
    /// # Errors
    /// A description if A is singular, the Schur complement is singular, or the result
    /// is not finite.
    pub fn solve(&mut self, values: &[f64], shift: &[f64], rhs: &mut [f64]) -> Result<(), String> {
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
                a[pos] += shift[self.global_of[i]];
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
        let s = [[d[0][0] - dot(&c[0], &b[0]), d[0][1] - dot(&c[0], &b[1])], [d[1][0] - dot(&c[1], &b[0]), d[1][1] - dot(&c[1], &b[1])]];
        let g = [rhs[self.border[0]] - dot(&c[0], &u), rhs[self.border[1]] - dot(&c[1], &u)];
        let det = s[0][0] * s[1][1] - s[0][1] * s[1][0];
        let scale = (s[0][0] * s[1][1]).abs().max((s[0][1] * s[1][0]).abs());
        if !(det.abs() > 1e-14 * scale && det.is_finite()) {
            return Err(format!("singular Schur complement of (c, ω₂): det {det:.3e}"));
        }
        let y = [(g[0] * s[1][1] - s[0][1] * g[1]) / det, (s[0][0] * g[1] - s[1][0] * g[0]) / det];
        for (i, &gl) in self.global_of.iter().enumerate() {
            rhs[gl] = u[i] - b[0][i] * y[0] - b[1][i] * y[1];
        }
        rhs[self.border[0]] = y[0];
        rhs[self.border[1]] = y[1];
        if rhs.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err("non-finite Newton step".into())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A periodic tridiagonal system (the shape of the loop closure) solved and checked.
    #[test]
    fn periodic_system() {
        let n = 50;
        let (mut r, mut c, mut v) = (vec![], vec![], vec![]);
        for i in 0..n {
            for (j, a) in [(i, 4.0), ((i + 1) % n, -1.0), ((i + n - 1) % n, -1.0)] {
                r.push(i);
                c.push(j);
                v.push(a);
            }
        }
        // a duplicate, summed
        r.push(0);
        c.push(0);
        v.push(1.0);
        let mut lu = SparseLu::new();
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
        lu.factorize(&v).unwrap();
        assert_eq!(lu.symbolic_factorisations, 1);
        assert_eq!(lu.numeric_factorisations, 2);
        assert!(lu.factorize(&vec![f64::NAN; v.len()]).is_err());
    }

    /// The bordered solve against the plain LU on a periodic band with two dense border
    /// rows and columns (the shape of the drive's Newton systems), with and without a
    /// diagonal shift.
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
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        for shift in [vec![], vec![0.5; n]] {
            let mut b = vec![0.0; n];
            for k in 0..r.len() {
                b[r[k]] += v[k] * x[c[k]];
            }
            if !shift.is_empty() {
                for i in 0..n {
                    b[i] += shift[i] * x[i];
                }
            }
            let mut bordered = BorderedLu::new(&r, &c, n, border).unwrap();
            bordered.solve(&v, &shift, &mut b).unwrap();
            for i in 0..n {
                assert!((b[i] - x[i]).abs() < 1e-12, "{i}: {} vs {}", b[i], x[i]);
            }
        }
    }
}
