//! `bvp`: a generic multi-segment boundary value problem engine and the belt problems
//! written as BVPs.
//!
//! Layers (each one file or folder):
//! - [`problem`]: the standard form (segments on [0, 1], parameters, boundary residual),
//! - [`solution`]: a solved problem with dense output and work statistics,
//! - [`error`]: failures carrying their numbers,
//! - `collocation`: collocation with residual control and adaptive mesh, the damped
//!   Newton and sparse LU of the shared `numerics` crate ([`newton`] adapts them),
//! - `shooting`: multiple shooting on diffsol,
//! - `continuation`: natural-parameter and pseudo-arclength continuation, fold detection,
//! - `analytical`: closed forms used by tests and examples,
//! - [`belt`]: what every belt problem shares — one options struct, one error type, the
//!   stages of a run (homotopy, final solve, work counters) and the balance self-checks,
//! - [`sigma_map`]: the belt point at a contour coordinate σ (for the common view),
//! - [`string_hanging`]: the extensible string on two pulleys,
//! - [`rod_hanging`]: the Kirchhoff rod on two pulleys,
//! - [`string_drive`]: the steady friction drive (stick and slip zones),
//! - [`scene`]: from a validated scene to a BVP run.

pub mod error;
pub mod jacobian;
pub mod problem;
pub mod solution;
pub mod elliptic;
pub mod shooting;
pub mod analytical;
pub mod collocation;
pub mod continuation;
pub mod newton;
pub mod belt;
pub mod scene;
pub mod sigma_map;
pub mod string_hanging;
pub mod string_drive;
pub mod rod_hanging;
pub mod cosserat_hanging;
pub mod cosserat_pulley;
pub mod cosserat_drive;

pub use error::BvpError;
pub use problem::{JacobianMode, Problem, Scalar};
pub use solution::{SegmentSolution, Solution, Stats};
