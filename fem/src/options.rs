//! Options of an FE run: the contract [`FemOptions`] (mesh, formulation, penalty) and
//! the solver settings [`SolverSettings`], each field with its default and valid range.

use drive::scene::Scene;

use crate::error::FemError;
use crate::mesh::MAX_ELEMENTS;

/// Options of an FE run.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FemOptions {
    /// Number of elements over the whole loop, 4 ≤ N ≤ 2²⁰. Default: the scene's
    /// `fem.elements` (256).
    pub elements: usize,
    /// Formulation name from [`crate::available_formulations`]. Default
    /// [`crate::default_formulation`].
    pub formulation: String,
    /// Penalty factor P of the normal contact (N/m², > 0, finite); `None` = chosen from
    /// the belt: P = κ EA/R² with κ = [`SolverSettings::penalty_factor`]
    /// (docs/fem-string.md §9, §11).
    pub penalty: Option<f64>,
}

impl FemOptions {
    /// The `options` record of a run ([`crate::FemRun::options`]): method, elements,
    /// formulation, the resolved penalty and the solver settings, with the analysis' own
    /// entries `extra` (a JSON object) added.
    pub(crate) fn record(&self, penalty: Option<f64>, settings: &SolverSettings, extra: serde_json::Value) -> serde_json::Value {
        let mut record = serde_json::json!({
            "method": "fem",
            "elements": self.elements,
            "formulation": self.formulation,
            "penalty": penalty,
            "settings": settings,
        });
        if let (Some(r), serde_json::Value::Object(e)) = (record.as_object_mut(), extra) {
            r.extend(e);
        }
        record
    }

    /// The scene's `fem` block (elements, penalty) with formulation `formulation`.
    pub fn from_scene(scene: &Scene, formulation: &str) -> FemOptions {
        let f = scene.fem_settings();
        FemOptions { elements: f.elements, formulation: formulation.to_string(), penalty: f.penalty }
    }

    /// Checks the documented ranges.
    ///
    /// # Errors
    /// [`FemError::InvalidOption`] naming the field, or [`FemError::UnknownFormulation`].
    pub fn validate(&self) -> Result<(), FemError> {
        if !(4..=MAX_ELEMENTS).contains(&self.elements) {
            return Err(FemError::InvalidOption {
                field: "elements",
                value: self.elements.to_string(),
                reason: format!("need 4 ≤ elements ≤ {MAX_ELEMENTS} (one element per region at least)"),
            });
        }
        if let Some(p) = self.penalty {
            if !(p.is_finite() && p > 0.0) {
                return Err(FemError::InvalidOption {
                    field: "penalty",
                    value: p.to_string(),
                    reason: "the penalty factor must be positive and finite (N/m²)".into(),
                });
            }
        }
        if crate::formulation::find_element(&self.formulation).is_none() {
            return Err(FemError::UnknownFormulation {
                name: self.formulation.clone(),
                available: crate::available_formulations().iter().map(|s| s.to_string()).collect(),
            });
        }
        Ok(())
    }
}

