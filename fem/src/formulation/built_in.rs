//! The formulations shipped with the crate: each is a list of term units
//! ([`super::StandardTerms`]: Biot strain, gravity, penalty contact and, for the rod,
//! bending) with one integration rule per term — so a built-in formulation is data, one
//! [`BuiltIn`] value, not a type of its own.

use super::{biot_density, Formulation, TermRules, Theory};
use crate::kinematics::Scalar;
use crate::quadrature::Rule;

/// A built-in formulation: Biot strain (N = EA(λ − 1), (S1)), Hermite cubics (eq. 43),
/// the standard terms with the rules `rules`, for the belt theory `theory`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BuiltIn {
    /// Registry name.
    pub name: &'static str,
    /// One line for listings.
    pub description: &'static str,
    /// String or Kirchhoff rod (the rod shares one slope pair per transition and gets
    /// the augmented map, docs/fem-rod.md §3).
    pub theory: Theory,
    /// Rule per term.
    pub rules: TermRules,
}

impl Formulation for BuiltIn {
    fn name(&self) -> &'static str { self.name }
    fn description(&self) -> &'static str { self.description }
    fn strain_measure(&self) -> &'static str { "Biot" }
    fn theory(&self) -> Theory { self.theory }
    fn rules(&self) -> TermRules { self.rules }
    fn strain_energy_density<D: Scalar>(&self, stretch: D, axial_stiffness: f64) -> D { biot_density(stretch, axial_stiffness) }
}

const GAUSS3: Rule = Rule::Gauss(3);

/// `string-simpson` (the default): Simpson rule (ξ = −1, 0, 1) for the strain energy,
/// gravity and penalty contact. §7.3 of the reference recommends Simpson for the
/// membrane energy against membrane locking (the points at which Fig. 7 shows the
/// Hermite element reproduces a bent configuration's strain best); for the contact it
/// recommends the trapezoidal rule (nodes only) with augmented Lagrangians — with a
/// penalty on a stiff string that lets the belt cut chords through the pulley between
/// the nodes (a length error O(h²/R²) larger than the belt strain on coarse meshes), so
/// the contact is sampled at the Simpson points too (docs/fem-string.md §6).
pub const STRING_SIMPSON: BuiltIn = BuiltIn {
    name: "string-simpson",
    description: "extensible string, Biot strain, Hermite cubics (eq. 43), Simpson rule (ξ = −1, 0, 1) for strain, gravity and penalty contact (§7.3)",
    theory: Theory::String,
    rules: TermRules { strain: Rule::Simpson, gravity: Rule::Simpson, contact: Rule::Simpson, bending: GAUSS3 },
};

/// `string-gauss`: strain energy, gravity and penalty contact all by the 3-point Gauss
/// rule (exact to degree 5) (docs/fem-string.md §6).
pub const STRING_GAUSS: BuiltIn = BuiltIn {
    name: "string-gauss",
    description: "extensible string, Biot strain, Hermite cubics (eq. 43), 3-point Gauss rule for strain, gravity and penalty contact",
    theory: Theory::String,
    rules: TermRules { strain: GAUSS3, gravity: GAUSS3, contact: GAUSS3, bending: GAUSS3 },
};

/// `rod-simpson`: Kirchhoff rod (extensible, unshearable): membrane energy ½EA(λ − 1)²
/// sampled at ξ = −1, 0, 1 (§7.3, Fig. 7: the remedy of membrane locking), bending
/// energy ½EI κ², gravity and penalty contact by 3-point Gauss (docs/fem-rod.md §4 on why
/// not Simpson for the contact); C¹ augmented transitions (K9), derivatives per
/// integration point by each term's chain rule (`PointJet`) and the chain rule through
/// the map (docs/fem-rod.md §4).
pub const ROD_SIMPSON: BuiltIn = BuiltIn {
    name: "rod-simpson",
    description: "Kirchhoff rod, Biot strain, Hermite cubics (eq. 43) with C¹ augmented transitions (§7.2), Simpson rule for the membrane energy (§7.3), Gauss 3 for bending, gravity and penalty contact",
    theory: Theory::Kirchhoff,
    rules: TermRules { strain: Rule::Simpson, gravity: GAUSS3, contact: GAUSS3, bending: GAUSS3 },
};

/// `rod-gauss`: Kirchhoff rod with every term by 3-point Gauss — the formulation §7.3
/// warns about (membrane locking where elements are bent to or straightened from the
/// pulley's curvature), kept beside `rod-simpson` to show it.
pub const ROD_GAUSS: BuiltIn = BuiltIn {
    name: "rod-gauss",
    description: "Kirchhoff rod, Biot strain, Hermite cubics (eq. 43) with C¹ augmented transitions (§7.2), 3-point Gauss rule for every term",
    theory: Theory::Kirchhoff,
    rules: TermRules { strain: GAUSS3, gravity: GAUSS3, contact: GAUSS3, bending: GAUSS3 },
};
