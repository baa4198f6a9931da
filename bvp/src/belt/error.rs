//! The one error type of every belt problem: why a belt scene has no computed solution.
//! Each variant carries the numbers a user needs.

use numerics::Sig;
use thiserror::Error;

use crate::analytical::belt_creep::CreepError;
use crate::error::BvpError;

use super::balance::Balance;

/// Why a belt problem (string, Kirchhoff rod, string drive) has no computed solution.
#[derive(Debug, Clone, Error)]
pub enum BeltError {
    /// A physical input or an option is non-finite or out of range.
    #[error("invalid input: {name} = {} ({reason})", Sig(*value))]
    InvalidInput { name: &'static str, value: f64, reason: &'static str },
    /// A weightless belt longer than the contour has no unique equilibrium.
    #[error("no unique equilibrium: without gravity a belt of length L = {} m not shorter than the contour L_geom = {} m hangs slack in any shape; add gravity or shorten the belt", Sig(*length), Sig(*geometric_length))]
    WeightlessSlack { length: f64, geometric_length: f64 },
    /// Decided by belt-creep theory before any iteration (drive without gravity: exact).
    #[error(transparent)]
    Creep(#[from] CreepError),
    /// Drive with gravity: the stick zone of a pulley vanished on the homotopy path, i.e.
    /// the torque exceeds the friction capacity of the sagging belt.
    #[error("no steady solution: resisting torque M₂ + d₂ω₁ = {torque:.6} N·m exceeds the friction capacity; on the homotopy path (torque {:.3}, gravity {:.3}, length {:.3}, speed {:.3} of the scene's) {reason}", path[0], path[1], path[2], path[3])]
    FrictionCapacityExceeded { torque: f64, path: [f64; 4], reason: String },
    /// Drive with gravity: a slip arc shrank to zero on the homotopy path — the resisting
    /// torque is below the torque of the belt's own weight hanging on the pulley
    /// (≈ 2ρgR²), so friction in the slip zone would have to reverse; that topology is
    /// not modelled.
    #[error("no steady solution of the modelled topology: resisting torque {torque:.6} N·m is so small that on the homotopy path (torque {:.3}, gravity {:.3}, length {:.3}, speed {:.3} of the scene's) {reason}; the belt's weight on the pulley (≈ 2ρgR² = {weight_torque:.4e} N·m) would drive it", path[0], path[1], path[2], path[3])]
    SlipReversed { torque: f64, weight_torque: f64, path: [f64; 4], reason: String },
    /// Drive with inertia: the belt speed must stay below the longitudinal wave speed
    /// √(EA/ρ) (ρc² < EA in (D2)).
    #[error("no steady solution: belt speed ω₁R = {} m/s reaches the longitudinal wave speed √(EA/ρ) = {} m/s", Sig(*belt_speed), Sig(*wave_speed))]
    WaveSpeedReached { belt_speed: f64, wave_speed: f64 },
    /// Moving Cosserat belt: the transport term χ = ρc² must stay below the axial and the
    /// shear stiffness (spec §1.2: the constitutive inversion divides by b − χ).
    #[error("no steady solution: transport term ρc² = {} N is at or above the {stiffness} {} N (critical transport rate √(b/ρ) = {} m/s, given c = {} m/s)", Sig(*chi), Sig(*value), Sig(*critical_rate), Sig(*transport_rate))]
    SpeedAtOrAboveCritical { stiffness: &'static str, value: f64, chi: f64, transport_rate: f64, critical_rate: f64 },
    /// Moving belt on one pulley: an end's effective tension T̃ = N − ρc²(1 + N/b₁) is not
    /// positive (the belt would buckle under its own momentum flux).
    #[error("no steady solution: effective tension T̃ = {} N ≤ 0 at the {end} end (axial force {} N, ρc² = {} N)", Sig(*effective), Sig(*tension), Sig(*chi))]
    EffectiveTensionNotPositive { end: &'static str, tension: f64, effective: f64, chi: f64 },
    /// One pulley, mode `tensions`: the tension ratio is beyond the friction the wrap can
    /// hold — φ_B was moved up to the contact start (the stick arc shrunk to `stick_arc`)
    /// and the free tension reached only `reached` against the scene's `target` (the
    /// string's capstan estimate for comparison: it ignores the rod's edge pressure peaks).
    #[error("no steady creep solution: friction capacity exceeded — with the stick arc shrunk to {} rad the {end} tension reaches {} N, not the given {} N (μ = {}; the string's capstan slip arc ln(T̃_high/T̃_low)/μ = {} rad against its contact arc {} rad)", Sig(*stick_arc), Sig(*reached), Sig(*target), Sig(*mu), Sig(*string_slip_arc), Sig(*contact_arc))]
    CapstanLimitExceeded { end: &'static str, target: f64, reached: f64, stick_arc: f64, string_slip_arc: f64, contact_arc: f64, mu: f64 },
    /// One pulley, mode `tensions` beyond the string's capstan: the search of φ_B toward
    /// the contact start stopped at a failed solve before it met the scene's free tension
    /// or the contact start — no statement about the capacity.
    #[error("mode `tensions` beyond the string's capstan: the search of the stick → slip angle stopped at φ_B = {} rad, where the solve failed ({cause}); the {end} tension had reached {} N (given {} N) at a stick arc of {} rad", Sig(*phi), Sig(*reached), Sig(*target), Sig(*stick_arc))]
    CapstanSearchFailed { end: &'static str, target: f64, reached: f64, stick_arc: f64, phi: f64, cause: Box<BeltError> },
    /// A prescribed stick → slip angle outside the pulley's contact arc (the drive with
    /// the driver's φ_B given and M₂ released, spec §3.4): checked against the contact
    /// angles of the solution the solve starts from, polar angles unwrapped.
    #[error("invalid input: the {pulley} pulley's stick → slip angle φ_B = {} rad lies outside its contact arc, first contact {} rad, last contact {} rad (polar angles, unwrapped, of the solution it starts from): the stick or the slip arc would vanish", Sig(*angle), Sig(*first_contact), Sig(*last_contact))]
    TransitionOutsideContact { pulley: &'static str, angle: f64, first_contact: f64, last_contact: f64 },
    /// One pulley: an admissibility condition of the assumed stick/slip topology fails
    /// after the solve (spec §2.4), with the numbers.
    #[error("inadmissible one-pulley solution: {0}")]
    Inadmissible(String),
    /// Kirchhoff rod: the string of the same data (the homotopy start) failed.
    #[error("string of the same data: {0}")]
    StringStart(Box<BeltError>),
    /// The homotopy from the closed-form start stalled before the scene: `at` says which
    /// scene quantity the path was switching on and how far it got, `hard` the
    /// dimensionless number of the scene that makes that part of the path hard.
    #[error("{stage} stalled at η = {} — {at}; {hard} ({cause})", Sig(*eta))]
    HomotopyStalled { stage: &'static str, eta: f64, at: String, hard: String, cause: BvpError },
    /// The first solve, at the scene's own parameters from a start that needs no
    /// continuation (a closed-form state or a previous solution), did not converge: `stage`
    /// names the start, `hard` the scene's layers.
    #[error("{stage} did not converge — {hard} ({cause})")]
    StartFailed { stage: &'static str, hard: String, cause: BvpError },
    /// Shooting: the integration of a flow failed inside a shooting interval many lengths
    /// of the scene's shear layer long — the flow grows like e^{interval/layer} across it
    /// ([`across_layer`]).
    #[error("cannot integrate across the shear layer √(a/(b₂ − ρc²)) = {} m: its {intervals} shooting intervals per segment are ≈ {} m long on an arc, {} layer lengths, so a flow grows by up to e^{} across one ({cause}); bvp-collocation solves such scenes, or raise `bvp.shooting_intervals` (at b₂ = 1e4 N on `cosserat-hanging`, 32 sufficed; at 1e6 N, 64 did not)", Sig(*layer), Sig(*interval), (interval / layer).round(), (interval / layer).round())]
    ShootingAcrossLayer { layer: f64, interval: f64, intervals: usize, cause: BvpError },
    /// The solver failed (homotopy or final solve).
    #[error("{stage}: {cause}")]
    Solver { stage: &'static str, cause: BvpError },
    /// The solution violates a contact condition of the assumed segment topology.
    #[error("contact condition violated: {0}")]
    ContactViolated(String),
    /// A balance the solver reports failed its check ([`crate::belt::balance`]): the
    /// converged discrete solution does not satisfy the belt's equilibrium, e.g. when the
    /// scene's numbers lie beyond what double precision resolves (EA ≥ 1e17 N, a centre
    /// distance of 1e50 m).
    #[error("self-check failed: {0}; the solution is not trustworthy (scene numbers such as an axial stiffness of 1e17 N or a centre distance of 1e50 m lie beyond what double precision resolves against the belt's weight and load)")]
    BalanceFailed(Balance),
}

/// `e`, or [`BeltError::ShootingAcrossLayer`] where it is a shooting final solve whose
/// integration failed and a shooting interval on an arc (`arc` m of contact split into
/// `opts.shooting_intervals`) spans more than ten shear layers `layer` (m): the failure
/// then has that cause, measured on `cosserat-hanging` and `cosserat-pulley` from b₂ = 1e4
/// N on (docs/cosserat-hanging.md).
pub fn across_layer(e: BeltError, opts: &super::BeltOptions, layer: f64, arc: f64) -> BeltError {
    let intervals = opts.shooting_intervals.max(1);
    let interval = arc / intervals as f64;
    match e {
        BeltError::Solver { cause: cause @ BvpError::IntegrationFailed { .. }, .. } if opts.method == super::BvpMethod::Shooting && interval > 10.0 * layer => BeltError::ShootingAcrossLayer { layer, interval, intervals, cause },
        e => e,
    }
}
