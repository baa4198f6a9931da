//! `drive`: *what the scene is* — the first layer of beltcheck, on which the `bvp`
//! and `fem` crates (two independent ways to solve a scene) and the `verification`
//! crate (holding them against each other) are built.
//!
//! - [`scene`]: the scene JSON of DESIGN.md — drive geometry, belt theory and
//!   stiffnesses, effects, analysis, solver and gate settings — parsed with errors
//!   that name the field path (unknown fields with the nearest valid name suggested)
//!   and validated (signs, geometry, theory/effect/analysis compatibility);
//! - [`contour`]: the compound contour g(σ) of two pulleys with t_g, n_g, α
//!   (§5 of the reference, eqs. 27 and 38) and the inverse map point → (σ, ν), and the
//!   open contour of a one-pulley scene ([`OpenContour`]);
//! - [`pending`]: what the scene format describes but no solver solves yet
//!   ([`NotYetSolvable`], naming the issue that brings it);
//! - [`view`]: the common solution view ([`SolutionView`]) through which the harness
//!   samples any solution, and [`sample_fields`];
//! - [`summary`], [`result`]: the named scalars and the result JSON of DESIGN.md;
//! - [`error`]: [`SceneError`] and [`ResultError`], which carry paths and numbers;
//! - [`schemas`]: the JSON Schemas of the scene and result formats, from these types.
//!
//! Units are SI throughout. Nothing here panics on any input: bad input is an
//! error value.
//!
//! ```
//! use drive::Scene;
//! let scene = Scene::from_json_str(r#"{
//!   "name": "string-hanging",
//!   "drive": {"pulley_radius": 0.08, "centre_distance": 0.45,
//!             "driver_speed": 0.0, "driven_torque": 0.0},
//!   "belt": {"theory": "string", "length": 1.41, "axial_stiffness": 2.0e4,
//!            "mass_per_length": 0.12},
//!   "effects": {"gravity": 9.81, "contact": "frictionless"},
//!   "analysis": "static"
//! }"#).unwrap();
//! assert!(scene.slack_ratio() > 1.0);
//! let c = scene.contour();
//! let (sigma, nu) = c.sigma_nu(c.position(0.3, 0.01));
//! assert!((sigma - 0.3).abs() < 1e-12 && (nu - 0.01).abs() < 1e-12);
//!
//! let err = Scene::from_json_str(r#"{"name": "x", "drive": {"pulley_radius": 0.08,
//!   "centre_distance": 0.45, "driver_speed": 0, "driven_torque": 0},
//!   "belt": {"theory": "string", "length": 1.41, "axial_stifness": 2e4,
//!            "mass_per_length": 0.12},
//!   "effects": {"contact": "frictionless"}, "analysis": "static"}"#).unwrap_err();
//! assert_eq!(err.to_string(),
//!   "unknown field `belt.axial_stifness`; did you mean `axial_stiffness`?");
//! ```

pub mod contour;
pub mod error;
pub mod pending;
pub mod result;
pub mod scene;
mod schema;
pub mod schemas;
mod suggest;
pub mod summary;
pub mod view;

pub use contour::{Contour, OpenContour, OpenRegion, Path, Pulley, Region};
pub use pending::{not_yet_solvable, NotYetSolvable, Solver, Unsolved};
pub use error::{ResultError, SceneError};
pub use result::{Cost, CostPhases, Discretisation, Fields, Refinement, Frame, History, MeasuredComparison, RunResult, SurfaceFields, TimeSeries, FIELD_NORM_NAMES, SURFACE_FIELD_NAMES};
pub use scene::{
    Analysis, Belt, BvpMethod, BvpSettings, Camber, Contact, DriveGeometry, Effects, ElasticLayer, End,
    FemSettings, GateSettings, Layout, OnePulleyLoad, Plate, Scene, Section, ShellRun, Steering, SteeringDrum, Theory,
};
pub use summary::{Global, PulleyId, PulleyQuantity, PulleySummary, Quantity, Summary, SCALAR_NAMES};
pub use view::{fields_at, sample_fields, ContactState, SolutionView};
