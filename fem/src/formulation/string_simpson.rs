//! `string-simpson` (the default): extensible string, Biot strain, every term with the
//! Simpson rule — the sampling points ξ = −1, 0, 1 at which §7.3 (Fig. 7) shows the
//! Hermite element reproduces a bent configuration's strain best.

use super::{biot_density, Formulation, TermRules};
use crate::kinematics::Scalar;
use crate::quadrature::Rule;

/// Extensible string, Biot strain; Simpson rule (ξ = −1, 0, 1) for the strain energy,
/// gravity and penalty contact. §7.3 of the reference recommends Simpson for the
/// membrane energy against membrane locking; for the contact it recommends the
/// trapezoidal rule (nodes only) with augmented Lagrangians — with a penalty on a stiff
/// string that lets the belt cut chords through the pulley between the nodes (a length
/// error O(h²/R²) larger than the belt strain on coarse meshes), so the contact is
/// sampled at the Simpson points too (docs/fem-string.md §6).
#[derive(Debug, Clone, Copy, Default)]
pub struct StringSimpson;

impl Formulation for StringSimpson {
    fn name(&self) -> &'static str {
        "string-simpson"
    }

    fn description(&self) -> &'static str {
        "extensible string, Biot strain, Hermite cubics (eq. 43), Simpson rule (ξ = −1, 0, 1) for strain, gravity and penalty contact (§7.3)"
    }

    fn strain_measure(&self) -> &'static str {
        "Biot"
    }

    fn rules(&self) -> TermRules {
        TermRules { strain: Rule::Simpson, gravity: Rule::Simpson, contact: Rule::Simpson, bending: Rule::Gauss(3) }
    }

    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D {
        biot_density(stretch, axial_stiffness)
    }
}
