//! The Newton systems of the collocation equations solved by condensing the stage
//! unknowns interval by interval (local elimination, as in COLNEW: Ascher, Christiansen
//! & Russell, ACM TOMS 7, 1981), so that the sparse LU only sees the much smaller system
//! of the mesh-node values and the parameters.
//!
//! # Condensation
//!
//! On interval i of segment k (dimension n, s stages, width h) write J_l = ∂f/∂y and
//! P_l = ∂f/∂p at stage l. A Newton system J x = b (layout of
//! [`super::discretisation`]) has there the stage rows and the continuity rows
//!
//! ```text
//!     K x_Y − E x_i − G x_p = b_S,      K = I − h (a_jl J_l)_{jl},  E = (I, …, I)ᵀ,  G_j = h Σ_l a_jl P_l,
//!     x_{i+1} − x_i − B x_Y − h Σ_l b_l P_l x_p = b_C,              B = h (b_1 J_1, …, b_s J_s),
//! ```
//!
//! so with x_Y = K⁻¹ (b_S + E x_i + G x_p) and V = B K⁻¹,
//!
//! ```text
//!     x_{i+1} − Φ x_i − Ψ x_p = b_C + V b_S,      Φ = I + V E,  Ψ = h Σ_l b_l P_l + V G.
//! ```
//!
//! V is formed by the *transposed condensation*: with K's dense LU (partial pivoting),
//! Vᵀ = K⁻ᵀ Bᵀ is solved through the transposed factors ([`dense_solve_transposed`])
//! with its n columns side by side, so a Newton matrix costs n solves with Kᵀ per
//! interval instead of the n + n_used of W = K⁻¹ [E | G] (the form before 3 Dec 2026),
//! V E is the sum of V's s column blocks instead of a product, and only G (not W) is
//! kept. The right-hand side needs V b_S and, after the node values, one solve with K
//! for the stage values.
//!
//! These n rows per interval and the boundary rows (which only see the segment ends and
//! p) form the condensed system in the node values and p; it is factorised by the
//! structured LU of [`super::abd`] (row pivoting inside 2n-row windows, no symbolic
//! analysis) when its final dense system, of order 2 Σ n_k + n_p, is small
//! ([`MAX_BLOCK_ORDER`]), else — and when a pivot of the structured elimination
//! vanishes — by the sparse LU ([`SparseLu`], symbolic factorisation kept while the
//! mesh does not change); the stage values follow from x_Y = K⁻¹ (b_S + E x_i + G x_p). The
//! work per interval is that of one dense LU of order s n, independent of the mesh,
//! and the condensed system is (s + 1) times smaller than the full one.
//!
//! K is nonsingular for h ‖J‖ small enough (it is the matrix of one implicit
//! Runge–Kutta step). Where a pivot of K vanishes (|u_rr| ≤ 10⁻¹⁴ max |K|, or not
//! finite), the whole Jacobian of that Newton iteration is factorised uncondensed
//! instead ([`Discretisation::jacobian`] and the sparse LU), so the condensation never
//! makes a solvable Newton step fail.

use super::abd::BlockLu;
use super::discretisation::Discretisation;
use super::scheme::Tableau;
use numerics::phases::{timed, Phase};
use crate::error::BvpError;
use crate::jacobian::{bc_jacobian, RhsJacobian};
use crate::newton::SparseLu;
use crate::problem::{JacobianMode, Problem};

/// `$body` with `$n` bound to n = `$value` — a literal constant in the arms n = 1 … 6,
/// so that the loops over the components of an `#[inline(always)]` function called in
/// `$body` with it unroll (the per-interval work of the condensation and of its solves
/// with n at run time was dominated by loop and bounds overhead on rows of 4 entries).
macro_rules! small_n {
    ($value:expr, $n:ident => $body:expr) => {
        match $value {
            1 => { let $n = 1; $body }
            2 => { let $n = 2; $body }
            3 => { let $n = 3; $body }
            4 => { let $n = 4; $body }
            5 => { let $n = 5; $body }
            6 => { let $n = 6; $body }
            $n => $body,
        }
    };
}
pub(crate) use small_n;

/// `$body` with `$s` bound to the number of stages s = `$value`, a literal constant for
/// the schemes' s = 2, 3, 4 (as [`small_n`] for the components).
macro_rules! small_s {
    ($value:expr, $s:ident => $body:expr) => {
        match $value {
            2 => { let $s = 2; $body }
            3 => { let $s = 3; $body }
            4 => { let $s = 4; $body }
            $s => $body,
        }
    };
}

/// In-place LU with partial pivoting of the m × m row-major matrix `a` (L unit lower,
/// U upper, both in `a`); `piv[r]` is the row swapped with row r at step r. False if a
/// pivot is not finite or |u_rr| ≤ 10⁻¹⁴ max |a_ij| (numerically singular).
pub(crate) fn dense_lu(a: &mut [f64], m: usize, piv: &mut [usize]) -> bool {
    eliminate(a, m, m, m, piv)
}

/// Partial-pivoting elimination of the first `k` columns of the row-major
/// `rows` × `cols` block `a` (rows ≥ k; all columns updated, whole rows swapped;
/// multipliers stored below the diagonal of the first k columns); `piv[r]` is the row
/// swapped with r at step r. False if a pivot is not finite or |u_rr| ≤ 10⁻¹⁴ times
/// the largest |entry| of the first k columns. With rows = cols = k it is the LU of a
/// square matrix ([`dense_lu`]); [`super::abd`] eliminates 2n × n column blocks.
pub(crate) fn eliminate(a: &mut [f64], rows: usize, cols: usize, k: usize, piv: &mut [usize]) -> bool {
    let scale = if k == cols {
        max_abs(a[..rows * cols].iter())
    } else {
        max_abs((0..rows).flat_map(|r| a[r * cols..r * cols + k].iter()))
    };
    if !(scale.is_finite() && scale > 0.0) {
        return false;
    }
    for r in 0..k {
        let p = (r..rows).fold(r, |best, i| if a[i * cols + r].abs() > a[best * cols + r].abs() { i } else { best });
        piv[r] = p;
        if p != r {
            for c in 0..cols {
                a.swap(r * cols + c, p * cols + c);
            }
        }
        let d = a[r * cols + r];
        if !(d.is_finite() && d.abs() > 1e-14 * scale) {
            return false;
        }
        // Row slices instead of indices: a bounds check per row, not per multiply–add.
        let (head, below) = a.split_at_mut((r + 1) * cols);
        let pivot_row = &head[r * cols + r + 1..(r + 1) * cols];
        // A zero entry leaves its row as it is (its multiplier 0 / d is zero): no
        // division (K of a sparse ∂f/∂y has many, e.g. the elastica's x and y columns).
        for row in below[..(rows - r - 1) * cols].chunks_exact_mut(cols) {
            if row[r] == 0.0 {
                continue;
            }
            let f = row[r] / d;
            row[r] = f;
            if f != 0.0 {
                for (o, &u) in row[r + 1..].iter_mut().zip(pivot_row) {
                    *o -= f * u;
                }
            }
        }
    }
    true
}

/// max |v| over `values`, NaNs ignored as by `f64::max` (an infinite entry makes it
/// infinite) — the same value as a fold with `f64::max`, but a comparison that compiles
/// to `maxpd` instead of `f64::max`'s NaN handling (which was ~22 % of the instructions
/// of a 16 × 16 LU).
fn max_abs<'v>(values: impl Iterator<Item = &'v f64>) -> f64 {
    values.fold(0.0_f64, |m, v| {
        let a = v.abs();
        if a > m {
            a
        } else {
            m
        }
    })
}

