//! The collocation equations on a fixed mesh: unknown layout, residual, sparse
//! Jacobian, dense output and the residual estimate used for mesh control.
//!
//! # Unknowns (vector z of length [`Discretisation::n`])
//!
//! Segment k with mesh 0 = x_0 < … < x_{N_k} = 1 and dimension n = n_k owns the block
//!
//! ```text
//!     [ y_0, Y_{0,1}, …, Y_{0,s}, y_1, Y_{1,1}, …, Y_{N−1,s}, y_N ]      ((N(s+1) + 1) n entries)
//! ```
//!
//! (node values y_i, stage values Y_{i,j} ≈ y(x_i + c_j h_i)); the n_p parameters come
//! after the last segment. The continuation parameter η is not part of z.
//!
//! # Equations (rows)
//!
//! Interval i of segment k gives (s + 1) n rows, in this order:
//!
//! ```text
//!     Y_{i,j} − y_i − h Σ_l a_jl f_k(x_i + c_l h, Y_{i,l}, p, η) = 0,   j = 1..s   (stage equations)
//!     y_{i+1} − y_i − h Σ_l b_l  f_k(x_i + c_l h, Y_{i,l}, p, η) = 0              (continuity)
//! ```
//!
//! and the Σ n_k + n_p boundary rows g(y_0(0), y_0(1), …, p, η) = 0 come last, so the
//! system is square.

use super::condensed::small_n;
use super::scheme::{horner, Scheme, Tableau};
use crate::error::BvpError;
use crate::jacobian::{bc_jacobian, rhs_jacobian};
use crate::problem::{JacobianMode, Problem};
use crate::solution::{SegmentSolution, Solution, Stats};
use std::cell::Cell;
use std::rc::Rc;

/// 5-point Lobatto quadrature on [0, 1] (exact for degree 7): nodes and weights.
const LOBATTO5_T: [f64; 5] = [
    0.0,
    0.172_673_164_646_011_4, // (1 − √(3/7)) / 2
    0.5,
    0.827_326_835_353_988_6, // (1 + √(3/7)) / 2
    1.0,
];
const LOBATTO5_W: [f64; 5] = [1.0 / 20.0, 49.0 / 180.0, 16.0 / 45.0, 49.0 / 180.0, 1.0 / 20.0];

/// Check a mesh: at least two nodes, finite, strictly increasing, from 0 to 1.
pub(crate) fn validate_mesh(mesh: &[f64], what: &str) -> Result<(), BvpError> {
    if mesh.len() < 2 {
        return Err(BvpError::InvalidInput(format!("{what}: a mesh needs at least 2 nodes")));
    }
    if mesh.iter().any(|x| !x.is_finite()) {
        return Err(BvpError::NonFinite { what: format!("{what} mesh") });
    }
    if mesh.windows(2).any(|w| w[1] <= w[0]) {
        return Err(BvpError::InvalidInput(format!("{what}: mesh not strictly increasing")));
    }
    let (a, b) = (mesh[0], mesh[mesh.len() - 1]);
    if a.abs() > 1e-12 || (b - 1.0).abs() > 1e-12 {
        return Err(BvpError::InvalidInput(format!("{what}: mesh must span [0, 1], spans [{a}, {b}]")));
    }
    Ok(())
}

/// One collocation row of F: end − start − h Σ_l w_l f_l with w a row of the tableau's A
/// (stage row) or its b (continuity row) and f_l the l-th stage slope of component a
/// (`slopes` holds the s stage slopes of dimension n one after the other).
pub(crate) struct OdeRow<'r> {
    end: f64,
    start: f64,
    h: f64,
    weights: &'r [f64],
    slopes: &'r [f64],
    n: usize,
    a: usize,
}

impl OdeRow<'_> {
    /// The terms w_l f_la, l = 1 … s.
    fn weighted(&self) -> impl Iterator<Item = f64> + '_ {
        self.weights.iter().enumerate().map(|(l, w)| w * self.slopes[l * self.n + self.a])
    }
}

