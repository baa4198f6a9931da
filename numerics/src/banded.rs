//! A banded LU with a dense border: the direct solve of the finite-element Newton
//! systems whose unknowns, numbered node by node along a mesh, couple only within a band
//! — except a few global unknowns (dense rows and columns: the drive's belt speed and
//! driven speed) and, on a closed loop, the unknowns where the mesh wraps around (the
//! last element couples the last node with the first).
//!
//! [`BandStructure::detect`] finds, from the pattern alone, a border — the fewest
//! unknowns whose removal leaves a narrow band, chosen by an estimate of the flops —
//! and [`BorderedBand`] factorises the matrix as
//!
//! ```text
//!   [A B; C D],   A band (half-widths kl, ku), B, C dense columns / rows of the border,
//!   A = P L U     (LAPACK's gbtf2: partial pivoting by rows within the band),
//!   V = A⁻¹ B,  S = D − C V (m × m, dense LU with partial pivoting),
//!   solve:  u = A⁻¹ r_A,  y = S⁻¹ (r_D − C u),  x_A = u − V y,  x_D = y.
//! ```
//!
//! The cost is linear in n: (kl + ku + kl)·kl per column for the LU, m band solves for
//! V, m²n for S; a general sparse LU (faer's, with its fill-reducing ordering) of such a
//! matrix costs 5–10× more at the sizes of the steady drive (docs/performance.md). The m
//! solves for V run as two halves of the columns at once (rayon; the same numbers to the
//! bit), and their back substitution starts at the fill the interchanges actually made,
//! not at the top of the fill room.
//!
//! For symmetric matrices ([`BorderedBand::symmetric`], an energy's Hessian) A is
//! factorised by Cholesky, A = L Lᵀ, where it is positive definite, and
//!
//! ```text
//!   W = L⁻¹ B,  S = D − Wᵀ W,
//!   solve:  u = A⁻¹ r_A,  y = S⁻¹ (r_D − C u),  x_A = u − L⁻ᵀ (W y),  x_D = y:
//! ```
//!
//! kl²/2 per column for the factor, m forward solves over a band of kl, m²n/2 for S —
//! against the LU's kl(kl + ku), m solves forward and back over kl + (kl + ku). An A that
//! is not positive definite (a pivot l_jj² at or below the LU's threshold), or values
//! that are not symmetric, go to the LU as without it.
//!
//! **Singular**: a pivot |u_jj| ≤ τ max_i |a_ij| (τ = 64 ε, the largest entry of the
//! original column j of the whole matrix, border rows included) — invariant under a
//! scaling of the matrix or of its columns. For the Schur complement the scale of
//! column l is max_k (|D_kl| + Σ_i |C_ki| |V_il|), the size of the terms that cancel.

use crate::linear::LinearError;

/// Relative pivot threshold τ (see the module docs).
pub const PIVOT_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// |pivot| ≤ τ scale, or not finite.
fn is_zero_pivot(pivot: f64, scale: f64) -> bool {
    pivot.partial_cmp(&(PIVOT_TOLERANCE * scale)) != Some(std::cmp::Ordering::Greater) || !pivot.is_finite()
}

/// With a border, the band block A must be well conditioned as well as regular: its
/// inverse enters V = A⁻¹B and S = D − C V, so an A with a pivot |u_jj| ≤ this ratio of
/// its column's scale (cond(A) ≳ 1e8 while the whole matrix may be well conditioned)
/// would lose ~cond(A) ε in the solution unseen. Such a block is a [`BandFailure::Band`]
/// (the caller's general LU takes over).
pub const BORDER_PIVOT_RATIO: f64 = 1e-8;

/// Largest border (dense rows and columns) [`BandStructure::detect`] accepts.
pub const MAX_BORDER: usize = 64;

/// Largest half-bandwidth [`BandStructure::detect`] accepts.
pub const MAX_HALF_BAND: usize = 96;

/// LU with partial pivoting of an n × n band matrix with kl sub- and ku
/// superdiagonals, in LAPACK's band storage: column j holds rows j − ku − kl … j + kl
/// (the top kl rows are the room for the fill of the row interchanges).
#[derive(Debug, Clone)]
pub struct BandLu {
    n: usize,
    kl: usize,
    ku: usize,
    /// Leading dimension 2 kl + ku + 1.
    ld: usize,
    ab: Vec<f64>,
    pivots: Vec<usize>,
    /// The largest distance j − i of an entry u_ij of U that the last factorisation can
    /// have made nonzero (ku, plus the fill of its row interchanges; ≤ kl + ku): the
    /// solves' back substitution starts there instead of at the fill room's top.
    fill: usize,
}

impl BandLu {
    /// An n × n band matrix of zeros with half-widths `kl`, `ku`.
    pub fn zeros(n: usize, kl: usize, ku: usize) -> Self {
        let ld = 2 * kl + ku + 1;
        BandLu { n, kl, ku, ld, ab: vec![0.0; ld * n], pivots: vec![0; n], fill: kl + ku }
    }

    /// Order n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Half-bandwidths (kl, ku).
    pub fn half_widths(&self) -> (usize, usize) {
        (self.kl, self.ku)
    }

    /// Storage position of entry (i, j), if it lies in the band.
    pub fn position(&self, i: usize, j: usize) -> Option<usize> {
        (i < self.n && j < self.n && i <= j + self.kl && j <= i + self.ku).then(|| j * self.ld + self.kl + self.ku + i - j)
    }

    /// Set every entry (and the fill room) to zero.
    pub fn clear(&mut self) {
        self.ab.fill(0.0);
    }

    /// Add `v` to entry (i, j).
    ///
    /// # Panics
    /// If (i, j) lies outside the band (a caller's indexing error).
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let p = self.position(i, j).unwrap_or_else(|| panic!("entry ({i}, {j}) outside the band"));
        self.ab[p] += v;
    }

    /// Add `v` at a storage position from [`Self::position`].
    pub fn add_at(&mut self, position: usize, v: f64) {
        self.ab[position] += v;
    }

    /// The largest |a_ij| of each column j (call before [`Self::factorize`]).
    pub fn column_maxima(&self) -> Vec<f64> {
        self.ab.chunks_exact(self.ld).map(|c| c.iter().fold(0.0_f64, |m, v| m.max(v.abs()))).collect()
    }

    /// Factorise in place (gbtf2). `scale[j]` is the size of column j against which a
    /// pivot is judged zero (see the module docs); `None`: the band's own column maxima.
    ///
    /// # Errors
    /// The first column j whose pivot is ≤ τ scale[j] (or not finite), with the pivot.
    pub fn factorize(&mut self, scale: Option<&[f64]>) -> Result<(), (usize, f64, f64)> {
        let own;
        let scale = match scale {
            Some(s) => s,
            None => {
                own = self.column_maxima();
                &own
            }
        };
        let (n, kl, ld) = (self.n, self.kl, self.ld);
        let kv = self.kl + self.ku;
        let mut ju = 0;
        self.fill = self.ku;
        for (j, &column_scale) in scale.iter().enumerate().take(n) {
            let km = kl.min(n - 1 - j);
            let base = j * ld + kv;
            let (mut p, mut best) = (0, self.ab[base].abs());
            for r in 1..=km {
                let a = self.ab[base + r].abs();
                if a > best {
                    (p, best) = (r, a);
                }
            }
            self.pivots[j] = j + p;
            if is_zero_pivot(best, column_scale) {
                return Err((j, best, column_scale));
            }
            ju = ju.max((j + self.ku + p).min(n - 1));
            // row j of U reaches column ju at most (the elimination below writes no farther)
            self.fill = self.fill.max(ju - j);
            if p != 0 {
                for c in j..=ju {
                    let top = c * ld + kv - (c - j);
                    self.ab.swap(top, top + p);
                }
            }
            let inv = 1.0 / self.ab[base];
            for v in &mut self.ab[base + 1..=base + km] {
                *v *= inv;
            }
            if km == 0 {
                continue;
            }
            let (left, right) = self.ab.split_at_mut((j + 1) * ld);
            let l = &left[base + 1..=base + km];
            for c in j + 1..=ju {
                let top = (c - j - 1) * ld + kv - (c - j);
                let a = right[top];
                if a != 0.0 {
                    for (x, &m) in right[top + 1..=top + km].iter_mut().zip(l) {
                        *x -= a * m;
                    }
                }
            }
        }
        Ok(())
    }

    /// The pivot |u_jj| smallest against `scale[j]` after [`Self::factorize`]: (j, |u_jj|, scale[j]).
    pub fn smallest_pivot(&self, scale: &[f64]) -> Option<(usize, f64, f64)> {
        let kv = self.kl + self.ku;
        (0..self.n.min(scale.len()))
            .map(|j| (j, self.ab[j * self.ld + kv].abs(), scale[j]))
            .min_by(|a, b| (a.1 / a.2).total_cmp(&(b.1 / b.2)))
    }

    /// Overwrite `b` (length n) with A⁻¹ b from the factors.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, kl, ld) = (self.n, self.kl, self.ld);
        let kv = self.kl + self.ku;
        for j in 0..n {
            let p = self.pivots[j];
            if p != j {
                b.swap(p, j);
            }
            let km = kl.min(n - 1 - j);
            let t = b[j];
            if t != 0.0 {
                let l = &self.ab[j * ld + kv + 1..=j * ld + kv + km];
                for (x, &m) in b[j + 1..=j + km].iter_mut().zip(l) {
                    *x -= t * m;
                }
            }
        }
        for j in (0..n).rev() {
            let col = &self.ab[j * ld..(j + 1) * ld];
            b[j] /= col[kv];
            let t = b[j];
            if t != 0.0 {
                // rows above j − fill hold exact zeros of U (the fill room no interchange used)
                let top = j.saturating_sub(self.fill);
                // rows top … j−1 of column j sit at storage rows kv − (j − i)
                for (i, x) in b[top..j].iter_mut().enumerate() {
                    *x -= t * col[kv - (j - top - i)];
                }
            }
        }
    }
}

impl BandLu {
    /// Overwrite the n × m row-major `b` (row i: the m right-hand sides' entries i) with
    /// A⁻¹ b: per column the operations of [`Self::solve_in_place`] in its order (the
    /// same result to the bit), the factors read once for all m columns.
    pub fn solve_many_in_place(&self, b: &mut [f64], m: usize) {
        let (n, kl, ld) = (self.n, self.kl, self.ld);
        let kv = self.kl + self.ku;
        if m == 0 {
            return;
        }
        assert_eq!(b.len(), n * m, "right-hand sides of {n} × {m}");
        for j in 0..n {
            let p = self.pivots[j];
            if p != j {
                let (head, tail) = b.split_at_mut(p * m);
                head[j * m..(j + 1) * m].swap_with_slice(&mut tail[..m]);
            }
            let km = kl.min(n - 1 - j);
            let l = &self.ab[j * ld + kv + 1..=j * ld + kv + km];
            let (head, tail) = b.split_at_mut((j + 1) * m);
            let t = &head[j * m..];
            for (row, &lr) in tail.chunks_exact_mut(m).zip(l) {
                for (x, &tk) in row.iter_mut().zip(t) {
                    // x − 0 = x for every x: the skip of the single solve, branch-free
                    *x -= if tk != 0.0 { tk * lr } else { 0.0 };
                }
            }
        }
        for j in (0..n).rev() {
            let col = &self.ab[j * ld..(j + 1) * ld];
            let top = j.saturating_sub(self.fill);
            let (head, tail) = b.split_at_mut(j * m);
            let t = &mut tail[..m];
            for x in t.iter_mut() {
                *x /= col[kv];
            }
            for (i, row) in head[top * m..].chunks_exact_mut(m).enumerate() {
                let a = col[kv - (j - top - i)];
                for (x, &tk) in row.iter_mut().zip(t.iter()) {
                    *x -= if tk != 0.0 { tk * a } else { 0.0 };
                }
            }
        }
    }
}

