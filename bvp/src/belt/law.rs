//! The section law of a belt theory: what a belt theory supplies to the one belt BVP
//! ([`super::problem::BeltProblem`]) for each segment the [`Topology`] names.
//!
//! 1. the state layout of a span and of each arc kind ([`SectionLaw::state_names`]) and
//!    its own parameters ([`SectionLaw::extra_params`]);
//! 2. the span and arc right-hand sides in the segment's own independent variable
//!    ([`SectionLaw::span_rhs`], [`SectionLaw::arc_rhs`]): the law, not the topology,
//!    decides whether a span runs in s or in x and what its span parameter means;
//! 3. the transition conditions at a contact start, between two arcs (stick → slip), at
//!    a contact end and at the mid-span split, and the conditions of the whole loop
//!    (length, kinematics, torque balance);
//! 4. the point output x, y, θ, N, Q, M, p, f_t, λ ([`BeltPoint`], absent ones `None`);
//! 5. its first integral and its balance self-check.
//!
//! The string (`string_hanging`), the Kirchhoff rod (`rod_hanging`) and the string in
//! steady motion with Coulomb friction (`string_drive`) are the laws today;
//! docs/bvp-engine.md ("Adding a belt theory") says how the Cosserat rod plugs in.

use crate::problem::Scalar;

use super::error::BeltError;
use super::solution::BeltSolution;
use super::topology::{ArcKind, PowerFlow, Pulley, SegmentKind, Topology};

/// Scales of a belt problem's nondimensionalisation.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Scales {
    /// Length scale H (m).
    pub length: f64,
    /// Force scale F_ref (N).
    pub force: f64,
    /// Speed scale V = √(F_ref/ρ) (m/s): the unit of the scaled transport rate.
    pub speed: f64,
}

/// The rows of a boundary residual, written in order.
pub struct Rows<'a, D> {
    r: &'a mut [D],
    i: usize,
}

impl<'a, D: Copy> Rows<'a, D> {
    /// Rows written into `r` from its start.
    pub fn new(r: &'a mut [D]) -> Self {
        Self { r, i: 0 }
    }

    /// Write the next row.
    pub fn push(&mut self, v: D) {
        self.r[self.i] = v;
        self.i += 1;
    }

    /// Rows written so far.
    pub fn written(&self) -> usize {
        self.i
    }
}

/// The physical loop a solution lies on: the pulleys and the belt's weight.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Pulleys {
    /// Pulley radius R to the belt centreline (m).
    pub radius: f64,
    /// Centre distance H (m).
    pub centre_distance: f64,
    /// Weight per unstretched length ρg (N/m); 0 without gravity.
    pub weight: f64,
}

/// One point of the belt in physical units (SI): what a law outputs at (segment, ξ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltPoint {
    /// Position x (m).
    pub x: f64,
    /// Position y (m).
    pub y: f64,
    /// Tangent angle θ (rad, unwrapped as the law's states); `None` where the law does
    /// not carry it.
    pub theta: Option<f64>,
    /// Axial force N (the tension T of a string), N.
    pub tension: f64,
    /// Effective tension T̃ = T − ρc²λ of a moving belt (N); `None` at rest.
    pub effective_tension: Option<f64>,
    /// Transverse force Q (N); `None` for a string.
    pub shear: Option<f64>,
    /// Bending moment M (N·m); `None` for a string.
    pub moment: Option<f64>,
    /// Shear strain Γ₂ = Q/b₂ (dimensionless) of a shear-deformable rod; `None` for an
    /// unshearable model.
    pub shear_strain: Option<f64>,
    /// Stretch λ.
    pub stretch: f64,
    /// Material coordinate s (m), 0 where the belt leaves the driver.
    pub material: f64,
    /// Contact force per unstretched length p (N/m) on an arc; `None` on a span.
    pub pressure: Option<f64>,
    /// Friction force on the belt per unstretched length f_t (N/m, + in the direction of
    /// travel) on an arc with friction; `None` elsewhere.
    pub friction: Option<f64>,
    /// Polar angle on the pulley (rad, unwrapped); `None` on a span.
    pub angle: Option<f64>,
    /// Accumulated torque of the belt on the pulley (N·m) where the law integrates it;
    /// `None` elsewhere.
    pub torque: Option<f64>,
}

impl BeltPoint {
    /// A point with the outputs every law has (x, y, N, λ, s, the tangent angle θ); the
    /// others `None` until the law sets them.
    pub fn new(x: f64, y: f64, theta: f64, tension: f64, stretch: f64, material: f64) -> Self {
        Self {
            x,
            y,
            theta: Some(theta),
            tension,
            effective_tension: None,
            shear: None,
            moment: None,
            shear_strain: None,
            stretch,
            material,
            pressure: None,
            friction: None,
            angle: None,
            torque: None,
        }
    }
}

