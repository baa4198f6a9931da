//! The Kirchhoff–Love shell of Paper E in MEL description (issue 15; docs/fem-shell.md):
//! unknowns {S, ν, z} over (σ, ζ) on the Bogner–Fox–Schmit elements of
//! [`crate::surface`].
//!
//! - [`transition`]: the geometry of the element columns (α, which σ-edges are
//!   Cartesian/polar transitions), the augmented C¹ construction at the transitions
//!   (docs/fem-shell.md (S11)–(S12)) and the material derivatives (37) of the position;
//! - [`membrane`]: the stiffness coefficients of (19), Green's membrane strain with
//!   camber and the quadratic energy density of (19);
//! - [`interlayer`]: the elastic interlayer (40)–(41) with the drums, their tilt and the
//!   per-point tangential deformation (docs/fem-shell.md §7–§8);
//! - [`hanging`]: stage (0), the static hanging belt with its zero modes constrained
//!   (docs/fem-shell.md §9.1);
//! - [`runoff`]: stages (1)–(2), the ramps of camber and tilt at rest and the
//!   transient with rotation, the belt's lateral offset and drift velocity
//!   (docs/fem-shell.md §9.2–§9.3);
//! - [`scene`]: a `shell` scene solved by stages 0–2 (and the tilt schedule after the
//!   start), with its histories, surface frames, summary and self-checks (issue 15);
//! - [`compensation`]: the constant swivel of the steering drum that cancels a camber's
//!   run-off (spec E-5), a scalar root over whole solves;
//! - [`kernel`]: the shell as one [`crate::surface::assembly::SurfaceKernel`]
//!   ([`kernel::Shell`]), with the augmented map at the transitions.

pub mod compensation;
pub mod hanging;
pub mod interlayer;
pub mod kernel;
pub mod membrane;
pub mod runoff;
pub mod scene;
pub mod transition;

use thiserror::Error;

/// Why a shell mesh or element cannot be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ShellError {
    /// The surface mesh's loop length differs from the contour's L_geom.
    #[error("the mesh's loop length {mesh} m differs from the contour's L_geom = {contour} m")]
    LengthMismatch { mesh: f64, contour: f64 },
    /// A Cartesian/polar transition of the contour that is no σ-node of the mesh (α must
    /// be constant on every element, docs/fem-shell.md §4).
    #[error("the transition at σ = {sigma} m is no σ-node of the mesh (nearest node at {nearest} m)")]
    TransitionNotANode { sigma: f64, nearest: f64 },
    /// The surface mesh cannot be built.
    #[error(transparent)]
    Surface(#[from] crate::surface::SurfaceError),
    /// Single-node constraints need a ζ-node on the centre line ζ = 0.
    #[error("no ζ-node at ζ = 0 for the zero-mode constraints (nearest at {nearest} m); use an even number of ζ-elements on a symmetric width")]
    NoCentreNode { nearest: f64 },
    /// The planar start (the equivalent rod) failed.
    #[error("the planar start (equivalent Kirchhoff rod): {0}")]
    PlanarStart(Box<crate::FemError>),
    /// The static shell's Newton failed.
    #[error("the static hanging shell: {0}")]
    Static(Box<crate::analysis::time_stepping::TimeSteppingError>),
    /// A material or model parameter out of its range.
    #[error("{what} = {value} is out of range")]
    BadParameter { what: &'static str, value: f64 },
    /// A scene the shell's FE has no model for (named reason).
    #[error("the shell's FE cannot solve this scene: {0}")]
    NotModelled(String),
    /// A step of the run failed (stage and time named).
    #[error("{stage} failed at t = {time} s (step {step}): {cause}")]
    Step { stage: &'static str, step: usize, time: f64, cause: Box<crate::analysis::time_stepping::TimeSteppingError> },
    /// A self-check of a finished run failed: the numbers are not trusted.
    #[error("self-check failed: {0}")]
    Check(String),
}
