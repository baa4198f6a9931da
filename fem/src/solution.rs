//! The FE solution behind the common view (`drive::view::SolutionView`) and its summary
//! (docs/fem-string.md §10).

use std::f64::consts::PI;
use std::sync::Arc;

use drive::contour::{Pulley, Region};
use drive::summary::{PulleySummary, Summary};
use drive::view::{ContactState, SolutionView};
use numerics::quadrature::lagrange;

use crate::dofs::DofMap;
use crate::element::{ElementLayout, Field};
use crate::formulation::layout::LayoutElement;
use crate::formulation::Kernel;
use crate::kinematics::{ElementContext, PointFields, TermParams, NDOF};
use crate::mesh::Mesh;

/// Sub-intervals per element scanned for sign changes of the gap.
const GAP_SCAN: usize = 16;

/// A converged MEL solution: the mesh, each element's local unknowns, the term
/// parameters and the element (for the axial force and the recovery rules). Generic
/// over the element's unknown count N and its kernel K, like
/// [`crate::assembly::Assembler`]: the point fields S, ν (and any further field of the
/// layout, e.g. θ, by [`Self::field`]) are read through the element's
/// [`ElementLayout`]; the default is the string layout of the registered formulations
/// (N = 8, `dyn Kernel`).
pub struct FemSolution<const N: usize = NDOF, K: LayoutElement<N> + ?Sized = dyn Kernel> {
    mesh: Mesh,
    layout: ElementLayout,
    local: Vec<[f64; N]>,
    params: TermParams,
    length: f64,
    kernel: Arc<K>,
    summary: Summary,
    /// Recovered contact zones (driver, driven).
    zones: [Option<ContactZone>; 2],
    /// ρc² of steady transport (N), if the belt moves with inertia: the free spans then
    /// carry the effective tension N − ρc²λ (docs/fem-drive.md §12).
    transport: Option<f64>,
}

/// Contact zone of one pulley (σ of entry and exit, unwrapped so that
/// σ_start < σ_end; polar angles of the boundary points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactZone {
    /// σ of the first entry into contact in the direction of σ, m.
    pub sigma_start: f64,
    /// σ of the last exit, m.
    pub sigma_end: f64,
    /// Polar angle of the entry point about the pulley centre, rad, (−π, π].
    pub angle_start: f64,
    /// Polar angle of the exit point, rad, (−π, π].
    pub angle_end: f64,
    /// Separate intervals of γ < 0 found in the window (1 for a clean solution).
    pub intervals: usize,
    /// True if both boundaries were recovered by the tangency construction (§10); false
    /// if a boundary is the raw zero crossing of the gap. For a rod: true if both edges
    /// were located by the force resultant and moment of the window (docs/fem-rod.md §5).
    pub recovered: bool,
    /// Rod only: the edge force at the entry (K10), N.
    pub edge_force_start: Option<f64>,
    /// Rod only: the edge force at the exit (K10), N.
    pub edge_force_end: Option<f64>,
}

/// Spec §2.6/§3.7's Cosserat quantities of one contact zone ([`FemSolution::cosserat_zone`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CosseratZone {
    /// Smallest contact pressure per unit reference length over the zone, N/m.
    pub pressure_min: Option<f64>,
    /// Largest |Γ₂| over the zone, its edges included.
    pub shear_strain_max: Option<f64>,
    /// Bending moment at the first contact point, N·m.
    pub moment_start: Option<f64>,
    /// Bending moment at the last contact point, N·m.
    pub moment_end: Option<f64>,
}

impl CosseratZone {
    /// Write the quantities into a pulley's summary block.
    pub fn fill(&self, ps: &mut PulleySummary) {
        ps.pressure_min = self.pressure_min;
        ps.shear_strain_max = self.shear_strain_max;
        ps.moment_start = self.moment_start;
        ps.moment_end = self.moment_end;
    }
}

/// 8-point Gauss–Legendre rule on [−1, 1].
const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

