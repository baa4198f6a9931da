//! The one options struct of every belt problem (string, Kirchhoff rod, string drive) and
//! of a scene's BVP run: the scene's `bvp` block plus the homotopy settings.

use serde::Serialize;

use crate::collocation::Scheme;
use crate::problem::JacobianMode;

/// The two BVP methods of the final solve: the scene's own `bvp.method` type.
pub use drive::scene::BvpMethod;

/// Options of a belt BVP run. The final tolerance is held here once: the homotopy and
/// the final solve read it from this struct, no copy is made on the way down.
#[derive(Debug, Clone, Serialize)]
pub struct BeltOptions {
    /// Method of the final solve (scene `bvp.method`). Default: collocation.
    pub method: BvpMethod,
    /// Tolerance of the final solve, in the method's own definition (collocation: the
    /// relative residual norm of [`crate::collocation`]; shooting: the scaled matching
    /// defect of [`crate::shooting`]). Scene `bvp.tolerance`; default 1e-8; valid
    /// (1e-13, 1e-2].
    pub tolerance: f64,
    /// Collocation scheme of the final solve (scene `bvp.scheme`). Default: gauss8
    /// ([`Scheme::default`]).
    pub scheme: Scheme,
    /// Mesh cap of every collocation solve, total nodes (scene `bvp.max_nodes`).
    /// Default 20 000.
    pub max_nodes: usize,
    /// Shooting intervals per segment (scene `bvp.shooting_intervals`). Default 8.
    pub shooting_intervals: usize,
    /// Jacobians by AD (default) or finite differences.
    pub jacobian: JacobianMode,
    /// Tolerance of the collocation solves along the homotopy path (always gauss6).
    /// Default 1e-5.
    pub homotopy_tolerance: f64,
    /// Kirchhoff rod only: boundary-layer length √(EI₀/T) of the homotopy start,
    /// relative to H. Default 0.05; valid: finite and > 0.
    pub start_layer: f64,
}

impl Default for BeltOptions {
    fn default() -> Self {
        Self {
            method: BvpMethod::Collocation,
            tolerance: 1e-8,
            scheme: Scheme::default(),
            max_nodes: 20_000,
            shooting_intervals: 8,
            jacobian: JacobianMode::Ad,
            homotopy_tolerance: 1e-5,
            start_layer: 0.05,
        }
    }
}

/// The BVP solvers' final tolerance range (lower bound exclusive, upper inclusive): below
/// 1e-13 the residual estimate of a double-precision solve is round-off.
pub const TOLERANCE_RANGE: (f64, f64) = (1e-13, 1e-2);

/// Whether `t` lies in [`TOLERANCE_RANGE`].
pub fn tolerance_in_range(t: f64) -> bool {
    t > TOLERANCE_RANGE.0 && t <= TOLERANCE_RANGE.1
}

impl BeltOptions {
    /// Collocation with `scheme` at `tolerance`, other options default.
    pub fn collocation(scheme: Scheme, tolerance: f64) -> Self {
        Self { method: BvpMethod::Collocation, scheme, tolerance, ..Self::default() }
    }

    /// Shooting at `tolerance`, other options default.
    pub fn shooting(tolerance: f64) -> Self {
        Self { method: BvpMethod::Shooting, tolerance, ..Self::default() }
    }

    /// Scheme/intervals and tolerance in words.
    pub fn detail(&self) -> String {
        match self.method {
            BvpMethod::Collocation => format!("{}, tolerance {:.0e}", self.scheme.name(), self.tolerance),
            BvpMethod::Shooting => format!("{} intervals per segment, tolerance {:.0e}", self.shooting_intervals, self.tolerance),
        }
    }

    /// The final tolerance within (1e-13, 1e-2] ([`TOLERANCE_RANGE`]).
    pub fn check_tolerance(&self) -> Result<(), super::BeltError> {
        if tolerance_in_range(self.tolerance) {
            Ok(())
        } else {
            Err(super::BeltError::InvalidInput { name: "tolerance", value: self.tolerance, reason: "must lie in (1e-13, 1e-2]" })
        }
    }
}
