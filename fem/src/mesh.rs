//! The MEL mesh: nodes at fixed contour coordinates σ, element boundaries on every
//! Cartesian/polar transition (docs/fem-string.md §5).
//!
//! N elements are distributed over the four regions of [`drive::contour::Region::ALL`]
//! in proportion to the *weighted* region length (spans H, arcs w·πR, w = `arc_weight`
//! ≥ 1 refines near the pulleys), at least one per region and symmetrically: ⌊N/2⌋ is
//! split between one span and one arc by rounding (each ≥ 1) and mirrored to the other
//! span and arc; an odd N puts the extra element on the upper span. Within a region the
//! elements are uniform (the open mesh of the one-pulley layout grades a span longer
//! than [`OPEN_SPAN_RADII`] R geometrically from its arc, [`Mesh::open`]). Node 0 sits at
//! σ = 0 (top of the driver); node k at the start of element k; element N − 1 ends at
//! σ = L_c ≡ 0 (the loop closure).

use drive::contour::{Contour, Region};

use crate::error::FemError;

/// Largest number of elements accepted (memory guard: ~1 kB per element).
pub const MAX_ELEMENTS: usize = 1 << 20;

/// One element: σ ∈ [σ_a, σ_a + h) inside one region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementGeometry {
    /// σ at the element start, m.
    pub sigma_a: f64,
    /// Element length in σ, m (> 0).
    pub h: f64,
    /// The region the element lies in.
    pub region: Region,
}

/// Nodes and elements of a closed MEL mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    contour: Contour,
    /// σ of node k (k = 0..N), strictly increasing, `nodes[0] = 0`.
    nodes: Vec<f64>,
    elements: Vec<ElementGeometry>,
    /// Elements per region, in the order of [`Region::ALL`].
    per_region: [usize; 4],
    /// Node index of each region's first node (the transitions), order of [`Region::ALL`].
    transition_nodes: [usize; 4],
    /// An open mesh ([`Mesh::open`]): the first three regions only, N + 1 distinct nodes.
    open: bool,
    /// Growth rate κ (1/m) of each region's base density 1/(1 + κ d), d the distance
    /// from the arc the region joins ([`Mesh::open`]'s long spans); 0: uniform.
    growth: [f64; 4],
}

impl Mesh {
    /// A mesh of `elements` elements (≥ 4) on `contour`, with arcs weighted by
    /// `arc_weight` (≥ 1, finite) in the distribution.
    ///
    /// # Errors
    /// [`FemError::InvalidOption`] for fewer than 4 or more than [`MAX_ELEMENTS`]
    /// elements or an invalid weight.
    pub fn new(contour: Contour, elements: usize, arc_weight: f64) -> Result<Mesh, FemError> {
        if !(4..=MAX_ELEMENTS).contains(&elements) {
            return Err(FemError::InvalidOption {
                field: "elements",
                value: elements.to_string(),
                reason: format!(
                    "need at least 4 elements (one per region of the contour) and at most {MAX_ELEMENTS}"
                ),
            });
        }
        if !(arc_weight.is_finite() && arc_weight >= 1.0) {
            return Err(FemError::InvalidOption {
                field: "arc_weight",
                value: arc_weight.to_string(),
                reason: "the arc refinement weight must be finite and ≥ 1".into(),
            });
        }
        let per_region = distribute(&contour, elements, arc_weight);
        let (mut nodes, els, transition_nodes) = uniform_regions(&contour, per_region);
        nodes.push(contour.length());
        Ok(Mesh { contour, nodes, elements: els, per_region, transition_nodes, open: false, growth: [0.0; 4] })
    }

    /// An **open** mesh of `elements` elements (≥ 4) on the first three regions of
    /// `contour` — upper span, driven arc, lower span — for the one-pulley layout
    /// (docs/fem-cosserat.md §12.1: its open contour is the loop's of H = D without the
    /// driver arc, shifted by −D/2 in x). Elements per region in proportion to the
    /// weighted lengths (spans min(D, D_s), arc w·πR, D_s = [`OPEN_SPAN_RADII`]·R; ≥ 1
    /// each; the spans split equally, an odd remainder on the upper span), so that the
    /// arc's share does not shrink with D beyond D_s (D ≤ D_s: the distribution and the
    /// uniform mesh of before). The arc is uniform; a span of D ≤ D_s too; a longer span
    /// is graded geometrically from the arc outwards: its first element is the uniform
    /// element D_s/n of its n elements at D_s, the next ones grow by a constant ratio
    /// q = (1 + κD)^{1/n} (the density 1/(1 + κd), d the distance from the arc, [`span_growth`])
    /// so that the n elements cover D — the belt is straight there beyond the bending
    /// layer √(a/T̃) at the arc, and the cubic elements are exact on a straight belt.
    /// N + 1 distinct nodes: node 0 at σ = 0 (the inflow end), node N at σ = 2D + πR
    /// (the outflow end); no closure.
    ///
    /// # Errors
    /// As [`Mesh::new`].
    pub fn open(contour: Contour, elements: usize, arc_weight: f64) -> Result<Mesh, FemError> {
        let closed = Mesh::new(contour, elements, arc_weight)?;
        let span = contour.centre_distance();
        let measured = span.min(OPEN_SPAN_RADII * contour.radius());
        let arc = arc_weight * std::f64::consts::PI * contour.radius();
        let arcs = ((elements as f64 * arc / (2.0 * measured + arc)).round() as usize).clamp(1, elements - 2);
        let spans = elements - arcs;
        let per_region = [spans - spans / 2, arcs, spans / 2, 0];
        let growth = [span_growth(span, measured, per_region[0]), 0.0, span_growth(span, measured, per_region[2]), 0.0];
        let (mut nodes, els, transition_nodes) = if growth == [0.0; 4] {
            uniform_regions(&contour, per_region)
        } else {
            based_regions(&contour, per_region, growth)
        };
        nodes.push(contour.region_bounds(Region::LowerSpan).1);
        Ok(Mesh { nodes, elements: els, per_region, transition_nodes, open: true, growth, ..closed })
    }

