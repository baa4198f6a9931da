//! Admissibility of a static FE solution on frictionless pulleys (issue 12 item 5,
//! docs/fem-rod.md §10): a converged Newton solve of a coarse or unresolved mesh can
//! be a discrete equilibrium that is no belt-on-pulley state. Checked after every static
//! string and rod solve:
//!
//! - **errors** ([`FemError::InadmissibleContact`]): a contact zone that covers the
//!   inner point of its pulley (the point facing the other pulley); a concentrated
//!   edge force below −[`EDGE_FORCE_TOLERANCE`]·F (a pulley that pulls the belt);
//!   and ([`FemError::UnreportedContact`]) a pulley that carries contact force above
//!   [`UNREPORTED_LOAD_TOLERANCE`]·F with no contact zone reported;
//! - **warnings** (returned, carried in the run's notes): a bending boundary layer
//!   ℓ_b = √(EI/N) at a contact edge thinner than [`LAYER_ELEMENTS`]⁻¹ element there —
//!   heights and tensions still converge, edge forces and contact angles are not resolved.
//!
//! F is the force scale: the largest axial force at the span midpoints.

use drive::contour::Pulley;
use drive::view::SolutionView;

use crate::error::FemError;
use crate::formulation::layout::LayoutElement;
use crate::solution::FemSolution;

/// A negative edge force is inadmissible below −1e-6 F (the recovery is a difference of
/// O(F) section forces evaluated to the Newton tolerance, ≈ 1e-9 F; the reproducer of
/// 7 elements has −1.26 N ≈ −1.0 F).
pub const EDGE_FORCE_TOLERANCE: f64 = 1e-6;

/// A pulley carrying more penalty contact force than 1e-6 F without a reported contact
/// zone is inadmissible (a belt that merely touches carries ≈ 0; the reproducer with
/// R = 0.01 m carries O(F)).
pub const UNREPORTED_LOAD_TOLERANCE: f64 = 1e-6;

/// Elements per layer length ℓ_b the element at a contact edge must give: the layer is
/// resolved if h ≤ ℓ_b/LAYER_ELEMENTS (docs/fem-rod.md §10 for the measured ratios).
pub const LAYER_ELEMENTS: f64 = 1.0;

/// The diagnostics of one contact edge of a rod.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EdgeLayer {
    /// σ of the edge, m.
    pub sigma: f64,
    /// Axial force N at the edge, N.
    pub axial_force: f64,
    /// ℓ_b = √(EI/N), m (0 if N ≤ 0: a compressed edge is never resolved).
    pub layer_length: f64,
    /// Length of the element holding the edge, m.
    pub element_size: f64,
}

impl EdgeLayer {
    /// Elements the whole mesh needs so that this edge's element is ≤ ℓ_b/LAYER_ELEMENTS
    /// (the mesh is refined uniformly in its arc weighting, so h scales as 1/n); `None`
    /// for an edge with N ≤ 0, which no mesh resolves.
    pub fn elements_needed(&self, elements: usize) -> Option<usize> {
        let ratio = self.element_size * LAYER_ELEMENTS / self.layer_length;
        ratio.is_finite().then(|| (elements as f64 * ratio).ceil().max(elements as f64) as usize)
    }

    /// True if h ≤ ℓ_b/LAYER_ELEMENTS.
    pub fn resolved(&self) -> bool {
        self.element_size * LAYER_ELEMENTS <= self.layer_length
    }
}

fn name(p: Pulley) -> &'static str {
    match p {
        Pulley::Driver => "driver",
        Pulley::Driven => "driven",
    }
}

