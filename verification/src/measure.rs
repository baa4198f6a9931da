//! Error measures against the reference, observed orders, Richardson extrapolation.
//!
//! # Definitions (also in docs/verification.md)
//! - **Summary scalar** q (a flat name of [`drive::summary::SCALAR_NAMES`]): relative
//!   error e = |q − q_ref| / |q_ref|. Undefined (`None`, shown "—") if either value is
//!   absent or q_ref = 0. A polar angle on a pulley (`contact_start`, `contact_end`,
//!   `stick_slip_angle`, [`is_polar_angle`]): e = |q − q_ref| wrapped into (−π, π], over
//!   π (relative to a half turn).
//! - **Field norms** ([`drive::result::FIELD_NORM_NAMES`]) of a field f ∈ {deflection ν,
//!   axial force N, moment M} sampled at the n uniform points σ_i = i·L_geom/n of the
//!   harness ([`crate::run::Samples`]):
//!   `<field>_max` = max_i |f_i − f_ref,i| / max_i |f_ref,i|,
//!   `<field>_l2` = (Σ_i (f_i − f_ref,i)²)^½ / (Σ_i f_ref,i²)^½ — the ratio of the L2
//!   norms over the loop (the uniform rectangle rule of a periodic function is its
//!   trapezoidal rule, so the common factor L_geom/n cancels). Undefined if either
//!   solution lacks the field or the reference field is identically 0.
//! - **Observed order** between successive levels k−1, k of a mesh sequence with
//!   element counts n_{k−1} < n_k: p_k = ln(e_{k−1}/e_k) / ln(n_k/n_{k−1}), which is
//!   log₂(e_{k−1}/e_k) for mesh halving. Undefined if an error is absent or 0.
//! - **Self-convergence order** of three successive FE values q₁, q₂, q₃ (ratio r):
//!   p = ln(|q₂ − q₁| / |q₃ − q₂|) / ln r — measured from the FE sequence alone, so the
//!   extrapolation below does not borrow the BVP answer.
//! - **Richardson extrapolation**: q_R = q₃ + (q₃ − q₂) / (r^p − 1) with the
//!   self-convergence order p (undefined if p is not finite and > 0).
//! - **Mutual convergence**: the relative error of q_R against the BVP reference,
//!   |q_R − q_ref| / |q_ref|. Fields are extrapolated pointwise with the order of their
//!   differences in the same norm.

use serde::Serialize;

use crate::run::{RunData, Samples};

/// Max or L2 norm over the σ samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Norm {
    /// max_i |f_i|.
    Max,
    /// (Σ_i f_i²)^½ (the L2 norm over the loop up to the factor (L_geom/n)^½).
    L2,
}

/// What a quantity of the tables is.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QuantityKind {
    /// A summary scalar by flat name.
    Scalar,
    /// A norm of a field's error: field `deflection` | `tension` | `moment`.
    FieldNorm {
        /// Field name as in [`Samples::field`].
        field: String,
        /// Which norm.
        norm: Norm,
    },
}

/// A named quantity of the error tables.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Quantity {
    /// Summary flat name (`driver.contact_arc`) or field norm name (`tension_l2`).
    pub name: String,
    /// Scalar or field norm.
    pub kind: QuantityKind,
}

impl Quantity {
    /// The quantity of a name: a field norm if it is one of
    /// [`drive::result::FIELD_NORM_NAMES`], else a summary scalar.
    pub fn named(name: &str) -> Quantity {
        if drive::result::FIELD_NORM_NAMES.contains(&name) {
            if let Some((field, norm)) = name.rsplit_once('_') {
                let norm = if norm == "max" { Norm::Max } else { Norm::L2 };
                return Quantity { name: name.to_string(), kind: QuantityKind::FieldNorm { field: field.to_string(), norm } };
            }
        }
        Quantity { name: name.to_string(), kind: QuantityKind::Scalar }
    }

    /// True for a summary scalar.
    pub fn is_scalar(&self) -> bool {
        self.kind == QuantityKind::Scalar
    }

    /// The quantities of a reference solution: every summary scalar it produces, then
    /// the max and L2 norms of each field it has (deflection, axial force, and the
    /// moment where present), in the order of FIELD_NORM_NAMES — none for a reference
    /// without fields (a closed form).
    pub fn of_reference(reference: &RunData) -> Vec<Quantity> {
        let mut q: Vec<Quantity> = reference.summary.scalars().into_iter().map(|(n, _)| Quantity::named(&n)).collect();
        for name in drive::result::FIELD_NORM_NAMES {
            let quantity = Quantity::named(name);
            if let QuantityKind::FieldNorm { field, .. } = &quantity.kind {
                if reference.samples.field(field).is_some_and(|f| !f.is_empty()) {
                    q.push(quantity);
                }
            }
        }
        q
    }