/// Largest |a_ij − a_ji| relative to the larger of columns i's and j's largest entries
/// for which a [`BorderedBand`] made [`BorderedBand::symmetric`] takes a matrix as
/// symmetric (τ of the pivots): the lower triangle it factorises then differs from the
/// matrix by round-off of its columns' size.
pub const SYMMETRY_TOLERANCE: f64 = PIVOT_TOLERANCE;

/// Cholesky factor L (A = L Lᵀ) of a symmetric positive definite n × n band matrix of
/// half-width k, in lower band storage: column j holds rows j … j + k (leading dimension
/// k + 1). No pivoting: it exists and is backward stable exactly when A is positive
/// definite, which the pivots l_jj² > 0 decide as they are computed.
#[derive(Debug, Clone, Default)]
struct BandCholesky {
    n: usize,
    k: usize,
    l: Vec<f64>,
}

impl BandCholesky {
    /// The lower triangle of `band`'s matrix (read before its LU) factorised. A pivot
    /// l_jj² ≤ `ratio` · scale[j] (or not finite) is an error (j, pivot, scale[j]): A is
    /// not positive definite, or too ill-conditioned to be factorised without pivoting.
    fn factorize(&mut self, band: &BandLu, scale: &[f64], ratio: f64) -> Result<(), (usize, f64, f64)> {
        let (n, k) = (band.n, band.kl);
        let (ld, kv) = (k + 1, band.kl + band.ku);
        self.n = n;
        self.k = k;
        self.l.resize(ld * n, 0.0);
        for j in 0..n {
            let from = j * band.ld + kv;
            self.l[j * ld..(j + 1) * ld].copy_from_slice(&band.ab[from..from + ld]);
        }
        let l = &mut self.l;
        for j in 0..n {
            let pivot = l[j * ld];
            if pivot.partial_cmp(&(ratio * scale[j])) != Some(std::cmp::Ordering::Greater) || !pivot.is_finite() {
                return Err((j, pivot, scale[j]));
            }
            let root = pivot.sqrt();
            let km = k.min(n - 1 - j);
            l[j * ld] = root;
            let inv = 1.0 / root;
            for x in &mut l[j * ld + 1..=j * ld + km] {
                *x *= inv;
            }
            // the trailing update of the columns j + 1 … j + km, rows down to j + km
            let (left, right) = l.split_at_mut((j + 1) * ld);
            let column = &left[j * ld + 1..=j * ld + km];
            for c in 1..=km {
                let a = column[c - 1];
                if a != 0.0 {
                    let target = &mut right[(c - 1) * ld..(c - 1) * ld + km - c + 1];
                    for (x, &m) in target.iter_mut().zip(&column[c - 1..]) {
                        *x -= a * m;
                    }
                }
            }
        }
        Ok(())
    }

    /// Overwrite the n × m row-major `b` with L⁻¹ b (forward substitution).
    fn forward_many(&self, b: &mut [f64], m: usize) {
        let (n, k, ld) = (self.n, self.k, self.k + 1);
        for j in 0..n {
            let km = k.min(n - 1 - j);
            let col = &self.l[j * ld..=j * ld + km];
            let (head, tail) = b.split_at_mut((j + 1) * m);
            let t = &mut head[j * m..];
            let inv = 1.0 / col[0];
            for x in t.iter_mut() {
                *x *= inv;
            }
            for (row, &lr) in tail.chunks_exact_mut(m).zip(&col[1..]) {
                for (x, &tk) in row.iter_mut().zip(t.iter()) {
                    *x -= tk * lr;
                }
            }
        }
    }

    /// Overwrite `b` (length n) with L⁻ᵀ b (back substitution).
    fn backward(&self, b: &mut [f64]) {
        let (n, k, ld) = (self.n, self.k, self.k + 1);
        for j in (0..n).rev() {
            let km = k.min(n - 1 - j);
            let col = &self.l[j * ld..=j * ld + km];
            let s: f64 = col[1..].iter().zip(&b[j + 1..=j + km]).map(|(a, x)| a * x).sum();
            b[j] = (b[j] - s) / col[0];
        }
    }
}

/// Solve `b` (n × m row-major) in place by `solve(part, columns)` on two halves of its
/// columns at once (rayon): per column the same operations as one call on all m, so the
/// same numbers to the bit.
fn solve_columns_in_two(b: &mut [f64], n: usize, m: usize, solve: impl Fn(&mut [f64], usize) + Sync) {
    if m < 2 || n == 0 {
        solve(b, m);
        return;
    }
    let m1 = m / 2;
    let m2 = m - m1;
    let mut first = vec![0.0; n * m1];
    let mut second = vec![0.0; n * m2];
    for ((row, a), z) in b.chunks_exact(m).zip(first.chunks_exact_mut(m1)).zip(second.chunks_exact_mut(m2)) {
        a.copy_from_slice(&row[..m1]);
        z.copy_from_slice(&row[m1..]);
    }
    rayon::join(|| solve(&mut first, m1), || solve(&mut second, m2));
    for ((row, a), z) in b.chunks_exact_mut(m).zip(first.chunks_exact(m1)).zip(second.chunks_exact(m2)) {
        row[..m1].copy_from_slice(a);
        row[m1..].copy_from_slice(z);
    }
}

/// The border and band of a pattern: `inner` (global indices in order) form a band of
/// half-widths (kl, ku) once `border` is taken out.
#[derive(Debug, Clone, PartialEq)]
pub struct BandStructure {
    pub n: usize,
    pub border: Vec<usize>,
    pub inner: Vec<usize>,
    pub kl: usize,
    pub ku: usize,
}

impl BandStructure {
    /// The cheapest band-plus-border split of the n × n pattern (`rows`, `cols`) with
    /// the unknowns `forced` in the border, or `None` if the best one is no band (a
    /// border of more than [`MAX_BORDER`] or a half-width above [`MAX_HALF_BAND`]).
    /// Two orders of the unknowns are tried, the given one and [`neighbour_order`]
    /// (unknowns appended after a mesh's, e.g. one per friction point, moved next to
    /// the nodes they couple with); in each, for each candidate half-width w (the
    /// distinct distances of the entries, ascending), the entries farther than w are
    /// covered by border unknowns greedily (the one on most such entries first — a dense
    /// row and column before the two ends of a wrap-around); the split of least
    /// estimated flops ([`BandStructure::flops`]) is taken.
    pub fn detect(n: usize, rows: &[usize], cols: &[usize], forced: &[usize]) -> Option<BandStructure> {
        if forced.iter().any(|&f| f >= n) {
            return None;
        }
        let mut is_forced = vec![false; n];
        for &f in forced {
            is_forced[f] = true;
        }
        // the distinct off-diagonal entries off the forced unknowns, with multiplicity (a
        // pattern lists an entry once per element or point that couples it: the steady
        // drive's 58 000 entries at 627 unknowns are ~8 000 distinct)
        let listed = rows.iter().zip(cols).filter(|&(&r, &c)| r != c && !is_forced[r] && !is_forced[c]).map(|(&r, &c)| (r, c, 1));
        let distinct = by_distance(n, listed);
        let natural: Vec<usize> = (0..n).collect();
        let moved = neighbour_order_of(n, &distinct);
        let first = Self::detect_in_order(&natural, &distinct, forced);
        let second = if moved == natural { None } else { Self::detect_in_order(&moved, &distinct, forced) };
        match (first, second) {
            (Some(a), Some(b)) => Some(if b.flops() < a.flops() { b } else { a }),
            (a, b) => a.or(b),
        }
    }

    /// The split of the n × n pattern (`rows`, `cols`) with the unknowns `border` (in
    /// this order) as the border and all others, in their given order, as the band, its
    /// half-widths read from the pattern — for a caller that knows its structure, e.g. a
    /// closed loop of a mesh's nodes numbered node by node and cut at one node: that
    /// node's unknowns as the border, the band the rest (a closed surface mesh whose
    /// band is wider than [`MAX_HALF_BAND`] or whose cut is larger than [`MAX_BORDER`],
    /// the caps of [`Self::detect`]'s search, which do not apply here). `None` if a
    /// border index is ≥ n or given twice.
    pub fn with_border(n: usize, rows: &[usize], cols: &[usize], border: &[usize]) -> Option<BandStructure> {
        let mut inner_of = vec![usize::MAX; n];
        for &b in border {
            if b >= n || inner_of[b] == usize::MAX - 1 {
                return None;
            }
            inner_of[b] = usize::MAX - 1;
        }
        let mut inner = Vec::with_capacity(n - border.len());
        for g in 0..n {
            if inner_of[g] == usize::MAX {
                inner_of[g] = inner.len();
                inner.push(g);
            }
        }
        let (mut kl, mut ku) = (0, 0);
        for (&r, &c) in rows.iter().zip(cols) {
            let (i, j) = (inner_of[r], inner_of[c]);
            if i < n && j < n {
                kl = kl.max(i.saturating_sub(j));
                ku = ku.max(j.saturating_sub(i));
            }
        }
        Some(BandStructure { n, border: border.to_vec(), inner, kl, ku })
    }

    /// Estimated flops of one factorisation: n w (3w + 1) for the band's LU and solves
    /// (w = max(kl, ku)), m n (3w + 1) + m² n for the border of m unknowns.
    pub fn flops(&self) -> f64 {
        band_flops(self.n, self.kl.max(self.ku), self.border.len())
    }

