//! The shell as one [`SurfaceKernel`] (docs/fem-shell.md §3, §6): energy densities per
//! dσ dζ of the membrane (Simpson × Gauss 3) and of bending and gravity (Gauss 3 × 3),
//! (S10), over the fields {S, ν, z} of the
//! Bogner–Fox–Schmit elements, with the augmented C¹ map (S12) at the Cartesian/polar
//! transitions given to the assembler as quadratic products
//! ([`SurfaceKernel::quadratic_terms`]).
//!
//! The unknown S is the periodic part S̃ of the gauge S = c₀(σ − d(t)) + S̃ (S2, S2′;
//! d(t) the drums' travel, 0 at rest): the kernel reads the derivatives of S̃ and adds c₀
//! to ∂σS. Camber enters as the intrinsic strain
//! F* = diag(f, 1), f = 1/ℓ*(ζ), ℓ* = 1 − κ_c ζ (S9); the initial area element is
//! dA* = ∂σS ℓ* dσ dζ (S8). The camber curvature is a piecewise-linear history κ_c(t)
//! read at the point's time ([`Shell::with_camber`]): stage (1) ramps it at rest
//! (docs/fem-shell.md §9.2).

use drive::contour::Contour;
use nalgebra::SVector;
use num_dual::{hessian, Dual2SVec64, Dual64};

use crate::element::{BfsRectangle, ElementLayout, Field, SHELL};
use crate::quadrature::Rule;
use crate::surface::assembly::{CutHistory, PointDerivative, PointVariable, QuadraticTerm, SurfaceKernel, SurfacePoint, SurfaceTerm};
use crate::surface::mesh::SurfaceMesh;
use crate::Scalar;

use super::interlayer::{Foot, Interlayer, Schedule, CONTACT_ENTRY, CONTACT_FLAG, CONTACT_GAP, CONTACT_SHARE, DEFORMATION, ENTRY_RECORD, STATE};
use super::membrane::{self, quadratic_energy, response, ShellSection};
use super::transition::{material_derivatives, Column, ShellElement, TransitionSides, NU, S, Z};
use super::ShellError;

/// Number of point values the shell reads ([`Shell::variables`]).
pub const SHELL_VALUES: usize = 15;

/// The point values in the densities' argument order: S̃ (∂σ, ∂ζ), ν (all six rows),
/// z (∂σ, ∂ζ, ∂²σ, ∂σ∂ζ, ∂²ζ), then S̃ and z themselves — the rows of
/// [`crate::element::SURFACE_DERIVATIVES`] the energy needs. S̃ and z enter the
/// interlayer only (the position against a tilted drum, the material offset of (S13));
/// membrane, bending and gravity are invariant to a material shift and a lateral
/// translation. The second derivatives of S never enter (their terms of the second
/// material derivatives are tangential and drop out of (S6)).
const VARIABLES: [(Field, PointDerivative); SHELL_VALUES] = [
    (Field::S, PointDerivative::DSigma),
    (Field::S, PointDerivative::DZeta),
    (Field::Nu, PointDerivative::Value),
    (Field::Nu, PointDerivative::DSigma),
    (Field::Nu, PointDerivative::DZeta),
    (Field::Nu, PointDerivative::DSigmaSigma),
    (Field::Nu, PointDerivative::DSigmaZeta),
    (Field::Nu, PointDerivative::DZetaZeta),
    (Field::Z, PointDerivative::DSigma),
    (Field::Z, PointDerivative::DZeta),
    (Field::Z, PointDerivative::DSigmaSigma),
    (Field::Z, PointDerivative::DSigmaZeta),
    (Field::Z, PointDerivative::DZetaZeta),
    (Field::S, PointDerivative::Value),
    (Field::Z, PointDerivative::Value),
];

/// Index of the membrane term in [`Shell::terms`].
pub const MEMBRANE: usize = 0;
/// Index of the bending and gravity term in [`Shell::terms`].
pub const BENDING_GRAVITY: usize = 1;
/// Index of the interlayer term in [`Shell::terms`] (present with an interlayer).
pub const INTERLAYER: usize = 2;

/// Where the shell lies, for the heights of gravity: on the contour (g_y(σ), n_g,y(σ) of
/// eq. 27), or a flat horizontal strip at y = 0 with n_g = +j.
#[derive(Debug, Clone, PartialEq)]
enum Placement {
    Contour(Contour),
    Strip,
}

/// The shell on a mesh: section, gauge, camber, the element columns and gravity.
#[derive(Debug, Clone, PartialEq)]
pub struct Shell {
    section: ShellSection,
    gauge: f64,
    /// κ_c(t), 1/m.
    camber: Schedule,
    sides: TransitionSides,
    zeta_elements: usize,
    placement: Placement,
    /// ρ_s h g: weight per initial area, N/m² (0: no gravity).
    weight: f64,
    /// The elastic interlayer with the drums (§7), if any.
    interlayer: Option<Interlayer>,
    /// ζ of the mesh's two edges, m (the fibre lengths checked there).
    edges: [f64; 2],
}

impl Shell {
    /// The shell of `section` laid on `contour` with the mesh `mesh`: gauge
    /// c₀ = L_ref/L_geom (> 0), camber curvature κ_c (1/m).
    ///
    /// # Errors
    /// [`ShellError::BadParameter`] (c₀ not finite and positive, κ_c not finite, a fibre
    /// of non-positive initial length 1 − κ_c ζ on the mesh's width); the errors of
    /// [`TransitionSides::new`] (a transition that is no σ-node, a length mismatch).
    pub fn on_contour(section: ShellSection, gauge: f64, camber: f64, contour: &Contour, mesh: &SurfaceMesh) -> Result<Shell, ShellError> {
        Ok(Shell { placement: Placement::Contour(*contour), ..Shell::with_sides(section, gauge, camber, TransitionSides::new(contour, mesh)?, mesh)? })
    }

    /// The shell as a flat periodic strip (α = 0 on every column, no transition).
    ///
    /// # Errors
    /// As [`Shell::on_contour`] for the parameters.
    pub fn strip(section: ShellSection, gauge: f64, camber: f64, mesh: &SurfaceMesh) -> Result<Shell, ShellError> {
        Shell::with_sides(section, gauge, camber, TransitionSides::strip(mesh.sigma_elements()), mesh)
    }

    /// The shell on given columns (e.g. [`TransitionSides::without_augmentation`] for a
    /// comparison with the plain BFS map); gravity, if set, as on a flat strip.
    ///
    /// # Errors
    /// As [`Shell::on_contour`] for the parameters; a column count other than the mesh's.
    pub fn with_sides(section: ShellSection, gauge: f64, camber: f64, sides: TransitionSides, mesh: &SurfaceMesh) -> Result<Shell, ShellError> {
        if !(gauge.is_finite() && gauge > 0.0) {
            return Err(ShellError::BadParameter { what: "gauge c₀", value: gauge });
        }
        if !camber.is_finite() {
            return Err(ShellError::BadParameter { what: "camber curvature", value: camber });
        }
        if sides.columns() != mesh.sigma_elements() {
            return Err(ShellError::BadParameter { what: "columns of the transition sides", value: sides.columns() as f64 });
        }
        let zeta = mesh.zeta_nodes();
        let shell = Shell {
            section,
            gauge,
            camber: Schedule::constant(0.0),
            sides,
            zeta_elements: mesh.zeta_elements(),
            placement: Placement::Strip,
            weight: 0.0,
            interlayer: None,
            edges: [zeta[0], zeta[zeta.len() - 1]],
        };
        shell.with_camber(Schedule::constant(camber))
    }

    /// The shell with the camber curvature κ_c(t) (1/m; piecewise linear, so the
    /// initial fibre length 1 − κ_c ζ is checked at the schedule's points).
    ///
    /// # Errors
    /// [`ShellError::BadParameter`]: a fibre of non-positive initial length at an edge
    /// of the mesh's width at some point of the schedule.
    pub fn with_camber(self, camber: Schedule) -> Result<Shell, ShellError> {
        for &(_, kappa) in camber.points() {
            for edge in self.edges {
                if 1.0 - kappa * edge <= 0.0 {
                    return Err(ShellError::BadParameter { what: "initial fibre length 1 − κ_c ζ at an edge", value: 1.0 - kappa * edge });
                }
            }
        }
        Ok(Shell { camber, ..self })
    }

    /// The shell with gravity: ρ_s h g, weight per initial area (N/m², ≥ 0).
    ///
    /// # Errors
    /// [`ShellError::BadParameter`] for a weight that is not finite and ≥ 0.
    pub fn with_gravity(self, weight: f64) -> Result<Shell, ShellError> {
        if !(weight.is_finite() && weight >= 0.0) {
            return Err(ShellError::BadParameter { what: "weight per area ρ_s h g", value: weight });
        }
        Ok(Shell { weight, ..self })
    }