/// The collocation system of a problem on a fixed set of meshes.
pub(crate) struct Discretisation<'a, P: Problem> {
    pub problem: &'a P,
    pub scheme: Scheme,
    pub tab: Tableau,
    pub mode: JacobianMode,
    /// One mesh per segment.
    pub meshes: Vec<Vec<f64>>,
    /// n_k per segment.
    pub dims: Vec<usize>,
    /// First unknown of each segment block; `offsets[m]` is the first parameter.
    pub offsets: Vec<usize>,
    /// First collocation row of each segment; `row_offsets[m]` is the first BC row.
    pub row_offsets: Vec<usize>,
    pub n_params: usize,
    /// Number of unknowns (= equations).
    pub n: usize,
    /// Right-hand-side evaluations with f64 arguments (including those inside
    /// finite-difference Jacobians), shared by all discretisations derived with
    /// [`Self::with_meshes`].
    pub rhs_evals: Rc<Cell<usize>>,
}

impl<'a, P: Problem> Discretisation<'a, P> {
    pub fn new(problem: &'a P, scheme: Scheme, mode: JacobianMode, meshes: Vec<Vec<f64>>) -> Result<Self, BvpError> {
        Self::with_counter(problem, scheme, mode, meshes, Rc::new(Cell::new(0)))
    }

    fn with_counter(
        problem: &'a P,
        scheme: Scheme,
        mode: JacobianMode,
        meshes: Vec<Vec<f64>>,
        rhs_evals: Rc<Cell<usize>>,
    ) -> Result<Self, BvpError> {
        let m = problem.n_segments();
        if m == 0 {
            return Err(BvpError::InvalidInput("problem has no segments".into()));
        }
        if meshes.len() != m {
            return Err(BvpError::InvalidInput(format!("{} meshes for {m} segments", meshes.len())));
        }
        let mut meshes = meshes;
        for (k, mesh) in meshes.iter_mut().enumerate() {
            validate_mesh(mesh, &format!("segment {k}"))?;
            let last = mesh.len() - 1;
            mesh[0] = 0.0;
            mesh[last] = 1.0;
        }
        let dims: Vec<usize> = (0..m).map(|k| problem.dim(k)).collect();
        if dims.contains(&0) {
            return Err(BvpError::InvalidInput("a segment has ODE dimension 0".into()));
        }
        let n_params = problem.n_params();
        let tab = Tableau::new(scheme);
        let s = tab.s;
        let mut offsets = vec![0];
        let mut row_offsets = vec![0];
        for k in 0..m {
            let intervals = meshes[k].len() - 1;
            offsets.push(offsets[k] + (intervals * (s + 1) + 1) * dims[k]);
            row_offsets.push(row_offsets[k] + intervals * (s + 1) * dims[k]);
        }
        let n = offsets[m] + n_params;
        let n_bc = problem.n_bc();
        if row_offsets[m] + n_bc != n {
            return Err(BvpError::InvalidInput(format!(
                "problem has {n_bc} boundary conditions, needs Σ n_k + n_p = {}",
                dims.iter().sum::<usize>() + n_params
            )));
        }
        Ok(Self { problem, scheme, tab, mode, meshes, dims, offsets, row_offsets, n_params, n, rhs_evals })
    }

    /// The same problem and scheme on other meshes.
    pub fn with_meshes(&self, meshes: Vec<Vec<f64>>) -> Result<Self, BvpError> {
        Self::with_counter(self.problem, self.scheme, self.mode, meshes, self.rhs_evals.clone())
    }

    pub fn n_segments(&self) -> usize {
        self.dims.len()
    }

    /// Total number of mesh nodes over all segments.
    pub fn n_nodes(&self) -> usize {
        self.meshes.iter().map(Vec::len).sum()
    }

    /// Index of y_i (node i) of segment k in z.
    pub fn node(&self, k: usize, i: usize) -> usize {
        self.offsets[k] + i * (self.tab.s + 1) * self.dims[k]
    }