/// Overwrite the m × nc row-major block `x` (nc right-hand sides side by side) with
/// A⁻¹ x for the factorisation of [`dense_lu`]. Each column sees the operations of a
/// row-by-row forward and back substitution in the usual order (x_r − Σ_k l_rk x_k,
/// k ascending; then (x_r − Σ_k u_rk x_k)/u_rr), but the nc columns' updates are
/// independent and run side by side: one dependency chain per row instead of one per
/// row and column (the W solves of [`CondensedLu::factorize`] were ~15 % of a gauss8
/// elastica solve as one column at a time).
pub(crate) fn dense_solve(lu: &[f64], m: usize, piv: &[usize], x: &mut [f64], nc: usize) {
    let x = &mut x[..m * nc];
    swap_rows(x, &piv[..m], nc, false);
    match nc {
        1 => return substitute_fixed::<1>(lu, m, x),
        2 => return substitute_fixed::<2>(lu, m, x),
        3 => return substitute_fixed::<3>(lu, m, x),
        4 => return substitute_fixed::<4>(lu, m, x),
        5 => return substitute_fixed::<5>(lu, m, x),
        6 => return substitute_fixed::<6>(lu, m, x),
        7 => return substitute_fixed::<7>(lu, m, x),
        8 => return substitute_fixed::<8>(lu, m, x),
        _ => {}
    }
    for r in 1..m {
        let (done, rest) = x.split_at_mut(r * nc);
        let xr = &mut rest[..nc];
        for (&l, xk) in lu[r * m..r * m + r].iter().zip(done.chunks_exact(nc)) {
            for (o, v) in xr.iter_mut().zip(xk) {
                *o -= l * v;
            }
        }
    }
    for r in (0..m).rev() {
        let (head, tail) = x.split_at_mut((r + 1) * nc);
        let xr = &mut head[r * nc..];
        for (&u, xk) in lu[r * m + r + 1..(r + 1) * m].iter().zip(tail.chunks_exact(nc)) {
            for (o, v) in xr.iter_mut().zip(xk) {
                *o -= u * v;
            }
        }
        let d = lu[r * m + r];
        for o in xr.iter_mut() {
            *o /= d;
        }
    }
}

/// Overwrite the m × nc row-major block `x` (nc right-hand sides side by side) with
/// A⁻ᵀ x for the factorisation P A = L U of [`dense_lu`]: Aᵀ = Uᵀ Lᵀ P, so Uᵀ w = x by
/// forward and Lᵀ v = w by backward substitution, each as updates by the contiguous
/// rows of U and L (row r of U updates the rows after r of w, row r of L those before r
/// of v), then x = Pᵀ v (the row swaps undone in reverse order). With A = K and x = Bᵀ
/// this is the transposed condensation's Vᵀ = K⁻ᵀ Bᵀ ([`CondensedLu`]). A row of w that
/// is exactly zero updates nothing and is skipped (B is zero in the columns of the
/// components no right-hand side depends on, e.g. the elastica's x and y).
pub(crate) fn dense_solve_transposed(lu: &[f64], m: usize, piv: &[usize], x: &mut [f64], nc: usize) {
    let x = &mut x[..m * nc];
    match nc {
        1 => transposed_fixed::<1>(lu, m, x),
        2 => transposed_fixed::<2>(lu, m, x),
        3 => transposed_fixed::<3>(lu, m, x),
        4 => transposed_fixed::<4>(lu, m, x),
        5 => transposed_fixed::<5>(lu, m, x),
        6 => transposed_fixed::<6>(lu, m, x),
        7 => transposed_fixed::<7>(lu, m, x),
        8 => transposed_fixed::<8>(lu, m, x),
        _ => {
            for r in 0..m {
                let (head, tail) = x.split_at_mut((r + 1) * nc);
                let d = lu[r * m + r];
                let xr = &mut head[r * nc..];
                for o in xr.iter_mut() {
                    *o /= d;
                }
                if xr.iter().all(|&v| v == 0.0) {
                    continue;
                }
                for (&u, xc) in lu[r * m + r + 1..(r + 1) * m].iter().zip(tail.chunks_exact_mut(nc)) {
                    for (o, v) in xc.iter_mut().zip(xr.iter()) {
                        *o -= u * v;
                    }
                }
            }
            for r in (1..m).rev() {
                let (head, tail) = x.split_at_mut(r * nc);
                let xr = &tail[..nc];
                if xr.iter().all(|&v| v == 0.0) {
                    continue;
                }
                for (&l, xc) in lu[r * m..r * m + r].iter().zip(head.chunks_exact_mut(nc)) {
                    for (o, v) in xc.iter_mut().zip(xr) {
                        *o -= l * v;
                    }
                }
            }
        }
    }
    swap_rows(x, &piv[..m], nc, true);
}

/// Apply the row interchanges `piv` of a [`dense_lu`] (row r with `piv[r]`, r
/// ascending; undone in reverse order with `undo`) to the row-major block `x` of `nc`
/// columns.
fn swap_rows(x: &mut [f64], piv: &[usize], nc: usize, undo: bool) {
    let mut one = |(r, &p): (usize, &usize)| {
        if p != r {
            for c in 0..nc {
                x.swap(r * nc + c, p * nc + c);
            }
        }
    };
    if undo {
        piv.iter().enumerate().rev().for_each(&mut one);
    } else {
        piv.iter().enumerate().for_each(&mut one);
    }
}

/// The substitutions of [`dense_solve_transposed`] (before the row swaps) for a
/// compile-time number NC of right-hand sides, the same operations as its general loop.
/// Inlined, so that [`Kernels`] of a compile-time order m get it unrolled.
#[inline(always)]
fn transposed_fixed<const NC: usize>(lu: &[f64], m: usize, x: &mut [f64]) {
    let (rows, _) = x.as_chunks_mut::<NC>();
    let rows = &mut rows[..m];
    for r in 0..m {
        let (head, tail) = rows.split_at_mut(r + 1);
        let d = lu[r * m + r];
        let mut xr = head[r];
        for v in xr.iter_mut() {
            *v /= d;
        }
        head[r] = xr;
        if xr.iter().all(|&v| v == 0.0) {
            continue;
        }
        for (&u, xc) in lu[r * m + r + 1..(r + 1) * m].iter().zip(tail.iter_mut()) {
            for c in 0..NC {
                xc[c] -= u * xr[c];
            }
        }
    }
    for r in (1..m).rev() {
        let (head, tail) = rows.split_at_mut(r);
        let xr = tail[0];
        if xr.iter().all(|&v| v == 0.0) {
            continue;
        }
        for (&l, xc) in lu[r * m..r * m + r].iter().zip(head.iter_mut()) {
            for c in 0..NC {
                xc[c] -= l * xr[c];
            }
        }
    }
}

/// The substitutions of [`dense_solve`] (after the row swaps) for a compile-time
/// number NC of right-hand sides: each row's NC sums are accumulated in registers
/// (vectorised over the columns), in the same order as the general loop (x_r − l_r0 x_0
/// − l_r1 x_1 − …, then (x_r − Σ u_rk x_k)/u_rr with k ascending), so the result is the
/// same to the bit at a fraction of its loop overhead (the W and t solves were 23 % of
/// the instructions of a gauss8 elastica solve with the general loop). Inlined, so that
/// [`Kernels`] of a compile-time order m get it unrolled.
#[inline(always)]
fn substitute_fixed<const NC: usize>(lu: &[f64], m: usize, x: &mut [f64]) {
    let (rows, _) = x.as_chunks_mut::<NC>();
    let rows = &mut rows[..m];
    for r in 1..m {
        let (done, rest) = rows.split_at_mut(r);
        let mut acc = rest[0];
        for (&l, xk) in lu[r * m..r * m + r].iter().zip(done.iter()) {
            for c in 0..NC {
                acc[c] -= l * xk[c];
            }
        }
        rest[0] = acc;
    }
    for r in (0..m).rev() {
        let (head, tail) = rows.split_at_mut(r + 1);
        let mut acc = head[r];
        for (&u, xk) in lu[r * m + r + 1..(r + 1) * m].iter().zip(tail.iter()) {
            for c in 0..NC {
                acc[c] -= u * xk[c];
            }
        }
        let d = lu[r * m + r];
        for a in acc.iter_mut() {
            *a /= d;
        }
        head[r] = acc;
    }
}

/// Two one-column solves side by side: (LUs, order m, pivots, right-hand sides).
type SolvePair = fn([&[f64]; 2], usize, [&[usize]; 2], [&mut [f64]; 2]);