    /// The shell with the elastic interlayer `interlayer` against its drums (§7, §8):
    /// a third term ([`INTERLAYER`], the interlayer's σ-rule × its ζ-rule, [`STATE`] history values per
    /// point); the core advects its history by `interlayer.transport`.
    ///
    /// # Errors
    /// [`ShellError::BadParameter`]: the shell is not on a contour, or the interlayer's
    /// numbers ([`Interlayer::validate`]).
    pub fn with_interlayer(self, interlayer: Interlayer) -> Result<Shell, ShellError> {
        if self.placement == Placement::Strip {
            return Err(ShellError::BadParameter { what: "interlayer on a shell that is not on a contour (columns)", value: self.sides.columns() as f64 });
        }
        interlayer.validate()?;
        Ok(Shell { interlayer: Some(interlayer), ..self })
    }

    /// The interlayer, if any.
    pub fn interlayer(&self) -> Option<&Interlayer> {
        self.interlayer.as_ref()
    }

    /// c₀ of the gauge (S2).
    pub fn gauge(&self) -> f64 {
        self.gauge
    }

    /// The section.
    pub fn section(&self) -> ShellSection {
        self.section
    }

    /// ℓ*(ζ) = 1 − κ_c(t) ζ: initial length of the fibre at ζ per reference length (S9)
    /// at time t.
    pub fn fibre_length(&self, zeta: f64, time: f64) -> f64 {
        1.0 - self.camber.at(time) * zeta
    }

    /// The camber history κ_c(t).
    pub fn camber(&self) -> &Schedule {
        &self.camber
    }

    /// The column of element e.
    fn column(&self, element: usize) -> Column {
        self.sides.column(element / self.zeta_elements)
    }

    /// The six derivative rows of S, ν, z from the point values `v` (S with the gauge:
    /// ∂σS = c₀ + ∂σS̃; the rows the energy does not read — S, z and the second
    /// derivatives of S — are 0).
    pub fn fields<D: Scalar>(&self, v: &[D; SHELL_VALUES]) -> [[D; 6]; 3] {
        let mut fields = [[D::zero(); 6]; 3];
        fields[S][1..3].copy_from_slice(&v[0..2]);
        fields[S][1] += self.gauge;
        fields[NU].copy_from_slice(&v[2..8]);
        fields[Z][1..].copy_from_slice(&v[8..13]);
        fields[S][0] = v[13];
        fields[Z][0] = v[14];
        fields
    }

    /// g(σ), t_g(σ), n_g(σ) in the drawing plane: of the contour, or of the flat strip
    /// (g = (σ, 0), t_g = i, n_g = j).
    fn frame(&self, sigma: f64) -> [[f64; 2]; 3] {
        match &self.placement {
            Placement::Contour(contour) => [contour.g(sigma), contour.t_g(sigma), contour.n_g(sigma)],
            Placement::Strip => [[sigma, 0.0], [1.0, 0.0], [0.0, 1.0]],
        }
    }

    /// The position r = g + ν n_g + z k (S1) of the point, global (x, y, z), m.
    pub fn position<D: Scalar>(&self, at: &SurfacePoint, v: &[D; SHELL_VALUES]) -> [D; 3] {
        let [g, _, n] = self.frame(at.sigma);
        [v[2] * n[0] + g[0], v[2] * n[1] + g[1], v[14]]
    }