impl<const N: usize, K: LayoutElement<N> + ?Sized> Clone for FemSolution<N, K> {
    fn clone(&self) -> Self {
        FemSolution {
            mesh: self.mesh.clone(),
            layout: self.layout,
            local: self.local.clone(),
            params: self.params,
            length: self.length,
            kernel: self.kernel.clone(),
            summary: self.summary.clone(),
            zones: self.zones,
            transport: self.transport,
        }
    }
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> FemSolution<N, K> {
    /// The solution for global unknowns `z` of `dofs` on `mesh` with belt length `length`.
    pub fn new(mesh: Mesh, dofs: &DofMap<N>, z: &[f64], params: TermParams, length: f64, kernel: Arc<K>) -> Self {
        // effective local unknowns: the element's map at shared transition slopes (the
        // rod's augmented map, docs/fem-rod.md K9) applied once, so that every evaluation
        // below sees the slopes each element actually uses
        let flags = crate::dofs::augmented_flags(&mesh, kernel.separate_transition_slopes());
        let local = (0..mesh.len())
            .map(|e| {
                let el = ElementContext { geometry: mesh.elements()[e], contour: *mesh.contour(), params, augmented: flags[e] };
                kernel.effective(&el, &dofs.gather(e, z, length))
            })
            .collect();
        let layout = kernel.layout();
        let mut sol = FemSolution { mesh, layout, local, params, length, kernel, summary: Summary::default(), zones: [None; 2], transport: None };
        if sol.params.penalty.is_some() {
            sol.zones = if sol.kernel.theory() == drive::scene::Theory::Cosserat {
                [sol.loaded_zone(Pulley::Driver), sol.loaded_zone(Pulley::Driven)]
            } else if sol.params.bending_stiffness.is_some() {
                [sol.rod_zone(Pulley::Driver), sol.rod_zone(Pulley::Driven)]
            } else {
                [sol.recovered_zone(Pulley::Driver), sol.recovered_zone(Pulley::Driven)]
            };
        }
        sol.summary = sol.compute_summary();
        sol
    }

    /// The same solution of a belt in steady transport with inertia ρc² (N): the
    /// contact boundaries are recovered with the effective tension N − ρc²λ of the free
    /// spans (docs/fem-drive.md §12) and the summary recomputed.
    pub fn with_transport_inertia(mut self, rho_c2: f64) -> Self {
        self.transport = (rho_c2 != 0.0).then_some(rho_c2);
        if self.params.penalty.is_some() && self.params.bending_stiffness.is_none() {
            self.zones = [self.recovered_zone(Pulley::Driver), self.recovered_zone(Pulley::Driven)];
        }
        self.summary = self.compute_summary();
        self
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The term parameters of the converged state.
    pub fn params(&self) -> &TermParams {
        &self.params
    }

    /// Contact intervals of γ < 0 found per pulley (driver, driven): 1 for a clean
    /// solution (0: no contact).
    pub fn contact_intervals(&self) -> [usize; 2] {
        [0, 1].map(|k| self.zones[k].map_or(0, |z| z.intervals))
    }

    /// The recovered contact zone of a pulley (the one the summary and the contact
    /// state use).
    pub fn zone(&self, pulley: Pulley) -> Option<ContactZone> {
        match pulley {
            Pulley::Driver => self.zones[0],
            Pulley::Driven => self.zones[1],
        }
    }

    fn context(&self, e: usize) -> ElementContext {
        // the stored local unknowns are already effective (augmented map applied)
        ElementContext { geometry: self.mesh.elements()[e], contour: *self.mesh.contour(), params: self.params, augmented: [false; 2] }
    }

    /// The fields S, ∂σS, ν, ∂σν, ∂²σν of element e at ξ.
    #[inline]
    fn point(&self, e: usize, xi: f64) -> PointFields<f64> {
        self.context(e).layout_fields(self.layout, &self.local[e], xi)
    }

    /// Element, its context and the fields at σ.
    fn at(&self, sigma: f64) -> (ElementContext, PointFields<f64>) {
        let (e, xi) = self.mesh.locate(sigma);
        (self.context(e), self.point(e, xi))
    }

    /// The element's field layout.
    pub fn layout(&self) -> ElementLayout {
        self.layout
    }

    /// The element.
    pub fn kernel(&self) -> &Arc<K> {
        &self.kernel
    }

    /// Value, ∂σ and ∂²σ of `field` at σ (wrapped); `None` if the element's layout does
    /// not carry the field (θ of a string). For S without the per-loop offset.
    pub fn field(&self, field: Field, sigma: f64) -> Option<[f64; 3]> {
        let f = self.layout.position(field)?;
        Some(self.one_sided_field(f, sigma, false))
    }

    /// Value, ∂σ and ∂²σ of field number `field` of the layout at σ from one side (as
    /// [`Self::one_sided_fields`]).
    pub fn one_sided_field(&self, field: usize, sigma: f64, left: bool) -> [f64; 3] {
        let (e, xi) = if left { self.mesh.locate_left(sigma) } else { self.mesh.locate(sigma) };
        self.context(e).field(self.layout, &self.local[e], field, xi)
    }

    /// Fields S, ∂σS, ν, ∂σν at σ (wrapped; S without the per-loop offset).
    pub fn fields(&self, sigma: f64) -> PointFields<f64> {
        self.at(sigma).1
    }

    /// Fields at σ from one side: `left` = the element ending at σ if σ is a node (the
    /// slopes differ at a region transition), else the element containing σ.
    pub fn one_sided_fields(&self, sigma: f64, left: bool) -> PointFields<f64> {
        let (e, xi) = if left { self.mesh.locate_left(sigma) } else { self.mesh.locate(sigma) };
        self.point(e, xi)
    }

    /// Belt length L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Axial force recovered from the strain rule's points, interpolated (see the
    /// view's `axial_force`), N.
    pub fn recovered_axial_force(&self, sigma: f64) -> f64 {
        let (e, xi) = self.mesh.locate(sigma);
        let el = self.context(e);
        let pts = self.kernel.rules().strain.points();
        let values: Vec<(f64, f64)> = pts.iter().map(|&(x, _)| (x, self.kernel.axial_force_at(&el, &self.local[e], x))).collect();
        lagrange(&values, xi)
    }

    /// Stretch λ at σ.
    pub fn stretch(&self, sigma: f64) -> f64 {
        let (el, p) = self.at(sigma);
        el.stretch(&p)
    }

    /// Gap γ at σ (None where no pulley can be reached), m.
    pub fn gap(&self, sigma: f64) -> Option<f64> {
        let (el, p) = self.at(sigma);
        el.gap(&p)
    }

    /// The frictionless invariant E = N + N²/(2EA) − ρ g y at σ (S6), N; `None` without
    /// gravity.
    pub fn invariant(&self, sigma: f64) -> Option<f64> {
        let w = self.params.weight?;
        let n = self.axial_force(sigma);
        let y = self.position(sigma)[1];
        Some(n + n * n / (2.0 * self.params.axial_stiffness) - w * y)
    }

    /// Largest penetration max(−γ) at the integration points of the contact rule and the
    /// nodes, m (0 if the belt does not penetrate anywhere).
    pub fn max_penetration(&self) -> f64 {
        let rule = self.kernel.rules().contact;
        let mut m: f64 = 0.0;
        for e in 0..self.mesh.len() {
            let el = self.context(e);
            for xi in rule.points().iter().map(|p| p.0).chain([-1.0, 1.0]) {
                if let Some(g) = el.gap(&self.point(e, xi)) {
                    m = m.max(-g);
                }
            }
        }
        m
    }

    /// Smallest axial force at the strain rule's points and the nodes (N from the law at
    /// the stretch there, unrecovered), with its σ.
    pub fn min_axial_force(&self) -> (f64, f64) {
        let rule = self.kernel.rules().strain;
        let mut best = (0.0, f64::INFINITY);
        for e in 0..self.mesh.len() {
            let el = self.context(e);
            for xi in rule.points().iter().map(|p| p.0).chain([-1.0, 1.0]) {
                let n = self.kernel.axial_force_at(&el, &self.local[e], xi);
                if n < best.1 {
                    best = (el.sigma(xi), n);
                }
            }
        }
        best
    }

    /// The σ-window (start, end) where the gap to `pulley` is defined — its arc ± R,
    /// unwrapped — and the contour length L_c, m.
    fn contact_window(&self, pulley: Pulley) -> (f64, f64, f64) {
        let c = self.mesh.contour();
        let arc = match pulley {
            Pulley::Driven => Region::DrivenArc,
            Pulley::Driver => Region::DriverArc,
        };
        let (a, b) = c.region_bounds(arc);
        (a - c.radius(), b + c.radius(), c.length())
    }

    /// The contact zone of a pulley: the hull of {γ < 0} in the σ-window where the gap
    /// to that pulley is defined (its arc and the span parts with |x − x_k| < R),
    /// boundaries by bisection on the interpolant between scan points (not snapped to
    /// nodes). `None` if the belt does not touch the pulley.
    pub fn contact_zone(&self, pulley: Pulley) -> Option<ContactZone> {
        let (w0, w1, l) = self.contact_window(pulley);
        // elements overlapping the window, unwrapped (the driver's window runs past L_c)
        let mut parts: Vec<(f64, usize, f64)> = Vec::new(); // (start, element, offset)
        for (e, g) in self.mesh.elements().iter().enumerate() {
            for off in [-l, 0.0, l] {
                let (sa, sb) = (g.sigma_a + off, g.sigma_a + g.h + off);
                if sb > w0 && sa < w1 {
                    parts.push((sa, e, off));
                }
            }
        }
        parts.sort_by(|x, y| x.0.total_cmp(&y.0));
        // sign changes of γ (γ undefined = free); at the window edges |x − x_k| = R, no
        // contact is possible, so the scan starts outside contact
        let mut events: Vec<(f64, bool)> = Vec::new(); // (σ unwrapped, entering contact?)
        for &(_, e, off) in &parts {
            let el = self.context(e);
            let gap_at = |xi: f64| -> f64 { el.gap(&self.point(e, xi)).unwrap_or(f64::INFINITY) };
            let mut xi_prev = -1.0;
            let mut g_prev = gap_at(-1.0);
            for j in 1..=GAP_SCAN {
                let xi = -1.0 + 2.0 * j as f64 / GAP_SCAN as f64;
                let g = gap_at(xi);
                if (g < 0.0) != (g_prev < 0.0) {
                    let root = bisect(&gap_at, xi_prev, xi);
                    let sigma = el.sigma(root) + off;
                    if sigma > w0 && sigma < w1 {
                        events.push((sigma, g < 0.0));
                    }
                }
                xi_prev = xi;
                g_prev = g;
            }
        }
        let entries: Vec<f64> = events.iter().filter(|ev| ev.1).map(|ev| ev.0).collect();
        let exits: Vec<f64> = events.iter().filter(|ev| !ev.1).map(|ev| ev.0).collect();
        let mut sigma_start = entries.first().copied()?;
        let mut sigma_end = exits.iter().rev().find(|&&s| s > sigma_start).copied().unwrap_or(w1);
        if self.kernel.contact_multipliers().is_some() {
            // the augmented Lagrangian: the gap in the zone is zero up to round-off of
            // either sign, its sign changes there are no edges; the edge is where the
            // free side's gap touches zero
            sigma_start = self.touching(sigma_start, 1.0).unwrap_or(sigma_start);
            sigma_end = self.touching(sigma_end, -1.0).unwrap_or(sigma_end);
            // …which places it to a fraction of an element only (the gap's double zero);
            // the zone's force places it to the mesh's resolution of the pressure
            sigma_start = self.force_edge(pulley, sigma_start, 1.0).map_or(sigma_start, |e| e.0);
            sigma_end = self.force_edge(pulley, sigma_end, -1.0).map_or(sigma_end, |e| e.0);
        }
        Some(ContactZone {
            sigma_start,
            sigma_end,
            angle_start: self.mesh.contour().polar_angle(pulley, self.position(sigma_start)),
            angle_end: self.mesh.contour().polar_angle(pulley, self.position(sigma_end)),
            intervals: entries.len().max(1),
            recovered: false,
            edge_force_start: None,
            edge_force_end: None,
        })
    }

    /// The contact edge of the augmented-Lagrangian solution near the crossing `sigma`
    /// (unwrapped; `inward` = +1 at an entry, −1 at an exit; docs/fem-cosserat.md
    /// §12.5). In the zone the gap is zero up to round-off of either sign, so its sign
    /// changes there are no edges; beside the edge the free side's gap touches zero,
    /// γ ≈ p₀(σ − σ_b)²/(2b₂) with the edge pressure p₀ (the Cosserat rod's pressure step
    /// is a jump of γ″), so σ_b is taken as the vertex of the parabola through γ at 2, 3
    /// and 4 quarters of the local element length outside `sigma` — clear of the zone's
    /// round-off, but biased by the gap's cubic term there (§12.5: the contact edges of
    /// this reading are 2e-3 off at 128 elements, 5e-4 at 256). `None` where that
    /// parabola does not open upwards.
    fn touching(&self, sigma: f64, inward: f64) -> Option<f64> {
        let l = self.mesh.contour().length();
        let (e, _) = self.mesh.locate(sigma.rem_euclid(l));
        let d = 0.25 * self.mesh.elements()[e].h;
        let gap = |x: f64| {
            let (e, xi) = self.mesh.locate(x.rem_euclid(l));
            self.context(e).gap(&self.point(e, xi))
        };
        let x2 = sigma - inward * 3.0 * d;
        let (y1, y2, y3) = (gap(x2 - d)?, gap(x2)?, gap(x2 + d)?);
        let curvature = y3 - 2.0 * y2 + y1;
        let vertex = x2 - d * (y3 - y1) / (2.0 * curvature);
        (curvature > 0.0 && vertex.is_finite() && (vertex - sigma).abs() < 4.0 * d).then_some(vertex)
    }

    /// The contact edge of the augmented-Lagrangian solution from its contact forces
    /// (docs/fem-cosserat.md §12.5), near the estimate `sigma0` (unwrapped; `inward` =
    /// +1 at an entry, −1 at an exit). G(x), the contact force ⟨λ − Pγ⟩₊ applied from the
    /// free side up to x (the points of [`Self::contact_forces`]), is taken at the
    /// [`FORCE_EDGE_NODES`] nodes that follow the node nearest to `sigma0` inwards; the
    /// edge is the root of the polynomial through them next to `sigma0` — where the zone's
    /// force starts: a simple zero with the edge pressure as slope, where the gap has a
    /// double zero (γ ≈ p₀x²/(2b₂)) that places the edge to a fraction of an element
    /// only — and the edge pressure per unit contour length is the polynomial's slope
    /// there. The nearest node is left out: on a mesh fitted to the edge G vanishes
    /// there by construction (no loaded point outside it) and would pin the root to the
    /// node; without it a misplaced edge node shows as the surplus (or missing) force the
    /// first element inside has to carry, which moves the root off the node. Returns
    /// (σ_b, p_σ); `None` without a penalty, with too few nodes inside, or where the
    /// polynomial has no rising root between the first node inside and one element
    /// outward of the nearest node ([`rising_root`]).
    fn force_edge(&self, pulley: Pulley, sigma0: f64, inward: f64) -> Option<(f64, f64)> {
        self.params.penalty?;
        let (nodes, g_at) = self.inward_forces(pulley, sigma0, inward);
        let nearest = nodes.iter().copied().min_by(|x, y| x.abs().total_cmp(&y.abs()))?;
        let floor = 1e-12 * self.mesh.contour().length();
        let n = FORCE_EDGE_NODES;
        let x: Vec<f64> = nodes.into_iter().filter(|d| *d > nearest + floor).take(n).collect();
        if x.len() < n {
            return None;
        }
        let pts: Vec<(f64, f64)> = x.iter().map(|&xj| (xj, g_at(xj))).collect();
        // the edge lies between the nearest node and the first one inside, or at most
        // one element beyond the nearest node outward: a root further out is an
        // extrapolation of the fit, not an edge
        let (t, p) = rising_root(&pts, nearest - (x[0] - nearest))?;
        Some((sigma0 + inward * t, p))
    }

    /// The nodes' distances inward from σ (`inward` = +1 at an entry, −1 at an exit),
    /// all of them, ascending, each node once — unwrapped, as σ, into the σ-window where
    /// the gap to `pulley` is defined — and G(x), the sum of the contact forces
    /// ([`Self::contact_forces`]) at points less than x inward from σ: the force applied
    /// from the free side up to x (the zone is one interval).
    fn inward_forces(&self, pulley: Pulley, sigma: f64, inward: f64) -> (Vec<f64>, impl Fn(f64) -> f64) {
        let forces = self.contact_forces(pulley);
        let l = self.mesh.contour().length();
        let (w0, w1, _) = self.contact_window(pulley);
        let unwrap = |x: f64| [x - l, x, x + l].into_iter().find(|y| *y > w0 && *y < w1).unwrap_or(x);
        let b = unwrap(sigma);
        let mut nodes: Vec<f64> = self.mesh.node_sigmas().iter().map(|&n| inward * (unwrap(n) - b)).collect();
        nodes.sort_by(f64::total_cmp);
        nodes.dedup();
        let distances: Vec<(f64, f64)> = forces.into_iter().map(|(s, f)| (inward * (s - b), f)).collect();
        // a point on x itself (a rule with points on the nodes) counts half: G(x) is then
        // the mean of its limits from both sides, as the polynomial through it is
        (nodes, move |x: f64| distances.iter().map(|f| if f.0 < x { f.1 } else if f.0 == x { 0.5 * f.1 } else { 0.0 }).sum::<f64>())
    }

    /// The contact zone with both boundaries recovered from the free spans (tangency
    /// construction, docs/fem-string.md §10); a boundary that cannot be recovered keeps
    /// its raw zero crossing of γ.
    pub fn recovered_zone(&self, pulley: Pulley) -> Option<ContactZone> {
        let raw = self.contact_zone(pulley)?;
        let mut z = raw;
        let mut both = true;
        match self.tangency(pulley, raw.sigma_start, false) {
            Some((sigma, angle)) => {
                z.sigma_start = sigma;
                z.angle_start = angle;
            }
            None => both = false,
        }
        match self.tangency(pulley, raw.sigma_end, true) {
            Some((sigma, angle)) => {
                z.sigma_end = sigma;
                z.angle_end = angle;
            }
            None => both = false,
        }
        if z.sigma_end <= z.sigma_start {
            return Some(raw);
        }
        z.recovered = both;
        Some(z)
    }

    /// Tangency recovery of one contact boundary near the raw boundary σ_b
    /// (docs/fem-string.md §10). At the anchor — the middle of the span on the free side
    /// of the boundary — the FE belt has position r_P, unit tangent t_P and the force
    /// F_P = F_x t_P / t_x from the span's horizontal force F_x (constant in a free
    /// span); the free belt is continued from there towards the pulley with the string's
    /// own equilibrium (S2): F(s) = F_P + ρ g (s − s_P) e_y, r(s) = r_P + ∫ λ F/|F| ds,
    /// λ = 1 + |F|/EA, and the boundary is the point where it is tangent to the pulley,
    /// (r − C)·F = 0. Returns the (unwrapped) σ of the contour normal through that point
    /// and its polar angle; `None` if the anchor is not clearly free or no tangency is
    /// found within reach.
    fn tangency(&self, pulley: Pulley, sigma_b: f64, leaving: bool) -> Option<(f64, f64)> {
        let c = self.mesh.contour();
        let centre = c.pulley_centre(pulley);
        let (eb, _) = self.mesh.locate(sigma_b);
        let h = self.mesh.elements()[eb].h;
        let dir = if leaving { 1.0 } else { -1.0 };
        // the free span on the free side of the boundary, and the anchor in its middle
        let mut region = c.region(sigma_b);
        if region.is_polar() {
            let (a, b) = c.region_bounds(region);
            region = c.region(if leaving { b + 1e-9 } else { a - 1e-9 });
        }
        let (sa, sb) = c.region_bounds(region);
        let span = sb - sa;
        let d_a = 0.5 * span;
        let anchor = if leaving { sa + d_a } else { sb - d_a };
        // unwrap the anchor next to σ_b
        let l = c.length();
        let off = (anchor - c.wrap(sigma_b)).rem_euclid(l);
        let off = if off > 0.5 * l { off - l } else { off };
        let sigma_p = sigma_b + off;
        let distance = off.abs();
        if dir * off <= 0.0 {
            return None;
        }
        let (e, xi) = self.mesh.locate(sigma_p);
        let el = self.context(e);
        let p = self.point(e, xi);
        let [r, r1, _] = el.curve_at(&p);
        let speed = r1[0].hypot(r1[1]);
        let ea = self.params.axial_stiffness;
        let t = [r1[0] / speed, r1[1] / speed];
        // the force at the anchor from the span's horizontal force F_x (constant in a
        // free span, (S2)), which the FE gives most accurately in the middle of the span,
        // far from the contact edges; the local N_P only where the belt is too steep
        // with steady transport the span carries the effective tension N − ρc²λ
        let rc2 = self.transport.unwrap_or(0.0);
        let n_local = self.recovered_axial_force(sigma_p) - rc2 * self.stretch(sigma_p);
        let f_p = match self.span_horizontal_force(sigma_p, dir) {
            Some(fx) if t[0].abs() > 0.1 && fx * t[0] > 0.0 => [fx, fx * t[1] / t[0]],
            _ => [n_local * t[0], n_local * t[1]],
        };
        let n_p = f_p[0].hypot(f_p[1]);
        if !(speed > 0.0 && n_p > 0.0 && n_p.is_finite()) {
            return None;
        }
        let w = self.params.weight.unwrap_or(0.0);
        // force and position at unstretched arclength u from the anchor (u < 0: back)
        let force = |u: f64| [f_p[0], f_p[1] + w * u];
        let position = |u: f64| -> [f64; 2] {
            // 8-point Gauss–Legendre of the smooth integrand λ F/|F| on [0, u]
            let mut acc = [0.0, 0.0];
            for &(x, wt) in GL8.iter() {
                let f = force(0.5 * u * (1.0 + x));
                let nf = f[0].hypot(f[1]);
                // N = T̃ + ρc²λ and λ = 1 + N/EA give λ = (1 + T̃/EA)/(1 − ρc²/EA)
                let lam = (1.0 + nf / ea) / (1.0 - rc2 / ea);
                acc[0] += wt * lam * f[0] / nf;
                acc[1] += wt * lam * f[1] / nf;
            }
            [r[0] + 0.5 * u * acc[0], r[1] + 0.5 * u * acc[1]]
        };
        let g = |u: f64| -> f64 {
            let q = position(u);
            let f = force(u);
            ((q[0] - centre[0]) * f[0] + (q[1] - centre[1]) * f[1]) / f[0].hypot(f[1])
        };
        // on the free side the belt moves away from (leaving) or towards the pulley
        if dir * g(0.0) <= 0.0 || g(0.0).is_nan() {
            return None;
        }
        // search up to 1.5× the FE's own unstretched length from the anchor to the raw
        // boundary (the belt can be much longer than its σ-range where it hangs far from
        // an arc)
        let s_length = (self.fields(sigma_p).s - self.fields(sigma_b).s).rem_euclid(self.length);
        let s_length = if s_length > 0.5 * self.length { self.length - s_length } else { s_length };
        let reach = 1.5 * s_length.max(distance / p.ds.max(1e-12)) + 3.0 * h;
        let samples = 256;
        let mut u_prev = 0.0;
        for k in 1..=samples {
            let u = -dir * reach * k as f64 / samples as f64;
            if dir * g(u) <= 0.0 {
                let root = bisect(&g, u_prev, u);
                let q = position(root);
                let (sigma, _) = c.sigma_nu(q);
                let l = c.length();
                let d = (sigma - c.wrap(sigma_b)).rem_euclid(l);
                let d = if d > 0.5 * l { d - l } else { d };
                return Some((sigma_b + d, c.polar_angle(pulley, q)));
            }
            u_prev = u;
        }
        None
    }

    /// The horizontal force F_x = N t_x of the span that σ lies on (or, on an arc, of
    /// the span next to it in direction `dir`), averaged over the middle half of the
    /// span (32 points); with steady transport the effective tension (N − ρc²λ) t_x. `None` without gravity-free span data (never for this model).
    fn span_horizontal_force(&self, sigma: f64, dir: f64) -> Option<f64> {
        let c = self.mesh.contour();
        let mut region = c.region(sigma);
        if region.is_polar() {
            let (a, b) = c.region_bounds(region);
            region = c.region(if dir > 0.0 { b + 1e-9 } else { a - 1e-9 });
        }
        let (a, b) = c.region_bounds(region);
        let samples = 32;
        let mut sum = 0.0;
        for k in 0..samples {
            let s = a + (b - a) * (0.25 + 0.5 * (k as f64 + 0.5) / samples as f64);
            let (e, xi) = self.mesh.locate(s);
            let [_, r1, _] = self.context(e).curve_at(&self.point(e, xi));
            let speed = r1[0].hypot(r1[1]);
            let n = self.recovered_axial_force(s) - self.transport.map_or(0.0, |rc2| rc2 * self.stretch(s));
            sum += n * r1[0] / speed;
        }
        let fx = sum / samples as f64;
        fx.is_finite().then_some(fx)
    }

    /// σ (wrapped to [0, L_c)) of the contact boundaries: driver start, driver end,
    /// driven start, driven end (those that exist).
    /// For a Cosserat rod these are the zero crossings of the gap — the kinks of the
    /// discrete penalty solution the mesh is fitted to — not the edges of its zone,
    /// which lie the penalty layer inside them ([`Self::loaded_zone`]).
    pub fn contact_boundaries(&self) -> Vec<f64> {
        self.contact_edges().into_iter().flat_map(|(_, start, end)| [start, end]).collect()
    }

    /// The contact boundaries of [`Self::contact_boundaries`] per zone: (pulley, σ_start,
    /// σ_end), driver first.
    pub fn contact_edges(&self) -> Vec<(Pulley, f64, f64)> {
        let c = self.mesh.contour();
        let shift = if self.kernel.theory() == drive::scene::Theory::Cosserat { self.penalty_layer().unwrap_or(0.0) } else { 0.0 };
        [Pulley::Driver, Pulley::Driven].into_iter().zip(self.zones).filter_map(|(p, z)| z.map(|z| (p, c.wrap(z.sigma_start - shift), c.wrap(z.sigma_end + shift)))).collect()
    }

    fn pulley_summary(&self, pulley: Pulley) -> PulleySummary {
        // the Cosserat rod has no concentrated edge forces (its pressure is finite)
        let cosserat = self.kernel.theory() == drive::scene::Theory::Cosserat;
        let rod = self.params.bending_stiffness.is_some() && !cosserat;
        match self.zone(pulley) {
            None => PulleySummary {
                contact_arc: Some(0.0),
                edge_force_start: rod.then_some(0.0),
                edge_force_end: rod.then_some(0.0),
                ..Default::default()
            },
            Some(z) => {
                let mut ps = PulleySummary {
                    contact_arc: Some((z.angle_start - z.angle_end).rem_euclid(2.0 * PI)),
                    contact_start: Some(z.angle_start),
                    contact_end: Some(z.angle_end),
                    edge_force_start: z.edge_force_start,
                    edge_force_end: z.edge_force_end,
                    // its finite pressure just inside the zone instead (issue 13)
                    edge_pressure_start: cosserat.then(|| self.edge_pressure(pulley, z.sigma_start, 1.0)).flatten(),
                    edge_pressure_end: cosserat.then(|| self.edge_pressure(pulley, z.sigma_end, -1.0)).flatten(),
                    ..Default::default()
                };
                if cosserat {
                    self.cosserat_zone(z.sigma_start, z.sigma_end).fill(&mut ps);
                }
                ps
            }
        }
    }

    /// The discrete contact forces of a pulley: for every point of the contact rule in
    /// the σ-window where the gap to that pulley is defined (its arc ± R), the unwrapped
    /// σ and the force w·(h/2)·P⟨−γ⟩ the energy applies there (N), in σ order — the
    /// point forces the penalty term actually exerts, so their sums are consistent with
    /// the discrete equilibrium.
    pub fn contact_forces(&self, pulley: Pulley) -> Vec<(f64, f64)> {
        let Some(penalty) = self.params.penalty else { return Vec::new() };
        let (w0, w1, l) = self.contact_window(pulley);
        let rule = self.kernel.rules().contact;
        let mut out = Vec::new();
        for (e, g) in self.mesh.elements().iter().enumerate() {
            for off in [-l, 0.0, l] {
                let (sa, sb) = (g.sigma_a + off, g.sigma_a + g.h + off);
                if sb <= w0 || sa >= w1 {
                    continue;
                }
                let el = self.context(e);
                for &(xi, wt) in rule.points() {
                    let sigma = el.sigma(xi) + off;
                    if sigma <= w0 || sigma >= w1 {
                        continue;
                    }
                    let gap = el.gap(&self.point(e, xi));
                    out.push((sigma, wt * el.jacobian() * self.kernel.contact_traction(penalty, el.sigma(xi), gap)));
                }
            }
        }
        out.sort_by(|x, y| x.0.total_cmp(&y.0));
        // a node shared by two elements appears twice (Simpson): both halves are forces
        out
    }

    /// One contact edge of a rod (docs/fem-rod.md §5). `sigma0`: the outermost point of
    /// the contact rule that carries a penalty force; `inward`: +1 for an entry (contact
    /// continues in +σ), −1 for an exit.
    ///
    /// **Location.** At the edge the moment is continuous and equals the arc's
    /// −EIλ/R (R3); on the free side f(σ) = M(σ) + EIλ(σ)/R > 0 grows linearly with the
    /// distance (slope λ P_edge, the shear jump). Scanning from 8 elements on the free
    /// side towards the pulley, the first σ_ε with f = ε = 0.02 EIλ/R is found by
    /// bisection, and the edge is extrapolated linearly, σ_b = σ_ε + inward ε/|f′|, with
    /// f′ from a difference over h/4 on the free side (the remainder is O(Δ²/ℓ_b) with
    /// Δ = ε/(λ P_edge) far below ℓ_b = √(EI/N)).
    ///
    /// **Force.** By statics of the free span (R2), Q′ = ρ g e_y: the section force at
    /// the edge is Q_b = Q_m + ρ g (s_b − s_m) e_y with Q_m = N t + V n at the middle of
    /// the free span (where the FE's N and V are accurate and V ≈ 0) and s the material
    /// coordinate. With n_r the pulley normal at the edge (= the rod's left normal) and
    /// V_arc of (R3, R4), (R6) gives F = Q_b·n_r − V_arc at an entry and
    /// F = V_arc − Q_b·n_r at an exit. Returns (σ_b, F).
    fn rod_edge(&self, pulley: Pulley, sigma0: f64, inward: f64) -> Option<(f64, f64)> {
        let ei = self.params.bending_stiffness?;
        let c = *self.mesh.contour();
        let r = c.radius();
        let (e0, _) = self.mesh.locate(sigma0);
        let h = self.mesh.elements()[e0].h;
        let f = |s: f64| -> f64 {
            let m = self.rod_resultants(s).map_or(f64::NAN, |x| x.0);
            m + ei * self.stretch(s) / r
        };
        let eps = 0.02 * ei / r;
        let start = sigma0 - inward * 8.0 * h;
        let step = h / 16.0;
        let mut prev = start;
        if f(prev).is_nan() || f(prev) <= eps {
            return None;
        }
        let mut hit = None;
        for k in 1..=(12 * 16) {
            let s = start + inward * step * k as f64;
            if f(s) <= eps {
                hit = Some((prev, s));
                break;
            }
            prev = s;
        }
        let (mut a, mut b) = hit?;
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if f(m) > eps {
                a = m;
            } else {
                b = m;
            }
        }
        let s_eps = 0.5 * (a + b);
        let delta = 0.25 * h;
        let slope = (f(s_eps - inward * delta) - eps) / delta;
        if slope.is_nan() || slope <= 0.0 {
            return None;
        }
        let sigma_b = s_eps + inward * eps / slope;
        // the free span and its middle (unwrapped next to σ_b)
        let l = c.length();
        let (a_arc, b_arc) = c.region_bounds(match pulley {
            Pulley::Driven => Region::DrivenArc,
            Pulley::Driver => Region::DriverArc,
        });
        let span = c.region(if inward > 0.0 { a_arc - 1e-9 } else { b_arc + 1e-9 });
        let (sa, sb) = c.region_bounds(span);
        let mid = 0.5 * (sa + sb);
        let d = (mid - c.wrap(sigma_b)).rem_euclid(l);
        let sigma_m = sigma_b + if d > 0.5 * l { d - l } else { d };
        let (em, xm) = self.mesh.locate(sigma_m);
        let [_, r1, _] = self.context(em).curve_at(&self.point(em, xm));
        let speed = r1[0].hypot(r1[1]);
        let (t, n) = ([r1[0] / speed, r1[1] / speed], [-r1[1] / speed, r1[0] / speed]);
        let (nm, vm) = (self.axial_force(sigma_m), self.rod_resultants(sigma_m)?.1);
        let w = self.params.weight.unwrap_or(0.0);
        let ds = self.material_coordinate(sigma_b) - self.material_coordinate(sigma_m);
        let q = [nm * t[0] + vm * n[0], nm * t[1] + vm * n[1] + w * ds];
        let centre = c.pulley_centre(pulley);
        let pos = self.position(sigma_b);
        let phi = (pos[1] - centre[1]).atan2(pos[0] - centre[0]);
        let nr = [phi.cos(), phi.sin()];
        let ea = self.params.axial_stiffness;
        let lambda = self.stretch(sigma_b);
        let v_arc = -ei * w * phi.cos() / (r * ea * lambda * (1.0 + ei / (ea * r * r)));
        let v_span = q[0] * nr[0] + q[1] * nr[1];
        let force = inward * (v_span - v_arc);
        (force.is_finite() && sigma_b.is_finite()).then_some((sigma_b, force))
    }

    /// The contact zone of a Cosserat rod (docs/fem-cosserat.md §9): the zero crossings
    /// of the gap ([`Self::contact_zone`]), each moved into the zone by the penalty
    /// layer ℓ_P of [`Self::penalty_layer`] — the true edge (pressure step, tangent
    /// departure) lies ℓ_P inside the crossing of the penalty-regularised solution.
    /// There is no concentrated edge force.
    pub fn loaded_zone(&self, pulley: Pulley) -> Option<ContactZone> {
        let z = self.contact_zone(pulley)?;
        let shift = self.penalty_layer().unwrap_or(0.0);
        self.zone_between(pulley, z.sigma_start + shift, z.sigma_end - shift, false, [None, None])
    }

    /// P⟨−γ⟩ of element `e` at ξ (N per unit contour length): the values at the contact
    /// rule's points (where the formulation applies the penalty) interpolated, or
    /// extrapolated, by their Lagrange polynomial.
    fn penalty_pressure(&self, penalty: f64, e: usize, xi: f64) -> f64 {
        let el = self.context(e);
        let values: Vec<(f64, f64)> = self
            .kernel
            .rules()
            .contact
            .points()
            .iter()
            .map(|&(x, _)| (x, self.kernel.contact_traction(penalty, el.sigma(x), el.gap(&self.point(e, x)))))
            .collect();
        lagrange(&values, xi)
    }

    /// The edge pressure of a Cosserat rod's contact zone on `pulley` (issue 13: "contact
    /// pressure per unit reference length just inside the zone at its first/last point";
    /// docs/fem-cosserat.md §12.5), at the zone edge σ_b ([`Self::loaded_zone`];
    /// `inward` = +1 at an entry, −1 at an exit). The penalty's pointwise pressure is no
    /// measure of it (the cubic ν is pressed in at the contact rule's points only and
    /// oscillates from node to node), its sums are: G(x), the contact force the penalty
    /// applies between the edge's gap crossing and x (the points of
    /// [`Self::contact_forces`], the penalty layer's included — it carries the force of
    /// the limit solution between its edge σ_b and x), is taken at σ_b (G = 0) and at the
    /// next three nodes inside; the edge pressure per unit contour length is G′(σ_b) of
    /// the cubic through these four points (the pressure that is quadratic over the
    /// three elements and has their forces), per unit material length p_σ/∂σS.
    /// `None` without a penalty, fewer than three nodes inside the zone, or for a
    /// non-positive or non-finite value.
    pub fn edge_pressure(&self, pulley: Pulley, sigma_b: f64, inward: f64) -> Option<f64> {
        self.params.penalty?;
        if self.kernel.contact_multipliers().is_some() {
            // the augmented Lagrangian: G′ at the edge the zone's force locates
            let (e, xi) = if inward < 0.0 { self.mesh.locate_left(sigma_b) } else { self.mesh.locate(sigma_b) };
            let ds = self.context(e).field(self.layout, &self.local[e], 0, xi)[1];
            return self.force_edge(pulley, sigma_b, inward).map(|(_, p)| p / ds).filter(|p| p.is_finite());
        }
        let (nodes, g_at) = self.inward_forces(pulley, sigma_b, inward);
        let floor = (1e-12 * self.mesh.contour().length()).max(EDGE_LAYER_SKIP * self.penalty_layer().unwrap_or(0.0));
        let inside: Vec<f64> = nodes.into_iter().filter(|d| *d > floor).collect();
        let x: [f64; 3] = inside.get(..3)?.try_into().ok()?;
        let g = x.map(&g_at);
        // G′(0) of the cubic through (0, 0), (x_j, G_j): Σ_j G_j L_j′(0), L_j′(0) =
        // Π_{m≠j} (−x_m) / (x_j Π_{m≠j} (x_j − x_m)) over m among the three inside
        let slope: f64 = (0..3)
            .map(|j| {
                let others = (0..3).filter(|&m| m != j);
                let num: f64 = others.clone().map(|m| -x[m]).product();
                let den: f64 = x[j] * others.map(|m| x[j] - x[m]).product::<f64>();
                g[j] * num / den
            })
            .sum();
        let (e, xi) = if inward < 0.0 { self.mesh.locate_left(sigma_b) } else { self.mesh.locate(sigma_b) };
        let ds = self.context(e).field(self.layout, &self.local[e], 0, xi)[1];
        let per_material = slope / ds;
        (per_material.is_finite() && per_material > 0.0).then_some(per_material)
    }

    /// Spec §2.6/§3.7's Cosserat quantities of the contact zone [σ_start, σ_end]
    /// (unwrapped, σ_start < σ_end; docs/fem-cosserat.md §12.10):
    /// - `pressure_min`: the smallest element-mean pressure F_e/(h_e ∂σS) over the
    ///   elements inside the zone (F_e the contact force the element's rule applies),
    ///   the penalty layer's [`EDGE_LAYER_SKIP`] ℓ_P at each edge left out (there the
    ///   regularised pressure falls to 0, the limit's does not). The pointwise penalty
    ///   pressure oscillates from node to node; the element's force does not, and its
    ///   mean is the pressure at the element's middle to O(h²). `None` if no element
    ///   lies inside.
    /// - `shear_strain_max`: max |Γ₂| at the zone's edges and 8 points per element
    ///   inside.
    /// - `moment_start`, `moment_end`: M at the edges.
    pub fn cosserat_zone(&self, sigma_start: f64, sigma_end: f64) -> CosseratZone {
        let c = *self.mesh.contour();
        let l = c.length();
        let skip = EDGE_LAYER_SKIP * self.penalty_layer().unwrap_or(0.0);
        let (inner_a, inner_b) = (sigma_start + skip, sigma_end - skip);
        let mut pressure_min: Option<f64> = None;
        let mut strain_max: Option<f64> = None;
        let mut strain = |sigma: f64| {
            if let Some(g) = self.shear_strain(c.wrap(sigma)) {
                strain_max = Some(strain_max.map_or(g.abs(), |m: f64| m.max(g.abs())));
            }
        };
        // Γ₂ peaks at a kink on the edge; the regularised solution rounds it off over
        // the penalty layer, between the gap's crossings ℓ_P outside the zone
        let layer = self.penalty_layer().unwrap_or(0.0);
        let (outer_a, outer_b) = (sigma_start - layer, sigma_end + layer);
        strain(outer_a);
        strain(outer_b);
        let rule = self.kernel.rules().contact;
        for (e, g) in self.mesh.elements().iter().enumerate() {
            for off in [-l, 0.0, l] {
                let (sa, sb) = (g.sigma_a + off, g.sigma_a + g.h + off);
                if sb <= outer_a || sa >= outer_b {
                    continue;
                }
                for j in 0..8 {
                    let sigma = sa + (sb - sa) * (j as f64 + 0.5) / 8.0;
                    if sigma > outer_a && sigma < outer_b {
                        strain(sigma);
                    }
                }
                let Some(penalty) = self.params.penalty else { continue };
                if sa < inner_a || sb > inner_b {
                    continue;
                }
                let el = self.context(e);
                let force: f64 = rule.points().iter().map(|&(xi, wt)| wt * el.jacobian() * self.kernel.contact_traction(penalty, el.sigma(xi), el.gap(&self.point(e, xi)))).sum();
                let ds = el.field(self.layout, &self.local[e], 0, 0.0)[1];
                let p = force / (g.h * ds);
                if p.is_finite() {
                    pressure_min = Some(pressure_min.map_or(p, |m| m.min(p)));
                }
            }
        }
        let moment = |sigma: f64| self.rod_resultants(c.wrap(sigma)).map(|x| x.0);
        CosseratZone { pressure_min, shear_strain_max: strain_max, moment_start: moment(sigma_start), moment_end: moment(sigma_end) }
    }

    /// The decay length ℓ_P = 1/k of the penalty's own mode at a contact edge of a
    /// Cosserat rod on the penalty foundation P (docs/fem-cosserat.md §9): the section
    /// rotation φ and the gap w of a ∝ e^{kx} solve a φ″ + b₂(w′ − φ) = 0,
    /// b₂(w″ − φ′) = P w, so a b₂ k⁴ − P a k² + P b₂ = 0 and
    /// k² = (P a + √(P²a² − 4 a b₂² P))/(2 a b₂) (≈ P/b₂ for ℓ_P ≪ √(a/b₂)). With a
    /// constant curvature jump at the edge the gap crosses zero ℓ_P outside the edge of
    /// the limit P → ∞. `None` without a penalty, a, b₂, or where the roots are complex
    /// (P a < 4 b₂²: the bending-dominated regime, the shear rod's Kirchhoff limit,
    /// where this shift does not apply).
    pub fn penalty_layer(&self) -> Option<f64> {
        if self.kernel.contact_multipliers().is_some() {
            // the augmented Lagrangian closes the gap in the zone: no penalty layer
            return None;
        }
        let (p, a, b2) = (self.params.penalty?, self.params.bending_stiffness?, self.kernel.shear_stiffness()?);
        let disc = p * p * a * a - 4.0 * a * b2 * b2 * p;
        (disc > 0.0).then(|| ((2.0 * a * b2) / (p * a + disc.sqrt())).sqrt())
    }

    /// The one-interval contact zone on `pulley` from σ_start to σ_end (`None` if empty),
    /// with its polar angles and the edge forces at start and end.
    fn zone_between(&self, pulley: Pulley, sigma_start: f64, sigma_end: f64, recovered: bool, [edge_force_start, edge_force_end]: [Option<f64>; 2]) -> Option<ContactZone> {
        if sigma_end <= sigma_start {
            return None;
        }
        let c = self.mesh.contour();
        let angle = |s: f64| c.polar_angle(pulley, self.position(s));
        Some(ContactZone { sigma_start, sigma_end, angle_start: angle(sigma_start), angle_end: angle(sigma_end), intervals: 1, recovered, edge_force_start, edge_force_end })
    }

    /// The contact zone of a rod (docs/fem-rod.md §5): both edges located and their
    /// concentrated forces measured by [`Self::rod_edge`]; the raw outermost loaded
    /// points of the contact rule (and no edge force) where that fails.
    pub fn rod_zone(&self, pulley: Pulley) -> Option<ContactZone> {
        let forces = self.contact_forces(pulley);
        let first = forces.iter().find(|f| f.1 > 0.0)?.0;
        let last = forces.iter().rev().find(|f| f.1 > 0.0)?.0;
        let start = self.rod_edge(pulley, first, 1.0);
        let end = self.rod_edge(pulley, last, -1.0);
        let (sigma_start, sigma_end) = (start.map_or(first, |x| x.0), end.map_or(last, |x| x.0));
        self.zone_between(pulley, sigma_start, sigma_end, start.is_some() && end.is_some(), [start.map(|x| x.1), end.map(|x| x.1)])
    }

    /// The penalty-window measure of an edge force (docs/fem-rod.md §5, K11): at the
    /// mesh node nearest to the edge σ_b (a node after contact fitting), the contact
    /// forces the penalty term applies (contact rule's points, w·(h/2)·P⟨−γ⟩) summed over
    /// the 3 elements on each side of that node, minus the distributed part on the
    /// contact side, ∫ p over those 3 elements, with p extrapolated linearly from the
    /// mean pressures of the next two groups of 3 elements. `inward` = +1 at an entry,
    /// −1 at an exit. `None` without a penalty.
    pub fn window_edge_force(&self, sigma_b: f64, inward: f64) -> Option<f64> {
        let penalty = self.params.penalty?;
        let n = self.mesh.len();
        let nodes = self.mesh.node_sigmas();
        let c = self.mesh.contour();
        let w = c.wrap(sigma_b);
        let k = (0..n)
            .min_by(|&a, &b| {
                let da = (nodes[a] - w).abs().min(c.length() - (nodes[a] - w).abs());
                let db = (nodes[b] - w).abs().min(c.length() - (nodes[b] - w).abs());
                da.total_cmp(&db)
            })?;
        let rule = self.kernel.rules().contact;
        let element_force = |e: usize| -> (f64, f64) {
            let el = self.context(e);
            let f: f64 = rule
                .points()
                .iter()
                .map(|&(xi, wt)| {
                    wt * el.jacobian() * self.kernel.contact_traction(penalty, el.sigma(xi), el.gap(&self.point(e, xi)))
                })
                .sum();
            (f, el.geometry.h)
        };
        // element j steps from the node: contact side j = 0, 1, …; free side j = −1, −2, −3
        let elem = |j: i64| -> usize {
            let idx = if inward > 0.0 { k as i64 + j } else { k as i64 - 1 - j };
            idx.rem_euclid(n as i64) as usize
        };
        let group = |from: i64| -> (f64, f64) {
            (from..from + 3).map(|j| element_force(elem(j))).fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
        };
        let (free, _) = group(-3);
        let (fa, la) = group(0);
        let (fb, lb) = group(3);
        let (fc, lc) = group(6);
        let (pb, pc) = (fb / lb, fc / lc);
        let (ca, cb, cc) = (0.5 * la, la + 0.5 * lb, la + lb + 0.5 * lc);
        let pa = pb + (pc - pb) * (ca - cb) / (cc - cb);
        let edge = free + fa - la * pa;
        edge.is_finite().then_some(edge)
    }

    /// Bending moment M = EI θ_σ/∂σS (docs/fem-rod.md K3, K4) and transverse force
    /// V = −∂σM/|∂σr| (K5) in element e at ξ, by a dual number in ξ.
    fn moment_and_shear(&self, e: usize, xi: f64, ei: f64) -> (f64, f64) {
        use num_dual::Dual64;
        let el = self.context(e);
        let q = &self.local[e];
        let x = Dual64::from_re(xi).derivative();
        let (wv, wd, w2) = crate::hermite::weights_generic(x, el.geometry.h);
        let comb = |w: &[Dual64; 4], i: [usize; 4]| w[0] * q[i[0]] + w[1] * q[i[1]] + w[2] * q[i[2]] + w[3] * q[i[3]];
        let (s, nu) = (self.layout.hermite_indices(0), self.layout.hermite_indices(1));
        let p = PointFields { sigma: el.sigma(xi), s: comb(&wv, s), ds: comb(&wd, s), nu: comb(&wv, nu), dnu: comb(&wd, nu), d2nu: comb(&w2, nu) };
        let m = el.curvature(&p) * ei;
        let speed = el.tangent_length(&p).re;
        let dm_dsigma = m.eps * 2.0 / el.geometry.h;
        (m.re, -dm_dsigma / speed)
    }

    /// The Cosserat section moment M = a κ, κ = (∂σψ − α)/∂σs (docs/fem-cosserat.md C2:
    /// the rate of the director angle θ = ϑ_g + ψ, not of the centreline's tangent,
    /// which differs by the rate of the shear angle), and V = −∂σM/|∂σr| from it, in
    /// element e at ξ.
    fn section_moment_and_shear(&self, e: usize, xi: f64, a: f64) -> (f64, f64) {
        let el = self.context(e);
        let [s, psi] = [Field::S, Field::Theta].map(|f| self.layout.position(f).map(|k| el.field(self.layout, &self.local[e], k, xi)));
        let (Some([_, ds, d2s]), Some([_, dpsi, d2psi])) = (s, psi) else {
            return (f64::NAN, f64::NAN);
        };
        let rate = dpsi - el.alpha();
        let m = a * rate / ds;
        let dm_dsigma = a * (d2psi / ds - rate * d2s / (ds * ds));
        (m, -dm_dsigma / el.tangent_length(&self.point(e, xi)))
    }

    /// M and V at σ: inside an element from its interpolant, at a node the mean of the
    /// two one-sided values (∂²σν of the Hermite cubics jumps between elements; for the
    /// Cosserat rod [`Self::section_moment_and_shear`], whose M is continuous).
    fn rod_resultants(&self, sigma: f64) -> Option<(f64, f64)> {
        let ei = self.params.bending_stiffness?;
        if self.kernel.theory() == drive::scene::Theory::Cosserat {
            let (e, xi) = self.mesh.locate(sigma);
            return Some(self.section_moment_and_shear(e, xi, ei));
        }
        let (e, xi) = self.mesh.locate(sigma);
        let (m, v) = self.moment_and_shear(e, xi, ei);
        if xi == -1.0 {
            let (el, xl) = self.mesh.locate_left(sigma);
            let (ml, vl) = self.moment_and_shear(el, xl, ei);
            return Some((0.5 * (m + ml), 0.5 * (v + vl)));
        }
        Some((m, v))
    }

    fn compute_summary(&mut self) -> Summary {
        let c = *self.mesh.contour();
        let h = c.centre_distance();
        let upper = 0.5 * h;
        let lower = h + PI * c.radius() + 0.5 * h;
        let driver = self.pulley_summary(Pulley::Driver);
        let driven = self.pulley_summary(Pulley::Driven);
        let contact = self.params.penalty.is_some();
        Summary {
            y_upper_mid: Some(self.position(upper)[1]),
            y_lower_mid: Some(self.position(lower)[1]),
            tension_upper_mid: Some(self.axial_force(upper)),
            tension_lower_mid: Some(self.axial_force(lower)),
            moment_upper_mid: self.bending_moment(upper),
            moment_lower_mid: self.bending_moment(lower),
            driver: contact.then_some(driver),
            driven: contact.then_some(driven),
            ..Summary::default()
        }
    }
}

/// The rising root of the Lagrange interpolant through `pts` (x ascending, G(x) the
/// accumulated contact force) next to x = 0, by Newton from 0, and the slope there:
/// `None` unless the root lies in (`lower`, x₀), the slope is positive and the
/// polynomial vanishes there to 1e-9 of its last value.
fn rising_root(pts: &[(f64, f64)], lower: f64) -> Option<(f64, f64)> {
    let (x0, g_last) = (pts.first()?.0, pts.last()?.1);
    let slope = |t: f64| {
        let d = 1e-7 * x0;
        (lagrange(pts, t + d) - lagrange(pts, t - d)) / (2.0 * d)
    };
    // Newton from the estimate: G rises through the edge with the edge pressure
    let mut t = 0.0;
    for _ in 0..50 {
        let step = lagrange(pts, t) / slope(t);
        t -= step;
        if !t.is_finite() || step.abs() < 1e-12 * x0 {
            break;
        }
    }
    let p = slope(t);
    (t.is_finite() && t > lower && t < x0 && p > 0.0 && lagrange(pts, t).abs() < 1e-9 * g_last.abs()).then_some((t, p))
}

/// The nodes inside a contact zone through whose contact forces the augmented
/// Lagrangian's edge is located (`FemSolution::force_edge`): G(x) is extrapolated back
/// over about an element by the polynomial of degree 5 through them. Measured on
/// `cosserat-pulley` at 256 elements (docs/fem-cosserat.md §12.5), contact-arc error
/// against the BVP for 4, 5, 6, 7 nodes: 2.1e-4, 9.5e-5, 5.1e-5, 3.1e-5; 6 is the first
/// at or below the penalty's 6.1e-5, and at 512 elements it gives 1.4e-6.
const FORCE_EDGE_NODES: usize = 6;

/// Nodes closer to a Cosserat contact edge than this many penalty layers ℓ_P
/// ([`FemSolution::penalty_layer`]) are not used by [`FemSolution::edge_pressure`]: inside
/// the layer the penalty's force G(x) from the gap crossing is not yet the limit
/// solution's from the edge (G at the edge itself is not 0 but the layer's force), and a
/// node there bends the cubic — on `cosserat-hanging` at 2048 elements a node 1.1 ℓ_P
/// inside gave 651 N/m against the BVP's 549.5 (docs/fem-cosserat.md §12.5).
const EDGE_LAYER_SKIP: f64 = 4.0;

/// Root of a continuous f on [a, b] with f(a), f(b) on different sides of 0 (bisection
/// to |b − a| < 1e-15 in ξ, i.e. 1e-15·h/2 in σ).
fn bisect(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let neg_a = f(a) < 0.0;
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if (f(m) < 0.0) == neg_a {
            a = m;
        } else {
            b = m;
        }
        if (b - a).abs() < 1e-15 {
            break;
        }
    }
    0.5 * (a + b)
}

