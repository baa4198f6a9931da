//! Jacobians of the problem functions by forward-mode AD (`num_dual::Dual64`) or by
//! central finite differences (for tests and as a cross-check).
//!
//! Matrices are dense, row-major `Vec<f64>`.

use crate::problem::{JacobianMode, Problem};
use num_dual::{Dual64, DualSVec64};

/// Central-difference step for argument value `u`: ε^{1/3} · max(1, |u|), ε = 2^-52.
fn fd_step(u: f64) -> f64 {
    f64::EPSILON.cbrt() * u.abs().max(1.0)
}

/// `values` as dual numbers, the entry at `seed` (if any) with derivative part 1: the
/// input of one forward-mode AD pass for the column of that entry.
fn seeded(values: &[f64], seed: Option<usize>) -> Vec<Dual64> {
    values
        .iter()
        .enumerate()
        .map(|(i, &v)| if Some(i) == seed { Dual64::from_re(v).derivative() } else { Dual64::from_re(v) })
        .collect()
}

/// Value and derivatives of f_k at (x, y, p, η).
///
/// Returns `(f, dfdy, dfdp, dfdeta)`: `f` has n_k entries, `dfdy` is n_k × n_k,
/// `dfdp` is n_k × n_p (both row-major) and `dfdeta` has n_k entries.
pub fn rhs_jacobian<P: Problem>(
    problem: &P,
    mode: JacobianMode,
    k: usize,
    x: f64,
    y: &[f64],
    p: &[f64],
    eta: f64,
) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = y.len();
    let np = p.len();
    let mut f = vec![0.0; n];
    problem.rhs(k, x, y, p, eta, &mut f);
    let mut dfdy = vec![0.0; n * n];
    let mut dfdp = vec![0.0; n * np];
    let mut dfdeta = vec![0.0; n];
    // Column j of the full derivative [∂f/∂y | ∂f/∂p | ∂f/∂η].
    let column = |j: usize, out: &mut [f64]| match mode {
        JacobianMode::Ad => {
            let yd = seeded(y, Some(j));
            let pd = seeded(p, j.checked_sub(n));
            let ed = if j == n + np { Dual64::from_re(eta).derivative() } else { Dual64::from_re(eta) };
            let mut fd = vec![Dual64::from_re(0.0); n];
            problem.rhs(k, x, &yd, &pd, ed, &mut fd);
            for (o, v) in out.iter_mut().zip(&fd) {
                *o = v.eps;
            }
        }
        JacobianMode::FiniteDifference => {
            // f with argument j of (y, p, η) set to `value`.
            let f_with = |value: f64| -> Vec<f64> {
                let (mut yv, mut pv, mut ev) = (y.to_vec(), p.to_vec(), eta);
                let slot: &mut f64 = if j < n {
                    &mut yv[j]
                } else if j < n + np {
                    &mut pv[j - n]
                } else {
                    &mut ev
                };
                *slot = value;
                let mut fv = vec![0.0; n];
                problem.rhs(k, x, &yv, &pv, ev, &mut fv);
                fv
            };
            let u0 = if j < n {
                y[j]
            } else if j < n + np {
                p[j - n]
            } else {
                eta
            };
            let h = fd_step(u0);
            let (fp, fm) = (f_with(u0 + h), f_with(u0 - h));
            for i in 0..n {
                out[i] = (fp[i] - fm[i]) / (2.0 * h);
            }
        }
    };
    let mut col = vec![0.0; n];
    // Columns of y, of the parameters f_k can depend on (the others are exactly zero),
    // and of η.
    let declared = problem.rhs_params(k);
    let reads = |i: usize| declared.is_none_or(|params| params.binary_search(&i).is_ok());
    for j in (0..n + np + 1).filter(|&j| j < n || j == n + np || reads(j - n)) {
        column(j, &mut col);
        for (i, &value) in col.iter().enumerate() {
            put_entry(i, j, n, np, value, &mut dfdy, &mut dfdp, &mut dfdeta);
        }
    }
    (f, dfdy, dfdp, dfdeta)
}