    /// Index of the stage value Y_{i,j} of segment k in z.
    pub fn stage(&self, k: usize, i: usize, j: usize) -> usize {
        self.node(k, i) + (j + 1) * self.dims[k]
    }

    /// First row of interval i of segment k.
    pub(crate) fn row(&self, k: usize, i: usize) -> usize {
        self.row_offsets[k] + i * (self.tab.s + 1) * self.dims[k]
    }

    /// Parameters p inside z.
    pub fn params<'z>(&self, z: &'z [f64]) -> &'z [f64] {
        &z[self.offsets[self.n_segments()]..]
    }

    pub(crate) fn count(&self, evals: usize) {
        self.rhs_evals.set(self.rhs_evals.get() + evals);
    }

    /// f_k at stage (i, j) with f64 arguments.
    fn stage_rhs(&self, z: &[f64], eta: f64, k: usize, i: usize, out: &mut [f64]) {
        let n = self.dims[k];
        let s = self.tab.s;
        let mesh = &self.meshes[k];
        let h = mesh[i + 1] - mesh[i];
        let p = self.params(z);
        for j in 0..s {
            let y = &z[self.stage(k, i, j)..self.stage(k, i, j) + n];
            self.problem.rhs(k, mesh[i] + self.tab.c[j] * h, y, p, eta, &mut out[j * n..(j + 1) * n]);
        }
        self.count(s);
    }

    /// End states y_k(0), y_k(1) of all segments.
    pub(crate) fn ends<'z>(&self, z: &'z [f64]) -> (Vec<&'z [f64]>, Vec<&'z [f64]>) {
        let m = self.n_segments();
        let ya = (0..m).map(|k| &z[self.node(k, 0)..self.node(k, 0) + self.dims[k]]).collect();
        let yb = (0..m)
            .map(|k| {
                let i = self.node(k, self.meshes[k].len() - 1);
                &z[i..i + self.dims[k]]
            })
            .collect();
        (ya, yb)
    }

    /// Every collocation row of F (all but the boundary rows) as `put(row, terms)`:
    /// F_row = end − start − h Σ_l w_l f_l ([`OdeRow`]), for [`Self::residual_terms`]
    /// ([`Self::residual`] computes the same rows by [`interval_residual`]).
    fn ode_rows(&self, z: &[f64], eta: f64, mut put: impl FnMut(usize, OdeRow<'_>)) {
        let s = self.tab.s;
        let mut f = Vec::new();
        for k in 0..self.n_segments() {
            let n = self.dims[k];
            f.resize(s * n, 0.0);
            let mesh = &self.meshes[k];
            for i in 0..mesh.len() - 1 {
                let h = mesh[i + 1] - mesh[i];
                self.stage_rhs(z, eta, k, i, &mut f);
                let yi = self.node(k, i);
                let yn = self.node(k, i + 1);
                let row = self.row(k, i);
                for j in 0..s {
                    let yj = self.stage(k, i, j);
                    for a in 0..n {
                        let weights = &self.tab.a[j * s..(j + 1) * s];
                        put(row + j * n + a, OdeRow { end: z[yj + a], start: z[yi + a], h, weights, slopes: &f, n, a });
                    }
                }
                for a in 0..n {
                    put(row + s * n + a, OdeRow { end: z[yn + a], start: z[yi + a], h, weights: &self.tab.b, slopes: &f, n, a });
                }
            }
        }
    }

    /// Residual F(z, η) of the module documentation into `r` (length n).
    ///
    /// Per interval the rows of [`Self::ode_rows`] with the same operations in the same
    /// order ([`interval_residual`], n a constant for n ≤ 6): the closures and index
    /// arithmetic of the generic row loop were ~60 % of a residual pass of the gauss8
    /// elastica.
    pub fn residual(&self, z: &[f64], eta: f64, r: &mut [f64]) {
        let s = self.tab.s;
        let mut f = Vec::new();
        for k in 0..self.n_segments() {
            let n = self.dims[k];
            f.resize(s * n, 0.0);
            let mesh = &self.meshes[k];
            for i in 0..mesh.len() - 1 {
                let h = mesh[i + 1] - mesh[i];
                self.stage_rhs(z, eta, k, i, &mut f);
                let yi = self.node(k, i);
                let row = self.row(k, i);
                let zb = &z[yi..yi + (s + 2) * n];
                let rb = &mut r[row..row + (s + 1) * n];
                small_n!(n, nc => match s {
                    2 => interval_residual(nc, 2, &self.tab, h, zb, &f, rb),
                    3 => interval_residual(nc, 3, &self.tab, h, zb, &f, rb),
                    4 => interval_residual(nc, 4, &self.tab, h, zb, &f, rb),
                    _ => interval_residual(nc, s, &self.tab, h, zb, &f, rb),
                });
            }
        }
        let (ya, yb) = self.ends(z);
        let m = self.n_segments();
        self.problem.bc(&ya, &yb, self.params(z), eta, &mut r[self.row_offsets[m]..]);
    }

    /// The magnitude T_i of the terms that [`Self::residual`] sums in each row i, so that
    /// its rounding error is |δF_i| ≲ u T_i (u = 2⁻⁵³; each row is a short sum whose
    /// partial sums are bounded by T_i):
    ///
    /// ```text
    ///     stage row (j, a):       |Y_ja| + |y_ia| + h Σ_l |a_jl| |f_la|,
    ///     continuity row a:       |y_{i+1,a}| + |y_ia| + h Σ_l |b_l| |f_la|,
    ///     boundary row r:         |g_r| + Σ_c |∂g_r/∂w_c| |w_c|   (w: segment ends, p, η),
    /// ```
    ///
    /// the boundary rows' terms estimated to first order through their derivatives (a
    /// function of the ends is a sum of terms of that size). Written into `t` (length n).
    pub fn residual_terms(&self, z: &[f64], eta: f64, t: &mut [f64]) {
        self.ode_rows(z, eta, |row, o| t[row] = o.end.abs() + o.start.abs() + o.h * o.weighted().map(f64::abs).sum::<f64>());
        let (ya, yb) = self.ends(z);
        let m = self.n_segments();
        let p = self.params(z);
        let (g, dg) = bc_jacobian(self.problem, self.mode, &ya, &yb, p, eta);
        // Columns of dg: [y_0(0), y_0(1), y_1(0), y_1(1), …, p, η].
        let args: Vec<f64> = (0..m).flat_map(|k| ya[k].iter().chain(yb[k]).copied()).chain(p.iter().copied()).chain([eta]).collect();
        let nu = args.len();
        for (r, gr) in g.iter().enumerate() {
            let terms: f64 = args.iter().enumerate().map(|(c, w)| (dg[r * nu + c] * w).abs()).sum();
            t[self.row_offsets[m] + r] = gr.abs() + terms;
        }
    }

    /// The boundary residual g alone.
    pub fn bc_residual(&self, z: &[f64], eta: f64) -> Vec<f64> {
        let (ya, yb) = self.ends(z);
        let mut g = vec![0.0; self.problem.n_bc()];
        self.problem.bc(&ya, &yb, self.params(z), eta, &mut g);
        g
    }

    /// Jacobian ∂F/∂z as triplets (appended to `rows`, `cols`, `vals` after clearing
    /// them; the pattern depends only on the mesh) and the dense column ∂F/∂η into
    /// `jeta` (length n).
    pub fn jacobian(
        &self,
        z: &[f64],
        eta: f64,
        rows: &mut Vec<usize>,
        cols: &mut Vec<usize>,
        vals: &mut Vec<f64>,
        jeta: &mut Vec<f64>,
    ) {
        rows.clear();
        cols.clear();
        vals.clear();
        jeta.clear();
        jeta.resize(self.n, 0.0);
        let s = self.tab.s;
        let np = self.n_params;
        let pofs = self.offsets[self.n_segments()];
        let p = self.params(z).to_vec();
        let mut push = |r: usize, c: usize, v: f64| {
            rows.push(r);
            cols.push(c);
            vals.push(v);
        };
        for k in 0..self.n_segments() {
            let n = self.dims[k];
            let per_call = super::condensed::per_call(self.mode, n, np);
            let mesh = &self.meshes[k];
            let mut jac = Vec::with_capacity(s);
            for i in 0..mesh.len() - 1 {
                let h = mesh[i + 1] - mesh[i];
                jac.clear();
                for j in 0..s {
                    let y = &z[self.stage(k, i, j)..self.stage(k, i, j) + n];
                    let x = mesh[i] + self.tab.c[j] * h;
                    jac.push(rhs_jacobian(self.problem, self.mode, k, x, y, &p, eta));
                }
                self.count(s * per_call);
                let yi = self.node(k, i);
                let yn = self.node(k, i + 1);
                let row = self.row(k, i);
                // s stage rows (weights a_j·) and the continuity row (weights b).
                for j in 0..=s {
                    let w: &[f64] = if j < s { &self.tab.a[j * s..(j + 1) * s] } else { &self.tab.b };
                    for a in 0..n {
                        let r = row + j * n + a;
                        push(r, yi + a, -1.0);
                        if j == s {
                            push(r, yn + a, 1.0);
                        }
                        for l in 0..s {
                            let dfdy = &jac[l].1;
                            let ys = self.stage(k, i, l);
                            for b in 0..n {
                                let mut v = -h * w[l] * dfdy[a * n + b];
                                if l == j && a == b {
                                    v += 1.0;
                                }
                                push(r, ys + b, v);
                            }
                        }
                        for q in 0..np {
                            let v: f64 = (0..s).map(|l| w[l] * jac[l].2[a * np + q]).sum();
                            push(r, pofs + q, -h * v);
                        }
                        jeta[r] = -h * (0..s).map(|l| w[l] * jac[l].3[a]).sum::<f64>();
                    }
                }
            }
        }
        // Boundary rows: columns of dg are [y_0(0), y_0(1), y_1(0), y_1(1), …, p, η].
        let (ya, yb) = self.ends(z);
        let (_, dg) = bc_jacobian(self.problem, self.mode, &ya, &yb, self.params(z), eta);
        let m = self.n_segments();
        let mut colmap = Vec::new();
        for k in 0..m {
            let a0 = self.node(k, 0);
            let b0 = self.node(k, self.meshes[k].len() - 1);
            colmap.extend(a0..a0 + self.dims[k]);
            colmap.extend(b0..b0 + self.dims[k]);
        }
        colmap.extend(pofs..pofs + np);
        let nu = colmap.len() + 1;
        let r0 = self.row_offsets[m];
        for i in 0..self.problem.n_bc() {
            for (c, &col) in colmap.iter().enumerate() {
                push(r0 + i, col, dg[i * nu + c]);
            }
            jeta[r0 + i] = dg[i * nu + nu - 1];
        }
    }

    /// Stage slopes K_{i,l} = f_k(x_i + c_l h, Y_{i,l}) of segment k, laid out
    /// `[i][l][a]` (length N s n).
    fn slopes(&self, z: &[f64], eta: f64, k: usize) -> Vec<f64> {
        let n = self.dims[k];
        let s = self.tab.s;
        let intervals = self.meshes[k].len() - 1;
        let mut out = vec![0.0; intervals * s * n];
        for i in 0..intervals {
            self.stage_rhs(z, eta, k, i, &mut out[i * s * n..(i + 1) * s * n]);
        }
        out
    }

    /// Collocation polynomials (dense output) of segment k: power-basis coefficients
    /// `poly[i][a][m]`, u_a(x_i + t h) = Σ_m c_m t^m, degree s.
    fn polys(&self, z: &[f64], slopes: &[f64], k: usize) -> Vec<Vec<Vec<f64>>> {
        let (n, s) = (self.dims[k], self.tab.s);
        let mut c = vec![0.0; n * (s + 1)];
        (0..self.meshes[k].len() - 1)
            .map(|i| {
                self.interval_poly(z, slopes, k, i, &mut c);
                c.chunks(s + 1).map(<[f64]>::to_vec).collect()
            })
            .collect()
    }

    /// The collocation polynomial of interval i of segment k into `c` (length n (s + 1),
    /// component a at `c[a (s + 1)..]`): u_a(x_i + t h) = Σ_m c_m t^m
    /// ([`poly_coefficients`], with n and s constants where they are small).
    fn interval_poly(&self, z: &[f64], slopes: &[f64], k: usize, i: usize, c: &mut [f64]) {
        let (n, s) = (self.dims[k], self.tab.s);
        let mesh = &self.meshes[k];
        let h = mesh[i + 1] - mesh[i];
        let yi = self.node(k, i);
        let y = &z[yi..yi + n];
        let kk = &slopes[i * s * n..(i + 1) * s * n];
        let lag = &self.tab.lagrange;
        small_n!(n, nc => match s {
            2 => poly_coefficients(nc, 2, h, y, kk, lag, c),
            3 => poly_coefficients(nc, 3, h, y, kk, lag, c),
            4 => poly_coefficients(nc, 4, h, y, kk, lag, c),
            _ => poly_coefficients(nc, s, h, y, kk, lag, c),
        });
    }

    /// The discrete solution as a [`Solution`] with the collocation polynomials as
    /// dense output.
    pub fn to_solution(&self, z: &[f64], eta: f64, stats: Stats) -> Solution {
        let segments = (0..self.n_segments())
            .map(|k| {
                let n = self.dims[k];
                let slopes = self.slopes(z, eta, k);
                let poly = self.polys(z, &slopes, k);
                let nodes =
                    (0..self.meshes[k].len()).map(|i| z[self.node(k, i)..self.node(k, i) + n].to_vec()).collect();
                SegmentSolution { mesh: self.meshes[k].clone(), nodes, poly }
            })
            .collect();
        Solution { segments, params: self.params(z).to_vec(), eta, stats }
    }

    /// Unknowns z on this discretisation from the dense output of `source` (node and
    /// stage values sampled from `source.eval`, parameters copied).
    pub fn sample(&self, source: &Solution) -> Result<Vec<f64>, BvpError> {
        validate_solution(self.problem, source, "solution to sample")?;
        let mut z = vec![0.0; self.n];
        for k in 0..self.n_segments() {
            let n = self.dims[k];
            let mesh = &self.meshes[k];
            let seg = &source.segments[k];
            for (i, &x) in mesh.iter().enumerate() {
                seg.eval_into(x, &mut z[self.node(k, i)..self.node(k, i) + n]);
                if i + 1 < mesh.len() {
                    let h = mesh[i + 1] - x;
                    for j in 0..self.tab.s {
                        let at = self.stage(k, i, j);
                        seg.eval_into(x + self.tab.c[j] * h, &mut z[at..at + n]);
                    }
                }
            }
        }
        let pofs = self.offsets[self.n_segments()];
        z[pofs..].copy_from_slice(&source.params);
        if z.iter().any(|v| !v.is_finite()) {
            return Err(BvpError::NonFinite { what: "sampled initial guess".into() });
        }
        Ok(z)
    }

    /// Residual estimate per interval and the boundary residual.
    ///
    /// ρ_i = ( ∫_0^1 Σ_a [ (u_a'(x) − f_a(x, u(x))) / (1 + |f_a(x, u(x))|) ]² dt )^{1/2},
    /// x = x_i + t h_i, by 5-point Lobatto quadrature (u: collocation polynomial);
    /// the boundary residual is max_i |g_i|. Returns (ρ per segment per interval,
    /// boundary residual).
    pub fn residual_norms(&self, z: &[f64], eta: f64) -> Result<(Vec<Vec<f64>>, f64), BvpError> {
        self.estimate(z, eta, None)
    }

    /// [`Self::residual_norms`] and the dense output at the same point: the
    /// [`Solution`] of [`Self::to_solution`] (default stats) to the bit, built from the
    /// stage slopes and interval polynomials the estimate computes anyway — the mesh
    /// transfer and the returned solution took them again (~5 % of a gauss8 elastica
    /// solve).
    pub fn residual_norms_and_solution(&self, z: &[f64], eta: f64) -> Result<(Vec<Vec<f64>>, f64, Solution), BvpError> {
        let mut segments = Vec::with_capacity(self.n_segments());
        let (rho, bc) = self.estimate(z, eta, Some(&mut segments))?;
        Ok((rho, bc, Solution { segments, params: self.params(z).to_vec(), eta, stats: Stats::default() }))
    }

    /// The residual estimate; with `output`, each segment's dense output is pushed to it.
    fn estimate(&self, z: &[f64], eta: f64, mut output: Option<&mut Vec<SegmentSolution>>) -> Result<(Vec<Vec<f64>>, f64), BvpError> {
        let s = self.tab.s;
        let p = self.params(z);
        let mut rho = Vec::with_capacity(self.n_segments());
        for k in 0..self.n_segments() {
            let n = self.dims[k];
            let mesh = &self.meshes[k];
            let slopes = self.slopes(z, eta, k);
            // one interval's polynomial at a time (the nested dense output of
            // `polys` was ~5 % of a gauss8 elastica solve in allocations)
            let mut poly = vec![0.0; n * (s + 1)];
            let mut u = vec![0.0; n];
            let mut f = vec![0.0; n];
            let mut rk = Vec::with_capacity(mesh.len() - 1);
            // ℓ_l(t) at the quadrature points, the same for every interval.
            let basis: Vec<[f64; 5]> =
                self.tab.lagrange.iter().map(|lag| LOBATTO5_T.map(|t| horner(lag, t))).collect();
            let mut dense = output.as_ref().map(|_| Vec::with_capacity(mesh.len() - 1));
            for i in 0..mesh.len() - 1 {
                let h = mesh[i + 1] - mesh[i];
                self.interval_poly(z, &slopes, k, i, &mut poly);
                if let Some(d) = dense.as_mut() {
                    d.push(poly.chunks(s + 1).map(<[f64]>::to_vec).collect());
                }
                let mut acc = 0.0;
                for (q, (&t, &w)) in LOBATTO5_T.iter().zip(&LOBATTO5_W).enumerate() {
                    for (ua, ca) in u.iter_mut().zip(poly.chunks(s + 1)) {
                        *ua = horner(ca, t);
                    }
                    self.problem.rhs(k, mesh[i] + t * h, &u, p, eta, &mut f);
                    for a in 0..n {
                        let du: f64 =
                            (0..s).map(|l| slopes[(i * s + l) * n + a] * basis[l][q]).sum();
                        let r = (du - f[a]) / (1.0 + f[a].abs());
                        acc += w * r * r;
                    }
                }
                let value = acc.sqrt();
                if !value.is_finite() {
                    return Err(BvpError::NonFinite {
                        what: format!("collocation residual on segment {k}, interval {i}"),
                    });
                }
                rk.push(value);
            }
            self.count(LOBATTO5_T.len() * (mesh.len() - 1));
            rho.push(rk);
            if let (Some(out), Some(poly)) = (output.as_mut(), dense) {
                let nodes = (0..mesh.len()).map(|i| z[self.node(k, i)..self.node(k, i) + n].to_vec()).collect();
                out.push(SegmentSolution { mesh: mesh.clone(), nodes, poly });
            }
        }
        let g = self.bc_residual(z, eta);
        let bc = g.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if !bc.is_finite() {
            return Err(BvpError::NonFinite { what: "boundary residual".into() });
        }
        Ok((rho, bc))
    }
}

