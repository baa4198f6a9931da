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

/// Time history of a transient (or of the transient run to a steady state)
/// (`history`, optional): one entry per time step in every vector, all of the length of
/// `time`. Quantities as in [`Summary`] (tensions are the axial forces at x = 0 of each
/// span, torques the moment of the belt on the pulley, clockwise positive); arcs in
/// rad. Written by FE drive runs only (docs/fem-drive.md §8).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct History {
    /// Time t at the end of each step, s.
    pub time: Vec<f64>,
    /// Driven speed ω₂ over the step, rad/s.
    pub driven_speed: Vec<f64>,
    /// Transport rate c over the step, m/s.
    pub transport_rate: Vec<f64>,
    /// Axial force at x = 0 of the upper span, N.
    pub tension_upper_mid: Vec<f64>,
    /// Axial force at x = 0 of the lower span, N.
    pub tension_lower_mid: Vec<f64>,
    /// Stick arc on the driver, rad.
    pub driver_stick_arc: Vec<f64>,
    /// Slip arc on the driver, rad.
    pub driver_slip_arc: Vec<f64>,
    /// Torque of the belt on the driver, N·m.
    pub driver_torque: Vec<f64>,
    /// Stick arc on the driven pulley, rad.
    pub driven_stick_arc: Vec<f64>,
    /// Slip arc on the driven pulley, rad.
    pub driven_slip_arc: Vec<f64>,
    /// Torque of the belt on the driven pulley, N·m.
    pub driven_torque: Vec<f64>,
    /// Steady-state rate r_n: largest scaled change of the unknowns per radian of
    /// driver rotation (docs/fem-drive.md §7), 1/rad.
    pub change_rate: Vec<f64>,
}

impl History {
    /// Number of recorded steps.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True without steps.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    fn columns(&self) -> [(&'static str, &Vec<f64>); 12] {
        [
            ("time", &self.time),
            ("driven_speed", &self.driven_speed),
            ("transport_rate", &self.transport_rate),
            ("tension_upper_mid", &self.tension_upper_mid),
            ("tension_lower_mid", &self.tension_lower_mid),
            ("driver_stick_arc", &self.driver_stick_arc),
            ("driver_slip_arc", &self.driver_slip_arc),
            ("driver_torque", &self.driver_torque),
            ("driven_stick_arc", &self.driven_stick_arc),
            ("driven_slip_arc", &self.driven_slip_arc),
            ("driven_torque", &self.driven_torque),
            ("change_rate", &self.change_rate),
        ]
    }

    /// Checks equal lengths and finite values.
    ///
    /// # Errors
    /// [`ResultError::FieldLength`] or [`ResultError::NotFinite`] naming the entry,
    /// e.g. `history.driven_speed[3]`.
    pub fn check(&self) -> Result<(), ResultError> {
        let n = self.time.len();
        for (name, v) in self.columns() {
            if v.len() != n {
                return Err(ResultError::FieldLength { field: format!("history.{name}"), len: v.len(), expected: n });
            }
            if let Some((i, &value)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(ResultError::NotFinite { quantity: format!("history.{name}[{i}]"), value });
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
    /// Time history of a transient FE run (optional; absent for static and BVP runs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub history: Option<History>,
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
        if let Some(h) = &self.history {
            h.check()?;
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
