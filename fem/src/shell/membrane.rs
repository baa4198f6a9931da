//! The shell's membrane energy (docs/fem-shell.md (S2), (S5), (S7)–(S10)) as a
//! [`SurfaceKernel`]: ½(A₁ (tr E)² + A₂ E··E) per initial area with
//! E = ½(F*ᵀ C° F* − I), C° the metric of the material derivatives (37), F* the camber's
//! intrinsic strain diag(1/ℓ*(ζ), 1), ℓ* = 1 − κ_c ζ; per dσ dζ times ∂σS ℓ*. Rule:
//! Simpson in σ × Gauss 3 in ζ (§7.3). The unknown S is the periodic part S̃ of the gauge
//! S = c₀σ + S̃ (S2): the kernel reads ∂σS̃ and adds c₀.
//!
//! The point values are those of the plain BFS fields: elements at a Cartesian/polar
//! transition need the augmented map of [`super::transition`] in the assembler
//! (docs/fem-shell.md §5, "In assembly") before this kernel runs on a drive's contour;
//! on a straight strip (α = 0) or inside an arc it is complete.

use crate::element::{ElementLayout, Field, SHELL};
use crate::quadrature::Rule;
use crate::surface::assembly::{PointDerivative, PointVariable, SurfaceKernel, SurfacePoint, SurfaceTerm};
use crate::Scalar;

use super::transition::{material_derivatives, NU, S, Z};
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

/// The point values the membrane reads, in the density's argument order: ∂σS̃, ∂ζS, ν,
/// ∂σν, ∂ζν, ∂σz, ∂ζz.
const VARIABLES: [(Field, PointDerivative); 7] = [
    (Field::S, PointDerivative::DSigma),
    (Field::S, PointDerivative::DZeta),
    (Field::Nu, PointDerivative::Value),
    (Field::Nu, PointDerivative::DSigma),
    (Field::Nu, PointDerivative::DZeta),
    (Field::Z, PointDerivative::DSigma),
    (Field::Z, PointDerivative::DZeta),
];

/// The membrane energy of a shell on a mesh whose σ-columns have the curvatures `alpha`.
#[derive(Debug, Clone, PartialEq)]
pub struct Membrane {
    section: ShellSection,
    gauge: f64,
    camber: f64,
    alpha: Vec<f64>,
    zeta_elements: usize,
}

impl Membrane {
    /// The membrane of `section` with gauge c₀ = L_ref/L_geom (> 0), camber curvature κ_c
    /// (1/m), α per σ-column (e.g. [`super::transition::Column::alpha`]) and n_ζ elements
    /// across (element e is in column e / n_ζ).
    ///
    /// # Errors
    /// [`ShellError::BadParameter`]: c₀ not finite and positive, κ_c not finite, n_ζ = 0,
    /// no column.
    pub fn new(section: ShellSection, gauge: f64, camber: f64, alpha: Vec<f64>, zeta_elements: usize) -> Result<Membrane, ShellError> {
        if !(gauge.is_finite() && gauge > 0.0) {
            return Err(ShellError::BadParameter { what: "gauge c₀", value: gauge });
        }
        if !camber.is_finite() {
            return Err(ShellError::BadParameter { what: "camber curvature", value: camber });
        }
        if zeta_elements == 0 || alpha.is_empty() {
            return Err(ShellError::BadParameter { what: "elements (columns × n_ζ)", value: (alpha.len() * zeta_elements) as f64 });
        }
        Ok(Membrane { section, gauge, camber, alpha, zeta_elements })
    }

    /// ℓ*(ζ) = 1 − κ_c ζ: initial length of the fibre at ζ per reference length (S9).
    pub fn fibre_length(&self, zeta: f64) -> f64 {
        1.0 - self.camber * zeta
    }

    /// α of the column holding `at`.
    fn alpha(&self, at: &SurfacePoint) -> f64 {
        self.alpha[at.element / self.zeta_elements]
    }