impl<const N: usize, K: LayoutElement<N> + ?Sized> SolutionView for FemSolution<N, K> {
    fn path(&self) -> drive::contour::Path {
        drive::contour::Path::Loop(*self.mesh.contour())
    }

    fn position(&self, sigma: f64) -> [f64; 2] {
        let (el, p) = self.at(sigma);
        el.position(&p)
    }

    /// The axial force recovered from the strain rule's points (docs/fem-string.md §10):
    /// N = EA(λ − 1) (the formulation's law) is evaluated where the strain energy samples
    /// it — the points of the strain rule — and interpolated between them by the Lagrange
    /// polynomial through those points (quadratic for the 3-point rules).
    fn axial_force(&self, sigma: f64) -> f64 {
        self.recovered_axial_force(sigma)
    }

    /// M = EI θ_σ/∂σS (docs/fem-rod.md K4) for a rod, `None` for a string.
    fn bending_moment(&self, sigma: f64) -> Option<f64> {
        self.rod_resultants(sigma).map(|x| x.0)
    }

    /// V = −∂σM/|∂σr| (docs/fem-rod.md K5) for a rod, `None` for a string.
    fn transverse_force(&self, sigma: f64) -> Option<f64> {
        self.rod_resultants(sigma).map(|x| x.1)
    }

