//! The one belt BVP: a segment [`topology`] built from the scene, a section [`law`] per
//! belt theory, and what every belt problem shares — the problem they make together
//! ([`problem::BeltProblem`]), one solution type and one view ([`solution`]), one options
//! struct ([`BeltOptions`]), one error type ([`BeltError`]), the stages of a run
//! (homotopy, final solve, work counters: [`run`]) and the self-checks of the balances a
//! run reports ([`balance`]).
//!
//! The belt models (`string_hanging`, `rod_hanging`, `string_drive`) are section laws
//! with their scaling and homotopy start; docs/bvp-engine.md ("Adding a belt theory")
//! says what a new theory adds.

pub mod balance;
pub mod error;
pub mod law;
pub mod options;
pub mod problem;
pub mod run;
pub mod solution;
pub mod topology;
pub mod view;

pub use error::BeltError;
pub use law::{BeltPoint, Scales, SectionLaw};
pub use options::{BeltOptions, BvpMethod};
pub use problem::BeltProblem;
pub use solution::{BeltSolution, EdgeForces};
pub use topology::{ArcKind, Pulley, SegmentKind, Topology};

/// Each named input finite and > 0, else [`BeltError::InvalidInput`] naming the first
/// that is not.
pub fn check_positive(inputs: &[(&'static str, f64)]) -> Result<(), BeltError> {
    for &(name, value) in inputs {
        if !(value.is_finite() && value > 0.0) {
            return Err(BeltError::InvalidInput { name, value, reason: "must be finite and > 0" });
        }
    }
    Ok(())
}

/// The pulleys must not overlap: H > 2R.
pub fn check_pulleys_apart(radius: f64, centre_distance: f64) -> Result<(), BeltError> {
    if centre_distance > 2.0 * radius {
        return Ok(());
    }
    Err(BeltError::InvalidInput {
        name: "centre_distance",
        value: centre_distance,
        reason: "must exceed twice the pulley radius (the pulleys overlap)",
    })
}
