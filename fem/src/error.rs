//! Why an FE run produced no solution: error values that carry the numbers a user needs.

use thiserror::Error;

/// Why an FE run produced no solution.
#[derive(Debug, Clone, Error, PartialEq)]
pub enum FemError {
    /// The scene asks for a model or formulation that does not exist.
    #[error("no finite element model for this scene: {0}")]
    Unsupported(String),

    /// A layout or theory the contract describes but the FE does not solve yet (the issue
    /// that brings it is named).
    #[error(transparent)]
    NotYetSolvable(#[from] drive::NotYetSolvable),

    /// A formulation name that is not registered.
    #[error("unknown element formulation `{name}`; registered: {available:?}")]
    UnknownFormulation {
        /// The name asked for.
        name: String,
        /// The registered names.
        available: Vec<String>,
    },

    /// An option outside its documented range.
    #[error("FE option `{field}` = {value}: {reason}")]
    InvalidOption {
        /// Option name (as in [`crate::FemOptions`] / [`crate::SolverSettings`]).
        field: &'static str,
        /// The offending value.
        value: String,
        /// The valid range.
        reason: String,
    },

    /// The scene has no unique equilibrium (e.g. a weightless slack loop).
    #[error("no unique equilibrium: belt length L = {} m exceeds the contour length L_geom = {} m and no gravity holds it taut (a weightless slack loop can take any shape)", numerics::Sig(*length), numerics::Sig(*geometric_length))]
    IllPosed {
        /// L, m.
        length: f64,
        /// L_geom = 2H + 2πR, m.
        geometric_length: f64,
    },

    /// Newton's method did not converge at a homotopy point.
    #[error("Newton did not converge at η = {} after {iterations} iterations: scaled update ‖Δ‖ = {update:.3e}, scaled residual ‖G‖ = {residual:.3e} (tolerance {tolerance:.1e}){}", numerics::Sig(*.eta), if *.line_search_failed { "; the line search found no acceptable step" } else { "" })]
    NewtonDiverged {
        /// Homotopy parameter.
        eta: f64,
        /// Iterations done.
        iterations: usize,
        /// Last scaled update norm (docs/fem-string.md §8).
        update: f64,
        /// Last scaled residual norm.
        residual: f64,
        /// The update tolerance.
        tolerance: f64,
        /// True if the line search gave up (no admissible or decreasing step).
        line_search_failed: bool,
    },

    /// The sparse tangent could not be factorised.
    #[error("singular tangent at η = {}, Newton iteration {iteration}: {detail}", numerics::Sig(*eta))]
    SingularTangent {
        /// Homotopy parameter.
        eta: f64,
        /// Newton iteration.
        iteration: usize,
        /// What faer reported.
        detail: String,
    },

    /// The homotopy step fell below its minimum.
    #[error("homotopy stalled at η = {} (step {step:.2e} < minimum {min_step:.1e}) after {steps} accepted steps; last failure: {last_failure}", numerics::Sig(*.eta))]
    HomotopyStalled {
        /// Last accepted η.
        eta: f64,
        /// Step that failed.
        step: f64,
        /// Minimum step.
        min_step: f64,
        /// Accepted steps so far.
        steps: usize,
        /// The last Newton failure.
        last_failure: String,
    },

    /// The static homotopy (weight on, then the loop lengthened to L) stalled: `at` says
    /// which scene quantity it was switching on and how far it got, `hard` the scene's
    /// numbers that make it hard and what to try (issue 12, "smaller ones").
    #[error("{at}: {cause}; {hard}")]
    StaticHomotopyStalled {
        /// The phase of the path and how far it got.
        at: String,
        /// The scene's numbers that make it hard, and what to try.
        hard: String,
        /// The continuation's failure ([`FemError::HomotopyStalled`]).
        cause: Box<FemError>,
    },

    /// The start of a continuation (its η = 0 problem) could not be solved, with the
    /// scene quantities that made it hard.
    #[error("the start state ({start}) did not converge: {cause}; {hard}")]
    StartFailed {
        /// Which start, in words.
        start: String,
        /// The solver's failure.
        cause: String,
        /// The scene quantities that make it hard, with their numbers.
        hard: String,
    },

    /// The converged static solution is no belt-on-pulley equilibrium
    /// (docs/fem-rod.md §10): a contact zone over the inner point of its pulley, a
    /// compressive edge force, or contact force on a pulley with no contact zone — an
    /// artefact of a mesh that does not resolve the contact (usually too coarse).
    #[error("inadmissible contact on the {pulley} pulley: {quantity} = {value:.6e}, limit {limit:.6e} — an artefact of the mesh of {elements} elements, not a belt resting on the pulley; {}", advice(*.elements_needed))]
    InadmissibleContact {
        /// `driver` or `driven`.
        pulley: String,
        /// What was checked (with its unit).
        quantity: String,
        /// Its value.
        value: f64,
        /// The admissible bound it crosses.
        limit: f64,
        /// Elements of the mesh.
        elements: usize,
        /// Elements a mesh needs to resolve the bending layers at the contact edges
        /// (`None`: the layers are resolved, or a string).
        elements_needed: Option<usize>,
    },

    /// A drive's self-check (docs/fem-drive.md §14): the torque the driven pulley takes
    /// from the contact tractions must equal its load M₂ + d₂ω₂, the equation the solve
    /// imposed. Off by more than [`crate::admissibility::TORQUE_BALANCE_TOLERANCE`] of the
    /// load scale, the converged state is round-off, not a solution (e.g. an axial
    /// stiffness of 1e50 N: tensions of 1e48 N cannot resolve a 13 N·m load).
    #[error("self-check failed: the driven pulley's torque from the contact tractions is {} N·m against its load M₂ + d₂ω₂ = {} N·m (off by {} N·m, limit {} N·m = {} × the load scale |M₂| + |d₂ω₁| + ρgLR); the solution is not trustworthy: the scene's numbers (e.g. an axial stiffness of {} N against the load) lie beyond what double precision resolves", numerics::Sig(*.torque), numerics::Sig(*.load), numerics::Sig((*.torque - *.load).abs()), numerics::Sig(*.limit), numerics::Sig(crate::admissibility::TORQUE_BALANCE_TOLERANCE), numerics::Sig(*.axial_stiffness))]
    TorqueBalance {
        /// Torque on the driven pulley from the tractions, N·m.
        torque: f64,
        /// M₂ + d₂ω₂, N·m.
        load: f64,
        /// The admissible difference, N·m.
        limit: f64,
        /// The belt's axial stiffness EA, N (for the message).
        axial_stiffness: f64,
    },

    /// The belt rests on a pulley (the penalty carries contact force) but no contact zone
    /// could be located (docs/fem-rod.md §10): for a rod whose bending layer √(EI/N) is
    /// not small against R the belt does not wrap the pulley — a near point contact the
    /// edge recovery (§5) does not represent.
    #[error("unreported contact on the {pulley} pulley: the belt rests on it (contact force {load:.6e} N, limit {limit:.6e} N) but no contact zone could be located; bending layer √(EI/N) = {layer_length:.3e} m against the pulley radius R = {radius:.3e} m{} — no FE answer for this scene: {}", if .layer_length.is_finite() { format!(" (ℓ_b/R = {:.3})", .layer_length / .radius) } else { String::new() }, if .layer_length.is_finite() && *.layer_length >= 0.5 * *.radius { "the belt does not wrap the pulley; use a larger pulley radius or a smaller EI" } else { "refine the mesh (--elements)" })]
    UnreportedContact {
        /// `driver` or `driven`.
        pulley: String,
        /// Sum of the penalty contact forces on the pulley, N.
        load: f64,
        /// The tolerance, N.
        limit: f64,
        /// √(EI/N) with N the axial force where the contact force is largest, m
        /// (∞ for a string).
        layer_length: f64,
        /// R, m.
        radius: f64,
    },

    /// A non-finite number appeared where a result was expected.
    #[error("non-finite {what}")]
    NonFinite {
        /// Which quantity.
        what: String,
    },

    /// The load on the driven pulley exceeds what friction can transmit on a pulley
    /// (docs/fem-drive.md §5): no steady creep solution exists.
    #[error("torque above the friction capacity{}: the {pulley} pulley must transmit {torque:.6e} N·m but its contact can carry at most {capacity:.6e} N·m (R ∫ μ τ_γ dσ over its contact zone)", at(.time))]
    FrictionCapacityExceeded {
        /// `driver` or `driven`.
        pulley: String,
        /// Torque to transmit, M₂ + d₂ω₂, N·m.
        torque: f64,
        /// R ∫ μ τ_γ dσ over the pulley's contact points, N·m.
        capacity: f64,
        /// Time of the step, s (`None`: the direct steady solve).
        time: Option<f64>,
    },

    /// Transport inertia at or above the critical speed (docs/fem-drive.md §6): the
    /// effective tension N − ρc²λ of a span is not positive, the step energy (D3) has no
    /// stationary point of the string's kind (the belt cannot be held on the pulleys).
    #[error("speed at or above critical{}: in the {span} span the axial force N = {tension:.6e} N does not exceed the transport term ρc²λ = {inertia_force:.6e} N (effective tension N − ρc²λ ≤ 0)", at(.time))]
    SpeedAtOrAboveCritical {
        /// `upper` or `lower`.
        span: String,
        /// Axial force N at the span midpoint, N.
        tension: f64,
        /// ρc²λ there with the transport rate c of the step, N.
        inertia_force: f64,
        /// Time of the step, s (`None`: the direct steady solve).
        time: Option<f64>,
    },

    /// A one-pulley prescription the FE cannot meet (docs/fem-cosserat.md §12.7): ω with
    /// N_in (ill-posed), or an ω or φ_B that no steady state of the scene has.
    #[error("one-pulley prescription `{name}` = {value}: {reason}")]
    Prescription {
        /// The scene field.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Why it cannot be met.
        reason: String,
    },

    /// The direct steady solve could not fit its mesh to the contact boundaries and
    /// stick→slip transitions (docs/fem-drive.md §12): a recovered point still lies a
    /// sizeable fraction of an element from any node, so the stick/slip arcs are not
    /// resolved. Usually a coarse mesh of a slack belt with gravity: refine it.
    #[error("the steady solve could not fit its mesh to the contact boundaries and stick/slip transitions: after {passes} passes a point still lies {last_move:.3e} m from its node ({fraction:.0}% of an arc element; limit 5%): {reason} — refine the mesh (docs/fem-drive.md §12)", fraction = 100.0 * .last_move / .element)]
    SteadyFitFailed {
        /// Fitting passes done.
        passes: usize,
        /// Largest distance of a recovered point from its node, m.
        last_move: f64,
        /// Arc element length πR/n_arc, m.
        element: f64,
        /// Why the fitting stopped.
        reason: String,
    },

    /// Paper D's scheme (`fem.steady_scheme` = `paper-d`, spec §3.5) did not find the
    /// prescribed stick→slip points that make its matching measures vanish: a
    /// fixed-topology solve failed, no bracket of a root was found, or the root find
    /// stopped (docs/cosserat-drive.md, "FE, second way").
    #[error("Paper D's scheme failed after {outer} outer iterations (matching residual {residual:.3e} N): {reason}")]
    PaperDFailed {
        /// Outer iterations (fixed-topology solves at a new pair of points) done.
        outer: usize,
        /// Largest |E_k| of the last solved pair, N (NaN before the first).
        residual: f64,
        /// What stopped it, with its numbers.
        reason: String,
    },

    /// The steady state reached has a slip run at the contact entry of a pulley followed
    /// by stick (docs/fem-drive.md §11): a discrete artefact of the contact boundary (a
    /// concentrated normal force there carries a concentrated friction force that drops
    /// the tension into the stick zone), not a Coulomb steady state of the string — the
    /// stick and slip arcs and span tensions would be wrong, so none are reported.
    #[error("steady state at t = {time} s has a slip zone at the contact entry of the {pulley} pulley ({entry_slip_points} friction points, friction force {entry_force:.6e} N on the belt, above 20 % of the transmitted force {transmitted:.6e} N) followed by stick: an artefact of the discrete contact boundary, not a belt-creep state (docs/fem-drive.md §11; happens for slack belts with gravity)")]
    EntrySlip {
        /// `driver` or `driven`.
        pulley: String,
        /// Friction points in the leading slip run.
        entry_slip_points: usize,
        /// Σ w τ of the pulley on the belt over that run (along +σ), N.
        entry_force: f64,
        /// (M₂ + d₂ω₂)/R, N.
        transmitted: f64,
        /// Time of the steady state, s.
        time: f64,
    },

    /// A time step of the drive transient failed (Newton did not converge).
    #[error("time step {step} (t = {} s) failed: {reason}", numerics::Sig(*time))]
    DriveStepFailed {
        /// Step number (1-based).
        step: usize,
        /// Time at the end of the step, s.
        time: f64,
        /// The Newton failure.
        reason: NewtonFailure,
    },

    /// The transient did not reach the steady state within the step limit.
    #[error("no steady state after {steps} time steps (t = {time} s): change rate {rate:.3e} per radian of driver rotation above the tolerance {tolerance:.1e}")]
    SteadyStateNotReached {
        /// Steps done.
        steps: usize,
        /// Time reached, s.
        time: f64,
        /// Last change rate r_n (docs/fem-drive.md §7).
        rate: f64,
        /// The steady-state tolerance.
        tolerance: f64,
    },
}

/// Why a Newton solve of the drive (a transient step, a steady solve) failed, with its
/// numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NewtonFailure {
    /// The state left the admissible set (∂σS ≤ 0 or a non-finite value).
    #[error("inadmissible state (∂σS ≤ 0 or non-finite) at Newton iteration {iteration}")]
    Inadmissible {
        /// Iteration at which the state was evaluated.
        iteration: usize,
    },
    /// The iteration limit was reached.
    #[error("no convergence in {iterations} Newton iterations (scaled update {update:.3e}, tolerance {tolerance:.1e})")]
    NotConverged {
        /// Iterations done.
        iterations: usize,
        /// Last scaled update.
        update: f64,
        /// Update tolerance.
        tolerance: f64,
    },
    /// The (regularised) tangent could not be factorised.
    #[error("singular {matrix} at Newton iteration {iteration}: {detail}")]
    Singular {
        /// "tangent" (energy minimisation) or "Jacobian" (semismooth system).
        matrix: &'static str,
        /// Iteration.
        iteration: usize,
        /// The sparse LU's message.
        detail: String,
    },
    /// The sparse LU rejected the pattern.
    #[error("sparse pattern: {0}")]
    Pattern(String),
    /// No step length gave an admissible or acceptable trial.
    #[error("{what} at Newton iteration {iteration} (scaled update {update:.3e})")]
    LineSearch {
        /// "line search failed" or "no admissible step".
        what: &'static str,
        /// Iteration.
        iteration: usize,
        /// Scaled update of the step.
        update: f64,
    },
    /// A point taken as stick to give its pulley an equation violates Coulomb's bound at
    /// the solution: the pulley slides over its whole contact.
    #[error("no Coulomb state: a pulley slides over its whole contact (|τ| = {traction:.6e} N/m above μτ_γ = {bound:.6e} N/m at σ = {sigma:.6} m)")]
    NoCoulombState {
        /// |τ_⊥|, N/m.
        traction: f64,
        /// μτ_γ, N/m.
        bound: f64,
        /// σ of the point, m.
        sigma: f64,
    },
}

/// What to do about an inadmissible contact.
fn advice(elements_needed: Option<usize>) -> String {
    match elements_needed {
        Some(n) => format!("use at least {n} elements (--elements {n}) so that one element spans the bending layer √(EI/N) at the contact edges"),
        None => "refine the mesh (--elements) or change the penalty (fem.penalty)".into(),
    }
}

/// " at t = … s" of a transient step, " in the steady state" of the direct solve.
fn at(time: &Option<f64>) -> String {
    match time {
        Some(t) => format!(" at t = {t} s"),
        None => " in the steady state".into(),
    }
}
