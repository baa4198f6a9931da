//! The stiffness coefficients of (19) ([`ShellSection`]) and the pointwise energy
//! functions of the shell (docs/fem-shell.md (S5), (S7)–(S10)): Green's membrane strain
//! E = ½(F*ᵀ C° F* − I) from the material derivatives (37) with the camber's intrinsic
//! strain F* = diag(1/ℓ*(ζ), 1), and the quadratic energy ½(A₁ (tr T)² + A₂ T··T) that
//! serves the membrane (T = E) and the bending (T = K, coefficients D₁, D₂). The kernel
//! that integrates them is [`super::kernel::Shell`].

use crate::Scalar;

use super::ShellError;
/// The stiffness coefficients of (19): membrane A₁, A₂ (N/m), bending D₁, D₂ (N m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellSection {
    /// A₁ = Ehν/(1 − ν²).
    pub a1: f64,
    /// A₂ = Eh/(1 + ν).
    pub a2: f64,
    /// D₁ = Eh³ν/(12(1 − ν²)).
    pub d1: f64,
    /// D₂ = Eh³/(12(1 + ν)).
    pub d2: f64,
}

impl ShellSection {
    /// The isotropic plate in plane stress (docs/fem-shell.md §3, [L]): Young's modulus E
    /// (Pa), Poisson's ratio ν ∈ (−1, ½), thickness h (m).
    ///
    /// # Errors
    /// [`ShellError::BadParameter`] naming the value out of range.
    pub fn isotropic(youngs_modulus: f64, poisson_ratio: f64, thickness: f64) -> Result<ShellSection, ShellError> {
        let positive = |what: &'static str, value: f64| if value.is_finite() && value > 0.0 { Ok(()) } else { Err(ShellError::BadParameter { what, value }) };
        positive("Young's modulus", youngs_modulus)?;
        positive("thickness", thickness)?;
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(ShellError::BadParameter { what: "Poisson's ratio", value: poisson_ratio });
        }
        let (eh, nu) = (youngs_modulus * thickness, poisson_ratio);
        let bending = eh * thickness * thickness / 12.0;
        Ok(ShellSection { a1: eh * nu / (1.0 - nu * nu), a2: eh / (1.0 + nu), d1: bending * nu / (1.0 - nu * nu), d2: bending / (1.0 + nu) })
    }
}

/// Green's membrane strain [E_ss, E_sζ, E_ζζ] in the initial frame (S8) from the
/// material derivatives (37) `[∂̊_s r, ∂̊_ζ r]` (components on any orthonormal frame) and
/// the camber factor f = 1/ℓ*(ζ): E = ½(F*ᵀ C° F* − I), F* = diag(f, 1).
pub fn strain<D: Scalar>(derivatives: &[[D; 3]; 2], f: f64) -> [D; 3] {
    let [rs, rz] = derivatives;
    [(dot(rs, rs) * (f * f) - 1.0) * 0.5, dot(rs, rz) * (0.5 * f), (dot(rz, rz) - 1.0) * 0.5]
}

/// ½(A₁ (tr E)² + A₂ E··E) of a symmetric 2 × 2 tensor [T_ss, T_sζ, T_ζζ] with the
/// coefficients (A₁, A₂) (membrane) or (D₁, D₂) (bending) of (19): J/m² per initial area.
pub fn quadratic_energy<D: Scalar>(first: f64, second: f64, t: &[D; 3]) -> D {
    let trace = t[0] + t[2];
    let contraction = t[0] * t[0] + t[1] * t[1] * 2.0 + t[2] * t[2];
    (trace * trace * first + contraction * second) * 0.5
}

/// The linear response ∂/∂T of [`quadratic_energy`]: first tr T I + second T,
/// [ss, sζ, ζζ] (membrane forces from E, bending moments from K).
pub fn response(first: f64, second: f64, t: &[f64; 3]) -> [f64; 3] {
    let trace = t[0] + t[2];
    [first * trace + second * t[0], second * t[1], first * trace + second * t[2]]
}

/// a · b of two 3-vectors.
pub(crate) fn dot<D: Scalar>(a: &[D; 3], b: &[D; 3]) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