    /// The lateral force per dσ dζ that each drum exerts on the belt at an interlayer
    /// point, `[driver, driven]` (N/m²): −∂/∂z of the drum's share of V_γ + V_⊥
    /// ([`Interlayer::shares`]) times J = ∂σS — z enters the energy only through the
    /// position r = (…, z), and the foot r_n(foot) is the committed history's, so this is
    /// exactly the integrand of the interlayer's gradient along the lateral translation
    /// z + d (the mode membrane, bending and gravity are blind to). Zeros without an
    /// interlayer.
    pub fn lateral_forces(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES], state: &[f64]) -> [f64; 2] {
        let dual: [Dual64; SHELL_VALUES] = std::array::from_fn(|k| Dual64::new(v[k], if k == 14 { 1.0 } else { 0.0 }));
        self.interlayer_shares(at, &dual, state).map(|w| -w.eps)
    }

    /// The interlayer's density per dσ dζ (V_γ + V_⊥ times J) split by drum,
    /// `[driver, driven]` ([`Interlayer::shares`]); zeros without an interlayer.
    pub(crate) fn interlayer_shares<D: Scalar>(&self, at: &SurfacePoint, v: &[D; SHELL_VALUES], state: &[f64]) -> [D; 2] {
        let Some(interlayer) = &self.interlayer else { return [D::zero(); 2] };
        let foot = self.foot(at, v, state);
        let jacobian = v[0] + self.gauge;
        interlayer.shares(&self.position(at, v), &foot, (at.time, at.dt), state).map(|w| w * jacobian)
    }

    /// r_n(foot) of (S13) at the point from the (advected) interlayer state: the
    /// upstream point σ_r = σ − cΔt and the material offset
    /// δs = S_{n+1}(σ) − S_n(σ_r) = S̃ − S̃_n ([`Interlayer::foot`]); zeros without a
    /// state. The gauge is transported with the drums (docs/fem-shell.md (S2′)):
    /// S = c₀(σ − d(t)) + S̃, d(t) the drums' travel ∫c dt, so the c₀cΔt of one step's
    /// transport cancels in δs and a belt rolling with the drums keeps S̃ — the step's
    /// Newton starts at the rigid rolling, not one step's travel (~h_arc) behind it.
    fn foot<D: Scalar>(&self, at: &SurfacePoint, v: &[D; SHELL_VALUES], state: &[f64]) -> Foot<D> {
        if state.is_empty() {
            return Foot { position: [D::zero(); 3], upstream: [0.0; 3], material: v[13], gauge: self.gauge, own: [0.0; 3] };
        }
        let shift = self.belt_speed(at.time - 0.5 * at.dt) * at.dt;
        let offset = v[13] - Interlayer::material(state);
        let (position, upstream) = Interlayer::foot(state, &self.frame(at.sigma - shift), offset);
        Foot { position, upstream, material: v[13], gauge: self.gauge, own: Interlayer::own_position(state, &self.frame(at.sigma)) }
    }

    /// Green's membrane strain [E_ss, E_sζ, E_ζζ] in the initial frame (S8) at `at`.
    pub fn strain<D: Scalar>(&self, at: &SurfacePoint, v: &[D; SHELL_VALUES]) -> [D; 3] {
        let derivatives = material_derivatives(self.column(at.element).alpha, &self.fields(v));
        membrane::strain(&derivatives, 1.0 / self.fibre_length(at.zeta, at.time))
    }

    /// The change of curvature K = F*ᵀ B° F* (S8), [K_ss, K_sζ, K_ζζ] in the initial
    /// frame, 1/m, at `at`: B° the second fundamental form (S6) of the actual surface in
    /// the material coordinates, b_ij = n · ∂̊_i∂̊_j r with n = ∂̊_s r × ∂̊_ζ r / |…| and the
    /// second derivatives (S4) of the position (b* = 0: flat initial surface).
    pub fn curvature<D: Scalar>(&self, at: &SurfacePoint, v: &[D; SHELL_VALUES]) -> [D; 3] {
        let alpha = self.column(at.element).alpha;
        let fields = self.fields(v);
        let [a, b] = material_derivatives(alpha, &fields);
        let (s, nu, z) = (&fields[S], &fields[NU], &fields[Z]);
        let cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        let norm = membrane::dot(&cross, &cross).sqrt();
        let n = cross.map(|c| c / norm);
        // (S4) in the frame (t_g, n_g, k)
        let r_ss = [nu[1] * (2.0 * alpha), nu[3] - (nu[0] * alpha + 1.0) * alpha, z[3]];
        let r_sz = [nu[2] * alpha, nu[4], z[4]];
        let r_zz = [D::zero(), nu[5], z[5]];
        let b = [membrane::dot(&n, &r_ss), membrane::dot(&n, &r_sz), membrane::dot(&n, &r_zz)];
        self.curvature_of(at, s[1], s[2], &b)
    }

    /// K from ∂σS (with the gauge), ∂ζS and the second fundamental form
    /// b = [b_ss, b_sζ, b_ζζ] in the material coordinates (the last step of
    /// [`Self::curvature`]).
    fn curvature_of<D: Scalar>(&self, at: &SurfacePoint, s_sigma: D, s_zeta: D, b: &[D; 3]) -> [D; 3] {
        let beta = s_zeta / s_sigma;
        let [b_ss, b_rs, b_zz] = *b;
        let f = 1.0 / self.fibre_length(at.zeta, at.time);
        [b_ss / (s_sigma * s_sigma) * (f * f), (b_rs - beta * b_ss) / s_sigma * f, b_zz - beta * b_rs * 2.0 + beta * beta * b_ss]
    }

    /// W_b + W_g per dσ dζ ([`BENDING_GRAVITY`]) from ∂σS (with the gauge), ∂ζS, b and
    /// ν: the outer function of [`Self::bending_hessian`]'s chain rule.
    fn bending_of<D: Scalar>(&self, at: &SurfacePoint, s_sigma: D, s_zeta: D, b: &[D; 3], nu: D) -> D {
        let area = s_sigma * self.fibre_length(at.zeta, at.time);
        let mut w = quadratic_energy(self.section.d1, self.section.d2, &self.curvature_of(at, s_sigma, s_zeta, b));
        if self.weight != 0.0 {
            w += self.height(at.sigma, nu) * self.weight;
        }
        w * area
    }

    /// W_m per dσ dζ ([`MEMBRANE`]) from ∂σS (with the gauge), ∂ζS and the products
    /// P·P, P·Q, Q·Q of P = (να + 1, ∂σν, ∂σz), Q = (0, ∂ζν, ∂ζz): the material
    /// derivatives (37) are a = P/∂σS, b = Q − βP (β = ∂ζS/∂σS), so a·a = P·P/∂σS²,
    /// a·b = (P·Q − β P·P)/∂σS, b·b = Q·Q − 2β P·Q + β² P·P — the outer function of
    /// [`Self::membrane_hessian`]'s chain rule.
    fn membrane_of<D: Scalar>(&self, at: &SurfacePoint, s_sigma: D, s_zeta: D, [pp, pq, qq]: [D; 3]) -> D {
        let f = 1.0 / self.fibre_length(at.zeta, at.time);
        let beta = s_zeta / s_sigma;
        let aa = pp / (s_sigma * s_sigma);
        let ab = (pq - beta * pp) / s_sigma;
        let bb = qq - beta * pq * 2.0 + beta * beta * pp;
        let strain = [(aa * (f * f) - 1.0) * 0.5, ab * (0.5 * f), (bb - 1.0) * 0.5];
        quadratic_energy(self.section.a1, self.section.a2, &strain) * (s_sigma * self.fibre_length(at.zeta, at.time))
    }

    /// W, ∂W/∂v and ∂²W/∂v² of [`MEMBRANE`] over the first 10 point values (its 7 and
    /// zeros; into the first 10 entries of `dw` and of the rows of `ddw`) by the chain
    /// rule through y = (∂σS, ∂ζS, P·P, P·Q, Q·Q) ([`Self::membrane_of`], AD over 5
    /// values): P and Q are linear in v, so ∂²W/∂v² = Jᵀ W_yy J + W_PP 2 ∇Pᵀ∇P +
    /// W_PQ (∇Pᵀ∇Q + ∇Qᵀ∇P) + W_QQ 2 ∇Qᵀ∇Q, J = ∂y/∂v. The AD of
    /// [`SurfaceKernel::density`] is the test oracle.
    fn membrane_hessian(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES], dw: &mut [f64; SHELL_VALUES], ddw: &mut [[f64; SHELL_VALUES]; SHELL_VALUES]) -> f64 {
        const M: usize = 10;
        let alpha = self.column(at.element).alpha;
        let p = [v[2] * alpha + 1.0, v[3], v[8]];
        let q = [0.0, v[4], v[9]];
        let mut dp = [[0.0; M]; 3];
        dp[0][2] = alpha;
        dp[1][3] = 1.0;
        dp[2][8] = 1.0;
        let mut dq = [[0.0; M]; 3];
        dq[1][4] = 1.0;
        dq[2][9] = 1.0;
        let y = SVector::<f64, 5>::from([v[0] + self.gauge, v[1], membrane::dot(&p, &p), membrane::dot(&p, &q), membrane::dot(&q, &q)]);
        let (w, g, h) = hessian(|y| self.membrane_of(at, y[0], y[1], [y[2], y[3], y[4]]), &y);
        let mut jac = [[0.0; M]; 5];
        jac[0][0] = 1.0;
        jac[1][1] = 1.0;
        for c in 0..3 {
            for k in 0..M {
                jac[2][k] += 2.0 * p[c] * dp[c][k];
                jac[3][k] += q[c] * dp[c][k] + p[c] * dq[c][k];
                jac[4][k] += 2.0 * q[c] * dq[c][k];
            }
        }
        let mut gj = [[0.0; M]; 5];
        for i in 0..5 {
            for j in 0..5 {
                let c = h[(i, j)];
                gj[i].iter_mut().zip(&jac[j]).for_each(|(o, jj)| *o += c * jj);
            }
        }
        for a in 0..M {
            dw[a] = (0..5).map(|i| g[i] * jac[i][a]).sum();
            for b in 0..M {
                let mut e: f64 = (0..5).map(|i| jac[i][a] * gj[i][b]).sum();
                for c in 0..3 {
                    e += g[2] * 2.0 * dp[c][a] * dp[c][b] + g[3] * (dp[c][a] * dq[c][b] + dq[c][a] * dp[c][b]) + g[4] * 2.0 * dq[c][a] * dq[c][b];
                }
                ddw[a][b] = e;
            }
        }
        w
    }

    /// W, ∂W/∂v and ∂²W/∂v² of [`BENDING_GRAVITY`] over its 13 point values (into the
    /// first 13 entries of `dw` and rows of `ddw`) by the chain rule through
    /// y = (∂σS, ∂ζS, b_ss, b_sζ, b_ζζ, ν) — the density is W(y) ([`Self::bending_of`],
    /// AD over 6 values) and the only nonlinear inner map is the unit normal: the
    /// material derivatives (37) give a × b = P × Q / ∂σS with P = (να + 1, ∂σν, ∂σz),
    /// Q = (0, ∂ζν, ∂ζz), so n = P × Q / |P × Q| depends on 5 values (AD over those),
    /// and r_ij of (S4) are linear in v: b_k = n · r_k,
    /// ∂²W/∂v² = Jᵀ W_yy J + Σ_c λ_c ∇²n_c + Σ_c (∇n_c ⊗ μ_c + μ_c ⊗ ∇n_c) with
    /// J = ∂y/∂v, λ_c = Σ_k W_{b_k} r_{k,c}, μ_c = Σ_k W_{b_k} ∇r_{k,c}. The same
    /// numbers as the AD of [`SurfaceKernel::density`] over 13 values to round-off, a
    /// fraction of its work (that AD is the test oracle).
    fn bending_hessian(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES], dw: &mut [f64; SHELL_VALUES], ddw: &mut [[f64; SHELL_VALUES]; SHELL_VALUES]) -> f64 {
        const M: usize = 13;
        const NORMAL: [usize; 5] = [2, 3, 4, 8, 9];
        let alpha = self.column(at.element).alpha;
        let x = SVector::<f64, 5>::from_fn(|k, _| v[NORMAL[k]]);
        let normal = hessian(
            |x| {
                let n = unit_normal(&[x[0] * alpha + 1.0, x[1], x[3]], &[Dual2SVec64::<5>::from_re(0.0), x[2], x[4]]);
                (n[0], n[1], n[2])
            },
            &x,
        );
        let normal = [normal.0, normal.1, normal.2];
        let n: [f64; 3] = std::array::from_fn(|c| normal[c].0);
        let mut dn = [[0.0; M]; 3];
        for (c, (_, g, _)) in normal.iter().enumerate() {
            for (k, &p) in NORMAL.iter().enumerate() {
                dn[c][p] = g[k];
            }
        }
        // r_ss, r_sζ, r_ζζ of (S4) and their (constant) derivatives
        let r = [[v[3] * (2.0 * alpha), v[5] - (v[2] * alpha + 1.0) * alpha, v[10]], [v[4] * alpha, v[6], v[11]], [0.0, v[7], v[12]]];
        let mut dr = [[[0.0; M]; 3]; 3];
        dr[0][0][3] = 2.0 * alpha;
        dr[0][1][5] = 1.0;
        dr[0][1][2] = -alpha * alpha;
        dr[0][2][10] = 1.0;
        dr[1][0][4] = alpha;
        dr[1][1][6] = 1.0;
        dr[1][2][11] = 1.0;
        dr[2][1][7] = 1.0;
        dr[2][2][12] = 1.0;
        let b: [f64; 3] = std::array::from_fn(|k| membrane::dot(&n, &r[k]));
        // J = ∂y/∂v
        let mut jac = [[0.0; M]; 6];
        jac[0][0] = 1.0;
        jac[1][1] = 1.0;
        jac[5][2] = 1.0;
        for k in 0..3 {
            for c in 0..3 {
                for p in 0..M {
                    jac[2 + k][p] += dn[c][p] * r[k][c] + n[c] * dr[k][c][p];
                }
            }
        }
        let y = SVector::<f64, 6>::from([v[0] + self.gauge, v[1], b[0], b[1], b[2], v[2]]);
        let (w, g, h) = hessian(|y| self.bending_of(at, y[0], y[1], &[y[2], y[3], y[4]], y[5]), &y);
        let mut gj = [[0.0; M]; 6];
        for i in 0..6 {
            for j in 0..6 {
                let c = h[(i, j)];
                gj[i].iter_mut().zip(&jac[j]).for_each(|(o, jj)| *o += c * jj);
            }
        }
        let lambda: [f64; 3] = std::array::from_fn(|c| (0..3).map(|k| g[2 + k] * r[k][c]).sum());
        let mu: [[f64; M]; 3] = std::array::from_fn(|c| std::array::from_fn(|q| (0..3).map(|k| g[2 + k] * dr[k][c][q]).sum()));
        for p in 0..M {
            dw[p] = (0..6).map(|i| g[i] * jac[i][p]).sum();
            for q in 0..M {
                let mut e: f64 = (0..6).map(|i| jac[i][p] * gj[i][q]).sum();
                for c in 0..3 {
                    e += dn[c][p] * mu[c][q] + mu[c][p] * dn[c][q];
                }
                ddw[p][q] = e;
            }
        }
        for (c, (_, _, hn)) in normal.iter().enumerate() {
            for (k, &p) in NORMAL.iter().enumerate() {
                for (l, &q) in NORMAL.iter().enumerate() {
                    ddw[p][q] += lambda[c] * hn[(k, l)];
                }
            }
        }
        w
    }

    /// The bending moments M = D₁ tr K I + D₂ K, [M_ss, M_sζ, M_ζζ] (per initial length,
    /// N m/m) at `at`.
    pub fn moments(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> [f64; 3] {
        response(self.section.d1, self.section.d2, &self.curvature(at, v))
    }

    /// The height r·j = g_y(σ) + ν n_g,y(σ) of the point (S1), m.
    fn height<D: Scalar>(&self, sigma: f64, nu: D) -> D {
        match &self.placement {
            Placement::Contour(contour) => nu * contour.n_g(sigma)[1] + contour.g(sigma)[1],
            Placement::Strip => nu,
        }
    }

    /// The membrane forces N = A₁ tr E I + A₂ E, [N_ss, N_sζ, N_ζζ] (second
    /// Piola–Kirchhoff, per initial length, N/m) at `at`.
    pub fn forces(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> [f64; 3] {
        response(self.section.a1, self.section.a2, &self.strain(at, v))
    }
}

impl SurfaceKernel<SHELL_VALUES> for Shell {
    fn layout(&self) -> ElementLayout {
        SHELL
    }

    fn variables(&self) -> [PointVariable; SHELL_VALUES] {
        VARIABLES.map(|(field, derivative)| PointVariable { field, derivative })
    }

    /// [`MEMBRANE`]: Simpson × Gauss 3 (§7.3); [`BENDING_GRAVITY`]: Gauss 3 × 3
    /// (docs/fem-shell.md §6: the text is silent, the rod's choice); [`INTERLAYER`]: the
    /// interlayer's σ-rule × its ζ-rule (Gauss 2 by default).
    fn terms(&self) -> Vec<SurfaceTerm> {
        let mut terms = vec![SurfaceTerm { rule: [Rule::Simpson, Rule::Gauss(3)], history: 0 }, SurfaceTerm { rule: [Rule::Gauss(3), Rule::Gauss(3)], history: 0 }];
        if let Some(layer) = &self.interlayer {
            terms.push(SurfaceTerm { rule: [layer.rule, layer.width_rule], history: STATE });
        }
        terms
    }

    /// (S10) per dσ dζ, each per initial area times dA*/(dσ dζ) = ∂σS ℓ*:
    /// [`MEMBRANE`] W_m = ½(A₁ (tr E)² + A₂ E··E); [`BENDING_GRAVITY`]
    /// W_b + W_g = ½(D₁ (tr K)² + D₂ K··K) + ρ_s h g (r·j).
    fn density<D: Scalar>(&self, term: usize, at: &SurfacePoint, v: &[D; SHELL_VALUES], state: &[f64]) -> D {
        if term == INTERLAYER {
            let interlayer = self.interlayer.as_ref().expect("the term exists with an interlayer");
            let foot = self.foot(at, v, state);
            return interlayer.density(&self.position(at, v), &foot, v[0] + self.gauge, (at.time, at.dt), state);
        }
        let area = (v[0] + self.gauge) * self.fibre_length(at.zeta, at.time);
        if term == MEMBRANE {
            return quadratic_energy(self.section.a1, self.section.a2, &self.strain(at, v)) * area;
        }
        let mut w = quadratic_energy(self.section.d1, self.section.d2, &self.curvature(at, v));
        if self.weight != 0.0 {
            w += self.height(at.sigma, v[2]) * self.weight;
        }
        w * area
    }

    /// [`MEMBRANE`]: the first derivatives of S̃, ν, z and ν itself (the material
    /// derivatives (37)), 7 of the 15; [`BENDING_GRAVITY`]: all but S̃ and z themselves,
    /// 13; [`INTERLAYER`]: ∂σS̃ (J), ν and z (the position), S̃ (the foot's offset), 4.
    fn term_variables(&self, term: usize) -> Vec<usize> {
        match term {
            MEMBRANE => vec![0, 1, 2, 3, 4, 8, 9],
            BENDING_GRAVITY => (0..13).collect(),
            _ => vec![0, 2, 13, 14],
        }
    }

    /// [`MEMBRANE`] and [`BENDING_GRAVITY`] by the chain rules of
    /// [`Shell::membrane_hessian`], [`Shell::bending_hessian`]; the interlayer by the
    /// assembler's AD.
    fn point_hessian(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES], _state: &[f64], dw: &mut [f64; SHELL_VALUES], ddw: &mut [[f64; SHELL_VALUES]; SHELL_VALUES]) -> Option<f64> {
        match term {
            MEMBRANE => Some(self.membrane_hessian(at, v, dw, ddw)),
            BENDING_GRAVITY => Some(self.bending_hessian(at, v, dw, ddw)),
            _ => None,
        }
    }

    /// ∂σS > 0 and a regular surface (|∂̊_s r × ∂̊_ζ r| > 0).
    fn admissible(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> bool {
        if v[0] + self.gauge <= 0.0 {
            return false;
        }
        let [a, b] = material_derivatives(self.column(at.element).alpha, &self.fields(v));
        let cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        membrane::dot(&cross, &cross) > 0.0
    }

    /// The interlayer's state from the converged point values (module [`super::interlayer`]).
    fn advance(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES], previous: &[f64], next: &mut [f64]) {
        match (&self.interlayer, term) {
            (Some(interlayer), INTERLAYER) => {
                let [a, _] = material_derivatives(self.column(at.element).alpha, &self.fields(v));
                let record = [v[2], v[14], a[0], a[1], a[2], v[13]];
                let foot = self.foot(at, v, previous);
                interlayer.advance(&self.position(at, v), &foot, &record, (at.time, at.dt), previous, next);
            }
            _ => next.copy_from_slice(previous),
        }
    }

    /// The interlayer's transport speed c (0 without one).
    fn belt_speed(&self, time: f64) -> f64 {
        self.interlayer.as_ref().map_or(0.0, |i| i.transport_at(time))
    }

    /// The interlayer's u ([`super::interlayer::DEFORMATION`]): advected within the
    /// values of the bracketing points.
    fn bounded_history(&self, term: usize) -> std::ops::Range<usize> {
        match (&self.interlayer, term) {
            (Some(_), INTERLAYER) => DEFORMATION,
            _ => 0..0,
        }
    }

    /// u is a field where the contact flag is set ([`super::interlayer::CONTACT_FLAG`]):
    /// next to a released point it is advected linearly (docs/fem-shell.md §9.3).
    fn history_support(&self, term: usize) -> Option<usize> {
        match (&self.interlayer, term) {
            (Some(_), INTERLAYER) => Some(CONTACT_FLAG),
            _ => None,
        }
    }

    /// The point's own committed gap, share of the contact, distance from its entry, the
    /// record at that entry and its own S̃_n (not advected).
    fn fixed_history(&self, term: usize) -> std::ops::Range<usize> {
        match (&self.interlayer, term) {
            (Some(_), INTERLAYER) => CONTACT_GAP..STATE,
            _ => 0..0,
        }
    }

    /// V_⊥ counts the part of each point's cell inside the committed contact
    /// ([`super::interlayer::CONTACT_SHARE`]), cut at the roots of the gap ([`Self::zone`]).
    fn cut_history(&self, term: usize) -> Option<CutHistory> {
        match (&self.interlayer, term) {
            (Some(_), INTERLAYER) => Some(CutHistory { indicator: CONTACT_GAP, share: CONTACT_SHARE, entry: Some(CONTACT_ENTRY), record: ENTRY_RECORD }),
            _ => None,
        }
    }

    /// The belt's position and S̃ where it meets the drum (the interlayer's
    /// [`super::interlayer::ENTRY_RECORD`]).
    fn edge_record(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES], out: &mut [f64]) {
        if let (Some(_), INTERLAYER) = (&self.interlayer, term) {
            out[..3].copy_from_slice(&self.position(at, v));
            out[3] = v[13];
        }
    }

    /// The gap to the nearest drum at the position of the point values `v`.
    fn zone(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> f64 {
        match (&self.interlayer, term) {
            (Some(interlayer), INTERLAYER) => interlayer.nearest_gap(&self.position(at, v), at.time),
            _ => 0.0,
        }
    }

    /// The augmented map (S12) on the columns with transition edges.
    fn quadratic_terms(&self, element: usize, rect: &BfsRectangle, xi: f64, eta: f64, out: &mut Vec<QuadraticTerm>) {
        let column = self.column(element);
        if column.augmented.start || column.augmented.end {
            let element = ShellElement { gauge: self.gauge, ..self.sides.element_of(column, *rect) };
            element.quadratic_terms(xi, eta, out);
        }
    }
}