/// The dense kernels of one interval's condensation for K of order m = s n with n
/// columns of V ([`CondensedLu`]): its LU ([`dense_lu`]), the transposed solve of Vᵀ
/// ([`dense_solve_transposed`], n columns) and the one-column solve of the stage
/// values ([`dense_solve`]). [`Kernels::new`] picks versions compiled for the order
/// (fully unrolled; the per-interval work of a gauss8 elastica solve was ~13 k
/// instructions per 16 × 16 LU for ~1.4 k multiply–adds, short rows of 1–15 entries
/// with their loop and bounds overhead) where (s, n) is one of the common shapes, the
/// general loops otherwise. The same results to the bit either way (test
/// `fixed_kernels_equal_the_general_ones_to_the_bit`).
#[derive(Clone, Copy)]
pub(crate) struct Kernels {
    lu: fn(&mut [f64], usize, &mut [usize]) -> bool,
    transposed: fn(&[f64], usize, &[usize], &mut [f64], usize),
    solve: fn(&[f64], usize, &[usize], &mut [f64]),
    /// `solve` of two intervals side by side ([`solve_square_pair`]).
    solve_pair: SolvePair,
    /// Compiled for the order (not the general loops).
    #[cfg(test)]
    fixed: bool,
}

impl Kernels {
    /// The general loops (any m and n).
    const GENERAL: Kernels = Kernels {
        lu: dense_lu,
        transposed: dense_solve_transposed,
        solve: |lu, m, piv, x| dense_solve(lu, m, piv, x, 1),
        solve_pair: |[la, lb], m, [pa, pb], [xa, xb]| {
            dense_solve(la, m, pa, xa, 1);
            dense_solve(lb, m, pb, xb, 1);
        },
        #[cfg(test)]
        fixed: false,
    };

    /// The kernels for K of order `m` = s `n` (s = 2, 3, 4 stages, n = 1 … 6 components:
    /// every Gauss scheme on the analytical problems and the belt laws' 2- and
    /// 5-component segments), the general ones for other shapes.
    pub fn new(m: usize, n: usize) -> Self {
        macro_rules! shapes {
            ($(($m:literal, $n:literal)),*) => {
                match (m, n) {
                    $(($m, $n) => Kernels { lu: lu_square::<$m>, transposed: transposed_square::<$m, $n>, solve: solve_square::<$m>,
                        solve_pair: solve_square_pair::<$m>,
                        #[cfg(test)]
                        fixed: true,
                    },)*
                    _ => Self::GENERAL,
                }
            };
        }
        // (m, n) = (s n, n) for s = 2, 3, 4
        shapes!((2, 1), (3, 1), (4, 1), (4, 2), (6, 2), (8, 2), (6, 3), (9, 3), (12, 3), (8, 4), (12, 4), (16, 4), (10, 5), (15, 5), (20, 5), (12, 6), (18, 6), (24, 6))
    }
}

/// [`dense_lu`] of order M (the argument m = M), the same pivots and the same value
/// of every entry of the factors: the pivot search and the test are [`eliminate`]'s,
/// and a row below the pivot is updated over all M columns by the pivot row with
/// zeros in its first r + 1 columns, which leaves those columns' values unchanged
/// (x − f·0 = x, up to the sign of a zero multiplier) — fixed-length rows that the
/// compiler unrolls and vectorises instead of rows of M − r − 1 entries.
fn lu_square<const M: usize>(a: &mut [f64], _m: usize, piv: &mut [usize]) -> bool {
    let (rows, _) = a.as_chunks_mut::<M>();
    let rows = &mut rows[..M];
    let scale = max_abs(rows.iter().flatten());
    if !(scale.is_finite() && scale > 0.0) {
        return false;
    }
    for r in 0..M {
        let mut p = r;
        for i in r + 1..M {
            if rows[i][r].abs() > rows[p][r].abs() {
                p = i;
            }
        }
        piv[r] = p;
        if p != r {
            rows.swap(r, p);
        }
        let d = rows[r][r];
        if !(d.is_finite() && d.abs() > 1e-14 * scale) {
            return false;
        }
        let mut u = rows[r];
        for v in &mut u[..=r] {
            *v = 0.0;
        }
        for row in rows[r + 1..].iter_mut() {
            if row[r] == 0.0 {
                continue;
            }
            let f = row[r] / d;
            if f != 0.0 {
                for (o, &v) in row.iter_mut().zip(&u) {
                    *o -= f * v;
                }
            }
            row[r] = f;
        }
    }
    true
}

/// [`dense_solve_transposed`] of order M with NC columns (the arguments m = M, nc = NC).
fn transposed_square<const M: usize, const NC: usize>(lu: &[f64], _m: usize, piv: &[usize], x: &mut [f64], _nc: usize) {
    let x = &mut x[..M * NC];
    transposed_fixed::<NC>(lu, M, x);
    swap_rows(x, &piv[..M], NC, true);
}

/// [`dense_solve`] of order M with one column (the argument m = M).
fn solve_square<const M: usize>(lu: &[f64], _m: usize, piv: &[usize], x: &mut [f64]) {
    let x = &mut x[..M];
    swap_rows(x, &piv[..M], 1, false);
    substitute_fixed::<1>(lu, M, x);
}

/// [`solve_square`] of two systems (two intervals' K) side by side: each sees exactly
/// the operations of `solve_square` in the same order (the same results to the bit),
/// but the two dependency chains of the substitutions — each row waits for the rows
/// before it and for a division — are interleaved, so that one fills the other's
/// latency (the stage solve of a gauss8 elastica was ~10 % of its CPU time).
fn solve_square_pair<const M: usize>(lu: [&[f64]; 2], _m: usize, piv: [&[usize]; 2], x: [&mut [f64]; 2]) {
    let [xa, xb] = x;
    let (xa, xb) = (&mut xa[..M], &mut xb[..M]);
    swap_rows(xa, &piv[0][..M], 1, false);
    swap_rows(xb, &piv[1][..M], 1, false);
    let (la, lb) = (&lu[0][..M * M], &lu[1][..M * M]);
    for r in 1..M {
        let (mut a, mut b) = (xa[r], xb[r]);
        for k in 0..r {
            a -= la[r * M + k] * xa[k];
            b -= lb[r * M + k] * xb[k];
        }
        xa[r] = a;
        xb[r] = b;
    }
    for r in (0..M).rev() {
        let (mut a, mut b) = (xa[r], xb[r]);
        for k in r + 1..M {
            a -= la[r * M + k] * xa[k];
            b -= lb[r * M + k] * xb[k];
        }
        xa[r] = a / la[r * M + r];
        xb[r] = b / lb[r * M + r];
    }
}

/// Default largest order of the structured LU's final dense system
/// ([`CondensedLu::max_block_order`]): its dense LU costs O(D³) per Newton iteration, so
/// problems with many segments (the Cosserat drive) stay on the sparse LU.
pub(crate) const MAX_BLOCK_ORDER: usize = 64;

/// Where the data of one interval lives in the flat buffers of [`CondensedLu`].
#[derive(Debug, Clone, Copy)]
struct Interval {
    /// Segment k and interval i.
    k: usize,
    i: usize,
    /// Start of K's LU (s n × s n) and of its pivots (s n).
    lu: usize,
    piv: usize,
    /// Start of Vᵀ = K⁻ᵀ Bᵀ, row-major s n × n.
    v: usize,
    /// Start of G, row-major s n × n_used: the columns of the parameters the interval
    /// uses (`CondensedLu::used`), in order.
    g: usize,
    /// Start of the interval's b_S in the solve scratch (s n).
    t: usize,
    /// Start of Φ (n × n) and Ψ (n × n_p), row-major.
    phi: usize,
    psi: usize,
}