    /// Green's membrane strain [E_ss, E_sζ, E_ζζ] in the initial frame (S8) at `at`
    /// from the point values `v` (argument order of the kernel), and ∂σS.
    pub fn strain<D: Scalar>(&self, at: &SurfacePoint, v: &[D; 7]) -> ([D; 3], D) {
        let mut fields = [[D::zero(); 6]; 3];
        let s_sigma = v[0] + self.gauge;
        fields[S][1] = s_sigma;
        fields[S][2] = v[1];
        fields[NU][..3].copy_from_slice(&v[2..5]);
        fields[Z][1] = v[5];
        fields[Z][2] = v[6];
        let [rs, rz] = material_derivatives(self.alpha(at), &fields);
        let dot = |a: &[D; 3], b: &[D; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let f = 1.0 / self.fibre_length(at.zeta);
        ([(dot(&rs, &rs) * (f * f) - 1.0) * 0.5, dot(&rs, &rz) * (0.5 * f), (dot(&rz, &rz) - 1.0) * 0.5], s_sigma)
    }

    /// The membrane forces N = A₁ tr E I + A₂ E, [N_ss, N_sζ, N_ζζ] (second
    /// Piola–Kirchhoff, per initial length, N/m) at `at`.
    pub fn forces(&self, at: &SurfacePoint, v: &[f64; 7]) -> [f64; 3] {
        let ([ess, esz, ezz], _) = self.strain(at, v);
        let (a1, a2) = (self.section.a1, self.section.a2);
        [a1 * (ess + ezz) + a2 * ess, a2 * esz, a1 * (ess + ezz) + a2 * ezz]
    }
}

impl SurfaceKernel<7> for Membrane {
    fn layout(&self) -> ElementLayout {
        SHELL
    }

    fn variables(&self) -> [PointVariable; 7] {
        VARIABLES.map(|(field, derivative)| PointVariable { field, derivative })
    }

    fn terms(&self) -> Vec<SurfaceTerm> {
        vec![SurfaceTerm { rule: [Rule::Simpson, Rule::Gauss(3)], history: 0 }]
    }

    /// ½(A₁ (tr E)² + A₂ E··E) ∂σS ℓ* (S10).
    fn density<D: Scalar>(&self, _term: usize, at: &SurfacePoint, v: &[D; 7], _state: &[f64]) -> D {
        let ([ess, esz, ezz], s_sigma) = self.strain(at, v);
        let trace = ess + ezz;
        let contraction = ess * ess + esz * esz * 2.0 + ezz * ezz;
        (trace * trace * self.section.a1 + contraction * self.section.a2) * s_sigma * (0.5 * self.fibre_length(at.zeta))
    }

    /// ∂σS > 0 and a positive initial fibre length.
    fn admissible(&self, at: &SurfacePoint, v: &[f64; 7]) -> bool {
        v[0] + self.gauge > 0.0 && self.fibre_length(at.zeta) > 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::assembly::{Evaluation, SurfaceAssembler};
    use crate::surface::mesh::SurfaceMesh;
    use crate::test_rng::Rng;

    /// Eh = 1000 N/m, ν_P = 0.3, h = 0.01 m.
    fn section() -> ShellSection {
        ShellSection::isotropic(1.0e5, 0.3, 0.01).unwrap()
    }

    fn static_ev() -> Evaluation<'static> {
        Evaluation { time: 0.0, dt: 0.0, history: None }
    }

    /// A flat periodic strip (α = 0) of length 2 m and width 0.6 m stretched uniformly:
    /// S = σ/λ₁ (c₀ = 1/λ₁, S̃ = 0), ν = 0, z = λ₂ζ. With free edges (E₂₂ = −ν_P E₁₁,
    /// exact in Green's strain since A₁/(A₁ + A₂) = ν_P) it is an equilibrium with
    /// N_ss = Eh E₁₁, N_ζζ = N_sζ = 0 and U = ½ Eh E₁₁² × (initial area c₀ L b) — the
    /// membrane patch test (docs/fem-shell.md V-2). Suppressing the contraction (λ₂ = 1)
    /// leaves a lateral force at the free edges: the gradient is not zero.
    #[test]
    fn uniform_stretch_of_a_flat_strip_gives_the_exact_membrane_force() {
        let (lambda, nu_p, eh) = (1.02, 0.3, 1000.0);
        let e11 = 0.5 * (lambda * lambda - 1.0);
        let mesh = SurfaceMesh::mapped(2.0, 6, |u| u + 0.1 * (std::f64::consts::TAU * u).sin(), [-0.3, 0.3], 3).unwrap();
        let membrane = Membrane::new(section(), 1.0 / lambda, 0.0, vec![0.0; 6], 3).unwrap();
        let asm = SurfaceAssembler::new(mesh, membrane, &[]).unwrap();
        let scale = eh * e11 * 0.6; // the axial force of the strip, N
        for (lateral, free) in [((1.0 - 2.0 * nu_p * e11).sqrt(), true), (1.0, false)] {
            let z_field = move |_: f64, zeta: f64| [lateral * zeta, 0.0, lateral, 0.0];
            let z = asm.interpolate(&[(Field::Z, &z_field)]);
            let (energy, gradient) = asm.gradient(&z, &static_ev()).unwrap();
            let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
            let at = SurfacePoint { sigma: 0.7, zeta: 0.1, element: 7, time: 0.0, dt: 0.0 };
            let forces = asm.kernel().forces(&at, &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, lateral]);
            if free {
                let exact = 0.5 * eh * e11 * e11 * (2.0 / lambda) * 0.6;
                assert!((energy - exact).abs() < 1e-13 * exact, "U = {energy} vs {exact}");
                assert!(largest < 1e-12 * scale, "not in equilibrium: largest gradient entry {largest:e}");
                assert!((forces[0] - eh * e11).abs() < 1e-13 * eh * e11 && forces[1].abs() < 1e-15 * eh * e11 && forces[2].abs() < 1e-13 * eh * e11, "N = {forces:?}");
            } else {
                assert!(largest > 1e-3 * scale, "edge force of the suppressed contraction not seen: {largest:e}");
                assert!(forces[2] > 0.1 * eh * e11, "N_ζζ = {} should be ν_P N_ss", forces[2]);
            }
        }
    }

