//! `rod-simpson`: Kirchhoff rod (extensible, unshearable), Biot membrane strain by the
//! Simpson rule, bending by Gauss 3, C¹ augmented transitions (docs/fem-rod.md §3, §4).

use super::{biot_density, Formulation, TermRules, Theory};
use crate::kinematics::Scalar;
use crate::quadrature::Rule;

/// Kirchhoff rod: membrane energy ½EA(λ − 1)² (Biot) sampled at ξ = −1, 0, 1 (§7.3,
/// Fig. 7: where the Hermite element reproduces a bent state's axial strain best, the
/// remedy of membrane locking), bending energy ½EI κ², gravity and penalty contact by
/// 3-point Gauss (docs/fem-rod.md §4 on why not Simpson for the contact). The element energy includes the augmented map (K9);
/// its derivatives come from the per-point AD path with the chain rule through the map
/// (`formulation::pointwise_derivatives_rod`).
#[derive(Debug, Clone, Copy, Default)]
pub struct RodSimpson;

impl Formulation for RodSimpson {
    fn name(&self) -> &'static str {
        "rod-simpson"
    }

    fn description(&self) -> &'static str {
        "Kirchhoff rod, Biot strain, Hermite cubics (eq. 43) with C¹ augmented transitions (§7.2), Simpson rule for the membrane energy (§7.3), Gauss 3 for bending, gravity and penalty contact"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn theory(&self) -> Theory {
        Theory::Kirchhoff
    }

    fn rules(&self) -> TermRules {
        TermRules { strain: Rule::Simpson, gravity: Rule::Gauss(3), contact: Rule::Gauss(3), bending: Rule::Gauss(3) }
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}