/// Entry (i, j) of the full derivative [∂f/∂y | ∂f/∂p | ∂f/∂η] (n components, n_p
/// parameters) written into its part: ∂f/∂y and ∂f/∂p row-major, ∂f/∂η a column.
#[allow(clippy::too_many_arguments)]
#[inline]
fn put_entry(i: usize, j: usize, n: usize, np: usize, value: f64, dfdy: &mut [f64], dfdp: &mut [f64], dfdeta: &mut [f64]) {
    if j < n {
        dfdy[i * n + j] = value;
    } else if j < n + np {
        dfdp[i * np + (j - n)] = value;
    } else {
        dfdeta[i] = value;
    }
}

/// [`rhs_jacobian`] into reusable buffers, allocating nothing once the buffers have
/// their sizes. In AD mode the Jacobian columns are seeded side by side in vector dual
/// numbers (`DualSVec64<W>`, W = 2, 4 or 8 lanes): one pass of `rhs` gives up to 8
/// columns — the elastica's 6 (4 states, 2 loads) in one pass with one sin and one cos
/// instead of 6 passes of `Dual64`. Each lane carries the operations of the `Dual64`
/// pass of its column (num-dual's product, quotient and chain rules are the same
/// formulas for both), so the values are [`rhs_jacobian`]'s; only where a `Dual64`
/// pass adds an exact zero term (a derivative no seeded argument reaches, which
/// `DualVec` keeps as absent) can the sign of a zero entry differ.
#[derive(Debug, Default)]
pub struct RhsJacobian {
    /// f (n_k).
    pub f: Vec<f64>,
    /// ∂f/∂y, n_k × n_k row-major.
    pub dfdy: Vec<f64>,
    /// ∂f/∂p, n_k × n_p row-major.
    pub dfdp: Vec<f64>,
    /// ∂f/∂η (n_k).
    pub dfdeta: Vec<f64>,
    /// The columns evaluated: y's, the parameters f_k reads, η (index into (y, p, η)).
    columns: Vec<usize>,
    lanes2: Lanes<2>,
    lanes4: Lanes<4>,
    lanes8: Lanes<8>,
}

/// Arguments and result of one AD pass with W derivative lanes.
#[derive(Debug, Default)]
struct Lanes<const W: usize> {
    yd: Vec<DualSVec64<W>>,
    pd: Vec<DualSVec64<W>>,
    out: Vec<DualSVec64<W>>,
}

impl<const W: usize> Lanes<W> {
    /// One pass of `rhs` with the columns `chunk` (≤ W, indices into (y, p, η)) seeded
    /// in lanes 0, 1, …; their derivatives written into `jac`, and f too if `first`.
    #[allow(clippy::too_many_arguments)]
    fn pass<P: Problem>(&mut self, problem: &P, k: usize, x: f64, y: &[f64], p: &[f64], eta: f64, chunk: &[usize], first: bool, jac: &mut [Vec<f64>; 4]) {
        let n = y.len();
        let np = p.len();
        self.yd.clear();
        self.yd.extend(y.iter().map(|&v| DualSVec64::from_re(v)));
        self.pd.clear();
        self.pd.extend(p.iter().map(|&v| DualSVec64::from_re(v)));
        let mut ed = DualSVec64::from_re(eta);
        for (lane, &j) in chunk.iter().enumerate() {
            if j < n {
                self.yd[j] = self.yd[j].derivative(lane);
            } else if j < n + np {
                self.pd[j - n] = self.pd[j - n].derivative(lane);
            } else {
                ed = ed.derivative(lane);
            }
        }
        self.out.clear();
        self.out.resize(n, DualSVec64::from_re(0.0));
        problem.rhs(k, x, &self.yd, &self.pd, ed, &mut self.out);
        let [f, dfdy, dfdp, dfdeta] = jac;
        for (i, v) in self.out.iter().enumerate() {
            if first {
                f[i] = v.re;
            }
            // Absent derivative part: every lane zero (the buffers are zero-filled).
            let Some(d) = &v.eps.0 else { continue };
            for (lane, &j) in chunk.iter().enumerate() {
                put_entry(i, j, n, np, d[lane], dfdy, dfdp, dfdeta);
            }
        }
    }
}

