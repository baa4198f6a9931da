//! `rod-gauss`: Kirchhoff rod (extensible, unshearable), every term by the 3-point Gauss
//! rule, C¹ augmented transitions (docs/fem-rod.md §3, §4).

use super::{biot_density, Formulation, TermRules, Theory};
use crate::kinematics::Scalar;
use crate::quadrature::Rule;

/// Kirchhoff rod: membrane ½EA(λ − 1)² (Biot), bending ½EI κ², gravity and penalty
/// contact all by 3-point Gauss — the formulation §7.3 warns about (membrane locking
/// where elements are bent to or straightened from the pulley's curvature), kept beside
/// `rod-simpson` to show it. Derivatives by the per-point AD path with the chain rule
/// through the augmented map (K9).
#[derive(Debug, Clone, Copy, Default)]
pub struct RodGauss;

impl Formulation for RodGauss {
    fn name(&self) -> &'static str {
        "rod-gauss"
    }

    fn description(&self) -> &'static str {
        "Kirchhoff rod, Biot strain, Hermite cubics (eq. 43) with C¹ augmented transitions (§7.2), 3-point Gauss rule for every term"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn theory(&self) -> Theory {
        Theory::Kirchhoff
    }

    fn rules(&self) -> TermRules {
        TermRules { strain: Rule::Gauss(3), gravity: Rule::Gauss(3), contact: Rule::Gauss(3), bending: Rule::Gauss(3) }
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}
