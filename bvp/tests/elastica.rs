//! The clamped–clamped elastica with unknown end loads against its exact first mode
//! (`bvp::analytical::elastica`; Love, *Mathematical Theory of Elasticity*, §263).
//!
//! Parameters: θ_max = 90° (k = sin 45° = 1/√2), a = 2E/K − 1 ≈ 0.45694, exact
//! P = 16K² ≈ 55.0, Q = 0. Start: θ = ε sin 2πs with ε = 1, P = 4π² (the linear buckling
//! mode, `elastica::guess`) — far from the answer (end position J_0(1) ≈ 0.77 vs 0.457).
//!
//! Tolerance justification: the error measure is `Exact::max_error` (component-wise,
//! relative to max(1, max|y_i|), over 2000 + 1 dense-output points, P relative, |Q|).
//! Shooting integrates at 0.1 · tolerance; the measured error/tolerance ratios (printed
//! with `--nocapture`) stay below 0.4, and the assertions allow 10 · tolerance. For
//! collocation the tolerance bounds the relative *residual* of the dense output, and
//! the solution error is the residual times the conditioning of the problem (the inverse
//! of the linearised operator); the measured ratios are ≤ 0.02 for orders 4 and 6 at
//! tolerances 1e-4 and 1e-6, the assertions allow 10 · tolerance (a conditioning factor
//! of 10).

use bvp::analytical::elastica::{guess, ClampedElastica, Exact};
use bvp::collocation::{self, CollocationOptions, Scheme};
use bvp::shooting::{self, ShootingOptions};
use bvp::{JacobianMode, Problem, Solution};

fn mode() -> Exact {
    Exact::new(std::f64::consts::FRAC_1_SQRT_2).unwrap()
}

/// One log line of a solve by `method` at tolerance `tol`: the error against the exact
/// mode (and its ratio to the tolerance), the load P, the end force Q and the work.
fn log_run(method: &str, tol: f64, err: f64, sol: &Solution) {
    eprintln!(
        "{method} tol {tol:.0e}: err {err:.2e} ({:.3}), P {:.10}, Q {:.1e}, newton {}, nodes {}",
        err / tol,
        sol.params[0],
        sol.params[1],
        sol.stats.newton_iterations,
        sol.stats.mesh_nodes
    );
}

#[test]
fn exact_mode_satisfies_the_ode_and_boundary_conditions() {
    // Checks the closed form itself: boundary values exact to rounding, and the ODE
    // residual by central differences (h = 1e-5: truncation ~h² |y'''| ≈ 1e-8 for
    // |y'''| ≤ 8kK · 16K² ≈ 600; rounding ~ε/h ≈ 1e-11) below 1e-6.
    let ex = mode();
    let problem = ex.problem();
    let [p, q] = ex.params();
    assert!((p - 55.0).abs() < 0.1 && q == 0.0 && (ex.end_position() - 0.456946).abs() < 1e-5);
    let (a, b) = (ex.state(0.0), ex.state(1.0));
    let mut r = [0.0; 6];
    problem.bc(&[&a[..]], &[&b[..]], &[p, q], 0.0, &mut r);
    assert!(r.iter().all(|v| v.abs() < 1e-14), "{r:?}");
    // Symmetry: θ(¼) = θ_max, y(½) = k/K, x(½) = a/2.
    let quarter = ex.state(0.25);
    assert!((quarter[2] - std::f64::consts::FRAC_PI_2).abs() < 1e-14);
    let half = ex.state(0.5);
    assert!(
        (half[1] - ex.k / ex.big_k).abs() < 1e-15
            && (half[0] - 0.5 * ex.end_position()).abs() < 1e-15
    );
    let h = 1e-5;
    for i in 1..50 {
        let s = i as f64 / 50.0;
        let (yp, ym, y) = (ex.state(s + h), ex.state(s - h), ex.state(s));
        let mut f = [0.0; 4];
        problem.rhs(0, s, &y, &[p, q], 0.0, &mut f);
        for c in 0..4 {
            let d = (yp[c] - ym[c]) / (2.0 * h);
            assert!(
                (d - f[c]).abs() < 1e-6 * (1.0 + f[c].abs()),
                "s {s} component {c}: {d} vs {}",
                f[c]
            );
        }
    }
}

