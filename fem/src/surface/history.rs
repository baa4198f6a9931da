//! History variables of a surface kernel: per term that keeps history
//! ([`SurfaceTerm::history`](super::assembly::SurfaceTerm::history) values per integration point), one state vector per
//! integration point of every element — the 2-D counterpart of
//! [`crate::formulation::terms::TermHistory`] with states as plain numbers, so that
//! they can be interpolated.
//!
//! A term's points form rows at fixed ζ (n_ζ × points of its ζ-rule) of columns around
//! the loop (n_σ × points of its σ-rule, in σ order). During a step the densities read
//! the states ([`SurfaceHistory::state`]); after it converged the kernel's
//! [`SurfaceKernel::advance`] gives the new states from the converged point values
//! ([`SurfaceHistory::advance`]).
//!
//! **Advection** (the belt carries the history along σ, spec §4.6 eq. 41): before a
//! step of length Δt the committed state at σ is replaced by the state at the foot
//! σ − cΔt (semi-Lagrangian; c = the kernel's belt speed at mid-step), interpolated along
//! its row by the cubic Lagrange polynomial through the four distinct points around the
//! foot (two on each side, periodic). Interpolation error O(h⁴ ∂⁴u) per step, h the
//! point spacing; over a loop of L/(cΔt) steps O(h⁴/(cΔt)) — third order at a fixed
//! Courant number cΔt/h. A shift by a whole number of points on a uniform arrangement is
//! exact; points at the same σ (element edges of a Simpson or trapezoidal rule) count once,
//! with their mean, in the interpolation.
//!
//! **Bounded components** ([`SurfaceKernel::bounded_history`]): a component that the
//! kernel carries from step to step by its own recursion (h_{n+1} = h̃_n + increment, the
//! interlayer's u) is clipped to the range of its values at the two points bracketing
//! the foot (the quasi-monotone semi-Lagrangian scheme of Bermejo & Staniforth 1992).
//! On a non-uniform arrangement the cubic Lagrange weights are not bounded by 1: with
//! the next spacing downstream short (x_{k+2} − x_{k+1} ≪ x_{k+1} − x_k) the point's own
//! weight exceeds 1 and a state that is re-interpolated at the same place every step
//! grows geometrically (docs/fem-shell.md §9.3: 1.6 per step at a contact exit next to
//! an element of 1/6 the length). Clipped, max|h̃| ≤ max|h| over the row for any
//! spacing and shift; where the field is smooth and monotone across the bracket the
//! clip is inactive and the cubic's accuracy is kept; across a jump (u released to 0 at
//! a contact exit) it removes the overshoot.
//!
//! **Released points** ([`SurfaceKernel::history_support`]): a bounded component that
//! the kernel sets to 0 outside a zone (u out of contact) jumps there, and the clip alone
//! does not keep the jump out of the cubic: next to a contact exit followed by a short
//! element the cubic weight of the last point in the zone on its own value is ≈ 1
//! (0.98 on the 32-element rod mesh at ωΔt = π/8) — inside the bracket, so not clipped —
//! and that point keeps its value for ~50 steps instead of passing it downstream within
//! one step: u piles up at the exit point (docs/fem-shell.md §9.3, "The exit point").
//! Where the four stencil points are not all marked as supporting the field, the bounded
//! components are interpolated linearly between the two bracketing points (second
//! order, bounded; the cubic elsewhere).
//!
//! **Entering the zone**: with both a support and a cut ([`CutHistory::entry`]), a
//! bracket whose upstream point is outside the zone and whose downstream point is inside
//! holds the zone's entry, at the inside point's committed distance from it. The bounded
//! components are then interpolated from the entry (the released value there) to the
//! inside point, and a foot before the entry takes the released value. From the point
//! before the entry instead, a value that accumulates from the entry (the interlayer's
//! u: the slip since the material touched the drum) counts the time the material would
//! have needed from that point: the first point inside holds (x₁ − x₀)/(x₁ − x_e) of its
//! value in the steady state, and the recursion carries the excess over the zone. That
//! bias appears only once the step is short enough for the first point's foot to lie
//! past the entry (|c|Δt < x₁ − x_e; before, the kernel's own entering formula serves the
//! point), so it switched on at some step of a refinement at fixed mesh
//! (docs/fem-shell.md §7 (h)).
//!
//! **Cut cells** ([`SurfaceKernel::cut_history`], [`CutHistory`]): an integrand that a
//! committed zone cuts inside an element (V_⊥ inside the interlayer's contact) counted
//! by whole points moves the zone's edges by whole cells, a first-order error in h
//! (docs/fem-shell.md §7 (b)). After each advance the core places each edge of the zone
//! between an inside and an outside neighbour of a row at the root of the kernel's
//! indicator ([`SurfaceKernel::zone`]: the gap) of the finite element solution along the
//! row; each point inside gets as its share the zone's part of its cell
//! ([`crate::quadrature::Rule::cell`]) plus that part of an outside neighbour's cell
//! (whose own value is not the zone's integrand), over its cell's length. The shares add
//! up to the zone's length, which changes continuously as an edge moves; a single share
//! still jumps where an edge crosses a point (the length changes hands between
//! neighbours), which moves the integral by a cell times the two points' difference of
//! the integrand — O(h²), where whole points moved it by O(h).

