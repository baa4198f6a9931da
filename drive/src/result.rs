//! The result of one run, exactly DESIGN.md's "Result format" (`beltcheck solve
//! --json`): `scene`, `method`, `converged`, `summary`, `cost`, `fields`, and
//! `options` (the solver options used, for reproducibility) — and, where a model
//! produces them, fields in the three shapes of the contract:
//! - along σ ([`Fields`], `fields`): the planar models;
//! - over the mid-surface (σ, ζ) ([`SurfaceFields`], `surface`): the shell;
//! - in time ([`TimeSeries`], `history`): scalar channels per time step and optional
//!   frames of fields along σ or over (σ, ζ) at chosen instants. The friction drive's
//!   channels ([`History`]) are one such series.
//!
//! Write results with [`RunResult::to_json_pretty`], which refuses non-finite
//! numbers (serde_json would silently write NaN as `null`).

use std::collections::BTreeMap;
use std::fmt;

use serde::{Deserialize, Serialize};

use crate::error::ResultError;
use crate::summary::Summary;
use crate::view::ContactState;

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
/// length of `sigma`. The five of every result are `sigma`, `x`, `y`, `tension` and (rods)
/// `moment`; a one-pulley scene (open belt) also writes `rotation`, `transverse_force`,
/// `shear_strain`, `pressure`, `friction` and `state`, each where its model has it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Fields {
    /// Contour coordinate σ, m: in [0, 2H + 2πR) round the two-pulley loop, in
    /// [0, 2D + πR] from the inflow end of a one-pulley scene.
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
    /// Section rotation θ(σ), rad: angle of the director e₁ from +x, counter-clockwise,
    /// continuous (0 at the inflow end, −π at the outflow end of a one-pulley scene);
    /// open belts of rods only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<Vec<f64>>,
    /// Transverse (shear) force Q(σ), N; open belts of rods only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transverse_force: Option<Vec<f64>>,
    /// Shear strain Γ₂(σ) = Q/b₂; open belts of Cosserat rods only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_strain: Option<Vec<f64>>,
    /// Contact pressure p(σ) ≥ 0 per unit contour length, N/m, 0 on the spans; open belts
    /// only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<Vec<f64>>,
    /// Friction traction f_t(σ) of the pulley on the belt per unit contour length, N/m,
    /// + along σ, 0 on the spans; open belts with friction only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<Vec<f64>>,
    /// Contact state at σ (`free`, `contact`, `stick`, `slip`); open belts only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<Vec<ContactState>>,
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
        for (name, v) in [
            ("moment", &self.moment),
            ("rotation", &self.rotation),
            ("transverse_force", &self.transverse_force),
            ("shear_strain", &self.shear_strain),
            ("pressure", &self.pressure),
            ("friction", &self.friction),
        ] {
            if let Some(v) = v {
                all.push((name, v));
            }
        }
        if let Some(state) = &self.state {
            if state.len() != n {
                return Err(ResultError::FieldLength { field: "state".into(), len: state.len(), expected: n });
            }
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
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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

impl From<History> for TimeSeries {
    /// The drive's channels under their JSON names (`driven_speed`, `driver_torque`, …):
    /// the same `history` JSON as before.
    fn from(h: History) -> TimeSeries {
        let mut series = BTreeMap::new();
        for (name, v) in h.columns().into_iter().skip(1) {
            series.insert(name.to_string(), v.clone());
        }
        TimeSeries { time: h.time, series, frames: Vec::new() }
    }
}

/// Names of the fields over the mid-surface ([`SurfaceFields`]) with their units:
/// - `x`, `y`, `z`: the mid-surface point r(σ, ζ), m (z lateral, along the drum axes);
/// - `membrane_force`: membrane force n_σσ per unit width along the belt, N/m;
/// - `bending_moment`: bending moment m_σσ per unit width, N;
/// - `contact_pressure`: interlayer pressure P γ, N/m²;
/// - `interlayer_shear`: |u|, the tangential displacement of the elastic interlayer, m.
pub const SURFACE_FIELD_NAMES: [&str; 7] = ["x", "y", "z", "membrane_force", "bending_moment", "contact_pressure", "interlayer_shear"];

/// Fields over the mid-surface of a shell belt (`surface`): values on the grid σ_i × ζ_j,
/// every field a matrix `[i][j]` of `sigma.len()` rows of `zeta.len()` values. JSON:
/// `{"sigma": [...], "zeta": [...], "<name>": [[...], ...], ...}` with names of
/// [`SURFACE_FIELD_NAMES`].
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct SurfaceFields {
    /// Contour coordinate σ along the belt, m.
    pub sigma: Vec<f64>,
    /// Width coordinate ζ ∈ [−b/2, b/2] across the belt, m.
    pub zeta: Vec<f64>,
    /// Field name → values at (σ_i, ζ_j).
    #[serde(flatten)]
    pub values: BTreeMap<String, Vec<Vec<f64>>>,
}

impl SurfaceFields {
    /// Checks names, the grid shape of every field and finite values.
    ///
    /// # Errors
    /// [`ResultError::UnknownField`] for a name outside [`SURFACE_FIELD_NAMES`],
    /// [`ResultError::FieldLength`] for a row count or row length that misses the grid,
    /// [`ResultError::NotFinite`] naming the sample, e.g. `surface.z[3][1]`.
    pub fn check(&self) -> Result<(), ResultError> {
        check_finite_vec("surface.sigma", &self.sigma)?;
        check_finite_vec("surface.zeta", &self.zeta)?;
        for (name, rows) in &self.values {
            if !SURFACE_FIELD_NAMES.contains(&name.as_str()) {
                return Err(ResultError::UnknownField {
                    field: format!("surface.{name}"),
                    suggestion: crate::suggest::nearest(name, SURFACE_FIELD_NAMES.iter().copied()),
                });
            }
            if rows.len() != self.sigma.len() {
                return Err(ResultError::FieldLength { field: format!("surface.{name}"), len: rows.len(), expected: self.sigma.len() });
            }
            for (i, row) in rows.iter().enumerate() {
                let field = format!("surface.{name}[{i}]");
                if row.len() != self.zeta.len() {
                    return Err(ResultError::FieldLength { field, len: row.len(), expected: self.zeta.len() });
                }
                check_finite_vec(&field, row)?;
            }
        }
        Ok(())
    }
}

/// Fields at one instant of a time series (`history.frames[k]`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Frame {
    /// t, s.
    pub time: f64,
    /// Fields along σ at t.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fields: Option<Fields>,
    /// Fields over (σ, ζ) at t.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<SurfaceFields>,
}

