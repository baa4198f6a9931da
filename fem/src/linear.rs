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
}