use super::assembly::{CutHistory, Evaluation, SurfaceAssembler, SurfaceKernel, SurfacePoint};
use crate::element::SurfaceElement;
use super::SurfaceError;

/// The states of one history term.
#[derive(Debug, Clone, PartialEq)]
pub struct TermStates {
    /// Values per point.
    width: usize,
    /// Points of the σ- and ζ-rule per element.
    per_sigma: usize,
    per_zeta: usize,
    /// Columns (n_σ · per_sigma) and rows (n_ζ · per_zeta).
    columns: usize,
    rows: usize,
    /// σ of each column, mod L.
    sigma: Vec<f64>,
    /// Distinct σ (increasing) and the columns at each.
    unique: Vec<f64>,
    groups: Vec<Vec<usize>>,
    /// (row · columns + column) · width + k.
    values: Vec<f64>,
    /// Components clipped to the bracketing values in the advection.
    bounded: std::ops::Range<usize>,
    /// The component marking where the bounded ones are a field (≥ ½).
    support: Option<usize>,
    /// Components each point keeps (not advected).
    fixed: std::ops::Range<usize>,
    /// The components of [`SurfaceKernel::cut_history`].
    cut: Option<CutHistory>,
    /// Each column's cell ([`crate::quadrature::Rule::cell`]) as offsets from its σ, m.
    cells: Vec<[f64; 2]>,
}

impl TermStates {
    /// Values per point.
    pub fn width(&self) -> usize {
        self.width
    }

    /// (rows, columns) of points.
    pub fn shape(&self) -> (usize, usize) {
        (self.rows, self.columns)
    }

    /// Points per element of the σ- and of the ζ-rule: element (i, j)'s point (a, b) is
    /// at row j · per_ζ + b, column i · per_σ + a (points in the rule's order, ξ
    /// increasing).
    pub fn points_per_element(&self) -> (usize, usize) {
        (self.per_sigma, self.per_zeta)
    }

    /// σ of each column (mod L), m.
    pub fn column_sigma(&self) -> &[f64] {
        &self.sigma
    }

    /// The state at (row, column).
    pub fn get(&self, row: usize, column: usize) -> &[f64] {
        let k = (row * self.columns + column) * self.width;
        &self.values[k..k + self.width]
    }

    /// Row and column of point (a, b) of element (i, j).
    fn place(&self, i: usize, j: usize, a: usize, b: usize) -> (usize, usize) {
        (j * self.per_zeta + b, i * self.per_sigma + a)
    }