/// The factorised Newton matrix ∂F/∂z of a [`Discretisation`], condensed to the node
/// values and parameters (module documentation), with the uncondensed sparse LU as the
/// fallback. Both sparse LUs keep their symbolic factorisation while the pattern does
/// not change, so one `CondensedLu` should live across the Newton iterations, meshes
/// and continuation steps of a solve.
#[derive(Debug, Default)]
pub(crate) struct CondensedLu {
    /// Sparse LU of the condensed system.
    lu: SparseLu,
    /// Sparse LU of the full system (only when a K was singular).
    full: SparseLu,
    /// The last factorisation was the full one.
    uncondensed: bool,
    /// Structured LU of the condensed system ([`BlockLu`]), used when its final dense
    /// system has order ≤ `max_block_order`; the sparse LU `lu` otherwise or when a
    /// pivot of the structured elimination vanishes.
    block: BlockLu,
    /// The last condensed factorisation was the structured one.
    structured: bool,
    /// Largest order Σ_k 2 n_k + n_p of the structured LU's final dense system (default
    /// [`MAX_BLOCK_ORDER`]; 0 forces the sparse LU).
    pub max_block_order: Option<usize>,
    /// Φ_i and Ψ_i of every interval, and the boundary Jacobian dg.
    phis: Vec<f64>,
    psis: Vec<f64>,
    dg: Vec<f64>,
    intervals: Vec<Interval>,
    /// Condensed index of the first node of each segment; `node_offsets[m]` = first
    /// parameter = number of node unknowns.
    node_offsets: Vec<usize>,
    /// Full-system sizes the layout was built for (n, stages).
    layout: (usize, usize),
    k_lu: Vec<f64>,
    piv: Vec<usize>,
    v: Vec<f64>,
    g: Vec<f64>,
    rows: Vec<usize>,
    cols: Vec<usize>,
    vals: Vec<f64>,
    jeta: Vec<f64>,
    scratch: Vec<f64>,
    /// Per interval and parameter q: ∂f/∂p_q is non-zero at some stage of the interval
    /// (interval-major, `n_params` each). W's p-columns and Ψ's columns of the others
    /// are exactly zero and not computed: a belt segment sees few of its problem's
    /// parameters (the Cosserat drive's 14: a span its length and c, an arc its contact
    /// angles, c and a stick stretch), so most of the n + n_p dense solves per interval
    /// drop out.
    used: Vec<bool>,
    rhs: Vec<f64>,
    /// f and its derivatives at the s stages of the current interval.
    jac: Vec<RhsJacobian>,
}

/// The per-mesh buffers of a dropped [`CondensedLu`] (emptied, their capacity kept),
/// which the next `CondensedLu` of the same thread starts with: a solve's buffers grow
/// with its meshes to ~0.9 MB (the gauss8 elastica's 212 intervals), and returned to the
/// allocator at the end of a solve they went back to the operating system, so every
/// solve page-faulted them in again — 183 faults and ~14 % of the CPU time of a gauss8
/// elastica solve (`docs/performance.md`, issue 17, run 10). The per-interval buffers
/// keep their length and contents as well (zero-filling the ~0.6 MB again on every
/// solve was ~3 % of its CPU time, run 11): every entry a factorisation or solve reads
/// it has written first (K, Vᵀ, the used columns of G, Φ, Ψ, the pivots and the stage
/// right-hand sides of every interval of the layout), so stale values are never read.
#[derive(Debug, Default)]
struct Spare {
    phis: Vec<f64>,
    psis: Vec<f64>,
    k_lu: Vec<f64>,
    piv: Vec<usize>,
    v: Vec<f64>,
    g: Vec<f64>,
    scratch: Vec<f64>,
    rhs: Vec<f64>,
    block: (Vec<f64>, Vec<usize>),
}

/// Largest [`Spare`] a thread keeps (bytes of capacity); larger buffers are freed.
const SPARE_BYTES: usize = 16 << 20;

impl Spare {
    fn bytes(&self) -> usize {
        let f = self.phis.capacity()
            + self.psis.capacity()
            + self.k_lu.capacity()
            + self.v.capacity()
            + self.g.capacity()
            + self.scratch.capacity()
            + self.rhs.capacity()
            + self.block.0.capacity();
        let u = self.piv.capacity() + self.block.1.capacity();
        f * size_of::<f64>() + u * size_of::<usize>()
    }
}

thread_local! {
    static SPARE: std::cell::Cell<Option<Spare>> = const { std::cell::Cell::new(None) };
}

impl Drop for CondensedLu {
    fn drop(&mut self) {
        let spare = Spare {
            phis: std::mem::take(&mut self.phis),
            psis: std::mem::take(&mut self.psis),
            k_lu: std::mem::take(&mut self.k_lu),
            piv: std::mem::take(&mut self.piv),
            v: std::mem::take(&mut self.v),
            g: std::mem::take(&mut self.g),
            scratch: std::mem::take(&mut self.scratch),
            rhs: std::mem::take(&mut self.rhs),
            block: self.block.take_buffers(),
        };
        if spare.bytes() <= SPARE_BYTES {
            // keep the larger of this and a spare already kept (nested solves); the
            // thread-local is gone only while the thread exits
            let _ = SPARE.try_with(|cell| {
                let kept = cell.take();
                cell.set(Some(match kept {
                    Some(k) if k.bytes() > spare.bytes() => k,
                    _ => spare,
                }));
            });
        }
    }
}

impl CondensedLu {
    /// A factorisation object with no layout yet; it takes over the buffers of this
    /// thread's last dropped one ([`Spare`]).
    pub fn new() -> Self {
        let mut lu = Self::default();
        if let Some(mut spare) = SPARE.try_with(std::cell::Cell::take).ok().flatten() {
            spare.rhs.clear();
            lu.phis = spare.phis;
            lu.psis = spare.psis;
            lu.k_lu = spare.k_lu;
            lu.piv = spare.piv;
            lu.v = spare.v;
            lu.g = spare.g;
            lu.scratch = spare.scratch;
            lu.rhs = spare.rhs;
            lu.block = BlockLu::with_buffers(spare.block);
        }
        lu
    }

    /// Numeric factorisations of the condensed system by the sparse LU and of the full
    /// system, and whether the last one was the structured LU.
    #[cfg(test)]
    pub fn factorisations(&self) -> (usize, usize, bool) {
        (self.lu.numeric_factorisations(), self.full.numeric_factorisations(), self.structured)
    }

    /// The buffer layout for `disc` (recomputed only when its shape changes).
    fn set_layout<P: Problem>(&mut self, disc: &Discretisation<'_, P>) {
        let s = disc.tab.s;
        let np = disc.n_params;
        let same = self.layout == (disc.n, s)
            && self.node_offsets.len() == disc.n_segments() + 1
            && self.intervals.len() == disc.meshes.iter().map(|m| m.len() - 1).sum::<usize>()
            && disc.meshes.iter().enumerate().all(|(k, m)| {
                self.node_offsets[k + 1] - self.node_offsets[k] == m.len() * disc.dims[k]
            });
        if same {
            return;
        }
        self.layout = (disc.n, s);
        self.intervals.clear();
        self.node_offsets = vec![0];
        let (mut lu, mut piv, mut v, mut g, mut t, mut phi, mut psi) = (0, 0, 0, 0, 0, 0, 0);
        for (k, mesh) in disc.meshes.iter().enumerate() {
            let n = disc.dims[k];
            let sn = s * n;
            self.node_offsets.push(self.node_offsets[k] + mesh.len() * n);
            for i in 0..mesh.len() - 1 {
                self.intervals.push(Interval { k, i, lu, piv, v, g, t, phi, psi });
                phi += n * n;
                psi += n * np;
                lu += sn * sn;
                piv += sn;
                v += sn * n;
                g += sn * np;
                t += sn;
            }
        }
        // grown, never shrunk or refilled: every entry of the layout is written before
        // it is read ([`Spare`])
        grow(&mut self.k_lu, lu);
        grow(&mut self.piv, piv);
        grow(&mut self.v, v);
        grow(&mut self.g, g);
        grow(&mut self.scratch, t);
        grow(&mut self.phis, phi);
        grow(&mut self.psis, psi);
    }

    /// Condensed row of the first continuity equation of interval i of segment k.
    fn condensed_row(&self, disc_dims: &[usize], k: usize, i: usize) -> usize {
        self.node_offsets[k] - k_rows_before(disc_dims, k) + i * disc_dims[k]
    }