    /// The section rotation θ of a rod: the Cosserat rod's θ = ϑ_g + ψ
    /// ([`LayoutElement::rotation_at`]), the Kirchhoff rod's tangent angle of ∂σr; unwrapped
    /// to lie within π of the contour's tangent angle (continuous on [0, L_geom)); `None`
    /// for a string.
    fn rotation(&self, sigma: f64) -> Option<f64> {
        self.params.bending_stiffness?;
        let (e, xi) = self.mesh.locate(sigma);
        let el = self.context(e);
        let theta = self.kernel.rotation_at(&el, &self.local[e], xi).unwrap_or_else(|| {
            let [_, r1, _] = el.curve_at(&self.point(e, xi));
            r1[1].atan2(r1[0])
        });
        Some(drive::contour::Path::Loop(*self.mesh.contour()).unwrap_near_tangent(sigma, theta))
    }

    /// Γ₂ of a shear-deformable element at σ from its fields ([`LayoutElement::shear_strain_at`]);
    /// `None` for an unshearable one.
    fn shear_strain(&self, sigma: f64) -> Option<f64> {
        let (e, xi) = self.mesh.locate(sigma);
        self.kernel.shear_strain_at(&self.context(e), &self.local[e], xi)
    }

    /// The penalty pressure P⟨−γ⟩ (N per unit contour length) recovered like the axial
    /// force: evaluated at the contact rule's points of the element (where the
    /// formulation applies it) and interpolated between them, ≥ 0; 0 outside the
    /// recovered contact zones; `None` without a contact term.
    fn contact_pressure(&self, sigma: f64) -> Option<f64> {
        let penalty = self.params.penalty?;
        if self.contact_state(sigma) == ContactState::Free {
            return Some(0.0);
        }
        let (e, xi) = self.mesh.locate(sigma);
        Some(self.penalty_pressure(penalty, e, xi).max(0.0))
    }