    /// [`Self::detect`] with the unknowns in the order `order` (a permutation of 0…n−1),
    /// on the `distinct` off-diagonal entries (r, c, multiplicity) off the forced unknowns.
    fn detect_in_order(order: &[usize], distinct: &[(usize, usize, usize)], forced: &[usize]) -> Option<BandStructure> {
        let n = order.len();
        let mut position = vec![0; n];
        for (p, &g) in order.iter().enumerate() {
            position[g] = p;
        }
        // the entries in positions of `order`, the farthest first: the entries outside a
        // band of half-width w are a prefix. Counts and degrees below are sums over the
        // pattern's entries (multiplicities), and the greedy cover does not depend on
        // the order of the entries of one distance
        let edges = by_distance(n, distinct.iter().map(|&(r, c, m)| (position[r], position[c], m)));
        // entries[k]: the entries (with multiplicity) of the k farthest distinct ones
        let mut entries = Vec::with_capacity(edges.len() + 1);
        entries.push(0usize);
        for &(_, _, m) in &edges {
            entries.push(entries.last().copied().unwrap_or(0) + m);
        }
        let mut degree = vec![0usize; n];
        for &(r, c, m) in &edges {
            degree[r] += m;
            degree[c] += m;
        }
        // a cover of k entries needs at least k / (the largest degree) unknowns
        let top_degree = degree.iter().copied().max().unwrap_or(0);
        degree.fill(0);
        let room = MAX_BORDER.saturating_sub(forced.len());
        let at_least = |entries: usize, degree: usize| if entries == 0 { 0 } else { entries.div_ceil(degree.max(1)) };
        // the work arrays of a cover: the far entries at each unknown (CSR), whether an
        // entry is still uncovered, the unknowns on far entries
        let (mut first, mut incident, mut alive, mut touched) = (vec![0usize; n + 1], Vec::new(), Vec::new(), Vec::new());
        // the greedy cover of the entries farther than w — each step the unknown on most
        // uncovered entries (ties: the lowest position) —, or `None` if it overflows the
        // room or cannot cost less than `bound` (its flops with the fewest unknowns that
        // could still cover what is left are ≥ `bound`: such a split would not be taken)
        let mut cover_outside = |w: usize, bound: f64| -> Option<Vec<usize>> {
            let distinct = edges.partition_point(|&(r, c, _)| r.abs_diff(c) > w);
            let mut count = entries[distinct];
            if count > room * top_degree || band_flops(n, w, forced.len() + at_least(count, top_degree)) >= bound {
                return None;
            }
            let far = &edges[..distinct];
            touched.clear();
            for &(r, c, m) in far {
                for v in [r, c] {
                    if degree[v] == 0 {
                        touched.push(v);
                    }
                    degree[v] += m;
                }
            }
            first.fill(0);
            for &(r, c, _) in far {
                first[r + 1] += 1;
                first[c + 1] += 1;
            }
            for v in 0..n {
                first[v + 1] += first[v];
            }
            incident.clear();
            incident.resize(2 * distinct, 0);
            let mut next = first.clone();
            for (k, &(r, c, _)) in far.iter().enumerate() {
                for v in [r, c] {
                    incident[next[v]] = k;
                    next[v] += 1;
                }
            }
            alive.clear();
            alive.resize(distinct, true);
            let mut cover = Vec::new();
            let result = loop {
                if count == 0 {
                    break Some(cover);
                }
                let most = touched.iter().copied().max_by_key(|&v| (degree[v], std::cmp::Reverse(v))).unwrap_or(0);
                let max_degree = degree[most];
                if cover.len() >= room || count > (room - cover.len()) * max_degree {
                    break None;
                }
                if band_flops(n, w, forced.len() + cover.len() + at_least(count, max_degree)) >= bound {
                    break None;
                }
                cover.push(most);
                for &k in &incident[first[most]..first[most + 1]] {
                    if alive[k] {
                        alive[k] = false;
                        let (r, c, m) = far[k];
                        degree[r] -= m;
                        degree[c] -= m;
                        count -= m;
                    }
                }
            };
            for &v in &touched {
                degree[v] = 0;
            }
            result
        };
        let mut distances: Vec<usize> = edges.iter().map(|&(r, c, _)| r.abs_diff(c)).filter(|&d| d <= MAX_HALF_BAND).collect();
        distances.push(0);
        distances.sort_unstable();
        distances.dedup();
        // the widest admissible band first: if its border overflows, every narrower one's does
        let widest = *distances.last().unwrap_or(&0);
        let mut best: Option<(f64, Vec<usize>)> = cover_outside(widest, f64::INFINITY).map(|cover| (band_flops(n, widest, forced.len() + cover.len()), cover));
        best.as_ref()?;
        for &w in &distances {
            let wf = w as f64;
            let bound = best.as_ref().map_or(f64::INFINITY, |(cost, _)| *cost);
            if n as f64 * wf * (3.0 * wf + 1.0) >= bound {
                break;
            }
            let Some(cover) = cover_outside(w, bound) else { continue };
            let cost = band_flops(n, w, forced.len() + cover.len());
            if cost < bound {
                best = Some((cost, cover));
            }
        }
        let (_, cover) = best?;
        let mut border: Vec<usize> = forced.to_vec();
        border.extend(cover.iter().map(|&p| order[p]));
        let mut in_border = vec![false; n];
        for &b in &border {
            in_border[b] = true;
        }
        let mut inner_of = vec![usize::MAX; n];
        let mut inner = Vec::with_capacity(n - border.len());
        for &g in order {
            if !in_border[g] {
                inner_of[g] = inner.len();
                inner.push(g);
            }
        }
        let (mut kl, mut ku) = (0, 0);
        // (the diagonal and the forced unknowns' entries lie in the band or the border)
        for &(r, c, _) in distinct {
            if !in_border[r] && !in_border[c] {
                let (i, j) = (inner_of[r], inner_of[c]);
                kl = kl.max(i.saturating_sub(j));
                ku = ku.max(j.saturating_sub(i));
            }
        }
        (kl <= MAX_HALF_BAND && ku <= MAX_HALF_BAND).then_some(BandStructure { n, border, inner, kl, ku })
    }
}

/// Estimated flops of a band of half-width w with a border of m unknowns (see
/// [`BandStructure::flops`]).
fn band_flops(n: usize, w: usize, m: usize) -> f64 {
    let (n, w, m) = (n as f64, w as f64, m as f64);
    n * (w * (3.0 * w + 1.0) + m * (3.0 * w + 1.0) + m * m)
}

/// The entries (r, c, multiplicity) of an n × n pattern (off the diagonal) sorted by
/// distance |r − c|, the farthest first, each distinct (r, c) once with the sum of its
/// multiplicities; the order within one distance is unspecified. A counting sort by
/// distance, the entries of one distance merged by (row, side of the diagonal):
/// O(entries + n).
fn by_distance(n: usize, entries: impl Iterator<Item = (usize, usize, usize)> + Clone) -> Vec<(usize, usize, usize)> {
    // bucket n − d holds distance d
    let mut start = vec![0usize; n + 1];
    for (r, c, _) in entries.clone() {
        start[n - r.abs_diff(c)] += 1;
    }
    let mut sum = 0;
    for s in start.iter_mut() {
        (*s, sum) = (sum, sum + *s);
    }
    let mut listed = vec![(0usize, 0usize, 0usize); sum];
    for e in entries {
        let b = &mut start[n - e.0.abs_diff(e.1)];
        listed[*b] = e;
        *b += 1;
    }
    let mut merged: Vec<(usize, usize, usize)> = Vec::with_capacity(sum / 4 + 1);
    // the merged entry of (row, side) within the current distance, from `current` on
    let mut seen = vec![usize::MAX; 2 * n];
    let (mut distance, mut current) = (usize::MAX, 0);
    for (r, c, m) in listed {
        let d = r.abs_diff(c);
        if d != distance {
            (distance, current) = (d, merged.len());
        }
        let key = 2 * r + usize::from(c > r);
        match seen[key] {
            k if k != usize::MAX && k >= current => merged[k].2 += m,
            _ => {
                seen[key] = merged.len();
                merged.push((r, c, m));
            }
        }
    }
    merged
}

/// The unknowns reordered so that each unknown coupled mostly far from its own index (an
/// unknown numbered after a mesh's, e.g. one per friction point) sits at the lower
/// median of its neighbours' indices, the others keeping their places (ties in index
/// order). "Far" is beyond T = 2 × (the median over the unknowns of their neighbours'
/// median distance) — a few nodes' unknowns on a mesh; the two ends of a closed loop's
/// numbering are near most of their neighbours and stay. The `forced` unknowns and the
/// diagonal are left out.
pub fn neighbour_order(n: usize, rows: &[usize], cols: &[usize], forced: &[usize]) -> Vec<usize> {
    let mut is_forced = vec![false; n];
    for &f in forced {
        is_forced[f] = true;
    }
    let listed = rows.iter().zip(cols).filter(|&(&r, &c)| r != c && !is_forced[r] && !is_forced[c]).map(|(&r, &c)| (r, c, 1));
    neighbour_order_of(n, &by_distance(n, listed))
}