    /// Evaluate and factorise ∂F/∂z of `disc` at (z, η).
    ///
    /// # Errors
    /// The sparse LU's errors ([`BvpError::SingularJacobian`], [`BvpError::NonFinite`]).
    pub fn factorize<P: Problem>(&mut self, disc: &Discretisation<'_, P>, z: &[f64], eta: f64) -> Result<(), BvpError> {
        self.set_layout(disc);
        if !self.condense(disc, z, eta) {
            self.uncondensed = true;
            disc.jacobian(z, eta, &mut self.rows, &mut self.cols, &mut self.vals, &mut self.jeta);
            return self.full.factorize(disc.n, &self.rows, &self.cols, &self.vals);
        }
        self.uncondensed = false;
        let order = 2 * disc.dims.iter().sum::<usize>() + disc.n_params;
        if order <= self.max_block_order.unwrap_or(MAX_BLOCK_ORDER) {
            let intervals: Vec<usize> = disc.meshes.iter().map(|m| m.len() - 1).collect();
            let ivs = &self.intervals;
            let first: Vec<usize> = (0..disc.n_segments()).map(|k| ivs.iter().position(|iv| iv.k == k).unwrap_or(0)).collect();
            let (phis, psis) = (&self.phis, &self.psis);
            let dims = &disc.dims;
            let np = disc.n_params;
            let block = &mut self.block;
            let dg = &self.dg;
            self.structured = timed(Phase::NumericFactorisation, || {
                block.factorize(
                    dims,
                    &intervals,
                    np,
                    |k, i| {
                        let iv = &ivs[first[k] + i];
                        &phis[iv.phi..iv.phi + dims[k] * dims[k]]
                    },
                    |k, i| {
                        let iv = &ivs[first[k] + i];
                        &psis[iv.psi..iv.psi + dims[k] * np]
                    },
                    dg,
                )
            });
            if self.structured {
                return Ok(());
            }
        }
        self.structured = false;
        self.triplets(disc);
        let nc = self.node_offsets[disc.n_segments()] + disc.n_params;
        self.lu.factorize(nc, &self.rows, &self.cols, &self.vals)
    }

    /// Build K's LU, V, G, Φ and Ψ per interval and the boundary Jacobian; false if a K
    /// is singular (nothing usable then).
    fn condense<P: Problem>(&mut self, disc: &Discretisation<'_, P>, z: &[f64], eta: f64) -> bool {
        let s = disc.tab.s;
        let mut jac = std::mem::take(&mut self.jac);
        jac.resize_with(s, RhsJacobian::default);
        let singular = self.condense_intervals(disc, z, eta, &mut jac);
        self.jac = jac;
        if singular {
            return false;
        }
        // Boundary rows: columns of dg are [y_0(0), y_0(1), y_1(0), y_1(1), …, p, η].
        let (ya, yb) = disc.ends(z);
        self.dg = bc_jacobian(disc.problem, disc.mode, &ya, &yb, disc.params(z), eta).1;
        true
    }

    /// The condensed system as triplets for the sparse LU: per interval the rows
    /// x_{i+1} − Φ_i x_i − Ψ_i p, then the boundary rows.
    fn triplets<P: Problem>(&mut self, disc: &Discretisation<'_, P>) {
        let np = disc.n_params;
        let m = disc.n_segments();
        let pofs = self.node_offsets[m];
        // n (n + 1 + n_p) entries per interval and n_bc (2 Σ n_k + n_p) boundary
        // entries, reserved at once (growing them by doubling on every new mesh was
        // ~3 % of a gauss8 elastica solve in reallocations).
        let entries: usize = self.intervals.iter().map(|iv| disc.dims[iv.k] * (disc.dims[iv.k] + 1 + np)).sum::<usize>()
            + disc.problem.n_bc() * (2 * disc.dims.iter().sum::<usize>() + np);
        for v in [&mut self.rows, &mut self.cols] {
            v.clear();
            v.reserve(entries);
        }
        self.vals.clear();
        self.vals.reserve(entries);
        for iv in &self.intervals {
            let n = disc.dims[iv.k];
            let phi = &self.phis[iv.phi..iv.phi + n * n];
            let psi = &self.psis[iv.psi..iv.psi + n * np];
            let r0 = self.condensed_row(&disc.dims, iv.k, iv.i);
            let c0 = self.node_offsets[iv.k] + iv.i * n;
            for a in 0..n {
                for c in 0..n {
                    self.rows.push(r0 + a);
                    self.cols.push(c0 + c);
                    self.vals.push(-phi[a * n + c]);
                }
                self.rows.push(r0 + a);
                self.cols.push(c0 + n + a);
                self.vals.push(1.0);
                // every p-column keeps its entry (exact zeros where unused): the pattern,
                // and with it the sparse LU's ordering and round-off, is that of every
                // Newton matrix before (catalogue results unchanged to the bit)
                for q in 0..np {
                    self.rows.push(r0 + a);
                    self.cols.push(pofs + q);
                    self.vals.push(-psi[a * np + q]);
                }
            }
        }
        let mut colmap = Vec::new();
        for k in 0..m {
            let n = disc.dims[k];
            let a0 = self.node_offsets[k];
            let b0 = self.node_offsets[k + 1] - n;
            colmap.extend(a0..a0 + n);
            colmap.extend(b0..b0 + n);
        }
        colmap.extend(pofs..pofs + np);
        let nu = colmap.len() + 1;
        let r0 = pofs - disc.dims.iter().sum::<usize>();
        for row in 0..disc.problem.n_bc() {
            for (c, &col) in colmap.iter().enumerate() {
                self.rows.push(r0 + row);
                self.cols.push(col);
                self.vals.push(self.dg[row * nu + c]);
            }
        }
    }

    /// The interval part of [`Self::condense`]; true if a K is singular.
    ///
    /// Per interval: K and its LU, Vᵀ = K⁻ᵀ Bᵀ by n solves with Kᵀ through that LU (the
    /// transposed condensation: n right-hand sides instead of the n + n_used of
    /// W = K⁻¹ [E | G]), then Φ = I + V E (the sums of V's s column blocks) and
    /// Ψ = h Σ_l b_l P_l + V G; G is kept for the back substitution.
    fn condense_intervals<P: Problem>(&mut self, disc: &Discretisation<'_, P>, z: &[f64], eta: f64, jac: &mut [RhsJacobian]) -> bool {
        let s = disc.tab.s;
        let np = disc.n_params;
        let p = disc.params(z);
        let mut qcols = Vec::with_capacity(np);
        let mut coef = Vec::with_capacity(s * s);
        self.used.clear();
        self.used.resize(self.intervals.len() * np, false);
        for iv in 0..self.intervals.len() {
            let Interval { k, i, lu, piv, v, g, phi, psi, .. } = self.intervals[iv];
            let n = disc.dims[k];
            let sn = s * n;
            let mesh = &disc.meshes[k];
            let h = mesh[i + 1] - mesh[i];
            for (j, jj) in jac.iter_mut().enumerate() {
                let at = disc.stage(k, i, j);
                jj.evaluate(disc.problem, disc.mode, k, mesh[i] + disc.tab.c[j] * h, &z[at..at + n], p, eta, false);
            }
            disc.count(s * per_call(disc.mode, n, np));
            let used = &mut self.used[iv * np..(iv + 1) * np];
            let mut out = Condensation {
                kk: &mut self.k_lu[lu..lu + sn * sn],
                piv: &mut self.piv[piv..piv + sn],
                vv: &mut self.v[v..v + sn * n],
                gg: &mut self.g[g..g + sn * np],
                ph: &mut self.phis[phi..phi + n * n],
                ps: &mut self.psis[psi..psi + n * np],
            };
            let regular = small_n!(n, nc => small_s!(s, sc => condense_interval(nc, sc, &disc.tab, np, h, jac, used, &mut qcols, &mut coef, &mut out)));
            if !regular {
                return true;
            }
        }
        false
    }

