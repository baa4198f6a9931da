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
//! The public entry points below are the contract the CLI and the verification harness
//! use: [`available_formulations`] (the plug-in registry, by name) and [`solve_scene`].

use drive::scene::Scene;
use drive::summary::Summary;
use drive::view::SolutionView;
use thiserror::Error;

/// Options of an FE run.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FemOptions {
    /// Number of elements over the whole loop. Default: the scene's `fem.elements` (256).
    pub elements: usize,
    /// Formulation name from [`available_formulations`].
    pub formulation: String,
    /// Penalty factor of the normal contact (N/m²); `None` = chosen from the belt.
    pub penalty: Option<f64>,
}

/// Work of an FE run.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct FemStats {
    /// Wall time of the whole run (homotopy included), s.
    pub wall_seconds: f64,
    /// Newton iterations summed over the homotopy.
    pub newton_iterations: usize,
    /// Unknowns of the global system.
    pub unknowns: usize,
    /// Elements.
    pub elements: usize,
    /// Homotopy steps.
    pub homotopy_steps: usize,
}

/// An FE run: the solution behind the common view, its summary and cost.
pub struct FemRun {
    /// The solution, sampled through the common view.
    pub view: Box<dyn SolutionView + Send + Sync>,
    /// The summary.
    pub summary: Summary,
    /// Work counters.
    pub stats: FemStats,
    /// Options used (for reproducibility).
    pub options: serde_json::Value,
    /// The energy terms assembled (the effects simulated), e.g. "strain energy (Biot, gauss3)".
    pub terms: Vec<String>,
}

/// Why an FE run produced no solution.
#[derive(Debug, Error)]
pub enum FemError {
    /// The scene asks for a model or formulation that does not exist.
    #[error("no finite element model for this scene: {0}")]
    Unsupported(String),
}

/// Names of the element formulations registered with the plug-in trait.
pub fn available_formulations() -> Vec<&'static str> {
    Vec::new()
}

/// Solve a scene with MEL finite elements.
pub fn solve_scene(_scene: &Scene, opts: &FemOptions) -> Result<FemRun, FemError> {
    Err(FemError::Unsupported(format!(
        "formulation `{}`: no MEL finite element formulation is implemented yet (registered: {:?})",
        opts.formulation,
        available_formulations()
    )))
}

#[cfg(test)]
mod tests {
    /// The registry reports honestly that no formulation exists yet.
    #[test]
    fn registry_is_empty_until_elements_exist() {
        assert!(super::available_formulations().is_empty());
    }
}
