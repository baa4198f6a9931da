//! The result of one run, exactly DESIGN.md's "Result format" (`beltcheck solve
//! --json`): `scene`, `method`, `converged`, `summary`, `cost`, `fields`, and
//! `options` (the solver options used, for reproducibility).
//!
//! Write results with [`RunResult::to_json_pretty`], which refuses non-finite
//! numbers (serde_json would silently write NaN as `null`).

use serde::{Deserialize, Serialize};

use crate::error::ResultError;
use crate::summary::Summary;

/// Names of the field norms the harness computes over σ and a gate may name (see
/// [`crate::GateSettings::tolerances`]): max and L2 norms of the error in the
/// deflection ν(σ), the axial force and the bending moment.
pub const FIELD_NORM_NAMES: [&str; 6] = [
    "deflection_max",
    "deflection_l2",
    "tension_max",
    "tension_l2",
    "moment_max",
    "moment_l2",
];

/// Fields sampled at points σ of the contour (`fields`); all vectors have the
/// length of `sigma`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Fields {
    /// Contour coordinate σ, m, in [0, 2H + 2πR).
    pub sigma: Vec<f64>,
    /// x of the belt point r(σ), m.
    pub x: Vec<f64>,
    /// y of the belt point r(σ), m.
    pub y: Vec<f64>,
    /// Axial force N(σ), N.
    pub tension: Vec<f64>,
    /// Bending moment M(σ), N·m; absent for a string.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moment: Option<Vec<f64>>,
}

impl Fields {
    /// Number of samples (length of `sigma`).
    pub fn len(&self) -> usize {
        self.sigma.len()
    }

    /// True without samples.
    pub fn is_empty(&self) -> bool {
        self.sigma.is_empty()
    }

    /// Checks equal lengths and finite values.
    ///
    /// # Errors
    /// [`ResultError::FieldLength`], or [`ResultError::NotFinite`] naming the
    /// sample, e.g. `fields.tension[12]`.
    pub fn check(&self) -> Result<(), ResultError> {
        let n = self.sigma.len();
        let mut all: Vec<(&str, &Vec<f64>)> = vec![
            ("sigma", &self.sigma),
            ("x", &self.x),
            ("y", &self.y),
            ("tension", &self.tension),
        ];
        if let Some(m) = &self.moment {
            all.push(("moment", m));
        }
        for (name, v) in &all {
            if v.len() != n {
                return Err(ResultError::FieldLength {
                    field: name.to_string(),
                    len: v.len(),
                    expected: n,
                });
            }
        }
        for (name, v) in all {
            if let Some((i, &value)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(ResultError::NotFinite {
                    quantity: format!("fields.{name}[{i}]"),
                    value,
                });
            }
        }
        Ok(())
    }
}

/// Work spent on a run (`cost`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Cost {
    /// Wall-clock time of the solve, s.
    pub wall_seconds: f64,
    /// Newton iterations, summed over continuation steps and outer loops.
    pub newton_iterations: usize,
    /// Number of unknowns of the final discrete system.
    pub unknowns: usize,
    /// Mesh nodes of the final mesh (collocation nodes or FE nodes), if meaningful.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh_nodes: Option<usize>,
}

/// One run = scene + method + discretisation (DESIGN.md "Result format").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// Scene name.
    pub scene: String,
    /// Method, e.g. `bvp-collocation`, `bvp-shooting`, or an FE formulation name.
    pub method: String,
    /// Whether the solver met its tolerance.
    pub converged: bool,
    /// Named scalars.
    pub summary: Summary,
    /// Work spent.
    pub cost: Cost,
    /// Sampled fields, if requested.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fields: Option<Fields>,
    /// The solver options used (e.g. the serialised settings block), so the run can
    /// be reproduced.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub options: Option<serde_json::Value>,
}

impl RunResult {
    /// Checks that nothing non-finite would be written: summary, wall time, fields.
    ///
    /// # Errors
    /// The first offending quantity.
    pub fn check(&self) -> Result<(), ResultError> {
        self.summary.check_finite()?;
        if !self.cost.wall_seconds.is_finite() {
            return Err(ResultError::NotFinite {
                quantity: "cost.wall_seconds".into(),
                value: self.cost.wall_seconds,
            });
        }
        if let Some(f) = &self.fields {
            f.check()?;
        }
        Ok(())
    }

    /// Pretty JSON in the result format, after [`RunResult::check`].
    ///
    /// # Errors
    /// As [`RunResult::check`].
    pub fn to_json_pretty(&self) -> Result<String, ResultError> {
        self.check()?;
        // Cannot fail for these types once all numbers are finite.
        Ok(serde_json::to_string_pretty(self).unwrap_or_default())
    }

    /// Reads a result written by [`RunResult::to_json_pretty`] (or another tool).
    ///
    /// # Errors
    /// serde_json's error for malformed input.
    pub fn from_json_str(text: &str) -> Result<RunResult, serde_json::Error> {
        serde_json::from_str(text)
    }
}