    /// Overwrite `x` (length `disc.n`, the right-hand side in the row layout) with the
    /// solution of the last factorised system (in the unknown layout).
    ///
    /// # Errors
    /// The sparse LU's errors.
    pub fn solve<P: Problem>(&mut self, disc: &Discretisation<'_, P>, x: &mut [f64]) -> Result<(), BvpError> {
        if self.uncondensed {
            return self.full.solve_in_place(x);
        }
        let s = disc.tab.s;
        let np = disc.n_params;
        let m = disc.n_segments();
        let pofs = self.node_offsets[m];
        self.rhs.clear();
        self.rhs.resize(pofs + np, 0.0);
        // Condensed right-hand side b_C + V b_S; b_S kept for the back substitution.
        for iv in &self.intervals {
            let n = disc.dims[iv.k];
            let sn = s * n;
            let row = disc.row(iv.k, iv.i);
            let r0 = self.condensed_row(&disc.dims, iv.k, iv.i);
            let bs = &x[row..row + sn];
            self.scratch[iv.t..iv.t + sn].copy_from_slice(bs);
            let out = &mut self.rhs[r0..r0 + n];
            let vv = &self.v[iv.v..iv.v + sn * n];
            small_n!(n, nc => condensed_rhs(nc, vv, bs, &x[row + sn..row + sn + n], out));
        }
        let bc0 = disc.row_offsets[m];
        let cbc0 = pofs - disc.dims.iter().sum::<usize>();
        let n_bc = disc.n - bc0;
        self.rhs[cbc0..cbc0 + n_bc].copy_from_slice(&x[bc0..]);
        if self.structured {
            let block = &mut self.block;
            let rhs = &mut self.rhs;
            timed(Phase::LinearSolves, || block.solve(rhs));
        } else {
            self.lu.solve_in_place(&mut self.rhs)?;
        }
        // Back substitution: node values and parameters, then
        // x_Y = K⁻¹ (b_S + E x_i + G x_p).
        let full_p = disc.offsets[m];
        x[full_p..].copy_from_slice(&self.rhs[pofs..]);
        for k in 0..m {
            let n = disc.dims[k];
            for i in 0..disc.meshes[k].len() {
                let at = disc.node(k, i);
                let from = self.node_offsets[k] + i * n;
                x[at..at + n].copy_from_slice(&self.rhs[from..from + n]);
            }
        }
        let p = &self.rhs[pofs..];
        for (ivx, iv) in self.intervals.iter().enumerate() {
            let n = disc.dims[iv.k];
            let sn = s * n;
            let used = &self.used[ivx * np..(ivx + 1) * np];
            let nq = used.iter().filter(|&&u| u).count();
            let at = disc.stage(iv.k, iv.i, 0);
            let xs = &mut x[at..at + sn];
            xs.copy_from_slice(&self.scratch[iv.t..iv.t + sn]);
            let xi = self.node_offsets[iv.k] + iv.i * n;
            let xi = &self.rhs[xi..xi + n];
            let gg = &self.g[iv.g..iv.g + sn * nq];
            small_n!(n, nc => stage_rhs(nc, xs, xi, gg, used, p));
        }
        // The stage solves, two intervals of a segment at a time (independent systems).
        let mut ivx = 0;
        while ivx < self.intervals.len() {
            let iv = self.intervals[ivx];
            let n = disc.dims[iv.k];
            let sn = s * n;
            let kernels = Kernels::new(sn, n);
            let at = disc.stage(iv.k, iv.i, 0);
            let lu = |iv: &Interval| &self.k_lu[iv.lu..iv.lu + sn * sn];
            let piv = |iv: &Interval| &self.piv[iv.piv..iv.piv + sn];
            match self.intervals.get(ivx + 1) {
                Some(next) if next.k == iv.k => {
                    let bt = disc.stage(next.k, next.i, 0);
                    let (head, tail) = x.split_at_mut(bt);
                    (kernels.solve_pair)([lu(&iv), lu(next)], sn, [piv(&iv), piv(next)], [&mut head[at..at + sn], &mut tail[..sn]]);
                    ivx += 2;
                }
                _ => {
                    (kernels.solve)(lu(&iv), sn, piv(&iv), &mut x[at..at + sn]);
                    ivx += 1;
                }
            }
        }
        if !x.iter().fold(true, |ok, v| ok & v.is_finite()) {
            return Err(BvpError::SingularJacobian {
                iteration: 0,
                detail: "condensed collocation solve produced non-finite values".into(),
            });
        }
        Ok(())
    }
}

/// The condensed right-hand side b_C + V b_S of one interval into `out` (n entries;
/// `vv` = Vᵀ, s n × n row-major), the products summed over the rows of Vᵀ in order,
/// then b_C added. Inlined for a constant n ([`small_n`]).
#[inline(always)]
fn condensed_rhs(n: usize, vv: &[f64], bs: &[f64], bc: &[f64], out: &mut [f64]) {
    let out = &mut out[..n];
    out.fill(-0.0);
    for (vrow, &b) in vv.chunks_exact(n).zip(bs) {
        for (o, &v) in out.iter_mut().zip(vrow) {
            *o += v * b;
        }
    }
    for (o, &c) in out.iter_mut().zip(bc) {
        *o += c;
    }
}

/// b_S + E x_i + G x_p of one interval, added to `xs` (= b_S, s n entries): x_i's
/// component r mod n, then G's row r times the used parameters in order. Inlined for a
/// constant n ([`small_n`]).
#[inline(always)]
fn stage_rhs(n: usize, xs: &mut [f64], xi: &[f64], gg: &[f64], used: &[bool], p: &[f64]) {
    let xi = &xi[..n];
    let nq = gg.len() / xs.len().max(1);
    for (r, o) in xs.iter_mut().enumerate() {
        *o += xi[r % n];
        for (&gv, q) in gg[r * nq..(r + 1) * nq].iter().zip((0..p.len()).filter(|&q| used[q])) {
            *o += gv * p[q];
        }
    }
}

/// The outputs of [`condense_interval`] for one interval: K's LU and pivots, Vᵀ, G, Φ
/// and Ψ ([`Interval`]).
struct Condensation<'b> {
    kk: &'b mut [f64],
    piv: &'b mut [usize],
    vv: &'b mut [f64],
    gg: &'b mut [f64],
    ph: &'b mut [f64],
    ps: &'b mut [f64],
}

/// One interval of [`CondensedLu::condense_intervals`] from its stage Jacobians `jac`
/// (width h, n components, n_p parameters): which parameters it uses, K and its LU,
/// Vᵀ = K⁻ᵀ Bᵀ, G, Φ = I + V E and Ψ = h Σ_l b_l P_l + V G; false if K is singular.
/// Inlined into a call per small n, so that the loops over the components unroll (the
/// assembly was ~11 k instructions per interval of the gauss8 elastica with n at run
/// time), and per s = `tab.s` ([`small_s`]); the same operations in the same order for
/// every n and s.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn condense_interval(
    n: usize,
    s: usize,
    tab: &Tableau,
    np: usize,
    h: f64,
    jac: &[RhsJacobian],
    used: &mut [bool],
    qcols: &mut Vec<usize>,
    coef: &mut Vec<f64>,
    out: &mut Condensation<'_>,
) -> bool {
    debug_assert_eq!(s, tab.s);
    let (ta, tb, jac) = (&tab.a[..s * s], &tab.b[..s], &jac[..s]);
    let sn = s * n;
    for (q, u) in used.iter_mut().enumerate() {
        *u = jac.iter().any(|jl| (0..n).any(|a| jl.dfdp[a * np + q] != 0.0));
    }
    qcols.clear();
    qcols.extend((0..np).filter(|&q| used[q]));
    let nq = qcols.len();
    // K = I − h (a_jl J_l), row-major; Vᵀ starts as Bᵀ: row l n + c is
    // h b_l (J_l)_·c, column c of B's block l.
    let kk = &mut *out.kk;
    coef.clear();
    coef.extend(ta.iter().map(|&a| -h * a));
    for (j, (kblock, cj)) in kk.chunks_exact_mut(n * sn).zip(coef.chunks_exact(s)).enumerate() {
        for (a, krow) in kblock.chunks_exact_mut(sn).enumerate() {
            for ((kl, jl), &k_coef) in krow.chunks_exact_mut(n).zip(jac.iter()).zip(cj) {
                for (o, &d) in kl.iter_mut().zip(&jl.dfdy[a * n..(a + 1) * n]) {
                    *o = k_coef * d;
                }
            }
            krow[j * n + a] += 1.0;
        }
    }
    let vv = &mut *out.vv;
    for (l, jl) in jac.iter().enumerate() {
        let hb = h * tb[l];
        for c in 0..n {
            for (a, o) in vv[(l * n + c) * n..(l * n + c + 1) * n].iter_mut().enumerate() {
                *o = hb * jl.dfdy[a * n + c];
            }
        }
    }
    // G (row-major sn × n_used): row j n + a, column q: h Σ_l a_jl (P_l)_aq. Every
    // entry is written (no fill: tiny memsets per row were ~2 % of a solve).
    let gg = &mut out.gg[..sn * nq];
    for j in 0..s {
        for a in 0..n {
            let grow = &mut gg[(j * n + a) * nq..(j * n + a + 1) * nq];
            for (o, &q) in grow.iter_mut().zip(qcols.iter()) {
                let mut acc = 0.0;
                for (l, jl) in jac.iter().enumerate() {
                    acc += h * ta[j * s + l] * jl.dfdp[a * np + q];
                }
                *o = acc;
            }
        }
    }
    let kernels = Kernels::new(sn, n);
    if !(kernels.lu)(kk, sn, out.piv) {
        return false;
    }
    (kernels.transposed)(kk, sn, out.piv, vv, n);
    // Φ = I + Σ_j V_j (V's column blocks), Ψ = h Σ_l b_l P_l + V G (zero in the
    // columns of unused parameters).
    let ph = &mut *out.ph;
    for a in 0..n {
        for c in 0..n {
            let mut acc = if a == c { 1.0 } else { 0.0 };
            for j in 0..s {
                acc += vv[(j * n + c) * n + a];
            }
            ph[a * n + c] = acc;
        }
    }
    let ps = &mut *out.ps;
    let mut qi = 0;
    for q in 0..np {
        if !used[q] {
            for a in 0..n {
                ps[a * np + q] = 0.0;
            }
            continue;
        }
        for a in 0..n {
            let vg: f64 = (0..sn).map(|r| vv[r * n + a] * gg[r * nq + qi]).sum();
            ps[a * np + q] = vg + h * (0..s).map(|l| tb[l] * jac[l].dfdp[a * np + q]).sum::<f64>();
        }
        qi += 1;
    }
    true
}