impl RhsJacobian {
    /// Evaluate f_k and its derivatives at (x, y, p, η) into the buffers; the column
    /// ∂f/∂η only with `eta_column` (else `dfdeta` is left zero: the condensed Newton
    /// matrix at fixed η needs ∂f/∂y and ∂f/∂p alone).
    ///
    /// In AD mode f is the value part of the first dual pass — the same f64 operations
    /// as a plain call of `rhs`, so the same bits — instead of one more call.
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate<P: Problem>(
        &mut self,
        problem: &P,
        mode: JacobianMode,
        k: usize,
        x: f64,
        y: &[f64],
        p: &[f64],
        eta: f64,
        eta_column: bool,
    ) {
        if matches!(mode, JacobianMode::FiniteDifference) {
            (self.f, self.dfdy, self.dfdp, self.dfdeta) = rhs_jacobian(problem, mode, k, x, y, p, eta);
            return;
        }
        let n = y.len();
        let np = p.len();
        for (v, len) in [(&mut self.f, n), (&mut self.dfdy, n * n), (&mut self.dfdp, n * np), (&mut self.dfdeta, n)] {
            v.clear();
            v.resize(len, 0.0);
        }
        let declared = problem.rhs_params(k);
        let reads = |i: usize| declared.is_none_or(|params| params.binary_search(&i).is_ok());
        self.columns.clear();
        self.columns.extend((0..n + np + 1).filter(|&j| if j < n { true } else if j < n + np { reads(j - n) } else { eta_column }));
        let mut jac = [std::mem::take(&mut self.f), std::mem::take(&mut self.dfdy), std::mem::take(&mut self.dfdp), std::mem::take(&mut self.dfdeta)];
        let columns = &self.columns;
        match columns.len() {
            0..=2 => self.lanes2.pass(problem, k, x, y, p, eta, columns, true, &mut jac),
            3..=4 => self.lanes4.pass(problem, k, x, y, p, eta, columns, true, &mut jac),
            _ => {
                for (c, chunk) in columns.chunks(8).enumerate() {
                    self.lanes8.pass(problem, k, x, y, p, eta, chunk, c == 0, &mut jac);
                }
            }
        }
        [self.f, self.dfdy, self.dfdp, self.dfdeta] = jac;
    }
}

/// Value and full derivative of the boundary residual g.
///
/// Arguments are the stacked end states `ya[k] = y_k(0)`, `yb[k] = y_k(1)`.
/// Returns `(g, dg)` with `dg` of shape n_bc × (2 Σ n_k + n_p + 1), row-major, columns
/// ordered [y_0(0), y_0(1), y_1(0), y_1(1), …, p, η].
pub fn bc_jacobian<P: Problem>(
    problem: &P,
    mode: JacobianMode,
    ya: &[&[f64]],
    yb: &[&[f64]],
    p: &[f64],
    eta: f64,
) -> (Vec<f64>, Vec<f64>) {
    // Flatten all arguments into one vector u so that one column loop serves both modes.
    let dims: Vec<usize> = ya.iter().map(|s| s.len()).collect();
    let mut u: Vec<f64> = Vec::new();
    for k in 0..dims.len() {
        u.extend_from_slice(ya[k]);
        u.extend_from_slice(yb[k]);
    }
    let ny = u.len();
    u.extend_from_slice(p);
    u.push(eta);
    let nu = u.len();
    let nbc = problem.n_bc();

    fn eval_at<P: Problem, D: crate::problem::Scalar>(problem: &P, dims: &[usize], u: &[D], ny: usize, out: &mut [D]) {
        let mut ya: Vec<&[D]> = Vec::with_capacity(dims.len());
        let mut yb: Vec<&[D]> = Vec::with_capacity(dims.len());
        let mut off = 0;
        for &n in dims {
            ya.push(&u[off..off + n]);
            yb.push(&u[off + n..off + 2 * n]);
            off += 2 * n;
        }
        let nu = u.len();
        problem.bc(&ya, &yb, &u[ny..nu - 1], u[nu - 1], out);
    }

    let mut g = vec![0.0; nbc];
    eval_at(problem, &dims, &u, ny, &mut g);
    let mut dg = vec![0.0; nbc * nu];
    for j in 0..nu {
        match mode {
            JacobianMode::Ad => {
                let ud = seeded(&u, Some(j));
                let mut gd = vec![Dual64::from_re(0.0); nbc];
                eval_at(problem, &dims, &ud, ny, &mut gd);
                for i in 0..nbc {
                    dg[i * nu + j] = gd[i].eps;
                }
            }
            JacobianMode::FiniteDifference => {
                let h = fd_step(u[j]);
                let mut up = u.clone();
                up[j] += h;
                let mut um = u.clone();
                um[j] -= h;
                let mut gp = vec![0.0; nbc];
                let mut gm = vec![0.0; nbc];
                eval_at(problem, &dims, &up, ny, &mut gp);
                eval_at(problem, &dims, &um, ny, &mut gm);
                for i in 0..nbc {
                    dg[i * nu + j] = (gp[i] - gm[i]) / (2.0 * h);
                }
            }
        }
    }
    (g, dg)
}

