//! Failures of the BVP engine. Each variant carries the numbers a user needs.

use thiserror::Error;

/// Why a BVP solve or continuation did not produce a solution.
#[derive(Debug, Clone, Error)]
pub enum BvpError {
    /// The damped Newton iteration did not reach the tolerance.
    #[error("Newton iteration did not converge: residual {residual:.3e} after {iterations} iterations (tolerance {tolerance:.1e})")]
    NewtonDiverged { iterations: usize, residual: f64, tolerance: f64 },
    /// The Jacobian was singular (numerically) at the current iterate.
    #[error("singular Jacobian at Newton iteration {iteration}: {detail}")]
    SingularJacobian { iteration: usize, detail: String },
    /// Mesh adaptation hit the node cap before the residual met the tolerance.
    #[error("mesh cap of {max_nodes} nodes reached with scaled residual {residual:.3e} above tolerance {tolerance:.1e}")]
    MeshCapReached { max_nodes: usize, residual: f64, tolerance: f64 },
    /// Mesh adaptation used its maximum number of passes without meeting the
    /// tolerance (collocation `max_refinements`).
    #[error("mesh adaptation stopped after {passes} passes with scaled residual {residual:.3e} above tolerance {tolerance:.1e}")]
    RefinementLimit { passes: usize, residual: f64, tolerance: f64 },
    /// Mesh refinement stopped reducing the residual: [`FLOOR_PASSES`] refinement passes
    /// in a row added nodes without halving the best residual so far, also after
    /// [`DAMPING_PASSES`] halvings of the offending segments — a floor of this problem's
    /// residual above the tolerance.
    ///
    /// [`FLOOR_PASSES`]: crate::collocation::FLOOR_PASSES
    /// [`DAMPING_PASSES`]: crate::collocation::DAMPING_PASSES
    #[error(
        "mesh adaptation reached a residual floor: {floor_passes} refinement passes in a row (now {nodes} nodes) left the scaled residual at {residual:.3e}, best {best:.3e}, above tolerance {tolerance:.1e}, also after halving the offending segments — a floor of this problem's residual (round-off, or a fast mode the mesh cannot resolve); a tolerance of {attainable:.0e} or looser is attainable",
        floor_passes = crate::collocation::FLOOR_PASSES
    )]
    ResidualFloor { nodes: usize, residual: f64, best: f64, tolerance: f64, attainable: f64 },
    /// A fold could not be located between two branch points.
    #[error("fold location between eta = {eta_a:.9e} and eta = {eta_b:.9e} failed: {detail}")]
    FoldLocationFailed { eta_a: f64, eta_b: f64, detail: String },
    /// The ODE integrator (shooting) failed.
    #[error("ODE integration failed on segment {segment} near x = {x:.6}: {detail}")]
    IntegrationFailed { segment: usize, x: f64, detail: String },
    /// Continuation could not advance: step size fell below its minimum.
    #[error("continuation stalled at eta = {eta:.9e}: step {step:.3e} below minimum {min_step:.1e} ({cause})")]
    ContinuationStalled { eta: f64, step: f64, min_step: f64, cause: String },
    /// A residual or state became non-finite.
    #[error("non-finite value in {what}")]
    NonFinite { what: String },
    /// Options or guess inconsistent with the problem.
    #[error("invalid input: {0}")]
    InvalidInput(String),
}

/// A sparse factorisation or solve failure as the BVP engine reports it: a singular or
/// non-finite Jacobian, or an inconsistent pattern (a bug in the caller).
impl From<numerics::LinearError> for BvpError {
    fn from(e: numerics::LinearError) -> Self {
        use numerics::LinearError as L;
        match e {
            L::NonFiniteMatrix { .. } => BvpError::NonFinite { what: "Jacobian entries".into() },
            L::Singular { .. } | L::SingularSchur { .. } | L::NonFiniteSolution => {
                BvpError::SingularJacobian { iteration: 0, detail: e.to_string() }
            }
            L::InvalidPattern { .. } | L::DimensionMismatch { .. } | L::NotFactorised => {
                BvpError::InvalidInput(format!("sparse LU: {e}"))
            }
        }
    }
}

/// A Newton failure as the BVP engine reports it: iteration limit, exhausted damping and
/// a failed line search are [`BvpError::NewtonDiverged`] with the last scaled correction
/// as `residual`; a failing factorisation or solve carries its iteration.
impl From<numerics::newton::NewtonError<BvpError>> for BvpError {
    fn from(e: numerics::newton::NewtonError<BvpError>) -> Self {
        use numerics::newton::{NewtonError as N, Stage};
        match e {
            N::InvalidOptions(_) | N::DimensionMismatch { .. } => BvpError::InvalidInput(e.to_string()),
            N::NonFinite { what, .. } => BvpError::NonFinite { what: what.to_string() },
            N::MaxIterations { iterations, correction, tolerance, .. } => {
                BvpError::NewtonDiverged { iterations, residual: correction, tolerance }
            }
            N::DampingExhausted { iteration, correction, tolerance, .. }
            | N::LineSearchFailed { iteration, correction, tolerance, .. } => {
                BvpError::NewtonDiverged { iterations: iteration, residual: correction, tolerance }
            }
            N::SingularStep { iteration, .. } => BvpError::SingularJacobian {
                iteration,
                detail: "non-finite Newton correction (numerically singular Jacobian)".into(),
            },
            N::Problem { iteration, stage: Stage::Factorize | Stage::Solve, error } => match error {
                BvpError::SingularJacobian { detail, .. } => BvpError::SingularJacobian { iteration, detail },
                other => other,
            },
            N::Problem { stage: Stage::Residual, error, .. } => error,
        }
    }
}

/// `Ok` if `value` lies in (0, 1] (the range of the options' fractions: damping floors,
/// tolerance ratios), else [`BvpError::InvalidInput`] naming the option `name`.
pub(crate) fn check_fraction(name: &str, value: f64) -> Result<(), BvpError> {
    if value > 0.0 && value <= 1.0 {
        Ok(())
    } else {
        Err(BvpError::InvalidInput(format!("{name} {value:e} outside (0, 1]")))
    }
}
