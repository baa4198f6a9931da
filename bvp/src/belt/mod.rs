//! What every belt problem shares: one options struct ([`BeltOptions`]), one error type
//! ([`BeltError`]), the stages of a run (homotopy, final solve, work counters:
//! [`run`]) and the self-checks of the balances a run reports ([`balance`]).
//!
//! The belt models (`string_hanging`, `rod_hanging`, `string_drive`) supply their scaled
//! problem, start, acceptance test and point output; docs/bvp-engine.md ("Adding a belt
//! theory") says what a new theory adds.

pub mod balance;
pub mod error;
pub mod options;
pub mod run;

pub use error::BeltError;
pub use options::{BeltOptions, BvpMethod};