/// p × q / |p × q|.
fn unit_normal<D: Scalar>(p: &[D; 3], q: &[D; 3]) -> [D; 3] {
    let c = [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]];
    let norm = membrane::dot(&c, &c).sqrt();
    c.map(|c| c / norm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::SurfaceElement;
    use crate::shell::transition::contour_mesh;
    use crate::shell::interlayer::Drum;
    use crate::surface::assembly::{Evaluation, SurfaceAssembler};
    use crate::surface::history::SurfaceHistory;
    use crate::test_rng::Rng;

    /// Eh = 1000 N/m, ν_P = 0.3, h = 0.01 m.
    fn section() -> ShellSection {
        ShellSection::isotropic(1.0e5, 0.3, 0.01).unwrap()
    }

    fn static_ev() -> Evaluation<'static> {
        Evaluation { time: 0.0, dt: 0.0, history: None }
    }

    /// R = 0.3 m, H = 1.1 m: O(1) geometry.
    fn contour() -> Contour {
        Contour::new(0.3, 1.1).unwrap()
    }

    /// Gradient and Hessian of `asm` at `z` against central differences along `n`
    /// random directions: step 1e-6 on unknowns of size ≲ 1, truncation h²|E'''| and
    /// round-off ε|E|/h ≲ 1e-9 of the entries' scale; tolerance 1e-6 of the largest
    /// entry (of the directional derivative: of max(|slope|, 1e-3 U)).
    fn check_derivatives(asm: &SurfaceAssembler<Shell, SHELL_VALUES>, z: &[f64], seed: u64, n: usize) {
        check_derivatives_at(asm, z, &static_ev(), seed, n);
    }

    /// [`check_derivatives`] in the evaluation `ev` (time, step, history).
    fn check_derivatives_at(asm: &SurfaceAssembler<Shell, SHELL_VALUES>, z: &[f64], ev: &Evaluation, seed: u64, n: usize) {
        let mut rng = Rng(seed);
        let ev = *ev;
        let assembled = asm.assemble(z, &ev).unwrap();
        let (rows, cols) = asm.pattern();
        let step = 1e-6;
        for _ in 0..n {
            let d: Vec<f64> = z.iter().map(|_| 2.0 * rng.next() - 1.0).collect();
            let shifted = |t: f64| -> Vec<f64> { z.iter().zip(&d).map(|(a, b)| a + t * b).collect() };
            let (ep, gp) = asm.gradient(&shifted(step), &ev).unwrap();
            let (em, gm) = asm.gradient(&shifted(-step), &ev).unwrap();
            let slope: f64 = assembled.gradient.iter().zip(&d).map(|(g, v)| g * v).sum();
            let fd = (ep - em) / (2.0 * step);
            assert!((slope - fd).abs() < 1e-6 * slope.abs().max(1e-3 * assembled.energy.abs()), "directional derivative {slope} vs {fd}");
            let mut hd = vec![0.0; z.len()];
            for ((&i, &j), &h) in rows.iter().zip(cols).zip(&assembled.values) {
                hd[i] += h * d[j];
            }
            let largest = hd.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for ((p, m), h) in gp.iter().zip(&gm).zip(&hd) {
                assert!(((p - m) / (2.0 * step) - h).abs() < 1e-6 * largest, "Hessian × direction {h} vs {}", (p - m) / (2.0 * step));
            }
        }
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
        let shell = Shell::strip(section(), 1.0 / lambda, 0.0, &mesh).unwrap();
        let asm = SurfaceAssembler::new(mesh, shell, &[]).unwrap();
        let scale = eh * e11 * 0.6; // the axial force of the strip, N
        for (lateral, free) in [((1.0 - 2.0 * nu_p * e11).sqrt(), true), (1.0, false)] {
            let z_field = move |_: f64, zeta: f64| [lateral * zeta, 0.0, lateral, 0.0];
            let z = asm.interpolate(&[(Field::Z, &z_field)]);
            let (energy, gradient) = asm.gradient(&z, &static_ev()).unwrap();
            let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
            let at = SurfacePoint { sigma: 0.7, zeta: 0.1, element: 7, time: 0.0, dt: 0.0 };
            let mut v = [0.0; SHELL_VALUES];
            v[9] = lateral;
            let forces = asm.kernel().forces(&at, &v);
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

    /// The closed belt stretched uniformly by λ on the contour offset by ν₀: ν = ν₀,
    /// z = λ₂ζ, and S piecewise linear with ∂σS = 1/λ on the spans and (1 + ν₀/R)/λ on
    /// the arcs — then ∂̊_s r = λ t_g everywhere (S3). The S-slope jumps at every
    /// transition: the state is a C¹ field of the augmented map (the transition nodes
    /// carry the Cartesian slope 1/λ, (S11) gives the polar one), and no plain BFS field.
    /// Gauge c₀ = (2H + 2π(R + ν₀))/(λ L_geom), initial area c₀ L_geom b.
    fn stretched_belt(lambda: f64, nu0: f64, contour: &Contour, mesh: &SurfaceMesh) -> (f64, impl Fn(f64, f64) -> [f64; 4]) {
        let (r, h) = (contour.radius(), contour.centre_distance());
        let c0 = (2.0 * h + 2.0 * std::f64::consts::PI * (r + nu0)) / (lambda * contour.length());
        let (span, arc) = (1.0 / lambda, (1.0 + nu0 / r) / lambda);
        let t = contour.transitions();
        let ends = [t[1], t[2], t[3], contour.length()];
        let slopes = [span, arc, span, arc];
        let tolerance = 1e-9 * contour.length();
        let transitions = t;
        let length = mesh.length();
        let s_tilde = move |sigma: f64, _: f64| {
            let mut s = 0.0;
            for k in 0..4 {
                s += slopes[k] * (sigma.min(ends[k]) - t[k]).max(0.0);
            }
            let on_transition = transitions.iter().any(|&tt| (tt - sigma).abs() < tolerance) || (sigma - length).abs() < tolerance;
            // at a transition node the Cartesian side's slope (docs/fem-shell.md §5)
            let slope = if on_transition { span } else { slopes[(0..4).rev().find(|&k| sigma >= t[k]).unwrap_or(0)] };
            [s - c0 * sigma, slope - c0, 0.0, 0.0]
        };
        (c0, s_tilde)
    }

    #[test]
    fn uniformly_stretched_closed_belt_has_the_exact_membrane_energy_across_transitions() {
        let (lambda, nu0, nu_p, eh, b): (f64, f64, f64, f64, f64) = (1.01, 0.02, 0.3, 1000.0, 0.4);
        let e11 = 0.5 * (lambda * lambda - 1.0);
        let lateral = (1.0 - 2.0 * nu_p * e11).sqrt();
        let contour = contour();
        let mesh = contour_mesh(&contour, [3, 2, 4, 1], 0.15, vec![-0.2, -0.05, 0.2]).unwrap();
        let (c0, s_tilde) = stretched_belt(lambda, nu0, &contour, &mesh);
        let nu = move |_: f64, _: f64| [nu0, 0.0, 0.0, 0.0];
        let z_field = move |_: f64, zeta: f64| [lateral * zeta, 0.0, lateral, 0.0];
        let exact = 0.5 * eh * e11 * e11 * c0 * contour.length() * b;
        let membrane = ShellSection { d1: 0.0, d2: 0.0, ..section() };
        let shell = Shell::on_contour(membrane, c0, 0.0, &contour, &mesh).unwrap();
        let plain = Shell::with_sides(membrane, c0, 0.0, TransitionSides::new(&contour, &mesh).unwrap().without_augmentation(), &mesh).unwrap();
        let asm = SurfaceAssembler::new(mesh.clone(), shell, &[]).unwrap();
        let z = asm.interpolate(&[(Field::S, &s_tilde), (Field::Nu, &nu), (Field::Z, &z_field)]);
        let energy = asm.energy(&z, &static_ev()).unwrap();
        // round-off of a sum over 60 elements × 27 points of O(1e-2) J
        assert!((energy - exact).abs() < 1e-12 * exact, "augmented: U = {energy} vs exact {exact} (rel. {:e})", (energy - exact) / exact);
        let plain = SurfaceAssembler::new(mesh.clone(), plain, &[]).unwrap();
        let wrong = plain.energy(&z, &static_ev()).unwrap();
        assert!((wrong - exact).abs() > 1e-2 * exact, "plain BFS map: U = {wrong} should miss {exact}");
        // the assembler's point values are the augmented fields of shell::transition
        let sides = TransitionSides::new(&contour, &mesh).unwrap();
        let m = mesh.zeta_elements();
        for e in (0..mesh.len()).filter(|&e| sides.column(e / m).augmented != Default::default()) {
            let el = ShellElement { gauge: c0, ..sides.element(&mesh, e) };
            let q: [f64; crate::shell::transition::SHELL_DOFS] = asm.dofs().gather(e, &z).try_into().unwrap();
            for (xi, eta) in [(-0.9, 0.3), (0.4, -0.6)] {
                let [sigma, zeta] = el.rect.point(xi, eta);
                let want = el.fields(&q, xi, eta);
                for (field, k) in [(Field::S, S), (Field::Nu, NU), (Field::Z, Z)] {
                    let got = asm.field_at(&z, field, sigma, zeta).unwrap();
                    for row in 0..6 {
                        assert!((got[row] - want[k][row]).abs() < 1e-12 * (1.0 + want[k][row].abs()), "element {e} {field:?} row {row}: {} vs {}", got[row], want[k][row]);
                    }
                }
                // ∂σS of the whole state: c₀ + ∂σS̃ is the region's slope inside the element
                let slope = asm.field_at(&z, Field::S, sigma, zeta).unwrap()[1] + c0;
                assert!((slope - (1.0 + nu0 / contour.radius()) / lambda).abs() < 1e-12, "polar slope {slope}");
            }
        }
    }

    /// Gradient and Hessian of the assembled shell on the closed contour (camber, graded
    /// mesh, arcs of one and of two elements: every transition element augmented at one
    /// or both ends) at a random state with |ν| ~ 0.03 (a tenth of R) against central
    /// differences; the two zero modes of docs/fem-shell.md §1, §9: a constant added to S̃
    /// or to z leaves the energy unchanged.
    #[test]
    fn shell_derivatives_match_central_differences_at_transitions_and_zero_modes_are_free() {
        let contour = contour();
        for per_region in [[2, 1, 2, 2], [3, 2, 2, 1]] {
            let mesh = contour_mesh(&contour, per_region, 0.15, vec![-0.3, 0.05, 0.3]).unwrap();
            let shell = Shell::on_contour(section(), 1.03, 0.4, &contour, &mesh).unwrap();
            let asm = SurfaceAssembler::new(mesh, shell, &[]).unwrap();
            let mut rng = Rng(0x3e3b_0a11);
            let mut r = |scale: f64| scale * (2.0 * rng.next() - 1.0);
            let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
            let z: Vec<f64> = reference.iter().map(|v| v + r(0.03)).collect();
            check_derivatives(&asm, &z, 0x5eed, 6);
            let ev = static_ev();
            let energy = asm.energy(&z, &ev).unwrap();
            for field in [Field::S, Field::Z] {
                let constant = asm.interpolate(&[(field, &|_: f64, _: f64| [0.37, 0.0, 0.0, 0.0])]);
                let moved: Vec<f64> = z.iter().zip(&constant).map(|(a, b)| a + b).collect();
                let shifted = asm.energy(&moved, &ev).unwrap();
                assert!((shifted - energy).abs() < 1e-13 * energy, "{field:?} + const changes U: {shifted} vs {energy}");
            }
        }
    }

    /// V-3 of docs/fem-shell.md: the belt wrapped isometrically on the contour (c₀ = 1,
    /// S̃ = 0, ν = 0, z = ζ): E ≡ 0, K = diag(α, 0), so U = U_b = ½ D/R² × 2πR b = πDb/R
    /// with D = Eh³/(12(1 − ν_P²)) — the lateral curvature is held at zero (z = ζ, ν = 0),
    /// the wide-plate value; with ν_P = 0 the bending energy of the curvature change 1/R
    /// against the flat unstressed belt, ½(Eh³/12)/R² per area. The integrand is constant
    /// per element, so the rule is exact: round-off.
    #[test]
    fn belt_wrapped_on_the_contour_has_the_bending_energy_of_the_arcs() {
        let contour = contour();
        let (e_modulus, h, b) = (1.0e5, 0.01, 0.4);
        let mesh = contour_mesh(&contour, [3, 2, 4, 1], 0.15, vec![-0.2, -0.05, 0.2]).unwrap();
        for nu_p in [0.0, 0.3] {
            let section = ShellSection::isotropic(e_modulus, nu_p, h).unwrap();
            let shell = Shell::on_contour(section, 1.0, 0.0, &contour, &mesh).unwrap();
            let asm = SurfaceAssembler::new(mesh.clone(), shell, &[]).unwrap();
            let z = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
            let energy = asm.energy(&z, &static_ev()).unwrap();
            let d = e_modulus * h.powi(3) / (12.0 * (1.0 - nu_p * nu_p));
            let exact = std::f64::consts::PI * d * b / contour.radius();
            assert!((energy - exact).abs() < 1e-13 * exact, "ν_P = {nu_p}: U = {energy} vs πDb/R = {exact}");
            // the moment on an arc: M_ss = D K_ss (K_ζζ = 0), M_ζζ = ν_P M_ss
            let at = SurfacePoint { sigma: 1.5, zeta: 0.0, element: 3 * mesh.zeta_elements() + 1, time: 0.0, dt: 0.0 };
            let mut v = [0.0; SHELL_VALUES];
            v[9] = 1.0;
            let m = asm.kernel().moments(&at, &v);
            let k = asm.kernel().curvature(&at, &v);
            assert!((k[0] - 1.0 / contour.radius()).abs() < 1e-14 && k[1].abs() < 1e-15 && k[2].abs() < 1e-15, "K = {k:?}");
            assert!((m[0] - d / contour.radius()).abs() < 1e-13 * m[0] && (m[2] - nu_p * m[0]).abs() < 1e-13 * m[0], "M = {m:?}");
        }
    }

    /// Cylindrical bending of a flat strip (V-4) at a point, in closed form: ν_σσ = −κ
    /// (n = −n_g, so K_ss = κ) with the anticlastic curvature K_ζζ = −ν_P κ of a narrow
    /// strip with free edges gives W_b = ½(Eh³/12)κ² per area (the Poisson coupling
    /// D₁/(D₁ + D₂) = ν_P makes M_ζζ = 0); held flat across (K_ζζ = 0, a wide plate)
    /// ½Dκ², D = Eh³/(12(1 − ν_P²)). Round-off.
    #[test]
    fn cylindrical_bending_of_a_strip_has_the_plate_energies() {
        let (e_modulus, nu_p, h, kappa) = (2.0e11, 0.3, 1.0e-3, 2.5);
        let mesh = SurfaceMesh::mapped(2.0, 4, |u| u, [-0.1, 0.1], 2).unwrap();
        let shell = Shell::strip(ShellSection::isotropic(e_modulus, nu_p, h).unwrap(), 1.0, 0.0, &mesh).unwrap();
        let at = SurfacePoint { sigma: 0.3, zeta: 0.02, element: 1, time: 0.0, dt: 0.0 };
        let bending = e_modulus * h.powi(3) / 12.0;
        for (lateral, exact) in [(nu_p * kappa, 0.5 * bending * kappa * kappa), (0.0, 0.5 * bending / (1.0 - nu_p * nu_p) * kappa * kappa)] {
            let mut v = [0.0; SHELL_VALUES];
            v[9] = 1.0; // ∂ζz
            v[5] = -kappa; // ∂²σν
            v[7] = lateral; // ∂²ζν
            let w = shell.density(BENDING_GRAVITY, &at, &v, &[]);
            assert!((w - exact).abs() < 1e-13 * exact, "W_b = {w} vs {exact}");
            let m = shell.moments(&at, &v);
            if lateral != 0.0 {
                assert!(m[2].abs() < 1e-13 * m[0], "free edge: M_ζζ = {} of M_ss = {}", m[2], m[0]);
            }
        }
    }

    /// Gravity (S10): lifting a flat horizontal strip rigidly by d (ν + d, n_g = +j)
    /// changes W_g by weight × d, the weight ρ_s h g × initial area c₀ L ∫ℓ* dζ
    /// (camber, random state: ∫∂σS̃ = 0 over the loop; the integrands are polynomials of
    /// degree ≤ 3 per direction, exact under Gauss 3 × 3) — and nothing else changes.
    #[test]
    fn lifting_a_strip_changes_gravity_by_weight_times_height() {
        let (weight, c0, camber, d) = (75.0, 1.02, 0.3, 0.013);
        let mesh = SurfaceMesh::mapped(2.0, 5, |u| u + 0.05 * (std::f64::consts::TAU * u).sin(), [-0.25, 0.35], 3).unwrap();
        let shell = Shell::strip(section(), c0, camber, &mesh).unwrap().with_gravity(weight).unwrap();
        let asm = SurfaceAssembler::new(mesh, shell, &[]).unwrap();
        let mut rng = Rng(0x9a7);
        let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
        let z: Vec<f64> = reference.iter().map(|v| v + 0.02 * (2.0 * rng.next() - 1.0)).collect();
        let lift = asm.interpolate(&[(Field::Nu, &|_: f64, _: f64| [d, 0.0, 0.0, 0.0])]);
        let lifted: Vec<f64> = z.iter().zip(&lift).map(|(a, b)| a + b).collect();
        let ev = static_ev();
        let (before, after) = (asm.energy(&z, &ev).unwrap(), asm.energy(&lifted, &ev).unwrap());
        // ∫ℓ* dζ over [−0.25, 0.35]: 0.6 − κ_c (0.35² − 0.25²)/2
        let initial_area = c0 * 2.0 * (0.6 - camber * (0.35f64.powi(2) - 0.25f64.powi(2)) / 2.0);
        let exact = weight * initial_area * d;
        assert!(((after - before) - exact).abs() < 1e-12 * before.abs().max(exact), "ΔW_g = {} vs weight × d = {exact}", after - before);
    }

    /// Gradient and Hessian of each energy on its own (membrane: D = 0; bending:
    /// A = 0; gravity: A = D = 0) on the closed contour with camber at a random state,
    /// elements at transitions included, against central differences — the bending and
    /// gravity terms are 1e-5 of the membrane's in the full shell and would hide under
    /// its tolerance; and the zero modes (S̃ + const, z + const) of the bending.
    #[test]
    fn each_term_matches_central_differences_at_transitions() {
        let contour = contour();
        let mesh = contour_mesh(&contour, [2, 2, 2, 1], 0.15, vec![-0.3, 0.05, 0.3]).unwrap();
        let full = section();
        let zero = ShellSection { a1: 0.0, a2: 0.0, d1: 0.0, d2: 0.0 };
        for (what, section, weight) in [("membrane", ShellSection { d1: 0.0, d2: 0.0, ..full }, 0.0), ("bending", ShellSection { a1: 0.0, a2: 0.0, ..full }, 0.0), ("gravity", zero, 75.0)] {
            // κ_c(t) ramping through 0.4 1/m at t = 0 (stage (1)'s camber)
            let camber = Schedule::new(vec![(-1.0, 0.0), (1.0, 0.8)]).unwrap();
            let shell = Shell::on_contour(section, 1.03, 0.0, &contour, &mesh).unwrap().with_camber(camber).unwrap().with_gravity(weight).unwrap();
            let asm = SurfaceAssembler::new(mesh.clone(), shell, &[]).unwrap();
            let mut rng = Rng(0x0be_d1e);
            let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
            let z: Vec<f64> = reference.iter().map(|v| v + 0.03 * (2.0 * rng.next() - 1.0)).collect();
            let energy = asm.energy(&z, &static_ev()).unwrap();
            assert!(energy.abs() > 0.0, "{what}: no energy");
            check_derivatives(&asm, &z, 0x7e57, 4);
            if what == "bending" {
                for field in [Field::S, Field::Z] {
                    let constant = asm.interpolate(&[(field, &|_: f64, _: f64| [0.37, 0.0, 0.0, 0.0])]);
                    let moved: Vec<f64> = z.iter().zip(&constant).map(|(a, b)| a + b).collect();
                    let shifted = asm.energy(&moved, &static_ev()).unwrap();
                    assert!((shifted - energy).abs() < 1e-13 * energy, "bending: {field:?} + const changes U: {shifted} vs {energy}");
                }
            }
        }
    }

    /// The interlayer of a shell on `contour`: P = 1e5 N/m³, P_⊥ = `shear`, both drums
    /// at ω = 2 rad/s (transport ωR), the driver tilted by ramps of β_x, β_y.
    fn interlayer(contour: &Contour, shear: f64) -> Interlayer {
        let omega = 2.0;
        let tilted = Drum {
            centre: contour.pulley_centre(drive::contour::Pulley::Driver),
            speed: omega,
            tilt_x: crate::shell::interlayer::Schedule::new(vec![(0.0, 0.0), (1.0, 0.04)]).unwrap(),
            tilt_y: crate::shell::interlayer::Schedule::new(vec![(0.0, 0.0), (1.0, -0.06)]).unwrap(),
        };
        let driven = Drum::aligned(contour.pulley_centre(drive::contour::Pulley::Driven), omega);
        Interlayer { normal: 1.0e5, shear, drums: [tilted, driven], radius: contour.radius(), transport: omega * contour.radius(), start: f64::NEG_INFINITY, rule: Rule::Trapezoidal, width_rule: Rule::Gauss(2) }
    }

    /// V-6 for the interlayer alone (A = D = 0, no gravity): closed contour with camber,
    /// every transition element augmented, a random state pressed into the drums
    /// (ν ≈ −0.01 ± 0.005, so the arcs and the span ends next to them are in contact),
    /// the driver drum tilted (β_x, β_y ramping), the history recorded at a random state
    /// and advected by a non-integer shift: gradient and Hessian against central
    /// differences. The tangential part is active (V_⊥ changes the energy by > 1 %) and
    /// depends on S̃ (the implicit foot of (S13)) and on z (tilted axis).
    #[test]
    fn interlayer_derivatives_match_central_differences_in_contact_at_transitions_with_tilt() {
        let contour = contour();
        let zero = ShellSection { a1: 0.0, a2: 0.0, d1: 0.0, d2: 0.0 };
        // the second mesh with the drums at rest (the rotation starts later, stage (1):
        // only the tilt moves the drum)
        for (per_region, start) in [([2, 2, 2, 1], f64::NEG_INFINITY), ([3, 1, 2, 2], 10.0)] {
            let mesh = contour_mesh(&contour, per_region, 0.15, vec![-0.3, 0.05, 0.3]).unwrap();
            let shell = Shell::on_contour(zero, 1.03, 0.4, &contour, &mesh).unwrap().with_interlayer(Interlayer { start, ..interlayer(&contour, 3.0e4) }).unwrap();
            let asm = SurfaceAssembler::new(mesh.clone(), shell, &[]).unwrap();
            let mut rng = Rng(0x1a7e_7a11);
            let mut r = |scale: f64| scale * (2.0 * rng.next() - 1.0);
            let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0]), (Field::Nu, &|_: f64, _: f64| [-0.01, 0.0, 0.0, 0.0])]);
            let before: Vec<f64> = reference.iter().map(|v| v + r(0.005)).collect();
            let z: Vec<f64> = before.iter().map(|v| v + r(0.005)).collect();
            let (t0, dt) = (0.3, 0.04);
            let history = SurfaceHistory::new(&asm, t0).unwrap();
            let recorded = history.advance(&asm, &before, &Evaluation { time: t0, dt: 0.0, history: Some(&history) });
            let advected = recorded.advected(asm.kernel().belt_speed(t0 + 0.5 * dt) * dt);
            let ev = Evaluation { time: t0 + dt, dt, history: Some(&advected) };
            check_derivatives_at(&asm, &z, &ev, 0xfeed, 6);
            let energy = asm.energy(&z, &ev).unwrap();
            let normal_only = asm.energy(&z, &Evaluation { history: None, ..ev }).unwrap();
            assert!(energy - normal_only > 1e-2 * energy, "V_⊥ inactive: {energy} vs V_γ {normal_only}");
            for field in [Field::S, Field::Z] {
                let constant = asm.interpolate(&[(field, &|_: f64, _: f64| [0.003, 0.0, 0.0, 0.0])]);
                let moved: Vec<f64> = z.iter().zip(&constant).map(|(a, b)| a + b).collect();
                let shifted = asm.energy(&moved, &ev).unwrap();
                assert!((shifted - energy).abs() > 1e-4 * energy, "{field:?} + const does not change V_⊥ + V_γ: {shifted} vs {energy}");
            }
        }
    }

    /// The shell with every term differentiated over all 15 point values (the default
    /// [`SurfaceKernel::term_variables`]): the oracle of the per-term variables.
    struct AllVariables(Shell);

    impl SurfaceKernel<SHELL_VALUES> for AllVariables {
        fn layout(&self) -> ElementLayout {
            self.0.layout()
        }
        fn variables(&self) -> [PointVariable; SHELL_VALUES] {
            self.0.variables()
        }
        fn terms(&self) -> Vec<SurfaceTerm> {
            self.0.terms()
        }
        fn density<D: Scalar>(&self, term: usize, at: &SurfacePoint, v: &[D; SHELL_VALUES], state: &[f64]) -> D {
            self.0.density(term, at, v, state)
        }
        fn admissible(&self, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> bool {
            self.0.admissible(at, v)
        }
        fn advance(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES], previous: &[f64], next: &mut [f64]) {
            self.0.advance(term, at, v, previous, next);
        }
        fn quadratic_terms(&self, element: usize, rect: &BfsRectangle, xi: f64, eta: f64, out: &mut Vec<QuadraticTerm>) {
            self.0.quadratic_terms(element, rect, xi, eta, out);
        }
        fn belt_speed(&self, time: f64) -> f64 {
            self.0.belt_speed(time)
        }
        fn bounded_history(&self, term: usize) -> std::ops::Range<usize> {
            self.0.bounded_history(term)
        }
        fn history_support(&self, term: usize) -> Option<usize> {
            self.0.history_support(term)
        }
        fn fixed_history(&self, term: usize) -> std::ops::Range<usize> {
            self.0.fixed_history(term)
        }
        fn cut_history(&self, term: usize) -> Option<CutHistory> {
            self.0.cut_history(term)
        }
        fn zone(&self, term: usize, at: &SurfacePoint, v: &[f64; SHELL_VALUES]) -> f64 {
            self.0.zone(term, at, v)
        }
    }

    /// Energy, gradient and Hessian against the oracle [`AllVariables`] (forward AD of
    /// every term over all 15 point values), to round-off (1e-12 of the largest entry):
    /// [`Shell::term_variables`] lists every value each density reads, and the chain
    /// rules of [`Shell::membrane_hessian`] and [`Shell::bending_hessian`] give the AD's
    /// Hessian. The full shell with camber, gravity and the interlayer in contact with
    /// its history (V_⊥ active), the driver drum tilted, at transitions, in a step and in
    /// the static evaluation; then bending with gravity alone (1e-5 of the membrane in
    /// the full shell, hidden under its tolerance there) and the membrane alone at
    /// |ν| ~ 0.03.
    #[test]
    fn per_term_derivatives_match_the_ad_over_all_values() {
        let close = |x: &[f64], y: &[f64], what: &str| {
            let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            let worst = x.iter().zip(y).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(worst <= 1e-12 * scale, "{what}: {worst:e} of {scale:e}");
        };
        let compare = |asm: &SurfaceAssembler<Shell, SHELL_VALUES>, oracle: &SurfaceAssembler<AllVariables, SHELL_VALUES>, z: &[f64], ev: &Evaluation| {
            let (a, b) = (asm.assemble(z, ev).unwrap(), oracle.assemble(z, ev).unwrap());
            assert!((a.energy - b.energy).abs() <= 1e-13 * b.energy.abs());
            close(&a.gradient, &b.gradient, "gradient");
            close(&a.values, &b.values, "Hessian");
            let (ga, gb) = (asm.gradient(z, ev).unwrap(), oracle.gradient(z, ev).unwrap());
            close(&ga.1, &gb.1, "gradient (first-order path)");
        };
        let contour = contour();
        let mesh = contour_mesh(&contour, [2, 2, 2, 1], 0.15, vec![-0.3, 0.05, 0.3]).unwrap();
        let shell = Shell::on_contour(section(), 1.03, 0.4, &contour, &mesh).unwrap().with_gravity(75.0).unwrap().with_interlayer(interlayer(&contour, 3.0e4)).unwrap();
        let asm = SurfaceAssembler::new(mesh.clone(), shell.clone(), &[]).unwrap();
        let oracle = SurfaceAssembler::new(mesh.clone(), AllVariables(shell), &[]).unwrap();
        let mut rng = Rng(0x5_0b5e7);
        let mut r = |scale: f64| scale * (2.0 * rng.next() - 1.0);
        let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0]), (Field::Nu, &|_: f64, _: f64| [-0.01, 0.0, 0.0, 0.0])]);
        let before: Vec<f64> = reference.iter().map(|v| v + r(0.005)).collect();
        let z: Vec<f64> = before.iter().map(|v| v + r(0.005)).collect();
        let (t0, dt) = (0.3, 0.04);
        let history = SurfaceHistory::new(&asm, t0).unwrap();
        let recorded = history.advance(&asm, &before, &Evaluation { time: t0, dt: 0.0, history: Some(&history) });
        let advected = recorded.advected(asm.kernel().belt_speed(t0 + 0.5 * dt) * dt);
        let step = Evaluation { time: t0 + dt, dt, history: Some(&advected) };
        assert!(asm.energy(&z, &step).unwrap() - asm.energy(&z, &Evaluation { history: None, ..step }).unwrap() > 0.0, "V_⊥ inactive");
        for ev in [step, static_ev()] {
            compare(&asm, &oracle, &z, &ev);
        }
        for (section, weight) in [(ShellSection { a1: 0.0, a2: 0.0, ..section() }, 75.0), (ShellSection { d1: 0.0, d2: 0.0, ..section() }, 0.0)] {
            let alone = Shell::on_contour(section, 1.03, 0.4, &contour, &mesh).unwrap().with_gravity(weight).unwrap();
            let asm = SurfaceAssembler::new(mesh.clone(), alone.clone(), &[]).unwrap();
            let oracle = SurfaceAssembler::new(mesh.clone(), AllVariables(alone), &[]).unwrap();
            let reference = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0])]);
            let z: Vec<f64> = reference.iter().map(|v| v + r(0.03)).collect();
            compare(&asm, &oracle, &z, &static_ev());
        }
    }

    /// Rigid rolling (module `interlayer`): the belt pressed into the drums (ν = −0.01
    /// everywhere, c₀ = 1) turns with them: after a step of exactly one arc element
    /// (cΔt = h_arc, uniform arcs: the advection is exact), S̃ unchanged (the gauge
    /// S = c₀(σ − d(t)) + S̃ moves with the drums: each material point moved by cΔt),
    /// the tangential deformation is zero to round-off at
    /// every arc point whose foot was on the arc — the drum point under the material is
    /// moved by the exact rotation — and zero by the entry rule where the foot was on the
    /// span. With a lateral step of the belt by d (z + d) the arcs carry u = d k exactly
    /// (the lateral deformation of the layer). Held back (S̃ raised by c₀cΔt: the drums
    /// turn, the belt does not) the arcs carry the drum's travel, |u| ≈ cΔt.
    #[test]
    fn belt_rolling_rigidly_with_the_drums_has_no_tangential_deformation() {
        let contour = contour();
        let per_region = [4, 6, 4, 6];
        let mesh = contour_mesh(&contour, per_region, 0.0, vec![-0.2, 0.0, 0.2]).unwrap();
        let mut layer = interlayer(&contour, 1.0e4);
        layer.drums[0] = Drum::aligned(layer.drums[0].centre, layer.drums[0].speed);
        let shell = Shell::on_contour(section(), 1.0, 0.0, &contour, &mesh).unwrap().with_interlayer(layer).unwrap();
        let asm = SurfaceAssembler::new(mesh.clone(), shell, &[]).unwrap();
        let c = asm.kernel().belt_speed(0.0);
        let h_arc = std::f64::consts::PI * contour.radius() / 6.0;
        let dt = h_arc / c;
        let start = asm.interpolate(&[(Field::Z, &|_: f64, zeta: f64| [zeta, 0.0, 1.0, 0.0]), (Field::Nu, &|_: f64, _: f64| [-0.01, 0.0, 0.0, 0.0])]);
        let history = SurfaceHistory::new(&asm, 0.0).unwrap();
        let recorded = history.advance(&asm, &start, &Evaluation { time: 0.0, dt: 0.0, history: Some(&history) });
        let advected = recorded.advected(c * dt);
        let ev = Evaluation { time: dt, dt, history: Some(&advected) };
        for (lateral, rolling) in [(0.0, true), (0.004, true), (0.0, false)] {
            let travel = if rolling { 0.0 } else { c * dt };
            let moved = asm.interpolate(&[(Field::S, &move |_: f64, _: f64| [travel, 0.0, 0.0, 0.0]), (Field::Z, &move |_: f64, zeta: f64| [zeta + lateral, 0.0, 1.0, 0.0]), (Field::Nu, &|_: f64, _: f64| [-0.01, 0.0, 0.0, 0.0])]);
            let next = advected.advance(&asm, &moved, &ev);
            let states = next.term(INTERLAYER).unwrap();
            let (rows, columns) = states.shape();
            let t = contour.transitions();
            let (mut on_arcs, mut held) = (0, f64::INFINITY);
            for (column, &sigma) in states.column_sigma().iter().enumerate() {
                let arc = (t[1] + h_arc * 0.5 < sigma && sigma < t[2] + 1e-9) || (t[3] + h_arc * 0.5 < sigma);
                for row in 0..rows {
                    let u = Interlayer::deformation(states.get(row, column));
                    if arc {
                        on_arcs += 1;
                        let want = [0.0, 0.0, lateral];
                        if rolling {
                            assert!((0..3).all(|k| (u[k] - want[k]).abs() < 1e-15), "σ = {sigma}: u = {u:?}, want {want:?}");
                        } else {
                            held = held.min(u[0].hypot(u[1]));
                        }
                    }
                }
            }
            assert!(on_arcs >= 4 * 2 * 5 && columns > 0, "{on_arcs} arc points");
            if !rolling {
                assert!(held > 0.9 * c * dt, "a belt held back: |u| = {held:e} on the arcs, drum travel {:e}", c * dt);
            }
        }
    }
}