/// The (s + 1) n collocation rows of one interval into `rb`: `zb` = [y_i, Y_1, …, Y_s,
/// y_{i+1}] (each n entries), `f` the s stage slopes; row (j, a) = Y_ja − y_ia −
/// h Σ_l a_jl f_la, row (s, a) = y_{i+1,a} − y_ia − h Σ_l b_l f_la, the sum from 0 in
/// the order of l — [`OdeRow`]'s terms and order, so the bits of the generic loop.
/// Inlined for a constant n ([`small_n`]) and s = `tab.s`.
#[inline(always)]
fn interval_residual(n: usize, s: usize, tab: &Tableau, h: f64, zb: &[f64], f: &[f64], rb: &mut [f64]) {
    let f = &f[..s * n];
    let start = &zb[..n];
    let (a_all, b) = (&tab.a[..s * s], &tab.b[..s]);
    for j in 0..=s {
        let w: &[f64] = if j < s { &a_all[j * s..(j + 1) * s] } else { b };
        let end = &zb[(j + 1) * n..(j + 2) * n];
        let out = &mut rb[j * n..(j + 1) * n];
        for a in 0..n {
            let mut acc = 0.0;
            for (l, &wl) in w.iter().enumerate() {
                acc += wl * f[l * n + a];
            }
            out[a] = end[a] - start[a] - h * acc;
        }
    }
}