/// Quantities in time (`history`): named scalar channels, one value per time step, all
/// of the length of `time`, and optional frames of fields at chosen instants. JSON:
/// `{"time": [...], "<channel>": [...], ..., "frames": [...]}` — a friction drive's
/// [`History`] converts to it with the same JSON. Channel names are lowercase
/// identifiers (`a`–`z`, `0`–`9`, `_`, `.`), other than `time` and `frames`; their units
/// are the model's (the drive's: [`History`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct TimeSeries {
    /// Time t at the end of each step, s.
    pub time: Vec<f64>,
    /// Channel name → one value per step.
    #[serde(flatten)]
    pub series: BTreeMap<String, Vec<f64>>,
    /// Fields at chosen instants, in increasing time. Optional, default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub frames: Vec<Frame>,
}

impl TimeSeries {
    /// Number of recorded steps.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True without steps.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// The values of a channel.
    pub fn channel(&self, name: &str) -> Option<&[f64]> {
        self.series.get(name).map(Vec::as_slice)
    }

    /// Appends a step: t and the value of every channel (a channel first seen here must
    /// be the first step; [`TimeSeries::check`] refuses ragged channels).
    pub fn push(&mut self, time: f64, values: &[(&str, f64)]) {
        self.time.push(time);
        for &(name, v) in values {
            self.series.entry(name.to_string()).or_default().push(v);
        }
    }

    /// Checks channel names and lengths, finite values, and frames in increasing time
    /// with valid fields.
    ///
    /// # Errors
    /// [`ResultError::UnknownField`] for an invalid channel name,
    /// [`ResultError::FieldLength`] or [`ResultError::NotFinite`] naming the entry, e.g.
    /// `history.driven_speed[3]`, `history.frames[1].surface.z[0][2]`.
    pub fn check(&self) -> Result<(), ResultError> {
        check_finite_vec("history.time", &self.time)?;
        let n = self.time.len();
        for (name, v) in &self.series {
            let valid = !name.is_empty()
                && !matches!(name.as_str(), "time" | "frames")
                && name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || matches!(c, '_' | '.'));
            if !valid {
                return Err(ResultError::UnknownField { field: format!("history.{name}"), suggestion: None });
            }
            if v.len() != n {
                return Err(ResultError::FieldLength { field: format!("history.{name}"), len: v.len(), expected: n });
            }
            check_finite_vec(&format!("history.{name}"), v)?;
        }
        for (k, f) in self.frames.iter().enumerate() {
            let at = |e: ResultError| e.within(&format!("history.frames[{k}]."));
            check_finite_vec(&format!("history.frames[{k}].time"), std::slice::from_ref(&f.time))?;
            if k > 0 && f.time <= self.frames[k - 1].time {
                return Err(ResultError::NotFinite { quantity: format!("history.frames[{k}].time (not after frames[{}])", k - 1), value: f.time });
            }
            if let Some(fields) = &f.fields {
                fields.check().map_err(at)?;
            }
            if let Some(surface) = &f.surface {
                surface.check().map_err(at)?;
            }
        }
        Ok(())
    }
}

