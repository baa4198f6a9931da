//! Helpers of the unit tests: a reproducible random sequence and a dense reference solve.

/// A reproducible pseudo-random sequence in [−1, 1) (64-bit LCG, Knuth's MMIX
/// constants) — enough to scatter a test pattern; no statistical quality needed.
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Dense Gaussian elimination with partial pivoting (the reference solve).
pub fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs())).unwrap();
        a.swap(k, p);
        b.swap(k, p);
        let (pivot_rows, below) = a.split_at_mut(k + 1);
        let pivot = &pivot_rows[k];
        for (i, row) in below.iter_mut().enumerate() {
            let f = row[k] / pivot[k];
            for (x, &p) in row[k..].iter_mut().zip(&pivot[k..]) {
                *x -= f * p;
            }
            b[k + 1 + i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x
}

/// The dense matrix of (row, col, value) triplets, duplicates summed.
pub fn dense_of(n: usize, r: &[usize], c: &[usize], v: &[f64]) -> Vec<Vec<f64>> {
    let mut a = vec![vec![0.0; n]; n];
    for k in 0..r.len() {
        a[r[k]][c[k]] += v[k];
    }
    a
}