/// [`neighbour_order`] of the distinct off-diagonal entries (r, c, multiplicity) off the
/// forced unknowns.
fn neighbour_order_of(n: usize, distinct: &[(usize, usize, usize)]) -> Vec<usize> {
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(r, c, _) in distinct {
        neighbours[r].push(c);
    }
    let lower_median = |v: &mut Vec<usize>| {
        v.sort_unstable();
        v[(v.len() - 1) / 2]
    };
    let mut median_distance: Vec<usize> = Vec::with_capacity(n);
    for (g, list) in neighbours.iter_mut().enumerate() {
        list.sort_unstable();
        list.dedup();
        if !list.is_empty() {
            median_distance.push(lower_median(&mut list.iter().map(|&j| j.abs_diff(g)).collect()));
        }
    }
    if median_distance.is_empty() {
        return (0..n).collect();
    }
    let far = 2 * lower_median(&mut median_distance).max(1);
    let key: Vec<usize> = neighbours
        .iter()
        .enumerate()
        .map(|(g, list)| {
            let distant = list.iter().filter(|&&j| j.abs_diff(g) > far).count();
            if 2 * distant > list.len() {
                list[(list.len() - 1) / 2]
            } else {
                g
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&g| (key[g], g));
    order
}

/// Where a pattern entry goes.
#[derive(Debug, Clone, Copy)]
enum Slot {
    /// A storage position of the band.
    Band(usize),
    /// B: (inner row, border column).
    B(usize, usize),
    /// C: (border row, inner column).
    C(usize, usize),
    /// D: (border row, border column).
    D(usize, usize),
}

/// Dense LU with partial pivoting of the m × m Schur complement (row-major).
#[derive(Debug, Clone, Default)]
struct DenseLu {
    m: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

impl DenseLu {
    /// Factorise `a` (row-major m × m); `scale[l]` judges the pivot of column l.
    /// Returns the determinant on a pivot ≤ τ scale[l].
    fn factorize(&mut self, m: usize, mut a: Vec<f64>, scale: &[f64]) -> Result<(), f64> {
        let mut pivots = vec![0; m];
        let mut det = 1.0;
        for k in 0..m {
            let p = (k..m).max_by(|&i, &j| a[i * m + k].abs().total_cmp(&a[j * m + k].abs())).unwrap_or(k);
            pivots[k] = p;
            if p != k {
                // the trailing columns only (LINPACK's order: the solve interleaves the
                // interchanges with the elimination)
                for l in k..m {
                    a.swap(k * m + l, p * m + l);
                }
                det = -det;
            }
            let pivot = a[k * m + k];
            det *= pivot;
            if is_zero_pivot(pivot.abs(), scale[k]) {
                // the determinant so far, the remaining pivots taken as the rows left
                return Err(if pivot.is_finite() { det } else { f64::NAN });
            }
            for i in k + 1..m {
                let f = a[i * m + k] / pivot;
                a[i * m + k] = f;
                for l in k + 1..m {
                    a[i * m + l] -= f * a[k * m + l];
                }
            }
        }
        *self = DenseLu { m, a, pivots };
        Ok(())
    }

    fn solve_in_place(&self, b: &mut [f64]) {
        let m = self.m;
        for k in 0..m {
            b.swap(k, self.pivots[k]);
            for i in k + 1..m {
                b[i] -= self.a[i * m + k] * b[k];
            }
        }
        for k in (0..m).rev() {
            let s: f64 = (k + 1..m).map(|l| self.a[k * m + l] * b[l]).sum();
            b[k] = (b[k] - s) / self.a[k * m + k];
        }
    }
}

/// Why a [`BorderedBand`] factorisation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum BandFailure {
    /// A pivot of the band block A: (inner column, |pivot|, column scale). With a
    /// border the whole matrix may still be regular (A alone singular).
    Band { column: usize, pivot: f64, scale: f64 },
    /// The Schur complement's LU: the determinant up to the failing pivot.
    Schur { det: f64 },
}

/// The LU of a matrix of pattern (`rows`, `cols`) split by a [`BandStructure`] (see the
/// module docs for the algebra). Values are given in pattern order, duplicates summed.
#[derive(Debug, Clone)]
pub struct BorderedBand {
    structure: BandStructure,
    slots: Vec<Slot>,
    /// Band position of each inner unknown's diagonal.
    diagonal: Vec<usize>,
    band: BandLu,
    /// V = A⁻¹ B, row-major (inner × border) — or, after a Cholesky factorisation,
    /// W = L⁻¹ B; C row-major (border × inner).
    v: Vec<f64>,
    c: Vec<f64>,
    schur: DenseLu,
    /// Try the Cholesky factorisation of A first ([`Self::symmetric`]).
    symmetric: bool,
    cholesky: BandCholesky,
    /// The last factorisation's A was factorised by Cholesky (else by the LU).
    by_cholesky: bool,
    /// Factorisations done by Cholesky, and matrices it refused (not symmetric, A not
    /// positive definite, or the border's Schur complement judged singular on the
    /// Cholesky path: the LU took them).
    pub cholesky_factorisations: usize,
    pub cholesky_refusals: usize,
}

impl BorderedBand {
    /// The split of the pattern by `structure` (from [`BandStructure::detect`] on it).
    pub fn new(structure: BandStructure, rows: &[usize], cols: &[usize]) -> Self {
        let n = structure.n;
        let mut place = vec![(false, 0usize); n];
        for (k, &b) in structure.border.iter().enumerate() {
            place[b] = (true, k);
        }
        for (i, &g) in structure.inner.iter().enumerate() {
            place[g] = (false, i);
        }
        let band = BandLu::zeros(structure.inner.len(), structure.kl, structure.ku);
        let slots = rows
            .iter()
            .zip(cols)
            .map(|(&r, &c)| match (place[r], place[c]) {
                ((false, i), (false, j)) => Slot::Band(band.position(i, j).expect("the structure's band holds every inner entry")),
                ((false, i), (true, k)) => Slot::B(i, k),
                ((true, k), (false, j)) => Slot::C(k, j),
                ((true, k), (true, l)) => Slot::D(k, l),
            })
            .collect();
        let diagonal = (0..structure.inner.len()).map(|i| band.position(i, i).unwrap_or(0)).collect();
        BorderedBand {
            structure,
            slots,
            diagonal,
            band,
            v: Vec::new(),
            c: Vec::new(),
            schur: DenseLu::default(),
            symmetric: false,
            cholesky: BandCholesky::default(),
            by_cholesky: false,
            cholesky_factorisations: 0,
            cholesky_refusals: 0,
        }
    }

    /// The same, for symmetric matrices (an energy's Hessian): each factorisation first
    /// checks the values' symmetry (to [`SYMMETRY_TOLERANCE`]) and factorises A by
    /// Cholesky, A = L Lᵀ — half the band LU's work, and the border's Schur complement
    /// S = D − Wᵀ W from the m forward solves W = L⁻¹ B alone (the LU needs forward and
    /// back solves over a band widened by its interchanges' fill room). A matrix that is
    /// not symmetric, or whose A has a pivot l_jj² at or below the LU's threshold (A not
    /// positive definite — an indefinite Hessian away from a minimum — or as ill
    /// conditioned as the LU would refuse), is factorised by the LU as without this; the
    /// solution agrees with the LU's to round-off.
    pub fn symmetric(structure: BandStructure, rows: &[usize], cols: &[usize]) -> Self {
        BorderedBand { symmetric: true, ..Self::new(structure, rows, cols) }
    }

    /// The split in use.
    pub fn structure(&self) -> &BandStructure {
        &self.structure
    }

    /// Factorise the matrix of `values` (pattern order) with `shift[g]` added to the
    /// diagonal of each unknown g (empty: none).
    ///
    /// # Errors
    /// [`BandFailure`]: a zero pivot of A (the caller may fall back to a general LU of
    /// the whole matrix) or of the Schur complement (the matrix is singular).
    pub fn factorize(&mut self, values: &[f64], shift: &[f64]) -> Result<(), BandFailure> {
        let (ni, m) = (self.structure.inner.len(), self.structure.border.len());
        self.band.clear();
        let mut b = vec![0.0; ni * m];
        let mut c = vec![0.0; m * ni];
        let mut d = vec![0.0; m * m];
        for (slot, &v) in self.slots.iter().zip(values) {
            match *slot {
                Slot::Band(p) => self.band.add_at(p, v),
                Slot::B(i, k) => b[k * ni + i] += v,
                Slot::C(k, j) => c[k * ni + j] += v,
                Slot::D(k, l) => d[k * m + l] += v,
            }
        }
        if !shift.is_empty() {
            for (i, &g) in self.structure.inner.iter().enumerate() {
                self.band.add_at(self.diagonal[i], shift[g]);
            }
            for (k, &g) in self.structure.border.iter().enumerate() {
                d[k * m + k] += shift[g];
            }
        }
        // a pivot of A is judged against its whole column, the border rows included
        let mut scale = self.band.column_maxima();
        for row in c.chunks_exact(ni.max(1)).take(m) {
            for (s, x) in scale.iter_mut().zip(row) {
                *s = s.max(x.abs());
            }
        }
        self.by_cholesky = false;
        if self.symmetric {
            if self.values_symmetric(&b, &c, &d, &scale) {
                let ratio = if m > 0 { BORDER_PIVOT_RATIO } else { PIVOT_TOLERANCE };
                // a Schur complement judged singular here goes to the LU path too (its
                // terms' size is measured more coarsely than there), not to faer's LU
                if self.cholesky.factorize(&self.band, &scale, ratio).is_ok() && self.cholesky_border(&b, &c, &d).is_ok() {
                    return Ok(());
                }
            }
            self.cholesky_refusals += 1;
        }
        self.band.factorize(Some(&scale)).map_err(|(column, pivot, scale)| BandFailure::Band { column, pivot, scale })?;
        if m > 0 {
            if let Some((column, pivot, scale)) = self.band.smallest_pivot(&scale).filter(|&(_, p, s)| p.partial_cmp(&(BORDER_PIVOT_RATIO * s)) != Some(std::cmp::Ordering::Greater)) {
                return Err(BandFailure::Band { column, pivot, scale });
            }
        }
        // V = A⁻¹ B, all m columns in one sweep over the factors (row-major: row i holds
        // the m values of inner unknown i) — the same operations in the same order per
        // column as m single solves, so the same V to the bit, but the band's factors
        // (n (2kl + ku + 1) values, megabytes at a shell's widths) are read once, not m times
        let mut v = vec![0.0; ni * m];
        for (k, col) in b.chunks_exact(ni.max(1)).take(m).enumerate() {
            for (i, &x) in col.iter().enumerate() {
                v[i * m + k] = x;
            }
        }
        let band = &self.band;
        solve_columns_in_two(&mut v, ni, m, |part, columns| band.solve_many_in_place(part, columns));
        // S = D − C V and the size of its terms: per (k, l) the sum over i in order (a zero
        // C_ki adds an exact zero and is skipped; C is nonzero only next to the border)
        let mut s = d;
        let mut size: Vec<f64> = s.iter().map(|x| x.abs()).collect();
        let (mut dot, mut abs) = (vec![0.0; m], vec![0.0; m]);
        for k in 0..m {
            dot.fill(0.0);
            abs.fill(0.0);
            for (i, &x) in c[k * ni..(k + 1) * ni].iter().enumerate() {
                if x == 0.0 {
                    continue;
                }
                for ((dl, al), &y) in dot.iter_mut().zip(abs.iter_mut()).zip(&v[i * m..(i + 1) * m]) {
                    *dl += x * y;
                    *al += (x * y).abs();
                }
            }
            for l in 0..m {
                s[k * m + l] -= dot[l];
                size[k * m + l] += abs[l];
            }
        }
        let col_scale: Vec<f64> = (0..m).map(|l| (0..m).fold(0.0_f64, |a, k| a.max(size[k * m + l]))).collect();
        self.schur.factorize(m, s, &col_scale).map_err(|det| BandFailure::Schur { det })?;
        self.v = v;
        self.c = c;
        Ok(())
    }

    /// Whether the assembled A (band storage, before its factorisation), B (column k:
    /// `b[k ni..]`), C (row k: `c[k ni..]`) and D are symmetric: |a_ij − a_ji| ≤
    /// [`SYMMETRY_TOLERANCE`] × the larger of the two columns' largest entries (`scale`
    /// for A's columns, the border columns' own). An entry-by-entry relative test would
    /// refuse an assembled Hessian: entries that are sums cancelling to a small value
    /// differ from their mirror by 1e-7 … 1 of themselves (the shell's, at ≤ 6.5e-16 of
    /// their columns, docs/performance.md).
    fn values_symmetric(&self, b: &[f64], c: &[f64], d: &[f64], scale: &[f64]) -> bool {
        let band = &self.band;
        if band.kl != band.ku {
            return false;
        }
        let (ni, m) = (self.structure.inner.len(), self.structure.border.len());
        let border_scale: Vec<f64> = (0..m).map(|k| b[k * ni..(k + 1) * ni].iter().chain((0..m).map(|l| &d[l * m + k])).fold(0.0_f64, |a, x| a.max(x.abs()))).collect();
        let close = |x: f64, y: f64, size: f64| (x - y).abs() <= SYMMETRY_TOLERANCE * size;
        let (n, k, ld, kv) = (band.n, band.kl, band.ld, band.kl + band.ku);
        // a_(j+r, j) in column j's storage row kv + r, a_(j, j+r) in column j + r's row kv − r
        let band_symmetric = (0..n).all(|j| (1..=k.min(n - 1 - j)).all(|r| close(band.ab[j * ld + kv + r], band.ab[(j + r) * ld + kv - r], scale[j].max(scale[j + r]))));
        band_symmetric
            && (0..m).all(|k| (0..ni).all(|i| close(b[k * ni + i], c[k * ni + i], scale[i].max(border_scale[k]))))
            && (0..m).all(|k| (0..k).all(|l| close(d[k * m + l], d[l * m + k], border_scale[k].max(border_scale[l]))))
    }

    /// The border after A = L Lᵀ: W = L⁻¹ B (m forward solves, two halves of the columns
    /// at once), S = D − Wᵀ W (the upper triangle of WᵀW summed over the rows in two
    /// halves at once, mirrored) and its LU; the size of S's terms |D_kl| + ‖W_k‖ ‖W_l‖
    /// (≥ Σ_i |W_ik| |W_il|, the size of the LU path) judges its pivots.
    fn cholesky_border(&mut self, b: &[f64], c: &[f64], d: &[f64]) -> Result<(), BandFailure> {
        let (ni, m) = (self.structure.inner.len(), self.structure.border.len());
        let mut w = vec![0.0; ni * m];
        for (k, col) in b.chunks_exact(ni.max(1)).take(m).enumerate() {
            for (i, &x) in col.iter().enumerate() {
                w[i * m + k] = x;
            }
        }
        let cholesky = &self.cholesky;
        if m > 0 {
            solve_columns_in_two(&mut w, ni, m, |part, columns| cholesky.forward_many(part, columns));
        }
        let gram = |rows: &[f64]| {
            let mut acc = vec![0.0; m * m];
            if m == 0 {
                return acc;
            }
            for row in rows.chunks_exact(m) {
                for (k, &x) in row.iter().enumerate() {
                    if x != 0.0 {
                        for (a, &y) in acc[k * m + k..(k + 1) * m].iter_mut().zip(&row[k..]) {
                            *a += x * y;
                        }
                    }
                }
            }
            acc
        };
        let half = (ni / 2) * m;
        let (upper, lower) = rayon::join(|| gram(&w[..half]), || gram(&w[half..]));
        let norm: Vec<f64> = (0..m).map(|k| (upper[k * m + k] + lower[k * m + k]).sqrt()).collect();
        let mut s = d.to_vec();
        let mut size = vec![0.0; m * m];
        for k in 0..m {
            for l in 0..m {
                let (p, q) = (k.min(l), k.max(l));
                let x = s[k * m + l];
                s[k * m + l] = x - (upper[p * m + q] + lower[p * m + q]);
                size[k * m + l] = x.abs() + norm[k] * norm[l];
            }
        }
        let col_scale: Vec<f64> = (0..m).map(|l| (0..m).fold(0.0_f64, |a, k| a.max(size[k * m + l]))).collect();
        self.schur.factorize(m, s, &col_scale).map_err(|det| BandFailure::Schur { det })?;
        self.v = w;
        self.c = c.to_vec();
        self.by_cholesky = true;
        self.cholesky_factorisations += 1;
        Ok(())
    }

    /// Overwrite `x` (length n, global order) with the solution (after a successful
    /// [`Self::factorize`]).
    pub fn solve_in_place(&self, x: &mut [f64]) {
        let (ni, m) = (self.structure.inner.len(), self.structure.border.len());
        let mut u: Vec<f64> = self.structure.inner.iter().map(|&g| x[g]).collect();
        if self.by_cholesky {
            self.cholesky.forward_many(&mut u, 1);
            self.cholesky.backward(&mut u);
        } else {
            self.band.solve_in_place(&mut u);
        }
        let mut y: Vec<f64> = self.structure.border.iter().map(|&g| x[g]).collect();
        for (k, yk) in y.iter_mut().enumerate() {
            *yk -= self.c[k * ni..(k + 1) * ni].iter().zip(&u).map(|(a, b)| a * b).sum::<f64>();
        }
        self.schur.solve_in_place(&mut y);
        if self.by_cholesky {
            // x_A = u − A⁻¹ B y = u − L⁻ᵀ (W y)
            if m > 0 {
                let mut t: Vec<f64> = self.v.chunks_exact(m).map(|wi| wi.iter().zip(&y).map(|(a, b)| a * b).sum()).collect();
                self.cholesky.backward(&mut t);
                u.iter_mut().zip(&t).for_each(|(a, b)| *a -= b);
            }
        } else if m > 0 {
            for (ui, vi) in u.iter_mut().zip(self.v.chunks_exact(m)) {
                for (&v, &yl) in vi.iter().zip(&y) {
                    *ui -= if yl != 0.0 { v * yl } else { 0.0 };
                }
            }
        }
        for (&g, &ui) in self.structure.inner.iter().zip(&u) {
            x[g] = ui;
        }
        for (&g, &yk) in self.structure.border.iter().zip(&y) {
            x[g] = yk;
        }
    }
}

impl From<BandFailure> for LinearError {
    fn from(f: BandFailure) -> LinearError {
        match f {
            BandFailure::Band { column, pivot, scale } => LinearError::Singular {
                detail: format!("banded LU: pivot {pivot:.3e} of inner column {column} ≤ {PIVOT_TOLERANCE:.1e} × its column's largest entry {scale:.3e}"),
            },
            BandFailure::Schur { det } => LinearError::SingularSchur { det },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::SparseLu;
    use crate::test_support::{dense_of, dense_solve, Lcg};

    type Triplets = (Vec<usize>, Vec<usize>, Vec<f64>);

    fn push(t: &mut Triplets, r: usize, c: usize, v: f64) {
        t.0.push(r);
        t.1.push(c);
        t.2.push(v);
    }

    /// A random n × n band (kl, ku) whose diagonal is small against the subdiagonals, so
    /// that partial pivoting must swap rows; some entries given twice (summed).
    fn random_band(n: usize, kl: usize, ku: usize, rng: &mut Lcg) -> Triplets {
        let mut t = (vec![], vec![], vec![]);
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = if i == j { 0.01 * rng.next() } else { rng.next() };
                push(&mut t, i, j, v);
            }
        }
        for k in 0..n / 5 {
            let e = (7 * k) % t.0.len();
            let (r, c) = (t.0[e], t.1[e]);
            push(&mut t, r, c, 0.1 * rng.next());
        }
        t
    }

    /// max_i |x_i − y_i| / max_i |y_i|.
    fn relative_difference(x: &[f64], y: &[f64]) -> f64 {
        let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        x.iter().zip(y).fold(0.0_f64, |m, (a, b)| m.max((a - b).abs())) / scale
    }

    /// The random matrices below have condition numbers of 10²…10⁴ (small diagonal):
    /// two backward-stable solves then agree to ≈ cond · ε ≤ 1e-11.
    const AGREE: f64 = 1e-10;

    #[test]
    fn band_lu_matches_a_dense_solve_and_pivots() {
        let mut rng = Lcg(99);
        for (n, kl, ku) in [(1, 0, 0), (7, 2, 1), (40, 3, 5), (60, 7, 7), (25, 0, 4), (25, 4, 1)] {
            let (r, c, v) = random_band(n, kl, ku, &mut rng);
            let mut band = BandLu::zeros(n, kl, ku);
            for k in 0..r.len() {
                band.add(r[k], c[k], v[k]);
            }
            band.factorize(None).unwrap();
            if kl > 0 {
                // the small diagonal made partial pivoting swap rows
                assert!(band.pivots.iter().enumerate().any(|(j, &p)| p != j), "{n} {kl} {ku}: no interchange");
            }
            let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let expected = dense_solve(dense_of(n, &r, &c, &v), b.clone());
            let mut x = b.clone();
            band.solve_in_place(&mut x);
            assert!(relative_difference(&x, &expected) < AGREE, "{n} {kl} {ku}: {}", relative_difference(&x, &expected));
        }
    }

    /// The m right-hand sides solved in one sweep equal m single solves to the bit (the
    /// same operations in the same order per column; zero entries, which the single
    /// solve skips, included).
    #[test]
    fn many_right_hand_sides_solve_as_single_ones_to_the_bit() {
        let mut rng = Lcg(7);
        for (n, kl, ku, m) in [(1, 0, 0, 3), (30, 3, 5, 4), (60, 7, 7, 1), (25, 4, 1, 6)] {
            let (r, c, v) = random_band(n, kl, ku, &mut rng);
            let mut band = BandLu::zeros(n, kl, ku);
            for k in 0..r.len() {
                band.add(r[k], c[k], v[k]);
            }
            band.factorize(None).unwrap();
            // column-major columns, every third entry zero
            let columns: Vec<Vec<f64>> = (0..m).map(|_| (0..n).map(|i| if i % 3 == 1 { 0.0 } else { rng.next() }).collect()).collect();
            let mut many: Vec<f64> = (0..n * m).map(|q| columns[q % m][q / m]).collect();
            band.solve_many_in_place(&mut many, m);
            for (k, col) in columns.iter().enumerate() {
                let mut x = col.clone();
                band.solve_in_place(&mut x);
                for i in 0..n {
                    assert_eq!(many[i * m + k].to_bits(), x[i].to_bits(), "{n} {kl} {ku} {m}: ({i}, {k})");
                }
            }
        }
    }

    /// The back substitution starts at the fill the factorisation recorded (ku without
    /// interchanges) instead of the fill room's top kl + ku: the rows skipped hold exact
    /// zeros, so the single and the many-column solves give the same bits as from the
    /// top; the split of the columns into two halves solved at once gives the same bits
    /// as one sweep.
    #[test]
    fn the_solves_skip_the_unused_fill_room_and_split_columns_to_the_bit() {
        let mut rng = Lcg(23);
        for (n, kl, ku, m, dominant) in [(40, 3, 5, 5, true), (40, 3, 5, 5, false), (60, 7, 7, 6, true), (25, 4, 1, 3, false)] {
            let (r, c, mut v) = random_band(n, kl, ku, &mut rng);
            if dominant {
                for k in 0..r.len() {
                    if r[k] == c[k] {
                        v[k] += 10.0 * (kl + ku + 1) as f64;
                    }
                }
            }
            let mut band = BandLu::zeros(n, kl, ku);
            for k in 0..r.len() {
                band.add(r[k], c[k], v[k]);
            }
            band.factorize(None).unwrap();
            if dominant {
                assert_eq!(band.fill, ku, "{n} {kl} {ku}: no interchange, no fill");
            } else {
                assert!(band.fill > ku && band.fill <= kl + ku, "{n} {kl} {ku}: fill {}", band.fill);
            }
            let mut from_top = band.clone();
            from_top.fill = kl + ku;
            let rhs: Vec<f64> = (0..n * m).map(|_| rng.next()).collect();
            let (mut a, mut b) = (rhs.clone(), rhs.clone());
            band.solve_many_in_place(&mut a, m);
            from_top.solve_many_in_place(&mut b, m);
            assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()), "{n} {kl} {ku}: many");
            let (mut x, mut y) = (rhs[..n].to_vec(), rhs[..n].to_vec());
            band.solve_in_place(&mut x);
            from_top.solve_in_place(&mut y);
            assert!(x.iter().zip(&y).all(|(p, q)| p.to_bits() == q.to_bits()), "{n} {kl} {ku}: single");
            let mut split = rhs.clone();
            solve_columns_in_two(&mut split, n, m, |part, columns| band.solve_many_in_place(part, columns));
            assert!(split.iter().zip(&a).all(|(p, q)| p.to_bits() == q.to_bits()), "{n} {kl} {ku}: split");
        }
    }

    /// A closed chain of `nodes` nodes with `dofs` unknowns each, every element coupling
    /// all unknowns of two neighbouring nodes (the last element the last node with the
    /// first: the wrap-around), plus `globals` unknowns at the end coupled to all (dense
    /// rows and columns); a small diagonal so that pivoting is needed.
    fn closed_chain(nodes: usize, dofs: usize, globals: usize, rng: &mut Lcg) -> (usize, Triplets) {
        chain(nodes, dofs, globals, true, rng)
    }

    /// As [`closed_chain`], open (no last element) if not `closed`.
    fn chain(nodes: usize, dofs: usize, globals: usize, closed: bool, rng: &mut Lcg) -> (usize, Triplets) {
        let n = nodes * dofs + globals;
        let mut t = (vec![], vec![], vec![]);
        for e in 0..if closed { nodes } else { nodes - 1 } {
            let unknowns: Vec<usize> = (0..dofs).map(|k| e * dofs + k).chain((0..dofs).map(|k| ((e + 1) % nodes) * dofs + k)).collect();
            for &i in &unknowns {
                for &j in &unknowns {
                    push(&mut t, i, j, if i == j { 0.01 * rng.next() } else { rng.next() });
                }
            }
        }
        for g in nodes * dofs..n {
            for i in 0..n {
                push(&mut t, i, g, rng.next());
                if i != g {
                    push(&mut t, g, i, rng.next());
                }
            }
        }
        (n, t)
    }

    #[test]
    fn the_wrap_around_and_the_global_unknowns_go_to_the_border() {
        let mut rng = Lcg(3);
        let (n, (r, c, _)) = closed_chain(30, 4, 2, &mut rng);
        let s = BandStructure::detect(n, &r, &c, &[]).unwrap();
        // the two dense unknowns first (most far entries), then one node's four
        let mut border = s.border.clone();
        border.sort_unstable();
        assert_eq!(border, vec![0, 1, 2, 3, 120, 121]);
        assert_eq!((s.kl, s.ku), (7, 7));
        assert_eq!(s.inner.len() + s.border.len(), n);
        // the forced border is kept, the rest found the same way
        let forced = BandStructure::detect(n, &r, &c, &[121, 120]).unwrap();
        assert_eq!(&forced.border[..2], &[121, 120]);
        assert_eq!(forced.border.len(), 6);
        // an open chain is a band without border
        let (n, (r, c, _)) = chain(20, 3, 0, false, &mut rng);
        let s = BandStructure::detect(n, &r, &c, &[]).unwrap();
        assert!(s.border.is_empty());
        assert_eq!((s.kl, s.ku), (5, 5));
        // a random sparse pattern is no band
        let (mut rr, mut cc) = (vec![], vec![]);
        for i in 0..300 {
            for _ in 0..6 {
                rr.push(i);
                cc.push(((rng.next() + 1.0) * 150.0) as usize % 300);
            }
        }
        assert_eq!(BandStructure::detect(300, &rr, &cc, &[]), None);
    }

    /// A closed chain (4 unknowns per node) with one unknown per node of its first half
    /// numbered after the mesh (a friction point: coupled with the unknowns of the
    /// node's two elements and with its neighbouring points), and two global unknowns
    /// between the mesh and the points, given as the forced border.
    fn chain_with_points(nodes: usize, rng: &mut Lcg) -> (usize, Vec<usize>, Triplets) {
        let (nm, mut t) = closed_chain(nodes, 4, 2, rng);
        let points = nodes / 2;
        let n = nm + points;
        for p in 0..points {
            let node = p + 1;
            let mut coupled: Vec<usize> = (4 * (node - 1)..4 * (node + 2)).collect();
            coupled.extend([nm + p, nm - 2]);
            if p > 0 {
                coupled.push(nm + p - 1);
            }
            for &i in &coupled {
                push(&mut t, nm + p, i, rng.next());
                if i != nm + p {
                    push(&mut t, i, nm + p, rng.next());
                }
            }
        }
        (n, vec![nm - 2, nm - 1], t)
    }

    #[test]
    fn unknowns_numbered_after_the_mesh_move_into_the_band() {
        let mut rng = Lcg(21);
        let (n, forced, (r, c, v)) = chain_with_points(40, &mut rng);
        let s = BandStructure::detect(n, &r, &c, &forced).unwrap();
        // the two forced unknowns and one node's four; the points inside the band
        assert_eq!(s.border.len(), 6, "{:?}", s.border);
        assert!(s.kl.max(s.ku) <= 12, "{} {}", s.kl, s.ku);
        let order = neighbour_order(n, &r, &c, &forced);
        assert_eq!(&order[..4], &[0, 1, 2, 3], "the closed loop's first node stays");
        let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let mut lu = BorderedBand::new(s, &r, &c);
        lu.factorize(&v, &[]).unwrap();
        let mut x = b.clone();
        lu.solve_in_place(&mut x);
        let d = relative_difference(&x, &dense_solve(dense_of(n, &r, &c, &v), b));
        assert!(d < AGREE, "{d}");
    }

    #[test]
    fn bordered_cyclic_band_matches_a_dense_solve() {
        let mut rng = Lcg(11);
        for (nodes, dofs, globals) in [(30, 4, 2), (12, 2, 0), (50, 6, 1), (3, 4, 2)] {
            let (n, (r, c, v)) = closed_chain(nodes, dofs, globals, &mut rng);
            let structure = BandStructure::detect(n, &r, &c, &[]).unwrap();
            let mut lu = BorderedBand::new(structure, &r, &c);
            let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            for shift in [vec![], (0..n).map(|i| 0.3 + 0.01 * i as f64).collect::<Vec<_>>()] {
                let mut dense = dense_of(n, &r, &c, &v);
                for (i, s) in shift.iter().enumerate() {
                    dense[i][i] += s;
                }
                let expected = dense_solve(dense, b.clone());
                lu.factorize(&v, &shift).unwrap();
                let mut x = b.clone();
                lu.solve_in_place(&mut x);
                let d = relative_difference(&x, &expected);
                assert!(d < AGREE, "{nodes} × {dofs} + {globals}: {d}");
            }
            // the same through SparseLu::banded, which must have chosen the band
            let mut sparse: SparseLu = SparseLu::banded();
            sparse.set_pattern(n, &r, &c).unwrap();
            assert!(sparse.band_structure().is_some());
            sparse.factorize(&v).unwrap();
            let mut x = b.clone();
            sparse.solve_in_place(&mut x).unwrap();
            assert!(relative_difference(&x, &dense_solve(dense_of(n, &r, &c, &v), b.clone())) < AGREE);
        }
    }

    /// The unknowns of each element of a closed surface mesh of `ns` × `nz` elements
    /// with `d` unknowns per node, numbered node by node (σ-node i, ζ-node j: unknowns
    /// d((nz + 1) i + j) …), element (i, j) in order i, then j, over its four nodes —
    /// the last σ-element's with the first σ-node (the belt's wrap-around).
    fn surface_elements(ns: usize, nz: usize, d: usize) -> impl Iterator<Item = Vec<usize>> {
        let per = d * (nz + 1);
        (0..ns).flat_map(move |i| {
            (0..nz).map(move |j| {
                let corners = [(i, j), ((i + 1) % ns, j), (i, j + 1), ((i + 1) % ns, j + 1)];
                corners.iter().flat_map(|&(a, b)| (0..d).map(move |k| a * per + b * d + k)).collect()
            })
        })
    }

    /// A closed surface mesh of `ns` × `nz` elements with `d` unknowns per node,
    /// numbered node by node (σ-node i, ζ-node j: unknowns d((nz + 1) i + j) …), each
    /// element coupling all unknowns of its four nodes, the last σ-element the last
    /// σ-nodes with the first (the belt's wrap-around); a small diagonal.
    fn closed_surface(ns: usize, nz: usize, d: usize, rng: &mut Lcg) -> (usize, Triplets) {
        let per = d * (nz + 1);
        let n = ns * per;
        let mut t = (vec![], vec![], vec![]);
        for unknowns in surface_elements(ns, nz, d) {
            for &r in &unknowns {
                for &c in &unknowns {
                    push(&mut t, r, c, if r == c { 0.01 * rng.next() } else { rng.next() });
                }
            }
        }
        (n, t)
    }

    /// The cut of a closed surface mesh at σ-node 0 (the shell's split): the border is
    /// that node's unknowns, the band the rest in order with the half-width from a
    /// σ-node's first unknown to the last of the next σ-node's second ζ-node; the solve
    /// agrees with faer's general sparse LU and a dense LU to round-off, with the band
    /// and faer chosen by the same `SparseLu`; the split is the one
    /// [`BandStructure::detect`] finds where its caps allow; bad borders are refused.
    #[test]
    fn a_closed_surface_cut_at_one_sigma_node_is_a_band_and_a_border() {
        let mut rng = Lcg(17);
        for (ns, nz, d) in [(12, 2, 4), (9, 4, 3), (3, 1, 2), (40, 2, 12), (2, 3, 2)] {
            let (n, (r, c, v)) = closed_surface(ns, nz, d, &mut rng);
            let per = d * (nz + 1);
            let border: Vec<usize> = (0..per).collect();
            let s = BandStructure::with_border(n, &r, &c, &border).unwrap();
            assert_eq!(s.border, border);
            assert_eq!(s.inner, (per..n).collect::<Vec<_>>());
            let w = if ns == 2 { 2 * d - 1 } else { per + 2 * d - 1 };
            assert_eq!((s.kl, s.ku), (w, w), "{ns} × {nz} × {d}");
            if ns >= 9 && w <= MAX_HALF_BAND && per <= MAX_BORDER {
                let found = BandStructure::detect(n, &r, &c, &[]).unwrap();
                assert_eq!((found.kl, found.ku, found.border.len()), (w, w, per), "{ns} × {nz} × {d}: detect");
            }
            let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
            let mut band: SparseLu = SparseLu::new();
            band.set_pattern_with_border(n, &r, &c, &border).unwrap();
            band.factorize(&v).unwrap();
            assert!(band.band_structure().is_some() && band.band_refusals == 0);
            let mut x = b.clone();
            band.solve_in_place(&mut x).unwrap();
            let mut general: SparseLu = SparseLu::new();
            general.set_pattern(n, &r, &c).unwrap();
            general.factorize(&v).unwrap();
            assert!(general.band_structure().is_none());
            let mut y = b.clone();
            general.solve_in_place(&mut y).unwrap();
            assert!(relative_difference(&x, &y) < AGREE, "{ns} × {nz} × {d}: against faer {}", relative_difference(&x, &y));
            if n <= 500 {
                let expected = dense_solve(dense_of(n, &r, &c, &v), b.clone());
                assert!(relative_difference(&x, &expected) < AGREE, "{ns} × {nz} × {d}: against dense");
            }
        }
        let (n, (r, c, _)) = closed_surface(5, 2, 2, &mut rng);
        assert_eq!(BandStructure::with_border(n, &r, &c, &[0, 1, 1]), None);
        assert_eq!(BandStructure::with_border(n, &r, &c, &[n]), None);
        let mut lu: SparseLu = SparseLu::new();
        assert!(lu.set_pattern_with_border(n, &r, &c, &[2, n + 3]).is_err());
        // an empty border: the natural order's band, as wide as the wrap-around (σ-node
        // 0's first unknown with the last of σ-node 4's second ζ-node: 4 × 6 + 2 × 2 − 1)
        let s = BandStructure::with_border(n, &r, &c, &[]).unwrap();
        assert_eq!((s.kl, s.ku), (27, 27));
    }

    /// A symmetric matrix on the closed surface's pattern: per element Eᵀ E of a random
    /// square E over its four nodes' unknowns (positive semidefinite, exactly symmetric:
    /// (i, j) and (j, i) sum the same products in the same order), plus `shift` on the
    /// diagonal — positive definite for a positive shift, indefinite for a negative one
    /// below the smallest eigenvalues.
    fn symmetric_surface(ns: usize, nz: usize, d: usize, shift: f64, rng: &mut Lcg) -> (usize, Triplets) {
        let per = d * (nz + 1);
        let n = ns * per;
        let mut t = (vec![], vec![], vec![]);
        for unknowns in surface_elements(ns, nz, d) {
            let q = unknowns.len();
            let e: Vec<f64> = (0..q * q).map(|_| rng.next()).collect();
            for (a, &r) in unknowns.iter().enumerate() {
                for (b, &c) in unknowns.iter().enumerate() {
                    push(&mut t, r, c, (0..q).map(|k| e[k * q + a] * e[k * q + b]).sum());
                }
            }
        }
        for g in 0..n {
            push(&mut t, g, g, shift);
        }
        (n, t)
    }

    /// The band Cholesky of a symmetric matrix cut at σ-node 0 ([`SparseLu::symmetric`]):
    /// a positive definite matrix is factorised by it and solved as the LU and a dense
    /// solve do, to round-off; an indefinite one (A not positive definite), one whose
    /// values are not symmetric, and one whose pattern has kl ≠ ku go to the LU (a
    /// refusal each) and are solved as well; without a border (m = 0) too; a positive
    /// definite A whose bordered whole is indefinite keeps the Cholesky (the Schur
    /// complement's LU pivots).
    #[test]
    fn the_band_cholesky_solves_symmetric_positive_definite_matrices_and_refuses_the_others() {
        let mut rng = Lcg(31);
        for (ns, nz, d) in [(12, 2, 4), (9, 4, 3), (3, 1, 2), (30, 2, 6)] {
            for (shift, definite) in [(0.5, true), (-3.0, false)] {
                let (n, (r, c, v)) = symmetric_surface(ns, nz, d, shift, &mut rng);
                let per = d * (nz + 1);
                for border in [(0..per).collect::<Vec<_>>(), vec![]] {
                    let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
                    let mut lu: SparseLu = SparseLu::new();
                    lu.set_pattern_with_border(n, &r, &c, &border).unwrap();
                    lu.factorize(&v).unwrap();
                    let mut expected = b.clone();
                    lu.solve_in_place(&mut expected).unwrap();
                    let mut cholesky: SparseLu = SparseLu::symmetric();
                    cholesky.set_pattern_with_border(n, &r, &c, &border).unwrap();
                    cholesky.factorize(&v).unwrap();
                    assert_eq!(cholesky.cholesky_counts(), if definite { (1, 0) } else { (0, 1) }, "{ns} × {nz} × {d}, shift {shift}, border {}", border.len());
                    let mut x = b.clone();
                    cholesky.solve_in_place(&mut x).unwrap();
                    let dlu = relative_difference(&x, &expected);
                    assert!(dlu < AGREE, "{ns} × {nz} × {d}, shift {shift}: against the LU {dlu}");
                    if n <= 500 {
                        let dense = dense_solve(dense_of(n, &r, &c, &v), b.clone());
                        assert!(relative_difference(&x, &dense) < AGREE, "{ns} × {nz} × {d}, shift {shift}: against dense");
                    }
                    if definite && !border.is_empty() {
                        // one off-diagonal entry of the band changed on one side only
                        let k = (0..r.len()).find(|&k| r[k] == per + 1 && c[k] == per + 2).unwrap();
                        let mut skew = v.clone();
                        skew[k] += 1e-3;
                        cholesky.factorize(&skew).unwrap();
                        assert_eq!(cholesky.cholesky_counts(), (1, 1));
                        let mut x = b.clone();
                        cholesky.solve_in_place(&mut x).unwrap();
                        // the plain LU of the same skewed values (any n)
                        lu.factorize(&skew).unwrap();
                        let mut expected = b.clone();
                        lu.solve_in_place(&mut expected).unwrap();
                        assert!(relative_difference(&x, &expected) < AGREE, "{ns} × {nz} × {d}: skew");
                        // symmetric to within round-off (one entry off by 1e-15 of itself):
                        // still the Cholesky's, and the LU's answer
                        let mut near = v.clone();
                        near[k] *= 1.0 + 1e-15;
                        cholesky.factorize(&near).unwrap();
                        assert_eq!(cholesky.cholesky_counts(), (2, 1), "{ns} × {nz} × {d}: symmetric to round-off refused");
                        let mut x = b.clone();
                        cholesky.solve_in_place(&mut x).unwrap();
                        lu.factorize(&near).unwrap();
                        let mut expected = b.clone();
                        lu.solve_in_place(&mut expected).unwrap();
                        assert!(relative_difference(&x, &expected) < AGREE, "{ns} × {nz} × {d}: near-symmetric");
                    }
                }
            }
        }
        // A positive definite, the whole matrix indefinite through its border (the
        // border's diagonal lowered by 50, so S = D − WᵀW is negative definite): the
        // Cholesky of A is kept and S goes to its dense LU — as a dense solve
        let (n, (r, c, mut v)) = symmetric_surface(12, 2, 4, 0.5, &mut rng);
        let per = 4 * 3;
        for k in 0..r.len() {
            if r[k] == c[k] && r[k] < per {
                v[k] -= 50.0;
            }
        }
        let border: Vec<usize> = (0..per).collect();
        let b: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let mut cholesky: SparseLu = SparseLu::symmetric();
        cholesky.set_pattern_with_border(n, &r, &c, &border).unwrap();
        cholesky.factorize(&v).unwrap();
        assert_eq!(cholesky.cholesky_counts(), (1, 0), "a positive definite A refused for its border");
        let mut x = b.clone();
        cholesky.solve_in_place(&mut x).unwrap();
        let dense = dense_solve(dense_of(n, &r, &c, &v), b.clone());
        assert!(relative_difference(&x, &dense) < AGREE, "indefinite whole: against dense {}", relative_difference(&x, &dense));
        // a band with kl ≠ ku: never symmetric
        let (r, c, v) = random_band(30, 2, 4, &mut rng);
        let s = BandStructure::with_border(30, &r, &c, &[]).unwrap();
        let mut band = BorderedBand::symmetric(s, &r, &c);
        band.factorize(&v, &[]).unwrap();
        assert_eq!((band.cholesky_factorisations, band.cholesky_refusals), (0, 1));
    }

    /// The time of one numeric factorisation of the shell's study-scene pattern
    /// (128 × 4 elements, 12 unknowns per node: 7 680 unknowns) by the band cut at
    /// σ-node 0 and by faer's general sparse LU (`cargo test --release -p numerics
    /// shell_shaped -- --ignored --nocapture`).
    #[test]
    #[ignore]
    fn shell_shaped_band_against_faer_timing() {
        let mut rng = Lcg(5);
        for (ns, nz) in [(32, 2), (64, 2), (128, 2), (128, 4), (256, 4)] {
            let (n, (r, c, v)) = closed_surface(ns, nz, 12, &mut rng);
            let border: Vec<usize> = (0..12 * (nz + 1)).collect();
            let time = |lu: &mut SparseLu| {
                (0..3)
                    .map(|_| {
                        let start = std::time::Instant::now();
                        lu.factorize(&v).unwrap();
                        start.elapsed().as_secs_f64()
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let mut band: SparseLu = SparseLu::new();
            band.set_pattern_with_border(n, &r, &c, &border).unwrap();
            let mut general: SparseLu = SparseLu::new();
            general.set_pattern(n, &r, &c).unwrap();
            let (tb, tg) = (time(&mut band), time(&mut general));
            println!("{ns} × {nz}: {n} unknowns, band {:?}: {tb:.4} s, faer {tg:.4} s", band.band_structure().map(|s| (s.kl, s.border.len())));
        }
        // a symmetric positive definite matrix of the pattern: the band LU against the
        // band Cholesky (`SparseLu::symmetric`), both cut at σ-node 0
        for (ns, nz) in [(64, 4), (128, 4), (256, 8)] {
            let (n, (r, c, v)) = symmetric_surface(ns, nz, 12, 1.0, &mut rng);
            let border: Vec<usize> = (0..12 * (nz + 1)).collect();
            let time = |lu: &mut SparseLu| {
                lu.set_pattern_with_border(n, &r, &c, &border).unwrap();
                (0..3)
                    .map(|_| {
                        let start = std::time::Instant::now();
                        lu.factorize(&v).unwrap();
                        start.elapsed().as_secs_f64()
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let (mut lu, mut cholesky): (SparseLu, SparseLu) = (SparseLu::new(), SparseLu::symmetric());
            let (tl, tc) = (time(&mut lu), time(&mut cholesky));
            println!("{ns} × {nz} symmetric: {n} unknowns, band LU {tl:.4} s, band Cholesky {tc:.4} s ({:?} by Cholesky, refused)", cholesky.cholesky_counts());
        }
    }

    /// A band matrix whose columns 5 and 6 are equal (rank n − 1), well scaled
    /// otherwise; and the same with column 6 perturbed by 1e-6 (regular, cond ≈ 1e7).
    fn nearly_singular(perturbation: f64) -> Triplets {
        let (n, kl, ku) = (12, 2, 2);
        let mut rng = Lcg(5);
        let mut a = vec![vec![0.0; n]; n];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate().take((i + ku + 1).min(n)).skip(i.saturating_sub(kl)) {
                *x = if i == j { 3.0 } else { rng.next() };
            }
            // rows 4…7 hold both columns inside the band
            row[5] = if (4..=7).contains(&i) { 1.0 + 0.1 * i as f64 } else { 0.0 };
            row[6] = row[5] + if i == 6 { perturbation } else { 0.0 };
        }
        let mut t = (vec![], vec![], vec![]);
        for (i, row) in a.iter().enumerate() {
            for (j, &x) in row.iter().enumerate() {
                if i.abs_diff(j) <= 2 {
                    push(&mut t, i, j, x);
                }
            }
        }
        t
    }

    #[test]
    fn singular_detection_is_independent_of_the_scale() {
        for scale in [1.0, 1e-150, 1e150] {
            // the band's own verdict: refused at every scale
            let (r, c, v) = nearly_singular(0.0);
            let structure = BandStructure::detect(12, &r, &c, &[]).unwrap();
            assert!(structure.border.is_empty());
            let scaled: Vec<f64> = v.iter().map(|x| x * scale).collect();
            let mut band = BorderedBand::new(structure, &r, &c);
            assert!(matches!(band.factorize(&scaled, &[]), Err(BandFailure::Band { column: 6, .. })), "scale {scale}: {:?}", band.factorize(&scaled, &[]));
            // SparseLu hands it to faer's LU, whose verdict stands
            let mut lu: SparseLu = SparseLu::banded();
            lu.set_pattern(12, &r, &c).unwrap();
            assert!(faer_verdict(&mut lu, 12, &r, &c, &scaled), "scale {scale}");
            // regular: not refused at any scale, and every column scaled differently
            let (r, c, v) = nearly_singular(1e-6);
            let column_scaled: Vec<f64> = v.iter().zip(&c).map(|(x, &j)| x * scale * 10f64.powi(j as i32 * 7 - 40)).collect();
            let mut lu: SparseLu = SparseLu::banded();
            lu.set_pattern(12, &r, &c).unwrap();
            lu.factorize(&column_scaled).unwrap();
            let x: Vec<f64> = (0..12).map(|i| 1.0 + i as f64).collect();
            let mut b = vec![0.0; 12];
            for k in 0..r.len() {
                b[r[k]] += column_scaled[k] * x[c[k]] / (scale * 10f64.powi(c[k] as i32 * 7 - 40));
            }
            lu.solve_in_place(&mut b).unwrap();
            for (i, bi) in b.iter().enumerate() {
                // y = D⁻¹ x with D the column scaling; cond ≈ 1e7: ≈ 1e-9 … 1e-8 relative
                let y = x[i] / (scale * 10f64.powi(i as i32 * 7 - 40));
                assert!((bi - y).abs() <= 1e-7 * y.abs(), "scale {scale}, {i}: {bi} vs {y}");
            }
        }
        // a zero border row: the Schur complement is singular, named with its determinant;
        // SparseLu hands it to faer's LU
        let mut rng = Lcg(8);
        let (n, (r, c, v)) = closed_chain(10, 2, 1, &mut rng);
        let zero_row: Vec<f64> = r.iter().zip(&v).map(|(&ri, &x)| if ri == n - 1 { 0.0 } else { x * 1e-200 }).collect();
        let mut band = BorderedBand::new(BandStructure::detect(n, &r, &c, &[]).unwrap(), &r, &c);
        assert!(matches!(band.factorize(&zero_row, &[]), Err(BandFailure::Schur { det }) if det == 0.0));
        let mut lu: SparseLu = SparseLu::banded();
        lu.set_pattern(n, &r, &c).unwrap();
        assert!(lu.band_structure().is_some());
        assert!(faer_verdict(&mut lu, n, &r, &c, &zero_row));
    }

    /// The fallback gives faer's verdict: `lu` (banded, refused by the band) factorises
    /// and solves exactly as faer's LU alone — both fail, or both give the same solution
    /// (for an exactly singular matrix faer's LU may see a round-off pivot and return a
    /// huge finite solution, as the solver without the banded LU did).
    fn faer_verdict(lu: &mut SparseLu, n: usize, r: &[usize], c: &[usize], values: &[f64]) -> bool {
        let mut faer: SparseLu = SparseLu::new();
        faer.set_pattern(n, r, c).unwrap();
        let solve = |lu: &mut SparseLu| -> Result<Vec<f64>, LinearError> {
            lu.factorize(values)?;
            let mut x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
            lu.solve_in_place(&mut x)?;
            Ok(x)
        };
        let (ours, theirs) = (solve(lu), solve(&mut faer));
        lu.band_structure().is_none() && ours == theirs
    }

    /// A tridiagonal (−1, 2, −1) matrix of order 10 with its last row scaled by 1e-20 is
    /// regular (cond ≈ 60 before the scaling); its last pivot, ≈ 1e-20, is ≤ τ × its
    /// column's largest entry 1, so the band refuses it without a border (review item,
    /// the case of [[1, 1], [1e-20, 2e-20]]): SparseLu hands it to faer's LU, which
    /// solves it to round-off (without the fallback `factorize` returned `Singular`).
    #[test]
    fn a_badly_row_scaled_regular_matrix_falls_back_to_the_general_lu() {
        let n: usize = 10;
        let mut t = (vec![], vec![], vec![]);
        for i in 0..n {
            let row_scale = if i == n - 1 { 1e-20 } else { 1.0 };
            for j in i.saturating_sub(1)..=(i + 1).min(n - 1) {
                push(&mut t, i, j, row_scale * if i == j { 2.0 } else { -1.0 });
            }
        }
        let (r, c, v) = t;
        let mut lu: SparseLu = SparseLu::banded();
        lu.set_pattern(n, &r, &c).unwrap();
        assert!(lu.band_structure().is_some_and(|s| s.border.is_empty()));
        lu.factorize(&v).unwrap();
        assert!(lu.band_structure().is_none());
        let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let mut b = vec![0.0; n];
        for k in 0..r.len() {
            b[r[k]] += v[k] * x[c[k]];
        }
        lu.solve_in_place(&mut b).unwrap();
        // cond ≈ 60 for the row-equilibrated matrix: ≈ 1e-14 relative
        assert!(relative_difference(&b, &x) < 1e-12, "{b:?}");
    }

    /// The 6-cycle C₆ (adjacency, zero diagonal) is regular; with node 0 in the border
    /// its band block is the path P₅, singular: the banded LU hands the pattern to faer.
    /// The 6-cycle C₆ + δI factorised by the banded LU (node 0 lands in the border):
    /// the LU and the relative difference of its solution to the dense solve.
    fn cycle6(delta: f64) -> (SparseLu, f64) {
        let n = 6;
        let mut t = (vec![], vec![], vec![]);
        for i in 0..n {
            push(&mut t, i, (i + 1) % n, 1.0);
            push(&mut t, (i + 1) % n, i, 1.0);
            push(&mut t, i, i, delta);
        }
        let (r, c, v) = t;
        let mut lu: SparseLu = SparseLu::banded();
        lu.set_pattern(n, &r, &c).unwrap();
        assert_eq!(lu.band_structure().map(|s| s.border.clone()), Some(vec![0]));
        lu.factorize(&v).unwrap();
        let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let mut x = b.clone();
        lu.solve_in_place(&mut x).unwrap();
        let difference = relative_difference(&x, &dense_solve(dense_of(n, &r, &c, &v), b));
        (lu, difference)
    }

    #[test]
    fn a_singular_band_block_falls_back_to_the_general_lu() {
        let (lu, difference) = cycle6(0.0);
        assert!(lu.band_structure().is_none());
        assert!(difference < 1e-14);
        assert_eq!((lu.symbolic_factorisations, lu.numeric_factorisations), (2, 1));
    }

    /// C₆ + δI with δ = 1e-12 is well conditioned (cond ≈ 2), but its band block P₅ + δI
    /// (node 0 in the border) has cond ≈ 1e12: block elimination through A⁻¹ would lose
    /// ~1e-4 of the solution. The block is refused ([`BORDER_PIVOT_RATIO`]) and the
    /// general LU solves to round-off (review item; without the check the difference
    /// to the dense solve is ~1e-4).
    #[test]
    fn an_ill_conditioned_band_block_under_a_border_falls_back_to_the_general_lu() {
        let (lu, difference) = cycle6(1e-12);
        assert!(lu.band_structure().is_none(), "the ill-conditioned band block is handed to the general LU");
        assert!(difference < 1e-12, "{difference}");
    }

    /// The merged entries, the pruned covers and the incremental degrees choose the split
    /// the plain greedy of every entry chose (`reference`), on the shapes the solvers
    /// give — closed chains with global unknowns, points numbered after the mesh (with
    /// and without a forced border), every entry listed several times — and on random
    /// sparse entries added to them (which change the band, the border or make it none).
    #[test]
    fn the_merged_detection_chooses_the_plain_greedys_split() {
        let mut rng = Lcg(77);
        // (n, rows, cols, forced)
        type Case = (usize, Vec<usize>, Vec<usize>, Vec<usize>);
        let mut cases: Vec<Case> = Vec::new();
        for (nodes, dofs, globals) in [(30, 4, 2), (12, 2, 0), (50, 6, 1), (3, 4, 2), (64, 4, 3)] {
            let (n, (r, c, _)) = closed_chain(nodes, dofs, globals, &mut rng);
            cases.push((n, r, c, vec![]));
        }
        for nodes in [8, 40, 97] {
            let (n, forced, (r, c, _)) = chain_with_points(nodes, &mut rng);
            cases.push((n, r.clone(), c.clone(), forced.clone()));
            cases.push((n, r.clone(), c.clone(), vec![]));
            // each entry listed three times, in another order
            let (mut r3, mut c3) = (r.clone(), c.clone());
            r3.extend(r.iter().rev());
            c3.extend(c.iter().rev());
            r3.extend(&r);
            c3.extend(&c);
            cases.push((n, r3, c3, forced));
        }
        for (n, r, c, forced) in cases.clone() {
            for extra in [1, 3, 10, 40, 400] {
                let (mut r2, mut c2) = (r.clone(), c.clone());
                for _ in 0..extra {
                    let i = ((rng.next() + 1.0) * 0.5 * n as f64) as usize % n;
                    let j = ((rng.next() + 1.0) * 0.5 * n as f64) as usize % n;
                    r2.extend([i, j]);
                    c2.extend([j, i]);
                }
                cases.push((n, r2, c2, forced.clone()));
            }
        }
        // a random sparse pattern: no band
        let (mut rr, mut cc) = (vec![], vec![]);
        for i in 0..300 {
            for _ in 0..6 {
                rr.push(i);
                cc.push(((rng.next() + 1.0) * 150.0) as usize % 300);
            }
        }
        cases.push((300, rr, cc, vec![]));
        let (mut bands, mut borders) = (0, 0);
        for (n, r, c, forced) in &cases {
            let got = BandStructure::detect(*n, r, c, forced);
            assert_eq!(got, reference::detect(*n, r, c, forced), "n = {n}, {} entries, forced {forced:?}", r.len());
            assert_eq!(neighbour_order(*n, r, c, forced), reference::reference_order(*n, r, c, forced));
            bands += usize::from(got.is_some());
            borders += usize::from(got.is_some_and(|s| s.border.len() > forced.len()));
        }
        // the cases exercise found bands with borders and refused patterns alike
        assert!(bands > 20 && borders > 10 && bands < cases.len(), "{bands} bands, {borders} with a border, of {}", cases.len());
    }

    /// The detection before its entries were merged and its covers pruned (kept to
    /// check that both give the same split).
    mod reference {
        use super::super::{band_flops, BandStructure, MAX_BORDER, MAX_HALF_BAND};

        pub fn detect(n: usize, rows: &[usize], cols: &[usize], forced: &[usize]) -> Option<BandStructure> {
            if forced.iter().any(|&f| f >= n) {
                return None;
            }
            let natural: Vec<usize> = (0..n).collect();
            let moved = reference_order(n, rows, cols, forced);
            let first = detect_in_order(&natural, rows, cols, forced);
            let second = if moved == natural { None } else { detect_in_order(&moved, rows, cols, forced) };
            match (first, second) {
                (Some(a), Some(b)) => Some(if b.flops() < a.flops() { b } else { a }),
                (a, b) => a.or(b),
            }
        }


        /// [`Self::detect`] with the unknowns in the order `order` (a permutation of 0…n−1).
        fn detect_in_order(order: &[usize], rows: &[usize], cols: &[usize], forced: &[usize]) -> Option<BandStructure> {
            let n = order.len();
            let mut position = vec![0; n];
            for (p, &g) in order.iter().enumerate() {
                position[g] = p;
            }
            let mut is_forced = vec![false; n];
            for &f in forced {
                is_forced[f] = true;
            }
            // edges in positions of `order`, the farthest first: the entries outside a band
            // of half-width w are a prefix
            let mut edges: Vec<(usize, usize)> = rows.iter().zip(cols).filter(|&(&r, &c)| r != c && !is_forced[r] && !is_forced[c]).map(|(&r, &c)| (position[r], position[c])).collect();
            edges.sort_unstable_by_key(|&(r, c)| std::cmp::Reverse(r.abs_diff(c)));
            let mut degree = vec![0usize; n];
            for &(r, c) in &edges {
                degree[r] += 1;
                degree[c] += 1;
            }
            // a cover of k entries needs at least k / (the largest degree) unknowns
            let top_degree = degree.iter().copied().max().unwrap_or(0);
            degree.fill(0);
            let room = MAX_BORDER.saturating_sub(forced.len());
            let mut cover_outside = |w: usize| -> Option<Vec<usize>> {
                let count = edges.partition_point(|&(r, c)| r.abs_diff(c) > w);
                if count > room * top_degree {
                    return None;
                }
                let mut far = edges[..count].to_vec();
                let mut cover = Vec::new();
                while !far.is_empty() {
                    for &(r, c) in &far {
                        degree[r] += 1;
                        degree[c] += 1;
                    }
                    let most = far.iter().flat_map(|&(r, c)| [r, c]).max_by_key(|&v| (degree[v], std::cmp::Reverse(v))).unwrap_or(0);
                    let max_degree = degree[most];
                    for &(r, c) in &far {
                        degree[r] = 0;
                        degree[c] = 0;
                    }
                    if cover.len() >= room || far.len() > (room - cover.len()) * max_degree {
                        return None;
                    }
                    cover.push(most);
                    far.retain(|&(r, c)| r != most && c != most);
                }
                Some(cover)
            };
            let mut distances: Vec<usize> = edges.iter().map(|&(r, c)| r.abs_diff(c)).filter(|&d| d <= MAX_HALF_BAND).collect();
            distances.push(0);
            distances.sort_unstable();
            distances.dedup();
            // the widest admissible band first: if its border overflows, every narrower one's does
            let widest = *distances.last().unwrap_or(&0);
            let mut best: Option<(f64, Vec<usize>)> = cover_outside(widest).map(|cover| (band_flops(n, widest, forced.len() + cover.len()), cover));
            best.as_ref()?;
            for &w in &distances {
                let wf = w as f64;
                if best.as_ref().is_some_and(|(cost, _)| n as f64 * wf * (3.0 * wf + 1.0) >= *cost) {
                    break;
                }
                let Some(cover) = cover_outside(w) else { continue };
                let cost = band_flops(n, w, forced.len() + cover.len());
                if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                    best = Some((cost, cover));
                }
            }
            let (_, cover) = best?;
            let mut border: Vec<usize> = forced.to_vec();
            border.extend(cover.iter().map(|&p| order[p]));
            let mut in_border = vec![false; n];
            for &b in &border {
                in_border[b] = true;
            }
            let mut inner_of = vec![usize::MAX; n];
            let mut inner = Vec::with_capacity(n - border.len());
            for &g in order {
                if !in_border[g] {
                    inner_of[g] = inner.len();
                    inner.push(g);
                }
            }
            let (mut kl, mut ku) = (0, 0);
            for (&r, &c) in rows.iter().zip(cols) {
                if !in_border[r] && !in_border[c] {
                    let (i, j) = (inner_of[r], inner_of[c]);
                    kl = kl.max(i.saturating_sub(j));
                    ku = ku.max(j.saturating_sub(i));
                }
            }
            (kl <= MAX_HALF_BAND && ku <= MAX_HALF_BAND).then_some(BandStructure { n, border, inner, kl, ku })
        }

        pub fn reference_order(n: usize, rows: &[usize], cols: &[usize], forced: &[usize]) -> Vec<usize> {
            let mut is_forced = vec![false; n];
            for &f in forced {
                is_forced[f] = true;
            }
            let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
            for (&r, &c) in rows.iter().zip(cols) {
                if r != c && !is_forced[r] && !is_forced[c] {
                    neighbours[r].push(c);
                }
            }
            let lower_median = |v: &mut Vec<usize>| {
                v.sort_unstable();
                v[(v.len() - 1) / 2]
            };
            let mut median_distance: Vec<usize> = Vec::with_capacity(n);
            for (g, list) in neighbours.iter_mut().enumerate() {
                list.sort_unstable();
                list.dedup();
                if !list.is_empty() {
                    median_distance.push(lower_median(&mut list.iter().map(|&j| j.abs_diff(g)).collect()));
                }
            }
            if median_distance.is_empty() {
                return (0..n).collect();
            }
            let far = 2 * lower_median(&mut median_distance).max(1);
            let key: Vec<usize> = neighbours
                .iter()
                .enumerate()
                .map(|(g, list)| {
                    let distant = list.iter().filter(|&&j| j.abs_diff(g) > far).count();
                    if 2 * distant > list.len() {
                        list[(list.len() - 1) / 2]
                    } else {
                        g
                    }
                })
                .collect();
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by_key(|&g| (key[g], g));
            order
        }
    }
}