/// The first non-finite entry of `v` as [`ResultError::NotFinite`] named `name[i]`.
fn check_finite_vec(name: &str, v: &[f64]) -> Result<(), ResultError> {
    match v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        Some((i, &value)) => Err(ResultError::NotFinite { quantity: format!("{name}[{i}]"), value }),
        None => Ok(()),
    }
}

/// The discretisation parameter of a run: a tolerance (BVP, closed forms solved to a
/// tolerance), a 1-D mesh along σ (the rods and strings), or a 2-D mesh over (σ, ζ) with a
/// time step (the shell's transient). JSON: `{"tolerance": 1e-8}`, `{"elements": 64}`,
/// `{"mesh2d": {"sigma": 64, "zeta": 4, "time_step": 0.01}}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Discretisation {
    /// BVP: the solver's relative tolerance (its norm is defined by the `bvp` crate).
    Tolerance(f64),
    /// FE: number of elements round the loop.
    Elements(usize),
    /// FE over the mid-surface: elements along σ and across ζ, and the time step Δt, s.
    Mesh2d {
        /// Elements along the belt (σ).
        sigma: usize,
        /// Elements across the width (ζ).
        zeta: usize,
        /// Time step Δt, s.
        time_step: f64,
    },
}

/// What a refinement from one discretisation to the next refines
/// ([`Discretisation::refinement`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refinement {
    /// Every discretisation parameter by one ratio (a 1-D mesh; a 2-D mesh with its time
    /// step): the sequence converges to the model's solution.
    Together,
    /// A 2-D mesh at one time step: the sequence converges to the limit in space at that
    /// step.
    Mesh,
    /// The time step on one 2-D mesh: the sequence converges to the time-continuous
    /// limit on that mesh.
    Step,
    /// n_ζ alone, on one σ-mesh at one time step: the sequence converges to the limit
    /// across the width on that σ-mesh and step.
    Width,
}

impl Discretisation {
    /// The refinement ratio r > 1 from `self` to the finer `fine`
    /// ([`Discretisation::refinement`] without its kind).
    pub fn refinement_ratio(self, fine: Discretisation) -> Option<f64> {
        self.refinement(fine).map(|(_, r)| r)
    }

    /// How `fine` refines `self`, and by which ratio r > 1: n_fine/n for 1-D meshes
    /// ([`Refinement::Together`]: a 1-D mesh has one h); for 2-D meshes either σ and Δt
    /// together (their ratios agree to 1e-9: the limit of space and time), or σ alone at
    /// one Δt ([`Refinement::Mesh`]: the limit in space at that step), or Δt alone on one
    /// mesh ([`Refinement::Step`]: the time-continuous limit on that mesh), or n_ζ alone
    /// on one σ-mesh at one Δt ([`Refinement::Width`], ratio n_ζ,fine/n_ζ: the limit
    /// across the width on that σ-mesh and step). Otherwise ζ is refined
    /// with σ by the same ratio or held (a sequence at one n_ζ converges to that n_ζ's
    /// limit: the error across the width is then not in what the sequence measures, and
    /// a study says so); a step refinement holds both counts. `None` for tolerances,
    /// mixed kinds, ratios ≤ 1 or that differ.
    pub fn refinement(self, fine: Discretisation) -> Option<(Refinement, f64)> {
        let (kind, r) = match (self, fine) {
            (Discretisation::Elements(a), Discretisation::Elements(b)) => (Refinement::Together, b as f64 / a as f64),
            (Discretisation::Mesh2d { sigma: s0, zeta: z0, time_step: t0 }, Discretisation::Mesh2d { sigma: s1, zeta: z1, time_step: t1 }) => {
                let (rs, rz, rt) = (s1 as f64 / s0 as f64, z1 as f64 / z0 as f64, t0 / t1);
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
                let zeta_follows = close(rs, rz) || z0 == z1;
                if s0 == s1 && z0 == z1 {
                    (Refinement::Step, rt)
                } else if s0 == s1 && close(rt, 1.0) {
                    (Refinement::Width, rz)
                } else if zeta_follows && close(rt, 1.0) {
                    (Refinement::Mesh, rs)
                } else if zeta_follows && close(rs, rt) {
                    (Refinement::Together, rs)
                } else {
                    return None;
                }
            }
            _ => return None,
        };
        (r.is_finite() && r > 1.0).then_some((kind, r))
    }