    /// Gradient and Hessian of the assembled membrane (camber, polar and Cartesian
    /// columns, a random state near the reference) against central differences along
    /// random directions; and the two zero modes of docs/fem-shell.md §1, §9: a constant
    /// added to S̃ or to z leaves the energy unchanged.
    #[test]
    fn membrane_derivatives_match_central_differences_and_zero_modes_are_free() {
        let mesh = SurfaceMesh::new(1.7, vec![0.0, 0.3, 0.55, 0.9, 1.3], vec![-0.3, 0.05, 0.3]).unwrap();
        let membrane = Membrane::new(section(), 1.03, 0.4, vec![0.0, 0.0, 1.0 / 0.3, 1.0 / 0.3, 0.0], 2).unwrap();
        let asm = SurfaceAssembler::new(mesh, membrane, &[]).unwrap();
        let mut rng = Rng(0x3e3b_0a11);
        let mut r = |scale: f64| scale * (2.0 * rng.next() - 1.0);
        let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
        let z: Vec<f64> = reference.iter().map(|v| v + r(0.03)).collect();
        let ev = static_ev();
        let assembled = asm.assemble(&z, &ev).unwrap();
        let (rows, cols) = asm.pattern();
        let step = 1e-6;
        for _ in 0..6 {
            let d: Vec<f64> = z.iter().map(|_| r(1.0)).collect();
            let shifted = |t: f64| -> Vec<f64> { z.iter().zip(&d).map(|(a, b)| a + t * b).collect() };
            let (ep, gp) = asm.gradient(&shifted(step), &ev).unwrap();
            let (em, gm) = asm.gradient(&shifted(-step), &ev).unwrap();
            let slope: f64 = assembled.gradient.iter().zip(&d).map(|(g, v)| g * v).sum();
            let fd = (ep - em) / (2.0 * step);
            assert!((slope - fd).abs() < 1e-6 * slope.abs().max(1e-3 * assembled.energy), "directional derivative {slope} vs {fd}");
            let mut hd = vec![0.0; z.len()];
            for ((&i, &j), &h) in rows.iter().zip(cols).zip(&assembled.values) {
                hd[i] += h * d[j];
            }
            let largest = hd.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for ((p, m), h) in gp.iter().zip(&gm).zip(&hd) {
                assert!(((p - m) / (2.0 * step) - h).abs() < 1e-6 * largest, "Hessian × direction {h} vs {}", (p - m) / (2.0 * step));
            }
        }
        for field in [Field::S, Field::Z] {
            let constant = asm.interpolate(&[(field, &|_: f64, _: f64| [0.37, 0.0, 0.0, 0.0])]);
            let moved: Vec<f64> = z.iter().zip(&constant).map(|(a, b)| a + b).collect();
            let energy = asm.energy(&moved, &ev).unwrap();
            assert!((energy - assembled.energy).abs() < 1e-13 * assembled.energy, "{field:?} + const changes U: {energy} vs {}", assembled.energy);
        }
    }
}