/// Solver settings (docs/fem-string.md §8, §9). `Default` gives the documented values.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolverSettings {
    /// Newton converges when a full step has ‖Δ‖ ≤ this (scaled update, §8). Default
    /// 1e-10; range (0, 1e-3].
    pub update_tolerance: f64,
    /// Newton iteration limit per homotopy step; also sets the step control (§9).
    /// Default 20; ≥ 5.
    pub max_step_iterations: usize,
    /// First homotopy step Δη. Default 1/8; (0, ½].
    pub initial_step: f64,
    /// Largest homotopy step. Default ¼; [initial_step, ½].
    pub max_step: f64,
    /// Smallest homotopy step before `HomotopyStalled`. Default 1e-6; (0, initial_step].
    pub min_step: f64,
    /// Limit on homotopy steps (accepted + rejected). Default 400; ≥ 1.
    pub max_steps: usize,
    /// Arc refinement weight w of the mesh distribution (§5). Default 1; ≥ 1.
    pub arc_weight: f64,
    /// κ of the default penalty P = κ EA/R² (§9, §11). Default 1e5; > 0.
    pub penalty_factor: f64,
    /// κ_h: the homotopy runs with the penalty capped at κ_h EA/R², which is then
    /// raised ×10 per Newton solve to the final P (§9). Default 1e4; > 0.
    pub homotopy_penalty_factor: f64,
    /// Fit the mesh to the contact boundaries after the homotopy (§5): move a node to
    /// each located boundary and re-solve, until they agree. Default true.
    pub contact_fitting: bool,
    /// Largest number of fitting passes (refits) of the static fit, per penalty level:
    /// `FitRules::max_passes` of [`crate::fitting`]. Default 10; ≥ 1. The direct steady
    /// drive solve has its own limit, `string_drive::DriveSettings::max_fits`.
    pub max_fits: usize,
    /// Fitting has converged when every recovered point lies within this times L_c of
    /// its node — for the static fit, of the position its node was fitted to; for the
    /// direct steady solve, of the nearest node ([`crate::fitting::Measure`]). Default
    /// 1e-9 (1.4e-9 m in `string-hanging`); (0, 1e-3].
    pub fit_tolerance: f64,
    /// The grading of the static fit's meshes towards the contact edges
    /// ([`crate::mesh::Grading`]); `None` (default): the model's own — a Cosserat rod's
    /// shear layer ([`crate::static_homotopy::shear_layer_grading`]), none for a string or a
    /// Kirchhoff rod. Read only by the static hanging problem's contact fitting
    /// (`StringHanging`, with `contact_fitting`); the drives' fits keep their own
    /// gradings. The shell's planar start sets it to its contact layer
    /// (`HangingBelt::edge_grading`, docs/fem-shell.md §9.1).
    pub grading: Option<crate::mesh::Grading>,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            update_tolerance: 1e-10,
            max_step_iterations: 20,
            initial_step: 0.125,
            max_step: 0.25,
            min_step: 1e-6,
            max_steps: 400,
            arc_weight: 1.0,
            penalty_factor: 1e5,
            homotopy_penalty_factor: 1e4,
            contact_fitting: true,
            max_fits: 10,
            fit_tolerance: 1e-9,
            grading: None,
        }
    }
}

impl SolverSettings {
    /// Checks the documented ranges.
    ///
    /// # Errors
    /// [`FemError::InvalidOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), FemError> {
        let bad = |field: &'static str, value: String, reason: &str| {
            Err(FemError::InvalidOption { field, value, reason: reason.to_string() })
        };
        if !(self.update_tolerance > 0.0 && self.update_tolerance <= 1e-3) {
            return bad("update_tolerance", self.update_tolerance.to_string(), "must lie in (0, 1e-3]");
        }
        if self.max_step_iterations < 5 {
            return bad("max_step_iterations", self.max_step_iterations.to_string(), "must be ≥ 5");
        }
        if !(self.initial_step > 0.0 && self.initial_step <= 0.5) {
            return bad("initial_step", self.initial_step.to_string(), "must lie in (0, 0.5]");
        }
        if !(self.max_step >= self.initial_step && self.max_step <= 0.5) {
            return bad("max_step", self.max_step.to_string(), "must lie in [initial_step, 0.5]");
        }
        if !(self.min_step > 0.0 && self.min_step <= self.initial_step) {
            return bad("min_step", self.min_step.to_string(), "must lie in (0, initial_step]");
        }
        if self.max_steps == 0 {
            return bad("max_steps", "0".into(), "must be ≥ 1");
        }
        if !(self.arc_weight.is_finite() && self.arc_weight >= 1.0) {
            return bad("arc_weight", self.arc_weight.to_string(), "must be finite and ≥ 1");
        }
        if let Some(g) = self.grading {
            if !(g.width.is_finite() && g.width > 0.0 && g.ratio.is_finite() && g.ratio >= 0.0) {
                return bad("grading", format!("width {:e} m, ratio {:e}", g.width, g.ratio), "needs a positive finite width and a finite ratio ≥ 0");
            }
        }
        if !(self.penalty_factor.is_finite() && self.penalty_factor > 0.0) {
            return bad("penalty_factor", self.penalty_factor.to_string(), "must be positive and finite");
        }
        if !(self.homotopy_penalty_factor.is_finite() && self.homotopy_penalty_factor > 0.0) {
            return bad("homotopy_penalty_factor", self.homotopy_penalty_factor.to_string(), "must be positive and finite");
        }
        if self.max_fits == 0 {
            return bad("max_fits", "0".into(), "must be ≥ 1");
        }
        if !(self.fit_tolerance > 0.0 && self.fit_tolerance <= 1e-3) {
            return bad("fit_tolerance", self.fit_tolerance.to_string(), "must lie in (0, 1e-3]");
        }
        Ok(())
    }
}
