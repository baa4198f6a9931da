//! The number type of every function that is differentiated by forward-mode AD.

use num_dual::DualNum;

/// Scalar types residuals and energies are evaluated with: `f64` for values and the
/// dual numbers of [`num_dual`] for exact first (and higher) derivatives. Generic code
/// bounds its number type by `D: Scalar`; the blanket implementation covers every
/// `DualNum<Primitive = f64>`.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}
impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}