    /// The length of [from, to] (`from` ≤ `to` ≤ `from` + L) in the zone whose edges
    /// lie between the distinct points (periodic): `inside` per distinct point, `edges[k]`
    /// the edge between points k and k + 1 where one of them is inside ([`Self::cut`]).
    fn zone_length(&self, inside: &[bool], edges: &[f64], from: f64, to: f64, length: f64) -> f64 {
        let n = self.unique.len() as isize;
        let index = |k: isize| k.rem_euclid(n) as usize;
        let x = |k: isize| self.unique[index(k)] + k.div_euclid(n) as f64 * length;
        // the piece holding `from`: x(k) ≤ from (k = −1 is the last point one period back)
        let wraps = from.div_euclid(length);
        let mut k = self.unique.partition_point(|&u| u <= from - wraps * length) as isize - 1 + wraps as isize * n;
        let mut total = 0.0;
        while x(k) < to {
            let (x0, x1) = (x(k), x(k + 1));
            let edge = edges[index(k)] + (x0 - self.unique[index(k)]);
            let zone = match (inside[index(k)], inside[index(k + 1)]) {
                (true, true) => Some((x0, x1)),
                (false, false) => None,
                (true, false) => Some((x0, edge)),
                (false, true) => Some((edge, x1)),
            };
            if let Some((a, b)) = zone {
                total += (b.min(to) - a.max(from)).max(0.0);
            }
            k += 1;
        }
        total
    }

    /// Sets every point's share ([`SurfaceKernel::cut_history`], [`CutHistory`]) from its
    /// row: the edges between inside and outside neighbours (the roots of the indicator
    /// `at(e, σ, row)` along the row, in the element e of one of the two points that
    /// holds σ), then the zone's part of the cell of each point inside, and of each
    /// outside neighbour's cell, given to the inside point next to it; with
    /// [`CutHistory::entry`], each point's distance from the zone's upstream edge, upstream
    /// meaning towards −σ for a `downstream` transport along +σ and towards +σ otherwise.
    fn cut(&mut self, cut: &CutHistory, length: f64, downstream: bool, elements: &dyn Fn(usize, usize) -> (usize, [f64; 2]), at: &dyn Fn(usize, f64, usize) -> f64, record: &dyn Fn(usize, f64, usize, &mut [f64])) {
        let n = self.unique.len();
        let mut distinct = vec![0; self.columns];
        for (k, group) in self.groups.iter().enumerate() {
            for &c in group {
                distinct[c] = k;
            }
        }
        // the column of group k whose cell reaches furthest downstream (`last`) or upstream
        let edge = |k: usize, last: bool| -> usize {
            let group = self.groups[k].iter().copied();
            if last {
                group.max_by(|&a, &b| self.cells[a][1].total_cmp(&self.cells[b][1]))
            } else {
                group.min_by(|&a, &b| self.cells[a][0].total_cmp(&self.cells[b][0]))
            }
            .expect("a group has a column")
        };
        for row in 0..self.rows {
            let values: Vec<f64> = self.groups.iter().map(|g| g.iter().map(|&col| self.get(row, col)[cut.indicator]).sum::<f64>() / g.len() as f64).collect();
            let inside: Vec<bool> = values.iter().map(|&v| v > 0.0).collect();
            // the edge between k and k + 1 (a σ in [x_k, x_{k+1}], x_{k+1} unwrapped)
            // and the element holding it
            let (edges, holders): (Vec<f64>, Vec<usize>) = (0..n)
                .map(|k| {
                    let next = (k + 1) % n;
                    let (x0, x1) = (self.unique[k], self.unique[next] + if next == 0 { length } else { 0.0 });
                    if inside[k] == inside[next] {
                        return (x0, 0);
                    }
                    // the elements of the two points next to each other, with their σ-ranges
                    let (first, [_, end]) = elements(edge(k, true), row);
                    let (second, _) = elements(edge(next, false), row);
                    let g = |sigma: f64| -> Result<f64, std::convert::Infallible> { Ok(if sigma <= end { at(first, sigma, row) } else { at(second, sigma, row) }) };
                    let linear = x0 + (x1 - x0) * values[k] / (values[k] - values[next]);
                    let root = numerics::roots::brent(g, x0, x1, 1e-12 * (x1 - x0)).unwrap_or(linear).clamp(x0, x1);
                    (root, if root <= end { first } else { second })
                })
                .unzip();
            let mut counted = vec![0.0; self.columns];
            for column in 0..self.columns {
                let ([lo, hi], sigma, k) = (self.cells[column], self.sigma[column], distinct[column]);
                if inside[k] {
                    counted[column] += self.zone_length(&inside, &edges, sigma + lo, sigma + hi, length);
                } else {
                    counted[edge((k + n - 1) % n, true)] += self.zone_length(&inside, &edges, sigma + lo, sigma, length);
                    counted[edge((k + 1) % n, false)] += self.zone_length(&inside, &edges, sigma, sigma + hi, length);
                }
            }
            for column in 0..self.columns {
                let [lo, hi] = self.cells[column];
                let value = if hi > lo { counted[column] / (hi - lo) } else { f64::from(u8::from(inside[distinct[column]])) };
                self.values[(row * self.columns + column) * self.width + cut.share] = value;
            }
            if cut.entry.is_some() || !cut.record.is_empty() {
                let travelled = Self::travelled(&self.unique, &inside, &edges, length, downstream);
                // the kernel's record at each upstream edge, once per edge (zero outside)
                let width = cut.record.len();
                let mut records = vec![0.0; n * width];
                let mut recorded = vec![false; n];
                for column in 0..self.columns {
                    let (distance, upstream) = travelled[distinct[column]];
                    let base = (row * self.columns + column) * self.width;
                    if let Some(entry) = cut.entry {
                        self.values[base + entry] = distance;
                    }
                    if width == 0 {
                        continue;
                    }
                    let target = &mut self.values[base + cut.record.start..base + cut.record.end];
                    match upstream {
                        Some(j) => {
                            let slot = &mut records[j * width..(j + 1) * width];
                            if !recorded[j] {
                                record(holders[j], edges[j].rem_euclid(length), row, slot);
                                recorded[j] = true;
                            }
                            target.copy_from_slice(slot);
                        }
                        None => target.fill(0.0),
                    }
                }
            }
        }
    }