    /// `Contact` inside a recovered contact zone (consistent with the summary's
    /// boundaries), else `Free`.
    fn contact_state(&self, sigma: f64) -> ContactState {
        let c = self.mesh.contour();
        let l = c.length();
        let w = c.wrap(sigma);
        for z in self.zones.iter().flatten() {
            // z.sigma_start may be unwrapped below 0 or above L_c
            let d = (w - z.sigma_start).rem_euclid(l);
            if d <= z.sigma_end - z.sigma_start {
                return ContactState::Contact;
            }
        }
        ContactState::Free
    }

    fn material_coordinate(&self, sigma: f64) -> f64 {
        let l = self.mesh.contour().length();
        let loops = (sigma / l).floor();
        let s = self.fields(sigma).s;
        if loops.is_finite() {
            s + loops * self.length
        } else {
            f64::NAN
        }
    }

    fn deflection(&self, sigma: f64) -> f64 {
        self.fields(sigma).nu
    }

    fn summary(&self) -> Summary {
        self.summary.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::rising_root;

    /// The accumulated force G(x) = p·(x − t₀) sampled at the six nodes h … 6h inside a
    /// mesh whose nearest node to the estimate is x = 0 (the interpolant is exact): the
    /// root and the edge pressure are found when the edge lies inside the first element
    /// or within one element outward; an edge 2.5 elements outward is an extrapolation
    /// of the fit and is refused (it was accepted up to 6 elements out before), as is a
    /// falling G.
    #[test]
    fn the_edge_root_is_accepted_within_one_element_only() {
        let (h, p) = (1e-3, 250.0);
        let sample = |t0: f64, p: f64| -> Vec<(f64, f64)> { (1..=6).map(|j| j as f64 * h).map(|x| (x, p * (x - t0))).collect() };
        for t0 in [0.3 * h, 0.0, -0.7 * h] {
            let (t, slope) = rising_root(&sample(t0, p), -h).expect("an edge within one element");
            assert!((t - t0).abs() < 1e-12 * h, "t0 = {t0}: root {t}");
            assert!((slope - p).abs() < 1e-6 * p, "t0 = {t0}: slope {slope}");
        }
        assert_eq!(rising_root(&sample(-2.5 * h, p), -h), None, "2.5 elements outward");
        assert_eq!(rising_root(&sample(0.3 * h, -p), -h), None, "falling G");
    }
}