    /// The value of a scalar quantity in a run (`None` for a field norm or an absent
    /// scalar).
    pub fn value(&self, run: &RunData) -> Option<f64> {
        match self.kind {
            QuantityKind::Scalar => run.summary.get(&self.name),
            QuantityKind::FieldNorm { .. } => None,
        }
    }

    /// The error of `run` against `reference` (module docs).
    pub fn error(&self, run: &RunData, reference: &RunData) -> Option<f64> {
        match &self.kind {
            QuantityKind::Scalar => scalar_error(&self.name, run.summary.get(&self.name)?, reference.summary.get(&self.name)?),
            QuantityKind::FieldNorm { field, norm } => {
                field_error(run.samples.field(field)?, reference.samples.field(field)?, *norm)
            }
        }
    }
}

/// A finite value or `None`.
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// True for a summary scalar that is a polar angle on a pulley (a position in (−π, π]:
/// `contact_start`, `contact_end`, `stick_slip_angle` of any pulley), whose error
/// [`scalar_error`] measures against a half turn.
pub fn is_polar_angle(name: &str) -> bool {
    matches!(name.rsplit('.').next(), Some("contact_start" | "contact_end" | "stick_slip_angle"))
}

/// The error of summary scalar `name` (module docs): [`relative`], but for a polar angle
/// ([`is_polar_angle`]) the difference wrapped into (−π, π] over π — relative to a half
/// turn, since an angle's size says where its zero is, not how large it is (a stick →
/// slip point near φ = 0 made the relative error arbitrary, and ±π are the same point).
pub fn scalar_error(name: &str, value: f64, reference: f64) -> Option<f64> {
    if is_polar_angle(name) {
        let pi = std::f64::consts::PI;
        let d = (value - reference + pi).rem_euclid(2.0 * pi) - pi;
        return finite(d.abs() / pi);
    }
    relative(value, reference)
}

/// |value − reference| / |reference|; `None` if reference = 0 or anything is not finite.
pub fn relative(value: f64, reference: f64) -> Option<f64> {
    if reference == 0.0 {
        return None;
    }
    finite((value - reference).abs() / reference.abs())
}

/// The norm of a vector.
pub fn norm(v: impl IntoIterator<Item = f64>, norm: Norm) -> f64 {
    match norm {
        Norm::Max => v.into_iter().fold(0.0, |m, x| m.max(x.abs())),
        Norm::L2 => v.into_iter().map(|x| x * x).sum::<f64>().sqrt(),
    }
}

/// ‖f − g‖ / ‖g‖ over the samples; `None` if the lengths differ, ‖g‖ = 0 or not finite.
pub fn field_error(f: &[f64], reference: &[f64], n: Norm) -> Option<f64> {
    if f.len() != reference.len() || f.is_empty() {
        return None;
    }
    let den = norm(reference.iter().copied(), n);
    if den == 0.0 {
        return None;
    }
    finite(norm(f.iter().zip(reference).map(|(a, b)| a - b), n) / den)
}

/// p = ln(e_coarse/e_fine) / ln(ratio), ratio = n_fine/n_coarse > 1.
pub fn observed_order(e_coarse: Option<f64>, e_fine: Option<f64>, ratio: f64) -> Option<f64> {
    let (a, b) = (e_coarse?, e_fine?);
    if a <= 0.0 || b <= 0.0 || ratio <= 1.0 {
        return None;
    }
    finite((a / b).ln() / ratio.ln())
}

/// Self-convergence order of three successive values at mesh ratio r:
/// ln(|q₂ − q₁| / |q₃ − q₂|) / ln r.
pub fn self_order(q1: f64, q2: f64, q3: f64, ratio: f64) -> Option<f64> {
    observed_order(Some((q2 - q1).abs()), Some((q3 - q2).abs()), ratio)
}

/// q_R = q_fine + (q_fine − q_coarse) / (r^p − 1); `None` unless p > 0 and finite.
pub fn richardson(coarse: f64, fine: f64, ratio: f64, p: f64) -> Option<f64> {
    if !(p.is_finite() && p > 0.0 && ratio > 1.0) {
        return None;
    }
    finite(fine + (fine - coarse) / (ratio.powf(p) - 1.0))
}

