//! Membrane locking: the leaf spring bent to a semicircle — §7.3 of the reference,
//! eq. (45), (46), Fig. 7 (docs/fem-rod.md §4, §9).
//!
//! An initially straight leaf spring of length πR, r̂ = s i, is bent to the semicircle
//! r = R sin(s/R) i + R(cos(s/R) − 1) j, whose axial strain Γ₁ = |r′| − 1 vanishes
//! identically (46). One Cartesian Hermite element (eq. 43) on s ∈ [0, πR] interpolates
//! it from the nodal values and slopes r(0) = 0, r′(0) = i, r(πR) = −2R j, r′(πR) = −i.
//! Its strain Γ₁(ξ) is not zero; the test samples it at the strain-rule points of the two
//! rod formulations — Simpson (ξ = −1, 0, 1; `rod-simpson`) and Gauss 3 (ξ = 0, ±√0.6;
//! `rod-gauss`) — and asserts that Simpson reproduces Γ₁ = 0 better, in the largest and
//! in the weighted mean-square sampled strain (what enters the membrane energy), by at
//! least a factor 1.5 (measured: largest 4.51e-2 vs 1.36e-1, 3.0×; weighted rms 3.68e-2 vs
//! 1.06e-1, 2.9×; Γ₁ = −0.0451 at ξ = 0 for both, −0.136 at ξ = ±√0.6; the sample values
//! are printed). Independent of R (Γ₁ is dimensionless and the geometry scales with R).

use fem::hermite::weights;

/// Γ₁ = |r′| − 1 of the one-element interpolant at ξ, for radius `r`.
fn strain(r: f64, xi: f64) -> f64 {
    let h = std::f64::consts::PI * r;
    let (_, wd) = weights(xi, h);
    // (value_a, slope_a, value_b, slope_b) of x(s) and y(s)
    let x = [0.0, 1.0, 0.0, -1.0];
    let y = [0.0, 0.0, -2.0 * r, 0.0];
    let dx: f64 = wd.iter().zip(&x).map(|(w, q)| w * q).sum();
    let dy: f64 = wd.iter().zip(&y).map(|(w, q)| w * q).sum();
    dx.hypot(dy) - 1.0
}

#[test]
fn simpson_sampling_reproduces_the_unstrained_semicircle_better_than_gauss() {
    for r in [0.08, 1.0, 25.0] {
        let mut measures = Vec::new();
        for name in ["rod-simpson", "rod-gauss"] {
            let rule = fem::formulation::find(name).unwrap().rules().strain;
            let samples: Vec<(f64, f64, f64)> = rule.points().iter().map(|&(xi, w)| (xi, w, strain(r, xi))).collect();
            let max = samples.iter().fold(0.0f64, |m, s| m.max(s.2.abs()));
            let mean_square = samples.iter().map(|s| s.1 * s.2 * s.2).sum::<f64>() / 2.0;
            println!("R = {r}: {name} ({rule}) samples {samples:?}: max |Γ₁| = {max:.4e}, weighted rms = {:.4e}", mean_square.sqrt());
            measures.push((max, mean_square.sqrt()));
        }
        let (simpson, gauss) = (measures[0], measures[1]);
        // at the nodes the interpolant has the exact unit slopes: Γ₁(±1) = 0 to round-off
        assert!(strain(r, -1.0).abs() < 1e-14 && strain(r, 1.0).abs() < 1e-14);
        assert!(gauss.0 > 1.5 * simpson.0, "largest sampled strain: simpson {:.3e}, gauss {:.3e}", simpson.0, gauss.0);
        assert!(gauss.1 > 1.5 * simpson.1, "weighted rms strain: simpson {:.3e}, gauss {:.3e}", simpson.1, gauss.1);
        // and neither is zero: the cubic cannot represent the circle (the phenomenon itself)
        assert!(simpson.0 > 1e-3);
    }
}