/// What a section law has at a contact boundary ([`SectionLaw::CONTACT_EDGES`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactEdges {
    /// Concentrated reactions: the jump of the transverse force (summary
    /// `edge_force_*`; absent where the law has no transverse force, the string).
    Forces,
    /// A finite pressure just inside the zone (summary `edge_pressure_*`).
    Pressures,
}

/// A belt theory as the one belt BVP asks for it (module docs). `Self` is the scaled
/// problem along its homotopy path (η = 1 is the scene); `Data` the scene's physical data.
pub trait SectionLaw: Clone + std::fmt::Debug + Send + Sync + Sized {
    /// The scene's physical data (SI units).
    type Data: Clone + std::fmt::Debug + Send + Sync;
    /// What the homotopy started from that the solution keeps (`()` for a closed-form
    /// start; the Kirchhoff rod keeps the string solution of the same data).
    type Start: Clone + std::fmt::Debug + Send + Sync;

    /// Coulomb coefficient μ of the arcs with friction; `None` when frictionless.
    fn friction(_data: &Self::Data) -> Option<f64> {
        None
    }

    /// Which pulley puts power into the belt (the slip signs of the arcs with friction,
    /// [`Pulley::slip_sign`](super::topology::Pulley::slip_sign)); from the driver for a
    /// law without friction.
    fn power_flow(&self) -> PowerFlow {
        PowerFlow::FromDriver
    }