    /// Each distinct point's distance from the zone's upstream edge along the row
    /// (periodic, `x` the points' σ, `edges[k]` the edge between points k and k + 1 where
    /// one of them is inside), and the index k of that edge: 0 and None outside, `length`
    /// and None everywhere if no point is outside. Upstream is towards −σ if `downstream`
    /// (transport along +σ), else towards +σ.
    fn travelled(x: &[f64], inside: &[bool], edges: &[f64], length: f64, downstream: bool) -> Vec<(f64, Option<usize>)> {
        let n = x.len();
        let Some(outside) = inside.iter().position(|&i| !i) else {
            return vec![(length, None); n];
        };
        let mut out = vec![(0.0, None); n];
        // the distance travelled inside so far and the edge, None outside
        let mut travelled: Option<(f64, usize)> = None;
        // walk once around the loop with the transport, from a point outside
        let walk = |step: usize| if downstream { (outside + step) % n } else { (outside + n - step % n) % n };
        for step in 1..=n {
            let (k, previous) = (walk(step), walk(step - 1));
            // the spacing from `previous` to k along the walk (unwrapped)
            let gap = if downstream { x[k] - x[previous] } else { x[previous] - x[k] };
            let gap = if gap < 0.0 { gap + length } else { gap };
            travelled = match (inside[k], travelled) {
                (false, _) => None,
                (true, Some((t, edge))) => Some((t + gap, edge)),
                // the first point inside: from the edge between the two, `edges` being
                // indexed by the lower point of a pair and lying in its interval
                (true, None) => Some(if downstream { ((gap - (edges[previous] - x[previous])).max(0.0), previous) } else { ((edges[k] - x[k]).max(0.0), k) }),
            };
            out[k] = travelled.map_or((0.0, None), |(t, edge)| (t, Some(edge)));
        }
        out
    }

