//! `fem`: mixed Eulerian–Lagrangian (MEL) finite elements of belt drives — the second,
//! independent way beltcheck computes a scene.
//!
//! Role (DESIGN.md, "The MEL finite elements"): elements sit at fixed points of the
//! looped contour coordinate σ of [`drive::contour::Contour`] while material flows
//! through the mesh. Primary unknowns are the material coordinate s(σ) and the transverse
//! deflection ν(σ) (eq. 27), approximated by cubic Hermite functions (eq. 43); each effect
//! of a scene (strain energy, gravity, contact, transport inertia) is one energy term over
//! elements, assembled only when the scene calls for it; element derivatives come from
//! forward-mode AD; global systems are solved by Newton on faer's sparse LU with homotopy
//! from tight to slack configurations (§7.1). Solutions implement
//! [`drive::view::SolutionView`], so the verification harness compares them with the BVP
//! references without either crate seeing the other (`fem` never depends on `bvp`).
//!
//! Status: the element library is not built yet (issue "MEL finite elements: the string
//! hanging on two pulleys"). The crate exists so that the dependency structure of the
//! workspace is in place; [`available_formulations`] is the registry the harness will
//! query and is empty today.

/// Names of the element formulations registered with the plug-in trait. Empty until the
/// first MEL element lands; the CLI reports "no FE formulation available" instead of
/// pretending to solve.
pub fn available_formulations() -> Vec<&'static str> {
    Vec::new()
}

#[cfg(test)]
mod tests {
    /// The registry reports honestly that no formulation exists yet.
    #[test]
    fn registry_is_empty_until_elements_exist() {
        assert!(super::available_formulations().is_empty());
    }
}
