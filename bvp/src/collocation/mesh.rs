//! Mesh adaptation from the per-interval residual estimate ρ_i (see
//! `CollocationOptions::tolerance`).
//!
//! With residual order q (ρ ∝ h^q, `Scheme::residual_order`):
//! - **insertion**: an interval with ρ_i > tol is split in two equal parts if
//!   ρ_i ≤ 2^q tol (halving h divides ρ by 2^q), otherwise in three (one or two new
//!   nodes);
//! - **removal**: two neighbouring intervals (widths h_1, h_2, H = h_1 + h_2) are merged
//!   when the predicted residual of the merged interval,
//!   max(ρ_1 (H/h_1)^q, ρ_2 (H/h_2)^q), is at most tol / 2^q. The merged interval then
//!   keeps a safety margin 2^q below the insertion threshold: splitting it again would
//!   only be needed if the asymptotic prediction were off by more than that factor.
//!   Each interval takes part in at most one merge per pass.

/// Insert nodes into intervals whose residual exceeds `tol`.
pub(crate) fn refine(mesh: &[f64], rho: &[f64], tol: f64, q: usize) -> Vec<f64> {
    let two_q = 2f64.powi(q as i32);
    let mut out = Vec::with_capacity(mesh.len() * 2);
    for (i, &r) in rho.iter().enumerate() {
        let (a, b) = (mesh[i], mesh[i + 1]);
        out.push(a);
        if r > tol {
            if r <= two_q * tol {
                out.push(0.5 * (a + b));
            } else {
                out.push(a + (b - a) / 3.0);
                out.push(a + 2.0 * (b - a) / 3.0);
            }
        }
    }
    out.push(mesh[mesh.len() - 1]);
    out
}

/// Every interval halved.
pub(crate) fn halve(mesh: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * mesh.len());
    for w in mesh.windows(2) {
        out.extend([w[0], 0.5 * (w[0] + w[1])]);
    }
    out.push(mesh[mesh.len() - 1]);
    out
}

/// Merge pairs of intervals whose residual is far below `tol`; `None` if no pair
/// qualifies.
pub(crate) fn coarsen(mesh: &[f64], rho: &[f64], tol: f64, q: usize) -> Option<Vec<f64>> {
    let qi = q as i32;
    let limit = tol / 2f64.powi(qi);
    let intervals = rho.len();
    let mut out = Vec::with_capacity(mesh.len());
    out.push(mesh[0]);
    let mut i = 0;
    while i < intervals {
        if i + 1 < intervals {
            let h1 = mesh[i + 1] - mesh[i];
            let h2 = mesh[i + 2] - mesh[i + 1];
            let big = h1 + h2;
            let predicted = (rho[i] * (big / h1).powi(qi)).max(rho[i + 1] * (big / h2).powi(qi));
            if predicted <= limit {
                out.push(mesh[i + 2]);
                i += 2;
                continue;
            }
        }
        out.push(mesh[i + 1]);
        i += 1;
    }
    (out.len() < mesh.len()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refine_inserts_one_or_two_nodes() {
        let mesh = [0.0, 0.5, 1.0];
        // q = 2: ρ = 3 tol ≤ 4 tol → one node; ρ = 10 tol → two nodes.
        let out = refine(&mesh, &[3.0, 10.0], 1.0, 2);
        assert_eq!(out.len(), 3 + 1 + 2);
        assert!((out[1] - 0.25).abs() < 1e-15);
        assert!((out[3] - (0.5 + 0.5 / 3.0)).abs() < 1e-15);
        assert_eq!(refine(&mesh, &[0.5, 0.5], 1.0, 2), mesh.to_vec());
    }

    #[test]
    fn coarsen_keeps_margin() {
        let mesh = [0.0, 0.25, 0.5, 0.75, 1.0];
        // q = 2, equal halves: predicted = 4 ρ; limit tol/4 → merge iff ρ ≤ tol/16.
        assert_eq!(coarsen(&mesh, &[0.06, 0.06, 0.07, 0.07], 1.0, 2).unwrap(), vec![0.0, 0.5, 0.75, 1.0]);
        assert_eq!(coarsen(&mesh, &[0.06; 4], 1.0, 2).unwrap(), vec![0.0, 0.5, 1.0]);
        assert!(coarsen(&mesh, &[0.07; 4], 1.0, 2).is_none());
        // A merged mesh never needs refinement by the asymptotic model.
        let merged = coarsen(&mesh, &[0.0625; 4], 1.0, 2).unwrap();
        let predicted: Vec<f64> = vec![0.0625 * 4.0; merged.len() - 1];
        assert_eq!(refine(&merged, &predicted, 1.0, 2), merged);
    }
}