/// The largest scaled difference |J_ad − J_fd| / (1 + |J_ad|) between the AD and the
/// central-difference Jacobians, over every entry of ∂f_k/∂(y, p, η) of every segment k
/// at (x, `ys[k]`, p, η) and of ∂g at (`ya`, `yb`, p, η). The derivative check every
/// problem's tests run: central differences with h ~ ε^{1/3} are accurate to O(ε^{2/3})
/// times the second-derivative scale, so a wrong AD entry (O(1)) stands far above it.
pub fn ad_fd_mismatch<P: Problem>(problem: &P, x: f64, ys: &[Vec<f64>], ya: &[&[f64]], yb: &[&[f64]], p: &[f64], eta: f64) -> f64 {
    let scaled = |a: &[f64], f: &[f64]| a.iter().zip(f).map(|(u, v)| (u - v).abs() / (1.0 + u.abs())).fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for (k, y) in ys.iter().enumerate() {
        let a = rhs_jacobian(problem, JacobianMode::Ad, k, x, y, p, eta);
        let f = rhs_jacobian(problem, JacobianMode::FiniteDifference, k, x, y, p, eta);
        worst = worst.max(scaled(&a.1, &f.1)).max(scaled(&a.2, &f.2)).max(scaled(&a.3, &f.3));
    }
    let (ga, da) = bc_jacobian(problem, JacobianMode::Ad, ya, yb, p, eta);
    let (gf, df) = bc_jacobian(problem, JacobianMode::FiniteDifference, ya, yb, p, eta);
    worst.max(scaled(&ga, &gf)).max(scaled(&da, &df))
}

/// [`ad_fd_mismatch`] at an arbitrary but fixed point of a problem with parameters `p`
/// at η: segment k's state y_i = 0.3 + 0.17 i − 0.05 k at x = 0.37, its end values
/// 0.2 + 0.1 (i + j) with j = 2k at ξ = 0 and 2k + 1 at ξ = 1 — generic values, so that
/// no derivative vanishes by symmetry.
pub fn ad_fd_mismatch_sampled<P: Problem>(problem: &P, p: &[f64], eta: f64) -> f64 {
    let m = problem.n_segments();
    let state = |k: usize| (0..problem.dim(k)).map(|i| 0.3 + 0.17 * i as f64 - 0.05 * k as f64).collect();
    let ys: Vec<Vec<f64>> = (0..m).map(state).collect();
    let end = |j: usize| -> Vec<f64> { (0..problem.dim(j / 2)).map(|i| 0.2 + 0.1 * (i + j) as f64).collect() };
    let ends: Vec<Vec<f64>> = (0..2 * m).map(end).collect();
    let ya: Vec<&[f64]> = (0..m).map(|k| ends[2 * k].as_slice()).collect();
    let yb: Vec<&[f64]> = (0..m).map(|k| ends[2 * k + 1].as_slice()).collect();
    ad_fd_mismatch(problem, 0.37, &ys, &ya, &yb, p, eta)
}