    /// The states advected by `shift` = cΔt along σ (module documentation).
    fn advected(&self, shift: f64, length: f64) -> TermStates {
        let mut out = self.clone();
        if shift == 0.0 {
            return out;
        }
        let n = self.unique.len();
        // the mean state at distinct point k (periodic index) of `row`
        let mean = |row: usize, k: usize, c: usize| -> f64 {
            let g = &self.groups[k % n];
            g.iter().map(|&col| self.get(row, col)[c]).sum::<f64>() / g.len() as f64
        };
        // abscissa of periodic index k (k may run past n by the stencil)
        let x = |k: isize| -> f64 {
            let wraps = k.div_euclid(n as isize);
            self.unique[k.rem_euclid(n as isize) as usize] + wraps as f64 * length
        };
        for column in 0..self.columns {
            let mut foot = (self.sigma[column] - shift).rem_euclid(length);
            let k = match self.unique.partition_point(|&u| u <= foot).checked_sub(1) {
                Some(k) => k as isize,
                None => {
                    foot += length;
                    n as isize - 1
                }
            };
            let stencil = [k - 1, k, k + 1, k + 2];
            let xs = stencil.map(x);
            let weights: [f64; 4] = std::array::from_fn(|r| (0..4).filter(|&s| s != r).map(|s| (foot - xs[s]) / (xs[r] - xs[s])).product());
            let ks = stencil.map(|k| k.rem_euclid(n as isize) as usize);
            // the bracket's linear weight of its downstream point
            let linear = (foot - xs[1]) / (xs[2] - xs[1]);
            let entry = self.cut.as_ref().and_then(|cut| cut.entry);
            for row in 0..self.rows {
                let supported = self.support.is_none_or(|s| ks.iter().all(|&k| mean(row, k, s) >= 0.5));
                // the zone's upstream edge inside the bracket: the weight from the edge
                // (module documentation, "Entering the zone")
                let weight = match (self.support, entry) {
                    (Some(s), Some(d)) if !supported => {
                        let inside = [mean(row, ks[1], s) >= 0.5, mean(row, ks[2], s) >= 0.5];
                        if shift > 0.0 && inside == [false, true] {
                            let edge = xs[2] - mean(row, ks[2], d);
                            if edge > xs[1] { ((foot - edge) / (xs[2] - edge)).clamp(0.0, 1.0) } else { linear }
                        } else if shift < 0.0 && inside == [true, false] {
                            let edge = xs[1] + mean(row, ks[1], d);
                            if edge < xs[2] { ((foot - xs[1]) / (edge - xs[1])).clamp(0.0, 1.0) } else { linear }
                        } else {
                            linear
                        }
                    }
                    _ => linear,
                };
                for c in 0..self.width {
                    let mut v: f64 = (0..4).map(|r| weights[r] * mean(row, ks[r], c)).sum();
                    if self.bounded.contains(&c) {
                        let (a, b) = (mean(row, ks[1], c), mean(row, ks[2], c));
                        v = if supported { v.clamp(a.min(b), a.max(b)) } else { a + (b - a) * weight };
                    }
                    if self.fixed.contains(&c) {
                        v = self.get(row, column)[c];
                    }
                    out.values[(row * self.columns + column) * self.width + c] = v;
                }
            }
        }
        out
    }
}

/// The history states of every term of a kernel (None for a term without history).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceHistory {
    terms: Vec<Option<TermStates>>,
    length: f64,
}

impl SurfaceHistory {
    /// The initial states ([`SurfaceKernel::initial`]) at time `time`.
    ///
    /// # Errors
    /// [`SurfaceError::TooFewHistoryPoints`]: fewer than four distinct σ points per row.
    pub fn new<K: SurfaceKernel<P>, const P: usize>(asm: &SurfaceAssembler<K, P>, time: f64) -> Result<SurfaceHistory, SurfaceError> {
        let mesh = asm.mesh();
        let length = mesh.length();
        let mut terms = Vec::new();
        for (t, term) in asm.terms().iter().enumerate() {
            if term.history == 0 {
                terms.push(None);
                continue;
            }
            let [rs, rz] = term.rule;
            let (per_sigma, per_zeta) = (rs.points().len(), rz.points().len());
            let (columns, rows) = (mesh.sigma_elements() * per_sigma, mesh.zeta_elements() * per_zeta);
            let mut states = TermStates { width: term.history, per_sigma, per_zeta, columns, rows, sigma: vec![0.0; columns], unique: Vec::new(), groups: Vec::new(), values: vec![0.0; rows * columns * term.history], bounded: asm.kernel().bounded_history(t), support: asm.kernel().history_support(t), fixed: asm.kernel().fixed_history(t), cut: asm.kernel().cut_history(t), cells: vec![[0.0; 2]; columns] };
            for e in 0..mesh.len() {
                let (i, j) = mesh.element_position(e);
                for point in asm.points(e, t, time, 0.0) {
                    let (row, column) = states.place(i, j, point.a, point.b);
                    states.sigma[column] = point.at.sigma.rem_euclid(length);
                    states.cells[column] = asm.cell(e, t, &point).map(|c| c - point.at.sigma);
                    let k = (row * columns + column) * term.history;
                    asm.kernel().initial(t, &point.at, &mut states.values[k..k + term.history]);
                }
            }
            let mut order: Vec<usize> = (0..columns).collect();
            order.sort_by(|&a, &b| states.sigma[a].total_cmp(&states.sigma[b]));
            for c in order {
                let s = states.sigma[c];
                match states.unique.last() {
                    Some(&u) if (s - u).abs() <= 1e-12 * length => states.groups.last_mut().expect("a group per distinct σ").push(c),
                    _ => {
                        states.unique.push(s);
                        states.groups.push(vec![c]);
                    }
                }
            }
            // σ = L wrapped to 0 and the point at 0 are one
            if states.unique.len() > 1 && (states.unique[states.unique.len() - 1] - length).abs() <= 1e-12 * length {
                let last = states.groups.pop().expect("non-empty");
                states.unique.pop();
                states.groups[0].extend(last);
            }
            if states.unique.len() < 4 {
                return Err(SurfaceError::TooFewHistoryPoints { term: t, points: states.unique.len() });
            }
            terms.push(Some(states));
        }
        Ok(SurfaceHistory { terms, length })
    }