    /// The growth rates κ (1/m) of the regions' base densities 1/(1 + κd) ([`Mesh::open`]);
    /// 0 for a uniform region.
    pub fn growth(&self) -> [f64; 4] {
        self.growth
    }

    /// True for an open mesh ([`Mesh::open`]).
    pub fn is_open(&self) -> bool {
        self.open
    }

    /// The regions the mesh covers: all four of a loop, the first three of an open mesh.
    pub fn regions(&self) -> &'static [Region] {
        if self.open {
            &Region::ALL[..3]
        } else {
            &Region::ALL
        }
    }

    /// Number of distinct nodes: N on a loop, N + 1 on an open mesh.
    pub fn node_count(&self) -> usize {
        self.elements.len() + usize::from(self.open)
    }

    /// σ of the domain's end: L_c of a loop, 2H + πR of an open mesh.
    pub fn end_sigma(&self) -> f64 {
        self.nodes[self.elements.len()]
    }

    /// A mesh with the topology of [`Mesh::new`] (same elements per region, so the same
    /// unknowns and sparsity pattern) whose nodes are moved so that each of
    /// `breakpoints` (σ, any order, wrapped) is a node: a region containing breakpoints
    /// is split at them and its elements distributed over the pieces in proportion to
    /// their lengths (≥ 1 each; largest remainders). A breakpoint closer than 2 % of the
    /// region's uniform element length to a region end or another breakpoint, or one a
    /// region has no element to spare for, is ignored (the returned list says which were
    /// used).
    ///
    /// # Errors
    /// As [`Mesh::new`].
    pub fn fitted(contour: Contour, elements: usize, arc_weight: f64, breakpoints: &[f64]) -> Result<(Mesh, Vec<f64>), FemError> {
        Mesh::graded(contour, elements, arc_weight, breakpoints, None)
    }

    /// [`Mesh::fitted`], with the elements graded towards the breakpoints by `grading`
    /// (`None`: uniform pieces, exactly [`Mesh::fitted`]): the element counts of the
    /// pieces of a region are in proportion to ∫ρ dσ over them instead of their lengths,
    /// and inside a piece the nodes equidistribute ∫ρ dσ ([`Grading`]).
    ///
    /// # Errors
    /// As [`Mesh::new`].
    pub fn graded(contour: Contour, elements: usize, arc_weight: f64, breakpoints: &[f64], grading: Option<Grading>) -> Result<(Mesh, Vec<f64>), FemError> {
        Ok(Mesh::new(contour, elements, arc_weight)?.regraded(breakpoints, grading, 0.0))
    }

    /// [`Mesh::graded`] on this mesh's topology (its regions and elements per region,
    /// open or closed; the node positions of `self` do not matter). Pieces whose
    /// remainders of the largest-remainder distribution lie within `tie` elements of each
    /// other are tied: the extra element goes to the first of them, not to the longer by
    /// a few nm — the mirror-image end pieces of the upper span of a symmetric loop
    /// fitted to its contact boundaries would otherwise get it by the round-off of their
    /// lengths, and a fitting that moves their cuts by nm flips it between them, and the
    /// discrete solution with it (the static fit's `tie`, docs/fem-string.md §5); 0: the
    /// largest remainder decides, however small the difference.
    pub fn regraded(&self, breakpoints: &[f64], grading: Option<Grading>, tie: f64) -> (Mesh, Vec<f64>) {
        let (base, contour) = (self, self.contour);
        let elements = self.elements.len();
        let mut nodes = Vec::with_capacity(elements + 1);
        let mut els = Vec::with_capacity(elements);
        let mut used = Vec::new();
        for (k, region) in base.regions().iter().enumerate() {
            let (a, b) = contour.region_bounds(*region);
            let m = base.per_region[k];
            let h_uniform = (b - a) / m as f64;
            let min_gap = 0.02 * h_uniform;
            let mut cuts: Vec<f64> = breakpoints
                .iter()
                .map(|&s| contour.wrap(s))
                .filter(|&s| s.is_finite() && s > a + min_gap && s < b - min_gap)
                .collect();
            cuts.sort_by(f64::total_cmp);
            let mut kept: Vec<f64> = Vec::new();
            for c in cuts {
                if kept.last().is_none_or(|&l| c - l > min_gap) {
                    kept.push(c);
                }
            }
            kept.truncate(m.saturating_sub(1));
            let mut edges = vec![a];
            edges.extend(&kept);
            edges.push(b);
            used.extend(kept);
            let pieces = edges.len() - 1;
            // the measure of a piece: its length, or ∫ρ over it when graded; on a region
            // of a base density (a long open span), its ∫ plus the grading's excess
            let kappa = base.growth[k];
            let based = kappa > 0.0;
            let measure = |x: f64| match (based, grading) {
                (false, _) => grading.map_or(x, |g| g.cumulative(x, breakpoints, &contour)),
                (true, None) => base_measure(*region, &contour, kappa, x),
                (true, Some(g)) => base_measure(*region, &contour, kappa, x) + (g.cumulative(x, breakpoints, &contour) - x),
            };
            let lengths: Vec<f64> = edges.windows(2).map(|w| measure(w[1]) - measure(w[0])).collect();
            let total = measure(b) - measure(a);
            let spare = (m - pieces) as f64;
            let ideal: Vec<f64> = lengths.iter().map(|l| spare * l / total).collect();
            let counts = apportion(&ideal, m, tie);
            for p in 0..pieces {
                let (pa, pb) = (edges[p], edges[p + 1]);
                let n = counts[p];
                let h = (pb - pa) / n as f64;
                // node j of the piece: uniform, or where ∫ρ reaches j/n of the piece's
                let (ma, mb) = (measure(pa), measure(pb));
                let node = |j: usize| match (based, grading) {
                    (false, None) => pa + j as f64 * h,
                    (true, None) => base_inverse(*region, &contour, kappa, ma + (mb - ma) * j as f64 / n as f64),
                    (_, Some(_)) => invert(&measure, ma + (mb - ma) * j as f64 / n as f64, pa, pb),
                };
                for j in 0..n {
                    let sa = if j == 0 { pa } else { node(j) };
                    let sb = if j + 1 == n { pb } else { node(j + 1) };
                    nodes.push(sa);
                    els.push(ElementGeometry { sigma_a: sa, h: sb - sa, region: *region });
                }
            }
        }
        nodes.push(base.end_sigma());
        let mesh = Mesh { contour, nodes, elements: els, per_region: base.per_region, transition_nodes: base.transition_nodes, open: base.open, growth: base.growth };
        (mesh, used)
    }

    /// The contour.
    pub fn contour(&self) -> &Contour {
        &self.contour
    }

    /// Number of elements N (= number of distinct nodes, the loop being closed).
    pub fn len(&self) -> usize {
        self.elements.len()
    }

    /// Never true (a mesh has ≥ 4 elements); for clippy's `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.elements.is_empty()
    }

    /// The elements in σ order.
    pub fn elements(&self) -> &[ElementGeometry] {
        &self.elements
    }

    /// σ of the N + 1 node positions (the last is L_c, the same node as the first).
    pub fn node_sigmas(&self) -> &[f64] {
        &self.nodes
    }

    /// Elements per region, in the order of [`Region::ALL`].
    pub fn elements_per_region(&self) -> [usize; 4] {
        self.per_region
    }

    /// Node indices of the four transitions (first node of each region).
    pub fn transition_nodes(&self) -> [usize; 4] {
        self.transition_nodes
    }

    /// True if node k is a region transition (where the slopes are doubled).
    pub fn is_transition(&self, node: usize) -> bool {
        if self.open {
            // the two interior transitions; the end nodes are no transitions
            self.transition_nodes[1..3].contains(&node)
        } else {
            self.transition_nodes.contains(&node)
        }
    }

    /// The element containing σ (wrapped periodically) and the local ξ ∈ [−1, 1].
    /// A non-finite σ gives element 0 and ξ = NaN (never a panic).
    pub fn locate(&self, sigma: f64) -> (usize, f64) {
        // an open mesh does not wrap: σ beyond an end lands in the end element
        let w = if self.open { sigma.clamp(0.0, self.end_sigma()) } else { self.contour.wrap(sigma) };
        if !w.is_finite() {
            return (0, f64::NAN);
        }
        // last node ≤ w among nodes[0..N]
        let n = self.elements.len();
        let k = match self.nodes[..n].binary_search_by(|x| x.total_cmp(&w)) {
            Ok(k) => k,
            Err(k) => k.saturating_sub(1),
        };
        let e = &self.elements[k.min(n - 1)];
        let xi = (2.0 * (w - e.sigma_a) / e.h - 1.0).clamp(-1.0, 1.0);
        (k.min(n - 1), xi)
    }

    /// The element to the left of σ (σ ∈ (σ_a, σ_b], wrapped) and ξ: at a node, the
    /// element that *ends* there ([`Mesh::locate`] gives the one that starts there).
    pub fn locate_left(&self, sigma: f64) -> (usize, f64) {
        let (k, xi) = self.locate(sigma);
        if xi == -1.0 && !(self.open && k == 0) {
            let n = self.elements.len();
            ((k + n - 1) % n, 1.0)
        } else {
            (k, xi)
        }
    }

    /// Mean length of the elements that meet at node k (used to scale slope residuals).
    pub fn node_spacing(&self, node: usize) -> f64 {
        let n = self.elements.len();
        if self.open && (node == 0 || node == n) {
            return self.elements[node.min(n - 1)].h;
        }
        let prev = &self.elements[(node + n - 1) % n];
        let next = &self.elements[node % n];
        0.5 * (prev.h + next.h)
    }
}