/// The bending layers at the contact edges of a rod solution (empty for a string or
/// without contact).
pub fn edge_layers<const N: usize, K: LayoutElement<N> + ?Sized>(sol: &FemSolution<N, K>) -> Vec<(Pulley, EdgeLayer)> {
    let Some(ei) = sol.params().bending_stiffness else { return Vec::new() };
    let mut out = Vec::new();
    for p in [Pulley::Driver, Pulley::Driven] {
        let Some(z) = sol.zone(p) else { continue };
        for sigma in [z.sigma_start, z.sigma_end] {
            let n = sol.axial_force(sigma);
            // a compressed edge (N ≤ 0) has no layer of the tension kind: length 0
            let layer_length = if n > 0.0 { (ei / n).sqrt() } else { 0.0 };
            // the element on either side of the edge: the longer one
            let (e, _) = sol.mesh().locate(sigma);
            let (el, _) = sol.mesh().locate_left(sigma);
            let h = sol.mesh().elements()[e].h.max(sol.mesh().elements()[el].h);
            out.push((p, EdgeLayer { sigma, axial_force: n, layer_length, element_size: h }));
        }
    }
    out
}

/// Check a converged static solution (docs/fem-rod.md §10). Returns the warnings (empty
/// for a clean result).
///
/// # Errors
/// [`FemError::InadmissibleContact`] with the pulley, the quantity, its value and limit,
/// and the elements a resolved mesh needs where the bending layer tells.
pub fn check<const N: usize, K: LayoutElement<N> + ?Sized>(sol: &FemSolution<N, K>) -> Result<Vec<String>, FemError> {
    if sol.params().penalty.is_none() {
        return Ok(Vec::new());
    }
    let s = sol.summary();
    let scale = [s.tension_upper_mid, s.tension_lower_mid].into_iter().flatten().fold(0.0f64, |m, t| m.max(t.abs()));
    let elements = sol.mesh().len();
    let layers = edge_layers(sol);
    let needed = layers.iter().filter(|l| !l.1.resolved()).filter_map(|l| l.1.elements_needed(elements)).max();
    let inadmissible = |pulley: Pulley, quantity: String, value: f64, limit: f64| FemError::InadmissibleContact {
        pulley: name(pulley).into(),
        quantity,
        value,
        limit,
        elements,
        elements_needed: needed,
    };
    for p in [Pulley::Driver, Pulley::Driven] {
        let forces = sol.contact_forces(p);
        let load: f64 = forces.iter().map(|f| f.1).sum();
        let Some(z) = sol.zone(p) else {
            if load > UNREPORTED_LOAD_TOLERANCE * scale {
                let peak = forces.iter().copied().fold((f64::NAN, 0.0f64), |m, f| if f.1 > m.1 { f } else { m });
                let layer_length = sol.params().bending_stiffness.map_or(f64::INFINITY, |ei| (ei / sol.axial_force(peak.0).max(0.0)).sqrt());
                return Err(FemError::UnreportedContact {
                    pulley: name(p).into(),
                    load,
                    limit: UNREPORTED_LOAD_TOLERANCE * scale,
                    layer_length,
                    radius: sol.mesh().contour().radius(),
                });
            }
            continue;
        };
        // σ runs clockwise round both pulleys (σ = 0 on top of the driver), so the zone
        // covers the polar angles from φ_start clockwise to φ_end. It must not cover the
        // inner point of the pulley (φ = 0 on the driver, π on the driven: the point
        // facing the other pulley), which the spans, leaving towards the other pulley
        // from the top and the bottom, never wrap. (A stricter rule — the entry in the
        // lower half — fails the very slack loop L/L_geom = 1.15, whose lower span comes
        // up on the outer side to 176.6° by the BVP as by the FE.)
        let inner: f64 = match p {
            Pulley::Driver => 0.0,
            Pulley::Driven => std::f64::consts::PI,
        };
        let tau = 2.0 * std::f64::consts::PI;
        let covered = (z.angle_start - z.angle_end).rem_euclid(tau);
        let to_inner = (z.angle_start - inner).rem_euclid(tau);
        if to_inner <= covered {
            return Err(inadmissible(
                p,
                format!("contact zone from {:.4}° clockwise to {:.4}° covers the inner point at {:.0}° [deg of wrap past it]", z.angle_start.to_degrees(), z.angle_end.to_degrees(), inner.to_degrees()),
                (covered - to_inner).to_degrees(),
                0.0,
            ));
        }
        // A belt pressed on the pulley at a contact edge needs p = N/R + (its weight's
        // normal component) ≥ 0 just inside the zone, so N ≥ −ρgR there: a more
        // compressive axial force is a discrete equilibrium of a mesh that does not
        // resolve the contact (`rod-hanging` at 5 elements: N = −1.5 N at an edge).
        let weight_floor = sol.params().weight.unwrap_or(0.0).abs() * sol.mesh().contour().radius();
        for (what, sigma) in [("first", z.sigma_start), ("last", z.sigma_end)] {
            let n = sol.axial_force(sigma);
            let limit = -weight_floor - EDGE_FORCE_TOLERANCE * scale;
            if n.is_nan() || n < limit {
                return Err(inadmissible(p, format!("axial force at the {what} contact [N] (compressive: a belt pressed on the pulley needs N ≥ −ρgR)"), n, limit));
            }
        }
        for (what, force) in [("first", z.edge_force_start), ("last", z.edge_force_end)] {
            if let Some(f) = force {
                if f < -EDGE_FORCE_TOLERANCE * scale {
                    return Err(inadmissible(
                        p,
                        format!("edge force at the {what} contact [N] (compressive: the pulley would pull the belt)"),
                        f,
                        -EDGE_FORCE_TOLERANCE * scale,
                    ));
                }
            }
        }
    }
    // one warning for the worst edge, with the count of unresolved edges
    let unresolved: Vec<&(Pulley, EdgeLayer)> = layers.iter().filter(|l| !l.1.resolved()).collect();
    let worst = unresolved.iter().max_by(|a, b| (a.1.element_size / a.1.layer_length).total_cmp(&(b.1.element_size / b.1.layer_length)));
    let warnings = worst
        .map(|(p, l)| {
            let advice = match l.elements_needed(elements) {
                Some(n) => format!("use at least {n} elements"),
                None => "N ≤ 0 there: no mesh resolves it; refine the mesh and check the scene".into(),
            };
            format!(
                "unresolved bending layer at {} of 4 contact edges (worst on the {} pulley): ℓ_b = √(EI/N) = {:.3e} m (N = {:.4e} N) against an element of {:.3e} m there — edge forces and contact angles are not resolved; {advice}",
                unresolved.len(),
                name(*p),
                l.layer_length,
                l.axial_force,
                l.element_size,
            )
        })
        .into_iter()
        .collect();
    Ok(warnings)
}

