//! `string-gauss`: extensible string, Biot strain, Gauss 3-point rule for every term.

use super::{biot_density, Formulation, TermRules};
use crate::kinematics::Scalar;
use crate::quadrature::Rule;

/// Extensible string, Biot strain (N = EA(λ − 1)), strain energy, gravity and penalty
/// contact all integrated with the 3-point Gauss rule (exact to degree 5)
/// (docs/fem-string.md §6).
#[derive(Debug, Clone, Copy, Default)]
pub struct StringGauss;

impl Formulation for StringGauss {
    fn name(&self) -> &'static str {
        "string-gauss"
    }

    fn description(&self) -> &'static str {
        "extensible string, Biot strain, Hermite cubics (eq. 43), 3-point Gauss rule for strain, gravity and penalty contact"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn rules(&self) -> TermRules {
        TermRules { strain: Rule::Gauss(3), gravity: Rule::Gauss(3), contact: Rule::Gauss(3), bending: Rule::Gauss(3) }
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}