/// A mesh density graded towards points c_k (the contact edges of a Cosserat rod, whose
/// shear layer of width √(a/b₂) a uniform mesh does not resolve, docs/fem-cosserat.md
/// §9): ρ(σ) = 1 + `ratio` Σ_k exp(−|σ − c_k|/`width`) (periodic in σ), so that the
/// elements next to a point are about 1 + `ratio` times shorter than far from it. The
/// density is fixed (it does not depend on the element count): a sequence of graded
/// meshes refines one smooth map, and shows the discretisation's order.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Grading {
    /// Decay length of the refinement, m (> 0).
    pub width: f64,
    /// Peak refinement (≥ 0; 0 is uniform).
    pub ratio: f64,
}

impl Grading {
    /// `elements` elements on [a, b] graded towards both ends (the free edges of a shell
    /// across its width, docs/fem-shell.md §9.5): ρ(x) = 1 + `ratio`(exp(−(x − a)/`width`) +
    /// exp(−(b − x)/`width`)), node j where ∫ₐ^x ρ reaches j/n of ∫ₐ^b ρ. The nodes are
    /// mirror-symmetric about (a + b)/2 (the middle one exactly there for even n), the ends
    /// exactly a and b; `elements` + 1 nodes (0 elements is taken as 1), increasing.
    pub fn interval(&self, a: f64, b: f64, elements: usize) -> Vec<f64> {
        let w = self.width;
        let n = elements.max(1);
        // ∫ₐ^x ρ: x − a + r w [(1 − e^{−(x−a)/w}) + (e^{−(b−x)/w} − e^{−(b−a)/w})]
        let measure = |x: f64| x - a + self.ratio * w * (-(-(x - a) / w).exp_m1() + (-(b - x) / w).exp() - (-(b - a) / w).exp());
        let total = measure(b);
        let mut nodes: Vec<f64> = (0..=n).map(|j| if j == 0 { a } else if j == n { b } else { invert(&measure, total * j as f64 / n as f64, a, b) }).collect();
        let mid = 0.5 * (a + b);
        for j in 1..n.div_ceil(2) {
            let half = 0.5 * ((nodes[n - j] - mid) - (nodes[j] - mid));
            nodes[j] = mid - half;
            nodes[n - j] = mid + half;
        }
        if n % 2 == 0 {
            nodes[n / 2] = mid;
        }
        nodes
    }

