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

/// One balance of a run held against its tolerance.
#[derive(Debug, Clone, PartialEq)]
pub struct Balance {
    /// Which balance: "closure defect" or "power imbalance".
    pub name: &'static str,
    /// Its value (N or W).
    pub value: f64,
    /// Unit of `value` and `scale`.
    pub unit: &'static str,
    /// The scale it is measured against (N or W).
    pub scale: f64,
    /// What the scale is ("belt weight ρgL", "force scale F_ref", "power scale P_ref").
    pub scale_name: &'static str,
    /// The relative tolerance.
    pub tolerance: f64,
}

impl std::fmt::Display for Balance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} {:.3e} {} exceeds {:.1e} × the scene's {} {:.3e} {}",
            self.name, self.value, self.unit, self.tolerance, self.scale_name, self.scale, self.unit
        )
    }
}

impl Balance {
    /// |value| ≤ tolerance · scale, else [`BeltError::BalanceFailed`] with the numbers.
    pub fn check(self) -> Result<(), BeltError> {
        if self.value.abs() <= self.tolerance * self.scale { Ok(()) } else { Err(BeltError::BalanceFailed(self)) }
    }
}

/// Check the closure defect `defect` (N) against the belt weight `weight` = ρgL (N) or,
/// without gravity, the force scale `force_scale` = F_ref (N).
pub fn check_closure(defect: f64, weight: f64, force_scale: f64) -> Result<(), BeltError> {
    let (scale, scale_name) = closure_scale(weight, force_scale);
    Balance { name: "closure defect", value: defect, unit: "N", scale, scale_name, tolerance: CLOSURE_TOLERANCE }.check()
}

/// The closure check of a frictionless loop of unstretched length `length` (m): its
/// closure defect against the belt's weight ρgL.
pub fn check_loop_closure<L: super::law::SectionLaw>(sol: &super::solution::BeltSolution<L>, length: f64) -> Result<(), BeltError> {
    check_closure(sol.closure_defect().unwrap_or(0.0), sol.pulleys.weight * length, sol.scales.force)
}

/// Check the power imbalance `imbalance` (W) against `power_scale` = P_ref (W).
pub fn check_power(imbalance: f64, power_scale: f64) -> Result<(), BeltError> {
    let scale_name = "power scale P_ref";
    Balance { name: "power imbalance", value: imbalance, unit: "W", scale: power_scale, scale_name, tolerance: POWER_TOLERANCE }.check()
}

/// The power scale P_ref of a drive's balance check (W): the scene's transmitted power
/// |(M₂ + d₂ω₁) ω₁|, or F_ref |ω₁|R (`force_scale` = F_ref) for a drive without load.
pub fn drive_power_scale(d: &crate::string_drive::StringDrive, force_scale: f64) -> f64 {
    let resisting = (d.net_load() * d.driver_speed).abs();
    if resisting > 0.0 { resisting } else { force_scale * d.driver_speed.abs() * d.radius }
}

/// Power balance of a steady drive with data `d` (W): (input M_in ω₁, output
/// (M₂ + d₂ω₂) ω₂, slip dissipation D = Σ ∫_slip f_t (ωR − cλ) ds), the dissipation by
/// 5-point Gauss–Legendre quadrature on each mesh interval of the dense output
/// (docs/string-drive.md, "Torques, power"; the Cosserat drive's D-3). Any law on the
/// drive topology whose points carry the torque, the friction and the stretch.
pub fn drive_power<L: super::law::SectionLaw>(sol: &super::solution::BeltSolution<L>, d: &crate::string_drive::StringDrive) -> (f64, f64, f64) {
    use super::topology::Pulley;
    let input = -sol.torque(Pulley::Driver).expect("the drive integrates the torque") * d.driver_speed;
    let omega2 = sol.driven_speed().expect("a drive has its motion");
    let output = (d.driven_torque + d.driven_damping * omega2) * omega2;
    let dissipation = [(Pulley::Driven, omega2), (Pulley::Driver, d.driver_speed)]
        .into_iter()
        .map(|(pulley, omega)| sol.slip_dissipation(pulley, omega).expect("a drive has slip arcs"))
        .sum();
    (input, output, dissipation)
}