    /// (1) State component names of a span.
    const SPAN_STATES: &'static [&'static str];
    /// (1) State component names of an arc (of every kind, unless
    /// [`SectionLaw::state_names`] says otherwise).
    const ARC_STATES: &'static [&'static str];

    /// (1) State component names of a segment of `kind` (its dimension is their number);
    /// a law whose stick and slip states differ (the Cosserat rod: λ is a state in slip
    /// only) overrides this.
    fn state_names(&self, kind: SegmentKind) -> &'static [&'static str] {
        match kind {
            SegmentKind::Span => Self::SPAN_STATES,
            SegmentKind::Arc(_) => Self::ARC_STATES,
        }
    }

    /// (1) Names of the law's own parameters, after the topology's (λ₁, λ₂ of the
    /// Cosserat drive); none by default.
    fn extra_params(&self) -> &'static [&'static str] {
        &[]
    }

    /// (2) The parameters the span and arc right-hand sides read besides each segment's
    /// own span length or arc angles (indices into p; the topology's come first, then
    /// [`SectionLaw::extra_params`]). The default, every parameter, is always right; a
    /// law that declares fewer makes its Jacobian cheaper and must read no other (the
    /// moving string reads the belt speed c).
    fn rhs_reads(&self, topology: &Topology) -> Vec<usize> {
        (0..topology.n_params() + self.extra_params().len()).collect()
    }

    /// (2) Right-hand side of a span, times its span parameter `span` (the segment runs on
    /// ξ ∈ [0, 1]).
    #[allow(clippy::too_many_arguments)]
    fn span_rhs<D: Scalar>(&self, topology: &Topology, span: D, y: &[D], p: &[D], eta: D, f: &mut [D]);

    /// (2) Right-hand side of an arc of `kind` on `pulley` at polar angle `phi`, times the
    /// arc's angle Δφ = `dphi` (the segment runs on ξ ∈ [0, 1], φ = φ_a + Δφ ξ).
    #[allow(clippy::too_many_arguments)]
    fn arc_rhs<D: Scalar>(
        &self,
        topology: &Topology,
        kind: ArcKind,
        pulley: Pulley,
        phi: D,
        dphi: D,
        y: &[D],
        p: &[D],
        eta: D,
        f: &mut [D],
    );

    /// (3) The split of a span at x = 0: by default x (component 0) is 0 and every state
    /// is continuous.
    fn mid_span<D: Scalar>(&self, left_end: &[D], right_start: &[D], rows: &mut Rows<D>) {
        rows.push(left_end[0]);
        for c in 0..left_end.len() {
            rows.push(right_start[c] - left_end[c]);
        }
    }

    /// (3) A span meets `pulley` at angle `phi` and continues on an arc of `kind`;
    /// `jump` is the topology's closure jump where it applies (the driver's first contact
    /// of a frictionless loop), added to the axial force there; `p` the parameter vector
    /// (the Cosserat law's F̃ = (C2) at the stick stretch λ_i reads it).
    #[allow(clippy::too_many_arguments)]
    fn contact_start<D: Scalar>(
        &self,
        kind: ArcKind,
        pulley: Pulley,
        phi: D,
        span_end: &[D],
        arc_start: &[D],
        jump: Option<D>,
        p: &[D],
        eta: D,
        rows: &mut Rows<D>,
    );

    /// (3) Two arcs on `pulley` (stick → slip), with the parameter vector `p` (a law
    /// whose stick stretch λ_i is its own parameter writes λ = λ_i here): by default
    /// every state is continuous.
    fn arc_to_arc<D: Scalar>(&self, _pulley: Pulley, from_end: &[D], to_start: &[D], _p: &[D], rows: &mut Rows<D>) {
        for j in 0..from_end.len() {
            rows.push(to_start[j] - from_end[j]);
        }
    }

    /// (3) The belt leaves `pulley` at angle `phi`; `closes_loop` where the last segment
    /// closes the loop into segment 0 (material coordinate restarts, θ gains 2π).
    #[allow(clippy::too_many_arguments)]
    fn contact_end<D: Scalar>(
        &self,
        pulley: Pulley,
        phi: D,
        arc_end: &[D],
        span_start: &[D],
        closes_loop: bool,
        p: &[D],
        eta: D,
        rows: &mut Rows<D>,
    );

    /// (3) The end conditions of an open topology ([`Junction::OpenEnds`](super::topology::Junction::OpenEnds)):
    /// `inflow` is the state at the start of segment 0, `outflow` at the end of the last
    /// segment. Only a law written for an open layout (the Cosserat belt on one pulley)
    /// is ever put on an open topology; a closed-loop law keeps this default, which
    /// says so.
    fn open_ends<D: Scalar>(&self, _inflow: &[D], _outflow: &[D], _p: &[D], _eta: D, _rows: &mut Rows<D>) {
        unreachable!("a closed-loop section law has no end conditions: it is never put on an open topology")
    }

    /// (3) The conditions of the whole loop, after the junctions: the total unstretched
    /// length, and for a drive the stick-zone kinematics and the driven pulley's torque
    /// balance.
    fn loop_conditions<D: Scalar>(&self, topology: &Topology, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, rows: &mut Rows<D>);

    /// (4) The point output of segment `k` at state `y` (scaled), polar angle `phi` on an
    /// arc, parameters `p` (scaled).
    #[allow(clippy::too_many_arguments)]
    fn point(&self, data: &Self::Data, scales: &Scales, topology: &Topology, k: usize, phi: Option<f64>, y: &[f64], p: &[f64]) -> BeltPoint;

    /// (5) The law's first integral at a point (N), where it has one (frictionless loop).
    fn first_integral(_data: &Self::Data, _point: &BeltPoint) -> Option<f64> {
        None
    }

    /// (5) The balance self-check of a converged solution ([`super::balance`]).
    fn check_balance(solution: &BeltSolution<Self>) -> Result<(), BeltError>;

    /// The topology's acceptance window: (contact-angle window, arc slack), rad, for
    /// [`Topology::check`].
    fn admissible_window(&self) -> (f64, f64);

    /// Name of the arc force that must stay positive ([`SectionLaw::arc_force`]).
    fn arc_force_name(&self) -> &'static str;

    /// The arc force of an arc node state (scaled) that the homotopy's acceptance test
    /// keeps positive and holds the closure jump against: by default arc state 0 (the
    /// tension of the string and the rod).
    fn arc_force(&self, arc_state: &[f64]) -> f64 {
        arc_state[0]
    }

    /// The homotopy start is the scene itself (its path η: 0 → 1 is the identity), so the
    /// run goes straight to one collocation solve at the path tolerance and the final
    /// solve ([`super::run::direct_and_final_solve`]). By default false: every law
    /// continues from a simpler start.
    fn starts_at_scene(&self) -> bool {
        false
    }

    /// What the law has at a contact boundary: concentrated edge forces (the unshearable
    /// rod: jumps of the transverse force), or a finite edge pressure (the Cosserat rod).
    const CONTACT_EDGES: ContactEdges = ContactEdges::Forces;

    /// The force the slip-direction check of [`BeltSolution::check_contact`] compares
    /// through a slip zone with its value where the stick zone begins (N): by default the
    /// axial force; a law whose axial force varies in the edge layers of a contact zone
    /// (the Cosserat drive: N = b₁(λ cos γ − 1)) gives one that follows the stretch.
    fn slip_force(&self, _data: &Self::Data, point: &BeltPoint) -> f64 {
        point.tension
    }

    /// The point-wise force condition of the contact check: which force must stay
    /// positive on this kind of segment (name, value in N), if any.
    fn positive_force(kind: SegmentKind, point: &BeltPoint) -> Option<(&'static str, f64)>;
}
