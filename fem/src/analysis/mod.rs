//! Analyses over the 2-D surface discretisation ([`crate::surface`]): the time stepping
//! with history variables the shell needs ([`time_stepping`]; docs/fem-time-stepping.md).
//! The 1-D analyses (static homotopy, quasistatic transient, direct steady state) live
//! beside their model in `static_homotopy` and `string_drive`.

pub mod time_stepping;
