//! Integration rules on the reference element ξ ∈ [−1, 1] (§7.3 of the reference): the
//! rules live in the `numerics` crate (shared with the BVP collocation nodes); each
//! energy term receives one as a value (docs/fem-string.md §6).

pub use numerics::quadrature::{QuadratureError, Rule};
