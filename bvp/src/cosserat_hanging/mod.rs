//! `cosserat-hanging`: an extensible, shear-deformable (Cosserat) rod loop hanging under
//! gravity on two non-rotating frictionless pulleys — the static companion of Papers C
//! and D, as the six-segment BVP of `docs/cosserat-hanging.md` (45 unknowns).
//!
//! [`solve`] starts as the Kirchhoff rod does ([`crate::rod_hanging`]): the string of
//! the same data, the rod guess at a bending stiffness a₀ whose layer √(a₀/T) is 5 % of
//! H, with θ = φ − π/2, M = −a₀λ/R and λ = 1 + N/b₁ on the arcs, then continuation in
//! log a to the scene's a at the scene's shear stiffness b₂, then the final solve by
//! collocation or shooting. The Cosserat rod is a section law ([`law`]) on the
//! frictionless two-pulley topology — no code of its own beyond its equations.

pub mod law;

use std::f64::consts::FRAC_PI_2;
use std::time::Instant;

use serde::Serialize;

use crate::belt::topology::Scaling;
use crate::belt::{BeltError, BeltOptions, BeltProblem, BeltSolution};
use crate::rod_hanging::{self, RodHanging, ScaledRodHanging};
use crate::solution::Solution;
use crate::string_hanging::StringHanging;
pub use law::ScaledCosseratHanging;

/// Physical data of the scene (SI units): the Kirchhoff rod's and the shear stiffness.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CosseratHanging {
    /// R, H, L, b₁ = EA, a = EI, ρ, g as the Kirchhoff rod's (b₂ → ∞).
    #[serde(flatten)]
    pub rod: RodHanging,
    /// Shear stiffness b₂ (N).
    pub shear_stiffness: f64,
}

impl CosseratHanging {
    /// The string with the same data (a and b₂ dropped).
    pub fn string(&self) -> StringHanging {
        self.rod.string()
    }

    /// The shear layer ℓ_s = √(a/b₂) (m) over which the edge pressure decays (CH6).
    pub fn shear_layer(&self) -> f64 {
        (self.rod.bending_stiffness / self.shear_stiffness).sqrt()
    }
}

/// A solved `cosserat-hanging` scene; its `start` is the string solution of the same data.
pub type CosseratHangingSolution = BeltSolution<ScaledCosseratHanging>;

fn validate(d: &CosseratHanging, opts: &BeltOptions) -> Result<(), BeltError> {
    if !(d.shear_stiffness.is_finite() && d.shear_stiffness > 0.0) {
        return Err(BeltError::InvalidInput {
            name: "shear_stiffness",
            value: d.shear_stiffness,
            reason: "must be finite and > 0 (b₂ → ∞ is the Kirchhoff rod)",
        });
    }
    rod_hanging::validate(&d.rod, opts)
}

/// The Cosserat guess at a₀ from the string solution (scaled): on the spans the
/// Kirchhoff rod's guess ([`rod_hanging::rod_guess`]: θ from the force direction, M in
/// exponential layers at the pulleys), on the arcs zero shear, θ = φ − π/2, with
/// λ = 1 + N/b₁ and M = −a₀λ/R; the string's parameters.
pub fn cosserat_guess(string: &Solution, problem: &BeltProblem<ScaledCosseratHanging>, nodes: usize) -> Solution {
    let law = &problem.law.rod;
    let rod = BeltProblem::new(problem.topology.clone(), law.clone());
    let spans = rod_hanging::rod_guess(string, &rod, nodes);
    let topo = &problem.topology;
    Solution::from_fn(topo.len(), nodes, spans.params.clone(), 0.0, |k, xi| match topo.segment(k).scaling {
        Scaling::Span { .. } => spans.eval(k, xi),
        Scaling::Arc { start, end, .. } => {
            let arc = string.eval(k, xi);
            let (n, s) = (arc[0], arc[1]);
            let phi = spans.params[start] + xi * (spans.params[end] - spans.params[start]);
            let lambda = 1.0 + n / law.axial_stiffness;
            vec![lambda, phi - FRAC_PI_2, -law.bending_start * lambda / law.radius, s]
        }
    })
}

/// Solve a `cosserat-hanging` scene from its data alone.
pub fn solve(data: &CosseratHanging, opts: &BeltOptions) -> Result<CosseratHangingSolution, BeltError> {
    let clock = Instant::now();
    validate(data, opts)?;
    let (string, path) = rod_hanging::string_start(&data.string(), data.rod.bending_stiffness, opts)?;
    let (h, fr) = (string.scales.length, string.scales.force);
    let sp = string.problem.law.clone();
    let law = |bending_start| ScaledCosseratHanging {
        rod: ScaledRodHanging {
            radius: sp.radius,
            axial_stiffness: sp.axial_stiffness,
            weight: sp.weight,
            length: sp.length,
            bending_start,
            bending: data.rod.bending_stiffness / (fr * h * h),
        },
        shear_stiffness: data.shear_stiffness / fr,
    };
    let shear_layer = (data.rod.bending_stiffness / data.shear_stiffness).sqrt();
    rod_hanging::solve_from_string(*data, law, string, &path, |s, pb| cosserat_guess(s, pb, 81), opts, clock).map_err(|e| crate::belt::error::across_layer(e, opts, shear_layer, std::f64::consts::PI * data.rod.radius))
}

impl CosseratHangingSolution {
    /// a₀ (N·m²) of the homotopy start.
    pub fn bending_start(&self) -> f64 {
        self.problem.law.rod.bending_start * self.scales.force * self.scales.length * self.scales.length
    }
}