/// `v` at least `len` long (new entries zero; existing ones kept).
pub(crate) fn grow<T: Copy + Default>(v: &mut Vec<T>, len: usize) {
    if v.len() < len {
        v.resize(len, T::default());
    }
}

/// Σ_{k' < k} n_k': the condensed rows of segment k start this far before its first
/// node unknown (one node more than intervals per segment).
fn k_rows_before(dims: &[usize], k: usize) -> usize {
    dims[..k].iter().sum()
}

/// Right-hand-side evaluations of one stage Jacobian.
pub(crate) fn per_call(mode: JacobianMode, n: usize, np: usize) -> usize {
    match mode {
        JacobianMode::Ad => 1,
        JacobianMode::FiniteDifference => 1 + 2 * (n + np + 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dense LU solves a system needing pivoting to round-off, and reports a
    /// singular matrix.
    #[test]
    fn dense_lu_pivots_and_detects_singularity() {
        // A = [[0, 2, 1], [1, 1, 0], [3, 0, 1]], x = (1, −2, 3) → b = A x.
        let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let x_true = [1.0, -2.0, 3.0];
        let mut b: Vec<f64> = (0..3).map(|r| (0..3).map(|c| a0[r * 3 + c] * x_true[c]).sum()).collect();
        let mut a = a0;
        let mut piv = [0; 3];
        assert!(dense_lu(&mut a, 3, &mut piv));
        dense_solve(&a, 3, &piv, &mut b, 1);
        for (u, v) in b.iter().zip(&x_true) {
            assert!((u - v).abs() < 1e-14, "{b:?}");
        }
        let mut singular = [1.0, 2.0, 2.0, 4.0];
        assert!(!dense_lu(&mut singular, 2, &mut [0; 2]));
    }

    /// The transposed solve of [`dense_solve_transposed`] through the LU of A solves
    /// Aᵀ X = B: checked against the LU of Aᵀ itself (a different elimination, so to
    /// round-off: both are backward stable on this matrix of condition ~10², 1e-12
    /// relative to the largest entry of X leaves a margin of ~10³; a wrong triangle,
    /// a missed division or the swaps undone in the wrong order give O(1)), for the
    /// fixed-width kernels (1 and 4 columns) and the general loop (11), with right-hand
    /// sides that have exact zero rows (skipped by the kernels) and a matrix that needs
    /// pivoting.
    #[test]
    fn transposed_solve_equals_the_solve_with_the_transposed_matrix() {
        let m = 7;
        let a: Vec<f64> = (0..m * m).map(|i| ((i * 7 + 3) % 11) as f64 - 5.0 + if i % (m + 1) == 0 { 0.5 } else { 0.0 }).collect();
        let at: Vec<f64> = (0..m * m).map(|i| a[(i % m) * m + i / m]).collect();
        let (mut lu, mut piv) = (a.clone(), vec![0; m]);
        assert!(dense_lu(&mut lu, m, &mut piv));
        assert!(piv.iter().enumerate().any(|(r, &p)| p != r), "the test matrix needs pivoting");
        let (mut lut, mut pivt) = (at.clone(), vec![0; m]);
        assert!(dense_lu(&mut lut, m, &mut pivt));
        for nc in [1, 4, 11] {
            // rows 0, 1 and 4 zero: a zero row of the right-hand side stays skippable
            // only until a pivot row below it is eliminated into it
            let rhs: Vec<f64> = (0..m * nc)
                .map(|i| if [0, 1, 4].contains(&(i / nc)) { 0.0 } else { 1.0 / (1.0 + (i * 5 % 13) as f64) - 0.3 })
                .collect();
            let mut x = rhs.clone();
            dense_solve_transposed(&lu, m, &piv, &mut x, nc);
            let mut y = rhs.clone();
            dense_solve(&lut, m, &pivt, &mut y, nc);
            let scale = y.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
            let err = x.iter().zip(&y).fold(0.0_f64, |e, (u, v)| e.max((u - v).abs()));
            assert!(err <= 1e-12 * scale, "{nc} columns: max |x − y| = {err:e} (scale {scale})");
            // and Aᵀ x reproduces the right-hand side
            for r in 0..m {
                for c in 0..nc {
                    let ax: f64 = (0..m).map(|k| a[k * m + r] * x[k * nc + c]).sum();
                    assert!((ax - rhs[r * nc + c]).abs() <= 1e-12 * scale.max(1.0), "{nc} columns: residual at ({r}, {c})");
                }
            }
        }
    }

    /// The kernels compiled for an order give the general loops' results to the bit
    /// (up to the sign of a zero, which the full-row updates of [`lu_square`] may flip
    /// in an untouched entry): the same pivots, LU entries, Vᵀ and stage solutions, for
    /// every shape (s, n) they are compiled for, on K-like matrices (identity minus a
    /// random block with whole zero columns, as K of the elastica, and some zero
    /// entries below the diagonal) that need pivoting. A shape outside the list gets
    /// the general loops.
    #[test]
    fn fixed_kernels_equal_the_general_ones_to_the_bit() {
        let bits = |v: &[f64]| v.iter().map(|&x| if x == 0.0 { 0 } else { x.to_bits() }).collect::<Vec<_>>();
        let mut state = 3u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for s in 2..=4 {
            for n in 1..=6 {
                let m = s * n;
                let fixed = Kernels::new(m, n);
                assert!(fixed.fixed, "s = {s}, n = {n}: compiled kernels");
                let a: Vec<f64> = (0..m * m)
                    .map(|i| {
                        let (r, c) = (i / m, i % m);
                        let v = if c % n == 0 && n > 1 || (r + 2 * c) % 7 == 0 { 0.0 } else { 3.0 * next() };
                        if r == c { 1.0 + 0.1 * v } else { v }
                    })
                    .collect();
                let (mut lu_g, mut piv_g) = (a.clone(), vec![0; m]);
                let (mut lu_f, mut piv_f) = (a.clone(), vec![0; m]);
                assert!((Kernels::GENERAL.lu)(&mut lu_g, m, &mut piv_g), "s = {s}, n = {n}: regular");
                assert!((fixed.lu)(&mut lu_f, m, &mut piv_f));
                assert!(m < 3 || piv_g.iter().enumerate().any(|(r, &p)| p != r), "s = {s}, n = {n}: pivoting");
                assert_eq!(piv_f, piv_g, "s = {s}, n = {n}: pivots");
                assert_eq!(bits(&lu_f), bits(&lu_g), "s = {s}, n = {n}: LU");
                let rhs: Vec<f64> = (0..m * n).map(|i| if (i / n) % n == 1 { 0.0 } else { next() }).collect();
                let (mut v_g, mut v_f) = (rhs.clone(), rhs.clone());
                (Kernels::GENERAL.transposed)(&lu_g, m, &piv_g, &mut v_g, n);
                (fixed.transposed)(&lu_f, m, &piv_f, &mut v_f, n);
                assert_eq!(bits(&v_f), bits(&v_g), "s = {s}, n = {n}: transposed solve");
                let (mut x_g, mut x_f) = (rhs[..m].to_vec(), rhs[..m].to_vec());
                (Kernels::GENERAL.solve)(&lu_g, m, &piv_g, &mut x_g);
                (fixed.solve)(&lu_f, m, &piv_f, &mut x_f);
                assert_eq!(bits(&x_f), bits(&x_g), "s = {s}, n = {n}: solve");
                // two systems side by side (the other one Aᵀ): each exactly its own solve
                let mut lu_t: Vec<f64> = (0..m * m).map(|i| a[(i % m) * m + i / m]).collect();
                let mut piv_t = vec![0; m];
                assert!((fixed.lu)(&mut lu_t, m, &mut piv_t), "s = {s}, n = {n}: Aᵀ regular");
                let rhs_t: Vec<f64> = (0..m).map(|_| next()).collect();
                let mut x_t = rhs_t.clone();
                (fixed.solve)(&lu_t, m, &piv_t, &mut x_t);
                for k in [fixed, Kernels::GENERAL] {
                    let (mut p1, mut p2) = (rhs[..m].to_vec(), rhs_t.clone());
                    (k.solve_pair)([&lu_f, &lu_t], m, [&piv_f, &piv_t], [&mut p1, &mut p2]);
                    assert_eq!(bits(&p1), bits(&x_f), "s = {s}, n = {n}: first of a pair");
                    assert_eq!(bits(&p2), bits(&x_t), "s = {s}, n = {n}: second of a pair");
                }
                // and the general solve solves A x = b (so the comparison is of solutions)
                let b = &rhs[..m];
                let res = (0..m).map(|r| ((0..m).map(|c| a[r * m + c] * x_g[c]).sum::<f64>() - b[r]).abs()).fold(0.0, f64::max);
                let xmax = x_g.iter().fold(0.0_f64, |t, v| t.max(v.abs()));
                assert!(res < 1e-12 * m as f64 * (1.0 + xmax), "s = {s}, n = {n}: residual {res:e}");
            }
        }
        assert!(!Kernels::new(35, 7).fixed && !Kernels::new(16, 3).fixed, "other shapes: the general loops");
    }

    /// Right-hand sides solved side by side give each column exactly (to the bit) what
    /// its own solve gives — for the fixed-width kernels (3 and 8 columns) and for the
    /// general loop (11 columns): the block solve only interleaves independent
    /// operations, so the condensed Newton matrices are those of the column-by-column
    /// solves before it. The one-column solve is checked against a plain
    /// row-by-row substitution written out here.
    #[test]
    fn block_solve_equals_column_solves_to_the_bit() {
        let m = 5;
        let mut a: Vec<f64> = (0..m * m).map(|i| ((i * 7 + 3) % 11) as f64 - 5.0 + if i % (m + 1) == 0 { 0.5 } else { 0.0 }).collect();
        let mut piv = vec![0; m];
        assert!(dense_lu(&mut a, m, &mut piv));
        assert!(piv.iter().enumerate().any(|(r, &p)| p != r), "the test matrix needs pivoting");
        for nc in [3, 8, 11] {
            let cols: Vec<Vec<f64>> = (0..nc).map(|c| (0..m).map(|r| 1.0 / (1.0 + (r * 3 + c) as f64)).collect()).collect();
            let mut block: Vec<f64> = (0..m).flat_map(|r| cols.iter().map(move |col| col[r])).collect();
            dense_solve(&a, m, &piv, &mut block, nc);
            for (c, col) in cols.iter().enumerate() {
                let mut x = col.clone();
                dense_solve(&a, m, &piv, &mut x, 1);
                let mut y = col.clone();
                for (r, &p) in piv.iter().enumerate() {
                    y.swap(r, p);
                }
                for r in 0..m {
                    for k in 0..r {
                        y[r] -= a[r * m + k] * y[k];
                    }
                }
                for r in (0..m).rev() {
                    for k in r + 1..m {
                        y[r] -= a[r * m + k] * y[k];
                    }
                    y[r] /= a[r * m + r];
                }
                for r in 0..m {
                    assert_eq!(x[r].to_bits(), y[r].to_bits(), "one column: row {r}, column {c}");
                    assert_eq!(block[r * nc + c].to_bits(), x[r].to_bits(), "{nc} columns: row {r}, column {c}");
                }
            }
        }
    }

    /// A `CondensedLu` dropped at the end of a solve leaves its buffers to the next one
    /// of the thread ([`Spare`]), with their stale contents: the next solve takes them
    /// (no allocation or zero-filling) and gives the same result to the bit as a
    /// solve in a new thread (no spare), also with another problem's (other n, other
    /// sizes) buffers in between.
    #[test]
    fn spare_buffers_are_reused_and_leave_every_result_unchanged() {
        use crate::analytical::bratu::{Bratu, BratuBranch, Exact as BratuExact};
        use crate::analytical::elastica::{guess, Exact};
        use crate::collocation::{solve, CollocationOptions, Scheme};
        use crate::Solution;

        fn bits(sol: &Solution) -> Vec<u64> {
            let seg = &sol.segments[0];
            let mut out: Vec<u64> = seg.mesh.iter().map(|x| x.to_bits()).collect();
            out.extend(seg.nodes.iter().flatten().map(|y| y.to_bits()));
            out.extend(sol.params.iter().map(|p| p.to_bits()));
            out.push(sol.stats.newton_iterations as u64);
            out
        }
        fn spare() -> Option<(usize, usize, usize)> {
            SPARE.with(|c| {
                let kept = c.take();
                let cap = kept.as_ref().map(|k| (k.bytes(), k.k_lu.capacity(), k.block.0.capacity()));
                c.set(kept);
                cap
            })
        }
        fn elastica() -> Solution {
            let exact = Exact::new(std::f64::consts::FRAC_1_SQRT_2).unwrap();
            let opts = CollocationOptions { scheme: Scheme::Gauss8, tolerance: 1e-8, ..Default::default() };
            solve(&exact.problem(), &guess(1.0, 11), &opts).unwrap()
        }
        fn bratu() -> Solution {
            let exact = BratuExact::new(3.51, BratuBranch::Lower).unwrap();
            let opts = CollocationOptions { scheme: Scheme::Gauss6, tolerance: 1e-8, ..Default::default() };
            let sol = solve(&Bratu, &exact.guess(11), &opts).unwrap();
            assert!(exact.max_dense_error(&sol, 2001) < 1e-9);
            sol
        }
        let fresh = |f: fn() -> Solution| std::thread::spawn(move || {
            assert!(spare().is_none(), "a new thread has no spare buffers");
            bits(&f())
        });
        let (elastica_fresh, bratu_fresh) = (fresh(elastica).join().unwrap(), fresh(bratu).join().unwrap());
        std::thread::spawn(move || {
            assert_eq!(bits(&bratu()), bratu_fresh);
            assert_eq!(bits(&elastica()), elastica_fresh, "after Bratu's buffers");
            // 212 intervals of 16 × 16 LUs: the spare holds at least those
            let (bytes, k_lu, steps) = spare().expect("the solve left its buffers");
            assert!(k_lu >= 212 * 16 * 16 && steps > 0 && bytes >= k_lu * 8, "{bytes} {k_lu} {steps}");
            // a new CondensedLu takes them with their lengths (no zero-filling again)
            let mut lu = CondensedLu::new();
            assert!(spare().is_none());
            assert!(lu.k_lu.len() >= 212 * 16 * 16 && lu.k_lu.capacity() == k_lu && lu.v.len() >= 212 * 16 * 4 && lu.piv.len() >= 212 * 16);
            let (block_steps, _) = lu.block.take_buffers();
            assert_eq!(block_steps.capacity(), steps);
            assert!(!block_steps.is_empty());
            drop(lu);
            assert_eq!(bits(&elastica()), elastica_fresh, "with its own buffers");
            assert_eq!(bits(&bratu()), bratu_fresh, "after the elastica's buffers");
            // too large a spare is not kept
            let mut big = CondensedLu::new();
            big.k_lu = Vec::with_capacity(SPARE_BYTES / 8 + 1);
            drop(big);
            assert!(spare().is_none(), "a spare above SPARE_BYTES is freed");
        })
        .join()
        .unwrap();
    }
}