#[test]
fn shooting_recovers_the_exact_mode_with_both_jacobians() {
    let ex = mode();
    let problem: ClampedElastica = ex.problem();
    let g = guess(1.0, 11);
    for jacobian in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
        for &tol in &[1e-4, 1e-7, 1e-10] {
            let opts = ShootingOptions {
                tolerance: tol,
                jacobian,
                ..Default::default()
            };
            let sol = shooting::solve(&problem, &g, &opts).expect("elastica by shooting");
            let err = ex.max_error(&sol, 2000);
            log_run(&format!("shooting {jacobian:?}"), tol, err, &sol);
            assert!(err <= 10.0 * tol, "{jacobian:?} tol {tol:e}: error {err:e}");
            assert!(
                sol.params[1].abs() <= 10.0 * tol * sol.params[0],
                "Q = {}",
                sol.params[1]
            );
            // Work counter (measured: 4, 5, 5 corrections for both Jacobian modes): a
            // change in the Newton path or the damping shows up here.
            let expected = if tol > 1e-5 { 4 } else { 5 };
            assert_eq!(
                sol.stats.newton_iterations, expected,
                "{jacobian:?} tol {tol:e}: {:?}",
                sol.stats
            );
            assert_eq!(sol.stats.unknowns, 4 * 4 + 2);
            assert!(sol.stats.max_residual <= tol);
        }
    }
}

#[test]
fn collocation_recovers_the_exact_mode_at_orders_four_and_six() {
    let ex = mode();
    let problem = ex.problem();
    let g = guess(1.0, 11);
    let shoot = shooting::solve(
        &problem,
        &g,
        &ShootingOptions {
            tolerance: 1e-10,
            ..Default::default()
        },
    )
    .unwrap();
    for scheme in [Scheme::Gauss4, Scheme::Gauss6] {
        for jacobian in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
            for &tol in &[1e-4, 1e-6] {
                let opts = CollocationOptions {
                    scheme,
                    tolerance: tol,
                    jacobian,
                    ..Default::default()
                };
                let sol = collocation::solve(&problem, &g, &opts).expect("elastica by collocation");
                let err = ex.max_error(&sol, 2000);
                log_run(&format!("collocation {scheme:?} {jacobian:?}"), tol, err, &sol);
                assert!(
                    err <= 10.0 * tol,
                    "{scheme:?} {jacobian:?} tol {tol:e}: error {err:e}"
                );
                // The two methods agree on the load to the looser of their accuracies.
                assert!((sol.params[0] - shoot.params[0]).abs() <= 10.0 * tol * shoot.params[0]);
            }
        }
    }
}

/// The accuracy-matched solve of the speed comparison with scipy's `solve_bvp`
/// (`docs/bvp-engine.md`, "Speed"; `bvp/examples/speed.rs`): gauss8 (the default
/// scheme) at tol 1e-8 from the linear mode must be at least as accurate as scipy at
/// tol 1e-8 on this problem (error 4.5e-11 with 1281 nodes), or the speed ratio would
/// compare unequal accuracies. Measured 1.38e-11 on 213 nodes with 7 Newton iterations;
/// the node bound (300, scipy's 1281 / 4) catches a mesh adaptation or Newton change
/// that buys the accuracy with many more nodes. Both Jacobian modes: the condensation
/// sees the same matrices up to the finite differences' error.
#[test]
fn gauss8_at_tol_1e_8_is_as_accurate_as_scipy_with_a_fifth_of_its_nodes() {
    let ex = mode();
    let problem = ex.problem();
    let g = guess(1.0, 11);
    for jacobian in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
        let opts = CollocationOptions { scheme: Scheme::Gauss8, tolerance: 1e-8, jacobian, ..Default::default() };
        let sol = collocation::solve(&problem, &g, &opts).expect("elastica by gauss8");
        let err = ex.max_error(&sol, 2000);
        log_run(&format!("collocation gauss8 {jacobian:?}"), 1e-8, err, &sol);
        assert!(err <= 4.5e-11, "{jacobian:?}: error {err:e}");
        assert!(sol.stats.mesh_nodes <= 300, "{jacobian:?}: {:?}", sol.stats);
        assert!(sol.stats.max_residual <= 1e-8);
    }
}