    /// C(σ) = ∫₀^σ ρ dσ′ up to a constant (σ unwrapped, in the region's range), with the
    /// points wrapped and taken with their neighbours one contour length either side.
    fn cumulative(&self, sigma: f64, points: &[f64], contour: &Contour) -> f64 {
        let l = contour.length();
        let w = self.width;
        let mut c = sigma;
        for &p in points {
            let p = contour.wrap(p);
            if !p.is_finite() {
                continue;
            }
            for off in [-l, 0.0, l] {
                let d = sigma - (p + off);
                // ∫ exp(−|x|/w) dx = w sign(x) (1 − exp(−|x|/w))
                c += self.ratio * w * d.signum() * (1.0 - (-d.abs() / w).exp());
            }
        }
        c
    }
}

/// Uniform elements in each region of [`Region::ALL`], `per_region[k]` of them in region k
/// (0: none): the node σ (without the end node), the elements and each region's first
/// node.
fn uniform_regions(contour: &Contour, per_region: [usize; 4]) -> (Vec<f64>, Vec<ElementGeometry>, [usize; 4]) {
    let elements = per_region.iter().sum::<usize>();
    let mut nodes = Vec::with_capacity(elements + 1);
    let mut els = Vec::with_capacity(elements);
    let mut transition_nodes = [0; 4];
    for (k, region) in Region::ALL.iter().enumerate() {
        let (a, b) = contour.region_bounds(*region);
        let n = per_region[k];
        transition_nodes[k] = nodes.len();
        let h = (b - a) / n as f64;
        for i in 0..n {
            let sa = if i == 0 { a } else { a + i as f64 * h };
            nodes.push(sa);
            let sb = if i + 1 == n { b } else { a + (i + 1) as f64 * h };
            els.push(ElementGeometry { sigma_a: sa, h: sb - sa, region: *region });
        }
    }
    (nodes, els, transition_nodes)
}

/// Spans of an open mesh longer than this many pulley radii are weighed in the element
/// distribution as this long and graded ([`Mesh::open`]): 5 R, the catalogue scene's
/// D = 0.5 m at R = 0.1 m, whose mesh is unchanged.
pub const OPEN_SPAN_RADII: f64 = 5.0;