/// Pointwise Richardson extrapolation of a field from its last three levels: the order
/// is the self-convergence order of the differences in norm `n`. Returns the
/// extrapolated samples and the order used.
pub fn richardson_field(f1: &[f64], f2: &[f64], f3: &[f64], ratio: f64, n: Norm) -> Option<(Vec<f64>, f64)> {
    if f1.len() != f3.len() || f2.len() != f3.len() {
        return None;
    }
    let d21 = norm(f2.iter().zip(f1).map(|(a, b)| a - b), n);
    let d32 = norm(f3.iter().zip(f2).map(|(a, b)| a - b), n);
    let p = observed_order(Some(d21), Some(d32), ratio)?;
    let out: Option<Vec<f64>> = f2.iter().zip(f3).map(|(&c, &f)| richardson(c, f, ratio, p)).collect();
    Some((out?, p))
}

/// The field of a norm quantity from samples.
pub fn field_of<'a>(s: &'a Samples, q: &Quantity) -> Option<&'a [f64]> {
    match &q.kind {
        QuantityKind::FieldNorm { field, .. } => s.field(field),
        QuantityKind::Scalar => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// e = C h^2 on halving meshes gives p = 2 exactly; Richardson with that order
    /// recovers the limit of q(h) = q* + C h^2 exactly.
    #[test]
    fn orders_and_extrapolation_of_a_second_order_sequence() {
        let q = |n: f64| 3.0 + 5.0 / (n * n);
        let (q1, q2, q3) = (q(8.0), q(16.0), q(32.0));
        let p = self_order(q1, q2, q3, 2.0).unwrap();
        assert!((p - 2.0).abs() < 1e-9, "{p}");
        let r = richardson(q2, q3, 2.0, p).unwrap();
        assert!((r - 3.0).abs() < 1e-12, "{r}");
        let e = |v: f64| relative(v, 3.0);
        assert!((observed_order(e(q1), e(q2), 2.0).unwrap() - 2.0).abs() < 1e-12);
        // Non-doubling sequence: ratio 1.5.
        assert!((observed_order(e(q(8.0)), e(q(12.0)), 1.5).unwrap() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn undefined_measures_are_none_never_nan() {
        assert_eq!(relative(1.0, 0.0), None);
        // polar angles against a half turn, wrapped: near 0 and across ±π
        let pi = std::f64::consts::PI;
        assert!((scalar_error("pulley.stick_slip_angle", 1e-3, -2e-3).unwrap() - 3e-3 / pi).abs() < 1e-15);
        assert!((scalar_error("driver.contact_start", pi - 1e-3, -pi + 1e-3).unwrap() - 2e-3 / pi).abs() < 1e-12);
        assert_eq!(scalar_error("driver.contact_start", 0.5, 0.5), Some(0.0));
        assert_eq!(scalar_error("driver.contact_arc", 1.1, 1.0), relative(1.1, 1.0));
        assert!(!is_polar_angle("driver.stick_arc") && is_polar_angle("driven.contact_end"));
        assert_eq!(relative(f64::NAN, 1.0), None);
        assert_eq!(observed_order(Some(0.0), Some(1.0), 2.0), None);
        assert_eq!(observed_order(None, Some(1.0), 2.0), None);
        assert_eq!(observed_order(Some(1.0), Some(1.0), 1.0), None);
        assert_eq!(self_order(1.0, 1.0, 1.0, 2.0), None);
        assert_eq!(richardson(1.0, 2.0, 2.0, 0.0), None);
        assert_eq!(richardson(1.0, 2.0, 2.0, f64::NAN), None);
        assert_eq!(field_error(&[1.0], &[0.0], Norm::Max), None);
        assert_eq!(field_error(&[1.0, 2.0], &[1.0], Norm::L2), None);
    }

    #[test]
    fn field_norms() {
        let r = [3.0, 4.0];
        let f = [3.0, 4.5];
        assert!((field_error(&f, &r, Norm::Max).unwrap() - 0.125).abs() < 1e-15);
        assert!((field_error(&f, &r, Norm::L2).unwrap() - 0.1).abs() < 1e-15);
        let q = Quantity::named("tension_l2");
        assert_eq!(q.kind, QuantityKind::FieldNorm { field: "tension".into(), norm: Norm::L2 });
        assert!(Quantity::named("driver.contact_arc").is_scalar());
    }

    #[test]
    fn field_extrapolation() {
        let f = |n: f64| vec![1.0 + 1.0 / (n * n), 2.0 - 3.0 / (n * n)];
        let (r, p) = richardson_field(&f(4.0), &f(8.0), &f(16.0), 2.0, Norm::L2).unwrap();
        assert!((p - 2.0).abs() < 1e-9);
        assert!((r[0] - 1.0).abs() < 1e-12 && (r[1] - 2.0).abs() < 1e-12);
    }
}
