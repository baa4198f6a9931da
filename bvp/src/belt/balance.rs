//! Every balance a belt solver reports is also a check (issue 12, item 6): a run whose
//! own balance fails is an error, not a result.
//!
//! - **Closure defect** f (string and rod on frictionless pulleys): the tension jump
//!   the discrete solution needs at the driver's first contact; 0 for the exact
//!   solution. Check: |f| ≤ [`CLOSURE_TOLERANCE`] · F_check, where F_check is the
//!   smallest force the answer has to resolve: the belt's weight ρgL with gravity (the
//!   sag is set by it), else the force scale F_ref (the stretched-on tension,
//!   docs/string-hanging.md "Scaling"). A tension so large against the weight that its
//!   round-off exceeds 1e-4 of the weight cannot give the sag: the catalogue string with
//!   a centre distance of 1e50 m returned sags of 1e17 m with a lower span above the
//!   upper one, and a closure defect of 1e23 N against a weight of 1.7 N.
//! - **Power imbalance** of the steady drive: input M_in ω₁ − output (M₂ + d₂ω₂) ω₂ −
//!   slip dissipation D. Check: |imbalance| ≤ [`POWER_TOLERANCE`] · P_ref, where P_ref is
//!   the scene's resisting power (M₂ + d₂ω₁) ω₁, or F_ref ω₁R (force scale times belt
//!   speed) for a drive without load.
//!
//! Both tolerances are 1e-4 relative: far above what a converged solve leaves (the
//! catalogue at tolerance 1e-8: |f| ≤ 1e-14 ρgL, |imbalance| ≤ 1e-9 P_ref) and far below
//! the failures this catches — axial stiffness 1e17…1e50 N or centre distances of 1e50 m,
//! where the stretch λ − 1 = T/EA or the weight vanishes below the round-off of the
//! other terms and the discrete equations no longer see it (power imbalances of 1e-3 to
//! 1e36 times P_ref).

use super::BeltError;

/// Relative tolerance of the closure defect, against the force scale F_ref.
pub const CLOSURE_TOLERANCE: f64 = 1e-4;

/// Relative tolerance of the drive's power imbalance, against F_ref · ω₁R.
pub const POWER_TOLERANCE: f64 = 1e-4;

/// The force a closure defect is measured against (N): the belt weight `weight` = ρgL
/// when it is > 0, else the force scale `force_scale` = F_ref.
pub fn closure_scale(weight: f64, force_scale: f64) -> (f64, &'static str) {
    if weight > 0.0 { (weight, "belt weight ρgL") } else { (force_scale, "force scale F_ref") }
}

/// Check the closure defect `defect` (N) against the belt weight `weight` = ρgL (N) or,
/// without gravity, the force scale `force_scale` = F_ref (N).
pub fn check_closure(defect: f64, weight: f64, force_scale: f64) -> Result<(), BeltError> {
    let (scale, scale_name) = closure_scale(weight, force_scale);
    if defect.abs() <= CLOSURE_TOLERANCE * scale {
        return Ok(());
    }
    Err(BeltError::BalanceFailed {
        balance: "closure defect",
        value: defect,
        unit: "N",
        scale,
        scale_name,
        tolerance: CLOSURE_TOLERANCE,
    })
}

/// Check the power imbalance `imbalance` (W) against `power_scale` = P_ref (W).
pub fn check_power(imbalance: f64, power_scale: f64) -> Result<(), BeltError> {
    if imbalance.abs() <= POWER_TOLERANCE * power_scale {
        return Ok(());
    }
    Err(BeltError::BalanceFailed {
        balance: "power imbalance",
        value: imbalance,
        unit: "W",
        scale: power_scale,
        scale_name: "power scale P_ref",
        tolerance: POWER_TOLERANCE,
    })
}