/// The growth rate κ (1/m) of a span of length `span` with `n` elements whose first
/// element (at the arc) is `measured`/n: the root of ((1 + κD)^{1/n} − 1)/κ = D_s/n
/// (the first element of the density 1/(1 + κd) equidistributed); 0 when `span` ≤
/// `measured` (uniform) or for a single element.
pub fn span_growth(span: f64, measured: f64, n: usize) -> f64 {
    if n < 2 || span <= measured || !(span.is_finite() && measured > 0.0) {
        return 0.0;
    }
    let n = n as f64;
    let h0 = measured / n;
    // the first element; decreasing in κ from D/n (κ → 0) to 0
    let first = |kappa: f64| (kappa * span).ln_1p() / n;
    let first = |kappa: f64| first(kappa).exp_m1() / kappa;
    let (mut lo, mut hi) = (0.0, 1.0 / span);
    while first(hi) > h0 {
        lo = hi;
        hi *= 2.0;
    }
    // bisection in κ to round-off (the first element is monotone in κ)
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if first(mid) > h0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The base measure ∫ dσ/(1 + κd) (m, increasing in σ) of a span region, d the distance
/// from the arc it joins: the upper span ends at the arc, the lower span starts there.
fn base_measure(region: Region, contour: &Contour, kappa: f64, sigma: f64) -> f64 {
    let (a, b) = contour.region_bounds(region);
    match region {
        Region::UpperSpan => -(kappa * (b - sigma)).ln_1p() / kappa,
        _ => (kappa * (sigma - a)).ln_1p() / kappa,
    }
}

/// σ of the base measure `m` ([`base_measure`]'s inverse).
fn base_inverse(region: Region, contour: &Contour, kappa: f64, m: f64) -> f64 {
    let (a, b) = contour.region_bounds(region);
    match region {
        Region::UpperSpan => b - (-kappa * m).exp_m1() / kappa,
        _ => a + (kappa * m).exp_m1() / kappa,
    }
}

/// [`uniform_regions`] with the regions of a growth rate κ > 0 graded by their base
/// density ([`base_measure`]): node j of n where the measure reaches j/n of the region's.
fn based_regions(contour: &Contour, per_region: [usize; 4], growth: [f64; 4]) -> (Vec<f64>, Vec<ElementGeometry>, [usize; 4]) {
    let (mut nodes, mut els, transition_nodes) = uniform_regions(contour, per_region);
    for (k, region) in Region::ALL.iter().enumerate() {
        let kappa = growth[k];
        if kappa <= 0.0 {
            continue;
        }
        let (a, b) = contour.region_bounds(*region);
        let (ma, mb) = (base_measure(*region, contour, kappa, a), base_measure(*region, contour, kappa, b));
        let first = transition_nodes[k];
        let n = per_region[k];
        for j in 1..n {
            nodes[first + j] = base_inverse(*region, contour, kappa, ma + (mb - ma) * j as f64 / n as f64);
        }
        for j in 0..n {
            let sa = nodes[first + j];
            let sb = if j + 1 == n { b } else { nodes[first + j + 1] };
            els[first + j] = ElementGeometry { sigma_a: sa, h: sb - sa, region: *region };
        }
    }
    (nodes, els, transition_nodes)
}

/// σ in [a, b] where the increasing `measure` takes `target` (bisection to 1e-15 m).
fn invert(measure: &dyn Fn(f64) -> f64, target: f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if measure(m) < target {
            a = m;
        } else {
            b = m;
        }
        if b - a < 1e-15 {
            break;
        }
    }
    0.5 * (a + b)
}

/// `m` elements over pieces with the ideal spare counts `ideal` (the counts beyond the
/// one every piece has; Σ ideal = m − pieces): 1 + ⌊ideal⌋ each, the rest by largest
/// remainders. Remainders within `tie` (elements) of the largest are a tie, given to the
/// piece of the lowest index ([`Mesh::regraded`]).
fn apportion(ideal: &[f64], m: usize, tie: f64) -> Vec<usize> {
    let mut counts: Vec<usize> = ideal.iter().map(|x| 1 + x.floor() as usize).collect();
    let mut remainder: Vec<f64> = ideal.iter().map(|x| x - x.floor()).collect();
    while counts.iter().sum::<usize>() < m {
        let largest = remainder.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let Some(k) = remainder.iter().position(|&r| r >= largest - tie) else { break };
        counts[k] += 1;
        // each piece gets at most one of the rest
        remainder[k] = f64::NEG_INFINITY;
    }
    counts
}