    /// The element count along σ of a mesh (the x-axis of convergence plots); `None`
    /// for a tolerance.
    pub fn elements_along(self) -> Option<usize> {
        match self {
            Discretisation::Tolerance(_) => None,
            Discretisation::Elements(n) | Discretisation::Mesh2d { sigma: n, .. } => Some(n),
        }
    }

    /// Checks a discretisation read from outside: a tolerance finite in (0, 1), at
    /// least one element, a time step finite and > 0.
    ///
    /// # Errors
    /// [`ResultError::Discretisation`] naming the entry, e.g. `discretisation.elements`.
    pub fn check(self) -> Result<(), ResultError> {
        let bad = |field: &str, value: f64, expected: &'static str| Err(ResultError::Discretisation { field: format!("discretisation.{field}"), value, expected });
        match self {
            Discretisation::Tolerance(t) if !(t > 0.0 && t < 1.0) => bad("tolerance", t, "a tolerance in (0, 1)"),
            Discretisation::Elements(0) => bad("elements", 0.0, "at least one element"),
            Discretisation::Mesh2d { sigma, zeta, .. } if sigma == 0 || zeta == 0 => {
                bad(if sigma == 0 { "mesh2d.sigma" } else { "mesh2d.zeta" }, 0.0, "at least one element")
            }
            Discretisation::Mesh2d { time_step, .. } if !(time_step.is_finite() && time_step > 0.0) => bad("mesh2d.time_step", time_step, "a finite time step > 0"),
            _ => Ok(()),
        }
    }

    /// The short form of tables and plot labels: `1e-8`, `256`, `64×4 Δt 1e-2`.
    pub fn cell(self) -> String {
        match self {
            Discretisation::Tolerance(t) => fmt_tolerance(t),
            Discretisation::Elements(n) => n.to_string(),
            Discretisation::Mesh2d { sigma, zeta, time_step } => format!("{sigma}×{zeta} Δt {}", fmt_tolerance(time_step)),
        }
    }
}

impl fmt::Display for Discretisation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Discretisation::Tolerance(t) => write!(f, "tol {}", fmt_tolerance(*t)),
            Discretisation::Elements(n) => write!(f, "{n} el."),
            Discretisation::Mesh2d { sigma, zeta, time_step } => write!(f, "{sigma}×{zeta} el., Δt {} s", crate::error::num(time_step)),
        }
    }
}

/// A tolerance as `1e-8` (or `2.5e-8`).
pub fn fmt_tolerance(t: f64) -> String {
    let s = format!("{t:.1e}");
    s.replace(".0e", "e")
}

/// Work spent on a run (`cost`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// Where the wall time went, per phase, with the step counts (optional; absent in
    /// results written before it existed or by tools that do not measure it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phases: Option<CostPhases>,
}

/// The wall time of a run by phase (`cost.phases`), s. Each phase's seconds are
/// *exclusive* — a phase nested in another (the numeric LU inside a Newton iteration's
/// assembly, the Newton solves inside a fitting pass) is not counted in the outer one —
/// so the phases and `other` add up to `wall_seconds`. `fitting_total` alone is
/// inclusive. Phases a method does not have are 0 (shooting has no symbolic LU, an FE
/// solve no integration of flows).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct CostPhases {
    /// Jacobian assembly (element or interval evaluations, scatter, the collocation's
    /// condensation), s.
    pub assembly: f64,
    /// Symbolic sparse LU (ordering, elimination structure; once per pattern), s.
    pub symbolic_factorisation: f64,
    /// Numeric LU, s.
    pub numeric_factorisation: f64,
    /// Triangular solves with the factorised Jacobian, s.
    pub linear_solves: f64,
    /// Residual evaluations of Newton trials and the error estimate of mesh adaptation, s.
    pub residuals: f64,
    /// Integration of the flows (shooting), s.
    pub integration: f64,
    /// Mesh adaptation: new meshes and the transfer of the solution onto them, s.
    pub mesh_adaptation: f64,
    /// Mesh fitting (FE) outside its Newton solves: locating breakpoints, building the
    /// fitted mesh, transferring the state, s.
    pub fitting: f64,
    /// The rest of the wall time (set-up, continuation bookkeeping, summary, sampling), s.
    pub other: f64,
    /// Wall time inside the mesh fitting, its Newton solves included, s (inclusive).
    pub fitting_total: f64,
    /// Accepted continuation (homotopy) steps.
    pub continuation_steps: usize,
    /// Mesh adaptation passes (collocation).
    pub mesh_refinements: usize,
    /// Accepted mesh fitting passes (FE).
    pub fitting_passes: usize,
}