    /// The states of term t (None if it keeps no history).
    pub fn term(&self, t: usize) -> Option<&TermStates> {
        self.terms.get(t).and_then(Option::as_ref)
    }

    /// True if no term keeps history.
    pub fn is_empty(&self) -> bool {
        self.terms.iter().all(Option::is_none)
    }

    /// The state of term t at point (a, b) of its rule on element e.
    ///
    /// # Panics
    /// If term t keeps no history (a kernel/assembler mismatch).
    pub fn state(&self, t: usize, e: usize, a: usize, b: usize) -> &[f64] {
        let states = self.terms[t].as_ref().expect("a term with history has states");
        let n_zeta = states.rows / states.per_zeta;
        let (row, column) = states.place(e / n_zeta, e % n_zeta, a, b);
        states.get(row, column)
    }

    /// Every state carried by `shift` = cΔt along σ (module documentation).
    pub fn advected(&self, shift: f64) -> SurfaceHistory {
        SurfaceHistory { terms: self.terms.iter().map(|t| t.as_ref().map(|s| s.advected(shift, self.length))).collect(), length: self.length }
    }

    /// The states after a converged step: [`SurfaceKernel::advance`] at every point from
    /// the converged unknowns `z` and these (advected) states.
    pub fn advance<K: SurfaceKernel<P>, const P: usize>(&self, asm: &SurfaceAssembler<K, P>, z: &[f64], ev: &Evaluation) -> SurfaceHistory {
        let mut next = self.clone();
        let mesh = asm.mesh();
        for (t, slot) in next.terms.iter_mut().enumerate() {
            let Some(states) = slot else { continue };
            let previous = self.terms[t].as_ref().expect("same terms");
            let width = states.width;
            let cut = states.cut.clone();
            for e in 0..mesh.len() {
                let (i, j) = mesh.element_position(e);
                let q = asm.dofs().gather(e, z);
                for point in asm.points(e, t, ev.time, ev.dt) {
                    let (row, column) = states.place(i, j, point.a, point.b);
                    let v = asm.values(&point.weights, &asm.quadratic(e, point.xi, point.eta), &q);
                    let k = (row * states.columns + column) * width;
                    asm.kernel().advance(t, &point.at, &v, previous.get(row, column), &mut states.values[k..k + width]);
                    if let Some(cut) = &cut {
                        states.values[k + cut.indicator] = asm.kernel().zone(t, &point.at, &v);
                    }
                }
            }
            if let Some(cut) = cut {
                let (per_sigma, per_zeta, nz) = (states.per_sigma, states.per_zeta, mesh.zeta_elements());
                let eta_rule = asm.terms()[t].rule[1];
                // the element of a column in a row, and its σ-range
                let elements = |column: usize, row: usize| -> (usize, [f64; 2]) {
                    let e = (column / per_sigma) * nz + row / per_zeta;
                    let el = mesh.element(e);
                    (e, [el.origin[0], el.origin[0] + el.size[0]])
                };
                // the point at σ (mod L) on element e, at the row's η, and the fields there
                let point = |e: usize, sigma: f64, row: usize| {
                    let el = mesh.element(e);
                    let xi = 2.0 * (sigma - el.origin[0]).rem_euclid(self.length) / el.size[0] - 1.0;
                    let eta = eta_rule.points()[row % per_zeta].0;
                    let [s, zeta] = el.point(xi, eta);
                    let v = asm.values(&el.derivative_weights(xi, eta), &asm.quadratic(e, xi, eta), &asm.dofs().gather(e, z));
                    (SurfacePoint { sigma: s, zeta, element: e, time: ev.time, dt: ev.dt }, v)
                };
                // the indicator there, and the kernel's record there
                let at = |e: usize, sigma: f64, row: usize| -> f64 {
                    let (p, v) = point(e, sigma, row);
                    asm.kernel().zone(t, &p, &v)
                };
                let record = |e: usize, sigma: f64, row: usize, out: &mut [f64]| {
                    let (p, v) = point(e, sigma, row);
                    asm.kernel().edge_record(t, &p, &v, out);
                };
                let downstream = asm.kernel().belt_speed(ev.time + 0.5 * ev.dt) >= 0.0;
                states.cut(&cut, self.length, downstream, &elements, &at, &record);
            }
        }
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`TermStates::travelled`]: each point's distance from the zone's upstream edge,
    /// walked with the transport (+σ) or against it, across the loop's end, 0 outside,
    /// the row's length where no point is outside; the edges off the points (one at a
    /// point: distance 0). A walk from the wrong edge would give the exit's distances
    /// (0.35 … 0.05 for 0.05 … 0.35). Each point names the edge it is measured from.
    #[test]
    fn travelled_is_the_distance_from_the_upstream_edge() {
        let x: Vec<f64> = (0..10).map(|k| 0.1 * k as f64).collect();
        let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(p, q)| (p - q).abs() < 1e-12);
        let distance = |t: &[(f64, Option<usize>)]| t.iter().map(|p| p.0).collect::<Vec<_>>();
        let mut inside = vec![false; 10];
        let mut edges = x.clone();
        for k in 3..=6 {
            inside[k] = true;
        }
        (edges[2], edges[6]) = (0.25, 0.65);
        let plus = TermStates::travelled(&x, &inside, &edges, 1.0, true);
        assert!(close(&distance(&plus), &[0.0, 0.0, 0.0, 0.05, 0.15, 0.25, 0.35, 0.0, 0.0, 0.0]), "{plus:?}");
        assert!(plus.iter().enumerate().all(|(k, p)| p.1 == inside[k].then_some(2)), "{plus:?}");
        let minus = TermStates::travelled(&x, &inside, &edges, 1.0, false);
        assert!(close(&distance(&minus), &[0.0, 0.0, 0.0, 0.35, 0.25, 0.15, 0.05, 0.0, 0.0, 0.0]), "{minus:?}");
        assert!(minus.iter().enumerate().all(|(k, p)| p.1 == inside[k].then_some(6)), "{minus:?}");
        // across the loop's end: inside 0.8, 0.9, 0.0, 0.1; the edge before 0.8 at a point
        let mut inside = vec![false; 10];
        for k in [8, 9, 0, 1] {
            inside[k] = true;
        }
        let mut edges = x.clone();
        (edges[7], edges[1]) = (0.8, 0.12);
        let plus = TermStates::travelled(&x, &inside, &edges, 1.0, true);
        assert!(close(&distance(&plus), &[0.2, 0.3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1]), "{plus:?}");
        assert!(plus.iter().enumerate().all(|(k, p)| p.1 == inside[k].then_some(7)), "{plus:?}");
        let minus = TermStates::travelled(&x, &inside, &edges, 1.0, false);
        assert!(close(&distance(&minus), &[0.12, 0.02, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.32, 0.22]), "{minus:?}");
        assert!(minus.iter().enumerate().all(|(k, p)| p.1 == inside[k].then_some(1)), "{minus:?}");
        assert_eq!(TermStates::travelled(&x, &[true; 10], &x, 1.0, true), vec![(1.0, None); 10]);
    }
}