/// Elements per region: proportional to the weighted lengths, ≥ 1 each, sum = `n`,
/// symmetric (upper = lower span, driven = driver arc) — the left–right symmetry of the
/// drive is kept by the mesh. For odd `n` the upper span gets the extra element.
fn distribute(contour: &Contour, n: usize, arc_weight: f64) -> [usize; 4] {
    let span = contour.centre_distance();
    let arc = arc_weight * std::f64::consts::PI * contour.radius();
    let half = n / 2; // ≥ 2
    let spans = ((half as f64 * span / (span + arc)).round() as usize).clamp(1, half - 1);
    let arcs = half - spans;
    [spans + n % 2, arcs, spans, arcs]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contour() -> Contour {
        Contour::new(0.08, 0.45).unwrap()
    }

    #[test]
    fn mirror_pieces_keep_their_elements_through_a_tie() {
        // the upper span of string-hanging at 256 elements (82 in the span) fitted to its
        // two contact boundaries 14.679 mm from its ends: the two end pieces are equal
        // up to ±3 nm; the extra element goes to the first piece for either sign (by
        // their round-off it used to go to the longer one, flipping the mesh)
        let c = contour();
        let m0 = Mesh::new(c, 256, 1.0).unwrap();
        let (a, b) = c.region_bounds(Region::UpperSpan);
        let mut counts = Vec::new();
        for d in [3e-9, -3e-9, 1e-12, -1e-12] {
            let (m, used) = m0.regraded(&[a + 0.014679082, b - 0.014679082 + d], None, 1e-3);
            assert_eq!(used.len(), 2);
            let node = |s: f64| m.node_sigmas().iter().position(|&n| n == s).unwrap();
            // elements of the left and the right end piece
            let right_end = if b == c.length() { m.len() } else { node(b) };
            let per = vec![node(used[0]) - node(a), right_end - node(used[1])];
            counts.push(per);
        }
        assert!(counts.iter().all(|c| *c == counts[0]), "{counts:?}");
        assert_eq!(counts[0][0], 4, "{counts:?}");
        // a clear difference still decides by the remainders: 2.577 against 2.6 elements
        assert_eq!(apportion(&[2.577, 73.823, 2.6], 82, 1e-3), vec![3, 75, 4]);
        assert_eq!(apportion(&[2.6, 73.823, 2.577], 82, 1e-3), vec![4, 75, 3]);
        assert_eq!(apportion(&[2.5775, 73.845, 2.5775], 82, 1e-3), vec![4, 75, 3]);
        // without a tie tolerance a difference of 1e-9 elements decides
        assert_eq!(apportion(&[2.577, 73.846 - 1e-9, 2.577 + 1e-9], 82, 0.0), vec![3, 75, 4]);
    }

    #[test]
    fn distribution_and_transitions() {
        let c = contour();
        for n in [4, 5, 7, 16, 64, 255, 256, 1000] {
            let m = Mesh::new(c, n, 1.0).unwrap();
            assert_eq!(m.len(), n);
            let per = m.elements_per_region();
            assert_eq!(per.iter().sum::<usize>(), n);
            assert!(per.iter().all(|&k| k >= 1));
            // transitions are nodes
            for (k, region) in Region::ALL.iter().enumerate() {
                let node = m.transition_nodes()[k];
                assert_eq!(m.node_sigmas()[node], c.region_bounds(*region).0);
                assert!(m.is_transition(node));
            }
            // contiguous, positive lengths, each inside one region
            for (k, e) in m.elements().iter().enumerate() {
                assert!(e.h > 0.0);
                assert_eq!(m.node_sigmas()[k], e.sigma_a);
                assert!((m.node_sigmas()[k + 1] - (e.sigma_a + e.h)).abs() < 1e-15);
                assert_eq!(c.region(e.sigma_a + 0.5 * e.h), e.region);
            }
            assert_eq!(*m.node_sigmas().last().unwrap(), c.length());
        }
        // proportional: H = 0.45, πR = 0.2513, 256 → spans ≈ 82, arcs ≈ 46
        let m = Mesh::new(c, 256, 1.0).unwrap();
        let per = m.elements_per_region();
        assert_eq!(per[0], per[2]);
        assert_eq!(per[1], per[3]);
        assert!((per[0] as f64 / 256.0 - 0.45 / c.length()).abs() < 2.0 / 256.0);
        // refinement near the pulleys
        let r = Mesh::new(c, 256, 3.0).unwrap();
        assert!(2 * r.elements_per_region()[1] > 3 * per[1]);
        assert_eq!(per, [82, 46, 82, 46]);
    }

    #[test]
    fn locate() {
        let c = contour();
        let m = Mesh::new(c, 64, 1.0).unwrap();
        for k in 0..m.len() {
            let e = m.elements()[k];
            let (k2, xi) = m.locate(e.sigma_a + 0.25 * e.h);
            assert_eq!(k2, k);
            assert!((xi + 0.5).abs() < 1e-12);
            let (k3, xi3) = m.locate(e.sigma_a);
            assert_eq!(k3, k);
            assert!((xi3 + 1.0).abs() < 1e-12);
        }
        let (k, xi) = m.locate(c.length() - 1e-12);
        assert_eq!(k, m.len() - 1);
        assert!(xi > 0.99);
        assert_eq!(m.locate(-1e-300).0, 0);
        assert!(m.locate(f64::NAN).1.is_nan());
    }

    /// `Grading::interval`: increasing, mirror-symmetric nodes with exact ends; every
    /// element carries the same measure ∫ρ (the density integrated in closed form, to
    /// round-off); a zero ratio is uniform.
    #[test]
    fn an_interval_graded_towards_both_ends() {
        let g = Grading { width: 0.007, ratio: 8.0 };
        for n in [2, 4, 7, 16] {
            let x = g.interval(-0.1, 0.1, n);
            assert_eq!((x.len(), x[0], x[n]), (n + 1, -0.1, 0.1));
            assert!(x.windows(2).all(|p| p[1] > p[0]), "{x:?}");
            for j in 0..=n {
                assert_eq!(x[j], -x[n - j], "mirror symmetry at {j}: {x:?}");
            }
            if n % 2 == 0 {
                assert_eq!(x[n / 2], 0.0);
            }
        }
        // equal measure per element, ∫ρ in closed form, on a symmetric and a shifted interval
        for (a, b) in [(-0.1, 0.1), (0.1, 0.3), (-0.37, 0.05)] {
            let w = g.width;
            let measure = |x: f64| x - a + g.ratio * w * ((1.0 - (-(x - a) / w).exp()) + (-(b - x) / w).exp() - (-(b - a) / w).exp());
            for n in [3, 8, 17] {
                let x = g.interval(a, b, n);
                assert_eq!((x[0], x[n]), (a, b), "the ends exactly");
                let each = measure(b) / n as f64;
                for k in 0..n {
                    assert!((measure(x[k + 1]) - measure(x[k]) - each).abs() < 1e-12 * measure(b), "[{a}, {b}] / {n}, element {k}: {x:?}");
                }
            }
        }
        // the edge element is about 1 + ratio(1 + e^{−b/w}) times shorter than the spacing
        // of the measure (measured 1.034 of it), the middle one about as long
        let x = g.interval(-0.1, 0.1, 64);
        let total = 0.2 + 8.0 * 0.007 * 2.0 * (1.0 - (-0.2_f64 / 0.007).exp());
        let spacing = total / 64.0;
        let edge = x[1] - x[0];
        let rho_edge = 1.0 + 8.0 * (1.0 + (-0.2_f64 / 0.007).exp());
        assert!((edge * rho_edge / spacing - 1.0).abs() < 0.05, "edge {edge} against {}", spacing / rho_edge);
        assert!(((x[33] - x[32]) / spacing - 1.0).abs() < 1e-3, "middle {}", x[33] - x[32]);
        // no grading: uniform
        let u = Grading { width: 0.007, ratio: 0.0 }.interval(0.0, 1.0, 4);
        for (j, v) in u.iter().enumerate() {
            assert!((v - j as f64 / 4.0).abs() < 1e-14, "{u:?}");
        }
    }

    /// A graded fitted mesh keeps the topology and the breakpoints as nodes, and its
    /// elements next to a breakpoint are shorter than the uniform ones by about
    /// 1 + ratio (corrected for the density's mean over the piece); no grading is the
    /// uniform fitted mesh exactly.
    #[test]
    fn graded_towards_the_breakpoints() {
        let c = contour();
        let (a, b) = c.region_bounds(Region::DriverArc);
        let points = [a + 0.035, b - 0.035];
        let (uniform, _) = Mesh::fitted(c, 512, 1.0, &points).unwrap();
        assert_eq!(Mesh::graded(c, 512, 1.0, &points, None).unwrap().0, uniform);
        let g = Grading { width: 0.0045, ratio: 8.0 };
        let (m, used) = Mesh::graded(c, 512, 1.0, &points, Some(g)).unwrap();
        assert_eq!(used.len(), 2);
        assert_eq!(m.elements_per_region(), uniform.elements_per_region());
        for p in points {
            assert!(m.node_sigmas().iter().any(|&n| (n - p).abs() < 1e-12), "breakpoint {p} is no node");
        }
        for (k, e) in m.elements().iter().enumerate() {
            assert!(e.h > 0.0);
            assert!((m.node_sigmas()[k + 1] - (e.sigma_a + e.h)).abs() < 1e-15);
        }
        // the arc's mean element, and the density's mean over it: ∫ρ/(b − a)
        let n_arc = m.elements_per_region()[3] as f64;
        let mean = (b - a) / n_arc;
        let density = 1.0 + g.ratio * 2.0 * 2.0 * g.width / (b - a);
        let at = |s: f64| m.elements()[m.locate(s).0].h;
        let edge = at(points[0] + 1e-6);
        let expected = mean * density / (1.0 + g.ratio);
        assert!((edge / expected - 1.0).abs() < 0.15, "edge element {edge} against {expected}");
        let middle = at(0.5 * (a + b));
        assert!((middle / (mean * density) - 1.0).abs() < 0.05, "far element {middle} against {}", mean * density);
    }

    #[test]
    fn bad_input() {
        assert!(Mesh::new(contour(), 3, 1.0).is_err());
        assert!(Mesh::new(contour(), 0, 1.0).is_err());
        assert!(Mesh::new(contour(), 64, 0.5).is_err());
        assert!(Mesh::new(contour(), 64, f64::NAN).is_err());
        assert!(Mesh::new(contour(), MAX_ELEMENTS + 1, 1.0).is_err());
    }

    /// A long open span (D > [`OPEN_SPAN_RADII`] R, issue 13 "long D"): the arc keeps the
    /// element count of D = 5R at every D, both spans are graded geometrically from the
    /// arc (first element D_s/n, constant ratio, the last node at the end), a refit keeps
    /// the span nodes, and D = 5R itself is the uniform mesh of before.
    #[test]
    fn long_open_spans_are_graded_and_keep_the_arc_elements() {
        let r = 0.1;
        let ds = OPEN_SPAN_RADII * r;
        for n in [16, 64, 128, 256] {
            let reference = Mesh::open(Contour::new(r, ds).unwrap(), n, 1.0).unwrap();
            assert_eq!(reference.growth(), [0.0; 4], "D = 5R is uniform");
            let per0 = reference.elements_per_region();
            for d in [0.5 + 1e-9, 1.0, 10.0, 20.0, 50.0, 1000.0] {
                let c = Contour::new(r, d).unwrap();
                let m = Mesh::open(c, n, 1.0).unwrap();
                let per = m.elements_per_region();
                assert_eq!(per, per0, "D = {d}, {n} elements");
                assert!(m.node_sigmas().windows(2).all(|w| w[1] > w[0]), "D = {d}: nodes increasing");
                assert_eq!(m.end_sigma(), c.region_bounds(Region::LowerSpan).1);
                for (k, e) in m.elements().iter().enumerate() {
                    assert!((m.node_sigmas()[k + 1] - (e.sigma_a + e.h)).abs() <= 1e-12 * d, "D = {d}: element {k} contiguous");
                    assert_eq!(c.region(e.sigma_a + 0.5 * e.h), e.region);
                }
                // the spans, ordered from the arc outwards: first element D_s/n, ratio q
                let upper: Vec<f64> = m.elements()[..per[0]].iter().rev().map(|e| e.h).collect();
                let lower: Vec<f64> = m.elements()[per[0] + per[1]..].iter().map(|e| e.h).collect();
                for span in [upper, lower] {
                    let k = span.len();
                    assert!((span[0] / (ds / k as f64) - 1.0).abs() < 1e-9, "D = {d}: first span element {} against D_s/n = {}", span[0], ds / k as f64);
                    assert!((span.iter().sum::<f64>() / d - 1.0).abs() < 1e-12, "D = {d}: the span is covered");
                    let q = span[1] / span[0];
                    assert!(q >= 1.0 && span.windows(2).all(|w| (w[1] / w[0] / q - 1.0).abs() < 1e-6), "D = {d}, {n} elements: not geometric");
                }
                // the arc: uniform, its elements those of D = 5R
                let arc = &m.elements()[per[0]..per[0] + per[1]];
                let arc0 = &reference.elements()[per[0]..per[0] + per[1]];
                assert!(arc.iter().zip(arc0).all(|(a, b)| (a.h - b.h).abs() < 1e-12), "D = {d}: arc elements");
                // a refit to two points on the arc (the contact edges) keeps the spans
                let (a, b) = c.region_bounds(Region::DrivenArc);
                let (g, used) = m.regraded(&[a + 0.3 * (b - a), a + 0.6 * (b - a)], None, 0.0);
                if n >= 64 {
                    assert_eq!(used.len(), 2);
                }
                assert_eq!(g.growth(), m.growth());
                for k in (0..per[0]).chain(per[0] + per[1]..n) {
                    assert!((g.node_sigmas()[k] - m.node_sigmas()[k]).abs() <= 1e-12 * d, "D = {d}: refit moved span node {k}");
                }
                // graded towards the points: the span's far elements as before to 1 %
                let (gg, _) = m.regraded(&[a + 0.3 * (b - a), a + 0.6 * (b - a)], Some(Grading { width: 0.006, ratio: 8.0 }), 0.0);
                assert!((gg.elements()[0].h / m.elements()[0].h - 1.0).abs() < 1e-2 && (gg.elements()[n - 1].h / m.elements()[n - 1].h - 1.0).abs() < 1e-2);
            }
        }
        // the growth: 0 up to D_s and for a single element, and (1 + κD)^{1/n} at 256
        assert_eq!(span_growth(0.5, 0.5, 97), 0.0);
        assert_eq!(span_growth(0.4, 0.5, 97), 0.0);
        assert_eq!(span_growth(10.0, 0.5, 1), 0.0);
        let kappa = span_growth(10.0, 0.5, 97);
        let q = (kappa * 10.0).ln_1p() / 97.0;
        assert!((q.exp() - 1.048).abs() < 2e-3, "ratio {}", q.exp());
    }

    /// The open mesh (docs/fem-cosserat.md §12.1): three regions, ≥ 1 element each,
    /// nodes increasing from 0 to 2H + πR, transitions interior only, locate without
    /// wrapping, and a regraded open mesh keeps the topology.
    #[test]
    fn open_mesh() {
        let c = Contour::new(0.1, 0.5).unwrap();
        for n in [4, 5, 64, 255] {
            let m = Mesh::open(c, n, 1.0).unwrap();
            let per = m.elements_per_region();
            assert_eq!(per.iter().sum::<usize>(), n);
            assert!(per[..3].iter().all(|&k| k >= 1) && per[3] == 0);
            assert!(m.node_sigmas().windows(2).all(|w| w[1] > w[0]));
            assert!(!m.is_transition(0) && !m.is_transition(n));
            assert!(m.is_transition(per[0]) && m.is_transition(per[0] + per[1]));
            assert_eq!(m.elements()[per[0]].region, Region::DrivenArc);
            assert_eq!(m.locate(-1.0), (0, -1.0));
            assert_eq!(m.locate(5.0), (n - 1, 1.0));
            assert_eq!(m.locate_left(0.0), (0, -1.0));
            let b = [0.5 + 0.05, 0.5 + 0.2];
            let (g, used) = m.regraded(&b, Some(Grading { width: 0.003, ratio: 8.0 }), 0.0);
            assert!(g.is_open() && g.elements_per_region() == per && g.end_sigma() == m.end_sigma());
            if n >= 64 {
                assert_eq!(used.len(), 2);
                for p in b {
                    assert!(g.node_sigmas().iter().any(|s| (s - p).abs() < 1e-12));
                }
            }
        }
    }
}