impl CostPhases {
    /// The exclusive phases with their names, `other` last, in the order of the JSON.
    pub fn named(&self) -> [(&'static str, f64); 9] {
        [
            ("assembly", self.assembly),
            ("symbolic_factorisation", self.symbolic_factorisation),
            ("numeric_factorisation", self.numeric_factorisation),
            ("linear_solves", self.linear_solves),
            ("residuals", self.residuals),
            ("integration", self.integration),
            ("mesh_adaptation", self.mesh_adaptation),
            ("fitting", self.fitting),
            ("other", self.other),
        ]
    }

    /// The phase with the most seconds, `other` included (`None` if all are 0).
    pub fn dominant(&self) -> Option<(&'static str, f64)> {
        self.named().into_iter().filter(|(_, s)| *s > 0.0).max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// One run = scene + method + discretisation (DESIGN.md "Result format").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// Fields over the mid-surface (σ, ζ) of a shell run (optional).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<SurfaceFields>,
    /// Quantities in time of a transient run (optional; absent for static and BVP runs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub history: Option<TimeSeries>,
    /// The discretisation of the run (optional): the tolerance of a BVP run, the
    /// elements of an FE run. `beltcheck check` needs it on every result it reads: it
    /// orders the runs of one code and measures their observed orders by it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub discretisation: Option<Discretisation>,
    /// Stated warnings of the solver about this result (optional; absent or empty for
    /// a clean result): e.g. an unresolved bending layer or slip zone. A reader that
    /// treats results as trusted numbers should treat a warned one as not trusted.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// A user's measurement held against a channel of `history` (optional; `beltcheck
    /// solve --measured FILE.csv` of a shell scene).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<MeasuredComparison>,
}

/// A measured series overlaid on a channel of the run's history (`measured`): at each
/// measured time inside the simulated rotation, the measurement, the model (linear
/// between its steps) and their difference model − measured. Times count from the start
/// of the drums' rotation, s; values in the channel's unit (m for the lateral channels).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct MeasuredComparison {
    /// The file the measurement was read from.
    pub file: String,
    /// The history channel compared with, e.g. `lateral_offset`.
    pub channel: String,
    /// Measured times inside the simulated rotation, s.
    pub time: Vec<f64>,
    /// The measured values there.
    pub measured: Vec<f64>,
    /// The model's values there.
    pub model: Vec<f64>,
    /// model − measured.
    pub difference: Vec<f64>,
    /// Measured samples outside the simulated rotation (not compared).
    pub outside: usize,
    /// Root mean square of the differences.
    pub rms_difference: f64,
    /// Largest |difference|.
    pub max_difference: f64,
}

impl MeasuredComparison {
    /// Checks equal lengths and finite numbers.
    ///
    /// # Errors
    /// [`ResultError::FieldLength`] or [`ResultError::NotFinite`] naming the entry, e.g.
    /// `measured.difference[2]`.
    pub fn check(&self) -> Result<(), ResultError> {
        let n = self.time.len();
        for (name, v) in [("time", &self.time), ("measured", &self.measured), ("model", &self.model), ("difference", &self.difference)] {
            if v.len() != n {
                return Err(ResultError::FieldLength { field: format!("measured.{name}"), len: v.len(), expected: n });
            }
            check_finite_vec(&format!("measured.{name}"), v)?;
        }
        check_finite_vec("measured.rms_difference", &[self.rms_difference])?;
        check_finite_vec("measured.max_difference", &[self.max_difference])
    }
}

impl RunResult {
    /// Checks that nothing non-finite or ragged would be written: summary, wall time,
    /// fields, surface fields, history.
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
        if let Some(p) = &self.cost.phases {
            let named = p.named();
            let bad = named.iter().copied().chain([("fitting_total", p.fitting_total)]).find(|(_, v)| !v.is_finite());
            if let Some((name, value)) = bad {
                return Err(ResultError::NotFinite { quantity: format!("cost.phases.{name}"), value });
            }
        }
        if let Some(f) = &self.fields {
            f.check()?;
        }
        if let Some(s) = &self.surface {
            s.check()?;
        }
        if let Some(h) = &self.history {
            h.check()?;
        }
        if let Some(d) = self.discretisation {
            d.check()?;
        }
        if let Some(m) = &self.measured {
            m.check()?;
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