/// The power-basis coefficients of one interval's collocation polynomial into `c`
/// (n (s + 1) entries): c_a0 = y_a, c_a(m+1) = Σ_l h K_la ℓ_lm / (m + 1), summed from 0 in
/// the order of l (`kk` the s stage slopes, `lagrange` the s Lagrange polynomials of
/// degree s − 1). Inlined for constant n and s, so that the loops unroll and the
/// divisions by 1, 2 and 4 become exact multiplications (the same bits).
#[inline(always)]
fn poly_coefficients(n: usize, s: usize, h: f64, y: &[f64], kk: &[f64], lagrange: &[Vec<f64>], c: &mut [f64]) {
    let (y, kk) = (&y[..n], &kk[..s * n]);
    for (a, ca) in c[..n * (s + 1)].chunks_exact_mut(s + 1).enumerate() {
        ca.fill(0.0);
        ca[0] = y[a];
        for (l, lag) in lagrange[..s].iter().enumerate() {
            let kl = kk[l * n + a];
            for (m, &lm) in lag[..s].iter().enumerate() {
                ca[m + 1] += h * kl * lm / (m + 1) as f64;
            }
        }
    }
}

/// Check that a solution/guess fits the problem: segment count, dimensions, parameter
/// count, meshes, dense output shapes and finiteness.
pub(crate) fn validate_solution<P: Problem>(problem: &P, sol: &Solution, what: &str) -> Result<(), BvpError> {
    let m = problem.n_segments();
    if sol.segments.len() != m {
        return Err(BvpError::InvalidInput(format!("{what}: {} segments, problem has {m}", sol.segments.len())));
    }
    if sol.params.len() != problem.n_params() {
        return Err(BvpError::InvalidInput(format!(
            "{what}: {} parameters, problem has {}",
            sol.params.len(),
            problem.n_params()
        )));
    }
    if sol.params.iter().any(|v| !v.is_finite()) || !sol.eta.is_finite() {
        return Err(BvpError::NonFinite { what: format!("{what}: parameters or eta") });
    }
    for (k, seg) in sol.segments.iter().enumerate() {
        validate_mesh(&seg.mesh, &format!("{what}, segment {k}"))?;
        let n = problem.dim(k);
        let intervals = seg.mesh.len() - 1;
        let shapes_ok = seg.nodes.len() == seg.mesh.len()
            && seg.nodes.iter().all(|v| v.len() == n)
            && seg.poly.len() == intervals
            && seg.poly.iter().all(|p| p.len() == n && p.iter().all(|c| !c.is_empty()));
        if !shapes_ok {
            return Err(BvpError::InvalidInput(format!(
                "{what}, segment {k}: node or dense-output shapes do not match dimension {n} \
                 and {} mesh nodes",
                seg.mesh.len()
            )));
        }
        let finite = seg.nodes.iter().flatten().all(|v| v.is_finite())
            && seg.poly.iter().flatten().flatten().all(|v| v.is_finite());
        if !finite {
            return Err(BvpError::NonFinite { what: format!("{what}, segment {k}") });
        }
    }
    Ok(())
}
