//! Structured LU of the condensed collocation system (the almost-block-diagonal system
//! of the mesh-node values of [`super::condensed`]) by Gaussian elimination with row
//! pivoting inside 2n-row windows, instead of a general sparse LU with its fill-reducing
//! ordering and symbolic analysis per mesh.
//!
//! Per segment (dimension n, intervals 0 … N−1) the condensed rows are
//!
//! ```text
//!     x_{i+1} − Φ_i x_i − Ψ_i p = r_i,
//! ```
//!
//! and the boundary rows g_x [x_0^k, x_N^k, p] = r_g couple the segment ends and p. In
//! the column order (x_1, …, x_{N−1}; then x_N, x_0, p of every segment) the unknown x_i
//! appears only in rows i−1 and i, so partial pivoting on that ordered matrix picks its
//! pivots for x_i among those 2n rows: step i stacks the n rows left over from step i−1
//! (their x_i and border coefficients, the border being x_0 and p) on row block i
//! (−Φ_i, I, −Ψ_i), factorises the 2n × n column block of x_i with partial pivoting,
//! and carries the n rows it did not pick to step i+1. What is left after step N−1 are
//! n rows in (x_N, x_0, p) per segment; with the boundary rows they form a dense system
//! of order D = Σ_k 2 n_k + n_p, solved by dense LU with partial pivoting. The node values
//! follow by back substitution. This is Gaussian elimination with partial pivoting of
//! the whole matrix in one fixed column order (the "alternate row" structure of the
//! almost-block-diagonal solvers, e.g. Diaz, Fairweather & Keast, ACM TOMS 9, 1983,
//! with the segment ends as a border), so it is as stable as a partial-pivoting LU and
//! costs O(N n² (n + n_p)) without any symbolic analysis.
//!
//! A pivot with |u| ≤ 10⁻¹⁴ times the largest entry of its column block (or not
//! finite) makes [`BlockLu::factorize`] return false; the caller then factorises with
//! the general sparse LU.

use super::condensed::{dense_lu, eliminate, grow};

/// One segment's part of the factorisation.
#[derive(Debug, Clone, Copy)]
struct Segment {
    /// Dimension n and number of intervals N.
    n: usize,
    intervals: usize,
    /// Start of the steps' blocks (2n × (2n + n + n_p) each) and pivots (n each) and of
    /// the forward-substitution values kept for the back substitution (n per step).
    steps: usize,
    pivots: usize,
    /// First column of x_0 of this segment in the final dense system (x_N follows).
    col: usize,
    /// First row of this segment's left-over rows in the final dense system.
    row: usize,
}

/// The factorisation (module documentation).
#[derive(Debug, Default)]
pub(crate) struct BlockLu {
    segments: Vec<Segment>,
    n_params: usize,
    /// Order D of the final dense system.
    order: usize,
    steps: Vec<f64>,
    pivots: Vec<usize>,
    dense: Vec<f64>,
    dense_piv: Vec<usize>,
    /// Left-over rows of the current step (n × (n + n + n_p)).
    carry: Vec<f64>,
    /// Solve scratch: the forward values per step, the final right-hand side.
    forward: Vec<f64>,
    rhs: Vec<f64>,
}

/// The window of one elimination step: row-major 2n × (n [x_i] + n [x_{i+1}] + n
/// [x_0] + n_p [p]).
fn width(n: usize, np: usize) -> usize {
    3 * n + np
}

impl BlockLu {
    /// Its two largest buffers (the steps' blocks and pivots), for reuse by a later
    /// `BlockLu` ([`Self::with_buffers`]); this one is left without them.
    pub(crate) fn take_buffers(&mut self) -> (Vec<f64>, Vec<usize>) {
        (std::mem::take(&mut self.steps), std::mem::take(&mut self.pivots))
    }

    /// A new `BlockLu` with the given buffers, their contents kept: every step's block
    /// and pivots are written by [`Self::factorize`] before they are read, so this is
    /// the state of [`Default`] but for the buffers (not zero-filled again).
    pub(crate) fn with_buffers((steps, pivots): (Vec<f64>, Vec<usize>)) -> Self {
        Self { steps, pivots, ..Self::default() }
    }