/// The driven pulley's torque balance may be off by 1e-6 of the load scale (measured on
/// the catalogue's drives, both senses and power flows, 32 and 128 elements: ≤ 4e-14 for
/// the steady solve, ≤ 4e-11 for a transient's last step; an axial stiffness of 1e50 N
/// is off by 1 or by 1e19).
pub const TORQUE_BALANCE_TOLERANCE: f64 = 1e-6;

/// Self-check of a two-pulley drive's result (steady or transient; docs/fem-drive.md
/// §14): the torque the driven pulley takes from the contact tractions equals its load
/// M₂ + d₂ω₂. The scale is |M₂| + |d₂ω₁| + ρgLR (the load, or the belt's weight on
/// the pulley radius for a free-running drive); a drive with no load and no gravity has
/// nothing to check. A result without a driven pulley (one-pulley layout) passes.
///
/// # Errors
/// [`FemError::TorqueBalance`] with the torque, the load and the limit.
pub fn check_drive_torque(problem: &crate::FemProblem, summary: &drive::summary::Summary) -> Result<(), FemError> {
    let (Some(torque), Some(omega2)) = (summary.driven.as_ref().and_then(|p| p.torque), summary.driven_speed) else {
        return Ok(());
    };
    let d = &problem.drive;
    let load = d.driven_torque + d.driven_damping * omega2;
    let weight = problem.belt.mass_per_length * problem.effects.gravity.unwrap_or(0.0).abs() * problem.belt.length * problem.geometry.radius;
    let limit = TORQUE_BALANCE_TOLERANCE * (d.driven_torque.abs() + (d.driven_damping * d.driver_speed).abs() + weight);
    let off = (torque - load).abs();
    // a NaN torque or speed fails too
    if limit > 0.0 && (off.is_nan() || off > limit) {
        return Err(FemError::TorqueBalance { torque, load, limit, axial_stiffness: problem.belt.axial_stiffness });
    }
    Ok(())
}
