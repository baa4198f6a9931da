//! The 2-D discretisation over the belt's mid-surface (σ, ζ) — σ the looped contour
//! coordinate (periodic, length L), ζ ∈ [ζ₀, ζ₁] the material width coordinate (issue
//! 11: "2-D elements over (σ, ζ) … so that the shell issue adds an element, not a
//! framework"; docs/fem-time-stepping.md).
//!
//! - [`mesh`]: the structured mesh — n_σ elements around the loop (non-uniform spacing
//!   allowed, the last element closes the loop), n_ζ across the width;
//! - [`dofs`]: the numbering of the Bogner–Fox–Schmit unknowns (per node and field f,
//!   ∂σf, ∂ζf, ∂σ∂ζf) of the fields a kernel uses, periodic in σ, with homogeneous edge
//!   constraints at ζ₀, ζ₁;
//! - [`assembly`]: the [`assembly::SurfaceKernel`] interface (energy densities per
//!   integration point over the point values of the kernel's fields, one Gauss rule per
//!   direction per term, optional history per point) and [`assembly::SurfaceAssembler`]
//!   (energy, gradient and sparse Hessian by forward-mode AD over the point values and
//!   the exact chain rule through the BFS weights; parallel over elements);
//! - [`history`]: per-integration-point states of a kernel's history terms, committed
//!   after a converged step and advected along σ (semi-Lagrangian, cubic Lagrange
//!   interpolation).
//!
//! The analysis that steps these in time is [`crate::analysis::time_stepping`].

pub mod assembly;
pub mod dofs;
pub mod history;
pub mod mesh;

use numerics::linear::LinearError;
use thiserror::Error;

/// Why a surface mesh, numbering, assembly or history cannot be built or evaluated.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SurfaceError {
    /// Too few elements in one direction.
    #[error("{direction}: {elements} elements, need at least {minimum}")]
    TooFewElements { direction: &'static str, elements: usize, minimum: usize },
    /// Node coordinates that are not finite and strictly increasing inside their range.
    #[error("{direction} node {index} at {value} is not finite and strictly increasing inside [{low}, {high}]")]
    BadNode { direction: &'static str, index: usize, value: f64, low: f64, high: f64 },
    /// A loop length or width that is not finite and positive.
    #[error("{what} = {value} must be finite and > 0")]
    BadLength { what: &'static str, value: f64 },
    /// A kernel whose layout is not 2-D, or a field it reads that the layout lacks.
    #[error("kernel layout {layout}: {reason}")]
    BadKernel { layout: String, reason: String },
    /// A history term whose rule gives too few distinct σ points per row to interpolate
    /// cubically (4 are needed).
    #[error("history term {term}: {points} distinct σ points per row, cubic interpolation needs 4")]
    TooFewHistoryPoints { term: usize, points: usize },
    /// Two kernels meant to share one numbering (stiffness and mass) do not.
    #[error("the mass kernel's numbering differs from the stiffness kernel's: {detail}")]
    MassMismatch { detail: String },
    /// An evaluation where every point must be admissible and every value finite (a
    /// Hessian at an accepted iterate, the mass matrix) is not.
    #[error("{what}: an integration point is inadmissible or a value is not finite")]
    Inadmissible { what: &'static str },
    /// A sparse factorisation or solve failed.
    #[error(transparent)]
    Linear(#[from] LinearError),
}
