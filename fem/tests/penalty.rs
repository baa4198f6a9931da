//! Penalty convergence (§6.1 of the reference; docs/fem-string.md §11).
//!
//! `string-hanging`, the default `string-simpson`, 128 elements, penalty P = κ EA/R² for
//! κ = 10², 10³, 10⁴, 10⁵, 10⁶ (10⁵ is the default).
//!
//! Expected: the penetration of a frictionless string on a pulley is δ = p/P with the
//! contact pressure p ≈ N/R (S5), so δ ∝ 1/P exactly (ratio 10 per decade of κ); the
//! solution differs from the rigid-pulley limit by O(δ) in geometry, so the summary
//! quantities approach their P → ∞ values like 1/P, until the difference reaches the
//! level where the mesh (fixed here) no longer changes with P.
//!
//! Checks: penetration ratios per decade in [9, 11]; δ < 1e-9 R at the default; the
//! distance of each summary quantity from its κ = 10⁶ value shrinks by 5–20× per decade,
//! i.e. the penalty error is ∝ 1/P. Measured (docs/fem-string.md §11): δ = 5.6e-8,
//! 5.6e-9, 5.6e-10, 5.7e-11, 5.8e-12 m; tension_upper_mid − its κ = 10⁶ value 2.6e-5,
//! 3.1e-6, 3.2e-7, 3.0e-8 N — at the default (10⁵) 150× below the mesh error of these
//! 128 elements (4.7e-6 N, tests/fem_vs_bvp.rs) and comparable to it at 512 elements.

mod common;

use common::*;
use drive::contour::Region;
use drive::view::SolutionView;
use fem::SolverSettings;

const KAPPAS: [f64; 5] = [1e2, 1e3, 1e4, 1e5, 1e6];
const QUANTITIES: [&str; 5] = ["y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid", "driver.contact_arc"];

/// Largest penetration ⟨−γ⟩ = p/P over 2000 samples of the middle halves of the two
/// arcs (deep inside the contact zones, where γ = ν and the Hermite cubic represents the
/// penalised state exactly; near the coordinate transitions the cubic also dips between
/// integration points, an O(h⁴/R³) ≈ 1e-8 m discretisation effect independent of P), m.
fn max_penetration(view: &dyn SolutionView, penalty: f64) -> f64 {
    let c = view.contour().expect("a two-pulley loop");
    let mut worst: f64 = 0.0;
    for region in [Region::DrivenArc, Region::DriverArc] {
        let (a, b) = c.region_bounds(region);
        for k in 0..1000 {
            let s = a + (b - a) * (0.25 + 0.5 * k as f64 / 1000.0);
            worst = worst.max(view.contact_pressure(s).unwrap_or(0.0) / penalty);
        }
    }
    worst
}

#[test]
fn penetration_and_solution_converge_as_the_penalty_grows() {
    let scene = scene("string-hanging");
    let (ea, r) = (scene.belt.axial_stiffness, scene.drive.pulley_radius);
    let settings = SolverSettings::default();
    let mut pen = Vec::new();
    let mut values: Vec<Vec<f64>> = Vec::new();
    for kappa in KAPPAS {
        let p = kappa * ea / (r * r);
        let run = run_with(&scene, 128, fem::default_formulation(), Some(p), &settings);
        let d = max_penetration(run.view.as_ref(), p);
        println!("κ = {kappa:.0e}: P = {p:.3e} N/m², max penetration {d:.3e} m, {} Newton iterations", run.stats.newton_iterations);
        pen.push(d);
        values.push(QUANTITIES.iter().map(|q| run.summary.get(q).unwrap()).collect());
    }
    for k in 1..KAPPAS.len() {
        let ratio = pen[k - 1] / pen[k];
        // ratio of the maximal penetrations: p changes by O(1/P) too, hence ±10 %
        assert!((9.0..=11.0).contains(&ratio), "penetration ratio {ratio:.3} from κ = {:.0e}", KAPPAS[k - 1]);
    }
    assert!(pen[3] < 1e-9 * r, "default penetration {:.3e} m", pen[3]);
    for (j, q) in QUANTITIES.iter().enumerate() {
        let diff: Vec<f64> = (0..KAPPAS.len() - 1).map(|k| (values[k][j] - values[4][j]).abs()).collect();
        println!("{q:<20} |q(κ) − q(1e6)| for κ = 1e2…1e5: {diff:?}");
        // the penalty error e(P) ∝ 1/P: e(κ) − e(10⁶) shrinks ≈ 10× per decade (≈ 9× for
        // the last decade, where e(10⁶) = e(10⁵)/10 is subtracted)
        for k in 1..diff.len() {
            let ratio = diff[k - 1] / diff[k];
            assert!((5.0..=20.0).contains(&ratio), "{q}: ratio {ratio:.2} at κ = {:.0e}: {diff:?}", KAPPAS[k]);
        }
    }
}