    /// Factorise the condensed system of segments with dimensions `dims` and
    /// `intervals` (per segment), `n_params` parameters, the interval blocks
    /// `phi(k, i)` (n × n) and `psi(k, i)` (n × n_p, row-major) and the boundary
    /// Jacobian `dg` (n_bc × (2 Σ n_k + n_p + 1), columns [y_0(0), y_0(1), …, p, η],
    /// the η column ignored). False if a pivot vanishes (module documentation).
    pub fn factorize<'b>(
        &mut self,
        dims: &[usize],
        intervals: &[usize],
        n_params: usize,
        phi: impl Fn(usize, usize) -> &'b [f64],
        psi: impl Fn(usize, usize) -> &'b [f64],
        dg: &[f64],
    ) -> bool {
        let np = n_params;
        self.n_params = np;
        self.order = dims.iter().map(|n| 2 * n).sum::<usize>() + np;
        let d = self.order;
        self.segments.clear();
        let (mut steps, mut pivots, mut col, mut row) = (0, 0, 0, 0);
        for (&n, &nint) in dims.iter().zip(intervals) {
            self.segments.push(Segment { n, intervals: nint, steps, pivots, col, row });
            let w = width(n, np);
            steps += nint.saturating_sub(1) * 2 * n * w;
            pivots += nint.saturating_sub(1) * n;
            col += 2 * n;
            row += n;
        }
        grow(&mut self.steps, steps);
        grow(&mut self.pivots, pivots);
        self.dense.clear();
        self.dense.resize(d * d, 0.0);
        self.dense_piv.resize(d, 0);
        for (k, seg) in self.segments.clone().into_iter().enumerate() {
            let Segment { n, intervals: nint, .. } = seg;
            let w = width(n, np);
            // Rows of interval 0: x_1 − Φ_0 x_0 − Ψ_0 p; as the carry, columns
            // [x_1 | (unused) | x_0 | p].
            self.carry.clear();
            self.carry.resize(n * w, 0.0);
            let (f0, s0) = (phi(k, 0), psi(k, 0));
            for a in 0..n {
                let row = &mut self.carry[a * w..(a + 1) * w];
                row[a] = 1.0;
                for c in 0..n {
                    row[2 * n + c] = -f0[a * n + c];
                }
                for q in 0..np {
                    row[3 * n + q] = -s0[a * np + q];
                }
            }
            for i in 1..nint {
                let at = seg.steps + (i - 1) * 2 * n * w;
                let block = &mut self.steps[at..at + 2 * n * w];
                // Top: the carry (x_i, —, x_0, p); bottom: row block i (−Φ_i, I, 0, −Ψ_i).
                block[..n * w].copy_from_slice(&self.carry);
                let (fi, si) = (phi(k, i), psi(k, i));
                for a in 0..n {
                    let row = &mut block[(n + a) * w..(n + a + 1) * w];
                    row.fill(0.0);
                    for c in 0..n {
                        row[c] = -fi[a * n + c];
                    }
                    row[n + a] = 1.0;
                    for q in 0..np {
                        row[3 * n + q] = -si[a * np + q];
                    }
                }
                let piv = &mut self.pivots[seg.pivots + (i - 1) * n..seg.pivots + i * n];
                if !eliminate(block, 2 * n, w, n, piv) {
                    return false;
                }
                // The rows not picked, now in (x_{i+1}, x_0, p): the next carry, its x_{i+1}
                // columns moved to the front.
                for a in 0..n {
                    let src = &block[(n + a) * w..(n + a + 1) * w];
                    let dst = &mut self.carry[a * w..(a + 1) * w];
                    dst[..n].copy_from_slice(&src[n..2 * n]);
                    dst[n..2 * n].fill(0.0);
                    dst[2 * n..].copy_from_slice(&src[2 * n..]);
                }
            }
            // Left-over rows into the final system: x_N, x_0 and p columns.
            for a in 0..n {
                let src = &self.carry[a * w..(a + 1) * w];
                let dst = &mut self.dense[(seg.row + a) * d..(seg.row + a + 1) * d];
                dst[seg.col + n..seg.col + 2 * n].copy_from_slice(&src[..n]);
                dst[seg.col..seg.col + n].copy_from_slice(&src[2 * n..3 * n]);
                dst[d - np..].copy_from_slice(&src[3 * n..]);
            }
        }
        // Boundary rows: dg's columns are those of the final system, then η.
        let n_rows = self.segments.iter().map(|s| s.n).sum::<usize>();
        let n_bc = d - n_rows;
        debug_assert_eq!(dg.len(), n_bc * (d + 1));
        for r in 0..n_bc {
            self.dense[(n_rows + r) * d..(n_rows + r + 1) * d].copy_from_slice(&dg[r * (d + 1)..r * (d + 1) + d]);
        }
        dense_lu(&mut self.dense, d, &mut self.dense_piv)
    }

    /// Overwrite `x` with the solution of the factorised system: on entry the
    /// right-hand side in the condensed row order (per segment its N n continuity rows,
    /// segment after segment, then the boundary rows), on return the unknowns in the
    /// condensed order (per segment its N + 1 node values, then p).
    pub fn solve(&mut self, x: &mut [f64]) {
        let np = self.n_params;
        let d = self.order;
        let total_steps: usize = self.segments.iter().map(|s| s.intervals.saturating_sub(1) * s.n).sum();
        self.forward.resize(total_steps, 0.0);
        self.rhs.clear();
        self.rhs.resize(d, 0.0);
        let mut window = Vec::new();
        let (mut row0, mut fwd0) = (0, 0);
        for seg in &self.segments {
            let Segment { n, intervals: nint, .. } = *seg;
            let w = width(n, np);
            // Carry's right-hand side starts as interval 0's.
            window.clear();
            window.extend_from_slice(&x[row0..row0 + n]);
            window.resize(2 * n, 0.0);
            for i in 1..nint {
                window[n..].copy_from_slice(&x[row0 + i * n..row0 + (i + 1) * n]);
                let block = &self.steps[seg.steps + (i - 1) * 2 * n * w..seg.steps + i * 2 * n * w];
                let piv = &self.pivots[seg.pivots + (i - 1) * n..seg.pivots + i * n];
                // P A = L U with whole rows swapped during the elimination: all swaps
                // first, then L.
                for (r, &p) in piv.iter().enumerate() {
                    window.swap(r, p);
                }
                for r in 0..n {
                    let v = window[r];
                    for rr in r + 1..2 * n {
                        window[rr] -= block[rr * w + r] * v;
                    }
                }
                let f = fwd0 + (i - 1) * n;
                self.forward[f..f + n].copy_from_slice(&window[..n]);
                window.copy_within(n..2 * n, 0);
            }
            self.rhs[seg.row..seg.row + n].copy_from_slice(&window[..n]);
            row0 += nint * n;
            fwd0 += nint.saturating_sub(1) * n;
        }
        let n_rows = self.segments.iter().map(|s| s.n).sum::<usize>();
        self.rhs[n_rows..].copy_from_slice(&x[row0..row0 + d - n_rows]);
        super::condensed::dense_solve(&self.dense, d, &self.dense_piv, &mut self.rhs, 1);
        // Back substitution per segment: x_i = U⁻¹ (y_i − U_{x_{i+1}} x_{i+1} − U_b [x_0; p]).
        let p = &self.rhs[d - np..];
        let (mut node0, mut fwd0) = (0, 0);
        for seg in &self.segments {
            let Segment { n, intervals: nint, .. } = *seg;
            let w = width(n, np);
            let x0 = &self.rhs[seg.col..seg.col + n];
            let xn = &self.rhs[seg.col + n..seg.col + 2 * n];
            x[node0..node0 + n].copy_from_slice(x0);
            x[node0 + nint * n..node0 + (nint + 1) * n].copy_from_slice(xn);
            for i in (1..nint).rev() {
                let block = &self.steps[seg.steps + (i - 1) * 2 * n * w..seg.steps + i * 2 * n * w];
                let (done, next) = x.split_at_mut(node0 + (i + 1) * n);
                let xi = &mut done[node0 + i * n..];
                let xnext = &next[..n];
                for r in (0..n).rev() {
                    let row = &block[r * w..(r + 1) * w];
                    let mut acc = self.forward[fwd0 + (i - 1) * n + r];
                    for c in r + 1..n {
                        acc -= row[c] * xi[c];
                    }
                    for c in 0..n {
                        acc -= row[n + c] * xnext[c];
                    }
                    for c in 0..n {
                        acc -= row[2 * n + c] * x0[c];
                    }
                    for q in 0..np {
                        acc -= row[3 * n + q] * p[q];
                    }
                    xi[r] = acc / row[r];
                }
            }
            node0 += (nint + 1) * n;
            fwd0 += nint.saturating_sub(1) * n;
        }
        x[node0..node0 + np].copy_from_slice(p);
    }
}
